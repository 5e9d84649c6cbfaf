# SPDX-License-Identifier: MIT
"""Pictures of ttd_sim's final states: each OBJ that `ttd_sim --obj DIR` wrote (one group per
body, "g body_K shape" or "g static_K shape") drawn as shaded triangles with matplotlib, moving
bodies coloured by height, static ones grey and cut to the region the moving ones occupy.

    /usr/bin/python3 examples/sim/picture.py --out DIR build/examples/sim/*.obj

Writes DIR/NAME.png for each NAME.obj. Exits 77 (CTest's "skipped") with a message when numpy or
matplotlib is missing (Debian: apt-get install python3-numpy python3-matplotlib).
"""
import argparse
import os
import sys


def read_obj(path):
    """The OBJ's vertices, and its triangles grouped by body: [(name, is_static, (m, 3) indices)]."""
    import numpy as np

    verts, groups = [], []
    for line in open(path):
        f = line.split()
        if not f:
            continue
        if f[0] == "v":
            verts.append([float(x) for x in f[1:4]])
        elif f[0] == "g":
            groups.append((f[1], f[1].startswith("static"), []))
        elif f[0] == "f":
            groups[-1][2].append([int(x) - 1 for x in f[1:4]])
    return np.array(verts), [(n, s, np.array(t, int)) for n, s, t in groups]


def draw(path, out):
    import numpy as np
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    v, groups = read_obj(path)
    moving = np.concatenate([t.ravel() for _, s, t in groups if not s])
    lo, hi = v[moving].min(0), v[moving].max(0)
    pad = 0.15 * max(hi - lo) + 0.3
    lo, hi = lo - pad, hi + pad
    lo[2] = min(lo[2], -0.05)
    tris, colours = [], []
    light = np.array([0.4, -0.5, 0.77])
    z0, z1 = v[moving, 2].min(), v[moving, 2].max()
    for _, static, t in groups:
        tri = v[t]
        if static:  # clip static boxes to the box around the moving bodies
            tri = np.clip(tri, lo, hi)
        n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        keep = np.linalg.norm(n, axis=1) > 1e-12
        tri, n = tri[keep], n[keep] / np.linalg.norm(n[keep], axis=1, keepdims=True)
        shade = 0.35 + 0.65 * np.clip(n @ light, 0, 1)
        if static:
            c = np.tile([0.75, 0.75, 0.75, 0.35], (len(tri), 1))
        else:
            c = plt.cm.viridis((tri[:, :, 2].mean(1) - z0) / max(z1 - z0, 1e-9))
        c[:, :3] *= shade[:, None]
        tris.append(tri)
        colours.append(c)
    fig = plt.figure(figsize=(7, 7))
    ax = fig.add_subplot(projection="3d")
    ax.add_collection3d(Poly3DCollection(np.concatenate(tris), facecolors=np.concatenate(colours), edgecolors="none"))
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(lo[2], hi[2])
    ax.set_box_aspect(hi - lo)
    ax.view_init(elev=20, azim=-60)
    name = os.path.splitext(os.path.basename(path))[0]
    ax.set_title(f"ttd_sim {name}: final state, {sum(1 for _, s, _ in groups if not s)} moving bodies")
    png = os.path.join(out, name + ".png")
    fig.savefig(png, dpi=100, bbox_inches="tight")
    plt.close(fig)
    print(f"wrote {png}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=".", help="folder for the pictures (default: here)")
    ap.add_argument("obj", nargs="+", help="OBJ files written by ttd_sim --obj")
    args = ap.parse_args()
    try:
        import numpy  # noqa: F401
        import matplotlib  # noqa: F401
    except ImportError as e:
        print(f"picture.py: SKIPPED, no pictures drawn: {e} (apt-get install python3-numpy python3-matplotlib)")
        return 77
    missing = [p for p in args.obj if not os.path.exists(p)]
    if missing:
        print(f"picture.py: missing {', '.join(missing)} (run ttd_sim --obj first)", file=sys.stderr)
        return 1
    for p in args.obj:
        draw(p, args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
