# SPDX-License-Identifier: MIT
"""An independent triangle-triangle distance in numpy, vectorised over pairs, for small
cases: the minimum over the 6 vertex-face and 9 edge-edge sub-distances, and 0 where an edge
of one triangle crosses the other (the case the 15 sub-distances miss). It follows no part of
the library's code. Degenerate triangles are handled because each sub-distance is: a
zero-area face contributes nothing and its edges (segments, possibly points) cover it."""
import numpy as np


def _dot(a, b):
    return np.einsum("...i,...i->...", a, b)


def point_segment(P, A, B):
    """Distance from points P to segments AB (arrays (..., 3))."""
    d = B - A
    dd = _dot(d, d)
    t = np.where(dd > 0, _dot(P - A, d) / np.where(dd > 0, dd, 1.0), 0.0)
    t = np.clip(t, 0.0, 1.0)
    return np.linalg.norm(P - (A + t[..., None] * d), axis=-1)


def _inside(X, A, B, C, n):
    """X (in the plane of ABC, normal n) is inside the closed triangle."""
    return (
        (_dot(np.cross(B - A, X - A), n) >= 0)
        & (_dot(np.cross(C - B, X - B), n) >= 0)
        & (_dot(np.cross(A - C, X - C), n) >= 0)
    )


def point_triangle(P, A, B, C):
    """Distance from points P to triangles ABC: the face when P projects inside, else an edge."""
    n = np.cross(B - A, C - A)
    nn = _dot(n, n)
    safe = np.where(nn > 0, nn, 1.0)
    h = _dot(P - A, n) / safe
    X = P - h[..., None] * n
    face = np.where((nn > 0) & _inside(X, A, B, C, n), np.abs(h) * np.sqrt(nn), np.inf)
    edges = np.minimum(np.minimum(point_segment(P, A, B), point_segment(P, B, C)), point_segment(P, C, A))
    return np.minimum(face, edges)


def segment_segment(P0, P1, Q0, Q1):
    """Distance between segments P0P1 and Q0Q1: the interior critical point when it lies in
    both segments, else the best of the four endpoint-segment distances (the minimum of a
    convex function on the square of parameters is inside or on an edge of it)."""
    u, v, w = P1 - P0, Q1 - Q0, P0 - Q0
    a, b, c, d, e = _dot(u, u), _dot(u, v), _dot(v, v), _dot(u, w), _dot(v, w)
    D = a * c - b * b
    ok = D > 1e-14 * a * c
    Ds = np.where(ok, D, 1.0)
    s = (b * e - c * d) / Ds
    t = (a * e - b * d) / Ds
    ok &= (s >= 0) & (s <= 1) & (t >= 0) & (t <= 1)
    interior = np.where(ok, np.linalg.norm(P0 + s[..., None] * u - Q0 - t[..., None] * v, axis=-1), np.inf)
    ends = np.minimum(
        np.minimum(point_segment(P0, Q0, Q1), point_segment(P1, Q0, Q1)),
        np.minimum(point_segment(Q0, P0, P1), point_segment(Q1, P0, P1)),
    )
    return np.minimum(interior, ends)


def segment_crosses_triangle(P0, P1, A, B, C):
    """The segment has its ends strictly on opposite sides of the triangle's plane and
    crosses the plane inside the triangle."""
    n = np.cross(B - A, C - A)
    d0, d1 = _dot(P0 - A, n), _dot(P1 - A, n)
    crosses = d0 * d1 < 0
    f = np.where(crosses, d0 / np.where(crosses, d0 - d1, 1.0), 0.0)
    X = P0 + f[..., None] * (P1 - P0)
    return crosses & _inside(X, A, B, C, n)


def triangle_distance(S, T):
    """Distances of pairs S[i], T[i] given as (n, 3, 3) float64 arrays."""
    S = np.asarray(S, np.float64).reshape(-1, 3, 3)
    T = np.asarray(T, np.float64).reshape(-1, 3, 3)
    best = np.full(len(S), np.inf)
    crossing = np.zeros(len(S), bool)
    for i in range(3):
        best = np.minimum(best, point_triangle(S[:, i], T[:, 0], T[:, 1], T[:, 2]))
        best = np.minimum(best, point_triangle(T[:, i], S[:, 0], S[:, 1], S[:, 2]))
        for j in range(3):
            best = np.minimum(best, segment_segment(S[:, i], S[:, (i + 1) % 3], T[:, j], T[:, (j + 1) % 3]))
        crossing |= segment_crosses_triangle(S[:, i], S[:, (i + 1) % 3], T[:, 0], T[:, 1], T[:, 2])
        crossing |= segment_crosses_triangle(T[:, i], T[:, (i + 1) % 3], S[:, 0], S[:, 1], S[:, 2])
    return np.where(crossing, 0.0, best)
