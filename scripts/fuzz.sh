#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz/) with clang, AddressSanitizer and
# UndefinedBehaviorSanitizer, and runs each for a bounded time from the corpus kept in
# tests/fuzz/corpus/ (copied to the build folder first, so the repository is not written).
# A crash, a sanitizer report or a failed check stops the run with status 1; the input that
# caused it is left in $build/artifacts/.
# Where clang or its libFuzzer runtime is missing, the script tries to install the runtime
# (apt-get, when run as root) and otherwise skips with a message and status 0.
# The mutations start from a fixed seed (TTD_FUZZ_SEED, default 20261126), so that a failure in
# CI reruns the same way here; TTD_FUZZ_SEED=0 lets libFuzzer pick one (long campaigns that
# explore beyond CI's path: docs/testing.md).
# Usage: scripts/fuzz.sh [seconds per target, default 30]   (build folder: build-fuzz/, or $TTD_FUZZ_BUILD_DIR)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-${TTD_FUZZ_SECONDS:-30}}
build=${TTD_FUZZ_BUILD_DIR:-build-fuzz}
seed=${TTD_FUZZ_SEED:-20261126}
jobs=$(nproc 2>/dev/null || echo 2)
CC_FUZZ=${CC_FUZZ:-clang}

skip() { echo "fuzz.sh: SKIPPED: $*"; exit 0; }

command -v "$CC_FUZZ" > /dev/null 2>&1 || skip "no $CC_FUZZ compiler on this machine"

# Can clang link a libFuzzer program? (Debian ships the runtime in libclang-rt-N-dev.)
probe_dir=$(mktemp -d)
trap 'rm -rf "$probe_dir"' EXIT
cat > "$probe_dir/probe.c" <<'PROBE'
#include <stddef.h>
#include <stdint.h>
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) { (void)data; (void)size; return 0; }
PROBE
can_fuzz() { "$CC_FUZZ" -fsanitize=fuzzer,address,undefined "$probe_dir/probe.c" -o "$probe_dir/probe" > /dev/null 2>&1; }
if ! can_fuzz; then
    major=$("$CC_FUZZ" -dumpversion 2>/dev/null | cut -d. -f1)
    echo "fuzz.sh: $CC_FUZZ $major cannot link -fsanitize=fuzzer"
    if [ "$(id -u)" = 0 ] && command -v apt-get > /dev/null 2>&1; then
        export DEBIAN_FRONTEND=noninteractive
        apt-get update -qq || true
        # clang >= 14 on Debian/Ubuntu: libclang-rt-N-dev; older: libclang-common-N-dev
        echo "fuzz.sh: installing the Debian package libclang-rt-$major-dev (else libclang-common-$major-dev) with apt-get"
        apt-get install -y -q "libclang-rt-$major-dev" 2>&1 ||
            apt-get install -y -q "libclang-common-$major-dev" 2>&1 || true
    fi
    can_fuzz || skip "$CC_FUZZ cannot link libFuzzer programs here (install libclang-rt-$major-dev)"
fi

mkdir -p "$build"
# Everything instrumented for coverage and the sanitizers; only the fuzz targets are built.
CC="$CC_FUZZ" cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTTD_FUZZ=ON -DTTD_SANITIZE=ON \
    -DTTD_BUILD_CLI=OFF -DCMAKE_C_FLAGS="-fsanitize=fuzzer-no-link" > "$build/cmake.log" 2>&1 ||
    { cat "$build/cmake.log"; exit 1; }
cmake --build "$build" -j "$jobs" --target fuzz_parse_line fuzz_batch fuzz_meshfile fuzz_mesh fuzz_points fuzz_mesh_ccd
# fuzz_ccd (continuous collision against the exact rational reference) needs GMP (libgmp-dev)
targets="parse_line batch meshfile mesh points mesh_ccd"
if cmake --build "$build" -j "$jobs" --target fuzz_ccd > "$build/fuzz_ccd_build.log" 2>&1; then
    targets="$targets ccd"
else
    echo "fuzz.sh: fuzz_ccd not built (GMP, libgmp-dev, not found?): skipped"
fi

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
mkdir -p "$build/artifacts"
status=0
for target in $targets; do
    work="$build/corpus/$target"
    rm -rf "$work"
    mkdir -p "$work"
    cp tests/fuzz/corpus/$target/* "$work/"
    exe=$(find "$build" -name "fuzz_$target" -type f -perm -u+x | head -n 1)
    echo "fuzz.sh: fuzz_$target for $seconds s from $(ls "$work" | wc -l) corpus files, seed $seed"
    # -max_len: long enough for the CLI's 4096-byte lines, 64 double pairs, and small meshes
    if ! "$exe" "$work" -seed="$seed" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=10000 \
            -artifact_prefix="$build/artifacts/$target-" -print_final_stats=1 2> "$build/fuzz_$target.log"; then
        echo "fuzz.sh: fuzz_$target FAILED (input saved under $build/artifacts/):"
        tail -n 40 "$build/fuzz_$target.log"
        status=1
    else
        grep -E '^(stat::number_of_executed_units|stat::new_units_added)|^#[0-9]+ *DONE' "$build/fuzz_$target.log" || true
        echo "fuzz.sh: fuzz_$target passed; corpus now $(ls "$work" | wc -l) files"
    fi
done
exit $status
