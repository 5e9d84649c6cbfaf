# SPDX-License-Identifier: MIT
"""A cloth: a square sheet of about 20,000 triangles falls onto a sphere resting on a floor,
drapes over it and folds onto itself where it piles on the floor. Position-based dynamics; each
step moves the sheet's ttd.Mesh (Mesh.set_vertices: a refit, not a rebuild) and takes its
self-contacts (ttd.mesh_self_contacts, pairs sharing one vertex included) and the sheet-sphere
contacts (ttd.mesh_contacts) within the cloth's thickness; both push the triangles apart.

    python examples/cloth.py                           # 100 x 100 quads (20,000 triangles), cloth.png
    python examples/cloth.py --n 40 --steps 150 --out small.png
    python examples/cloth.py --threads 1               # the queries on one core
    python examples/cloth.py --scenario fall           # thrown at 40 m/s onto a plate 0.02 thick, CCD on
    python examples/cloth.py --scenario fold --no-ccd  # a half turned down onto the other: it crosses

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

The fast scenarios (--scenario fall, fold; simulate_fast, docs/ccd.md section 11) move the sheet
further in one step than its contact thickness and the plate's thickness together, so the
contacts at the step's end alone let it through; CCD (ttd.mesh_self_ccd, and ttd.mesh_ccd
against the plate) limits every step: limit_step stops the vertices of an impact short of it.
Each step is then checked by the discrete queries at --samples times along it (self-collide,
sheet-plate collide) and by side checks; python/tests/test_cloth_ccd.py runs both with and
without CCD (without, it must cross).
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


def sheet(n, side=2.0, height=0.8, tilt=(0.05, 0.02)):
    """An n x n grid of quads, side `side`, at z = height, slightly tilted (z rises by tilt[0] x +
    tilt[1] y) so that it does not land symmetrically; its faces and its edges (each quad's four
    sides, once, and one diagonal)."""
    u = np.linspace(-side / 2, side / 2, n + 1)
    x, y = np.meshgrid(u, u)
    V = np.stack([x.ravel(), y.ravel(), height + tilt[0] * x.ravel() + tilt[1] * y.ravel()], 1)
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


def keep_lengths(X, E, rest, iterations, pinned=None):
    """The edge-length constraints, `iterations` rounds, in place: Jacobi-style with relaxation.
    Pinned vertices (a bool mask) do not move; an edge's other end then takes its whole share."""
    if pinned is not None:
        w = (~pinned).astype(float)
        wa, wb = w[E[:, 0]], w[E[:, 1]]
        share = 2 * np.stack([wa, wb], 1) / np.maximum(wa + wb, 1)[:, None]
    for _ in range(iterations):
        e = X[E[:, 1]] - X[E[:, 0]]
        length = np.maximum(np.linalg.norm(e, axis=1), 1e-12)
        corr = (0.5 * (length - rest) / length)[:, None] * e
        if pinned is None:
            ca = cb = corr
        else:
            ca, cb = corr * share[:, :1], corr * share[:, 1:]
        for c in range(3):  # under-relaxed Jacobi: each vertex takes part in up to 8 edges
            X[:, c] += 0.5 * (np.bincount(E[:, 0], ca[:, c], len(X)) - np.bincount(E[:, 1], cb[:, c], len(X)))


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
        Xold, X = X, X + 0.99 * (X - Xold) + g * dt * dt
        keep_lengths(X, E, rest, iterations)
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


# ---- fast motions that no longer tunnel: a fall onto a thin plate and a fold, CCD limiting each step ----

PLATE_SIDE, PLATE_THICKNESS = 3.0, 0.02  # the plate's top face at z = 0, wider than the sheet


def plate():
    """A thin square plate: a box PLATE_SIDE x PLATE_SIDE x PLATE_THICKNESS, its top at z = 0."""
    a, t = PLATE_SIDE / 2, PLATE_THICKNESS
    V = np.array([[x, y, z] for z in (-t, 0.0) for y in (-a, a) for x in (-a, a)])
    F = np.array([[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4], [2, 6, 3], [3, 6, 7],
                  [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]])
    return V, F


def ccd_vertices(result, F, self_query):
    """The sheet's vertices in a MeshCCDResult's pairs (the sheet is mesh a; in a self query both)."""
    out = []
    for kind, a, b in zip(result.kind.tolist(), result.a.tolist(), result.b.tolist()):
        if kind == ttd.MESH_CCD_VF:
            out += [a[0]] + (F[b[0]].tolist() if self_query else [])
        elif kind == ttd.MESH_CCD_FV:
            out += F[a[0]].tolist()
        else:
            out += a + (b if self_query else [])
    return np.unique(np.array(out, dtype=np.int64))


CCD_ROUNDS = 8


def limit_step(start, X0, X1, F, plate_mesh, plate_vertices, shared_vertex, threads, fraction=0.9, rounds=CCD_ROUNDS):
    """CCD limits the step X0 -> X1 (each vertex on a straight line; `start` is a ttd.Mesh at X0) in
    place. While the sheet's self-CCD (and the sheet against the plate) finds a time of impact toi,
    the vertices of the pairs at that toi are stopped at `fraction` of it (moved back along their
    paths; the caller zeroes their velocity: an inelastic stop), and the query is asked again,
    since the stopped vertices change their neighbours' paths. A query reports only the pairs at
    its earliest toi, so a sheet landing tilted needs a round for each moment a vertex lands;
    after `rounds` rounds every vertex goes back to `fraction` of the earliest toi left (a prefix
    of paths that touch nothing, so the step never ends touching or crossed) and every vertex is
    stopped: the whole sheet's impact is taken as inelastic. (Letting the vertices not yet stopped
    keep their speed instead makes the next steps stop short again and again, by ever smaller
    fractions: tried.) Returns the stopped vertices (a bool mask), the rounds that found an impact,
    the earliest toi of each, the queries' ms (self-CCD, sheet-plate CCD), and the whole sheet's
    fraction of the step (1, or fraction * toi)."""
    stopped = np.zeros(len(X0), bool)
    tois, ms = [], np.zeros(2)
    for r in range(rounds + 1):
        t0 = time.process_time()
        hits = [(ttd.mesh_self_ccd(start, X1, shared_vertex=shared_vertex, threads=threads), True)]
        t1 = time.process_time()
        if plate_mesh is not None:
            hits.append((ttd.mesh_ccd(start, X1, plate_mesh, plate_vertices, threads=threads), False))
        ms += ((t1 - t0) * 1e3, (time.process_time() - t1) * 1e3)
        hits = [(h, s) for h, s in hits if h.toi <= 1.0]
        if not hits:
            return stopped, len(tois), tois, ms, 1.0
        tois.append(min(h.toi for h, _ in hits))
        for h, s in hits:
            v = ccd_vertices(h, F, s)
            if r < rounds:
                X1[v] = X0[v] + fraction * h.toi * (X1[v] - X0[v])
            stopped[v] = True
    scale = fraction * tois[-1]  # the whole sheet stops short of the earliest impact left
    X1[:] = X0 + scale * (X1 - X0)
    stopped[:] = True
    return stopped, len(tois), tois, ms, scale


def crossing(probe, X0, X1, plate_mesh, samples, shared_vertex):
    """The independent check, by the discrete queries: the sheet at `samples` times along the step's
    straight paths (the end included), each time self-collide (pairs sharing one vertex included
    when shared_vertex) and the sheet against the plate at distance 0. `probe` is a ttd.Mesh of the
    sheet, moved here. None, or (t, what) of the first touching or crossing found. A layer that
    passes wholly through another between two samples is not seen here: the side checks of
    simulate_fast are for that."""
    for k in range(1, samples + 1):
        t = k / samples
        probe.set_vertices(X0 + t * (X1 - X0))
        s = ttd.mesh_self_collide(probe, shared_vertex=shared_vertex)
        if s.hit:
            return t, f"self-collide: triangles {s.tri_i} and {s.tri_j}"
        if plate_mesh is not None:
            c = ttd.mesh_collide(probe, plate_mesh, None)
            if c.hit:
                return t, f"sheet-plate collide: triangles {int(c.tri_a)} and {int(c.tri_b)}"
    return None


def below_lying(X, lying_faces, which):
    """How many of the vertices `which` lie under the lying half of the fold: their closest point on
    it inside a triangle (not on its edges) and on its lower side (the sheet's triangles face +z)."""
    if not which.any():
        return 0
    c = ttd.closest_points(ttd.Mesh(X, lying_faces), X[which])
    tri = lying_faces[c.triangle]
    n = np.cross(X[tri[:, 1]] - X[tri[:, 0]], X[tri[:, 2]] - X[tri[:, 0]])
    side = np.einsum("ij,ij->i", X[which] - c.point, n)
    return int(((c.bary > 1e-9).all(1) & (side < 0)).sum())


def simulate_fast(scenario, n=40, steps=120, dt=1 / 120, speed=40.0, ccd=True, iterations=None, thickness=None,
                  shared_vertex=True, threads=0, samples=4, report=0, callback=None):
    """A fast motion, CCD limiting every step (ccd=False: the same without, to show it tunnel).

    'fall': the sheet (side 2, tilted as in simulate) starts 0.6 above the thin plate (side 3,
    0.02 thick, its top at z = 0; a floor at z = -0.5 under it) moving down at `speed` m/s.
    'fold': the sheet lies on the floor, its half x < 0 held there (pinned, as a hand holds a
    napkin's half on a table), its half x > 0 standing up along the line x = 0 and turning down
    onto the other half, its top edge at `speed` m/s (the points of the half at the speeds of a
    rigid turn).

    A step is simulate's (Verlet, the edge lengths, the floor, the contacts within the thickness
    h pushed apart, but a pushed vertex loses its velocity: an inelastic contact, which a fast
    impact needs not to bounce back), then with ccd limit_step from the step's start: vertices
    stopped short of an impact lose their velocity too. After every step `crossing` checks the step's
    motion at `samples` times, and the side checks: the fall, every vertex above the plate's
    footprint must stay above its bottom face, and no vertex may be below the plate's top where
    it was above it at the start of the step and in the footprint at both ends; the fold, every
    vertex of the moving half over the lying half (x < 0) must stay above the lying half's
    highest vertex. Returns a dict: the steps' records (step, stops' rounds, tois, ms of the CCD
    queries (self, sheet-plate), of the step (the check not counted; process CPU time, so a
    loaded machine inflates them less than wall time), crossing or None), the final vertices and faces, and the first
    crossing (step, what) or None."""
    if scenario not in ("fall", "fold"):
        raise ValueError(f"unknown scenario {scenario!r} (fall, fold)")
    edge = 2.0 / n
    h = thickness if thickness is not None else 0.6 * edge
    iterations = iterations if iterations is not None else max(12, n // 3)
    if scenario == "fall":
        V, F, E = sheet(n, height=0.6)
        PV, PF = plate()
        plate_mesh = ttd.Mesh(PV, PF)
        velocity = np.tile([0.0, 0.0, -speed], (len(V), 1))
        lying = None
    else:
        if n % 2:
            raise ValueError("the fold needs an even n (the hinge on a grid line)")
        V, F, E = sheet(n, height=FLOOR + 0.5 * h, tilt=(0.0, 0.0))
        PV = plate_mesh = None
        up = V[:, 0] > 1e-12
        r = V[up, 0].copy()  # distance from the hinge
        V[up, 0] = 0.0
        V[up, 2] += r
        velocity = np.zeros_like(V)
        velocity[up, 0] = -speed * r / r.max()
        lying = ~up
    rest = np.linalg.norm(V[E[:, 0]] - V[E[:, 1]], axis=1)  # the fold's bend keeps every edge's length
    if lying is not None:
        lying_faces = F[lying[F].all(1)]
    X, Xold = V.copy(), V - velocity * dt
    cloth = ttd.Mesh(V, F, threads=threads)   # at each step's end: the contacts
    start = ttd.Mesh(V, F, threads=threads)   # at each step's start: the CCD
    probe = ttd.Mesh(V, F, threads=threads)   # the check
    g = np.array([0.0, 0.0, -9.81])
    records, first = [], None
    for step in range(steps):
        t0 = time.process_time()
        X0 = X.copy()
        Xold, X = X, X + 0.99 * (X - Xold) + g * dt * dt
        keep_lengths(X, E, rest, iterations, lying)
        X[:, 2] = np.maximum(X[:, 2], FLOOR + 0.5 * h)
        cloth.set_vertices(X, threads=threads)
        normals = triangle_normals(X, F)
        before = X.copy()
        sc = ttd.mesh_self_contacts(cloth, h, shared_vertex=shared_vertex, threads=threads)
        push_apart(X, F, sc.tri_i, sc.tri_j, sc.p, sc.q, sc.distance, h, normals[sc.tri_i])
        if plate_mesh is not None:
            cc = ttd.mesh_contacts(cloth, plate_mesh, None, h, threads=threads)
            push_apart(X, F, cc.tri_a, cc.tri_b, cc.p, cc.q, cc.distance, h, normals[cc.tri_a], b_static=True)
        X[:, 2] = np.maximum(X[:, 2], FLOOR + 0.5 * h)
        if lying is not None:
            X[lying] = X0[lying]  # held flat on the floor
        pushed = (X != before).any(1)
        Xold[pushed] = X[pushed]  # a contact's push is inelastic: it gives no speed away from the contact
        rounds, tois, ccd_ms = 0, [], np.zeros(2)
        if ccd:
            start.set_vertices(X0, threads=threads)
            stopped, rounds, tois, ccd_ms, scale = limit_step(start, X0, X, F, plate_mesh, PV, shared_vertex, threads)
            Xold[stopped] = X[stopped]
        step_ms = (time.process_time() - t0) * 1e3
        found = crossing(probe, X0, X, plate_mesh, samples, shared_vertex)
        if found is None and scenario == "fall":
            inside = (np.abs(X[:, :2]) < PLATE_SIDE / 2).all(1)
            was_inside = (np.abs(X0[:, :2]) < PLATE_SIDE / 2).all(1)
            below = inside & (X[:, 2] < -PLATE_THICKNESS)
            through = inside & was_inside & (X0[:, 2] > 0) & (X[:, 2] < 0)
            if below.any() or through.any():
                found = 1.0, f"side: {int((below | through).sum())} vertices passed through the plate"
        elif found is None:
            under = below_lying(X, lying_faces, ~lying & (X[:, 0] < -2 * edge))
            if under:
                found = 1.0, f"side: {under} vertices of the turning half under the lying half"
        if found is not None and first is None:
            first = (step, found[1])
        records.append((step, rounds, tois, ccd_ms, step_ms, found))
        if callback is not None:
            callback(step, X0, X)
        if report and (step % report == 0 or step == steps - 1 or rounds):
            print(f"{step:6d} {rounds:6d} {(min(tois) if tois else float('inf')):10.4g} {ccd_ms[0]:9.2f} {ccd_ms[1]:9.2f} "
                  f"{step_ms:9.2f} "
                  f"{X[:, 2].min():9.3f}  {'' if found is None else f'CROSSED at t = {found[0]:g}: {found[1]}'}",
                  flush=True)
    return {"records": records, "X": X, "F": F, "first_crossing": first, "thickness": h}


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


def main_fast(a):
    """--scenario fall / fold: simulate_fast's table and summary."""
    n = a.n if a.n is not None else 40
    steps = a.steps if a.steps is not None else 120
    ccd = not a.no_ccd
    print(f"{a.scenario}: {2 * n * n} triangles, {a.speed:g} m/s, dt {a.dt:g} s, CCD {'on' if ccd else 'OFF'}; "
          f"ttd {ttd.__version__}, isa {ttd.isa_selected()}, threads {a.threads or 'all'}; every step checked at "
          f"{a.samples} times along it")
    print(f"{'step':>6} {'rounds':>6} {'toi':>10} {'self ms':>9} {'plate ms':>9} {'step ms':>9} {'lowest z':>9}")
    r = simulate_fast(a.scenario, n, steps, dt=a.dt, speed=a.speed, ccd=ccd, iterations=a.iterations,
                      thickness=a.thickness, shared_vertex=not a.no_shared_vertex, threads=a.threads,
                      samples=a.samples, report=a.report)
    rec = r["records"]
    hit = [x for x in rec if x[1]]
    queries = sum(x[1] + (x[1] <= CCD_ROUNDS) for x in hit)  # the last query found nothing, unless all rounds hit
    tois = [t for x in hit for t in x[2]]
    print(f"steps {len(rec)}; steps that CCD limited {len(hit)} (rounds {sum(x[1] for x in hit)}; earliest toi of "
          f"each round from {min(tois) if tois else float('inf'):.4g} to {max(tois) if tois else float('inf'):.4g}); "
          f"mean ms per step: self-CCD {np.mean([x[3][0] for x in rec]):.2f}, sheet-plate CCD "
          f"{np.mean([x[3][1] for x in rec]):.2f}, whole step {np.mean([x[4] for x in rec]):.2f} (the check not counted); "
          f"a query on the limited steps: self-CCD {sum(x[3][0] for x in hit) / max(1, queries):.2f}, "
          f"sheet-plate {sum(x[3][1] for x in hit) / max(1, queries):.2f}")
    if r["first_crossing"] is None:
        print(f"final: no crossing in {len(rec)} steps; lowest point {r['X'][:, 2].min():.3f}")
    else:
        step, what = r["first_crossing"]
        print(f"final: CROSSED at step {step} ({what}); lowest point {r['X'][:, 2].min():.3f}")
    return 0 if r["first_crossing"] is None or not ccd else 1


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scenario", choices=("drape", "fall", "fold"), default="drape",
                    help="drape (default): onto a sphere; fall: fast onto a thin plate; fold: fast onto itself")
    ap.add_argument("--n", type=int, default=None, help="quads along a side (triangles: 2 n^2; default 100, fall/fold 40)")
    ap.add_argument("--steps", type=int, default=None, help="default 300, fall/fold 120")
    ap.add_argument("--iterations", type=int, default=None, help="constraint rounds per step (default max(12, n / 3))")
    ap.add_argument("--thickness", type=float, default=None, help="the contact margin (default 0.6 of an edge)")
    ap.add_argument("--no-shared-vertex", action="store_true", help="leave out pairs sharing one vertex")
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--report", type=int, default=25)
    ap.add_argument("--out", default="cloth.png")
    ap.add_argument("--speed", type=float, default=40.0, help="fall/fold: the sheet's (fold: its edge's) speed, m/s")
    ap.add_argument("--dt", type=float, default=1 / 120, help="fall/fold: the step, s (default 1/120)")
    ap.add_argument("--no-ccd", action="store_true", help="fall/fold: no CCD, to see the sheet cross")
    ap.add_argument("--samples", type=int, default=4, help="fall/fold: times along each step the check looks at")
    a = ap.parse_args()
    if a.scenario != "drape":
        raise SystemExit(main_fast(a))
    a.n = a.n if a.n is not None else 100
    a.steps = a.steps if a.steps is not None else 300
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
