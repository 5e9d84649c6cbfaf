# SPDX-License-Identifier: MIT
"""Batches larger than one machine's memory, on Dask: ttd.distance chunk by chunk.

    import dask.array as da
    from distributed import Client
    import ttd.dask

    client = Client("tcp://scheduler:8786")   # a cluster; Client(LocalCluster()) on one machine
    S = da.from_zarr("S.zarr")                # (n, 9) or (n, 3, 3), chunked along the pairs
    T = da.from_zarr("T.zarr")
    d = ttd.dask.distance(S, T, threads=1)    # lazy: a dask array of n distances
    d.min().compute(), (d < 0.01).sum().compute()

Each chunk is one ttd.distance call on a worker, so only a chunk of pairs (72 bytes per float32
triangle pair, 144 per float64, plus its distances) must fit in a worker's memory at once.
The result equals one ttd.distance call on all the pairs, bit for bit: a pair's result
depends on that pair alone, not on its neighbours, the chunking or the thread count.

ttd.distance's threads option is per call: threads=0 (its default) uses every core of the
worker's machine in each call, which suits one worker thread per machine; with several worker
threads (or processes) per machine, threads=1 keeps them from competing for the cores.
Warnings (non-finite input, non-convergence) are issued on the workers, where Dask logs them.
"""
import functools

import numpy as np

import ttd

__all__ = ["distance"]


def _pairs_2d(X, name):
    if X.ndim == 2 and X.shape[1] == 9:
        return X
    if X.ndim == 3 and X.shape[1:] == (3, 3):
        return X.reshape((X.shape[0], 9))
    raise ValueError(f"{name} has shape {X.shape}: ttd.dask.distance takes (n, 9) or (n, 3, 3) arrays")


def distance(S, T, **options):
    """Distances of the pairs S[i], T[i] as a lazy dask array, one ttd.distance call per chunk.

    S, T: dask arrays (or anything dask.array.asarray takes) of shape (n, 9) or (n, 3, 3),
    chunked along the first axis; T is rechunked to S's chunks where they differ, and each
    triangle is kept whole within a chunk. options: those of ttd.distance (method, precision,
    isa, threads, rho, tol, max_iterations), checked here, before anything is computed, as is
    the dtype rule. points=True is not offered: compute the points of the pairs you keep (say,
    those within a margin) with ttd.distance(..., points=True) on them.

    Returns a dask array of shape (n,) and dtype float32 or float64 (as ttd.distance would).
    """
    import dask.array as da

    if options.get("points"):
        raise ValueError("ttd.dask.distance returns distances only; call ttd.distance(..., points=True) "
                         "on the pairs whose points you need")
    S = _pairs_2d(da.asarray(S), "S")
    T = _pairs_2d(da.asarray(T), "T")
    if S.shape[0] != T.shape[0]:
        raise ValueError(f"S and T hold {S.shape[0]} and {T.shape[0]} pairs: they must be equal")
    # Options and dtypes are checked now, on no pairs; the empty result gives the dtype.
    empty = ttd.distance(np.zeros((0, 9), S.dtype), np.zeros((0, 9), T.dtype), **options)
    S = S.rechunk({1: -1})
    T = T.rechunk((S.chunks[0], (9,)))
    return da.map_blocks(functools.partial(ttd.distance, **options), S, T, drop_axis=1, dtype=empty.dtype,
                         meta=empty, chunks=(S.chunks[0],))
