#!/bin/sh
# SPDX-License-Identifier: MIT
# `ttd dist --binary-in / --binary-out`: raw little-endian float64 (or float32 with --precision
# float) arrays, 18 numbers per pair in, 1 (distance) or 7 (with --points) out. Checked against
# the text path on the same pairs, with an independent converter (perl's pack/unpack; Debian's
# perl-base is always there, the conversions are skipped with a message where perl is not):
# the same numbers in both directions, standard input and output, a truncated last record (an
# error naming its byte offset, the whole records before it computed), a non-finite record,
# empty input, the byte order, and the options that do not go with binary output.
# Usage: sh test_binary.sh path/to/ttd
set -u
TTD=${1:?usage: test_binary.sh path/to/ttd}
DIR=$(mktemp -d) || exit 1
trap 'rm -rf "$DIR"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
pass() { echo "ok   $*"; }
GOOD='0 0 0 1 0 0 0 1 0 0 0 2 1 0 2 0 1 2'

# Byte order, without any converter: the distance 2 is 00..00 40 in little-endian float64,
# 00 00 00 40 in float32; the input 18 numbers written by printf's octal escapes.
zero8='\0\0\0\0\0\0\0\0'
one8='\0\0\0\0\0\0\360\077'
two8='\0\0\0\0\0\0\0\100'
{ printf "$zero8$zero8$zero8$one8$zero8$zero8$zero8$one8$zero8"
  printf "$zero8$zero8$two8$one8$zero8$two8$zero8$one8$two8"; } > "$DIR/one.f64"
[ "$(wc -c < "$DIR/one.f64")" -eq 144 ] || fail "test input is not 144 bytes"
"$TTD" dist --binary-in --binary-out "$DIR/one.f64" > "$DIR/out.bin" || fail "binary: exit status $?"
[ "$(od -An -v -tx1 "$DIR/out.bin" | tr -d ' \n')" = 0000000000000040 ] || fail "float64 out: $(od -An -tx1 "$DIR/out.bin")"
out=$("$TTD" dist --binary-in "$DIR/one.f64") || fail "binary in, text out: exit status $?"
[ "$out" = 2 ] || fail "binary in, text out: '$out'"
printf '%s\n' "$GOOD" | "$TTD" dist --precision float --binary-out > "$DIR/out.bin" || fail "float out: exit status $?"
[ "$(od -An -v -tx1 "$DIR/out.bin" | tr -d ' \n')" = 00000040 ] || fail "float32 out: $(od -An -tx1 "$DIR/out.bin")"
pass byte_order

# Empty input: no output, success.
"$TTD" dist --binary-in --binary-out < /dev/null > "$DIR/out.bin" || fail "empty: exit status $?"
[ ! -s "$DIR/out.bin" ] || fail "empty input gave output"
pass empty_input

# Truncated last record: the whole records are computed and written, then an error that names
# the byte offset of the partial record; status 1. The same on standard input.
cat "$DIR/one.f64" "$DIR/one.f64" > "$DIR/trunc.f64"
head -c 100 "$DIR/one.f64" >> "$DIR/trunc.f64"
"$TTD" dist --binary-in "$DIR/trunc.f64" > "$DIR/out" 2> "$DIR/err"
rc=$?
[ $rc -eq 1 ] || fail "truncated: exit status $rc, want 1"
[ "$(cat "$DIR/out")" = "$(printf '2\n2')" ] || fail "truncated: output '$(cat "$DIR/out")'"
grep -q "trunc.f64: .*byte offset 288" "$DIR/err" || fail "truncated: message '$(cat "$DIR/err")'"
"$TTD" dist --binary-in < "$DIR/trunc.f64" > "$DIR/out" 2> "$DIR/err"
[ $? -eq 1 ] && grep -q "<stdin>: .*byte offset 288" "$DIR/err" || fail "truncated stdin: '$(cat "$DIR/err")'"
head -c 10 "$DIR/one.f64" | "$TTD" dist --binary-in --precision float > "$DIR/out" 2> "$DIR/err"
[ $? -eq 1 ] && grep -q "byte offset 0" "$DIR/err" && [ ! -s "$DIR/out" ] || fail "10 bytes: '$(cat "$DIR/err")'"
pass truncated_record

# A record with NaN (bytes ff..ff) or inf: its output is NaN, a message names the record and its
# byte offset, the records around it are computed; status 1.
{ cat "$DIR/one.f64"; printf "$zero8$zero8$zero8"; printf '\377\377\377\377\377\377\377\377'
  head -c 112 "$DIR/one.f64"; cat "$DIR/one.f64"; } > "$DIR/nan.f64"
[ "$(wc -c < "$DIR/nan.f64")" -eq 432 ] || fail "nan test input is $(wc -c < "$DIR/nan.f64") bytes"
"$TTD" dist --binary-in "$DIR/nan.f64" > "$DIR/out" 2> "$DIR/err"
rc=$?
[ $rc -eq 1 ] || fail "nan record: exit status $rc"
[ "$(cat "$DIR/out")" = "$(printf '2\nnan\n2')" ] || fail "nan record: output '$(cat "$DIR/out")'"
grep -q "nan.f64: record 2 (byte offset 144)" "$DIR/err" || fail "nan record: message '$(cat "$DIR/err")'"
pass nonfinite_record

# Options that do not go with binary output, and binary output to a terminal is refused.
for opts in "--binary-out --detail"; do
    # shellcheck disable=SC2086
    "$TTD" dist $opts "$DIR/one.f64" > /dev/null 2> "$DIR/err"
    [ $? -eq 2 ] && grep -q '^ttd: ' "$DIR/err" || fail "options '$opts': want status 2 and a message"
done
pass bad_combinations

if ! command -v perl > /dev/null 2>&1; then
    echo "skip conversions: perl not found"
    exit 0
fi

# Random pairs, text and binary: in double every number is printed with %.17g, so text and
# binary carry the same doubles. In float the coordinates are multiples of 2^-10 below 2, exact
# in float and in decimal, so perl's double-to-float packing rounds nothing.
awk 'BEGIN { srand(11); for (i = 0; i < 3000; i++) { l = ""; o = rand() - 0.5;
     for (k = 0; k < 18; k++) l = l sprintf(" %.17g", rand() + (k >= 9 ? o : 0)); print l } }' > "$DIR/rand.txt"
awk 'BEGIN { srand(12); for (i = 0; i < 3000; i++) { l = "";
     for (k = 0; k < 18; k++) l = l sprintf(" %.17g", int(rand() * 2048) / 1024); print l } }' > "$DIR/grid.txt"
to_bin() { perl -ne 'print pack("'"$1"'<*", split)' "$2"; }
from_bin() { # from_bin d|f PER-LINE FORMAT: numbers per line, printed with FORMAT
    perl -e 'local $/; my @v = unpack("'"$1"'<*", <STDIN>); my $n = '"$2"';
             for (my $i = 0; $i < @v; $i += $n) { print join(" ", map { $_ != $_ ? "nan" : sprintf("'"$3"'", $_) } @v[$i .. $i + $n - 1]), "\n" }'
}
to_bin d "$DIR/rand.txt" > "$DIR/rand.f64"
[ "$(wc -c < "$DIR/rand.f64")" -eq $((3000 * 144)) ] || fail "converter: rand.f64 has $(wc -c < "$DIR/rand.f64") bytes"
to_bin f "$DIR/grid.txt" > "$DIR/grid.f32"

"$TTD" dist --points "$DIR/rand.txt" > "$DIR/text.txt" || fail "text: exit status $?"
"$TTD" dist --points --binary-in "$DIR/rand.f64" > "$DIR/bin_in.txt" || fail "binary in: exit status $?"
cmp -s "$DIR/text.txt" "$DIR/bin_in.txt" || fail "double: binary input gives other results than text"
"$TTD" dist --points --binary-in --binary-out < "$DIR/rand.f64" > "$DIR/both.bin" || fail "binary both: exit status $?"
[ "$(wc -c < "$DIR/both.bin")" -eq $((3000 * 56)) ] || fail "double --points: $(wc -c < "$DIR/both.bin") bytes out"
from_bin d 7 '%.17g' < "$DIR/both.bin" > "$DIR/both.txt"
cmp -s "$DIR/text.txt" "$DIR/both.txt" || fail "double: binary output differs from text"
"$TTD" dist --binary-out "$DIR/rand.txt" | from_bin d 1 '%.17g' > "$DIR/d.txt"
cut -d' ' -f1 "$DIR/text.txt" | cmp -s - "$DIR/d.txt" || fail "double: distances only differ"
pass double_conversions

"$TTD" dist --precision float --points "$DIR/grid.txt" > "$DIR/ftext.txt" || fail "float text: exit status $?"
"$TTD" dist --precision float --points --binary-in --binary-out "$DIR/grid.f32" > "$DIR/fboth.bin" ||
    fail "float binary: exit status $?"
[ "$(wc -c < "$DIR/fboth.bin")" -eq $((3000 * 28)) ] || fail "float --points: $(wc -c < "$DIR/fboth.bin") bytes out"
from_bin f 7 '%.9g' < "$DIR/fboth.bin" > "$DIR/fboth.txt"
cmp -s "$DIR/ftext.txt" "$DIR/fboth.txt" || fail "float: binary differs from text"
pass float_conversions
exit 0
