# SPDX-License-Identifier: MIT
"""A pile: 200 balls dropped into a bin on a floor, pushed apart by penalty forces from the
scene's contact manifolds, moved by a plain integrator; a picture of the final pile.

    python examples/scene_pile.py                          # 200 balls, 2,500 steps, pile.png
    python examples/scene_pile.py --bodies 50 --steps 800 --out small.png
    python examples/scene_pile.py --precision float32 --threads 1

The balls are icospheres (radius 0.5, 80 triangles at --level 1), rigid bodies of mass 1 with
the inertia of a ball. The bin is five static boxes: a floor larger than the bin and four
walls; their group and mask (Scene.set_filter) keep the static bodies from being tested against
each other. Each step asks the scene for the contact manifolds within --margin (at most 4
points per body pair) and applies, at every point, a spring-damper force along the point's
normal, k * depth - c * (normal speed), depth = margin - d (so the balls rest on a cushion of
less than the margin: exact distances are 0 for touching or crossing triangles and carry no
depth of their own), and a Coulomb-capped viscous friction; a body pair's points share its
spring (k and c are divided by its point count). Semi-implicit Euler: velocities from forces,
then positions from the new velocities, orientations as unit quaternions turned by the angular
velocity. Balls start on a jittered lattice over the bin and fall together.

Every --report steps it prints the step, the simulated time, the manifold's points, the body
pairs whose triangles touch or cross (should stay 0: the cushion holds), the kinetic energy and
the milliseconds per step; at the end the pile's height, and it writes --out (PNG) with
matplotlib (Debian's python3-matplotlib), or says why not when matplotlib is missing.
"""
import argparse
import math
import time

import numpy as np

import ttd


def icosphere(level, radius):
    """A sphere: the icosahedron, each triangle split into four `level` times."""
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
    return radius * np.array(v), np.array(f)


def box(lo, hi):
    """The box [lo, hi] (3-vectors), 12 triangles."""
    v = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])], float)
    f = [[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1], [2, 3, 7], [2, 7, 6], [0, 2, 6],
         [0, 6, 4], [1, 5, 7], [1, 7, 3]]
    return v, np.array(f)


def quat_mul(a, b):
    """Hamilton products of quaternions (w, x, y, z), row by row."""
    w1, x1, y1, z1 = a.T
    w2, x2, y2, z2 = b.T
    return np.stack([w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                     w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2], 1)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bodies", type=int, default=200, help="balls (default 200)")
    ap.add_argument("--level", type=int, default=1, help="icosphere subdivisions (default 1: 80 triangles)")
    ap.add_argument("--steps", type=int, default=2500)
    ap.add_argument("--dt", type=float, default=0.002, help="time step, s (default 0.002)")
    ap.add_argument("--margin", type=float, default=0.1, help="contact margin: the cushion's thickness (default 0.1)")
    ap.add_argument("--stiffness", type=float, default=5000.0, help="k, N/m per body pair (default 5000)")
    ap.add_argument("--damping", type=float, default=40.0, help="c, N s/m per body pair (default 40)")
    ap.add_argument("--friction", type=float, default=0.4, help="Coulomb coefficient (default 0.4)")
    ap.add_argument("--report", type=int, default=250, help="print every this many steps")
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--precision", default="float64", choices=["float64", "float32"])
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--out", default="pile.png", help="the picture (PNG); '' for none")
    args = ap.parse_args()

    rng = np.random.default_rng(args.seed)
    radius, mass, g = 0.5, 1.0, np.array([0.0, 0.0, -9.81])
    inertia = 0.4 * mass * radius ** 2
    n = args.bodies
    # The bin: a square of side about 1.1 sqrt(n / 6) ball diameters, so that the pile is ~6 deep.
    side = max(2, int(math.ceil(1.1 * math.sqrt(n / 6))))
    half = side * radius + 0.05
    ball_v, ball_f = icosphere(args.level, radius)
    ball = ttd.Mesh(ball_v, ball_f, precision=args.precision)
    height = 4 * radius * (n / side ** 2 + 2)
    statics = [box([-half - 2, -half - 2, -1], [half + 2, half + 2, 0]),  # the floor, top at z = 0
               box([-half - 0.5, -half - 0.5, 0], [-half, half + 0.5, height]),
               box([half, -half - 0.5, 0], [half + 0.5, half + 0.5, height]),
               box([-half, -half - 0.5, 0], [half, -half, height]),
               box([-half, half, 0], [half, half + 0.5, height])]
    static_meshes = [ttd.Mesh(v, f, precision=args.precision) for v, f in statics]

    # Balls on a lattice over the bin, spacing 1.25 diameters, jittered; at rest.
    per_side = max(1, int((2 * half - 2 * radius) // (2.5 * radius)) + 1)
    k = np.arange(n)
    spacing = 2.5 * radius
    x = np.stack([-half + radius + 0.05 + spacing * (k % per_side), -half + radius + 0.05 + spacing * ((k // per_side) % per_side),
                  radius + 0.2 + spacing * (k // per_side ** 2)], 1).astype(float)
    x[:, :2] += 0.1 * radius * (rng.random((n, 2)) - 0.5)
    v = np.zeros((n, 3))
    w = np.zeros((n, 3))
    q = np.tile([1.0, 0, 0, 0], (n, 1))

    poses = np.tile(np.eye(4)[:3], (n + len(statics), 1, 1))

    def place():
        poses[:n] = ttd.pose(quat=q, t=x)
        return poses

    scene = ttd.Scene([ball] * n + static_meshes, place())
    for s in range(n, n + len(statics)):
        scene.set_filter(s, 2, 1)  # static bodies: group 2, tested against group 1 (the balls) only
    for b in range(n):
        scene.set_filter(b, 1, 3)
    print(f"ttd {ttd.version}: {n} balls of {ball.triangle_count} triangles in a bin {2 * half:.1f} wide, "
          f"{args.precision}, dt {args.dt} s, margin {args.margin}, instruction set {ttd.isa_selected()}")
    print(f"{'step':>6} {'time s':>7} {'points':>7} {'crossing':>8} {'kinetic J':>10} {'ms/step':>8}")

    def kinetic():
        return 0.5 * mass * float(np.sum(v * v)) + 0.5 * inertia * float(np.sum(w * w))

    crossing_max = 0
    t_report = time.perf_counter()
    for step in range(1, args.steps + 1):
        m = scene.manifold(args.margin, 4, threads=args.threads)
        i, j = m.i.astype(np.intp), m.j.astype(np.intp)
        point = m.point.astype(float)
        normal = m.normal.astype(float)
        depth = m.depth.astype(float)
        # each body pair's points share its spring
        _, inverse, counts = np.unique(i * (n + len(statics)) + j, return_inverse=True, return_counts=True)
        share = 1.0 / counts[inverse]
        # the velocity of each body at the point (static bodies: 0)
        vel = np.zeros((len(i), 2, 3))
        for side_k, b in enumerate((i, j)):
            moving = b < n
            bb = b[moving]
            vel[moving, side_k] = v[bb] + np.cross(w[bb], point[moving] - x[bb])
        rel = vel[:, 1] - vel[:, 0]                       # j's velocity relative to i's
        vn = np.sum(rel * normal, 1)                      # > 0: separating
        fn = np.maximum(0.0, share * (args.stiffness * depth - args.damping * vn))
        vt = rel - vn[:, None] * normal
        speed = np.linalg.norm(vt, axis=1)
        ft_mag = np.minimum(args.friction * fn, share * args.damping * speed)
        ft = -(ft_mag / np.maximum(speed, 1e-12))[:, None] * vt
        f = fn[:, None] * normal + ft                     # the force on j; -f on i
        F = np.zeros((n + len(statics), 3))
        T = np.zeros((n + len(statics), 3))
        np.add.at(F, j, f)
        np.add.at(F, i, -f)
        xi = np.concatenate([x, np.zeros((len(statics), 3))])
        np.add.at(T, j, np.cross(point - xi[j], f))
        np.add.at(T, i, np.cross(point - xi[i], -f))
        # semi-implicit Euler
        v += args.dt * (F[:n] / mass + g)
        w += args.dt * T[:n] / inertia
        w *= 1.0 - 0.2 * args.dt                          # a little rolling resistance
        x += args.dt * v
        q += 0.5 * args.dt * quat_mul(np.concatenate([np.zeros((n, 1)), w], 1), q)
        q /= np.linalg.norm(q, axis=1, keepdims=True)
        scene.set_poses(place())
        if step % args.report == 0 or step == args.steps:
            crossing = int(np.sum(scene.collide(0.0, threads=args.threads).i < n))
            crossing_max = max(crossing_max, crossing)
            ms = 1e3 * (time.perf_counter() - t_report) / (args.report if step % args.report == 0 else step % args.report)
            print(f"{step:6d} {step * args.dt:7.2f} {len(i):7d} {crossing:8d} {kinetic():10.4f} {ms:8.2f}")
            t_report = time.perf_counter()

    top = float(np.max(x[:, 2]) + radius)
    inside = bool(np.all(np.abs(x[:, :2]) < half) and np.all(x[:, 2] > 0))
    print(f"final: pile height {top:.2f} (balls' centres {np.min(x[:, 2]):.2f} .. {np.max(x[:, 2]):.2f}), "
          f"kinetic energy {kinetic():.4f} J, every ball in the bin: {inside}, "
          f"body pairs touching or crossing at the reports: at most {crossing_max}")
    if args.out:
        picture(args.out, ball_v, ball_f, poses[:n], half, height)


def picture(path, ball_v, ball_f, poses, half, height):
    """The balls as shaded triangles, coloured by height, in the bin's outline (matplotlib)."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    except ImportError:
        print(f"matplotlib is not installed: no picture written to {path} (apt-get install python3-matplotlib)")
        return
    R, t = poses[:, :, :3], poses[:, :, 3]
    tris = (np.einsum("bij,vj->bvi", R, ball_v) + t[:, None, :])[:, ball_f]  # (n, m, 3, 3)
    tris = tris.reshape(-1, 3, 3)
    normals = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
    normals /= np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-12)
    light = np.array([0.4, -0.5, 0.77])
    shade = 0.35 + 0.65 * np.clip(normals @ light, 0, 1)
    z = tris[:, :, 2].mean(1)
    colours = plt.cm.viridis((z - z.min()) / max(np.ptp(z), 1e-9))
    colours[:, :3] *= shade[:, None]
    fig = plt.figure(figsize=(8, 8))
    ax = fig.add_subplot(projection="3d")
    ax.add_collection3d(Poly3DCollection(tris, facecolors=colours, edgecolors="none"))
    top = max(float(t[:, 2].max()) + 0.6, 1.0)
    for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1)):  # the bin's corners
        ax.plot([sx * half] * 2, [sy * half] * 2, [0, top], color="0.5", lw=0.8)
    square = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1], [-1, -1]]) * half
    ax.plot(square[:, 0], square[:, 1], 0, color="0.3", lw=1)
    ax.set_xlim(-half - 0.5, half + 0.5)
    ax.set_ylim(-half - 0.5, half + 0.5)
    ax.set_zlim(0, max(top, 2 * half))
    ax.set_box_aspect((1, 1, max(top, 2 * half) / (2 * half + 1)))
    ax.view_init(elev=22, azim=-60)
    ax.set_title(f"{len(poses)} balls after the drop (ttd.Scene manifolds, penalty forces)")
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
