#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Compares two builds' `ttd scene manifold` outputs over scripts/manifold_md5.py's scenes where a
change adds points to solid pairs with a vertex inside (docs/scenes.md 5b: the edges' deepest
points kept where deeper than the deepest vertex) and must change nothing else:

    /usr/bin/python3 scripts/manifold_md5.py OLD/ttd W1 --save OLD_OUT > OLD_LIST
    /usr/bin/python3 scripts/manifold_md5.py NEW/ttd W2 --save NEW_OUT > NEW_LIST
    /usr/bin/python3 scripts/manifold_edges_diff.py OLD_LIST OLD_OUT NEW_OUT

Checks, per body pair: at K = 0 (every merged point) the old points are all still there except
those the merge folds into a new point (reported: how far the farthest lies from one), and each
new point lies deeper than every old point below 0 of its pair, which had some (a vertex inside);
at K = 2 and 4 only the pairs changed at K = 0 change. Exit 1 on a violation. The tower's runs
(after the listing's "all" line) are not saved, so not read here: their md5s, and the "tower" line,
must be equal in the two listings.
"""
import collections
import sys

sys.path.insert(0, __file__.rsplit("/", 1)[0])
from manifold_output import beyond_k0, changed_pairs, rows, same_run, saved_runs  # noqa: E402


def main():
    listing, old_dir, new_dir = sys.argv[1:4]
    problems, changed, gained_points, lost_n, lost_far = 0, 0, 0, 0, 0.0
    pairs_at_0 = {}
    every = [args for _, args in saved_runs(listing)]
    for n, args in enumerate(every, 1):
        key, K = same_run(args)
        o, w = rows(f"{old_dir}/{n}.txt"), rows(f"{new_dir}/{n}.txt")
        diff = changed_pairs(o, w)
        changed += bool(diff)
        if K != "0":
            continue
        pairs_at_0[key] = diff
        for p in diff:
            old, new = collections.Counter(o.get(p, [])), collections.Counter(w.get(p, []))
            extra, lost = list((new - old).elements()), list((old - new).elements())
            gained_points += len(extra)
            below = [float(r.split()[8]) for r in o.get(p, []) if float(r.split()[8]) < 0]
            if not extra or not below:
                print(f"run {n} pair {p}: changed without new points or without a vertex inside")
                problems += 1
                continue
            for r in extra:
                if not float(r.split()[8]) < min(below):
                    print(f"run {n} pair {p}: a new point at {r.split()[8]}, not below the deepest vertex {min(below)}")
                    problems += 1
            for r in lost:
                x = [float(v) for v in r.split()[2:5]]
                near = min(sum((a - float(b)) ** 2 for a, b in zip(x, e.split()[2:5])) ** 0.5 for e in extra)
                lost_far = max(lost_far, near)
                lost_n += 1
    problems += beyond_k0(enumerate(every, 1), pairs_at_0, old_dir, new_dir)
    print(f"{len(every)} runs, {changed} changed; at K = 0 {gained_points} points added, {lost_n} folded into them by "
          f"the merge (the farthest {lost_far:.3g} from one); {problems} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
