# SPDX-License-Identifier: MIT
"""ttd.cuda without a GPU (CI): the library is found through TTD_GPU_LIBRARY, a missing one
and a build without CUDA say so, and arrays that are not in GPU memory or have the wrong shape or
dtype are refused before anything is launched. The device side (CuPy, PyTorch, DLPack, the CPU's
bits) is python/tests/cuda_device_check.py, run by scripts/test-gpu-device.sh on a GPU."""
import ctypes

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


# ---- meshes under many poses (ttd.cuda.Mesh, mesh_distance, mesh_collide) -------------------

def _tetra(dtype=np.float64):
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=dtype)
    f = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    return v, f


@pytest.fixture
def cpu_library(gpu_library, monkeypatch):
    build, _ = _build_dir()
    candidates = sorted((build / "src").glob("libttd.so*"))
    if not candidates:
        pytest.skip(f"no libttd.so in {build / 'src'}")
    monkeypatch.setenv("TTD_LIBRARY", str(candidates[0]))
    monkeypatch.setattr(tc, "_cpu_loaded", None)
    return candidates[0]


def test_mesh_without_a_usable_gpu_says_why(cpu_library):
    if tc.info()["usable"]:
        pytest.skip("a GPU is usable here: python/tests/cuda_device_check.py covers it")
    v, f = _tetra()
    with pytest.raises(tc.CudaUnavailableError) as e:
        tc.Mesh(v, f)
    assert "built without" in str(e.value) or "no usable" in str(e.value) or "driver" in str(e.value)
    with pytest.raises(tc.CudaUnavailableError):
        tc.Mesh(*_tetra(np.float32))


def test_mesh_missing_cpu_library_is_a_clear_error(gpu_library, monkeypatch, tmp_path):
    monkeypatch.setenv("TTD_LIBRARY", str(tmp_path / "libttd.so"))
    monkeypatch.setenv("TTD_GPU_LIBRARY", str(tmp_path / "gpu" / "libttd_gpu.so"))
    monkeypatch.setattr(tc, "_cpu_loaded", None)
    monkeypatch.setattr(tc, "_loaded", None)
    with pytest.raises(tc.CudaUnavailableError):
        tc.Mesh(*_tetra())


@pytest.mark.parametrize("vertices, faces, error, match", [
    (np.zeros((4, 2)), [[0, 1, 2]], ValueError, "shape"),
    (np.zeros((0, 3)), [[0, 1, 2]], ValueError, "shape"),
    (np.zeros((4, 3)), [[0, 1, 4]], ValueError, "index"),
    (np.zeros((4, 3)), [[0, -1, 2]], ValueError, "index"),
    (np.zeros((4, 3)), [[0.0, 1.0, 2.0]], ValueError, "integer"),
    (np.zeros((4, 3)), np.zeros((0, 3), dtype=int), ValueError, "shape"),
    (np.array([[0, 0, 0], [1, 0, 0], [0, np.nan, 0]]), [[0, 1, 2]], ValueError, "finite"),
    (FakeDeviceArray((4, 3)), [[0, 1, 2]], TypeError, "host memory"),
])
def test_bad_meshes_are_refused_before_any_upload(cpu_library, vertices, faces, error, match):
    with pytest.raises(error, match=match):
        tc.Mesh(vertices, faces)


class _NotUploaded(tc.Mesh):
    """A Mesh as the checks see it, without a device (never uploaded)."""

    def __init__(self, dtype=np.float64, closed=False):
        self.dtype = np.dtype(dtype)
        self._handle = None if closed else ctypes.c_void_p(0x1000)

    def close(self):
        self._handle = None



@pytest.mark.parametrize("query", [tc.mesh_distance, tc.mesh_collide])
def test_mesh_queries_refuse_bad_arguments_before_launching(gpu_library, query):
    a, b = _NotUploaded(), _NotUploaded()
    good = FakeDeviceArray((5, 12))
    with pytest.raises(TypeError, match="not an array in GPU memory"):
        query(a, b, np.zeros((5, 12)))
    with pytest.raises(ValueError, match=r"\(k, 3, 4\) or \(k, 12\)"):
        query(a, b, FakeDeviceArray((5, 3, 3)))
    with pytest.raises(TypeError, match="float64 or float32"):
        query(a, b, FakeDeviceArray((5, 12), "<i8"))
    with pytest.raises(ValueError, match="C-contiguous"):
        query(a, b, FakeDeviceArray((5, 12), "<f8", (192, 8)))
    with pytest.raises(TypeError, match="ttd.cuda.Mesh"):
        query(a, "mesh", good)
    with pytest.raises(TypeError, match="need meshes of float32"):
        query(a, b, FakeDeviceArray((5, 12), "<f4"))
    with pytest.raises(TypeError, match="need meshes of float64"):
        query(_NotUploaded(np.float32), _NotUploaded(np.float32), good)
    with pytest.raises(ValueError, match="closed"):
        query(a, _NotUploaded(closed=True), good)
    for bad in (-1.0, float("nan")):
        with pytest.raises(ValueError, match="must be >= 0"):
            query(a, b, good, bad)


@pytest.mark.parametrize("query", [tc.closest_points, tc.signed_distance])
def test_point_queries_refuse_bad_arguments_before_launching(gpu_library, query):
    m = _NotUploaded()
    good = FakeDeviceArray((5, 3))
    with pytest.raises(TypeError, match="not an array in GPU memory"):
        query(m, np.zeros((5, 3)))
    with pytest.raises(ValueError, match=r"shape \(n, 3\)"):
        query(m, FakeDeviceArray((5, 4)))
    with pytest.raises(TypeError, match="float64 or float32"):
        query(m, FakeDeviceArray((5, 3), "<i4"))
    with pytest.raises(ValueError, match="C-contiguous"):
        query(m, FakeDeviceArray((5, 3), "<f8", (48, 8)))
    with pytest.raises(TypeError, match="ttd.cuda.Mesh"):
        query(object(), good)
    with pytest.raises(TypeError, match="need a mesh of that dtype"):
        query(m, FakeDeviceArray((5, 3), "<f4"))
    with pytest.raises(ValueError, match="closed"):
        query(_NotUploaded(closed=True), good)
    for bad in (-1.0, float("nan")):
        with pytest.raises(ValueError, match="must be >= 0"):
            query(m, good, bad)


def test_signed_distance_constants_match_the_header():
    # include/ttd/ttd_gpu.h's TTD_GPU_POINT_SIDE_REFUSED; ttd.h's TTD_POINT_* flags use bits 0-4
    import pathlib
    header = pathlib.Path(__file__).resolve().parents[2] / "include" / "ttd" / "ttd_gpu.h"
    assert f"#define TTD_GPU_POINT_SIDE_REFUSED 0x{tc.POINT_SIDE_REFUSED:x}u" in header.read_text()
    assert tc.POINT_SIDE_REFUSED > 0x10


# ---- continuous collision (ttd.cuda.ccd_vertex_face, ccd_edge_edge) ---------------------------

def test_ccd_refuses_bad_arguments_before_launching(gpu_library):
    v, f = FakeDeviceArray((5, 3)), FakeDeviceArray((5, 3, 3))
    e = FakeDeviceArray((5, 2, 3))
    with pytest.raises(TypeError, match="not an array in GPU memory"):
        tc.ccd_vertex_face(np.zeros((5, 3)), f, v, f)
    with pytest.raises(ValueError, match=r"shape \(n, 3, 3\)"):
        tc.ccd_vertex_face(v, FakeDeviceArray((5, 9)), v, f)
    with pytest.raises(ValueError, match=r"shape \(n, 2, 3\)"):
        tc.ccd_edge_edge(e, e, FakeDeviceArray((5, 3, 2)), e)
    with pytest.raises(TypeError, match="float64 or float32"):
        tc.ccd_edge_edge(e, e, e, FakeDeviceArray((5, 2, 3), "<i4"))
    with pytest.raises(TypeError, match="same dtype"):
        tc.ccd_vertex_face(v, f, FakeDeviceArray((5, 3), "<f4"), f)
    with pytest.raises(ValueError, match="5 and 4 queries"):
        tc.ccd_edge_edge(e, e, e, FakeDeviceArray((4, 2, 3)))
    with pytest.raises(ValueError, match="C-contiguous"):
        tc.ccd_vertex_face(v, f, FakeDeviceArray((5, 3), "<f8", (48, 8)), f)
    for bad in (-1.0, float("nan"), float("inf")):
        with pytest.raises(ValueError, match="min_separation"):
            tc.ccd_edge_edge(e, e, e, e, min_separation=bad)

