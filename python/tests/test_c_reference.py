# SPDX-License-Identifier: MIT
"""The extension gives the C library's own results, bit for bit: against ttd_batch_d/f
called through ctypes on libttd.so (c_reference.py), and against the `ttd dist` program's
printed output (round-trip precision), for every method, precision and instruction set."""
import subprocess
import warnings

import numpy as np
import pytest

import c_reference
from c_reference import ctiming_module
import ttd
from cases import random_pairs

PRECISIONS = [np.float64, np.float32]


def assert_same_records(r, records):
    """A PairResult equals the C result structs, field by field, bit for bit (NaN = NaN)."""
    for field in c_reference.FIELDS:
        ours = np.asarray(getattr(r, field))
        theirs = records[field]
        assert ours.dtype == theirs.dtype, field
        assert ours.shape == theirs.shape, field
        np.testing.assert_array_equal(ours, theirs, err_msg=field)


@pytest.mark.filterwarnings("ignore::ttd.NotConvergedWarning")
@pytest.mark.parametrize("dtype", PRECISIONS, ids=["float64", "float32"])
@pytest.mark.parametrize("method", c_reference.METHODS)
def test_every_method_equals_the_c_library(libttd, method, dtype):
    S, T = random_pairs(1000, seed=21, dtype=dtype)
    status, records = libttd.batch(S, T, method=method)
    assert status in (0, 1)  # TTD_OK, or TTD_WARN_NOT_CONVERGED for the paper's ttd1
    assert_same_records(ttd.distance(S, T, method=method, points=True), records)
    np.testing.assert_array_equal(ttd.distance(S, T, method=method), records["distance"])


@pytest.mark.parametrize("dtype", PRECISIONS, ids=["float64", "float32"])
def test_every_isa_equals_the_c_library(libttd, dtype):
    S, T = random_pairs(700, seed=22, dtype=dtype)
    for isa in ttd.ISAS:
        if isa == "auto" or not ttd.isa_available(isa):
            continue
        status, records = libttd.batch(S, T, isa=ttd.ISAS.index(isa))
        assert status == 0
        assert_same_records(ttd.distance(S, T, isa=isa, points=True), records)


def test_options_reach_the_library(libttd):
    S, T = random_pairs(300, seed=23)
    kw = dict(rho=1e3, tol=1e-6, max_iterations=7)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ttd.NotConvergedWarning)
        ours = ttd.distance(S, T, method="penalty", points=True, threads=1, **kw)
    status, records = libttd.batch(S, T, method="penalty", threads=1, **kw)
    assert_same_records(ours, records)
    # ... and change the result: the defaults give other bits.
    _, defaults = libttd.batch(S, T, method="penalty")
    assert not np.array_equal(records["distance"], defaults["distance"])


def test_nonfinite_pairs_equal_the_c_library(libttd):
    S, T = random_pairs(600, seed=24)
    S[5, 1, 2] = np.nan
    T[17, 0, 0] = np.inf
    S[300, 2, 1] = -np.inf
    status, records = libttd.batch(S, T)
    assert status == 2  # TTD_ERR_NONFINITE_INPUT
    with pytest.warns(ttd.NonFiniteInputWarning, match="3 of 600 pairs"):
        r = ttd.distance(S, T, points=True)
    assert_same_records(r, records)


def test_record_layout_matches_ctypes():
    # The extension takes offsets with offsetof(); ctypes lays the structs out by itself.
    for dtype, Result in ((ttd.RESULT_DTYPE_FLOAT64, c_reference.ResultD),
                          (ttd.RESULT_DTYPE_FLOAT32, c_reference.ResultF)):
        assert dtype.itemsize == c_reference.ctypes.sizeof(Result)
        assert list(dtype.names) == c_reference.FIELDS
        for name in c_reference.FIELDS:
            assert dtype.fields[name][1] == getattr(Result, name).offset, name


def test_version_is_the_librarys(libttd):
    assert ttd.version == libttd.version() == ttd.__version__
    assert ttd.version == f"{ttd._ttd.VERSION_MAJOR}.{ttd._ttd.VERSION_MINOR}.{ttd._ttd.VERSION_PATCH}"


def test_names_are_the_librarys(libttd):
    assert ttd.METHODS == tuple(libttd.lib.ttd_method_name(i).decode() for i in range(len(ttd.METHODS)))
    assert libttd.lib.ttd_method_name(len(ttd.METHODS)) is None
    assert ttd.ISAS == tuple(libttd.lib.ttd_isa_name(i).decode() for i in range(len(ttd.ISAS)))
    assert libttd.lib.ttd_isa_name(len(ttd.ISAS)) is None
    assert [m.value for m in ttd.Method] == list(ttd.METHODS)
    assert [i.value for i in ttd.Isa] == list(ttd.ISAS)


@pytest.mark.parametrize("precision", ["double", "float"])
def test_equals_the_ttd_program(ttd_program, precision):
    # `ttd dist --points` prints d, p and q so that they read back to the same bits (%.17g
    # for double, %.9g for float); its input is rounded to float with --precision float.
    S, T = random_pairs(200, seed=25)
    S[3] = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]
    T[3] = S[3] + [0, 0, 2]
    text = "\n".join(" ".join(repr(float(x)) for x in np.concatenate([s.ravel(), t.ravel()]))
                     for s, t in zip(S, T))
    out = subprocess.run([str(ttd_program), "dist", "--points", "--precision", precision],
                         input=text, capture_output=True, text=True, check=True).stdout
    dtype = np.float64 if precision == "double" else np.float32
    printed = np.array([[float(x) for x in line.split()] for line in out.splitlines()]).astype(dtype)
    assert printed.shape == (200, 7)
    r = ttd.distance(S.astype(dtype), T.astype(dtype), points=True)
    np.testing.assert_array_equal(printed[:, 0], r.distance)
    np.testing.assert_array_equal(printed[:, 1:4], r.p)
    np.testing.assert_array_equal(printed[:, 4:7], r.q)
    assert printed[3, 0] == 2.0


@pytest.mark.parametrize("dtype", PRECISIONS, ids=["float64", "float32"])
def test_benchmark_timer_makes_the_same_call(dtype):
    # bench/python_overhead.py subtracts ttd._ctiming's time from ttd.distance's: it must time
    # the same library call, which writes the same results into the same buffer.
    _ctiming = ctiming_module()

    S, T = random_pairs(500, seed=26, dtype=dtype)
    out = np.empty(500, dtype)
    assert _ctiming.time_calls(S.reshape(500, 9), T.reshape(500, 9), out, 3, threads=1) > 0
    np.testing.assert_array_equal(out, ttd.distance(S, T))
    rec = np.empty(500, ttd.RESULT_DTYPE_FLOAT64 if dtype == np.float64 else ttd.RESULT_DTYPE_FLOAT32)
    _ctiming.time_calls(S, T, rec, 1, method="penalty", points=True)
    assert_same_records(ttd.distance(S, T, method="penalty", points=True), rec)
    with pytest.raises(ValueError, match="out must hold n distances"):
        _ctiming.time_calls(S, T, np.empty(499, dtype), 1)
