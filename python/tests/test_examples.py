# SPDX-License-Identifier: MIT
"""The examples run (small sizes): python/examples/scene_motion.py prints its per-step table,
python/examples/scene_pile.py settles a small pile without crossings and writes its picture (the
picture's check is skipped, saying so, without matplotlib); python/examples/cloth.py runs, and
every step of a small sheet's simulation has the self-contacts and sheet-sphere contacts of the
brute force over every triangle pair."""
import importlib.util
import pathlib
import re
import subprocess
import sys

import pytest

EXAMPLES = pathlib.Path(__file__).resolve().parents[1] / "examples"


def run(script, *args, cwd):
    done = subprocess.run([sys.executable, str(EXAMPLES / script), *args], capture_output=True, text=True, cwd=cwd,
                          timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr
    return done.stdout


@pytest.mark.parametrize("precision", ["float64", "float32"])
def test_scene_motion_example(tmp_path, precision):
    out = run("scene_motion.py", "--bodies", "27", "--level", "1", "--steps", "3", "--threads", "2", "--precision",
              precision, cwd=tmp_path)
    rows = [line.split() for line in out.splitlines() if re.match(r"\s*\d+\s", line)]
    assert [r[0] for r in rows] == ["0", "1", "2"] and all(len(r) == 12 for r in rows)
    assert "mean ms per step" in out


def test_scene_pile_example(tmp_path):
    png = tmp_path / "pile.png"
    out = run("scene_pile.py", "--bodies", "12", "--steps", "1500", "--report", "300", "--out", str(png), cwd=tmp_path)
    final = [line for line in out.splitlines() if line.startswith("final:")]
    assert final and "every ball in the bin: True" in final[0], out
    # settled: little kinetic energy left, and at the last report no body pair touching or
    # crossing (a ball landing may touch for a moment, and an earlier report may catch it)
    rows = [line.split() for line in out.splitlines() if line.strip() and line.split()[0].isdigit()]
    assert rows and rows[-1][0] == "1500" and rows[-1][3] == "0" and float(rows[-1][4]) < 1.0, out
    if importlib.util.find_spec("matplotlib") is None:
        assert "matplotlib is not installed" in out
        pytest.skip("matplotlib is not installed: the pile's picture was not written "
                    "(apt-get install python3-matplotlib; scripts/test-python.sh installs it when run as root)")
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_cloth_example(tmp_path):
    png = tmp_path / "cloth.png"
    out = run("cloth.py", "--n", "10", "--steps", "40", "--report", "10", "--out", str(png), cwd=tmp_path)
    assert "200 triangles" in out and "mean ms per step" in out, out
    if importlib.util.find_spec("matplotlib") is None:
        assert "matplotlib is not installed" in out
        pytest.skip("matplotlib is not installed: the cloth's picture was not written")
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_cloth_contacts_every_step_equal_brute_force():
    """A 10 x 10 sheet (200 triangles) over 110 steps, landing on the sphere and folding on the
    floor: each step's self-contacts (pairs sharing one vertex included) and sheet-sphere contacts
    are the brute force's over every triangle pair, pair for pair with their distances."""
    import numpy as np

    from meshes import brute_force
    from test_deform import self_brute_force

    spec = importlib.util.spec_from_file_location("cloth", EXAMPLES / "cloth.py")
    cloth = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(cloth)
    seen = [0, 0]

    def check(step, sheet, sphere, sc, cc, h):
        key, d, _, _ = self_brute_force(sheet, True)
        within = d <= h
        want = dict(zip(map(tuple, key[within].tolist()), d[within].tolist()))
        got = dict(zip(zip(sc.tri_i.tolist(), sc.tri_j.tolist()), sc.distance.tolist()))
        assert got == want, f"step {step}: self-contacts differ"
        d = brute_force(sheet, sphere, np.eye(4)).distance
        want = {(int(i), int(j)): d[i, j] for i, j in zip(*np.nonzero(d <= h))}
        got = dict(zip(zip(cc.tri_a.tolist(), cc.tri_b.tolist()), cc.distance.tolist()))
        assert got == want, f"step {step}: sheet-sphere contacts differ"
        seen[0] += len(sc.distance)
        seen[1] += len(cc.distance)

    cloth.simulate(n=10, steps=110, sphere_level=1, callback=check)
    assert seen[0] > 0 and seen[1] > 0, seen
