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
        ttd_py_value_error("ttd: min_separation must be finite and >= 0 (got %R)", delta);
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


PyDoc_STRVAR(mesh_ccd_doc,
             "_mesh_ccd(a, a1, b, b1, min_separation, shared, threads) -> (toi, kind, a_ids, b_ids, pair_toi, gap, flags,\n"
             "triangle_pairs, queries, searches)\n"
             "a, b ttd.Mesh (b None: self); a1, b1 C-contiguous (nv, 3) arrays of the mesh's dtype.\n"
             "Private: use ttd.mesh_ccd, ttd.mesh_self_ccd.");

/* A mesh's t = 1 array: an (nv, 3) C-contiguous, aligned array of the mesh's dtype (the wrapper made it so). */
static int t1_ok(const ttd_py_mesh *m, PyObject *o, const char *name)
{
    if (!PyArray_Check(o) || PyArray_TYPE((PyArrayObject *)o) != m->type || !PyArray_IS_C_CONTIGUOUS((PyArrayObject *)o) ||
        !PyArray_ISALIGNED((PyArrayObject *)o) ||
        PyArray_SIZE((PyArrayObject *)o) != 3 * PyArray_DIM(m->vertices, 0)) {
        PyErr_Format(PyExc_ValueError, "ttd: %s must be a C-contiguous, aligned (%zd, 3) array of the mesh's dtype", name,
                     (Py_ssize_t)PyArray_DIM(m->vertices, 0));
        return 0;
    }
    return 1;
}

static PyObject *py_mesh_ccd(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *a, *a1, *b, *b1;
    double delta;
    int shared, threads;
    if (!PyArg_ParseTuple(args, "OOOOdii", &a, &a1, &b, &b1, &delta, &shared, &threads))
        return NULL;
    const int is_self = b == Py_None;
    if (!PyObject_TypeCheck(a, &ttd_py_MeshType) || (!is_self && !PyObject_TypeCheck(b, &ttd_py_MeshType))) {
        PyErr_SetString(PyExc_TypeError, "ttd: the meshes must be ttd.Mesh objects");
        return NULL;
    }
    const ttd_py_mesh *ma = (const ttd_py_mesh *)a, *mb = is_self ? NULL : (const ttd_py_mesh *)b;
    if (!t1_ok(ma, a1, is_self ? "vertices_t1" : "a_vertices_t1") || (!is_self && !t1_ok(mb, b1, "b_vertices_t1")))
        return NULL;
    if (!is_self && ma->type != mb->type) {
        PyErr_SetString(PyExc_ValueError, "ttd: both meshes must have one dtype (float32 or float64)");
        return NULL;
    }
    ttd_options opt = ttd_default_options();
    opt.threads = threads;
    PyObject *meshes[2] = {a, is_self ? a : b};
    if (ttd_py_meshes_use(meshes, 2) < 0)
        return NULL;
    ttd_mesh_ccd_result r;
    ttd_status st;
    const void *p1 = PyArray_DATA((PyArrayObject *)a1), *q1 = is_self ? NULL : PyArray_DATA((PyArrayObject *)b1);
    const int d = ma->type == NPY_DOUBLE;
    const unsigned flags = shared ? TTD_SELF_SHARED_VERTEX : 0u;
    Py_BEGIN_ALLOW_THREADS
    if (is_self)
        st = d ? ttd_mesh_self_ccd_d(&opt, ma->mesh, p1, delta, flags, &r)
               : ttd_mesh_self_ccd_f(&opt, ma->mesh, p1, delta, flags, &r);
    else
        st = d ? ttd_mesh_ccd_d(&opt, ma->mesh, p1, mb->mesh, q1, delta, &r)
               : ttd_mesh_ccd_f(&opt, ma->mesh, p1, mb->mesh, q1, delta, &r);
    Py_END_ALLOW_THREADS
    ttd_py_meshes_release(meshes, 2);
    if (st == TTD_ERR_BAD_OPTIONS) {
        return ttd_py_value_error("ttd: min_separation must be finite and >= 0 (got %R)", delta);
    }
    if (st == TTD_ERR_NONFINITE_MESH) {
        PyErr_SetString(PyExc_ValueError, "ttd: the vertices at t = 1 hold NaN or infinite coordinates");
        return NULL;
    }
    if (st != TTD_OK) {
        if (ttd_py_raise_fatal(st, &opt) == 0)
            PyErr_Format(PyExc_SystemError, "ttd: unexpected status %d from mesh CCD", (int)st);
        return NULL;
    }
    const npy_intp n = (npy_intp)r.count;
    npy_intp d1[1] = {n}, d2[2] = {n, 2};
    PyArrayObject *kind = (PyArrayObject *)PyArray_SimpleNew(1, d1, NPY_UINT8);
    PyArrayObject *ia = (PyArrayObject *)PyArray_SimpleNew(2, d2, NPY_INT64);
    PyArrayObject *ib = (PyArrayObject *)PyArray_SimpleNew(2, d2, NPY_INT64);
    PyArrayObject *toi = (PyArrayObject *)PyArray_SimpleNew(1, d1, NPY_DOUBLE);
    PyArrayObject *gap = (PyArrayObject *)PyArray_SimpleNew(1, d1, NPY_DOUBLE);
    PyArrayObject *fl = (PyArrayObject *)PyArray_SimpleNew(1, d1, NPY_UINT32);
    PyObject *res = NULL;
    if (kind && ia && ib && toi && gap && fl) {
        for (npy_intp i = 0; i < n; ++i) {
            const ttd_mesh_ccd_pair *p = &r.pairs[i];
            ((uint8_t *)PyArray_DATA(kind))[i] = (uint8_t)p->kind;
            for (int k = 0; k < 2; ++k) { /* unused ids (UINT32_MAX) as -1 */
                ((int64_t *)PyArray_DATA(ia))[2 * i + k] = p->a[k] == UINT32_MAX ? -1 : (int64_t)p->a[k];
                ((int64_t *)PyArray_DATA(ib))[2 * i + k] = p->b[k] == UINT32_MAX ? -1 : (int64_t)p->b[k];
            }
            ((double *)PyArray_DATA(toi))[i] = p->toi;
            ((double *)PyArray_DATA(gap))[i] = p->gap;
            ((uint32_t *)PyArray_DATA(fl))[i] = p->flags;
        }
        res = Py_BuildValue("(dNNNNNNKKK)", r.toi, kind, ia, ib, toi, gap, fl, (unsigned long long)r.triangle_pairs,
                            (unsigned long long)r.queries, (unsigned long long)r.searches);
    } else {
        Py_XDECREF(kind), Py_XDECREF(ia), Py_XDECREF(ib), Py_XDECREF(toi), Py_XDECREF(gap), Py_XDECREF(fl);
    }
    ttd_mesh_ccd_free(&r);
    return res;
}

PyDoc_STRVAR(mesh_ccd_rigid_doc,
             "_mesh_ccd_rigid(a, a_poses, b, b_poses, min_separation) -> (toi, hit, distance, tolerance, flags, steps,\n"
             "tri_a, tri_b)\n"
             "a, b ttd.Mesh of one dtype; a_poses, b_poses C-contiguous (2, 3, 4) arrays of that dtype (checked\n"
             "poses at t = 0 and t = 1). Private: use ttd.mesh_ccd_rigid.");

/* A body's two poses: a C-contiguous, aligned array of 24 reals of the mesh's dtype (the wrapper made it so). */
static int poses_ok(const ttd_py_mesh *m, PyObject *o, const char *name)
{
    if (!PyArray_Check(o) || PyArray_TYPE((PyArrayObject *)o) != m->type || !PyArray_IS_C_CONTIGUOUS((PyArrayObject *)o) ||
        !PyArray_ISALIGNED((PyArrayObject *)o) || PyArray_SIZE((PyArrayObject *)o) != 24) {
        PyErr_Format(PyExc_ValueError, "ttd: %s must be a C-contiguous (2, 3, 4) array of the mesh's dtype", name);
        return 0;
    }
    return 1;
}

static PyObject *py_mesh_ccd_rigid(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *a, *pa, *b, *pb;
    double delta;
    if (!PyArg_ParseTuple(args, "OOOOd", &a, &pa, &b, &pb, &delta))
        return NULL;
    if (!PyObject_TypeCheck(a, &ttd_py_MeshType) || !PyObject_TypeCheck(b, &ttd_py_MeshType)) {
        PyErr_SetString(PyExc_TypeError, "ttd: the meshes must be ttd.Mesh objects");
        return NULL;
    }
    const ttd_py_mesh *ma = (const ttd_py_mesh *)a, *mb = (const ttd_py_mesh *)b;
    if (ma->type != mb->type) {
        PyErr_SetString(PyExc_ValueError, "ttd: both meshes must have one dtype (float32 or float64)");
        return NULL;
    }
    if (!poses_ok(ma, pa, "a's poses") || !poses_ok(mb, pb, "b's poses"))
        return NULL;
    ttd_options opt = ttd_default_options();
    opt.threads = 1;
    PyObject *meshes[2] = {a, b};
    if (ttd_py_meshes_use(meshes, 2) < 0)
        return NULL;
    ttd_mesh_ccd_rigid_result r;
    ttd_status st;
    const void *p = PyArray_DATA((PyArrayObject *)pa), *q = PyArray_DATA((PyArrayObject *)pb);
    const int d = ma->type == NPY_DOUBLE;
    Py_BEGIN_ALLOW_THREADS
    st = d ? ttd_mesh_ccd_rigid_d(&opt, ma->mesh, p, mb->mesh, q, delta, &r)
           : ttd_mesh_ccd_rigid_f(&opt, ma->mesh, p, mb->mesh, q, delta, &r);
    Py_END_ALLOW_THREADS
    ttd_py_meshes_release(meshes, 2);
    if (st == TTD_ERR_BAD_OPTIONS) {
        return ttd_py_value_error("ttd: min_separation must be finite and >= 0 (got %R)", delta);
    }
    if (st != TTD_OK) {
        if (ttd_py_raise_fatal(st, &opt) == 0)
            PyErr_Format(PyExc_SystemError, "ttd: unexpected status %d from rigid mesh CCD", (int)st);
        return NULL;
    }
    return Py_BuildValue("(dOddIIll)", r.toi, r.hit ? Py_True : Py_False, r.distance, r.tolerance, (unsigned)r.flags,
                         (unsigned)r.steps, r.tri_a == UINT32_MAX ? -1L : (long)r.tri_a,
                         r.tri_b == UINT32_MAX ? -1L : (long)r.tri_b);
}

PyDoc_STRVAR(rigid_pose_at_doc, "_rigid_pose_at(p0, p1, t) -> (12 floats)\n"
                                "p0, p1 sequences of 12 floats. Private: use ttd.rigid_pose_at.");

static PyObject *py_rigid_pose_at(PyObject *self, PyObject *args)
{
    (void)self;
    double p0[12], p1[12], t, q[12];
    if (!PyArg_ParseTuple(args, "(dddddddddddd)(dddddddddddd)d", &p0[0], &p0[1], &p0[2], &p0[3], &p0[4], &p0[5],
                          &p0[6], &p0[7], &p0[8], &p0[9], &p0[10], &p0[11], &p1[0], &p1[1], &p1[2], &p1[3], &p1[4],
                          &p1[5], &p1[6], &p1[7], &p1[8], &p1[9], &p1[10], &p1[11], &t))
        return NULL;
    const ttd_status st = ttd_rigid_pose_at_d(p0, p1, t, q);
    if (st == TTD_ERR_BAD_OPTIONS) {
        return ttd_py_value_error("ttd: t must lie in [0, 1] (got %R)", t);
    }
    if (st != TTD_OK) {
        PyErr_SetString(PyExc_ValueError, "ttd: a pose holds a NaN or infinite number");
        return NULL;
    }
    return Py_BuildValue("(dddddddddddd)", q[0], q[1], q[2], q[3], q[4], q[5], q[6], q[7], q[8], q[9], q[10], q[11]);
}

PyMethodDef ttd_py_ccd_methods[] = {
    {"_ccd", py_ccd, METH_VARARGS, ccd_doc},
    {"_mesh_ccd", py_mesh_ccd, METH_VARARGS, mesh_ccd_doc},
    {"_mesh_ccd_rigid", py_mesh_ccd_rigid, METH_VARARGS, mesh_ccd_rigid_doc},
    {"_rigid_pose_at", py_rigid_pose_at, METH_VARARGS, rigid_pose_at_doc},
    {NULL, NULL, 0, NULL},
};
