#!/bin/sh
# SPDX-License-Identifier: MIT
# `ttd dist` on good input: known distances, comments and blank lines, --points round trip,
# float precision, empty input, no final newline, a 100000-line stream, threads, methods,
# --detail (flags, features, weights), the count of unconverged pairs, a byte-order mark and
# trailing comments, float input rounded once.
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
# --detail: 17 columns (distance, p, q, weights of A B C, weights of D E F, feature_p,
# feature_q, iterations, flags), on pairs whose answer is known by construction:
#  1. vertex D = (1,1,1) above the face of ABC (z = 0): p = (1,1,0) = 0.5 A + 0.25 B + 0.25 C,
#     q = D, distance 1;
#  2. edge AB (z = 0, the rest of ABC below) against edge DE (z = 1, the rest of DEF above),
#     crossing at x = y = 0: p = (0,0,0), q = (0,0,1), both midpoints, distance 1;
#  3. DEF pierces ABC: distance 0, flagged intersecting;
#  4. ABC collinear (a segment), DEF a unit away: flagged degenerate_s.
printf '%s\n' '0 0 0 4 0 0 0 4 0  1 1 1 2 1 3 1 2 3' \
              '-1 0 0 1 0 0 0 -1 -1  0 -1 1 0 1 1 0 0 2' \
              '0 0 0 2 0 0 0 2 0  0.5 0.5 -1 0.5 0.5 1 0.7 0.6 1' \
              '0 0 0 1 0 0 2 0 0  0 1 0 1 1 0 0 1 1' > "$DIR/known.txt"
"$TTD" dist --detail "$DIR/known.txt" > "$DIR/detail.txt" || fail "--detail exit status $?"
awk 'function near(a, b) { d = a - b; if (d < 0) d = -d; return d <= 1e-15 }
     function want(k, v) { if (!near($k, v)) { print "line " NR " field " k ": " $k " want " v; bad = 1 } }
     NF != 17 { print "line " NR ": " NF " fields"; bad = 1; next }
     NR == 1 { want(1, 1); want(2, 1); want(3, 1); want(4, 0); want(5, 1); want(6, 1); want(7, 1)
               want(8, 0.5); want(9, 0.25); want(10, 0.25); want(11, 1); want(12, 0); want(13, 0)
               if ($14 != "ABC" || $15 != "D" || $16 != 0 || $17 != "-") { print "line 1: " $0; bad = 1 } }
     NR == 2 { want(1, 1); for (k = 2; k <= 6; k++) want(k, 0); want(7, 1)
               want(8, 0.5); want(9, 0.5); want(10, 0); want(11, 0.5); want(12, 0.5); want(13, 0)
               if ($14 != "AB" || $15 != "DE" || $17 != "-") { print "line 2: " $0; bad = 1 } }
     NR == 3 { want(1, 0); if ($17 != "intersecting") { print "line 3: " $0; bad = 1 } }
     NR == 4 { want(1, 1); if ($17 != "degenerate_s") { print "line 4: " $0; bad = 1 } }
     END { if (NR != 4) { print NR " lines"; bad = 1 } exit bad }' "$DIR/detail.txt" || fail "--detail on known pairs"
# On random pairs: the first 7 columns are those of --points; the weights are non-negative,
# sum to 1 and rebuild p and q from the input vertices; a feature letter is present exactly
# when its weight is non-zero.
"$TTD" dist --detail "$DIR/rand.txt" > "$DIR/rdetail.txt" || fail "--detail random: exit status $?"
cut -d' ' -f1-7 "$DIR/rdetail.txt" | cmp -s - "$DIR/points.txt" || fail "--detail: columns 1-7 differ from --points"
paste -d' ' "$DIR/rand.txt" "$DIR/rdetail.txt" |
    awk 'function abs(x) { return x < 0 ? -x : x }
         { for (t = 0; t < 2; t++) { o = 18 + 1 + 1 + 3 * t; w = 18 + 8 + 3 * t; sum = 0
             for (k = 0; k < 3; k++) { if ($(w + k) < 0) { print NR ": negative weight"; exit 1 } sum += $(w + k) }
             if (abs(sum - 1) > 1e-15) { print NR ": weights sum to " sum; exit 1 }
             for (c = 0; c < 3; c++) { x = 0
                 for (k = 0; k < 3; k++) x += $(w + k) * $(9 * t + 3 * k + c + 1)
                 if (abs(x - $(o + c)) > 1e-14) { print NR ": weights rebuild " x " not " $(o + c); exit 1 } }
             f = $(18 + 14 + t); letters = t ? "DEF" : "ABC"
             for (k = 0; k < 3; k++) if ((index(f, substr(letters, k + 1, 1)) > 0) != ($(w + k) > 0)) {
                 print NR ": feature " f " against weight " $(w + k); exit 1 } } }' || fail "--detail weights and features"
pass detail

# Iterative methods: the warning counts the pairs that did not converge, and the count is the
# number of pairs --detail flags not_converged (penalty with one iteration leaves many).
"$TTD" dist --method penalty --max-iter 1 --detail "$DIR/rand.txt" > "$DIR/nc.txt" 2> "$DIR/nc.err" ||
    fail "not converged: exit status $?"
flagged=$(grep -c 'not_converged' "$DIR/nc.txt")
[ "$flagged" -gt 0 ] || fail "not converged: no pair flagged with --max-iter 1"
grep -q "warning: $flagged of 2000 pairs did not converge" "$DIR/nc.err" ||
    fail "not converged: want a count of $flagged in: $(cat "$DIR/nc.err")"
"$TTD" dist --method penalty "$DIR/rand.txt" > /dev/null 2> "$DIR/nc.err" || fail "penalty: exit status $?"
[ ! -s "$DIR/nc.err" ] || fail "penalty at the defaults warns: $(cat "$DIR/nc.err")"
pass not_converged_count

# A UTF-8 byte-order mark at the start of the input is skipped; a '#' comment after the 18
# numbers is accepted (with or without a blank before it); comment-only and blank lines still
# give no output line.
printf '\357\273\277# made by an editor\n%s # first\n\n  # only a comment\n%s#second\n' \
    '0 0 0 1 0 0 0 1 0 0 0 2 1 0 2 0 1 2' '0 0 0 1 0 0 0 1 0 0 0 3 1 0 3 0 1 3' > "$DIR/bom.txt"
out=$("$TTD" dist "$DIR/bom.txt") || fail "bom and trailing comments: exit status $?"
[ "$out" = "$(printf '2\n3')" ] || fail "bom and trailing comments: got '$out'"
printf '\357\273\277%s\n' '0 0 0 1 0 0 0 1 0 0 0 2 1 0 2 0 1 2' | "$TTD" dist > "$DIR/out" || fail "bom on stdin"
[ "$(cat "$DIR/out")" = 2 ] || fail "bom on stdin: $(cat "$DIR/out")"
pass bom_and_trailing_comment

# Float input is rounded once, decimal to float: 1 + 2^-24 + 1e-32 lies just above the midpoint
# between 1 and the next float 1 + 2^-23, so it is 1.00000012 (through double it would be the
# midpoint exactly, and tie to 1). Parallel faces at that height give it as the distance.
X=1.00000005960464477539062500000001
out=$(printf '0 0 0 1 0 0 0 1 0  0 0 %s 1 0 %s 0 1 %s\n' $X $X $X | "$TTD" dist --precision float) ||
    fail "float rounding: exit status $?"
[ "$out" = 1.00000012 ] || fail "float rounding: got '$out', want 1.00000012"
H=1.000000059604644775390625
out=$(printf '0 0 0 1 0 0 0 1 0  0 0 %s 1 0 %s 0 1 %s\n' $H $H $H | "$TTD" dist --precision float) ||
    fail "float midpoint: exit status $?"
[ "$out" = 1 ] || fail "float midpoint: got '$out', want 1 (ties to even)"
pass float_rounded_once
exit 0
