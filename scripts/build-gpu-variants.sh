#!/usr/bin/env bash
# Builds libttd_gpu with other block sizes and launch bounds, for the tuning runs of
# scripts/test-gpu-device.sh (docs/gpu.md, section 5): each variant's library goes to
# $build/gpu-variants/b<threads>m<min blocks>/, where that script finds it.
#   scripts/build-gpu-variants.sh "128 3" "256 2" ...     (default: the list below)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${TTD_BUILD_DIR:-build}
[ $# -gt 0 ] || set -- "64 0" "256 0" "128 3" "128 4" "128 6" "256 2"
for v in "$@"; do
    read -r threads minb <<< "$v"
    dir="$build/gpu-variants/b${threads}m${minb}"
    mkdir -p "$dir"
    cmake -S . -B "$dir/build" -DCMAKE_BUILD_TYPE=Release -DTTD_CUDA=ON -DTTD_CUDA_VERBOSE=ON \
        -DTTD_GPU_BLOCK="$threads" -DTTD_GPU_MIN_BLOCKS="$minb" > "$dir.configure.log"
    cmake --build "$dir/build" -j "$(nproc)" --target ttd_gpu > "$dir.build.log" 2>&1
    cp -L "$dir/build/src/gpu/libttd_gpu.so.0" "$dir/"
    rm -rf "$dir/build"
    # each exact kernel's registers and spills, from ptxas -v
    echo "b${threads}m${minb}:" $(awk '/Compiling entry function .*gpu_exact/ { k = $0; sub(/.*_Z[0-9]+/, "", k); sub(/m.*_/, "", k); n = split($0, a, "P"); k = ($0 ~ /_Pd/ || $0 ~ /PKd/ ? "d" : "f") ($0 ~ /result/ ? "-full" : "-dist") }
        /spill stores/ && k { sp = $5 } /Used [0-9]+ registers/ && k { print k "=" $5 "r/" sp "B"; k = "" }' "$dir.build.log")
done
