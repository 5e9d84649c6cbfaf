# SPDX-License-Identifier: MIT
"""ttd.Mesh and the mesh queries.

Values: against the brute force of meshes.py (ttd.distance over every triangle pair, b moved
as the header documents), bit for bit: the minimum, its pair and points; the contact set pair
for pair; the per-triangle closest partners; collision. Against the C library called through
ctypes on libttd.so (c_reference.CMesh): every field of every query, bit for bit, in both
precisions, on several instruction sets and thread counts. Then the API: shapes, dtypes, pose
layouts and conversions, empty input, out=, the Mesh object (copies, attributes, pickling), and
every error path with its message.
"""
import math
import pickle

import numpy as np
import pytest

import c_reference
from c_reference import ctiming_module
import ttd
from meshes import MESHES, brute_force, cube, icosphere, mesh_pair, random_poses

DTYPES = [np.float64, np.float32]
# The result types' fields, in the documented order (the C structs' order).
DISTANCE_FIELDS = ("distance", "p", "q", "tri_a", "tri_b", "feature_a", "feature_b", "flags", "node_tests",
                   "pair_tests")
CONTACT_FIELDS = ("pose", "tri_a", "tri_b", "distance", "p", "q", "pose_start")
PARTNER_FIELDS = ("partner", "distance", "p", "q")


def _cases():
    c = []
    names = list(MESHES)
    for i, na in enumerate(names):
        for j, (nb, spread) in enumerate(((names[(i + 2) % len(names)], 1.5), (na, 0.4))):
            pose = random_poses(1, seed=100 + 2 * i + j, spread=spread)[0]
            c.append((f"{na}-{nb}-{spread}", MESHES[na], MESHES[nb], pose))
    box = cube()
    on_top = np.eye(4)
    on_top[2, 3] = 1
    c.append(("cube-on-cube", box, box, on_top))
    edge = np.eye(4)
    edge[0, 3] = edge[1, 3] = 1
    c.append(("cube-edge-to-edge", box, box, edge))
    c.append(("identical-torus", MESHES["torus"], MESHES["torus"], np.eye(4)))
    v2, f2 = icosphere(2)
    c.append(("nested", (4 * v2, f2), MESHES["icosphere"], np.eye(4)))
    far = np.eye(4)
    far[:3, :3] = random_poses(1, seed=7)[0, :3, :3]
    far[0, 3], far[1, 3] = 1e6, -3e5
    c.append(("far-1e6", MESHES["icosphere"], MESHES["torus"], far))
    shift = np.array([2e5, -1e5, 7e5])
    R = random_poses(1, seed=8)[0, :3, :3]
    off = np.eye(4)
    off[:3, :3] = R
    off[:3, 3] = shift - R @ shift + [2.5, 0, 0]
    (vi, fi), (vt, ft) = MESHES["icosphere"], MESHES["torus"]
    c.append(("offset-1e5", (vi + shift, fi), (vt + shift, ft), off))
    return c


CASES = _cases()


def meshes_of(case, dtype):
    _, (va, fa), (vb, fb), pose = case
    return ttd.Mesh(va.astype(dtype), fa), ttd.Mesh(vb.astype(dtype), fb), pose


def size_of(A, B):
    return float(max(np.linalg.norm(np.ptp(m.vertices.astype(float), axis=0)) for m in (A, B)))


# ---- values against the brute force ---------------------------------------------------------

@pytest.mark.parametrize("dtype", DTYPES, ids=["float64", "float32"])
@pytest.mark.parametrize("case", CASES, ids=[c[0] for c in CASES])
def test_distance_equals_brute_force(case, dtype):
    A, B, pose = meshes_of(case, dtype)
    allp = brute_force(A, B, pose)
    best = allp.distance.min()
    r = ttd.mesh_distance(A, B, pose)
    assert r.distance.dtype == dtype and r.p.dtype == dtype
    assert r.distance == best, (r.distance, best)
    i, j = int(r.tri_a), int(r.tri_b)
    assert allp.distance[i, j] == best
    np.testing.assert_array_equal(r.p, allp.p[i, j])
    np.testing.assert_array_equal(r.q, allp.p[i, j] if best == 0 else allp.q[i, j])
    assert (r.feature_a, r.feature_b) == (allp.feature_p[i, j], allp.feature_q[i, j])
    assert r.flags == (ttd.MeshFlag.INTERSECTING if best == 0 else 0)
    # An upper bound just above the minimum changes nothing; just below, it is exceeded.
    u = ttd.mesh_distance(A, B, pose, upper_bound=np.nextafter(best, np.inf, dtype=dtype))
    assert u.distance == best and (u.tri_a, u.tri_b) == (r.tri_a, r.tri_b)
    if best > 0:
        u = ttd.mesh_distance(A, B, pose, upper_bound=np.nextafter(best, 0, dtype=dtype))
        assert u.flags == ttd.MeshFlag.ABOVE_BOUND and math.isinf(u.distance)
        assert u.tri_a == ttd.NO_TRIANGLE == u.tri_b
    # rel_tol: a pair within the promised factor, which the brute force confirms.
    u = ttd.mesh_distance(A, B, pose, rel_tol=0.25)
    assert best <= u.distance <= 1.25 * best + 1e-6 * size_of(A, B)
    assert allp.distance[u.tri_a, u.tri_b] == u.distance


def _sorted_pairs(tri_a, tri_b):
    order = np.lexsort((tri_b, tri_a))
    return order, np.stack([tri_a[order], tri_b[order]], 1)


@pytest.mark.parametrize("dtype", DTYPES, ids=["float64", "float32"])
@pytest.mark.parametrize("case", CASES, ids=[c[0] for c in CASES])
def test_contacts_closest_collide_equal_brute_force(case, dtype):
    A, B, pose = meshes_of(case, dtype)
    allp = brute_force(A, B, pose)
    d = allp.distance
    best = d.min()
    size = size_of(A, B)
    for margin in (0.0, float(best), float(best) + 0.05 * size, float(best) + 0.3 * size):
        m = dtype(margin)  # what the library compares with
        c = ttd.mesh_contacts(A, B, pose, margin)
        want_i, want_j = np.nonzero(d <= m)
        order, got = _sorted_pairs(c.tri_a, c.tri_b)
        np.testing.assert_array_equal(got, np.stack([want_i, want_j], 1))  # np.nonzero is row-major: sorted
        np.testing.assert_array_equal(c.distance[order], d[want_i, want_j])
        np.testing.assert_array_equal(c.p[order], allp.p[want_i, want_j])
        q = np.where((d[want_i, want_j] == 0)[:, None], allp.p[want_i, want_j], allp.q[want_i, want_j])
        np.testing.assert_array_equal(c.q[order], q)
        assert c.distance.dtype == dtype and c.tri_a.dtype == np.uint32
        np.testing.assert_array_equal(c.pose, np.zeros(len(want_i)))
        np.testing.assert_array_equal(c.pose_start, [0, len(want_i)])

        col = ttd.mesh_collide(A, B, pose, margin)
        assert col.hit == (best <= m)
        if col.hit:
            assert d[col.tri_a, col.tri_b] <= m
        else:
            assert col.tri_a == ttd.NO_TRIANGLE == col.tri_b

        cl = ttd.mesh_closest(A, B, pose, margin)
        for side, dd, mine, theirs in ((cl.for_a, d, allp.p, allp.q), (cl.for_b, d.T, allp.q, allp.p)):
            within = dd <= m
            partner = np.where(within.any(1), np.argmin(np.where(within, dd, np.inf), 1), ttd.NO_TRIANGLE)
            np.testing.assert_array_equal(side.partner, partner)  # argmin takes the first: the smaller index
            has = partner != ttd.NO_TRIANGLE
            rows = np.nonzero(has)[0]
            cols = partner[has].astype(np.intp)
            np.testing.assert_array_equal(side.distance[has], dd[rows, cols])
            assert np.all(np.isinf(side.distance[~has])) and np.all(np.isnan(side.p[~has]))
            if side is cl.for_a:
                p_want, q_want = mine[rows, cols], theirs[rows, cols]
            else:
                p_want, q_want = mine.transpose(1, 0, 2)[rows, cols], theirs.transpose(1, 0, 2)[rows, cols]
            zero = (dd[rows, cols] == 0)[:, None]
            # at distance 0 the contact's q is its p (the point on a): the same point for both
            p_on_a = q_want if side is cl.for_b else p_want
            np.testing.assert_array_equal(side.p[has], np.where(zero, p_on_a, p_want))
            np.testing.assert_array_equal(side.q[has], np.where(zero, p_on_a, q_want))


@pytest.mark.parametrize("dtype", DTYPES, ids=["float64", "float32"])
def test_many_poses_equal_single_poses_and_brute_force(dtype):
    A, B = mesh_pair("icosphere", "torus", dtype)
    P = random_poses(25, seed=31, spread=1.2)
    r = ttd.mesh_distance(A, B, P)
    c = ttd.mesh_contacts(A, B, P, 0.1)
    col = ttd.mesh_collide(A, B, P, 0.05)
    cl = ttd.mesh_closest(A, B, P, 0.1)
    assert r.distance.shape == (25,) and r.p.shape == (25, 3) and cl.for_a.partner.shape == (25, A.triangle_count)
    assert len(c.pose_start) == 26 and np.all(np.diff(c.pose) >= 0)
    for k in range(25):
        one = ttd.mesh_distance(A, B, P[k])
        for field in DISTANCE_FIELDS:
            np.testing.assert_array_equal(getattr(r, field)[k], getattr(one, field), err_msg=field)
        assert r.distance[k] == brute_force(A, B, P[k]).distance.min()
        s = slice(c.pose_start[k], c.pose_start[k + 1])
        assert np.all(c.pose[s] == k)
        ck = ttd.mesh_contacts(A, B, P[k], 0.1)
        for field in ("tri_a", "tri_b", "distance", "p", "q"):
            np.testing.assert_array_equal(getattr(c, field)[s], getattr(ck, field), err_msg=field)
        assert col.hit[k] == ttd.mesh_collide(A, B, P[k], 0.05).hit == (r.distance[k] <= dtype(0.05))
        np.testing.assert_array_equal(cl.for_b.partner[k], ttd.mesh_closest(A, B, P[k], 0.1).for_b.partner)


# ---- values against the C library (ctypes) --------------------------------------------------

def _assert_records(ours, theirs, fields):
    for f in fields:
        np.testing.assert_array_equal(np.asarray(getattr(ours, f)), theirs[f], err_msg=f)
        assert np.asarray(getattr(ours, f)).dtype == theirs[f].dtype, f


@pytest.mark.parametrize("dtype", DTYPES, ids=["float64", "float32"])
def test_every_query_equals_the_c_library(libttd, dtype):
    (va, fa), (vb, fb) = MESHES["torus"], MESHES["icosphere"]
    va, vb = va.astype(dtype), vb.astype(dtype)
    A, B = ttd.Mesh(va, fa), ttd.Mesh(vb, fb)
    st, CA = libttd.mesh(va, fa)
    assert st == 0
    st, CB = libttd.mesh(vb, fb)
    assert st == 0
    assert CA.counts() == (A.vertex_count, A.triangle_count, A.node_count)
    P = random_poses(40, seed=32, spread=1.3)
    isas = [i for i in ttd.ISAS if i != "auto" and ttd.isa_available(i)]
    for isa, threads in [("auto", 0)] + [(i, t) for i in isas for t in (1, 2)]:
        kw = dict(isa=ttd.ISAS.index(isa), threads=threads)
        st, want = CA.distance(CB, P, np.inf, 0.0, **kw)
        assert st == 0
        _assert_records(ttd.mesh_distance(A, B, P, isa=isa, threads=threads), want, DISTANCE_FIELDS)
        st, want = CA.distance(CB, P, 0.2, 0.1, **kw)
        _assert_records(ttd.mesh_distance(A, B, P, upper_bound=0.2, rel_tol=0.1, isa=isa, threads=threads), want,
                        DISTANCE_FIELDS)
        st, want = CA.collide(CB, P, 0.02, **kw)
        assert st == 0
        got = ttd.mesh_collide(A, B, P, 0.02, isa=isa, threads=threads)
        np.testing.assert_array_equal(got.hit, want["hit"] != 0)
        _assert_records(got, want, ("tri_a", "tri_b", "node_tests", "pair_tests"))
        st, want, starts = CA.contacts(CB, P, 0.08, **kw)
        assert st == 0
        got = ttd.mesh_contacts(A, B, P, 0.08, isa=isa, threads=threads)
        _assert_records(got, want, ("tri_a", "tri_b", "distance", "p", "q"))
        np.testing.assert_array_equal(got.pose_start, starts)
        st, wa, wb = CA.closest(CB, P, 0.08, **kw)
        assert st == 0
        got = ttd.mesh_closest(A, B, P, 0.08, isa=isa, threads=threads)
        _assert_records(got.for_a, wa, PARTNER_FIELDS)
        _assert_records(got.for_b, wb, PARTNER_FIELDS)


def test_result_types():
    A, B = mesh_pair("cube", "cube")
    for result, fields in ((ttd.mesh_distance(A, B, np.eye(4)), DISTANCE_FIELDS),
                           (ttd.mesh_contacts(A, B, np.eye(4), 0.1), CONTACT_FIELDS),
                           (ttd.mesh_closest(A, B, np.eye(4), 0.1).for_a, PARTNER_FIELDS),
                           (ttd.mesh_collide(A, B, np.eye(4)), ("hit", "tri_a", "tri_b", "node_tests", "pair_tests"))):
        assert tuple(type(result).__doc__ is not None and f for f in fields) == fields
        assert len(result) == len(fields) and type(result)._fields == fields
        for i, f in enumerate(fields):
            assert result[i] is getattr(result, f)


def test_record_layouts_match_ctypes():
    for dtype, (MeshResult, Contact, _, Closest) in c_reference.MESH_STRUCTS.items():
        f64 = dtype == np.float64
        for ours, struct in ((ttd.MESH_RESULT_DTYPE_FLOAT64 if f64 else ttd.MESH_RESULT_DTYPE_FLOAT32, MeshResult),
                             (ttd.CONTACT_DTYPE_FLOAT64 if f64 else ttd.CONTACT_DTYPE_FLOAT32, Contact),
                             (ttd.CLOSEST_DTYPE_FLOAT64 if f64 else ttd.CLOSEST_DTYPE_FLOAT32, Closest),
                             (ttd.COLLISION_DTYPE, c_reference.Collision)):
            theirs = c_reference.records(struct, (struct * 1)(), 0).dtype
            assert ours == theirs, (ours, theirs)
            assert ours.itemsize == c_reference.ctypes.sizeof(struct)


def test_c_library_statuses_match_the_exceptions(libttd):
    # The conditions the extension reports are the ones the library refuses.
    (v, f) = MESHES["cube"]
    st, C = libttd.mesh(v, f)
    A = ttd.Mesh(v, f)
    bad = np.eye(4)
    bad[0, 0] = 1 + 2e-6
    assert C.distance(C, bad)[0] == 24  # TTD_ERR_BAD_POSE
    with pytest.raises(ValueError, match="not a rotation within 1e-6"):
        ttd.mesh_distance(A, A, bad)
    ok = np.eye(4)
    ok[0, 0] = 1 + 4e-7
    assert C.distance(C, ok)[0] == 0
    ttd.mesh_distance(A, A, ok)
    assert C.contacts(C, np.eye(4), -1.0)[0] == 18  # TTD_ERR_BAD_OPTIONS
    assert libttd.mesh(v, f + 1)[0] == 20  # TTD_ERR_INDEX_OUT_OF_RANGE
    v2 = v.copy()
    v2[3, 1] = np.nan
    assert libttd.mesh(v2, f)[0] == 23  # TTD_ERR_NONFINITE_MESH


# ---- the Mesh object ------------------------------------------------------------------------

def test_mesh_attributes_and_copies():
    v, f = MESHES["torus"]
    v = v.copy()
    A = ttd.Mesh(v, f)
    assert A.vertex_count == len(v) and A.triangle_count == len(f) and A.node_count >= 1
    assert A.dtype == np.float64 and A.vertices.dtype == np.float64 and A.faces.dtype == np.uint32
    np.testing.assert_array_equal(A.vertices, v)
    np.testing.assert_array_equal(A.faces, f)
    assert not A.vertices.flags.writeable and not A.faces.flags.writeable
    assert not np.shares_memory(A.vertices, v)
    before = ttd.mesh_distance(A, A, random_poses(3, seed=1))
    v += 5  # the mesh kept its own copy
    after = ttd.mesh_distance(A, A, random_poses(3, seed=1))
    np.testing.assert_array_equal(before.distance, after.distance)
    with pytest.raises(AttributeError):
        A.vertices = v
    with pytest.raises(ValueError):
        A.vertices[0, 0] = 1
    assert "252 triangles" in repr(A) and "float64" in repr(A)


def test_mesh_dtypes_and_precision():
    v, f = MESHES["icosphere"]
    A32 = ttd.Mesh(v.astype(np.float32), f)
    assert A32.dtype == np.float32 and A32.vertices.dtype == np.float32
    r = ttd.mesh_distance(A32, A32, random_poses(4, seed=2))
    assert all(getattr(r, x).dtype == np.float32 for x in ("distance", "p", "q"))
    assert ttd.Mesh(v, f, precision="float32").dtype == np.float32
    assert ttd.Mesh(v.astype(np.float32), f, precision=np.float64).dtype == np.float64
    assert ttd.Mesh(np.round(v * 10).astype(np.int16), f).dtype == np.float64  # integers count as float64
    # Any integer dtype of faces, the same mesh.
    ref = ttd.mesh_distance(ttd.Mesh(v, f), A32 and ttd.Mesh(v, f), random_poses(5, seed=3)).distance
    for fd in (np.int8, np.uint8, np.int16, np.uint16, np.int32, np.uint32, np.int64, np.uint64):
        if np.iinfo(fd).max < f.max():
            continue
        B = ttd.Mesh(v, f.astype(fd))
        np.testing.assert_array_equal(B.faces, f)
        np.testing.assert_array_equal(ttd.mesh_distance(B, B, random_poses(5, seed=3)).distance, ref)
    # Layouts: Fortran order, strided and big-endian arrays are read as their values.
    B = ttd.Mesh(np.asfortranarray(v), f[:, ::-1][:, ::-1])
    np.testing.assert_array_equal(ttd.mesh_distance(B, B, random_poses(5, seed=3)).distance, ref)
    B = ttd.Mesh(v.astype(">f8"), f.astype(">i4"))
    np.testing.assert_array_equal(ttd.mesh_distance(B, B, random_poses(5, seed=3)).distance, ref)
    # Lists work; threads= builds the same mesh.
    B = ttd.Mesh(v.tolist(), f.tolist(), threads=1)
    assert B.node_count == ttd.Mesh(v, f, threads=2).node_count
    np.testing.assert_array_equal(ttd.mesh_distance(B, B, random_poses(5, seed=3)).distance, ref)


@pytest.mark.parametrize("dtype", DTYPES, ids=["float64", "float32"])
def test_mesh_pickles_and_rebuilds_the_same(dtype):
    A, B = mesh_pair("torus", "grid", dtype)
    A2, B2 = pickle.loads(pickle.dumps((A, B)))
    assert A2 is not A and A2.dtype == dtype and A2.node_count == A.node_count
    np.testing.assert_array_equal(A2.vertices, A.vertices)
    np.testing.assert_array_equal(A2.faces, A.faces)
    P = random_poses(20, seed=4)
    r, r2 = ttd.mesh_distance(A, B, P), ttd.mesh_distance(A2, B2, P)
    for field in DISTANCE_FIELDS:
        np.testing.assert_array_equal(getattr(r, field), getattr(r2, field))
    c, c2 = ttd.mesh_contacts(A, B, P, 0.1), ttd.mesh_contacts(A2, B2, P, 0.1)
    for field in CONTACT_FIELDS:
        np.testing.assert_array_equal(getattr(c, field), getattr(c2, field))
    # Results pickle too.
    c3 = pickle.loads(pickle.dumps(c))
    assert type(c3) is ttd.MeshContacts
    np.testing.assert_array_equal(c3.p, c.p)


# ---- poses, shapes, dtypes, empty input, out= -------------------------------------------------

def test_pose_layouts_and_conversions():
    A, B = mesh_pair("icosphere", "cube")
    P = random_poses(6, seed=5)
    ref = ttd.mesh_distance(A, B, P)
    for poses in (P[:, :3, :], np.asfortranarray(P), P.astype(">f8"), np.stack([P, P], 1)[:, 0],
                  list(P.tolist())):
        np.testing.assert_array_equal(ttd.mesh_distance(A, B, poses).distance, ref.distance)
    # A single pose, (4, 4) or (3, 4): scalars and (3,) points.
    one = ttd.mesh_distance(A, B, P[2, :3])
    assert isinstance(one.distance, np.float64) and one.p.shape == (3,) and isinstance(one.tri_a, np.uint32)
    assert one.distance == ref.distance[2]
    # Integer poses (the identity) are exact.
    np.testing.assert_array_equal(ttd.mesh_distance(A, B, np.eye(4, dtype=int)).p,
                                  ttd.mesh_distance(A, B, np.eye(4)).p)
    # float32 poses on float64 meshes are widened (exactly); float64 poses on float32 meshes rounded.
    P32 = P.astype(np.float32)
    np.testing.assert_array_equal(ttd.mesh_distance(A, B, P32).distance,
                                  ttd.mesh_distance(A, B, P32.astype(np.float64)).distance)
    A32, B32 = mesh_pair("icosphere", "cube", np.float32)
    np.testing.assert_array_equal(ttd.mesh_distance(A32, B32, P).distance, ttd.mesh_distance(A32, B32, P32).distance)


@pytest.mark.parametrize("dtype", DTYPES, ids=["float64", "float32"])
def test_empty_poses(dtype):
    A, B = mesh_pair("cube", "torus", dtype)
    for shape in ((0, 4, 4), (0, 3, 4)):
        P = np.zeros(shape)
        r = ttd.mesh_distance(A, B, P)
        assert r.distance.shape == (0,) and r.distance.dtype == dtype and r.p.shape == (0, 3)
        c = ttd.mesh_contacts(A, B, P, 0.1)
        assert c.tri_a.shape == (0,) and c.p.shape == (0, 3) and c.distance.dtype == dtype
        np.testing.assert_array_equal(c.pose_start, [0])
        col = ttd.mesh_collide(A, B, P)
        assert col.hit.shape == (0,) and col.hit.dtype == bool
        cl = ttd.mesh_closest(A, B, P, 0.1)
        assert cl.for_a.partner.shape == (0, A.triangle_count) and cl.for_b.p.shape == (0, B.triangle_count, 3)
    # The checks do not depend on K.
    for call in (lambda P: ttd.mesh_distance(A, B, P, upper_bound=-1),
                 lambda P: ttd.mesh_distance(A, B, P, rel_tol=math.nan),
                 lambda P: ttd.mesh_contacts(A, B, P, -0.5), lambda P: ttd.mesh_closest(A, B, P, math.inf),
                 lambda P: ttd.mesh_collide(A, B, P, threads=-2)):
        for P in (np.zeros((0, 4, 4)), random_poses(2, seed=6)):
            with pytest.raises(ValueError, match="out of range"):
                call(P)


def test_no_contacts_and_far_apart():
    A, B = mesh_pair("icosphere", "torus")
    P = np.eye(4)
    P[0, 3] = 10
    c = ttd.mesh_contacts(A, B, P, 0.5)
    assert c.tri_a.shape == (0,) and c.p.shape == (0, 3)
    np.testing.assert_array_equal(c.pose_start, [0, 0])
    cl = ttd.mesh_closest(A, B, P, 0.5, for_b=False)
    assert cl.for_b is None and np.all(cl.for_a.partner == ttd.NO_TRIANGLE)
    assert ttd.mesh_closest(A, B, P, 0.5, for_a=False).for_a is None


@pytest.mark.parametrize("dtype", DTYPES, ids=["float64", "float32"])
def test_out(dtype):
    A, B = mesh_pair("torus", "icosphere", dtype)
    P = random_poses(7, seed=9)
    rec = ttd.MESH_RESULT_DTYPE_FLOAT64 if dtype == np.float64 else ttd.MESH_RESULT_DTYPE_FLOAT32
    out = np.empty(7, rec)
    r = ttd.mesh_distance(A, B, P, out=out)
    assert np.shares_memory(r.distance, out)
    np.testing.assert_array_equal(out["distance"], ttd.mesh_distance(A, B, P).distance)
    cout = np.empty(7, ttd.COLLISION_DTYPE)
    col = ttd.mesh_collide(A, B, P, 0.1, out=cout)
    np.testing.assert_array_equal(cout["hit"] != 0, col.hit)
    one = np.empty((), rec)
    ttd.mesh_distance(A, B, P[3], out=one)
    assert one["distance"] == r.distance[3]
    other = ttd.MESH_RESULT_DTYPE_FLOAT32 if dtype == np.float64 else ttd.MESH_RESULT_DTYPE_FLOAT64
    with pytest.raises(TypeError, match="out has dtype"):
        ttd.mesh_distance(A, B, P, out=np.empty(7, other))
    with pytest.raises(ValueError, match=r"out has shape \(6,\)"):
        ttd.mesh_distance(A, B, P, out=out[:6])
    with pytest.raises(ValueError, match="C-contiguous"):
        ttd.mesh_distance(A, B, P, out=np.empty(14, rec)[::2])
    with pytest.raises(TypeError, match="numpy array"):
        ttd.mesh_collide(A, B, P, out=[0] * 7)
    crec = ttd.CLOSEST_DTYPE_FLOAT64 if dtype == np.float64 else ttd.CLOSEST_DTYPE_FLOAT32
    oa, ob = np.empty((7, A.triangle_count), crec), np.empty((7, B.triangle_count), crec)
    cl = ttd.mesh_closest(A, B, P, 0.1, out=(oa, ob))
    assert np.shares_memory(cl.for_a.partner, oa) and np.shares_memory(cl.for_b.distance, ob)
    fresh = ttd.mesh_closest(A, B, P, 0.1)
    np.testing.assert_array_equal(oa["partner"], fresh.for_a.partner)
    np.testing.assert_array_equal(ob["distance"], fresh.for_b.distance)
    cl = ttd.mesh_closest(A, B, P, 0.1, for_a=False, out=(None, ob))
    assert cl.for_a is None and np.shares_memory(cl.for_b.p, ob)
    cl = ttd.mesh_closest(A, B, P, 0.1, out=(oa, None))  # None: a new array for that side
    np.testing.assert_array_equal(cl.for_b.partner, fresh.for_b.partner)
    with pytest.raises(ValueError, match="not computed"):
        ttd.mesh_closest(A, B, P, 0.1, for_b=False, out=(oa, ob))
    with pytest.raises(ValueError, match=r"out has shape \(7, 12\).*shape \(K, m\)"):
        ttd.mesh_closest(A, B, P, 0.1, out=(oa[:, :12].copy(), ob))
    with pytest.raises(ValueError, match="share memory"):
        m = A.triangle_count
        big = np.empty(8 * m, crec)
        ttd.mesh_closest(A, A, P, 0.1, out=(big[:7 * m].reshape(7, m), big[m:].reshape(7, m)))
    with pytest.raises(TypeError, match="out must be a tuple"):
        ttd.mesh_closest(A, B, P, 0.1, out=oa)
    # out overlapping the poses it is computed from
    raw = np.zeros(7 * 12 * np.dtype(dtype).itemsize + 64, np.uint8)
    poses = raw[:7 * 12 * np.dtype(dtype).itemsize].view(dtype).reshape(7, 3, 4)
    poses[:] = P[:, :3].astype(dtype)
    with pytest.raises(ValueError, match="shares memory with poses"):
        ttd.mesh_distance(A, B, poses, out=raw[:7 * rec.itemsize].view(rec))


# ---- errors ---------------------------------------------------------------------------------

def test_mesh_errors():
    v, f = MESHES["cube"]
    with pytest.raises(ValueError, match=r"vertices has shape \(8, 2\)"):
        ttd.Mesh(v[:, :2], f)
    with pytest.raises(ValueError, match=r"faces has shape \(12, 4\)"):
        ttd.Mesh(v, np.hstack([f, f[:, :1]]))
    with pytest.raises(ValueError, match="vertices is empty"):
        ttd.Mesh(np.zeros((0, 3)), f)
    with pytest.raises(ValueError, match="faces is empty"):
        ttd.Mesh(v, np.zeros((0, 3), int))
    for bad in (np.nan, np.inf, -np.inf):
        w = v.copy()
        w[5, 2] = bad
        with pytest.raises(ValueError, match=r"vertices\[5\] = \(1.0, 0.0, (nan|inf|-inf)\) is not finite"):
            ttd.Mesh(w, f)
        with pytest.raises(ValueError, match=r"vertices\[5\]"):
            ttd.Mesh(w.astype(np.float32), f)
    g = f.copy()
    g[7, 1] = 8
    with pytest.raises(IndexError, match=r"faces\[7, 1\] = 8 is out of range: the mesh has 8 vertices"):
        ttd.Mesh(v, g)
    g[7, 1] = -1
    with pytest.raises(IndexError, match=r"faces\[7, 1\] = -1 is negative"):
        ttd.Mesh(v, g)
    with pytest.raises(IndexError, match=r"= 18446744073709551615 is out of range"):
        ttd.Mesh(v, g.astype(np.uint64))
    with pytest.raises(TypeError, match="faces has dtype float64"):
        ttd.Mesh(v, f.astype(float))
    with pytest.raises(TypeError, match="faces has dtype bool"):
        ttd.Mesh(v, f > 3)
    with pytest.raises(TypeError, match="vertices has dtype complex128"):
        ttd.Mesh(v.astype(complex), f)
    with pytest.raises(TypeError, match="vertices has dtype float16"):
        ttd.Mesh(v.astype(np.float16), f)
    with pytest.raises(ValueError, match="precision="):
        ttd.Mesh(v, f, precision="float")
    with pytest.raises(ValueError, match="threads=-1 is out of range"):
        ttd.Mesh(v, f, threads=-1)
    with pytest.raises(TypeError):
        ttd.Mesh(v)
    with pytest.raises(ValueError, match="vertices is not an array"):
        ttd.Mesh([[0, 0, 0], [1, 2]], f)


@pytest.mark.parametrize("dtype,limit", [(np.float64, 2.0**508), (np.float32, 2.0**60)])
def test_coordinate_range(dtype, limit):
    """The C library's mesh coordinate range (ttd.h), named per vertex and per pose."""
    v, f = MESHES["cube"]
    w = v.astype(dtype)
    w[3] = (0, 4 * limit, 0)
    with pytest.raises(ValueError, match=r"vertices\[3\] = .* is beyond the mesh coordinate range"):
        ttd.Mesh(w, f)
    A, B = mesh_pair("cube", "icosphere", dtype)
    P = random_poses(4, seed=3).astype(dtype)
    far = P.copy()
    far[2, 0, 3] = 2 * limit
    with pytest.raises(ValueError, match=r"poses\[2\] moves mesh b beyond the mesh coordinate range"):
        ttd.mesh_distance(A, B, far)
    with pytest.raises(ValueError, match=r"^poses moves mesh b beyond"):
        ttd.mesh_collide(A, B, far[2], 0.1)
    near = P.copy()
    near[2, 0, 3] = limit / 4  # within the range: answered, far apart
    d = ttd.mesh_distance(A, B, near)
    assert d.distance[2] > limit / 8


def test_query_errors():
    A, B = mesh_pair("cube", "icosphere")
    A32, _ = mesh_pair("cube", "icosphere", np.float32)
    P = random_poses(3, seed=10)
    with pytest.raises(TypeError, match="b must be a ttd.Mesh, not numpy.ndarray"):
        ttd.mesh_distance(A, B.vertices, P)
    with pytest.raises(TypeError, match="a is a float64 mesh and b a float32 mesh"):
        ttd.mesh_contacts(A, A32, P, 0.1)
    for shape in ((3, 4, 3), (3, 2, 4), (4,), (2, 3, 4, 4), ()):
        with pytest.raises(ValueError, match="poses has shape"):
            ttd.mesh_collide(A, B, np.zeros(shape))
    with pytest.raises(TypeError, match="poses has dtype complex128"):
        ttd.mesh_distance(A, B, P.astype(complex))
    bottom = P.copy()
    bottom[1, 3] = [0, 0, 0.5, 1]
    with pytest.raises(ValueError, match=r"poses\[1\] has bottom row \(0.0, 0.0, 0.5, 1.0\)"):
        ttd.mesh_distance(A, B, bottom)
    with pytest.raises(ValueError, match=r"^poses has bottom row"):
        ttd.mesh_distance(A, B, bottom[1])
    for entry, value, message in (((0, 0), np.nan, "NaN or infinite"), ((1, 3), np.inf, "NaN or infinite"),
                                  ((0, 0), 1.001, "not a rotation within 1e-6"),
                                  ((0, 1), 0.01, "not a rotation within 1e-6"),
                                  ((2, 2), 1 + 2e-6, "not a rotation within 1e-6")):
        bad = P.copy()
        bad[(2,) + entry] = value
        with pytest.raises(ValueError, match=r"poses\[2\] (has a|is) " + message):
            ttd.mesh_distance(A, B, bad)
        with pytest.raises(ValueError, match=r"poses\[2\]"):
            ttd.mesh_closest(A, B, bad[:, :3], 0.1)
    flip = P.copy()
    flip[0, :3, 2] *= -1
    with pytest.raises(ValueError, match=r"poses\[0\] is not a rotation: det R = -1"):
        ttd.mesh_collide(A, B, flip)
    with pytest.raises(ValueError, match=r"^poses is not a rotation"):
        ttd.mesh_contacts(A, B, flip[0], 0.1)
    nearly = P.copy()
    nearly[0, 2, 2] += 4e-7  # within the tolerance
    ttd.mesh_distance(A, B, nearly)
    with pytest.raises(ValueError, match=r"margin=-0.1 is out of range"):
        ttd.mesh_contacts(A, B, P, -0.1)
    with pytest.raises(ValueError, match=r"margin=inf is out of range"):
        ttd.mesh_collide(A, B, P, math.inf)
    with pytest.raises(ValueError, match=r"margin=1e\+40 is out of range.*overflows float32"):
        ttd.mesh_closest(A32, A32, P, 1e40)
    ttd.mesh_distance(A32, A32, P, upper_bound=1e40)  # overflows to inf: no bound
    with pytest.raises(ValueError, match=r"upper_bound=nan is out of range"):
        ttd.mesh_distance(A, B, P, upper_bound=math.nan)
    with pytest.raises(ValueError, match=r"rel_tol=-1.0 is out of range"):
        ttd.mesh_distance(A, B, P, rel_tol=-1)
    with pytest.raises(TypeError, match="margin must be a real number"):
        ttd.mesh_contacts(A, B, P, "0.1")
    with pytest.raises(TypeError, match="margin must be a real number, not None"):
        ttd.mesh_contacts(A, B, P, None)
    with pytest.raises(TypeError, match="upper_bound must be a real number"):
        ttd.mesh_distance(A, B, P, upper_bound=True)
    with pytest.raises(ValueError, match="for_a and for_b are both False"):
        ttd.mesh_closest(A, B, P, 0.1, for_a=False, for_b=False)
    with pytest.raises(ValueError, match="isa='x' is not one of"):
        ttd.mesh_distance(A, B, P, isa="x")
    missing = [i for i in ttd.ISAS if i != "auto" and not ttd.isa_available(i)]
    if missing:
        with pytest.raises(ttd.IsaUnavailableError, match=f"isa='{missing[0]}' is not available"):
            ttd.mesh_collide(A, B, P, isa=missing[0])
    with pytest.raises(TypeError):
        ttd.mesh_distance(A, B, P, 1.0)  # upper_bound is keyword-only


def test_bad_ttd_isa_environment(monkeypatch):
    """An unusable TTD_ISA is ignored by the library (ttd.h), for mesh queries as for pairs."""
    A, B = mesh_pair("cube", "icosphere")
    P = random_poses(5, seed=4)
    want = ttd.mesh_distance(A, B, P)
    monkeypatch.setenv("TTD_ISA", "nonsense")
    got = ttd.mesh_distance(A, B, P)
    np.testing.assert_array_equal(got.distance, want.distance)
    np.testing.assert_array_equal(got.p, want.p)
    assert len(ttd.mesh_contacts(A, B, np.zeros((0, 4, 4)), 0.1).distance) == 0


# ---- documentation and type hints -------------------------------------------------------------

def test_stub_covers_the_extension():
    import ast
    import inspect
    import pathlib

    stub = ast.parse((pathlib.Path(ttd.__file__).parent / "_ttd.pyi").read_text())
    defined = {}
    for node in stub.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            defined[node.name] = node
        elif isinstance(node, ast.AnnAssign):
            defined[node.target.id] = node
    public = [n for n in dir(ttd._ttd) if not n.startswith("_")]
    assert sorted(set(public) - set(defined)) == []
    for name in ("mesh_distance", "mesh_contacts", "mesh_closest", "mesh_collide"):
        args = defined[name].args
        stubbed = [a.arg for a in args.args] + [a.arg for a in args.kwonlyargs]
        real = inspect.signature(getattr(ttd._ttd, name)).parameters
        assert stubbed == list(real), name
        assert [a.arg for a in args.kwonlyargs] == [p for p, v in real.items() if v.kind is v.KEYWORD_ONLY], name
        # The package's query (ttd/_poses.py) takes the extension's parameters, poses optional,
        # and the world poses pose_a and pose_b.
        wrapped = inspect.signature(getattr(ttd, name)).parameters
        assert [p for p in wrapped if p not in ("pose_a", "pose_b")] == list(real), name
        assert wrapped["poses"].default is None and wrapped["pose_a"].kind is wrapped["pose_a"].KEYWORD_ONLY
    mesh = [n for n in defined["Mesh"].body if isinstance(n, ast.FunctionDef) and n.name == "__init__"][0]
    assert [a.arg for a in mesh.args.args + mesh.args.kwonlyargs] == ["self"] + list(inspect.signature(ttd.Mesh).parameters)
    for obj in (ttd.Mesh, ttd.mesh_distance, ttd.mesh_contacts, ttd.mesh_closest, ttd.mesh_collide, ttd.MeshDistance,
                ttd.MeshContacts, ttd.MeshCollision, ttd.MeshClosest, ttd.ClosestPartners, ttd.MeshFlag):
        assert obj.__doc__ and len(obj.__doc__) > 40, obj


@pytest.mark.parametrize("dtype", DTYPES, ids=["float64", "float32"])
def test_benchmark_c_timer_makes_the_same_calls(dtype):
    # bench/python_overhead.py compares ttd's mesh queries with ttd._ctiming.time_mesh_calls: the
    # same library calls on meshes built from the same arrays must write the same records.
    _ctiming = ctiming_module()

    A, B = mesh_pair("torus", "icosphere", dtype)
    P = random_poses(30, seed=12, spread=1.2)[:, :3].astype(dtype).copy()
    cargs = (A.vertices, A.faces, B.vertices, B.faces, P, 2)
    f64 = dtype == np.float64
    out = np.empty(30, ttd.MESH_RESULT_DTYPE_FLOAT64 if f64 else ttd.MESH_RESULT_DTYPE_FLOAT32)
    assert _ctiming.time_mesh_calls(*cargs, out=out) > 0
    r = ttd.mesh_distance(A, B, P)
    for field in DISTANCE_FIELDS:
        np.testing.assert_array_equal(out[field], getattr(r, field), err_msg=field)
    col = np.empty(30, ttd.COLLISION_DTYPE)
    _ctiming.time_mesh_calls(*cargs, query="collide", margin=0.05, out=col)
    np.testing.assert_array_equal(col["hit"] != 0, ttd.mesh_collide(A, B, P, 0.05).hit)
    rec = ttd.CLOSEST_DTYPE_FLOAT64 if f64 else ttd.CLOSEST_DTYPE_FLOAT32
    fa, fb = np.empty((30, A.triangle_count), rec), np.empty((30, B.triangle_count), rec)
    _ctiming.time_mesh_calls(*cargs, query="closest", margin=0.05, out=fa, out2=fb)
    cl = ttd.mesh_closest(A, B, P, 0.05)
    np.testing.assert_array_equal(fa["partner"], cl.for_a.partner)
    np.testing.assert_array_equal(fb["distance"], cl.for_b.distance)
    assert _ctiming.time_mesh_calls(*cargs, query="contacts", margin=0.05, fresh=True) > 0
    with pytest.raises(ValueError, match="query is"):
        _ctiming.time_mesh_calls(*cargs, query="nope", out=out)
