#!/usr/bin/env bash
# Thread scaling of the scene queries, for a machine with quiet cores (docs/scene-speed.md,
# section 4): the 2-core development machines are too loaded for a two-thread ratio to mean
# anything. Runs `ttd bench`'s scene section without FCL and Bullet (its rows with 2 threads),
# then `ttd scene contacts` at 1, 2, 4, 8, 16 threads and `ttd scene manifold` at 1 and 2 on the
# scenes the benchmark wrote.
#
# Usage: scripts/bench-threads-device.sh OUTDIR   (ttd: $TTD, default build/cli/ttd; the bunny:
#        $TTD_BUNNY, default build/data/bunny.obj, its scene left out when absent)
set -uo pipefail
out=${1:?usage: scripts/bench-threads-device.sh OUTDIR}
ttd=${TTD:-build/cli/ttd}
bunny=${TTD_BUNNY:-build/data/bunny.obj}
[ -x "$ttd" ] || { echo "bench-threads-device.sh: no ttd at $ttd (build it, or set TTD)" >&2; exit 1; }
mkdir -p "$out/bench"
scenes=$(mktemp -d)
trap 'rm -rf "$scenes"' EXIT
{ date -u; uptime; lscpu | grep -E "Model name|Thread|Core|Socket"; "$ttd" info; } > "$out/machine.txt" 2>&1
workloads=icospheres,mixed,sparse
[ -f "$bunny" ] && workloads=icospheres,bunnies,mixed,sparse
timeout 280 "$ttd" bench --no-probes --scene-workloads "$workloads" --no-fcl --no-deform --bunny "$bunny" \
    --scene-write "$scenes" --out "$out/bench" > "$out/bench.txt" 2>&1
echo "bench status $?; $(uptime)" >> "$out/bench.txt"
for s in ${workloads//,/ }; do
    margin=$(head -1 "$scenes/$s.txt" | grep -o -- '--margin [0-9.e-]*')
    for t in 1 2 4 8 16; do
        echo "== $s contacts threads $t"
        timeout 60 "$ttd" scene contacts "$scenes/$s.txt" $margin --threads $t --stats --repeat 5 --count 2>&1 | tail -2
    done
    echo "== $s manifold (4 points) threads 1, 2"
    for t in 1 2; do
        timeout 60 "$ttd" scene manifold "$scenes/$s.txt" $margin --max-points 4 --threads $t --stats --repeat 5 --count 2>&1 | tail -2
    done
done > "$out/sweep.txt" 2>&1
echo "$(uptime)" >> "$out/sweep.txt"
