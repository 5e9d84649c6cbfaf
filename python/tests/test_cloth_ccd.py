# SPDX-License-Identifier: MIT
"""python/examples/cloth.py's fast scenarios, CCD limiting every step (docs/ccd.md, section 11):
a sheet thrown at 40 m/s onto a plate 0.02 thick, and a sheet's half turned down onto the other
half with its edge at 40 m/s. Every step's motion is checked by the discrete queries at 8 times
along it (self-collide with the pairs sharing one vertex, and the sheet against the plate) and
by the scenarios' side checks; with CCD no step may touch or cross, and the same scenario
without CCD must cross (so the checks can fail)."""
import importlib.util
import pathlib
import subprocess
import sys

import numpy as np
import pytest

EXAMPLES = pathlib.Path(__file__).resolve().parents[1] / "examples"


@pytest.fixture(scope="module")
def cloth():
    spec = importlib.util.spec_from_file_location("cloth", EXAMPLES / "cloth.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_fall_onto_plate_never_crosses(cloth):
    r = cloth.simulate_fast("fall", n=12, steps=30, samples=8, threads=1)
    assert r["first_crossing"] is None, r["first_crossing"]
    limited = [x for x in r["records"] if x[1]]
    assert limited, "CCD never limited a step: the fall is not fast enough to show anything"
    assert all(x[5] is None for x in r["records"])
    # the sheet ends on the plate: above its top, within two thicknesses of it
    X = r["X"]
    assert X[:, 2].min() > 0 and X[:, 2].min() < 2 * r["thickness"], X[:, 2].min()


def test_fall_without_ccd_passes_through(cloth):
    r = cloth.simulate_fast("fall", n=12, steps=30, samples=8, ccd=False, threads=1)
    assert r["first_crossing"] is not None
    step, what = r["first_crossing"]
    assert step <= 3, r["first_crossing"]
    # steps carried the sheet from above the plate to under it
    assert r["X"][:, 2].min() < -cloth.PLATE_THICKNESS


def test_fold_never_crosses(cloth):
    r = cloth.simulate_fast("fold", n=16, steps=40, samples=8, threads=1)
    assert r["first_crossing"] is None, r["first_crossing"]
    assert any(x[1] for x in r["records"]), "CCD never limited a step"
    # folded: the turning half lies over the held half, above it
    V, _, _ = cloth.sheet(16)
    turning = V[:, 0] > 1e-12
    X = r["X"]
    assert X[turning, 0].max() < 0 and X[turning, 0].min() < -0.8, (X[turning, 0].min(), X[turning, 0].max())
    assert X[turning, 2].min() > X[~turning, 2].max() - 1e-12


def test_fold_without_ccd_crosses(cloth):
    r = cloth.simulate_fast("fold", n=16, steps=40, samples=8, ccd=False, threads=1)
    assert r["first_crossing"] is not None
    assert "self-collide" in r["first_crossing"][1] or "under the lying half" in r["first_crossing"][1]


def test_limit_step_stops_short_of_impact(cloth):
    """limit_step on one step through the plate: the sheet's vertices move straight down 0.5
    from 0.2 above it; every vertex ends above the plate, short of the plate's top by the
    fraction kept, and a vertex stopped is where its path meets fraction * toi."""
    V, F, _ = cloth.sheet(6, height=0.2, tilt=(0.0, 0.0))
    PV, PF = cloth.plate()
    import ttd

    X1 = V - [0, 0, 0.5]
    start = ttd.Mesh(V, F)
    stopped, rounds, tois, _, scale = cloth.limit_step(start, V, X1, F, ttd.Mesh(PV, PF), PV, True, 1)
    assert rounds >= 1 and stopped.all()
    assert tois[0] == pytest.approx(0.4, abs=1e-9)  # 0.2 of 0.5: flat, every vertex at once
    assert np.allclose(X1[:, 2], 0.2 - 0.9 * 0.4 * 0.5)
    assert scale == 1.0


@pytest.mark.parametrize("scenario", ["fall", "fold"])
def test_cli(tmp_path, scenario):
    args = [sys.executable, str(EXAMPLES / "cloth.py"), "--scenario", scenario, "--n", "16", "--steps", "25",
            "--report", "5", "--threads", "1"]
    done = subprocess.run(args, capture_output=True, text=True, cwd=tmp_path, timeout=300)
    assert done.returncode == 0 and "final: no crossing in 25 steps" in done.stdout, done.stdout + done.stderr
    done = subprocess.run(args + ["--no-ccd"], capture_output=True, text=True, cwd=tmp_path, timeout=300)
    assert done.returncode == 0 and "final: CROSSED at step" in done.stdout, done.stdout + done.stderr
