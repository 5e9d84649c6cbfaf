# SPDX-License-Identifier: MIT
"""ttd.weld, load_mesh(weld=) and Mesh.from_file(weld=): against an O(n^2) reference (every pair
within the tolerance joined, classes numbered by their first vertex, the lexicographically
smallest member kept) and by construction: a binary STL of a closed icosphere and torus whose
facets write their corners with last-bit differences is refused by the solid mode as read and
accepted once welded."""
import struct

import numpy as np
import pytest

import ttd
from meshes import icosphere, torus


def reference_weld(v, f, tol):
    n = len(v)
    parent = list(range(n))

    def root(x):
        while parent[x] != x:
            x = parent[x]
        return x

    for i in range(n):
        d = v[i + 1:] - v[i]
        if tol == 0:
            near = np.all(d == 0, axis=1)
        else:
            with np.errstate(over="ignore", invalid="ignore"):
                s = d / tol
                near = np.all(np.abs(d) <= tol, axis=1) & ((s * s).sum(axis=1) <= 1.0)
        for j in np.nonzero(near)[0]:
            a, b = root(i), root(i + 1 + int(j))
            parent[max(a, b)] = min(a, b)
    roots = [root(i) for i in range(n)]
    new = {}
    for i in range(n):
        new.setdefault(roots[i], len(new))
    index = np.array([new[r] for r in roots], dtype=np.uint32)
    out = np.empty((len(new), 3), dtype=v.dtype)
    for c in range(len(new)):
        members = v[index == c]
        best = min(members.tolist())  # lexicographic
        out[c] = np.array(best, dtype=v.dtype) + 0.0
    g = index[f]
    keep = (g[:, 0] != g[:, 1]) & (g[:, 1] != g[:, 2]) & (g[:, 0] != g[:, 2])
    return out, g[keep], index


def clustered(rng, n, scale, spread, m):
    centres = rng.uniform(-scale, scale, size=(n // 4 + 1, 3))
    centres[rng.random(centres.shape) < 0.1] = 0.0
    v = centres[rng.integers(0, len(centres), n)].copy()
    kind = rng.integers(0, 3, n)
    v[kind == 1] += rng.uniform(-spread, spread, size=(int((kind == 1).sum()), 3))
    ulp = np.spacing(np.abs(v)) * rng.integers(-3, 4, size=v.shape)
    v[kind == 2] += ulp[kind == 2]
    v[(v == 0) & (rng.random(v.shape) < 0.5)] = -0.0
    return v, rng.integers(0, n, size=(m, 3))


@pytest.mark.parametrize("scale,spread,tols", [(1.0, 1e-3, [1e-3, 5e-4, 0.0]), (1.0, 0.3, [0.1, 3.0]),
                                               (1e10, 1e-5, [1e-6, 1e-5]), (1e-200, 1e-203, [1e-203, 0.0])])
def test_weld_against_reference(scale, spread, tols):
    rng = np.random.default_rng(7)
    for _ in range(3):
        v, f = clustered(rng, 150, scale, spread, 200)
        for tol in tols:
            vo, fo, idx = ttd.weld(v, f, tol, return_index=True)
            rv, rf, ri = reference_weld(v, f, tol)
            np.testing.assert_array_equal(idx, ri)
            assert vo.tobytes() == rv.tobytes()  # bit for bit, zeros as +0
            np.testing.assert_array_equal(fo, rf)
            assert vo.dtype == np.float64 and fo.dtype == np.uint32


def test_weld_float32_and_signed_zero():
    v = np.array([[-0.0, 0, -0.0], [0, -0.0, 0], [1, 0, 0], [0, 1, 0]], dtype=np.float32)
    f = np.array([[0, 2, 3], [1, 2, 3], [0, 1, 2]])
    vo, fo = ttd.weld(v, f, 0)
    assert vo.dtype == np.float32 and len(vo) == 3 and len(fo) == 2  # (0 1 2) collapsed
    assert not np.signbit(vo).any()
    rng = np.random.default_rng(3)
    v, f = clustered(rng, 120, 1.0, 1e-3, 100)
    v32 = v.astype(np.float32)
    vo, fo, idx = ttd.weld(v32, f, 1e-3, return_index=True)
    rv, rf, ri = reference_weld(v32.astype(np.float64), f, float(np.float32(1e-3)))
    np.testing.assert_array_equal(idx, ri)
    np.testing.assert_array_equal(vo.astype(np.float64), rv)


def test_weld_errors():
    v = np.eye(3)
    f = np.array([[0, 1, 2]])
    for bad in (-1.0, float("nan"), float("inf")):
        with pytest.raises(ValueError, match="tolerance"):
            ttd.weld(v, f, bad)
    with pytest.raises(IndexError):
        ttd.weld(v, np.array([[0, 1, 3]]), 0.1)
    with pytest.raises(ValueError, match="not finite"):
        ttd.weld(np.array([[0, 0, np.nan], [1, 0, 0], [0, 1, 0]]), f, 0.1)
    with pytest.raises(TypeError):
        ttd.weld(v, f, "0.1")


def soup_stl(path, v, f, rng):
    """A binary STL of (v, f), each facet's corners moved by up to 2 ulps (float32 in the file)."""
    corners = v[f].astype(np.float32)
    steps = rng.integers(-2, 3, size=corners.shape)
    for k in range(1, 3):
        up = steps >= k
        down = steps <= -k
        corners[up] = np.nextafter(corners[up], np.float32(np.inf))
        corners[down] = np.nextafter(corners[down], np.float32(-np.inf))
    with open(path, "wb") as out:
        out.write(b"\0" * 80 + struct.pack("<I", len(f)))
        for tri in corners:
            out.write(b"\0" * 12 + tri.astype("<f4").tobytes() + b"\0\0")


@pytest.mark.parametrize("shape", ["icosphere", "torus"])
def test_stl_soup_becomes_closed(tmp_path, shape):
    v, f = icosphere(3) if shape == "icosphere" else torus(1.0, 0.35, 40, 20)
    path = tmp_path / "soup.stl"
    soup_stl(path, np.asarray(v), np.asarray(f), np.random.default_rng(1))
    inner = ttd.Mesh(np.asarray(v) * 0.01 + (np.array([1.0, 0, 0]) if shape == "torus" else 0.0), f)
    loose = ttd.Mesh.from_file(path)
    with pytest.raises(ValueError, match="closed"):
        ttd.mesh_distance(loose, inner, solid=True)
    closed = ttd.Mesh.from_file(path, weld=1e-5)
    assert closed.vertex_count == len(v) and closed.triangle_count == len(f)
    r = ttd.mesh_distance(closed, inner, solid=True)
    assert r.distance == 0  # the small copy lies inside the solid
    vw, fw = ttd.load_mesh(path, weld=1e-5, precision="float32")
    assert vw.dtype == np.float32 and len(vw) == len(v) and len(fw) == len(f)
    with pytest.raises(ValueError, match="weld"):
        ttd.load_mesh(path, weld=-1)
    with pytest.raises(ValueError, match="collapses"):
        ttd.load_mesh(path, weld=100.0)
