#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Compares two builds' `ttd scene manifold` outputs over scripts/manifold_md5.py's scenes where a
change adds, to each pair of convex solids found overlapping, one point at the pair's penetration
depth (docs/scenes.md 5b) and must change nothing else:

    /usr/bin/python3 scripts/manifold_md5.py OLD/ttd W1 --save OLD_OUT > OLD_LIST
    /usr/bin/python3 scripts/manifold_md5.py NEW/ttd W2 --save NEW_OUT > NEW_LIST
    /usr/bin/python3 scripts/manifold_sat_diff.py OLD_LIST NEW_LIST OLD_OUT NEW_OUT W2

Checks: every surface run and the tower's runs the same bit for bit (by their md5 in the two
listings); per body pair of the solid runs at K = 0 (every merged point), a changed pair is a
pair of convex bodies (balls, boxes and the floor; not a torus) that had a point below 0, and
either keeps its points, only the normals of those at its depth changed (the pair's direction;
within 1e-8 of the deepest in double, 2e-4 in float, relative above 1: the seed's window), or
gains exactly one point, no higher than its deepest old point (to 1e-12 in double, 1e-6 in
float, relative above 1), and loses only points the merge folds into that one (reported: how
far the farthest lies from it); at K = 2 and 4 only the pairs changed at K = 0 change. Reports
how many pairs of convex bodies with a point below 0 did not change (their deepest point's
normal already the pair's direction, to the bit). Exit 1 on a violation.
"""
import collections
import sys

sys.path.insert(0, __file__.rsplit("/", 1)[0])
from manifold_output import beyond_k0, changed_pairs, listings, same_run, solid_rows  # noqa: E402


def main():
    old_list, new_list, old_dir, new_dir, work = sys.argv[1:6]
    both = listings(old_list, new_list)
    if both is None:
        return 1
    lo, ln = both
    problems = 0
    saved = 0
    changed_md5 = 0
    for n, ((mo, args), (mn, _)) in enumerate(zip(lo, ln), 1):
        solid = "--solid" in args
        tower = "tower-" in args[1]
        saved += not tower
        if mo != mn:
            changed_md5 += 1
            if not solid:
                print(f"run {n} ({' '.join(args)}): a {'tower' if tower else 'surface'} run changed")
                problems += 1
    gained, lost_n, lost_far, pairs_changed, convex_overlap, convex_same = 0, 0, 0.0, 0, 0, 0
    above = 0.0  # the most a new point lies above its pair's deepest old point (float rounding)
    renormed, normals = 0, 0  # pairs whose points stay, those at the depth given its direction
    pairs_at_0 = {}
    for n, (_, args) in enumerate(lo[:saved], 1):
        if "--solid" not in args:
            continue
        key, K = same_run(args)
        body, o, w = solid_rows(n, args, work, old_dir, new_dir)
        diff = changed_pairs(o, w)
        if K != "0":
            continue
        pairs_at_0[key] = diff
        for p in set(o) | set(w):
            convex = "torus" not in (body[p[0]], body[p[1]])
            below = [float(r.split()[8]) for r in o.get(p, []) if float(r.split()[8]) < 0]
            if convex and below:
                convex_overlap += 1
                convex_same += p not in diff
            if p not in diff:
                continue
            pairs_changed += 1
            if not convex or not below:
                print(f"run {n} pair {p} ({body[p[0]]}, {body[p[1]]}): changed, {len(below)} old points below 0")
                problems += 1
                continue
            # the same points with the pair's direction as the normal of those at its depth
            strip = lambda rows: sorted(" ".join(r.split()[:5] + r.split()[8:]) for r in rows)
            if strip(o.get(p, [])) == strip(w.get(p, [])):
                renormed += 1
                tol = (1e-8 if "double" in args else 2e-4) * max(1.0, abs(min(below)))
                for a, b in zip(sorted(o[p], key=lambda r: r.split()[:5] + r.split()[8:]),
                                sorted(w[p], key=lambda r: r.split()[:5] + r.split()[8:])):
                    if a != b:
                        normals += 1
                        if not float(a.split()[8]) <= min(below) + tol:
                            print(f"run {n} pair {p}: a normal changed at {a.split()[8]}, above the depth {min(below)}")
                            problems += 1
                continue
            old, new = collections.Counter(o.get(p, [])), collections.Counter(w.get(p, []))
            extra, lost = list((new - old).elements()), list((old - new).elements())
            if len(extra) != 1:
                print(f"run {n} pair {p} ({body[p[0]]}, {body[p[1]]}): changed, {len(extra)} new points, "
                      f"{len(below)} old below 0")
                problems += 1
                continue
            gained += 1
            d = float(extra[0].split()[8])
            # in float the old points' distances are the float point query's, the new one's from
            # float coordinates in double: a few 1e-8 apart where both are the depth
            tol = (1e-12 if "double" in args else 1e-6) * max(1.0, abs(min(below)))
            if d > min(below):
                above = max(above, d - min(below))
            if not d <= min(below) + tol:
                print(f"run {n} pair {p}: the new point at {d}, above the deepest old point {min(below)}")
                problems += 1
            x = [float(v) for v in extra[0].split()[2:5]]
            for r in lost:
                far = sum((a - float(b)) ** 2 for a, b in zip(x, r.split()[2:5])) ** 0.5
                lost_far = max(lost_far, far)
                lost_n += 1
    solid = ((n, args) for n, (_, args) in enumerate(lo[:saved], 1) if "--solid" in args)
    problems += beyond_k0(solid, pairs_at_0, old_dir, new_dir)
    print(f"{len(lo)} runs, {changed_md5} changed (solid runs only); at K = 0 {pairs_changed} pairs changed: "
          f"{renormed} keeping their points, {normals} of them at the depth given the separating direction as normal; "
          f"{gained} gaining one point, {lost_n} old points folded into them by the merge (the farthest "
          f"{lost_far:.3g} from it), the new point at most {above:.3g} above the deepest old one; {convex_overlap} pairs of convex bodies had a point below 0, {convex_same} of them "
          f"unchanged; {problems} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
