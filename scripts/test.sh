#!/usr/bin/env bash
# Builds ttd and runs every test (the README's test command; .ci/run calls it).
# Usage: scripts/test.sh            (build folder: build/, or $TTD_BUILD_DIR)
# Installs the optional Bullet and assimp (below) with apt-get when run as root; the Python tests
# (scripts/test-python.sh) install the Debian
# packages they lack with apt-get when run as root, and say which first.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${TTD_BUILD_DIR:-build}
jobs=$(nproc 2>/dev/null || echo 2)
# Optional: Bullet (libbullet-dev, found through pkg-config) for the simulator's comparison
# program, examples/sim/bullet/ (docs/simulator.md); without it that program and its test are
# not built, and CMake says so.
missing=()
command -v pkg-config > /dev/null 2>&1 || missing+=(pkg-config)
[ -f /usr/include/bullet/btBulletDynamicsCommon.h ] || missing+=(libbullet-dev)
# Optional: assimp (libassimp-dev, its C API) as the independent reader that tests/test_meshfile_formats.c
# compares the OFF and glTF readers' triangle counts with, and the writer of glTF files it reads;
# without it those checks are skipped, and the test says so.
[ -f /usr/include/assimp/cimport.h ] || missing+=(libassimp-dev)
# Optional: GMP (libgmp-dev) for the continuous-collision tests' exact rational reference
# (tests/ccd_ref/); without it test_ccd runs its other checks and says what it skipped.
# (the header lies in /usr/include or, on multiarch Debian, in /usr/include/<triplet>: either will do)
[ -f /usr/include/gmp.h ] || compgen -G "/usr/include/*-linux-*/gmp.h" > /dev/null || missing+=(libgmp-dev)
scripts/install-optional.sh test.sh "${missing[@]}"
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release ${TTD_CMAKE_ARGS:-}
cmake --build "$build" -j "$jobs"
ctest --test-dir "$build" --output-on-failure --no-tests=error -j "$jobs"
# The Python package (python/), built against this build's library and tested with pytest;
# skipped with a message where Python's Debian packages cannot be had (scripts/test-python.sh).
echo "test.sh: the Python tests next (scripts/test-python.sh: as root it installs the Debian packages it lacks, naming them)" >&2
scripts/test-python.sh "$build"
