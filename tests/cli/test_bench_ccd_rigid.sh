#!/bin/sh
# SPDX-License-Identifier: MIT
# `ttd bench ccd --rigid` on a few motions: its rows (an icosphere and two tori; the bunny row
# skipped or measured), hits within the motions, the scene's step on 1 and 2 threads with the
# same hits and their ratio timed alternately, within its rounds' range; with FCL's program beside ttd, every motion where ttd and FCL disagree settled by
# the sampled distance never in FCL's favour (the "fcl" column of "right" is 0): a check on ttd.
# Usage: sh test_bench_ccd_rigid.sh path/to/ttd
set -u
TTD=${1:?usage: test_bench_ccd_rigid.sh path/to/ttd}
fail() { echo "FAIL: $*" >&2; exit 1; }
pass() { echo "ok   $*"; }

out=$("$TTD" bench ccd --rigid --motions 6 --reps 1 --bodies 40) || fail "exited $?: $out"
# the first '|' segment ends: tris motions hits steps most ms
rows=$(echo "$out" | awk -F'|' '/^(icosphere|torus)/ { n = split($1, f, " "); if (f[n - 4] == 6 && f[n - 3] >= 0 && f[n - 3] <= 6) print }' | wc -l)
[ "$rows" -eq 3 ] || fail "expected 3 rows of 6 motions: $out"
hits=$(echo "$out" | awk '/^scene step/ { for (i = 1; i <= NF; ++i) if ($i == "hit;") print $(i - 1) }' | sort -u | wc -l)
[ "$hits" -eq 1 ] || fail "the scene's step: 1 and 2 threads differ: $out"
echo "$out" | awk '/^scene step, .* two threads over one, alternating: / {
    split($0, a, "alternating: "); split(a[2], f, /[x( ,-]+/); ok = f[1] > 0 && f[2] >= 3 && f[4] <= f[1] + 0 && f[1] <= f[5] + 0 }
  END { exit !ok }' || fail "the scene's step: no two-thread ratio within its rounds' range: $out"
pass "rows and the scene's step"
if [ -x "$(dirname "$TTD")/ttd_fcl_ccd_bench" ]; then
    # segments between the bars: 2 FCL (RSS) hits, ms, ratio; 3 hit only in ttd, FCL, max |dtoi|; 4 right: ttd,
    # FCL, open; 5 FCL OBBRSS hits
    bad=$(echo "$out" | awk -F'|' '/^(icosphere|torus)/ { split($4, r, " "); if (r[2] != 0) print }')
    [ -z "$bad" ] || fail "the sampled distance proved FCL right and ttd wrong: $bad"
    echo "$out" | grep -q "^FCL: .*ttd_fcl_ccd_bench" || fail "FCL's program exists but was not run: $out"
    pass "FCL beside it; no disagreement settled in FCL's favour"
fi
"$TTD" bench ccd --rigid --bogus > /dev/null 2>&1 && fail "a bad option exited 0"
pass "a bad option: exit 2"
exit 0
