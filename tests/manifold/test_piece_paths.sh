#!/bin/sh
# SPDX-License-Identifier: MIT
# The manifold's step 0 per pair of planar pieces and contact by contact must give the same bits
# (src/scene/manifold_corners_impl.h, docs/scene-speed.md section 9). TTD_GROUPS and TTD_SINGLE
# are ttd built with PIECE_FEW / PIECE_GAIN overridden so that every group of flat contacts takes
# the group path, or goes contact by contact; every run of scripts/manifold_md5.py (its scenes,
# tower included) must print the same md5 with each as with the default build TTD.
#   sh test_piece_paths.sh TTD TTD_GROUPS TTD_SINGLE
# Exit 77 (skipped) without a python3 that has numpy ($PYTHON, python3, /usr/bin/python3 tried).
set -eu
[ $# -eq 3 ] || { echo "usage: $0 TTD TTD_GROUPS TTD_SINGLE" >&2; exit 2; }
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
for ttd in "$1" "$2" "$3"; do
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
for i in 2 3; do
    if ! cmp -s "$tmp/out1" "$tmp/out$i"; then
        name=$([ $i -eq 2 ] && echo "every group as a group" || echo "every group contact by contact")
        echo "FAIL: $name: md5s differ from the default build's:" >&2
        diff "$tmp/out1" "$tmp/out$i" >&2 || true
        fail=1
    fi
done
[ $fail -eq 0 ] && echo "ok: $runs lines, the same md5s on both paths: $(grep '^all\|^tower' "$tmp/out1" | tr '\n' ' ')"
exit $fail
