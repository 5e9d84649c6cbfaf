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

# grid sizes are checked before anything is written, with a message; a file already there is kept
printf 'old\n' > "$DIR/keep.npy"
grid_refused() { # want-status message-pattern dims [more options]
    want=$1 pat=$2 dims=$3
    shift 3
    "$TTD" points grid "$DIR/cube.obj" --origin "0 0 0" --step 0.1 --dims "$dims" --out "$DIR/keep.npy" "$@" 2> "$DIR/err"
    rc=$?
    [ $rc -eq "$want" ] || fail "grid --dims '$dims' $*: exit $rc, want $want"
    grep -q "$pat" "$DIR/err" || fail "grid --dims '$dims' $*: message $(cat "$DIR/err")"
    [ "$(cat "$DIR/keep.npy")" = "old" ] || fail "grid --dims '$dims' $*: the file there was overwritten"
    ls "$DIR" | grep -q 'keep.npy.tmp' && fail "grid --dims '$dims' $*: a temporary file was left"
    return 0
}
grid_refused 2 "overflows" "4294967296 4294967296 4294967296"   # 2^96 points
grid_refused 2 "memory" "1 1000000 1000000"                     # one slab of 8 TB
grid_refused 1 "free" "100000000000 10 10"                      # 80 TB on the disk
grid_refused 2 "bad value for --step" "10 10 10" --step 0
grid_refused 2 "bad value for --step" "10 10 10" --step "0.1 -0.1 0.1"
pass "grid: overflowing dims, a slab beyond memory, a file beyond the free disk, zero and negative steps refused"

# Interrupted (SIGINT, as Ctrl-C) while it runs: exit 1, the file there untouched, no temporary
# file; --progress on a pipe writes a line an update, at most 4 a second.
"$TTD" points grid "$DIR/cube.obj" --origin "0 0 0" --step 0.001 --dims "100000000 1 1" --out "$DIR/keep.npy" \
    --progress 2> "$DIR/err" &
pid=$!
sleep 2
kill -INT $pid
wait $pid
rc=$?
[ $rc -eq 1 ] || fail "interrupted grid: exit $rc, want 1"
grep -q "interrupted" "$DIR/err" || fail "interrupted grid: message $(tail -n 2 "$DIR/err")"
[ "$(cat "$DIR/keep.npy")" = "old" ] || fail "interrupted grid: the file there was overwritten"
ls "$DIR" | grep -q 'keep.npy.tmp' && fail "interrupted grid: a temporary file was left"
lines=$(grep -c "ttd points grid: .*slabs" "$DIR/err")
[ "$lines" -ge 1 ] && [ "$lines" -le 12 ] || fail "interrupted grid: $lines progress lines in about 2 s, want 1..12"
# without --progress, standard error not a terminal: no progress lines, even for 2^20 points
"$TTD" points grid "$DIR/cube.obj" --origin "0 0 0" --step 0.01 --dims "128 128 64" --out "$DIR/big.npy" 2> "$DIR/err" ||
    fail "grid of 2^20 points: exit status"
[ ! -s "$DIR/err" ] || fail "grid of 2^20 points to a pipe printed progress: $(head -c 200 "$DIR/err")"
[ "$(wc -c < "$DIR/big.npy")" -eq $((128 + 128 * 128 * 64 * 8)) ] || fail "grid of 2^20 points: size"
pass "grid: interrupted, progress throttled and only on a terminal (or --progress)"

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
