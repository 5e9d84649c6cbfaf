#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Writes issue 32's box tower as `ttd scene` files, one per triangulation, for timing the
manifold against the contacts with `ttd scene ... --stats --repeat` (issue 32, item 6): 18 boxes
3 x 1 x 0.6, three per layer, the layers turned by 90 degrees in turn, on a floor, resting 1e-3
apart (under a margin of 0.01), in four triangulations of the boxes: 12 triangles ("plain"); a
centre vertex per face ("centre"); faces cut 4 x 4 with in-plane jitter ("cut"); faces fanned
from a corner into long slivers ("sliver"). The same scenes as `ttd bench`'s tower-KIND workloads
(bench/scene_bench.c), which `ttd bench --scene-workloads tower-cut --scene-write DIR` also writes.

    /usr/bin/python3 scripts/tower_scene.py DIR      # writes DIR/tower-<kind>.txt and the meshes
"""
import os
import sys


def face_frames(h):
    """Per face: a corner o and the two edge vectors U, V (U x V outward)."""
    out = []
    for axis in range(3):
        for sgn in (-1, 1):
            u, w = (axis + 1) % 3, (axis + 2) % 3
            U, V = (u, w) if sgn > 0 else (w, u)
            o = [0.0, 0.0, 0.0]
            o[axis] = sgn * h[axis]
            o[U] = -h[U]
            o[V] = -h[V]
            eu = [0.0, 0.0, 0.0]
            ev = [0.0, 0.0, 0.0]
            eu[U] = 2 * h[U]
            ev[V] = 2 * h[V]
            out.append((o, eu, ev))
    return out


class SplitMix:
    """splitmix64 and a uniform double in [0, 1) from its top 53 bits: the generator of `ttd bench`'s
    tower (bench/scene_bench.c), so that both make the same jitter."""

    def __init__(self, seed):
        self.s = seed

    def uniform(self):
        m = (1 << 64) - 1
        self.s = (self.s + 0x9E3779B97F4A7C15) & m
        z = self.s
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & m
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & m
        z ^= z >> 31
        return (z >> 11) * 2.0 ** -53


def box_mesh(dims, kind, seed=3):
    h = [d / 2 for d in dims]
    rng = SplitMix(seed)
    verts, index, tris = [], {}, []

    def vid(p):
        k = tuple(round(x, 15) + 0.0 for x in p)
        if k not in index:
            index[k] = len(verts)
            verts.append(list(p))
        return index[k]

    def at(o, eu, ev, a, b):
        return [o[r] + a * eu[r] + b * ev[r] for r in range(3)]

    for o, eu, ev in face_frames(h):
        if kind == "plain":
            q = [[vid(at(o, eu, ev, a, b)) for b in (0, 1)] for a in (0, 1)]
            tris += [[q[0][0], q[1][0], q[1][1]], [q[0][0], q[1][1], q[0][1]]]
        elif kind == "centre":
            c = vid(at(o, eu, ev, 0.5, 0.5))
            ring = [(0, 0), (1, 0), (1, 1), (0, 1)]
            for k in range(4):
                p, q = ring[k], ring[(k + 1) % 4]
                tris.append([vid(at(o, eu, ev, *p)), vid(at(o, eu, ev, *q)), c])
        elif kind == "cut":
            n = 4
            g = {}
            for a in range(n + 1):
                for b in range(n + 1):
                    rim = a in (0, n) or b in (0, n)  # the rim kept, so faces share its vertices
                    ja = 0 if rim else (2.0 * rng.uniform() - 1.0) * 0.3 / n  # in the face's plane
                    jb = 0 if rim else (2.0 * rng.uniform() - 1.0) * 0.3 / n
                    g[a, b] = vid(at(o, eu, ev, a / n + ja, b / n + jb))
            for a in range(n):
                for b in range(n):
                    tris += [[g[a, b], g[a + 1, b], g[a + 1, b + 1]], [g[a, b], g[a + 1, b + 1], g[a, b + 1]]]
        else:  # sliver: the far edges cut in m, fanned from corner (0, 0)
            m = 12
            rim = [(1, k / m) for k in range(m + 1)] + [(1 - k / m, 1) for k in range(1, m + 1)]
            c = vid(at(o, eu, ev, 0, 0))
            for k in range(len(rim) - 1):
                tris.append([c, vid(at(o, eu, ev, *rim[k])), vid(at(o, eu, ev, *rim[k + 1]))])
    return verts, tris


def write_obj(path, v, f):
    with open(path, "w") as out:
        for x in v:
            out.write("v %.17g %.17g %.17g\n" % tuple(x))
        for t in f:
            out.write("f %d %d %d\n" % tuple(k + 1 for k in t))


def main():
    if len(sys.argv) > 2 or (len(sys.argv) == 2 and sys.argv[1].startswith("-")):
        # an option is not a folder to write into (--help wrote a folder named --help)
        print(__doc__.strip(), file=sys.stderr if sys.argv[1] not in ("-h", "--help") else sys.stdout)
        sys.exit(0 if sys.argv[1] in ("-h", "--help") else 2)
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    os.makedirs(out, exist_ok=True)
    write_obj(f"{out}/tower-floor.obj", *box_mesh([20.0, 20.0, 1.0], "plain"))
    gap = 1e-3
    for kind in ("plain", "centre", "cut", "sliver"):
        write_obj(f"{out}/tower-box-{kind}.obj", *box_mesh([3.0, 1.0, 0.6], kind))
        lines = [f"mesh floor tower-floor.obj", f"mesh box tower-box-{kind}.obj",
                 "body floor 1 0 0 0  0 1 0 0  0 0 1 -0.5"]
        for layer in range(6):
            z = 0.3 + layer * (0.6 + gap) + gap
            for k in (-1, 0, 1):
                off = k * (1 + 2 * gap)
                if layer % 2 == 0:  # long along x, side by side along y
                    lines.append(f"body box 1 0 0 0  0 1 0 {off:.17g}  0 0 1 {z:.17g}")
                else:  # turned by 90 degrees about z
                    lines.append(f"body box 0 -1 0 {off:.17g}  1 0 0 0  0 0 1 {z:.17g}")
        with open(f"{out}/tower-{kind}.txt", "w") as f:
            f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
