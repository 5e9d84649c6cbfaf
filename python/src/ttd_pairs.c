/* SPDX-License-Identifier: MIT */
/* ttd.distance: the pair API over ttd_batch_d / ttd_batch_f, and ttd.PairResult. Inputs are
 * used in place when they are C-contiguous in the computed dtype (copied otherwise); the
 * interpreter lock is released around the library call. With points=True the library writes
 * its result structs into one numpy record array laid out as ttd_result_d / ttd_result_f
 * (offsets taken with offsetof), and PairResult's fields are views of it: nothing is copied. */
#include "ttd_py.h"

#include <stddef.h>
#include <string.h>

static PyTypeObject *ttd_py_PairResult;
static PyArray_Descr *ttd_py_record_d, *ttd_py_record_f;

/* PairResult's fields, in the order of the C structs' members. */
enum { TTD_PY_NFIELDS = 9 };
static PyObject *ttd_py_field_names[TTD_PY_NFIELDS];

static PyStructSequence_Field ttd_py_pair_result_fields[TTD_PY_NFIELDS + 1] = {
    {"distance", "|p - q| per pair, shape (...); NaN for pairs with NaN or inf coordinates"},
    {"p", "closest point on the first triangle (S), shape (..., 3)"},
    {"q", "closest point on the second triangle (T), shape (..., 3); equals p up to rounding when they intersect"},
    {"bary_p", "weights of S's vertices A, B, C that give p (non-negative, sum 1), shape (..., 3)"},
    {"bary_q", "weights of T's vertices D, E, F that give q, shape (..., 3)"},
    {"flags", "uint32: ttd.Flag bits (NONFINITE, DEGENERATE_S, DEGENERATE_T, INTERSECTING, NOT_CONVERGED, FALLBACK)"},
    {"feature_p", "uint8: bit i set when vertex i of S has a non-zero weight in p (1 bit: a vertex, 2: an edge, 3: the face)"},
    {"feature_q", "uint8: the same for q on T"},
    {"iterations", "uint16: Newton iterations used (0 for the exact method)"},
    {NULL, NULL},
};

static PyStructSequence_Desc ttd_py_pair_result_desc = {
    "ttd.PairResult",
    "Everything ttd knows about each pair, from ttd.distance(..., points=True).\n\n"
    "A named tuple of numpy arrays (numpy scalars for a single pair): distance, p, q, bary_p,\n"
    "bary_q, flags, feature_p, feature_q, iterations (the C struct's order). The arrays are views of one block laid\n"
    "out as the C library's result struct (strided, not contiguous); numpy.ascontiguousarray\n"
    "copies one out where contiguous memory is needed.",
    ttd_py_pair_result_fields,
    TTD_PY_NFIELDS,
};

/* A numpy record dtype with the C struct's field offsets and size; real is "f8" or "f4". */
static PyArray_Descr *ttd_py_record_descr_of(const char *real, const size_t offsets[TTD_PY_NFIELDS], size_t size)
{
    char vec[16];
    PyOS_snprintf(vec, sizeof vec, "(3,)%s", real);
    const char *formats[TTD_PY_NFIELDS] = {real, vec, vec, vec, vec, "u4", "u1", "u1", "u2"};
    return ttd_py_record_descr(TTD_PY_NFIELDS, ttd_py_field_names, formats, offsets, size);
}

#define TTD_PY_OFFSETS(T)                                                                        \
    {offsetof(T, distance), offsetof(T, p),         offsetof(T, q),                                \
     offsetof(T, bary_p),   offsetof(T, bary_q),    offsetof(T, flags),                            \
     offsetof(T, feature_p), offsetof(T, feature_q), offsetof(T, iterations)}

int ttd_py_pairs_init(PyObject *module)
{
    if ((ttd_py_PairResult = ttd_py_named_tuple(module, &ttd_py_pair_result_desc, ttd_py_field_names)) == NULL)
        return -1;
    static const size_t off_d[TTD_PY_NFIELDS] = TTD_PY_OFFSETS(ttd_result_d);
    static const size_t off_f[TTD_PY_NFIELDS] = TTD_PY_OFFSETS(ttd_result_f);
    ttd_py_record_d = ttd_py_record_descr_of("f8", off_d, sizeof(ttd_result_d));
    ttd_py_record_f = ttd_py_record_descr_of("f4", off_f, sizeof(ttd_result_f));
    if (!ttd_py_record_d || !ttd_py_record_f)
        return -1;
    /* The record dtypes, for tests and for users who want the raw structs. */
    Py_INCREF(ttd_py_record_d);
    if (PyModule_AddObject(module, "RESULT_DTYPE_FLOAT64", (PyObject *)ttd_py_record_d) < 0) {
        Py_DECREF(ttd_py_record_d);
        return -1;
    }
    Py_INCREF(ttd_py_record_f);
    if (PyModule_AddObject(module, "RESULT_DTYPE_FLOAT32", (PyObject *)ttd_py_record_f) < 0) {
        Py_DECREF(ttd_py_record_f);
        return -1;
    }
    return 0;
}

typedef struct pair_piece {
    const ttd_options *opt;
    int type;
    const void *s, *t;
    void *distance, *results;
} pair_piece;

static ttd_status pair_piece_run(void *ctx, size_t b, size_t e)
{
    const pair_piece *c = ctx;
    if (c->type == NPY_DOUBLE)
        return ttd_batch_d(c->opt, e - b, (const double *)c->s + 9 * b, (const double *)c->t + 9 * b,
                           c->distance ? (double *)c->distance + b : NULL,
                           c->results ? (ttd_result_d *)c->results + b : NULL);
    return ttd_batch_f(c->opt, e - b, (const float *)c->s + 9 * b, (const float *)c->t + 9 * b,
                       c->distance ? (float *)c->distance + b : NULL, c->results ? (ttd_result_f *)c->results + b : NULL);
}

/* The library call with the interpreter lock released; n == 0 gets the checks of a one-pair
 * call instead (options and instruction set), so that errors do not depend on n. */
static ttd_status ttd_py_batch(const ttd_options *opt, int type, npy_intp n, const void *s, const void *t,
                               void *distance, void *results)
{
    if (n == 0)
        return ttd_py_check_options(opt);
    /* in pieces, Ctrl-C checked between them (ttd_py_run_pieces); results do not depend on them */
    pair_piece c = {opt, type, s, t, distance, results};
    ttd_status st;
    return ttd_py_run_pieces((size_t)n, (size_t)1 << 20, pair_piece_run, &c, &st) < 0 ? TTD_PY_INTERRUPTED : st;
}

/* The warnings of the non-fatal statuses; -1 when one was turned into an error. */
static int ttd_py_pair_warnings(ttd_status st, const ttd_options *opt, npy_intp n, npy_intp nonfinite,
                                npy_intp not_converged)
{
    if (st == TTD_ERR_NONFINITE_INPUT) {
        PyObject *msg = PyUnicode_FromFormat(
            "%zd of %zd pairs had NaN or infinite coordinates: their outputs are NaN (flag "
            "ttd.Flag.NONFINITE); the other pairs were computed",
            nonfinite, n);
        if (msg == NULL)
            return -1;
        int r = PyErr_WarnEx(ttd_py_NonFiniteInputWarning, PyUnicode_AsUTF8(msg), 1);
        Py_DECREF(msg);
        if (r < 0)
            return -1;
    }
    /* The library reports non-finite input in preference to non-convergence; the flags (when
     * there are results) tell both. */
    if (st == TTD_WARN_NOT_CONVERGED || not_converged > 0) {
        PyObject *msg = not_converged > 0
            ? PyUnicode_FromFormat("the %s method hit max_iterations=%d on %zd of %zd pairs (flag "
                                   "ttd.Flag.NOT_CONVERGED): their points lie on the triangles but "
                                   "may not be the closest",
                                   ttd_method_name(opt->method), opt->max_iterations, not_converged, n)
            : PyUnicode_FromFormat("the %s method hit max_iterations=%d on some of %zd pairs: their "
                                   "distances may be above the minimum (points=True flags them with "
                                   "ttd.Flag.NOT_CONVERGED)",
                                   ttd_method_name(opt->method), opt->max_iterations, n);
        if (msg == NULL)
            return -1;
        int r = PyErr_WarnEx(ttd_py_NotConvergedWarning, PyUnicode_AsUTF8(msg), 1);
        Py_DECREF(msg);
        if (r < 0)
            return -1;
    }
    return 0;
}

/* Distances only: one contiguous array of the pair shape (a numpy scalar for one pair), or
 * the caller's array out (checked by ttd_py_check_out), returned as it is. */
static PyObject *ttd_py_distances(const ttd_options *opt, int type, int lead, PyArrayObject *s, PyArrayObject *t,
                                  npy_intp n, PyArrayObject *out)
{
    PyArrayObject *d = out;
    if (d != NULL)
        Py_INCREF(d);
    else if ((d = (PyArrayObject *)PyArray_SimpleNew(lead, PyArray_DIMS(s), type)) == NULL)
        return NULL;
    ttd_status st = ttd_py_batch(opt, type, n, PyArray_DATA(s), PyArray_DATA(t), PyArray_DATA(d), NULL);
    if (ttd_py_raise_fatal(st, opt) < 0) {
        Py_DECREF(d);
        return NULL;
    }
    npy_intp nonfinite = 0;
    if (st == TTD_ERR_NONFINITE_INPUT) {
        for (npy_intp i = 0; i < n; ++i) {
            if (type == NPY_DOUBLE ? ((const double *)PyArray_DATA(d))[i] != ((const double *)PyArray_DATA(d))[i]
                                   : ((const float *)PyArray_DATA(d))[i] != ((const float *)PyArray_DATA(d))[i])
                ++nonfinite;
        }
    }
    if (st != TTD_OK && ttd_py_pair_warnings(st, opt, n, nonfinite, 0) < 0) {
        Py_DECREF(d);
        return NULL;
    }
    return out != NULL ? (PyObject *)d : PyArray_Return(d);
}

/* Everything: the record array the library fills (new, or the caller's out), and PairResult's
 * views of it. */
static PyObject *ttd_py_full(const ttd_options *opt, int type, int lead, PyArrayObject *s, PyArrayObject *t,
                             npy_intp n, PyArrayObject *out)
{
    PyArray_Descr *descr = type == NPY_DOUBLE ? ttd_py_record_d : ttd_py_record_f;
    PyArrayObject *rec = out;
    if (rec != NULL) {
        Py_INCREF(rec);
    } else {
        Py_INCREF(descr);
        rec = (PyArrayObject *)PyArray_NewFromDescr(&PyArray_Type, descr, lead, PyArray_DIMS(s), NULL, NULL, 0, NULL);
        if (rec == NULL)
            return NULL;
    }
    PyObject *result = NULL;
    ttd_status st = ttd_py_batch(opt, type, n, PyArray_DATA(s), PyArray_DATA(t), NULL, PyArray_DATA(rec));
    if (ttd_py_raise_fatal(st, opt) < 0)
        goto done;
    npy_intp nonfinite = 0, not_converged = 0;
    if (st != TTD_OK) {
        const char *base = PyArray_DATA(rec);
        const size_t size = type == NPY_DOUBLE ? sizeof(ttd_result_d) : sizeof(ttd_result_f);
        const size_t off = type == NPY_DOUBLE ? offsetof(ttd_result_d, flags) : offsetof(ttd_result_f, flags);
        for (npy_intp i = 0; i < n; ++i) {
            uint32_t f;
            memcpy(&f, base + (size_t)i * size + off, sizeof f);
            nonfinite += (f & TTD_PAIR_NONFINITE) != 0;
            not_converged += (f & TTD_PAIR_NOT_CONVERGED) != 0;
        }
    }
    if (st != TTD_OK && ttd_py_pair_warnings(st, opt, n, nonfinite, not_converged) < 0)
        goto done;
    result = ttd_py_named_new(ttd_py_PairResult, TTD_PY_NFIELDS);
    if (result != NULL && ttd_py_set_views(result, 0, rec, ttd_py_field_names, TTD_PY_NFIELDS) < 0)
        Py_CLEAR(result);
done:
    Py_DECREF(rec);
    return result;
}

/* Non-zero when the bytes of two arrays (contiguous, so one range each) overlap. */
static int ttd_py_overlap(PyArrayObject *a, PyArrayObject *b)
{
    const char *pa = PyArray_DATA(a), *pb = PyArray_DATA(b);
    return PyArray_NBYTES(a) > 0 && PyArray_NBYTES(b) > 0 && pa < pb + PyArray_NBYTES(b) &&
           pb < pa + PyArray_NBYTES(a);
}

/* out= must be what the call writes: an ndarray of the pair shape (s's first lead dims) and
 * dtype want, C-contiguous, writeable, sharing no memory with the inputs that the library
 * reads while it writes. -1 with an exception naming the problem otherwise. */
static int ttd_py_check_out(PyObject *obj, PyArray_Descr *want, const char *want_name, int lead, PyArrayObject *s,
                            PyArrayObject *t)
{
    if (!PyArray_Check(obj)) {
        PyErr_Format(PyExc_TypeError, "out must be a numpy array, not %.100s", Py_TYPE(obj)->tp_name);
        return -1;
    }
    PyArrayObject *out = (PyArrayObject *)obj;
    if (!PyArray_EquivTypes(PyArray_DESCR(out), want)) {
        PyErr_Format(PyExc_TypeError, "out has dtype %S: this call writes %s", (PyObject *)PyArray_DESCR(out),
                     want_name);
        return -1;
    }
    if (PyArray_NDIM(out) != lead || !PyArray_CompareLists(PyArray_DIMS(out), PyArray_DIMS(s), lead)) {
        PyObject *shape = PyTuple_New(lead);
        for (int i = 0; shape != NULL && i < lead; ++i)
            PyTuple_SET_ITEM(shape, i, PyLong_FromSsize_t(PyArray_DIM(s, i)));
        if (shape != NULL)
            PyErr_Format(PyExc_ValueError, "out has %d dimension(s) where the pairs have shape %R", PyArray_NDIM(out),
                         shape);
        Py_XDECREF(shape);
        return -1;
    }
    if (!PyArray_IS_C_CONTIGUOUS(out) || !PyArray_ISWRITEABLE(out) || !PyArray_ISALIGNED(out)) {
        PyErr_SetString(PyExc_ValueError, "out must be C-contiguous, aligned and writeable");
        return -1;
    }
    if (ttd_py_overlap(out, s) || ttd_py_overlap(out, t)) {
        PyErr_SetString(PyExc_ValueError, "out shares memory with S or T, which are read while it is written");
        return -1;
    }
    return 0;
}

PyDoc_STRVAR(ttd_py_distance_doc,
"distance(S, T, *, method='exact', precision=None, points=False, isa='auto', threads=0, rho=None, tol=None, max_iterations=None, out=None)\n"
"--\n\n"
"Minimum distance between the triangles of S and T, pair by pair.\n\n"
"S, T : array_like, shape (..., 3, 3) or (..., 9)\n"
"    Triangles: three vertices (rows) of x, y, z, or the same 9 numbers flat. S[i] is paired\n"
"    with T[i]; the pair dimensions (before the triangle's) must be equal, e.g. (n,) for n\n"
"    pairs or () for one pair. The two may differ in layout ((n, 3, 3) with (n, 9)).\n"
"    float32 input is computed in float32 and float64 input in float64; integer and bool\n"
"    input counts as float64. S and T of different precisions raise TypeError unless\n"
"    precision says which to use. Arrays that are not C-contiguous, aligned and in native\n"
"    byte order are copied; others are read in place.\n"
"method : str\n"
"    One of ttd.METHODS (or a ttd.Method): 'exact' (default; exact to rounding), 'penalty'\n"
"    (the paper's quasi-Newton penalty method), 'penalty-ref' (the paper's ttd1 step for\n"
"    step), 'barrier' (log-barrier Newton), 'certified' (penalty, checked, exact fallback).\n"
"precision : None, 'float32' or 'float64'\n"
"    None (default): from the arrays, as above. 'float32' ('single', numpy.float32) or\n"
"    'float64' ('double', numpy.float64) converts both arrays to it.\n"
"points : bool\n"
"    False (default): return the distances only. True: return a ttd.PairResult with the\n"
"    distances, closest points p and q, their barycentric weights, features, flags and\n"
"    iteration counts.\n"
"isa : str\n"
"    Instruction set, one of ttd.ISAS (or a ttd.Isa): 'auto' (default) picks the best one\n"
"    the CPU supports, unless the environment variable TTD_ISA names one.\n"
"threads : int\n"
"    Worker threads for the batch, >= 0; 0 (default) uses every online core. Results do\n"
"    not depend on it.\n"
"rho, tol, max_iterations : iterative methods only; None keeps the library's default\n"
"    rho in (0, 1e150] (penalty weight, default 1e6), tol in [0, 1] (step length at which\n"
"    Newton stops, on the pair scaled to unit size; default 1e-12), max_iterations in\n"
"    1..65535 (default 99).\n"
"out : numpy.ndarray, optional\n"
"    Where to write, instead of a new array (a reused buffer saves allocating and\n"
"    zeroing fresh memory on every call): C-contiguous, writeable, of the pair shape, and\n"
"    of the computed dtype (points=False) or ttd.RESULT_DTYPE_FLOAT64 / FLOAT32\n"
"    (points=True); it may not share memory with S or T.\n\n"
"Returns\n"
"    points=False: a numpy array of the pair shape and the computed dtype, or a numpy\n"
"    scalar (numpy.float64 or numpy.float32) for a single pair; out itself when given.\n"
"    points=True: a ttd.PairResult of such arrays (p, q, bary_p, bary_q with a trailing 3),\n"
"    views of one record array (out when given).\n\n"
"Pairs with NaN or infinite coordinates get NaN outputs and the flag ttd.Flag.NONFINITE;\n"
"the other pairs are computed, and a ttd.NonFiniteInputWarning says how many there were\n"
"(warnings.simplefilter('error', ttd.NonFiniteInputWarning) makes it an exception). An\n"
"iterative method that hits max_iterations gives ttd.NotConvergedWarning. Empty input\n"
"(no pairs) returns empty arrays after the same checks of the options.\n\n"
"Raises TypeError (dtypes, argument types), ValueError (shapes, names, ranges),\n"
"ttd.IsaUnavailableError (an instruction set that cannot run here), MemoryError.\n"
"The interpreter lock is released while the library computes, so Python threads that\n"
"call ttd run in parallel.");

static PyObject *ttd_py_distance(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *kwlist[] = {"S", "T", "method", "precision", "points", "isa", "threads", "rho", "tol",
                             "max_iterations", "out", NULL};
    PyObject *s_obj, *t_obj, *method = NULL, *precision = NULL, *isa = NULL, *threads = NULL, *rho = NULL,
             *tol = NULL, *max_iterations = NULL, *out_obj = NULL;
    int points = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OO|$OOpOOOOOO:distance", kwlist, &s_obj, &t_obj, &method,
                                     &precision, &points, &isa, &threads, &rho, &tol, &max_iterations, &out_obj))
        return NULL;
    if (out_obj == Py_None)
        out_obj = NULL;
    ttd_options opt;
    int type;
    if (ttd_py_options(method, isa, threads, rho, tol, max_iterations, &opt) < 0 ||
        ttd_py_precision(precision, &type) < 0)
        return NULL;

    PyObject *out = NULL;
    PyArrayObject *s0 = NULL, *t0 = NULL, *s = NULL, *t = NULL;
    int lead_s, lead_t;
    if ((s0 = ttd_py_as_array(s_obj, "S")) == NULL || (t0 = ttd_py_as_array(t_obj, "T")) == NULL)
        goto done;
    if (ttd_py_triangle_lead(s0, "S", &lead_s) < 0 || ttd_py_triangle_lead(t0, "T", &lead_t) < 0 ||
        ttd_py_same_lead(s0, lead_s, t0, lead_t, "S and T") < 0)
        goto done;
    if (type == NPY_NOTYPE) {
        int ts = ttd_py_natural_type(s0, "S"), tt = ts < 0 ? -1 : ttd_py_natural_type(t0, "T");
        if (ts < 0 || tt < 0)
            goto done;
        if (ts != tt) {
            PyErr_Format(PyExc_TypeError,
                         "S has dtype %S and T has dtype %S, which ttd computes in %s and %s: a call "
                         "computes in one precision and never widens float32 silently; pass "
                         "precision='float32' or precision='float64', or convert one with .astype()",
                         (PyObject *)PyArray_DESCR(s0), (PyObject *)PyArray_DESCR(t0),
                         ts == NPY_DOUBLE ? "float64" : "float32", tt == NPY_DOUBLE ? "float64" : "float32");
            goto done;
        }
        type = ts;
    }
    if ((s = ttd_py_as_real(s0, "S", type)) == NULL || (t = ttd_py_as_real(t0, "T", type)) == NULL)
        goto done;
    if (out_obj != NULL) {
        PyArray_Descr *want = points ? (type == NPY_DOUBLE ? ttd_py_record_d : ttd_py_record_f)
                                     : PyArray_DescrFromType(type);
        const char *want_name = points ? (type == NPY_DOUBLE ? "ttd.RESULT_DTYPE_FLOAT64" : "ttd.RESULT_DTYPE_FLOAT32")
                                       : (type == NPY_DOUBLE ? "float64" : "float32");
        int bad = ttd_py_check_out(out_obj, want, want_name, lead_s, s, t);
        if (!points)
            Py_DECREF(want);
        if (bad < 0)
            goto done;
    }
    npy_intp n = PyArray_MultiplyList(PyArray_DIMS(s), lead_s);
    out = points ? ttd_py_full(&opt, type, lead_s, s, t, n, (PyArrayObject *)out_obj)
                 : ttd_py_distances(&opt, type, lead_s, s, t, n, (PyArrayObject *)out_obj);
done:
    Py_XDECREF(s0);
    Py_XDECREF(t0);
    Py_XDECREF(s);
    Py_XDECREF(t);
    return out;
}

PyMethodDef ttd_py_pairs_methods[] = {
    {"distance", (PyCFunction)(void (*)(void))ttd_py_distance, METH_VARARGS | METH_KEYWORDS, ttd_py_distance_doc},
    {NULL, NULL, 0, NULL},
};
