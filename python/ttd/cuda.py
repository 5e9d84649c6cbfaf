# SPDX-License-Identifier: MIT
"""ttd.cuda: the exact method on triangle pairs that already live in GPU memory.

    import cupy as cp, ttd.cuda
    s = cp.asarray(S)                 # (n, 3, 3) or (n, 9), float32 or float64, C-contiguous
    t = cp.asarray(T)
    d = ttd.cuda.distance(s, t)       # (n,) on the same device, the CPU's bits for every pair

Works on CuPy arrays, PyTorch CUDA tensors and anything else with ``__cuda_array_interface__``;
an object with only ``__dlpack__`` (a JAX array, say) is taken through CuPy's ``from_dlpack``
without a copy. The result is allocated by the input's library (a torch tensor for torch
inputs, else a CuPy array) unless ``out`` is given, and is computed asynchronously on that
library's current stream, as its own operations are.

The kernels are libttd_gpu's (include/ttd/ttd_gpu.h, docs/gpu.md), loaded with ctypes, so this
module needs neither the compiled extension's CUDA support nor a CUDA Python package of its own:
it finds the library through the environment variable TTD_GPU_LIBRARY (a path), else the
system's library path (``cmake --install`` puts libttd_gpu there). Without a library, a
library built without CUDA, or a usable GPU, every call raises CudaUnavailableError saying why.
"""
import ctypes
import ctypes.util
import os

__all__ = ["CudaUnavailableError", "available", "info", "distance"]


class CudaUnavailableError(RuntimeError):
    """libttd_gpu cannot be found, was built without CUDA, or finds no usable GPU."""


class _Info(ctypes.Structure):
    # include/ttd/ttd_gpu.h, struct ttd_gpu_info
    _fields_ = [
        ("built", ctypes.c_int),
        ("device", ctypes.c_int),
        ("device_count", ctypes.c_int),
        ("cc_major", ctypes.c_int),
        ("cc_minor", ctypes.c_int),
        ("runtime_version", ctypes.c_int),
        ("driver_version", ctypes.c_int),
        ("block_threads", ctypes.c_int),
        ("min_blocks", ctypes.c_int),
        ("registers_d", ctypes.c_int),
        ("registers_f", ctypes.c_int),
        ("name", ctypes.c_char * 128),
        ("message", ctypes.c_char * 192),
    ]


_OK, _NOT_BUILT, _NO_DEVICE = 0, 1, 2
_loaded = None


def _library():
    """libttd_gpu, loaded once, with its entry points' signatures."""
    global _loaded
    if _loaded is not None:
        return _loaded
    path = os.environ.get("TTD_GPU_LIBRARY") or ctypes.util.find_library("ttd_gpu")
    if not path:
        raise CudaUnavailableError("libttd_gpu not found: set TTD_GPU_LIBRARY to its path, or install it "
                                   "(cmake --install) where the system finds libraries")
    try:
        lib = ctypes.CDLL(path)
    except OSError as e:
        raise CudaUnavailableError(f"libttd_gpu could not be loaded from {path}: {e}") from None
    lib.ttd_gpu_query.argtypes = [ctypes.POINTER(_Info)]
    lib.ttd_gpu_query.restype = ctypes.c_int
    lib.ttd_gpu_status_string.argtypes = [ctypes.c_int]
    lib.ttd_gpu_status_string.restype = ctypes.c_char_p
    for name in ("ttd_gpu_batch_d", "ttd_gpu_batch_f"):
        fn = getattr(lib, name)
        fn.argtypes = [ctypes.c_size_t, ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p,
                       ctypes.c_void_p]
        fn.restype = ctypes.c_int
    _loaded = lib
    return lib


def info():
    """What libttd_gpu's query finds: a dict with 'usable' (bool), 'name', 'compute_capability',
    'driver', 'runtime', 'message' (why not usable), ... Raises CudaUnavailableError only when
    the library itself cannot be loaded."""
    lib = _library()
    i = _Info()
    status = lib.ttd_gpu_query(ctypes.byref(i))
    return {
        "usable": status == _OK,
        "built": bool(i.built),
        "device": i.device,
        "device_count": i.device_count,
        "name": i.name.decode(errors="replace"),
        "compute_capability": (i.cc_major, i.cc_minor),
        "driver": i.driver_version,
        "runtime": i.runtime_version,
        "block_threads": i.block_threads,
        "registers": {"float64": i.registers_d, "float32": i.registers_f},
        "message": i.message.decode(errors="replace"),
    }


def available():
    """True when libttd_gpu loads, was built with CUDA and finds a usable GPU."""
    try:
        return info()["usable"]
    except CudaUnavailableError:
        return False


def _interface(a, what):
    """(a's __cuda_array_interface__, the object that holds it), through CuPy for DLPack-only
    objects."""
    iface = getattr(a, "__cuda_array_interface__", None)
    # DLPack device types: 2 CUDA, 3 CUDA host (pinned), 13 CUDA managed; numpy's is 1, the CPU
    on_gpu = hasattr(a, "__dlpack_device__") and a.__dlpack_device__()[0] in (2, 3, 13)
    if iface is None and on_gpu and hasattr(a, "__dlpack__"):
        try:
            import cupy
        except ImportError:
            raise TypeError(f"{what}: an object with only __dlpack__ needs CuPy to be taken without a copy") from None
        a = cupy.from_dlpack(a)
        iface = a.__cuda_array_interface__
    if iface is None:
        raise TypeError(f"{what} is not an array in GPU memory (no __cuda_array_interface__ or __dlpack__): "
                        f"got {type(a).__name__}; use ttd.distance for arrays in host memory")
    return iface, a


def _contiguous(iface):
    strides = iface.get("strides")
    if strides is None:
        return True
    size = int(iface["typestr"][2:])
    expect = size
    for dim, st in zip(reversed(iface["shape"]), reversed(strides)):
        if dim > 1 and st != expect:
            return False
        expect *= dim
    return True


def _pairs(a, what):
    iface, holder = _interface(a, what)
    typestr, shape = iface["typestr"], tuple(iface["shape"])
    if typestr not in ("<f8", "<f4"):
        raise TypeError(f"{what} must hold float64 or float32, not {typestr}")
    if len(shape) == 3 and shape[1:] == (3, 3):
        n = shape[0]
    elif len(shape) == 2 and shape[1] == 9:
        n = shape[0]
    else:
        raise ValueError(f"{what} must have shape (n, 3, 3) or (n, 9), not {shape}")
    if not _contiguous(iface):
        raise ValueError(f"{what} must be C-contiguous")
    return holder, iface, typestr, n


def _stream_of(holder):
    """The current stream of the array's library, as an integer handle (0: the default)."""
    mod = type(holder).__module__.split(".")[0]
    if mod == "torch":
        import torch
        return torch.cuda.current_stream(holder.device).cuda_stream
    if mod == "cupy":
        import cupy
        return cupy.cuda.get_current_stream().ptr
    return 0


def _empty_like_lib(holder, n, typestr):
    mod = type(holder).__module__.split(".")[0]
    if mod == "torch":
        import torch
        return torch.empty(n, dtype=torch.float64 if typestr == "<f8" else torch.float32, device=holder.device)
    try:
        import cupy
    except ImportError:
        raise TypeError("pass out= (a GPU array of n reals): the input's library cannot allocate the result, "
                        "and CuPy is not installed") from None
    return cupy.empty(n, dtype=cupy.float64 if typestr == "<f8" else cupy.float32)


def distance(s, t, out=None):
    """Exact distances of n triangle pairs in GPU memory: s and t (n, 3, 3) or (n, 9), both
    float64 or both float32, C-contiguous, on the current device. Returns out, or a new (n,)
    array of the inputs' library, filled asynchronously on that library's current stream. A pair
    with a NaN or infinite coordinate gets NaN."""
    lib = _library()
    hs, si, ts, n = _pairs(s, "s")
    ht, ti, tt, nt = _pairs(t, "t")
    if ts != tt:
        raise TypeError(f"s and t must have the same dtype ({ts} and {tt})")
    if n != nt:
        raise ValueError(f"s and t hold {n} and {nt} pairs")
    if out is None:
        out = _empty_like_lib(hs, n, ts)
    oi, ho = _interface(out, "out")
    if oi["typestr"] != ts or tuple(oi["shape"]) not in ((n,),) or not _contiguous(oi):
        raise ValueError(f"out must be a C-contiguous ({n},) array of {ts}")
    if n == 0:
        return out
    fn = lib.ttd_gpu_batch_d if ts == "<f8" else lib.ttd_gpu_batch_f
    status = fn(n, si["data"][0], ti["data"][0], oi["data"][0], None, _stream_of(hs))
    if status != _OK:
        message = lib.ttd_gpu_status_string(status).decode(errors="replace")
        if status in (_NOT_BUILT, _NO_DEVICE):
            detail = info()["message"]
            raise CudaUnavailableError(f"{message}{': ' + detail if detail else ''}")
        raise RuntimeError(f"ttd_gpu_batch: {message}")
    return out
