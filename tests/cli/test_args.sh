#!/bin/sh
# SPDX-License-Identifier: MIT
# Every command's command line, the bad ones above all: unknown options, options of another
# subcommand, missing values, bad numbers, missing and extra operands, "--", "-" and --help.
# For each case below the exit status, standard output (line count and cksum) and standard error
# (its first line, then line count and cksum) are written as a record and compared with
# tests/cli/args_expected.txt, so a change to how arguments are read (cli/common.c's option walker,
# a command moved onto it) shows every message or status it alters. Beyond the comparison, a
# status 2 must leave standard output empty and say on standard error, after "ttd: ", what is
# wrong. Files named by the cases do not exist: every case stops at the command line or at the
# first file (exit 1).
# Usage: sh test_args.sh path/to/ttd            compare with args_expected.txt
#        sh test_args.sh path/to/ttd --write F  write the records to F (to renew the expected file
#                                               after a deliberate change of a message: read the diff)
# To compare two programs (before and after a refactor): write F with each, then diff the two files.
set -u
TTD=${1:?usage: test_args.sh path/to/ttd [--write FILE]}
case $TTD in /*) ;; *) TTD=$(pwd)/$TTD ;; esac
HERE=$(cd "$(dirname "$0")" && pwd)
WRITE=
[ $# -ge 3 ] && [ "$2" = --write ] && WRITE=$3
case $WRITE in ''|/*) ;; *) WRITE=$(pwd)/$WRITE ;; esac
DIR=$(mktemp -d) || exit 1
trap 'rm -rf "$DIR"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
unset TTD_ISA
cd "$DIR" || exit 1

# One case a line: the arguments after `ttd`, as shell words.
cat > cases <<'EOF'
dist --bogus
dist -x
dist --bogus=1
dist --points=1
dist --threads
dist --threads abc
dist --threads=-1
dist --threads=
dist --method nope
dist --rho 0
dist --rho nan
dist --tol 2
dist --max-iter 0
dist --isa nope
dist --precision half
dist a b
dist --detail --binary-out
dist -- -x
dist nofile.txt
dist --help
dist -h
mesh
mesh bogus
mesh distance
mesh distance a
mesh distance a b c
mesh distance a b --bogus
mesh distance a b -x
mesh distance a b --margin 1
mesh contacts a b
mesh contacts a b --margin x
mesh contacts a b --margin -1
mesh contacts a b --margin 1e39 --precision float
mesh contacts a b --margin
mesh distance a b --upper-bound
mesh distance a b --rel-tol=abc
mesh collide a b --rel-tol 1
mesh collide a b --per-triangle
mesh collide a b --count
mesh self-contacts a --pose '1 0 0 0 0 1 0 0 0 0 1 0' --margin 1
mesh self-contacts a b --margin 1
mesh self-collide
mesh contacts a b --solid --margin 1
mesh distance a b --shared-vertex
mesh distance a b --pose 1 --poses p
mesh distance - b --poses -
mesh distance a b --threads -1
mesh distance a b --weld -1
mesh distance a b --isa nope
mesh distance a b --precision half
mesh distance a -- -b --x
mesh distance nofile.obj nofile2.obj
mesh distance --help
mesh contacts -h
mesh mass
mesh mass a b
mesh mass a --bogus
mesh mass a -x
mesh mass a --json=1
mesh mass a --density
mesh mass a --density 0
mesh mass a --density=nan
mesh mass a --density x
mesh mass a --density inf
mesh mass a --weld -1
mesh mass a --weld=x
mesh mass a --precision half
mesh mass a --precision=
mesh mass -- -a
mesh mass nofile.obj --json --strict --density 2 --precision float --weld 0
mesh mass --help
mesh mass -h
scene
scene bogus a
scene collide
scene collide a b
scene collide a --bogus
scene collide a -x
scene collide a --nearest
scene distance a --count
scene collide a --max-points 3
scene manifold a --max-points -1
scene manifold a --max-points
scene manifold a --max-points=x
scene collide a --margin x
scene collide a --margin -1
scene collide a --margin 1e39 --precision float
scene distance a --margin 1e39
scene collide a --repeat 0
scene collide a --repeat
scene collide a --weld=-1
scene collide - --motion -
scene collide a --threads x
scene collide a --isa nope
scene collide a --stats=1
scene collide -- -a
scene manifold nofile.scene --names --stats --solid --strict --orthonormalize --count
scene distance nofile.scene --nearest --margin 1
scene collide --help
scene manifold -h
ccd
ccd a b
ccd --bogus
ccd -x
ccd --kind
ccd --kind xx a
ccd --min-separation -1 a
ccd --min-separation=nan a
ccd --threads x a
ccd -- a
ccd nofile.csv
ccd --help
mesh-ccd
mesh-ccd a
mesh-ccd a b c
mesh-ccd a b c d e
mesh-ccd a b --bogus
mesh-ccd a b -x
mesh-ccd a b --min-separation nan
mesh-ccd a b --min-separation -1
mesh-ccd a b --threads
mesh-ccd a b --threads=x
mesh-ccd a b c d --shared-vertex
mesh-ccd a b -- c
mesh-ccd --help
mesh-ccd-rigid
mesh-ccd-rigid a b
mesh-ccd-rigid a b c d
mesh-ccd-rigid a b c --bogus
mesh-ccd-rigid a b c --min-separation x
mesh-ccd-rigid a b c --min-separation
mesh-ccd-rigid a b c --float=1
mesh-ccd-rigid --help
points
points bogus
points closest
points closest a
points closest a b c
points closest a b --bogus
points closest a b -x
points closest a b --threads
points closest a b --threads x
points closest a b --upper-bound -1
points closest a b --pose 1
points closest a b --progress=1
points closest -- a b
points grid a
points grid a --dims 0,1,1 --origin 0,0,0 --step 1,1,1 --out o
points grid a --step 0,1,1
points closest --help
info x
info --help
EOF

# record ARGS...: one case's record on standard output.
record() {
    printf '== ttd'; printf ' %s' "$@"; printf '\n'
    "$TTD" "$@" < /dev/null > out 2> err
    rc=$?
    printf 'status %d\n' "$rc"
    [ -s out ] && printf 'stdout %s lines, cksum %s\n' "$(wc -l < out | tr -d ' ')" "$(cksum < out | cut -d ' ' -f 1)"
    if [ -s err ]; then
        printf 'stderr %s\n' "$(head -n 1 err)"
        [ "$(wc -l < err)" -gt 1 ] && printf 'stderr %s lines, cksum %s\n' "$(wc -l < err | tr -d ' ')" "$(cksum < err | cut -d ' ' -f 1)"
    fi
    # The properties every case must have, whatever the expected file says.
    [ "$rc" -le 2 ] || fail "ttd $*: exit status $rc"
    if [ "$rc" -eq 2 ]; then
        [ -s out ] && fail "ttd $*: exit status 2 with output on standard output"
        head -n 1 err | grep -q '^ttd: .' || head -n 1 err | grep -q '^usage: ttd ' ||
            fail "ttd $*: exit status 2 without a message: $(head -n 1 err)"
    fi
    return 0
}

: > records
while IFS= read -r line; do
    eval "set -- $line"
    record "$@" >> records || exit 1
done < cases
n=$(wc -l < cases | tr -d ' ')
if [ -n "$WRITE" ]; then
    cp records "$WRITE" || exit 1
    echo "wrote $n cases to $WRITE"
    exit 0
fi
diff -u "$HERE/args_expected.txt" records > diff || { cat diff; fail "records differ from args_expected.txt (above)"; }
echo "ok   $n command lines: statuses and messages as args_expected.txt"
