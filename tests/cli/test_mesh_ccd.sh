#!/bin/sh
# SPDX-License-Identifier: MIT
# `ttd mesh-ccd` on OBJ files this script writes: a triangle falling through a square at
# t = 1/2 (two meshes, and the same as one mesh against itself), --min-separation, --summary,
# --float, --shared-vertex; and the error paths (exit 2 for the command line, 1 for files that do
# not match). Only POSIX sh and awk. Usage: sh test_mesh_ccd.sh path/to/ttd
set -u
TTD=${1:?usage: test_mesh_ccd.sh path/to/ttd}
DIR=$(mktemp -d) || exit 1
trap 'rm -rf "$DIR"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
pass() { echo "ok   $*"; }

square() { printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n'; }
tri() { # $1: z
    printf 'v 0.25 0.25 %s\nv 0.75 0.25 %s\nv 0.25 0.75 %s\nf 1 2 3\n' "$1" "$1" "$1"
}
square > "$DIR/a.obj"
tri 1 > "$DIR/b0.obj"
tri -1 > "$DIR/b1.obj"
tri 1.5 > "$DIR/b_miss.obj"
tri 2 > "$DIR/b_high.obj"

out=$("$TTD" mesh-ccd "$DIR/a.obj" "$DIR/a.obj" "$DIR/b0.obj" "$DIR/b1.obj") || fail "two meshes exited $?"
echo "$out" | awk 'NR == 1 { exit !($1 == "toi" && $2 <= 0.5 && $2 > 0.4999 && $3 == "pairs" && $4 >= 3) }' ||
    fail "the falling triangle: $out"
# b's three vertices reach the square's face (fv) at t = 1/2: each is one line
[ "$(echo "$out" | awk '$1 == "fv"' | wc -l)" -ge 3 ] || fail "the vertex-face pairs: $out"
pass "a triangle falling through a square: toi 1/2, its vertices' pairs"

out=$("$TTD" mesh-ccd --summary "$DIR/a.obj" "$DIR/a.obj" "$DIR/b0.obj" "$DIR/b_miss.obj") || fail "miss exited $?"
[ "$(echo "$out" | wc -l)" -eq 1 ] || fail "--summary printed more than one line: $out"
echo "$out" | awk '{ exit !($2 == "inf" && $4 == 0) }' || fail "a miss: $out"
# from z = 2 down to z = 1: within 1.25 of the square from t = 0.75 on
out=$("$TTD" mesh-ccd --summary --min-separation 1.25 "$DIR/a.obj" "$DIR/a.obj" "$DIR/b_high.obj" "$DIR/b0.obj") ||
    fail "min-separation exited $?"
echo "$out" | awk '{ exit !($2 <= 0.75 && $2 > 0.7499 && $4 >= 1) }' || fail "--min-separation 1.25: $out"
out=$("$TTD" mesh-ccd --summary --min-separation 0.75 "$DIR/a.obj" "$DIR/a.obj" "$DIR/b_high.obj" "$DIR/b0.obj")
echo "$out" | awk '{ exit !($2 == "inf") }' || fail "--min-separation 0.75: $out"
pass "--summary, a miss, and --min-separation"

# one mesh of both: the square's vertices first, then the triangle's (indices 4..6)
{ square; tri 1 | sed 's/^f 1 2 3$/f 5 6 7/'; } > "$DIR/s0.obj"
{ square; tri -1 | sed 's/^f 1 2 3$/f 5 6 7/'; } > "$DIR/s1.obj"
self=$("$TTD" mesh-ccd "$DIR/s0.obj" "$DIR/s1.obj") || fail "self exited $?"
two=$("$TTD" mesh-ccd "$DIR/a.obj" "$DIR/a.obj" "$DIR/b0.obj" "$DIR/b1.obj")
[ "$(echo "$self" | awk 'NR == 1 { print $2 }')" = "$(echo "$two" | awk 'NR == 1 { print $2 }')" ] ||
    fail "self and two meshes differ: $self / $two"
echo "$self" | awk 'NR > 1 && $1 != "vf" && $1 != "ee" { exit 1 }' || fail "self kinds: $self"
"$TTD" mesh-ccd --shared-vertex --float --threads 1 "$DIR/s0.obj" "$DIR/s1.obj" > /dev/null || fail "--shared-vertex --float"
pass "one mesh against itself gives the same toi; --shared-vertex, --float"

"$TTD" mesh-ccd "$DIR/a.obj" > /dev/null 2>&1; [ $? -eq 2 ] || fail "one file: not exit 2"
"$TTD" mesh-ccd --min-separation -1 "$DIR/s0.obj" "$DIR/s1.obj" > /dev/null 2>&1; [ $? -eq 2 ] || fail "negative: not exit 2"
"$TTD" mesh-ccd --shared-vertex "$DIR/a.obj" "$DIR/a.obj" "$DIR/b0.obj" "$DIR/b1.obj" > /dev/null 2>&1
[ $? -eq 2 ] || fail "--shared-vertex with two meshes: not exit 2"
"$TTD" mesh-ccd "$DIR/a.obj" "$DIR/b0.obj" > "$DIR/o" 2>&1; [ $? -eq 1 ] || fail "mismatched files: not exit 1"
grep -q "same triangles" "$DIR/o" || fail "mismatched files: $(cat "$DIR/o")"
"$TTD" mesh-ccd "$DIR/a.obj" "$DIR/none.obj" > /dev/null 2>&1; [ $? -eq 1 ] || fail "a missing file: not exit 1"
"$TTD" mesh-ccd --help | grep -q "usage: ttd mesh-ccd" || fail "--help"
pass "errors: exit 2 for the command line, 1 for the files"
