#!/bin/sh
# SPDX-License-Identifier: MIT
# `ttd dist` on good input: known distances, comments and blank lines, --points round trip,
# float precision, empty input, no final newline, a 100000-line stream, threads, methods.
# Usage: sh test_dist.sh path/to/ttd
set -u
TTD=${1:?usage: test_dist.sh path/to/ttd}
DIR=$(mktemp -d) || exit 1
trap 'rm -rf "$DIR"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
pass() { echo "ok   $*"; }

# Parallel faces 2 apart (distance 2 whatever the method's feature choice), then a pair
# whose faces are parallel at 0.3.
printf '0 0 0 1 0 0 0 1 0   0 0 2 1 0 2 0 1 2\n' > "$DIR/one.txt"
out=$("$TTD" dist "$DIR/one.txt") || fail "dist exit status $?"
[ "$out" = "2" ] || fail "distance '$out', want 2"
pass known_distance

# Comments, blank lines, leading blanks, tabs and CRLF are fine; line k of the output is the
# k-th pair line.
printf '# header\n\n   \n  # indented comment\n\t0 0 0 1 0 0 0 1 0\t0 0 2 1 0 2 0 1 2\r\n# between\n0 0 0 1 0 0 0 1 0 0 0 5 1 0 5 0 1 5\n\n' > "$DIR/comments.txt"
out=$("$TTD" dist "$DIR/comments.txt") || fail "comments: exit status $?"
[ "$out" = "$(printf '2\n5')" ] || fail "comments: got '$out'"
pass comments_and_blank_lines

# No final newline: the last line still counts. Standard input works the same, and '-' too.
printf '0 0 0 1 0 0 0 1 0 0 0 2 1 0 2 0 1 2\n0 0 0 1 0 0 0 1 0 0 0 3 1 0 3 0 1 3' > "$DIR/nonl.txt"
out=$("$TTD" dist < "$DIR/nonl.txt") || fail "no final newline: exit status $?"
[ "$out" = "$(printf '2\n3')" ] || fail "no final newline: got '$out'"
out2=$("$TTD" dist - < "$DIR/nonl.txt") || fail "'-': exit status $?"
[ "$out" = "$out2" ] || fail "'-' differs from no FILE"
pass no_final_newline

# Empty input and comment-only input: no output, success.
: > "$DIR/empty.txt"
out=$("$TTD" dist "$DIR/empty.txt") || fail "empty: exit status $?"
[ -z "$out" ] || fail "empty: got '$out'"
out=$(printf '# only\n\n' | "$TTD" dist) || fail "comment-only: exit status $?"
[ -z "$out" ] || fail "comment-only: got '$out'"
pass empty_input

# Random pairs for the rest (awk's srand/rand: any values will do, they only need to be finite).
awk 'BEGIN { srand(7); for (i = 0; i < 2000; i++) { l = ""; o = rand() - 0.5;
     for (k = 0; k < 18; k++) l = l sprintf(" %.17g", rand() + (k >= 9 ? o : 0)); print l } }' > "$DIR/rand.txt"

# --points: 7 numbers a line, each printed so that it reads back to the same double (printing
# the parsed value again with %.17g gives the same text), and d = |p - q|.
"$TTD" dist --points "$DIR/rand.txt" > "$DIR/points.txt" || fail "--points exit status $?"
awk 'NF != 7 { print "line " NR ": " NF " fields"; bad = 1; exit }
     { for (k = 1; k <= 7; k++) if (sprintf("%.17g", $k + 0) != $k) { print "line " NR ": " $k " does not round-trip"; bad = 1; exit }
       dx = $2 - $5; dy = $3 - $6; dz = $4 - $7; e = sqrt(dx*dx + dy*dy + dz*dz) - $1; if (e < 0) e = -e
       if (e > 1e-12) { print "line " NR ": |p-q| - d = " e; bad = 1; exit } }
     END { if (NR != 2000) { print NR " lines"; bad = 1 } exit bad }' "$DIR/points.txt" || fail "--points output"
cut -d' ' -f1 "$DIR/points.txt" > "$DIR/d_from_points.txt"
"$TTD" dist "$DIR/rand.txt" > "$DIR/d.txt" || fail "dist exit status $?"
cmp -s "$DIR/d.txt" "$DIR/d_from_points.txt" || fail "distance differs with and without --points"
pass points_round_trip

# Float: the input is rounded to float first (0.3 -> 0.300000011920928955) and printed with %.9g.
printf '0 0 0 1 0 0 0 1 0 0 0 0.3 1 0 0.3 0 1 0.3\n' > "$DIR/float.txt"
d=$("$TTD" dist "$DIR/float.txt") || fail "double exit status $?"
f=$("$TTD" dist --precision float "$DIR/float.txt") || fail "float exit status $?"
awk -v d="$d" -v f="$f" 'BEGIN { ed = d - 0.3; ef = f - 0.300000011920928955
     if (ed < 0) ed = -ed; if (ef < 0) ef = -ef
     exit !(ed < 1e-15 && ef < 1e-7 && d != f) }' || fail "float: double '$d', float '$f'"
"$TTD" dist --precision float --points "$DIR/rand.txt" > "$DIR/fpoints.txt" || fail "float --points exit status $?"
awk '{ for (k = 1; k <= NF; k++) if (sprintf("%.9g", $k + 0) != $k) { print "line " NR ": " $k; exit 1 } }' \
    "$DIR/fpoints.txt" || fail "float output not %.9g"
pass float_precision

# Every method gives the known distance 2 within its documented accuracy (the barrier's 1e-8,
# the loosest of them, relative to the pair's size 1), and the options reach the method.
for m in exact penalty penalty-ref barrier certified; do
    out=$("$TTD" dist --method "$m" "$DIR/one.txt") || fail "--method $m: exit status $?"
    awk -v d="$out" 'BEGIN { e = d - 2; if (e < 0) e = -e; exit !(e <= 2e-8) }' || fail "--method $m: '$out'"
done
out=$("$TTD" dist --method=penalty --rho=1e5 --tol 1e-12 --max-iter=50 "$DIR/one.txt") || fail "penalty options"
awk -v d="$out" 'BEGIN { e = d - 2; if (e < 0) e = -e; exit !(e <= 1e-10) }' || fail "penalty options: '$out'"
pass methods

# Long input: 100000 lines stream through (block by block); the thread count must not change
# a single bit.
i=0; : > "$DIR/big.txt"
while [ $i -lt 50 ]; do cat "$DIR/rand.txt" >> "$DIR/big.txt"; i=$((i + 1)); done
"$TTD" dist --threads 1 "$DIR/big.txt" > "$DIR/big1.txt" || fail "big: exit status $?"
[ "$(wc -l < "$DIR/big1.txt")" -eq 100000 ] || fail "big: $(wc -l < "$DIR/big1.txt") lines"
"$TTD" dist --threads 2 < "$DIR/big.txt" > "$DIR/big2.txt" || fail "big, 2 threads: exit status $?"
cmp -s "$DIR/big1.txt" "$DIR/big2.txt" || fail "big: 1 and 2 threads differ"
"$TTD" dist --threads 0 --method penalty "$DIR/big.txt" > "$DIR/bigp0.txt" || fail "big penalty: exit status $?"
"$TTD" dist --threads 1 --method penalty "$DIR/big.txt" > "$DIR/bigp1.txt" || fail "big penalty: exit status $?"
cmp -s "$DIR/bigp0.txt" "$DIR/bigp1.txt" || fail "big penalty: thread counts differ"
pass stream_100000_lines

# --isa: scalar always works; every ISA named on the 'cpu' and 'built' lines of info works and
# prints the scalar row's distances to within the kernels' agreement (8 eps of the pair's size,
# about 1e-15 here; the rows are in fact bit-identical on x86).
"$TTD" dist --isa scalar "$DIR/rand.txt" > "$DIR/rand_scalar.txt" || fail "--isa scalar"
built=$("$TTD" info | sed -n 's/^built://p')
cpu=$("$TTD" info | sed -n 's/^cpu://p')
for isa in sse2 avx2 avx512 neon; do
    case " $built " in *" $isa "*) ;; *) continue ;; esac
    case " $cpu " in *" $isa "*) ;; *) continue ;; esac
    "$TTD" dist --isa "$isa" "$DIR/rand.txt" > "$DIR/rand_isa.txt" || fail "--isa $isa"
    paste "$DIR/rand_scalar.txt" "$DIR/rand_isa.txt" |
        awk '{ e = $1 - $2; if (e < 0) e = -e; if (e > 1e-14) { print "line " NR ": " $0; exit 1 } }' ||
        fail "--isa $isa differs from scalar"
    out=$(TTD_ISA=$isa "$TTD" dist "$DIR/one.txt") || fail "TTD_ISA=$isa"
    awk -v d="$out" 'BEGIN { exit !(d == 2) }' || fail "TTD_ISA=$isa: '$out'"
done
pass isa_option
exit 0
