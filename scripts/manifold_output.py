# SPDX-License-Identifier: MIT
"""Reading what scripts/manifold_md5.py writes (its listing of runs, and with --save each run's
`ttd scene manifold` output as DIR/N.txt), for the scripts that compare two builds' outputs:
manifold_edges_diff.py, manifold_sat_diff.py, manifold_faces_diff.py and
manifold_regions_diff.py. A module, not a command."""
import collections


def listing(path):
    """The runs of a listing, in order: (md5, the command's arguments after the program), less
    the lines of the md5s over all runs ("all") and over the tower's ("tower")."""
    out = []
    for line in open(path):
        f = line.split()
        if f[0] in ("all", "tower"):
            continue
        out.append((f[0], f[2:]))
    return out


def rows(path):
    """A run's output lines (those of a manifold point: 17 or more columns), by body pair (i, j)."""
    g = collections.defaultdict(list)
    for line in open(path):
        f = line.split()
        if len(f) >= 17:
            g[(int(f[0]), int(f[1]))].append(line)
    return g


def kinds(scene):
    """The mesh name of each body of a scene file, in body order."""
    out = []
    for line in open(scene):
        f = line.split()
        if f and f[0] == "body":
            out.append(f[1])
    return out


def same_run(args):
    """A run's arguments less --max-points K (the key shared by its K = 0, 2 and 4 runs), and K."""
    k = args.index("--max-points")
    return tuple(args[:k] + args[k + 2:]), args[k + 1]


def listings(old_path, new_path):
    """Both builds' listings, or None after saying so when they hold different runs."""
    lo, ln = listing(old_path), listing(new_path)
    if [a for _, a in lo] != [a for _, a in ln]:
        print("the listings hold different runs")
        return None
    return lo, ln


def surface_or_tower_changes(lo, ln):
    """(runs whose md5 changed, those of them that are surface or tower runs), each of the latter
    said: changes that may touch only the solid runs' points below 0."""
    changed = problems = 0
    for n, ((mo, args), (mn, _)) in enumerate(zip(lo, ln), 1):
        if mo != mn:
            changed += 1
            if "--solid" not in args or "tower-" in args[1]:
                print(f"run {n} ({' '.join(args)}): a surface or tower run changed")
                problems += 1
    return changed, problems


def solid_rows(n, args, work, old_dir, new_dir):
    """Run n's bodies' mesh names (its scene relative to WORK unless absolute) and both builds'
    rows by body pair."""
    scene = args[1] if args[1].startswith("/") else f"{work}/{args[1]}"
    return kinds(scene), rows(f"{old_dir}/{n}.txt"), rows(f"{new_dir}/{n}.txt")
