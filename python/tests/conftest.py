# SPDX-License-Identifier: MIT
"""Shared fixtures: random pairs, and the C library's own results through paths independent
of the extension (ctypes on libttd.so, and the `ttd dist` program) from a CMake build folder.

The build folder is TTD_TEST_BUILD_DIR (scripts/test-python.sh sets it to the build it made;
then a missing library or program is an error), else the repository's build/ (then the tests
that need it are skipped when it is missing, saying so).
"""
import os
import pathlib

import pytest
from cases import random_pairs

REPO = pathlib.Path(__file__).resolve().parents[2]


def _build_dir():
    given = os.environ.get("TTD_TEST_BUILD_DIR")
    return (pathlib.Path(given), True) if given else (REPO / "build", False)


def _needed(path: pathlib.Path, what: str) -> pathlib.Path:
    build, required = _build_dir()
    if path.exists():
        return path
    message = f"{what} not found at {path} (build the C library with CMake in {build})"
    if required:
        pytest.fail(message + "; TTD_TEST_BUILD_DIR names this build, so it must be there")
    pytest.skip(message)


@pytest.fixture(scope="session")
def libttd():
    """The C library through ctypes (c_reference.Library)."""
    import c_reference

    build, _ = _build_dir()
    candidates = sorted((build / "src").glob("libttd.so*"))
    path = _needed(candidates[0] if candidates else build / "src" / "libttd.so", "libttd.so")
    return c_reference.Library(path)


@pytest.fixture(scope="session")
def ttd_program():
    """Path of the `ttd` command-line program."""
    build, _ = _build_dir()
    return _needed(build / "cli" / "ttd", "the ttd program")


@pytest.fixture
def pairs():
    return random_pairs(2000, seed=11)
