# SPDX-License-Identifier: MIT
"""Ctrl-C in long calls: a child process starts a call sized to take about 30 seconds
(ttd.sdf_grid, ttd.closest_points on a large batch, ttd.mesh_distance and ttd.mesh_contacts over
many poses), the test
sends it SIGINT a second in, and the call must end with KeyboardInterrupt within a few seconds
(the extension checks for signals between pieces of the batch, from the calling thread), leaving
the mesh usable (no query still marked in use) for the next call."""
import os
import pathlib
import signal
import subprocess
import sys
import time

import pytest

TESTS = pathlib.Path(__file__).resolve().parent

CHILD = r"""
import sys, time
import numpy as np, ttd
sys.path.insert(0, sys.argv[2])
from meshes import icosphere, random_poses

what = sys.argv[1]
v, f = icosphere(6 if what != "grid" else 4)
M = ttd.Mesh(v, f)
rng = np.random.default_rng(7)
if what == "grid":
    work = lambda n: ttd.sdf_grid(M, [-1.5, -1.5, -1.5], 0.01, (n, 200, 200))
    small, cap = 5, 800                         # slabs of 40,000 points; at most 256 MB of output
elif what == "points":
    P = rng.uniform(-20, 20, (6_000_000, 3))    # far points: the longest walks
    work = lambda n: ttd.closest_points(M, P[:n])
    small, cap = 100_000, len(P)
elif what == "contacts":
    poses = np.tile(random_poses(2_000, seed=3, spread=0), (100, 1, 1))
    poses[:, 0, 3] = 2.0                        # spheres all but touching: about 20 contacts a pose,
    work = lambda n: ttd.mesh_contacts(M, M, poses[:n], 2e-4)  # 0.16 ms; 200 MB if not stopped
    small, cap = 200, len(poses)
else:
    poses = np.tile(random_poses(2_000, seed=3, spread=0), (100, 1, 1))
    poses[:, 0, 3] = 2.5                        # copies of a sphere of 81,920 triangles, 0.5 apart
    work = lambda n: ttd.mesh_distance(M, M, poses[:n])
    small, cap = 200, len(poses)
t = time.monotonic(); work(small); rate = small / (time.monotonic() - t)
n = int(min(cap, max(small, 30 * rate)))       # about 30 s of work, within the memory cap
print("start", n / rate, flush=True)
t0 = time.monotonic()
try:
    work(n)
    print("finished", time.monotonic() - t0, flush=True)
except KeyboardInterrupt:
    print("interrupted", time.monotonic() - t0, flush=True)
    ttd.closest_points(M, np.zeros((1, 3)))    # everything released: the mesh serves the next call
    M.set_vertices(v)                          # and is not marked as in use by the stopped one
    print("usable", flush=True)
"""


@pytest.mark.skipif(not hasattr(signal, "SIGINT") or os.name != "posix", reason="POSIX signals")
@pytest.mark.parametrize("what", ["grid", "points", "mesh", "contacts"])
def test_ctrl_c_stops_a_long_call(what):
    child = subprocess.Popen([sys.executable, "-c", CHILD, what, str(TESTS)], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True)
    try:
        line = child.stdout.readline().split()
        assert line and line[0] == "start", (line, child.stderr.read())
        expected = float(line[1])
        time.sleep(1.0)
        child.send_signal(signal.SIGINT)
        sent = time.monotonic()
        out, err = child.communicate(timeout=120)
        took = time.monotonic() - sent
    finally:
        if child.poll() is None:
            child.kill()
            child.wait()
    assert "interrupted" in out and "usable" in out, (out, err)
    # the whole call would take `expected` seconds; it must stop within a few after the signal
    # (the pieces take about 0.1 s; the margin is for a loaded machine and the interpreter's exit)
    assert expected > 8, f"the call was sized to {expected:.1f} s: too short to tell an interrupt from its end"
    assert took < 5, f"{what}: stopped {took:.1f} s after SIGINT (the whole call: about {expected:.0f} s)"
