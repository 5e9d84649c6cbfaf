/* SPDX-License-Identifier: MIT */
/* The point queries of ttd._ttd (include/ttd/ttd.h, "Point queries"; docs/points.md):
 * ttd.closest_points, ttd.signed_distance, ttd.winding_number, ttd.contains and ttd.sdf_grid on a
 * ttd.Mesh. Points are any array of shape (..., 3), converted to the mesh's dtype; results have the
 * shape (...). The interpreter lock is released while the library computes. */
#include "ttd_py.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

enum { NCP = 8, NSD = 5, NWN = 2, NCT = 1 };

static PyStructSequence_Field cp_fields[NCP + 1] = {
    {"distance", "the exact distance to the mesh, shape (...); inf beyond upper_bound, NaN for a NaN point"},
    {"point", "the closest point on the mesh, shape (..., 3), in the points' frame"},
    {"triangle", "uint32: the triangle it lies on (ttd.NO_TRIANGLE beyond the bound or for a NaN point)"},
    {"bary", "the weights of the triangle's vertices that give point, shape (..., 3)"},
    {"feature", "uint8: vertex bits with a non-zero weight (1 bit: a vertex, 2: an edge, 3: the face)"},
    {"flags", "uint8: ttd.POINT_* bits (NONFINITE, ABOVE_BOUND, INSIDE, DEGENERATE, SIGN_UNPROVEN)"},
    {"node_tests", "uint32: hierarchy nodes tested for the point"},
    {"triangle_tests", "uint32: triangles measured exactly for the point"},
    {NULL, NULL},
};
static PyStructSequence_Desc cp_desc = {
    "ttd.ClosestPoints",
    "The result of ttd.closest_points: a named tuple of arrays over the points, views of one\n"
    "record array laid out as the C library's ttd_point_result_d/_f (ttd.POINT_RESULT_DTYPE_*).",
    cp_fields, NCP,
};
static PyStructSequence_Field sd_fields[NSD + 1] = {
    {"distance", "the signed distance, negative inside (|winding number| >= 1/2), shape (...)"},
    {"point", "the closest point on the mesh, shape (..., 3)"},
    {"triangle", "uint32: the triangle it lies on"},
    {"inside", "bool: the point is inside (|winding number| >= 1/2)"},
    {"flags", "uint8: ttd.POINT_* bits (INSIDE; SIGN_UNPROVEN where an open mesh's side is not proven)"},
    {NULL, NULL},
};
static PyStructSequence_Desc sd_desc = {
    "ttd.SignedDistance", "The result of ttd.signed_distance: a named tuple of arrays over the points.", sd_fields, NSD,
};
static PyStructSequence_Field wn_fields[NWN + 1] = {
    {"winding", "float64: the generalized winding number, shape (...) (about 1 inside a closed mesh, 0 outside)"},
    {"inside", "bool: |winding| >= 1/2 (the inside rule of every query)"},
    {NULL, NULL},
};
static PyStructSequence_Desc wn_desc = {
    "ttd.WindingNumber", "The result of ttd.winding_number: a named tuple of arrays over the points.", wn_fields, NWN,
};
static PyStructSequence_Field ct_fields[NCT + 1] = {
    {"inside", "bool: the point is inside the mesh (|winding number| >= 1/2), shape (...)"},
    {NULL, NULL},
};
static PyStructSequence_Desc ct_desc = {
    "ttd.Containment", "The result of ttd.contains: a named tuple of one bool array over the points.", ct_fields, NCT,
};

static PyTypeObject *ClosestPoints, *SignedDistance, *WindingNumber, *Containment;
/* Points in a batch's first piece between Ctrl-C checks (ttd_py_run_pieces): a batch this size
 * or smaller is one library call. */
#define TTD_PY_POINTS_PIECE 65536

static PyObject *cp_names[NCP], *sd_names[NSD], *wn_names[NWN], *ct_names[NCT];
static PyArray_Descr *cp_rec[2]; /* [0] float64, [1] float32 */

#define CP_OFFSETS(T)                                                                                  \
    {offsetof(T, distance), offsetof(T, point), offsetof(T, triangle), offsetof(T, bary), offsetof(T, feature), \
     offsetof(T, flags), offsetof(T, node_tests), offsetof(T, triangle_tests)}

static int add_obj(PyObject *module, const char *name, PyObject *obj)
{
    if (obj == NULL)
        return -1;
    Py_INCREF(obj);
    if (PyModule_AddObject(module, name, obj) < 0) {
        Py_DECREF(obj);
        return -1;
    }
    return 0;
}

int ttd_py_points_init(PyObject *module)
{
    if (!(ClosestPoints = ttd_py_named_tuple(module, &cp_desc, cp_names)) ||
        !(SignedDistance = ttd_py_named_tuple(module, &sd_desc, sd_names)) ||
        !(WindingNumber = ttd_py_named_tuple(module, &wn_desc, wn_names)) ||
        !(Containment = ttd_py_named_tuple(module, &ct_desc, ct_names)))
        return -1;
    static const size_t off[2][NCP] = {CP_OFFSETS(ttd_point_result_d), CP_OFFSETS(ttd_point_result_f)};
    static const size_t size[2] = {sizeof(ttd_point_result_d), sizeof(ttd_point_result_f)};
    static const char *const reals[2] = {"f8", "f4"}, *const vecs[2] = {"(3,)f8", "(3,)f4"};
    for (int i = 0; i < 2; ++i) {
        const char *fmt[NCP] = {reals[i], vecs[i], "u4", vecs[i], "u1", "u1", "u4", "u4"};
        cp_rec[i] = ttd_py_record_descr(NCP, cp_names, fmt, off[i], size[i]);
        if (add_obj(module, i ? "POINT_RESULT_DTYPE_FLOAT32" : "POINT_RESULT_DTYPE_FLOAT64", (PyObject *)cp_rec[i]) < 0)
            return -1;
    }
    if (PyModule_AddIntConstant(module, "POINT_NONFINITE", TTD_POINT_NONFINITE) < 0 ||
        PyModule_AddIntConstant(module, "POINT_ABOVE_BOUND", TTD_POINT_ABOVE_BOUND) < 0 ||
        PyModule_AddIntConstant(module, "POINT_INSIDE", TTD_POINT_INSIDE) < 0 ||
        PyModule_AddIntConstant(module, "POINT_DEGENERATE", TTD_POINT_DEGENERATE) < 0 ||
        PyModule_AddIntConstant(module, "POINT_SIGN_UNPROVEN", TTD_POINT_SIGN_UNPROVEN) < 0)
        return -1;
    return 0;
}

/* What every point query takes, checked and converted. */
typedef struct pq {
    const ttd_py_mesh *mesh;
    int type, f;            /* the mesh's NPY_DOUBLE or NPY_FLOAT; f: float */
    ttd_options opt;
    PyArrayObject *points;  /* C-contiguous, of type (owned) */
    npy_intp n;
    int nd;                 /* result dimensions: the points' minus the last */
    npy_intp dims[NPY_MAXDIMS];
    double pose_d[12];
    float pose_f[12];
    int has_pose;
    int in_use;             /* the mesh marked in use (ttd_py_meshes_use): set_vertices refuses */
} pq;

static int pq_begin(PyObject *mesh, PyObject *points, PyObject *pose, PyObject *isa, PyObject *threads, pq *q)
{
    memset(q, 0, sizeof *q);
    if (!PyObject_TypeCheck(mesh, &ttd_py_MeshType)) {
        PyErr_Format(PyExc_TypeError, "mesh must be a ttd.Mesh, not %.100s", Py_TYPE(mesh)->tp_name);
        return -1;
    }
    q->mesh = (const ttd_py_mesh *)mesh;
    q->type = q->mesh->type;
    q->f = q->type == NPY_FLOAT;
    if (ttd_py_options(NULL, isa, threads, NULL, NULL, NULL, &q->opt) < 0)
        return -1;
    PyArrayObject *a = ttd_py_as_array(points, "points");
    if (a == NULL)
        return -1;
    const int nd = PyArray_NDIM(a);
    if (nd < 1 || PyArray_DIM(a, nd - 1) != 3) {
        PyObject *shape = ttd_py_shape(a);
        PyErr_Format(PyExc_ValueError, "points must have shape (..., 3), not %S", shape);
        Py_XDECREF(shape);
        Py_DECREF(a);
        return -1;
    }
    q->points = ttd_py_as_real(a, "points", q->type);
    Py_DECREF(a);
    if (q->points == NULL)
        return -1;
    q->nd = nd - 1;
    q->n = 1;
    for (int i = 0; i < q->nd; ++i) {
        q->dims[i] = PyArray_DIM(q->points, i);
        q->n *= q->dims[i];
    }
    if (pose != NULL && pose != Py_None) {
        PyArrayObject *p = ttd_py_as_array(pose, "pose"), *pd = NULL;
        if (p != NULL && PyArray_NDIM(p) == 2 && (PyArray_DIM(p, 0) == 3 || PyArray_DIM(p, 0) == 4) &&
            PyArray_DIM(p, 1) == 4)
            pd = ttd_py_as_real(p, "pose", NPY_DOUBLE);
        else if (p != NULL)
            PyErr_SetString(PyExc_ValueError, "pose must have shape (3, 4) or (4, 4): [R | t], x_points = R x_mesh + t");
        Py_XDECREF(p);
        if (pd == NULL) {
            Py_CLEAR(q->points);
            return -1;
        }
        const double *x = PyArray_DATA(pd);
        for (int k = 0; k < 12; ++k) {
            q->pose_d[k] = x[k];
            q->pose_f[k] = ttd_py_to_float(x[k]);
        }
        Py_DECREF(pd);
        q->has_pose = 1;
    }
    /* as the mesh queries: not while Mesh.set_vertices moves it (RuntimeError), and set_vertices
     * refuses to start until this query ends (pq_end) */
    if (ttd_py_meshes_use(&mesh, 1) < 0) {
        Py_CLEAR(q->points);
        return -1;
    }
    q->in_use = 1;
    return 0;
}

static void pq_end(pq *q)
{
    Py_CLEAR(q->points);
    if (q->in_use) {
        PyObject *mesh = (PyObject *)q->mesh;
        ttd_py_meshes_release(&mesh, 1);
        q->in_use = 0;
    }
}

/* The status's exception or warning; -1 when one was raised. */
static int pq_status(ttd_status st, const pq *q)
{
    if (st == TTD_PY_INTERRUPTED) /* raised already (KeyboardInterrupt) */
        return -1;
    if (st == TTD_ERR_NONFINITE_INPUT) {
        return PyErr_WarnEx(ttd_py_NonFiniteInputWarning,
                            "ttd: some points had NaN or infinite coordinates; their outputs are NaN", 1) < 0
                   ? -1
                   : 0;
    }
    if (st == TTD_ERR_COORDINATE_RANGE) {
        PyErr_Format(PyExc_ValueError, "ttd: a point (in the mesh's frame) or the pose is beyond the meshes' range, " TTD_PY_RANGE_TEXT);
        return -1;
    }
    if (st == TTD_ERR_BAD_POSE) {
        PyErr_SetString(PyExc_ValueError, "ttd: pose is not a rotation and translation (R^T R - I within 1e-6, det R > 0, finite)");
        return -1;
    }
    if (st == TTD_ERR_BAD_OPTIONS && q != NULL) {
        PyErr_SetString(PyExc_ValueError, "ttd: upper_bound must be >= 0 (or None)");
        return -1;
    }
    return ttd_py_raise_fatal(st, &q->opt);
}

/* A new array of the result shape (...) plus extra trailing dimensions. */
static PyArrayObject *pq_array(const pq *q, int type_num)
{
    return (PyArrayObject *)PyArray_SimpleNew(q->nd, q->dims, type_num);
}

static PyArrayObject *pq_records(const pq *q)
{
    PyArray_Descr *d = cp_rec[q->f];
    Py_INCREF(d);
    return (PyArrayObject *)PyArray_NewFromDescr(&PyArray_Type, d, q->nd, q->dims, NULL, NULL, 0, NULL);
}

/* The library call (closest: sd NULL; signed: sd set) on points [b, e), with the lock released
 * (ttd_py_run_pieces: Ctrl-C between pieces). */
typedef struct pq_piece {
    const pq *q;
    double ub;
    void *rec, *sd;
    double *w;
    float *wf;
} pq_piece;

static ttd_status pq_closest_piece(void *ctx, size_t b, size_t e)
{
    const pq_piece *c = ctx;
    const pq *q = c->q;
    const char *pts = (const char *)PyArray_DATA(q->points) + 3 * b * (q->f ? sizeof(float) : sizeof(double));
    if (q->f) {
        ttd_point_result_f *rec = (ttd_point_result_f *)c->rec + b;
        return c->sd ? ttd_points_signed_distance_f(&q->opt, q->mesh->mesh, e - b, (const float *)pts,
                                                    q->has_pose ? q->pose_f : NULL, ttd_py_to_float(c->ub),
                                                    (float *)c->sd + b, rec)
                     : ttd_points_closest_f(&q->opt, q->mesh->mesh, e - b, (const float *)pts,
                                            q->has_pose ? q->pose_f : NULL, ttd_py_to_float(c->ub), rec);
    }
    ttd_point_result_d *rec = (ttd_point_result_d *)c->rec + b;
    return c->sd ? ttd_points_signed_distance_d(&q->opt, q->mesh->mesh, e - b, (const double *)pts,
                                                q->has_pose ? q->pose_d : NULL, c->ub, (double *)c->sd + b, rec)
                 : ttd_points_closest_d(&q->opt, q->mesh->mesh, e - b, (const double *)pts,
                                        q->has_pose ? q->pose_d : NULL, c->ub, rec);
}

static ttd_status pq_closest(const pq *q, double ub, void *rec, void *sd)
{
    pq_piece c = {q, ub, rec, sd, NULL, NULL};
    ttd_status st;
    return ttd_py_run_pieces((size_t)q->n, TTD_PY_POINTS_PIECE, pq_closest_piece, &c, &st) < 0 ? TTD_PY_INTERRUPTED : st;
}

PyDoc_STRVAR(closest_points_doc,
"closest_points(mesh, points, *, pose=None, upper_bound=None, isa='auto', threads=0)\n"
"--\n\n"
"The exact closest point of mesh to each point: the minimum over every triangle of the exact\n"
"point-triangle distance, bit for bit, ties to the smallest triangle index.\n\n"
"mesh : ttd.Mesh (float64 or float32: the query runs in its dtype).\n"
"points : array of shape (..., 3), converted to the mesh's dtype.\n"
"pose : optional (3, 4) or (4, 4) [R | t]: the mesh's pose in the points' frame.\n"
"upper_bound : optional float >= 0: points farther than it get inf and ttd.NO_TRIANGLE.\n\n"
"Returns a ttd.ClosestPoints of arrays of shape (...): distance, point (..., 3), triangle,\n"
"bary (..., 3), feature, flags, node_tests, triangle_tests. NaN or infinite points get NaN\n"
"outputs and a ttd.NonFiniteInputWarning. The interpreter lock is released while it computes.");

static PyObject *py_closest_points(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *kwlist[] = {"mesh", "points", "pose", "upper_bound", "isa", "threads", NULL};
    PyObject *mesh, *points, *pose = NULL, *ub_obj = NULL, *isa = NULL, *threads = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OO|$OOOO:closest_points", kwlist, &mesh, &points, &pose, &ub_obj, &isa,
                                     &threads))
        return NULL;
    double ub = (double)INFINITY;
    pq q;
    if (ttd_py_real_arg(ub_obj, "upper_bound", &ub) < 0 || pq_begin(mesh, points, pose, isa, threads, &q) < 0)
        return NULL;
    PyObject *result = NULL;
    PyArrayObject *rec = pq_records(&q);
    if (rec == NULL)
        goto done;
    if (q.n > 0 && pq_status(pq_closest(&q, ub, PyArray_DATA(rec), NULL), &q) < 0)
        goto done;
    result = ttd_py_named_new(ClosestPoints, NCP);
    if (result != NULL && ttd_py_set_views(result, 0, rec, cp_names, NCP) < 0)
        Py_CLEAR(result);
done:
    Py_XDECREF(rec);
    pq_end(&q);
    return result;
}

PyDoc_STRVAR(signed_distance_doc,
"signed_distance(mesh, points, *, pose=None, upper_bound=None, isa='auto', threads=0)\n"
"--\n\n"
"Signed distances: the exact closest-point distance, negative inside the mesh (|generalized\n"
"winding number| >= 1/2: for a closed mesh, its solid whichever way it is wound).\n\n"
"Arguments as ttd.closest_points. Returns a ttd.SignedDistance: distance (...), point (..., 3),\n"
"triangle (...), inside (...) bool, flags (...) uint8 (ttd.POINT_INSIDE, ttd.POINT_SIGN_UNPROVEN:\n"
"an open mesh's side that rounding leaves unproven).");

static PyObject *py_signed_distance(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *kwlist[] = {"mesh", "points", "pose", "upper_bound", "isa", "threads", NULL};
    PyObject *mesh, *points, *pose = NULL, *ub_obj = NULL, *isa = NULL, *threads = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OO|$OOOO:signed_distance", kwlist, &mesh, &points, &pose, &ub_obj,
                                     &isa, &threads))
        return NULL;
    double ub = (double)INFINITY;
    pq q;
    if (ttd_py_real_arg(ub_obj, "upper_bound", &ub) < 0 || pq_begin(mesh, points, pose, isa, threads, &q) < 0)
        return NULL;
    PyObject *result = NULL, *views = NULL;
    PyArrayObject *rec = pq_records(&q), *sd = pq_array(&q, q.type), *inside = pq_array(&q, NPY_BOOL);
    if (rec == NULL || sd == NULL || inside == NULL)
        goto done;
    if (q.n > 0 && pq_status(pq_closest(&q, ub, PyArray_DATA(rec), PyArray_DATA(sd)), &q) < 0)
        goto done;
    npy_bool *in = PyArray_DATA(inside);
    for (npy_intp i = 0; i < q.n; ++i)
        in[i] = (q.f ? ((const ttd_point_result_f *)PyArray_DATA(rec))[i].flags
                     : ((const ttd_point_result_d *)PyArray_DATA(rec))[i].flags) & TTD_POINT_INSIDE
                    ? 1
                    : 0;
    views = ttd_py_named_new(ClosestPoints, NCP);
    if (views == NULL || ttd_py_set_views(views, 0, rec, cp_names, NCP) < 0)
        goto done;
    result = ttd_py_named_new(SignedDistance, NSD);
    if (result == NULL)
        goto done;
    PyTuple_SET_ITEM(result, 0, (PyObject *)sd);
    sd = NULL;
    PyObject *pt = PyTuple_GET_ITEM(views, 1), *tri = PyTuple_GET_ITEM(views, 2), *fl = PyTuple_GET_ITEM(views, 5);
    Py_INCREF(pt);
    Py_INCREF(tri);
    Py_INCREF(fl);
    PyTuple_SET_ITEM(result, 1, pt);
    PyTuple_SET_ITEM(result, 2, tri);
    PyTuple_SET_ITEM(result, 3, (PyObject *)inside);
    inside = NULL;
    PyTuple_SET_ITEM(result, 4, fl);
done:
    Py_XDECREF(views);
    Py_XDECREF(rec);
    Py_XDECREF(sd);
    Py_XDECREF(inside);
    pq_end(&q);
    return result;
}

static ttd_status pq_winding_piece(void *ctx, size_t b, size_t e)
{
    const pq_piece *c = ctx;
    const pq *q = c->q;
    ttd_status st;
    if (q->f) {
        const float *pts = (const float *)PyArray_DATA(q->points) + 3 * b;
        st = ttd_points_winding_number_f(&q->opt, q->mesh->mesh, e - b, pts, q->has_pose ? q->pose_f : NULL, c->wf + b);
        for (size_t i = b; i < e && st < TTD_ERR_FIRST_FATAL; ++i)
            c->w[i] = (double)c->wf[i];
        return st;
    }
    const double *pts = (const double *)PyArray_DATA(q->points) + 3 * b;
    return ttd_points_winding_number_d(&q->opt, q->mesh->mesh, e - b, pts, q->has_pose ? q->pose_d : NULL, c->w + b);
}

/* The winding numbers (as float64) into w; -1 with an exception. */
static int pq_winding(const pq *q, double *w)
{
    if (q->n == 0)
        return 0;
    ttd_status st;
    const size_t n = (size_t)q->n;
    float *wf = q->f ? PyMem_RawMalloc(n * sizeof *wf) : NULL;
    if (q->f && wf == NULL) {
        PyErr_NoMemory();
        return -1;
    }
    pq_piece c = {q, 0, NULL, NULL, w, wf};
    if (ttd_py_run_pieces(n, TTD_PY_POINTS_PIECE, pq_winding_piece, &c, &st) < 0)
        st = TTD_PY_INTERRUPTED;
    PyMem_RawFree(wf);
    return pq_status(st, q);
}

/* Whether each point is inside (ttd_points_contains) into in; -1 with an exception. */
static int pq_contains(const pq *q, npy_bool *in)
{
    if (q->n == 0)
        return 0;
    ttd_status st;
    const void *pts = PyArray_DATA(q->points);
    const size_t n = (size_t)q->n;
    Py_BEGIN_ALLOW_THREADS
    if (q->f)
        st = ttd_points_contains_f(&q->opt, q->mesh->mesh, n, pts, q->has_pose ? q->pose_f : NULL, (uint8_t *)in);
    else
        st = ttd_points_contains_d(&q->opt, q->mesh->mesh, n, pts, q->has_pose ? q->pose_d : NULL, (uint8_t *)in);
    Py_END_ALLOW_THREADS
    return pq_status(st, q);
}

PyDoc_STRVAR(winding_number_doc,
"winding_number(mesh, points, *, pose=None, isa='auto', threads=0)\n"
"--\n\n"
"The generalized winding number of mesh about each point, computed hierarchically (Barill et al.\n"
"2018) with a bounded error (docs/points.md). Returns a ttd.WindingNumber: winding (...) float64,\n"
"inside (...) bool (|winding| >= 1/2, ttd.contains's rule: the winding number is tightened until\n"
"it settles that side).");

PyDoc_STRVAR(contains_doc,
"contains(mesh, points, *, pose=None, isa='auto', threads=0)\n"
"--\n\n"
"Whether each point is inside mesh (|generalized winding number| >= 1/2: a closed mesh's solid\n"
"whichever way it is wound). Returns a\n"
"ttd.Containment: inside (...) bool.");

static PyObject *winding_or_contains(PyObject *args, PyObject *kwargs, int contains)
{
    static char *kwlist[] = {"mesh", "points", "pose", "isa", "threads", NULL};
    PyObject *mesh, *points, *pose = NULL, *isa = NULL, *threads = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, contains ? "OO|$OOO:contains" : "OO|$OOO:winding_number", kwlist, &mesh,
                                     &points, &pose, &isa, &threads))
        return NULL;
    pq q;
    if (pq_begin(mesh, points, pose, isa, threads, &q) < 0)
        return NULL;
    PyObject *result = NULL;
    PyArrayObject *w = contains ? NULL : pq_array(&q, NPY_DOUBLE), *inside = pq_array(&q, NPY_BOOL);
    if ((!contains && w == NULL) || inside == NULL)
        goto done;
    if (contains) { /* the library's decision, as it is */
        if (pq_contains(&q, PyArray_DATA(inside)) < 0)
            goto done;
    } else { /* the library's winding numbers (side-tightened), and its one rule on them */
        if (pq_winding(&q, PyArray_DATA(w)) < 0)
            goto done;
        const double *wv = PyArray_DATA(w);
        npy_bool *in = PyArray_DATA(inside);
        for (npy_intp i = 0; i < q.n; ++i)
            in[i] = (npy_bool)ttd_winding_inside(wv[i]);
    }
    result = ttd_py_named_new(contains ? Containment : WindingNumber, contains ? NCT : NWN);
    if (result == NULL)
        goto done;
    if (contains) {
        PyTuple_SET_ITEM(result, 0, (PyObject *)inside);
    } else {
        PyTuple_SET_ITEM(result, 0, (PyObject *)w);
        PyTuple_SET_ITEM(result, 1, (PyObject *)inside);
        w = NULL;
    }
    inside = NULL;
done:
    Py_XDECREF(w);
    Py_XDECREF(inside);
    pq_end(&q);
    return result;
}

static PyObject *py_winding_number(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    return winding_or_contains(args, kwargs, 0);
}

static PyObject *py_contains(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    return winding_or_contains(args, kwargs, 1);
}

PyDoc_STRVAR(sdf_grid_doc,
"sdf_grid(mesh, origin, step, shape, *, isa='auto', threads=0)\n"
"--\n\n"
"Signed distances on a regular grid, in the mesh's frame: an array of the given shape (nx, ny,\n"
"nz) and the mesh's dtype whose [i, j, k] is the signed distance at origin + (i, j, k) * step\n"
"(each coordinate computed as origin[c] + i * step[c] in the mesh's dtype). step is one number\n"
"or three, each > 0. Computed slab by slab (or row by row): Ctrl-C stops it (KeyboardInterrupt).");

/* The grid's slabs (x index i), or rows (i, j), [b, e): each one library call on a grid of one slab
 * or row whose origin is the point origin + (i, j, 0) * step computed as the library computes a
 * whole grid's coordinates, so the pieces give the whole call's bits. */
typedef struct grid_piece {
    const ttd_options *opt;
    const ttd_mesh *mesh;
    int f;
    double o[3], s[3];
    float of[3], sf[3];
    size_t dims[3];
    int rows;
    void *out;
} grid_piece;

static ttd_status grid_run_piece(void *ctx, size_t b, size_t e)
{
    const grid_piece *g = ctx;
    const size_t per = g->rows ? g->dims[2] : g->dims[1] * g->dims[2];
    const size_t d1[3] = {1, g->rows ? 1 : g->dims[1], g->dims[2]};
    ttd_status st = TTD_OK;
    for (size_t u = b; u < e && st < TTD_ERR_FIRST_FATAL; ++u) {
        const size_t i = g->rows ? u / g->dims[1] : u, j = g->rows ? u % g->dims[1] : 0;
        ttd_status s1;
        if (g->f) {
            const float o[3] = {g->of[0] + (float)i * g->sf[0], g->of[1] + (float)j * g->sf[1], g->of[2]};
            s1 = ttd_sdf_grid_f(g->opt, g->mesh, o, g->sf, d1, (float *)g->out + u * per);
        } else {
            const double o[3] = {g->o[0] + (double)i * g->s[0], g->o[1] + (double)j * g->s[1], g->o[2]};
            s1 = ttd_sdf_grid_d(g->opt, g->mesh, o, g->s, d1, (double *)g->out + u * per);
        }
        if (s1 > st)
            st = s1;
    }
    return st;
}

static PyObject *py_sdf_grid(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *kwlist[] = {"mesh", "origin", "step", "shape", "isa", "threads", NULL};
    PyObject *mesh, *origin, *step, *shape, *isa = NULL, *threads = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OOOO|$OO:sdf_grid", kwlist, &mesh, &origin, &step, &shape, &isa,
                                     &threads))
        return NULL;
    if (!PyObject_TypeCheck(mesh, &ttd_py_MeshType)) {
        PyErr_Format(PyExc_TypeError, "mesh must be a ttd.Mesh, not %.100s", Py_TYPE(mesh)->tp_name);
        return NULL;
    }
    const ttd_py_mesh *m = (const ttd_py_mesh *)mesh;
    ttd_options opt;
    if (ttd_py_options(NULL, isa, threads, NULL, NULL, NULL, &opt) < 0)
        return NULL;
    double o[3], s[3];
    npy_intp dims[3];
    PyArrayObject *oa = ttd_py_as_array(origin, "origin"), *sa = ttd_py_as_array(step, "step"),
                  *ha = ttd_py_as_array(shape, "shape");
    PyArrayObject *od = oa ? ttd_py_as_real(oa, "origin", NPY_DOUBLE) : NULL, *sdd = sa ? ttd_py_as_real(sa, "step", NPY_DOUBLE) : NULL,
                  *hd = ha ? ttd_py_as_real(ha, "shape", NPY_DOUBLE) : NULL;
    Py_XDECREF(oa);
    Py_XDECREF(sa);
    Py_XDECREF(ha);
    /* each problem its own message */
    int ok = od && sdd && hd;
    if (ok && PyArray_SIZE(od) != 3) {
        PyErr_Format(PyExc_ValueError, "sdf_grid: origin must be 3 numbers (x, y, z), not %zd", (Py_ssize_t)PyArray_SIZE(od));
        ok = 0;
    } else if (ok && PyArray_SIZE(sdd) != 3 && PyArray_SIZE(sdd) != 1) {
        PyErr_Format(PyExc_ValueError, "sdf_grid: step must be 1 number or 3, not %zd", (Py_ssize_t)PyArray_SIZE(sdd));
        ok = 0;
    } else if (ok && PyArray_SIZE(hd) != 3) {
        PyErr_Format(PyExc_ValueError, "sdf_grid: shape must be 3 integers (nx, ny, nz), not %zd", (Py_ssize_t)PyArray_SIZE(hd));
        ok = 0;
    }
    char why[160];
    for (int c = 0; ok && c < 3; ++c) {
        o[c] = ((const double *)PyArray_DATA(od))[c];
        s[c] = ((const double *)PyArray_DATA(sdd))[PyArray_SIZE(sdd) == 1 ? 0 : c];
        const double h = ((const double *)PyArray_DATA(hd))[c];
        PyObject *kind = PyExc_ValueError;
        why[0] = '\0';
        if (!isfinite(o[c]) || !isfinite(s[c]))
            snprintf(why, sizeof why, "sdf_grid: origin and step must be finite");
        else if (!(s[c] > 0))
            snprintf(why, sizeof why, "sdf_grid: step must be > 0 on every axis, not %.17g on axis %d", s[c], c);
        else if (h != floor(h))
            kind = PyExc_TypeError, snprintf(why, sizeof why, "sdf_grid: shape must be integers, not %.17g on axis %d", h, c);
        else if (!(h >= 0))
            snprintf(why, sizeof why, "sdf_grid: shape must be >= 0 on every axis, not %.0f on axis %d", h, c);
        else if (!(h < 1e15))
            snprintf(why, sizeof why, "sdf_grid: shape %.0f on axis %d is beyond any array", h, c);
        if (why[0]) {
            PyErr_SetString(kind, why);
            ok = 0;
        }
        dims[c] = ok ? (npy_intp)h : 0;
    }
    Py_XDECREF(od);
    Py_XDECREF(sdd);
    Py_XDECREF(hd);
    if (!ok)
        return NULL;
    PyArrayObject *out = (PyArrayObject *)PyArray_SimpleNew(3, dims, m->type);
    if (out == NULL)
        return NULL;
    if (PyArray_SIZE(out) == 0)
        return (PyObject *)out;
    grid_piece g = {&opt, m->mesh, m->type == NPY_FLOAT, {0}, {0}, {0}, {0},
                    {(size_t)dims[0], (size_t)dims[1], (size_t)dims[2]}, 0, PyArray_DATA(out)};
    for (int c = 0; c < 3; ++c) {
        g.o[c] = o[c], g.s[c] = s[c];
        g.of[c] = ttd_py_to_float(o[c]), g.sf[c] = ttd_py_to_float(s[c]);
    }
    /* the grid in pieces between Ctrl-C checks: whole x slabs, or rows of a slab when one slab is large */
    g.rows = g.dims[1] * g.dims[2] > TTD_PY_POINTS_PIECE;
    const size_t units = g.rows ? g.dims[0] * g.dims[1] : g.dims[0];
    const size_t per = g.rows ? g.dims[2] : g.dims[1] * g.dims[2];
    ttd_status st;
    if (ttd_py_meshes_use(&mesh, 1) < 0) { /* as every query: not while set_vertices moves it */
        Py_DECREF(out);
        return NULL;
    }
    const int run = ttd_py_run_pieces(units, per >= TTD_PY_POINTS_PIECE ? 1 : TTD_PY_POINTS_PIECE / per, grid_run_piece, &g, &st);
    ttd_py_meshes_release(&mesh, 1);
    if (run < 0) {
        Py_DECREF(out);
        return NULL;
    }
    if (st == TTD_ERR_BAD_OPTIONS) {
        PyErr_SetString(PyExc_ValueError, "sdf_grid: origin and step must be finite");
        Py_DECREF(out);
        return NULL;
    }
    if (ttd_py_raise_fatal(st, &opt) < 0) {
        Py_DECREF(out);
        return NULL;
    }
    return (PyObject *)out;
}

PyMethodDef ttd_py_points_methods[] = {
    {"closest_points", (PyCFunction)(void (*)(void))py_closest_points, METH_VARARGS | METH_KEYWORDS, closest_points_doc},
    {"signed_distance", (PyCFunction)(void (*)(void))py_signed_distance, METH_VARARGS | METH_KEYWORDS, signed_distance_doc},
    {"winding_number", (PyCFunction)(void (*)(void))py_winding_number, METH_VARARGS | METH_KEYWORDS, winding_number_doc},
    {"contains", (PyCFunction)(void (*)(void))py_contains, METH_VARARGS | METH_KEYWORDS, contains_doc},
    {"sdf_grid", (PyCFunction)(void (*)(void))py_sdf_grid, METH_VARARGS | METH_KEYWORDS, sdf_grid_doc},
    {NULL, NULL, 0, NULL},
};
