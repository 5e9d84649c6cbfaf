# SPDX-License-Identifier: MIT
"""Deforming meshes from Python: Mesh.set_vertices, and the queries on a moved mesh against the
brute force of the moved vertices (ttd.distance over every pair, tests/meshes.py)."""
import threading
import time

import numpy as np
import pytest

import ttd
from meshes import MESHES, brute_force, random_poses


def bent(v, t):
    """v bent round the z axis by angle proportional to x (strength t)."""
    a = t * (v[:, 0] - v[:, 0].min())
    r = v[:, 1] + 2.0
    return np.stack([r * np.sin(a), r * np.cos(a) - 2.0, v[:, 2] + 0.1 * np.sin(3 * v[:, 0])], 1)


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
@pytest.mark.parametrize("name", ["icosphere", "torus", "grid", "slivers"])
def test_moved_mesh_queries_equal_brute_force(name, dtype):
    v, f = MESHES[name]
    A = ttd.Mesh(v.astype(dtype), f)
    B = ttd.Mesh(v.astype(dtype), f)
    assert A.generation == 0 and A.rebuilds == 0
    for step, t in enumerate((0.3, 0.9, 1.6)):
        w = bent(v, t).astype(dtype)
        A.set_vertices(w)
        assert A.generation == step + 1
        np.testing.assert_array_equal(A.vertices, w)
        assert not A.vertices.flags.writeable
        for pose in random_poses(3, seed=step, spread=0.8):
            allp = brute_force(A, B, pose)
            d = allp.distance
            r = ttd.mesh_distance(A, B, pose)
            assert r.distance == d.min()
            margin = dtype(d.min() + 0.1 * (d.max() - d.min()))
            c = ttd.mesh_contacts(A, B, pose, margin)
            want = set(zip(*np.nonzero(d <= margin)))
            assert set(zip(c.tri_a.tolist(), c.tri_b.tolist())) == want
            np.testing.assert_array_equal(c.distance, d[c.tri_a, c.tri_b])


def test_set_vertices_refuses_bad_input_and_keeps_the_mesh():
    v, f = MESHES["icosphere"]
    A = ttd.Mesh(v, f)
    pose = np.eye(4)
    pose[0, 3] = 2.5
    before = ttd.mesh_distance(A, A, pose)
    with pytest.raises(ValueError, match="rows"):
        A.set_vertices(np.vstack([v, v[:1]]))
    with pytest.raises(ValueError, match="shape"):
        A.set_vertices(v[:, :2])
    bad = v.copy()
    bad[3, 1] = np.nan
    with pytest.raises(ValueError, match=r"vertices\[3\]"):
        A.set_vertices(bad)
    bad[3, 1] = 1e300
    with pytest.raises(ValueError, match="range"):
        A.set_vertices(bad)
    with pytest.raises(ValueError):
        A.set_vertices(v, threads=-1)
    assert A.generation == 0
    after = ttd.mesh_distance(A, A, pose)
    assert after.distance == before.distance and after.tri_a == before.tri_a


def test_float32_mesh_takes_float64_input_converted():
    v, f = MESHES["torus"]
    A = ttd.Mesh(v.astype(np.float32), f)
    A.set_vertices(bent(v, 0.5))  # float64 in: converted to the mesh's float32
    assert A.vertices.dtype == np.float32
    np.testing.assert_array_equal(A.vertices, bent(v, 0.5).astype(np.float32))


def test_set_vertices_and_queries_from_threads_never_overlap():
    """A query running in another thread makes set_vertices raise (and the other way round);
    whichever wins, nothing crashes, and the mesh answers as a fresh one afterwards."""
    v, f = MESHES["torus"]
    big_v = np.concatenate([v + [3.0 * k, 0, 0] for k in range(40)])
    big_f = np.concatenate([f + len(v) * k for k in range(40)])
    A = ttd.Mesh(big_v, big_f)
    poses = random_poses(200, seed=4, spread=2.0)
    stop = threading.Event()
    moved = [0, 0]  # done, refused

    def mover():
        while not stop.is_set():
            try:
                A.set_vertices(big_v, threads=1)
                moved[0] += 1
            except RuntimeError as e:
                assert "in use" in str(e)
                moved[1] += 1
            time.sleep(0.0005)

    th = threading.Thread(target=mover)
    th.start()
    queried = [0, 0]  # done, refused
    try:
        end = time.monotonic() + 0.5
        while time.monotonic() < end or moved[0] == 0:
            try:
                ttd.mesh_distance(A, A, poses, threads=1)
                queried[0] += 1
            except RuntimeError as e:
                assert "set_vertices" in str(e)
                queried[1] += 1
    finally:
        stop.set()
        th.join()
    assert moved[0] > 0
    fresh = ttd.Mesh(big_v, big_f)
    np.testing.assert_array_equal(ttd.mesh_distance(A, A, poses).distance, ttd.mesh_distance(fresh, fresh, poses).distance)


def test_point_queries_and_set_vertices_never_overlap():
    """Point queries wait for nothing and refuse a concurrent Mesh.set_vertices as the mesh queries
    do (RuntimeError either way round): every answer a point query returns is the answer for one
    of the two vertex sets, never a mix, and no crash (the moves alternate between the mesh and its
    vertices shuffled, which rebuilds the hierarchy)."""
    v, f = MESHES["torus"]
    big_v = np.concatenate([v + [3.0 * k, 0, 0] for k in range(30)])
    big_f = np.concatenate([f + len(v) * k for k in range(30)])
    shuffled = big_v[np.random.default_rng(1).permutation(len(big_v))]
    rng = np.random.default_rng(2)
    P = np.column_stack([rng.uniform(-1.5, 90, 4000), rng.uniform(-1.5, 1.5, 4000), rng.uniform(-0.6, 0.6, 4000)])
    queries = {
        "closest": lambda m: ttd.closest_points(m, P, threads=1).distance,
        "signed": lambda m: ttd.signed_distance(m, P, threads=1).distance,
        "winding": lambda m: ttd.winding_number(m, P, threads=1).winding,
        "contains": lambda m: ttd.contains(m, P, threads=1).inside,
        "grid": lambda m: ttd.sdf_grid(m, [-1.5, -1.5, -0.6], 0.5, [8, 7, 4], threads=1),
    }
    want = {k: (q(ttd.Mesh(big_v, big_f)), q(ttd.Mesh(shuffled, big_f))) for k, q in queries.items()}
    A = ttd.Mesh(big_v, big_f)
    stop = threading.Event()
    moved = [0, 0]  # done, refused

    def mover():
        k = 0
        while not stop.is_set():
            try:
                A.set_vertices(shuffled if k % 2 == 0 else big_v, threads=1)
                moved[0] += 1
                k += 1
            except RuntimeError as e:
                assert "in use" in str(e)
                moved[1] += 1
            time.sleep(0.0002)

    th = threading.Thread(target=mover)
    th.start()
    answered = refused = 0
    try:
        end = time.monotonic() + 1.5
        # at least 4 updates, but never past a hard limit (ThreadSanitizer runs this slowly)
        while (time.monotonic() < end or moved[0] < 4) and time.monotonic() < end + 120:
            for name, q in queries.items():
                try:
                    got = q(A)
                except RuntimeError as e:
                    assert "set_vertices" in str(e)
                    refused += 1
                    continue
                answered += 1
                assert any(np.array_equal(got, w) for w in want[name]), f"{name}: an answer of neither vertex set"
    finally:
        stop.set()
        th.join()
    assert moved[0] >= 4 and answered > 0


def self_brute_force(m, shared_vertex):
    """Every counting pair (i < j) of mesh m by the header's rules, with its ttd.distance result:
    no shared vertex (by index): (T_i, T_j); exactly one, v, and each triangle another vertex
    (shared_vertex): the nearer of (E_i, T_j) and (T_i, E_j), E the vertices other than v in their
    order, the last repeated. Returns the pairs (n, 2) and their distances, p and q; vectorised."""
    V, F = m.vertices, m.faces.astype(np.int64)
    I, J = np.triu_indices(len(F), 1)
    A, B = F[I], F[J]  # (n, 3)
    first = np.ones((len(F), 3), bool)  # an index's first occurrence in its triangle
    first[:, 1] = F[:, 1] != F[:, 0]
    first[:, 2] = (F[:, 2] != F[:, 0]) & (F[:, 2] != F[:, 1])
    hit = (A[:, :, None] == B[:, None, :]).any(2) & first[I]  # distinct indices of A found in B
    shared = hit.sum(1)
    plain = shared == 0
    S, T, key, kind = [V[A[plain]]], [V[B[plain]]], [np.stack([I[plain], J[plain]], 1)], [np.ones(plain.sum(), int)]
    if shared_vertex:
        one = np.nonzero(shared == 1)[0]
        v = A[one, np.argmax(hit[one], 1)]
        def edge(T):  # vertices other than v, in order, the last repeated; None where none is left
            keep = T != v[:, None]
            out = np.empty_like(T)
            ok = keep.any(1)
            for r in np.nonzero(ok)[0]:
                e = T[r][keep[r]].tolist()
                out[r] = (e + [e[-1]] * 2)[:3]
            return out, ok
        EA, oka = edge(A[one])
        EB, okb = edge(B[one])
        ok = oka & okb
        one, EA, EB = one[ok], EA[ok], EB[ok]
        # the two entries of a pair side by side: (E_i, T_j), (T_i, E_j)
        S.append(np.stack([V[EA], V[A[one]]], 1).reshape(-1, 3, 3))
        T.append(np.stack([V[B[one]], V[EB]], 1).reshape(-1, 3, 3))
        key.append(np.stack([I[one], J[one]], 1))
        kind.append(np.full(len(one), 2))
    S, T, key, kind = np.concatenate(S), np.concatenate(T), np.concatenate(key), np.concatenate(kind)
    return key, *_reduce(S, T, kind)


def _reduce(S, T, kind):
    """ttd.distance on the entries, and per pair (kind[k] entries each) the nearer, the first on
    ties: distance, p, q (q = p at distance 0)."""
    if len(S) == 0:
        return np.zeros(0), np.zeros((0, 3)), np.zeros((0, 3))
    r = ttd.distance(S, T, points=True)
    at = np.concatenate([[0], np.cumsum(kind)[:-1]])
    second = np.minimum(at + 1, len(S) - 1)
    best = np.where((kind == 2) & (r.distance[second] < r.distance[at]), second, at)
    d = r.distance[best]
    return d, r.p[best], np.where((d == 0)[:, None], r.p[best], r.q[best])


def self_brute_dict(m, shared_vertex):
    """self_brute_force as {(i, j): (d, p, q)}."""
    key, d, p, q = self_brute_force(m, shared_vertex)
    return {(int(i), int(j)): (d[k], p[k], q[k]) for k, (i, j) in enumerate(key)}


def folded(n=6, gap=0.05):
    """A sheet folded into two layers gap apart over a round fold (its own small generator)."""
    u, w = np.meshgrid(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1))
    s = u.ravel() * (1 + np.pi * gap / 2)
    half = 0.5
    x = np.where(s < half, s, np.where(s < half + np.pi * gap / 2, half + gap / 2 * np.sin((s - half) / (gap / 2)),
                                       half - (s - half - np.pi * gap / 2)))
    z = np.where(s < half, 0.0, np.where(s < half + np.pi * gap / 2, gap / 2 - gap / 2 * np.cos((s - half) / (gap / 2)),
                                         gap))
    V = np.stack([x, w.ravel(), z], 1)
    F = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            F += [[a, a + 1, a + n + 2], [a, a + n + 2, a + n + 1]]
    return V, np.array(F)


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
@pytest.mark.parametrize("shared_vertex", [False, True])
@pytest.mark.parametrize("name", ["folded", "grid", "torus", "slivers"])
def test_self_contacts_equal_brute_force(name, shared_vertex, dtype):
    v, f = folded() if name == "folded" else MESHES[name]
    m = ttd.Mesh(v.astype(dtype), f)
    want = self_brute_dict(m, shared_vertex)
    d = np.array([x[0] for x in want.values()])
    for margin in (0.0, float(np.sort(d)[len(d) // 50]), float(np.sort(d)[len(d) // 10])):
        margin = dtype(margin)
        r = ttd.mesh_self_contacts(m, margin, shared_vertex=shared_vertex)
        assert type(r).__name__ == "SelfContacts" and r.distance.dtype == dtype
        assert np.all(r.tri_i < r.tri_j)
        got = {(int(i), int(j)): k for k, (i, j) in enumerate(zip(r.tri_i, r.tri_j))}
        assert set(got) == {ij for ij, x in want.items() if x[0] <= margin}
        for ij, k in got.items():
            assert r.distance[k] == want[ij][0]
            np.testing.assert_array_equal(r.p[k], want[ij][1])
            np.testing.assert_array_equal(r.q[k], want[ij][2])
        c = ttd.mesh_self_collide(m, margin, shared_vertex=shared_vertex)
        assert c.hit == (len(got) > 0)
        if c.hit:
            assert c.tri_i < c.tri_j and (c.tri_i, c.tri_j) in got
        else:
            assert c.tri_i == ttd.NO_TRIANGLE == c.tri_j


def test_self_queries_threads_isas_and_errors():
    v, f = folded(12, 0.02)
    m = ttd.Mesh(v, f)
    ref = ttd.mesh_self_contacts(m, 0.03, shared_vertex=True, isa="scalar", threads=1)
    assert len(ref.tri_i) > 100
    for isa in ttd.ISAS:
        if not ttd.isa_available(isa):
            continue
        for threads in (1, 2):
            r = ttd.mesh_self_contacts(m, 0.03, shared_vertex=True, isa=isa, threads=threads)
            for a, b in zip(r, ref):
                np.testing.assert_array_equal(a, b)
    assert ttd.mesh_self_collide(m).hit is False
    with pytest.raises(ValueError, match="margin"):
        ttd.mesh_self_contacts(m, -1.0)
    with pytest.raises(ValueError, match="margin"):
        ttd.mesh_self_contacts(m, float("nan"))
    with pytest.raises(TypeError, match="ttd.Mesh"):
        ttd.mesh_self_contacts(v, 0.1)
    with pytest.raises(TypeError):
        ttd.mesh_self_contacts(m, None)
    with pytest.raises(TypeError):
        ttd.mesh_self_contacts(m, 0.1, True)  # shared_vertex is keyword-only
    # a moved mesh: the self-contacts of its new vertices
    m.set_vertices(v * [1, 1, 0.5])
    assert {(int(i), int(j)) for i, j in zip(*ttd.mesh_self_contacts(m, 0.011)[:2])} == {
        ij for ij, x in self_brute_dict(m, False).items() if x[0] <= 0.011
    }


def test_scene_sees_moved_meshes():
    """A Scene's bodies move with their meshes: after set_vertices the scene's contacts are those of
    the moved vertices at the bodies' poses (ttd.mesh_contacts with world poses), ids kept; a mesh
    shared by two bodies moves for both."""
    v, f = MESHES["grid"]
    tv, tf = MESHES["torus"]
    G, T = ttd.Mesh(v, f), ttd.Mesh(tv, tf)
    poses = np.stack([np.eye(4)] * 3)
    poses[1, :3, 3] = [1.4, 0, 0]
    poses[2, :3, 3] = [0.3, 0.4, 0.2]
    scene = ttd.Scene([G, G, T], poses)
    for step, t in enumerate((0.0, 0.6, 1.3)):
        G.set_vertices(bent(v, t) * (1 + step))
        got = scene.contacts(0.05)
        assert scene.id_limit == 3
        for i, j in ((0, 1), (0, 2), (1, 2)):
            A, B = (G, T) if j == 2 else (G, G)
            want = ttd.mesh_contacts(A, B, None, 0.05, pose_a=poses[i], pose_b=poses[j])
            mine = (got.i == i) & (got.j == j)
            assert set(zip(got.tri_i[mine].tolist(), got.tri_j[mine].tolist())) == set(
                zip(want.tri_a.tolist(), want.tri_b.tolist())
            )
