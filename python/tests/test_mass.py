# SPDX-License-Identifier: MIT
"""ttd.mass_properties (docs/mass-properties.md; issue 32, item 5) against exact rational
arithmetic: every double is a dyadic rational, so the volume, first and second moments of the
mesh's vertices as given are summed exactly here with fractions.Fraction (the tetrahedra from the
origin, a different grouping from the library's, whose reference point is the box's centre), and
the library's answer must agree to a few roundings of the quantities' size. On random
tetrahedra, boxes turned by random rotations far from the origin, and random star-shaped
polyhedra (icosphere topology, random radii), in float64 and float32; a mesh wound inward gives
the negated volume and the same mass, centre and inertia; density scales mass and inertia;
refusals of open meshes, bad densities and non-meshes. Two SolidWorks parts' STL files
(tests/data/cad) against the same exact sums (their published figures: tests/test_mass.c)."""

import math
import pathlib
from fractions import Fraction

import numpy as np
import pytest

import ttd
from meshes import cube, icosphere

DTYPES = [np.float64, np.float32]


def exact(v, f, density):
    """Volume, centre, inertia about the centre (as Fractions) of closed mesh (v, f)."""
    V = Fraction(0)
    S = [Fraction(0)] * 3
    C = [[Fraction(0)] * 3 for _ in range(3)]
    P = [[Fraction(float(x)) for x in row] for row in v]
    for t in f:
        a, b, c = (P[int(k)] for k in t)
        det = (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
               + a[2] * (b[0] * c[1] - b[1] * c[0]))
        vt = det / 6
        V += vt
        s = [a[r] + b[r] + c[r] for r in range(3)]
        for r in range(3):
            S[r] += vt * s[r] / 4
            for q in range(3):
                C[r][q] += vt / 20 * (a[r] * a[q] + b[r] * b[q] + c[r] * c[q] + s[r] * s[q])
    g = [S[r] / V for r in range(3)]
    Cc = [[C[r][q] - V * g[r] * g[q] for q in range(3)] for r in range(3)]
    sign = 1 if V > 0 else -1
    tr = Cc[0][0] + Cc[1][1] + Cc[2][2]
    inertia = [[density * sign * ((tr if r == q else 0) - Cc[r][q]) for q in range(3)] for r in range(3)]
    return V, g, inertia


def check(mesh, v, f, density, dtype, what):
    p = ttd.mass_properties(mesh, density)
    vv = np.asarray(v, dtype=dtype)  # the vertices the library holds
    V, g, inertia = exact(vv, f, density)
    size = float(np.max(np.abs(vv - vv.mean(axis=0)))) * 2
    far = float(np.max(np.abs(vv)))
    eps = 64 * np.finfo(np.float64).eps  # the library computes in double either way
    assert abs(p.volume - float(V)) <= eps * size ** 3, (what, p.volume, float(V))
    assert abs(p.mass - density * abs(float(V))) <= eps * density * size ** 3, what
    for r in range(3):
        assert abs(p.center[r] - float(g[r])) <= eps * far, (what, r, p.center[r], float(g[r]))
    big = max(abs(float(x)) for row in inertia for x in row)
    for r in range(3):
        for q in range(3):
            assert abs(p.inertia[r, q] - float(inertia[r][q])) <= eps * big * (far / size), \
                (what, r, q, p.inertia[r, q], float(inertia[r][q]))
    return p


def rotation(rng):
    q = rng.normal(size=4)
    w, x, y, z = q / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


@pytest.mark.parametrize("dtype", DTYPES, ids=["float64", "float32"])
def test_exact_rational(dtype):
    rng = np.random.default_rng(32)
    tet_faces = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], dtype=np.uint32)
    for k in range(20):  # random tetrahedra, wound outward
        v = rng.normal(size=(4, 3)) * 10.0 ** rng.uniform(-3, 3) + rng.normal(size=3) * 10.0 ** rng.uniform(-2, 4)
        if np.linalg.det(np.array([v[1] - v[0], v[2] - v[0], v[3] - v[0]])) < 0:
            v[[1, 2]] = v[[2, 1]]
        check(ttd.Mesh(v, tet_faces, precision=dtype), v, tet_faces, 1.0, dtype, f"tetrahedron {k}")
    cv, cf = cube()
    for k in range(6):  # boxes turned and moved far
        v = (cv - 0.5) * rng.uniform(0.1, 5, size=3) @ rotation(rng).T + rng.normal(size=3) * 10.0 ** rng.uniform(0, 5)
        check(ttd.Mesh(v, cf, precision=dtype), v, cf, 2.5, dtype, f"box {k}")
    sv, sf = icosphere(2)
    for k in range(3):  # star-shaped: random radii
        v = sv * rng.uniform(0.5, 1.5, size=(len(sv), 1)) + rng.normal(size=3)
        check(ttd.Mesh(v, sf, precision=dtype), v, sf, 0.7, dtype, f"star {k}")


CAD = pathlib.Path(__file__).resolve().parents[2] / "tests" / "data" / "cad"


@pytest.mark.parametrize("dtype", DTYPES, ids=["float64", "float32"])
def test_cad_parts_exact(dtype):
    # STL corners are floats, so both precisions hold the file's vertices; welded as tests/test_mass.c does
    precision = "float64" if dtype is np.float64 else "float32"
    for name, density in (("angle_block.STL", 0.036127), ("idler_riser.STL", 0.09754366)):
        v, f = ttd.load_mesh(CAD / name, precision=precision, weld=1e-9)
        assert v.dtype == dtype and len(f) == {"angle_block.STL": 704, "idler_riser.STL": 1572}[name]
        p = check(ttd.Mesh(v, f, precision=dtype), v, f, density, dtype, name)
        assert p.volume > 0  # the exporter winds outward


@pytest.mark.parametrize("dtype", DTYPES, ids=["float64", "float32"])
def test_box_orientation_density(dtype):
    v, f = cube()
    v = v * np.array([3.0, 1.0, 0.5])
    p = ttd.mass_properties(ttd.Mesh(v, f, precision=dtype))
    assert isinstance(p, ttd.MassProperties) and p._fields == ("mass", "volume", "area", "center", "inertia")
    assert p.volume == pytest.approx(1.5, rel=1e-14) and p.mass == pytest.approx(1.5, rel=1e-14)
    assert p.area == pytest.approx(2 * (3 + 1.5 + 0.5), rel=1e-14)
    np.testing.assert_allclose(p.center, [1.5, 0.5, 0.25], rtol=1e-14)
    want = 1.5 / 12 * np.diag([1 + 0.25, 9 + 0.25, 9 + 1])
    np.testing.assert_allclose(p.inertia, want, rtol=1e-13, atol=1e-14)
    inward = ttd.mass_properties(ttd.Mesh(v, f[:, ::-1].copy(), precision=dtype), density=2.0)
    assert inward.volume == pytest.approx(-1.5, rel=1e-14) and inward.mass == pytest.approx(3.0, rel=1e-14)
    np.testing.assert_allclose(inward.center, p.center, rtol=1e-14)
    np.testing.assert_allclose(inward.inertia, 2 * p.inertia, rtol=1e-13, atol=1e-14)


def test_sphere_converges():
    errs = []
    for level in (2, 3, 4, 5):
        v, f = icosphere(level)
        p = ttd.mass_properties(ttd.Mesh(v, f))
        errs.append(4 * math.pi / 3 - p.volume)
        assert 0 < errs[-1]  # inscribed
        np.testing.assert_allclose(np.diag(p.inertia), p.inertia.trace() / 3, rtol=1e-3)
    assert all(b < a / 3 for a, b in zip(errs, errs[1:]))


def test_refusals():
    v, f = cube()
    m = ttd.Mesh(v, f)
    for bad in (0.0, -1.0, math.nan, math.inf):
        with pytest.raises(ValueError, match="density"):
            ttd.mass_properties(m, bad)
    with pytest.raises(TypeError):
        ttd.mass_properties(m, "1")
    with pytest.raises(TypeError, match="ttd.Mesh"):
        ttd.mass_properties(v)
    with pytest.raises(ValueError, match="not closed"):
        ttd.mass_properties(ttd.Mesh(v, f[1:]))
    flipped = f.copy()
    flipped[0] = flipped[0, ::-1]
    with pytest.raises(ValueError, match="not closed"):
        ttd.mass_properties(ttd.Mesh(v, flipped))
