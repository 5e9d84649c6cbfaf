# SPDX-License-Identifier: MIT
"""Issue 36's folded sheet for self-contacts, through Python: a strip of 595 x 85 square quads
(101,150 triangles) folded flat into 7 layers (about 85 x 85 quads each), margin half an edge,
the layers 1.5 margins apart (pairs only at the folds) or 0.8 (every triangle near the next
layer's). The same construction as gen/meshes.c's ttd_gen_folded_strip (`ttd bench`'s rows
sheet7-101k), written here with numpy.

    /usr/bin/python3 bench/self_sheet.py                 # time ttd.mesh_self_contacts, one thread
    /usr/bin/python3 bench/self_sheet.py --obj DIR       # also write DIR/sheet7-apart.obj, -touching.obj
                                                         # (for `ttd mesh self-contacts`, callgrind, md5)

It prints, per gap, the pairs found and the median of --repeat calls of ttd.mesh_self_contacts
(one thread, ttd.Mesh built once): wall and CPU time, and CPU time a pair found. `ttd bench
--self-only` times the same query from C (its self_cpu column).
"""
import argparse
import math
import os
import sys
import time

import numpy as np


def folded_strip(nx, ny, layers, gap, t=1.0):
    """Vertices and triangles of ttd_gen_folded_strip(nx, ny, layers, gap, t)."""
    w = nx + 1
    theta = math.pi * t
    r = 0.5 * gap
    arc = r * theta
    a = (1.0 - (layers - 1) * arc) / layers
    if not a > 0:
        raise ValueError("the arcs are longer than the sheet")
    xs, zs = np.empty(w), np.empty(w)
    for i in range(w):
        s, x, z, phi = i / nx, 0.0, 0.0, 0.0
        for k in range(layers):
            run = s if (s < a or k == layers - 1) else a
            x += run * math.cos(phi)
            z += run * math.sin(phi)
            s -= run
            if s <= 0 or k == layers - 1:
                break
            side = 1.0 if k % 2 == 0 else -1.0
            turn = s / r if s < arc else theta
            cx, cz = x - side * r * math.sin(phi), z + side * r * math.cos(phi)
            phi += side * turn
            x = cx + side * r * math.sin(phi)
            z = cz - side * r * math.cos(phi)
            s -= s if s < arc else arc
            if s <= 0:
                break
        xs[i], zs[i] = x, z
    j, i = np.meshgrid(np.arange(ny + 1), np.arange(w), indexing="ij")
    V = np.stack([xs[i].ravel(), (j / nx).ravel(), zs[i].ravel()], 1)
    jj, ii = np.meshgrid(np.arange(ny), np.arange(nx), indexing="ij")
    A = (jj * w + ii).ravel()
    B, C = A + 1, A + w + 1
    D = C - 1
    F = np.empty((2 * nx * ny, 3), dtype=np.uint32)
    F[0::2] = np.stack([A, B, C], 1)
    F[1::2] = np.stack([A, C, D], 1)
    return V, F


def write_obj(path, V, F):
    with open(path, "w") as f:
        for p in V:
            f.write("v %.17g %.17g %.17g\n" % tuple(p))
        for t in F:
            f.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--nx", type=int, default=595)
    ap.add_argument("--ny", type=int, default=85)
    ap.add_argument("--layers", type=int, default=7)
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--obj", metavar="DIR", help="write the two sheets as OBJ files into DIR")
    args = ap.parse_args()
    margin = 0.5 / args.nx
    sheets = {}
    for name, g in (("apart", 1.5), ("touching", 0.8)):
        V, F = folded_strip(args.nx, args.ny, args.layers, g * margin)
        sheets[name] = (V, F)
        if args.obj:
            path = os.path.join(args.obj, "sheet7-%s.obj" % name)
            write_obj(path, V, F)
            print("wrote %s (%d triangles, margin %.17g)" % (path, len(F), margin))
    try:
        import ttd
    except ImportError as e:
        print("ttd is not importable (%s): no timings" % e, file=sys.stderr)
        return
    print("%-9s %9s %9s %10s %10s %10s" % ("sheet", "tris", "pairs", "py_ms", "py_cpu", "ns_pair"))
    for name, (V, F) in sheets.items():
        m = ttd.Mesh(V, F)
        wall, cpu = [], []
        n = 0
        for _ in range(args.repeat):
            t0, c0 = time.perf_counter(), time.thread_time()
            res = ttd.mesh_self_contacts(m, margin, threads=1)
            c1, t1 = time.thread_time(), time.perf_counter()
            wall.append((t1 - t0) * 1e3)
            cpu.append((c1 - c0) * 1e3)
            n = len(res.distance)
        print("%-9s %9d %9d %10.2f %10.2f %10.1f" % (name, len(F), n, np.median(wall), np.median(cpu),
                                                     np.median(cpu) * 1e6 / max(n, 1)))


if __name__ == "__main__":
    main()
