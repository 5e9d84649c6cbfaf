# SPDX-License-Identifier: MIT
"""The scene CLI (`ttd scene`, cli/scene.c) and ttd.Scene give identical answers (issue 17): the
same scene file read by both, every query's lines compared digit for digit (the CLI prints
%.17g in double, %.9g in float; Python's values are formatted the same way)."""
import subprocess

import numpy as np
import pytest

import ttd

CUBE_V = np.array([[x, y, z] for z in (0, 1) for y in (0, 1) for x in (0, 1)], float)
CUBE_F = np.array([[0, 2, 3], [0, 3, 1], [4, 5, 7], [4, 7, 6], [0, 1, 5], [0, 5, 4],
                   [2, 6, 7], [2, 7, 3], [0, 4, 6], [0, 6, 2], [1, 3, 7], [1, 7, 5]], np.uint32)


def write_scene(folder, poses):
    with open(folder / "cube.obj", "w") as f:
        f.writelines(f"v {x:.17g} {y:.17g} {z:.17g}\n" for x, y, z in CUBE_V)
        f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in CUBE_F)
    with open(folder / "scene.txt", "w") as f:
        f.write("mesh cube cube.obj\n")
        for P in poses:
            f.write("body cube " + " ".join(f"{x:.17g}" for x in P[:3].ravel()) + "\n")
    return folder / "scene.txt"


def fmt(x, dtype):
    return f"{float(x):.17g}" if dtype == np.float64 else f"{float(x):.9g}"


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_cli_and_python_agree(tmp_path, ttd_program, dtype):
    rng = np.random.default_rng(17)
    poses = []
    for k in range(7):  # a row of cubes, turned, some touching, some crossing, some apart
        q = rng.normal(size=4)
        P = ttd.pose(quat=q, t=[1.05 * k + rng.uniform(-0.3, 0.1), rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2)])
        poses.append(P.astype(dtype).astype(np.float64))
    path = write_scene(tmp_path, poses)
    prec = [] if dtype == np.float64 else ["--precision", "float"]
    mesh = ttd.Mesh(CUBE_V.astype(dtype), CUBE_F)
    scene = ttd.Scene([mesh] * len(poses), np.array(poses, dtype))
    margin = 0.05

    def cli(*args):
        out = subprocess.run([str(ttd_program), "scene", *args, str(path), *prec], capture_output=True, text=True,
                             check=True)
        return out.stdout.splitlines()

    # contacts: i j ia ib d p q
    c = scene.contacts(margin)
    want = [" ".join([str(c.i[k]), str(c.j[k]), str(c.tri_i[k]), str(c.tri_j[k]), fmt(c.distance[k], dtype)]
                     + [fmt(x, dtype) for x in c.p[k]] + [fmt(x, dtype) for x in c.q[k]]) for k in range(len(c.i))]
    assert len(want) > 0
    assert cli("contacts", "--margin", str(margin)) == want
    # collide: i j ia ib
    h = scene.collide(margin)
    assert cli("collide", "--margin", str(margin)) == [f"{a} {b} {x} {y}" for a, b, x, y in
                                                       zip(h.i, h.j, h.tri_i, h.tri_j)]
    # distance: d i j ia ib p q
    d = scene.distance()
    assert cli("distance") == [" ".join([fmt(d.distance, dtype), str(d.i), str(d.j), str(d.tri_i), str(d.tri_j)]
                                        + [fmt(x, dtype) for x in d.p] + [fmt(x, dtype) for x in d.q])]
    # manifold: i j point normal d depth point_i point_j key; the CLI sorts each body pair's points by triangles
    m = scene.manifold(margin, 4)
    rows = sorted(range(len(m.i)), key=lambda k: (m.i[k], m.j[k], m.tri_i[k], m.tri_j[k]))
    want = [" ".join([str(m.i[k]), str(m.j[k])] + [fmt(x, dtype) for x in m.point[k]]
                     + [fmt(x, dtype) for x in m.normal[k]] + [fmt(m.distance[k], dtype), fmt(m.depth[k], dtype)]
                     + [fmt(x, dtype) for x in m.point_i[k]] + [fmt(x, dtype) for x in m.point_j[k]]
                     + [f"{int(m.key[k]):016x}"])
            for k in rows]
    assert cli("manifold", "--margin", str(margin), "--max-points", "4") == want
