#!/bin/sh
# Smoke test of the benchmark (CI runs it through CTest): `ttd bench --quick --json` must
# finish, produce rows with the required fields and positive times for the exact method on
# the scalar code, include FCL rows when ttd_fcl_bench sits next to ttd, and `--csv` must
# start with its header. Timings are not checked: they belong to the benchmark, not to tests.
# Usage: sh tests/cli/test_bench.sh path/to/ttd
set -eu
ttd=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT INT TERM
fail() { echo "test_bench: FAILED: $*" >&2; exit 1; }

"$ttd" bench --quick --json --quiet > "$tmp/out.json" || fail "ttd bench --quick --json exited with $?"
head -c 1 "$tmp/out.json" | grep -q '{' || fail "output is not a JSON object"
grep -q '"rows": \[' "$tmp/out.json" || fail "no rows array"

# Every row (one object per line) holds the required fields.
rows=$(grep -c '^    {"workload": ' "$tmp/out.json" || true)
[ "$rows" -ge 4 ] || fail "expected at least 4 rows, got $rows"
for field in workload method precision isa threads pairs ns_per_pair speedup_vs_scalar; do
  n=$(grep '^    {"workload": ' "$tmp/out.json" | grep -c "\"$field\": " || true)
  [ "$n" -eq "$rows" ] || fail "field $field in $n of $rows rows"
done

# The paper's workload and the random one, exact method, scalar, both precisions, with a
# positive time and a speedup of 1 against itself.
for w in paper random; do
  for p in double float; do
    line=$(grep "\"workload\": \"$w\", \"method\": \"exact\", \"precision\": \"$p\", \"isa\": \"scalar\"" "$tmp/out.json" |
           grep '"threads": 1,' | head -n 1)
    [ -n "$line" ] || fail "no exact scalar $p row for $w"
    ns=$(printf '%s\n' "$line" | sed 's/.*"ns_per_pair": \([^,]*\),.*/\1/')
    awk -v x="$ns" 'BEGIN { exit !(x + 0 > 0) }' || fail "ns_per_pair '$ns' for $w $p"
    printf '%s\n' "$line" | grep -q '"speedup_vs_scalar": 1,' || fail "scalar row's speedup is not 1 ($w $p)"
  done
done

# FCL rows when the FCL program was built next to ttd.
if [ -x "$(dirname "$ttd")/ttd_fcl_bench" ]; then
  grep -q '"method": "fcl"' "$tmp/out.json" || fail "ttd_fcl_bench exists but there are no fcl rows"
fi

# The JSON parses, where a parser is at hand.
if command -v python3 >/dev/null 2>&1; then
  python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); assert len(d["rows"]) > 0' "$tmp/out.json" ||
    fail "the JSON does not parse"
fi

"$ttd" bench --quick --csv --quiet --no-probes --no-fcl --workloads paper --methods exact > "$tmp/out.csv" ||
  fail "ttd bench --csv exited with $?"
head -n 1 "$tmp/out.csv" | grep -q '^workload,method,precision,isa,lanes,threads,pairs,' || fail "CSV header"
[ "$(wc -l < "$tmp/out.csv")" -ge 3 ] || fail "CSV has no rows"
echo "test_bench: ok ($rows rows)"
