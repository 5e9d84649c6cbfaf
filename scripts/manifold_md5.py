#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""The md5 of `ttd scene manifold` over a fixed set of scenes, for refactors that must not change
a bit of the manifold (issue 32, item 8): piles of icospheres, tori and boxes (cut 1 x 1 and
3 x 3) on a floor, turned and touching, crossing and resting; as surfaces and as solids; at
margins 0.02 and 0.2, K = 4, 2 and 0, double and float. Prints one md5 per run and one over all;
then issue 32's tower in four triangulations (scripts/tower_scene.py) at margin 0.01, K = 4 and 0,
double and float, with its own md5 over those ("tower").

    /usr/bin/python3 scripts/manifold_md5.py build/cli/ttd [WORKDIR] [--save DIR]

--save DIR also writes each run's output to DIR/N.txt (N from 1, in the order printed), for
scripts/manifold_*_diff.py to compare two builds where the md5s differ (they read both through
scripts/manifold_output.py).
"""
import hashlib
import math
import os
import subprocess
import sys

import numpy as np


def icosphere(level):
    t = (1 + 5 ** 0.5) / 2
    v = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t],
         [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]]
    f = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2],
         [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11],
         [6, 2, 10], [8, 6, 7], [9, 8, 1]]
    v = [list(np.array(x) / np.linalg.norm(x)) for x in v]
    for _ in range(level):
        mid = {}
        nf = []
        for a, b, c in f:
            m = []
            for x, y in ((a, b), (b, c), (c, a)):
                k = (min(x, y), max(x, y))
                if k not in mid:
                    p = np.array(v[x]) + np.array(v[y])
                    v.append(list(p / np.linalg.norm(p)))
                    mid[k] = len(v) - 1
                m.append(mid[k])
            nf += [[a, m[0], m[2]], [b, m[1], m[0]], [c, m[2], m[1]], [m[0], m[1], m[2]]]
        f = nf
    return np.array(v), np.array(f)


def torus(R, r, nu, nv):
    v = [[(R + r * math.cos(2 * math.pi * j / nv)) * math.cos(2 * math.pi * i / nu),
          (R + r * math.cos(2 * math.pi * j / nv)) * math.sin(2 * math.pi * i / nu),
          r * math.sin(2 * math.pi * j / nv)] for i in range(nu) for j in range(nv)]
    f = []
    for i in range(nu):
        for j in range(nv):
            a, b = i * nv + j, ((i + 1) % nu) * nv + j
            c, d = ((i + 1) % nu) * nv + (j + 1) % nv, i * nv + (j + 1) % nv
            f += [[a, b, c], [a, c, d]]
    return np.array(v), np.array(f)


def box(dims, n):
    h = np.array(dims) / 2
    verts, index, faces = [], {}, []

    def vid(x):
        k = tuple(x)
        if k not in index:
            index[k] = len(verts)
            verts.append(x)
        return index[k]

    for axis in range(3):
        for sgn in (-1, 1):
            u, w = (axis + 1) % 3, (axis + 2) % 3
            U, V = (u, w) if sgn > 0 else (w, u)
            for iu in range(n):
                for iv in range(n):
                    q = {}
                    for du in (0, 1):
                        for dv in (0, 1):
                            x = [0.0, 0.0, 0.0]
                            x[axis] = sgn * h[axis]
                            x[U] = -h[U] + 2 * h[U] * ((iu + du) / n)
                            x[V] = -h[V] + 2 * h[V] * ((iv + dv) / n)
                            q[du, dv] = vid(x)
                    faces += [[q[0, 0], q[1, 0], q[1, 1]], [q[0, 0], q[1, 1], q[0, 1]]]
    return np.array(verts), np.array(faces)


def write_obj(path, v, f):
    with open(path, "w") as out:
        for x in v:
            out.write("v %.17g %.17g %.17g\n" % tuple(x))
        for t in f:
            out.write("f %d %d %d\n" % tuple(int(k) + 1 for k in t))


def rot(rng):
    q = rng.normal(size=4)
    w, x, y, z = q / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def main():
    args = sys.argv[1:]
    save = None
    if "--save" in args:
        k = args.index("--save")
        save = args[k + 1]
        del args[k:k + 2]
        os.makedirs(save, exist_ok=True)
    ttd = args[0]
    work = args[1] if len(args) > 1 else "/tmp/ttd-manifold-md5"
    os.makedirs(work, exist_ok=True)
    write_obj(f"{work}/ball.obj", *icosphere(2))
    write_obj(f"{work}/torus.obj", *torus(1.0, 0.3, 24, 12))
    write_obj(f"{work}/box.obj", *box([1.0, 0.6, 0.4], 1))
    write_obj(f"{work}/boxcut.obj", *box([1.0, 0.6, 0.4], 3))
    write_obj(f"{work}/floor.obj", *box([12.0, 12.0, 1.0], 4))
    rng = np.random.default_rng(8)
    scenes = []
    for s in range(3):
        lines = ["mesh ball ball.obj", "mesh torus torus.obj", "mesh box box.obj", "mesh boxcut boxcut.obj",
                 "mesh floor floor.obj", "body floor 1 0 0 0  0 1 0 0  0 0 1 -0.5"]
        n = 0
        for k in range(40):
            kind = ["ball", "torus", "box", "boxcut"][k % 4]
            R = rot(rng) if s != 1 else np.eye(3)
            c = rng.uniform(-2.5, 2.5, size=3)
            c[2] = abs(c[2]) * 0.6 + (0.35 if s == 1 else 0.2)
            if s == 1:  # a resting layer: boxes flat on the floor at small gaps
                c[2] = {"box": 0.2, "boxcut": 0.2, "ball": 1.0, "torus": 0.3}[kind] + 0.003 * (k % 3)
            lines.append(f"body {kind} " + "  ".join(" ".join("%.17g" % x for x in list(R[r]) + [c[r]]) for r in range(3)))
            n += 1
        scenes.append("\n".join(lines) + "\n")
    total = hashlib.md5()
    runs = 0
    for s, text in enumerate(scenes):
        path = f"{work}/scene{s}.txt"
        with open(path, "w") as out:
            out.write(text)
        for solid in ([], ["--solid"]):
            for prec in ("double", "float"):
                for margin in ("0.02", "0.2"):
                    for k in ("4", "2", "0"):
                        cmd = [ttd, "scene", "manifold", path, "--margin", margin, "--max-points", k,
                               "--precision", prec] + solid
                        out = subprocess.run(cmd, check=True, capture_output=True).stdout
                        total.update(out)
                        runs += 1
                        if save:
                            with open(f"{save}/{runs}.txt", "wb") as f:
                                f.write(out)
                        print(hashlib.md5(out).hexdigest(), len(out.splitlines()), " ".join(cmd[2:]).replace(work + "/", ""))
    print("all", total.hexdigest())
    # issue 32's tower in its four triangulations (scripts/tower_scene.py; the bench's tower-KIND
    # scenes), summed apart so that "all" stays comparable with the figures recorded before it
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import tower_scene
    sys.argv = [sys.argv[0], work]
    tower_scene.main()
    tower = hashlib.md5()
    for kind in ("plain", "centre", "cut", "sliver"):
        for prec in ("double", "float"):
            for k in ("4", "0"):
                cmd = [ttd, "scene", "manifold", f"{work}/tower-{kind}.txt", "--margin", "0.01", "--max-points", k,
                       "--precision", prec]
                out = subprocess.run(cmd, check=True, capture_output=True).stdout
                tower.update(out)
                print(hashlib.md5(out).hexdigest(), len(out.splitlines()), " ".join(cmd[2:]).replace(work + "/", ""))
    print("tower", tower.hexdigest())


if __name__ == "__main__":
    main()
