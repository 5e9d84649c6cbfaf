# SPDX-License-Identifier: MIT
"""ttd.cuda without a GPU (CI): the library is found through TTD_GPU_LIBRARY, a missing one
and a build without CUDA say so, and arrays that are not in GPU memory or have the wrong shape or
dtype are refused before anything is launched. The device side (CuPy, PyTorch, DLPack, the CPU's
bits) is python/tests/cuda_device_check.py, run by scripts/test-gpu-device.sh on a GPU."""
import numpy as np
import pytest

import ttd.cuda as tc
from conftest import _build_dir


class FakeDeviceArray:
    """An object that claims to be a GPU array (its pointer is never dereferenced by the checks)."""

    def __init__(self, shape, typestr="<f8", strides=None):
        self.__cuda_array_interface__ = {"shape": shape, "typestr": typestr, "data": (0x1000, False),
                                         "strides": strides, "version": 3}


@pytest.fixture
def gpu_library(monkeypatch):
    build, _ = _build_dir()
    path = build / "src" / "gpu" / "libttd_gpu.so"
    if not path.exists():
        pytest.skip(f"no libttd_gpu at {path}")
    monkeypatch.setenv("TTD_GPU_LIBRARY", str(path))
    monkeypatch.setattr(tc, "_loaded", None)
    return path


def test_missing_library_is_a_clear_error(monkeypatch, tmp_path):
    monkeypatch.setenv("TTD_GPU_LIBRARY", str(tmp_path / "libttd_gpu.so"))
    monkeypatch.setattr(tc, "_loaded", None)
    with pytest.raises(tc.CudaUnavailableError, match="could not be loaded"):
        tc.distance(FakeDeviceArray((1, 9)), FakeDeviceArray((1, 9)))
    assert tc.available() is False


def test_info_matches_the_build(gpu_library):
    info = tc.info()
    assert set(info) >= {"usable", "built", "name", "message"}
    if not info["usable"]:
        assert info["message"]  # says why
        assert tc.available() is False


def test_host_arrays_are_refused(gpu_library):
    S = np.zeros((4, 3, 3))
    with pytest.raises(TypeError, match="not an array in GPU memory"):
        tc.distance(S, S)


@pytest.mark.parametrize("shape, typestr, strides, error", [
    ((4, 3, 2), "<f8", None, ValueError),
    ((4, 3, 3), "<i4", None, TypeError),
    ((4, 9), "<f8", (144, 8), ValueError),   # every other row: not contiguous
])
def test_bad_device_arrays_are_refused(gpu_library, shape, typestr, strides, error):
    bad = FakeDeviceArray(shape, typestr, strides)
    good = FakeDeviceArray((4, 9))
    with pytest.raises(error):
        tc.distance(bad, good)


def test_mismatched_inputs_are_refused(gpu_library):
    out = FakeDeviceArray((4,))
    with pytest.raises(TypeError, match="same dtype"):
        tc.distance(FakeDeviceArray((4, 9)), FakeDeviceArray((4, 9), "<f4"), out=out)
    with pytest.raises(ValueError, match="4 and 5 pairs"):
        tc.distance(FakeDeviceArray((4, 9)), FakeDeviceArray((5, 9)), out=out)
    with pytest.raises(ValueError, match="out must be"):
        tc.distance(FakeDeviceArray((4, 9)), FakeDeviceArray((4, 9)), out=FakeDeviceArray((3,)))


def test_without_a_usable_gpu_the_call_says_why(gpu_library):
    if tc.info()["usable"]:
        pytest.skip("a GPU is usable here: python/tests/cuda_device_check.py covers it")
    with pytest.raises(tc.CudaUnavailableError):
        tc.distance(FakeDeviceArray((4, 9)), FakeDeviceArray((4, 9)), out=FakeDeviceArray((4,)))
