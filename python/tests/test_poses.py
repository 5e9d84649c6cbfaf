# SPDX-License-Identifier: MIT
"""Poses as users hold them: ttd.pose (quaternions in both orders, matrices, translations,
batches) against the tests' own quaternion formula; ttd.orthonormalize against the exact
rotation a few printed digits came from; the mesh queries with world poses (pose_a=, pose_b=)
against the same queries on meshes whose vertices were moved into the world here (results in
the world frame); identity as the default pose."""
import math

import numpy as np
import pytest

import ttd
from meshes import icosphere, random_poses, rotation, torus


def test_pose_from_quaternion_both_orders():
    rng = np.random.default_rng(3)
    for _ in range(20):
        q = rng.standard_normal(4)
        t = rng.standard_normal(3)
        P = ttd.pose(quat=q, t=t)
        assert P.shape == (3, 4) and P.dtype == np.float64
        np.testing.assert_allclose(P[:, :3], rotation(q), rtol=0, atol=1e-15)
        np.testing.assert_array_equal(P[:, 3], t)
        np.testing.assert_array_equal(ttd.pose(quat=np.roll(q, -1), t=t, order="xyzw"), P)  # (x, y, z, w)
    # 90 degrees about z: (w, x, y, z) = (cos 45, 0, 0, sin 45); unnormalised input is normalised.
    P = ttd.pose(quat=[2, 0, 0, 2])
    np.testing.assert_allclose(P, [[0, -1, 0, 0], [1, 0, 0, 0], [0, 0, 1, 0]], atol=1e-15)
    np.testing.assert_array_equal(ttd.pose(), np.eye(4)[:3])
    np.testing.assert_array_equal(ttd.pose(t=[1, 2, 3])[:, 3], [1, 2, 3])
    R = rotation([1, 2, 3, 4])
    np.testing.assert_array_equal(ttd.pose(R=R, t=[1, 2, 3])[:, :3], R)


def test_pose_batches_broadcast():
    rng = np.random.default_rng(4)
    q = rng.standard_normal((5, 4))
    P = ttd.pose(quat=q, t=[1, 0, 0])
    assert P.shape == (5, 3, 4)
    for k in range(5):
        np.testing.assert_array_equal(P[k], ttd.pose(quat=q[k], t=[1, 0, 0]))
    P = ttd.pose(t=rng.standard_normal((7, 3)))
    assert P.shape == (7, 3, 4) and np.all(P[:, :, :3] == np.eye(3))
    # the result is what the queries take
    A = ttd.Mesh(*icosphere(1))
    assert ttd.mesh_distance(A, A, ttd.pose(quat=q, t=[5, 0, 0])).distance.shape == (5,)


def test_pose_errors():
    with pytest.raises(ValueError, match="R or quat, not both"):
        ttd.pose(R=np.eye(3), quat=[1, 0, 0, 0])
    with pytest.raises(ValueError, match="order must be 'wxyz' or 'xyzw'"):
        ttd.pose(quat=[1, 0, 0, 0], order="zyx")
    with pytest.raises(ValueError, match="zero or non-finite quaternion"):
        ttd.pose(quat=[0, 0, 0, 0])
    with pytest.raises(ValueError, match="zero or non-finite quaternion"):
        ttd.pose(quat=[1, 0, math.nan, 0])
    with pytest.raises(ValueError, match=r"quat has shape \(3,\)"):
        ttd.pose(quat=[1, 0, 0])
    with pytest.raises(ValueError, match=r"R has shape \(3, 4\)"):
        ttd.pose(R=np.zeros((3, 4)))
    with pytest.raises(ValueError, match=r"t has shape \(2,\)"):
        ttd.pose(t=[1, 2])


C5 = 0.70711  # cos 45 degrees printed with 5 digits


def test_orthonormalize_repairs_printed_rotations():
    printed = np.array([[C5, -C5, 0, 3], [C5, C5, 0, 0], [0, 0, 1, 0]])
    A = ttd.Mesh(*icosphere(1))
    with pytest.raises(ValueError, match="not a rotation within 1e-6"):
        ttd.mesh_distance(A, A, printed)
    fixed = ttd.orthonormalize(printed)
    assert fixed.shape == (3, 4) and fixed.dtype == np.float64
    c = math.sqrt(0.5)
    np.testing.assert_allclose(fixed[:, :3], [[c, -c, 0], [c, c, 0], [0, 0, 1]], rtol=0, atol=1e-15)
    np.testing.assert_array_equal(fixed[:, 3], printed[:, 3])
    exact = ttd.pose(R=[[c, -c, 0], [c, c, 0], [0, 0, 1]], t=[3, 0, 0])
    assert abs(ttd.mesh_distance(A, A, fixed).distance - ttd.mesh_distance(A, A, exact).distance) < 1e-14
    # Shapes: (3, 3), (4, 4) with its bottom row, batches; float32 stays float32.
    np.testing.assert_array_equal(ttd.orthonormalize(printed[:, :3]), fixed[:, :3])
    h = np.vstack([printed, [0, 0, 0, 1]])
    out = ttd.orthonormalize(h)
    assert out.shape == (4, 4) and np.all(out[3] == [0, 0, 0, 1])
    np.testing.assert_array_equal(out[:3], fixed)
    batch = np.stack([printed, np.eye(4)[:3], fixed])
    np.testing.assert_array_equal(ttd.orthonormalize(batch)[0], fixed)
    np.testing.assert_allclose(ttd.orthonormalize(batch)[1], np.eye(4)[:3], atol=1e-16)
    assert ttd.orthonormalize(printed.astype(np.float32)).dtype == np.float32
    # random rotations rounded to 4 digits come back within rounding of a rotation
    P = np.round(random_poses(50, seed=8), 4)
    R = ttd.orthonormalize(P)[:, :3, :3]
    assert np.max(np.abs(np.swapaxes(R, 1, 2) @ R - np.eye(3))) < 1e-14
    assert np.all(np.linalg.det(R) > 0)
    assert np.max(np.abs(R - P[:, :3, :3])) < 1e-3


def test_orthonormalize_errors():
    with pytest.raises(ValueError, match=r"poses\[1\] has det R = -1.0"):
        ttd.orthonormalize(np.stack([np.eye(3), np.diag([1.0, 1, -1])]))
    with pytest.raises(ValueError, match="has det R"):
        ttd.orthonormalize(np.zeros((3, 3)))
    with pytest.raises(ValueError, match="bottom row"):
        ttd.orthonormalize(2 * np.eye(4))
    with pytest.raises(ValueError, match="takes"):
        ttd.orthonormalize(np.eye(2))
    with pytest.raises(TypeError):
        ttd.orthonormalize(np.array([["a"] * 3] * 3))


# ---- world poses -----------------------------------------------------------------------------

def _world_meshes(dtype=np.float64):
    (va, fa), (vb, fb) = icosphere(1), torus()
    return (va, fa), (vb, fb), ttd.Mesh(va.astype(dtype), fa), ttd.Mesh(vb.astype(dtype), fb)


def _moved(v, P):
    return v @ P[:3, :3].T + P[:3, 3]


@pytest.mark.parametrize("dtype", [np.float64, np.float32], ids=["float64", "float32"])
def test_world_poses_equal_meshes_moved_to_the_world(dtype):
    (va, fa), (vb, fb), A, B = _world_meshes(dtype)
    Ta = random_poses(6, seed=21, spread=3)
    Tb = Ta.copy()
    rng = np.random.default_rng(22)
    u = rng.standard_normal((6, 3))
    Tb[:, :3, 3] += u / np.linalg.norm(u, axis=1, keepdims=True) * np.array([1.0, 1.5, 2.2, 2.6, 3.0, 3.5])[:, None]
    # near a: the first touch, the last are apart
    Tb[:, :3, :3] = random_poses(6, seed=23)[:, :3, :3]
    r = ttd.mesh_distance(A, B, pose_a=Ta, pose_b=Tb)
    assert r.distance.shape == (6,) and r.p.dtype == dtype
    tol = 1e-12 if dtype == np.float64 else 2e-5
    for k in range(6):
        WA = ttd.Mesh(_moved(va, Ta[k]).astype(dtype), fa)
        WB = ttd.Mesh(_moved(vb, Tb[k]).astype(dtype), fb)
        w = ttd.mesh_distance(WA, WB)
        assert abs(r.distance[k] - w.distance) <= tol * 10
        if w.distance > 0.01:  # a unique pair: the same points, in the world frame
            np.testing.assert_allclose(r.p[k], w.p, atol=tol * 10)
            np.testing.assert_allclose(r.q[k], w.q, atol=tol * 10)
            np.testing.assert_allclose(np.linalg.norm(r.p[k].astype(float) - r.q[k]), r.distance[k], atol=tol * 10)
        assert ttd.mesh_collide(A, B, pose_a=Ta[k], pose_b=Tb[k], margin=0.05).hit == ttd.mesh_collide(WA, WB, margin=0.05).hit
    # The same triangles and distances as the relative pose inv(Ta) Tb, points mapped by Ta.
    rel = np.linalg.inv(Ta) @ Tb
    r_rel = ttd.mesh_distance(A, B, rel)
    np.testing.assert_allclose(r.distance, r_rel.distance, rtol=0, atol=tol * 10)
    apart = r_rel.distance > 0.01  # where the closest pair is unique
    assert apart.any() and not apart.all()
    np.testing.assert_allclose(r.p[apart], (np.einsum("kij,kj->ki", Ta[:, :3, :3], r_rel.p) + Ta[:, :3, 3])[apart],
                               atol=tol * 10)


def test_world_contacts_and_closest():
    (va, fa), (vb, fb), A, B = _world_meshes()
    Ta = ttd.pose(quat=[1, 2, 3, 4], t=[10, -3, 2])
    Tb = ttd.pose(quat=[4, 1, 0, 2], t=[10.5, -3, 2.9])
    WA, WB = ttd.Mesh(_moved(va, Ta), fa), ttd.Mesh(_moved(vb, Tb), fb)
    c = ttd.mesh_contacts(A, B, pose_a=Ta, pose_b=Tb, margin=0.1)
    w = ttd.mesh_contacts(WA, WB, margin=0.1)
    assert len(c.distance) > 0
    got = sorted(zip(c.tri_a.tolist(), c.tri_b.tolist()))
    assert got == sorted(zip(w.tri_a.tolist(), w.tri_b.tolist()))
    order_c = np.lexsort((c.tri_b, c.tri_a))
    order_w = np.lexsort((w.tri_b, w.tri_a))
    np.testing.assert_allclose(c.distance[order_c], w.distance[order_w], atol=1e-12)
    far = w.distance[order_w] > 1e-3
    np.testing.assert_allclose(c.p[order_c][far], w.p[order_w][far], atol=1e-11)
    cl = ttd.mesh_closest(A, B, pose_a=Ta, pose_b=Tb, margin=0.1)
    wl = ttd.mesh_closest(WA, WB, margin=0.1)
    np.testing.assert_array_equal(cl.for_a.partner != ttd.NO_TRIANGLE, wl.for_a.partner != ttd.NO_TRIANGLE)
    found = (cl.for_a.partner != ttd.NO_TRIANGLE) & (wl.for_a.distance > 1e-3)
    np.testing.assert_allclose(cl.for_a.p[found], wl.for_a.p[found], atol=1e-11)
    assert ttd.mesh_closest(A, B, pose_a=Ta, pose_b=Tb, margin=0.1, for_b=False).for_b is None


def test_world_poses_broadcast_and_defaults():
    _, _, A, B = _world_meshes()
    P = random_poses(5, seed=30, spread=2)
    one = ttd.mesh_distance(A, B, P)
    # pose_a alone (b at the world origin) and pose_b alone (a at the origin)
    r = ttd.mesh_distance(A, B, pose_b=P)
    np.testing.assert_allclose(r.distance, one.distance, atol=1e-14)
    np.testing.assert_array_equal(r.tri_a, one.tri_a)
    r = ttd.mesh_distance(A, B, pose_a=np.linalg.inv(P))
    np.testing.assert_allclose(r.distance, one.distance, atol=1e-12)
    # one pose of a against K of b
    T = ttd.pose(quat=[1, 1, 0, 0], t=[0, 0, 4])
    r = ttd.mesh_distance(A, B, pose_a=T, pose_b=T @ P)
    np.testing.assert_allclose(r.distance, one.distance, atol=1e-12)
    # identity defaults: no pose at all is the identity, one pose: scalar results
    d0, d1 = ttd.mesh_distance(A, B), ttd.mesh_distance(A, B, np.eye(4))
    for x, y in zip(d0, d1):
        np.testing.assert_array_equal(x, y)
    assert np.ndim(d0.distance) == 0
    assert ttd.mesh_collide(A, B).hit == ttd.mesh_collide(A, B, np.eye(4)).hit
    assert len(ttd.mesh_contacts(A, B, margin=0.0).pose_start) == 2


def test_world_pose_errors():
    _, _, A, B = _world_meshes()
    with pytest.raises(ValueError, match="do not go together"):
        ttd.mesh_distance(A, B, np.eye(4), pose_a=np.eye(4))
    bad = random_poses(3, seed=1)
    bad[2, 0, 0] += 1e-3
    with pytest.raises(ValueError, match=r"pose_b\[2\] is not a rotation within 1e-6"):
        ttd.mesh_distance(A, B, pose_b=bad)
    with pytest.raises(ValueError, match=r"pose_a is not a rotation: det R = -1.0"):
        ttd.mesh_collide(A, B, pose_a=np.diag([1.0, 1, -1, 1]))
    with pytest.raises(ValueError, match="pose_a holds 2 poses and pose_b 3"):
        ttd.mesh_distance(A, B, pose_a=random_poses(2, seed=2), pose_b=random_poses(3, seed=3))
    with pytest.raises(ValueError, match="bottom row"):
        ttd.mesh_distance(A, B, pose_a=2 * np.eye(4))
    with pytest.raises(TypeError, match="margin"):
        ttd.mesh_contacts(A, B)
