# SPDX-License-Identifier: MIT
"""ttd.distance's interface: what shapes and dtypes it takes and gives back, empty input,
copies of awkward layouts, warnings, and every error path (each a Python exception that
names the problem). Values are tested in test_values.py and test_c_reference.py."""
import pickle
import warnings

import numpy as np
import pytest

import ttd
from cases import random_pairs


@pytest.fixture
def sT():
    S, T = random_pairs(12, seed=31)
    return S, T


# ---- shapes -------------------------------------------------------------------------------

def test_layouts_and_pair_shapes(sT):
    S, T = sT
    d = ttd.distance(S, T)
    assert d.shape == (12,) and d.dtype == np.float64 and d.flags.c_contiguous
    # (n, 9) is the same triangles, and the two layouts mix.
    np.testing.assert_array_equal(ttd.distance(S.reshape(12, 9), T.reshape(12, 9)), d)
    np.testing.assert_array_equal(ttd.distance(S, T.reshape(12, 9)), d)
    # Any pair shape: (3, 4) pairs give a (3, 4) array.
    np.testing.assert_array_equal(ttd.distance(S.reshape(3, 4, 3, 3), T.reshape(3, 4, 9)), d.reshape(3, 4))
    r = ttd.distance(S.reshape(3, 4, 9), T.reshape(3, 4, 9), points=True)
    assert r.distance.shape == (3, 4) and r.p.shape == (3, 4, 3) and r.flags.shape == (3, 4)


def test_single_pair_gives_scalars(sT):
    S, T = sT
    d = ttd.distance(S[0], T[0])
    assert isinstance(d, np.float64) and d == ttd.distance(S, T)[0]
    assert ttd.distance(S[0].ravel(), T[0].ravel()) == d
    assert isinstance(ttd.distance(S[0].astype(np.float32), T[0].astype(np.float32)), np.float32)
    # Nested lists are arrays too.
    assert ttd.distance(S[0].tolist(), T[0].tolist()) == d
    r = ttd.distance(S[0], T[0], points=True)
    assert isinstance(r, ttd.PairResult)
    assert r.distance == d and r.p.shape == (3,) and isinstance(r.flags, np.uint32)
    assert isinstance(r.feature_p, np.uint8) and isinstance(r.iterations, np.uint16)


def test_pair_result_is_a_named_tuple(sT):
    S, T = sT
    r = ttd.distance(S, T, points=True)
    assert len(r) == 9 and r[0] is r.distance
    d, p, q, bary_p, bary_q, flags, feature_p, feature_q, iterations = r
    assert p.shape == (12, 3) and flags.dtype == np.uint32 and feature_q.dtype == np.uint8
    assert iterations.dtype == np.uint16
    # Fields are views of one block laid out as the C struct.
    assert p.strides == (ttd.RESULT_DTYPE_FLOAT64.itemsize, 8)
    assert np.may_share_memory(p, q) and not np.shares_memory(p, q)
    # Results pickle (to move between processes, e.g. with Dask).
    r2 = pickle.loads(pickle.dumps(r))
    assert type(r2) is ttd.PairResult
    for a, b in zip(r, r2):
        np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize("shape", [(4, 3), (12, 8), (3,), (), (12, 3, 4), (12, 9, 1), (2, 3, 3, 2)])
def test_bad_shapes_name_the_argument(shape):
    good = np.zeros((12, 9))
    bad = np.zeros(shape)
    with pytest.raises(ValueError, match=r"S has shape .*\(\.\.\., 3, 3\).*\(\.\.\., 9\)"):
        ttd.distance(bad, good)
    with pytest.raises(ValueError, match="T has shape"):
        ttd.distance(good, bad)


def test_pair_shapes_must_match():
    with pytest.raises(ValueError, match=r"S and T have shapes \(12, 9\) and \(11, 9\)"):
        ttd.distance(np.zeros((12, 9)), np.zeros((11, 9)))
    with pytest.raises(ValueError, match="S and T have shapes"):
        ttd.distance(np.zeros((3, 3)), np.zeros((5, 3, 3)))  # no broadcasting
    with pytest.raises(ValueError, match="S and T have shapes"):
        ttd.distance(np.zeros((2, 6, 9)), np.zeros((12, 9)))


def test_not_an_array():
    with pytest.raises(ValueError, match="S is not an array of coordinates"):
        ttd.distance([[1, 2, 3], [4, 5]], np.zeros(9))
    with pytest.raises(TypeError, match="T has dtype object"):
        ttd.distance(np.zeros(9), [None] * 9)
    with pytest.raises(TypeError, match="T has dtype <U1"):
        ttd.distance(np.zeros(9), ["a"] * 9)


# ---- dtypes -------------------------------------------------------------------------------

def test_dtype_rules(sT):
    S, T = sT
    d64 = ttd.distance(S, T)
    S32, T32 = S.astype(np.float32), T.astype(np.float32)
    d32 = ttd.distance(S32, T32)
    assert d32.dtype == np.float32
    # precision= converts both, either way.
    np.testing.assert_array_equal(ttd.distance(S, T, precision="float32"), d32)
    np.testing.assert_array_equal(ttd.distance(S32, T32, precision="float64"),
                                  ttd.distance(S32.astype(np.float64), T32.astype(np.float64)))
    for name in ("single", np.float32, np.dtype("float32"), "f4"):
        assert ttd.distance(S, T, precision=name).dtype == np.float32
    for name in ("double", np.float64, "float64", "f8"):
        assert ttd.distance(S32, T32, precision=name).dtype == np.float64
    # Integers and bools are float64.
    Si, Ti = np.round(S * 8).astype(np.int32), np.round(T * 8).astype(np.int64)
    di = ttd.distance(Si, Ti)
    assert di.dtype == np.float64
    np.testing.assert_array_equal(di, ttd.distance(Si.astype(float), Ti.astype(float)))
    assert ttd.distance(Si.astype(bool), Ti.astype(np.uint8)).dtype == np.float64
    assert ttd.distance(Si, Ti, precision="float32").dtype == np.float32


def test_mixed_precisions_are_refused(sT):
    S, T = sT
    with pytest.raises(TypeError, match="S has dtype float64 and T has dtype float32"):
        ttd.distance(S, T.astype(np.float32))
    with pytest.raises(TypeError, match="S has dtype int64 and T has dtype float32.*precision="):
        ttd.distance(S.astype(np.int64), T.astype(np.float32))


@pytest.mark.parametrize("dtype", [np.float16, np.longdouble, np.complex128])
def test_unsupported_dtypes(sT, dtype):
    S, T = sT
    if dtype is np.longdouble and np.finfo(np.longdouble).bits == 64:
        pytest.skip("long double is double here")
    with pytest.raises(TypeError, match="S has dtype"):
        ttd.distance(S.astype(dtype), T.astype(dtype))
    if dtype is not np.complex128:  # an explicit precision converts real dtypes
        assert ttd.distance(S.astype(dtype), T.astype(dtype), precision="float64").dtype == np.float64
    else:
        with pytest.raises(TypeError, match="S has dtype complex128: ttd takes real coordinates"):
            ttd.distance(S.astype(dtype), T.astype(dtype), precision="float64")


@pytest.mark.parametrize("bad", ["float", "half", "float16", np.int32, 3, "int"])
def test_bad_precision(sT, bad):
    S, T = sT
    with pytest.raises(ValueError, match="precision="):
        ttd.distance(S, T, precision=bad)


def test_awkward_layouts_are_copied(sT):
    S, T = sT
    d = ttd.distance(S, T)
    big = np.zeros((12, 3, 3, 2))
    big[..., 1] = S
    assert not big[..., 1].flags.c_contiguous
    np.testing.assert_array_equal(ttd.distance(big[..., 1], T), d)  # strided
    np.testing.assert_array_equal(ttd.distance(np.asfortranarray(S), T), d)  # Fortran order
    np.testing.assert_array_equal(ttd.distance(S.astype(">f8"), T.astype(">f8")), d)  # big-endian
    np.testing.assert_array_equal(ttd.distance(S[::-1], T[::-1]), d[::-1])
    # Misaligned float64 (offset by one byte in a byte buffer).
    buf = np.zeros(S.nbytes + 1, np.uint8)
    mis = buf[1:].view(np.float64).reshape(S.shape)
    mis[...] = S
    assert not mis.flags.aligned
    np.testing.assert_array_equal(ttd.distance(mis, T), d)
    # The inputs are not modified.
    S0 = S.copy()
    ttd.distance(S, T, points=True)
    np.testing.assert_array_equal(S, S0)


# ---- out= ----------------------------------------------------------------------------------

def test_out_is_written_and_returned(sT):
    S, T = sT
    d = ttd.distance(S, T)
    out = np.full(12, -1.0)
    assert ttd.distance(S, T, out=out) is out
    np.testing.assert_array_equal(out, d)
    out32 = np.empty((3, 4), np.float32)
    assert ttd.distance(S.reshape(3, 4, 9).astype(np.float32), T.reshape(3, 4, 9).astype(np.float32),
                        out=out32) is out32
    one = np.empty((), np.float64)
    assert ttd.distance(S[0], T[0], out=one) is one and one == d[0]
    rec = np.empty(12, ttd.RESULT_DTYPE_FLOAT64)
    r = ttd.distance(S, T, points=True, out=rec)
    ref = ttd.distance(S, T, points=True)
    assert r.p.base is rec or np.may_share_memory(r.p, rec)
    for a, b in zip(r, ref):
        np.testing.assert_array_equal(a, b)
    np.testing.assert_array_equal(rec["q"], ref.q)
    assert ttd.distance(S, T, out=None).shape == (12,)


def test_out_errors(sT):
    S, T = sT
    with pytest.raises(TypeError, match="out has dtype float32: this call writes float64"):
        ttd.distance(S, T, out=np.empty(12, np.float32))
    with pytest.raises(TypeError, match="this call writes ttd.RESULT_DTYPE_FLOAT64"):
        ttd.distance(S, T, points=True, out=np.empty(12, ttd.RESULT_DTYPE_FLOAT32))
    with pytest.raises(TypeError, match="this call writes ttd.RESULT_DTYPE_FLOAT32"):
        ttd.distance(S.astype(np.float32), T.astype(np.float32), points=True, out=np.empty(12))
    with pytest.raises(ValueError, match=r"out has 1 dimension\(s\) where the pairs have shape \(3, 4\)"):
        ttd.distance(S.reshape(3, 4, 9), T.reshape(3, 4, 9), out=np.empty(12))
    with pytest.raises(ValueError, match="out has 1 dimension"):
        ttd.distance(S, T, out=np.empty(11))
    with pytest.raises(ValueError, match="C-contiguous"):
        ttd.distance(S, T, out=np.empty(24)[::2])
    ro = np.empty(12)
    ro.flags.writeable = False
    with pytest.raises(ValueError, match="writeable"):
        ttd.distance(S, T, out=ro)
    with pytest.raises(TypeError, match="out must be a numpy array, not list"):
        ttd.distance(S, T, out=[0.0] * 12)
    buf = np.zeros(12 * 9 + 12)
    Sb = buf[:108].reshape(12, 9)
    Sb[...] = S.reshape(12, 9)
    with pytest.raises(ValueError, match="shares memory with S or T"):
        ttd.distance(Sb, T, out=buf[100:112])
    np.testing.assert_array_equal(ttd.distance(Sb, T, out=buf[108:]), ttd.distance(S, T))


# ---- empty input ------------------------------------------------------------------------

@pytest.mark.parametrize("shape", [(0, 9), (0, 3, 3), (4, 0, 9)])
@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_empty_input(shape, dtype):
    e = np.zeros(shape, dtype)
    d = ttd.distance(e, e)
    lead = shape[:-2] if shape[-1] == 3 else shape[:-1]
    assert d.shape == lead and d.dtype == dtype
    r = ttd.distance(e, e, points=True)
    assert r.distance.shape == lead and r.p.shape == lead + (3,) and r.flags.shape == lead
    assert r.p.dtype == dtype


def test_empty_input_still_checks_options():
    e = np.zeros((0, 9))
    with pytest.raises(ValueError, match="rho"):
        ttd.distance(e, e, method="penalty", rho=-1)
    unavailable = [i for i in ttd.ISAS if i != "auto" and not ttd.isa_available(i)]
    if unavailable:
        with pytest.raises(ttd.IsaUnavailableError):
            ttd.distance(e, e, isa=unavailable[0])
    with pytest.raises(ValueError, match="method"):
        ttd.distance(e, e, method="nope")


# ---- non-finite input and non-convergence -------------------------------------------------

def test_nonfinite_pairs_warn_and_give_nan(sT):
    S, T = sT
    clean = ttd.distance(S, T)
    S = S.copy()
    S[2, 0, 0] = np.nan
    S[7, 2, 1] = np.inf
    with pytest.warns(ttd.NonFiniteInputWarning, match="2 of 12 pairs had NaN or infinite coordinates"):
        d = ttd.distance(S, T)
    assert np.isnan(d[[2, 7]]).all()
    keep = np.ones(12, bool)
    keep[[2, 7]] = False
    np.testing.assert_array_equal(d[keep], clean[keep])
    with pytest.warns(ttd.NonFiniteInputWarning):
        r = ttd.distance(S.astype(np.float32), T.astype(np.float32), points=True)
    assert np.isnan(r.p[2]).all() and np.isnan(r.bary_q[7]).all()
    np.testing.assert_array_equal((r.flags & ttd.Flag.NONFINITE) != 0, ~keep)
    # The warning can be made an error.
    with warnings.catch_warnings():
        warnings.simplefilter("error", ttd.NonFiniteInputWarning)
        with pytest.raises(ttd.NonFiniteInputWarning):
            ttd.distance(S, T)
    assert issubclass(ttd.NonFiniteInputWarning, RuntimeWarning)


def test_not_converged_warns_with_the_count():
    S, T = random_pairs(200, seed=32)
    with pytest.warns(ttd.NotConvergedWarning, match=r"max_iterations=1 on (\d+) of 200 pairs") as w:
        r = ttd.distance(S, T, method="penalty", max_iterations=1, points=True)
    flagged = np.count_nonzero(r.flags & ttd.Flag.NOT_CONVERGED)
    assert flagged > 0 and f"on {flagged} of 200" in str(w[0].message)
    with pytest.warns(ttd.NotConvergedWarning, match="some of 200 pairs"):
        ttd.distance(S, T, method="penalty", max_iterations=1)
    # Both conditions at once: the flags report both.
    S[0, 0, 0] = np.nan
    with pytest.warns(RuntimeWarning) as w:
        ttd.distance(S, T, method="penalty", max_iterations=1, points=True)
    assert {type(x.message) for x in w} == {ttd.NonFiniteInputWarning, ttd.NotConvergedWarning}
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ttd.distance(S[1:], T[1:])  # the exact method never warns on finite input


# ---- options ------------------------------------------------------------------------------

def test_enums_and_names_are_accepted(sT):
    S, T = sT
    for m in ttd.Method:
        a = ttd.distance(S, T, method=m, threads=1)
        b = ttd.distance(S, T, method=m.value, threads=1)
        np.testing.assert_array_equal(a, b)
    assert str(ttd.Method.PENALTY_REFERENCE) == "penalty-ref"
    np.testing.assert_array_equal(ttd.distance(S, T, isa=ttd.Isa.SCALAR), ttd.distance(S, T, isa="scalar"))
    assert ttd.Flag.INTERSECTING == ttd._ttd.PAIR_INTERSECTING == 8


@pytest.mark.parametrize("kw,exc,match", [
    (dict(method="fast"), ValueError, r"method='fast' is not one of 'exact', 'penalty'"),
    (dict(method=1), TypeError, "method must be a str, not int"),
    (dict(isa="avx9"), ValueError, r"isa='avx9' is not one of 'auto', 'scalar'"),
    (dict(isa=None, method=None), None, None),
    (dict(threads=-1), ValueError, r"threads=-1 is out of range: threads >= 0"),
    (dict(threads=2**40), ValueError, r"threads=1099511627776 is out of range"),
    (dict(threads=1.5), TypeError, "threads must be an int, not float"),
    (dict(threads=True), TypeError, "threads must be an int, not bool"),
    (dict(method="penalty", rho=0), ValueError, r"rho=0.0 is out of range: rho in \(0, 1e150\]"),
    (dict(method="penalty", rho=float("nan")), ValueError, "rho=nan is out of range"),
    (dict(method="penalty", rho=1e200), ValueError, "rho=1e\\+200 is out of range"),
    (dict(method="penalty", rho="big"), TypeError, "rho must be a real number, not str"),
    (dict(method="penalty", tol=2), ValueError, r"tol=2.0 is out of range: tol in \[0, 1\]"),
    (dict(method="penalty", tol=-1e-300), ValueError, "tol=-1e-300 is out of range"),
    (dict(method="penalty", max_iterations=0), ValueError, "max_iterations=0 is out of range: 1 <="),
    (dict(method="penalty", max_iterations=65536), ValueError, "max_iterations=65536 is out of range"),
    (dict(method="penalty", max_iterations=2.0), TypeError, "max_iterations must be an int"),
    # The library checks every option whatever the method: out of range is refused for exact too.
    (dict(rho=-5), ValueError, "rho=-5.0 is out of range"),
])
def test_option_errors(sT, kw, exc, match):
    S, T = sT
    if exc is None:
        ttd.distance(S, T, **kw)
        return
    with pytest.raises(exc, match=match):
        ttd.distance(S, T, **kw)


def test_numpy_scalars_as_options(sT):
    S, T = sT
    a = ttd.distance(S, T, method="penalty", rho=np.float32(1e4), max_iterations=np.int64(50), threads=np.uint8(1))
    b = ttd.distance(S, T, method="penalty", rho=1e4, max_iterations=50, threads=1)
    np.testing.assert_array_equal(a, b)


def test_signature_errors(sT):
    S, T = sT
    with pytest.raises(TypeError):
        ttd.distance(S, T, "exact")  # options are keyword-only
    with pytest.raises(TypeError):
        ttd.distance(S)
    with pytest.raises(TypeError):
        ttd.distance(S, T, methd="exact")


def test_threads_do_not_change_results():
    S, T = random_pairs(20000, seed=33)
    ref = ttd.distance(S, T, threads=1, points=True)
    for threads in (0, 2, 3, 7):
        r = ttd.distance(S, T, threads=threads, points=True)
        for a, b in zip(r, ref):
            np.testing.assert_array_equal(a, b)


# ---- instruction sets ---------------------------------------------------------------------

def test_isa_queries():
    assert ttd.isa_available("scalar")
    assert not ttd.isa_available("auto")
    chosen = ttd.isa_selected()
    assert chosen in ttd.ISAS and chosen != "auto" and ttd.isa_available(chosen)
    assert ttd.isa_selected("scalar") == "scalar"
    assert ttd.isa_lanes("scalar") == 1
    assert ttd.isa_lanes("avx2", "float32") == 8 and ttd.isa_lanes("avx2", precision="float64") == 4
    assert ttd.isa_lanes() == ttd.isa_lanes(chosen)
    with pytest.raises(ValueError, match="isa='x87' is not one of"):
        ttd.isa_available("x87")
    with pytest.raises(TypeError, match="isa must be a str"):
        ttd.isa_available(3)
    with pytest.raises(ValueError, match="precision"):
        ttd.isa_lanes("sse2", "half")
    with pytest.raises(ValueError, match="needs a precision"):
        ttd.isa_lanes("sse2", None)


def test_unavailable_isa(sT):
    S, T = sT
    unavailable = [i for i in ttd.ISAS if i != "auto" and not ttd.isa_available(i)]
    if not unavailable:
        pytest.skip("every instruction set runs here")
    isa = unavailable[0]
    with pytest.raises(ttd.IsaUnavailableError, match=f"isa='{isa}' is not available here.*available: 'scalar'"):
        ttd.distance(S, T, isa=isa)
    with pytest.raises(ttd.IsaUnavailableError):
        ttd.isa_selected(isa)
    assert issubclass(ttd.IsaUnavailableError, RuntimeError)


def test_ttd_isa_environment_variable(sT, monkeypatch):
    S, T = sT
    monkeypatch.setenv("TTD_ISA", "scalar")
    assert ttd.isa_selected() == "scalar"
    np.testing.assert_array_equal(ttd.distance(S, T), ttd.distance(S, T, isa="scalar"))
    monkeypatch.setenv("TTD_ISA", "SCALAR")  # any letter case
    assert ttd.isa_selected() == "scalar"
    # a name that is unknown (or cannot run here) is ignored by the library: the best is used
    monkeypatch.delenv("TTD_ISA")
    best = ttd.isa_selected()
    monkeypatch.setenv("TTD_ISA", "bogus")
    assert ttd.isa_selected() == best
    np.testing.assert_array_equal(ttd.distance(S, T), ttd.distance(S, T, isa=best))
    assert ttd.isa_lanes() == ttd.isa_lanes(best)
    ttd.distance(S, T, isa="scalar")  # a forced isa ignores the variable


# ---- documentation ------------------------------------------------------------------------

def test_everything_public_is_documented():
    for name in ttd.__all__:
        obj = getattr(ttd, name)
        if callable(obj) or isinstance(obj, type):
            assert obj.__doc__ and len(obj.__doc__) > 40, name
    import inspect
    sig = inspect.signature(ttd.distance)
    assert list(sig.parameters)[:3] == ["S", "T", "method"]
    assert sig.parameters["method"].kind is inspect.Parameter.KEYWORD_ONLY
