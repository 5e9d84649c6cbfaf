# SPDX-License-Identifier: MIT
"""Meshes, poses and the brute force for the mesh tests.

The meshes are made here with numpy (an icosphere, a torus, a cube, a bumpy grid, and meshes
of degenerate triangles and slivers); the poses are random rotations from unit quaternions. The
brute force is ttd.distance over every triangle pair, with b's vertices moved into a's frame
exactly as include/ttd/ttd.h documents, ((r0 x + r1 y) + r2 z) + t per coordinate in the
meshes' dtype, so that each pair's distance is the very number the mesh query's kernel
computes: a query must equal the brute force's minimum bit for bit, and its contact set must be
the brute-force set. (ttd.distance itself is checked against an independent numpy brute force
and against the C library in test_values.py and test_c_reference.py.)
"""
import numpy as np

import ttd


def icosphere(level=1, radius=1.0):
    """A sphere: the icosahedron, each triangle split into four `level` times."""
    t = (1 + 5 ** 0.5) / 2
    v = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t],
         [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]]
    f = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2],
         [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11],
         [6, 2, 10], [8, 6, 7], [9, 8, 1]]
    v = [np.array(x, float) / np.linalg.norm(x) for x in v]
    for _ in range(level):
        mid = {}

        def middle(i, j):
            key = (min(i, j), max(i, j))
            if key not in mid:
                m = v[i] + v[j]
                v.append(m / np.linalg.norm(m))
                mid[key] = len(v) - 1
            return mid[key]

        g = []
        for a, b, c in f:
            ab, bc, ca = middle(a, b), middle(b, c), middle(c, a)
            g += [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
        f = g
    return radius * np.array(v), np.array(f, np.int64)


def torus(R=1.0, r=0.35, nu=14, nv=9):
    """A torus around the z axis: nu x nv quads, two triangles each."""
    u = 2 * np.pi * np.arange(nu) / nu
    w = 2 * np.pi * np.arange(nv) / nv
    U, W = np.meshgrid(u, w, indexing="ij")
    v = np.stack([(R + r * np.cos(W)) * np.cos(U), (R + r * np.cos(W)) * np.sin(U), r * np.sin(W)], -1).reshape(-1, 3)
    f = []
    for i in range(nu):
        for j in range(nv):
            a, b = i * nv + j, ((i + 1) % nu) * nv + j
            c, d = ((i + 1) % nu) * nv + (j + 1) % nv, i * nv + (j + 1) % nv
            f += [[a, b, c], [a, c, d]]
    return v, np.array(f, np.int64)


def cube():
    """The unit cube [0, 1]^3, 12 triangles."""
    v = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
    f = [[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1], [2, 3, 7], [2, 7, 6], [0, 2, 6],
         [0, 6, 4], [1, 5, 7], [1, 7, 3]]
    return v, np.array(f, np.int64)


def grid(n=6, seed=3):
    """A bumpy square sheet over [0, 1]^2: (n+1)^2 vertices, 2 n^2 triangles."""
    rng = np.random.default_rng(seed)
    x, y = np.meshgrid(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1), indexing="ij")
    v = np.stack([x, y, 0.05 * rng.random(x.shape)], -1).reshape(-1, 3)
    f = []
    for i in range(n):
        for j in range(n):
            a, b, c, d = i * (n + 1) + j, (i + 1) * (n + 1) + j, (i + 1) * (n + 1) + j + 1, i * (n + 1) + j + 1
            f += [[a, b, c], [a, c, d]]
    return v, np.array(f, np.int64)


def slivers():
    """Needles, caps, a segment, a point, repeated vertices, a non-manifold fan."""
    v = np.array([[0, 0, 0], [1, 0, 0], [1, 1e-9, 0], [0.5, 1e-7, 1e-8], [0.2, 0.3, 0.1], [0.2, 0.3, 0.1],
                  [0.4, 0.6, 0.2], [0.6, 0.9, 0.3], [-0.3, 0.2, 0.4]], float)
    f = np.array([[0, 1, 2], [0, 1, 3], [4, 5, 4], [4, 6, 7], [8, 8, 8], [0, 8, 3], [2, 3, 6], [0, 1, 6]], np.int64)
    return v, f


MESHES = {"icosphere": icosphere(1), "torus": torus(), "cube": cube(), "grid": grid(), "slivers": slivers()}


def rotation(q):
    """The rotation matrix of a quaternion (w, x, y, z), normalised first; float64."""
    w, x, y, z = np.asarray(q, float) / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def random_poses(k, seed, spread=1.5, homogeneous=True):
    """k random rigid motions, (k, 4, 4) (or (k, 3, 4)), translations uniform in [-spread, spread)^3."""
    rng = np.random.default_rng(seed)
    P = np.zeros((k, 4, 4))
    for i in range(k):
        P[i, :3, :3] = rotation(rng.standard_normal(4))
    P[:, :3, 3] = spread * (2 * rng.random((k, 3)) - 1)
    P[:, 3, 3] = 1
    return P if homogeneous else P[:, :3, :].copy()


def mesh_pair(name_a, name_b, dtype=np.float64):
    (va, fa), (vb, fb) = MESHES[name_a], MESHES[name_b]
    return ttd.Mesh(va.astype(dtype), fa), ttd.Mesh(vb.astype(dtype), fb)


def move(vertices, pose):
    """b's vertices in a's frame, as the library computes them: ((r0 x + r1 y) + r2 z) + t per
    coordinate, in the dtype of vertices (the pose is converted to it first)."""
    P = np.asarray(pose).astype(vertices.dtype)
    x, y, z = vertices[:, 0:1], vertices[:, 1:2], vertices[:, 2:3]
    return ((x * P[:3, 0] + y * P[:3, 1]) + z * P[:3, 2]) + P[:3, 3]


def brute_force(a, b, pose):
    """ttd.PairResult of every pair (triangle i of a, triangle j of b) under pose, shape (na, nb)."""
    S = a.vertices[a.faces]
    T = move(b.vertices, pose)[b.faces]
    na, nb = len(S), len(T)
    return ttd.distance(np.broadcast_to(S[:, None], (na, nb, 3, 3)), np.broadcast_to(T[None, :], (na, nb, 3, 3)),
                        points=True)
