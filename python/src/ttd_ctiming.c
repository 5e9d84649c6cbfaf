/* SPDX-License-Identifier: MIT */
/* ttd._ctiming: the C side of bench/python_overhead.py, and nothing else. It times the
 * library calls that ttd.distance and the mesh queries make (ttd_batch_d / ttd_batch_f,
 * ttd_mesh_*_d / _f with the same options), called back to back from C on the same input and
 * output buffers, so that the benchmark can subtract them from the time of the Python calls in
 * the same process: timing the C call through ctypes instead would add ctypes' own per-call
 * cost (about a microsecond) to the side that should have none. The output buffer is the
 * caller's, the one the Python call writes with out=, so that the two sides differ only in the
 * call. The meshes are built here from the arrays the Python meshes were built from (the build
 * is deterministic: the same hierarchy). */
#define _POSIX_C_SOURCE 200809L
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include <math.h>
#include <string.h>
#include <time.h>

#include <ttd/ttd.h>

static double ttd_ct_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

PyDoc_STRVAR(ttd_ct_time_calls_doc,
"time_calls(S, T, out, calls, method='exact', threads=0, points=False)\n--\n\n"
"Seconds taken by `calls` back-to-back ttd_batch_d (float64 buffers) or ttd_batch_f\n"
"(float32) calls on the pairs of S and T (C-contiguous buffers of 9 numbers per triangle),\n"
"with the options ttd.distance builds for the same arguments, writing into out: a writable\n"
"C-contiguous buffer of n distances, or of n result structs with points=True (the buffer\n"
"that ttd.distance(..., out=out) writes, so that both sides store to the same addresses).\n"
"The interpreter lock is released while it runs. Raises RuntimeError on a library error.");

static PyObject *ttd_ct_time_calls(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *kwlist[] = {"S", "T", "out", "calls", "method", "threads", "points", NULL};
    PyObject *s_obj, *t_obj, *out_obj;
    Py_buffer s, t, o;
    Py_ssize_t calls;
    const char *method = "exact";
    int threads = 0, points = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OOOn|sip:time_calls", kwlist, &s_obj, &t_obj, &out_obj, &calls,
                                     &method, &threads, &points))
        return NULL;
    if (PyObject_GetBuffer(s_obj, &s, PyBUF_C_CONTIGUOUS | PyBUF_FORMAT) < 0)
        return NULL;
    if (PyObject_GetBuffer(t_obj, &t, PyBUF_C_CONTIGUOUS | PyBUF_FORMAT) < 0) {
        PyBuffer_Release(&s);
        return NULL;
    }
    if (PyObject_GetBuffer(out_obj, &o, PyBUF_C_CONTIGUOUS | PyBUF_WRITABLE) < 0) {
        PyBuffer_Release(&s);
        PyBuffer_Release(&t);
        return NULL;
    }
    PyObject *ret = NULL;
    void *out = o.buf;
    const char fs = s.format ? s.format[strlen(s.format) - 1] : '?';
    const char ft = t.format ? t.format[strlen(t.format) - 1] : '?';
    const int dbl = fs == 'd';
    if (fs != ft || (fs != 'd' && fs != 'f') || s.len != t.len || s.len % (9 * s.itemsize) != 0 || calls < 1) {
        PyErr_SetString(PyExc_ValueError, "time_calls: S and T must be equal-sized float64 or float32 buffers "
                                          "of 9 numbers per triangle, and calls >= 1");
        goto done;
    }
    ttd_options opt = ttd_default_options();
    int m = 0;
    while (m < TTD_METHOD_COUNT && strcmp(ttd_method_name((ttd_method)m), method) != 0)
        ++m;
    if (m == TTD_METHOD_COUNT) {
        PyErr_Format(PyExc_ValueError, "time_calls: unknown method '%s'", method);
        goto done;
    }
    opt.method = (ttd_method)m;
    opt.threads = threads;
    const size_t n = (size_t)s.len / (size_t)(9 * s.itemsize);
    const size_t per = points ? (dbl ? sizeof(ttd_result_d) : sizeof(ttd_result_f)) : (size_t)s.itemsize;
    if ((size_t)o.len != n * per) {
        PyErr_SetString(PyExc_ValueError, "time_calls: out must hold n distances, or n result structs with points=True");
        goto done;
    }
    ttd_status st = TTD_OK;
    double t0, t1;
    Py_BEGIN_ALLOW_THREADS
    t0 = ttd_ct_now();
    for (Py_ssize_t i = 0; i < calls && st < TTD_ERR_FIRST_FATAL; ++i) {
        if (dbl)
            st = ttd_batch_d(&opt, n, s.buf, t.buf, points ? NULL : out, points ? out : NULL);
        else
            st = ttd_batch_f(&opt, n, s.buf, t.buf, points ? NULL : out, points ? out : NULL);
    }
    t1 = ttd_ct_now();
    Py_END_ALLOW_THREADS
    if (st >= TTD_ERR_FIRST_FATAL)
        PyErr_Format(PyExc_RuntimeError, "time_calls: %s", ttd_status_string(st));
    else
        ret = PyFloat_FromDouble(t1 - t0);
done:
    PyBuffer_Release(&s);
    PyBuffer_Release(&t);
    PyBuffer_Release(&o);
    return ret;
}

PyDoc_STRVAR(ttd_ct_time_mesh_calls_doc,
"time_mesh_calls(va, fa, vb, fb, poses, calls, query='distance', margin=0.0, threads=0, out=None, out2=None, fresh=False)\n--\n\n"
"Seconds taken by `calls` back-to-back ttd_mesh_<query>_d (float64 buffers) or _f (float32)\n"
"calls on meshes a and b built here from va, fa and vb, fb (C-contiguous buffers of 3 reals\n"
"and 3 uint32 indices per row), under the K poses of `poses` (12 reals [R | t] each), with\n"
"the options the Python query builds for threads. query: 'distance' (out: K result structs),\n"
"'collide' (out: K ttd_collision, margin), 'contacts' (margin; one ttd_contacts set reused\n"
"over the calls as a C caller would, or a fresh one per call with fresh=True, as the Python\n"
"call gets), 'closest' (margin; out and out2: the for_a and for_b records). The interpreter\n"
"lock is released while it runs. Raises RuntimeError on a library error.");

/* A C-contiguous buffer of obj whose format ends in one of fmts ("df" or "I"); -1 with
 * ValueError otherwise. */
static int ttd_ct_buffer(PyObject *obj, Py_buffer *b, const char *fmts, int writable, const char *name)
{
    if (PyObject_GetBuffer(obj, b, PyBUF_C_CONTIGUOUS | PyBUF_FORMAT | (writable ? PyBUF_WRITABLE : 0)) < 0)
        return -1;
    const char f = b->format ? b->format[strlen(b->format) - 1] : '?';
    if (strchr(fmts, f) == NULL || (f == 'I' && b->itemsize != 4)) {
        PyErr_Format(PyExc_ValueError, "time_mesh_calls: %s must be a buffer of %s", name,
                     fmts[0] == 'I' ? "uint32" : "float64 or float32");
        PyBuffer_Release(b);
        return -1;
    }
    return 0;
}

static PyObject *ttd_ct_time_mesh_calls(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *kwlist[] = {"va", "fa", "vb", "fb", "poses", "calls", "query", "margin", "threads", "out", "out2",
                             "fresh", NULL};
    PyObject *objs[5], *out_obj = Py_None, *out2_obj = Py_None;
    Py_ssize_t calls;
    const char *query = "distance";
    double margin = 0;
    int threads = 0, fresh = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OOOOOn|sdiOOp:time_mesh_calls", kwlist, &objs[0], &objs[1],
                                     &objs[2], &objs[3], &objs[4], &calls, &query, &margin, &threads, &out_obj,
                                     &out2_obj, &fresh))
        return NULL;
    static const char *const names[5] = {"va", "fa", "vb", "fb", "poses"};
    Py_buffer b[7];
    int held = 0;
    PyObject *ret = NULL;
    ttd_mesh *a = NULL, *m = NULL;
    for (; held < 5; ++held)
        if (ttd_ct_buffer(objs[held], &b[held], held == 1 || held == 3 ? "I" : "df", 0, names[held]) < 0)
            goto done;
    if (out_obj != Py_None) {
        if (PyObject_GetBuffer(out_obj, &b[held], PyBUF_C_CONTIGUOUS | PyBUF_WRITABLE) < 0)
            goto done;
        ++held;
    }
    void *out = out_obj != Py_None ? b[5].buf : NULL;
    void *out2 = NULL;
    if (out2_obj != Py_None) {
        if (PyObject_GetBuffer(out2_obj, &b[held], PyBUF_C_CONTIGUOUS | PyBUF_WRITABLE) < 0)
            goto done;
        out2 = b[held++].buf;
    }
    const int dbl = b[0].itemsize == 8;
    if (b[2].itemsize != b[0].itemsize || b[4].itemsize != b[0].itemsize || calls < 1 || b[4].len % (12 * b[4].itemsize)) {
        PyErr_SetString(PyExc_ValueError, "time_mesh_calls: va, vb and poses must share one real type, poses hold "
                                          "12 reals each, and calls >= 1");
        goto done;
    }
    const int q = strcmp(query, "distance") == 0 ? 0 : strcmp(query, "collide") == 0 ? 1
                  : strcmp(query, "contacts") == 0 ? 2 : strcmp(query, "closest") == 0 ? 3 : -1;
    const size_t k = (size_t)(b[4].len / (12 * b[4].itemsize));
    const size_t nva = (size_t)(b[0].len / (3 * b[0].itemsize)), nta = (size_t)(b[1].len / 12);
    const size_t nvb = (size_t)(b[2].len / (3 * b[2].itemsize)), ntb = (size_t)(b[3].len / 12);
    const size_t rec = q == 0 ? (dbl ? sizeof(ttd_mesh_result_d) : sizeof(ttd_mesh_result_f))
                       : q == 1 ? sizeof(ttd_collision) : (dbl ? sizeof(ttd_closest_d) : sizeof(ttd_closest_f));
    if (q < 0 || ((q == 0 || q == 1 || q == 3) && (out == NULL || (size_t)b[5].len != k * rec * (q == 3 ? nta : 1))) ||
        (q == 3 && out2 != NULL && (size_t)b[6].len != k * rec * ntb)) {
        PyErr_SetString(PyExc_ValueError, "time_mesh_calls: query is 'distance', 'collide', 'contacts' or 'closest', "
                                          "and out (and out2) must hold the records the query writes");
        goto done;
    }
    ttd_options opt = ttd_default_options();
    opt.threads = threads;
    ttd_status st = dbl ? ttd_mesh_create_d(&opt, b[0].buf, nva, b[1].buf, nta, &a)
                        : ttd_mesh_create_f(&opt, b[0].buf, nva, b[1].buf, nta, &a);
    if (st == TTD_OK)
        st = dbl ? ttd_mesh_create_d(&opt, b[2].buf, nvb, b[3].buf, ntb, &m)
                 : ttd_mesh_create_f(&opt, b[2].buf, nvb, b[3].buf, ntb, &m);
    if (st != TTD_OK) {
        PyErr_Format(PyExc_RuntimeError, "time_mesh_calls: %s", ttd_status_string(st));
        goto done;
    }
    ttd_contacts_d sd = {0};
    ttd_contacts_f sf = {0};
    const void *poses = b[4].buf;
    double t0, t1;
    Py_BEGIN_ALLOW_THREADS
    t0 = ttd_ct_now();
    for (Py_ssize_t i = 0; i < calls && st == TTD_OK; ++i) {
        switch (q) {
        case 0:
            st = dbl ? ttd_mesh_distance_d(&opt, a, m, k, poses, (double)INFINITY, 0, out)
                     : ttd_mesh_distance_f(&opt, a, m, k, poses, INFINITY, 0, out);
            break;
        case 1:
            st = dbl ? ttd_mesh_collide_d(&opt, a, m, k, poses, margin, out)
                     : ttd_mesh_collide_f(&opt, a, m, k, poses, (float)margin, out);
            break;
        case 2:
            st = dbl ? ttd_mesh_contacts_d(&opt, a, m, k, poses, margin, &sd)
                     : ttd_mesh_contacts_f(&opt, a, m, k, poses, (float)margin, &sf);
            if (fresh) {
                ttd_contacts_free_d(&sd);
                ttd_contacts_free_f(&sf);
            }
            break;
        default:
            st = dbl ? ttd_mesh_closest_d(&opt, a, m, k, poses, margin, out, out2)
                     : ttd_mesh_closest_f(&opt, a, m, k, poses, (float)margin, out, out2);
            break;
        }
    }
    t1 = ttd_ct_now();
    Py_END_ALLOW_THREADS
    ttd_contacts_free_d(&sd);
    ttd_contacts_free_f(&sf);
    if (st != TTD_OK)
        PyErr_Format(PyExc_RuntimeError, "time_mesh_calls: %s", ttd_status_string(st));
    else
        ret = PyFloat_FromDouble(t1 - t0);
done:
    ttd_mesh_destroy(a);
    ttd_mesh_destroy(m);
    for (int i = 0; i < held; ++i)
        PyBuffer_Release(&b[i]);
    return ret;
}

static PyMethodDef ttd_ct_methods[] = {
    {"time_calls", (PyCFunction)(void (*)(void))ttd_ct_time_calls, METH_VARARGS | METH_KEYWORDS,
     ttd_ct_time_calls_doc},
    {"time_mesh_calls", (PyCFunction)(void (*)(void))ttd_ct_time_mesh_calls, METH_VARARGS | METH_KEYWORDS,
     ttd_ct_time_mesh_calls_doc},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef ttd_ct_module = {
    PyModuleDef_HEAD_INIT, "ttd._ctiming",
    "C-side timings of the library calls behind ttd.distance and the mesh queries, for "
    "bench/python_overhead.py only.",
    -1, ttd_ct_methods, NULL, NULL, NULL, NULL,
};

PyMODINIT_FUNC PyInit__ctiming(void);
PyMODINIT_FUNC PyInit__ctiming(void)
{
    return PyModule_Create(&ttd_ct_module);
}
