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


def saved_runs(path):
    """The runs of a listing whose output --save writes (DIR/N.txt, N from 1 in this order): all
    but the tower's, which manifold_md5.py prints after the "all" line and does not save."""
    out = []
    for line in open(path):
        f = line.split()
        if f[0] == "all":
            break
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


def solid_changes(old_path, new_path):
    """For changes that may touch only the solid runs' points below 0: the old listing, the runs
    whose md5 changed, and those of them that are surface or tower runs (each said); or None
    after saying so when the listings hold different runs."""
    both = listings(old_path, new_path)
    if both is None:
        return None
    lo, ln = both
    changed = problems = 0
    for n, ((mo, args), (mn, _)) in enumerate(zip(lo, ln), 1):
        if mo != mn:
            changed += 1
            if "--solid" not in args or "tower-" in args[1]:
                print(f"run {n} ({' '.join(args)}): a surface or tower run changed")
                problems += 1
    return lo, changed, problems


def changed_pairs(o, w):
    """The body pairs whose rows differ between two runs' rows (as sets of lines, order aside)."""
    return {p for p in set(o) | set(w) if sorted(o.get(p, [])) != sorted(w.get(p, []))}


def beyond_k0(runs, pairs_at_0, old_dir, new_dir):
    """Of runs, (n, args) each, those at K = 2 or 4 where a pair changed that did not change in the
    K = 0 run of the same scene and options (pairs_at_0: same_run's key -> its changed pairs),
    each said; their number."""
    problems = 0
    for n, args in runs:
        key, K = same_run(args)
        if K == "0":
            continue
        diff = changed_pairs(rows(f"{old_dir}/{n}.txt"), rows(f"{new_dir}/{n}.txt"))
        if not diff <= pairs_at_0.get(key, set()):
            print(f"run {n}: pairs changed that did not change at K = 0: {sorted(diff - pairs_at_0.get(key, set()))}")
            problems += 1
    return problems


def solid_rows(n, args, work, old_dir, new_dir):
    """Run n's bodies' mesh names (its scene relative to WORK unless absolute) and both builds'
    rows by body pair."""
    scene = args[1] if args[1].startswith("/") else f"{work}/{args[1]}"
    return kinds(scene), rows(f"{old_dir}/{n}.txt"), rows(f"{new_dir}/{n}.txt")
