#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Compares two builds' `ttd scene manifold` outputs over scripts/manifold_md5.py's scenes where a
change adds, to solid pairs that are not both convex (here: a torus with anything), the points
where the depth peaks inside a face (docs/scenes.md 5b, "the faces' deepest points"), and must
change nothing else:

    /usr/bin/python3 scripts/manifold_md5.py OLD/ttd W1 --save OLD_OUT > OLD_LIST
    /usr/bin/python3 scripts/manifold_md5.py NEW/ttd W2 --save NEW_OUT > NEW_LIST
    /usr/bin/python3 scripts/manifold_faces_diff.py OLD_LIST NEW_LIST OLD_OUT NEW_OUT W2

Checks: every surface run and the tower's runs the same bit for bit (by their md5); per body pair
of the solid runs at K = 0 (every merged point), a changed pair has a torus and had a point below
0; its new points all lie deeper than its deepest old point; the old points it lost are those
the merge folds into a new one (reported: how far the farthest lies from it). Reports how many
pairs with a torus and a point below 0 changed, the points added, and the largest gain in depth.
Exit 1 on a violation.
"""
import collections
import sys

sys.path.insert(0, __file__.rsplit("/", 1)[0])
from manifold_output import solid_changes, solid_rows  # noqa: E402


def main():
    old_list, new_list, old_dir, new_dir, work = sys.argv[1:6]
    got = solid_changes(old_list, new_list)
    if got is None:
        return 1
    lo, changed_runs, problems = got
    pairs = changed = added = lost_n = 0
    gain, lost_far = 0.0, 0.0
    for n, (_, args) in enumerate(lo, 1):
        if "--solid" not in args or "tower-" in args[1] or args[args.index("--max-points") + 1] != "0":
            continue
        body, o, w = solid_rows(n, args, work, old_dir, new_dir)
        for p in set(o) | set(w):
            below = [float(r.split()[8]) for r in o.get(p, []) if float(r.split()[8]) < 0]
            torus = "torus" in (body[p[0]], body[p[1]])
            pairs += torus and bool(below)
            if sorted(o.get(p, [])) == sorted(w.get(p, [])):
                continue
            changed += 1
            if not torus or not below:
                print(f"run {n} pair {p} ({body[p[0]]}, {body[p[1]]}): changed, {len(below)} old points below 0")
                problems += 1
                continue
            old, new = collections.Counter(o.get(p, [])), collections.Counter(w.get(p, []))
            extra, lost = list((new - old).elements()), list((old - new).elements())
            added += len(extra)
            for e in extra:
                d = float(e.split()[8])
                if not d < min(below):
                    print(f"run {n} pair {p}: a new point at {d}, not below the deepest old point {min(below)}")
                    problems += 1
                gain = max(gain, min(below) - d)
            for r in lost:
                far = min(sum((float(a) - float(b)) ** 2 for a, b in zip(e.split()[2:5], r.split()[2:5])) ** 0.5
                          for e in extra) if extra else float("inf")
                lost_far = max(lost_far, far)
                lost_n += 1
    print(f"{changed_runs} runs changed; at K = 0: {changed} of {pairs} pairs with a torus and a point below 0 "
          f"changed, {added} points added (the largest gain in depth {gain:.3g}), {lost_n} old points merged "
          f"into them (farthest {lost_far:.3g} away); {problems} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
