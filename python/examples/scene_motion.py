# SPDX-License-Identifier: MIT
"""A scene of many bodies in motion: every step moves every body a little (set_poses) and asks
the scene's queries, printing per-step counts and times.

    python examples/scene_motion.py                       # 1,000 icospheres, 20 steps
    python examples/scene_motion.py --bodies 5000 --spacing 3 --steps 50 --threads 1
    python examples/scene_motion.py --precision float32 --margin 0.05

The bodies are icospheres of radius 1 (1,280 triangles at --level 3) on a jittered cubic
lattice of --spacing (2.01: neighbours nearly touch, and some do as they move), plus one large
floor under them. Each step turns and shifts every body by small random amounts (a random walk
around its lattice site), then runs collide (margin 0), collide within --margin, contacts
within --margin, the manifolds within --margin (--max-points each) and the closest pair, and
prints the counts and the milliseconds of each call (set_poses included).
"""
import argparse
import time

import numpy as np

import ttd


def icosphere(level):
    """A unit sphere: the icosahedron, each triangle split into four `level` times."""
    t = (1 + 5 ** 0.5) / 2
    v = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t],
         [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]]
    f = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2],
         [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11],
         [6, 2, 10], [8, 6, 7], [9, 8, 1]]
    v = [np.array(x, float) / np.linalg.norm(x) for x in v]
    for _ in range(level):
        mid, g = {}, []

        def middle(i, j):
            if (min(i, j), max(i, j)) not in mid:
                m = v[i] + v[j]
                v.append(m / np.linalg.norm(m))
                mid[min(i, j), max(i, j)] = len(v) - 1
            return mid[min(i, j), max(i, j)]

        for a, b, c in f:
            g += [[a, middle(a, b), middle(c, a)], [b, middle(b, c), middle(a, b)],
                  [c, middle(c, a), middle(b, c)], [middle(a, b), middle(b, c), middle(c, a)]]
        f = g
    return np.array(v), np.array(f)


def box(lo, hi):
    """The box [lo, hi] (3-vectors), 12 triangles."""
    v = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])], float)
    f = [[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1], [2, 3, 7], [2, 7, 6], [0, 2, 6],
         [0, 6, 4], [1, 5, 7], [1, 7, 3]]
    return v, np.array(f)


def small_rotations(rng, n, angle):
    """n random rotations by up to `angle` radians (as quaternions through ttd.pose)."""
    axis = rng.standard_normal((n, 3))
    axis /= np.linalg.norm(axis, axis=1, keepdims=True)
    half = 0.5 * angle * rng.random((n, 1))
    return ttd.pose(quat=np.concatenate([np.cos(half), np.sin(half) * axis], 1))[:, :, :3]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bodies", type=int, default=1000, help="icospheres (default 1000)")
    ap.add_argument("--level", type=int, default=3, help="icosphere subdivisions: 20 * 4**level triangles (default 3)")
    ap.add_argument("--spacing", type=float, default=2.01, help="lattice spacing; the spheres' radius is 1 (default 2.01)")
    ap.add_argument("--steps", type=int, default=20)
    ap.add_argument("--step-size", type=float, default=0.01, help="each step's shift and turn (radians) bound")
    ap.add_argument("--margin", type=float, default=0.02)
    ap.add_argument("--max-points", type=int, default=4)
    ap.add_argument("--threads", type=int, default=0, help="0: every core")
    ap.add_argument("--precision", default="float64", choices=["float64", "float32"])
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()

    rng = np.random.default_rng(args.seed)
    t0 = time.perf_counter()
    sphere = ttd.Mesh(*icosphere(args.level), precision=args.precision)
    side = int(np.ceil(args.bodies ** (1 / 3)))
    sites = np.stack(np.meshgrid(*[np.arange(side)] * 3, indexing="ij"), -1).reshape(-1, 3)[: args.bodies]
    sites = args.spacing * sites.astype(float)
    extent = sites.max(0) + 2
    floor = ttd.Mesh(*box([-2, -2, -1.5], [extent[0], extent[1], -1.0]), precision=args.precision)
    R = np.tile(np.eye(3), (args.bodies, 1, 1))
    x = sites + 0.002 * rng.standard_normal(sites.shape)
    poses = np.zeros((args.bodies + 1, 3, 4))
    poses[-1, :, :3] = np.eye(3)

    def place():
        poses[:-1, :, :3] = R
        poses[:-1, :, 3] = x
        return poses

    scene = ttd.Scene([sphere] * args.bodies + [floor], place())
    build = time.perf_counter() - t0
    print(f"ttd {ttd.version}: {args.bodies} icospheres of {sphere.triangle_count} triangles and a floor, "
          f"{args.precision}, instruction set {ttd.isa_selected()}, threads={args.threads}; built in {build:.2f} s")
    print(f"{'step':>4} {'move':>7} {'touch':>6} {'ms':>7} {'within':>6} {'ms':>7} {'contacts':>8} {'ms':>7} "
          f"{'points':>6} {'ms':>7} {'closest':>10} {'ms':>7}")
    totals = np.zeros(6)
    for step in range(args.steps):
        # a small random move of every body, pulled back towards its site
        R = small_rotations(rng, args.bodies, args.step_size) @ R
        x += args.step_size * (2 * rng.random(x.shape) - 1) - 0.1 * (x - sites)
        times = []
        t = time.perf_counter()
        scene.set_poses(place())
        times.append(time.perf_counter() - t)
        t = time.perf_counter()
        touch = scene.collide(0.0, threads=args.threads)
        times.append(time.perf_counter() - t)
        t = time.perf_counter()
        within = scene.collide(args.margin, threads=args.threads)
        times.append(time.perf_counter() - t)
        t = time.perf_counter()
        contacts = scene.contacts(args.margin, threads=args.threads)
        times.append(time.perf_counter() - t)
        t = time.perf_counter()
        manifold = scene.manifold(args.margin, args.max_points, threads=args.threads)
        times.append(time.perf_counter() - t)
        t = time.perf_counter()
        closest = scene.distance(threads=args.threads)
        times.append(time.perf_counter() - t)
        totals += times
        ms = [1e3 * s for s in times]
        print(f"{step:4d} {ms[0]:7.2f} {len(touch.i):6d} {ms[1]:7.2f} {len(within.i):6d} {ms[2]:7.2f} "
              f"{len(contacts.i):8d} {ms[3]:7.2f} {len(manifold.i):6d} {ms[4]:7.2f} {float(closest.distance):10.3g} "
              f"{ms[5]:7.2f}")
    if args.steps:
        per = 1e3 * totals / args.steps
        print(f"mean ms per step: set_poses {per[0]:.2f}, collide(0) {per[1]:.2f}, collide(margin) {per[2]:.2f}, "
              f"contacts {per[3]:.2f}, manifold {per[4]:.2f}, distance {per[5]:.2f}; all {per.sum():.2f}")


if __name__ == "__main__":
    main()
