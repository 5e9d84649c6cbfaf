#!/bin/sh
# SPDX-License-Identifier: MIT
# The ttd program's other entries: --help, --version, info, dist --help exit 0 with the
# expected content; no command or an unknown one exits 2.
# Usage: sh test_misc.sh path/to/ttd
set -u
TTD=${1:?usage: test_misc.sh path/to/ttd}
fail() { echo "FAIL: $*" >&2; exit 1; }

out=$("$TTD" --help) || fail "--help exit status $?"
case "$out" in *"usage: ttd"*dist*info*) ;; *) fail "--help: $out" ;; esac
out=$("$TTD" dist --help) || fail "dist --help exit status $?"
case "$out" in *"--method"*"--precision"*"--points"*"--isa"*"--threads"*) ;; *) fail "dist --help: $out" ;; esac
out=$("$TTD" --version) || fail "--version exit status $?"
echo "$out" | grep -q '^ttd [0-9][0-9]*\.[0-9][0-9]*\.[0-9][0-9]*$' || fail "--version: $out"
echo "$out" | grep -q '^auto: ' || fail "--version lacks the chosen ISA: $out"
out=$("$TTD" info) || fail "info exit status $?"
for key in '^ttd ' '^built: scalar' '^cpu: *scalar' '^auto: ' '^threads: '; do
    echo "$out" | grep -q "$key" || fail "info lacks '$key': $out"
done
# What auto picks is built and supported, and TTD_ISA=scalar changes it.
auto=$(echo "$out" | sed -n 's/^auto: *\([a-z0-9]*\).*/\1/p')
case " $(echo "$out" | sed -n 's/^built://p') " in *" $auto "*) ;; *) fail "auto '$auto' not built" ;; esac
case " $(echo "$out" | sed -n 's/^cpu://p') " in *" $auto "*) ;; *) fail "auto '$auto' not supported" ;; esac
TTD_ISA=scalar "$TTD" info | grep -q '^auto: *scalar' || fail "TTD_ISA=scalar not shown"
echo "ok   help_version_info"

"$TTD" > /dev/null 2>&1
[ $? -eq 2 ] || fail "no command: want exit 2"
"$TTD" frobnicate > /dev/null 2>&1
[ $? -eq 2 ] || fail "unknown command: want exit 2"
echo "ok   usage_errors"
exit 0
