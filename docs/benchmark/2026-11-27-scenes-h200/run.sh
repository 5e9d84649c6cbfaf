#!/usr/bin/env bash
# The scene section of ttd bench with FCL and Bullet, on the device machine's quiet cores, one
# scene per run so that each run's table survives a time limit.
D=$(cd "$(dirname "$0")" && pwd)
export LD_LIBRARY_PATH=$D
{ date -u; nproc; uptime; lscpu | grep -E "Model name|Core|Socket"; "$D/ttd" info; } > "$OUT/machine.txt" 2>&1
for st in icospheres:160 mixed:100 sparse:90 bunnies:75; do
  s=${st%%:*}; t=${st##*:}
  mkdir -p "$OUT/$s"
  timeout $t "$D/ttd" bench --no-probes --scene-workloads $s --no-deform \
    --bunny "$D/bunny.obj" > "$OUT/$s/bench.txt" 2>&1
  echo "bench rc=$?; $(uptime)" >> "$OUT/$s/bench.txt"
  grep -E "^$s .*(contacts|manifold-4|motion)" "$OUT/$s/bench.txt"
done
