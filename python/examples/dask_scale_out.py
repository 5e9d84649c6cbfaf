# SPDX-License-Identifier: MIT
"""Minimum distance and near pairs over a batch far larger than memory, on a Dask cluster.

    python examples/dask_scale_out.py                               # a LocalCluster here
    python examples/dask_scale_out.py --scheduler tcp://host:8786   # an existing cluster

The same code runs on one machine and on many: only the Client changes. For a cluster, start
`dask-scheduler` on one machine and `dask-worker tcp://host:8786` on each of the others
(every one with ttd installed, `pip install --no-build-isolation ./python`), then pass the
scheduler's address.

The pairs are generated chunk by chunk on the workers (ttd's benchmark workload: vertices
uniform in the unit cube, the second triangle shifted by up to half a unit), so the whole
batch never exists anywhere: the default 50 million float64 pairs are 7.2 GB of coordinates,
of which each worker holds one chunk (2 million pairs, 288 MB) at a time. It prints the
number of intersecting pairs (distance 0), the closest pair that does not intersect (its
closest points computed for that pair alone), how many pairs are within a margin, and --check compares one chunk
with a single ttd.distance call on the same pairs.
"""
import argparse
import time

import dask.array as da
import numpy as np
from distributed import Client, LocalCluster

import ttd
import ttd.dask


def random_pairs(n, chunk, seed, dtype):
    """S and T as lazy dask arrays of shape (n, 9): nothing is generated until computed."""
    rs = da.random.RandomState(seed)
    S = rs.random_sample((n, 9), chunks=(chunk, 9))
    offset = rs.random_sample((n, 3), chunks=(chunk, 3)) - 0.5
    T = rs.random_sample((n, 9), chunks=(chunk, 9)) + da.concatenate([offset] * 3, axis=1)
    return S.astype(dtype), T.astype(dtype)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scheduler", help="address of a running Dask scheduler (default: start a LocalCluster)")
    ap.add_argument("--workers", type=int, default=2, help="LocalCluster worker processes (default 2)")
    ap.add_argument("--pairs", type=int, default=50_000_000, help="number of pairs (default 50,000,000)")
    ap.add_argument("--chunk", type=int, default=2_000_000, help="pairs per chunk (default 2,000,000)")
    ap.add_argument("--precision", choices=["float32", "float64"], default="float64")
    ap.add_argument("--method", choices=ttd.METHODS, default="exact")
    ap.add_argument("--margin", type=float, default=0.01, help="count the pairs closer than this (default 0.01)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--check", action="store_true", help="compare the first chunk with one local ttd.distance call")
    args = ap.parse_args()

    if args.scheduler:
        client = Client(args.scheduler)
    else:
        # One single-threaded process per worker; each ttd call then uses one core (threads=1).
        client = Client(LocalCluster(n_workers=args.workers, threads_per_worker=1, dashboard_address=None))
    print(f"ttd {ttd.version} on {client}")

    S, T = random_pairs(args.pairs, args.chunk, args.seed, args.precision)
    d = ttd.dask.distance(S, T, method=args.method, threads=1)

    separated = da.where(d > 0, d, np.inf)
    t0 = time.perf_counter()
    i_min, d_min, n_touch, n_near = client.compute(
        [separated.argmin(), separated.min(), (d == 0).sum(), (d < args.margin).sum()], sync=True)
    seconds = time.perf_counter() - t0
    print(f"{args.pairs:,} pairs ({args.precision}, {args.method}) in {seconds:.2f} s, "
          f"{1e9 * seconds / args.pairs:.1f} ns per pair including generation")
    print(f"intersecting (distance 0): {n_touch:,}; closer than {args.margin}: {n_near:,}")

    # The details of one pair: fetch its two triangles and compute it alone, with points.
    s, t = client.compute([S[i_min], T[i_min]], sync=True)
    r = ttd.distance(s, t, method=args.method, points=True)
    print(f"closest separated pair: {i_min}, distance {d_min!r}, p = {r.p}, q = {r.q}, "
          f"features {r.feature_p:03b} {r.feature_q:03b}")
    assert r.distance == d_min

    if args.check:
        k = min(args.chunk, args.pairs)
        s, t, dk = client.compute([S[:k], T[:k], d[:k]], sync=True)
        same = np.array_equal(ttd.distance(s, t, method=args.method), dk)
        print(f"check: the first {k:,} distances {'equal' if same else 'DIFFER FROM'} one local call")
        if not same:
            raise SystemExit(1)
    client.close()


if __name__ == "__main__":
    main()
