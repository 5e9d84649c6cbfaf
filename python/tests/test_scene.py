# SPDX-License-Identifier: MIT
"""ttd.Scene: every query against an independent brute force over all triangle pairs of all
eligible body pairs in the world frame (ttd.distance on each body's vertices moved exactly as
include/ttd/ttd.h documents, ((r0 x + r1 y) + r2 z) + t per coordinate in the scene's dtype,
body i's triangle first): equal bit for bit where the library promises it (distances, points,
triangles; the manifolds' points drawn from the contacts and their corners merged as the
library documents, re-done here in numpy); filters, exclusions, removals and
additions, set_poses, both dtypes, 1 and 2 threads identical, the lock released, bad input."""
import math
import threading
import time

import numpy as np
import pytest

import ttd
from meshes import cube, grid, icosphere, move, random_poses, torus
from test_threads import long_switch_interval, released_during  # noqa: F401 (a fixture)

DTYPES = [np.float64, np.float32]
NO = ttd.NO_TRIANGLE


def meshes(dtype):
    gv, gf = grid(8)
    return [ttd.Mesh(*icosphere(1), precision=dtype), ttd.Mesh(*torus(), precision=dtype),
            ttd.Mesh(*cube(), precision=dtype), ttd.Mesh(gv * [6, 6, 1] - [3, 3, 1.2], gf, precision=dtype)]


def scene_setup(dtype, n=7, seed=5, spread=1.3):
    """n bodies of the four meshes (the last one a floor at the identity) at random poses."""
    M = meshes(dtype)
    ms = [M[k % 3] for k in range(n - 1)] + [M[3]]
    P = random_poses(n, seed, spread=spread)
    P[-1] = np.eye(4)
    return ms, P


class World:
    """The brute force: every triangle pair of every body pair, in the world frame."""

    def __init__(self, ms, P, dtype, present=None, eligible=None):
        self.ms, self.P, self.dtype = ms, np.asarray(P), dtype
        self.present = present if present is not None else set(range(len(ms)))
        self.eligible = eligible or (lambda i, j: True)
        self.tris = {b: move(ms[b].vertices, self.P[b])[ms[b].faces] for b in self.present}
        self.pairs = {}
        for i in sorted(self.present):
            for j in sorted(self.present):
                if i < j and self.eligible(i, j):
                    S, T = self.tris[i], self.tris[j]
                    na, nb = len(S), len(T)
                    self.pairs[i, j] = ttd.distance(np.broadcast_to(S[:, None], (na, nb, 3, 3)),
                                                    np.broadcast_to(T[None, :], (na, nb, 3, 3)), points=True)

    def contacts(self, margin):
        m = self.dtype(margin)
        rows = []
        for (i, j), r in sorted(self.pairs.items()):
            for a, b in np.argwhere(r.distance <= m):
                rows.append((i, j, a, b, r.distance[a, b], r.p[a, b], r.q[a, b]))
        return rows

    def closest(self):
        best = None
        for (i, j), r in sorted(self.pairs.items()):
            k = np.argmin(r.distance)  # the first minimum in (tri_i, tri_j) order
            a, b = np.unravel_index(k, r.distance.shape)
            if best is None or r.distance[a, b] < best[4]:
                best = (i, j, a, b, r.distance[a, b], r.p[a, b], r.q[a, b])
        return best


def assert_contacts_equal(got, want):
    assert len(got.i) == len(want)
    for k, (i, j, a, b, d, p, q) in enumerate(want):
        assert (got.i[k], got.j[k], got.tri_i[k], got.tri_j[k]) == (i, j, a, b), k
        assert got.distance[k] == d
        np.testing.assert_array_equal(got.p[k], p)
        np.testing.assert_array_equal(got.q[k], q)


def mesh_radius(mesh):
    """The library's radius of a mesh: from its vertices' bounding-box centre to the farthest
    vertex, rounded up by 4 eps (src/mesh/build.c)."""
    v = mesh.vertices.astype(np.float64)
    c = 0.5 * v.min(axis=0) + 0.5 * v.max(axis=0)
    return math.sqrt(np.max(np.sum((v - c) ** 2, axis=1))) * (1 + 4 * np.finfo(np.float64).eps)


FLAT_ANGLE = 1e-3  # mesh/edges.h's TTD_FLAT_ANGLE, as docs/scenes.md documents it
CORNER_ANGLE = 0.1  # face on face (docs/scenes.md, section 5, step 0)


def mesh_shape(mesh):
    """A mesh's shape around each triangle, found here by comparing triangles (docs/scenes.md 5a,
    "the edge information"): each corner's place (the smallest corner index 3 t + k at the same
    point), its first triangle, whether the place lies inside a flat part, whether each edge k
    (corner k to k + 1) is flat, and the triangle across each real (convex or concave) edge."""
    X = mesh.vertices.astype(np.float64)[mesh.faces]  # (nt, 3, 3), the mesh's own values
    nt = len(X)
    corners = X.reshape(-1, 3)
    index = {}
    place = np.empty(3 * nt, dtype=np.int64)
    for c, x in enumerate(map(tuple, (corners + 0.0).tolist())):  # + 0.0: -0 is 0
        place[c] = index.setdefault(x, c)
    place = place.reshape(nt, 3)
    normal = np.zeros((nt, 3))
    has = np.zeros(nt, dtype=bool)
    for t in range(nt):
        e1, e2 = X[t, 1] - X[t, 0], X[t, 2] - X[t, 0]
        m = max(np.abs(e1).max(), np.abs(e2).max())
        if len(set(place[t])) < 3 or not m > 0:
            continue
        e1, e2 = e1 / m, e2 / m
        c = np.cross(e1, e2)
        ln = math.sqrt(c @ c)
        if ln > 64 * np.finfo(np.float64).eps * math.sqrt(e1 @ e1) * math.sqrt(e2 @ e2):
            has[t], normal[t] = True, c / ln
    cos_flat = math.cos(FLAT_ANGLE)
    around = {}
    for t in range(nt):
        for k in range(3):
            around.setdefault(place[t, k], []).append(t)
    flat_edge = np.zeros((nt, 3), dtype=bool)
    real_edge = np.zeros((nt, 3), dtype=bool)
    across = np.full((nt, 3), -1, dtype=np.int64)
    for t in range(nt):
        for k in range(3):
            a, b = place[t, k], place[t, (k + 1) % 3]
            others = [u for u in sorted(set(around[a])) if u != t and b in place[u]] if has[t] else []
            if len(others) != 1 or not has[others[0]]:
                continue
            u = others[0]
            ia, ib = list(place[u]).index(a), list(place[u]).index(b)
            if (ib + 1) % 3 != ia:
                continue  # not running the other way
            far = [q for q in range(3) if place[u, q] not in (a, b)][0]
            side = (X[u, far] - X[t, k]) @ normal[t]
            if normal[t] @ normal[u] >= cos_flat:
                flat_edge[t, k] = True
            elif side != 0:
                real_edge[t, k], across[t, k] = True, u
    flat_vertex = np.zeros((nt, 3), dtype=bool)
    for t in range(nt):
        for k in range(3):
            ring = around[place[t, k]]
            t0 = min(ring)
            flat_vertex[t, k] = all(
                has[u] and has[t0] and normal[u] @ normal[t0] >= cos_flat and flat_edge[u, q] and flat_edge[u, (q + 2) % 3]
                for u in set(ring) for q in range(3) if place[u, q] == place[t, k])
    first = place // 3
    return place, first, flat_vertex, flat_edge, across, has


def unit_normals(X):
    """The unit normals of triangles X (n, 3, 3) in float64; 0 where a triangle has none."""
    X = np.asarray(X, dtype=np.float64)
    c = np.cross(X[:, 1] - X[:, 0], X[:, 2] - X[:, 0])
    ln = np.sqrt(np.sum(c * c, axis=1))
    return np.where(ln[:, None] > 0, c / np.where(ln > 0, ln, 1)[:, None], 0)


def corners(world, i, j, margin):
    """The corners of flat contact body pair (i, j) adds to its contacts (docs/scenes.md 5, step
    0; tests/scene_corners_ref.h in C), where a contact's triangles lie face on face (both have a
    normal, opposite within CORNER_ANGLE): each vertex not inside a flat part within the margin of
    the other triangle; each two edges not between coplanar triangles whose closest points lie
    inside both within the margin. The same question (a vertex's place and the other triangle;
    two edges' places) once, with the smallest triangles asking it; each vertex once, at its
    smallest distance (ties to the smaller triangle). The exact method on the scalar row, the
    vertex as a triangle of three equal vertices, each edge from its smaller end, the smaller
    first. [(a, b, d, p, q)]"""
    real = world.dtype
    m = real(margin)
    r = world.pairs[i, j]
    S, T = world.tris[i], world.tris[j]
    shape = [mesh_shape(world.ms[i]), mesh_shape(world.ms[j])]
    tri = [S, T]
    verts, edges = {}, {}  # question -> the smallest triangles asking it
    NS, NT = unit_normals(S), unit_normals(T)
    for a, b in np.argwhere(r.distance <= m):
        if not (shape[0][5][a] and shape[1][5][b] and NS[a] @ NT[b] <= -math.cos(CORNER_ANGLE)):
            continue
        t = (a, b)
        for side in (0, 1):
            place, _, flat_vertex, _, _, _ = shape[side]
            for k in range(3):
                if not flat_vertex[t[side], k]:
                    key = (side, place[t[side], k], t[1 - side])
                    verts[key] = min(verts.get(key, (a, b, k)), (a, b, k))
        pa, _, _, flat_e, _, _ = shape[0]
        pb, _, _, flat_f, _, _ = shape[1]
        for k in range(3):
            ea = tuple(sorted((pa[a, k], pa[a, (k + 1) % 3])))
            if flat_e[a, k] or ea[0] == ea[1]:
                continue
            for l in range(3):
                eb = tuple(sorted((pb[b, l], pb[b, (l + 1) % 3])))
                if flat_f[b, l] or eb[0] == eb[1]:
                    continue
                edges[ea, eb] = min(edges.get((ea, eb), (a, b, k, l)), (a, b, k, l))
    out = []
    if verts:
        keys = sorted(verts)
        P = np.array([[tri[side][verts[key][side], verts[key][2]]] * 3 for key in keys for side in [key[0]]], dtype=real)
        Q = np.array([tri[1 - key[0]][key[2]] for key in keys], dtype=real)
        res = ttd.distance(P, Q, points=True, isa="scalar")
        best = {}
        for key, x, d, q in zip(keys, P[:, 0], res.distance, res.q):
            side, pl, other = key
            if not d <= m:
                continue
            if (side, pl) not in best or (d, other) < best[side, pl][:2]:
                a, b, _ = verts[key]
                far = x if d == 0 else q
                best[side, pl] = (d, other, (a, b, d, x if side == 0 else far, far if side == 0 else x))
        out += [best[k][2] for k in sorted(best)]
    if edges:
        def canon(e0, e1):
            return (e0, e1) if tuple(e0) <= tuple(e1) else (e1, e0)
        segs = []
        for key in sorted(edges):
            a, b, k, l = edges[key]
            s_, t_ = canon(S[a, k], S[a, (k + 1) % 3]), canon(T[b, l], T[b, (l + 1) % 3])
            second = (tuple(s_[0]), tuple(s_[1])) > (tuple(t_[0]), tuple(t_[1]))
            segs.append((a, b, second, t_ if second else s_, s_ if second else t_))
        A = np.array([[x[3][0], x[3][1], x[3][1]] for x in segs], dtype=real)
        B = np.array([[x[4][0], x[4][1], x[4][1]] for x in segs], dtype=real)
        res = ttd.distance(A, B, points=True, isa="scalar")
        for (a, b, second, _, _), d, p, q, wp, wq in zip(segs, res.distance, res.p, res.q, res.bary_p, res.bary_q):
            if not (d <= m and 0 < wp[0] < 1 and 0 < wq[0] < 1):
                continue
            first_pt, other = p, (p if d == 0 else q)
            out.append((a, b, d, other if second else first_pt, first_pt if second else other))
    return out


def planar_triangles(mesh):
    """Per triangle: whether its flat piece (the triangles joined by flat edges) is planar, every
    vertex of the piece within 2^-36 of the mesh's scale (the power of two at or above its largest
    coordinate) of the plane of the piece's largest triangle (docs/scenes.md 5, step 0)."""
    X = mesh.vertices.astype(np.float64)[mesh.faces]
    nt = len(X)
    place, _, _, flat_edge, _, has = mesh_shape(mesh)
    piece = list(range(nt))

    def root(t):
        while piece[t] != t:
            t = piece[t]
        return t
    for t in range(nt):
        for k in range(3):
            if flat_edge[t, k]:
                a, b = place[t, k], place[t, (k + 1) % 3]
                for u in range(nt):
                    if u != t and a in place[u] and b in place[u]:
                        ra, rb = root(t), root(u)
                        piece[max(ra, rb)] = min(ra, rb)
    top = float(np.abs(X).max()) if nt else 0.0
    tol = math.ldexp(1.0, math.frexp(top)[1] - 36) if top > 0 else math.ldexp(1.0, -36)
    groups = {}
    for t in range(nt):
        groups.setdefault(root(t), []).append(t)
    planar = np.zeros(nt, dtype=bool)
    for ts in groups.values():
        areas = [np.linalg.norm(np.cross(X[t, 1] - X[t, 0], X[t, 2] - X[t, 0])) for t in ts]
        big = ts[int(np.argmax(areas))]
        n = np.cross(X[big, 1] - X[big, 0], X[big, 2] - X[big, 0])
        ok = all(has[t] for t in ts) and np.linalg.norm(n) > 0
        if ok:
            n = n / np.linalg.norm(n)
            ok = all(abs((X[t, k] - X[big, 0]) @ n) <= tol for t in ts for k in range(3))
        planar[ts] = ok
    return planar


def flat_contacts(world, i, j, cs):
    """Which contacts cs [(a, b, d, p, q)] of body pair (i, j) are of flat contact (docs/scenes.md 5,
    step 0): face on face (as corners() tests it), both triangles' pieces planar; none when one
    such contact is at distance 0. Their region's corners stand for them. The scenes here are
    surfaces (a solid's pairs keep every contact)."""
    NS, NT = unit_normals(world.tris[i]), unit_normals(world.tris[j])
    hi, hj = mesh_shape(world.ms[i])[5], mesh_shape(world.ms[j])[5]
    pi, pj = planar_triangles(world.ms[i]), planar_triangles(world.ms[j])
    flat = [bool(hi[c[0]] and hj[c[1]] and NS[c[0]] @ NT[c[1]] <= -math.cos(CORNER_ANGLE) and pi[c[0]] and pj[c[1]])
            for c in cs]
    if any(f and not c[2] > 0 for f, c in zip(flat, cs)):
        return [False] * len(cs)
    return flat


def manifold_kept(world, margin):
    """The points a manifold draws from, re-done (docs/scenes.md, section 5): per body pair, its
    contacts and the corners they add, in depth order (distance, triangles, midpoint), a point
    within 1e-3 of the smaller radius of a point kept before it goes.
    {(i, j): (tolerance, [(a, b, point, d, depth)])}"""
    real = world.dtype
    by_pair = {}
    for row in world.contacts(margin):
        by_pair.setdefault(row[:2], []).append(row[2:])
    out = {}
    for (i, j), cs in sorted(by_pair.items()):
        flat = flat_contacts(world, i, j, cs)
        cs = [c for c, f in zip(cs, flat) if not f] + corners(world, i, j, margin)

        def mid(c):
            return 0.5 * np.asarray(c[3], dtype=np.float64) + 0.5 * np.asarray(c[4], dtype=np.float64)
        cs = sorted(cs, key=lambda c: (c[2], c[0], c[1], tuple(mid(c))))
        tol = 1e-3 * min(mesh_radius(world.ms[i]), mesh_radius(world.ms[j]))
        kept = []
        for c in cs:
            point = mid(c).astype(real)
            x = point.astype(np.float64)
            if all(math.sqrt(np.sum((x - k[2].astype(np.float64)) ** 2)) > tol for k in kept):
                kept.append((c[0], c[1], point, c[2], real(real(margin) - c[2])))
        out[i, j] = (tol, kept)
    return out


def check_all(scene, world, margins=(0.0, 0.05, 0.3)):
    dtype = world.dtype
    for margin in margins:
        want = world.contacts(margin)
        got = scene.contacts(margin)
        assert_contacts_equal(got, want)
        # collide: the body pairs within the margin, with a witness within it
        hit = scene.collide(margin)
        pairs = sorted({(c[0], c[1]) for c in want})
        assert list(zip(hit.i.tolist(), hit.j.tolist())) == pairs
        for i, j, a, b in zip(hit.i, hit.j, hit.tri_i, hit.tri_j):
            assert world.pairs[i, j].distance[a, b] <= dtype(margin)
        # manifold: min(K, kept) points per body pair, each a kept contact or corner (triangles, point,
        # distance, depth bit for bit), the first within the seed's window of the smallest
        # distance, no two within the tolerance, unit normals (the rule: tests/test_scene_contacts.c)
        kept = manifold_kept(world, margin)
        window = 2.0 ** -30 if dtype == np.float64 else 2.0 ** -16
        for max_points in (1, 4, 0):
            m = scene.manifold(margin, max_points)
            at = 0
            for (i, j), (tol, ks) in kept.items():
                want = len(ks) if max_points == 0 else min(max_points, len(ks))
                rows = range(at, at + want)
                at += want
                big = max(mesh_radius(world.ms[i]), mesh_radius(world.ms[j]))
                for n, k in enumerate(rows):
                    assert (m.i[k], m.j[k]) == (i, j), (margin, max_points, k)
                    same = [x for x in ks if (x[0], x[1]) == (m.tri_i[k], m.tri_j[k]) and np.array_equal(x[2], m.point[k])]
                    assert len(same) == 1, (margin, max_points, k)
                    _, _, point, d, depth = same[0]
                    assert m.distance[k] == d and m.depth[k] == depth
                    # each body's point: point their midpoint, |point_i - point_j| = |d|
                    pi, pj = m.point_i[k].astype(np.float64), m.point_j[k].astype(np.float64)
                    assert np.array_equal((0.5 * pi + 0.5 * pj).astype(dtype), m.point[k])
                    gap = math.sqrt((pi - pj) @ (pi - pj))
                    assert abs(gap - abs(float(d))) <= (1e-12 if dtype == np.float64 else 1e-6) * big
                    nv = m.normal[k].astype(np.float64)
                    assert abs(np.sqrt(nv @ nv) - 1) < 1e-5
                    if n == 0:
                        assert float(d) - float(ks[0][3]) <= window * big
                    for k2 in rows[:n]:
                        gap = m.point[k].astype(np.float64) - m.point[k2].astype(np.float64)
                        assert math.sqrt(gap @ gap) > tol * (1 - 1e-9)
            assert len(m.i) == at, (margin, max_points)
    # distance
    best = world.closest()
    for nearest in (False, True):
        d = scene.distance(nearest=nearest)
        if best is None:
            assert d.distance == np.inf and (d.i, d.j, d.tri_i, d.tri_j) == (NO, NO, NO, NO)
        else:
            assert (d.i, d.j, d.tri_i, d.tri_j) == best[:4]
            assert d.distance == best[4]
            np.testing.assert_array_equal(d.p, best[5])
            np.testing.assert_array_equal(d.q, best[6])
        assert (d.nearest is None) == (not nearest)
    near = scene.distance(nearest=True).nearest
    assert len(near.i) == scene.id_limit
    for b in range(scene.id_limit):
        if b not in world.present:
            assert near.distance[b] == np.inf and (near.j[b], near.tri_i[b], near.tri_j[b]) == (NO, NO, NO)
            continue
        cands = []
        for (i, j), r in world.pairs.items():
            if b in (i, j):
                D = r.distance if b == i else r.distance.T  # body b's triangles first
                k = np.argmin(D)
                a, c = np.unravel_index(k, D.shape)
                cands.append((D[a, c], j if b == i else i, a, c))
        if not cands:
            assert near.distance[b] == np.inf and near.j[b] == NO
            continue
        dist, partner, a, c = min(cands)
        assert near.i[b] == b
        assert (near.distance[b], near.j[b], near.tri_i[b], near.tri_j[b]) == (dist, partner, a, c), b
        assert np.all(near.p[b] == near.q[b]) if dist == 0 else abs(np.linalg.norm(
            near.p[b].astype(np.float64) - near.q[b].astype(np.float64)) - dist) <= 1e-5 * max(1.0, dist)


@pytest.mark.parametrize("dtype", DTYPES, ids=["float64", "float32"])
def test_queries_equal_the_brute_force(dtype):
    ms, P = scene_setup(dtype)
    scene = ttd.Scene(ms, P)
    assert scene.dtype == dtype and len(scene) == 7 and scene.id_limit == 7
    world = World(ms, P, dtype)
    assert len(world.contacts(0.05)) > 0, "the scene has contacts"
    check_all(scene, world)


@pytest.mark.parametrize("dtype", DTYPES, ids=["float64", "float32"])
def test_stacked_cubes_corners(dtype):
    """Unit cubes stacked face on face on a flat floor (turned, tilted by up to 0.02, offset,
    flush and at gaps within the margin): the manifolds with their corners of flat contact
    against the brute force."""
    cube_mesh = ttd.Mesh(*cube(), precision=dtype)
    fv, ff = grid(4)
    fv[:, 2] = 0
    floor = ttd.Mesh(fv * [4, 4, 1] - [2, 2, 0], ff, precision=dtype)
    P = [np.eye(4)]
    z = 0.003
    for yaw, tilt, off, gap in ((0.3, 0.0, 0.1, 0.0), (-0.2, 0.02, -0.15, 0.004), (0.0, 0.0, 0.3, 0.002)):
        cy, sy, ct, st = math.cos(yaw), math.sin(yaw), math.cos(tilt), math.sin(tilt)
        R = np.array([[cy, -sy * ct, sy * st], [sy, cy * ct, -cy * st], [0, st, ct]])
        Q = np.eye(4)
        Q[:3, :3] = R
        Q[:3, 3] = np.array([off, -off, z + gap + 0.5]) - R @ [0.5, 0.5, 0.5]
        P.append(Q)
        z += 1 + gap + 0.5 * abs(tilt) + 0.01
    ms = [floor] + [cube_mesh] * 3
    scene = ttd.Scene(ms, np.array(P))
    world = World(ms, np.array(P), dtype)
    n = sum(len(corners(world, i, j, 0.05)) for (i, j), r in world.pairs.items() if (r.distance <= dtype(0.05)).any())
    assert n > 0, "the stack has corners of flat contact"
    check_all(scene, world, margins=(0.0, 0.05))


@pytest.mark.parametrize("dtype", DTYPES, ids=["float64", "float32"])
def test_poses_3x4_and_builder_give_the_same_scene(dtype):
    ms, P = scene_setup(dtype)
    a = ttd.Scene(ms, P[:, :3, :])
    b = ttd.Scene(precision=dtype)
    assert [b.add(m, p) for m, p in zip(ms, P)] == list(range(7))
    for s in (a, b):
        assert_contacts_equal(s.contacts(0.1), World(ms, P, dtype).contacts(0.1))


@pytest.mark.parametrize("dtype", DTYPES, ids=["float64", "float32"])
def test_set_poses_moves_every_body(dtype):
    ms, P = scene_setup(dtype)
    scene = ttd.Scene(ms, P)
    for step in range(3):
        Q = random_poses(7, 100 + step, spread=1.2)
        Q[-1] = np.eye(4)
        Q[-1, 2, 3] = -0.1 * step
        scene.set_poses(Q if step % 2 else Q[:, :3, :])
        check_all(scene, World(ms, Q, dtype), margins=(0.0, 0.1))
    scene.set_pose(2, np.eye(4))
    Q[2] = np.eye(4)
    check_all(scene, World(ms, Q, dtype), margins=(0.1,))


@pytest.mark.parametrize("dtype", DTYPES, ids=["float64", "float32"])
def test_solids(dtype):
    """Solid bodies (docs/scenes.md, section 5b): a unit cube sunk 0.1 into another has its
    deepest point at depth margin + 0.1 with normal +z (as surfaces: no point below 0); a half cube
    inside a cube is found by collide(0) (the inner body's triangle 0), distance 0, and its
    manifold's points are its 8 vertices at minus their exact distance to the outer cube
    (ttd.closest_points with the outer body's pose) and the pair's penetration depth, 0.75 along
    an axis; an open mesh cannot be a solid."""
    unit = ttd.Mesh(*cube(), precision=dtype)
    v, f = cube()
    half = ttd.Mesh(0.5 * v, f, precision=dtype)
    up = np.eye(4)
    up[:3, 3] = [0.25, 0.25, 0.9]
    scene = ttd.Scene([unit, half], np.array([np.eye(4), up]))
    assert np.all(scene.manifold(0.01, 0).distance >= 0)
    scene.set_solid(0)
    scene.set_solid(1, solid=True)
    m = scene.manifold(0.01, 4)
    k = int(np.argmax(m.depth))
    assert abs(float(m.depth[k]) - 0.11) <= (1e-12 if dtype == np.float64 else 1e-6)
    np.testing.assert_allclose(m.normal[k].astype(np.float64), [0, 0, 1], atol=1e-6)
    assert np.sum(m.distance < 0) == 4  # the half cube's bottom corners, the deepest level
    scene.set_solid(1, solid=False)
    assert np.all(scene.manifold(0.01, 0).distance >= 0)
    # nested
    inner = np.eye(4)
    inner[:3, 3] = [0.25, 0.25, 0.25]
    nest = ttd.Scene([unit, half], np.array([np.eye(4), inner]))
    assert len(nest.collide().i) == 0
    nest.set_solid(0)
    nest.set_solid(1)
    hit = nest.collide()
    assert (hit.i.tolist(), hit.j.tolist(), hit.tri_i.tolist(), hit.tri_j.tolist()) == ([0], [1], [NO], [0])
    d = nest.distance(nearest=True)
    assert d.distance == 0 and np.all(d.nearest.distance == 0)
    m = nest.manifold(0.01, 0)
    assert len(m.i) == 9 and np.all(m.distance < 0)
    # the pair's penetration depth (two convex solids): the half cube leaves the cube by 0.75
    # along an axis; the other 8 points are the half cube's corners
    deep = m.distance < -0.5
    assert np.sum(deep) == 1 and abs(float(m.distance[deep][0]) + 0.75) <= 1e-6
    n = m.normal[deep][0].astype(np.float64)
    assert sorted(np.abs(n).tolist()) == [0, 0, 1]
    point_i, point_j, dist = m.point_i[~deep], m.point_j[~deep], m.distance[~deep]
    corners = move(half.vertices, inner)
    # the inner body's points are its corners; the outer's lie on its faces, -d from them
    np.testing.assert_array_equal(sorted(map(tuple, point_j.astype(np.float64))),
                                  sorted(map(tuple, corners.astype(dtype).astype(np.float64))))
    out = point_i.astype(np.float64)
    assert np.all(np.min(np.minimum(np.abs(out), np.abs(out - 1)), axis=1) <= 1e-6)
    np.testing.assert_allclose(np.linalg.norm(out - point_j, axis=1), -dist.astype(np.float64), atol=1e-6)
    want = ttd.closest_points(unit, corners, pose=np.eye(4)).distance
    got = sorted(float(-x) for x in dist)
    assert got == sorted(float(x) for x in want)
    # an open mesh is no solid
    gv, gf = grid(2)
    flat = ttd.Scene([ttd.Mesh(gv, gf, precision=dtype)], np.array([np.eye(4)]))
    with pytest.raises(ValueError, match="cannot be a solid"):
        flat.set_solid(0)
    flat.set_solid(0, solid=False)
    flat.remove(0)
    with pytest.raises((ValueError, IndexError)):
        flat.set_solid(0)


@pytest.mark.parametrize("dtype", DTYPES, ids=["float64", "float32"])
def test_filters_exclusions_removals(dtype):
    ms, P = scene_setup(dtype)
    scene = ttd.Scene(ms, P)
    groups = {0: (1, 0xFFFFFFFF), 1: (2, 0xFFFFFFFF ^ 2), 2: (2, 1), 3: (4, 0), 4: (1, 0xFFFFFFFF)}
    for b, (g, m) in groups.items():
        scene.set_filter(b, g, m)
    scene.exclude(6, 0)
    scene.exclude(1, 5)
    scene.exclude(1, 5, excluded=False)
    scene.exclude(4, 6)

    def eligible(i, j):
        gi, mi = groups.get(i, (1, 0xFFFFFFFF))
        gj, mj = groups.get(j, (1, 0xFFFFFFFF))
        return bool(gi & mj) and bool(gj & mi) and {i, j} not in ({0, 6}, {4, 6})

    check_all(scene, World(ms, P, dtype, eligible=eligible))
    scene.remove(1)
    scene.remove(4)
    present = {0, 2, 3, 5, 6}
    assert len(scene) == 5 and scene.id_limit == 7 and scene.ids.tolist() == sorted(present)
    assert scene.meshes[1] is None and scene.meshes[0] is ms[0]
    check_all(scene, World(ms, P, dtype, present=present, eligible=eligible))
    # an addition gets id 7; set_poses takes one pose per id, removed ones ignored
    assert scene.add(ms[0], P[1]) == 7
    ms2, P2 = ms + [ms[0]], np.concatenate([P, P[1:2]])
    present.add(7)
    check_all(scene, World(ms2, P2, dtype, present=present, eligible=eligible))
    Q = P2.copy()
    Q[:, :3, 3] *= 0.9
    Q[1, 0, 0] = np.nan  # removed: ignored
    scene.set_poses(Q)
    Q[1] = P2[1]
    check_all(scene, World(ms2, Q, dtype, present=present, eligible=eligible), margins=(0.0, 0.1))


def test_one_mesh_for_every_body_and_meshes_outlive_the_scene():
    import gc
    P = np.tile(np.eye(4), (3, 1, 1))
    P[:, 0, 3] = [0, 2.0, 4.5]
    scene = ttd.Scene(ttd.Mesh(*icosphere(1)), P)  # the only reference to the mesh is the scene's
    gc.collect()
    assert len(scene) == 3 and scene.meshes[0] is scene.meshes[2]
    hit = scene.collide()
    assert hit.i.tolist() == [0] and hit.j.tolist() == [1]  # touching at x = 1
    assert ttd.Scene([scene.meshes[0]]).id_limit == 1  # a mesh and no poses: the identity


@pytest.mark.parametrize("dtype", DTYPES, ids=["float64", "float32"])
def test_threads_and_isas_give_identical_results(dtype):
    ms, P = scene_setup(dtype, n=9, seed=8)
    scene = ttd.Scene(ms, P)
    ref = None
    for isa in [i for i in ttd.ISAS if i != "auto" and ttd.isa_available(i)]:
        for threads in (1, 2):
            got = (scene.contacts(0.2, isa=isa, threads=threads), scene.collide(0.1, isa=isa, threads=threads),
                   scene.manifold(0.2, 3, isa=isa, threads=threads),
                   scene.distance(nearest=True, isa=isa, threads=threads))
            flat = [np.asarray(x) for r in got for x in r if not isinstance(x, tuple)]
            flat += [np.asarray(x) for x in got[3].nearest]
            if ref is None:
                ref = flat
            for x, y in zip(flat, ref):
                np.testing.assert_array_equal(x, y)


def test_upper_bound_and_empty_scenes():
    ms, P = scene_setup(np.float64)
    scene = ttd.Scene(ms, P)
    best = scene.distance()
    assert scene.distance(upper_bound=float(best.distance)).distance == best.distance
    far = ttd.Scene([ms[0], ms[0]], np.stack([np.eye(4), np.eye(4)]))
    far.set_pose(1, np.array([[1, 0, 0, 10.0], [0, 1, 0, 0], [0, 0, 1, 0]]))
    d = far.distance(upper_bound=1.0, nearest=True)
    assert d.distance == np.inf and d.i == NO and d.nearest.j.tolist() == [NO, NO]
    assert far.distance().distance == pytest.approx(8.0, abs=1e-9)
    for s in (ttd.Scene(), ttd.Scene(precision="float32"), ttd.Scene([ms[0]])):
        assert len(s.collide().i) == 0 and len(s.contacts(1.0).i) == 0 and len(s.manifold(1.0).i) == 0
        assert s.distance().distance == np.inf
    assert ttd.Scene().dtype is None and ttd.Scene(precision="float32").dtype == np.float32


def test_results_are_views_of_library_records():
    ms, P = scene_setup(np.float64)
    scene = ttd.Scene(ms, P)
    c = scene.contacts(0.1)
    assert c.p.base is not None and c.i.base is c.p.base
    assert c.p.base.dtype == ttd.SCENE_CONTACT_DTYPE_FLOAT64
    assert scene.manifold(0.1).point.base.dtype == ttd.SCENE_POINT_DTYPE_FLOAT64
    assert scene.collide(0.1).i.base.dtype == ttd.SCENE_HIT_DTYPE
    f = ttd.Scene([ttd.Mesh(*icosphere(1), precision="float32")] * 2, P[:2])
    assert f.contacts(3.0).distance.dtype == np.float32
    assert f.manifold(3.0).normal.dtype == np.float32


def icosphere_block():
    """27 level-3 icospheres on a 3x3x3 grid, 1.9 apart: a query of tens of milliseconds."""
    A = ttd.Mesh(*icosphere(3))
    P = np.tile(np.eye(4), (27, 1, 1))
    P[:, :3, 3] = 1.9 * np.stack(np.meshgrid(*[np.arange(3)] * 3, indexing="ij"), -1).reshape(-1, 3)
    return A, ttd.Scene(A, P)


def test_the_lock_is_released(long_switch_interval):  # noqa: F811
    _, scene = icosphere_block()
    assert released_during(lambda: scene.contacts(0.2, threads=1))
    assert released_during(lambda: scene.manifold(0.2, threads=1))


def test_concurrent_use_is_serialised():
    ms, P = scene_setup(np.float64)
    scene = ttd.Scene(ms, P)
    want = scene.contacts(0.1)
    errors = []

    def worker(k):
        try:
            for _ in range(20):
                if k == 0:
                    scene.set_poses(P)
                got = scene.contacts(0.1, threads=1)
                assert np.array_equal(got.distance, want.distance)
        except Exception as e:  # pragma: no cover - reported below
            errors.append(e)

    ts = [threading.Thread(target=worker, args=(k,)) for k in range(3)]
    for t in ts:
        t.start()
    for t in ts:
        t.join()
    assert not errors


def test_set_poses_ignores_the_rows_of_removed_ids():
    # (N, 4, 4) poses: a removed id's row is ignored whatever it holds, a bottom row that is not
    # 0 0 0 1 or NaN included, as (N, 3, 4) poses are; a present id's is still checked.
    ms, P = scene_setup(np.float64)
    scene = ttd.Scene(ms, P)
    scene.remove(2)
    scene.remove(5)
    present = {0, 1, 3, 4, 6}
    Q = P.copy()
    Q[:, :3, 3] += 0.05
    Q[2] = 0.0              # all zeros: no rotation, bottom row 0 0 0 0
    Q[5, 3] = np.nan
    scene.set_poses(Q)
    check_all(scene, World(ms, np.where(np.isin(np.arange(len(P)), [2, 5])[:, None, None], P, Q), np.float64,
                           present=present), margins=(0.1,))
    Q[3, 3, 3] = 2.0
    with pytest.raises(ValueError, match=r"poses\[3\] has bottom row \(0.0, 0.0, 0.0, 2.0\)"):
        scene.set_poses(Q)


def test_set_poses_counts_the_ids_under_the_lock():
    # set_poses compares the number of poses with id_limit while it holds the scene, so an add
    # from another thread between the caller's reading of id_limit and the call gives the
    # count's ValueError, never the library's index error. Each round: a long query holds the
    # scene; an add and then a set_poses (its poses counted before the add) wait for it; when
    # the add goes first, the set_poses sees one id more than it was given.
    A, scene = icosphere_block()
    raced, rounds = 0, 0
    while raced < 3 and rounds < 40:
        rounds += 1
        poses = np.tile(np.eye(4), (scene.id_limit, 1, 1))
        poses[:, :3, 3] = 5.0 * np.arange(scene.id_limit)[:, None]
        outcome = []

        def query():
            scene.contacts(0.2, threads=1)

        def add():
            scene.add(A, np.eye(4))

        def set_poses():
            try:
                scene.set_poses(poses)
                outcome.append(None)
            except Exception as e:  # noqa: BLE001 (the kind of error is the point)
                outcome.append(e)

        ts = [threading.Thread(target=t) for t in (query, add, set_poses)]
        for t in ts:
            t.start()
            time.sleep(0.01)
        for t in ts:
            t.join()
        e = outcome[0]
        if e is not None:
            assert isinstance(e, ValueError), repr(e)
            assert str(e) == (f"poses holds {len(poses)} poses: the scene takes one per body id, "
                              f"{len(poses) + 1} (id_limit)"), str(e)
            raced += 1
    assert raced > 0, f"in {rounds} rounds the add never went before the set_poses"


# ---- bad input ------------------------------------------------------------------------------

def test_bad_input():
    ms, P = scene_setup(np.float64)
    scene = ttd.Scene(ms, P)
    F = ttd.Mesh(*icosphere(1), precision="float32")
    with pytest.raises(ValueError, match=r"poses has shape \(7, 3, 3\)"):
        ttd.Scene(ms, P[:, :3, :3])
    with pytest.raises(ValueError, match="7 meshes and 6 poses"):
        ttd.Scene(ms, P[:6])
    with pytest.raises(TypeError, match=r"meshes\[2\] must be a ttd.Mesh, not int"):
        ttd.Scene([ms[0], ms[1], 3])
    with pytest.raises(TypeError, match=r"meshes\[1\] is a float32 mesh in a float64 scene"):
        ttd.Scene([ms[0], F])
    with pytest.raises(TypeError, match="float64 mesh in a float32 scene"):
        ttd.Scene([ms[0]], precision="float32")
    with pytest.raises(TypeError, match="a float32 mesh cannot join a float64 scene"):
        scene.add(F)
    with pytest.raises(TypeError, match="poses without meshes"):
        ttd.Scene(None, P)
    Q = P.copy()
    Q[3, :3, :3] = np.diag([1, 1, -1])
    with pytest.raises(ValueError, match=r"poses\[3\] \(body 3\) is not a rotation: det R = -1.0"):
        ttd.Scene(ms, Q)
    with pytest.raises(ValueError, match=r"poses\[3\] \(body 3\) is not a rotation: det R = -1.0"):
        scene.set_poses(Q)
    Q = P.copy()
    Q[5, 0, 1] += 1e-3
    with pytest.raises(ValueError, match=r"poses\[5\] \(body 5\) is not a rotation within 1e-6"):
        scene.set_poses(Q)
    Q = P.copy()
    Q[2, 1, 3] = np.nan
    with pytest.raises(ValueError, match=r"poses\[2\] \(body 2\) has a NaN or infinite entry"):
        scene.set_poses(Q)
    check_all(scene, World(ms, P, np.float64), margins=(0.1,))  # a refused set_poses changes nothing
    Q = P.copy()
    Q[4, 3] = [0, 0, 1, 1]
    with pytest.raises(ValueError, match=r"poses\[4\] has bottom row \(0.0, 0.0, 1.0, 1.0\)"):
        scene.set_poses(Q)
    Q = P.copy()
    Q[1, 0, 3] = 1e300
    with pytest.raises(ValueError, match=r"poses\[1\] \(body 1\) moves its mesh beyond the mesh coordinate range"):
        scene.set_poses(Q)
    with pytest.raises(ValueError, match=r"poses holds 6 poses: the scene takes one per body id, 7"):
        scene.set_poses(P[:6])
    with pytest.raises(ValueError, match=r"pose \(of body 2\) is not a rotation within 1e-6"):
        scene.set_pose(2, np.eye(4) * 1.1 + np.diag([0, 0, 0, -0.1]))
    with pytest.raises(ValueError, match=r"pose has shape \(4,\)"):
        scene.set_pose(2, np.zeros(4))
    with pytest.raises(ValueError, match=r"pose \(of the body being added, id 7\) has a NaN"):
        scene.add(ms[0], np.full((3, 4), np.nan))
    assert scene.id_limit == 7
    with pytest.raises(IndexError, match="no such body"):
        scene.set_pose(9, np.eye(4))
    with pytest.raises(IndexError, match="no such body"):
        scene.remove(7)
    with pytest.raises(IndexError, match="is not a body id"):
        scene.remove(-1)
    with pytest.raises(TypeError, match="integer body id"):
        scene.remove(1.0)
    with pytest.raises(ValueError, match="a pair is two different bodies"):
        scene.exclude(2, 2)
    with pytest.raises(IndexError, match="j = 12: no such body"):
        scene.exclude(2, 12)
    with pytest.raises(ValueError, match="group = -1 is out of range"):
        scene.set_filter(0, -1, 1)
    with pytest.raises(ValueError, match="mask = 4294967296 is out of range"):
        scene.set_filter(0, 1, 2 ** 32)
    for bad in (-1.0, math.nan, math.inf):
        with pytest.raises(ValueError, match="margin=.* is out of range"):
            scene.collide(bad)
        with pytest.raises(ValueError, match="margin=.* is out of range"):
            scene.contacts(bad)
        with pytest.raises(ValueError, match="margin=.* is out of range"):
            scene.manifold(bad)
    with pytest.raises(ValueError, match="upper_bound=-1.0 is out of range"):
        scene.distance(-1.0)
    with pytest.raises(ValueError, match="upper_bound=nan is out of range"):
        scene.distance(math.nan)
    with pytest.raises(ValueError, match="max_points=-1 is out of range"):
        scene.manifold(0.1, -1)
    with pytest.raises(TypeError, match="margin must be a real number"):
        scene.contacts(None)
    with pytest.raises(TypeError, match="margin"):
        scene.collide("0.1")
    with pytest.raises(ValueError, match="threads"):
        scene.collide(threads=-1)
    with pytest.raises(ValueError, match="isa"):
        scene.collide(isa="nonsense")
    scene.remove(3)
    with pytest.raises(IndexError, match="body 3 was removed"):
        scene.set_filter(3, 1, 1)
    with pytest.raises(IndexError, match="i = 3: body 3 was removed"):
        scene.exclude(3, 1)


@pytest.mark.parametrize("dtype", DTYPES, ids=["float64", "float32"])
def test_sparse_scene_distances_and_nearest(dtype):
    # Bodies apart: positive distances, so the closest pair, each body's nearest and the
    # manifolds are tested away from contact.
    ms, P = scene_setup(dtype, n=7, seed=11, spread=4.0)
    P[-1, 2, 3] = -6.0
    scene = ttd.Scene(ms, P)
    world = World(ms, P, dtype)
    near = scene.distance(nearest=True)
    assert near.distance > 0 and np.all(near.nearest.distance > 0)
    check_all(scene, world, margins=(0.0, 0.5, 1.5))
    assert len(scene.manifold(1.5).i) > 0


def test_stub_covers_the_scene():
    import ast
    import inspect
    import pathlib

    stub = ast.parse((pathlib.Path(ttd.__file__).parent / "_ttd.pyi").read_text())
    cls = [n for n in stub.body if isinstance(n, ast.ClassDef) and n.name == "Scene"][0]
    methods = {n.name: n for n in cls.body if isinstance(n, ast.FunctionDef)}
    for name in ("add", "remove", "set_pose", "set_poses", "set_filter", "exclude", "collide", "distance",
                 "contacts", "manifold"):
        a = methods[name].args
        stubbed = [x.arg for x in a.posonlyargs + a.args + a.kwonlyargs][1:]
        real = inspect.signature(getattr(ttd.Scene, name)).parameters
        assert stubbed == [p for p in real if p != "self"], name
        assert [x.arg for x in a.kwonlyargs] == [p for p, v in real.items() if v.kind is v.KEYWORD_ONLY], name
    init = methods["__init__"].args
    assert [x.arg for x in init.args + init.kwonlyargs][1:] == list(inspect.signature(ttd.Scene).parameters)
    for obj in (ttd.Scene, ttd.SceneCollision, ttd.SceneContacts, ttd.SceneDistance, ttd.SceneManifold,
                ttd.Scene.collide, ttd.Scene.distance, ttd.Scene.contacts, ttd.Scene.manifold):
        assert obj.__doc__ and len(obj.__doc__) > 40, obj


class _Array(__import__("ctypes").Structure):
    import ctypes as _c
    _fields_ = [("data", _c.c_void_p), ("count", _c.c_size_t), ("capacity", _c.c_size_t)]


@pytest.mark.parametrize("dtype", DTYPES, ids=["float64", "float32"])
def test_against_the_c_scene_api(libttd, dtype):
    # The same scene made through ctypes on libttd.so: every field of every query's records is
    # the C library's, and the records' dtypes match the structs' sizes.
    import ctypes

    ms, P = scene_setup(dtype, n=7, seed=5)
    scene = ttd.Scene(ms, P)
    scene.set_filter(2, 2, 2)
    scene.exclude(0, 6)
    lib = libttd.lib
    sfx = "d" if dtype == np.float64 else "f"
    real = ctypes.c_double if dtype == np.float64 else ctypes.c_float
    cmeshes = [libttd.mesh(m.vertices, m.faces)[1] for m in ms]
    handle = ctypes.c_void_p()
    assert getattr(lib, "ttd_scene_create_" + sfx)(ctypes.byref(handle)) == 0
    try:
        poses = np.ascontiguousarray(P[:, :3, :].astype(dtype))
        for k, cm in enumerate(cmeshes):
            bid = ctypes.c_uint32()
            assert getattr(lib, "ttd_scene_add_" + sfx)(handle, cm.handle, poses[k].ctypes.data_as(ctypes.POINTER(real)),
                                                        ctypes.byref(bid)) == 0 and bid.value == k
        assert lib.ttd_scene_set_filter(handle, 2, 2, 2) == 0 and lib.ttd_scene_exclude_pair(handle, 0, 6, 1) == 0
        lib.ttd_scene_array_free.argtypes = [ctypes.POINTER(_Array)]
        opt = ctypes.byref(libttd.options())
        f = "FLOAT64" if dtype == np.float64 else "FLOAT32"

        def array_query(name, records, *args):
            arr = _Array()
            fn = getattr(lib, f"ttd_scene_{name}_{sfx}")
            assert fn(opt, handle, *[real(a) if isinstance(a, float) else a for a in args], ctypes.byref(arr)) == 0
            try:
                raw = ctypes.string_at(arr.data, arr.count * records.itemsize) if arr.count else b""
                return np.frombuffer(raw, dtype=records)
            finally:
                lib.ttd_scene_array_free(ctypes.byref(arr))

        pairs = [(array_query("collide", ttd.SCENE_HIT_DTYPE, 0.1), scene.collide(0.1)),
                 (array_query("contacts", getattr(ttd, "SCENE_CONTACT_DTYPE_" + f), 0.2), scene.contacts(0.2)),
                 (array_query("manifold", getattr(ttd, "SCENE_POINT_DTYPE_" + f), 0.2, ctypes.c_size_t(3)),
                  scene.manifold(0.2, 3))]
        for want, got in pairs:
            assert len(want) == len(got[0]) > 0
            for name in want.dtype.names:
                np.testing.assert_array_equal(getattr(got, name), want[name])
        rec = getattr(ttd, "SCENE_CONTACT_DTYPE_" + f)
        closest = np.zeros((), rec)
        nearest = np.zeros(7, rec)
        fn = getattr(lib, "ttd_scene_distance_" + sfx)
        assert fn(opt, handle, real(np.inf), ctypes.c_void_p(closest.ctypes.data), ctypes.c_void_p(nearest.ctypes.data)) == 0
        d = scene.distance(nearest=True)
        for name in rec.names:
            np.testing.assert_array_equal(getattr(d, name), closest[name])
            np.testing.assert_array_equal(getattr(d.nearest, name), nearest[name])
    finally:
        lib.ttd_scene_destroy.argtypes = [ctypes.c_void_p]
        lib.ttd_scene_destroy(handle)


@pytest.mark.parametrize("dtype", DTYPES, ids=["float64", "float32"])
def test_manifold_keys(dtype):
    """Manifold keys (docs/scenes.md, section 5c): uint64, one per point; a stack of three turned
    cubes on a floor moved as a whole by 1e-9 (float: 1e-6) keeps every body pair's keys; a box
    on a box keeps distinct keys for its four corners."""
    unit = ttd.Mesh(*cube(), precision=dtype)
    v, f = cube()
    floor = ttd.Mesh(np.array([8.0, 8.0, 1.0]) * v - np.array([4.0, 4.0, 1.0]), f, precision=dtype)
    poses = [np.eye(4)]
    z = 0.0
    for k in range(3):
        a = 0.3 * k + 0.1
        P = np.eye(4)
        P[:2, :2] = [[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]]
        P[:3, 3] = [0.05 * k, -0.04 * k, z + 1e-3]
        z += 1 + 1e-3
        poses.append(P)
    poses = np.array(poses)
    scene = ttd.Scene([floor, unit, unit, unit], poses)
    m = scene.manifold(0.01, 4)
    assert m.key.dtype == np.uint64 and len(m.key) == 12
    for i in range(3):  # a turned cube's four corners on the face below: four keys
        assert len(set(m.key[m.j == i + 1].tolist())) == 4
    moved = poses.copy()
    moved[:, :3, 3] += 1e-9 if dtype == np.float64 else 1e-6
    m2 = ttd.Scene([floor, unit, unit, unit], moved).manifold(0.01, 4)
    assert sorted(zip(m.i.tolist(), m.j.tolist(), m.key.tolist())) == \
        sorted(zip(m2.i.tolist(), m2.j.tolist(), m2.key.tolist()))
