# SPDX-License-Identifier: MIT
"""Two meshes under a million poses, on a Dask cluster: minimum distance, collision and contacts.

    python examples/dask_mesh_poses.py                               # a LocalCluster here
    python examples/dask_mesh_poses.py --scheduler tcp://host:8786   # an existing cluster
    python examples/dask_mesh_poses.py --mesh-a a.obj --mesh-b b.obj # your meshes (OBJ files)

The same code runs on one machine and on many: only the Client changes (see
examples/dask_scale_out.py for starting a cluster). The poses of b in a's frame are generated
chunk by chunk on the workers (random rotations from normally distributed quaternions,
translations uniform in a box around a), so they never exist in one place. The two meshes go
to the workers by pickling: a ttd.Mesh pickles as its vertex and face arrays and each worker
rebuilds it once (the build is deterministic, so every worker queries the same hierarchy).

It prints how many poses put the meshes in contact (distance 0) and within a margin, the
closest separated pose with its points and triangles (recomputed here from that pose alone),
and the number of triangle pairs within the margin over the first --contact-poses poses.
--check compares the first chunk with one local call.
"""
import argparse
import time

import dask.array as da
import numpy as np
from distributed import Client, LocalCluster

import ttd
import ttd.dask


def icosphere(level):
    """A unit sphere: the icosahedron, each triangle split into four `level` times."""
    t = (1 + 5 ** 0.5) / 2
    v = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t],
         [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]]
    f = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2],
         [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11],
         [6, 2, 10], [8, 6, 7], [9, 8, 1]]
    v = [np.array(x, float) / np.linalg.norm(x) for x in v]
    for _ in range(level):
        mid, g = {}, []

        def middle(i, j):
            if (min(i, j), max(i, j)) not in mid:
                m = v[i] + v[j]
                v.append(m / np.linalg.norm(m))
                mid[min(i, j), max(i, j)] = len(v) - 1
            return mid[min(i, j), max(i, j)]

        for a, b, c in f:
            g += [[a, middle(a, b), middle(c, a)], [b, middle(b, c), middle(a, b)],
                  [c, middle(c, a), middle(b, c)], [middle(a, b), middle(b, c), middle(c, a)]]
        f = g
    return np.array(v), np.array(f)


def torus(R=1.0, r=0.3, nu=40, nv=20):
    """A torus around the z axis, nu x nv quads of two triangles."""
    U, W = np.meshgrid(2 * np.pi * np.arange(nu) / nu, 2 * np.pi * np.arange(nv) / nv, indexing="ij")
    v = np.stack([(R + r * np.cos(W)) * np.cos(U), (R + r * np.cos(W)) * np.sin(U), r * np.sin(W)], -1)
    i, j = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
    a, b = i * nv + j, (i + 1) % nu * nv + j
    c, d = (i + 1) % nu * nv + (j + 1) % nv, i * nv + (j + 1) % nv
    f = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)])
    return v.reshape(-1, 3), f


def read_obj(path):
    """Vertices and triangles of an OBJ file ('v x y z' and 'f i j k ...' lines; polygons fanned)."""
    v, f = [], []
    with open(path) as fh:
        for line in fh:
            parts = line.split()
            if parts and parts[0] == "v":
                v.append([float(x) for x in parts[1:4]])
            elif parts and parts[0] == "f":
                idx = [int(p.split("/")[0]) for p in parts[1:]]
                idx = [i - 1 if i > 0 else len(v) + i for i in idx]  # 1-based, or negative from the end
                f += [[idx[0], idx[k], idx[k + 1]] for k in range(1, len(idx) - 1)]
    return np.array(v, float), np.array(f, np.int64)


def rotations(q):
    """(n, 3, 3) rotation matrices of n quaternions (w, x, y, z), normalised first."""
    w, x, y, z = (q / np.linalg.norm(q, axis=1, keepdims=True)).T
    return np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),
                     2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                     2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], 1).reshape(-1, 3, 3)


def poses_block(q, t):
    """(n, 3, 4) poses [R | t] from n quaternions and translations: one chunk, on a worker."""
    return np.concatenate([rotations(q), t[:, :, None]], axis=2)


def random_poses(n, chunk, box, seed):
    """n poses as a lazy dask array (n, 3, 4): nothing is generated until computed."""
    rs = da.random.RandomState(seed)
    q = rs.standard_normal((n, 4), chunks=(chunk, 4))
    t = box * (2 * rs.random_sample((n, 3), chunks=(chunk, 3)) - 1)
    return da.map_blocks(poses_block, q, t, new_axis=2, chunks=(q.chunks[0], (3,), (4,)), dtype=float)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scheduler", help="address of a running Dask scheduler (default: start a LocalCluster)")
    ap.add_argument("--workers", type=int, default=2, help="LocalCluster worker processes (default 2)")
    ap.add_argument("--poses", type=int, default=1_000_000, help="number of poses (default 1,000,000)")
    ap.add_argument("--chunk", type=int, default=50_000, help="poses per chunk (default 50,000)")
    ap.add_argument("--mesh-a", help="OBJ file of mesh a (default: a sphere of 1,280 triangles)")
    ap.add_argument("--mesh-b", help="OBJ file of mesh b (default: a torus of 1,600 triangles)")
    ap.add_argument("--precision", choices=["float32", "float64"], default="float64")
    ap.add_argument("--box", type=float, default=2.0, help="translations uniform in [-box, box]^3 (default 2)")
    ap.add_argument("--margin", type=float, default=0.01, help="the margin of collision and contacts (default 0.01)")
    ap.add_argument("--contact-poses", type=int, default=20_000,
                    help="poses whose contacts are counted (default 20,000; contacts cost more per pose)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--check", action="store_true", help="compare the first chunk with one local call")
    args = ap.parse_args()

    va, fa = read_obj(args.mesh_a) if args.mesh_a else icosphere(3)
    vb, fb = read_obj(args.mesh_b) if args.mesh_b else torus()
    A = ttd.Mesh(va.astype(args.precision), fa)
    B = ttd.Mesh(vb.astype(args.precision), fb)
    if args.scheduler:
        client = Client(args.scheduler)
    else:
        # One single-threaded process per worker; each ttd call then uses one core (threads=1).
        client = Client(LocalCluster(n_workers=args.workers, threads_per_worker=1, dashboard_address=None))
    print(f"ttd {ttd.version} on {client}; a: {A}; b: {B}")

    P = random_poses(args.poses, args.chunk, args.box, args.seed)
    r = ttd.dask.mesh_distance(A, B, P, threads=1)  # (K,) records: r["distance"], r["p"], ...
    hit = ttd.dask.mesh_collide(A, B, P, args.margin, threads=1)["hit"]
    d = r["distance"]
    separated = da.where(d > 0, d, np.inf)
    t0 = time.perf_counter()
    i_min, d_min, n_touch, n_near, n_hit = client.compute(
        [separated.argmin(), separated.min(), (d == 0).sum(), (d <= args.margin).sum(), (hit != 0).sum()], sync=True)
    seconds = time.perf_counter() - t0
    print(f"{args.poses:,} poses ({args.precision}): distance and collision in {seconds:.2f} s, "
          f"{1e6 * seconds / args.poses:.1f} us per pose including generation")
    print(f"in contact (distance 0): {n_touch:,}; within {args.margin}: {n_near:,} "
          f"(collision query: {n_hit:,})")
    assert n_near == n_hit

    # The closest separated pose, recomputed here from that pose alone.
    pose = client.compute(P[i_min], sync=True)
    one = ttd.mesh_distance(A, B, pose)
    print(f"closest separated pose {i_min}: distance {d_min!r}, triangles {one.tri_a} and {one.tri_b}, "
          f"p = {one.p}, q = {one.q}")
    assert one.distance == d_min

    k = min(args.contact_poses, args.poses)
    parts = ttd.dask.mesh_contacts(A, B, P[:k], args.margin, threads=1)
    t0 = time.perf_counter()
    n_pairs = client.compute(parts.map(lambda c: c.distance.size).sum(), sync=True)
    print(f"triangle pairs within {args.margin} over the first {k:,} poses: {n_pairs:,} "
          f"({time.perf_counter() - t0:.2f} s)")

    if args.check:
        k = min(args.chunk, args.poses)
        poses, got = client.compute([P[:k], r[:k]], sync=True)
        here = ttd.mesh_distance(A, B, poses)
        same = all(np.array_equal(got[f], getattr(here, f)) for f in ("distance", "p", "q", "tri_a", "tri_b"))
        print(f"check: the first {k:,} poses {'equal' if same else 'DIFFER FROM'} one local call")
        if not same:
            raise SystemExit(1)
    client.close()


if __name__ == "__main__":
    main()
