# SPDX-License-Identifier: MIT
"""The C library called through ctypes on the shared library libttd.so: a path to the C
results that shares nothing with the extension (its own declarations of the structs, its own
argument handling), so that the tests can hold the extension to the library's exact bits."""
import ctypes

import numpy as np


class Options(ctypes.Structure):
    _fields_ = [
        ("method", ctypes.c_int),
        ("isa", ctypes.c_int),
        ("threads", ctypes.c_int),
        ("rho", ctypes.c_double),
        ("tol", ctypes.c_double),
        ("max_iterations", ctypes.c_int),
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
