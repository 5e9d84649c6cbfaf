#!/usr/bin/env bash
# Builds ttd with AddressSanitizer and UndefinedBehaviorSanitizer (-DTTD_SANITIZE=ON, every
# report fatal) and runs every test, the CLI tests included, under them. A sanitizer report
# aborts the program (abort_on_error), so the tests see a crash, never a plain failure status.
# Usage: scripts/test-sanitize.sh      (build folder: build-sanitize/, or $TTD_SANITIZE_BUILD_DIR)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${TTD_SANITIZE_BUILD_DIR:-build-sanitize}
jobs=$(nproc 2>/dev/null || echo 2)
# RelWithDebInfo: optimised (the tests' loops stay fast) with line numbers in the reports.
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTTD_SANITIZE=ON ${TTD_CMAKE_ARGS:-}
cmake --build "$build" -j "$jobs"
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:detect_stack_use_after_return=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1:abort_on_error=1}
# ttd.install is left out: it links a plain downstream project against the installed library,
# whose sanitized objects need the sanitizer runtimes that project does not link (scripts/test.sh
# runs it on the plain build).
ctest --test-dir "$build" --output-on-failure --no-tests=error -j "$jobs" -E '^ttd[.]install$'
