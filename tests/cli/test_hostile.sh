#!/bin/sh
# SPDX-License-Identifier: MIT
# `ttd dist` on hostile input, beyond test_errors.sh (which covers malformed fields, NaN/inf,
# an inner NUL, a 128 KB line, random bytes, missing files, bad options): line-end and file
# shapes (CRLF, CR only, no final newline, empty file, blank CR lines, a byte-order mark), a
# 1 MB line with and without its newline, a 1 MB comment, the 4096-byte line limit exactly,
# NUL-only input, every truncation of a good line, the program's own binary as input, closed
# or full output and input streams, and numeric extremes. Each run is under `timeout`: a hang
# or a crash (status >= 124) fails, and so does any status other than the one expected.
# Usage: sh test_hostile.sh path/to/ttd
set -u
TTD=${1:?usage: test_hostile.sh path/to/ttd}
DIR=$(mktemp -d) || exit 1
trap 'rm -rf "$DIR"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
pass() { echo "ok   $*"; }
GOOD='0 0 0 1 0 0 0 1 0 0 0 2 1 0 2 0 1 2'
if command -v timeout > /dev/null 2>&1; then TO="timeout 20"; else TO=; fi

# run NAME WANT-STATUS FILE [options]: ttd dist [options] FILE, stdout in $DIR/out, stderr in
# $DIR/err; fails on a hang or crash, or a status other than WANT-STATUS.
run() {
    name=$1; want=$2; file=$3; shift 3
    # shellcheck disable=SC2086
    $TO "$TTD" dist "$@" "$file" > "$DIR/out" 2> "$DIR/err"
    rc=$?
    [ $rc -lt 124 ] || fail "$name: hang or crash (status $rc): $(head -c 300 "$DIR/err")"
    [ $rc -eq "$want" ] || fail "$name: status $rc, want $want: $(head -c 300 "$DIR/err")"
}
want_out() { # want_out NAME EXPECTED-OUTPUT
    [ "$(cat "$DIR/out")" = "$1" ] || fail "$2: output '$(head -c 200 "$DIR/out")', want '$1'"
}
want_err() { # want_err NAME GREP-PATTERN
    grep -q "$1" "$DIR/err" || fail "$2: no '$1' in: $(head -c 300 "$DIR/err")"
}

# CRLF line ends: the CR is white space, the pairs and comments read as usual.
printf '%s\r\n# comment\r\n\r\n  \t\r\n%s\r\n' "$GOOD" "$GOOD" > "$DIR/crlf.txt"
run crlf 0 "$DIR/crlf.txt"; want_out "$(printf '2\n2')" crlf; pass crlf

# CR-only line ends (old Mac): one long line of 36 numbers, reported as such.
printf '%s\r%s\r' "$GOOD" "$GOOD" > "$DIR/cr.txt"
run cr_only 1 "$DIR/cr.txt"; want_out nan cr_only; want_err "cr.txt:1: " cr_only; pass cr_only

# No final newline on a good last line: computed, status 0.
printf '%s\n%s' "$GOOD" "$GOOD" > "$DIR/nonl.txt"
run no_final_newline 0 "$DIR/nonl.txt"; want_out "$(printf '2\n2')" no_final_newline; pass no_final_newline

# Empty file, /dev/null, only blank lines and comments: no output, status 0.
: > "$DIR/empty.txt"
run empty_file 0 "$DIR/empty.txt"; want_out "" empty_file
run dev_null 0 /dev/null; want_out "" dev_null
printf '\n\n# only comments\n   \n#\n' > "$DIR/blank.txt"
run only_blank 0 "$DIR/blank.txt"; want_out "" only_blank
pass empty_inputs

# A UTF-8 byte-order mark at the start of the input is skipped; one at the start of a later line
# is an error naming that line (it is not white space), and reading goes on.
printf '\357\273\277%s\n%s\n' "$GOOD" "$GOOD" > "$DIR/bom.txt"
run bom 0 "$DIR/bom.txt"; want_out "$(printf '2\n2')" bom
printf '%s\n\357\273\277%s\n%s\n' "$GOOD" "$GOOD" "$GOOD" > "$DIR/bom2.txt"
run bom_line_2 1 "$DIR/bom2.txt"; want_out "$(printf '2\nnan\n2')" bom_line_2; want_err "bom2.txt:2: " bom_line_2
printf '\357\273\277' > "$DIR/bomonly.txt"
run bom_only 0 "$DIR/bomonly.txt"; want_out "" bom_only
pass byte_order_mark

# A 1 MB line between good ones, with and without its newline, and a 1 MB comment.
mb() { head -c 1048576 /dev/zero | tr '\0' "$1"; }
{ printf '%s\n' "$GOOD"; mb 7; printf '\n%s\n' "$GOOD"; } > "$DIR/mb.txt"
run megabyte_line 1 "$DIR/mb.txt"; want_out "$(printf '2\nnan\n2')" megabyte_line
want_err "mb.txt:2: line longer than" megabyte_line
{ printf '%s\n' "$GOOD"; mb ' '; mb 1; } > "$DIR/mbnonl.txt"
run megabyte_last_line 1 "$DIR/mbnonl.txt"; want_out "$(printf '2\nnan')" megabyte_last_line
want_err "mbnonl.txt:2: " megabyte_last_line
{ printf '#'; mb x; printf '\n%s\n' "$GOOD"; } > "$DIR/mbcomment.txt"
run megabyte_comment 0 "$DIR/mbcomment.txt"; want_out 2 megabyte_comment
pass megabyte_lines

# The line limit (4096 bytes without the newline): at the limit computed, one more byte that is
# not a blank refused.
pad=$(awk -v n=$((4096 - ${#GOOD})) 'BEGIN { s = ""; for (i = 0; i < n; i++) s = s " "; printf "%s", s }')
printf '%s%s\n' "$GOOD" "$pad" > "$DIR/limit.txt"
[ "$(head -n 1 "$DIR/limit.txt" | wc -c)" -eq 4097 ] || fail "limit: test line is not 4096 bytes"
run line_limit 0 "$DIR/limit.txt"; want_out 2 line_limit
printf '%s%s7\n%s\n' "$GOOD" "$pad" "$GOOD" > "$DIR/limit1.txt"
run line_limit_plus_one 1 "$DIR/limit1.txt"; want_out "$(printf 'nan\n2')" line_limit_plus_one
want_err "limit1.txt:1: line longer than 4096" line_limit_plus_one
# A byte-order mark does not count towards the first line's limit.
printf '\357\273\277%s%s\n' "$GOOD" "$pad" > "$DIR/limitbom.txt"
run line_limit_bom 0 "$DIR/limitbom.txt"; want_out 2 line_limit_bom
printf '\357\273\277%s%s7\n' "$GOOD" "$pad" > "$DIR/limitbom1.txt"
run line_limit_bom_plus_one 1 "$DIR/limitbom1.txt"; want_err "limitbom1.txt:1: line longer than 4096" line_limit_bom_plus_one
pass line_limit

# Blanks beyond the limit are not data: a pair followed by a megabyte of blanks (spaces, tabs,
# CR, VT, FF; with and without its newline, after a byte-order mark) and a line of blanks alone
# are read as if the blanks were not there. One byte that is not a blank after them is refused.
blanks() { head -c 1048576 /dev/zero | tr '\0' ' '; printf '\t\r\v\f \t'; }
{ printf '%s' "$GOOD"; blanks; printf '\n'; blanks; printf '\n%s' "$GOOD"; blanks; } > "$DIR/blanks.txt"
run trailing_blanks 0 "$DIR/blanks.txt"; want_out "$(printf '2\n2')" trailing_blanks
[ -s "$DIR/err" ] && fail "trailing_blanks: $(head -c 300 "$DIR/err")"
{ printf '\357\273\277%s' "$GOOD"; blanks; printf '\n'; } > "$DIR/blanksbom.txt"
run trailing_blanks_bom 0 "$DIR/blanksbom.txt"; want_out 2 trailing_blanks_bom
{ printf '%s' "$GOOD"; blanks; printf '7\n%s\n' "$GOOD"; } > "$DIR/blanks7.txt"
run trailing_blanks_then_data 1 "$DIR/blanks7.txt"; want_out "$(printf 'nan\n2')" trailing_blanks_then_data
want_err "blanks7.txt:1: line longer than 4096" trailing_blanks_then_data
pass trailing_blanks

# NUL bytes only (one long line), NUL at the start of a line, NUL inside a comment.
head -c 100000 /dev/zero > "$DIR/nul.bin"
run nul_only 1 "$DIR/nul.bin"; want_out nan nul_only; want_err "nul.bin:1: " nul_only
printf '\000%s\n%s\n' "$GOOD" "$GOOD" > "$DIR/nul1.txt"
run nul_first 1 "$DIR/nul1.txt"; want_out "$(printf 'nan\n2')" nul_first; want_err "nul1.txt:1: " nul_first
printf '# a\000b\n%s\n' "$GOOD" > "$DIR/nulc.txt"
run nul_in_comment 0 "$DIR/nulc.txt"; want_out 2 nul_in_comment
pass nul_bytes

# Every strict prefix of a good line (the last number has one digit, so none is a pair), as
# the last line without newline and as a line followed by a good one.
len=${#GOOD}
i=1
while [ $i -lt "$len" ]; do
    prefix=$(printf '%s' "$GOOD" | head -c $i)
    case "$prefix" in *[!\ ]*) ;; *) i=$((i + 1)); continue ;; esac
    printf '%s\n%s' "$GOOD" "$prefix" > "$DIR/trunc.txt"
    run "truncated at $i" 1 "$DIR/trunc.txt"; want_out "$(printf '2\nnan')" "truncated at $i"
    want_err "trunc.txt:2: " "truncated at $i"
    printf '%s\n%s\n' "$prefix" "$GOOD" > "$DIR/trunc2.txt"
    run "truncated at $i, then a good line" 1 "$DIR/trunc2.txt"; want_out "$(printf 'nan\n2')" "truncated at $i+"
    i=$((i + 1))
done
pass "truncated_lines ($((len - 1)) prefixes)"

# The program's own binary as input (NULs, high bytes, long and short lines; deterministic for
# a build), in double, float and with --points.
head -c 400000 "$TTD" > "$DIR/self.bin"
for opts in "" "--precision float" "--points" "--method penalty"; do
    # shellcheck disable=SC2086
    run "own binary $opts" 1 "$DIR/self.bin" $opts
    want_err "bad lines (output nan)" "own binary $opts"
done
pass own_binary_as_input

# Closed standard input, closed and full standard output: an error, status 1, no crash.
$TO "$TTD" dist <&- > "$DIR/out" 2> "$DIR/err"
rc=$?; [ $rc -eq 1 ] || fail "closed stdin: status $rc"
printf '%s\n' "$GOOD" > "$DIR/good.txt"
$TO "$TTD" dist "$DIR/good.txt" >&- 2> "$DIR/err"
rc=$?; [ $rc -eq 1 ] || fail "closed stdout: status $rc"
if [ -w /dev/full ]; then
    $TO "$TTD" dist "$DIR/good.txt" > /dev/full 2> "$DIR/err"
    rc=$?; [ $rc -eq 1 ] || fail "full stdout: status $rc"
    want_err "error writing" full_stdout
fi
pass closed_and_full_streams

# Numeric extremes that are finite: computed (status 0), never NaN. A distance beyond DBL_MAX
# (DBL_MAX against -DBL_MAX) prints inf; everything else is finite.
M=1.7976931348623157e308
{
    echo "1e300 1e300 1e300 -1e300 0 0 0 1e300 0 -1e300 -1e300 -1e300 1e300 0 -1e300 0 1 -1e300"
    echo "$M 0 0 $M 1 0 $M 0 1 -$M 0 0 -$M 1 0 -$M 0 1"
    echo "-$M 0 0 $M 0 0 0 $M 0 0 0 1 1 0 1 0 1 1"
    echo "0 0 0 1e-320 0 0 0 1e-320 0 0 0 2e-320 1e-320 0 2e-320 0 1e-320 2e-320"
    echo "4.9406564584124654e-324 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0"
    echo "0x1p-1074 0 0 0x1.fffffffffffffp1023 0 0 0 0 0 0 0 0 0 0 0 0 0 0"
} > "$DIR/extreme.txt"
for opts in "" "--points" "--method penalty" "--method barrier" "--method penalty-ref"; do
    # shellcheck disable=SC2086
    run "extremes $opts" 0 "$DIR/extreme.txt" $opts
    grep -qi nan "$DIR/out" && fail "extremes $opts: NaN in $(cat "$DIR/out")"
    [ "$(wc -l < "$DIR/out")" -eq 6 ] || fail "extremes $opts: $(wc -l < "$DIR/out") output lines"
    # only line 2 (distance beyond DBL_MAX) may be inf
    awk 'NR != 2 && /inf/ { exit 1 }' "$DIR/out" || fail "extremes $opts: inf outside line 2: $(cat "$DIR/out")"
done
{
    echo "3e38 0 0 3e38 1 0 3e38 0 1 -3e38 0 0 -3e38 1 0 -3e38 0 1"
    echo "0 0 0 1e-45 0 0 0 1e-45 0 0 0 3e-45 1e-45 0 3e-45 0 1e-45 3e-45"
    echo "1e30 1e30 1e30 -1e30 0 0 0 1e30 0 -1e30 -1e30 -1e30 1e30 0 -1e30 0 1 -1e30"
} > "$DIR/fextreme.txt"
run "float extremes" 0 "$DIR/fextreme.txt" --precision float --points
grep -qi nan "$DIR/out" && fail "float extremes: NaN in $(cat "$DIR/out")"
pass numeric_extremes

# Option values that overflow their types: status 2 and a message, nothing read.
for opts in "--threads 99999999999999999999" "--max-iter 4294967297" "--rho 1e400" "--tol 1e-400x" \
            "--max-iter ''" "--threads 1e3"; do
    # shellcheck disable=SC2086
    eval "$TO \"\$TTD\" dist $opts \"\$DIR/good.txt\"" > /dev/null 2> "$DIR/err"
    rc=$?
    [ $rc -eq 2 ] || fail "options '$opts': status $rc, want 2"
    grep -q '^ttd: ' "$DIR/err" || fail "options '$opts': no message"
done
pass overflowing_option_values
exit 0
