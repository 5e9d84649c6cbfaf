# SPDX-License-Identifier: MIT
"""The point queries on an open mesh: an icosphere of level 5 (20,480 triangles) with every 37th
face removed (554 holes, 19,926 triangles), 200,000 points uniform in its box and 200,000 beside
the holes (on each hole's normal line within 0.05 of its centre, where the winding number passes
1/2 away from the surface). Times `ttd points closest|signed|winding` (one thread) for each ttd
program given, counts the sides on which two programs' answers differ and checks up to 200 of
those against a solid-angle sum in numpy's long double (docs/points.md, section 5.4).

    build/python-venv/bin/python bench/points/holed_sphere.py build/cli/ttd [OTHER_TTD ...]

(the venv scripts/test-python.sh makes: python/tests/meshes.py, which makes the sphere, imports
ttd)
"""
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "python", "tests"))
from meshes import icosphere  # noqa: E402
from test_points_inside import ref_winding  # noqa: E402  (numpy's long double solid-angle sum)


def main(programs):
    v, f = icosphere(5)
    keep = np.arange(len(f)) % 37 != 0
    F, holes = f[keep], f[~keep]
    rng = np.random.default_rng(3)
    a, b, c = v[holes[:, 0]], v[holes[:, 1]], v[holes[:, 2]]
    centre, n = (a + b + c) / 3, np.cross(b - a, c - a)
    n /= np.linalg.norm(n, axis=1)[:, None]
    k = rng.integers(0, len(holes), 200000)
    sets = {"box": rng.uniform(-1.3, 1.3, (200000, 3)), "holes": centre[k] + n[k] * rng.uniform(-0.05, 0.05, (200000, 1))}
    with tempfile.TemporaryDirectory() as d:
        mesh = os.path.join(d, "holed.obj")
        with open(mesh, "w") as o:
            o.writelines("v %.17g %.17g %.17g\n" % tuple(x) for x in v)
            o.writelines("f %d %d %d\n" % tuple(t + 1) for t in F)
        print(f"mesh: icosphere level 5 less every 37th face: {len(F)} triangles, {len(holes)} holes")
        inside = {}
        for name, P in sets.items():
            path = os.path.join(d, name + ".npy")
            np.save(path, P)
            for q in ("closest", "signed", "winding"):
                for i, ttd in enumerate(programs):
                    t0 = time.perf_counter()
                    out = subprocess.run([ttd, "points", q, mesh, path, "--threads", "1"], check=True, capture_output=True,
                                         text=True).stdout
                    dt = time.perf_counter() - t0
                    col = np.loadtxt(out.splitlines(), usecols=0)
                    if q == "signed":
                        inside[name, i, q] = np.signbit(col)
                    elif q == "winding":
                        inside[name, i, q] = np.abs(col) >= 0.5  # the rule of this tree's ttd_winding_inside
                    print(f"  {name:5s} {q:7s} program {i}: {dt:6.2f} s for {len(P)} points")
            for i in range(len(programs)):
                print(f"  {name}: program {i}: winding's |w| >= 1/2 differs from signed's side on "
                      f"{int((inside[name, i, 'winding'] != inside[name, i, 'signed']).sum())} points")
            for i in range(1, len(programs)):
                for q in ("signed", "winding"):
                    diff = np.flatnonzero(inside[name, 0, q] != inside[name, i, q])
                    ref = np.array([abs(ref_winding(v, F, P[j])) >= 0.5 for j in diff[:200]], bool)
                    wrong = [int((inside[name, m, q][diff[:200]] != ref).sum()) for m in (0, i)]
                    print(f"  {name}: {q} sides that differ, program 0 vs {i}: {diff.size}; of the first {ref.size}, "
                          f"against the long double sum, program 0 wrong on {wrong[0]}, program {i} on {wrong[1]}")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
