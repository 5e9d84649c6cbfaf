#!/usr/bin/env bash
# Fetches Tight-Inclusion (Continuous-Collision-Detection/Tight-Inclusion, MIT) for `ttd bench
# ccd` at the commit its figures in docs/ccd.md were measured with, and installs what its build
# needs (Eigen, spdlog, fmt: Debian packages, through scripts/install-optional.sh). TI's own
# CMake downloads its dependencies; ttd's build (bench/ti/CMakeLists.txt) compiles its sources
# against the system's instead, so the checkout is used as fetched.
# Usage: scripts/get-tight-inclusion.sh [DIR]    (default: third_party/tight-inclusion, git-ignored)
# Then: cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DTTD_TIGHT_INCLUSION_DIR=DIR
#       cmake --build build --target ttd ttd_ti_ccd_bench && build/cli/ttd bench ccd --queries ...
# Needs network access to GitHub; where there is none it says so and fails (the benchmark then
# runs without TI, as it does when TTD_TIGHT_INCLUSION_DIR is unset).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
dir=${1:-$here/third_party/tight-inclusion}
url=https://github.com/Continuous-Collision-Detection/Tight-Inclusion.git
commit=ca9a8c24fe91de3376d77975c5e9978f88e05794
"$here/scripts/install-optional.sh" get-tight-inclusion.sh libeigen3-dev libspdlog-dev libfmt-dev
if [ -e "$dir/src/tight_inclusion/ccd.cpp" ]; then
    echo "get-tight-inclusion.sh: $dir already holds Tight-Inclusion"
else
    if ! git clone --quiet "$url" "$dir"; then
        echo "get-tight-inclusion.sh: cannot clone $url (no network?); ttd bench ccd runs without Tight-Inclusion" >&2
        exit 1
    fi
fi
if [ -d "$dir/.git" ]; then
    git -C "$dir" checkout --quiet "$commit" ||
        echo "get-tight-inclusion.sh: commit $commit not found in $dir; using what is checked out" >&2
fi
echo "get-tight-inclusion.sh: configure ttd with -DTTD_TIGHT_INCLUSION_DIR=$dir"
