/* SPDX-License-Identifier: MIT */
/* The helpers of ttd_py.h: keyword arguments to ttd_options, names to enums, the precision
 * rules (float32 stays float32, integers become float64, mixed floats are an error), array
 * conversion (copies only when the layout or dtype requires it) and a C status to the Python
 * exception that names the problem. The C library checks the option ranges; when it rejects
 * options, one-field probes find which field it was, so the ranges live in one place. */
#include "ttd_py.h"

#include <limits.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* "'exact', 'penalty', ..." for messages; NULL with an exception set on failure. */
static PyObject *ttd_py_name_list(const char *(*name_of)(int), int count)
{
    PyObject *parts = PyList_New(0);
    if (parts == NULL)
        return NULL;
    for (int i = 0; i < count; ++i) {
        const char *n = name_of(i);
        PyObject *q = n ? PyUnicode_FromFormat("'%s'", n) : NULL;
        if (n && (q == NULL || PyList_Append(parts, q) < 0)) {
            Py_XDECREF(q);
            Py_DECREF(parts);
            return NULL;
        }
        Py_XDECREF(q);
    }
    PyObject *sep = PyUnicode_FromString(", ");
    PyObject *joined = sep ? PyUnicode_Join(sep, parts) : NULL;
    Py_XDECREF(sep);
    Py_DECREF(parts);
    return joined;
}

static const char *ttd_py_method_name_i(int i) { return ttd_method_name((ttd_method)i); }
static const char *ttd_py_isa_name_i(int i) { return ttd_isa_name((ttd_isa)i); }
static const char *ttd_py_available_isa_name_i(int i)
{
    return i != TTD_ISA_AUTO && ttd_isa_available((ttd_isa)i) ? ttd_isa_name((ttd_isa)i) : NULL;
}

/* The index of name among name_of(0..count-1), or -1 with an exception naming what. */
static int ttd_py_lookup(PyObject *name, const char *what, const char *(*name_of)(int), int count)
{
    if (!PyUnicode_Check(name)) {
        PyErr_Format(PyExc_TypeError, "%s must be a str, not %.100s", what, Py_TYPE(name)->tp_name);
        return -1;
    }
    for (int i = 0; i < count; ++i) {
        const char *n = name_of(i);
        if (n && PyUnicode_CompareWithASCIIString(name, n) == 0)
            return i;
    }
    PyObject *names = ttd_py_name_list(name_of, count);
    if (names) {
        PyErr_Format(PyExc_ValueError, "%s=%R is not one of %U", what, name, names);
        Py_DECREF(names);
    }
    return -1;
}

int ttd_py_isa_from_name(PyObject *name, ttd_isa *out)
{
    int i = ttd_py_lookup(name, "isa", ttd_py_isa_name_i, TTD_ISA_COUNT);
    if (i < 0)
        return -1;
    *out = (ttd_isa)i;
    return 0;
}

/* An integer argument that must fit a C int (the library checks its range). */
static int ttd_py_int_arg(PyObject *obj, const char *what, int *out)
{
    if (obj == NULL || obj == Py_None)
        return 0;
    if (!PyIndex_Check(obj) || PyBool_Check(obj)) {
        PyErr_Format(PyExc_TypeError, "%s must be an int, not %.100s", what, Py_TYPE(obj)->tp_name);
        return -1;
    }
    PyObject *v = PyNumber_Index(obj);
    if (v == NULL)
        return -1;
    int overflow = 0;
    long x = PyLong_AsLongAndOverflow(v, &overflow);
    Py_DECREF(v);
    if (x == -1 && PyErr_Occurred())
        return -1;
    if (overflow || x < INT_MIN || x > INT_MAX) {
        PyErr_Format(PyExc_ValueError, "%s=%R is out of range", what, obj);
        return -1;
    }
    *out = (int)x;
    return 0;
}

int ttd_py_real_arg(PyObject *obj, const char *what, double *out)
{
    if (obj == NULL || obj == Py_None)
        return 0;
    if (PyUnicode_Check(obj) || PyBytes_Check(obj) || PyBool_Check(obj) ||
        !(PyFloat_Check(obj) || PyIndex_Check(obj) || PyNumber_Check(obj))) {
        PyErr_Format(PyExc_TypeError, "%s must be a real number, not %.100s", what, Py_TYPE(obj)->tp_name);
        return -1;
    }
    double x = PyFloat_AsDouble(obj);
    if (x == -1.0 && PyErr_Occurred()) {
        PyErr_Clear();
        PyErr_Format(PyExc_TypeError, "%s must be a real number, not %.100s", what, Py_TYPE(obj)->tp_name);
        return -1;
    }
    *out = x;
    return 0;
}

int ttd_py_options(PyObject *method, PyObject *isa, PyObject *threads, PyObject *rho, PyObject *tol,
                   PyObject *max_iterations, ttd_options *out)
{
    ttd_options o = ttd_default_options();
    if (method != NULL && method != Py_None) {
        int m = ttd_py_lookup(method, "method", ttd_py_method_name_i, TTD_METHOD_COUNT);
        if (m < 0)
            return -1;
        o.method = (ttd_method)m;
    }
    if (isa != NULL && isa != Py_None && ttd_py_isa_from_name(isa, &o.isa) < 0)
        return -1;
    if (ttd_py_int_arg(threads, "threads", &o.threads) < 0 || ttd_py_real_arg(rho, "rho", &o.rho) < 0 ||
        ttd_py_real_arg(tol, "tol", &o.tol) < 0 ||
        ttd_py_int_arg(max_iterations, "max_iterations", &o.max_iterations) < 0)
        return -1;
    *out = o;
    return 0;
}

int ttd_py_precision(PyObject *precision, int *type_num)
{
    if (precision == NULL || precision == Py_None) {
        *type_num = NPY_NOTYPE;
        return 0;
    }
    /* "float" alone is refused: numpy reads it as float64, the ttd program as float32. */
    if (PyUnicode_Check(precision) && PyUnicode_CompareWithASCIIString(precision, "float") == 0) {
        PyErr_SetString(PyExc_ValueError,
                        "precision='float' is ambiguous (numpy's float is float64, the ttd program's "
                        "is float32): say 'float32' or 'float64'");
        return -1;
    }
    if (PyUnicode_Check(precision) && PyUnicode_CompareWithASCIIString(precision, "single") == 0) {
        *type_num = NPY_FLOAT;
        return 0;
    }
    if (PyUnicode_Check(precision) && PyUnicode_CompareWithASCIIString(precision, "double") == 0) {
        *type_num = NPY_DOUBLE;
        return 0;
    }
    PyArray_Descr *d = NULL;
    if (PyArray_DescrConverter2(precision, &d) && d != NULL) {
        int t = d->type_num;
        Py_DECREF(d);
        if (t == NPY_FLOAT || t == NPY_DOUBLE) {
            *type_num = t;
            return 0;
        }
    }
    PyErr_Clear();
    PyErr_Format(PyExc_ValueError,
                 "precision=%R is not one of None (from the arrays), 'float32' ('single', "
                 "numpy.float32), 'float64' ('double', numpy.float64)",
                 precision);
    return -1;
}

/* Kinds numpy converts to float without inventing values: bool, signed, unsigned, float. */
static int ttd_py_real_kind(char kind)
{
    return kind == 'b' || kind == 'i' || kind == 'u' || kind == 'f';
}

int ttd_py_natural_type(PyArrayObject *a, const char *name)
{
    PyArray_Descr *d = PyArray_DESCR(a);
    if (d->type_num == NPY_FLOAT || d->type_num == NPY_DOUBLE)
        return d->type_num;
    if (d->kind == 'b' || d->kind == 'i' || d->kind == 'u')
        return NPY_DOUBLE;
    if (d->kind == 'f')
        PyErr_Format(PyExc_TypeError,
                     "%s has dtype %S: ttd computes in float32 or float64; pass precision='float32' "
                     "or precision='float64' to convert it",
                     name, (PyObject *)d);
    else
        PyErr_Format(PyExc_TypeError,
                     "%s has dtype %S: ttd takes real coordinates (float32, float64, or integers, "
                     "which are computed in float64)",
                     name, (PyObject *)d);
    return -1;
}

PyArrayObject *ttd_py_as_array(PyObject *obj, const char *name)
{
    if (PyArray_Check(obj)) {
        Py_INCREF(obj);
        return (PyArrayObject *)obj;
    }
    if (obj == Py_None) { /* numpy would make a 0-d object array of it, refused for its shape */
        PyErr_Format(PyExc_TypeError, "%s must be an array of coordinates, not None", name);
        return NULL;
    }
    PyObject *a = PyArray_FromAny(obj, NULL, 0, 0, 0, NULL);
    if (a == NULL) {
        /* numpy's own message says what was wrong with the object; add which argument. */
        PyObject *type, *value, *tb;
        PyErr_Fetch(&type, &value, &tb);
        PyErr_NormalizeException(&type, &value, &tb);
        PyErr_Format(type ? type : PyExc_ValueError, "%s is not an array of coordinates: %S", name,
                     value ? value : Py_None);
        Py_XDECREF(type);
        Py_XDECREF(value);
        Py_XDECREF(tb);
    }
    return (PyArrayObject *)a;
}

PyArrayObject *ttd_py_as_real(PyArrayObject *a, const char *name, int type_num)
{
    if (PyArray_TYPE(a) == type_num && PyArray_ISCARRAY_RO(a) && PyArray_ISNOTSWAPPED(a)) {
        Py_INCREF(a);
        return a;
    }
    if (!ttd_py_real_kind(PyArray_DESCR(a)->kind)) {
        PyErr_Format(PyExc_TypeError, "%s has dtype %S: ttd takes real coordinates (bool, integer or float)",
                     name, (PyObject *)PyArray_DESCR(a));
        return NULL;
    }
    return (PyArrayObject *)PyArray_FromArray(a, PyArray_DescrFromType(type_num),
                                              NPY_ARRAY_C_CONTIGUOUS | NPY_ARRAY_ALIGNED | NPY_ARRAY_FORCECAST);
}

PyObject *ttd_py_shape(PyArrayObject *a)
{
    int nd = PyArray_NDIM(a);
    PyObject *t = PyTuple_New(nd);
    for (int i = 0; t != NULL && i < nd; ++i) {
        PyObject *v = PyLong_FromSsize_t(PyArray_DIM(a, i));
        if (v == NULL) {
            Py_CLEAR(t);
            break;
        }
        PyTuple_SET_ITEM(t, i, v);
    }
    return t;
}

PyArray_Descr *ttd_py_record_descr(int n, PyObject *const names[], const char *const formats[],
                                   const size_t offsets[], size_t itemsize)
{
    PyObject *nl = PyList_New(n), *fl = PyList_New(n), *ol = PyList_New(n), *spec = NULL;
    PyArray_Descr *descr = NULL;
    if (!nl || !fl || !ol)
        goto done;
    for (int i = 0; i < n; ++i) {
        PyObject *f = PyUnicode_FromString(formats[i]), *o = PyLong_FromSize_t(offsets[i]);
        if (!f || !o) {
            Py_XDECREF(f);
            Py_XDECREF(o);
            goto done;
        }
        Py_INCREF(names[i]);
        PyList_SET_ITEM(nl, i, names[i]);
        PyList_SET_ITEM(fl, i, f);
        PyList_SET_ITEM(ol, i, o);
    }
    spec = Py_BuildValue("{sOsOsOsn}", "names", nl, "formats", fl, "offsets", ol, "itemsize", (Py_ssize_t)itemsize);
    if (spec && !PyArray_DescrConverter(spec, &descr))
        descr = NULL;
done:
    Py_XDECREF(nl);
    Py_XDECREF(fl);
    Py_XDECREF(ol);
    Py_XDECREF(spec);
    return descr;
}

static int ttd_py_intern_fields(const PyStructSequence_Field *fields, int n, PyObject *names[])
{
    for (int i = 0; i < n; ++i)
        if ((names[i] = PyUnicode_InternFromString(fields[i].name)) == NULL)
            return -1;
    return 0;
}

PyTypeObject *ttd_py_named_tuple(PyObject *module, const PyStructSequence_Desc *desc, PyObject *names[])
{
    const int n = desc->n_in_sequence;
    if (ttd_py_intern_fields(desc->fields, n, names) < 0)
        return NULL;
    const char *dot = strrchr(desc->name, '.');
    const char *name = dot ? dot + 1 : desc->name;
    PyObject *collections = NULL, *factory = NULL, *fields = NULL, *args = NULL, *kwargs = NULL, *type = NULL;
    if ((collections = PyImport_ImportModule("collections")) == NULL ||
        (factory = PyObject_GetAttrString(collections, "namedtuple")) == NULL || (fields = PyTuple_New(n)) == NULL)
        goto fail;
    for (int i = 0; i < n; ++i) {
        Py_INCREF(names[i]);
        PyTuple_SET_ITEM(fields, i, names[i]);
    }
    if ((args = Py_BuildValue("(sO)", name, fields)) == NULL || (kwargs = Py_BuildValue("{ss}", "module", "ttd")) == NULL ||
        (type = PyObject_Call(factory, args, kwargs)) == NULL)
        goto fail;
    if (!PyType_Check(type) || !PyType_IsSubtype((PyTypeObject *)type, &PyTuple_Type)) {
        PyErr_SetString(PyExc_TypeError, "collections.namedtuple did not return a tuple type");
        goto fail;
    }
    /* The class's and each field's docstring (the field properties' docs are writable). */
    PyObject *doc = PyUnicode_FromString(desc->doc);
    if (doc == NULL || PyObject_SetAttrString(type, "__doc__", doc) < 0) {
        Py_XDECREF(doc);
        goto fail;
    }
    Py_DECREF(doc);
    for (int i = 0; i < n; ++i) {
        PyObject *getter = PyObject_GetAttr(type, names[i]);
        PyObject *fdoc = getter ? PyUnicode_FromString(desc->fields[i].doc) : NULL;
        int bad = fdoc == NULL || PyObject_SetAttrString(getter, "__doc__", fdoc) < 0;
        Py_XDECREF(getter);
        Py_XDECREF(fdoc);
        if (bad)
            goto fail;
    }
    Py_INCREF(type);
    if (PyModule_AddObject(module, name, type) < 0) {
        Py_DECREF(type);
        goto fail;
    }
    Py_DECREF(collections);
    Py_DECREF(factory);
    Py_DECREF(fields);
    Py_DECREF(args);
    Py_DECREF(kwargs);
    return (PyTypeObject *)type; /* the reference kept for the module's lifetime */
fail:
    Py_XDECREF(collections);
    Py_XDECREF(factory);
    Py_XDECREF(fields);
    Py_XDECREF(args);
    Py_XDECREF(kwargs);
    Py_XDECREF(type);
    return NULL;
}

PyObject *ttd_py_named_new(PyTypeObject *type, Py_ssize_t n)
{
    /* What tuple.__new__ does for a subclass: allocate n empty items, which the caller sets
     * with PyTuple_SET_ITEM (an item left NULL is safe to deallocate). */
    return type->tp_alloc(type, n);
}

int ttd_py_set_views(PyObject *tuple, int first, PyArrayObject *rec, PyObject *const names[], int n)
{
    for (int i = 0; i < n; ++i) {
        PyObject *v = PyObject_GetItem((PyObject *)rec, names[i]);
        if (v != NULL && PyArray_Check(v))
            v = PyArray_Return((PyArrayObject *)v);
        if (v == NULL)
            return -1;
        PyTuple_SET_ITEM(tuple, first + i, v);
    }
    return 0;
}

int ttd_py_triangle_lead(PyArrayObject *a, const char *name, int *lead)
{
    int nd = PyArray_NDIM(a);
    if (nd >= 1 && PyArray_DIM(a, nd - 1) == 9) {
        *lead = nd - 1;
        return 0;
    }
    if (nd >= 2 && PyArray_DIM(a, nd - 1) == 3 && PyArray_DIM(a, nd - 2) == 3) {
        *lead = nd - 2;
        return 0;
    }
    PyObject *shape = ttd_py_shape(a);
    if (shape) {
        PyErr_Format(PyExc_ValueError,
                     "%s has shape %R: triangles are given as (..., 3, 3) (vertices x rows of x y z) "
                     "or (..., 9)",
                     name, shape);
        Py_DECREF(shape);
    }
    return -1;
}

int ttd_py_same_lead(PyArrayObject *a, int lead_a, PyArrayObject *b, int lead_b, const char *names)
{
    if (lead_a == lead_b && PyArray_CompareLists(PyArray_DIMS(a), PyArray_DIMS(b), lead_a))
        return 0;
    PyObject *sa = ttd_py_shape(a), *sb = ttd_py_shape(b);
    if (sa && sb)
        PyErr_Format(PyExc_ValueError,
                     "%s have shapes %R and %R: the pair dimensions (before each triangle's (3, 3) "
                     "or (9,)) must be equal (numpy.broadcast_to repeats one triangle)",
                     names, sa, sb);
    Py_XDECREF(sa);
    Py_XDECREF(sb);
    return -1;
}

/* One pair computed with o: the status of the library's checks for these options. */
static ttd_status ttd_py_probe(const ttd_options *o)
{
    static const double s[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    static const double t[9] = {0, 0, 2, 1, 0, 2, 0, 1, 2};
    double d;
    return ttd_batch_d(o, 1, s, t, &d, NULL);
}

ttd_status ttd_py_check_options(const ttd_options *opt)
{
    return ttd_py_probe(opt);
}

/* Names the field of opt that the library refused, with its documented range (ttd.h). */
static void ttd_py_raise_bad_options(const ttd_options *opt)
{
    ttd_options o = ttd_default_options();
    o.isa = TTD_ISA_SCALAR;
    o.method = opt->method;
    ttd_options x = o;
    x.threads = opt->threads;
    if (ttd_py_probe(&x) == TTD_ERR_BAD_OPTIONS) {
        PyErr_Format(PyExc_ValueError, "threads=%d is out of range: threads >= 0 (0 = all cores)", opt->threads);
        return;
    }
    x = o;
    x.rho = opt->rho;
    if (ttd_py_probe(&x) == TTD_ERR_BAD_OPTIONS) {
        PyObject *v = PyFloat_FromDouble(opt->rho);
        PyErr_Format(PyExc_ValueError, "rho=%R is out of range: rho in (0, 1e150]", v);
        Py_XDECREF(v);
        return;
    }
    x = o;
    x.tol = opt->tol;
    if (ttd_py_probe(&x) == TTD_ERR_BAD_OPTIONS) {
        PyObject *v = PyFloat_FromDouble(opt->tol);
        PyErr_Format(PyExc_ValueError, "tol=%R is out of range: tol in [0, 1]", v);
        Py_XDECREF(v);
        return;
    }
    x = o;
    x.max_iterations = opt->max_iterations;
    if (ttd_py_probe(&x) == TTD_ERR_BAD_OPTIONS) {
        PyErr_Format(PyExc_ValueError, "max_iterations=%d is out of range: 1 <= max_iterations <= 65535",
                     opt->max_iterations);
        return;
    }
    PyErr_Format(PyExc_ValueError, "ttd refused the options: %s", ttd_status_string(TTD_ERR_BAD_OPTIONS));
}

static void ttd_py_raise_isa_unavailable(const ttd_options *opt)
{
    PyObject *avail = ttd_py_name_list(ttd_py_available_isa_name_i, TTD_ISA_COUNT);
    if (avail == NULL)
        return;
    const char *env = getenv("TTD_ISA");
    if (opt->isa == TTD_ISA_AUTO)
        PyErr_Format(ttd_py_IsaUnavailableError,
                     "the environment variable TTD_ISA=%s forces an instruction set that is not "
                     "available here or is not a name from ttd.ISAS; available: %U",
                     env ? env : "(unset)", avail);
    else
        PyErr_Format(ttd_py_IsaUnavailableError,
                     "isa='%s' is not available here (not built into this ttd, or not supported by "
                     "this CPU and OS); available: %U",
                     ttd_isa_name(opt->isa), avail);
    Py_DECREF(avail);
}

PyObject *ttd_py_value_error(const char *format, double value)
{
    PyObject *v = PyFloat_FromDouble(value);
    if (v != NULL) {
        PyErr_Format(PyExc_ValueError, format, v);
        Py_DECREF(v);
    }
    return NULL;
}

int ttd_py_raise_fatal(ttd_status st, const ttd_options *opt)
{
    if (st == TTD_PY_INTERRUPTED) /* raised already (ttd_py_run_pieces) */
        return -1;
    if (st < TTD_ERR_FIRST_FATAL)
        return 0;
    switch (st) {
    case TTD_ERR_BAD_OPTIONS: ttd_py_raise_bad_options(opt); break;
    case TTD_ERR_ISA_UNAVAILABLE: ttd_py_raise_isa_unavailable(opt); break;
    case TTD_ERR_OUT_OF_MEMORY:
        PyErr_SetString(PyExc_MemoryError, "ttd: out of memory for a worker thread's scratch block");
        break;
    case TTD_ERR_TOO_LARGE:
        PyErr_SetString(PyExc_MemoryError, "ttd: the batch is too large for its arrays to exist");
        break;
    case TTD_ERR_INDEX_OUT_OF_RANGE:
        PyErr_SetString(PyExc_IndexError, "ttd: a mesh triangle or vertex index is out of range");
        break;
    /* The mesh entries name the culprit before these can arise (ttd_mesh.c); these are the
     * fallbacks, with the library's own sentence. */
    case TTD_ERR_EMPTY:
    case TTD_ERR_NONFINITE_MESH:
    case TTD_ERR_BAD_POSE:
    case TTD_ERR_COORDINATE_RANGE:
        PyErr_Format(PyExc_ValueError, "ttd: %s", ttd_status_string(st));
        break;
    case TTD_ERR_PRECISION_MISMATCH:
        PyErr_Format(PyExc_TypeError, "ttd: %s", ttd_status_string(st));
        break;
    default:
        PyErr_Format(PyExc_SystemError, "ttd: unexpected status %d from the C library: %s", (int)st,
                     ttd_status_string(st));
        break;
    }
    return -1;
}

/* ---- pieces between signal checks (ttd_py.h) ---------------------------------------------- */

static double ttd_py_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int ttd_py_run_pieces(size_t n, size_t first, ttd_py_piece_fn fn, void *ctx, ttd_status *st)
{
    ttd_status worst = TTD_OK;
    size_t begin = 0, piece = first ? first : 1;
    while (begin < n) {
        const size_t end = n - begin > piece ? begin + piece : n;
        ttd_status s;
        double took;
        Py_BEGIN_ALLOW_THREADS
        const double t0 = ttd_py_seconds();
        s = fn(ctx, begin, end);
        took = ttd_py_seconds() - t0;
        Py_END_ALLOW_THREADS
        if (s >= TTD_ERR_FIRST_FATAL) {
            *st = s;
            return 0;
        }
        if (s > worst)
            worst = s;
        begin = end;
        /* the signal check, where a Ctrl-C's KeyboardInterrupt is raised (main thread only) */
        if (begin < n && PyErr_CheckSignals() < 0)
            return -1;
        /* about 0.1 s a piece: a stop within a second, and few enough calls not to cost time */
        if (took < 0.05 && piece <= SIZE_MAX / 2)
            piece *= 2;
        else if (took > 0.2 && piece > 1)
            piece /= 2;
    }
    *st = worst;
    return 0;
}
