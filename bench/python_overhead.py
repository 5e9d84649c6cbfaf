# SPDX-License-Identifier: MIT
"""The Python package's overhead against the C calls it makes, and its thread scaling.

    build/python-venv/bin/python bench/python_overhead.py [--quick] [--only-mesh]

(the interpreter of the venv that scripts/test-python.sh makes and installs ttd into; any
interpreter with ttd installed will do). It measures, in one process:

1. one pair per call: ttd.distance(s, t) in a Python loop against the same library call
   (ttd_batch_d with n = 1, the same options) in a C loop (ttd._ctiming, built into the
   package for this benchmark only when TTD_PYTHON_CTIMING=1, as scripts/test-python.sh does;
   wheels and plain installs leave it out). The C loop runs in the same process on the same arrays,
   so the difference is what Python adds per call: argument parsing, array checks, the output
   array and the lock release. (Timing the C call through ctypes instead would charge ctypes'
   own per-call cost, about a microsecond, to the C side.) Target: at most 5 us per call.
2. a 1,000,000-pair batch: ttd.distance(S, T) against the same C call, one and all threads,
   returning new arrays and writing into a reused one (out=); the C call writes into that
   same reused array, so that the two differ only in the call (no page faults on either side,
   the same memory written). Target: at most 5% over the C call.
3. two Python threads each computing a batch with threads=1, against one thread computing
   both: the speedup from releasing the interpreter lock, beside the same measurement made
   with two threads calling the C loop (the most two threads get on this machine).
4. mesh queries over many poses per call: ttd.mesh_distance, mesh_collide, mesh_contacts and
   mesh_closest on two meshes (a sphere of 1,280 and a torus of 1,600 triangles) under K random
   poses, against the same ttd_mesh_* call made from C on meshes built from the same arrays
   (ttd._ctiming.time_mesh_calls), per pose. Target: as fast per pose as the C API (ratio 1).
   The C side of distance and collide writes into the array the Python call writes with out=;
   its contacts reuse one contact set across calls, as a C caller would (and, as a control, a
   fresh one per call, as each Python call gets: the difference is the cost of new memory).
   Also one pose per call (a far pose, collision, one thread: a call of a few microseconds):
   the overhead per call.

Timings alternate between the Python and the C side (in rotating order), repeat, and report
medians; ratios are taken within the run. The machine's load is printed: on a shared machine, read the ratios,
not the absolute times.
"""
import argparse
import os
import platform
import statistics
import threading
import time

import numpy as np

import ttd
from ttd import _ctiming


def cpu_name():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def random_pairs(n, seed, dtype):
    """ttd's benchmark workload: vertices uniform in [0,1)^3, T shifted by up to half a unit."""
    rng = np.random.default_rng(seed)
    S = rng.random((n, 9))
    T = rng.random((n, 9)) + np.tile(rng.random((n, 3)) - 0.5, 3)
    return S.astype(dtype), T.astype(dtype)


def alternate(py, c, repeats):
    """Median seconds of py() and of c(), run alternately `repeats` times each."""
    tp, tc = [], []
    for _ in range(repeats):
        tp.append(py())
        tc.append(c())
    return statistics.median(tp), statistics.median(tc)


def single_pair(dtype, points, calls, repeats):
    s, t = random_pairs(1, 1, dtype)
    s, t = s[0], t[0]
    f = ttd.distance

    def py():
        t0 = time.perf_counter()
        if points:
            for _ in range(calls):
                f(s, t, points=True)
        else:
            for _ in range(calls):
                f(s, t)
        return time.perf_counter() - t0

    out = np.empty(1, ttd.RESULT_DTYPE_FLOAT64 if dtype == np.float64 else ttd.RESULT_DTYPE_FLOAT32) \
        if points else np.empty(1, dtype)

    def c():
        return _ctiming.time_calls(s, t, out, calls, points=points)

    tp, tc = alternate(py, c, repeats)
    return 1e9 * tp / calls, 1e9 * tc / calls


def batch(S, T, threads, points, repeats):
    """Median seconds of the Python call returning new arrays, of the Python call writing into
    a reused out= array, and of the C call (into a reused buffer), run in turn."""
    out = np.empty(len(S), ttd.RESULT_DTYPE_FLOAT64 if S.dtype == np.float64 else ttd.RESULT_DTYPE_FLOAT32) \
        if points else np.empty(len(S), S.dtype)

    def timed(**kw):
        t0 = time.perf_counter()
        ttd.distance(S, T, threads=threads, points=points, **kw)
        return time.perf_counter() - t0

    runs = [lambda: timed(), lambda: timed(out=out),
            lambda: _ctiming.time_calls(S, T, out, 1, threads=threads, points=points)]
    times = [[], [], []]
    for k in range(repeats):
        for i in range(3):  # each one first, second and third in turn: no side always follows another
            j = (i + k) % 3
            times[j].append(runs[j]())
    return tuple(statistics.median(t) for t in times)


def two_threads(work_a, work_b, repeats):
    """(one thread doing a then b, two threads doing a and b at once): median seconds."""

    def sequential():
        t0 = time.perf_counter()
        work_a()
        work_b()
        return time.perf_counter() - t0

    def parallel():
        threads = [threading.Thread(target=work_a), threading.Thread(target=work_b)]
        t0 = time.perf_counter()
        for th in threads:
            th.start()
        for th in threads:
            th.join()
        return time.perf_counter() - t0

    return alternate(sequential, parallel, repeats)


# ---- meshes over many poses -------------------------------------------------------------------

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
    return np.array(v), np.array(f, np.uint32)


def torus(R=1.0, r=0.3, nu=40, nv=20):
    U, W = np.meshgrid(2 * np.pi * np.arange(nu) / nu, 2 * np.pi * np.arange(nv) / nv, indexing="ij")
    v = np.stack([(R + r * np.cos(W)) * np.cos(U), (R + r * np.cos(W)) * np.sin(U), r * np.sin(W)], -1)
    i, j = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
    a, b = i * nv + j, (i + 1) % nu * nv + j
    c, d = (i + 1) % nu * nv + (j + 1) % nv, i * nv + (j + 1) % nv
    f = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)])
    return v.reshape(-1, 3), f.astype(np.uint32)


def random_poses(k, seed, box):
    """k poses (k, 3, 4): rotations from normally distributed quaternions, translations in [-box, box]^3."""
    rng = np.random.default_rng(seed)
    q = rng.standard_normal((k, 4))
    w, x, y, z = (q / np.linalg.norm(q, axis=1, keepdims=True)).T
    R = np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),
                  2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                  2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], 1).reshape(-1, 3, 3)
    return np.concatenate([R, box * (2 * rng.random((k, 3, 1)) - 1)], axis=2)


def mesh_rows(args):
    """Part 4: Python vs C per pose for each query, and the overhead of one pose per call."""
    (va, fa), (vb, fb) = icosphere(3), torus()
    print(f"   meshes: a sphere of {len(fa):,} triangles, a torus of {len(fb):,}; poses: random rotations, "
          f"translations in [-2, 2]^3; margin 0.01")
    print(f"   {'':38}{'K':>7}{'new':>9}{'out=':>9}{'C':>9}{'new/C':>8}{'out=/C':>8}{'best':>7}  us per pose (new, C); "
          f"target 1.00")
    print("   (medians; 'best': the fastest Python call (out= where offered) / the fastest C call, which contention"
          " on a shared machine disturbs least)")
    for dtype in (np.float64, np.float32):
        A, B = ttd.Mesh(va.astype(dtype), fa), ttd.Mesh(vb.astype(dtype), fb)
        cargs = (A.vertices, A.faces, B.vertices, B.faces)
        f64 = dtype == np.float64
        for query, k, threads in (("distance", args.poses, 1), ("distance", args.poses, 0), ("collide", args.poses, 1),
                                  ("contacts", args.contact_poses, 1), ("closest", args.contact_poses, 1)):
            P = random_poses(k, 5, 2.0).astype(dtype)
            out = out2 = None
            if query == "distance":
                out = np.empty(k, ttd.MESH_RESULT_DTYPE_FLOAT64 if f64 else ttd.MESH_RESULT_DTYPE_FLOAT32)
                py_new = lambda: ttd.mesh_distance(A, B, P, threads=threads)  # noqa: E731
                py_out = lambda: ttd.mesh_distance(A, B, P, threads=threads, out=out)  # noqa: E731
            elif query == "collide":
                out = np.empty(k, ttd.COLLISION_DTYPE)
                py_new = lambda: ttd.mesh_collide(A, B, P, 0.01, threads=threads)  # noqa: E731
                py_out = lambda: ttd.mesh_collide(A, B, P, 0.01, threads=threads, out=out)  # noqa: E731
            elif query == "contacts":
                py_new = py_out = lambda: ttd.mesh_contacts(A, B, P, 0.01, threads=threads)  # noqa: E731
            else:
                rec = ttd.CLOSEST_DTYPE_FLOAT64 if f64 else ttd.CLOSEST_DTYPE_FLOAT32
                out, out2 = np.empty((k, len(fa)), rec), np.empty((k, len(fb)), rec)
                py_new = lambda: ttd.mesh_closest(A, B, P, 0.01, threads=threads)  # noqa: E731
                py_out = lambda: ttd.mesh_closest(A, B, P, 0.01, threads=threads, out=(out, out2))  # noqa: E731

            def timed(f):
                t0 = time.perf_counter()
                f()
                return time.perf_counter() - t0

            runs = [lambda: timed(py_new), lambda: timed(py_out),
                    lambda: _ctiming.time_mesh_calls(*cargs, P, 1, query=query, margin=0.01, threads=threads,
                                                     out=out, out2=out2)]
            if query == "contacts":  # the control: C with a fresh contact set per call
                runs.append(lambda: _ctiming.time_mesh_calls(*cargs, P, 1, query=query, margin=0.01, threads=threads,
                                                             fresh=True))
            times = [[] for _ in runs]
            for r in range(args.repeats):
                for i in range(len(runs)):
                    j = (i + r) % len(runs)
                    times[j].append(runs[j]())
            med = [statistics.median(t) for t in times]
            label = f"{np.dtype(dtype).name}, {query}, threads={threads}{' (all)' if threads == 0 else ''}"
            same_out = query == "contacts"
            print(f"   {label:38}{k:7,}{med[0]:9.4f}{'':9}" if same_out else
                  f"   {label:38}{k:7,}{med[0]:9.4f}{med[1]:9.4f}", end="")
            best = min(times[0] if same_out else times[1]) / min(times[2])
            print(f"{med[2]:9.4f}{med[0] / med[2]:8.3f}{'' if same_out else f'{med[1] / med[2]:8.3f}':>8}{best:7.3f}"
                  f"  {1e6 * med[0] / k:.2f}, {1e6 * med[2] / k:.2f}")
            if query == "contacts":
                n = len(py_new().pose)
                print(f"   {'':38}{'':7}  ({n:,} contacts; C with a fresh set per call, as Python: {med[3]:.4f} s, "
                      f"new/that = {med[0] / med[3]:.3f})")
        # One far pose per call, collision on one thread (it stops at the roots' boxes): the
        # overhead per call.
        one = random_poses(1, 6, 0.0)[0].astype(dtype)
        one[:, 3] = [5, 0, 0]
        calls = args.calls
        crec = np.empty(1, ttd.COLLISION_DTYPE)

        def py_one():
            t0 = time.perf_counter()
            for _ in range(calls):
                ttd.mesh_collide(A, B, one, threads=1)
            return time.perf_counter() - t0

        tp, tc = alternate(py_one, lambda: _ctiming.time_mesh_calls(*cargs, one, calls, query="collide", threads=1,
                                                                    out=crec), args.repeats)
        mark = "met" if tp - tc <= 5e-6 * calls else "MISSED"
        print(f"   {np.dtype(dtype).name}, collide, one far pose per call, threads=1: Python {1e9 * tp / calls:.0f} ns, "
              f"C {1e9 * tc / calls:.0f} ns, overhead {1e9 * (tp - tc) / calls:.0f} ns per call (target <= 5000: {mark})")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--pairs", type=int, default=1_000_000, help="batch size (default 1,000,000)")
    ap.add_argument("--calls", type=int, default=200_000, help="single-pair calls per timing (default 200,000)")
    ap.add_argument("--repeats", type=int, default=15, help="timings per measurement, median taken (default 15)")
    ap.add_argument("--poses", type=int, default=10_000, help="poses per mesh distance / collide call (default 10,000)")
    ap.add_argument("--contact-poses", type=int, default=1_000,
                    help="poses per mesh contacts / closest call (default 1,000)")
    ap.add_argument("--only-mesh", action="store_true", help="part 4 (the mesh queries) only")
    ap.add_argument("--quick", action="store_true",
                    help="a few seconds: 100,000 pairs, 20,000 calls, 1,000 / 200 poses, 3 repeats")
    args = ap.parse_args()
    if args.quick:
        args.pairs, args.calls, args.repeats, args.poses, args.contact_poses = 100_000, 20_000, 3, 1_000, 200

    load0 = os.getloadavg()
    print(f"ttd {ttd.version}, Python {platform.python_version()}, numpy {np.__version__}; "
          f"{cpu_name()}, {os.cpu_count()} cores, instruction set {ttd.isa_selected()}")
    print(f"load average before: {load0[0]:.2f} {load0[1]:.2f} {load0[2]:.2f} (1, 5, 15 min)\n")

    if args.only_mesh:
        print("4. mesh queries, many poses per call: Python call / C call, median seconds per call")
        mesh_rows(args)
        load1 = os.getloadavg()
        print(f"\nload average after: {load1[0]:.2f} {load1[1]:.2f} {load1[2]:.2f}")
        return

    print("1. one pair per call (exact method): Python call vs the same C call, ns per call")
    print(f"   {'':28}{'Python':>10}{'C':>10}{'overhead':>10}  target <= 5000 ns")
    for dtype in (np.float64, np.float32):
        for points in (False, True):
            py, c = single_pair(dtype, points, args.calls, args.repeats)
            label = f"{np.dtype(dtype).name}, {'points=True' if points else 'distances'}"
            mark = "met" if py - c <= 5000 else "MISSED"
            print(f"   {label:28}{py:10.0f}{c:10.0f}{py - c:10.0f}  {mark}")

    print(f"\n2. {args.pairs:,} pairs per call (exact method): Python call / C call, median seconds;")
    print("   'new': ttd.distance returns new arrays; 'out=': it writes into a reused array, as the C call does")
    print(f"   {'':36}{'new':>9}{'out=':>9}{'C':>9}{'new/C':>8}{'out=/C':>8}  target <= 1.05")
    S, T = random_pairs(args.pairs, 2, np.float64)
    S32, T32 = S.astype(np.float32), T.astype(np.float32)
    for label, (a, b) in (("float64", (S, T)), ("float32", (S32, T32))):
        for threads in (1, 0):
            for points in (False, True):
                tn, to, tc = batch(a, b, threads, points, args.repeats)
                row = f"{label}, threads={threads}{' (all)' if threads == 0 else ''}, " \
                      f"{'points' if points else 'distances'}"
                marks = "/".join("met" if x / tc <= 1.05 else "MISSED" for x in (tn, to))
                print(f"   {row:36}{tn:9.4f}{to:9.4f}{tc:9.4f}{tn / tc:8.3f}{to / tc:8.3f}  {marks}")
    # The noise floor: the same C call timed as two sides, as above.
    out = np.empty(len(S), ttd.RESULT_DTYPE_FLOAT64)
    a, b = alternate(lambda: _ctiming.time_calls(S, T, out, 1, threads=1, points=True),
                     lambda: _ctiming.time_calls(S, T, out, 1, threads=1, points=True), args.repeats)
    print(f"   control: the float64 threads=1 points C call against itself: {a:.4f} / {b:.4f} = {a / b:.3f}")

    print(f"\n3. two threads, each {args.pairs:,} pairs with threads=1: one thread doing both / two at once")
    S2, T2 = random_pairs(args.pairs, 3, np.float64)
    out1, out2 = np.empty(len(S)), np.empty(len(S2))
    rows = [
        ("ttd.distance, out=", lambda: ttd.distance(S, T, threads=1, out=out1),
         lambda: ttd.distance(S2, T2, threads=1, out=out2)),
        ("ttd.distance, new arrays", lambda: ttd.distance(S, T, threads=1),
         lambda: ttd.distance(S2, T2, threads=1)),
        ("the C loop (_ctiming)", lambda: _ctiming.time_calls(S, T, out1, 1, threads=1),
         lambda: _ctiming.time_calls(S2, T2, out2, 1, threads=1)),
    ]
    speedups = {}
    for label, a, b in rows:
        seq, par = two_threads(a, b, args.repeats)
        speedups[label] = seq / par
        print(f"   Python threads calling {label:26}{seq:8.4f} s /{par:8.4f} s = {seq / par:.2f}x")
    c = speedups["the C loop (_ctiming)"]
    print(f"   the C loop's speedup is what two threads get here; ttd.distance reaches "
          f"{speedups['ttd.distance, out='] / c:.2f} of it with out=, "
          f"{speedups['ttd.distance, new arrays'] / c:.2f} with new arrays (1.00: the lock costs nothing)")

    print("\n4. mesh queries, many poses per call: Python call / C call, median seconds per call")
    mesh_rows(args)

    load1 = os.getloadavg()
    print(f"\nload average after: {load1[0]:.2f} {load1[1]:.2f} {load1[2]:.2f}; other processes share "
          f"the cores when it exceeds what this benchmark runs (1 thread, 2 in part 3 and threads=0)")


if __name__ == "__main__":
    main()
