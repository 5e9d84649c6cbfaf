#!/bin/sh
# SPDX-License-Identifier: MIT
# `ttd ccd FILE` on CSV files of the CCD benchmark's format this script writes: a vertex falling
# through a face at t = 1/2 (truth 1) and one passing beside it (truth 0); a line per query
# (index, hit, toi, truth) and the totals (false negatives and positives against the truth);
# --kind, --min-separation (the beside query then hits), --summary; and the error paths (exit 2
# for the command line, 1 for a bad file). Only POSIX sh and awk. Usage: sh test_ccd.sh path/to/ttd
set -u
TTD=${1:?usage: test_ccd.sh path/to/ttd}
DIR=$(mktemp -d) || exit 1
trap 'rm -rf "$DIR"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
pass() { echo "ok   $*"; }

# v, f0, f1, f2 at t = 0, then at t = 1; x y z as numerator,denominator; the truth last.
query() { # $1 $2: the vertex's x and y (as n,d pairs), $3 the truth
    printf '%s,%s,1,1,%s\n0,1,0,1,0,1,%s\n1,1,0,1,0,1,%s\n0,1,1,1,0,1,%s\n' "$1" "$2" "$3" "$3" "$3" "$3"
    printf '%s,%s,-1,1,%s\n0,1,0,1,0,1,%s\n1,1,0,1,0,1,%s\n0,1,1,1,0,1,%s\n' "$1" "$2" "$3" "$3" "$3" "$3"
}
mkdir -p "$DIR/vertex-face"
{ query 1,5 1,5 1; query 3,5 3,5 0; } > "$DIR/vertex-face/q.csv"

out=$("$TTD" ccd "$DIR/vertex-face/q.csv") || fail "ttd ccd exited $?"
echo "$out" | awk 'NR == 1 { exit !($1 == 0 && $2 == 1 && $3 <= 0.5 && $3 > 0.4999 && $4 == 1) }' ||
    fail "the falling vertex: $out"
echo "$out" | awk 'NR == 2 { exit !($1 == 1 && $2 == 0 && $3 == "inf" && $4 == 0) }' || fail "the passing vertex: $out"
echo "$out" | grep -q "queries 2 (vertex-face), hits 1, truth 1, false negatives 0, false positives 0" ||
    fail "totals: $out"
pass "a hit at t = 1/2 and a miss, with the totals"

cp "$DIR/vertex-face/q.csv" "$DIR/plain.csv"
"$TTD" ccd "$DIR/plain.csv" > /dev/null 2>&1 && fail "a path without the kind was accepted"
out=$("$TTD" ccd --kind vf --summary --min-separation 0.15 "$DIR/plain.csv") || fail "--kind vf exited $?"
[ "$(echo "$out" | wc -l)" -eq 1 ] || fail "--summary printed more than the totals: $out"
echo "$out" | grep -q "hits 2, truth 1, false negatives 0, false positives 1" || fail "--min-separation 0.15: $out"
pass "--kind, --summary and --min-separation (0.14 from the hypotenuse: a hit at 0.15)"

"$TTD" ccd --kind xx "$DIR/plain.csv" > "$DIR/o" 2>&1; [ $? -eq 2 ] || fail "--kind xx: not exit 2"
"$TTD" ccd --min-separation -1 --kind vf "$DIR/plain.csv" > "$DIR/o" 2>&1; [ $? -eq 2 ] || fail "negative separation: not exit 2"
head -5 "$DIR/vertex-face/q.csv" > "$DIR/vertex-face/short.csv"
"$TTD" ccd "$DIR/vertex-face/short.csv" > "$DIR/o" 2>&1; [ $? -eq 1 ] || fail "5 rows: not exit 1"
grep -q "not a multiple of 8" "$DIR/o" || fail "5 rows: $(cat "$DIR/o")"
printf '1,0,0,1,0,1,0\n' > "$DIR/vertex-face/zero.csv"
"$TTD" ccd "$DIR/vertex-face/zero.csv" > "$DIR/o" 2>&1; [ $? -eq 1 ] || fail "a zero denominator: not exit 1"
"$TTD" ccd "$DIR/vertex-face/missing.csv" > "$DIR/o" 2>&1; [ $? -eq 1 ] || fail "a missing file: not exit 1"
pass "errors: exit 2 for the command line, 1 for bad files"
