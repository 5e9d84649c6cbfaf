/* SPDX-License-Identifier: MIT */
/* ttd._ctiming: the C side of bench/python_overhead.py, and nothing else. It times the
 * library calls that ttd.distance makes (ttd_batch_d / ttd_batch_f with the same options),
 * called back to back from C on the same input and output buffers, so that the benchmark can
 * subtract them from the time of the Python calls in the same process: timing the C call
 * through ctypes instead would add ctypes' own per-call cost (about a microsecond) to the side
 * that should have none. The output buffer is the caller's, the one the Python call writes
 * with out=, so that the two sides differ only in the call. */
#define _POSIX_C_SOURCE 200809L
#define PY_SSIZE_T_CLEAN
#include <Python.h>

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

static PyMethodDef ttd_ct_methods[] = {
    {"time_calls", (PyCFunction)(void (*)(void))ttd_ct_time_calls, METH_VARARGS | METH_KEYWORDS,
     ttd_ct_time_calls_doc},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef ttd_ct_module = {
    PyModuleDef_HEAD_INIT, "ttd._ctiming",
    "C-side timings of the library calls behind ttd.distance, for bench/python_overhead.py only.",
    -1, ttd_ct_methods, NULL, NULL, NULL, NULL,
};

PyMODINIT_FUNC PyInit__ctiming(void);
PyMODINIT_FUNC PyInit__ctiming(void)
{
    return PyModule_Create(&ttd_ct_module);
}
