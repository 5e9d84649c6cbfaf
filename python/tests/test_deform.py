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
