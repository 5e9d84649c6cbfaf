# SPDX-License-Identifier: MIT
"""The C library called through ctypes on the shared library libttd.so: a path to the C
results that shares nothing with the extension (its own declarations of the structs, its own
argument handling), so that the tests can hold the extension to the library's exact bits.
Pairs (ttd_batch_d/f) and meshes (ttd_mesh_create_* and the mesh queries)."""
import ctypes
import os

import numpy as np


def ctiming_module():
    """ttd._ctiming, the benchmark's C-side timer: built only with TTD_PYTHON_CTIMING=1 (as
    scripts/test-python.sh does, which also sets TTD_TEST_BUILD_DIR: then it must be there);
    a package built without it skips the tests that use it."""
    import pytest

    if os.environ.get("TTD_TEST_BUILD_DIR"):
        from ttd import _ctiming

        return _ctiming
    return pytest.importorskip("ttd._ctiming", reason="ttd._ctiming is built only with TTD_PYTHON_CTIMING=1")


class Options(ctypes.Structure):
    _fields_ = [
        ("method", ctypes.c_int),
        ("isa", ctypes.c_int),
        ("threads", ctypes.c_int),
        ("rho", ctypes.c_double),
        ("tol", ctypes.c_double),
        ("max_iterations", ctypes.c_int),
        ("solid", ctypes.c_int),
        ("internal_cookie", ctypes.c_uint32),
    ]


def _result_struct(real):
    class Result(ctypes.Structure):
        _fields_ = [
            ("distance", real),
            ("p", real * 3),
            ("q", real * 3),
            ("bary_p", real * 3),
            ("bary_q", real * 3),
            ("flags", ctypes.c_uint32),
            ("feature_p", ctypes.c_uint8),
            ("feature_q", ctypes.c_uint8),
            ("iterations", ctypes.c_uint16),
        ]

    return Result


ResultD = _result_struct(ctypes.c_double)
ResultF = _result_struct(ctypes.c_float)
METHODS = ("exact", "penalty", "penalty-ref", "barrier", "certified")
FIELDS = [name for name, _ in ResultD._fields_]


def _mesh_structs(real):
    class MeshResult(ctypes.Structure):
        _fields_ = [("distance", real), ("p", real * 3), ("q", real * 3), ("tri_a", ctypes.c_uint32),
                    ("tri_b", ctypes.c_uint32), ("feature_a", ctypes.c_uint8), ("feature_b", ctypes.c_uint8),
                    ("flags", ctypes.c_uint16), ("node_tests", ctypes.c_uint32), ("pair_tests", ctypes.c_uint64)]

    class Contact(ctypes.Structure):
        _fields_ = [("tri_a", ctypes.c_uint32), ("tri_b", ctypes.c_uint32), ("distance", real), ("p", real * 3),
                    ("q", real * 3)]

    class Contacts(ctypes.Structure):
        _fields_ = [("pairs", ctypes.POINTER(Contact)), ("count", ctypes.c_size_t),
                    ("pose_start", ctypes.POINTER(ctypes.c_size_t)), ("poses", ctypes.c_size_t),
                    ("capacity", ctypes.c_size_t), ("pose_capacity", ctypes.c_size_t)]

    class Closest(ctypes.Structure):
        _fields_ = [("partner", ctypes.c_uint32), ("distance", real), ("p", real * 3), ("q", real * 3)]

    return MeshResult, Contact, Contacts, Closest


class Collision(ctypes.Structure):
    _fields_ = [("hit", ctypes.c_uint32), ("tri_a", ctypes.c_uint32), ("tri_b", ctypes.c_uint32),
                ("node_tests", ctypes.c_uint32), ("pair_tests", ctypes.c_uint64)]


MESH_STRUCTS = {np.dtype(np.float64): _mesh_structs(ctypes.c_double),
                np.dtype(np.float32): _mesh_structs(ctypes.c_float)}


def records(struct, buffer, count):
    """count structs of buffer (a ctypes array or pointer) as a numpy record array (a copy),
    its dtype taken from ctypes' layout of the struct."""
    names, formats = [], []
    for name, ctype in struct._fields_:
        names.append(name)
        if issubclass(ctype, ctypes.Array):
            formats.append((np.dtype(ctype._type_), (ctype._length_,)))
        else:
            formats.append(np.dtype(ctype))
    dtype = np.dtype({"names": names, "formats": formats, "offsets": [getattr(struct, n).offset for n in names],
                      "itemsize": ctypes.sizeof(struct)})
    if count == 0:
        return np.zeros(0, dtype)
    address = ctypes.addressof(buffer) if isinstance(buffer, ctypes.Array) else ctypes.cast(buffer, ctypes.c_void_p).value
    return np.frombuffer((ctypes.c_char * (count * ctypes.sizeof(struct))).from_address(address), dtype=dtype).copy()


class Library:
    """ttd_batch_d / ttd_batch_f and the name functions of libttd.so."""

    def __init__(self, path):
        self.path = path
        lib = self.lib = ctypes.CDLL(str(path))
        lib.ttd_default_options.restype = Options
        lib.ttd_default_options.argtypes = []
        for suffix, real, result in (("d", ctypes.c_double, ResultD), ("f", ctypes.c_float, ResultF)):
            fn = getattr(lib, "ttd_batch_" + suffix)
            fn.restype = ctypes.c_int
            fn.argtypes = [ctypes.POINTER(Options), ctypes.c_size_t, ctypes.POINTER(real), ctypes.POINTER(real),
                           ctypes.POINTER(real), ctypes.POINTER(result)]
        for suffix, real in (("d", ctypes.c_double), ("f", ctypes.c_float)):
            MeshResult, _, Contacts, Closest = MESH_STRUCTS[np.dtype(np.float64 if suffix == "d" else np.float32)]
            mesh, opt = ctypes.c_void_p, ctypes.POINTER(Options)
            head = [opt, mesh, mesh, ctypes.c_size_t, ctypes.POINTER(real)]
            for name, argtypes in (
                    ("ttd_mesh_create_", [opt, ctypes.POINTER(real), ctypes.c_size_t, ctypes.POINTER(ctypes.c_uint32),
                                          ctypes.c_size_t, ctypes.POINTER(ctypes.c_void_p)]),
                    ("ttd_mesh_distance_", head + [real, real, ctypes.POINTER(MeshResult)]),
                    ("ttd_mesh_contacts_", head + [real, ctypes.POINTER(Contacts)]),
                    ("ttd_mesh_closest_", head + [real, ctypes.POINTER(Closest), ctypes.POINTER(Closest)]),
                    ("ttd_mesh_collide_", head + [real, ctypes.POINTER(Collision)])):
                fn = getattr(lib, name + suffix)
                fn.restype = ctypes.c_int
                fn.argtypes = argtypes
            getattr(lib, "ttd_contacts_free_" + suffix).argtypes = [ctypes.POINTER(Contacts)]
            getattr(lib, "ttd_contacts_free_" + suffix).restype = None
        lib.ttd_mesh_destroy.argtypes = [ctypes.c_void_p]
        lib.ttd_mesh_destroy.restype = None
        for name in ("ttd_mesh_vertex_count", "ttd_mesh_triangle_count", "ttd_mesh_node_count"):
            getattr(lib, name).argtypes = [ctypes.c_void_p]
            getattr(lib, name).restype = ctypes.c_size_t
        lib.ttd_version_string.restype = ctypes.c_char_p
        lib.ttd_isa_name.restype = ctypes.c_char_p
        lib.ttd_isa_name.argtypes = [ctypes.c_int]
        lib.ttd_method_name.restype = ctypes.c_char_p
        lib.ttd_method_name.argtypes = [ctypes.c_int]

    def version(self):
        return self.lib.ttd_version_string().decode()

    def batch(self, S, T, method="exact", **fields):
        """(status, records): every pair's result struct as a numpy record array with the
        fields of ttd_result_d/f (offsets from ctypes' layout of the structs above)."""
        S = np.ascontiguousarray(S)
        T = np.ascontiguousarray(T)
        assert S.dtype == T.dtype and S.dtype in (np.float32, np.float64)
        dbl = S.dtype == np.float64
        real = ctypes.c_double if dbl else ctypes.c_float
        Result = ResultD if dbl else ResultF
        n = S.size // 9
        opt = self.lib.ttd_default_options()
        opt.method = METHODS.index(method)
        for k, v in fields.items():
            setattr(opt, k, v)
        out = (Result * max(n, 1))()
        fn = self.lib.ttd_batch_d if dbl else self.lib.ttd_batch_f
        status = fn(ctypes.byref(opt), n, S.ctypes.data_as(ctypes.POINTER(real)),
                    T.ctypes.data_as(ctypes.POINTER(real)), None, out)
        dtype = np.dtype({
            "names": FIELDS,
            "formats": ["f8" if dbl else "f4"] + [("f8" if dbl else "f4", (3,))] * 4 + ["u4", "u1", "u1", "u2"],
            "offsets": [getattr(Result, f).offset for f in FIELDS],
            "itemsize": ctypes.sizeof(Result),
        })
        return status, np.frombuffer(out, dtype=dtype, count=n).copy()

    # ---- meshes ----------------------------------------------------------------------------

    def options(self, **fields):
        opt = self.lib.ttd_default_options()
        for k, v in fields.items():
            setattr(opt, k, v)
        return opt

    def mesh(self, vertices, faces, **fields):
        """(status, CMesh) from ttd_mesh_create_d/f on vertices (float64 or float32) and faces."""
        V = np.ascontiguousarray(vertices)
        F = np.ascontiguousarray(faces, dtype=np.uint32)
        real = ctypes.c_double if V.dtype == np.float64 else ctypes.c_float
        handle = ctypes.c_void_p()
        fn = self.lib.ttd_mesh_create_d if V.dtype == np.float64 else self.lib.ttd_mesh_create_f
        status = fn(ctypes.byref(self.options(**fields)), V.ctypes.data_as(ctypes.POINTER(real)), len(V),
                    F.ctypes.data_as(ctypes.POINTER(ctypes.c_uint32)), len(F), ctypes.byref(handle))
        return status, (CMesh(self, handle, V.dtype) if status == 0 else None)


class CMesh:
    """A ttd_mesh made through ctypes, and the four queries on it (against another CMesh)."""

    def __init__(self, library, handle, dtype):
        self.library, self.lib, self.handle, self.dtype = library, library.lib, handle, np.dtype(dtype)
        self.MeshResult, self.Contact, self.Contacts, self.Closest = MESH_STRUCTS[self.dtype]
        self.real = ctypes.c_double if self.dtype == np.float64 else ctypes.c_float
        self.suffix = "d" if self.dtype == np.float64 else "f"

    def __del__(self):
        if getattr(self, "handle", None):
            self.lib.ttd_mesh_destroy(self.handle)
            self.handle = None

    def counts(self):
        return (self.lib.ttd_mesh_vertex_count(self.handle), self.lib.ttd_mesh_triangle_count(self.handle),
                self.lib.ttd_mesh_node_count(self.handle))

    def _poses(self, poses):
        """(k, 3, 4) [R | t] of (k, 4, 4) / (k, 3, 4) poses, C-contiguous in the mesh's dtype."""
        P = np.asarray(poses).astype(self.dtype)[..., :3, :].reshape(-1, 3, 4).copy()
        return P, len(P)

    def _call(self, name, b, P, *rest, **fields):
        fn = getattr(self.lib, f"ttd_mesh_{name}_{self.suffix}")
        return fn(ctypes.byref(self.library.options(**fields)), self.handle, b.handle, len(P),
                  P.ctypes.data_as(ctypes.POINTER(self.real)), *rest)

    def distance(self, b, poses, upper_bound=np.inf, rel_tol=0.0, **fields):
        P, k = self._poses(poses)
        out = (self.MeshResult * max(k, 1))()
        status = self._call("distance", b, P, upper_bound, rel_tol, out, **fields)
        return status, records(self.MeshResult, out, k)

    def collide(self, b, poses, margin=0.0, **fields):
        P, k = self._poses(poses)
        out = (Collision * max(k, 1))()
        status = self._call("collide", b, P, margin, out, **fields)
        return status, records(Collision, out, k)

    def contacts(self, b, poses, margin, **fields):
        """(status, contact records, pose_start)"""
        P, k = self._poses(poses)
        s = self.Contacts()
        status = self._call("contacts", b, P, margin, ctypes.byref(s), **fields)
        try:
            recs = records(self.Contact, s.pairs, s.count) if status == 0 else None
            starts = np.array([s.pose_start[i] for i in range(k + 1)]) if status == 0 else None
        finally:
            getattr(self.lib, "ttd_contacts_free_" + self.suffix)(ctypes.byref(s))
        return status, recs, starts

    def closest(self, b, poses, margin, **fields):
        """(status, for_a records (k, na), for_b records (k, nb))"""
        P, k = self._poses(poses)
        na, nb = self.counts()[1], b.counts()[1]
        fa, fb = (self.Closest * max(k * na, 1))(), (self.Closest * max(k * nb, 1))()
        status = self._call("closest", b, P, margin, fa, fb, **fields)
        return status, records(self.Closest, fa, k * na).reshape(k, na), records(self.Closest, fb, k * nb).reshape(k, nb)
