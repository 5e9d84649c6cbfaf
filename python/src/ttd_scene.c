/* SPDX-License-Identifier: MIT */
/* ttd.Scene: bodies (ttd.Mesh objects at world poses) and the four scene queries collide,
 * distance, contacts and manifold, over the "Scenes of many bodies" group of include/ttd/ttd.h.
 *
 * A Scene owns a C ttd_scene and a list of the Mesh objects of its bodies, indexed by body id
 * (None for a removed id), so that the meshes outlive the scene as the library requires. The
 * library's scene keeps broad-phase state between calls and must not be used from two threads
 * at once: every method takes the Scene's own lock (waiting for it with the interpreter lock
 * released), and the queries release the interpreter lock while the library computes. Results
 * are named tuples of numpy views of the library's own records: the growable array the library
 * filled (handed to numpy with a capsule that frees it, no copy), or a record array it wrote
 * into (distance). Refused poses are located after the library refused them, by the rule the
 * header documents, and named with their body. */
#include "ttd_py.h"

#include <math.h>
#include <pythread.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct ttd_py_scene {
    PyObject_HEAD
    ttd_scene *scene;        /* NULL until the precision is known (the first mesh added) */
    int type;                /* NPY_DOUBLE, NPY_FLOAT, or NPY_NOTYPE while scene is NULL */
    PyObject *meshes;        /* list: the Mesh of each id, None for a removed id */
    PyThread_type_lock lock; /* held by every method while it uses scene */
} ttd_py_scene;

static PyTypeObject ttd_py_SceneType;

/* ---- result types and record dtypes ------------------------------------------------------ */

enum { TTD_PY_NHIT = 4, TTD_PY_NSCONT = 7, TTD_PY_NSDIST = 8, TTD_PY_NPOINT = 11 };

static PyStructSequence_Field ttd_py_hit_fields[TTD_PY_NHIT + 1] = {
    {"i", "uint32, shape (n,): the first body of each pair within the margin (i < j)"},
    {"j", "uint32, shape (n,): the second body"},
    {"tri_i", "uint32, shape (n,): a triangle of body i of one witness pair within the margin"},
    {"tri_j", "uint32, shape (n,): its partner, a triangle of body j"},
    {NULL, NULL},
};
static PyStructSequence_Desc ttd_py_hit_desc = {
    "ttd.SceneCollision",
    "The result of Scene.collide: every eligible body pair (i, j), i < j, within the margin, with\n"
    "one witness pair of triangles each, sorted by (i, j). Views of the C library's\n"
    "ttd_scene_hit records (ttd.SCENE_HIT_DTYPE).",
    ttd_py_hit_fields, TTD_PY_NHIT,
};

static PyStructSequence_Field ttd_py_scont_fields[TTD_PY_NSCONT + 1] = {
    {"i", "uint32, shape (n,): body i of each triangle pair (i < j; for Scene.distance's nearest: the body itself)"},
    {"j", "uint32, shape (n,): body j (ttd.NO_TRIANGLE in a nearest record with no partner)"},
    {"tri_i", "uint32, shape (n,): the triangle of body i"},
    {"tri_j", "uint32, shape (n,): the triangle of body j"},
    {"distance", "shape (n,): the pair's distance (inf in a nearest record with no partner)"},
    {"p", "shape (n, 3): closest point on tri_i, in the world frame"},
    {"q", "shape (n, 3): closest point on tri_j, in the world frame; equal to p at distance 0"},
    {NULL, NULL},
};
static PyStructSequence_Desc ttd_py_scont_desc = {
    "ttd.SceneContacts",
    "The result of Scene.contacts: every triangle pair within the margin of every eligible body\n"
    "pair, as parallel arrays of n contacts in the world frame, sorted by (i, j) and then by\n"
    "triangles; also each body's nearest partner (Scene.distance(nearest=True)). Views of the C\n"
    "library's ttd_scene_contact_d/_f records (ttd.SCENE_CONTACT_DTYPE_FLOAT64 / FLOAT32).",
    ttd_py_scont_fields, TTD_PY_NSCONT,
};

static PyStructSequence_Field ttd_py_sdist_fields[TTD_PY_NSDIST + 1] = {
    {"i", "uint32: the first body of the closest eligible pair (ttd.NO_TRIANGLE when there is none within upper_bound)"},
    {"j", "uint32: the second body (i < j)"},
    {"tri_i", "uint32: the triangle of body i that realises the minimum"},
    {"tri_j", "uint32: the triangle of body j"},
    {"distance", "the minimum distance over the eligible pairs (0 touching or crossing; inf when none within upper_bound)"},
    {"p", "shape (3,): closest point on body i, in the world frame"},
    {"q", "shape (3,): closest point on body j; equal to p at distance 0"},
    {"nearest", "ttd.SceneContacts of each body id's nearest eligible other body (shape (id_limit,)), or None"},
    {NULL, NULL},
};
static PyStructSequence_Desc ttd_py_sdist_desc = {
    "ttd.SceneDistance",
    "The result of Scene.distance: the closest eligible body pair (numpy scalars and (3,) points,\n"
    "views of one ttd.SCENE_CONTACT_DTYPE_* record; ties to the smallest (i, j), then (tri_i,\n"
    "tri_j)), and nearest: None, or with nearest=True a ttd.SceneContacts of one record per body\n"
    "id (i the id, j its nearest partner; inf and ttd.NO_TRIANGLE for none and for removed ids).",
    ttd_py_sdist_fields, TTD_PY_NSDIST,
};

static PyStructSequence_Field ttd_py_point_fields[TTD_PY_NPOINT + 1] = {
    {"i", "uint32, shape (n,): the first body of the pair (i < j)"},
    {"j", "uint32, shape (n,): the second body"},
    {"tri_i", "uint32, shape (n,): the triangle of body i this point comes from"},
    {"tri_j", "uint32, shape (n,): the triangle of body j"},
    {"point", "shape (n, 3): the contact point in the world, the midpoint of a point of each body (the pair's closest points, or a corner of flat contact)"},
    {"normal", "shape (n, 3): unit normal from body i towards body j, from the bodies' shapes: a face's normal where a face of one body lies within the margin of the other, across two real edges, within the normal cones of the contact's features where they meet (docs/scenes.md, section 5a)"},
    {"distance", "shape (n,): the exact distance d between those two points (0 touching or crossing)"},
    {"depth", "shape (n,): margin - d"},
    {"point_i", "shape (n, 3): the point of body i (point is the midpoint of point_i and point_j)"},
    {"point_j", "shape (n, 3): the point of body j, at distance d from point_i (negative: the solids' points inside each other)"},
    {"key", "uint64, shape (n,): the contact's key, from the features of both bodies it lies on (vertex, edge, flat piece): the same while the contact persists (docs/scenes.md, section 5c)"},
    {NULL, NULL},
};
static PyStructSequence_Desc ttd_py_point_desc = {
    "ttd.SceneManifold",
    "The result of Scene.manifold: for every eligible body pair within the margin, at most\n"
    "max_points contact points (no two within 1e-3 of the smaller body's radius; the deepest\n"
    "first, then spread over the contact region),\n"
    "grouped by body pair in (i, j) order, as parallel arrays of n points. Views of the C\n"
    "library's ttd_scene_point_d/_f records (ttd.SCENE_POINT_DTYPE_FLOAT64 / FLOAT32).",
    ttd_py_point_fields, TTD_PY_NPOINT,
};

static PyTypeObject *ttd_py_SceneCollision, *ttd_py_SceneContacts, *ttd_py_SceneDistance, *ttd_py_SceneManifold;
static PyObject *ttd_py_hit_names[TTD_PY_NHIT], *ttd_py_scont_names[TTD_PY_NSCONT], *ttd_py_sdist_names[TTD_PY_NSDIST],
    *ttd_py_point_names[TTD_PY_NPOINT];
/* [0] float64, [1] float32 (the hit has no reals) */
static PyArray_Descr *ttd_py_hit_rec, *ttd_py_scont_rec[2], *ttd_py_point_rec[2];

static int ttd_py_scene_add_object(PyObject *module, const char *name, PyObject *obj)
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

#define TTD_PY_SCONT_OFFSETS(T)                                                                     \
    {offsetof(T, i), offsetof(T, j), offsetof(T, tri_i), offsetof(T, tri_j), offsetof(T, distance), \
     offsetof(T, p), offsetof(T, q)}
#define TTD_PY_POINT_OFFSETS(T)                                                                     \
    {offsetof(T, i), offsetof(T, j), offsetof(T, tri_i), offsetof(T, tri_j), offsetof(T, point),    \
     offsetof(T, normal), offsetof(T, distance), offsetof(T, depth), offsetof(T, point_i), offsetof(T, point_j),  \
     offsetof(T, key)}

static int ttd_py_scene_records(PyObject *module)
{
    static const size_t hit_off[TTD_PY_NHIT] = {offsetof(ttd_scene_hit, i), offsetof(ttd_scene_hit, j),
                                                offsetof(ttd_scene_hit, tri_i), offsetof(ttd_scene_hit, tri_j)};
    static const size_t cont_off[2][TTD_PY_NSCONT] = {TTD_PY_SCONT_OFFSETS(ttd_scene_contact_d),
                                                      TTD_PY_SCONT_OFFSETS(ttd_scene_contact_f)};
    static const size_t point_off[2][TTD_PY_NPOINT] = {TTD_PY_POINT_OFFSETS(ttd_scene_point_d),
                                                       TTD_PY_POINT_OFFSETS(ttd_scene_point_f)};
    static const size_t cont_size[2] = {sizeof(ttd_scene_contact_d), sizeof(ttd_scene_contact_f)};
    static const size_t point_size[2] = {sizeof(ttd_scene_point_d), sizeof(ttd_scene_point_f)};
    static const char *const reals[2] = {"f8", "f4"}, *const vecs[2] = {"(3,)f8", "(3,)f4"};
    static const char *const suffix[2] = {"FLOAT64", "FLOAT32"};
    const char *hit_fmt[TTD_PY_NHIT] = {"u4", "u4", "u4", "u4"};
    ttd_py_hit_rec = ttd_py_record_descr(TTD_PY_NHIT, ttd_py_hit_names, hit_fmt, hit_off, sizeof(ttd_scene_hit));
    if (ttd_py_scene_add_object(module, "SCENE_HIT_DTYPE", (PyObject *)ttd_py_hit_rec) < 0)
        return -1;
    for (int f = 0; f < 2; ++f) {
        const char *cont_fmt[TTD_PY_NSCONT] = {"u4", "u4", "u4", "u4", reals[f], vecs[f], vecs[f]};
        const char *point_fmt[TTD_PY_NPOINT] = {"u4", "u4", "u4", "u4", vecs[f], vecs[f], reals[f], reals[f],
                                                vecs[f], vecs[f], "u8"};
        ttd_py_scont_rec[f] = ttd_py_record_descr(TTD_PY_NSCONT, ttd_py_scont_names, cont_fmt, cont_off[f], cont_size[f]);
        ttd_py_point_rec[f] =
            ttd_py_record_descr(TTD_PY_NPOINT, ttd_py_point_names, point_fmt, point_off[f], point_size[f]);
        char name[64];
        PyOS_snprintf(name, sizeof name, "SCENE_CONTACT_DTYPE_%s", suffix[f]);
        if (ttd_py_scene_add_object(module, name, (PyObject *)ttd_py_scont_rec[f]) < 0)
            return -1;
        PyOS_snprintf(name, sizeof name, "SCENE_POINT_DTYPE_%s", suffix[f]);
        if (ttd_py_scene_add_object(module, name, (PyObject *)ttd_py_point_rec[f]) < 0)
            return -1;
    }
    return 0;
}

/* ---- the lock ---------------------------------------------------------------------------- */

static void ttd_py_scene_lock(ttd_py_scene *s)
{
    if (!PyThread_acquire_lock(s->lock, NOWAIT_LOCK)) {
        Py_BEGIN_ALLOW_THREADS
        PyThread_acquire_lock(s->lock, WAIT_LOCK);
        Py_END_ALLOW_THREADS
    }
}

static void ttd_py_scene_unlock(ttd_py_scene *s)
{
    PyThread_release_lock(s->lock);
}

/* ---- poses ------------------------------------------------------------------------------- */

static const char *ttd_py_type_name(int type)
{
    return type == NPY_FLOAT ? "float32" : "float64";
}

/* obj as a C-contiguous array of type, of one pose ((3, 4) or (4, 4)) when single, else of
 * (k, 3, 4) or (k, 4, 4): its shape checked, not its values. name is the argument's name. NULL
 * with the exception that names the problem. */
static PyArrayObject *ttd_py_scene_pose_array(PyObject *obj, int type, int single, const char *name)
{
    PyArrayObject *a = ttd_py_as_array(obj, name), *p = NULL;
    if (a == NULL)
        return NULL;
    const int nd = PyArray_NDIM(a);
    const npy_intp rows = nd >= 2 ? PyArray_DIM(a, nd - 2) : 0;
    if (!(nd == (single ? 2 : 3) && (rows == 3 || rows == 4) && PyArray_DIM(a, nd - 1) == 4)) {
        PyObject *shape = ttd_py_shape(a);
        if (shape)
            PyErr_Format(PyExc_ValueError, "%s has shape %R: %s", name, shape,
                         single ? "a pose is a (4, 4) homogeneous or a (3, 4) [R | t] array"
                                : "poses are given as an (N, 4, 4) homogeneous or an (N, 3, 4) [R | t] array, one per body");
        Py_XDECREF(shape);
        goto fail;
    }
    p = ttd_py_as_real(a, name, type);
fail:
    Py_DECREF(a);
    return p;
}

/* The poses of p (from ttd_py_scene_pose_array: single, or k of them) as a C-contiguous
 * (k, 3, 4) array, the bottom row of each 4x4 pose checked, except those of the ids s has
 * removed when s is not NULL (set_poses ignores them; the caller holds s's lock). Takes p's
 * reference. NULL with the exception that names the problem. */
static PyArrayObject *ttd_py_scene_pose_rows(PyArrayObject *p, int type, int single, const char *name,
                                             const struct ttd_py_scene *s)
{
    const npy_intp k = single ? 1 : PyArray_DIM(p, 0);
    if (PyArray_DIM(p, PyArray_NDIM(p) - 2) == 4) {
        const size_t bytes = type == NPY_DOUBLE ? sizeof(double) : sizeof(float);
        for (npy_intp i = 0; i < k; ++i) {
            double r[4];
            for (int c = 0; c < 4; ++c)
                r[c] = type == NPY_DOUBLE ? ((const double *)PyArray_DATA(p))[16 * i + 12 + c]
                                          : (double)((const float *)PyArray_DATA(p))[16 * i + 12 + c];
            if ((r[0] == 0 && r[1] == 0 && r[2] == 0 && r[3] == 1) ||
                (s != NULL && PyList_GET_ITEM(s->meshes, i) == Py_None))
                continue;
            PyObject *row = Py_BuildValue("(dddd)", r[0], r[1], r[2], r[3]);
            PyObject *where = single ? PyUnicode_FromString(name) : PyUnicode_FromFormat("%s[%zd]", name, (Py_ssize_t)i);
            if (row && where)
                PyErr_Format(PyExc_ValueError, "%U has bottom row %R: the last row of a 4x4 pose must be 0 0 0 1",
                             where, row);
            Py_XDECREF(row);
            Py_XDECREF(where);
            goto fail;
        }
        npy_intp dims[3] = {k, 3, 4};
        PyArrayObject *c = (PyArrayObject *)PyArray_SimpleNew(3, dims, type);
        if (c == NULL)
            goto fail;
        for (npy_intp i = 0; i < k; ++i)
            memcpy((char *)PyArray_DATA(c) + (size_t)i * 12 * bytes, (const char *)PyArray_DATA(p) + (size_t)i * 16 * bytes,
                   12 * bytes);
        Py_DECREF(p);
        p = c;
    }
    return p;
fail:
    Py_DECREF(p);
    return NULL;
}

/* obj as a C-contiguous (k, 3, 4) array of type: one pose ((3, 4) or (4, 4)) when single, else
 * (k, 3, 4) or (k, 4, 4); the bottom row of a 4x4 pose checked. name is the argument's name.
 * NULL with the exception that names the problem. */
static PyArrayObject *ttd_py_scene_poses(PyObject *obj, int type, int single, const char *name)
{
    PyArrayObject *p = ttd_py_scene_pose_array(obj, type, single, name);
    return p == NULL ? NULL : ttd_py_scene_pose_rows(p, type, single, name, NULL);
}

/* 0 when pose (12 reals of type) is a rigid motion by the rule of include/ttd/ttd.h (finite,
 * every entry of R^T R - I within 1e-6, det R > 0); otherwise 1 with a ValueError that calls it
 * what (a str). */
static int ttd_py_scene_bad_rotation(const void *pose, int type, PyObject *what)
{
    double p[12];
    int finite = 1;
    for (int j = 0; j < 12; ++j) {
        p[j] = type == NPY_DOUBLE ? ((const double *)pose)[j] : (double)((const float *)pose)[j];
        finite &= isfinite(p[j]) != 0;
    }
    const double r[9] = {p[0], p[1], p[2], p[4], p[5], p[6], p[8], p[9], p[10]};
    double defect = 0;
    for (int u = 0; u < 3; ++u)
        for (int v = 0; v < 3; ++v)
            defect = fmax(defect, fabs(r[u] * r[v] + r[3 + u] * r[3 + v] + r[6 + u] * r[6 + v] - (u == v ? 1.0 : 0.0)));
    const double det =
        r[0] * (r[4] * r[8] - r[5] * r[7]) - r[1] * (r[3] * r[8] - r[5] * r[6]) + r[2] * (r[3] * r[7] - r[4] * r[6]);
    if (finite && det > 0 && defect <= 1e-6)
        return 0;
    PyObject *value = PyFloat_FromDouble(finite && !(det > 0) ? det : defect);
    if (value == NULL)
        return 1;
    if (!finite)
        PyErr_Format(PyExc_ValueError, "%U has a NaN or infinite entry: a pose is a finite rotation R and translation t",
                     what);
    else if (!(det > 0))
        PyErr_Format(PyExc_ValueError,
                     "%U is not a rotation: det R = %R (a reflection or a singular matrix; a pose is a rotation R "
                     "and translation t)",
                     what, value);
    else
        PyErr_Format(PyExc_ValueError,
                     "%U is not a rotation within 1e-6: an entry of R^T R - I is %R (ttd takes rigid motions; "
                     "ttd.orthonormalize repairs R)",
                     what, value);
    Py_DECREF(value);
    return 1;
}

/* 0 when mesh moved by pose stays within the coordinate range; otherwise 1 with a ValueError. */
static int ttd_py_scene_bad_range(const ttd_mesh *mesh, const void *pose, int type, PyObject *what)
{
    size_t bad = 1;
    const ttd_status st = type == NPY_DOUBLE ? ttd_mesh_check_poses_d(mesh, mesh, 1, pose, &bad)
                                             : ttd_mesh_check_poses_f(mesh, mesh, 1, pose, &bad);
    if (st != TTD_ERR_COORDINATE_RANGE)
        return 0;
    PyErr_Format(PyExc_ValueError,
                 "%U moves its mesh beyond the mesh coordinate range: " TTD_PY_RANGE_TEXT
                 " for every vertex after the pose",
                 what);
    return 1;
}

/* The exception for a status of a call on one body's pose (what names it). Returns -1. */
static int ttd_py_scene_pose_error(ttd_status st, const ttd_mesh *mesh, const void *pose, int type, PyObject *what)
{
    if (st == TTD_ERR_BAD_POSE && ttd_py_scene_bad_rotation(pose, type, what))
        return -1;
    if (st == TTD_ERR_COORDINATE_RANGE && ttd_py_scene_bad_range(mesh, pose, type, what))
        return -1;
    if (st == TTD_ERR_OUT_OF_MEMORY)
        PyErr_NoMemory();
    else
        PyErr_Format(PyExc_ValueError, "%U: %s", what, ttd_status_string(st));
    return -1;
}

/* ---- the Scene type ---------------------------------------------------------------------- */

/* The C scene of precision type, made when the precision becomes known. */
static int ttd_py_scene_make(ttd_py_scene *s, int type)
{
    ttd_status st = type == NPY_DOUBLE ? ttd_scene_create_d(&s->scene) : ttd_scene_create_f(&s->scene);
    if (st != TTD_OK) {
        s->scene = NULL;
        PyErr_NoMemory();
        return -1;
    }
    s->type = type;
    return 0;
}

/* A body of mesh (a Mesh object) at pose (12 reals of the scene's type); what names the pose
 * for messages. Caller holds the lock. The id, or -1 with an exception. */
static long ttd_py_scene_add_body(ttd_py_scene *s, PyObject *mesh, const void *pose, PyObject *what)
{
    const ttd_py_mesh *m = (const ttd_py_mesh *)mesh;
    if (ttd_py_meshes_use(&mesh, 1) < 0) /* not while set_vertices moves it: its box is read */
        return -1;
    ttd_py_meshes_release(&mesh, 1);
    if (s->scene == NULL && ttd_py_scene_make(s, m->type) < 0)
        return -1;
    if (m->type != s->type) {
        PyErr_Format(PyExc_TypeError,
                     "a %s mesh cannot join a %s scene: a scene computes in one precision (build the meshes from "
                     "arrays of one dtype, or pass precision= to ttd.Mesh)",
                     ttd_py_type_name(m->type), ttd_py_type_name(s->type));
        return -1;
    }
    uint32_t id = 0;
    const ttd_status st = s->type == NPY_DOUBLE ? ttd_scene_add_d(s->scene, m->mesh, pose, &id)
                                                : ttd_scene_add_f(s->scene, m->mesh, pose, &id);
    if (st != TTD_OK)
        return ttd_py_scene_pose_error(st, m->mesh, pose, s->type, what);
    if (PyList_Append(s->meshes, mesh) < 0) {
        ttd_scene_remove(s->scene, id); /* the list and the scene stay in step */
        return -1;
    }
    return (long)id;
}

PyDoc_STRVAR(ttd_py_scene_doc,
"Scene(meshes=None, poses=None, *, precision=None)\n"
"--\n\n"
"A scene of bodies: each body a ttd.Mesh at a world pose [R | t] (x_world = R x_mesh + t),\n"
"for the queries over every eligible pair of bodies: collide, distance, contacts, manifold.\n\n"
"meshes : ttd.Mesh or sequence of ttd.Mesh, optional\n"
"    One mesh per body (a sequence of N), or one Mesh for every body. A mesh may serve many\n"
"    bodies; the scene keeps references to its meshes.\n"
"poses : array_like, shape (N, 4, 4) or (N, 3, 4), optional\n"
"    The bodies' world poses (default: the identity for each of len(meshes) bodies), converted\n"
"    to the scene's dtype and checked as the mesh queries check poses (R a rotation within\n"
"    1e-6, det R > 0; a 4x4 pose's bottom row 0 0 0 1).\n"
"precision : None, 'float32' or 'float64'\n"
"    The scene's dtype; None takes it from the meshes (from the first mesh added for an empty\n"
"    scene). Every mesh must have it (TypeError otherwise).\n\n"
"Bodies get ids 0, 1, 2, ... in the order they are added (add() returns the id); a removed\n"
"body's id is not given again. len(scene) is the number of bodies present, id_limit one more\n"
"than the largest id given. A Scene must not be used from two threads at once; its methods\n"
"wait for each other (a lock).");

static PyObject *ttd_py_scene_new(PyTypeObject *type, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = {"meshes", "poses", "precision", NULL};
    PyObject *meshes = NULL, *poses = NULL, *precision = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "|OO$O:Scene", kwlist, &meshes, &poses, &precision))
        return NULL;
    int want = NPY_NOTYPE;
    if (precision != NULL && ttd_py_precision(precision, &want) < 0)
        return NULL;
    ttd_py_scene *s = (ttd_py_scene *)type->tp_alloc(type, 0);
    if (s == NULL)
        return NULL;
    s->type = NPY_NOTYPE;
    PyObject *seq = NULL;
    PyArrayObject *p = NULL;
    if ((s->meshes = PyList_New(0)) == NULL || (s->lock = PyThread_allocate_lock()) == NULL) {
        if (!PyErr_Occurred())
            PyErr_NoMemory();
        goto fail;
    }
    /* the meshes: one for every body, or a sequence */
    Py_ssize_t n = 0;
    const int one = meshes != NULL && PyObject_TypeCheck(meshes, &ttd_py_MeshType);
    if (meshes != NULL && meshes != Py_None && !one) {
        if ((seq = PySequence_Fast(meshes, "meshes must be a ttd.Mesh or a sequence of ttd.Mesh")) == NULL)
            goto fail;
        n = PySequence_Fast_GET_SIZE(seq);
        for (Py_ssize_t i = 0; i < n; ++i) {
            PyObject *m = PySequence_Fast_GET_ITEM(seq, i);
            if (!PyObject_TypeCheck(m, &ttd_py_MeshType)) {
                PyErr_Format(PyExc_TypeError, "meshes[%zd] must be a ttd.Mesh, not %.100s", i, Py_TYPE(m)->tp_name);
                goto fail;
            }
        }
    } else if (meshes == NULL || meshes == Py_None) {
        if (poses != NULL && poses != Py_None) {
            PyErr_SetString(PyExc_TypeError, "poses without meshes: give the bodies' meshes too");
            goto fail;
        }
    } else {
        n = poses != NULL && poses != Py_None ? -1 : 1; /* one Mesh: as many bodies as poses */
    }
    /* the precision */
    if (meshes != NULL && meshes != Py_None) {
        for (Py_ssize_t i = 0; i < (one ? 1 : n); ++i) {
            const ttd_py_mesh *m = (const ttd_py_mesh *)(one ? meshes : PySequence_Fast_GET_ITEM(seq, i));
            if (want == NPY_NOTYPE)
                want = m->type;
            else if (m->type != want) {
                PyErr_Format(PyExc_TypeError,
                             "%s%zd%s is a %s mesh in a %s scene: a scene computes in one precision (build the "
                             "meshes from arrays of one dtype, or pass precision= to ttd.Mesh)",
                             one ? "meshes" : "meshes[", i, one ? "" : "]", ttd_py_type_name(m->type),
                             ttd_py_type_name(want));
                goto fail;
            }
        }
    }
    if (want != NPY_NOTYPE && ttd_py_scene_make(s, want) < 0)
        goto fail;
    if (meshes == NULL || meshes == Py_None)
        goto done;
    /* the poses */
    if (poses != NULL && poses != Py_None) {
        if ((p = ttd_py_scene_poses(poses, s->type, 0, "poses")) == NULL)
            goto fail;
        const npy_intp k = PyArray_DIM(p, 0);
        if (n >= 0 && k != n) {
            PyErr_Format(PyExc_ValueError, "%zd meshes and %zd poses: give one pose per body (and one mesh per body, "
                         "or one Mesh for all)", n, (Py_ssize_t)k);
            goto fail;
        }
        n = k;
    }
    {
        const size_t bytes = s->type == NPY_DOUBLE ? sizeof(double) : sizeof(float);
        static const double id_d[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
        static const float id_f[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
        for (Py_ssize_t i = 0; i < n; ++i) {
            PyObject *m = one ? meshes : PySequence_Fast_GET_ITEM(seq, i);
            const void *pose = p ? (const void *)((const char *)PyArray_DATA(p) + (size_t)i * 12 * bytes)
                                 : s->type == NPY_DOUBLE ? (const void *)id_d : (const void *)id_f;
            PyObject *what = PyUnicode_FromFormat("poses[%zd] (body %zd)", i, i);
            if (what == NULL)
                goto fail;
            const long id = ttd_py_scene_add_body(s, m, pose, what);
            Py_DECREF(what);
            if (id < 0)
                goto fail;
        }
    }
done:
    Py_XDECREF(seq);
    Py_XDECREF(p);
    return (PyObject *)s;
fail:
    Py_XDECREF(seq);
    Py_XDECREF(p);
    Py_DECREF(s);
    return NULL;
}

static void ttd_py_scene_dealloc(PyObject *obj)
{
    ttd_py_scene *s = (ttd_py_scene *)obj;
    ttd_scene_destroy(s->scene); /* before the meshes it refers to can go */
    Py_XDECREF(s->meshes);
    if (s->lock != NULL)
        PyThread_free_lock(s->lock);
    Py_TYPE(obj)->tp_free(obj);
}

static PyObject *ttd_py_scene_repr(PyObject *obj)
{
    ttd_py_scene *s = (ttd_py_scene *)obj;
    return PyUnicode_FromFormat("<ttd.Scene: %zd bodies, %s>", (Py_ssize_t)ttd_scene_body_count(s->scene),
                                s->type == NPY_NOTYPE ? "precision not yet known" : ttd_py_type_name(s->type));
}

static Py_ssize_t ttd_py_scene_len(PyObject *obj)
{
    return (Py_ssize_t)ttd_scene_body_count(((ttd_py_scene *)obj)->scene);
}

/* A body id argument: a non-negative integer below 2**32; -1 with an exception. */
static int ttd_py_scene_id(PyObject *obj, const char *name, uint32_t *id)
{
    if (PyBool_Check(obj) || !PyIndex_Check(obj)) {
        PyErr_Format(PyExc_TypeError, "%s must be an integer body id, not %.100s", name, Py_TYPE(obj)->tp_name);
        return -1;
    }
    PyObject *i = PyNumber_Index(obj);
    if (i == NULL)
        return -1;
    int overflow = 0;
    const long long v = PyLong_AsLongLongAndOverflow(i, &overflow);
    Py_DECREF(i);
    if (v == -1 && PyErr_Occurred())
        return -1;
    if (overflow || v < 0 || v >= (long long)UINT32_MAX) {
        PyErr_Format(PyExc_IndexError, "%s = %R is not a body id", name, obj);
        return -1;
    }
    *id = (uint32_t)v;
    return 0;
}

/* IndexError for an id that names no body present. */
static void ttd_py_scene_no_body(const ttd_py_scene *s, const char *name, uint32_t id)
{
    const size_t limit = ttd_scene_id_limit(s->scene);
    if (id < limit)
        PyErr_Format(PyExc_IndexError, "%s = %u: body %u was removed", name, (unsigned)id, (unsigned)id);
    else
        PyErr_Format(PyExc_IndexError, "%s = %u: no such body (ids are below %zu)", name, (unsigned)id, limit);
}

static int ttd_py_scene_present(const ttd_py_scene *s, uint32_t id)
{
    return s->scene != NULL && id < ttd_scene_id_limit(s->scene) && PyList_GET_ITEM(s->meshes, id) != Py_None;
}

/* The orientation's name of body id's mesh (for set_solid's refusal; id present). */
static const char *ttd_scene_body_orientation(const ttd_py_scene *s, uint32_t id)
{
    ttd_orientation o;
    PyObject *mesh = PyList_GET_ITEM(s->meshes, id);
    if (ttd_py_meshes_use(&mesh, 1) < 0) { /* being moved: its vertices cannot be read now */
        PyErr_Clear();
        return "unknown";
    }
    const ttd_status st = ttd_mesh_orientation(((const ttd_py_mesh *)mesh)->mesh, &o);
    ttd_py_meshes_release(&mesh, 1);
    return st == TTD_OK ? ttd_orientation_string(o) : "unknown";
}

PyDoc_STRVAR(ttd_py_scene_add_doc,
"add($self, mesh, pose=None)\n--\n\n"
"Adds a body of mesh (a ttd.Mesh of the scene's dtype) at the world pose ((4, 4) or (3, 4);\n"
"None: the identity) and returns its id (ids count up from 0 and are never reused).");

static PyObject *ttd_py_scene_add(PyObject *obj, PyObject *args, PyObject *kwargs)
{
    ttd_py_scene *s = (ttd_py_scene *)obj;
    static char *kwlist[] = {"mesh", "pose", NULL};
    PyObject *mesh, *pose = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O|O:add", kwlist, &mesh, &pose))
        return NULL;
    if (!PyObject_TypeCheck(mesh, &ttd_py_MeshType)) {
        PyErr_Format(PyExc_TypeError, "mesh must be a ttd.Mesh, not %.100s", Py_TYPE(mesh)->tp_name);
        return NULL;
    }
    const int type = s->type != NPY_NOTYPE ? s->type : ((const ttd_py_mesh *)mesh)->type;
    PyArrayObject *p = NULL;
    static const double id_d[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    static const float id_f[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    if (pose != NULL && pose != Py_None && (p = ttd_py_scene_poses(pose, type, 1, "pose")) == NULL)
        return NULL;
    const void *data = p ? PyArray_DATA(p) : type == NPY_DOUBLE ? (const void *)id_d : (const void *)id_f;
    PyObject *what = PyUnicode_FromFormat("pose (of the body being added, id %zu)", ttd_scene_id_limit(s->scene));
    long id = -1;
    if (what != NULL) {
        ttd_py_scene_lock(s);
        id = ttd_py_scene_add_body(s, mesh, data, what);
        ttd_py_scene_unlock(s);
        Py_DECREF(what);
    }
    Py_XDECREF(p);
    return id < 0 ? NULL : PyLong_FromLong(id);
}

PyDoc_STRVAR(ttd_py_scene_remove_doc,
"remove($self, id, /)\n--\n\n"
"Removes body id (IndexError when there is none). Its id is not given again; set_poses still\n"
"takes a pose for it (ignored).");

static PyObject *ttd_py_scene_remove(PyObject *obj, PyObject *arg)
{
    ttd_py_scene *s = (ttd_py_scene *)obj;
    uint32_t id;
    if (ttd_py_scene_id(arg, "id", &id) < 0)
        return NULL;
    ttd_py_scene_lock(s);
    int ok = ttd_py_scene_present(s, id) && ttd_scene_remove(s->scene, id) == TTD_OK;
    if (ok) {
        Py_INCREF(Py_None);
        PyList_SetItem(s->meshes, id, Py_None); /* releases the mesh: the C scene no longer refers to it */
    }
    ttd_py_scene_unlock(s);
    if (!ok) {
        ttd_py_scene_no_body(s, "id", id);
        return NULL;
    }
    Py_RETURN_NONE;
}

PyDoc_STRVAR(ttd_py_scene_set_pose_doc,
"set_pose($self, id, pose, /)\n--\n\n"
"Moves body id to the world pose ((4, 4) or (3, 4)), checked as the constructor checks poses.");

static PyObject *ttd_py_scene_set_pose(PyObject *obj, PyObject *args)
{
    ttd_py_scene *s = (ttd_py_scene *)obj;
    PyObject *id_obj, *pose;
    uint32_t id;
    if (!PyArg_ParseTuple(args, "OO:set_pose", &id_obj, &pose) || ttd_py_scene_id(id_obj, "id", &id) < 0)
        return NULL;
    if (!ttd_py_scene_present(s, id)) {
        ttd_py_scene_no_body(s, "id", id);
        return NULL;
    }
    PyArrayObject *p = ttd_py_scene_poses(pose, s->type, 1, "pose");
    if (p == NULL)
        return NULL;
    ttd_py_scene_lock(s);
    ttd_status st = TTD_ERR_INDEX_OUT_OF_RANGE;
    PyObject *mesh = NULL; /* the body's Mesh, held for the message */
    if (ttd_py_scene_present(s, id)) {
        mesh = PyList_GET_ITEM(s->meshes, id);
        Py_INCREF(mesh);
        if (ttd_py_meshes_use(&mesh, 1) == 0) { /* not while set_vertices moves it */
            ttd_py_meshes_release(&mesh, 1);
            st = s->type == NPY_DOUBLE ? ttd_scene_set_pose_d(s->scene, id, PyArray_DATA(p))
                                       : ttd_scene_set_pose_f(s->scene, id, PyArray_DATA(p));
        } else {
            st = TTD_PY_IN_USE;
        }
    }
    ttd_py_scene_unlock(s);
    if (st == TTD_PY_IN_USE) {
        Py_DECREF(mesh);
        Py_DECREF(p);
        return NULL;
    }
    if (st == TTD_ERR_INDEX_OUT_OF_RANGE)
        ttd_py_scene_no_body(s, "id", id);
    else if (st != TTD_OK) {
        PyObject *what = PyUnicode_FromFormat("pose (of body %u)", (unsigned)id);
        if (what != NULL) {
            ttd_py_scene_pose_error(st, ((const ttd_py_mesh *)mesh)->mesh, PyArray_DATA(p), s->type, what);
            Py_DECREF(what);
        }
    }
    Py_XDECREF(mesh);
    Py_DECREF(p);
    if (st != TTD_OK)
        return NULL;
    Py_RETURN_NONE;
}

PyDoc_STRVAR(ttd_py_scene_set_poses_doc,
"set_poses($self, poses, /)\n--\n\n"
"Moves every body at once: poses (id_limit, 4, 4) or (id_limit, 3, 4), one per id (the\n"
"entries of removed ids are ignored). Every pose is checked before any is set: a refused\n"
"pose leaves the scene as it was (ValueError naming the body).");

/* After a call on one pose per body id (p, the argument `arg`) refused with st: the exception
 * naming the first body whose pose the library's rule refuses, and why. 1 if one was named, 0
 * if none was (an exception may still be set, e.g. out of memory). Under the scene's lock. */
static int ttd_py_scene_name_refused(ttd_py_scene *s, size_t limit, PyArrayObject *p, int type, ttd_status st, const char *arg)
{
    const size_t bytes = type == NPY_DOUBLE ? sizeof(double) : sizeof(float);
    int named = 0;
    for (size_t id = 0; id < limit && !named; ++id) {
        PyObject *m = PyList_GET_ITEM(s->meshes, id);
        if (m == Py_None)
            continue;
        const void *pose = (const char *)PyArray_DATA(p) + id * 12 * bytes;
        PyObject *what = PyUnicode_FromFormat("%s[%zu] (body %zu)", arg, id, id);
        if (what == NULL)
            break;
        named = (st == TTD_ERR_BAD_POSE && ttd_py_scene_bad_rotation(pose, type, what)) ||
                (st == TTD_ERR_COORDINATE_RANGE && ttd_py_scene_bad_range(((ttd_py_mesh *)m)->mesh, pose, type, what));
        Py_DECREF(what);
    }
    return named;
}

static PyObject *ttd_py_scene_set_poses(PyObject *obj, PyObject *arg)
{
    ttd_py_scene *s = (ttd_py_scene *)obj;
    const int type = s->type == NPY_NOTYPE ? NPY_DOUBLE : s->type;
    PyArrayObject *p = ttd_py_scene_pose_array(arg, type, 0, "poses");
    if (p == NULL)
        return NULL;
    /* Under the lock, so that an add from another thread cannot come between the count and the
     * call: the ids counted, the bottom rows of present ids checked, the poses set, a refused
     * one named. */
    ttd_py_scene_lock(s);
    ttd_status st = TTD_OK;
    const size_t limit = ttd_scene_id_limit(s->scene);
    if ((size_t)PyArray_DIM(p, 0) != limit) {
        PyErr_Format(PyExc_ValueError, "poses holds %zd poses: the scene takes one per body id, %zu (id_limit)",
                     (Py_ssize_t)PyArray_DIM(p, 0), limit);
        goto done;
    }
    if ((p = ttd_py_scene_pose_rows(p, type, 0, "poses", s)) == NULL)
        goto done;
    if (limit > 0) {
        PyObject *const *items = PySequence_Fast_ITEMS(s->meshes);
        const Py_ssize_t n = PyList_GET_SIZE(s->meshes);
        if (ttd_py_meshes_use(items, n) < 0) /* not while set_vertices moves one */
            goto done;
        Py_BEGIN_ALLOW_THREADS
        st = type == NPY_DOUBLE ? ttd_scene_set_poses_d(s->scene, limit, PyArray_DATA(p))
                                : ttd_scene_set_poses_f(s->scene, limit, PyArray_DATA(p));
        Py_END_ALLOW_THREADS
        ttd_py_meshes_release(items, n);
    }
    if (st != TTD_OK) {
        if (!ttd_py_scene_name_refused(s, limit, p, type, st, "poses") && !PyErr_Occurred()) {
            if (st == TTD_ERR_OUT_OF_MEMORY)
                PyErr_NoMemory();
            else
                PyErr_Format(PyExc_ValueError, "poses: %s", ttd_status_string(st));
        }
    }
done:
    ttd_py_scene_unlock(s);
    Py_XDECREF(p);
    if (PyErr_Occurred())
        return NULL;
    Py_RETURN_NONE;
}

/* An unsigned 32-bit argument; -1 with an exception. */
static int ttd_py_scene_u32(PyObject *obj, const char *name, uint32_t *out)
{
    if (PyBool_Check(obj) || !PyIndex_Check(obj)) {
        PyErr_Format(PyExc_TypeError, "%s must be an integer (a 32-bit mask), not %.100s", name, Py_TYPE(obj)->tp_name);
        return -1;
    }
    PyObject *i = PyNumber_Index(obj);
    if (i == NULL)
        return -1;
    int overflow = 0;
    const long long v = PyLong_AsLongLongAndOverflow(i, &overflow);
    Py_DECREF(i);
    if (v == -1 && PyErr_Occurred())
        return -1;
    if (overflow || v < 0 || v > (long long)UINT32_MAX) {
        PyErr_Format(PyExc_ValueError, "%s = %R is out of range: a group or mask is 32 bits, 0 .. 2**32 - 1", name, obj);
        return -1;
    }
    *out = (uint32_t)v;
    return 0;
}

PyDoc_STRVAR(ttd_py_scene_set_filter_doc,
"set_filter($self, id, group, mask, /)\n--\n\n"
"Sets body id's collision group and mask (32-bit integers; each body starts in group 1 with\n"
"mask 0xFFFFFFFF). A pair (i, j) is queried when (group_i & mask_j) and (group_j & mask_i)\n"
"are both non-zero and the pair is not excluded.");

static PyObject *ttd_py_scene_set_filter(PyObject *obj, PyObject *args)
{
    ttd_py_scene *s = (ttd_py_scene *)obj;
    PyObject *id_obj, *g_obj, *m_obj;
    uint32_t id, group, mask;
    if (!PyArg_ParseTuple(args, "OOO:set_filter", &id_obj, &g_obj, &m_obj) || ttd_py_scene_id(id_obj, "id", &id) < 0 ||
        ttd_py_scene_u32(g_obj, "group", &group) < 0 || ttd_py_scene_u32(m_obj, "mask", &mask) < 0)
        return NULL;
    ttd_py_scene_lock(s);
    const int ok = ttd_py_scene_present(s, id) && ttd_scene_set_filter(s->scene, id, group, mask) == TTD_OK;
    ttd_py_scene_unlock(s);
    if (!ok) {
        ttd_py_scene_no_body(s, "id", id);
        return NULL;
    }
    Py_RETURN_NONE;
}

PyDoc_STRVAR(ttd_py_scene_exclude_doc,
"exclude($self, i, j, excluded=True)\n--\n\n"
"Excludes the pair of bodies i and j (i != j, either order) from every query, or with\n"
"excluded=False includes it again.");

static PyObject *ttd_py_scene_exclude(PyObject *obj, PyObject *args, PyObject *kwargs)
{
    ttd_py_scene *s = (ttd_py_scene *)obj;
    static char *kwlist[] = {"i", "j", "excluded", NULL};
    PyObject *i_obj, *j_obj;
    int excluded = 1;
    uint32_t i, j;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OO|p:exclude", kwlist, &i_obj, &j_obj, &excluded) ||
        ttd_py_scene_id(i_obj, "i", &i) < 0 || ttd_py_scene_id(j_obj, "j", &j) < 0)
        return NULL;
    if (i == j) {
        PyErr_Format(PyExc_ValueError, "i = j = %u: a pair is two different bodies", (unsigned)i);
        return NULL;
    }
    ttd_py_scene_lock(s);
    ttd_status st = TTD_ERR_INDEX_OUT_OF_RANGE;
    if (ttd_py_scene_present(s, i) && ttd_py_scene_present(s, j))
        st = ttd_scene_exclude_pair(s->scene, i, j, excluded);
    ttd_py_scene_unlock(s);
    if (st == TTD_ERR_INDEX_OUT_OF_RANGE)
        ttd_py_scene_no_body(s, ttd_py_scene_present(s, i) ? "j" : "i", ttd_py_scene_present(s, i) ? j : i);
    else if (st == TTD_ERR_OUT_OF_MEMORY)
        PyErr_NoMemory();
    else if (st != TTD_OK)
        PyErr_Format(PyExc_SystemError, "ttd: unexpected status %d from ttd_scene_exclude_pair", (int)st);
    if (st != TTD_OK)
        return NULL;
    Py_RETURN_NONE;
}

PyDoc_STRVAR(ttd_py_scene_set_solid_doc,
"set_solid($self, id, solid=True)\n--\n\n"
"Makes body id a solid (its mesh must be closed, wound outward or inward alike: ValueError\n"
"naming its Mesh.orientation for an open or inconsistently oriented mesh, the body unchanged),\n"
"or with solid=False a surface again (bodies start as surfaces). A pair of solids collides when\n"
"one lies inside the other (distance 0; the inner body's triangle 0 as witness, NO_TRIANGLE for\n"
"the outer), and its manifold holds the vertices of each body inside the other at negative\n"
"distances: minus their exact distance to the other's surface, depth = margin - distance past\n"
"the margin, normals out of the other body (docs/scenes.md, section 5b).");

static PyObject *ttd_py_scene_set_solid(PyObject *obj, PyObject *args, PyObject *kwargs)
{
    ttd_py_scene *s = (ttd_py_scene *)obj;
    static char *kwlist[] = {"id", "solid", NULL};
    PyObject *id_obj;
    int solid = 1;
    uint32_t id;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O|p:set_solid", kwlist, &id_obj, &solid) ||
        ttd_py_scene_id(id_obj, "id", &id) < 0)
        return NULL;
    ttd_py_scene_lock(s);
    ttd_status st = TTD_ERR_INDEX_OUT_OF_RANGE;
    if (ttd_py_scene_present(s, id))
        st = ttd_scene_set_solid(s->scene, id, solid);
    ttd_py_scene_unlock(s);
    if (st == TTD_ERR_INDEX_OUT_OF_RANGE)
        ttd_py_scene_no_body(s, "id", id);
    else if (st == TTD_ERR_MESH_NOT_CLOSED)
        PyErr_Format(PyExc_ValueError, "body %u cannot be a solid: its mesh is %s (Mesh.orientation): %s", (unsigned)id,
                     ttd_scene_body_orientation(s, id), ttd_status_string(st));
    else if (st == TTD_ERR_OUT_OF_MEMORY)
        PyErr_NoMemory();
    else if (st != TTD_OK)
        PyErr_Format(PyExc_SystemError, "ttd: unexpected status %d from ttd_scene_set_solid", (int)st);
    if (st != TTD_OK)
        return NULL;
    Py_RETURN_NONE;
}

/* ---- the queries ------------------------------------------------------------------------- */

typedef enum ttd_py_scene_kind { TTD_PY_SCOLLIDE, TTD_PY_SDISTANCE, TTD_PY_SCONTACTS, TTD_PY_SMANIFOLD } ttd_py_scene_kind;

/* The capsule that owns a ttd_scene_array whose buffer numpy arrays view. */
static void ttd_py_free_scene_array(PyObject *capsule)
{
    ttd_scene_array *a = PyCapsule_GetPointer(capsule, "ttd.scene_array");
    ttd_scene_array_free(a);
    free(a);
}

/* One library call of kind on scene (of type) with the lock released; its bodies' meshes (the
 * list meshes) are marked in use meanwhile (TTD_PY_IN_USE with RuntimeError when one is being
 * moved by Mesh.set_vertices). */
static ttd_status ttd_py_scene_call(ttd_py_scene_kind kind, const ttd_options *opt, ttd_scene *scene, int type,
                                    PyObject *meshes, double x, size_t max_points, void *out, void *nearest)
{
    const int d = type == NPY_DOUBLE;
    const float xf = ttd_py_to_float(x);
    ttd_status st = TTD_ERR_BAD_OPTIONS;
    PyObject *const *items = PySequence_Fast_ITEMS(meshes);
    const Py_ssize_t n = PyList_GET_SIZE(meshes);
    if (ttd_py_meshes_use(items, n) < 0)
        return TTD_PY_IN_USE;
    Py_BEGIN_ALLOW_THREADS
    switch (kind) {
    case TTD_PY_SCOLLIDE:
        st = d ? ttd_scene_collide_d(opt, scene, x, out) : ttd_scene_collide_f(opt, scene, xf, out);
        break;
    case TTD_PY_SDISTANCE:
        st = d ? ttd_scene_distance_d(opt, scene, x, out, nearest) : ttd_scene_distance_f(opt, scene, xf, out, nearest);
        break;
    case TTD_PY_SCONTACTS:
        st = d ? ttd_scene_contacts_d(opt, scene, x, out) : ttd_scene_contacts_f(opt, scene, xf, out);
        break;
    case TTD_PY_SMANIFOLD:
        st = d ? ttd_scene_manifold_d(opt, scene, x, max_points, out)
               : ttd_scene_manifold_f(opt, scene, xf, max_points, out);
        break;
    }
    Py_END_ALLOW_THREADS
    ttd_py_meshes_release(items, n);
    return st;
}

/* The exception for a query's status; -1. */
static int ttd_py_scene_query_raise(ttd_status st, ttd_py_scene_kind kind, const ttd_options *opt, double x, int type)
{
    if (st == TTD_PY_IN_USE) /* raised already */
        return -1;
    if (st == TTD_ERR_BAD_OPTIONS && ttd_py_check_options(opt) != TTD_ERR_BAD_OPTIONS) {
        PyObject *v = PyFloat_FromDouble(x);
        if (v == NULL)
            return -1;
        const int overflow = type == NPY_FLOAT && isfinite(x) && isinf(ttd_py_to_float(x));
        if (kind == TTD_PY_SDISTANCE)
            PyErr_Format(PyExc_ValueError, "upper_bound=%R is out of range: upper_bound >= 0 (math.inf for none)", v);
        else
            PyErr_Format(PyExc_ValueError, "margin=%R is out of range: a margin is finite and >= 0%s", v,
                         overflow ? " (it overflows float32, the scene's precision)" : "");
        Py_DECREF(v);
        return -1;
    }
    if (ttd_py_raise_fatal(st, opt) == 0)
        PyErr_Format(PyExc_SystemError, "ttd: unexpected status %d from a scene query", (int)st);
    return -1;
}

/* Runs a query that fills a ttd_scene_array and returns its items as a named tuple of views of
 * descr records. An empty scene of unknown precision is queried as an empty float64 scene. */
static PyObject *ttd_py_scene_array_query(ttd_py_scene *s, ttd_py_scene_kind kind, PyObject *isa, PyObject *threads,
                                          double x, size_t max_points)
{
    ttd_options opt;
    if (ttd_py_options(NULL, isa, threads, NULL, NULL, NULL, &opt) < 0)
        return NULL;
    ttd_scene_array *arr = calloc(1, sizeof *arr);
    if (arr == NULL)
        return PyErr_NoMemory();
    PyObject *capsule = NULL, *result = NULL;
    PyArrayObject *rec = NULL;
    ttd_py_scene_lock(s);
    ttd_scene *scene = s->scene, *temporary = NULL;
    int type = s->type;
    if (scene == NULL) {
        type = NPY_DOUBLE;
        if (ttd_scene_create_d(&temporary) != TTD_OK)
            temporary = NULL;
        scene = temporary;
    }
    ttd_status st = scene == NULL ? TTD_ERR_OUT_OF_MEMORY : ttd_py_scene_call(kind, &opt, scene, type, s->meshes, x, max_points, arr, NULL);
    ttd_scene_destroy(temporary);
    ttd_py_scene_unlock(s);
    if (st != TTD_OK) {
        ttd_py_scene_query_raise(st, kind, &opt, x, type);
        goto done;
    }
    const int f = type == NPY_FLOAT;
    PyArray_Descr *descr = kind == TTD_PY_SCOLLIDE ? ttd_py_hit_rec
                         : kind == TTD_PY_SCONTACTS ? ttd_py_scont_rec[f] : ttd_py_point_rec[f];
    PyTypeObject *rtype = kind == TTD_PY_SCOLLIDE ? ttd_py_SceneCollision
                        : kind == TTD_PY_SCONTACTS ? ttd_py_SceneContacts : ttd_py_SceneManifold;
    PyObject *const *names = kind == TTD_PY_SCOLLIDE ? ttd_py_hit_names
                           : kind == TTD_PY_SCONTACTS ? ttd_py_scont_names : ttd_py_point_names;
    const int nf = kind == TTD_PY_SCOLLIDE ? TTD_PY_NHIT : kind == TTD_PY_SCONTACTS ? TTD_PY_NSCONT : TTD_PY_NPOINT;
    npy_intp n = (npy_intp)arr->count;
    void *data = arr->data;
    capsule = PyCapsule_New(arr, "ttd.scene_array", ttd_py_free_scene_array);
    if (capsule == NULL)
        goto done;
    arr = NULL; /* the capsule's now */
    Py_INCREF(descr);
    rec = (PyArrayObject *)PyArray_NewFromDescr(&PyArray_Type, descr, 1, &n, NULL, n > 0 ? data : NULL,
                                                n > 0 ? NPY_ARRAY_CARRAY : 0, NULL);
    if (rec == NULL)
        goto done;
    if (n > 0) {
        const int bad = PyArray_SetBaseObject(rec, capsule); /* takes the capsule, even when it fails */
        capsule = NULL;
        if (bad < 0)
            goto done;
    }
    result = ttd_py_named_new(rtype, nf);
    if (result != NULL && ttd_py_set_views(result, 0, rec, names, nf) < 0)
        Py_CLEAR(result);
done:
    if (arr != NULL) {
        ttd_scene_array_free(arr);
        free(arr);
    }
    Py_XDECREF(capsule);
    Py_XDECREF(rec);
    return result;
}

PyDoc_STRVAR(ttd_py_scene_collide_doc,
"collide($self, margin=0.0, *, isa='auto', threads=0)\n--\n\n"
"Every eligible body pair (i, j), i < j, within margin (finite, >= 0; 0: touching or\n"
"crossing), with one witness pair of triangles each: a ttd.SceneCollision of (n,) uint32\n"
"arrays i, j, tri_i, tri_j, sorted by (i, j). The pairs are those whose distance over all\n"
"their triangle pairs in the world frame is <= margin. isa, threads: as in ttd.distance;\n"
"body pairs are spread over the threads and the result does not depend on either. The\n"
"interpreter lock is released while the library computes.");

static PyObject *ttd_py_scene_collide(PyObject *obj, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = {"margin", "isa", "threads", NULL};
    PyObject *margin_obj = NULL, *isa = NULL, *threads = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "|O$OO:collide", kwlist, &margin_obj, &isa, &threads))
        return NULL;
    double margin = 0;
    if (ttd_py_real_arg(margin_obj, "margin", &margin) < 0)
        return NULL;
    return ttd_py_scene_array_query((ttd_py_scene *)obj, TTD_PY_SCOLLIDE, isa, threads, margin, 0);
}

PyDoc_STRVAR(ttd_py_scene_contacts_doc,
"contacts($self, margin, *, isa='auto', threads=0)\n--\n\n"
"Every triangle pair within margin (finite, >= 0) of every eligible body pair: a\n"
"ttd.SceneContacts of parallel (n,) arrays i, j, tri_i, tri_j (uint32), distance, and p, q\n"
"(n, 3) (closest points on tri_i and tri_j, world frame; q == p at distance 0), sorted by\n"
"(i, j) then (tri_i, tri_j). The set equals the triangle pairs whose ttd.distance in the\n"
"world frame is <= margin, with the same distances and points, bit for bit. The arrays view\n"
"the buffer the C library filled. isa, threads: as in collide.");

static PyObject *ttd_py_scene_contacts(PyObject *obj, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = {"margin", "isa", "threads", NULL};
    PyObject *margin_obj, *isa = NULL, *threads = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O|$OO:contacts", kwlist, &margin_obj, &isa, &threads))
        return NULL;
    double margin = 0;
    if (margin_obj == Py_None) {
        PyErr_SetString(PyExc_TypeError, "margin must be a real number, not None");
        return NULL;
    }
    if (ttd_py_real_arg(margin_obj, "margin", &margin) < 0)
        return NULL;
    return ttd_py_scene_array_query((ttd_py_scene *)obj, TTD_PY_SCONTACTS, isa, threads, margin, 0);
}

PyDoc_STRVAR(ttd_py_scene_manifold_doc,
"manifold($self, margin, max_points=4, *, isa='auto', threads=0)\n--\n\n"
"Contact manifolds, what a simulator consumes: for every eligible body pair with triangle\n"
"pairs within margin (finite, >= 0), its contacts and the corners of flat contact they add\n"
"(where faces lie on faces: vertices within the margin of the other face, crossings of edges;\n"
"a box on a box: the corners of the faces' overlap) merged (in depth order, a point within\n"
"1e-3 of the smaller body's radius of a point kept goes) and at most max_points of them kept\n"
"(0: all): the deepest, then among the points of its level (within a quarter of the margin\n"
"left below it, none rising above a deeper one by more than 0.1 of their distance) the\n"
"farthest from it, the largest triangle, the largest area added. A\n"
"ttd.SceneManifold of parallel (n,) arrays i, j, tri_i, tri_j (uint32), point (n, 3) (the\n"
"midpoint of a point of each body, at their exact distance),\n"
"normal (n, 3) (unit, from body i towards body j, from the bodies' shapes: a face's normal\n"
"where a face of one body lies within the margin of the other, across two real edges, never\n"
"outside the normal cones of the contact's features where they meet; the same for any\n"
"triangulation of a flat face; docs/scenes.md, section 5a), distance (those points' d),\n"
"depth (margin - d), point_i and point_j (n, 3) (the point of each body) and key (uint64: the\n"
"features of both bodies the point lies on, unchanged while the contact persists; section\n"
"5c), grouped by body pair in (i, j) order. isa, threads: as in collide.");

static PyObject *ttd_py_scene_manifold(PyObject *obj, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = {"margin", "max_points", "isa", "threads", NULL};
    PyObject *margin_obj, *max_obj = NULL, *isa = NULL, *threads = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O|O$OO:manifold", kwlist, &margin_obj, &max_obj, &isa, &threads))
        return NULL;
    double margin = 0;
    if (margin_obj == Py_None) {
        PyErr_SetString(PyExc_TypeError, "margin must be a real number, not None");
        return NULL;
    }
    if (ttd_py_real_arg(margin_obj, "margin", &margin) < 0)
        return NULL;
    size_t max_points = 4;
    if (max_obj != NULL) {
        if (PyBool_Check(max_obj) || !PyIndex_Check(max_obj)) {
            PyErr_Format(PyExc_TypeError, "max_points must be an integer, not %.100s", Py_TYPE(max_obj)->tp_name);
            return NULL;
        }
        PyObject *i = PyNumber_Index(max_obj);
        if (i == NULL)
            return NULL;
        int overflow = 0;
        const long long v = PyLong_AsLongLongAndOverflow(i, &overflow);
        Py_DECREF(i);
        if (v == -1 && PyErr_Occurred())
            return NULL;
        if (overflow > 0 || (overflow == 0 && v < 0) || overflow < 0) {
            if (overflow > 0)
                max_points = 0; /* more than any pair has: all */
            else {
                PyErr_Format(PyExc_ValueError, "max_points=%R is out of range: >= 0 (0: every contact)", max_obj);
                return NULL;
            }
        } else
            max_points = (size_t)v;
    }
    return ttd_py_scene_array_query((ttd_py_scene *)obj, TTD_PY_SMANIFOLD, isa, threads, margin, max_points);
}

PyDoc_STRVAR(ttd_py_scene_distance_doc,
"distance($self, upper_bound=math.inf, *, nearest=False, isa='auto', threads=0)\n--\n\n"
"The closest eligible body pair: a ttd.SceneDistance of i, j, tri_i, tri_j (uint32), distance\n"
"and p, q ((3,), world frame; q == p at distance 0) as numpy scalars and arrays, ties to the\n"
"smallest (i, j) and then (tri_i, tri_j); beyond upper_bound (>= 0; math.inf: none) or with\n"
"no eligible pair, distance inf and i, j, tri_i, tri_j ttd.NO_TRIANGLE (p and q mean nothing\n"
"then). With nearest=True, its field nearest is a\n"
"ttd.SceneContacts of id_limit records, one per body id: i the id, j its nearest eligible\n"
"other body within upper_bound (p on body i; ties to the smallest partner, then triangles),\n"
"inf and ttd.NO_TRIANGLE for none and for removed ids; otherwise nearest is None. The\n"
"distance equals the minimum of ttd.distance over every triangle pair of every eligible body\n"
"pair in the world frame, bit for bit. isa, threads: as in collide.");

static PyObject *ttd_py_scene_distance(PyObject *obj, PyObject *args, PyObject *kwargs)
{
    ttd_py_scene *s = (ttd_py_scene *)obj;
    static char *kwlist[] = {"upper_bound", "nearest", "isa", "threads", NULL};
    PyObject *ub_obj = NULL, *isa = NULL, *threads = NULL;
    int want_nearest = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "|O$pOO:distance", kwlist, &ub_obj, &want_nearest, &isa, &threads))
        return NULL;
    double ub = (double)INFINITY;
    if (ttd_py_real_arg(ub_obj, "upper_bound", &ub) < 0)
        return NULL;
    ttd_options opt;
    if (ttd_py_options(NULL, isa, threads, NULL, NULL, NULL, &opt) < 0)
        return NULL;
    PyObject *result = NULL, *near = NULL;
    PyArrayObject *closest = NULL, *nearest = NULL;
    ttd_py_scene_lock(s);
    ttd_scene *scene = s->scene, *temporary = NULL;
    const int type = s->type == NPY_NOTYPE ? NPY_DOUBLE : s->type, f = type == NPY_FLOAT;
    if (scene == NULL && ttd_scene_create_d(&temporary) != TTD_OK)
        temporary = NULL;
    if (scene == NULL)
        scene = temporary;
    npy_intp limit = (npy_intp)ttd_scene_id_limit(scene);
    Py_INCREF(ttd_py_scont_rec[f]);
    closest = (PyArrayObject *)PyArray_NewFromDescr(&PyArray_Type, ttd_py_scont_rec[f], 0, NULL, NULL, NULL, 0, NULL);
    if (closest != NULL && want_nearest) {
        Py_INCREF(ttd_py_scont_rec[f]);
        nearest = (PyArrayObject *)PyArray_NewFromDescr(&PyArray_Type, ttd_py_scont_rec[f], 1, &limit, NULL, NULL, 0, NULL);
    }
    ttd_status st = TTD_OK;
    if (closest != NULL && (nearest != NULL || !want_nearest))
        st = scene == NULL ? TTD_ERR_OUT_OF_MEMORY
                           : ttd_py_scene_call(TTD_PY_SDISTANCE, &opt, scene, type, s->meshes, ub, 0, PyArray_DATA(closest),
                                               nearest ? PyArray_DATA(nearest) : NULL);
    ttd_scene_destroy(temporary);
    ttd_py_scene_unlock(s);
    if (closest == NULL || (want_nearest && nearest == NULL))
        goto done;
    if (st != TTD_OK) {
        ttd_py_scene_query_raise(st, TTD_PY_SDISTANCE, &opt, ub, type);
        goto done;
    }
    if (nearest != NULL) {
        if ((near = ttd_py_named_new(ttd_py_SceneContacts, TTD_PY_NSCONT)) == NULL ||
            ttd_py_set_views(near, 0, nearest, ttd_py_scont_names, TTD_PY_NSCONT) < 0)
            goto done;
    } else {
        near = Py_None;
        Py_INCREF(near);
    }
    if ((result = ttd_py_named_new(ttd_py_SceneDistance, TTD_PY_NSDIST)) == NULL ||
        ttd_py_set_views(result, 0, closest, ttd_py_scont_names, TTD_PY_NSCONT) < 0) {
        Py_CLEAR(result);
        goto done;
    }
    PyTuple_SET_ITEM(result, TTD_PY_NSDIST - 1, near);
    near = NULL;
done:
    Py_XDECREF(near);
    Py_XDECREF(closest);
    Py_XDECREF(nearest);
    return result;
}

static PyObject *ttd_py_scene_get_id_limit(PyObject *obj, void *closure)
{
    (void)closure;
    return PyLong_FromSize_t(ttd_scene_id_limit(((ttd_py_scene *)obj)->scene));
}

static PyObject *ttd_py_scene_get_dtype(PyObject *obj, void *closure)
{
    (void)closure;
    const ttd_py_scene *s = (const ttd_py_scene *)obj;
    if (s->type == NPY_NOTYPE)
        Py_RETURN_NONE;
    return (PyObject *)PyArray_DescrFromType(s->type);
}

static PyObject *ttd_py_scene_get_meshes(PyObject *obj, void *closure)
{
    (void)closure;
    return PyList_AsTuple(((ttd_py_scene *)obj)->meshes);
}

static PyObject *ttd_py_scene_get_ids(PyObject *obj, void *closure)
{
    (void)closure;
    const ttd_py_scene *s = (const ttd_py_scene *)obj;
    npy_intp n = (npy_intp)ttd_scene_body_count(s->scene), k = 0;
    PyArrayObject *a = (PyArrayObject *)PyArray_SimpleNew(1, &n, NPY_INTP);
    if (a == NULL)
        return NULL;
    npy_intp *d = PyArray_DATA(a);
    for (Py_ssize_t id = 0; id < PyList_GET_SIZE(s->meshes) && k < n; ++id)
        if (PyList_GET_ITEM(s->meshes, id) != Py_None)
            d[k++] = id;
    return (PyObject *)a;
}

static PyGetSetDef ttd_py_scene_getset[] = {
    {"id_limit", ttd_py_scene_get_id_limit, NULL, "one more than the largest body id given (removed ids included)", NULL},
    {"dtype", ttd_py_scene_get_dtype, NULL, "the scene's dtype (float32 or float64; None while no mesh has fixed it)", NULL},
    {"meshes", ttd_py_scene_get_meshes, NULL, "tuple of each id's Mesh (None for a removed id)", NULL},
    {"ids", ttd_py_scene_get_ids, NULL, "the ids of the bodies present, ascending (intp array)", NULL},
    {NULL, NULL, NULL, NULL, NULL},
};

PyDoc_STRVAR(ttd_py_scene_ccd_doc,
"ccd($self, poses_t1, *, min_separation=0.0, isa='auto', threads=0)\n--\n\n"
"Continuous collision over one step: every body moves rigidly from its pose in the scene\n"
"(t = 0) to poses_t1 (id_limit, 4, 4) or (id_limit, 3, 4) (t = 1): its origin on a straight\n"
"line, its rotation about one fixed axis at a constant rate (ttd.rigid_pose_at). Every eligible\n"
"body pair (filters, exclusions; solids as solids) that comes within min_separation (finite,\n"
">= 0) during the step: a ttd.SceneCCDResult of (n,) arrays i, j (uint32, i < j), toi (float64:\n"
"the pair's conservative time of impact, ttd.mesh_ccd_rigid's), tri_i, tri_j, flags, steps\n"
"(uint32) and distance (float64), sorted by (i, j). The scene is not changed (set_poses after).\n"
"isa, threads: as in collide; the result does not depend on them.");

/* The fields of a SceneCCDResult, from the library's items. */
static PyObject *ttd_py_scene_ccd_result(const ttd_scene_array *arr)
{
    const npy_intp n = (npy_intp)arr->count;
    const ttd_scene_ccd_hit *h = arr->data;
    PyArrayObject *a[8];
    const int types[8] = {NPY_UINT32, NPY_UINT32, NPY_DOUBLE, NPY_UINT32, NPY_UINT32, NPY_UINT32, NPY_UINT32, NPY_DOUBLE};
    for (int k = 0; k < 8; ++k)
        a[k] = (PyArrayObject *)PyArray_SimpleNew(1, (npy_intp[]){n}, types[k]);
    PyObject *res = NULL;
    for (int k = 0; k < 8; ++k)
        if (a[k] == NULL)
            goto done;
    for (npy_intp m = 0; m < n; ++m) {
        ((uint32_t *)PyArray_DATA(a[0]))[m] = h[m].i;
        ((uint32_t *)PyArray_DATA(a[1]))[m] = h[m].j;
        ((double *)PyArray_DATA(a[2]))[m] = h[m].toi;
        ((uint32_t *)PyArray_DATA(a[3]))[m] = h[m].tri_i;
        ((uint32_t *)PyArray_DATA(a[4]))[m] = h[m].tri_j;
        ((uint32_t *)PyArray_DATA(a[5]))[m] = h[m].flags;
        ((uint32_t *)PyArray_DATA(a[6]))[m] = h[m].steps;
        ((double *)PyArray_DATA(a[7]))[m] = h[m].distance;
    }
    PyObject *mod = PyImport_ImportModule("ttd._rigid");
    PyObject *cls = mod ? PyObject_GetAttrString(mod, "SceneCCDResult") : NULL;
    Py_XDECREF(mod);
    if (cls != NULL)
        res = PyObject_CallFunction(cls, "OOOOOOOO", a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7]);
    Py_XDECREF(cls);
done:
    for (int k = 0; k < 8; ++k)
        Py_XDECREF(a[k]);
    return res;
}

static PyObject *ttd_py_scene_ccd(PyObject *obj, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = {"poses_t1", "min_separation", "isa", "threads", NULL};
    PyObject *poses = NULL, *sep = NULL, *isa = NULL, *threads = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O|$OOO:ccd", kwlist, &poses, &sep, &isa, &threads))
        return NULL;
    double delta = 0;
    if (ttd_py_real_arg(sep, "min_separation", &delta) < 0)
        return NULL;
    if (!(delta >= 0) || !isfinite(delta)) {
        return ttd_py_value_error("min_separation=%R is out of range: finite and >= 0", delta);
    }
    ttd_options opt;
    if (ttd_py_options(NULL, isa, threads, NULL, NULL, NULL, &opt) < 0)
        return NULL;
    ttd_py_scene *s = (ttd_py_scene *)obj;
    const int type = s->type == NPY_NOTYPE ? NPY_DOUBLE : s->type;
    PyArrayObject *p = ttd_py_scene_pose_array(poses, type, 0, "poses_t1");
    if (p == NULL)
        return NULL;
    ttd_scene_array arr = {0};
    ttd_status st = TTD_OK;
    PyObject *result = NULL;
    ttd_py_scene_lock(s);
    const size_t limit = s->scene != NULL ? ttd_scene_id_limit(s->scene) : 0;
    if ((size_t)PyArray_DIM(p, 0) != limit) {
        PyErr_Format(PyExc_ValueError, "poses_t1 holds %zd poses: the scene takes one per body id, %zu (id_limit)",
                     (Py_ssize_t)PyArray_DIM(p, 0), limit);
        goto done;
    }
    if ((p = ttd_py_scene_pose_rows(p, type, 0, "poses_t1", s)) == NULL)
        goto done;
    if (s->scene != NULL) {
        PyObject *const *items = PySequence_Fast_ITEMS(s->meshes);
        const Py_ssize_t nm = PyList_GET_SIZE(s->meshes);
        if (ttd_py_meshes_use(items, nm) < 0)
            goto done;
        Py_BEGIN_ALLOW_THREADS
        st = type == NPY_DOUBLE ? ttd_scene_ccd_d(&opt, s->scene, limit, PyArray_DATA(p), delta, &arr)
                                : ttd_scene_ccd_f(&opt, s->scene, limit, PyArray_DATA(p), delta, &arr);
        Py_END_ALLOW_THREADS
        ttd_py_meshes_release(items, nm);
    }
    if (st == TTD_ERR_BAD_POSE || st == TTD_ERR_COORDINATE_RANGE) {
        if (!ttd_py_scene_name_refused(s, limit, p, type, st, "poses_t1") && !PyErr_Occurred())
            PyErr_Format(PyExc_ValueError, "poses_t1: %s", ttd_status_string(st));
    } else if (st != TTD_OK) {
        ttd_py_scene_query_raise(st, TTD_PY_SCOLLIDE, &opt, delta, type);
    } else {
        result = ttd_py_scene_ccd_result(&arr);
    }
done:
    ttd_py_scene_unlock(s);
    Py_XDECREF(p);
    ttd_scene_array_free(&arr);
    return result;
}

static PyMethodDef ttd_py_scene_type_methods[] = {
    {"add", (PyCFunction)(void (*)(void))ttd_py_scene_add, METH_VARARGS | METH_KEYWORDS, ttd_py_scene_add_doc},
    {"remove", ttd_py_scene_remove, METH_O, ttd_py_scene_remove_doc},
    {"set_pose", ttd_py_scene_set_pose, METH_VARARGS, ttd_py_scene_set_pose_doc},
    {"set_poses", ttd_py_scene_set_poses, METH_O, ttd_py_scene_set_poses_doc},
    {"set_filter", ttd_py_scene_set_filter, METH_VARARGS, ttd_py_scene_set_filter_doc},
    {"set_solid", (PyCFunction)(void (*)(void))ttd_py_scene_set_solid, METH_VARARGS | METH_KEYWORDS,
     ttd_py_scene_set_solid_doc},
    {"exclude", (PyCFunction)(void (*)(void))ttd_py_scene_exclude, METH_VARARGS | METH_KEYWORDS,
     ttd_py_scene_exclude_doc},
    {"collide", (PyCFunction)(void (*)(void))ttd_py_scene_collide, METH_VARARGS | METH_KEYWORDS,
     ttd_py_scene_collide_doc},
    {"distance", (PyCFunction)(void (*)(void))ttd_py_scene_distance, METH_VARARGS | METH_KEYWORDS,
     ttd_py_scene_distance_doc},
    {"contacts", (PyCFunction)(void (*)(void))ttd_py_scene_contacts, METH_VARARGS | METH_KEYWORDS,
     ttd_py_scene_contacts_doc},
    {"manifold", (PyCFunction)(void (*)(void))ttd_py_scene_manifold, METH_VARARGS | METH_KEYWORDS,
     ttd_py_scene_manifold_doc},
    {"ccd", (PyCFunction)(void (*)(void))ttd_py_scene_ccd, METH_VARARGS | METH_KEYWORDS, ttd_py_scene_ccd_doc},
    {NULL, NULL, 0, NULL},
};

static PySequenceMethods ttd_py_scene_as_sequence = {
    .sq_length = ttd_py_scene_len,
};

static PyTypeObject ttd_py_SceneType = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "ttd.Scene",
    .tp_basicsize = sizeof(ttd_py_scene),
    .tp_dealloc = ttd_py_scene_dealloc,
    .tp_repr = ttd_py_scene_repr,
    .tp_as_sequence = &ttd_py_scene_as_sequence,
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = ttd_py_scene_doc,
    .tp_methods = ttd_py_scene_type_methods,
    .tp_getset = ttd_py_scene_getset,
    .tp_new = ttd_py_scene_new,
};

/* ---- mass properties (ttd_mesh_mass_properties_d/_f) -------------------------------------- */

static PyStructSequence_Field ttd_py_mass_fields[] = {
    {"mass", "float: density * |volume|"},
    {"volume", "float: the signed volume (negative for a mesh wound inward)"},
    {"area", "float: the surface's area"},
    {"center", "float64, shape (3,): the centre of mass, in the mesh's coordinates"},
    {"inertia", "float64, shape (3, 3): the inertia tensor about the centre of mass"},
    {NULL, NULL},
};
static PyStructSequence_Desc ttd_py_mass_desc = {
    "ttd.MassProperties",
    "The result of ttd.mass_properties: a closed mesh's mass properties as a solid of uniform\n"
    "density (docs/mass-properties.md).",
    ttd_py_mass_fields, 5,
};
static PyTypeObject *ttd_py_MassProperties;
static PyObject *ttd_py_mass_names[5];

PyDoc_STRVAR(ttd_py_mass_properties_doc,
"mass_properties(mesh, density=1.0)\n--\n\n"
"The mass properties of a closed ttd.Mesh as a solid of uniform density (finite, > 0): a\n"
"ttd.MassProperties of mass (density * |volume|), volume (signed: negative for a mesh wound\n"
"inward), area, center (3,) and inertia (3, 3) about the center, in float64 for meshes of\n"
"either dtype, by the divergence theorem with compensated sums (docs/mass-properties.md).\n"
"Closed: every edge between two distinct vertex positions runs once each way; otherwise\n"
"ValueError. A closed mesh enclosing no volume has center and inertia NaN.");

static PyObject *ttd_py_mass_properties(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *kwlist[] = {"mesh", "density", NULL};
    PyObject *mesh, *dens = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O|O:mass_properties", kwlist, &mesh, &dens))
        return NULL;
    if (!PyObject_TypeCheck(mesh, &ttd_py_MeshType)) {
        PyErr_Format(PyExc_TypeError, "mesh must be a ttd.Mesh, not %.100s", Py_TYPE(mesh)->tp_name);
        return NULL;
    }
    double density = 1.0;
    if (dens != NULL && ttd_py_real_arg(dens, "density", &density) < 0)
        return NULL;
    if (!isfinite(density) || !(density > 0)) {
        PyErr_Format(PyExc_ValueError, "density=%R is out of range: a density is finite and > 0", dens);
        return NULL;
    }
    const ttd_py_mesh *m = (const ttd_py_mesh *)mesh;
    if (ttd_py_meshes_use(&mesh, 1) < 0)
        return NULL;
    ttd_mass_properties p;
    ttd_status st;
    Py_BEGIN_ALLOW_THREADS
    st = m->type == NPY_FLOAT ? ttd_mesh_mass_properties_f(m->mesh, density, &p)
                              : ttd_mesh_mass_properties_d(m->mesh, density, &p);
    Py_END_ALLOW_THREADS
    ttd_py_meshes_release(&mesh, 1);
    if (st == TTD_ERR_MESH_NOT_CLOSED) {
        PyErr_SetString(PyExc_ValueError, "mass_properties: the mesh is not closed (every edge between two vertex "
                                          "positions must run once each way, with one orientation)");
        return NULL;
    }
    if (st == TTD_ERR_OUT_OF_MEMORY)
        return PyErr_NoMemory();
    if (st != TTD_OK) {
        PyErr_Format(PyExc_SystemError, "ttd: unexpected status %d from mass_properties", (int)st);
        return NULL;
    }
    npy_intp d3 = 3, d33[2] = {3, 3};
    PyObject *c = PyArray_SimpleNew(1, &d3, NPY_DOUBLE), *I = PyArray_SimpleNew(2, d33, NPY_DOUBLE);
    PyObject *r = c && I ? ttd_py_named_new(ttd_py_MassProperties, 5) : NULL;
    if (r == NULL) {
        Py_XDECREF(c);
        Py_XDECREF(I);
        return NULL;
    }
    memcpy(PyArray_DATA((PyArrayObject *)c), p.center, sizeof p.center);
    memcpy(PyArray_DATA((PyArrayObject *)I), p.inertia, sizeof p.inertia);
    PyObject *mass = PyFloat_FromDouble(p.mass), *vol = PyFloat_FromDouble(p.volume), *area = PyFloat_FromDouble(p.area);
    if (!mass || !vol || !area) {
        Py_XDECREF(mass);
        Py_XDECREF(vol);
        Py_XDECREF(area);
        Py_DECREF(c);
        Py_DECREF(I);
        Py_DECREF(r);
        return NULL;
    }
    PyTuple_SET_ITEM(r, 0, mass);
    PyTuple_SET_ITEM(r, 1, vol);
    PyTuple_SET_ITEM(r, 2, area);
    PyTuple_SET_ITEM(r, 3, c);
    PyTuple_SET_ITEM(r, 4, I);
    return r;
}

static PyMethodDef ttd_py_mass_methods[] = {
    {"mass_properties", (PyCFunction)(void (*)(void))ttd_py_mass_properties, METH_VARARGS | METH_KEYWORDS,
     ttd_py_mass_properties_doc},
    {NULL, NULL, 0, NULL},
};

int ttd_py_scene_init(PyObject *module)
{
    if (!(ttd_py_MassProperties = ttd_py_named_tuple(module, &ttd_py_mass_desc, ttd_py_mass_names)) ||
        PyModule_AddFunctions(module, ttd_py_mass_methods) < 0)
        return -1;
    if (PyType_Ready(&ttd_py_SceneType) < 0 || ttd_py_scene_add_object(module, "Scene", (PyObject *)&ttd_py_SceneType) < 0)
        return -1;
    if (!(ttd_py_SceneCollision = ttd_py_named_tuple(module, &ttd_py_hit_desc, ttd_py_hit_names)) ||
        !(ttd_py_SceneContacts = ttd_py_named_tuple(module, &ttd_py_scont_desc, ttd_py_scont_names)) ||
        !(ttd_py_SceneDistance = ttd_py_named_tuple(module, &ttd_py_sdist_desc, ttd_py_sdist_names)) ||
        !(ttd_py_SceneManifold = ttd_py_named_tuple(module, &ttd_py_point_desc, ttd_py_point_names)))
        return -1;
    return ttd_py_scene_records(module);
}
