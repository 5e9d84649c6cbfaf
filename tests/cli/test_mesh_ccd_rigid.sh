#!/bin/sh
# SPDX-License-Identifier: MIT
# `ttd mesh-ccd-rigid` on a cube this script writes: a second cube sliding into the first (toi
# 2/3), stopping short (no hit), a quarter turn that swings a corner into it, --min-separation,
# --float, poses from standard input; and the error paths (exit 2 for the command line, 1 for
# files and refused poses). Only POSIX sh and awk. Usage: sh test_mesh_ccd_rigid.sh path/to/ttd
set -u
TTD=${1:?usage: test_mesh_ccd_rigid.sh path/to/ttd}
DIR=$(mktemp -d) || exit 1
trap 'rm -rf "$DIR"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
pass() { echo "ok   $*"; }

printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n' > "$DIR/cube.obj"
printf 'f 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\nf 1 2 6\nf 1 6 5\nf 3 7 8\nf 3 8 4\nf 1 5 7\nf 1 7 3\nf 2 4 8\nf 2 8 6\n' >> "$DIR/cube.obj"
I="1 0 0 0  0 1 0 0  0 0 1 0"
at() { printf '1 0 0 %s  0 1 0 0  0 0 1 0' "$1"; }
poses() { printf '%s\n%s\n%s\n%s\n' "$I" "$I" "$(at "$1")" "$(at "$2")" > "$DIR/$3"; }
poses 3 0 slide.txt
poses 3 1.5 short.txt

out=$("$TTD" mesh-ccd-rigid "$DIR/cube.obj" "$DIR/cube.obj" "$DIR/slide.txt") || fail "slide exited $?"
echo "$out" | awk '{ exit !($1 == "hit" && $2 == 1 && $4 <= 2 / 3 && $4 > 2 / 3 - 1e-6 && $6 <= 1e-8) }' ||
    fail "slide: $out"
pass "a cube sliding into another: toi 2/3"
out=$("$TTD" mesh-ccd-rigid "$DIR/cube.obj" "$DIR/cube.obj" "$DIR/short.txt") || fail "short exited $?"
echo "$out" | awk '{ exit !($2 == 0 && $4 == "inf" && $12 == -1) }' || fail "stopping short: $out"
out=$("$TTD" mesh-ccd-rigid --min-separation 0.6 "$DIR/cube.obj" "$DIR/cube.obj" "$DIR/short.txt") || fail "exited $?"
echo "$out" | awk '{ exit !($2 == 1 && $4 < 1 && $4 > 0.9) }' || fail "stopping 0.5 short, D 0.6: $out"
out=$("$TTD" mesh-ccd-rigid --float "$DIR/cube.obj" "$DIR/cube.obj" "$DIR/slide.txt") || fail "float exited $?"
echo "$out" | awk '{ exit !($2 == 1 && $4 <= 2 / 3 && $4 > 2 / 3 - 1e-3) }' || fail "float: $out"
pass "stopping short; --min-separation; --float"
# A quarter turn of A about z through its origin carries its corner (1, 0) round to (0, 1), into B
# sitting at y in [1.2, 2.2] above x in [-0.5, 0.5]; no pose at either end touches.
printf '%s\n0 -1 0 0  1 0 0 0  0 0 1 0\n1 0 0 -0.5  0 1 0 1.2  0 0 1 0\n1 0 0 -0.5  0 1 0 1.2  0 0 1 0\n' "$I" > "$DIR/turn.txt"
out=$("$TTD" mesh-ccd-rigid "$DIR/cube.obj" "$DIR/cube.obj" "$DIR/turn.txt") || fail "turn exited $?"
echo "$out" | awk '{ exit !($2 == 1 && $4 > 0 && $4 < 1) }' || fail "a quarter turn into a cube: $out"
# the other way round (-90 degrees) the cube keeps below y = 1: no contact
printf '%s\n0 1 0 0  -1 0 0 0  0 0 1 0\n1 0 0 -0.5  0 1 0 1.2  0 0 1 0\n1 0 0 -0.5  0 1 0 1.2  0 0 1 0\n' "$I" > "$DIR/back.txt"
out=$("$TTD" mesh-ccd-rigid "$DIR/cube.obj" "$DIR/cube.obj" "$DIR/back.txt") || fail "back exited $?"
echo "$out" | awk '{ exit !($2 == 0) }' || fail "a quarter turn away from the cube: $out"
out=$(cat "$DIR/slide.txt" | "$TTD" mesh-ccd-rigid "$DIR/cube.obj" "$DIR/cube.obj" -) || fail "stdin exited $?"
echo "$out" | awk '{ exit !($2 == 1) }' || fail "poses from standard input: $out"
pass "a quarter turn; poses from standard input"

"$TTD" mesh-ccd-rigid "$DIR/cube.obj" "$DIR/cube.obj" > /dev/null 2>&1; [ $? -eq 2 ] || fail "two files: not exit 2"
"$TTD" mesh-ccd-rigid --min-separation -1 "$DIR/cube.obj" "$DIR/cube.obj" "$DIR/slide.txt" > /dev/null 2>&1
[ $? -eq 2 ] || fail "negative separation: not exit 2"
printf '1 2 3\n' > "$DIR/few.txt"
"$TTD" mesh-ccd-rigid "$DIR/cube.obj" "$DIR/cube.obj" "$DIR/few.txt" > /dev/null 2>&1; [ $? -eq 1 ] || fail "3 numbers: not exit 1"
printf '%s\n%s\n2 0 0 3  0 1 0 0  0 0 1 0\n%s\n' "$I" "$I" "$I" > "$DIR/scaled.txt"
err=$("$TTD" mesh-ccd-rigid "$DIR/cube.obj" "$DIR/cube.obj" "$DIR/scaled.txt" 2>&1 >/dev/null); [ $? -eq 1 ] || fail "a scaled pose: not exit 1"
echo "$err" | grep -q "pose 3" || fail "a scaled pose not named: $err"
printf '%s\n%s\n%s\nnan 0 0 0  0 1 0 0  0 0 1 0\n' "$I" "$I" "$I" > "$DIR/nan.txt"
"$TTD" mesh-ccd-rigid "$DIR/cube.obj" "$DIR/cube.obj" "$DIR/nan.txt" > /dev/null 2>&1; [ $? -eq 1 ] || fail "NaN: not exit 1"
"$TTD" mesh-ccd-rigid "$DIR/none.obj" "$DIR/cube.obj" "$DIR/slide.txt" > /dev/null 2>&1; [ $? -eq 1 ] || fail "missing file: not exit 1"
pass "errors: exit 2 for the command line, 1 for files and poses"
exit 0
