# SPDX-License-Identifier: MIT
"""Python threads and ttd: the interpreter lock is released while the library computes (so
threads run in parallel), and concurrent calls give the results of sequential ones, for the
pair API, the mesh queries and the mesh build. Checked by what happens, not by timing: the
speed ratio is bench/python_overhead.py's job."""
import sys
import threading

import numpy as np
import pytest

import ttd
from cases import random_pairs
from meshes import icosphere, random_poses, torus


@pytest.fixture
def long_switch_interval():
    """With a 100 s switch interval a thread that holds the interpreter lock keeps it until it
    blocks or releases it itself: the interpreter never takes it away in between."""
    old = sys.getswitchinterval()
    sys.setswitchinterval(100.0)
    yield
    sys.setswitchinterval(old)


def released_during(call):
    """True when the interpreter lock was released while call() ran (see below)."""
    started, returned = threading.Event(), threading.Event()
    seen = []

    def observer():
        started.wait()
        seen.append(returned.is_set())

    def caller():
        started.set()
        call()
        returned.set()

    threads = [threading.Thread(target=observer), threading.Thread(target=caller)]
    threads[0].start()
    threads[1].start()
    for t in threads:
        t.join()
    return seen == [False]


@pytest.mark.parametrize("points", [False, True])
@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_lock_is_released_during_the_call(long_switch_interval, points, dtype):
    # The caller sets `started` and calls ttd (without blocking in between). The observer,
    # woken by `started`, can only get the lock when the caller gives it up: inside ttd if the
    # call releases it, otherwise only after the call has returned and `returned` is set.
    # So the observer sees `returned` unset exactly when the lock was released in the call.
    # The call lasts tens of milliseconds (the penalty method, one thread), far longer than
    # the observer needs to be woken and scheduled even on a busy machine.
    S, T = random_pairs(600_000, seed=41, dtype=dtype)
    started, returned = threading.Event(), threading.Event()
    seen = []

    def observer():
        started.wait()
        seen.append(returned.is_set())

    def caller():
        started.set()
        ttd.distance(S, T, method="penalty", threads=1, points=points)
        returned.set()

    threads = [threading.Thread(target=observer), threading.Thread(target=caller)]
    threads[0].start()
    threads[1].start()
    for t in threads:
        t.join()
    assert seen == [False], "the observer ran only after ttd.distance returned: the lock was held"


def test_concurrent_calls_give_the_sequential_results():
    batches = [random_pairs(50_000, seed=42 + k) for k in range(4)]
    methods = ["exact", "penalty", "certified", "exact"]
    expected = [ttd.distance(S, T, method=m, points=True) for (S, T), m in zip(batches, methods)]
    got = [None] * 4
    barrier = threading.Barrier(4)

    def work(k):
        barrier.wait()
        S, T = batches[k]
        for _ in range(3):
            got[k] = ttd.distance(S, T, method=methods[k], points=True, threads=2)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for r, e in zip(got, expected):
        for a, b in zip(r, e):
            np.testing.assert_array_equal(a, b)


def test_two_threads_on_one_batch():
    # The task's check: two Python threads calling at once on the same arrays.
    S, T = random_pairs(200_000, seed=46)
    expected = ttd.distance(S, T)
    out = [None, None]

    def work(k):
        out[k] = ttd.distance(S, T, threads=1)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    np.testing.assert_array_equal(out[0], expected)
    np.testing.assert_array_equal(out[1], expected)


def big_meshes(dtype=np.float64):
    (va, fa), (vb, fb) = icosphere(3), torus(1.0, 0.3, 40, 20)
    return ttd.Mesh(va.astype(dtype), fa), ttd.Mesh(vb.astype(dtype), fb)


@pytest.mark.parametrize("query", ["distance", "contacts", "closest", "collide"])
@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_lock_is_released_during_mesh_queries(long_switch_interval, query, dtype):
    # As above: each call lasts tens of milliseconds on one thread (1,280 x 1,600 triangles).
    # The poses are of the meshes' dtype: a conversion by numpy would release the lock itself.
    A, B = big_meshes(dtype)
    P = random_poses(4000 if query in ("distance", "collide") else 300, seed=43, spread=1.2).astype(dtype)
    calls = {"distance": lambda: ttd.mesh_distance(A, B, P, threads=1),
             "contacts": lambda: ttd.mesh_contacts(A, B, P, 0.02, threads=1),
             "closest": lambda: ttd.mesh_closest(A, B, P, 0.02, threads=1),
             "collide": lambda: ttd.mesh_collide(A, B, P, 0.3, threads=1)}
    assert released_during(calls[query]), "the observer ran only after the query returned: the lock was held"


def test_lock_is_released_while_a_mesh_is_built(long_switch_interval):
    # 200,000 triangles over 100 vertices: hundreds of milliseconds to build on one thread. The
    # arrays need no conversion by numpy, which would release the lock itself and let the
    # observer in before the build.
    rng = np.random.default_rng(47)
    V = rng.random((100, 3))
    F = rng.integers(0, 100, (200_000, 3))
    assert released_during(lambda: ttd.Mesh(V, F, threads=1))


def test_concurrent_mesh_queries_give_the_sequential_results():
    # Two (and four) Python threads query the same meshes at once: the results of one thread alone.
    A, B = big_meshes()
    P = [random_poses(150, seed=44 + k, spread=1.2) for k in range(4)]
    kinds = ["distance", "contacts", "distance", "collide"]

    def run(k, threads):
        if kinds[k] == "distance":
            return ttd.mesh_distance(A, B, P[k], threads=threads)
        if kinds[k] == "contacts":
            return ttd.mesh_contacts(A, B, P[k], 0.02, threads=threads)
        return ttd.mesh_collide(A, B, P[k], 0.1, threads=threads)

    expected = [run(k, 1) for k in range(4)]
    for n in (2, 4):
        got = [None] * n
        barrier = threading.Barrier(n)

        def work(k):
            barrier.wait()
            for _ in range(2):
                got[k] = run(k, 2)

        threads = [threading.Thread(target=work, args=(k,)) for k in range(n)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        for k in range(n):
            for a, b in zip(got[k], expected[k]):
                np.testing.assert_array_equal(a, b)
