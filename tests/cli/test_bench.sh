#!/bin/sh
# Smoke test of the benchmark (CI runs it through CTest): `ttd bench --quick --json` must
# finish, produce rows with the required fields and positive times for the exact method on
# the scalar code, include FCL rows when ttd_fcl_bench sits next to ttd, and `--csv` must
# start with its header; the rows of `ttd dist` itself (cli-text, cli-binary) must be there and
# their printed distances right. An instruction set the machine cannot run is an error (exit 2) that
# names it and lists the machine's; a run that measures nothing exits 1; a load average above
# the core count (from a file given in TTD_BENCH_LOADAVG) gives a warning on standard error and
# in the table's header. The mesh section (issue 9) of the quick run is checked too: its rows,
# placements and targets, and agreement with FCL's mesh program when that is built; so is the
# scene section (issue 17): its rows and, with FCL's scene program, agreement with FCL.
# Timings are not checked: they belong to the benchmark, not to tests.
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

# The command line's own rows: `ttd dist` as text and as binary, both precisions, a positive
# time, and the distances it printed agree with the exact method (disagree 0).
for w in cli-text cli-binary; do
  for p in double float; do
    line=$(grep "\"workload\": \"$w\", \"method\": \"exact\", \"precision\": \"$p\"" "$tmp/out.json" | head -n 1)
    [ -n "$line" ] || fail "no $w $p row"
    ns=$(printf '%s\n' "$line" | sed 's/.*"ns_per_pair": \([^,]*\),.*/\1/')
    awk -v x="$ns" 'BEGIN { exit !(x + 0 > 0) }' || fail "ns_per_pair '$ns' for $w $p"
    printf '%s\n' "$line" | grep -q '"disagree": 0,' || fail "$w $p: the printed distances disagree with the exact method"
  done
done

# FCL rows when the FCL program was built next to ttd.
if [ -x "$(dirname "$ttd")/ttd_fcl_bench" ]; then
  grep -q '"method": "fcl"' "$tmp/out.json" || fail "ttd_fcl_bench exists but there are no fcl rows"
fi

# The mesh section (issue 9) of the same quick run: generated meshes only (no file, no network),
# one row per line. Every workload and query is there, every ttd time is positive, the placements
# are where docs/benchmark.md says (ttd's distance within 1% of 1, 0.01 and 0.002 of the size;
# overlap: 0) and each distance row found the placement's distance; the eight targets each have a
# verdict. With FCL's mesh program next to ttd: FCL measured every row that has a counterpart,
# its distances agree with ttd's within 1e-12, its pair counts equal ttd's (double), and nothing
# disagrees. No timing is checked.
grep -q '^  "mesh": {"quick": true, ' "$tmp/out.json" || fail "no mesh section in the quick JSON"
grep '^      {"workload": ' "$tmp/out.json" > "$tmp/mesh.rows" || fail "no mesh rows"
for w in icosphere torus-small poses-ico; do
  for q in build distance collide collide+m contacts closest; do
    [ "$w" = poses-ico ] && [ "$q" != distance ] && continue
    grep "\"workload\": \"$w\"" "$tmp/mesh.rows" | grep -q "\"query\": \"$q\"" || fail "no mesh row $w $q"
  done
done
grep '"query": "contacts"' "$tmp/mesh.rows" | grep -q '"precision": "float"' || fail "no float contacts row"
grep -q '"pose": "random", .*"threads": 2,' "$tmp/mesh.rows" || fail "no 2-thread random-poses row"
field() { sed "s/.*\"$1\": \([^,]*\),.*/\1/"; }
bad=$(field ms < "$tmp/mesh.rows" | awk '!($1 + 0 > 0)' | wc -l)
[ "$bad" -eq 0 ] || fail "$bad mesh rows without a positive time"
# two threads over one timed alternately (issue 36 target 5): the median of at least 3 rounds'
# ratios, within the rounds' range
thread_ratio_ok() {
  while read -r line; do
    x=$(printf '%s\n' "$line" | field x_threads)
    lo=$(printf '%s\n' "$line" | field x_threads_lo)
    hi=$(printf '%s\n' "$line" | field x_threads_hi)
    n=$(printf '%s\n' "$line" | field thread_rounds)
    awk -v x="$x" -v lo="$lo" -v hi="$hi" -v n="$n" \
      'BEGIN { exit !(lo + 0 > 0 && lo + 0 <= x + 0 && x + 0 <= hi + 0 && n + 0 >= 3) }' ||
      fail "$2: two threads over one $x, range $lo-$hi, $n rounds: $line"
  done < "$1"
}
grep '"pose": "random", .*"threads": 2,' "$tmp/mesh.rows" > "$tmp/poses2.rows"
thread_ratio_ok "$tmp/poses2.rows" "mesh random poses"
for pl in far:1 near:0.01 contact:0.002 overlap:0; do
  pose=${pl%%:*}; want=${pl#*:}
  grep "\"pose\": \"$pose\", \"query\": \"distance\"" "$tmp/mesh.rows" > "$tmp/pl.rows" || fail "no $pose rows"
  while read -r line; do
    d=$(printf '%s\n' "$line" | field pose_distance)
    v=$(printf '%s\n' "$line" | field value)
    awk -v d="$d" -v v="$v" -v w="$want" 'BEGIN { ok = (w == 0) ? (d == 0) : (d >= 0.99 * w && d <= 1.01 * w); exit !(ok && d == v) }' ||
      fail "$pose placement: distance $d, query $v, want $want within 1%"
  done < "$tmp/pl.rows"
done
[ "$(grep -c '"verdict": "\(met\|MISSED\|n/a\)"' "$tmp/out.json")" -eq 8 ] || fail "the mesh targets are not 8 with a verdict"
if [ -x "$(dirname "$ttd")/ttd_fcl_mesh_bench" ]; then
  grep -q '"disagreements": 0,' "$tmp/out.json" || fail "ttd and FCL disagree in the mesh section"
  grep -v '"query": "collide+m"' "$tmp/mesh.rows" | grep -v '"fcl": "measured"' | grep -q . &&
    fail "mesh rows without FCL although ttd_fcl_mesh_bench exists"
  grep '"query": "distance"' "$tmp/mesh.rows" | field diff | awk '!($1 + 0 <= 1e-12)' | grep -q . &&
    fail "a distance differs from FCL's by more than 1e-12"
  grep '"query": "contacts", "precision": "double"' "$tmp/mesh.rows" | while read -r line; do
    [ "$(printf '%s\n' "$line" | field value)" = "$(printf '%s\n' "$line" | field fcl_value)" ] ||
      fail "contacts: ttd's pair count differs from FCL's: $line"
  done
fi

# The mesh section's table and CSV, without FCL: the section, its target lines (n/a without FCL),
# and a missing bunny said so, by path, while the other workloads go on. Bad names: exit 2.
"$ttd" bench --quick --no-probes --no-fcl --mesh-workloads icosphere,bunny --bunny "$tmp/no-bunny.obj" \
  --out "$tmp/mesh" > "$tmp/mesh.txt" 2> "$tmp/mesh.err" || fail "mesh table run exited with $?"
grep -q '^Mesh queries (issue 9)' "$tmp/mesh.txt" || fail "no mesh section in the table"
grep -q '^icosphere .* distance ' "$tmp/mesh.txt" || fail "no icosphere distance row in the table"
grep -q 'n/a: FCL absent' "$tmp/mesh.txt" || fail "targets without FCL are not n/a"
grep -q "no-bunny.obj" "$tmp/mesh.err" || fail "the missing bunny is not named: $(cat "$tmp/mesh.err")"
grep -q '^bunny: missing' "$tmp/mesh.txt" || fail "the table does not say the bunny is missing"
head -n 1 "$tmp/mesh/bench-mesh.csv" | grep -q '^workload,triangles,pose,' || fail "bench-mesh.csv header"
[ "$(wc -l < "$tmp/mesh/bench-mesh.csv")" -ge 10 ] || fail "bench-mesh.csv has too few rows"
rc=0
"$ttd" bench --quick --mesh-workloads icosphere,nosuch > /dev/null 2> "$tmp/err.txt" || rc=$?
[ "$rc" -eq 2 ] || fail "--mesh-workloads nosuch: exit status $rc, want 2"
grep -q "nosuch" "$tmp/err.txt" || fail "--mesh-workloads nosuch: not named"

# The scene section (issue 17) of the same quick run: generated scenes only (the bunnies are left
# out with --quick), every row with a positive time, the motion on 1 and 2 threads; with FCL's
# scene program next to ttd, FCL measured beside every row and no disagreement.
grep -q '^  "scene": {"quick": true, ' "$tmp/out.json" || fail "no scene section in the quick JSON"
grep '^        {"workload": ' "$tmp/out.json" > "$tmp/scene.rows" || fail "no scene rows"
for w in icospheres mixed sparse; do
  for q in build collide collide+m distance contacts; do
    grep "\"workload\": \"$w\"" "$tmp/scene.rows" | grep -q "\"query\": \"$q\"" || fail "no scene row $w $q"
  done
done
# issue 32's tower in four triangulations: its contacts and manifold rows, the manifold's ratio
# to the contacts in CPU time too
for w in tower-plain tower-centre tower-cut tower-sliver; do
  for q in contacts manifold-4; do
    grep "\"workload\": \"$w\"" "$tmp/scene.rows" | grep -q "\"query\": \"$q\"" || fail "no scene row $w $q"
  done
  grep "\"workload\": \"$w\"" "$tmp/scene.rows" | grep '"query": "manifold-4"' | grep -q '"x_ref_cpu": [0-9]' ||
    fail "no $w manifold-4 row with its CPU-time ratio"
done
grep '"query": "contacts"' "$tmp/scene.rows" | grep -q '"precision": "float"' || fail "no float scene contacts row"
grep '"query": "motion"' "$tmp/scene.rows" | grep -q '"threads": 2,' || fail "no 2-thread motion row"
for q in manifold-4 manifold-0 distance+n; do # issue 23's ratios: against ttd's contacts and distance
  grep "\"query\": \"$q\"" "$tmp/scene.rows" | grep -q '"x_ref": [0-9]' || fail "no $q row with its ratio"
done
grep '"query": "contacts"' "$tmp/scene.rows" | grep -q '"threads": 2,' || fail "no 2-thread contacts row"
# the manifold's verdict is read from the alternating CPU-time ratio where it was measured
bad=$(grep '"query": "manifold-4"' "$tmp/scene.rows" | grep '"x_ref_cpu": [0-9]' |
  sed 's/.*"x_ref_cpu": \([^,]*\),.*"target": \([^,]*\),.*"met": \([a-z]*\),.*/\1 \2 \3/' |
  awk '{ want = ($1 + 0 <= $2 + 0) ? "true" : "false"; if ($3 != want) print }' | wc -l)
[ "$bad" -eq 0 ] || fail "$bad manifold-4 rows whose verdict disagrees with their CPU-time ratio"
grep '"threads": 2,' "$tmp/scene.rows" > "$tmp/scene2.rows"
[ "$(grep -c '"target_of": "x_threads"' "$tmp/scene2.rows")" -eq "$(wc -l < "$tmp/scene2.rows")" ] ||
  fail "a 2-thread scene row without its x_threads target"
thread_ratio_ok "$tmp/scene2.rows" "scene"
# with Bullet's program next to ttd: its time beside every manifold-4 row (issue 26)
if [ -x "$(dirname "$ttd")/ttd_bullet_scene_bench" ]; then
  bad=$(grep '"query": "manifold-4"' "$tmp/scene.rows" | field bullet_ms | awk '!($1 + 0 > 0)' | wc -l)
  [ "$bad" -eq 0 ] || fail "$bad manifold-4 rows without Bullet's time although ttd_bullet_scene_bench exists"
fi
bad=$(field ms < "$tmp/scene.rows" | awk '!($1 + 0 > 0)' | wc -l)
[ "$bad" -eq 0 ] || fail "$bad scene rows without a positive time"
if [ -x "$(dirname "$ttd")/ttd_fcl_scene_bench" ]; then
  grep '^  "scene": ' "$tmp/out.json" | grep -q '"disagreements": 0,' || fail "ttd and FCL disagree in the scene section"
  # FCL has no manifold and no per-body nearest: those rows are timed against ttd's own contacts and
  # distance instead (issue 23); the two-thread rows are against ttd's own one thread (issue 26)
  bad=$(grep -v -e '"query": "manifold-' -e '"query": "distance+n"' -e '"target_of": "x_threads"' "$tmp/scene.rows" |
        field fcl_ms | awk '!($1 + 0 > 0)' | wc -l)
  [ "$bad" -eq 0 ] || fail "$bad scene rows without FCL's time although ttd_fcl_scene_bench exists"
fi
# --scene-write: the quick icospheres written for `ttd scene`, which reads them back to the same
# answer as the benchmark's rows (the bits of every pose and vertex survive the text)
mkdir "$tmp/scenes"
"$ttd" bench --quick --no-probes --no-fcl --scene-workloads icospheres --scene-write "$tmp/scenes" --json \
  > "$tmp/w.json" 2> "$tmp/w.err" || fail "--scene-write run exited with $?"
for f in icospheres.txt icospheres-mesh0.obj icospheres-motion.txt; do
  [ -s "$tmp/scenes/$f" ] || fail "--scene-write: no $f"
done
grep '^        {"workload": ' "$tmp/w.json" > "$tmp/w.rows"
for q in contacts collide+m; do
  want=$(grep "\"query\": \"$q\"" "$tmp/w.rows" | grep '"precision": "double"' | head -n 1 | field value)
  cmd=contacts; [ "$q" = contacts ] || cmd=collide
  got=$("$ttd" scene $cmd "$tmp/scenes/icospheres.txt" --margin 0.01 --count) || fail "ttd scene $cmd on the written scene"
  [ "$got" = "$want" ] || fail "--scene-write: ttd scene $cmd counts $got, the benchmark's $q row $want"
done
# the tower the benchmark writes is scripts/tower_scene.py's (the same meshes and poses, so the
# same manifold to the bit)
"$ttd" bench --quick --no-probes --no-fcl --scene-workloads tower-cut --scene-write "$tmp/scenes" > /dev/null 2>&1 ||
  fail "--scene-write tower-cut exited with $?"
if /usr/bin/python3 "$(dirname "$0")/../../scripts/tower_scene.py" "$tmp/towers" 2> /dev/null; then
  a=$("$ttd" scene manifold "$tmp/scenes/tower-cut.txt" --margin 0.01 | cksum)
  b=$("$ttd" scene manifold "$tmp/towers/tower-cut.txt" --margin 0.01 | cksum)
  [ "$a" = "$b" ] || fail "the benchmark's tower-cut is not scripts/tower_scene.py's"
fi
rc=0
"$ttd" bench --quick --scene-workloads icospheres,nosuch > /dev/null 2> "$tmp/err.txt" || rc=$?
[ "$rc" -eq 2 ] || fail "--scene-workloads nosuch: exit status $rc, want 2"
grep -q "nosuch" "$tmp/err.txt" || fail "--scene-workloads nosuch: not named"

# The JSON parses, where a parser is at hand.
if command -v python3 >/dev/null 2>&1; then
  python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); assert len(d["rows"]) > 0; assert len(d["scene"]["rows"]) > 0' "$tmp/out.json" ||
    fail "the JSON does not parse"
fi

"$ttd" bench --quick --csv --quiet --no-probes --no-fcl --workloads paper --methods exact > "$tmp/out.csv" ||
  fail "ttd bench --csv exited with $?"
head -n 1 "$tmp/out.csv" | grep -q '^workload,method,precision,isa,lanes,threads,pairs,' || fail "CSV header"
[ "$(wc -l < "$tmp/out.csv")" -ge 3 ] || fail "CSV has no rows"
# --save-pairs DIR: the paper workload's 1,000 pairs as `ttd dist --binary-in` reads them (18
# numbers a pair, S then T; float64 and float32), each giving the paper pair's distance as text
# input does; a folder that cannot be written: exit status 1, the file named.
mkdir -p "$tmp/pairs"
"$ttd" bench --quick --quiet --no-probes --no-fcl --workloads paper --methods exact --save-pairs "$tmp/pairs" \
  > /dev/null || fail "ttd bench --save-pairs exited with $?"
[ "$(stat -c %s "$tmp/pairs/paper.f64")" = 144000 ] || fail "--save-pairs: paper.f64 is not 1000 x 18 doubles"
[ "$(stat -c %s "$tmp/pairs/paper.f32")" = 72000 ] || fail "--save-pairs: paper.f32 is not 1000 x 18 floats"
echo "0 0 0 1 0 0 0 1 0 0.3 0.3 0.5 1 0.5 1.2 0.4 1.1 0.9" > "$tmp/paper.txt"
for prec in double float; do
  ext=f64; [ $prec = float ] && ext=f32
  want=$("$ttd" dist --precision $prec "$tmp/paper.txt") || fail "ttd dist on the paper pair"
  "$ttd" dist --precision $prec --binary-in "$tmp/pairs/paper.$ext" > "$tmp/saved.txt" ||
    fail "ttd dist --binary-in on paper.$ext"
  [ "$(wc -l < "$tmp/saved.txt")" = 1000 ] && [ "$(sort -u "$tmp/saved.txt")" = "$want" ] ||
    fail "--save-pairs: paper.$ext does not hold the paper pair 1000 times ($prec)"
done
rc=0
"$ttd" bench --quick --quiet --no-probes --no-fcl --workloads paper --methods exact \
  --save-pairs "$tmp/no-such-dir" > /dev/null 2> "$tmp/err.txt" || rc=$?
[ $rc = 1 ] && grep -q "cannot write $tmp/no-such-dir/paper.f64" "$tmp/err.txt" ||
  fail "--save-pairs into a missing folder: exit $rc, $(cat "$tmp/err.txt")"

# An instruction set this machine cannot run: exit 2 before anything is timed, naming the one
# asked for and listing what the machine has (the "cpu:" line of ttd info).
built=$("$ttd" info | sed -n 's/^built://p')
cpu=$("$ttd" info | sed -n 's/^cpu://p')
unavailable=0
for isa in sse2 avx2 avx512 neon; do
  case " $built " in *" $isa "*) case " $cpu " in *" $isa "*) continue ;; esac ;; esac
  unavailable=$((unavailable + 1))
  rc=0
  "$ttd" bench --quick --no-probes --no-fcl --workloads paper --methods exact --isa "$isa" > "$tmp/out.txt" 2> "$tmp/err.txt" || rc=$?
  [ "$rc" -eq 2 ] || fail "--isa $isa (unavailable): exit status $rc, want 2"
  grep -q "$isa" "$tmp/err.txt" || fail "--isa $isa: the message does not name it: $(cat "$tmp/err.txt")"
  grep -q "^cpu: *scalar" "$tmp/err.txt" || fail "--isa $isa: the message does not list the machine's: $(cat "$tmp/err.txt")"
  [ ! -s "$tmp/out.txt" ] || fail "--isa $isa: a table was written"
  rc=0
  "$ttd" bench --quick --no-probes --no-fcl --workloads paper --methods exact --isa "scalar,$isa" > /dev/null 2>&1 || rc=$?
  [ "$rc" -eq 2 ] || fail "--isa scalar,$isa: exit status $rc, want 2"
done
[ "$unavailable" -gt 0 ] || echo "test_bench: every ISA is available here; unavailable --isa not exercised"

# Nothing to measure (the barrier method has no SIMD kernel): an error, not "done: 0 rows".
auto=$("$ttd" info | sed -n 's/^auto: *\([a-z0-9]*\).*/\1/p')
if [ "$auto" != scalar ]; then
  rc=0
  "$ttd" bench --quick --no-probes --no-fcl --workloads paper --methods barrier --isa "$auto" > /dev/null 2> "$tmp/err.txt" || rc=$?
  [ "$rc" -eq 1 ] || fail "no rows: exit status $rc, want 1"
  grep -q "no rows" "$tmp/err.txt" || fail "no rows: message '$(cat "$tmp/err.txt")'"
fi

# Load average above the online cores (read from TTD_BENCH_LOADAVG in place of /proc/loadavg):
# a warning on standard error and in the table's header; none when the load is 0.
"$ttd" info > "$tmp/info.txt"
cores=$(sed -n 's/^threads: \([0-9]*\) online cores.*/\1/p' "$tmp/info.txt")
[ -n "$cores" ] || fail "no core count in ttd info"
printf '%d.50 1.00 1.00 3/200 12345\n' "$cores" > "$tmp/loadavg"
TTD_BENCH_LOADAVG="$tmp/loadavg" "$ttd" bench --quick --no-probes --no-fcl --workloads paper --methods exact \
  --precision double --isa scalar > "$tmp/table.txt" 2> "$tmp/err.txt" || fail "loaded run exited with $?"
grep -q "warning: .*load average" "$tmp/err.txt" || fail "no load warning on stderr: $(cat "$tmp/err.txt")"
sed -n '1,/^workload /p' "$tmp/table.txt" | grep -q "WARNING: .*load average" || fail "no load warning in the table header"
printf '0.00 0.00 0.00 1/200 12345\n' > "$tmp/loadavg"
TTD_BENCH_LOADAVG="$tmp/loadavg" "$ttd" bench --quick --no-probes --no-fcl --workloads paper --methods exact \
  --precision double --isa scalar > "$tmp/table.txt" 2> "$tmp/err.txt" || fail "quiet run exited with $?"
grep -qi "load average .*exceeds" "$tmp/err.txt" "$tmp/table.txt" && fail "load warning at load 0"

# `ttd bench points`: each mesh's label matches the triangles it has (--quick's torus is 10,000
# triangles, not the full run's million).
"$ttd" bench points --quick --no-refs --meshes torus --points 200 --threads 1 > "$tmp/points.txt" 2> "$tmp/points_err.txt" ||
  fail "ttd bench points --quick exited with $?"
grep -q "torus 10k (10000 triangles)" "$tmp/points_err.txt" || fail "points bench torus label: $(cat "$tmp/points_err.txt")"
grep -q "torus 1M" "$tmp/points.txt" "$tmp/points_err.txt" && fail "--quick's 10,000-triangle torus labelled 1M"

echo "test_bench: ok ($rows rows)"
