#!/bin/sh
# SPDX-License-Identifier: MIT
# The ttd program's other entries: --help, --version, info, dist --help, info --help exit 0
# with the expected content; no command, an unknown one, or info with an operand exits 2.
# Usage: sh test_misc.sh path/to/ttd
set -u
TTD=${1:?usage: test_misc.sh path/to/ttd}
DIR_ERR=$(mktemp) || exit 1
trap 'rm -f "$DIR_ERR"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

out=$("$TTD" --help) || fail "--help exit status $?"
case "$out" in *"usage: ttd"*dist*info*) ;; *) fail "--help: $out" ;; esac
out=$("$TTD" dist --help) || fail "dist --help exit status $?"
case "$out" in *"--method"*"--precision"*"--points"*"--isa"*"--threads"*) ;; *) fail "dist --help: $out" ;; esac
# It documents the line limit, the comment and byte-order-mark rules, --detail's columns, the
# binary formats, and that penalty-ref and barrier are for comparison.
for key in 4096 "byte-order mark" "'#'" "--detail" "17 columns" "--binary-in" "--binary-out" "little-endian" \
           "penalty-ref (the paper's MATLAB ttd1" "for comparison, not for use"; do
    case "$out" in *"$key"*) ;; *) fail "dist --help lacks '$key'" ;; esac
done
out=$("$TTD" --version) || fail "--version exit status $?"
echo "$out" | grep -q '^ttd [0-9][0-9]*\.[0-9][0-9]*\.[0-9][0-9]*$' || fail "--version: $out"
echo "$out" | grep -q '^auto: ' || fail "--version lacks the chosen ISA: $out"
out=$("$TTD" info) || fail "info exit status $?"
for key in '^ttd ' '^built: scalar' '^cpu: *scalar' '^auto: ' '^threads: ' '^gpu: \(usable\|not built\|built, not usable\)'; do
    echo "$out" | grep -q "$key" || fail "info lacks '$key': $out"
done
# What auto picks is built and supported, and TTD_ISA=scalar changes it.
auto=$(echo "$out" | sed -n 's/^auto: *\([a-z0-9]*\).*/\1/p')
case " $(echo "$out" | sed -n 's/^built://p') " in *" $auto "*) ;; *) fail "auto '$auto' not built" ;; esac
case " $(echo "$out" | sed -n 's/^cpu://p') " in *" $auto "*) ;; *) fail "auto '$auto' not supported" ;; esac
TTD_ISA=scalar "$TTD" info | grep -q '^auto: *scalar' || fail "TTD_ISA=scalar not shown"
echo "ok   help_version_info"

# info --help prints info's usage (not the info itself); an operand is an error.
out=$("$TTD" info --help) || fail "info --help exit status $?"
case "$out" in *"usage: ttd info"*) ;; *) fail "info --help: $out" ;; esac
echo "$out" | grep -q '^built:' && fail "info --help printed the info: $out"
"$TTD" info extra > /dev/null 2> "$DIR_ERR"
rc=$?
[ $rc -eq 2 ] || fail "info extra: exit status $rc, want 2"
grep -q "^ttd: info: .*extra" "$DIR_ERR" || fail "info extra: message '$(cat "$DIR_ERR")'"
"$TTD" info --frobnicate > /dev/null 2>&1
[ $? -eq 2 ] || fail "info --frobnicate: want exit 2"
echo "ok   info_arguments"

"$TTD" > /dev/null 2>&1
[ $? -eq 2 ] || fail "no command: want exit 2"
"$TTD" frobnicate > /dev/null 2>&1
[ $? -eq 2 ] || fail "unknown command: want exit 2"
echo "ok   usage_errors"
exit 0
