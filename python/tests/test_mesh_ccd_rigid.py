# SPDX-License-Identifier: MIT
"""ttd.mesh_ccd_rigid and ttd.rigid_pose_at (docs/ccd.md, section 13): pure translations against
ttd.mesh_ccd on the world vertices (linear vertex paths); rotations against the exact mesh
distance (ttd.mesh_distance) sampled along the motion built here in numpy, with the most the
distance can change between samples; the motion against Rodrigues' formula written here; float32;
touching at t = 0 and t = 1; the step bound; input errors."""
import math

import numpy as np
import pytest

import ttd
from meshes import icosphere, torus, cube, rotation


def rot(u, a):
    u = np.asarray(u, float) / np.linalg.norm(u)
    K = np.array([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
    return np.eye(3) + math.sin(a) * K + (1 - math.cos(a)) * K @ K


def pose_of(R, t):
    P = np.zeros((3, 4))
    P[:, :3] = R
    P[:, 3] = t
    return P


class Motion:
    """R(t) = Rot(u, t theta) R0, T(t) = (1 - t) T0 + t T1: the documented motion, written here."""

    def __init__(self, R0, u, theta, T0, T1):
        self.R0, self.u, self.theta = np.asarray(R0, float), u, theta
        self.T0, self.T1 = np.asarray(T0, float), np.asarray(T1, float)

    def at(self, t):
        return pose_of(rot(self.u, t * self.theta) @ self.R0, (1 - t) * self.T0 + t * self.T1)

    def speed(self, radius):
        return np.linalg.norm(self.T1 - self.T0) + self.theta * radius


def relative(ma, mb, t):
    A, B = ma.at(t), mb.at(t)
    Ra, Rb = A[:, :3], B[:, :3]
    return pose_of(Ra.T @ Rb, Ra.T @ (B[:, 3] - A[:, 3]))


def random_motion(rng, theta, T0, T1):
    return Motion(rotation(rng.standard_normal(4)), rng.standard_normal(3), theta, T0, T1)


def test_motion_matches_rodrigues():
    rng = np.random.default_rng(5)
    for _ in range(50):
        m = random_motion(rng, math.pi * rng.random(), rng.standard_normal(3), rng.standard_normal(3))
        p0, p1 = m.at(0.0), m.at(1.0)
        assert np.array_equal(ttd.rigid_pose_at(p0, p1, 0.0), p0)
        for t in (0.25, 0.5, 0.9, 1.0):
            assert np.allclose(ttd.rigid_pose_at(p0, p1, t), m.at(t), atol=1e-12, rtol=0)
    # A half turn about x, given as diag(1, -1, -1): the axis is +x (the sign rule).
    half = ttd.rigid_pose_at(np.eye(4), np.diag([1.0, -1.0, -1.0, 1.0]), 0.5)
    assert np.allclose(half[:, :3], rot([1, 0, 0], math.pi / 2), atol=1e-15)


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_rotations_against_sampled_distance(dtype):
    rng = np.random.default_rng(11)
    vt, ft = torus(1.0, 0.3, 14, 8)
    vb, fb = icosphere(1)
    vb = 0.3 * vb + [0.5, 0, 0]
    a, b = ttd.Mesh(vt.astype(dtype), ft), ttd.Mesh(vb.astype(dtype), fb)
    ra, rb = np.linalg.norm(vt, axis=1).max(), np.linalg.norm(vb, axis=1).max()
    n = 256
    hits = 0
    for case in range(16):
        ma = random_motion(rng, math.pi * rng.random(), [0, 0, 0], 0.2 * rng.standard_normal(3))
        d, s = rng.standard_normal(3), rng.standard_normal(3)
        d, s = d / np.linalg.norm(d), s / np.linalg.norm(s)
        off = 2.5 * rng.random()
        mb = random_motion(rng, math.pi * rng.random(), 3 * d + off * s, -d + off * s)
        delta = 0.05 if case % 4 == 3 else 0.0
        r = ttd.mesh_ccd_rigid(a, ma.at(0), ma.at(1), b, mb.at(0), mb.at(1), min_separation=delta)
        assert isinstance(r, ttd.RigidCCDResult) and r.flags == 0
        S = ra + rb + np.linalg.norm(ma.T1) + max(np.linalg.norm(mb.T0), np.linalg.norm(mb.T1))
        e = S * (2.0**-36 if dtype == np.float64 else 2.0**-15)
        V = (ma.speed(ra) + mb.speed(rb)) * 1.001
        ts = np.linspace(0, 1, n + 1)
        dist = np.array([ttd.mesh_distance(a, b, relative(ma, mb, t)).distance for t in ts])
        before = ts < r.toi if r.hit else np.ones(n + 1, bool)
        assert np.all(dist[before] > delta - e), f"case {case}: a sampled contact before toi {r.toi}"
        if r.hit:
            hits += 1
            assert 0 <= r.toi <= 1 and r.tri_a >= 0 and r.tri_b >= 0
            at = ttd.mesh_distance(a, b, relative(ma, mb, r.toi)).distance
            assert at <= delta + r.tolerance + e
            lower = (dist[:-1] + dist[1:] - V / n) / 2 > delta + r.tolerance + e
            lead = n if lower.all() else int(np.argmin(lower))
            assert r.toi >= ts[lead], f"case {case}: toi {r.toi} inside the proved-apart start"
        else:
            assert math.isinf(r.toi) and r.tri_a == -1
    assert 3 <= hits <= 13


def test_translation_matches_deforming():
    rng = np.random.default_rng(3)
    va, fa = icosphere(1)
    vb, fb = torus(0.8, 0.25, 12, 6)
    hits = 0
    for case in range(12):
        R = [rotation(rng.standard_normal(4)) for _ in range(2)]
        Ta = [0.1 * rng.standard_normal(3), [0.5, 0, 0] + 0.3 * rng.standard_normal(3)]
        b0 = np.array([2.6 + 0.3 * rng.random(), 0.5 * rng.standard_normal(), 0.5 * rng.standard_normal()])
        Tb = [b0, b0 - [0.5 + 0.5 * rng.random(), 0, 0] + 0.3 * rng.standard_normal(3)]
        delta = 0.02 if case % 3 == 2 else 0.0
        pa = [pose_of(R[0], t) for t in Ta]
        pb = [pose_of(R[1], t) for t in Tb]
        r = ttd.mesh_ccd_rigid(ttd.Mesh(va, fa), pa[0], pa[1], ttd.Mesh(vb, fb), pb[0], pb[1], min_separation=delta)
        wa = [va @ R[0].T + t for t in Ta]
        wb = [vb @ R[1].T + t for t in Tb]
        ref = ttd.mesh_ccd(ttd.Mesh(wa[0], fa), wa[1], ttd.Mesh(wb[0], fb), wb[1], min_separation=delta)
        assert r.hit == math.isfinite(ref.toi), f"case {case}: rigid {r.toi}, deforming {ref.toi}"
        if r.hit:
            hits += 1
            assert r.toi <= ref.toi + 1e-12
            # At toi the bodies are within the tolerance (posed exactly as the library poses them).
            P = [ttd.rigid_pose_at(pa[0], pa[1], r.toi), ttd.rigid_pose_at(pb[0], pb[1], r.toi)]
            got = ttd.mesh_distance(ttd.Mesh(va, fa), ttd.Mesh(vb, fb), pose_a=P[0], pose_b=P[1]).distance
            assert got <= delta + r.tolerance + 1e-12
    assert 3 <= hits <= 10


def test_degenerate_motions():
    v, f = cube()
    c = ttd.Mesh(v, f)
    I = np.eye(4)
    at = lambda x: pose_of(np.eye(3), [x, 0, 0])
    r = ttd.mesh_ccd_rigid(c, I, I, c, at(1.5), at(1.5))  # no motion, apart
    assert not r.hit and math.isinf(r.toi) and r.steps == 1
    r = ttd.mesh_ccd_rigid(c, I, I, c, at(1.0), at(3.0))  # touching at t = 0
    assert r.hit and r.toi == 0 and r.distance == 0
    r = ttd.mesh_ccd_rigid(c, I, I, c, at(3.0), at(1.0))  # touching at t = 1
    assert r.hit and 1 - r.tolerance <= r.toi <= 1
    r = ttd.mesh_ccd_rigid(c, I, I, c, at(3.0), at(1.0 + 1e-6))  # stopping short
    assert not r.hit
    # float32 alike
    c32 = ttd.Mesh(v.astype(np.float32), f)
    r = ttd.mesh_ccd_rigid(c32, I, I, c32, at(3.0), at(1.0))
    assert r.hit and 1 - r.tolerance <= r.toi <= 1
    # Sliding at a gap of min_separation + 3 tolerances: the step bound, a conservative hit.
    up = lambda x: pose_of(np.eye(3), [x, 0, 1.25])
    tol = ttd.mesh_ccd_rigid(c, I, I, c, up(-0.5), up(0.5)).tolerance
    r = ttd.mesh_ccd_rigid(c, I, I, c, up(-0.5), up(0.5), min_separation=0.25 - 3 * tol)
    assert r.hit and r.flags == 1 and 0 < r.toi < 1 and r.tri_a == -1 and math.isinf(r.distance)


def test_errors():
    v, f = cube()
    c, c32 = ttd.Mesh(v, f), ttd.Mesh(v.astype(np.float32), f)
    I = np.eye(4)
    with pytest.raises(ValueError):
        ttd.mesh_ccd_rigid(c, I, I, c, I, I, min_separation=-1)
    with pytest.raises(ValueError):
        ttd.mesh_ccd_rigid(c, I, I, c, I, I, min_separation=math.nan)
    with pytest.raises(TypeError):
        ttd.mesh_ccd_rigid(c, I, I, c, I, I, min_separation="0")
    bad = I.copy()
    bad[0, 1] = math.nan
    with pytest.raises(ValueError, match="NaN"):
        ttd.mesh_ccd_rigid(c, I, bad, c, I, I)
    with pytest.raises(ValueError, match="rotation"):
        ttd.mesh_ccd_rigid(c, I, I, c, I, 2 * I[:3])
    with pytest.raises(ValueError, match="rotation"):
        ttd.mesh_ccd_rigid(c, I, I, c, np.diag([-1.0, 1, 1, 1]), I)
    with pytest.raises(ValueError):
        ttd.mesh_ccd_rigid(c, I, I, c32, I, I)
    with pytest.raises(TypeError):
        ttd.mesh_ccd_rigid(v, I, I, c, I, I)
    with pytest.raises(ValueError):
        ttd.mesh_ccd_rigid(c, I, I, c, I, np.stack([I, I]))
    with pytest.raises(ValueError, match=r"\(got 1\.5\)"):
        ttd.rigid_pose_at(I, I, 1.5)
    # A batch of poses (K, 3, 4) is refused: rigid_pose_at used its first pose silently (the
    # second pose's turn below was dropped; checked with the old code).
    turn = np.eye(4)
    turn[:3, :3] = rot([0, 0, 1], 1.0)
    for p0, p1 in ((np.stack([I, turn])[:, :3], I), (I, np.stack([I, turn])[:, :3])):
        with pytest.raises(ValueError, match="one pose"):
            ttd.rigid_pose_at(p0, p1, 0.5)
