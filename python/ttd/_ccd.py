# SPDX-License-Identifier: MIT
"""Continuous collision of moving vertex-face, edge-edge and triangle pairs (docs/ccd.md).

Every vertex moves on a straight line from its position at t = 0 to its position at t = 1. A
query hits when the Euclidean distance comes to ``min_separation`` or less for some t in [0, 1];
``toi`` is then a conservative time of impact (never after the true first time; within the
tolerance of docs/ccd.md of it), ``inf`` without a hit. No contact is ever missed.
"""
from typing import NamedTuple

import numpy as np

from . import _ttd


class CCDResult(NamedTuple):
    """Results of n continuous-collision queries, one entry per query."""

    hit: np.ndarray  #: (n,) bool: the distance comes to min_separation or less in [0, 1]
    toi: np.ndarray  #: (n,) float64: conservative time of impact; inf without a hit, NaN for non-finite input
    gap: np.ndarray  #: (n,) float64: the distance computed near toi (approximate); inf without a hit
    flags: np.ndarray  #: (n,) uint32: 1 = the search's budget ran out (a conservative hit), 2 = non-finite input
    sub: np.ndarray  #: (n,) uint32: ccd_triangles only: the sub-query that gave toi (docs/ccd.md)
    evals: np.ndarray  #: (n,) uint32: time intervals examined


CCDResult.__module__ = "ttd"  # pickles as ttd.CCDResult, the name users see


def _shaped(x, name, tail):
    a = np.asarray(x)
    if a.dtype.kind not in "biuf":
        raise TypeError(f"ttd: {name} must be real numbers, not {a.dtype}")
    if a.shape[-len(tail):] != tail or a.ndim not in (len(tail), len(tail) + 1):
        want = "(n, " + ", ".join(map(str, tail)) + ")"
        raise ValueError(f"ttd: {name} must have shape {want} or {tail}, not {a.shape}")
    return np.ascontiguousarray(a.reshape((-1,) + tail), dtype=np.float64)


def _run(kind, arrays, names, tails, min_separation, threads):
    shaped = [_shaped(x, n, t) for x, n, t in zip(arrays, names, tails)]
    n = shaped[0].shape[0]
    for a, nm in zip(shaped, names):
        if a.shape[0] != n:
            raise ValueError(f"ttd: {nm} holds {a.shape[0]} queries, {names[0]} {n}")
    if isinstance(min_separation, (bool, np.bool_)) or not isinstance(min_separation, (int, float, np.number)):
        raise TypeError("ttd: min_separation must be a real number")
    if isinstance(threads, (bool, np.bool_)) or not isinstance(threads, (int, np.integer)) or threads < 0:
        raise ValueError("ttd: threads must be an integer >= 0 (0: all cores)")
    hit, toi, gap, flags, sub, evals = _ttd._ccd(kind, *shaped, float(min_separation), int(threads))
    return CCDResult(hit, toi, gap, flags, sub, evals)


def ccd_vertex_face(v_t0, f_t0, v_t1, f_t1, *, min_separation=0.0, threads=0):
    """Vertex against triangle: v_t0, v_t1 (n, 3) the vertex at t = 0 and 1, f_t0, f_t1 (n, 3, 3)
    the triangle's vertices (rows). Returns a CCDResult (hit, toi, ...)."""
    return _run(0, (v_t0, f_t0, v_t1, f_t1), ("v_t0", "f_t0", "v_t1", "f_t1"),
                ((3,), (3, 3), (3,), (3, 3)), min_separation, threads)


def ccd_edge_edge(ea_t0, eb_t0, ea_t1, eb_t1, *, min_separation=0.0, threads=0):
    """Edge against edge: each (n, 2, 3), an edge's two endpoints at t = 0 or 1. Returns a CCDResult."""
    return _run(1, (ea_t0, eb_t0, ea_t1, eb_t1), ("ea_t0", "eb_t0", "ea_t1", "eb_t1"),
                ((2, 3), (2, 3), (2, 3), (2, 3)), min_separation, threads)


def ccd_triangles(ta_t0, tb_t0, ta_t1, tb_t1, *, min_separation=0.0, threads=0):
    """Triangle against triangle: each (n, 3, 3); the earliest of the 6 vertex-face and 9
    edge-edge sub-queries, ``sub`` the one that gave it. Returns a CCDResult."""
    return _run(2, (ta_t0, tb_t0, ta_t1, tb_t1), ("ta_t0", "tb_t0", "ta_t1", "tb_t1"),
                ((3, 3), (3, 3), (3, 3), (3, 3)), min_separation, threads)


class MeshCCDResult(NamedTuple):
    """Continuous collision of deforming meshes (ttd.mesh_ccd, ttd.mesh_self_ccd; docs/ccd.md,
    section 10): the earliest time of impact and every vertex-face / edge-edge pair whose own
    conservative time is within 2**-52 of it, sorted by time, then kind and ids."""

    toi: float  #: the earliest time of impact in [0, 1]; inf when nothing comes within min_separation
    kind: np.ndarray  #: (n,) uint8: 0 vertex of a / triangle of b, 1 triangle of a / vertex of b, 2 edge / edge
    a: np.ndarray  #: (n, 2) int64: kind 0 (vertex, -1), 1 (triangle, -1), 2 the edge's vertices (smaller first)
    b: np.ndarray  #: (n, 2) int64: kind 0 (triangle, -1), 1 (vertex, -1), 2 the edge's vertices (smaller first)
    pair_toi: np.ndarray  #: (n,) float64: each pair's own conservative time of impact
    gap: np.ndarray  #: (n,) float64: the distance computed near that time (approximate)
    flags: np.ndarray  #: (n,) uint32: 1 = the pair's search used up its budget (a conservative hit)
    triangle_pairs: int  #: triangle pairs whose swept boxes came within min_separation
    queries: int  #: primitive pairs whose swept boxes came within min_separation (each once; self: of the triangle pairs not proved apart whole)
    searches: int  #: of those, the ones not proved apart by a face normal / edge cross product: searched


MeshCCDResult.__module__ = "ttd"

MESH_CCD_VF, MESH_CCD_FV, MESH_CCD_EE = 0, 1, 2


def _t1(mesh, x, name):
    if not isinstance(mesh, _ttd.Mesh):
        raise TypeError(f"ttd: the mesh must be a ttd.Mesh, not {type(mesh).__name__}")
    a = np.asarray(x)
    if a.dtype.kind not in "biuf":
        raise TypeError(f"ttd: {name} must be real numbers, not {a.dtype}")
    if a.shape != (mesh.vertex_count, 3):
        raise ValueError(f"ttd: {name} must have shape ({mesh.vertex_count}, 3) (the mesh's vertices at t = 1), "
                         f"not {a.shape}")
    # C-contiguous and aligned: an unaligned view (np.frombuffer at an odd offset) is copied.
    return np.require(a, dtype=mesh.dtype, requirements=['C', 'A'])


def _sep_threads(min_separation, threads):
    if isinstance(min_separation, (bool, np.bool_)) or not isinstance(min_separation, (int, float, np.number)):
        raise TypeError("ttd: min_separation must be a real number")
    if isinstance(threads, (bool, np.bool_)) or not isinstance(threads, (int, np.integer)) or threads < 0:
        raise ValueError("ttd: threads must be an integer >= 0 (0: all cores)")
    return float(min_separation), int(threads)


def mesh_ccd(a, a_vertices_t1, b, b_vertices_t1, *, min_separation=0.0, threads=0):
    """Two deforming meshes: a's vertices move on straight lines from ``a.vertices`` (t = 0) to
    ``a_vertices_t1`` (t = 1), b's likewise. Every vertex of one against every triangle of the
    other and every edge against every edge; returns a MeshCCDResult (``toi`` inf where nothing
    comes within ``min_separation``). No contact is missed; toi is never after the true first time."""
    x1 = _t1(a, a_vertices_t1, "a_vertices_t1")
    y1 = _t1(b, b_vertices_t1, "b_vertices_t1")
    if a.dtype != b.dtype:
        raise ValueError(f"ttd: both meshes must have one dtype, not {a.dtype} and {b.dtype}")
    d, t = _sep_threads(min_separation, threads)
    return MeshCCDResult(*_ttd._mesh_ccd(a, x1, b, y1, d, 0, t))


def mesh_self_ccd(mesh, vertices_t1, *, min_separation=0.0, shared_vertex=False, threads=0):
    """One deforming mesh against itself: the vertex-face and edge-edge pairs of triangle pairs that
    share no vertex (``shared_vertex``: also those sharing exactly one, less the sub-queries whose two
    primitives share a vertex). Each pair once; in a MeshCCDResult kind is 0 (vertex a[0] against
    triangle b[0]) or 2 (edge a against edge b, a < b)."""
    x1 = _t1(mesh, vertices_t1, "vertices_t1")
    d, t = _sep_threads(min_separation, threads)
    return MeshCCDResult(*_ttd._mesh_ccd(mesh, x1, None, None, d, 1 if shared_vertex else 0, t))
