/* SPDX-License-Identifier: MIT */
/* What the files of the extension module ttd._ttd share: the numpy C API set-up, the module's
 * exception and warning classes, and the helpers that turn Python arguments into the C
 * library's inputs (options, instruction sets, precisions, coordinate arrays) and a C status
 * into a Python exception or warning. Each query family (pairs, meshes) lives in its own file
 * and uses only these helpers and include/ttd/ttd.h. */
#ifndef TTD_PY_H
#define TTD_PY_H

#define PY_SSIZE_T_CLEAN
#include <Python.h>

/* One numpy API table for the whole module: ttd_module.c imports it, the others use it. */
#define NPY_NO_DEPRECATED_API NPY_1_7_API_VERSION
#define PY_ARRAY_UNIQUE_SYMBOL ttd_py_ARRAY_API
#ifndef TTD_PY_IMPORTS_NUMPY
#define NO_IMPORT_ARRAY
#endif
#include <numpy/arrayobject.h>

#include <ttd/ttd.h>

/* Classes made by ttd_module.c (strong references held for the module's lifetime). */
extern PyObject *ttd_py_IsaUnavailableError; /* RuntimeError: the instruction set cannot run here */
extern PyObject *ttd_py_NonFiniteInputWarning; /* RuntimeWarning: some pairs had NaN/inf */
extern PyObject *ttd_py_NotConvergedWarning;   /* RuntimeWarning: an iterative method hit its cap */

/* Options from the keyword arguments every query takes; NULL or None means the default.
 * On error returns -1 with a Python exception set. Ranges are left to the library (see
 * ttd_py_raise_fatal), so that they are checked in one place. */
int ttd_py_options(PyObject *method, PyObject *isa, PyObject *threads, PyObject *rho, PyObject *tol,
                   PyObject *max_iterations, ttd_options *out);

/* A real-number argument (int, float, numpy scalar; not bool or str) as a double, left as it is
 * for NULL or None; -1 with TypeError naming it (what) otherwise. Ranges are the caller's. */
int ttd_py_real_arg(PyObject *obj, const char *what, double *out);

/* An instruction set name (or a str subclass such as ttd.Isa) to its enum; -1 with ValueError
 * or TypeError set otherwise. */
int ttd_py_isa_from_name(PyObject *name, ttd_isa *out);

/* precision: None -> NPY_NOTYPE (take it from the arrays), else NPY_FLOAT or NPY_DOUBLE;
 * -1 with an exception set for anything else. */
int ttd_py_precision(PyObject *precision, int *type_num);

/* The float type a coordinate array is computed in when no precision is asked for: float32 ->
 * NPY_FLOAT, float64 -> NPY_DOUBLE, integers and bools -> NPY_DOUBLE (exact up to 2^53); -1
 * with TypeError (naming the argument) for any other dtype. */
int ttd_py_natural_type(PyArrayObject *a, const char *name);

/* obj as an array of its own dtype (anything numpy.asarray takes); NULL with an exception
 * (TypeError naming the argument for None). */
PyArrayObject *ttd_py_as_array(PyObject *obj, const char *name);

/* a converted to a C-contiguous, aligned, native-order array of type_num (a itself when it
 * already is one; a copy otherwise); TypeError naming the argument when a's dtype is not real
 * (bool, integer or float). */
PyArrayObject *ttd_py_as_real(PyArrayObject *a, const char *name, int type_num);

/* For a fatal status (>= TTD_ERR_FIRST_FATAL) of a call made with opt: raises the Python
 * exception that names the problem and returns -1. Returns 0 for TTD_OK and the two non-fatal
 * statuses, which the caller reports as warnings with the counts only it knows. */
int ttd_py_raise_fatal(ttd_status st, const ttd_options *opt);

/* Raises ValueError with format, whose one %R is value as Python writes a float (PyErr_Format
 * has no %g: it would print the letters). Returns NULL, for `return ttd_py_value_error(...)`. */
PyObject *ttd_py_value_error(const char *format, double value);

/* The array's shape as a tuple, for messages; NULL with an exception on failure. */
PyObject *ttd_py_shape(PyArrayObject *a);

/* A numpy record dtype laid out as a C struct: n fields with their names, numpy formats ("f8",
 * "(3,)f4", "u4", ...) and offsetof() offsets, and the struct's size; NULL with an exception. */
PyArray_Descr *ttd_py_record_descr(int n, PyObject *const names[], const char *const formats[],
                                   const size_t offsets[], size_t itemsize);

/* A result type: a real named tuple, collections.namedtuple(name, fields, module="ttd") (with
 * _fields, _asdict, _replace; it pickles as ttd.<name>), with desc's docstring on the class
 * and on each field, added to the module under desc's name without its "ttd." prefix; the
 * field names are interned into names (a PyStructSequence_Field array serves as the list of
 * names and docstrings). A new reference kept for the module's lifetime, or
 * NULL with an exception. */
PyTypeObject *ttd_py_named_tuple(PyObject *module, const PyStructSequence_Desc *desc, PyObject *names[]);

/* A new instance of the named tuple type with n items, all NULL until the caller sets them
 * with PyTuple_SET_ITEM; NULL with an exception. */
PyObject *ttd_py_named_new(PyTypeObject *type, Py_ssize_t n);

/* Sets items first .. first + n - 1 of the named tuple to the views rec[names[i]] of a
 * record array (numpy scalars where a view has no dimensions); -1 with an exception. */
int ttd_py_set_views(PyObject *tuple, int first, PyArrayObject *rec, PyObject *const names[], int n);

/* The shape (a, b, 3, 3) or (a, b, 9) of triangles: the number of leading dimensions, written
 * to *lead (0 for a single triangle), or -1 with ValueError naming the argument. */
int ttd_py_triangle_lead(PyArrayObject *a, const char *name, int *lead);

/* 0 when a (lead_a leading dimensions) and b (lead_b) have the same pair dimensions; -1 with
 * ValueError naming both ("S and T") otherwise. */
int ttd_py_same_lead(PyArrayObject *a, int lead_a, PyArrayObject *b, int lead_b, const char *names);

/* The status the library gives a one-pair call with opt: its checks of the options and of the
 * instruction set, for calls with nothing to compute (so that errors never depend on n). */
ttd_status ttd_py_check_options(const ttd_options *opt);

/* Ctrl-C in long calls. A batch of n items (points, poses, grid slabs, pairs) is computed by
 * fn(ctx, begin, end) on the items [begin, end), with the interpreter lock released, in pieces:
 * the first of `first` items (a batch that small is one call, as before), then pieces grown or
 * shrunk so that each takes about a tenth of a second. Between pieces, with the lock held, it
 * calls PyErr_CheckSignals() from the calling thread: a Ctrl-C (SIGINT) in the main thread raises
 * KeyboardInterrupt there and the batch stops within about a piece. Returns 0 with *st the first
 * fatal status (which stops the batch) or else the worst non-fatal one (TTD_ERR_NONFINITE_INPUT
 * over TTD_WARN_NOT_CONVERGED over TTD_OK); -1 with the signal handler's exception set, when
 * the caller must free what it made and return NULL. */
typedef ttd_status (*ttd_py_piece_fn)(void *ctx, size_t begin, size_t end);
int ttd_py_run_pieces(size_t n, size_t first, ttd_py_piece_fn fn, void *ctx, ttd_status *st);

/* A ttd.Mesh (ttd_mesh.c): the C mesh and the arrays it was built from. */
typedef struct ttd_py_mesh {
    PyObject_HEAD
    ttd_mesh *mesh;
    PyArrayObject *vertices; /* (nv, 3), the mesh's dtype, read-only, owned */
    PyArrayObject *faces;    /* (nt, 3) uint32, read-only, owned */
    int type;                /* NPY_DOUBLE or NPY_FLOAT */
    /* Calls that use the C mesh with the interpreter lock released (queries), and whether
     * Mesh.set_vertices is moving it: the library's mesh must not be read while it is written,
     * so each refuses to start while the other runs (RuntimeError). Read and written with the
     * lock held. */
    Py_ssize_t users;
    int moving;
} ttd_py_mesh;
extern PyTypeObject ttd_py_MeshType;

/* Marks every ttd.Mesh in objs (a sequence; other items are skipped) as used by a call about to
 * release the interpreter lock: 0, or -1 with RuntimeError when one is being moved by
 * set_vertices (then none is marked). ttd_py_meshes_release undoes it. */
int ttd_py_meshes_use(PyObject *const *objs, Py_ssize_t n);
/* The status a query wrapper returns when ttd_py_meshes_use refused (the exception is set). */
#define TTD_PY_IN_USE ((ttd_status)-1)
/* The status a wrapper returns when ttd_py_run_pieces was interrupted (the exception is set). */
#define TTD_PY_INTERRUPTED ((ttd_status)-2)
void ttd_py_meshes_release(PyObject *const *objs, Py_ssize_t n);

/* The mesh coordinate range, for messages. */
#define TTD_PY_RANGE_TEXT "|x| <= 2**60 (about 1.2e18) in float32 and 2**508 (about 8e152) in float64"

/* A real that was a double, as the float the float entries take (beyond float's range:
 * infinite). */
float ttd_py_to_float(double x);

/* Query families: each adds its functions and types to the module. */
int ttd_py_pairs_init(PyObject *module);
extern PyMethodDef ttd_py_pairs_methods[];
int ttd_py_mesh_init(PyObject *module);
extern PyMethodDef ttd_py_mesh_methods[];
int ttd_py_scene_init(PyObject *module); /* ttd.Scene and its result types (ttd_scene.c) */
int ttd_py_points_init(PyObject *module); /* the point queries and their result types (ttd_points.c) */
extern PyMethodDef ttd_py_points_methods[];
extern PyMethodDef ttd_py_ccd_methods[]; /* continuous collision's private _ccd (ttd_ccd.c; ttd/_ccd.py) */

#endif /* TTD_PY_H */
