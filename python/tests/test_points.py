# SPDX-License-Identifier: MIT
"""The point queries (ttd.closest_points, signed_distance, winding_number, contains, sdf_grid)
against an independent numpy brute force: the closest point of every triangle by Ericson's region
tests (Real-Time Collision Detection, 5.1.5) in float64, the minimum over all triangles; signs
against the face planes of a convex mesh (inside a convex polyhedron: behind every face)."""
import warnings

import numpy as np
import pytest

import ttd
from meshes import icosphere, torus


def closest_on_triangles(p, A, B, C):
    """Closest points of point p to every triangle (A, B, C: (m, 3)) and their squared distances."""
    ab, ac, ap = B - A, C - A, p - A
    d1, d2 = (ab * ap).sum(1), (ac * ap).sum(1)
    bp = p - B
    d3, d4 = (ab * bp).sum(1), (ac * bp).sum(1)
    cp = p - C
    d5, d6 = (ab * cp).sum(1), (ac * cp).sum(1)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        denom = 1.0 / (va + vb + vc)
        q = A + ab * (vb * denom)[:, None] + ac * (vc * denom)[:, None]
        t_ab = d1 / (d1 - d3)
        t_ac = d2 / (d2 - d6)
        t_bc = (d4 - d3) / ((d4 - d3) + (d5 - d6))
    regions = [
        ((d1 <= 0) & (d2 <= 0), A),
        ((d3 >= 0) & (d4 <= d3), B),
        ((d6 >= 0) & (d5 <= d6), C),
        ((vc <= 0) & (d1 >= 0) & (d3 <= 0), A + ab * t_ab[:, None]),
        ((vb <= 0) & (d2 >= 0) & (d6 <= 0), A + ac * t_ac[:, None]),
        ((va <= 0) & ((d4 - d3) >= 0) & ((d5 - d6) >= 0), B + (C - B) * t_bc[:, None]),
    ]
    done = np.zeros(len(A), bool)
    for mask, point in regions:
        m = mask & ~done
        q[m] = point[m]
        done |= m
    return q, ((q - p) ** 2).sum(1)


def brute(v, f, points):
    A, B, C = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    out = np.empty(len(points))
    for i, p in enumerate(points):
        out[i] = np.sqrt(closest_on_triangles(p, A, B, C)[1].min())
    return out


def sample_points(v, n, seed):
    rng = np.random.default_rng(seed)
    lo, hi = v.min(0), v.max(0)
    return lo - 0.2 * (hi - lo) + 1.4 * (hi - lo) * rng.random((n, 3))


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_closest_points_match_brute_force(dtype):
    v, f = torus(nu=24, nv=12)
    mesh = ttd.Mesh(v.astype(dtype), f)
    pts = sample_points(v, 400, 3).astype(dtype)
    r = ttd.closest_points(mesh, pts)
    assert r.distance.dtype == dtype and r.point.shape == (400, 3) and r.triangle.dtype == np.uint32
    ref = brute(v.astype(dtype).astype(np.float64), f, pts.astype(np.float64))
    tol = 1e-12 if dtype == np.float64 else 2e-6
    np.testing.assert_allclose(r.distance, ref, rtol=tol, atol=tol)
    # the point is on its triangle, at the distance, and rebuilt by its weights
    tri = v.astype(dtype).astype(np.float64)[f[r.triangle]]
    rebuilt = (r.bary[:, :, None].astype(np.float64) * tri).sum(1)
    np.testing.assert_allclose(rebuilt, r.point, atol=10 * tol)
    np.testing.assert_allclose(np.linalg.norm(r.point.astype(np.float64) - pts, axis=1), r.distance, rtol=10 * tol, atol=10 * tol)
    assert np.all(r.flags == 0) and np.all(r.node_tests > 0)


def test_shapes_bounds_and_nan():
    v, f = icosphere(2)
    mesh = ttd.Mesh(v, f)
    pts = sample_points(v, 24, 5).reshape(2, 3, 4, 3)
    r = ttd.closest_points(mesh, pts, upper_bound=0.3)
    assert r.distance.shape == (2, 3, 4) and r.point.shape == (2, 3, 4, 3)
    full = ttd.closest_points(mesh, pts)
    beyond = full.distance > 0.3
    assert beyond.any() and (~beyond).any()
    assert np.all(np.isinf(r.distance[beyond])) and np.all(r.triangle[beyond] == ttd.NO_TRIANGLE)
    assert np.all(r.flags[beyond] == ttd.POINT_ABOVE_BOUND)
    np.testing.assert_array_equal(r.distance[~beyond], full.distance[~beyond])
    bad = np.array([[0.0, 0, 0], [np.nan, 0, 0], [2, 2, 2]])
    with pytest.warns(ttd.NonFiniteInputWarning):
        r = ttd.closest_points(mesh, bad)
    assert np.isnan(r.distance[1]) and r.flags[1] == ttd.POINT_NONFINITE and np.isfinite(r.distance[[0, 2]]).all()
    with pytest.raises(ValueError):
        ttd.closest_points(mesh, np.zeros((4, 2)))
    with pytest.raises(ValueError):
        ttd.closest_points(mesh, np.zeros((1, 3)), upper_bound=-1)
    with pytest.raises(TypeError):
        ttd.closest_points(v, np.zeros((1, 3)))
    with pytest.raises(ValueError):
        ttd.closest_points(mesh, np.zeros((1, 3)), pose=np.eye(3))
    with pytest.raises(ValueError):
        ttd.closest_points(mesh, np.zeros((1, 3)), pose=2 * np.eye(4))
    assert ttd.closest_points(mesh, np.zeros((0, 3))).distance.shape == (0,)


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_signs_on_a_convex_mesh(dtype):
    v, f = icosphere(3)
    mesh = ttd.Mesh(v.astype(dtype), f)
    pts = sample_points(v, 3000, 7).astype(dtype)
    # inside a convex polyhedron: behind every face plane (outward normals)
    A, B, C = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    n = np.cross(B - A, C - A)
    height = (pts.astype(np.float64) @ n.T - (n * A).sum(1)) / np.linalg.norm(n, axis=1)
    inside = (height < 0).all(1)
    clear = np.abs(height).min(1) > 1e-3  # away from the surface's planes
    s = ttd.signed_distance(mesh, pts)
    assert s.distance.dtype == dtype and s.inside.dtype == np.bool_
    np.testing.assert_array_equal(s.inside[clear], inside[clear])
    np.testing.assert_array_equal(np.abs(s.distance), ttd.closest_points(mesh, pts).distance)
    np.testing.assert_array_equal(s.distance < 0, s.inside)
    # the flags carry the side; a closed mesh's side is the exact ray count, never unproven
    assert s.flags.dtype == np.uint8 and s.flags.shape == s.distance.shape
    np.testing.assert_array_equal((s.flags & ttd.POINT_INSIDE) != 0, s.inside)
    assert not np.any(s.flags & ttd.POINT_SIGN_UNPROVEN)
    w = ttd.winding_number(mesh, pts)
    np.testing.assert_array_equal(w.inside, s.inside)
    assert np.all(np.abs(w.winding - np.round(w.winding)) < 0.1)
    np.testing.assert_array_equal(ttd.contains(mesh, pts).inside, s.inside)


def test_pose_equals_moved_mesh():
    v, f = torus(nu=16, nv=8)
    R = np.array([[0.0, -1, 0], [1, 0, 0], [0, 0, 1]])
    t = np.array([0.5, -1.0, 2.0])
    pose = np.hstack([R, t[:, None]])
    moved = ttd.Mesh(v @ R.T + t, f)
    pts = sample_points(v @ R.T + t, 200, 9)
    a = ttd.closest_points(ttd.Mesh(v, f), pts, pose=pose)
    b = ttd.closest_points(moved, pts)
    np.testing.assert_allclose(a.distance, b.distance, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(a.point, b.point, atol=1e-12)


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_grid_equals_signed_distance(dtype):
    v, f = torus(nu=24, nv=12)
    mesh = ttd.Mesh(v.astype(dtype), f)
    origin, step, shape = np.array([-1.5, -1.5, -0.5]), 0.25, (13, 12, 5)
    g = ttd.sdf_grid(mesh, origin, step, shape)
    assert g.shape == shape and g.dtype == dtype
    o, s = origin.astype(dtype), dtype(step)
    i, j, k = np.meshgrid(*[np.arange(n, dtype=dtype) for n in shape], indexing="ij")
    pts = np.stack([o[0] + i * s, o[1] + j * s, o[2] + k * s], axis=-1)
    np.testing.assert_array_equal(g, ttd.signed_distance(mesh, pts).distance)
    assert (g < 0).any() and (g > 0).any()


def test_grid_argument_errors_are_distinct():
    v, f = torus(nu=12, nv=8)
    mesh = ttd.Mesh(v, f)
    with pytest.raises(ValueError, match="shape must be >= 0 on every axis, not -2 on axis 1"):
        ttd.sdf_grid(mesh, [0, 0, 0], 0.1, (3, -2, 4))
    with pytest.raises(TypeError, match="shape must be integers, not 2.5 on axis 0"):
        ttd.sdf_grid(mesh, [0, 0, 0], 0.1, (2.5, 3, 4))
    with pytest.raises(ValueError, match=r"origin must be 3 numbers \(x, y, z\), not 2"):
        ttd.sdf_grid(mesh, [0, 0], 0.1, (3, 3, 3))
    with pytest.raises(ValueError, match="step must be 1 number or 3, not 2"):
        ttd.sdf_grid(mesh, [0, 0, 0], [0.1, 0.1], (3, 3, 3))
    with pytest.raises(ValueError, match="shape must be 3 integers"):
        ttd.sdf_grid(mesh, [0, 0, 0], 0.1, (3, 3))
    for step in (0, -0.1, [0.1, 0.0, 0.1], [0.1, 0.1, -1]):
        with pytest.raises(ValueError, match="step must be > 0 on every axis"):
            ttd.sdf_grid(mesh, [0, 0, 0], step, (3, 3, 3))
    with pytest.raises(ValueError, match="finite"):
        ttd.sdf_grid(mesh, [0, np.nan, 0], 0.1, (3, 3, 3))


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
@pytest.mark.parametrize("shape", [(3, 300, 250), (7000, 2, 3)], ids=["rows", "slabs"])
def test_grid_in_pieces_equals_its_points(dtype, shape):
    # sdf_grid runs in pieces between Ctrl-C checks: rows of a slab when a slab is large, many
    # slabs a piece when slabs are small; every point must still be the one at origin + (i, j, k) *
    # step as the grid computes it, with the signed distance of that point.
    v, f = torus(nu=24, nv=12)
    mesh = ttd.Mesh(v.astype(dtype), f)
    origin, step = np.array([-1.3, -1.1, -0.45]), np.array([0.9 / shape[0], 2.3 / shape[1], 0.3 / shape[2]])
    g = ttd.sdf_grid(mesh, origin, step, shape)
    o, s = origin.astype(dtype), step.astype(dtype)
    i, j, k = np.meshgrid(*[np.arange(n, dtype=dtype) for n in shape], indexing="ij")
    pts = np.stack([o[0] + i * s[0], o[1] + j * s[1], o[2] + k * s[2]], axis=-1)
    np.testing.assert_array_equal(g, ttd.signed_distance(mesh, pts).distance)
    assert (g < 0).any() and (g > 0).any()
