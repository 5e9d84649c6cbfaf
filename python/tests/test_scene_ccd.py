# SPDX-License-Identifier: MIT
"""ttd.Scene.ccd (docs/ccd.md, section 13) against a brute force over every body pair: each
present pair the test's own copy of the filters and exclusions allows, through
ttd.mesh_ccd_rigid (a pair of solids as solids is left to the C test). The same pairs and times
to the bit, on 1, 2 and 3 threads; float32 scenes; a fast small body through a thin plate; errors."""
import math

import numpy as np
import pytest

import ttd
from meshes import icosphere, torus, cube, rotation


def world(rng, n, dtype):
    sphere, ring, box = icosphere(1, 0.6), torus(0.8, 0.25, 12, 6), cube()
    pend_v, pend_f = icosphere(1, 0.3)
    pend = (pend_v + [2.5, 0, 0], pend_f)
    shapes = [ttd.Mesh(v.astype(dtype), f) for v, f in (sphere, ring, box, pend)]
    meshes = [shapes[k % 4] for k in range(n)]
    P0 = np.zeros((n, 4, 4))
    P1 = np.zeros((n, 4, 4))
    for k in range(n):
        P0[k, :3, :3] = rotation(rng.standard_normal(4))
        P1[k, :3, :3] = rotation(rng.standard_normal(4))
        P0[k, :3, 3] = 7 * rng.random(3)
        P1[k, :3, 3] = P0[k, :3, 3] + 1.2 * (2 * rng.random(3) - 1)
        P0[k, 3, 3] = P1[k, 3, 3] = 1
    return meshes, P0, P1


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_against_brute_force(dtype):
    rng = np.random.default_rng(8)
    n = 20
    meshes, P0, P1 = world(rng, n, dtype)
    scene = ttd.Scene(meshes, P0.astype(dtype))
    group = [1 << (k % 3) for k in range(n)]
    mask = [~2 & 0xFFFFFFFF if k % 7 == 5 else 0xFFFFFFFF for k in range(n)]
    for k in range(n):
        scene.set_filter(k, group[k], mask[k])
    excluded = {(3 * e, 3 * e + 4) for e in range(5)}
    for i, j in excluded:
        scene.exclude(i, j)
    scene.remove(9)
    for delta in (0.0, 0.1):
        got = [scene.ccd(P1.astype(dtype), min_separation=delta, threads=t) for t in (1, 2, 3)]
        assert isinstance(got[0], ttd.SceneCCDResult)
        want = []
        for i in range(n):
            for j in range(i + 1, n):
                if 9 in (i, j) or (i, j) in excluded or not (group[i] & mask[j] and group[j] & mask[i]):
                    continue
                r = ttd.mesh_ccd_rigid(meshes[i], P0[i].astype(dtype), P1[i].astype(dtype), meshes[j],
                                       P0[j].astype(dtype), P1[j].astype(dtype), min_separation=delta)
                if r.hit:
                    want.append((i, j, r.toi, r.distance, r.steps))
        assert 0 < len(want) < 100
        for g in got:
            assert list(zip(g.i.tolist(), g.j.tolist())) == [w[:2] for w in want]
            assert np.array_equal(g.toi, [w[2] for w in want])
            assert np.array_equal(g.distance, [w[3] for w in want])
            assert np.array_equal(g.steps, [w[4] for w in want])
            assert g.i.dtype == np.uint32 and g.toi.dtype == np.float64


def test_fast_ball_through_plate():
    pv, pf = cube()
    plate = ttd.Mesh((pv - 0.5) * [2, 2, 0.1], pf)
    bv, bf = icosphere(2, 0.05)
    ball = ttd.Mesh(bv, bf)
    start = np.eye(4)
    start[2, 3] = 0.4
    end = start.copy()
    end[2, 3] = 0.4 - 40 / 60
    scene = ttd.Scene([plate, ball], np.stack([np.eye(4), start]))
    assert len(scene.collide().i) == 0
    r = scene.ccd(np.stack([np.eye(4), end]))
    exact = (0.4 + bv[:, 2].min() - 0.05) / (40 / 60)
    assert r.i.tolist() == [0] and r.j.tolist() == [1]
    assert exact - 1e-6 < r.toi[0] <= exact + 1e-12
    scene.set_poses(np.stack([np.eye(4), end]))
    assert len(scene.collide().i) == 0  # the step's end alone: tunnelled


def test_errors_and_empty():
    assert len(ttd.Scene().ccd(np.zeros((0, 4, 4))).i) == 0
    v, f = cube()
    scene = ttd.Scene([ttd.Mesh(v, f)] * 2, np.stack([np.eye(4)] * 2))
    with pytest.raises(ValueError, match="id_limit"):
        scene.ccd(np.stack([np.eye(4)] * 3))
    with pytest.raises(ValueError, match=r"min_separation=-1\.0 "):
        scene.ccd(np.stack([np.eye(4)] * 2), min_separation=-1)
    with pytest.raises(ValueError):
        scene.ccd(np.stack([np.eye(4)] * 2), min_separation=math.inf)
    bad = np.stack([np.eye(4)] * 2)
    bad[1, 0, 0] = 2
    with pytest.raises(ValueError, match="body 1"):
        scene.ccd(bad)
    bad[1, 0, 0] = math.nan
    with pytest.raises(ValueError, match="body 1"):
        scene.ccd(bad)
    with pytest.raises(ValueError):
        scene.ccd(np.eye(4))
