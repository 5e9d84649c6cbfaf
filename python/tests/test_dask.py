# SPDX-License-Identifier: MIT
"""Scale-out on Dask, on a distributed.LocalCluster of two worker processes (what a real cluster
runs, pickling included): ttd.dask.distance equals one ttd.distance call, bit for bit, with
chunks that do not align with the library's 256-pair blocks or its SIMD lanes; and the mesh
queries over 10,000 poses in chunks (the meshes pickled to the workers and rebuilt there) equal
one call on all the poses, field by field and bit for bit."""
import numpy as np
import pytest

import ttd
from cases import random_pairs
from meshes import icosphere, random_poses, rotation, torus

da = pytest.importorskip("dask.array", reason="python3-dask is not installed")
distributed = pytest.importorskip("distributed", reason="python3-distributed is not installed")
import ttd.dask  # noqa: E402  (after the skip: it needs dask)


@pytest.fixture(scope="module")
def client():
    # Two single-threaded worker processes, no dashboard: a few seconds to start.
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  silence_logs=40) as cluster, distributed.Client(cluster) as c:
        yield c


@pytest.mark.parametrize("method,dtype", [("exact", np.float64), ("exact", np.float32),
                                          ("penalty", np.float64), ("certified", np.float32)])
def test_chunks_on_a_cluster_equal_one_call(client, method, dtype):
    S, T = random_pairs(60_001, seed=51, dtype=dtype)
    one_call = ttd.distance(S, T, method=method)
    dS = da.from_array(S, chunks=(4_993, 3, 3))  # a prime chunk length
    dT = da.from_array(T.reshape(-1, 9), chunks=(10_000, 9))  # other chunks: rechunked to S's
    d = ttd.dask.distance(dS, dT, method=method, threads=1)
    assert d.dtype == dtype and d.shape == (60_001,) and d.numblocks == (13,)
    got = client.compute(d).result()
    assert got.dtype == dtype
    np.testing.assert_array_equal(got, one_call)
    # Reductions run on the workers too.
    assert client.compute(d.min()).result() == one_call.min()
    assert client.compute((d == 0).sum()).result() == np.count_nonzero(one_call == 0)


def test_pairs_generated_on_the_workers(client):
    # The example's pattern: pairs that never exist in one place; every chunk is made on a
    # worker from the seed. Checked against one call on the same pairs made here.
    n, chunk = 200_000, 25_000
    S = da.random.RandomState(7).random_sample((n, 9), chunks=(chunk, 9))
    T = da.random.RandomState(8).random_sample((n, 9), chunks=(chunk, 9)) + 0.25
    d = ttd.dask.distance(S, T)
    got = client.compute(d).result()
    np.testing.assert_array_equal(got, ttd.distance(*client.compute([S, T], sync=True)))


def test_bad_arguments_fail_before_computing():
    S = da.zeros((100, 9), chunks=10)
    with pytest.raises(ValueError, match="method="):
        ttd.dask.distance(S, S, method="nope")
    with pytest.raises(TypeError, match="S has dtype float64 and T has dtype float32"):
        ttd.dask.distance(S, S.astype(np.float32))
    with pytest.raises(ValueError, match=r"S has shape \(100, 8\)"):
        ttd.dask.distance(da.zeros((100, 8)), S)
    with pytest.raises(ValueError, match="100 and 99 pairs"):
        ttd.dask.distance(S, S[:99])
    with pytest.raises(ValueError, match="distances only"):
        ttd.dask.distance(S, S, points=True)


# ---- meshes over chunks of poses --------------------------------------------------------------

DISTANCE_FIELDS = ("distance", "p", "q", "tri_a", "tri_b", "feature_a", "feature_b", "flags", "node_tests",
                   "pair_tests")


def _meshes(dtype):
    (va, fa), (vb, fb) = icosphere(2), torus()
    return ttd.Mesh(va.astype(dtype), fa), ttd.Mesh(vb.astype(dtype), fb)


def _mesh_objects(task):
    """The ttd.Mesh objects written into one task of a graph."""
    if isinstance(task, ttd.Mesh):
        return [task]
    if isinstance(task, (tuple, list)):
        return [m for t in task for m in _mesh_objects(t)]
    if isinstance(task, dict):
        return [m for t in task.values() for m in _mesh_objects(t)]
    return []


@pytest.mark.parametrize("dtype", [np.float64, np.float32], ids=["float64", "float32"])
def test_mesh_poses_in_chunks_equal_one_call(client, dtype):
    A, B = _meshes(dtype)
    P = random_poses(10_000, seed=52, spread=1.3)
    dP = da.from_array(P, chunks=(997, 4, 4))  # a prime chunk length: 11 chunks
    r = ttd.dask.mesh_distance(A, B, dP, threads=1)
    rec = ttd.MESH_RESULT_DTYPE_FLOAT64 if dtype == np.float64 else ttd.MESH_RESULT_DTYPE_FLOAT32
    assert r.dtype == rec and r.shape == (10_000,) and r.numblocks == (11,)
    # The meshes are one task of the graph, whatever the number of chunks.
    graph = dict(r.__dask_graph__())
    assert sum(1 for task in graph.values() if _mesh_objects(task)) == 1
    got = client.compute(r).result()
    one = ttd.mesh_distance(A, B, P)
    for field in DISTANCE_FIELDS:
        np.testing.assert_array_equal(got[field], getattr(one, field), err_msg=field)
    assert client.compute(r["distance"].min()).result() == one.distance.min()

    col = client.compute(ttd.dask.mesh_collide(A, B, dP[:, :3, :], 0.01, threads=1)).result()
    one_col = ttd.mesh_collide(A, B, P, 0.01)
    assert col.dtype == ttd.dask.COLLISION_DTYPE and col["hit"].dtype == one_col.hit.dtype == np.bool_
    np.testing.assert_array_equal(col["hit"], one_col.hit)
    for field in ("tri_a", "tri_b", "node_tests", "pair_tests"):
        np.testing.assert_array_equal(col[field], getattr(one_col, field), err_msg=field)

    # Contacts cost far more per pose (hundreds of pairs each where the meshes cross): 3,000 poses.
    parts = ttd.dask.mesh_contacts(A, B, dP[:3000], 0.005, threads=1)
    assert parts.npartitions == 4
    one_c = ttd.mesh_contacts(A, B, P[:3000], 0.005)
    assert client.compute(parts.map(lambda c: c.distance.size).sum()).result() == one_c.distance.size > 1000
    joined = ttd.dask.concatenate_contacts(client.compute(parts).result())
    for got_field, want_field in zip(joined, one_c):
        np.testing.assert_array_equal(got_field, want_field)


def _poses_from(q, t):
    """(n, 3, 4) poses from n quaternions and n translations (a dask block function)."""
    out = np.empty((len(q), 3, 4))
    for i in range(len(q)):
        out[i, :, :3] = rotation(q[i])
    out[:, :, 3] = t
    return out


def test_mesh_poses_generated_on_the_workers(client):
    # The example's pattern: poses made chunk by chunk on the workers, never in one place.
    A, B = _meshes(np.float64)
    n, chunk = 6_000, 1_000
    q = da.random.RandomState(9).standard_normal((n, 4), chunks=(chunk, 4))
    t = 2.6 * da.random.RandomState(10).random_sample((n, 3), chunks=(chunk, 3)) - 1.3
    P = da.map_blocks(_poses_from, q, t, new_axis=2, chunks=(q.chunks[0], (3,), (4,)), dtype=float)
    r = ttd.dask.mesh_distance(A, B, P)
    got, poses = client.compute([r, P], sync=True)
    one = ttd.mesh_distance(A, B, poses)
    np.testing.assert_array_equal(got["distance"], one.distance)
    np.testing.assert_array_equal(got["p"], one.p)


def test_mesh_bad_arguments_fail_before_computing():
    A, B = _meshes(np.float64)
    A32, _ = _meshes(np.float32)
    P = da.zeros((100, 4, 4), chunks=10)
    with pytest.raises(ValueError, match=r"poses has shape \(100, 4\)"):
        ttd.dask.mesh_distance(A, B, da.zeros((100, 4)))
    with pytest.raises(TypeError, match="b must be a ttd.Mesh"):
        ttd.dask.mesh_collide(A, "B", P)
    with pytest.raises(TypeError, match="a is a float32 mesh and b a float64 mesh"):
        ttd.dask.mesh_distance(A32, B, P)
    with pytest.raises(ValueError, match="margin=-1.0 is out of range"):
        ttd.dask.mesh_contacts(A, B, P, -1.0)
    with pytest.raises(ValueError, match="upper_bound=-1.0 is out of range"):
        ttd.dask.mesh_distance(A, B, P, upper_bound=-1.0)
    with pytest.raises(ValueError, match="out= is not taken"):
        ttd.dask.mesh_distance(A, B, P, out=np.empty(100, ttd.MESH_RESULT_DTYPE_FLOAT64))
    with pytest.raises(ValueError, match="at least one"):
        ttd.dask.concatenate_contacts([])


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_point_queries_in_chunks_equal_one_call(client, dtype):
    v, f = torus(nu=32, nv=16)
    mesh = ttd.Mesh(v.astype(dtype), f)
    rng = np.random.default_rng(4)
    P = (3 * rng.random((20_011, 3)) - 1.5).astype(dtype)
    dP = da.from_array(P, chunks=(3_001, 3))
    r = client.compute(ttd.dask.closest_points(mesh, dP, threads=1)).result()
    one = ttd.closest_points(mesh, P)
    # every answer bit for bit; the counts of tests depend on the batch a point came in (its walk
    # is seeded by its neighbour in the batch's spatial order, docs/points.md section 3)
    for name in r.dtype.names:
        if name in ("node_tests", "triangle_tests"):
            assert np.all(r[name] > 0) and np.all(getattr(one, name) > 0)
        else:
            np.testing.assert_array_equal(r[name], getattr(one, name))
    sd = client.compute(ttd.dask.signed_distance(mesh, dP, threads=1)).result()
    np.testing.assert_array_equal(sd, ttd.signed_distance(mesh, P).distance)
    w = client.compute(ttd.dask.winding_number(mesh, dP)).result()
    np.testing.assert_array_equal(w, ttd.winding_number(mesh, P).winding)
    inside = client.compute(ttd.dask.contains(mesh, dP)).result()
    assert inside.dtype == np.bool_ and inside.any() and not inside.all()
    np.testing.assert_array_equal(inside, ttd.contains(mesh, P).inside)
