/* SPDX-License-Identifier: MIT */
/* ttd.Mesh and the mesh queries ttd.mesh_distance, mesh_contacts, mesh_closest and mesh_collide,
 * over the "Mesh queries" group of include/ttd/ttd.h.
 *
 * A Mesh owns a C ttd_mesh, built once with the interpreter lock released from private,
 * read-only copies of its arrays; the copies also serve its attributes and its pickling (an
 * unpickled Mesh is rebuilt from them, and the build is deterministic). Each query is one
 * library call over all K poses with the lock released, and its results are numpy views of the
 * library's own structs: record arrays the library writes into (distance, collision, closest
 * partners), or the contact buffer the library allocated, handed to numpy with a capsule that
 * frees it. Input errors are caught where the message can name the culprit (the vertex, the face
 * index, the pose); the library's checks stay the reference: a refused pose or parameter is
 * located after the library has refused it, by the rule the header documents. */
#include "ttd_py.h"
#include <ttd/meshfile.h>

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* ---- the Mesh type (its struct is in ttd_py.h: ttd.Scene's bodies refer to it) ------------ */

/* A one-triangle mesh in each precision: the queries' checks (options, instruction set,
 * parameters) are run on it for calls with no poses, so that errors do not depend on K. */
static ttd_mesh *ttd_py_probe_d, *ttd_py_probe_f;

/* A real that was a double, as the float the float entries take: beyond float's range it is
 * infinite (the conversion would be undefined in C). */
float ttd_py_to_float(double x)
{
    if (x > (double)FLT_MAX)
        return INFINITY;
    if (x < -(double)FLT_MAX)
        return -INFINITY;
    return (float)x;
}

/* "(x, y, z)" of three doubles, for messages; NULL with an exception. */
static PyObject *ttd_py_triple(double x, double y, double z)
{
    return Py_BuildValue("(ddd)", x, y, z);
}

/* vertices as a private C-contiguous copy of type (NPY_NOTYPE: from its dtype), checked: shape
 * (n, 3), a real dtype, n > 0, every coordinate finite. NULL with the exception that names the
 * problem. */
static PyArrayObject *ttd_py_mesh_vertices(PyObject *obj, int type, int *type_out)
{
    PyArrayObject *a = ttd_py_as_array(obj, "vertices"), *v = NULL;
    if (a == NULL)
        return NULL;
    if (PyArray_NDIM(a) != 2 || PyArray_DIM(a, 1) != 3) {
        PyObject *shape = ttd_py_shape(a);
        if (shape)
            PyErr_Format(PyExc_ValueError, "vertices has shape %R: a mesh's vertices are given as (n, 3) (x y z rows)",
                         shape);
        Py_XDECREF(shape);
        goto fail;
    }
    if (type == NPY_NOTYPE && (type = ttd_py_natural_type(a, "vertices")) < 0)
        goto fail;
    if ((v = ttd_py_as_real(a, "vertices", type)) == NULL)
        goto fail;
    if (v == a) {
        /* Used in place: copy, so that later changes to the caller's array do not reach the mesh.
         * (A plain copy: numpy's would hand the interpreter lock to other threads and back.) */
        Py_DECREF(v);
        if ((v = (PyArrayObject *)PyArray_SimpleNew(2, PyArray_DIMS(a), type)) == NULL)
            goto fail;
        memcpy(PyArray_DATA(v), PyArray_DATA(a), (size_t)PyArray_NBYTES(a));
    }
    const npy_intp n = PyArray_DIM(v, 0);
    if (n == 0) {
        PyErr_SetString(PyExc_ValueError, "vertices is empty: a mesh needs at least one vertex and one face");
        goto fail;
    }
    for (npy_intp i = 0; i < n; ++i) {
        double x[3];
        for (int c = 0; c < 3; ++c)
            x[c] = type == NPY_DOUBLE ? ((const double *)PyArray_DATA(v))[3 * i + c]
                                      : (double)((const float *)PyArray_DATA(v))[3 * i + c];
        if (isfinite(x[0]) && isfinite(x[1]) && isfinite(x[2]))
            continue;
        PyObject *row = ttd_py_triple(x[0], x[1], x[2]);
        if (row)
            PyErr_Format(PyExc_ValueError, "vertices[%zd] = %R is not finite: a mesh's coordinates must be finite",
                         (Py_ssize_t)i, row);
        Py_XDECREF(row);
        goto fail;
    }
    PyArray_CLEARFLAGS(v, NPY_ARRAY_WRITEABLE);
    Py_DECREF(a);
    *type_out = type;
    return v;
fail:
    Py_DECREF(a);
    Py_XDECREF(v);
    return NULL;
}

/* faces as a new (m, 3) uint32 array, checked: shape (m, 3), an integer dtype, m > 0, every
 * index in 0 .. nv - 1 and within 32 bits. NULL with the exception that names the face. */
static PyArrayObject *ttd_py_mesh_faces(PyObject *obj, npy_intp nv)
{
    PyArrayObject *a = ttd_py_as_array(obj, "faces"), *w = NULL, *out = NULL;
    if (a == NULL)
        return NULL;
    if (PyArray_NDIM(a) != 2 || PyArray_DIM(a, 1) != 3) {
        PyObject *shape = ttd_py_shape(a);
        if (shape)
            PyErr_Format(PyExc_ValueError,
                         "faces has shape %R: a mesh's faces are given as (m, 3) rows of vertex indices", shape);
        Py_XDECREF(shape);
        goto fail;
    }
    const char kind = PyArray_DESCR(a)->kind;
    if (kind != 'i' && kind != 'u') {
        PyErr_Format(PyExc_TypeError, "faces has dtype %S: faces are vertex indices, of an integer dtype",
                     (PyObject *)PyArray_DESCR(a));
        goto fail;
    }
    const int is_signed = kind == 'i';
    w = (PyArrayObject *)PyArray_FROM_OTF((PyObject *)a, is_signed ? NPY_INT64 : NPY_UINT64, NPY_ARRAY_CARRAY_RO);
    if (w == NULL)
        goto fail;
    const npy_intp m = PyArray_DIM(w, 0);
    if (m == 0) {
        PyErr_SetString(PyExc_ValueError, "faces is empty: a mesh needs at least one vertex and one face");
        goto fail;
    }
    npy_intp dims[2] = {m, 3};
    if ((out = (PyArrayObject *)PyArray_SimpleNew(2, dims, NPY_UINT32)) == NULL)
        goto fail;
    uint32_t *dst = PyArray_DATA(out);
    for (npy_intp i = 0; i < 3 * m; ++i) {
        const int64_t s = is_signed ? ((const int64_t *)PyArray_DATA(w))[i] : 0;
        const uint64_t u = is_signed ? (uint64_t)s : ((const uint64_t *)PyArray_DATA(w))[i];
        if (is_signed && s < 0) {
            PyErr_Format(PyExc_IndexError, "faces[%zd, %d] = %lld is negative: vertex indices start at 0",
                         (Py_ssize_t)(i / 3), (int)(i % 3), (long long)s);
            goto fail;
        }
        if (u >= (uint64_t)nv) {
            PyErr_Format(PyExc_IndexError,
                         "faces[%zd, %d] = %llu is out of range: the mesh has %zd vertices (indices 0 to %zd)",
                         (Py_ssize_t)(i / 3), (int)(i % 3), (unsigned long long)u, (Py_ssize_t)nv,
                         (Py_ssize_t)nv - 1);
            goto fail;
        }
        if (u > UINT32_MAX) {
            PyErr_Format(PyExc_ValueError,
                         "faces[%zd, %d] = %llu does not fit in 32 bits: ttd meshes index at most 2**32 vertices",
                         (Py_ssize_t)(i / 3), (int)(i % 3), (unsigned long long)u);
            goto fail;
        }
        dst[i] = (uint32_t)u;
    }
    PyArray_CLEARFLAGS(out, NPY_ARRAY_WRITEABLE);
    Py_DECREF(a);
    Py_DECREF(w);
    return out;
fail:
    Py_DECREF(a);
    Py_XDECREF(w);
    Py_XDECREF(out);
    return NULL;
}

PyDoc_STRVAR(ttd_py_mesh_doc,
"Mesh(vertices, faces, *, precision=None, threads=0)\n"
"--\n\n"
"A triangle mesh and its bounding-volume hierarchy: the operand of ttd.mesh_distance,\n"
"mesh_contacts, mesh_closest, mesh_collide and mesh_self_contacts. Its faces are fixed; its\n"
"vertices may move (set_vertices, for deforming meshes). Safe to share between threads (queries\n"
"only read it; set_vertices refuses to run during one).\n\n"
"vertices : array_like, shape (n, 3)\n"
"    Coordinates. float32 input gives a float32 mesh (queried in float32), float64 input a\n"
"    float64 mesh; integers and bools count as float64. Every coordinate must be finite.\n"
"faces : array_like, shape (m, 3), any integer dtype\n"
"    Vertex indices of each triangle, 0-based: each in 0 .. n - 1 (and within 32 bits).\n"
"    Degenerate triangles, repeated vertices and non-manifold meshes are fine.\n"
"precision : None, 'float32' or 'float64'\n"
"    None (default): from vertices' dtype, as above. 'float32' ('single', numpy.float32) or\n"
"    'float64' ('double', numpy.float64) converts the vertices to it.\n"
"threads : int\n"
"    Threads for building the hierarchy, >= 0; 0 (default) uses every core. The mesh built\n"
"    does not depend on it.\n\n"
"The arrays are copied (vertices into the mesh's dtype, faces into uint32), so later changes\n"
"to them do not reach the mesh; the interpreter lock is released while the hierarchy is\n"
"built. Attributes: vertices and faces (the read-only copies), dtype, vertex_count,\n"
"triangle_count, node_count (of the hierarchy). A Mesh pickles as its two arrays and is\n"
"rebuilt where it is unpickled (a Dask worker, say): the rebuilt mesh gives the same results\n"
"bit for bit.\n\n"
"Raises ValueError (a shape other than (n, 3) / (m, 3), no vertices or no faces, a NaN or\n"
"infinite coordinate or one beyond 2**60 in float32 / 2**508 in float64, naming the vertex;\n"
"an index beyond 32 bits), IndexError (a negative or\n"
"out-of-range index, naming the face), TypeError (vertices not real, faces not integers),\n"
"MemoryError.");

/* The mesh coordinate range (ttd.h): 2^60 in float, 2^508 in double. */

/* TTD_ERR_COORDINATE_RANGE from a build: names the first vertex beyond the range. */
static void ttd_py_raise_vertex_range(PyArrayObject *v, size_t nv, int type)
{
    const double limit = type == NPY_DOUBLE ? 0x1p508 : 0x1p60;
    for (size_t i = 0; i < nv; ++i) {
        double x[3];
        for (int c = 0; c < 3; ++c)
            x[c] = type == NPY_DOUBLE ? ((const double *)PyArray_DATA(v))[3 * i + c]
                                      : (double)((const float *)PyArray_DATA(v))[3 * i + c];
        if (fabs(x[0]) <= limit && fabs(x[1]) <= limit && fabs(x[2]) <= limit)
            continue;
        PyObject *p = Py_BuildValue("(ddd)", x[0], x[1], x[2]);
        if (p)
            PyErr_Format(PyExc_ValueError,
                         "vertices[%zu] = %R is beyond the mesh coordinate range: " TTD_PY_RANGE_TEXT
                         " (scale the meshes, or move them nearer the origin)",
                         i, p);
        Py_XDECREF(p);
        return;
    }
    PyErr_Format(PyExc_ValueError, "ttd: %s", ttd_status_string(TTD_ERR_COORDINATE_RANGE));
}

/* The exception for a status of a build or a vertex update from vertices v (nv rows of type t):
 * the vertex beyond the coordinate range, or the fatal status's. */
static void ttd_py_raise_vertices_status(ttd_status st, PyArrayObject *v, size_t nv, int t, const ttd_options *opt,
                                         const char *doing)
{
    if (st == TTD_ERR_COORDINATE_RANGE)
        ttd_py_raise_vertex_range(v, nv, t);
    else if (ttd_py_raise_fatal(st, opt) == 0)
        PyErr_Format(PyExc_SystemError, "ttd: unexpected status %d %s", (int)st, doing);
}

static PyObject *ttd_py_mesh_new(PyTypeObject *type, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = {"vertices", "faces", "precision", "threads", NULL};
    PyObject *v_obj, *f_obj, *precision = NULL, *threads = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OO|$OO:Mesh", kwlist, &v_obj, &f_obj, &precision, &threads))
        return NULL;
    ttd_options opt;
    int t;
    if (ttd_py_options(NULL, NULL, threads, NULL, NULL, NULL, &opt) < 0 || ttd_py_precision(precision, &t) < 0)
        return NULL;
    PyArrayObject *v = ttd_py_mesh_vertices(v_obj, t, &t);
    if (v == NULL)
        return NULL;
    PyArrayObject *f = ttd_py_mesh_faces(f_obj, PyArray_DIM(v, 0));
    if (f == NULL) {
        Py_DECREF(v);
        return NULL;
    }
    ttd_py_mesh *self = (ttd_py_mesh *)type->tp_alloc(type, 0);
    if (self == NULL) {
        Py_DECREF(v);
        Py_DECREF(f);
        return NULL;
    }
    self->vertices = v;
    self->faces = f;
    self->type = t;
    const size_t nv = (size_t)PyArray_DIM(v, 0), nt = (size_t)PyArray_DIM(f, 0);
    const void *vd = PyArray_DATA(v);
    const uint32_t *fd = PyArray_DATA(f);
    ttd_mesh *m = NULL;
    ttd_status st;
    Py_BEGIN_ALLOW_THREADS
    st = t == NPY_DOUBLE ? ttd_mesh_create_d(&opt, vd, nv, fd, nt, &m) : ttd_mesh_create_f(&opt, vd, nv, fd, nt, &m);
    Py_END_ALLOW_THREADS
    if (st != TTD_OK) {
        ttd_py_raise_vertices_status(st, v, nv, t, &opt, "building a mesh");
        Py_DECREF(self);
        return NULL;
    }
    self->mesh = m;
    return (PyObject *)self;
}

static void ttd_py_mesh_dealloc(PyObject *obj)
{
    ttd_py_mesh *self = (ttd_py_mesh *)obj;
    ttd_mesh_destroy(self->mesh);
    Py_XDECREF(self->vertices);
    Py_XDECREF(self->faces);
    Py_TYPE(obj)->tp_free(obj);
}

static PyObject *ttd_py_mesh_repr(PyObject *obj)
{
    const ttd_py_mesh *self = (const ttd_py_mesh *)obj;
    return PyUnicode_FromFormat("<ttd.Mesh: %zu vertices, %zu triangles, %s, %zu hierarchy nodes>",
                                ttd_mesh_vertex_count(self->mesh), ttd_mesh_triangle_count(self->mesh),
                                self->type == NPY_DOUBLE ? "float64" : "float32", ttd_mesh_node_count(self->mesh));
}

static PyObject *ttd_py_mesh_reduce(PyObject *obj, PyObject *unused)
{
    (void)unused;
    const ttd_py_mesh *self = (const ttd_py_mesh *)obj;
    return Py_BuildValue("O(OO)", (PyObject *)Py_TYPE(obj), (PyObject *)self->vertices, (PyObject *)self->faces);
}

static PyObject *ttd_py_mesh_get_vertices(PyObject *obj, void *closure)
{
    (void)closure;
    PyObject *v = (PyObject *)((ttd_py_mesh *)obj)->vertices;
    Py_INCREF(v);
    return v;
}

static PyObject *ttd_py_mesh_get_faces(PyObject *obj, void *closure)
{
    (void)closure;
    PyObject *f = (PyObject *)((ttd_py_mesh *)obj)->faces;
    Py_INCREF(f);
    return f;
}

static PyObject *ttd_py_mesh_get_dtype(PyObject *obj, void *closure)
{
    (void)closure;
    return (PyObject *)PyArray_DescrFromType(((ttd_py_mesh *)obj)->type);
}

int ttd_py_meshes_use(PyObject *const *objs, Py_ssize_t n)
{
    for (Py_ssize_t i = 0; i < n; ++i)
        if (PyObject_TypeCheck(objs[i], &ttd_py_MeshType) && ((ttd_py_mesh *)objs[i])->moving) {
            PyErr_SetString(PyExc_RuntimeError,
                            "a ttd.Mesh of this call is being moved by Mesh.set_vertices in another thread: a mesh "
                            "must not be queried while its vertices change");
            return -1;
        }
    for (Py_ssize_t i = 0; i < n; ++i)
        if (PyObject_TypeCheck(objs[i], &ttd_py_MeshType))
            ((ttd_py_mesh *)objs[i])->users++;
    return 0;
}

void ttd_py_meshes_release(PyObject *const *objs, Py_ssize_t n)
{
    for (Py_ssize_t i = 0; i < n; ++i)
        if (PyObject_TypeCheck(objs[i], &ttd_py_MeshType))
            ((ttd_py_mesh *)objs[i])->users--;
}

PyDoc_STRVAR(ttd_py_mesh_set_vertices_doc,
"set_vertices(vertices, *, threads=0)\n"
"--\n\n"
"Moves the mesh's vertices (a deforming mesh: cloth, soft bodies), its faces the same: the\n"
"hierarchy is refitted in place, much faster than building a new Mesh, and rebuilt when\n"
"refitting has degraded it (docs/mesh-queries.md, section 2b). Every query then answers for the\n"
"new positions exactly as for a mesh built from them; scenes holding this mesh move all its\n"
"bodies with it (their world boxes are updated on the scene's next call).\n\n"
"vertices : array_like, shape (n, 3), n = vertex_count\n"
"    The new coordinates, converted to the mesh's dtype and copied (mesh.vertices is then the\n"
"    new copy). Every coordinate finite and within the mesh coordinate range.\n"
"threads : int\n"
"    Threads for the refit, >= 0; 0 (default) uses every core. The result does not depend on it.\n\n"
"Not while the mesh is used by a query or a scene query running in another thread (and no\n"
"query on it starts until this returns): RuntimeError. ValueError for a shape other than\n"
"(vertex_count, 3), a NaN, infinite or out-of-range coordinate (naming the vertex); the mesh is\n"
"then as it was. The tree, unlike the answers, depends on the mesh's history: a pickled mesh is\n"
"rebuilt from its vertices, so the order of its contact sets may differ from this one's.");

static PyObject *ttd_py_mesh_set_vertices(PyObject *obj, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = {"vertices", "threads", NULL};
    ttd_py_mesh *self = (ttd_py_mesh *)obj;
    PyObject *v_obj, *threads = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O|$O:set_vertices", kwlist, &v_obj, &threads))
        return NULL;
    ttd_options opt;
    if (ttd_py_options(NULL, NULL, threads, NULL, NULL, NULL, &opt) < 0)
        return NULL;
    int t;
    PyArrayObject *v = ttd_py_mesh_vertices(v_obj, self->type, &t);
    if (v == NULL)
        return NULL;
    const size_t nv = ttd_mesh_vertex_count(self->mesh);
    if ((size_t)PyArray_DIM(v, 0) != nv) {
        PyErr_Format(PyExc_ValueError,
                     "vertices has %zd rows: the mesh has %zu vertices, and set_vertices moves them (its faces stay)",
                     (Py_ssize_t)PyArray_DIM(v, 0), nv);
        Py_DECREF(v);
        return NULL;
    }
    if (self->users > 0 || self->moving) {
        PyErr_SetString(PyExc_RuntimeError,
                        "this ttd.Mesh is in use by a query (or set_vertices) running in another thread: its vertices "
                        "must not change until that returns");
        Py_DECREF(v);
        return NULL;
    }
    ttd_mesh *m = self->mesh;
    const void *vd = PyArray_DATA(v);
    ttd_status st;
    self->moving = 1;
    Py_BEGIN_ALLOW_THREADS
    st = t == NPY_DOUBLE ? ttd_mesh_set_vertices_d(&opt, m, vd) : ttd_mesh_set_vertices_f(&opt, m, vd);
    Py_END_ALLOW_THREADS
    self->moving = 0;
    if (st != TTD_OK) {
        ttd_py_raise_vertices_status(st, v, nv, t, &opt, "moving a mesh's vertices");
        Py_DECREF(v);
        return NULL;
    }
    Py_SETREF(self->vertices, v);
    Py_RETURN_NONE;
}

static PyObject *ttd_py_mesh_get_refit(PyObject *obj, void *closure)
{
    ttd_mesh_refit_info info;
    if (ttd_mesh_get_refit_info(((ttd_py_mesh *)obj)->mesh, &info) != TTD_OK)
        return PyErr_NoMemory();
    return PyLong_FromUnsignedLongLong(((const char *)closure)[0] == 'g' ? info.generation : info.rebuilds);
}

static PyObject *ttd_py_mesh_get_count(PyObject *obj, void *closure)
{
    const ttd_mesh *m = ((ttd_py_mesh *)obj)->mesh;
    const char *which = closure;
    return PyLong_FromSize_t(which[0] == 'v' ? ttd_mesh_vertex_count(m)
                             : which[0] == 't' ? ttd_mesh_triangle_count(m)
                                               : ttd_mesh_node_count(m));
}

/* Mesh.orientation: ttd_mesh_orientation's name, computed with the interpreter lock released
 * and the mesh marked in use (set_vertices may not move it meanwhile). */
static PyObject *ttd_py_mesh_get_orientation(PyObject *obj, void *closure)
{
    (void)closure;
    if (ttd_py_meshes_use(&obj, 1) < 0)
        return NULL;
    const ttd_mesh *m = ((ttd_py_mesh *)obj)->mesh;
    ttd_orientation o = TTD_ORIENTATION_OPEN;
    ttd_status st;
    Py_BEGIN_ALLOW_THREADS
    st = ttd_mesh_orientation(m, &o);
    Py_END_ALLOW_THREADS
    ttd_py_meshes_release(&obj, 1);
    if (st != TTD_OK)
        return PyErr_NoMemory();
    return PyUnicode_FromString(ttd_orientation_string(o));
}

static PyGetSetDef ttd_py_mesh_getset[] = {
    {"vertices", ttd_py_mesh_get_vertices, NULL, "(n, 3) read-only copy of the vertices, in the mesh's dtype", NULL},
    {"faces", ttd_py_mesh_get_faces, NULL, "(m, 3) read-only copy of the faces, uint32", NULL},
    {"orientation", ttd_py_mesh_get_orientation, NULL,
     "'outward', 'inward' (closed, enclosing a positive or negative volume), 'inconsistent' (every edge on two "
     "triangles, some run the same way by both), 'open' (a boundary edge, or an edge on more than two), 'flat' "
     "(closed, no volume). Computed on each read. The inside the queries give a closed mesh is the same "
     "outward or inward (|winding number| >= 1/2)", NULL},
    {"dtype", ttd_py_mesh_get_dtype, NULL, "numpy.dtype float32 or float64: the precision of its queries", NULL},
    {"vertex_count", ttd_py_mesh_get_count, NULL, "number of vertices", "v"},
    {"triangle_count", ttd_py_mesh_get_count, NULL, "number of triangles (faces)", "t"},
    {"node_count", ttd_py_mesh_get_count, NULL, "nodes of its bounding-volume hierarchy (8 children each)", "n"},
    {"generation", ttd_py_mesh_get_refit, NULL, "set_vertices calls that moved the mesh (0 when built)", "g"},
    {"rebuilds", ttd_py_mesh_get_refit, NULL, "of those, the ones that rebuilt its hierarchy (it had degraded)", "r"},
    {NULL, NULL, NULL, NULL, NULL},
};

static PyObject *ttd_py_load_mesh(PyObject *self, PyObject *args, PyObject *kwargs);

/* Mesh.from_file(path, *, precision='float64', threads=0, strict=False, weld=None): the file read
 * by the library's reader (welded when asked), then the mesh built (the reader's precision is the
 * mesh's). */
static PyObject *ttd_py_mesh_from_file(PyObject *cls, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = {"path", "precision", "threads", "strict", "weld", NULL};
    PyObject *path, *threads = NULL, *weld = Py_None;
    const char *precision = "float64";
    int strict = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O|$sOpO:from_file", kwlist, &path, &precision, &threads, &strict,
                                     &weld))
        return NULL;
    PyObject *largs = Py_BuildValue("(O)", path), *lkw = Py_BuildValue("{s:s,s:O,s:O}", "precision", precision, "strict",
                                                                       strict ? Py_True : Py_False, "weld", weld);
    PyObject *read = largs && lkw ? ttd_py_load_mesh(NULL, largs, lkw) : NULL, *mesh = NULL;
    Py_XDECREF(largs);
    Py_XDECREF(lkw);
    if (read == NULL)
        return NULL;
    PyObject *margs = Py_BuildValue("(OO)", PyTuple_GET_ITEM(read, 0), PyTuple_GET_ITEM(read, 1));
    PyObject *mkw = threads != NULL ? Py_BuildValue("{s:s,s:O}", "precision", precision, "threads", threads)
                                    : Py_BuildValue("{s:s}", "precision", precision);
    if (margs != NULL && mkw != NULL)
        mesh = PyObject_Call(cls, margs, mkw);
    Py_XDECREF(margs);
    Py_XDECREF(mkw);
    Py_DECREF(read);
    return mesh;
}

static PyMethodDef ttd_py_mesh_type_methods[] = {
    {"__reduce__", ttd_py_mesh_reduce, METH_NOARGS, "Pickles as (vertices, faces); unpickling rebuilds the mesh."},
    {"set_vertices", (PyCFunction)(void (*)(void))ttd_py_mesh_set_vertices, METH_VARARGS | METH_KEYWORDS,
     ttd_py_mesh_set_vertices_doc},
    {"from_file", (PyCFunction)(void (*)(void))ttd_py_mesh_from_file, METH_CLASS | METH_VARARGS | METH_KEYWORDS,
     "from_file(path, *, precision='float64', threads=0, strict=False, weld=None)\n--\n\n"
     "The mesh in an OBJ, STL, PLY, OFF, glTF or 3MF file (ttd.load_mesh reads it), built in that\n"
     "precision; with\n"
     "weld=tol its vertices within tol merged first (ttd.weld), as an STL file needs to be closed."},
    {NULL, NULL, 0, NULL},
};

PyTypeObject ttd_py_MeshType = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "ttd.Mesh",
    .tp_basicsize = sizeof(ttd_py_mesh),
    .tp_dealloc = ttd_py_mesh_dealloc,
    .tp_repr = ttd_py_mesh_repr,
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = ttd_py_mesh_doc,
    .tp_methods = ttd_py_mesh_type_methods,
    .tp_getset = ttd_py_mesh_getset,
    .tp_new = ttd_py_mesh_new,
};

/* ---- result types and record dtypes ------------------------------------------------------ */

enum { TTD_PY_NDIST = 10, TTD_PY_NCOLL = 5, TTD_PY_NCONT = 7, TTD_PY_NCLOSE = 4, TTD_PY_NPAIR = 2, TTD_PY_NSELF = 5,
       TTD_PY_NSCOLL = 3 };

static PyStructSequence_Field ttd_py_distance_fields[TTD_PY_NDIST + 1] = {
    {"distance", "minimum distance per pose, shape (K,); 0 when the meshes touch or cross; inf with MeshFlag.ABOVE_BOUND"},
    {"p", "closest point on a, in a's frame, shape (K, 3)"},
    {"q", "closest point on b, in a's frame, shape (K, 3); equal to p when the distance is 0"},
    {"tri_a", "uint32: the triangle of a that realises the minimum (ttd.NO_TRIANGLE with MeshFlag.ABOVE_BOUND)"},
    {"tri_b", "uint32: the triangle of b"},
    {"feature_a", "uint8: vertex bits of tri_a that p lies on (1 bit: a vertex, 2: an edge, 3: the face)"},
    {"feature_b", "uint8: vertex bits of tri_b that q lies on"},
    {"flags", "uint16: ttd.MeshFlag bits (INTERSECTING, ABOVE_BOUND)"},
    {"node_tests", "uint32: box-against-node tests made"},
    {"pair_tests", "uint64: triangle pairs given to the exact method"},
    {NULL, NULL},
};
static PyStructSequence_Desc ttd_py_distance_desc = {
    "ttd.MeshDistance",
    "The result of ttd.mesh_distance: a named tuple of arrays over the K poses (numpy scalars and\n"
    "(3,) points for a single pose), the fields of the C library's ttd_mesh_result_d/_f in its\n"
    "order. The arrays are views of one record array (ttd.MESH_RESULT_DTYPE_FLOAT64 / FLOAT32).",
    ttd_py_distance_fields, TTD_PY_NDIST,
};

static PyStructSequence_Field ttd_py_collision_fields[TTD_PY_NCOLL + 1] = {
    {"hit", "bool per pose, shape (K,): some triangle pair is within the margin"},
    {"tri_a", "uint32: a triangle of a of the first such pair found (ttd.NO_TRIANGLE when none)"},
    {"tri_b", "uint32: its partner in b"},
    {"node_tests", "uint32: box-against-node tests made"},
    {"pair_tests", "uint64: triangle pairs given to the exact method"},
    {NULL, NULL},
};
static PyStructSequence_Desc ttd_py_collision_desc = {
    "ttd.MeshCollision",
    "The result of ttd.mesh_collide: a named tuple of arrays over the K poses (numpy scalars for\n"
    "a single pose). hit is a new bool array; the others are views of the C library's\n"
    "ttd_collision records (ttd.COLLISION_DTYPE).",
    ttd_py_collision_fields, TTD_PY_NCOLL,
};

static PyStructSequence_Field ttd_py_contacts_fields[TTD_PY_NCONT + 1] = {
    {"pose", "intp, shape (n,): the pose index of each contact (nondecreasing)"},
    {"tri_a", "uint32, shape (n,): the triangle of a"},
    {"tri_b", "uint32, shape (n,): the triangle of b"},
    {"distance", "shape (n,): the pair's distance, <= margin"},
    {"p", "shape (n, 3): closest point on tri_a, in a's frame"},
    {"q", "shape (n, 3): closest point on tri_b, in a's frame; equal to p at distance 0"},
    {"pose_start", "intp, shape (K + 1,): the contacts of pose k are [pose_start[k], pose_start[k + 1])"},
    {NULL, NULL},
};
static PyStructSequence_Desc ttd_py_contacts_desc = {
    "ttd.MeshContacts",
    "The result of ttd.mesh_contacts: every triangle pair within the margin, under all K poses,\n"
    "as parallel arrays of n contacts, pose by pose (in an order that depends only on the meshes\n"
    "and the pose), with each contact's pose index and the offsets pose_start. tri_a, tri_b,\n"
    "distance, p and q are views of the C library's own contact buffer (ttd.CONTACT_DTYPE_*).",
    ttd_py_contacts_fields, TTD_PY_NCONT,
};

static PyStructSequence_Field ttd_py_self_fields[TTD_PY_NSELF + 1] = {
    {"tri_i", "uint32, shape (n,): the first triangle of each pair"},
    {"tri_j", "uint32, shape (n,): the second, tri_i < tri_j"},
    {"distance", "shape (n,): the pair's distance, <= margin (for a pair sharing a vertex: away from it)"},
    {"p", "shape (n, 3): closest point on tri_i"},
    {"q", "shape (n, 3): closest point on tri_j; equal to p at distance 0"},
    {NULL, NULL},
};

static PyStructSequence_Desc ttd_py_self_desc = {
    "ttd.SelfContacts",
    "The result of ttd.mesh_self_contacts: every pair of one mesh's triangles within the margin\n"
    "that shares no vertex (with shared_vertex=True also those sharing one, by their edges\n"
    "opposite it), as parallel arrays in an order that depends only on the mesh; views of the C\n"
    "library's own contact buffer (ttd.CONTACT_DTYPE_*, whose tri_a and tri_b are tri_i, tri_j).",
    ttd_py_self_fields, TTD_PY_NSELF,
};

static PyStructSequence_Field ttd_py_scoll_fields[TTD_PY_NSCOLL + 1] = {
    {"hit", "bool: some pair is within the margin (margin 0: the mesh intersects itself)"},
    {"tri_i", "int: the first triangle of the first such pair found (ttd.NO_TRIANGLE when none)"},
    {"tri_j", "int: the second, tri_i < tri_j"},
    {NULL, NULL},
};

static PyStructSequence_Desc ttd_py_scoll_desc = {
    "ttd.SelfCollision",
    "The result of ttd.mesh_self_collide: whether one mesh comes within the margin of itself, by\n"
    "the pairs of ttd.mesh_self_contacts, with the first pair found (a witness that depends only on\n"
    "the mesh).",
    ttd_py_scoll_fields, TTD_PY_NSCOLL,
};

static PyStructSequence_Field ttd_py_partners_fields[TTD_PY_NCLOSE + 1] = {
    {"partner", "uint32, shape (K, m): the closest triangle of the other mesh within the margin (ttd.NO_TRIANGLE when none)"},
    {"distance", "shape (K, m): its distance (inf when none)"},
    {"p", "shape (K, m, 3): closest point on this mesh's triangle, in a's frame (NaN when none)"},
    {"q", "shape (K, m, 3): closest point on the partner, in a's frame (NaN when none)"},
    {NULL, NULL},
};
static PyStructSequence_Desc ttd_py_partners_desc = {
    "ttd.ClosestPartners",
    "For every triangle of one mesh under each pose, its closest partner in the other mesh within\n"
    "the margin: arrays of shape (K, m) ((m,) for a single pose), m the mesh's triangle count.\n"
    "Views of the C library's ttd_closest_d/_f records (ttd.CLOSEST_DTYPE_*). Ties go to the\n"
    "smaller partner index.",
    ttd_py_partners_fields, TTD_PY_NCLOSE,
};

static PyStructSequence_Field ttd_py_closest_fields[TTD_PY_NPAIR + 1] = {
    {"for_a", "ttd.ClosestPartners of a's triangles (partners in b), or None when for_a=False"},
    {"for_b", "ttd.ClosestPartners of b's triangles (partners in a), or None when for_b=False"},
    {NULL, NULL},
};
static PyStructSequence_Desc ttd_py_closest_desc = {
    "ttd.MeshClosest",
    "The result of ttd.mesh_closest: for_a and for_b, each a ttd.ClosestPartners (or None).",
    ttd_py_closest_fields, TTD_PY_NPAIR,
};

static PyTypeObject *ttd_py_SelfContacts, *ttd_py_SelfCollision;
static PyObject *ttd_py_self_names[TTD_PY_NSELF], *ttd_py_scoll_names[TTD_PY_NSCOLL];
static PyTypeObject *ttd_py_MeshDistance, *ttd_py_MeshCollision, *ttd_py_MeshContacts, *ttd_py_ClosestPartners,
    *ttd_py_MeshClosest;
static PyObject *ttd_py_distance_names[TTD_PY_NDIST], *ttd_py_collision_names[TTD_PY_NCOLL],
    *ttd_py_contacts_names[TTD_PY_NCONT], *ttd_py_partners_names[TTD_PY_NCLOSE], *ttd_py_closest_names[TTD_PY_NPAIR];
/* The records: [0] float64, [1] float32 (the collision record has no reals). */
static PyArray_Descr *ttd_py_dist_rec[2], *ttd_py_coll_rec, *ttd_py_cont_rec[2], *ttd_py_close_rec[2];

static int ttd_py_add(PyObject *module, const char *name, PyObject *obj)
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

#define TTD_PY_DIST_OFFSETS(T)                                                                   \
    {offsetof(T, distance), offsetof(T, p), offsetof(T, q), offsetof(T, tri_a), offsetof(T, tri_b), \
     offsetof(T, feature_a), offsetof(T, feature_b), offsetof(T, flags), offsetof(T, node_tests), \
     offsetof(T, pair_tests)}
#define TTD_PY_CONT_OFFSETS(T) {offsetof(T, tri_a), offsetof(T, tri_b), offsetof(T, distance), offsetof(T, p), offsetof(T, q)}
#define TTD_PY_CLOSE_OFFSETS(T) {offsetof(T, partner), offsetof(T, distance), offsetof(T, p), offsetof(T, q)}

static int ttd_py_make_records(PyObject *module)
{
    static const size_t dist_off[2][TTD_PY_NDIST] = {TTD_PY_DIST_OFFSETS(ttd_mesh_result_d),
                                                     TTD_PY_DIST_OFFSETS(ttd_mesh_result_f)};
    static const size_t cont_off[2][5] = {TTD_PY_CONT_OFFSETS(ttd_contact_d), TTD_PY_CONT_OFFSETS(ttd_contact_f)};
    static const size_t close_off[2][TTD_PY_NCLOSE] = {TTD_PY_CLOSE_OFFSETS(ttd_closest_d),
                                                       TTD_PY_CLOSE_OFFSETS(ttd_closest_f)};
    static const size_t coll_off[TTD_PY_NCOLL] = {offsetof(ttd_collision, hit), offsetof(ttd_collision, tri_a),
                                                  offsetof(ttd_collision, tri_b), offsetof(ttd_collision, node_tests),
                                                  offsetof(ttd_collision, pair_tests)};
    static const size_t dist_size[2] = {sizeof(ttd_mesh_result_d), sizeof(ttd_mesh_result_f)};
    static const size_t cont_size[2] = {sizeof(ttd_contact_d), sizeof(ttd_contact_f)};
    static const size_t close_size[2] = {sizeof(ttd_closest_d), sizeof(ttd_closest_f)};
    static const char *const reals[2] = {"f8", "f4"}, *const vecs[2] = {"(3,)f8", "(3,)f4"};
    static const char *const suffix[2] = {"FLOAT64", "FLOAT32"};
    for (int i = 0; i < 2; ++i) {
        const char *dist_fmt[TTD_PY_NDIST] = {reals[i], vecs[i], vecs[i], "u4", "u4", "u1", "u1", "u2", "u4", "u8"};
        const char *cont_fmt[5] = {"u4", "u4", reals[i], vecs[i], vecs[i]};
        const char *close_fmt[TTD_PY_NCLOSE] = {"u4", reals[i], vecs[i], vecs[i]};
        ttd_py_dist_rec[i] = ttd_py_record_descr(TTD_PY_NDIST, ttd_py_distance_names, dist_fmt, dist_off[i], dist_size[i]);
        ttd_py_cont_rec[i] = ttd_py_record_descr(5, ttd_py_contacts_names + 1, cont_fmt, cont_off[i], cont_size[i]);
        ttd_py_close_rec[i] =
            ttd_py_record_descr(TTD_PY_NCLOSE, ttd_py_partners_names, close_fmt, close_off[i], close_size[i]);
        char name[64];
        PyOS_snprintf(name, sizeof name, "MESH_RESULT_DTYPE_%s", suffix[i]);
        if (ttd_py_add(module, name, (PyObject *)ttd_py_dist_rec[i]) < 0)
            return -1;
        PyOS_snprintf(name, sizeof name, "CONTACT_DTYPE_%s", suffix[i]);
        if (ttd_py_add(module, name, (PyObject *)ttd_py_cont_rec[i]) < 0)
            return -1;
        PyOS_snprintf(name, sizeof name, "CLOSEST_DTYPE_%s", suffix[i]);
        if (ttd_py_add(module, name, (PyObject *)ttd_py_close_rec[i]) < 0)
            return -1;
    }
    const char *coll_fmt[TTD_PY_NCOLL] = {"u4", "u4", "u4", "u4", "u8"};
    ttd_py_coll_rec = ttd_py_record_descr(TTD_PY_NCOLL, ttd_py_collision_names, coll_fmt, coll_off, sizeof(ttd_collision));
    return ttd_py_add(module, "COLLISION_DTYPE", (PyObject *)ttd_py_coll_rec);
}

int ttd_py_mesh_init(PyObject *module)
{
    if (PyType_Ready(&ttd_py_MeshType) < 0 || ttd_py_add(module, "Mesh", (PyObject *)&ttd_py_MeshType) < 0)
        return -1;
    if (!(ttd_py_MeshDistance = ttd_py_named_tuple(module, &ttd_py_distance_desc, ttd_py_distance_names)) ||
        !(ttd_py_MeshCollision = ttd_py_named_tuple(module, &ttd_py_collision_desc, ttd_py_collision_names)) ||
        !(ttd_py_MeshContacts = ttd_py_named_tuple(module, &ttd_py_contacts_desc, ttd_py_contacts_names)) ||
        !(ttd_py_ClosestPartners = ttd_py_named_tuple(module, &ttd_py_partners_desc, ttd_py_partners_names)) ||
        !(ttd_py_MeshClosest = ttd_py_named_tuple(module, &ttd_py_closest_desc, ttd_py_closest_names)) ||
        !(ttd_py_SelfContacts = ttd_py_named_tuple(module, &ttd_py_self_desc, ttd_py_self_names)) ||
        !(ttd_py_SelfCollision = ttd_py_named_tuple(module, &ttd_py_scoll_desc, ttd_py_scoll_names)))
        return -1;
    if (ttd_py_make_records(module) < 0)
        return -1;
    if (PyModule_AddIntConstant(module, "MESH_INTERSECTING", TTD_MESH_INTERSECTING) < 0 ||
        PyModule_AddIntConstant(module, "MESH_ABOVE_BOUND", TTD_MESH_ABOVE_BOUND) < 0 ||
        PyModule_AddIntConstant(module, "MESH_CONTAINED", TTD_MESH_CONTAINED) < 0 ||
        ttd_py_add(module, "NO_TRIANGLE", PyLong_FromUnsignedLong(UINT32_MAX)) < 0)
        return -1;
    /* The probes: one triangle, built with options that cannot fail (TTD_ISA is not read). */
    static const double vd[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    static const float vf[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    static const uint32_t tri[3] = {0, 1, 2};
    ttd_options o = ttd_default_options();
    o.isa = TTD_ISA_SCALAR;
    o.threads = 1;
    if (ttd_py_probe_d == NULL && ttd_mesh_create_d(&o, vd, 3, tri, 1, &ttd_py_probe_d) != TTD_OK)
        ttd_py_probe_d = NULL;
    if (ttd_py_probe_f == NULL && ttd_mesh_create_f(&o, vf, 3, tri, 1, &ttd_py_probe_f) != TTD_OK)
        ttd_py_probe_f = NULL;
    if (ttd_py_probe_d == NULL || ttd_py_probe_f == NULL) {
        PyErr_SetString(PyExc_RuntimeError, "ttd: could not build the one-triangle meshes the mesh queries check with");
        return -1;
    }
    return 0;
}

/* ---- the queries: arguments ------------------------------------------------------------- */

typedef enum ttd_py_kind { TTD_PY_DISTANCE, TTD_PY_CONTACTS, TTD_PY_CLOSEST, TTD_PY_COLLIDE } ttd_py_kind;

/* What every query takes, checked and converted. */
typedef struct ttd_py_query {
    const ttd_py_mesh *a, *b;
    int type;             /* the meshes' NPY_DOUBLE or NPY_FLOAT */
    ttd_options opt;
    PyArrayObject *poses; /* k poses of 12 reals [R | t], C-contiguous, of type (owned) */
    npy_intp k;
    int single;           /* one pose given as (3, 4) or (4, 4): results drop the K axis */
} ttd_py_query;

/* poses to q->poses, q->k, q->single; -1 with the exception that names the problem. */
static int ttd_py_poses(PyObject *obj, ttd_py_query *q)
{
    PyArrayObject *a = ttd_py_as_array(obj, "poses"), *p = NULL;
    if (a == NULL)
        return -1;
    const int nd = PyArray_NDIM(a);
    const npy_intp rows = nd >= 2 ? PyArray_DIM(a, nd - 2) : 0;
    if (!((nd == 2 || nd == 3) && (rows == 3 || rows == 4) && PyArray_DIM(a, nd - 1) == 4)) {
        PyObject *shape = ttd_py_shape(a);
        if (shape)
            PyErr_Format(PyExc_ValueError,
                         "poses has shape %R: poses are given as (K, 4, 4) homogeneous or (K, 3, 4) [R | t] "
                         "arrays, or one (4, 4) / (3, 4) pose",
                         shape);
        Py_XDECREF(shape);
        goto fail;
    }
    q->single = nd == 2;
    q->k = nd == 3 ? PyArray_DIM(a, 0) : 1;
    if ((p = ttd_py_as_real(a, "poses", q->type)) == NULL)
        goto fail;
    if (rows == 4) {
        /* the bottom rows, then the top three rows of each pose into a compact (k, 3, 4) array */
        const size_t bytes = q->type == NPY_DOUBLE ? sizeof(double) : sizeof(float);
        for (npy_intp i = 0; i < q->k; ++i) {
            double r[4];
            for (int c = 0; c < 4; ++c)
                r[c] = q->type == NPY_DOUBLE ? ((const double *)PyArray_DATA(p))[16 * i + 12 + c]
                                             : (double)((const float *)PyArray_DATA(p))[16 * i + 12 + c];
            if (r[0] == 0 && r[1] == 0 && r[2] == 0 && r[3] == 1)
                continue;
            PyObject *row = Py_BuildValue("(dddd)", r[0], r[1], r[2], r[3]), *name = q->single
                ? PyUnicode_FromString("poses") : PyUnicode_FromFormat("poses[%zd]", (Py_ssize_t)i);
            if (row && name)
                PyErr_Format(PyExc_ValueError, "%U has bottom row %R: the last row of a 4x4 pose must be 0 0 0 1",
                             name, row);
            Py_XDECREF(row);
            Py_XDECREF(name);
            goto fail;
        }
        npy_intp dims[3] = {q->k, 3, 4};
        PyArrayObject *c = (PyArrayObject *)PyArray_SimpleNew(3, dims, q->type);
        if (c == NULL)
            goto fail;
        for (npy_intp i = 0; i < q->k; ++i)
            memcpy((char *)PyArray_DATA(c) + (size_t)i * 12 * bytes, (const char *)PyArray_DATA(p) + (size_t)i * 16 * bytes,
                   12 * bytes);
        Py_DECREF(p);
        p = c;
    }
    Py_DECREF(a);
    q->poses = p;
    return 0;
fail:
    Py_DECREF(a);
    Py_XDECREF(p);
    return -1;
}

/* a, b, poses and the options of every query into q (q->poses owned on success). */
static int ttd_py_query_begin(PyObject *a, PyObject *b, PyObject *poses, PyObject *isa, PyObject *threads,
                              ttd_py_query *q)
{
    memset(q, 0, sizeof *q);
    if (!PyObject_TypeCheck(a, &ttd_py_MeshType) || !PyObject_TypeCheck(b, &ttd_py_MeshType)) {
        PyObject *bad = PyObject_TypeCheck(a, &ttd_py_MeshType) ? b : a;
        PyErr_Format(PyExc_TypeError, "%s must be a ttd.Mesh, not %.100s", bad == a ? "a" : "b", Py_TYPE(bad)->tp_name);
        return -1;
    }
    q->a = (const ttd_py_mesh *)a;
    q->b = (const ttd_py_mesh *)b;
    if (q->a->type != q->b->type) {
        PyErr_Format(PyExc_TypeError,
                     "a is a %s mesh and b a %s mesh: a query computes in one precision; build both from "
                     "arrays of one dtype (or pass precision= to ttd.Mesh)",
                     q->a->type == NPY_DOUBLE ? "float64" : "float32", q->b->type == NPY_DOUBLE ? "float64" : "float32");
        return -1;
    }
    q->type = q->a->type;
    if (ttd_py_options(NULL, isa, threads, NULL, NULL, NULL, &q->opt) < 0)
        return -1;
    return ttd_py_poses(poses, q);
}

/* ---- the queries: library calls and their statuses ---------------------------------------- */

/* One library call of kind on k poses (x, y: margin, or upper_bound and rel_tol; converted to
 * float for float meshes). out: the records (closest: for_a), or a ttd_contacts_d/_f. */
static ttd_status ttd_py_call(ttd_py_kind kind, const ttd_options *opt, int type, const ttd_mesh *a, const ttd_mesh *b,
                              size_t k, const void *poses, double x, double y, void *out, void *out2)
{
    const int d = type == NPY_DOUBLE;
    const float xf = ttd_py_to_float(x), yf = ttd_py_to_float(y);
    switch (kind) {
    case TTD_PY_DISTANCE:
        return d ? ttd_mesh_distance_d(opt, a, b, k, poses, x, y, out) : ttd_mesh_distance_f(opt, a, b, k, poses, xf, yf, out);
    case TTD_PY_CONTACTS:
        return d ? ttd_mesh_contacts_d(opt, a, b, k, poses, x, out) : ttd_mesh_contacts_f(opt, a, b, k, poses, xf, out);
    case TTD_PY_CLOSEST:
        return d ? ttd_mesh_closest_d(opt, a, b, k, poses, x, out, out2)
                 : ttd_mesh_closest_f(opt, a, b, k, poses, xf, out, out2);
    case TTD_PY_COLLIDE:
        return d ? ttd_mesh_collide_d(opt, a, b, k, poses, x, out) : ttd_mesh_collide_f(opt, a, b, k, poses, xf, out);
    }
    return TTD_ERR_BAD_OPTIONS;
}

/* The status of a one-pose call of kind on the probe triangle: the library's checks of the
 * options, the instruction set and the parameters, without the caller's meshes and poses. */
static ttd_status ttd_py_probe(ttd_py_kind kind, const ttd_options *opt, int type, double x, double y)
{
    static const double pd[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    static const float pf[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    const int d = type == NPY_DOUBLE;
    union {
        ttd_mesh_result_d rd;
        ttd_mesh_result_f rf;
        ttd_collision c;
        ttd_closest_d cd;
        ttd_closest_f cf;
        ttd_contacts_d sd;
        ttd_contacts_f sf;
    } out;
    memset(&out, 0, sizeof out);
    ttd_options o = *opt;
    o.solid = 0; /* the probe's meshes are not closed; the real ones are checked by the query */
    opt = &o;
    ttd_status st = ttd_py_call(kind, opt, type, d ? ttd_py_probe_d : ttd_py_probe_f, d ? ttd_py_probe_d : ttd_py_probe_f,
                                1, d ? (const void *)pd : (const void *)pf, x, y, &out, NULL);
    if (kind == TTD_PY_CONTACTS) {
        if (d)
            ttd_contacts_free_d(&out.sd);
        else
            ttd_contacts_free_f(&out.sf);
    }
    return st;
}

/* Names the first pose that is not a rigid motion by the rule of include/ttd/ttd.h (finite; R^T R
 * - I within 1e-6 entry by entry; det R > 0), as a ValueError. */
static void ttd_py_raise_bad_pose(const ttd_py_query *q)
{
    for (npy_intp i = 0; i < q->k; ++i) {
        double p[12];
        int finite = 1;
        for (int j = 0; j < 12; ++j) {
            p[j] = q->type == NPY_DOUBLE ? ((const double *)PyArray_DATA(q->poses))[12 * i + j]
                                         : (double)((const float *)PyArray_DATA(q->poses))[12 * i + j];
            finite &= isfinite(p[j]) != 0;
        }
        const double r[9] = {p[0], p[1], p[2], p[4], p[5], p[6], p[8], p[9], p[10]};
        double defect = 0;
        for (int u = 0; u < 3; ++u)
            for (int v = 0; v < 3; ++v)
                defect = fmax(defect, fabs(r[u] * r[v] + r[3 + u] * r[3 + v] + r[6 + u] * r[6 + v] - (u == v ? 1.0 : 0.0)));
        const double det = r[0] * (r[4] * r[8] - r[5] * r[7]) - r[1] * (r[3] * r[8] - r[5] * r[6]) +
                           r[2] * (r[3] * r[7] - r[4] * r[6]);
        if (finite && det > 0 && defect <= 1e-6)
            continue;
        PyObject *name = q->single ? PyUnicode_FromString("poses") : PyUnicode_FromFormat("poses[%zd]", (Py_ssize_t)i);
        PyObject *value = PyFloat_FromDouble(finite && !(det > 0) ? det : defect);
        if (name && value) {
            if (!finite)
                PyErr_Format(PyExc_ValueError,
                             "%U has a NaN or infinite entry: a pose is a finite rotation R and translation t", name);
            else if (!(det > 0))
                PyErr_Format(PyExc_ValueError,
                             "%U is not a rotation: det R = %R (a reflection or a singular matrix; a pose is a "
                             "rotation R and translation t)",
                             name, value);
            else
                PyErr_Format(PyExc_ValueError,
                             "%U is not a rotation within 1e-6: an entry of R^T R - I is %R (ttd takes rigid "
                             "motions; orthonormalise R, e.g. with numpy.linalg.svd)",
                             name, value);
        }
        Py_XDECREF(name);
        Py_XDECREF(value);
        return;
    }
    PyErr_Format(PyExc_ValueError, "ttd: %s", ttd_status_string(TTD_ERR_BAD_POSE));
}

/* TTD_ERR_COORDINATE_RANGE from a query: names the pose that moves b beyond the range. */
static void ttd_py_raise_pose_range(const ttd_py_query *q)
{
    size_t bad = (size_t)q->k;
    const void *poses = PyArray_DATA(q->poses);
    if (q->type == NPY_DOUBLE)
        ttd_mesh_check_poses_d(q->a->mesh, q->b->mesh, (size_t)q->k, poses, &bad);
    else
        ttd_mesh_check_poses_f(q->a->mesh, q->b->mesh, (size_t)q->k, poses, &bad);
    if (bad >= (size_t)q->k) {
        PyErr_Format(PyExc_ValueError, "ttd: %s", ttd_status_string(TTD_ERR_COORDINATE_RANGE));
        return;
    }
    PyObject *name = q->single ? PyUnicode_FromString("poses") : PyUnicode_FromFormat("poses[%zu]", bad);
    if (name)
        PyErr_Format(PyExc_ValueError,
                     "%U moves mesh b beyond the mesh coordinate range: " TTD_PY_RANGE_TEXT
                     " for every vertex of b after the pose",
                     name);
    Py_XDECREF(name);
}

/* "margin=..." or the like refused by the library: names it with its range. */
static void ttd_py_raise_bad_param(const char *what, double x, int type, const char *range)
{
    PyObject *v = PyFloat_FromDouble(x);
    if (v == NULL)
        return;
    const int overflow = type == NPY_FLOAT && isfinite(x) && isinf(ttd_py_to_float(x));
    PyErr_Format(PyExc_ValueError, "%s=%R is out of range: %s%s", what, v, range,
                 overflow ? " (it overflows float32, the meshes' precision)" : "");
    Py_DECREF(v);
}

/* For a status other than TTD_OK: the exception that names the problem; returns -1. */
static int ttd_py_query_raise(ttd_status st, ttd_py_kind kind, const ttd_py_query *q, double x, double y)
{
    if (st == TTD_PY_IN_USE || st == TTD_PY_INTERRUPTED) /* raised already */
        return -1;
    switch (st) {
    case TTD_ERR_BAD_POSE:
        ttd_py_raise_bad_pose(q);
        return -1;
    case TTD_ERR_COORDINATE_RANGE:
        ttd_py_raise_pose_range(q);
        return -1;
    case TTD_ERR_MESH_NOT_CLOSED: { /* name the mesh, and what it is */
        ttd_orientation oa = TTD_ORIENTATION_OUTWARD, ob = TTD_ORIENTATION_OUTWARD;
        (void)ttd_mesh_orientation(q->a->mesh, &oa);
        (void)ttd_mesh_orientation(q->b->mesh, &ob);
        const int bad_a = oa == TTD_ORIENTATION_OPEN || oa == TTD_ORIENTATION_INCONSISTENT;
        PyErr_Format(PyExc_ValueError, "ttd: solid=True needs closed meshes: mesh %s is %s (Mesh.orientation '%s'): %s",
                     bad_a ? "a" : "b",
                     (bad_a ? oa : ob) == TTD_ORIENTATION_INCONSISTENT ? "inconsistently oriented" : "open",
                     ttd_orientation_string(bad_a ? oa : ob), ttd_status_string(st));
        return -1;
    }
    case TTD_ERR_BAD_OPTIONS:
        if (ttd_py_check_options(&q->opt) == TTD_ERR_BAD_OPTIONS) /* threads */
            return ttd_py_raise_fatal(st, &q->opt);
        if (kind != TTD_PY_DISTANCE)
            ttd_py_raise_bad_param("margin", x, q->type, "a margin is finite and >= 0");
        else if (ttd_py_probe(kind, &q->opt, q->type, x, 0) == TTD_ERR_BAD_OPTIONS)
            ttd_py_raise_bad_param("upper_bound", x, q->type, "upper_bound >= 0 (math.inf for none)");
        else
            ttd_py_raise_bad_param("rel_tol", y, q->type, "rel_tol is finite and >= 0");
        return -1;
    default:
        if (ttd_py_raise_fatal(st, &q->opt) == 0)
            PyErr_Format(PyExc_SystemError, "ttd: unexpected status %d from a mesh query", (int)st);
        return -1;
    }
}

/* Poses [b, e) of a query: one library call on them, its outputs at their offsets. */
typedef struct ttd_py_pose_piece {
    ttd_py_kind kind;
    const ttd_py_query *q;
    double x, y;
    void *out, *out2;
    size_t pose_stride, out_stride, out2_stride; /* bytes per pose */
} ttd_py_pose_piece;

static ttd_status ttd_py_pose_piece_run(void *ctx, size_t b, size_t e)
{
    const ttd_py_pose_piece *c = ctx;
    const ttd_py_query *q = c->q;
    const char *poses = (const char *)PyArray_DATA(q->poses) + b * c->pose_stride;
    void *out = c->out ? (char *)c->out + b * c->out_stride : NULL;
    void *out2 = c->out2 ? (char *)c->out2 + b * c->out2_stride : NULL;
    return ttd_py_call(c->kind, &q->opt, q->type, q->a->mesh, q->b->mesh, e - b, poses, c->x, c->y, out, out2);
}

/* mesh_contacts' poses in pieces: the first piece straight into set (the library's memory, which
 * the result views without a copy: a call of up to 16 poses is one piece); each later piece into
 * scratch, reused, and appended to tail (malloc'd). starts: every pose's offset, k + 1. A pose's
 * contacts and their order depend on that pose alone (ttd.h), so pieces change no answer. */
typedef struct ttd_py_contact_pieces {
    void *set, *scratch;   /* ttd_contacts_d or _f */
    int f;
    char *tail;
    size_t tail_n, tail_cap;
    size_t *starts;
    const ttd_py_query *q;
    double margin;
} ttd_py_contact_pieces;

static ttd_status ttd_py_contact_piece_run(void *ctx, size_t b, size_t e)
{
    ttd_py_contact_pieces *c = ctx;
    const ttd_py_query *q = c->q;
    const size_t elem = c->f ? sizeof(ttd_contact_f) : sizeof(ttd_contact_d);
    const char *poses = (const char *)PyArray_DATA(q->poses) + b * 12 * (c->f ? sizeof(float) : sizeof(double));
    void *into = b == 0 ? c->set : c->scratch;
    const ttd_status st = ttd_py_call(TTD_PY_CONTACTS, &q->opt, q->type, q->a->mesh, q->b->mesh, e - b, poses, c->margin,
                                      0, into, NULL);
    if (st >= TTD_ERR_FIRST_FATAL)
        return st;
    const size_t n = c->f ? ((ttd_contacts_f *)into)->count : ((ttd_contacts_d *)into)->count;
    const size_t *ps = c->f ? ((ttd_contacts_f *)into)->pose_start : ((ttd_contacts_d *)into)->pose_start;
    const void *pairs = c->f ? (void *)((ttd_contacts_f *)into)->pairs : (void *)((ttd_contacts_d *)into)->pairs;
    const size_t before = b == 0 ? 0 : c->starts[b];
    for (size_t i = b; i < e; ++i)
        c->starts[i + 1] = before + ps[i - b + 1];
    if (b == 0 || n == 0)
        return st;
    if (c->tail_n + n > c->tail_cap) {
        size_t cap = c->tail_cap ? c->tail_cap : 1024;
        while (cap < c->tail_n + n)
            cap *= 2;
        char *t = cap <= SIZE_MAX / elem ? realloc(c->tail, cap * elem) : NULL;
        if (t == NULL)
            return TTD_ERR_OUT_OF_MEMORY;
        c->tail = t;
        c->tail_cap = cap;
    }
    memcpy(c->tail + c->tail_n * elem, pairs, n * elem);
    c->tail_n += n;
    return st;
}

/* The call of kind on q's poses, with the lock released; K = 0 runs the checks on the probe. */
static ttd_status ttd_py_query_call(ttd_py_kind kind, const ttd_py_query *q, double x, double y, void *out, void *out2)
{
    if (q->k == 0)
        return ttd_py_probe(kind, &q->opt, q->type, x, y);
    ttd_status st;
    PyObject *const meshes[2] = {(PyObject *)q->a, (PyObject *)q->b};
    if (ttd_py_meshes_use(meshes, 2) < 0)
        return TTD_PY_IN_USE;
    if (kind == TTD_PY_CONTACTS) { /* out: a ttd_py_contact_pieces; Ctrl-C between pieces of poses */
        ttd_py_contact_pieces *c = out;
        c->q = q;
        c->margin = x;
        if (ttd_py_run_pieces((size_t)q->k, 16, ttd_py_contact_piece_run, c, &st) < 0)
            st = TTD_PY_INTERRUPTED;
    } else { /* poses in pieces, Ctrl-C checked between them (ttd_py_run_pieces) */
        const int d = q->type == NPY_DOUBLE;
        const size_t nta = (size_t)PyArray_DIM(q->a->faces, 0), ntb = (size_t)PyArray_DIM(q->b->faces, 0);
        ttd_py_pose_piece c = {kind, q, x, y, out, out2, 12 * (d ? sizeof(double) : sizeof(float)), 0, 0};
        if (kind == TTD_PY_DISTANCE)
            c.out_stride = d ? sizeof(ttd_mesh_result_d) : sizeof(ttd_mesh_result_f);
        else if (kind == TTD_PY_COLLIDE)
            c.out_stride = sizeof(ttd_collision);
        else
            c.out_stride = nta * (d ? sizeof(ttd_closest_d) : sizeof(ttd_closest_f)),
            c.out2_stride = ntb * (d ? sizeof(ttd_closest_d) : sizeof(ttd_closest_f));
        if (ttd_py_run_pieces((size_t)q->k, 16, ttd_py_pose_piece_run, &c, &st) < 0)
            st = TTD_PY_INTERRUPTED;
    }
    ttd_py_meshes_release(meshes, 2);
    return st;
}

/* ---- the queries: results ----------------------------------------------------------------- */

/* A record array of descr with the pose axis ((k,), or () for a single pose) and then the extra
 * dimension (0: none); or the caller's out, checked: the same dtype and shape, C-contiguous,
 * aligned, writeable, sharing no memory with the poses the library reads. */
static PyArrayObject *ttd_py_records(const ttd_py_query *q, PyArray_Descr *descr, const char *descr_name, npy_intp extra,
                                     PyObject *out)
{
    npy_intp dims[2];
    int nd = 0;
    if (!q->single)
        dims[nd++] = q->k;
    if (extra > 0)
        dims[nd++] = extra;
    if (out == NULL || out == Py_None) {
        Py_INCREF(descr);
        return (PyArrayObject *)PyArray_NewFromDescr(&PyArray_Type, descr, nd, dims, NULL, NULL, 0, NULL);
    }
    if (!PyArray_Check(out)) {
        PyErr_Format(PyExc_TypeError, "out must be a numpy array, not %.100s", Py_TYPE(out)->tp_name);
        return NULL;
    }
    PyArrayObject *o = (PyArrayObject *)out;
    if (!PyArray_EquivTypes(PyArray_DESCR(o), descr)) {
        PyErr_Format(PyExc_TypeError, "out has dtype %S: this call writes %s", (PyObject *)PyArray_DESCR(o), descr_name);
        return NULL;
    }
    if (PyArray_NDIM(o) != nd || !PyArray_CompareLists(PyArray_DIMS(o), dims, nd)) {
        PyObject *have = ttd_py_shape(o);
        if (have)
            PyErr_Format(PyExc_ValueError, "out has shape %R: this call writes %s", have,
                         extra > 0 ? (q->single ? "one record per triangle, shape (m,)"
                                                : "one record per pose and triangle, shape (K, m)")
                                   : q->single ? "one record, shape ()" : "one record per pose, shape (K,)");
        Py_XDECREF(have);
        return NULL;
    }
    if (!PyArray_IS_C_CONTIGUOUS(o) || !PyArray_ISWRITEABLE(o) || !PyArray_ISALIGNED(o)) {
        PyErr_SetString(PyExc_ValueError, "out must be C-contiguous, aligned and writeable");
        return NULL;
    }
    const char *po = PyArray_DATA(q->poses), *oo = PyArray_DATA(o);
    if (PyArray_NBYTES(o) > 0 && PyArray_NBYTES(q->poses) > 0 && po < oo + PyArray_NBYTES(o) &&
        oo < po + PyArray_NBYTES(q->poses)) {
        PyErr_SetString(PyExc_ValueError, "out shares memory with poses, which are read while it is written");
        return NULL;
    }
    Py_INCREF(o);
    return o;
}

PyDoc_STRVAR(ttd_py_mesh_distance_doc,
"mesh_distance(a, b, poses, *, upper_bound=math.inf, rel_tol=0.0, isa='auto', threads=0, out=None, solid=False)\n"
"--\n\n"
"Minimum distance between meshes a and b under each pose of b, with the closest points and\n"
"the triangles that realise it.\n\n"
"a, b : ttd.Mesh\n"
"    Both float64 or both float32 (TypeError otherwise); the query computes in that precision.\n"
"poses : array_like, shape (K, 4, 4) or (K, 3, 4), or one (4, 4) / (3, 4) pose\n"
"    Rigid motions of b into a's frame: x_a = R x_b + t, computed per coordinate as\n"
"    ((r0 x + r1 y) + r2 z) + t. Converted to the meshes' dtype (then checked): R must be a\n"
"    rotation (finite, R^T R = I within 1e-6 entry by entry, det R > 0), and the bottom row of\n"
"    a 4x4 pose must be 0 0 0 1 exactly. K may be 0.\n"
"upper_bound : float\n"
"    >= 0 (inf: none). A pose whose distance exceeds it may stop early; it then reports inf,\n"
"    no points, ttd.NO_TRIANGLE and the flag ttd.MeshFlag.ABOVE_BOUND.\n"
"rel_tol : float\n"
"    >= 0, finite (0: exact). The pair reported may be up to a factor 1 + rel_tol farther than\n"
"    the minimum (fewer pairs tested).\n"
"isa, threads : as in ttd.distance. The K poses are spread over the threads; results do not\n"
"    depend on either.\n"
"out : numpy.ndarray, optional\n"
"    Where the library writes its records instead of a new array: ttd.MESH_RESULT_DTYPE_FLOAT64\n"
"    (or FLOAT32 for float32 meshes), shape (K,) (() for one pose), C-contiguous, writeable.\n"
"solid : bool\n"
"    False (default): the meshes' surfaces are compared, so a mesh inside another is at the\n"
"    distance between their surfaces. True: both meshes are solids (they must be closed,\n"
"    ValueError otherwise); one inside the other gives distance 0 with ttd.MeshFlag.CONTAINED,\n"
"    p = q a vertex of the inner mesh and ttd.NO_TRIANGLE for the outer mesh's triangle.\n\n"
"Returns a ttd.MeshDistance: distance (K,), p, q (K, 3), tri_a, tri_b (K,) uint32,\n"
"feature_a, feature_b (K,) uint8, flags (K,) uint16 (ttd.MeshFlag), node_tests (uint32) and\n"
"pair_tests (uint64), in a's frame; numpy scalars and (3,) points for a single pose. The\n"
"distance equals the minimum of ttd.distance over every triangle pair (b's vertices moved\n"
"as above), bit for bit. The interpreter lock is released while the library computes.\n\n"
"Raises TypeError (not meshes, meshes of different precisions, a pose dtype that is not\n"
"real), ValueError (a shape, a pose that is not a rigid motion or that moves b beyond the\n"
"mesh coordinate range, naming it; upper_bound, rel_tol or threads out of range), ttd.IsaUnavailableError, MemoryError.");

static PyObject *ttd_py_mesh_distance(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *kwlist[] = {"a", "b", "poses", "upper_bound", "rel_tol", "isa", "threads", "out", "solid", NULL};
    PyObject *a, *b, *poses, *ub_obj = NULL, *rt_obj = NULL, *isa = NULL, *threads = NULL, *out_obj = NULL;
    int solid = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OOO|$OOOOOp:mesh_distance", kwlist, &a, &b, &poses, &ub_obj, &rt_obj,
                                     &isa, &threads, &out_obj, &solid))
        return NULL;
    double ub = (double)INFINITY, rt = 0;
    if (ttd_py_real_arg(ub_obj, "upper_bound", &ub) < 0 || ttd_py_real_arg(rt_obj, "rel_tol", &rt) < 0)
        return NULL;
    ttd_py_query q;
    if (ttd_py_query_begin(a, b, poses, isa, threads, &q) < 0)
        return NULL;
    q.opt.solid = solid;
    const int f = q.type == NPY_FLOAT;
    PyObject *result = NULL;
    PyArrayObject *rec = ttd_py_records(&q, ttd_py_dist_rec[f], f ? "ttd.MESH_RESULT_DTYPE_FLOAT32" : "ttd.MESH_RESULT_DTYPE_FLOAT64",
                                        0, out_obj);
    if (rec == NULL)
        goto done;
    ttd_status st = ttd_py_query_call(TTD_PY_DISTANCE, &q, ub, rt, PyArray_DATA(rec), NULL);
    if (st != TTD_OK) {
        ttd_py_query_raise(st, TTD_PY_DISTANCE, &q, ub, rt);
        goto done;
    }
    result = ttd_py_named_new(ttd_py_MeshDistance, TTD_PY_NDIST);
    if (result != NULL && ttd_py_set_views(result, 0, rec, ttd_py_distance_names, TTD_PY_NDIST) < 0)
        Py_CLEAR(result);
done:
    Py_XDECREF(rec);
    Py_XDECREF(q.poses);
    return result;
}

PyDoc_STRVAR(ttd_py_mesh_collide_doc,
"mesh_collide(a, b, poses, margin=0, *, isa='auto', threads=0, out=None, solid=False)\n"
"--\n\n"
"Whether meshes a and b come within margin of each other under each pose of b (margin 0: do\n"
"they touch or cross?). Each pose stops at its first witness pair.\n\n"
"a, b, poses, isa, threads : as in ttd.mesh_distance.\n"
"margin : float, finite and >= 0 (converted to the meshes' dtype).\n"
"out : numpy.ndarray, optional: ttd.COLLISION_DTYPE records, shape (K,) (() for one pose),\n"
"    written by the library instead of a new array.\n"
"solid : bool: as in ttd.mesh_distance (one closed mesh inside another collides).\n\n"
"Returns a ttd.MeshCollision: hit (K,) bool, and the first pair found within the margin,\n"
"tri_a and tri_b (K,) uint32 (ttd.NO_TRIANGLE where there is none), node_tests, pair_tests;\n"
"numpy scalars for a single pose. hit equals (the minimum distance <= margin). The\n"
"interpreter lock is released while the library computes. Raises as ttd.mesh_distance does.");

static PyObject *ttd_py_mesh_collide(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *kwlist[] = {"a", "b", "poses", "margin", "isa", "threads", "out", "solid", NULL};
    PyObject *a, *b, *poses, *margin_obj = NULL, *isa = NULL, *threads = NULL, *out_obj = NULL;
    int solid = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OOO|O$OOOp:mesh_collide", kwlist, &a, &b, &poses, &margin_obj, &isa,
                                     &threads, &out_obj, &solid))
        return NULL;
    double margin = 0;
    if (ttd_py_real_arg(margin_obj, "margin", &margin) < 0)
        return NULL;
    ttd_py_query q;
    if (ttd_py_query_begin(a, b, poses, isa, threads, &q) < 0)
        return NULL;
    q.opt.solid = solid;
    PyObject *result = NULL;
    PyArrayObject *hit = NULL, *rec = ttd_py_records(&q, ttd_py_coll_rec, "ttd.COLLISION_DTYPE", 0, out_obj);
    if (rec == NULL)
        goto done;
    ttd_status st = ttd_py_query_call(TTD_PY_COLLIDE, &q, margin, 0, PyArray_DATA(rec), NULL);
    if (st != TTD_OK) {
        ttd_py_query_raise(st, TTD_PY_COLLIDE, &q, margin, 0);
        goto done;
    }
    if ((hit = (PyArrayObject *)PyArray_SimpleNew(PyArray_NDIM(rec), PyArray_DIMS(rec), NPY_BOOL)) == NULL)
        goto done;
    const ttd_collision *c = PyArray_DATA(rec);
    npy_bool *h = PyArray_DATA(hit);
    for (npy_intp i = 0; i < q.k; ++i)
        h[i] = c[i].hit != 0;
    result = ttd_py_named_new(ttd_py_MeshCollision, TTD_PY_NCOLL);
    if (result == NULL)
        goto done;
    Py_INCREF(hit);
    PyTuple_SET_ITEM(result, 0, PyArray_Return(hit));
    if (ttd_py_set_views(result, 1, rec, ttd_py_collision_names + 1, TTD_PY_NCOLL - 1) < 0)
        Py_CLEAR(result);
done:
    Py_XDECREF(hit);
    Py_XDECREF(rec);
    Py_XDECREF(q.poses);
    return result;
}

/* The capsules that own a contact set whose buffer numpy arrays view. */
static void ttd_py_free_contacts_d(PyObject *capsule)
{
    ttd_contacts_d *set = PyCapsule_GetPointer(capsule, "ttd.contacts_d");
    ttd_contacts_free_d(set);
    free(set);
}

static void ttd_py_free_contacts_f(PyObject *capsule)
{
    ttd_contacts_f *set = PyCapsule_GetPointer(capsule, "ttd.contacts_f");
    ttd_contacts_free_f(set);
    free(set);
}

PyDoc_STRVAR(ttd_py_mesh_contacts_doc,
"mesh_contacts(a, b, poses, margin, *, isa='auto', threads=0)\n"
"--\n\n"
"Every triangle pair of a and b at distance <= margin, under each pose of b.\n\n"
"a, b, poses, isa, threads : as in ttd.mesh_distance.\n"
"margin : float, finite and >= 0 (converted to the meshes' dtype).\n\n"
"Returns a ttd.MeshContacts of parallel arrays over the n contacts of all poses, pose by\n"
"pose: pose (n,) intp (the pose index), tri_a, tri_b (n,) uint32, distance (n,), p, q (n, 3)\n"
"(in a's frame; q equals p at distance 0), and pose_start (K + 1,) intp: the contacts of pose\n"
"k are the slice pose_start[k]:pose_start[k + 1]. Within a pose the order depends only on\n"
"the meshes and the pose (not on threads or instruction set). The set equals the pairs\n"
"whose ttd.distance is <= margin, with the same distances and points, bit for bit. tri_a,\n"
"tri_b, distance, p and q are views of the buffer the C library filled (no copy) when the\n"
"poses ran as one piece (up to 16 poses; longer batches run in pieces, Ctrl-C checked between\n"
"them, and their contacts are joined into one array). The\n"
"interpreter lock is released while the library computes. Raises as ttd.mesh_distance does.");

/* The first n contacts of a contact set (*set, ttd_contacts_f when f) as a record array that
 * views the library's buffer, kept alive by a capsule that frees the set: *set is then NULL (the
 * capsule's, *capsule holding it when n is 0). NULL with an exception (*set still the caller's
 * unless the capsule was made). */
static PyArrayObject *ttd_py_contact_records(void **set, int f, npy_intp n, PyObject **capsule)
{
    void *pairs = f ? (void *)((ttd_contacts_f *)*set)->pairs : (void *)((ttd_contacts_d *)*set)->pairs;
    *capsule = PyCapsule_New(*set, f ? "ttd.contacts_f" : "ttd.contacts_d", f ? ttd_py_free_contacts_f : ttd_py_free_contacts_d);
    if (*capsule == NULL)
        return NULL;
    *set = NULL; /* the capsule's now */
    PyArray_Descr *descr = ttd_py_cont_rec[f];
    Py_INCREF(descr);
    PyArrayObject *rec = (PyArrayObject *)PyArray_NewFromDescr(&PyArray_Type, descr, 1, &n, NULL, n > 0 ? pairs : NULL,
                                                               n > 0 ? NPY_ARRAY_CARRAY : 0, NULL);
    if (rec == NULL || n == 0)
        return rec;
    const int bad = PyArray_SetBaseObject(rec, *capsule); /* takes the capsule, even when it fails */
    *capsule = NULL;
    if (bad < 0)
        Py_CLEAR(rec);
    return rec;
}

static PyObject *ttd_py_mesh_contacts(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *kwlist[] = {"a", "b", "poses", "margin", "isa", "threads", NULL};
    PyObject *a, *b, *poses, *margin_obj, *isa = NULL, *threads = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OOOO|$OO:mesh_contacts", kwlist, &a, &b, &poses, &margin_obj, &isa,
                                     &threads))
        return NULL;
    double margin = 0;
    if (ttd_py_real_arg(margin_obj, "margin", &margin) < 0)
        return NULL;
    if (margin_obj == Py_None) {
        PyErr_SetString(PyExc_TypeError, "margin must be a real number, not None");
        return NULL;
    }
    ttd_py_query q;
    if (ttd_py_query_begin(a, b, poses, isa, threads, &q) < 0)
        return NULL;
    const int f = q.type == NPY_FLOAT;
    PyObject *result = NULL, *capsule = NULL;
    PyArrayObject *rec = NULL, *pose = NULL, *start = NULL;
    /* The set lives on the heap: the capsule that frees it becomes the base of the views. */
    const size_t set_bytes = f ? sizeof(ttd_contacts_f) : sizeof(ttd_contacts_d);
    void *set = calloc(1, set_bytes);
    ttd_py_contact_pieces pc_ = {set, calloc(1, set_bytes), f, NULL, 0, 0, calloc((size_t)q.k + 1, sizeof(size_t)),
                                 &q, margin};
    if (set == NULL || pc_.scratch == NULL || pc_.starts == NULL) {
        PyErr_NoMemory();
        goto done;
    }
    ttd_status st = ttd_py_query_call(TTD_PY_CONTACTS, &q, margin, 0, &pc_, NULL);
    if (st == TTD_PY_INTERRUPTED)
        goto done; /* KeyboardInterrupt raised between pieces */
    if (st != TTD_OK) {
        ttd_py_query_raise(st, TTD_PY_CONTACTS, &q, margin, 0);
        goto done;
    }
    const size_t *ps = pc_.starts;
    npy_intp n = q.k == 0 ? 0 : (npy_intp)pc_.starts[q.k];
    if (pc_.tail_n == 0) { /* one piece, or later pieces without contacts: a view of the library's set */
        if ((rec = ttd_py_contact_records(&set, f, n, &capsule)) == NULL)
            goto done;
    } else { /* pieces: the first piece's contacts and the tail's, joined in an array of numpy's */
        const size_t elem = f ? sizeof(ttd_contact_f) : sizeof(ttd_contact_d), first = (size_t)n - pc_.tail_n;
        Py_INCREF(ttd_py_cont_rec[f]);
        if ((rec = (PyArrayObject *)PyArray_NewFromDescr(&PyArray_Type, ttd_py_cont_rec[f], 1, &n, NULL, NULL,
                                                         NPY_ARRAY_CARRAY, NULL)) == NULL)
            goto done;
        const void *pairs = f ? (void *)((ttd_contacts_f *)set)->pairs : (void *)((ttd_contacts_d *)set)->pairs;
        if (first)
            memcpy(PyArray_DATA(rec), pairs, first * elem);
        memcpy((char *)PyArray_DATA(rec) + first * elem, pc_.tail, pc_.tail_n * elem);
    }
    npy_intp k1 = q.k + 1;
    if ((pose = (PyArrayObject *)PyArray_SimpleNew(1, &n, NPY_INTP)) == NULL ||
        (start = (PyArrayObject *)PyArray_SimpleNew(1, &k1, NPY_INTP)) == NULL)
        goto done;
    npy_intp *pc = PyArray_DATA(pose), *sc = PyArray_DATA(start);
    sc[0] = 0;
    for (npy_intp i = 0; i < q.k; ++i) {
        sc[i + 1] = (npy_intp)ps[i + 1];
        for (npy_intp j = (npy_intp)ps[i]; j < (npy_intp)ps[i + 1]; ++j)
            pc[j] = i;
    }
    result = ttd_py_named_new(ttd_py_MeshContacts, TTD_PY_NCONT);
    if (result == NULL)
        goto done;
    PyTuple_SET_ITEM(result, 0, (PyObject *)pose);
    PyTuple_SET_ITEM(result, TTD_PY_NCONT - 1, (PyObject *)start);
    pose = start = NULL;
    if (ttd_py_set_views(result, 1, rec, ttd_py_contacts_names + 1, TTD_PY_NCONT - 2) < 0)
        Py_CLEAR(result);
done:
    for (int s = 0; s < 2; ++s) {
        void *x = s ? pc_.scratch : set;
        if (x == NULL)
            continue;
        if (f)
            ttd_contacts_free_f(x);
        else
            ttd_contacts_free_d(x);
        free(x);
    }
    free(pc_.tail);
    free(pc_.starts);
    Py_XDECREF(capsule);
    Py_XDECREF(rec);
    Py_XDECREF(pose);
    Py_XDECREF(start);
    Py_XDECREF(q.poses);
    return result;
}

PyDoc_STRVAR(ttd_py_mesh_closest_doc,
"mesh_closest(a, b, poses, margin, *, for_a=True, for_b=True, isa='auto', threads=0, out=None)\n"
"--\n\n"
"For every triangle of a and of b, its closest partner in the other mesh within margin,\n"
"under each pose of b (Hauser's per-triangle reduction of the contact set).\n\n"
"a, b, poses, isa, threads : as in ttd.mesh_distance.\n"
"margin : float, finite and >= 0 (converted to the meshes' dtype).\n"
"for_a, for_b : bool\n"
"    Which meshes' triangles to report (at least one).\n"
"out : (numpy.ndarray or None, numpy.ndarray or None), optional\n"
"    Where the library writes the records of for_a and for_b instead of new arrays:\n"
"    ttd.CLOSEST_DTYPE_FLOAT64 (FLOAT32 for float32 meshes), shape (K, m) ((m,) for one pose),\n"
"    C-contiguous, writeable; None for a side not asked for.\n\n"
"Returns a ttd.MeshClosest(for_a, for_b): each a ttd.ClosestPartners of arrays of shape\n"
"(K, m) ((m,) for a single pose; m that mesh's triangle count), or None when not asked for:\n"
"partner (uint32, ttd.NO_TRIANGLE when no triangle is within the margin), distance (inf\n"
"when none), p on the triangle itself and q on its partner ((K, m, 3), in a's frame; NaN\n"
"when none). Ties go to the smaller partner index. The interpreter lock is released while\n"
"the library computes. Raises as ttd.mesh_distance does.");

static PyObject *ttd_py_partners(PyArrayObject *rec)
{
    PyObject *r = ttd_py_named_new(ttd_py_ClosestPartners, TTD_PY_NCLOSE);
    if (r != NULL && ttd_py_set_views(r, 0, rec, ttd_py_partners_names, TTD_PY_NCLOSE) < 0)
        Py_CLEAR(r);
    return r;
}

static PyObject *ttd_py_mesh_closest(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *kwlist[] = {"a", "b", "poses", "margin", "for_a", "for_b", "isa", "threads", "out", NULL};
    PyObject *a, *b, *poses, *margin_obj, *isa = NULL, *threads = NULL, *out_obj = NULL;
    int for_a = 1, for_b = 1;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OOOO|$ppOOO:mesh_closest", kwlist, &a, &b, &poses, &margin_obj,
                                     &for_a, &for_b, &isa, &threads, &out_obj))
        return NULL;
    PyObject *out_a = NULL, *out_b = NULL;
    if (out_obj != NULL && out_obj != Py_None) {
        if (!PyTuple_Check(out_obj) || PyTuple_GET_SIZE(out_obj) != 2) {
            PyErr_Format(PyExc_TypeError, "out must be a tuple (out_a, out_b) of record arrays or None, not %.100s",
                         Py_TYPE(out_obj)->tp_name);
            return NULL;
        }
        out_a = PyTuple_GET_ITEM(out_obj, 0);
        out_b = PyTuple_GET_ITEM(out_obj, 1);
    }
    double margin = 0;
    if (ttd_py_real_arg(margin_obj, "margin", &margin) < 0)
        return NULL;
    if (margin_obj == Py_None) {
        PyErr_SetString(PyExc_TypeError, "margin must be a real number, not None");
        return NULL;
    }
    if (!for_a && !for_b) {
        PyErr_SetString(PyExc_ValueError, "for_a and for_b are both False: nothing to compute");
        return NULL;
    }
    ttd_py_query q;
    if (ttd_py_query_begin(a, b, poses, isa, threads, &q) < 0)
        return NULL;
    const int f = q.type == NPY_FLOAT;
    PyObject *result = NULL, *ra = NULL, *rb = NULL;
    PyArrayObject *reca = NULL, *recb = NULL;
    const char *rec_name = f ? "ttd.CLOSEST_DTYPE_FLOAT32" : "ttd.CLOSEST_DTYPE_FLOAT64";
    if ((!for_a && out_a != NULL && out_a != Py_None) || (!for_b && out_b != NULL && out_b != Py_None)) {
        PyErr_SetString(PyExc_ValueError, "out names an array for a side that is not computed (for_a or for_b False)");
        goto done;
    }
    if ((for_a && (reca = ttd_py_records(&q, ttd_py_close_rec[f], rec_name,
                                         (npy_intp)ttd_mesh_triangle_count(q.a->mesh), out_a)) == NULL) ||
        (for_b && (recb = ttd_py_records(&q, ttd_py_close_rec[f], rec_name,
                                         (npy_intp)ttd_mesh_triangle_count(q.b->mesh), out_b)) == NULL))
        goto done;
    if (reca != NULL && recb != NULL && PyArray_NBYTES(reca) > 0 && PyArray_NBYTES(recb) > 0 &&
        (const char *)PyArray_DATA(reca) < (const char *)PyArray_DATA(recb) + PyArray_NBYTES(recb) &&
        (const char *)PyArray_DATA(recb) < (const char *)PyArray_DATA(reca) + PyArray_NBYTES(reca)) {
        PyErr_SetString(PyExc_ValueError, "out's two arrays share memory: each side needs its own");
        goto done;
    }
    ttd_status st = ttd_py_query_call(TTD_PY_CLOSEST, &q, margin, 0, reca ? PyArray_DATA(reca) : NULL,
                                      recb ? PyArray_DATA(recb) : NULL);
    if (st != TTD_OK) {
        ttd_py_query_raise(st, TTD_PY_CLOSEST, &q, margin, 0);
        goto done;
    }
    if (reca && (ra = ttd_py_partners(reca)) == NULL)
        goto done;
    if (recb && (rb = ttd_py_partners(recb)) == NULL)
        goto done;
    if ((result = ttd_py_named_new(ttd_py_MeshClosest, TTD_PY_NPAIR)) == NULL)
        goto done;
    if (ra == NULL) {
        ra = Py_None;
        Py_INCREF(ra);
    }
    if (rb == NULL) {
        rb = Py_None;
        Py_INCREF(rb);
    }
    PyTuple_SET_ITEM(result, 0, ra);
    PyTuple_SET_ITEM(result, 1, rb);
    ra = rb = NULL;
done:
    Py_XDECREF(ra);
    Py_XDECREF(rb);
    Py_XDECREF(reca);
    Py_XDECREF(recb);
    Py_XDECREF(q.poses);
    return result;
}

/* ---- welding ----------------------------------------------------------------------------- */

PyDoc_STRVAR(ttd_py_weld_doc,
"weld(vertices, faces, tolerance, *, precision=None, return_index=False)\n"
"--\n\n"
"Merges vertices within tolerance of each other into one, for meshes whose triangles carry their\n"
"own copies of shared corners (STL, many CAD exports); include/ttd/ttd.h, ttd_mesh_weld_d, and\n"
"docs/mesh-files.md say exactly what is merged and kept:\n"
"- within: Euclidean distance <= tolerance; tolerance 0 merges equal values (-0 and +0 too);\n"
"- chained: a near b and b near c puts a, b, c in one vertex; the result does not depend on the\n"
"  vertices' order;\n"
"- kept: each class's lexicographically smallest vertex (x, then y, then z), exactly, zero as +0;\n"
"  classes numbered by their first vertex in the input;\n"
"- faces renumbered in their order; a face with two corners in one class is dropped (so the\n"
"  number dropped is len(faces) - len(new faces)).\n\n"
"vertices, faces and precision as for ttd.Mesh (float32 vertices are welded in float32).\n"
"tolerance : a real >= 0, finite.\n"
"Returns (vertices, faces), new arrays, and with return_index=True also index, an (n,) uint32\n"
"array: each old vertex's new index. Raises ValueError (a shape, a non-finite coordinate, a\n"
"tolerance that is negative or not finite), IndexError (an index out of range), TypeError.");

static PyObject *ttd_py_weld(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *kwlist[] = {"vertices", "faces", "tolerance", "precision", "return_index", NULL};
    PyObject *v_obj, *f_obj, *tol_obj, *precision = NULL, *result = NULL;
    int return_index = 0, t;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OOO|$Op:weld", kwlist, &v_obj, &f_obj, &tol_obj, &precision,
                                     &return_index))
        return NULL;
    double tol;
    if (ttd_py_real_arg(tol_obj, "tolerance", &tol) < 0 || ttd_py_precision(precision, &t) < 0)
        return NULL;
    if (!(tol >= 0) || !isfinite(tol)) {
        PyErr_Format(PyExc_ValueError, "tolerance must be a finite number >= 0, not %R", tol_obj);
        return NULL;
    }
    PyArrayObject *v = ttd_py_mesh_vertices(v_obj, t, &t), *f = NULL, *vo = NULL, *fo = NULL, *map = NULL;
    if (v == NULL)
        return NULL;
    if ((f = ttd_py_mesh_faces(f_obj, PyArray_DIM(v, 0))) == NULL)
        goto done;
    const npy_intp nv = PyArray_DIM(v, 0), nt = PyArray_DIM(f, 0);
    npy_intp vd[2] = {nv, 3}, fd[2] = {nt, 3}, md[1] = {nv};
    if ((vo = (PyArrayObject *)PyArray_SimpleNew(2, vd, t)) == NULL ||
        (fo = (PyArrayObject *)PyArray_SimpleNew(2, fd, NPY_UINT32)) == NULL ||
        (map = (PyArrayObject *)PyArray_SimpleNew(1, md, NPY_UINT32)) == NULL)
        goto done;
    size_t nvo = 0, nto = 0;
    ttd_status st;
    const float tf = ttd_py_to_float(tol);
    Py_BEGIN_ALLOW_THREADS
    st = t == NPY_DOUBLE ? ttd_mesh_weld_d(PyArray_DATA(v), (size_t)nv, PyArray_DATA(f), (size_t)nt, tol,
                                           PyArray_DATA(vo), &nvo, PyArray_DATA(fo), &nto, PyArray_DATA(map))
                         : ttd_mesh_weld_f(PyArray_DATA(v), (size_t)nv, PyArray_DATA(f), (size_t)nt, tf,
                                           PyArray_DATA(vo), &nvo, PyArray_DATA(fo), &nto, PyArray_DATA(map));
    Py_END_ALLOW_THREADS
    if (st != TTD_OK) {
        if (ttd_py_raise_fatal(st, NULL) == 0)
            PyErr_Format(PyExc_SystemError, "ttd: unexpected status %d welding", (int)st);
        goto done;
    }
    /* the arrays cut to the classes and the faces kept (copies: a view would keep the rest) */
    {
        PyObject *vs = PySequence_GetSlice((PyObject *)vo, 0, (Py_ssize_t)nvo);
        PyObject *fs = PySequence_GetSlice((PyObject *)fo, 0, (Py_ssize_t)nto);
        PyObject *vc = vs ? PyArray_NewCopy((PyArrayObject *)vs, NPY_CORDER) : NULL;
        PyObject *fc = fs ? PyArray_NewCopy((PyArrayObject *)fs, NPY_CORDER) : NULL;
        if (vc && fc)
            result = return_index ? PyTuple_Pack(3, vc, fc, (PyObject *)map) : PyTuple_Pack(2, vc, fc);
        Py_XDECREF(vs);
        Py_XDECREF(fs);
        Py_XDECREF(vc);
        Py_XDECREF(fc);
    }
done:
    Py_XDECREF(v);
    Py_XDECREF(f);
    Py_XDECREF(vo);
    Py_XDECREF(fo);
    Py_XDECREF(map);
    return result;
}

/* ---- mesh files ---------------------------------------------------------------------------- */

PyDoc_STRVAR(ttd_py_load_mesh_doc,
"load_mesh(path, *, precision='float64', strict=False, weld=None)\n"
"--\n\n"
"Reads a triangle mesh from an OBJ, STL (ASCII or binary), PLY (ASCII or binary), OFF or glTF 2.0\n"
"(GLB, .gltf with its buffers) or 3MF file, the\n"
"format told by the content, with the C library's reader (include/ttd/meshfile.h,\n"
"docs/mesh-files.md): polygons fan-triangulated, STL's repeated vertices merged.\n\n"
"precision : 'float64' (default) or 'float32' (coordinates rounded once from the file's text).\n"
"strict : bool: refuse OBJ lines that are not OBJ statements (default: skip them).\n"
"weld : None (default) or a tolerance >= 0: the vertices within it merged as ttd.weld does,\n"
"decided on the double coordinates (float32 ones are those of the vertex kept).\n\n"
"Returns (vertices, faces, skipped, dropped): vertices (N, 3) of that dtype, faces (M, 3)\n"
"uint32, skipped, the number of OBJ lines skipped, and dropped, the faces welding dropped.\n"
"Raises an OSError subclass for a file that cannot be read (FileNotFoundError,\n"
"PermissionError, IsADirectoryError, ...), ValueError naming FILE:LINE or the byte for a\n"
"malformed one, TypeError for a path that is not str or os.PathLike.");

static PyObject *ttd_py_load_mesh(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *kwlist[] = {"path", "precision", "strict", "weld", NULL};
    PyObject *path_obj, *bytes = NULL, *weld_obj = Py_None;
    const char *precision = "float64";
    int strict = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O|$spO:load_mesh", kwlist, &path_obj, &precision, &strict,
                                     &weld_obj))
        return NULL;
    double weld = 0;
    if (weld_obj != Py_None) {
        if (ttd_py_real_arg(weld_obj, "weld", &weld) < 0)
            return NULL;
        if (!(weld >= 0) || !isfinite(weld)) {
            PyErr_Format(PyExc_ValueError, "weld must be None or a finite tolerance >= 0, not %R", weld_obj);
            return NULL;
        }
    }
    const int f32 = strcmp(precision, "float32") == 0;
    if (!f32 && strcmp(precision, "float64") != 0) {
        PyErr_Format(PyExc_ValueError, "precision must be 'float64' or 'float32', not '%s'", precision);
        return NULL;
    }
    if (!PyUnicode_FSConverter(path_obj, &bytes))
        return NULL;
    ttd_meshfile m;
    char err[512], werr[256];
    size_t dropped = 0;
    int rc;
    const char *path = PyBytes_AS_STRING(bytes);
    /* I/O errors as Python's OSError subclasses (FileNotFoundError, PermissionError,
     * IsADirectoryError, ...), from errno: the file is opened once here first; what the reader
     * refuses afterwards is the content (ValueError) */
    if (strcmp(path, "-") != 0) {
        FILE *probe = fopen(path, "rb");
        int e = probe ? 0 : errno;
        struct stat sb;
        if (probe && fstat(fileno(probe), &sb) == 0 && S_ISDIR(sb.st_mode))
            e = EISDIR;
        if (probe)
            fclose(probe);
        if (e) {
            errno = e;
            PyErr_SetFromErrnoWithFilenameObject(PyExc_OSError, path_obj);
            Py_DECREF(bytes);
            return NULL;
        }
    }
    Py_BEGIN_ALLOW_THREADS
    rc = ttd_meshfile_read(path, (f32 ? TTD_MESHFILE_FLOAT : 0) | (strict ? TTD_MESHFILE_STRICT : 0), &m, err,
                           sizeof err);
    if (rc == 0 && weld_obj != Py_None && ttd_meshfile_weld(&m, weld, &dropped, werr, sizeof werr) != 0) {
        snprintf(err, sizeof err, "%s: %s", path, werr);
        ttd_meshfile_free(&m);
        rc = -1;
    }
    Py_END_ALLOW_THREADS
    Py_DECREF(bytes);
    if (rc != 0) {
        /* a read that failed part way (the reader says "read error") is an OSError too */
        PyObject *io = strstr(err, ": read error: ") != NULL ? Py_BuildValue("(is)", EIO, err) : NULL;
        if (io != NULL) {
            PyErr_SetObject(PyExc_OSError, io);
            Py_DECREF(io);
        } else
            PyErr_SetString(PyExc_ValueError, err);
        return NULL;
    }
    npy_intp vd[2] = {(npy_intp)m.nv, 3}, fd[2] = {(npy_intp)m.nt, 3};
    PyArrayObject *v = (PyArrayObject *)PyArray_SimpleNew(2, vd, f32 ? NPY_FLOAT : NPY_DOUBLE);
    PyArrayObject *t = (PyArrayObject *)PyArray_SimpleNew(2, fd, NPY_UINT32);
    PyObject *result = NULL;
    if (v != NULL && t != NULL) {
        if (f32)
            memcpy(PyArray_DATA(v), m.verts_f, 3 * m.nv * sizeof(float));
        else
            memcpy(PyArray_DATA(v), m.verts, 3 * m.nv * sizeof(double));
        memcpy(PyArray_DATA(t), m.tris, 3 * m.nt * sizeof(uint32_t));
        result = Py_BuildValue("(OOnn)", v, t, (Py_ssize_t)m.skipped_lines, (Py_ssize_t)dropped);
    }
    Py_XDECREF(v);
    Py_XDECREF(t);
    ttd_meshfile_free(&m);
    return result;
}

/* ---- self queries ---------------------------------------------------------------------------- */

/* The arguments of both self queries: the mesh, margin (converted for a float32 mesh), the flag
 * and the options; the library call with the lock released and the mesh marked in use. out: a
 * ttd_contacts_d/_f (contacts) or a ttd_collision. -1 with an exception. */
static int ttd_py_self_call(int contacts, PyObject *mesh, PyObject *margin_obj, int shared, PyObject *isa,
                            PyObject *threads, void *out, int *type)
{
    if (!PyObject_TypeCheck(mesh, &ttd_py_MeshType)) {
        PyErr_Format(PyExc_TypeError, "mesh must be a ttd.Mesh, not %.100s", Py_TYPE(mesh)->tp_name);
        return -1;
    }
    double margin = 0;
    if (margin_obj == Py_None) {
        PyErr_SetString(PyExc_TypeError, "margin must be a real number, not None");
        return -1;
    }
    ttd_options opt;
    if (ttd_py_real_arg(margin_obj, "margin", &margin) < 0 || ttd_py_options(NULL, isa, threads, NULL, NULL, NULL, &opt) < 0)
        return -1;
    const ttd_py_mesh *m = (const ttd_py_mesh *)mesh;
    const int d = m->type == NPY_DOUBLE;
    const float mf = ttd_py_to_float(margin);
    const unsigned flags = shared ? TTD_SELF_SHARED_VERTEX : 0u;
    *type = m->type;
    if (ttd_py_meshes_use(&mesh, 1) < 0)
        return -1;
    ttd_status st;
    Py_BEGIN_ALLOW_THREADS
    if (contacts)
        st = d ? ttd_mesh_self_contacts_d(&opt, m->mesh, margin, flags, out)
               : ttd_mesh_self_contacts_f(&opt, m->mesh, mf, flags, out);
    else
        st = d ? ttd_mesh_self_collide_d(&opt, m->mesh, margin, flags, out)
               : ttd_mesh_self_collide_f(&opt, m->mesh, mf, flags, out);
    Py_END_ALLOW_THREADS
    ttd_py_meshes_release(&mesh, 1);
    if (st == TTD_OK)
        return 0;
    if (st == TTD_ERR_BAD_OPTIONS && ttd_py_check_options(&opt) != TTD_ERR_BAD_OPTIONS)
        ttd_py_raise_bad_param("margin", margin, m->type, "a margin is finite and >= 0");
    else if (ttd_py_raise_fatal(st, &opt) == 0)
        PyErr_Format(PyExc_SystemError, "ttd: unexpected status %d from a self query", (int)st);
    return -1;
}

PyDoc_STRVAR(ttd_py_mesh_self_contacts_doc,
"mesh_self_contacts(mesh, margin, *, shared_vertex=False, isa='auto', threads=0)\n"
"--\n\n"
"Every pair of one mesh's triangles (i < j) at distance <= margin that shares no vertex (by index:\n"
"neighbours in the mesh touch by construction): the self-contacts of a cloth or a soft body.\n\n"
"mesh : ttd.Mesh\n"
"margin : float, finite and >= 0 (converted to the mesh's dtype)\n"
"shared_vertex : bool\n"
"    Also the pairs that share exactly one vertex v (each with another vertex), by how near they\n"
"    come away from it: the nearer of each triangle's edge opposite v against the other triangle\n"
"    (include/ttd/ttd.h, ttd_mesh_self_contacts_d): where a sheet folds onto itself at a vertex.\n"
"isa, threads : as in ttd.mesh_distance; the result does not depend on them.\n\n"
"Returns ttd.SelfContacts (tri_i, tri_j, distance, p, q), arrays over the n pairs, in an order\n"
"that depends only on the mesh; exact: each pair's distance and points are those of\n"
"ttd.distance on (triangle i, triangle j). Raises TypeError (not a Mesh), ValueError (margin),\n"
"RuntimeError (the mesh is being moved by set_vertices in another thread).");

static PyObject *ttd_py_mesh_self_contacts(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *kwlist[] = {"mesh", "margin", "shared_vertex", "isa", "threads", NULL};
    PyObject *mesh, *margin, *isa = NULL, *threads = NULL;
    int shared = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OO|$pOO:mesh_self_contacts", kwlist, &mesh, &margin, &shared, &isa,
                                     &threads))
        return NULL;
    /* the type is known once the mesh is checked: room for either set */
    void *set = calloc(1, sizeof(ttd_contacts_d) > sizeof(ttd_contacts_f) ? sizeof(ttd_contacts_d) : sizeof(ttd_contacts_f));
    if (set == NULL)
        return PyErr_NoMemory();
    int type = NPY_DOUBLE;
    PyObject *result = NULL, *capsule = NULL;
    PyArrayObject *rec = NULL;
    if (ttd_py_self_call(1, mesh, margin, shared, isa, threads, set, &type) < 0)
        goto done;
    const int f = type == NPY_FLOAT;
    const npy_intp n = (npy_intp)(f ? ((ttd_contacts_f *)set)->count : ((ttd_contacts_d *)set)->count);
    if ((rec = ttd_py_contact_records(&set, f, n, &capsule)) == NULL)
        goto done;
    if ((result = ttd_py_named_new(ttd_py_SelfContacts, TTD_PY_NSELF)) != NULL &&
        ttd_py_set_views(result, 0, rec, ttd_py_contacts_names + 1, TTD_PY_NSELF) < 0)
        Py_CLEAR(result);
done:
    if (set != NULL) {
        if (type == NPY_FLOAT)
            ttd_contacts_free_f(set);
        else
            ttd_contacts_free_d(set);
        free(set);
    }
    Py_XDECREF(capsule);
    Py_XDECREF(rec);
    return result;
}

PyDoc_STRVAR(ttd_py_mesh_self_collide_doc,
"mesh_self_collide(mesh, margin=0.0, *, shared_vertex=False, isa='auto', threads=0)\n"
"--\n\n"
"Whether one mesh comes within margin of itself (margin 0: does it intersect itself?), by the\n"
"pairs and rules of ttd.mesh_self_contacts; stops at the first such pair. Returns\n"
"ttd.SelfCollision (hit, tri_i, tri_j), tri_i < tri_j the witness (ttd.NO_TRIANGLE when none).");

static PyObject *ttd_py_mesh_self_collide(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *kwlist[] = {"mesh", "margin", "shared_vertex", "isa", "threads", NULL};
    PyObject *mesh, *margin = NULL, *isa = NULL, *threads = NULL;
    int shared = 0, type;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O|O$pOO:mesh_self_collide", kwlist, &mesh, &margin, &shared, &isa,
                                     &threads))
        return NULL;
    PyObject *zero = margin == NULL ? PyFloat_FromDouble(0) : NULL;
    if (margin == NULL && zero == NULL)
        return NULL;
    ttd_collision c;
    const int rc = ttd_py_self_call(0, mesh, margin ? margin : zero, shared, isa, threads, &c, &type);
    Py_XDECREF(zero);
    if (rc < 0)
        return NULL;
    PyObject *result = ttd_py_named_new(ttd_py_SelfCollision, TTD_PY_NSCOLL);
    if (result == NULL)
        return NULL;
    PyObject *items[3] = {PyBool_FromLong(c.hit != 0), PyLong_FromUnsignedLong(c.tri_a), PyLong_FromUnsignedLong(c.tri_b)};
    for (int k = 0; k < 3; ++k) {
        if (items[k] == NULL) {
            for (int j = k; j < 3; ++j)
                Py_XDECREF(items[j]);
            Py_DECREF(result);
            return NULL;
        }
        PyTuple_SET_ITEM(result, k, items[k]);
    }
    return result;
}

PyMethodDef ttd_py_mesh_methods[] = {
    {"load_mesh", (PyCFunction)(void (*)(void))ttd_py_load_mesh, METH_VARARGS | METH_KEYWORDS, ttd_py_load_mesh_doc},
    {"weld", (PyCFunction)(void (*)(void))ttd_py_weld, METH_VARARGS | METH_KEYWORDS, ttd_py_weld_doc},
    {"mesh_distance", (PyCFunction)(void (*)(void))ttd_py_mesh_distance, METH_VARARGS | METH_KEYWORDS,
     ttd_py_mesh_distance_doc},
    {"mesh_contacts", (PyCFunction)(void (*)(void))ttd_py_mesh_contacts, METH_VARARGS | METH_KEYWORDS,
     ttd_py_mesh_contacts_doc},
    {"mesh_closest", (PyCFunction)(void (*)(void))ttd_py_mesh_closest, METH_VARARGS | METH_KEYWORDS,
     ttd_py_mesh_closest_doc},
    {"mesh_collide", (PyCFunction)(void (*)(void))ttd_py_mesh_collide, METH_VARARGS | METH_KEYWORDS,
     ttd_py_mesh_collide_doc},
    {"mesh_self_contacts", (PyCFunction)(void (*)(void))ttd_py_mesh_self_contacts, METH_VARARGS | METH_KEYWORDS,
     ttd_py_mesh_self_contacts_doc},
    {"mesh_self_collide", (PyCFunction)(void (*)(void))ttd_py_mesh_self_collide, METH_VARARGS | METH_KEYWORDS,
     ttd_py_mesh_self_collide_doc},
    {NULL, NULL, 0, NULL},
};
