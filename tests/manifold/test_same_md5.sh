#!/bin/sh
# SPDX-License-Identifier: MIT
# Variant builds of ttd (each a path of the manifold forced or turned off at compile time, which
# must change no bit) against the default build TTD: every run of scripts/manifold_md5.py (its
# scenes, tower included) must print the same md5 with each variant as with TTD. Used by
# ttd.manifold_piece_paths (step 0 per pair of planar pieces and contact by contact,
# docs/scene-speed.md section 9) and ttd.manifold_cone_screen (the normals' screen and the keys'
# lanes, section 19).
#   sh test_same_md5.sh TTD TTD_VARIANT [TTD_VARIANT...]
# Exit 77 (skipped) without a python3 that has numpy ($PYTHON, python3, /usr/bin/python3 tried).
set -eu
[ $# -ge 2 ] || { echo "usage: $0 TTD TTD_VARIANT [TTD_VARIANT...]" >&2; exit 2; }
here=$(cd "$(dirname "$0")" && pwd)
md5py="$here/../../scripts/manifold_md5.py"
py=
for c in ${PYTHON:-} python3 /usr/bin/python3; do
    if "$c" -c 'import numpy' 2> /dev/null; then
        py=$c
        break
    fi
done
if [ -z "$py" ]; then
    echo "skipped: no python3 here imports numpy"
    exit 77
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
i=0
for ttd in "$@"; do
    i=$((i + 1))
    mkdir "$tmp/w$i"
    # the work folder's name is taken out of the printed commands by the script itself
    "$py" "$md5py" "$ttd" "$tmp/w$i" > "$tmp/out$i"
done
runs=$(grep -c . "$tmp/out1")
# 72 runs of the piles, their "all", 16 runs of the tower, its line
if [ "$runs" -ne 90 ]; then
    echo "FAIL: $runs lines from the default build, 90 expected:" >&2
    cat "$tmp/out1" >&2
    exit 1
fi
fail=0
i=1
shift
for ttd in "$@"; do
    i=$((i + 1))
    if ! cmp -s "$tmp/out1" "$tmp/out$i"; then
        echo "FAIL: $(basename "$ttd"): md5s differ from the default build's:" >&2
        diff "$tmp/out1" "$tmp/out$i" >&2 || true
        fail=1
    fi
done
[ $fail -eq 0 ] && echo "ok: $runs lines, the same md5s with every variant: $(grep '^all\|^tower' "$tmp/out1" | tr '\n' ' ')"
exit $fail
