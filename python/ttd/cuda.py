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

Meshes under many poses (docs/gpu.md, section 6):

    a = ttd.cuda.Mesh(verts_a, faces_a)          # built by ttd on the CPU, uploaded once
    b = ttd.cuda.Mesh(verts_b, faces_b)
    poses = cp.asarray(P)                        # (k, 3, 4) or (k, 12), the meshes' dtype
    r = ttd.cuda.mesh_distance(a, b, poses)      # r.distance: (k,), ttd.mesh_distance's bits
    c = ttd.cuda.mesh_collide(a, b, poses, 0.0)  # c.hit: (k,) int32, 0 or 1 (0x8000: pose refused)
    p = ttd.cuda.closest_points(a, cp.asarray(X))  # (n, 3) points: p.distance (n,), ttd.closest_points' bits
    s = ttd.cuda.signed_distance(a, cp.asarray(X))  # s.distance (n,), ttd.signed_distance's bits
                                                    # (a closed mesh, or one triangle; see signed_distance)

Continuous collision of moving primitives (docs/ccd.md, section 14):

    r = ttd.cuda.ccd_vertex_face(v0, f0, v1, f1)   # v (n, 3), f (n, 3, 3): r.hit, r.toi, ttd.ccd_vertex_face's bits
    r = ttd.cuda.ccd_edge_edge(a0, b0, a1, b1)     # each (n, 2, 3)

A Mesh needs libttd too (to build the hierarchy as the CPU does): TTD_LIBRARY (a path), else
next to libttd_gpu, else the system's library path.
"""
import collections
import ctypes
import ctypes.util
import os
import pathlib

__all__ = ["CudaUnavailableError", "available", "info", "distance", "Mesh", "mesh_distance", "mesh_collide",
           "closest_points", "signed_distance", "POSE_REFUSED", "POINT_SIDE_REFUSED", "ccd_vertex_face",
           "ccd_edge_edge"]

# include/ttd/ttd_gpu.h, TTD_GPU_POSE_REFUSED: a pose the CPU entry would refuse (flags bit; hit value)
POSE_REFUSED = 0x8000
# include/ttd/ttd_gpu.h, TTD_GPU_POINT_SIDE_REFUSED: a point whose side the device could not decide as
# the CPU does (flags bit of its record; its signed distance NaN)
POINT_SIDE_REFUSED = 0x80


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
    lib.ttd_gpu_mesh_upload.argtypes = [ctypes.c_void_p, ctypes.POINTER(ctypes.c_void_p)]
    lib.ttd_gpu_mesh_upload.restype = ctypes.c_int
    for name, real in (("d", ctypes.c_double), ("f", ctypes.c_float)):
        fn = getattr(lib, f"ttd_gpu_points_closest_{name}")
        fn.argtypes = [ctypes.c_void_p, ctypes.c_size_t, ctypes.c_void_p, real, ctypes.c_void_p, ctypes.c_void_p]
        fn.restype = ctypes.c_int
    lib.ttd_gpu_mesh_free.argtypes = [ctypes.c_void_p]
    lib.ttd_gpu_mesh_free.restype = None
    for name, real in (("d", ctypes.c_double), ("f", ctypes.c_float)):
        fn = getattr(lib, f"ttd_gpu_points_signed_distance_{name}")
        fn.argtypes = [ctypes.c_void_p, ctypes.c_size_t, ctypes.c_void_p, real, ctypes.c_void_p, ctypes.c_void_p,
                       ctypes.c_void_p]
        fn.restype = ctypes.c_int
    for name, real in (("d", ctypes.c_double), ("f", ctypes.c_float)):
        for query in ("distance", "collide"):
            fn = getattr(lib, f"ttd_gpu_mesh_{query}_{name}")
            fn.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_size_t, ctypes.c_void_p, real, ctypes.c_void_p,
                           ctypes.c_void_p]
            fn.restype = ctypes.c_int
    _loaded = lib
    return lib


_cpu_loaded = None


def _cpu_library():
    """libttd (the CPU library), for building a mesh's hierarchy as ttd does: TTD_LIBRARY, else next
    to libttd_gpu (the same folder or the one above, as in a build tree), else the system's path."""
    global _cpu_loaded
    if _cpu_loaded is not None:
        return _cpu_loaded
    candidates = [os.environ.get("TTD_LIBRARY")]
    gpu_path = os.environ.get("TTD_GPU_LIBRARY")
    if gpu_path:
        here = pathlib.Path(gpu_path).resolve().parent
        for folder in (here, here.parent):
            candidates += [str(p) for p in sorted(folder.glob("libttd.so*"))]
    candidates.append(ctypes.util.find_library("ttd"))
    errors = []
    for path in filter(None, candidates):
        try:
            lib = ctypes.CDLL(path)
            break
        except OSError as e:
            errors.append(f"{path}: {e}")
    else:
        raise CudaUnavailableError("libttd not found (ttd.cuda.Mesh builds the hierarchy with it): set TTD_LIBRARY "
                                   "to its path" + (f" ({'; '.join(errors)})" if errors else ""))
    for name, real in (("d", ctypes.c_double), ("f", ctypes.c_float)):
        fn = getattr(lib, f"ttd_mesh_create_{name}")
        fn.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_size_t, ctypes.c_void_p, ctypes.c_size_t,
                       ctypes.POINTER(ctypes.c_void_p)]
        fn.restype = ctypes.c_int
    for name, real in (("d", ctypes.c_double), ("f", ctypes.c_float)):
        fn = getattr(lib, f"ttd_points_closest_{name}")
        fn.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_size_t, ctypes.c_void_p, ctypes.c_void_p, real,
                       ctypes.c_void_p]
        fn.restype = ctypes.c_int
        fn = getattr(lib, f"ttd_points_signed_distance_{name}")
        fn.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_size_t, ctypes.c_void_p, ctypes.c_void_p, real,
                       ctypes.c_void_p, ctypes.c_void_p]
        fn.restype = ctypes.c_int
    lib.ttd_mesh_destroy.argtypes = [ctypes.c_void_p]
    lib.ttd_mesh_destroy.restype = None
    lib.ttd_status_string.argtypes = [ctypes.c_int]
    lib.ttd_status_string.restype = ctypes.c_char_p
    _cpu_loaded = lib
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


def _raise_status(lib, status, what):
    message = lib.ttd_gpu_status_string(status).decode(errors="replace")
    if status in (_NOT_BUILT, _NO_DEVICE):
        detail = info()["message"]
        raise CudaUnavailableError(f"{message}{': ' + detail if detail else ''}")
    if status == _BAD_ARGUMENT:
        raise ValueError(f"{what}: {message}")
    raise RuntimeError(f"{what}: {message}")


_BAD_ARGUMENT = 6


class Mesh:
    """A triangle mesh on the GPU: built by ttd on the CPU (the same hierarchy as ttd.Mesh) and
    copied to the current device once. vertices (n, 3) float64 or float32 (the precision of its
    queries), faces (m, 3) integer indices; or a ttd.Mesh (its vertices and faces). Free it with
    close() (or a with block); the device copy does not follow later changes of the arrays."""

    def __init__(self, vertices, faces=None):
        import numpy as np

        if faces is None and hasattr(vertices, "faces") and hasattr(vertices, "vertices"):
            vertices, faces = vertices.vertices, vertices.faces
        if hasattr(vertices, "__cuda_array_interface__"):
            raise TypeError("ttd.cuda.Mesh takes vertices and faces in host memory (numpy): the hierarchy is "
                            "built on the CPU")
        v = np.asarray(vertices)
        if v.dtype not in (np.float64, np.float32):
            v = v.astype(np.float64)
        f = np.asarray(faces)
        if v.ndim != 2 or v.shape[1] != 3 or len(v) == 0:
            raise ValueError(f"vertices must have shape (n, 3), n >= 1, not {v.shape}")
        if f.ndim != 2 or f.shape[1] != 3 or len(f) == 0 or not np.issubdtype(f.dtype, np.integer):
            raise ValueError(f"faces must be integer indices of shape (m, 3), m >= 1, not {f.dtype} {f.shape}")
        if f.min() < 0 or f.max() >= len(v):
            raise ValueError(f"faces index vertices 0..{len(v) - 1}: found {f.min()}..{f.max()}")
        if not np.isfinite(v).all():
            raise ValueError("vertices must be finite")
        self._v = np.ascontiguousarray(v)
        self._f = np.ascontiguousarray(f, dtype=np.uint32)
        self.dtype = self._v.dtype
        self._handle = None
        gpu = _library()
        cpu = _cpu_library()
        host = ctypes.c_void_p()
        create = cpu.ttd_mesh_create_d if self.dtype == np.float64 else cpu.ttd_mesh_create_f
        status = create(None, self._v.ctypes.data, len(self._v), self._f.ctypes.data, len(self._f), ctypes.byref(host))
        if status != 0:
            raise ValueError(f"ttd_mesh_create: {cpu.ttd_status_string(status).decode(errors='replace')}")
        try:
            # one signed distance makes the mesh's point data and finds whether it is closed (and an open
            # mesh's caps), so that the upload carries what the point queries and their signs need
            point = np.zeros(3, dtype=self.dtype)
            result = np.zeros(_POINT_RESULT[self.dtype.str], dtype=np.uint8)
            signed = cpu.ttd_points_signed_distance_d if self.dtype == np.float64 else cpu.ttd_points_signed_distance_f
            signed(None, host, 1, point.ctypes.data, None, float("inf"), None, result.ctypes.data)
            handle = ctypes.c_void_p()
            status = gpu.ttd_gpu_mesh_upload(host, ctypes.byref(handle))
        finally:
            cpu.ttd_mesh_destroy(host)
        if status != _OK:
            _raise_status(gpu, status, "ttd_gpu_mesh_upload")
        self._handle = handle

    @property
    def vertex_count(self):
        return len(self._v)

    @property
    def triangle_count(self):
        return len(self._f)

    def close(self):
        """Frees the device copy (no query on it may still be running on a stream)."""
        if self._handle is not None:
            _library().ttd_gpu_mesh_free(self._handle)
            self._handle = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        try:
            self.close()
        except Exception:
            pass


# the record sizes of include/ttd/ttd.h (ttd_mesh_result_d/_f, ttd_collision; tests/test_gpu_walk.c
# checks them); distance and hit are each record's first field
_RESULT = {"<f8": 80, "<f4": 56}
_COLLISION = 24
_POINT_RESULT = {"<f8": 72, "<f4": 44}  # ttd_point_result_d/_f; distance first

MeshDistanceGPU = collections.namedtuple("MeshDistanceGPU", ["distance", "records"])
MeshDistanceGPU.__doc__ = """ttd.cuda.mesh_distance's result, on the device: distance (k,), and the k
whole records (k, 80) uint8 (float32: (k, 56)) in ttd_mesh_result_d's (_f's) layout."""
MeshCollisionGPU = collections.namedtuple("MeshCollisionGPU", ["hit", "records"])
MeshCollisionGPU.__doc__ = """ttd.cuda.mesh_collide's result, on the device: hit (k,) int32 (0, 1, or
POSE_REFUSED), and the k records (k, 24) uint8 in ttd_collision's layout."""


def _poses(poses):
    iface, holder = _interface(poses, "poses")
    typestr, shape = iface["typestr"], tuple(iface["shape"])
    if typestr not in ("<f8", "<f4"):
        raise TypeError(f"poses must hold float64 or float32, not {typestr}")
    if not ((len(shape) == 3 and shape[1:] == (3, 4)) or (len(shape) == 2 and shape[1] == 12)):
        raise ValueError(f"poses must have shape (k, 3, 4) or (k, 12), not {shape}")
    if not _contiguous(iface):
        raise ValueError("poses must be C-contiguous")
    return holder, iface, typestr, shape[0]


def _records(holder, k, size):
    """k records of size bytes, allocated by the poses' library on its device."""
    mod = type(holder).__module__.split(".")[0]
    if mod == "torch":
        import torch
        return torch.empty((k, size), dtype=torch.uint8, device=holder.device)
    try:
        import cupy
    except ImportError:
        raise TypeError("the poses' library cannot allocate the result records, and CuPy is not installed") from None
    return cupy.empty((k, size), dtype=cupy.uint8)


def _column(records, offset, nbytes, kind):
    """A (k,) array of one field of the records (a copy, contiguous): kind 'f8', 'f4' or 'i4'."""
    mod = type(records).__module__.split(".")[0]
    part = records[:, offset:offset + nbytes]
    if mod == "torch":
        import torch
        dtype = {"f8": torch.float64, "f4": torch.float32, "i4": torch.int32}[kind]
        return part.contiguous().view(dtype).reshape(-1)
    return part.copy().view(kind).reshape(-1)


def _mesh_args(a, b, poses, limit, what):
    import numpy as np

    holder, iface, typestr, k = _poses(poses)
    if not isinstance(a, Mesh) or not isinstance(b, Mesh):
        raise TypeError(f"{what}: a and b must be ttd.cuda.Mesh objects")
    if a._handle is None or b._handle is None:
        raise ValueError(f"{what}: a mesh was closed")
    want = np.dtype(typestr)
    if a.dtype != want or b.dtype != want:
        raise TypeError(f"{what}: poses of {want} need meshes of {want} (got {a.dtype} and {b.dtype})")
    limit = float(limit)
    if not limit >= 0:
        raise ValueError(f"{what}: the bound must be >= 0 (inf for none), not {limit}")
    return holder, iface, typestr, k, limit


def mesh_distance(a, b, poses, upper_bound=float("inf")):
    """The minimum distance between the surfaces of Mesh a and Mesh b under each of k poses (GPU
    arrays (k, 3, 4) or (k, 12), the meshes' dtype; a pose maps b into a's frame), one GPU thread a
    pose, on the poses' library's current stream. Each distance has the bits ttd.mesh_distance
    gives (rel_tol 0, surfaces); a pose past upper_bound reads inf, a pose the CPU would refuse
    NaN (POSE_REFUSED in the record's flags)."""
    lib = _library()
    holder, iface, typestr, k, limit = _mesh_args(a, b, poses, upper_bound, "mesh_distance")
    size = _RESULT[typestr]
    records = _records(holder, k, size)
    if k == 0:
        return MeshDistanceGPU(_column(records, 0, 8 if typestr == "<f8" else 4, typestr[1:]), records)
    rec_iface, _ = _interface(records, "records")
    fn = lib.ttd_gpu_mesh_distance_d if typestr == "<f8" else lib.ttd_gpu_mesh_distance_f
    status = fn(a._handle, b._handle, k, iface["data"][0], limit, rec_iface["data"][0], _stream_of(holder))
    if status != _OK:
        _raise_status(lib, status, "ttd_gpu_mesh_distance")
    return MeshDistanceGPU(_column(records, 0, 8 if typestr == "<f8" else 4, typestr[1:]), records)


def mesh_collide(a, b, poses, margin=0.0):
    """Whether Mesh a and Mesh b come within margin (>= 0) under each of k poses (as
    mesh_distance's): hit (k,) int32, ttd.mesh_collide's verdict for every pose (surfaces), or
    POSE_REFUSED for a pose the CPU would refuse."""
    lib = _library()
    holder, iface, typestr, k, limit = _mesh_args(a, b, poses, margin, "mesh_collide")
    records = _records(holder, k, _COLLISION)
    if k > 0:
        rec_iface, _ = _interface(records, "records")
        fn = lib.ttd_gpu_mesh_collide_d if typestr == "<f8" else lib.ttd_gpu_mesh_collide_f
        status = fn(a._handle, b._handle, k, iface["data"][0], limit, rec_iface["data"][0], _stream_of(holder))
        if status != _OK:
            _raise_status(lib, status, "ttd_gpu_mesh_collide")
    return MeshCollisionGPU(_column(records, 0, 4, "i4"), records)


MeshClosestGPU = collections.namedtuple("MeshClosestGPU", ["distance", "records"])
MeshClosestGPU.__doc__ = """ttd.cuda.closest_points's result, on the device: distance (n,), and the n
whole records (n, 72) uint8 (float32: (n, 44)) in ttd_point_result_d's (_f's) layout."""


def _points_args(mesh, points, upper_bound, what):
    import numpy as np

    iface, holder = _interface(points, "points")
    typestr, shape = iface["typestr"], tuple(iface["shape"])
    if typestr not in ("<f8", "<f4"):
        raise TypeError(f"points must hold float64 or float32, not {typestr}")
    if len(shape) != 2 or shape[1] != 3:
        raise ValueError(f"points must have shape (n, 3), not {shape}")
    if not _contiguous(iface):
        raise ValueError("points must be C-contiguous")
    if not isinstance(mesh, Mesh):
        raise TypeError(f"{what}: mesh must be a ttd.cuda.Mesh")
    if mesh._handle is None:
        raise ValueError(f"{what}: the mesh was closed")
    if mesh.dtype != np.dtype(typestr):
        raise TypeError(f"{what}: points of {np.dtype(typestr)} need a mesh of that dtype (got {mesh.dtype})")
    limit = float(upper_bound)
    if not limit >= 0:
        raise ValueError(f"{what}: the bound must be >= 0 (inf for none), not {limit}")
    return iface, holder, typestr, shape[0], limit


def closest_points(mesh, points, upper_bound=float("inf")):
    """The closest point of Mesh mesh to each of n points (a GPU array (n, 3) of the mesh's dtype,
    in the mesh's frame), one GPU thread a point, on the points' library's current stream: each
    result has the bits ttd.closest_points gives (ties to the smallest triangle), NaN for a
    non-finite point, inf past upper_bound."""
    lib = _library()
    iface, holder, typestr, n, limit = _points_args(mesh, points, upper_bound, "closest_points")
    records = _records(holder, n, _POINT_RESULT[typestr])
    if n > 0:
        rec_iface, _ = _interface(records, "records")
        fn = lib.ttd_gpu_points_closest_d if typestr == "<f8" else lib.ttd_gpu_points_closest_f
        status = fn(mesh._handle, n, iface["data"][0], limit, rec_iface["data"][0], _stream_of(holder))
        if status != _OK:
            _raise_status(lib, status, "ttd_gpu_points_closest")
    return MeshClosestGPU(_column(records, 0, 8 if typestr == "<f8" else 4, typestr[1:]), records)


MeshSignedGPU = collections.namedtuple("MeshSignedGPU", ["distance", "records"])
MeshSignedGPU.__doc__ = """ttd.cuda.signed_distance's result, on the device: distance (n,), negative
inside, and the n closest-point records (n, 72) uint8 (float32: (n, 44)) in ttd_point_result_d's
(_f's) layout, TTD_POINT_INSIDE (4) set for the points inside."""


def signed_distance(mesh, points, upper_bound=float("inf")):
    """The signed distance of each of n points (a GPU array (n, 3) of the mesh's dtype, in the
    mesh's frame) to Mesh mesh, negative inside, one GPU thread a point, on the points' library's
    current stream: the bits ttd.signed_distance gives, the side decided by the CPU's exact ray
    count. The mesh must be closed (or open with a boundary that cancels by coordinates, or one
    triangle: unsigned); other open meshes raise ValueError (their winding number is a sum of
    atan2 values whose last bits differ between the host's libm and CUDA). A point whose ray
    count cannot be made exact reads NaN, with POINT_SIDE_REFUSED in its record's flags."""
    lib = _library()
    iface, holder, typestr, n, limit = _points_args(mesh, points, upper_bound, "signed_distance")
    nbytes = 8 if typestr == "<f8" else 4
    records = _records(holder, n, _POINT_RESULT[typestr])
    out = _records(holder, n, nbytes)
    if n > 0:
        rec_iface, _ = _interface(records, "records")
        out_iface, _ = _interface(out, "distances")
        fn = lib.ttd_gpu_points_signed_distance_d if typestr == "<f8" else lib.ttd_gpu_points_signed_distance_f
        status = fn(mesh._handle, n, iface["data"][0], limit, out_iface["data"][0], rec_iface["data"][0],
                    _stream_of(holder))
        if status != _OK:
            _raise_status(lib, status, "ttd_gpu_points_signed_distance")
    return MeshSignedGPU(_column(out, 0, nbytes, typestr[1:]), records)


# ---- continuous collision (docs/ccd.md, section 14) ----
CCDResultGPU = collections.namedtuple("CCDResultGPU", ["hit", "toi", "records"])
CCDResultGPU.__doc__ = """ttd.cuda.ccd_vertex_face's and ccd_edge_edge's result, on the device: hit (n,)
int32, toi (n,) float64 (inf without a hit, NaN for a non-finite query), and the n whole records
(n, 32) uint8 in ttd_ccd_result's layout (toi, gap, hit, flags, sub, evals), each the record the
CPU's ttd.ccd_vertex_face / ttd.ccd_edge_edge computes, bit for bit."""


def _ccd_fn(lib, name):
    fn = getattr(lib, name)
    fn.argtypes = [ctypes.c_size_t, ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p,
                   ctypes.c_double, ctypes.c_void_p, ctypes.c_void_p]
    fn.restype = ctypes.c_int
    return fn


def _ccd(kind, arrays, names, shapes, min_separation):
    lib = _library()
    ifaces, typestr, n, holder = [], None, None, None
    for a, what, shape in zip(arrays, names, shapes):
        iface, h = _interface(a, what)
        ts, sh = iface["typestr"], tuple(iface["shape"])
        if ts not in ("<f8", "<f4"):
            raise TypeError(f"{what} must hold float64 or float32, not {ts}")
        if typestr is not None and ts != typestr:
            raise TypeError(f"{names[0]} and {what} must have the same dtype ({typestr} and {ts})")
        if len(sh) != 1 + len(shape) or sh[1:] != shape:
            raise ValueError(f"{what} must have shape (n, {', '.join(map(str, shape))}), not {sh}")
        if n is not None and sh[0] != n:
            raise ValueError(f"{names[0]} and {what} hold {n} and {sh[0]} queries")
        if not _contiguous(iface):
            raise ValueError(f"{what} must be C-contiguous")
        typestr, n = ts, sh[0]
        holder = h if holder is None else holder
        ifaces.append(iface)
    delta = float(min_separation)
    if not (delta >= 0 and delta != float("inf")):
        raise ValueError(f"min_separation must be finite and >= 0, not {delta}")
    records = _records(holder, n, 32)
    if n > 0:
        rec_iface, _ = _interface(records, "records")
        name = f"ttd_gpu_ccd_{kind}_{'d' if typestr == '<f8' else 'f'}"
        status = _ccd_fn(lib, name)(n, *(i["data"][0] for i in ifaces), delta, rec_iface["data"][0],
                                    _stream_of(holder))
        if status != _OK:
            _raise_status(lib, status, name)
    return CCDResultGPU(_column(records, 16, 4, "i4"), _column(records, 0, 8, "f8"), records)


def ccd_vertex_face(v_t0, f_t0, v_t1, f_t1, *, min_separation=0.0):
    """Continuous collision of n moving vertices against n moving triangles in GPU memory (v (n, 3),
    f (n, 3, 3), all float64 or all float32, C-contiguous), one GPU thread a query, on the arrays'
    library's current stream: each answer is the one ttd.ccd_vertex_face gives, bit for bit."""
    return _ccd("vertex_face", (v_t0, f_t0, v_t1, f_t1), ("v_t0", "f_t0", "v_t1", "f_t1"),
                ((3,), (3, 3), (3,), (3, 3)), min_separation)


def ccd_edge_edge(ea_t0, eb_t0, ea_t1, eb_t1, *, min_separation=0.0):
    """Continuous collision of n moving edge pairs in GPU memory (each (n, 2, 3), all float64 or all
    float32, C-contiguous), as ttd.ccd_edge_edge, bit for bit, one GPU thread a query."""
    return _ccd("edge_edge", (ea_t0, eb_t0, ea_t1, eb_t1), ("ea_t0", "eb_t0", "ea_t1", "eb_t1"),
                ((2, 3), (2, 3), (2, 3), (2, 3)), min_separation)
# ---- end of continuous collision ----
