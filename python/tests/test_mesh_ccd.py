# SPDX-License-Identifier: MIT
"""ttd.mesh_ccd / ttd.mesh_self_ccd (docs/ccd.md, section 10) against a brute force written here
in numpy: every primitive pair of every triangle pair (no boxes), run through ttd.ccd_vertex_face
and ttd.ccd_edge_edge, the earliest toi and the pairs within 2**-52 of it; the result type,
float32 meshes, threads and input errors."""
import numpy as np
import pytest

import ttd

TOL = 2.0**-52


def grid(n, z=0.0):
    i, j = np.meshgrid(np.arange(n + 1), np.arange(n + 1))
    v = np.stack([i.ravel() / n, j.ravel() / n, np.full(i.size, z)], axis=1)
    f = []
    for y in range(n):
        for x in range(n):
            a = y * (n + 1) + x
            f += [[a, a + 1, a + n + 2], [a, a + n + 2, a + n + 1]]
    return v, np.array(f, dtype=np.uint32)


def edges(t):
    return [tuple(sorted((int(t[k]), int(t[(k + 1) % 3])))) for k in range(3)]


def brute(keys, xa0, xa1, fa, xb0, xb1, fb, delta):
    """keys: set of (kind, a0, a1, b0, b1) as the library names them."""
    keys = sorted(keys)
    vf = [k for k in keys if k[0] != 2]
    ee = [k for k in keys if k[0] == 2]
    out = []
    if vf:
        p0 = np.array([xa0[k[1]] if k[0] == 0 else xb0[k[3]] for k in vf])
        p1 = np.array([xa1[k[1]] if k[0] == 0 else xb1[k[3]] for k in vf])
        f0 = np.array([xb0[fb[k[3]]] if k[0] == 0 else xa0[fa[k[1]]] for k in vf])
        f1 = np.array([xb1[fb[k[3]]] if k[0] == 0 else xa1[fa[k[1]]] for k in vf])
        r = ttd.ccd_vertex_face(p0, f0, p1, f1, min_separation=delta)
        out += [(t, k) for t, h, k in zip(r.toi, r.hit, vf) if h]
    if ee:
        a0 = np.array([xa0[[k[1], k[2]]] for k in ee])
        a1 = np.array([xa1[[k[1], k[2]]] for k in ee])
        b0 = np.array([xb0[[k[3], k[4]]] for k in ee])
        b1 = np.array([xb1[[k[3], k[4]]] for k in ee])
        r = ttd.ccd_edge_edge(a0, b0, a1, b1, min_separation=delta)
        out += [(t, k) for t, h, k in zip(r.toi, r.hit, ee) if h]
    if not out:
        return np.inf, []
    best = min(t for t, _ in out)
    return best, sorted((t, k) for t, k in out if t <= best + TOL)


def keys_two(fa, fb):
    keys = set()
    for i, ta in enumerate(fa):
        for j, tb in enumerate(fb):
            for k in range(3):
                keys.add((0, int(ta[k]), -1, j, -1))
                keys.add((1, i, -1, int(tb[k]), -1))
            for e in edges(ta):
                for g in edges(tb):
                    keys.add((2, e[0], e[1], g[0], g[1]))
    return keys


def keys_self(f, shared):
    keys = set()
    for i in range(len(f)):
        for j in range(i + 1, len(f)):
            ti, tj = f[i], f[j]
            c = len(set(ti.tolist()) & set(tj.tolist()))
            if not (c == 0 or (c == 1 and shared)):
                continue
            for k in range(3):
                if ti[k] not in tj:
                    keys.add((0, int(ti[k]), -1, j, -1))
                if tj[k] not in ti:
                    keys.add((0, int(tj[k]), -1, i, -1))
            for e in edges(ti):
                for g in edges(tj):
                    if set(e) & set(g):
                        continue
                    keys.add((2,) + (e + g if e < g else g + e))
    return keys


def as_list(r):
    return sorted((float(t), (int(k), int(a[0]), int(a[1]), int(b[0]), int(b[1])))
                  for t, k, a, b in zip(r.pair_toi, r.kind, r.a, r.b))


def test_two_meshes_against_brute_force():
    rng = np.random.default_rng(5)
    va, fa = grid(4)
    vb, fb = grid(3, z=0.3)
    vb[:, :2] = 0.1 + 0.8 * vb[:, :2]
    for it in range(4):
        a1 = va + rng.uniform(-0.05, 0.05, va.shape)
        b1 = vb + rng.uniform(-0.05, 0.05, vb.shape) - [0, 0, 0.2 + 0.1 * it]
        ma, mb = ttd.Mesh(va, fa), ttd.Mesh(vb, fb)
        delta = 0.02 if it % 2 else 0.0
        r = ttd.mesh_ccd(ma, a1, mb, b1, min_separation=delta)
        assert isinstance(r, ttd.MeshCCDResult) and r._fields[0] == "toi"
        best, pairs = brute(keys_two(fa, fb), va, a1, fa, vb, b1, fb, delta)
        assert r.toi == best
        assert as_list(r) == pairs
        assert r.kind.dtype == np.uint8 and r.a.shape == (len(pairs), 2)
        if pairs:
            assert r.pair_toi.min() == r.toi
        r2 = ttd.mesh_ccd(ma, a1, mb, b1, min_separation=delta, threads=1)
        assert r2.toi == r.toi and as_list(r2) == as_list(r)


@pytest.mark.parametrize("shared", [False, True])
def test_self_against_brute_force(shared):
    rng = np.random.default_rng(11)
    v, f = grid(4)
    hits = 0
    for it in range(4):
        x1 = v + rng.uniform(-0.3, 0.3, v.shape)
        m = ttd.Mesh(v, f)
        r = ttd.mesh_self_ccd(m, x1, shared_vertex=shared, min_separation=0.01 * (it % 2))
        best, pairs = brute(keys_self(f, shared), v, x1, f, v, x1, f, 0.01 * (it % 2))
        assert r.toi == best
        assert as_list(r) == pairs
        hits += len(pairs) > 0
        assert all(k in (ttd.MESH_CCD_VF, ttd.MESH_CCD_EE) for k in r.kind.tolist())
    assert hits >= 2


def test_no_motion_and_float32():
    v, f = grid(3)
    m = ttd.Mesh(v, f)
    r = ttd.mesh_self_ccd(m, v)
    assert r.toi == np.inf and len(r.kind) == 0 and r.pair_toi.shape == (0,)
    # a second sheet 0.25 above, falling through: first contact at t = 0.25 / 0.5
    m2 = ttd.Mesh(v + [0, 0, 0.25], f)
    r = ttd.mesh_ccd(m, v, m2, v - [0, 0, 0.25])
    assert 0.5 - 1e-9 < r.toi <= 0.5 and len(r.kind) > 0
    v32 = v.astype(np.float32)
    up = np.array([0, 0, 0.25], np.float32)
    m32, m232 = ttd.Mesh(v32, f), ttd.Mesh(v32 + up, f)
    assert m32.dtype == np.float32
    r32 = ttd.mesh_ccd(m32, v32, m232, v32 - up)
    assert r32.toi == r.toi and as_list(r32) == as_list(r)


def test_errors():
    v, f = grid(2)
    m = ttd.Mesh(v, f)
    with pytest.raises(ValueError):
        ttd.mesh_self_ccd(m, v[:-1])
    with pytest.raises(ValueError, match=r"\(got -1\.0\)"):
        ttd.mesh_self_ccd(m, v, min_separation=-1.0)
    with pytest.raises(ValueError):
        ttd.mesh_self_ccd(m, v, min_separation=float("nan"))
    bad = v.copy()
    bad[2, 1] = np.nan
    with pytest.raises(ValueError):
        ttd.mesh_self_ccd(m, bad)
    with pytest.raises(ValueError):
        ttd.mesh_ccd(m, v, m, np.full_like(v, np.inf))
    with pytest.raises(TypeError):
        ttd.mesh_self_ccd(v, v)
    with pytest.raises(TypeError):
        ttd.mesh_self_ccd(m, v.astype(str))
    with pytest.raises(TypeError):
        ttd.mesh_self_ccd(m, v, min_separation="0")
    with pytest.raises(ValueError):
        ttd.mesh_self_ccd(m, v, threads=-1)
    with pytest.raises(ValueError):
        ttd.mesh_ccd(m, v, ttd.Mesh(v.astype(np.float32), f), v)


def test_unaligned_t1_array_is_copied():
    # A (nv, 3) float64 view at an odd byte offset is C-contiguous but not aligned: the wrapper
    # must hand C an aligned copy, with the same answer as the aligned array.
    v, f = grid(3)
    m = ttd.Mesh(v, f)
    x1 = v + [0.0, 0.0, 0.0]
    x1[:, 2] += 0.3 * np.sin(7 * x1[:, 0])
    buf = bytearray(x1.nbytes + 1)
    odd = np.frombuffer(buf, dtype=np.float64, count=x1.size, offset=1).reshape(x1.shape)
    odd[...] = x1
    assert not odd.flags.aligned and odd.flags.c_contiguous
    r, r_odd = ttd.mesh_self_ccd(m, x1), ttd.mesh_self_ccd(m, odd)
    assert r.toi == r_odd.toi and as_list(r) == as_list(r_odd)
