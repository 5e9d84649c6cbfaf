#!/usr/bin/env bash
# Two builds of ttd, A and B, timed in turn on the exact kernel's pair rows (random pairs and
# the two mesh pair workloads), each run with FCL's triDistance beside it; for a machine shared
# with other work (docs/kernel-speed.md). Per row it prints the fastest sample over all rounds
# (`ns_per_pair_min`, which other work can only make slower) for A and B, B's change, and each
# build's ratio to FCL's fastest sample of its own runs.
#
# Usage: bench/kernel_ab.sh TTD_A TTD_B ROUNDS [ttd bench options, e.g. --isa avx512]
# Runs at nice -15 in its own scheduler autogroup when root (as scripts/bench.sh does with
# TTD_BENCH_NICE=-15). FCL's program is taken from next to TTD_B.
set -euo pipefail
[ $# -ge 3 ] || { sed -n '2,10p' "$0" >&2; exit 2; }
a=$1 b=$2 rounds=$3
shift 3
fcl="$(dirname "$b")/ttd_fcl_bench"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
run() { # $1 binary, $2 output
  local cmd=("$1" bench --workloads random,mesh-near,mesh-contact --pairs 200000 --methods exact --threads 1
             --no-probes --no-mesh --no-scene --samples 11 --min-time 0.05 --json --fcl "$fcl" "${@:3}")
  if [ "$(id -u)" = 0 ]; then
    setsid bash -c 'echo -15 > /proc/self/autogroup 2>/dev/null; exec nice -n -15 "$@"' _ "${cmd[@]}" > "$2" 2>/dev/null
  else
    "${cmd[@]}" > "$2" 2>/dev/null
  fi
}
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
for r in $(seq 1 "$rounds"); do
  run "$a" "$tmp/A$r.json" "$@"
  run "$b" "$tmp/B$r.json" "$@"
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
/usr/bin/python3 - "$tmp" "$rounds" <<'PY'
import json, sys
tmp, rounds = sys.argv[1], int(sys.argv[2])
best = {}
for side in "AB":
    for r in range(1, rounds + 1):
        for row in json.load(open(f"{tmp}/{side}{r}.json"))["rows"]:
            key = (row["workload"], row["method"], row["precision"], row["isa"])
            v = row["ns_per_pair_min"]
            best.setdefault(side, {})
            best[side][key] = min(v, best[side].get(key, float("inf")))
print(f"{'workload':14} {'row':12} {'prec':6} {'isa':7} {'A ns':>8} {'B ns':>8} {'B/A':>6} {'A xfcl':>7} {'B xfcl':>7}")
for key in best["A"]:
    w, m, p, isa = key
    if m == "fcl":
        continue
    fa = best["A"].get((w, "fcl", p, "scalar")); fb = best["B"].get((w, "fcl", p, "scalar"))
    ta, tb = best["A"][key], best["B"].get(key, float("nan"))
    xa = f"{fa / ta:7.2f}" if fa else "      -"
    xb = f"{fb / tb:7.2f}" if fb else "      -"
    print(f"{w:14} {m:12} {p:6} {isa:7} {ta:8.2f} {tb:8.2f} {tb / ta:6.3f} {xa} {xb}")
for w in ("random", "mesh-near", "mesh-contact"):
    for p in ("double", "float"):
        k = (w, "fcl", p, "scalar")
        if k in best["A"]:
            print(f"FCL {w} {p}: fastest sample {best['A'][k]:.1f} ns (A's runs), {best['B'][k]:.1f} ns (B's runs)")
PY
