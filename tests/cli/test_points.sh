#!/bin/sh
# SPDX-License-Identifier: MIT
# `ttd points closest | signed | winding | grid` on a unit cube this script writes, against answers
# known by construction: points inside, outside along a face, an edge and a vertex, on the surface;
# the closest point and its distance; signs and winding numbers; --upper-bound; --pose (the cube
# moved by 5 along x); float; a .npy points file equal to the text file; a grid written as .npy
# (its header and size) and raw (its size); threads and instruction sets giving identical output;
# and the error paths (exit 2 for the command line, 1 for bad files), with nothing on standard
# output then. Only POSIX sh and awk (and od for the .npy bytes). Usage: sh test_points.sh path/to/ttd
set -u
TTD=${1:?usage: test_points.sh path/to/ttd}
DIR=$(mktemp -d) || exit 1
trap 'rm -rf "$DIR"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
pass() { echo "ok   $*"; }

cat > "$DIR/cube.obj" <<'E'
v 0 0 0
v 1 0 0
v 0 1 0
v 1 1 0
v 0 0 1
v 1 0 1
v 0 1 1
v 1 1 1
f 1 3 4
f 1 4 2
f 5 6 8
f 5 8 7
f 1 2 6
f 1 6 5
f 3 7 8
f 3 8 4
f 1 5 7
f 1 7 3
f 2 4 8
f 2 8 6
E
printf '0.5 0.5 0.5\n# a comment\n\n3 0.5 0.5\n2 2 0.5\n2 2 2\n0.5 0.5 1\n' > "$DIR/p.txt"

out=$("$TTD" points closest "$DIR/cube.obj" "$DIR/p.txt") || fail "closest exit status"
echo "$out" | awk 'NR == 1 && $1 != 0.5 { exit 1 } NR == 2 && ($1 != 2 || $3 != 1 || $4 != 0.5 || $5 != 0.5) { exit 1 }
    NR == 3 && ($1 - sqrt(2) > 1e-15 || $1 - sqrt(2) < -1e-15 || $3 != 1 || $4 != 1 || $5 != 0.5) { exit 1 }
    NR == 4 && ($1 - sqrt(3) > 1e-15 || $1 - sqrt(3) < -1e-15 || $3 != 1 || $4 != 1 || $5 != 1) { exit 1 }
    NR == 5 && $1 != 0 { exit 1 } END { if (NR != 5) exit 1 }' || fail "closest: $out"
pass "closest: inside, along a face, an edge, a vertex, on the surface"

out=$("$TTD" points signed "$DIR/cube.obj" "$DIR/p.txt") || fail "signed exit status"
echo "$out" | awk 'NR == 1 && $1 != -0.5 { exit 1 } NR == 2 && $1 != 2 { exit 1 } END { if (NR != 5) exit 1 }' ||
    fail "signed: $out"
out=$("$TTD" points winding "$DIR/cube.obj" "$DIR/p.txt") || fail "winding exit status"
echo "$out" | awk 'NR == 1 && ($1 < 0.99 || $1 > 1.01) { exit 1 } NR >= 2 && NR <= 4 && ($1 > 0.01 || $1 < -0.01) { exit 1 }
    END { if (NR != 5) exit 1 }' || fail "winding: $out"
pass "signed distance and winding number"

out=$("$TTD" points closest "$DIR/cube.obj" "$DIR/p.txt" --upper-bound 1.5) || fail "bound exit status"
echo "$out" | awk 'NR == 4 && $0 != "inf -1 nan nan nan" { exit 1 } NR == 3 && $2 == -1 { exit 1 }' || fail "bound: $out"
out=$("$TTD" points signed "$DIR/cube.obj" "$DIR/p.txt" --upper-bound 0.2) || fail "signed bound exit status"
echo "$out" | awk 'NR == 1 && $0 != "-inf -1 nan nan nan" { exit 1 }' || fail "signed bound: $out"
pass "--upper-bound"

out=$("$TTD" points closest "$DIR/cube.obj" - --pose "1 0 0 5  0 1 0 0  0 0 1 0" <<'E'
5.5 0.5 0.5
8 0.5 0.5
E
) || fail "pose exit status"
echo "$out" | awk 'NR == 1 && $1 != 0.5 { exit 1 } NR == 2 && ($1 != 2 || $3 != 6) { exit 1 }' || fail "pose: $out"
pass "--pose moves the mesh, points come back in the points' frame"

out=$("$TTD" points closest "$DIR/cube.obj" "$DIR/p.txt" --precision float) || fail "float exit status"
echo "$out" | awk 'NR == 3 && ($1 < 1.4142134 || $1 > 1.4142137) { exit 1 } END { if (NR != 5) exit 1 }' || fail "float: $out"
pass "float"

ref=$("$TTD" points closest "$DIR/cube.obj" "$DIR/p.txt" --isa scalar --threads 1)
n=0
for isa in $("$TTD" info 2>/dev/null | awk '$1 == "cpu:" { for (i = 2; i <= NF; ++i) if ($i != "scalar") print $i }'); do
    for th in 1 2; do
        got=$("$TTD" points closest "$DIR/cube.obj" "$DIR/p.txt" --isa "$isa" --threads $th)
        n=$((n + 1))
        [ "$got" = "$ref" ] || fail "--isa $isa --threads $th differs"
    done
done
[ $n -ge 2 ] || fail "no instruction set besides scalar tried"
pass "$n runs over instruction sets and threads identical"

# a .npy points file: float64, shape (2, 3), the header padded to 128 bytes
{
    printf '\223NUMPY\001\000\166\000' # header length 118: 10 + 118 = 128 bytes
    printf "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }"
    printf '%58s\n' ''
} > "$DIR/p.npy"
# the doubles 0.5 0.5 0.5 3 0.5 0.5, little-endian
printf '\000\000\000\000\000\000\340\077\000\000\000\000\000\000\340\077\000\000\000\000\000\000\340\077' >> "$DIR/p.npy"
printf '\000\000\000\000\000\000\010\100\000\000\000\000\000\000\340\077\000\000\000\000\000\000\340\077' >> "$DIR/p.npy"
got=$("$TTD" points closest "$DIR/cube.obj" "$DIR/p.npy") || fail ".npy exit status"
want=$(echo "$ref" | head -n 2)
[ "$got" = "$want" ] || fail ".npy points: $got"
pass ".npy points file"

"$TTD" points grid "$DIR/cube.obj" --origin "-0.5 -0.5 -0.5" --step 0.25 --dims "9 8 7" --out "$DIR/g.npy" --quiet ||
    fail "grid exit status"
size=$(wc -c < "$DIR/g.npy")
[ "$size" -eq $((128 + 9 * 8 * 7 * 8)) ] || fail "grid .npy size $size"
head -c 128 "$DIR/g.npy" | grep -q "'shape': (9, 8, 7)" || fail "grid .npy header"
"$TTD" points grid "$DIR/cube.obj" --origin "-0.5 -0.5 -0.5" --step "0.25 0.25 0.25" --dims "9 8 7" --out "$DIR/g.raw" \
    --precision float --quiet || fail "grid raw exit status"
[ "$(wc -c < "$DIR/g.raw")" -eq $((9 * 8 * 7 * 4)) ] || fail "grid raw size"
# the grid's centre point (i, j, k) = (4, 4, 4) is (0.5, 0.5, 0.5): -0.5, as a float at index (4*8 + 4)*7 + 4
v=$(od -A n -t f4 -j $(((36 * 7 + 4) * 4)) -N 4 "$DIR/g.raw" | awk '{ print $1 }')
[ "$v" = "-0.5" ] || fail "grid centre $v"
pass "grid: .npy and raw"

for args in "closest" "closest $DIR/cube.obj" "nosuch $DIR/cube.obj $DIR/p.txt" "closest $DIR/cube.obj $DIR/p.txt --upper-bound -1" \
    "closest $DIR/cube.obj $DIR/p.txt --pose 1" "grid $DIR/cube.obj --origin 0" "closest $DIR/cube.obj $DIR/p.txt --bogus 1"; do
    out=$("$TTD" points $args 2>/dev/null)
    rc=$?
    [ $rc -eq 2 ] || fail "points $args: exit $rc, want 2"
    [ -z "$out" ] || fail "points $args printed $out"
done
printf '1 2\n' > "$DIR/bad.txt"
printf 'v 0 0\n' > "$DIR/bad.obj"
for args in "closest $DIR/cube.obj $DIR/bad.txt" "closest $DIR/bad.obj $DIR/p.txt" "closest $DIR/cube.obj $DIR/none.txt" \
    "closest $DIR/cube.obj $DIR/bad.obj"; do
    out=$("$TTD" points $args 2>/dev/null)
    rc=$?
    [ $rc -eq 1 ] || fail "points $args: exit $rc, want 1"
    [ -z "$out" ] || fail "points $args printed $out"
done
pass "errors: exit 2 for the command line, 1 for bad files, nothing printed"
