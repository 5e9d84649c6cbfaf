# SPDX-License-Identifier: MIT
"""A cloth: a square sheet of about 20,000 triangles falls onto a sphere resting on a floor,
drapes over it and folds onto itself where it piles on the floor. Position-based dynamics; each
step moves the sheet's ttd.Mesh (Mesh.set_vertices: a refit, not a rebuild) and takes its
self-contacts (ttd.mesh_self_contacts, pairs sharing one vertex included) and the sheet-sphere
contacts (ttd.mesh_contacts) within the cloth's thickness; both push the triangles apart.

    python examples/cloth.py                           # 100 x 100 quads (20,000 triangles), cloth.png
    python examples/cloth.py --n 40 --steps 150 --out small.png
    python examples/cloth.py --threads 1               # the queries on one core

The sheet (side 2, at height 0.8) is a grid of --n x --n quads, each split in two; the sphere
(radius 0.5, an icosphere of 1,280 triangles) rests on the floor z = -0.5. A step: gravity and
damping by Verlet integration; --iterations rounds (default n / 3, at least 12, so that the
sheet is as stiff at any resolution) of the edge-length constraints (every grid edge and one
diagonal per quad), Jacobi-style with relaxation; the floor and the exact sphere as hard
limits; then the contacts. For a pair within the thickness h at distance d, the two triangles'
vertices are pushed apart along their closest points' direction (the first triangle's normal
at d = 0) by (h - d) / 2 each, shared out over their three vertices. The margin h (default
0.6 of the grid's edge) stays below a triangle's height, so the neighbours of a flat sheet are
not in contact; with --shared-vertex (default) a pair folded onto itself at a common vertex is.

It prints, every --report steps, the step, the self-contacts, the sheet-sphere contacts, the
milliseconds of the refit, of each query and of the solver, and the mesh's refit rebuilds so far;
at the end the mean per-step times, and it writes --out (PNG) with matplotlib (the sheet from
two sides, and the times per step), or says why not when matplotlib is missing. simulate() is
the loop, for the tests (python/tests/test_examples.py checks every step's contacts of a small
sheet against the brute force).
"""
import argparse
import time

import numpy as np

import ttd

SPHERE_RADIUS = 0.5
FLOOR = -0.5


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


def sheet(n, side=2.0, height=0.8):
    """An n x n grid of quads, side `side`, at z = height, slightly tilted so that it does not land
    symmetrically; its faces and its edges (each quad's four sides, once, and one diagonal)."""
    u = np.linspace(-side / 2, side / 2, n + 1)
    x, y = np.meshgrid(u, u)
    V = np.stack([x.ravel(), y.ravel(), height + 0.05 * x.ravel() + 0.02 * y.ravel()], 1)
    idx = np.arange((n + 1) * (n + 1)).reshape(n + 1, n + 1)
    a, b, c, d = idx[:-1, :-1].ravel(), idx[:-1, 1:].ravel(), idx[1:, 1:].ravel(), idx[1:, :-1].ravel()
    F = np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)])
    E = np.concatenate([np.stack([idx[:, :-1].ravel(), idx[:, 1:].ravel()], 1),
                        np.stack([idx[:-1, :].ravel(), idx[1:, :].ravel()], 1), np.stack([a, c], 1)])
    return V, F, E


def push_apart(X, F, tri_a, tri_b, p, q, d, h, normal_a, b_static=False):
    """Moves the vertices of triangles tri_a (and tri_b, unless b is static) apart along q -> p
    (a's normal where d = 0) by (h - d) / 2 each (all of it on a when b is static); a vertex in
    several pairs moves by the mean of their pushes (their sum would overshoot: a vertex of a
    sheet lying on a sphere is in dozens of pairs)."""
    if len(d) == 0:
        return
    dirn = p - q
    length = np.linalg.norm(dirn, axis=1)
    touching = length < 1e-12
    dirn = np.where(touching[:, None], normal_a, dirn / np.where(touching, 1.0, length)[:, None])
    push = dirn * (h - d)[:, None] * (1.0 if b_static else 0.5)
    verts = [F[tri_a, k] for k in range(3)] + ([] if b_static else [F[tri_b, k] for k in range(3)])
    signs = [1.0] * 3 + [-1.0] * (len(verts) - 3)
    at = np.concatenate(verts)
    count = np.bincount(at, minlength=len(X))
    for c in range(3):
        total = np.bincount(at, np.concatenate([s * push[:, c] for s in signs]), len(X))
        X[:, c] += total / np.maximum(count, 1)


def triangle_normals(X, F):
    n = np.cross(X[F[:, 1]] - X[F[:, 0]], X[F[:, 2]] - X[F[:, 0]])
    return n / np.maximum(np.linalg.norm(n, axis=1), 1e-30)[:, None]


def simulate(n=100, steps=300, dt=1 / 120, iterations=None, thickness=None, shared_vertex=True, threads=0,
             sphere_level=3, callback=None, report=0):
    """Runs the cloth for `steps` steps; calls callback(step, sheet_mesh, sphere_mesh, self_contacts,
    sphere_contacts, margin) after each step's queries; returns the final vertices, the faces, the
    sphere and the per-step timings (refit, self, sphere, solver) in ms."""
    V, F, E = sheet(n)
    iterations = iterations if iterations is not None else max(12, n // 3)  # stiff at any resolution
    rest = np.linalg.norm(V[E[:, 0]] - V[E[:, 1]], axis=1)
    h = thickness if thickness is not None else 0.6 * (2.0 / n)
    SV, SF = icosphere(sphere_level, SPHERE_RADIUS)
    sphere = ttd.Mesh(SV, SF)
    cloth = ttd.Mesh(V, F, threads=threads)
    X, Xold = V.copy(), V.copy()
    g = np.array([0.0, 0.0, -9.81])
    times = []
    for step in range(steps):
        t0 = time.perf_counter()
        # Verlet with a little damping, then the edge lengths, the floor and the sphere
        Xnew = X + 0.99 * (X - Xold) + g * dt * dt
        Xold, X = X, Xnew
        for _ in range(iterations):
            e = X[E[:, 1]] - X[E[:, 0]]
            length = np.maximum(np.linalg.norm(e, axis=1), 1e-12)
            corr = (0.5 * (length - rest) / length)[:, None] * e
            for c in range(3):  # under-relaxed Jacobi: each vertex takes part in up to 8 edges
                X[:, c] += 0.5 * (np.bincount(E[:, 0], corr[:, c], len(X)) - np.bincount(E[:, 1], corr[:, c], len(X)))
        r = np.linalg.norm(X, axis=1)
        inside = r < SPHERE_RADIUS + 0.5 * h
        X[inside] *= ((SPHERE_RADIUS + 0.5 * h) / np.maximum(r[inside], 1e-12))[:, None]
        X[:, 2] = np.maximum(X[:, 2], FLOOR + 0.5 * h)
        t1 = time.perf_counter()
        cloth.set_vertices(X, threads=threads)
        t2 = time.perf_counter()
        sc = ttd.mesh_self_contacts(cloth, h, shared_vertex=shared_vertex, threads=threads)
        t3 = time.perf_counter()
        cc = ttd.mesh_contacts(cloth, sphere, None, h, threads=threads)
        t4 = time.perf_counter()
        if callback is not None:
            callback(step, cloth, sphere, sc, cc, h)
        normals = triangle_normals(X, F)
        push_apart(X, F, sc.tri_i, sc.tri_j, sc.p, sc.q, sc.distance, h, normals[sc.tri_i])
        push_apart(X, F, cc.tri_a, cc.tri_b, cc.p, cc.q, cc.distance, h, normals[cc.tri_a], b_static=True)
        X[:, 2] = np.maximum(X[:, 2], FLOOR + 0.5 * h)
        t5 = time.perf_counter()
        times.append(((t2 - t1) * 1e3, (t3 - t2) * 1e3, (t4 - t3) * 1e3, ((t1 - t0) + (t5 - t4)) * 1e3,
                      len(sc.distance), len(cc.distance)))
        if report and (step % report == 0 or step == steps - 1):
            ti = times[-1]
            print(f"{step:6d} {ti[4]:10d} {ti[5]:10d} {ti[0]:9.2f} {ti[1]:9.2f} {ti[2]:9.2f} {ti[3]:9.2f} "
                  f"{cloth.rebuilds:9d}", flush=True)
    return X, F, (SV, SF), np.array(times)


def picture(path, X, F, sphere, times):
    """The sheet from above and from the side over the sphere, and the per-step times."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    except ImportError:
        print(f"matplotlib is not installed: no picture written to {path} (apt-get install python3-matplotlib)")
        return
    fig = plt.figure(figsize=(15, 5))
    light = np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8])
    nrm = triangle_normals(X, F)
    shade = 0.35 + 0.65 * np.abs(nrm @ light)
    # one collection, so that matplotlib orders the sheet's and the sphere's triangles by depth
    # together (two collections are drawn one over the other), and a finer sphere a little inside
    # the one simulated, so that its large triangles do not sort in front of the sheet on it
    SV, SF = icosphere(4, SPHERE_RADIUS * 0.97)
    polys = np.concatenate([X[F], SV[SF]])
    colours = np.concatenate([np.outer(shade, [0.25, 0.45, 0.8]), np.tile([0.85, 0.55, 0.4], (len(SF), 1))])
    for k, (elev, azim) in enumerate(((60, -60), (8, -90))):
        ax = fig.add_subplot(1, 3, k + 1, projection="3d")
        ax.add_collection3d(Poly3DCollection(polys, facecolors=colours, edgecolor="none"))
        ax.set_xlim(-0.95, 0.95)
        ax.set_ylim(-0.95, 0.95)
        ax.set_zlim(-0.55, 0.75)
        ax.view_init(elev=elev, azim=azim)
        ax.set_box_aspect((1.9, 1.9, 1.3))
        ax.set_axis_off()
        ax.set_title("the sheet after the last step" if k == 0 else "from the side")
    ax = fig.add_subplot(1, 3, 3)
    labels = ("refit (set_vertices)", "self-contacts", "sheet-sphere contacts", "solver (numpy)")
    for c in range(4):
        ax.plot(times[:, c], label=labels[c], lw=1)
    ax.set_yscale("log")
    ax.set_xlabel("step")
    ax.set_ylabel("ms")
    ax2 = ax.twinx()
    ax2.plot(times[:, 4], color="k", lw=0.8, ls="--", label="self-contact pairs")
    ax2.set_ylabel("self-contact pairs (dashed)")
    ax.legend(loc="upper left", fontsize=8)
    ax.set_title(f"per step, {len(F):,} triangles")
    fig.savefig(path, dpi=100, bbox_inches="tight")
    print(f"wrote {path}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n", type=int, default=100, help="quads along a side (triangles: 2 n^2; default 100)")
    ap.add_argument("--steps", type=int, default=300)
    ap.add_argument("--iterations", type=int, default=None, help="constraint rounds per step (default max(12, n / 3))")
    ap.add_argument("--thickness", type=float, default=None, help="the contact margin (default 0.6 of an edge)")
    ap.add_argument("--no-shared-vertex", action="store_true", help="leave out pairs sharing one vertex")
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--report", type=int, default=25)
    ap.add_argument("--out", default="cloth.png")
    a = ap.parse_args()
    print(f"{2 * a.n * a.n} triangles; ttd {ttd.__version__}, isa {ttd.isa_selected()}, threads {a.threads or 'all'}")
    print(f"{'step':>6} {'self':>10} {'sphere':>10} {'refit ms':>9} {'self ms':>9} {'sphere ms':>9} {'solver ms':>9} "
          f"{'rebuilds':>9}")
    X, F, sphere, times = simulate(a.n, a.steps, iterations=a.iterations, thickness=a.thickness,
                                   shared_vertex=not a.no_shared_vertex, threads=a.threads, report=a.report)
    m = times.mean(axis=0)
    print(f"mean ms per step: refit {m[0]:.2f}, self-contacts {m[1]:.2f}, sheet-sphere contacts {m[2]:.2f}, "
          f"solver {m[3]:.2f}; self-contact pairs: mean {m[4]:.0f}, last {times[-1, 4]:.0f}")
    print(f"final: lowest point {X[:, 2].min():.3f} (floor {FLOOR}), highest {X[:, 2].max():.3f}")
    picture(a.out, X, F, sphere, times)


if __name__ == "__main__":
    main()
