/* SPDX-License-Identifier: MIT */
/* Continuous collision (ttd.h's block of that name): one private function, _ccd, that the Python
 * wrappers in ttd/_ccd.py call with arrays already shaped and typed (float64, C-contiguous); it
 * returns the result columns as numpy arrays. */
#include "ttd_py.h"

#include <string.h>

PyDoc_STRVAR(ccd_doc, "_ccd(kind, a0, b0, a1, b1, min_separation, threads) -> (hit, toi, gap, flags, sub, evals)\n"
                      "kind 0 vertex-face, 1 edge-edge, 2 triangles; float64 C-contiguous arrays of n queries.\n"
                      "Private: use ttd.ccd_vertex_face, ttd.ccd_edge_edge, ttd.ccd_triangles.");

static PyObject *py_ccd(PyObject *self, PyObject *args)
{
    (void)self;
    int kind, threads;
    PyObject *o[4];
    double delta;
    if (!PyArg_ParseTuple(args, "iOOOOdi", &kind, &o[0], &o[1], &o[2], &o[3], &delta, &threads))
        return NULL;
    if (kind < 0 || kind > 2) {
        PyErr_SetString(PyExc_ValueError, "ttd: _ccd: kind must be 0, 1 or 2");
        return NULL;
    }
    /* Numbers a query in each array: a (vertex / edge a / triangle a) and b. */
    static const npy_intp per[3][2] = {{3, 9}, {6, 6}, {9, 9}};
    PyArrayObject *a[4] = {NULL, NULL, NULL, NULL};
    PyObject *res = NULL;
    for (int i = 0; i < 4; ++i) {
        a[i] = (PyArrayObject *)PyArray_FROMANY(o[i], NPY_DOUBLE, 0, 0, NPY_ARRAY_IN_ARRAY);
        if (a[i] == NULL)
            goto done;
    }
    const npy_intp n = PyArray_SIZE(a[0]) / per[kind][0];
    for (int i = 0; i < 4; ++i)
        if (PyArray_SIZE(a[i]) != n * per[kind][i & 1]) {
            PyErr_SetString(PyExc_ValueError, "ttd: _ccd: array sizes do not match");
            goto done;
        }
    if (n == 0) {
        PyErr_SetString(PyExc_ValueError, "ttd: no queries (n = 0)");
        goto done;
    }
    ttd_ccd_result *r = PyMem_RawMalloc(sizeof(ttd_ccd_result) * (size_t)n);
    if (r == NULL) {
        PyErr_NoMemory();
        goto done;
    }
    ttd_options opt = ttd_default_options();
    opt.threads = threads;
    const double *p[4];
    for (int i = 0; i < 4; ++i)
        p[i] = PyArray_DATA(a[i]);
    ttd_status st;
    Py_BEGIN_ALLOW_THREADS
    st = kind == 0 ? ttd_ccd_vertex_face_d(&opt, (size_t)n, p[0], p[1], p[2], p[3], delta, r)
         : kind == 1 ? ttd_ccd_edge_edge_d(&opt, (size_t)n, p[0], p[1], p[2], p[3], delta, r)
                     : ttd_ccd_triangles_d(&opt, (size_t)n, p[0], p[1], p[2], p[3], delta, r);
    Py_END_ALLOW_THREADS
    if (st == TTD_ERR_BAD_OPTIONS) {
        PyErr_Format(PyExc_ValueError, "ttd: min_separation must be finite and >= 0 (got %g) and threads >= 0", delta);
        PyMem_RawFree(r);
        goto done;
    }
    if (st != TTD_ERR_NONFINITE_INPUT && ttd_py_raise_fatal(st, &opt) < 0) {
        PyMem_RawFree(r);
        goto done;
    }
    npy_intp dims[1] = {n};
    PyArrayObject *hit = (PyArrayObject *)PyArray_SimpleNew(1, dims, NPY_BOOL);
    PyArrayObject *toi = (PyArrayObject *)PyArray_SimpleNew(1, dims, NPY_DOUBLE);
    PyArrayObject *gap = (PyArrayObject *)PyArray_SimpleNew(1, dims, NPY_DOUBLE);
    PyArrayObject *flags = (PyArrayObject *)PyArray_SimpleNew(1, dims, NPY_UINT32);
    PyArrayObject *sub = (PyArrayObject *)PyArray_SimpleNew(1, dims, NPY_UINT32);
    PyArrayObject *evals = (PyArrayObject *)PyArray_SimpleNew(1, dims, NPY_UINT32);
    if (hit && toi && gap && flags && sub && evals) {
        for (npy_intp i = 0; i < n; ++i) {
            ((npy_bool *)PyArray_DATA(hit))[i] = r[i].hit != 0;
            ((double *)PyArray_DATA(toi))[i] = r[i].toi;
            ((double *)PyArray_DATA(gap))[i] = r[i].gap;
            ((uint32_t *)PyArray_DATA(flags))[i] = r[i].flags;
            ((uint32_t *)PyArray_DATA(sub))[i] = r[i].sub;
            ((uint32_t *)PyArray_DATA(evals))[i] = r[i].evals;
        }
        res = Py_BuildValue("(NNNNNN)", hit, toi, gap, flags, sub, evals);
    } else {
        Py_XDECREF(hit), Py_XDECREF(toi), Py_XDECREF(gap), Py_XDECREF(flags), Py_XDECREF(sub), Py_XDECREF(evals);
    }
    PyMem_RawFree(r);
    if (res != NULL && st == TTD_ERR_NONFINITE_INPUT &&
        PyErr_WarnEx(ttd_py_NonFiniteInputWarning,
                     "ttd: some queries had NaN or infinite coordinates; their toi is NaN", 1) < 0)
        Py_CLEAR(res);
done:
    for (int i = 0; i < 4; ++i)
        Py_XDECREF(a[i]);
    return res;
}

PyMethodDef ttd_py_ccd_methods[] = {
    {"_ccd", py_ccd, METH_VARARGS, ccd_doc},
    {NULL, NULL, 0, NULL},
};
