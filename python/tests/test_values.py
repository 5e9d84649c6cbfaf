# SPDX-License-Identifier: MIT
"""ttd.distance's values: against the numpy brute force (brute_force.py), on configurations
whose answer is known by construction, and against the invariants every result must meet
(points on their triangles, |p - q| = d, weights that rebuild the points, feature bits)."""
import numpy as np
import pytest

import brute_force
import ttd
from cases import random_pairs


def size(S, T):
    """Longest edge of each pair: the scale that the library's accuracy targets refer to."""
    S = np.asarray(S, np.float64).reshape(-1, 3, 3)
    T = np.asarray(T, np.float64).reshape(-1, 3, 3)
    edges = [np.linalg.norm(X[:, (i + 1) % 3] - X[:, i], axis=-1) for X in (S, T) for i in range(3)]
    return np.max(edges, axis=0)


# Distance targets of docs/accuracy.md, relative to max(d, size), on the random family;
# the barrier method's holds for pairs at least 0.05 apart.
TARGETS = {
    ("exact", np.float64): 1e-12,
    ("exact", np.float32): 1e-5,
    ("certified", np.float64): 1e-12,
    ("certified", np.float32): 1e-5,
    ("penalty", np.float64): 1e-10,
    ("penalty", np.float32): 2e-4,
    ("barrier", np.float64): 1e-8,
}


def test_random_pairs_match_brute_force():
    # Measured: at most 7.2e-16 absolute on 60,000 pairs of unit size (seeds 0..2); the bound
    # is the exact method's target, 1e-12 of the size.
    S, T = random_pairs(4000, seed=1)
    d = ttd.distance(S, T)
    ref = brute_force.triangle_distance(S, T)
    assert d.dtype == np.float64 and d.shape == (4000,)
    assert np.all(np.abs(d - ref) <= 1e-12 * np.maximum(ref, size(S, T)))
    # The brute force finds the crossing pairs independently: the same ones must be 0.
    assert np.count_nonzero(ref == 0) > 300
    np.testing.assert_array_equal(d == 0, ref == 0)


@pytest.mark.parametrize("method,dtype", sorted(TARGETS, key=str))
def test_methods_meet_their_targets(method, dtype):
    S, T = random_pairs(1000, seed=2, dtype=dtype)
    d = ttd.distance(S, T, method=method)
    assert d.dtype == dtype
    # The float runs are held against the distance of the float-rounded input.
    ref = brute_force.triangle_distance(S.astype(np.float64), T.astype(np.float64))
    err = np.abs(d.astype(np.float64) - ref) / np.maximum(ref, size(S, T))
    keep = ref >= 0.05 if method == "barrier" else np.ones(len(ref), bool)
    assert np.max(err[keep]) <= TARGETS[(method, dtype)]


@pytest.mark.filterwarnings("ignore::ttd.NotConvergedWarning")
def test_penalty_reference_points_lie_on_triangles():
    # The paper's ttd1 has no distance target (docs/accuracy.md); its points must still be
    # on their triangles, so its distance is never below the true one.
    S, T = random_pairs(500, seed=3)
    r = ttd.distance(S, T, method="penalty-ref", points=True)
    ref = brute_force.triangle_distance(S, T)
    assert np.all(r.distance >= ref - 1e-12)


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
@pytest.mark.parametrize("method", ["exact", "penalty", "certified"])
def test_result_invariants(dtype, method):
    S, T = random_pairs(1500, seed=4, dtype=dtype)
    r = ttd.distance(S, T, method=method, points=True)
    eps = np.finfo(dtype).eps
    tol = 64 * eps  # rounding of forming p, q and |p - q| at unit scale
    S64, T64 = S.astype(np.float64), T.astype(np.float64)
    for field in ("distance", "p", "q", "bary_p", "bary_q"):
        assert getattr(r, field).dtype == dtype
    # |p - q| is the distance.
    pq = np.linalg.norm(r.p.astype(np.float64) - r.q.astype(np.float64), axis=-1)
    assert np.all(np.abs(pq - r.distance) <= tol)
    # The weights are a convex combination that rebuilds the points.
    for w, X, pt in ((r.bary_p, S64, r.p), (r.bary_q, T64, r.q)):
        assert np.all(w >= 0)
        assert np.all(np.abs(w.sum(axis=-1) - 1) <= tol)
        assert np.all(np.abs(np.einsum("ni,nij->nj", w.astype(np.float64), X) - pt) <= tol)
    # The feature bits are the vertices with non-zero weight.
    for w, feat in ((r.bary_p, r.feature_p), (r.bary_q, r.feature_q)):
        bits = (w[:, 0] != 0) * 1 + (w[:, 1] != 0) * 2 + (w[:, 2] != 0) * 4
        np.testing.assert_array_equal(bits, feat)
    # p is as close to T as d says (so it is a closest point), and q to S.
    ref = brute_force.triangle_distance(S64, T64)
    target = TARGETS[(method, dtype)] * np.maximum(ref, size(S, T)) + tol
    for pt, X in ((r.p, T64), (r.q, S64)):
        to_other = brute_force.point_triangle(pt.astype(np.float64), X[:, 0], X[:, 1], X[:, 2])
        assert np.all(np.abs(to_other - ref) <= target)
    # INTERSECTING exactly on the pairs at distance 0 (exact methods).
    if method != "penalty":
        np.testing.assert_array_equal((r.flags & ttd.Flag.INTERSECTING) != 0, r.distance == 0)
    assert np.all(r.iterations == 0) if method == "exact" else np.any(r.iterations > 0)


def tri(*rows):
    return np.array(rows, np.float64)


def test_parallel_triangles_at_a_known_gap():
    S = tri([0, 0, 0], [4, 0, 0], [0, 4, 0])
    for gap in (2.0, 0.125, 1e-9, 3e5):
        T = tri([1, 1, gap], [2, 1, gap], [1, 2, gap])  # projects strictly inside S
        r = ttd.distance(S, T, points=True)
        assert r.distance == gap
        assert r.q[2] == gap and r.p[2] == 0 and r.p[0] == r.q[0] and r.p[1] == r.q[1]
        assert r.feature_p == 7  # inside S's face
        assert r.flags == 0


def test_vertex_above_a_face():
    S = tri([0, 0, 0], [2, 0, 0], [0, 2, 0])
    h = 0.75
    T = tri([0.5, 0.25, h], [1.5, 1.0, 3.0], [0.2, 1.7, 2.0])  # D above S, E and F higher
    r = ttd.distance(S, T, points=True)
    assert r.distance == pytest.approx(h, rel=1e-15)
    np.testing.assert_allclose(r.p, [0.5, 0.25, 0.0], atol=1e-15)
    np.testing.assert_allclose(r.q, [0.5, 0.25, h], atol=1e-15)
    np.testing.assert_allclose(r.bary_q, [1, 0, 0], atol=1e-15)
    np.testing.assert_allclose(r.bary_p, [0.625, 0.25, 0.125], atol=1e-15)  # p = A + (B-A)/8 + (C-A)/16
    assert (r.feature_p, r.feature_q) == (7, 1)


def test_skew_edges():
    # S's edge AB on the x axis, T's edge DE parallel to y at height h over x = 0.5; the other
    # vertices lean away, so the edge pair is the closest.
    h = 0.5
    S = tri([0, 0, 0], [1, 0, 0], [0.5, 0, -1])
    T = tri([0.5, -1, h], [0.5, 1, h], [0.5, 0, h + 1])
    r = ttd.distance(S, T, points=True)
    assert r.distance == pytest.approx(h, rel=1e-15)
    np.testing.assert_allclose(r.p, [0.5, 0, 0], atol=1e-15)
    np.testing.assert_allclose(r.q, [0.5, 0, h], atol=1e-15)
    assert (r.feature_p, r.feature_q) == (3, 3)


def test_crossing_triangles_have_distance_zero():
    S = tri([0, 0, 0], [2, 0, 0], [0, 2, 0])
    T = tri([0.5, 0.5, -1], [0.5, 0.5, 1], [1.5, 1.5, 0.3])  # pierces S's face
    for dtype in (np.float64, np.float32):
        r = ttd.distance(S.astype(dtype), T.astype(dtype), points=True)
        assert r.distance == 0
        assert r.flags & ttd.Flag.INTERSECTING
        np.testing.assert_allclose(r.p, r.q, atol=4 * np.finfo(dtype).eps)


def test_degenerate_triangles_are_flagged_and_measured():
    S = tri([0, 0, 0], [1, 0, 0], [2, 0, 0])  # a segment
    T = tri([0.5, 1, 0], [1.5, 1, 0], [1, 3, 0])
    r = ttd.distance(S, T, points=True)
    assert r.flags & ttd.Flag.DEGENERATE_S and not r.flags & ttd.Flag.DEGENERATE_T
    assert r.distance == pytest.approx(1.0, rel=1e-15)
    assert r.distance == pytest.approx(brute_force.triangle_distance(S, T)[0], rel=1e-15)


def test_float32_is_computed_in_float32():
    S, T = random_pairs(2000, seed=5)
    d32 = ttd.distance(S.astype(np.float32), T.astype(np.float32))
    d64 = ttd.distance(S, T)
    assert d32.dtype == np.float32
    # Close to the double result (input rounding and the float target), but not a double
    # result rounded afterwards: a float32 computation differs in the last bits somewhere.
    assert np.all(np.abs(d32 - d64) <= 1e-5 * np.maximum(d64, size(S, T)))
    assert np.any(d32 != d64.astype(np.float32))
