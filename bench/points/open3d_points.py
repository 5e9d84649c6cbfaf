# SPDX-License-Identifier: MIT
"""Open3D's RaycastingScene.compute_distance (float32 throughout) on ttd's points file, for
`ttd bench points` (bench/points_bench.c, docs/points.md): prints "build_seconds query_seconds"
(wall clock, the query the best of 3) and writes the n distances as doubles to OUT. Run by
Debian's /usr/bin/python3 with python3-open3d; threads: Open3D's own (the benchmark pins the
one-thread run to one core with taskset).

    python3 open3d_points.py FILE OUT
"""
import sys
import time

import numpy as np
import open3d as o3d


def main():
    path, out = sys.argv[1], sys.argv[2]
    raw = open(path, "rb").read()
    nv, nt, n = np.frombuffer(raw, np.uint64, 3)
    off = 24
    v = np.frombuffer(raw, np.float64, 3 * int(nv), off).reshape(-1, 3)
    off += 24 * int(nv)
    t = np.frombuffer(raw, np.uint32, 3 * int(nt), off).reshape(-1, 3)
    off += 12 * int(nt)
    p = np.frombuffer(raw, np.float64, 3 * int(n), off).reshape(-1, 3)
    t0 = time.perf_counter()
    scene = o3d.t.geometry.RaycastingScene()
    scene.add_triangles(o3d.core.Tensor(v.astype(np.float32)), o3d.core.Tensor(t.astype(np.uint32)))
    pts = o3d.core.Tensor(p.astype(np.float32))
    scene.compute_distance(pts[:1])  # the scene is built on first use
    build = time.perf_counter() - t0
    best = 1e300
    for _ in range(3):
        t0 = time.perf_counter()
        d = scene.compute_distance(pts).numpy()
        best = min(best, time.perf_counter() - t0)
    d.astype(np.float64).tofile(out)
    print(f"{build:.9g} {best:.9g}")


if __name__ == "__main__":
    main()
