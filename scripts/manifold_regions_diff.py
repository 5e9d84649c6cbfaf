#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Compares two builds' `ttd scene manifold` outputs over scripts/manifold_md5.py's scenes where a
change gives the points below 0 of solid pairs that are not both convex (here: a torus with
anything) one direction per contact region (docs/scenes.md 5b, "contact regions"), and must change
nothing else:

    /usr/bin/python3 scripts/manifold_md5.py OLD/ttd W1 --save OLD_OUT > OLD_LIST
    /usr/bin/python3 scripts/manifold_md5.py NEW/ttd W2 --save NEW_OUT > NEW_LIST
    /usr/bin/python3 scripts/manifold_regions_diff.py OLD_LIST NEW_LIST OLD_OUT NEW_OUT W2

Checks: every surface run and the tower's runs the same bit for bit (by their md5); in every solid
run, at every K, every body pair keeps its points (all columns but the normal, bit for bit, in
the same order), a changed normal belongs to a point below 0 of a pair with a torus, and every
point at distance 0 or above keeps its normal. Reports, over the solid runs at K = 0, the pairs
with a torus and a point below 0, how many changed, the normals changed, and the number of
distinct normals among such pairs' points below 0 before and after (summed over the pairs).
Exit 1 on a violation.
"""
import sys

sys.path.insert(0, __file__.rsplit("/", 1)[0])
from manifold_output import solid_changes, solid_rows  # noqa: E402


def main():
    old_list, new_list, old_dir, new_dir, work = sys.argv[1:6]
    got = solid_changes(old_list, new_list)
    if got is None:
        return 1
    lo, changed_runs, problems = got
    saved = sum("tower-" not in args[1] for _, args in lo)  # the tower's runs come last
    pairs = changed = normals = dirs_old = dirs_new = 0
    for n, (_, args) in enumerate(lo[:saved], 1):
        if "--solid" not in args:
            continue
        k0 = args[args.index("--max-points") + 1] == "0"
        body, o, w = solid_rows(n, args, work, old_dir, new_dir)
        for p in sorted(set(o) | set(w)):
            a, b = o.get(p, []), w.get(p, [])
            torus = "torus" in (body[p[0]], body[p[1]])
            strip = lambda r: r.split()[:5] + r.split()[8:]
            if [strip(r) for r in a] != [strip(r) for r in b]:
                print(f"run {n} pair {p}: its points changed")
                problems += 1
                continue
            below_o = {tuple(r.split()[5:8]) for r in a if float(r.split()[8]) < 0}
            below_n = {tuple(r.split()[5:8]) for r in b if float(r.split()[8]) < 0}
            if k0 and torus and below_o:
                pairs += 1
                changed += a != b
                dirs_old += len(below_o)
                dirs_new += len(below_n)
            for x, y in zip(a, b):
                if x == y:
                    continue
                normals += k0
                if float(x.split()[8]) >= 0 or not torus:
                    print(f"run {n} pair {p} ({body[p[0]]}, {body[p[1]]}): a normal changed at distance "
                          f"{x.split()[8]}")
                    problems += 1
    print(f"{len(lo)} runs, {changed_runs} changed (solid runs only); at K = 0: {pairs} pairs with a torus and a "
          f"point below 0, {changed} of them changed, {normals} normals changed; distinct normals among their points "
          f"below 0: {dirs_old} before, {dirs_new} after; {problems} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
