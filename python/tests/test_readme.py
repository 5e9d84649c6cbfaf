# SPDX-License-Identifier: MIT
"""The README's Python blocks run as written (tests/cli/test_doc_examples.sh runs its other blocks):
its ```python blocks, joined in order, from the repository's folder, in this interpreter (the
installed package); and its install block (a venv that sees Debian's numpy, then pip) in a
temporary folder laid out as the repository, with the library of this build (TTD_CMAKE_BUILD_DIR,
so that pip does not compile the library a second time), and the installed package imported."""
import os
import pathlib
import shutil
import subprocess
import sys

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]
README = (REPO / "README.md").read_text()


def blocks(lang):
    """The README's fenced blocks of language lang ("" for a plain fence), in order."""
    out, cur, cur_lang = [], None, None
    for line in README.splitlines(keepends=True):
        if line.startswith("```"):
            if cur is None:
                cur, cur_lang = [], line[3:].strip()
            else:
                if cur_lang == lang:
                    out.append("".join(cur))
                cur = None
        elif cur is not None:
            cur.append(line)
    assert cur is None, "README.md: an unterminated block"
    return out


def test_python_blocks_run_as_written(tmp_path):
    code = "\n".join(blocks("python"))
    assert "ttd.Scene" in code and "ttd.Mesh" in code
    script = tmp_path / "readme.py"
    script.write_text(code + "\nprint('ran', len(d), len(r.distance), len(m.i) > 0)\n")
    done = subprocess.run([sys.executable, str(script)], cwd=REPO, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr
    assert done.stdout.split()[-4:] == ["ran", "1000000", "1000", "True"], done.stdout


def test_install_block_runs_as_written(tmp_path):
    (block,) = [b for b in blocks("") if "-m venv" in b]
    if not os.path.exists("/usr/bin/python3"):
        pytest.skip("the README's install block names /usr/bin/python3, which this machine lacks")
    build = os.environ.get("TTD_TEST_BUILD_DIR")
    if not build:
        pytest.skip("TTD_TEST_BUILD_DIR is not set (scripts/test-python.sh sets it): the block would compile the "
                    "library again")
    (tmp_path / "python").symlink_to(REPO / "python")
    env = dict(os.environ, TTD_CMAKE_BUILD_DIR=str(pathlib.Path(build).resolve()),
               TTD_PYTHON_BUILD_BASE=str(tmp_path / "python-build"), PIP_NO_INDEX="1",
               PIP_DISABLE_PIP_VERSION_CHECK="1")
    env.pop("VIRTUAL_ENV", None)
    done = subprocess.run(["sh", "-e", "-c", block], cwd=tmp_path, env=env, capture_output=True, text=True,
                          timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
    check = subprocess.run([str(tmp_path / ".venv/bin/python"), "-c",
                            "import ttd, numpy as np; s = np.eye(3)[None]; print(ttd.distance(s, s + 2)[0])"],
                           cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert check.returncode == 0 and float(check.stdout) == pytest.approx(2 * 3 ** 0.5), check.stdout + check.stderr
    shutil.rmtree(tmp_path / ".venv", ignore_errors=True)


def test_wheel_block_runs_as_written(tmp_path):
    # The README's offline wheel: built without an index, installed from the file into a venv
    # that sees Debian's numpy; the benchmark-only ttd._ctiming is not in it.
    (block,) = [b for b in blocks("") if "pip wheel" in b]
    if not os.path.exists("/usr/bin/python3"):
        pytest.skip("the README's wheel block names /usr/bin/python3, which this machine lacks")
    build = os.environ.get("TTD_TEST_BUILD_DIR")
    if not build:
        pytest.skip("TTD_TEST_BUILD_DIR is not set (scripts/test-python.sh sets it): the block would compile the "
                    "library again")
    (tmp_path / "python").symlink_to(REPO / "python")
    env = dict(os.environ, TTD_CMAKE_BUILD_DIR=str(pathlib.Path(build).resolve()),
               TTD_PYTHON_BUILD_BASE=str(tmp_path / "python-build"), PIP_DISABLE_PIP_VERSION_CHECK="1")
    for name in ("VIRTUAL_ENV", "PIP_NO_INDEX", "TTD_PYTHON_CTIMING"):
        env.pop(name, None)
    venv = subprocess.run(["/usr/bin/python3", "-m", "venv", "--system-site-packages", ".venv"], cwd=tmp_path,
                          env=env, capture_output=True, text=True, timeout=300)
    assert venv.returncode == 0, venv.stdout + venv.stderr
    done = subprocess.run(["sh", "-e", "-c", block], cwd=tmp_path, env=env, capture_output=True, text=True,
                          timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
    (wheel,) = (tmp_path / "dist").glob("ttd-*.whl")
    import zipfile

    names = zipfile.ZipFile(wheel).namelist()
    assert any(n.startswith("ttd/_ttd") and n.endswith(".so") for n in names), names
    assert not [n for n in names if "_ctiming" in n], names
    check = subprocess.run([str(tmp_path / ".venv/bin/python"), "-c",
                            "import importlib.util, ttd, numpy as np; s = np.eye(3)[None]; "
                            "print(ttd.distance(s, s + 2)[0], importlib.util.find_spec('ttd._ctiming') is None)"],
                           cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert check.returncode == 0, check.stdout + check.stderr
    d, absent = check.stdout.split()
    assert float(d) == pytest.approx(2 * 3 ** 0.5) and absent == "True", check.stdout
    shutil.rmtree(tmp_path / ".venv", ignore_errors=True)
