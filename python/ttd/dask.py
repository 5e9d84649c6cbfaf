# SPDX-License-Identifier: MIT
"""Batches larger than one machine's memory, on Dask: ttd.distance chunk by chunk, and the mesh
queries over poses chunk by chunk.

    import dask.array as da
    from distributed import Client
    import ttd.dask

    client = Client("tcp://scheduler:8786")   # a cluster; Client(LocalCluster()) on one machine
    S = da.from_zarr("S.zarr")                # (n, 9) or (n, 3, 3), chunked along the pairs
    T = da.from_zarr("T.zarr")
    d = ttd.dask.distance(S, T, threads=1)    # lazy: a dask array of n distances
    d.min().compute(), (d < 0.01).sum().compute()

    A, B = ttd.Mesh(va, fa), ttd.Mesh(vb, fb)
    poses = da.from_zarr("poses.zarr")        # (K, 4, 4) or (K, 3, 4), chunked along K
    r = ttd.dask.mesh_distance(A, B, poses)   # lazy: (K,) records of ttd.MESH_RESULT_DTYPE_*
    r["distance"].min().compute(), r["tri_a"][:10].compute()
    hit = ttd.dask.mesh_collide(A, B, poses, 0.01)["hit"]   # (K,) bool, True where within 0.01
    P = da.from_zarr("points.zarr")           # (n, 3), chunked along the points
    r = ttd.dask.closest_points(A, P)         # lazy: (n,) records of ttd.POINT_RESULT_DTYPE_*
    sd = ttd.dask.signed_distance(A, P)       # lazy: (n,) signed distances
    inside = ttd.dask.contains(A, P)          # lazy: (n,) bool
    parts = ttd.dask.mesh_contacts(A, B, poses, 0.01)       # a dask.bag: one MeshContacts per chunk
    contacts = ttd.dask.concatenate_contacts(parts.compute())  # = ttd.mesh_contacts on all poses

Each chunk is one call on a worker, so only a chunk (of pairs, or of poses and their results)
must fit in a worker's memory at once. The results equal one call on everything, bit for bit:
a pair's result depends on that pair alone, and a pose's on that pose and the meshes alone,
not on the chunking or the thread count.

Meshes reach the workers by pickling: a ttd.Mesh pickles as its vertex and face arrays and is
rebuilt where it is unpickled (the build is deterministic: the same hierarchy, the same
results). The two meshes are one task of the graph (a dask.delayed), so each worker receives
and rebuilds them once per computation, not once per chunk.

ttd's threads option is per call: threads=0 (its default) uses every core of the worker's
machine in each call, which suits one worker thread per machine; with several worker threads
(or processes) per machine, threads=1 keeps them from competing for the cores. Warnings
(non-finite input, non-convergence) are issued on the workers, where Dask logs them.
"""
import functools

import numpy as np

import ttd

__all__ = ["COLLISION_DTYPE", "closest_points", "concatenate_contacts", "contains", "distance", "mesh_collide",
           "mesh_contacts", "mesh_distance", "signed_distance", "winding_number"]

#: The records of ttd.dask.mesh_collide: ttd.COLLISION_DTYPE's fields with hit as bool (as
#: ttd.mesh_collide's hit is), packed.
COLLISION_DTYPE = np.dtype([("hit", np.bool_), ("tri_a", np.uint32), ("tri_b", np.uint32), ("node_tests", np.uint32),
                            ("pair_tests", np.uint64)])


def _pairs_2d(X, name):
    if X.ndim == 2 and X.shape[1] == 9:
        return X
    if X.ndim == 3 and X.shape[1:] == (3, 3):
        return X.reshape((X.shape[0], 9))
    raise ValueError(f"{name} has shape {X.shape}: ttd.dask.distance takes (n, 9) or (n, 3, 3) arrays")


def distance(S, T, **options):
    """Distances of the pairs S[i], T[i] as a lazy dask array, one ttd.distance call per chunk.

    S, T: dask arrays (or anything dask.array.asarray takes) of shape (n, 9) or (n, 3, 3),
    chunked along the first axis; T is rechunked to S's chunks where they differ, and each
    triangle is kept whole within a chunk. options: those of ttd.distance (method, precision,
    isa, threads, rho, tol, max_iterations), checked here, before anything is computed, as is
    the dtype rule. points=True is not offered: compute the points of the pairs you keep (say,
    those within a margin) with ttd.distance(..., points=True) on them.

    Returns a dask array of shape (n,) and dtype float32 or float64 (as ttd.distance would).
    """
    import dask.array as da

    if options.get("points"):
        raise ValueError("ttd.dask.distance returns distances only; call ttd.distance(..., points=True) "
                         "on the pairs whose points you need")
    S = _pairs_2d(da.asarray(S), "S")
    T = _pairs_2d(da.asarray(T), "T")
    if S.shape[0] != T.shape[0]:
        raise ValueError(f"S and T hold {S.shape[0]} and {T.shape[0]} pairs: they must be equal")
    # Options and dtypes are checked now, on no pairs; the empty result gives the dtype.
    empty = ttd.distance(np.zeros((0, 9), S.dtype), np.zeros((0, 9), T.dtype), **options)
    S = S.rechunk({1: -1})
    T = T.rechunk((S.chunks[0], (9,)))
    return da.map_blocks(functools.partial(ttd.distance, **options), S, T, drop_axis=1, dtype=empty.dtype,
                         meta=empty, chunks=(S.chunks[0],))


# ---- meshes over chunks of poses ---------------------------------------------------------------

def _poses_3d(poses):
    import dask.array as da

    P = da.asarray(poses)
    if P.ndim != 3 or P.shape[1:] not in ((4, 4), (3, 4)):
        raise ValueError(f"poses has shape {P.shape}: ttd.dask's mesh queries take (K, 4, 4) or (K, 3, 4) arrays")
    return P.rechunk({1: -1, 2: -1})


def _meshes(a, b):
    """The two meshes as one task of the graph (see the module's docstring); checked here."""
    import dask

    for name, m in (("a", a), ("b", b)):
        if not isinstance(m, ttd.Mesh):
            raise TypeError(f"{name} must be a ttd.Mesh, not {type(m).__name__}")
    return dask.delayed((a, b), pure=False)


def _records_block(poses, meshes, query, dtype, margin, options):
    a, b = meshes
    if query == "distance":
        out = np.empty(len(poses), dtype)
        ttd.mesh_distance(a, b, poses, out=out, **options)
        return out
    rec = np.empty(len(poses), ttd.COLLISION_DTYPE)
    ttd.mesh_collide(a, b, poses, margin, out=rec, **options)
    out = np.empty(len(poses), dtype)
    for name in dtype.names:
        out[name] = rec[name] != 0 if name == "hit" else rec[name]
    return out


def _records(a, b, poses, query, margin, options):
    import dask.array as da

    for key in ("out",):
        if key in options:
            raise ValueError(f"ttd.dask.mesh_{query} makes its own arrays: {key}= is not taken")
    P = _poses_3d(poses)
    empty = np.zeros((0,) + P.shape[1:], P.dtype)
    # Arguments, options and dtypes are checked now, on no poses.
    if query == "distance":
        ttd.mesh_distance(a, b, empty, **options)
        dtype = ttd.MESH_RESULT_DTYPE_FLOAT64 if a.dtype == np.float64 else ttd.MESH_RESULT_DTYPE_FLOAT32
    else:
        ttd.mesh_collide(a, b, empty, margin, **options)
        dtype = COLLISION_DTYPE
    return da.map_blocks(_records_block, P, _meshes(a, b), query, dtype, margin, options, drop_axis=[1, 2],
                         dtype=dtype, meta=np.empty(0, dtype), chunks=(P.chunks[0],))


def mesh_distance(a, b, poses, **options):
    """ttd.mesh_distance over a dask array of poses, one call per chunk: a lazy dask array.

    a, b: ttd.Mesh (sent to the workers once, pickled); poses: a dask array (or anything
    dask.array.asarray takes) of shape (K, 4, 4) or (K, 3, 4), chunked along K. options: those
    of ttd.mesh_distance (upper_bound, rel_tol, isa, threads), checked here before anything
    is computed, as are the meshes.

    Returns a dask array of shape (K,) of records laid out as the C library's result struct,
    dtype ttd.MESH_RESULT_DTYPE_FLOAT64 (or FLOAT32 for float32 meshes): r["distance"],
    r["p"] (K, 3), r["tri_a"], ... are the fields of ttd.MeshDistance. Equal, field by field
    and bit for bit, to one ttd.mesh_distance call on all the poses.
    """
    return _records(a, b, poses, "distance", 0.0, options)


def mesh_collide(a, b, poses, margin=0.0, **options):
    """ttd.mesh_collide over a dask array of poses, one call per chunk: a lazy dask array of
    shape (K,) of ttd.dask.COLLISION_DTYPE records (r["hit"] is bool, True where the meshes
    come within margin, as ttd.mesh_collide's hit; r["tri_a"], r["tri_b"], r["node_tests"],
    r["pair_tests"] as in ttd.COLLISION_DTYPE). Arguments as in ttd.dask.mesh_distance; equal,
    field by field, to one ttd.mesh_collide call on all the poses."""
    return _records(a, b, poses, "collide", margin, options)


def _contacts_block(poses, meshes, margin, first, options):
    a, b = meshes
    c = ttd.mesh_contacts(a, b, poses, margin, **options)
    return [c._replace(pose=c.pose + first)]


def mesh_contacts(a, b, poses, margin, **options):
    """ttd.mesh_contacts over a dask array of poses, one call per chunk: a lazy dask.bag with one
    item per chunk of poses, that chunk's ttd.MeshContacts, whose pose column holds the global
    pose indices (its pose_start indexes its own arrays: the chunk's poses).

    Arguments as in ttd.dask.mesh_distance, plus margin. concatenate_contacts() of the items,
    in order, equals one ttd.mesh_contacts call on all the poses. The bag's own reductions work
    on the workers, e.g. parts.map(lambda c: c.distance.size).sum().compute() counts them.
    """
    import dask
    import dask.bag as db

    P = _poses_3d(poses)
    ttd.mesh_contacts(a, b, np.zeros((0,) + P.shape[1:], P.dtype), margin, **options)
    meshes = _meshes(a, b)
    firsts = np.cumsum((0,) + P.chunks[0])[:-1]
    block = dask.delayed(_contacts_block, pure=True)
    return db.from_delayed([block(chunk, meshes, margin, int(first), options)
                            for chunk, first in zip(P.to_delayed().ravel(), firsts)])


def concatenate_contacts(parts):
    """One ttd.MeshContacts from those of consecutive chunks of poses (in pose order), as
    ttd.dask.mesh_contacts gives them: their arrays joined and pose_start rebuilt over all the
    poses. The arrays are new and contiguous."""
    parts = list(parts)
    if not parts:
        raise ValueError("concatenate_contacts needs at least one ttd.MeshContacts")
    counts = np.cumsum([0] + [len(c.pose) for c in parts])
    starts = [c.pose_start[:-1] + n for c, n in zip(parts, counts)] + [np.array([counts[-1]])]
    joined = [np.concatenate([getattr(c, f) for c in parts]) for f in ("pose", "tri_a", "tri_b", "distance", "p", "q")]
    return ttd.MeshContacts(*joined, np.concatenate(starts).astype(np.intp))


# ---- point queries ------------------------------------------------------------------------------


def _points_2d(P):
    import dask.array as da

    P = da.asarray(P)
    if P.ndim != 2 or P.shape[1] != 3:
        raise ValueError(f"points has shape {P.shape}: ttd.dask's point queries take (n, 3) arrays")
    return P.rechunk({1: 3})


def _mesh_task(mesh):
    import dask

    if not isinstance(mesh, ttd.Mesh):
        raise TypeError(f"mesh must be a ttd.Mesh, not {type(mesh).__name__}")
    return dask.delayed(mesh, pure=False)


def _points_block(points, mesh, query, options):
    if query == "closest":
        r = ttd.closest_points(mesh, points, **options)
        out = np.empty(len(points), ttd.POINT_RESULT_DTYPE_FLOAT64 if mesh.dtype == np.float64 else ttd.POINT_RESULT_DTYPE_FLOAT32)
        for name in out.dtype.names:
            out[name] = getattr(r, name)
        return out
    if query == "signed":
        return ttd.signed_distance(mesh, points, **options).distance
    if query == "contains":
        return ttd.contains(mesh, points, **options).inside
    return ttd.winding_number(mesh, points, **options).winding


def _points(mesh, points, query, options):
    import dask.array as da

    P = _points_2d(points)
    empty = np.zeros((0, 3), P.dtype)
    # The mesh and the options are checked now, on no points.
    if query == "closest":
        ttd.closest_points(mesh, empty, **options)
        dtype = ttd.POINT_RESULT_DTYPE_FLOAT64 if mesh.dtype == np.float64 else ttd.POINT_RESULT_DTYPE_FLOAT32
    elif query == "signed":
        ttd.signed_distance(mesh, empty, **options)
        dtype = mesh.dtype
    elif query == "contains":
        ttd.contains(mesh, empty, **options)
        dtype = np.dtype(np.bool_)
    else:
        ttd.winding_number(mesh, empty, **options)
        dtype = np.dtype(np.float64)
    return da.map_blocks(_points_block, P, _mesh_task(mesh), query, options, drop_axis=[1], dtype=dtype,
                         meta=np.empty(0, dtype), chunks=(P.chunks[0],))


def closest_points(mesh, points, **options):
    """ttd.closest_points over a dask array of points (n, 3), one call per chunk: a lazy dask array of
    shape (n,) of records laid out as the C library's ttd_point_result_d/_f (dtype
    ttd.POINT_RESULT_DTYPE_FLOAT64 or FLOAT32, the mesh's): r["distance"], r["point"] (n, 3),
    r["triangle"], ... are the fields of ttd.ClosestPoints. options: those of ttd.closest_points
    (pose, upper_bound, isa, threads), checked here. Equal, bit for bit, to one call on all the points.
    """
    return _points(mesh, points, "closest", options)


def signed_distance(mesh, points, **options):
    """ttd.signed_distance over a dask array of points (n, 3), chunk by chunk: a lazy dask array of the
    n signed distances (negative inside), in the mesh's dtype. Equal, bit for bit, to one call."""
    return _points(mesh, points, "signed", options)


def winding_number(mesh, points, **options):
    """ttd.winding_number over a dask array of points (n, 3), chunk by chunk: a lazy float64 dask array
    of the n winding numbers. Equal, bit for bit, to one call."""
    return _points(mesh, points, "winding", options)


def contains(mesh, points, **options):
    """ttd.contains over a dask array of points (n, 3), chunk by chunk: a lazy bool dask array, True
    where a point is inside the mesh (winding number >= 1/2). Equal to one call."""
    return _points(mesh, points, "contains", options)
