#!/usr/bin/env bash
# The GPU checks, for a machine with a GPU (docs/gpu.md, section 5). Compiles nothing: run it from
# the repository root on a build made elsewhere with CUDA (build/, or $TTD_BUILD_DIR; configure
# with -DTTD_CUDA=ON so that a missing nvcc fails there, not here). Writes what it prints, and an
# Nsight Compute report when TTD_NCU=1 and ncu is on PATH, under $OUT (or /tmp/ttd-gpu).
#   1. ttd info: the gpu: line (usable, device, compute capability, driver and runtime);
#   2. test_gpu: the pair set through ttd_gpu_batch_d/f on device memory against the CPU, bit for
#      bit, then device-resident distance-only pairs/s in both precisions beside ttd_batch on
#      this machine's cores (TTD_GPU_BENCH_PAIRS pairs, default 2^24).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${TTD_BUILD_DIR:-build}
out=${OUT:-/tmp/ttd-gpu}
mkdir -p "$out"
# the build's run path names the folder it was built in; a copy elsewhere finds libttd_gpu here
export LD_LIBRARY_PATH="$PWD/$build/src/gpu${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
[ -x "$build/tests/test_gpu" ] || { echo "test-gpu-device.sh: no $build/tests/test_gpu (build with -DTTD_CUDA=ON first)" >&2; exit 1; }
{ command -v nvidia-smi > /dev/null && nvidia-smi --query-gpu=name,driver_version,clocks.max.sm,memory.total --format=csv; } \
    2>&1 | tee "$out/nvidia-smi.txt" || true
"$build/cli/ttd" info | tee "$out/info.txt"
grep -q '^gpu: usable' "$out/info.txt" || { echo "test-gpu-device.sh: no usable GPU" >&2; exit 1; }
TTD_GPU_BENCH_PAIRS=${TTD_GPU_BENCH_PAIRS:-16777216} "$build/tests/test_gpu" 2>&1 | tee "$out/test_gpu.txt"
if [ "${TTD_NCU:-0}" = 1 ] && command -v ncu > /dev/null; then
    # the distance-only kernels, both precisions, on 2^20 pairs
    TTD_GPU_BENCH_PAIRS=1048576 ncu --set full -k regex:gpu_exact -c 4 -f -o "$out/ncu" \
        "$build/tests/test_gpu" gpu_device_throughput > "$out/ncu.txt" 2>&1 || cat "$out/ncu.txt"
fi
