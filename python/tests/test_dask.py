# SPDX-License-Identifier: MIT
"""Scale-out on Dask: ttd.dask.distance on a distributed.LocalCluster of two worker processes
(what a real cluster runs, pickling included) equals one ttd.distance call, bit for bit, with
chunks that do not align with the library's 256-pair blocks or its SIMD lanes."""
import numpy as np
import pytest

import ttd
from cases import random_pairs

da = pytest.importorskip("dask.array", reason="python3-dask is not installed")
distributed = pytest.importorskip("distributed", reason="python3-distributed is not installed")
import ttd.dask  # noqa: E402  (after the skip: it needs dask)


@pytest.fixture(scope="module")
def client():
    # Two single-threaded worker processes, no dashboard: a few seconds to start.
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  silence_logs=40) as cluster, distributed.Client(cluster) as c:
        yield c


@pytest.mark.parametrize("method,dtype", [("exact", np.float64), ("exact", np.float32),
                                          ("penalty", np.float64), ("certified", np.float32)])
def test_chunks_on_a_cluster_equal_one_call(client, method, dtype):
    S, T = random_pairs(60_001, seed=51, dtype=dtype)
    one_call = ttd.distance(S, T, method=method)
    dS = da.from_array(S, chunks=(4_993, 3, 3))  # a prime chunk length
    dT = da.from_array(T.reshape(-1, 9), chunks=(10_000, 9))  # other chunks: rechunked to S's
    d = ttd.dask.distance(dS, dT, method=method, threads=1)
    assert d.dtype == dtype and d.shape == (60_001,) and d.numblocks == (13,)
    got = client.compute(d).result()
    assert got.dtype == dtype
    np.testing.assert_array_equal(got, one_call)
    # Reductions run on the workers too.
    assert client.compute(d.min()).result() == one_call.min()
    assert client.compute((d == 0).sum()).result() == np.count_nonzero(one_call == 0)


def test_pairs_generated_on_the_workers(client):
    # The example's pattern: pairs that never exist in one place; every chunk is made on a
    # worker from the seed. Checked against one call on the same pairs made here.
    n, chunk = 200_000, 25_000
    S = da.random.RandomState(7).random_sample((n, 9), chunks=(chunk, 9))
    T = da.random.RandomState(8).random_sample((n, 9), chunks=(chunk, 9)) + 0.25
    d = ttd.dask.distance(S, T)
    got = client.compute(d).result()
    np.testing.assert_array_equal(got, ttd.distance(*client.compute([S, T], sync=True)))


def test_bad_arguments_fail_before_computing():
    S = da.zeros((100, 9), chunks=10)
    with pytest.raises(ValueError, match="method="):
        ttd.dask.distance(S, S, method="nope")
    with pytest.raises(TypeError, match="S has dtype float64 and T has dtype float32"):
        ttd.dask.distance(S, S.astype(np.float32))
    with pytest.raises(ValueError, match=r"S has shape \(100, 8\)"):
        ttd.dask.distance(da.zeros((100, 8)), S)
    with pytest.raises(ValueError, match="100 and 99 pairs"):
        ttd.dask.distance(S, S[:99])
    with pytest.raises(ValueError, match="distances only"):
        ttd.dask.distance(S, S, points=True)
