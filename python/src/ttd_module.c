/* SPDX-License-Identifier: MIT */
/* The extension module ttd._ttd: its initialisation (numpy's C API, the exception and warning
 * classes, the constants of include/ttd/ttd.h), the instruction-set queries and the version.
 * The queries themselves live in one file per family (ttd_pairs.c, ttd_mesh.c), each adding
 * its functions and types here. The Python package ttd re-exports all of it. */
#define TTD_PY_IMPORTS_NUMPY
#include "ttd_py.h"

PyObject *ttd_py_IsaUnavailableError;
PyObject *ttd_py_NonFiniteInputWarning;
PyObject *ttd_py_NotConvergedWarning;

PyDoc_STRVAR(ttd_py_isa_available_doc,
"isa_available(isa)\n--\n\n"
"True when the instruction set isa (a name from ttd.ISAS) is built into this ttd and\n"
"supported by this CPU and OS. 'auto' is never available as such (it picks one of the\n"
"others). Raises ValueError for an unknown name.");

static PyObject *ttd_py_isa_available(PyObject *self, PyObject *arg)
{
    (void)self;
    ttd_isa isa;
    if (ttd_py_isa_from_name(arg, &isa) < 0)
        return NULL;
    return PyBool_FromLong(ttd_isa_available(isa));
}

PyDoc_STRVAR(ttd_py_isa_selected_doc,
"isa_selected(isa='auto')\n--\n\n"
"The instruction set a call with this isa argument uses, as a name from ttd.ISAS: with\n"
"'auto' the best one available, or the one the environment variable TTD_ISA names.\n"
"Raises ttd.IsaUnavailableError when that one cannot run here.");

static PyObject *ttd_py_isa_selected(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *kwlist[] = {"isa", NULL};
    PyObject *name = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "|O:isa_selected", kwlist, &name))
        return NULL;
    ttd_options opt = ttd_default_options();
    if (name != NULL && ttd_py_isa_from_name(name, &opt.isa) < 0)
        return NULL;
    ttd_isa isa = ttd_isa_selected(&opt);
    if (isa == TTD_ISA_AUTO) {
        ttd_py_raise_fatal(TTD_ERR_ISA_UNAVAILABLE, &opt);
        return NULL;
    }
    return PyUnicode_FromString(ttd_isa_name(isa));
}

PyDoc_STRVAR(ttd_py_isa_lanes_doc,
"isa_lanes(isa='auto', precision='float64')\n--\n\n"
"Pairs computed side by side (SIMD lanes) by the instruction set isa in precision\n"
"'float32' or 'float64'; 1 for 'scalar'; 'auto' means the one isa_selected() gives. An\n"
"instruction set not built here gets the lanes its registers would hold.");

static PyObject *ttd_py_isa_lanes(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *kwlist[] = {"isa", "precision", NULL};
    PyObject *name = NULL, *precision = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "|OO:isa_lanes", kwlist, &name, &precision))
        return NULL;
    ttd_isa isa = TTD_ISA_AUTO;
    int type = NPY_DOUBLE;
    if (name != NULL && ttd_py_isa_from_name(name, &isa) < 0)
        return NULL;
    if (precision != NULL && ttd_py_precision(precision, &type) < 0)
        return NULL;
    if (type == NPY_NOTYPE) {
        PyErr_SetString(PyExc_ValueError, "isa_lanes needs a precision: 'float32' or 'float64'");
        return NULL;
    }
    if (isa == TTD_ISA_AUTO && ttd_isa_selected(NULL) == TTD_ISA_AUTO) {
        ttd_options opt = ttd_default_options();
        ttd_py_raise_fatal(TTD_ERR_ISA_UNAVAILABLE, &opt);
        return NULL;
    }
    return PyLong_FromLong(ttd_isa_lanes(isa, type == NPY_DOUBLE ? 8 : 4));
}

static PyMethodDef ttd_py_module_methods[] = {
    {"isa_available", ttd_py_isa_available, METH_O, ttd_py_isa_available_doc},
    {"isa_selected", (PyCFunction)(void (*)(void))ttd_py_isa_selected, METH_VARARGS | METH_KEYWORDS,
     ttd_py_isa_selected_doc},
    {"isa_lanes", (PyCFunction)(void (*)(void))ttd_py_isa_lanes, METH_VARARGS | METH_KEYWORDS, ttd_py_isa_lanes_doc},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef ttd_py_module = {
    PyModuleDef_HEAD_INIT,
    "ttd._ttd",
    "The C extension behind the ttd package (import ttd, not this).",
    -1,
    ttd_py_module_methods,
    NULL,
    NULL,
    NULL,
    NULL,
};

/* A tuple of the names name_of gives for 0..count-1. */
static PyObject *ttd_py_names(const char *(*name_of)(int), int count)
{
    PyObject *t = PyTuple_New(count);
    for (int i = 0; t != NULL && i < count; ++i) {
        PyObject *s = PyUnicode_FromString(name_of(i));
        if (s == NULL) {
            Py_CLEAR(t);
            break;
        }
        PyTuple_SET_ITEM(t, i, s);
    }
    return t;
}

static const char *ttd_py_method_name_of(int i) { return ttd_method_name((ttd_method)i); }
static const char *ttd_py_isa_name_of(int i) { return ttd_isa_name((ttd_isa)i); }

/* A new class added to the module under name; NULL with an exception on failure. */
static PyObject *ttd_py_new_class(PyObject *module, const char *qualified, const char *doc, PyObject *base,
                                  const char *name)
{
    PyObject *c = PyErr_NewExceptionWithDoc(qualified, doc, base, NULL);
    if (c == NULL)
        return NULL;
    Py_INCREF(c);
    if (PyModule_AddObject(module, name, c) < 0) {
        Py_DECREF(c);
        Py_DECREF(c);
        return NULL;
    }
    return c;
}

PyMODINIT_FUNC PyInit__ttd(void);
PyMODINIT_FUNC PyInit__ttd(void)
{
    import_array();
    PyObject *m = PyModule_Create(&ttd_py_module);
    if (m == NULL)
        return NULL;
    if (PyModule_AddFunctions(m, ttd_py_pairs_methods) < 0 || PyModule_AddFunctions(m, ttd_py_mesh_methods) < 0 ||
        PyModule_AddFunctions(m, ttd_py_points_methods) < 0 || PyModule_AddFunctions(m, ttd_py_ccd_methods) < 0)
        goto fail;
    ttd_py_IsaUnavailableError = ttd_py_new_class(
        m, "ttd.IsaUnavailableError",
        "The instruction set asked for (isa=..., or the environment variable TTD_ISA) is not built "
        "into this ttd or not supported by this CPU and OS.",
        PyExc_RuntimeError, "IsaUnavailableError");
    ttd_py_NonFiniteInputWarning = ttd_py_new_class(
        m, "ttd.NonFiniteInputWarning",
        "Some pairs had NaN or infinite coordinates: their outputs are NaN and flagged "
        "(ttd.Flag.NONFINITE); the other pairs were computed.",
        PyExc_RuntimeWarning, "NonFiniteInputWarning");
    ttd_py_NotConvergedWarning = ttd_py_new_class(
        m, "ttd.NotConvergedWarning",
        "An iterative method hit max_iterations on some pairs (ttd.Flag.NOT_CONVERGED): their "
        "points lie on the triangles but may not be the closest.",
        PyExc_RuntimeWarning, "NotConvergedWarning");
    if (!ttd_py_IsaUnavailableError || !ttd_py_NonFiniteInputWarning || !ttd_py_NotConvergedWarning)
        goto fail;

    if (PyModule_AddStringConstant(m, "version", ttd_version_string()) < 0 ||
        PyModule_AddIntConstant(m, "VERSION_MAJOR", TTD_VERSION_MAJOR) < 0 ||
        PyModule_AddIntConstant(m, "VERSION_MINOR", TTD_VERSION_MINOR) < 0 ||
        PyModule_AddIntConstant(m, "VERSION_PATCH", TTD_VERSION_PATCH) < 0 ||
        PyModule_AddIntConstant(m, "PAIR_NONFINITE", TTD_PAIR_NONFINITE) < 0 ||
        PyModule_AddIntConstant(m, "PAIR_DEGENERATE_S", TTD_PAIR_DEGENERATE_S) < 0 ||
        PyModule_AddIntConstant(m, "PAIR_DEGENERATE_T", TTD_PAIR_DEGENERATE_T) < 0 ||
        PyModule_AddIntConstant(m, "PAIR_INTERSECTING", TTD_PAIR_INTERSECTING) < 0 ||
        PyModule_AddIntConstant(m, "PAIR_NOT_CONVERGED", TTD_PAIR_NOT_CONVERGED) < 0 ||
        PyModule_AddIntConstant(m, "PAIR_FALLBACK", TTD_PAIR_FALLBACK) < 0)
        goto fail;
    PyObject *methods = ttd_py_names(ttd_py_method_name_of, TTD_METHOD_COUNT);
    if (methods == NULL || PyModule_AddObject(m, "METHODS", methods) < 0) {
        Py_XDECREF(methods);
        goto fail;
    }
    PyObject *isas = ttd_py_names(ttd_py_isa_name_of, TTD_ISA_COUNT);
    if (isas == NULL || PyModule_AddObject(m, "ISAS", isas) < 0) {
        Py_XDECREF(isas);
        goto fail;
    }
    if (ttd_py_pairs_init(m) < 0 || ttd_py_mesh_init(m) < 0 || ttd_py_scene_init(m) < 0 || ttd_py_points_init(m) < 0)
        goto fail;
    return m;
fail:
    Py_DECREF(m);
    return NULL;
}
