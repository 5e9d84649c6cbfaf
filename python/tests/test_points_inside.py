# SPDX-License-Identifier: MIT
"""The one inside rule (|winding number| >= 1/2) from Python, and Mesh.orientation.

ttd.contains, WindingNumber.inside and SignedDistance.inside must be one decision, the library's
(tightened until it settles the side), equal to an independent reference: the triangles' solid
angles summed here in numpy's long double, on open meshes (a sphere with holes) at points beside
the holes, where the winding number passes 1/2 away from the surface. A closed mesh wound inward
has the inside of the outward one; Mesh.orientation says which it is."""
import numpy as np
import pytest

import ttd
from meshes import cube, icosphere, torus

LD = np.longdouble


def ref_winding(V, F, x):
    """The winding number of (V, F) about x: van Oosterom and Strackee's solid angles in long double."""
    a = V[F].astype(LD) - np.asarray(x, dtype=LD)  # (m, 3, 3)
    la = np.sqrt((a * a).sum(2))
    A, B, C = a[:, 0], a[:, 1], a[:, 2]
    det = (A * np.cross(B, C)).sum(1)
    den = la[:, 0] * la[:, 1] * la[:, 2] + (A * B).sum(1) * la[:, 2] + (A * C).sum(1) * la[:, 1] + (B * C).sum(1) * la[:, 0]
    return (2 * np.arctan2(det, den)).sum() / (4 * LD(np.pi))


def holed(v, f, every):
    """(v, f) without every `every`-th face; the removed faces too."""
    keep = np.arange(len(f)) % every != 0
    return f[keep], f[~keep]


def points_beside_holes(V, F, holes):
    """Points on each hole's normal line at 1e-2..1e-10 from where the reference's |w| is 1/2, with
    the reference's |w| - 1/2 at each."""
    pts, gaps = [], []
    for h in holes:
        a, b, c = V[h]
        centre = (a + b + c) / 3
        n = np.cross(b - a, c - a)
        n /= np.linalg.norm(n)
        hl = np.linalg.norm(b - a)

        def gap(s):
            return abs(ref_winding(V, F, centre + s * n)) - LD(0.5)

        lo, hi = -hl, hl
        glo = gap(lo)
        if (glo > 0) == (gap(hi) > 0):
            continue
        for _ in range(55):
            mid = 0.5 * (lo + hi)
            if (gap(mid) > 0) == (glo > 0):
                lo = mid
            else:
                hi = mid
        for off in (1e-2, 1e-4, 1e-6, 1e-8, 1e-10):
            for sgn in (-1, 1):
                x = centre + (lo + sgn * off) * n
                pts.append(x)
                gaps.append(abs(ref_winding(V, F, x)) - LD(0.5))
    return np.array(pts), np.array(gaps)


@pytest.mark.parametrize("reverse", [False, True])
def test_contains_and_winding_inside_are_one_rule(reverse):
    v, f = icosphere(3)
    F, holes = holed(v, f, 37)
    if reverse:
        F = F[:, ::-1].copy()
    P, gap = points_beside_holes(v, F, holes)
    assert len(P) >= 100
    m = ttd.Mesh(v, F)
    assert m.orientation == "open"
    inside = ttd.contains(m, P).inside
    wn = ttd.winding_number(m, P)
    sd = ttd.signed_distance(m, P)
    np.testing.assert_array_equal(wn.inside, inside)
    np.testing.assert_array_equal(sd.inside, inside)
    np.testing.assert_array_equal(np.abs(wn.winding) >= 0.5, inside)
    np.testing.assert_array_equal(sd.distance < 0, inside)
    unproven = (sd.flags & ttd.POINT_SIGN_UNPROVEN) != 0
    assert np.all(np.abs(gap[unproven]) < 1e-6)
    decided = (np.abs(gap) > 1e-12) & ~unproven
    assert decided.sum() > len(P) // 2
    wrong = np.flatnonzero(inside[decided] != (gap[decided] > 0))
    assert wrong.size == 0, f"{wrong.size} of {decided.sum()} points on the wrong side, e.g. {P[decided][wrong[:3]]}"
    # float32: the same rule on the float winding numbers
    mf = ttd.Mesh(v.astype(np.float32), F)
    np.testing.assert_array_equal(ttd.winding_number(mf, P).inside, ttd.contains(mf, P).inside)


def flip_one(f):
    g = f.copy()
    g[3] = g[3, ::-1]
    return g


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_orientation(dtype):
    for v, f in (icosphere(2), torus(), cube()):
        v = v.astype(dtype)
        assert ttd.Mesh(v, f).orientation == "outward"
        assert ttd.Mesh(v, f[:, ::-1].copy()).orientation == "inward"
        assert ttd.Mesh(v, flip_one(f)).orientation == "inconsistent"
        assert ttd.Mesh(v, f[1:]).orientation == "open"
    sheet = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype)
    assert ttd.Mesh(sheet, [[0, 1, 2], [0, 2, 1]]).orientation == "flat"


@pytest.mark.parametrize("which", ["icosphere", "torus"])
def test_inward_closed_mesh_has_the_outward_inside(which):
    v, f = icosphere(3) if which == "icosphere" else torus(nu=40, nv=16)
    rng = np.random.default_rng(5)
    P = np.concatenate([rng.uniform(-1.6, 1.6, (3000, 3)), v[rng.integers(0, len(v), 3000)] * rng.uniform(0.97, 1.03, (3000, 1))])
    out, inw = ttd.Mesh(v, f), ttd.Mesh(v, f[:, ::-1].copy())
    assert inw.orientation == "inward"
    a, b = ttd.signed_distance(out, P), ttd.signed_distance(inw, P)
    np.testing.assert_array_equal(a.inside, b.inside)
    np.testing.assert_array_equal(np.signbit(a.distance), np.signbit(b.distance))
    np.testing.assert_allclose(a.distance, b.distance, rtol=0, atol=1e-14)
    np.testing.assert_array_equal(ttd.contains(inw, P).inside, ttd.contains(out, P).inside)
    w_out = ttd.winding_number(out, P).winding
    np.testing.assert_array_equal(ttd.winding_number(inw, P).winding, -w_out)
    # the outward mesh's exact ray count is the reference: 1 inside, 0 outside
    np.testing.assert_array_equal(ttd.contains(inw, P).inside, w_out == 1)
    assert 0.1 < a.inside.mean() < 0.9


def test_solid_refusal_names_the_mesh():
    v, f = icosphere(2)
    closed = ttd.Mesh(v, f)
    with pytest.raises(ValueError, match="mesh a is open"):
        ttd.mesh_distance(ttd.Mesh(v, f[1:]), closed, solid=True)
    with pytest.raises(ValueError, match="mesh b is inconsistently oriented"):
        ttd.mesh_distance(closed, ttd.Mesh(v, flip_one(f)), solid=True)
    # an inward mesh is a solid like the outward one: a small sphere inside it is contained
    small = ttd.Mesh(0.2 * v, f)
    r = ttd.mesh_distance(ttd.Mesh(v, f[:, ::-1].copy()), small, solid=True)
    assert r.distance == 0 and r.flags & ttd.MeshFlag.CONTAINED
    scene = ttd.Scene()
    scene.add(ttd.Mesh(v, f[:, ::-1].copy()))
    scene.add(ttd.Mesh(v, flip_one(f)))
    scene.set_solid(0)
    with pytest.raises(ValueError, match="body 1 cannot be a solid: its mesh is inconsistent"):
        scene.set_solid(1)
