#!/usr/bin/env bash
# The GPU checks, for a machine with a GPU (docs/gpu.md, section 5). Compiles nothing: run it from
# the repository root on a build made elsewhere with CUDA (build/, or $TTD_BUILD_DIR; configure
# with -DTTD_CUDA=ON so that a missing nvcc fails there, not here). Writes what it prints, and an
# Nsight Compute report when TTD_NCU=1 and ncu is on PATH, under $OUT (or /tmp/ttd-gpu).
#   1. nvidia-smi's device line and ttd info's gpu: line (usable, device, compute capability,
#      driver and runtime);
#   2. test_gpu: every pair family (TTD_GPU_BITS_PAIRS pairs each, default 1,000,000) through
#      ttd_gpu_batch_d/f on device memory and through the host entries, against the CPU's scalar
#      row bit for bit; then pairs/s (TTD_GPU_BENCH_PAIRS pairs, default 2^22) device-resident and
#      from host memory, beside ttd_batch on this machine's cores;
#   3. the throughput again with each library of $build/gpu-variants/*/ (other block sizes and
#      launch bounds, made by scripts/build-gpu-variants.sh), when there are any;
#   4. python/tests/cuda_device_check.py: ttd.cuda on CuPy, PyTorch and DLPack arrays against the
#      CPU's bits, when python3 has numpy;
#   5. test_gpu_walk: mesh poses on the device (docs/gpu.md, section 6): TTD_GPU_WALK_POSES poses
#      (default 1,000,000) of an 81,920-triangle rough sphere against itself through
#      ttd_gpu_mesh_distance/collide in double and float, against ttd_mesh_distance/collide on this
#      machine's cores, bit for bit (distance bits and flags; ties checked through the batch;
#      collide verdicts), and poses/s of both in the same run; then TTD_GPU_POINTS points (default
#      10,000,000: on vertices, near, in the box, far) through ttd_gpu_points_closest_d/f against
#      ttd_points_closest, whole results bit for bit, and points/s of both; and the entries'
#      argument checks on the device (the host walks' own tests need no device: scripts/test.sh).
#   6. test_gpu_signed: signed distances on the device (docs/gpu.md, section 6): the entries'
#      argument checks on device meshes, then TTD_GPU_POINTS points (default 10,000,000) on the
#      same rough sphere through ttd_gpu_points_signed_distance_d/f against
#      ttd_points_signed_distance on this machine's cores, distances and whole results bit for bit
#      (the inside flag included), and points/s of both.
#   7. test_gpu_ccd: continuous collision on the device (docs/ccd.md, section 14): the argument
#      checks, then every generated family (TTD_GPU_CCD_N queries a family and kind, default
#      20,000: vertex-face, edge-edge, triangles; three separations; double and float) and the kept
#      sample queries through ttd_gpu_ccd_* on device memory against the CPU batch, every field
#      bit for bit, and queries/s of the device and of this machine's cores on random queries.
set -uo pipefail
cd "$(dirname "$0")/.."
build=${TTD_BUILD_DIR:-build}
out=${OUT:-/tmp/ttd-gpu}
mkdir -p "$out"
status=0
# the build's run path names the folder it was built in; a copy elsewhere finds libttd_gpu here
export LD_LIBRARY_PATH="$PWD/$build/src/gpu${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
[ -x "$build/tests/test_gpu" ] || { echo "test-gpu-device.sh: no $build/tests/test_gpu (build with -DTTD_CUDA=ON first)" >&2; exit 1; }
{ command -v nvidia-smi > /dev/null && nvidia-smi --query-gpu=name,driver_version,clocks.max.sm,memory.total --format=csv; } \
    2>&1 | tee "$out/nvidia-smi.txt"
"$build/cli/ttd" info | tee "$out/info.txt"
grep -q '^gpu: usable' "$out/info.txt" || { echo "test-gpu-device.sh: no usable GPU" >&2; exit 1; }
TTD_GPU_BITS_PAIRS=${TTD_GPU_BITS_PAIRS:-1000000} TTD_GPU_BENCH_PAIRS=${TTD_GPU_BENCH_PAIRS:-4194304} \
    "$build/tests/test_gpu" 2>&1 | tee "$out/test_gpu.txt" || status=1
for v in "$build"/gpu-variants/*/; do
    [ -e "$v/libttd_gpu.so.0" ] || continue
    echo "=== variant $(basename "$v")"
    LD_LIBRARY_PATH="$PWD/$v" TTD_GPU_BENCH_PAIRS=${TTD_GPU_BENCH_PAIRS:-4194304} \
        "$build/tests/test_gpu" gpu_device_throughput 2>&1 || status=1
done 2>&1 | tee "$out/variants.txt"
if command -v python3 > /dev/null && python3 -c 'import numpy' 2> /dev/null; then
    PYTHONUNBUFFERED=1 python3 python/tests/cuda_device_check.py "$build" 2>&1 | tee "$out/python.txt" || status=1
else
    echo "test-gpu-device.sh: no python3 with numpy: ttd.cuda not checked" | tee "$out/python.txt"
fi
[ -x "$build/tests/test_gpu_walk" ] || { echo "test-gpu-device.sh: no $build/tests/test_gpu_walk" >&2; status=1; }
(
    rc=0
    for t in walk_entries_without_device walk_device; do
        TTD_GPU_WALK_POSES=${TTD_GPU_WALK_POSES:-1000000} TTD_GPU_POINTS=${TTD_GPU_POINTS:-10000000} \
            "$build/tests/test_gpu_walk" $t 2>&1 || rc=1
    done
    exit $rc
) | tee "$out/test_gpu_walk.txt" || status=1
[ -x "$build/tests/test_gpu_signed" ] || { echo "test-gpu-device.sh: no $build/tests/test_gpu_signed" >&2; status=1; }
(
    rc=0
    for t in signed_entries_without_device signed_device; do
        TTD_GPU_POINTS=${TTD_GPU_POINTS:-10000000} "$build/tests/test_gpu_signed" $t 2>&1 || rc=1
    done
    exit $rc
) | tee "$out/test_gpu_signed.txt" || status=1
# ---- continuous collision (step 7) ----
[ -x "$build/tests/test_gpu_ccd" ] || { echo "test-gpu-device.sh: no $build/tests/test_gpu_ccd" >&2; status=1; }
TTD_GPU_CCD_N=${TTD_GPU_CCD_N:-20000} "$build/tests/test_gpu_ccd" 2>&1 | tee "$out/test_gpu_ccd.txt" || status=1
# ---- end of continuous collision ----
if [ "${TTD_NCU:-0}" = 1 ] && command -v ncu > /dev/null; then
    # the distance-only kernel's first launch in each precision, on 2^20 pairs: occupancy, pipes,
    # stalls (the kernels are told apart by their mangled names: ...PKd... double, ...PKf... float)
    for p in d f; do
        TTD_GPU_BENCH_PAIRS=1048576 timeout 240 ncu --kernel-name-base mangled -k "regex:gpu_exact_dist_kernelmPK$p" -c 1 \
            --section SpeedOfLight --section Occupancy --section LaunchStats --section ComputeWorkloadAnalysis \
            --section WarpStateStats --section InstructionStats "$build/tests/test_gpu" gpu_device_throughput \
            > "$out/ncu-$p.txt" 2>&1 || echo "ncu failed (see ncu-$p.txt)"
    done
fi
exit $status
