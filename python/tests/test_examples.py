# SPDX-License-Identifier: MIT
"""The scene examples run (small sizes): python/examples/scene_motion.py prints its per-step
table, python/examples/scene_pile.py settles a small pile without crossings and writes its
picture (the picture's check is skipped, saying so, without matplotlib)."""
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
