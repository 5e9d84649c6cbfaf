#!/usr/bin/env bash
# The Python package's tests: builds the package in python/ against the library of a CMake
# build folder, installs it into a venv there and runs its pytest suite (python/tests).
# scripts/test.sh runs it after the C tests; it also runs alone:
#   scripts/test-python.sh [BUILD_DIR]     (default: $TTD_BUILD_DIR, else build/)
#
# The interpreter is $TTD_PYTHON, by default /usr/bin/python3: Debian's, which sees Debian's
# python3-numpy, -pytest, -setuptools, -dask and -distributed. (The `python3` first on PATH
# may be another one, such as pyenv's, without them.) The venv (BUILD_DIR/python-venv) is made
# with --system-site-packages so that those packages come from Debian, and pip builds without
# isolation and without an index, so nothing is downloaded: PyPI need not be reachable.
#
# Missing Debian packages are installed with apt-get when this runs as root (or with
# password-less sudo). Where they cannot be, the Python tests are skipped with a message that
# names what is missing, and the script exits 0. Dask, distributed, mypy and matplotlib are
# optional: without them only the scale-out tests, the type check of the docs' examples against
# the stub (python/tests/test_types.py), or the check of the pile example's picture
# (python/tests/test_examples.py) are skipped (pytest says so).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-${TTD_BUILD_DIR:-build}}
py=${TTD_PYTHON:-/usr/bin/python3}
debian_py=/usr/bin/python3

skip() {
    echo "test-python.sh: SKIPPED the Python tests: $*" >&2
    exit 0
}

# What $py lacks, as Debian package names (one line, empty when nothing is).
missing() {
    if ! command -v "$py" > /dev/null 2>&1; then
        echo "python3 python3-numpy python3-pytest python3-setuptools python3-pip python3-venv python3-dev python3-dask python3-distributed python3-mypy python3-matplotlib"
        return
    fi
    "$py" - << 'EOF'
import importlib.util, os, sysconfig
need = [("numpy", "python3-numpy"), ("pytest", "python3-pytest"), ("setuptools", "python3-setuptools"),
        ("pip", "python3-pip"), ("wheel", "python3-wheel"), ("ensurepip", "python3-venv"),
        ("dask.array", "python3-dask"), ("distributed", "python3-distributed"), ("mypy", "python3-mypy"),
        ("matplotlib", "python3-matplotlib")]
out = []
for module, package in need:
    try:
        found = importlib.util.find_spec(module) is not None
    except ImportError:  # dask.array's parent missing
        found = False
    if not found:
        out.append(package)
if not os.path.isfile(os.path.join(sysconfig.get_paths()["include"], "Python.h")):
    out.append("python3-dev")
print(" ".join(out))
EOF
}

lacking=$(missing)
tried=""
if [ -n "$lacking" ] && [ "$py" = "$debian_py" ]; then
    sudo=""
    if [ "$(id -u)" != 0 ] && command -v sudo > /dev/null 2>&1 && sudo -n true 2> /dev/null; then
        sudo="sudo -n"
    fi
    if command -v apt-get > /dev/null 2>&1 && { [ "$(id -u)" = 0 ] || [ -n "$sudo" ]; }; then
        echo "test-python.sh: installing the Debian packages $lacking with apt-get (apt-get lists them with what they depend on)" >&2
        # shellcheck disable=SC2086 # one package name per word
        if ! { $sudo apt-get update -qq && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q $lacking; } >&2; then
            echo "test-python.sh: apt-get could not install $lacking" >&2
        fi
        lacking=$(missing)
        tried=1
    fi
fi
command -v "$py" > /dev/null 2>&1 || skip "the interpreter $py was not found (TTD_PYTHON names another)"
required=""
for p in $lacking; do
    case $p in
        python3-dask | python3-distributed | python3-mypy | python3-matplotlib) ;;
        *) required="$required $p" ;;
    esac
done
if [ -n "$required" ]; then
    if [ -n "$tried" ]; then
        skip "$py lacks$required, which apt-get did not provide"
    elif [ "$py" = "$debian_py" ]; then
        skip "$py lacks$required (run as root, this script installs them: apt-get install$required)"
    fi
    skip "$py (TTD_PYTHON) lacks$required; unset TTD_PYTHON to use Debian's $debian_py"
fi
if [ -n "$lacking" ]; then
    echo "test-python.sh: $lacking not installed: the Dask tests, the type check of the docs' examples (mypy), or the check of the pile example's picture (matplotlib), will be skipped (apt-get install $lacking)" >&2
fi

# The library is built here (the package links its static archive); a sanitized build's
# archive needs the sanitizer runtimes, which the interpreter does not load.
[ -f "$build/CMakeCache.txt" ] || cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release > /dev/null
if grep -q '^TTD_SANITIZE:BOOL=ON' "$build/CMakeCache.txt"; then
    skip "$build is a sanitizer build (-DTTD_SANITIZE=ON); run it on a plain build"
fi
build=$(cd "$build" && pwd)
targets="ttd_static ttd_shared"  # the package's archive; ctypes' library and the ttd program for the tests
grep -q '^TTD_BUILD_CLI:BOOL=ON' "$build/CMakeCache.txt" && targets="$targets ttd"
# shellcheck disable=SC2086 # one target per word
cmake --build "$build" -j "$(nproc 2> /dev/null || echo 2)" --target $targets > /dev/null

venv=$build/python-venv
real='import os, sys; print(os.path.realpath(getattr(sys, "_base_executable", sys.executable)))'
if ! [ -x "$venv/bin/python" ] || [ "$("$venv/bin/python" -c "$real" 2> /dev/null)" != "$("$py" -c "$real")" ]; then
    rm -rf "$venv"
    "$py" -m venv --system-site-packages "$venv"
fi
echo "test-python.sh: building and installing python/ into $venv (interpreter $py)" >&2
# TTD_PYTHON_CTIMING=1: with the benchmark's C-side timer (ttd._ctiming), which bench/python_overhead.py
# and two tests use; wheels and plain installs leave it out.
TTD_CMAKE_BUILD_DIR=$build TTD_PYTHON_BUILD_BASE=$build/python-build TTD_PYTHON_CTIMING=1 \
    "$venv/bin/python" -m pip install --quiet --no-build-isolation --no-index --disable-pip-version-check ./python

# From the repository root, so that python/ttd (the sources) does not shadow the installed
# package; no bytecode or pytest cache is written into the tree.
TTD_TEST_BUILD_DIR=$build PYTHONDONTWRITEBYTECODE=1 "$venv/bin/python" -m pytest -q python/tests
