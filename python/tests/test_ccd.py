# SPDX-License-Identifier: MIT
"""ttd.ccd_vertex_face / ccd_edge_edge / ccd_triangles (docs/ccd.md): known motions, the result
type, input errors, threads, and min_separation against a sampled numpy distance (an independent
point-triangle distance: the plane when the projection is inside, else the three edges)."""
import warnings

import numpy as np
import pytest

import ttd

TRI = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])


def test_vertex_face_hit_and_miss():
    v0 = np.array([[0.2, 0.2, 1.0], [0.6, 0.6, 1.0]])
    v1 = np.array([[0.2, 0.2, -1.0], [0.6, 0.6, -1.0]])
    f = np.stack([TRI, TRI])
    r = ttd.ccd_vertex_face(v0, f, v1, f)
    assert isinstance(r, ttd.CCDResult) and isinstance(r, tuple)
    assert r._fields[:2] == ("hit", "toi")
    assert r.hit.tolist() == [True, False]
    assert 0.5 - 1e-6 <= r.toi[0] <= 0.5
    assert r.toi[1] == np.inf
    # min_separation: (0.6, 0.6) is 0.2 / sqrt(2) = 0.1414 from the hypotenuse.
    assert not ttd.ccd_vertex_face(v0[1], TRI, v1[1], TRI, min_separation=0.14).hit[0]
    assert ttd.ccd_vertex_face(v0[1], TRI, v1[1], TRI, min_separation=0.15).hit[0]


def test_edge_edge_and_triangles():
    ea0 = np.array([[-1.0, 0, 1], [1, 0, 1]])
    eb0 = np.array([[0.0, -1, 0], [0, 1, 0]])
    ea1 = ea0 - [0, 0, 2]
    r = ttd.ccd_edge_edge(ea0, eb0, ea1, eb0)
    assert r.hit[0] and 0.5 - 1e-6 <= r.toi[0] <= 0.5
    # A triangle falling flat onto another, vertex 0 first (it hangs lower).
    a0 = TRI + [0.1, 0.1, 1.0]
    a0[0, 2] = 0.5
    a1 = a0 - [0, 0, 2]
    tb = TRI * 3 - [1, 1, 0]
    r = ttd.ccd_triangles(a0, tb, a1, tb)
    assert r.hit[0] and 0.25 - 1e-6 <= r.toi[0] <= 0.25
    assert r.sub[0] == 0  # vertex 0 of a against b


def test_errors_and_nonfinite():
    with pytest.raises(ValueError):
        ttd.ccd_vertex_face(np.zeros((2, 3)), np.zeros((3, 3, 3)), np.zeros((2, 3)), np.zeros((2, 3, 3)))
    with pytest.raises(ValueError):
        ttd.ccd_edge_edge(np.zeros((1, 3, 3)), np.zeros((1, 2, 3)), np.zeros((1, 2, 3)), np.zeros((1, 2, 3)))
    with pytest.raises(ValueError, match=r"\(got -1\.0\)"):  # the value itself, not a format's letters
        ttd.ccd_vertex_face([0, 0, 1], TRI, [0, 0, -1], TRI, min_separation=-1.0)
    with pytest.raises(ValueError):
        ttd.ccd_vertex_face([0, 0, 1], TRI, [0, 0, -1], TRI, min_separation=float("nan"))
    with pytest.raises(ValueError):
        ttd.ccd_vertex_face(np.zeros((0, 3)), np.zeros((0, 3, 3)), np.zeros((0, 3)), np.zeros((0, 3, 3)))
    with pytest.raises(TypeError):
        ttd.ccd_vertex_face(["a", "b", "c"], TRI, [0, 0, -1], TRI)
    v1 = np.array([[0.2, 0.2, -1.0], [np.nan, 0.2, -1.0]])
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        r = ttd.ccd_vertex_face([[0.2, 0.2, 1.0]] * 2, [TRI, TRI], v1, [TRI, TRI])
    assert any(issubclass(x.category, ttd.NonFiniteInputWarning) for x in w)
    assert r.hit[0] and not r.hit[1] and np.isnan(r.toi[1]) and r.flags[1] == 2


def _point_triangle(p, a, b, c):
    """Distance from points p (m, 3) to triangles (m, 3) each: plane or edges."""
    n = np.cross(b - a, c - a)
    nn = np.einsum("ij,ij->i", n, n)
    out = np.full(len(p), np.inf)
    ok = nn > 0
    d = np.einsum("ij,ij->i", p - a, n)
    q = p - (d / np.where(ok, nn, 1))[:, None] * n
    inside = ok
    for u, v in ((a, b), (b, c), (c, a)):
        inside = inside & (np.einsum("ij,ij->i", np.cross(v - u, q - u), n) >= 0)
    out = np.where(inside, np.abs(d) / np.sqrt(np.where(ok, nn, 1)), out)
    for u, v in ((a, b), (b, c), (c, a)):
        e = v - u
        ee = np.einsum("ij,ij->i", e, e)
        s = np.clip(np.einsum("ij,ij->i", p - u, e) / np.where(ee > 0, ee, 1), 0, 1)
        out = np.minimum(out, np.linalg.norm(p - (u + s[:, None] * e), axis=1))
    return out


def test_min_separation_against_sampling():
    rng = np.random.default_rng(7)
    n = 300
    v0 = rng.uniform(-1, 1, (n, 3))
    v1 = v0 + rng.uniform(-1, 1, (n, 3))
    f0 = rng.uniform(-1, 1, (n, 3, 3))
    f1 = f0 + rng.uniform(-0.5, 0.5, (n, 3, 3))
    delta = 0.2
    r = ttd.ccd_vertex_face(v0, f0, v1, f1, min_separation=delta, threads=1)
    ts = np.linspace(0, 1, 2001)
    for i in range(n):
        p = v0[i] + ts[:, None] * (v1[i] - v0[i])
        f = f0[i] + ts[:, None, None] * (f1[i] - f0[i])
        d = _point_triangle(p, f[:, 0], f[:, 1], f[:, 2])
        below = np.nonzero(d <= delta - 1e-9)[0]
        if len(below):
            assert r.hit[i], i
            assert r.toi[i] <= ts[below[0]], i
        if r.hit[i] and len(below):
            # No earlier than a sample step before the first time the samples see.
            assert r.toi[i] >= ts[below[0]] - 2 * (ts[1] - ts[0]) - 1e-6 or d[: below[0]].min() <= delta + 1e-3, i
        if not r.hit[i]:
            assert d.min() > delta - 1e-9, i


def test_threads_do_not_change_results():
    rng = np.random.default_rng(3)
    n = 2000
    a0 = rng.uniform(-1, 1, (n, 2, 3))
    b0 = rng.uniform(-1, 1, (n, 2, 3))
    a1 = a0 + rng.uniform(-1, 1, (n, 2, 3))
    b1 = b0 + rng.uniform(-1, 1, (n, 2, 3))
    r1 = ttd.ccd_edge_edge(a0, b0, a1, b1, threads=1)
    r2 = ttd.ccd_edge_edge(a0, b0, a1, b1, threads=2)
    for x, y in zip(r1, r2):
        np.testing.assert_array_equal(x, y)
    assert 0 < r1.hit.sum() < n
