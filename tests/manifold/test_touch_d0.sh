#!/bin/sh
# SPDX-License-Identifier: MIT
# The manifold's touching pass (src/scene/manifold_impl.h, reduce_pair) must give the bits of the
# manifold without it: TTD_NO_TOUCH is ttd built with MANIFOLD_TOUCH_PASS=0, TTD one built with
# MANIFOLD_PASS_SMALL=0 (the passes also on a pair of few contacts, as this scene's). On the scene of
# tests/data/manifold_touch_d0 the deepest kept point (a corner) lies a rounding farther than the
# deepest contact (d0), and a corner lies between the pass's reach from d0 and choose_points'
# from the deepest kept: without the check that the deepest kept is d0, the touching pass
# answers without that corner (docs/scene-speed.md section 15, docs/scene-buffers.md section B).
#   sh test_touch_d0.sh TTD TTD_NO_TOUCH
set -eu
[ $# -eq 2 ] || { echo "usage: $0 TTD TTD_NO_TOUCH" >&2; exit 2; }
here=$(cd "$(dirname "$0")" && pwd)
scene="$here/../data/manifold_touch_d0/scene.txt"
margin=0.46339978852747071
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# the premise: the deepest contact is nearer than every point of the manifold (all of them, K = 0)
"$1" scene contacts "$scene" --margin $margin > "$tmp/contacts"
"$1" scene manifold "$scene" --margin $margin --max-points 0 > "$tmp/all"
d0=$(awk 'NR == 1 || $5 < m { m = $5 } END { printf "%.17g", m }' "$tmp/contacts")
dk=$(awk 'NR == 1 || $9 < m { m = $9 } END { printf "%.17g", m }' "$tmp/all")
if ! awk -v a="$d0" -v b="$dk" 'BEGIN { exit !(a + 0 < b + 0) }'; then
    echo "FAIL: the scene no longer builds the case: the deepest contact $d0, the deepest point $dk" >&2
    exit 1
fi
status=0
for k in 2 4 1 3 0; do
    "$1" scene manifold "$scene" --margin $margin --max-points $k > "$tmp/with"
    "$2" scene manifold "$scene" --margin $margin --max-points $k > "$tmp/without"
    if ! cmp -s "$tmp/with" "$tmp/without"; then
        echo "FAIL: K = $k: the manifold differs from the one without the touching pass" >&2
        diff "$tmp/with" "$tmp/without" >&2 || true
        status=1
    fi
done
[ $status -eq 0 ] && echo "ok: K = 0-4 as without the touching pass (deepest contact $d0, deepest point $dk)"
exit $status
