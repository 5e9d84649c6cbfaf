# SPDX-License-Identifier: MIT
"""Poses as users hold them: ttd.pose (rotation matrix or quaternion, and translation, to the
12-number [R | t] pose), ttd.orthonormalize (the nearest rotation), and the mesh queries with
world poses of both meshes (pose_a=, pose_b=), whose results are in the world frame."""
import math
from typing import Any, Optional, Tuple

import numpy as np
import numpy.typing as npt

from . import _ttd
from ._ttd import ClosestPartners, Mesh, MeshClosest, MeshCollision, MeshContacts, MeshDistance

_IDENTITY = np.eye(4)[:3].copy()
_IDENTITY.flags.writeable = False
_TOL = 1e-6  # the library's test of a rotation (include/ttd/ttd.h): every entry of R^T R - I


class _Required:
    """The default of margin in mesh_contacts and mesh_closest: poses may be left out (the
    identity), so margin follows a defaulted parameter, yet it must be given."""

    def __repr__(self) -> str:
        return "<required>"


_REQUIRED: Any = _Required()


def pose(R: Optional[npt.ArrayLike] = None, t: Optional[npt.ArrayLike] = None, quat: Optional[npt.ArrayLike] = None,
         order: str = "wxyz") -> npt.NDArray[np.float64]:
    """The pose [R | t] as a (3, 4) float64 array ((..., 3, 4) for batches), as the mesh queries take.

    R : (..., 3, 3) rotation matrices, or None.
    quat : (..., 4) quaternions, or None; normalised here (a zero quaternion is a ValueError).
        order="wxyz" (default: Eigen's and FCL's Quaternion(w, x, y, z), scipy's scalar_first)
        or "xyzw" (ROS's geometry_msgs/Quaternion, scipy's default).
    t : (..., 3) translations, or None (zero).

    Give R or quat (or neither: the identity), not both. Leading dimensions broadcast between
    the rotation and t. The result maps a body's coordinates into the parent frame:
    x_parent = R x + t (for a quaternion, R is the rotation it represents). Whether R is a
    rotation is checked by the queries (every entry of R^T R - I within 1e-6, det R > 0);
    ttd.orthonormalize() repairs matrices printed with few digits.
    """
    if R is not None and quat is not None:
        raise ValueError("pose takes R or quat, not both")
    if order not in ("wxyz", "xyzw"):
        raise ValueError(f"order must be 'wxyz' or 'xyzw', not {order!r}")
    if quat is not None:
        q = np.asarray(quat, dtype=np.float64)
        if q.shape[-1:] != (4,):
            raise ValueError(f"quat has shape {q.shape}: quaternions are (..., 4)")
        if order == "xyzw":
            q = q[..., [3, 0, 1, 2]]
        n = np.sqrt(np.sum(q * q, axis=-1, keepdims=True))
        if not np.all(np.isfinite(q)) or np.any(n == 0):
            raise ValueError("quat holds a zero or non-finite quaternion: it is no rotation")
        w, x, y, z = np.moveaxis(q / n, -1, 0)
        rot = np.stack([np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], -1),
                        np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], -1),
                        np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], -1)], -2)
    elif R is not None:
        rot = np.asarray(R, dtype=np.float64)
        if rot.shape[-2:] != (3, 3):
            raise ValueError(f"R has shape {rot.shape}: rotation matrices are (..., 3, 3)")
    else:
        rot = np.eye(3)
    tr = np.zeros(3) if t is None else np.asarray(t, dtype=np.float64)
    if tr.shape[-1:] != (3,):
        raise ValueError(f"t has shape {tr.shape}: translations are (..., 3)")
    lead = np.broadcast_shapes(rot.shape[:-2], tr.shape[:-1])
    out = np.empty(lead + (3, 4))
    out[..., :3] = rot
    out[..., 3] = tr
    return out


def _split(poses, name):
    """(R, t) of poses (..., 3, 4) or (..., 4, 4) as float64; the bottom row checked."""
    P = np.asarray(poses)
    if P.dtype.kind not in "biuf":
        raise TypeError(f"{name} has dtype {P.dtype}: poses are real")
    if P.ndim < 2 or P.shape[-2:] not in ((3, 4), (4, 4)):
        raise ValueError(f"{name} has shape {P.shape}: poses are (..., 4, 4) or (..., 3, 4)")
    P = P.astype(np.float64, copy=False)
    if P.shape[-2] == 4 and not np.all(P[..., 3, :] == (0, 0, 0, 1)):
        raise ValueError(f"{name}: the bottom row of a 4x4 pose must be 0 0 0 1")
    return P[..., :3, :3], P[..., :3, 3]


def orthonormalize(poses: npt.ArrayLike) -> npt.NDArray[np.floating]:
    """poses with each rotation part R replaced by the nearest rotation (the orthogonal polar
    factor U V^T of R = U S V^T): for poses printed or stored with few digits, which the
    queries' test (every entry of R^T R - I within 1e-6) refuses.

    poses : (..., 3, 3) rotation matrices, or (..., 3, 4) / (..., 4, 4) poses (t is kept).
    Returns a new array of the same shape, float32 for float32 input, float64 otherwise.
    Raises ValueError for a non-finite R or one with det R <= 0 (a reflection or a singular
    matrix: no rotation is near it in the sense of the polar factor).
    """
    P = np.asarray(poses)
    if P.dtype.kind not in "biuf":
        raise TypeError(f"poses has dtype {P.dtype}: poses are real")
    if P.ndim < 2 or P.shape[-2:] not in ((3, 3), (3, 4), (4, 4)):
        raise ValueError(f"poses has shape {P.shape}: orthonormalize takes (..., 3, 3), (..., 3, 4) or (..., 4, 4)")
    dtype = np.float32 if P.dtype == np.float32 else np.float64
    out = P.astype(np.float64, copy=True)
    if P.shape[-2:] == (4, 4) and not np.all(out[..., 3, :] == (0, 0, 0, 1)):
        raise ValueError("poses: the bottom row of a 4x4 pose must be 0 0 0 1")
    R = out[..., :3, :3]
    det = np.linalg.det(R) if R.size else np.zeros(R.shape[:-2])
    bad = ~(np.isfinite(det) & (det > 0))
    if np.any(bad):
        first = tuple(int(i) for i in np.argwhere(bad)[0])
        where = f"poses[{', '.join(map(str, first))}]" if first else "poses"
        raise ValueError(f"{where} has det R = {det[first]!r}: no rotation near it (a reflection, a singular "
                         "or a non-finite matrix)")
    if R.size:
        U, _, Vt = np.linalg.svd(R)
        out[..., :3, :3] = U @ Vt
    return out.astype(dtype, copy=False)


def _world(poses, name):
    """Checked world poses: (R (k, 3, 3), t (k, 3), single) in float64."""
    R, t = _split(poses, name)
    single = R.ndim == 2
    R, t = R.reshape(-1, 3, 3), t.reshape(-1, 3)
    if R.ndim != 3:
        raise ValueError(f"{name} has shape {np.shape(poses)}: one pose or (K, ...) poses")
    for k in range(len(R)):
        r = R[k]
        where = name if single else f"{name}[{k}]"
        if not (np.all(np.isfinite(r)) and np.all(np.isfinite(t[k]))):
            raise ValueError(f"{where} has a NaN or infinite entry")
        d = float(np.linalg.det(r))
        if not d > 0:
            raise ValueError(f"{where} is not a rotation: det R = {d!r}")
        defect = float(np.max(np.abs(r.T @ r - np.eye(3))))
        if not defect <= _TOL:
            raise ValueError(f"{where} is not a rotation within 1e-6: an entry of R^T R - I is {defect:.3g} "
                             "(ttd.orthonormalize repairs a rotation printed with few digits)")
    return R, t, single


def _relative(pose_a, pose_b, K_hint=None):
    """b's poses in a's frame from world poses, and a's world rotation and translation per pose
    (for mapping results back): (rel (K, 3, 4) or (3, 4), Ra (K, 3, 3), ta (K, 3))."""
    Ra, ta, sa = _world(_IDENTITY if pose_a is None else pose_a, "pose_a")
    Rb, tb, sb = _world(_IDENTITY if pose_b is None else pose_b, "pose_b")
    if len(Ra) != len(Rb) and min(len(Ra), len(Rb)) != 1:
        raise ValueError(f"pose_a holds {len(Ra)} poses and pose_b {len(Rb)}: give one of either, or as many")
    K = max(len(Ra), len(Rb))
    Ra, ta = np.broadcast_to(Ra, (K, 3, 3)), np.broadcast_to(ta, (K, 3))
    Rb, tb = np.broadcast_to(Rb, (K, 3, 3)), np.broadcast_to(tb, (K, 3))
    RaT = np.swapaxes(Ra, -1, -2)
    rel = np.empty((K, 3, 4))
    rel[:, :, :3] = RaT @ Rb
    rel[:, :, 3] = np.einsum("kij,kj->ki", RaT, tb - ta)
    if sa and sb:
        rel = rel[0]
    return rel, Ra, ta


def _to_world(x, Ra, ta, index=None):
    """Points x (..., 3) of a's frame to the world: Ra x + ta, per pose (index: the pose of
    each point's leading position, or None when x's first axis is the poses' or x is one)."""
    if x is None:
        return None
    dtype = x.dtype
    X = np.asarray(x, dtype=np.float64)
    if index is not None:
        R, t = Ra[index], ta[index]
        W = np.einsum("nij,nj->ni", R, X) + t
    elif X.ndim == 1:
        W = Ra[0] @ X + ta[0]
    else:
        extra = X.ndim - 2  # (K, 3) or (K, m, 3)
        R = Ra.reshape(Ra.shape[:1] + (1,) * extra + (3, 3))
        t = ta.reshape(ta.shape[:1] + (1,) * extra + (3,))
        W = np.einsum("...ij,...j->...i", R, X) + t
    return W.astype(dtype, copy=False)


def _poses_for(poses, pose_a, pose_b, query):
    if pose_a is None and pose_b is None:
        return (_IDENTITY if poses is None else poses), None
    if poses is not None:
        raise ValueError(f"mesh_{query}: poses (b in a's frame) and pose_a / pose_b (world poses) do not go "
                         "together")
    rel, Ra, ta = _relative(pose_a, pose_b)
    return rel, (Ra, ta)


def mesh_distance(a: Mesh, b: Mesh, poses: Optional[npt.ArrayLike] = None, *, pose_a: Optional[npt.ArrayLike] = None,
                  pose_b: Optional[npt.ArrayLike] = None, upper_bound: float = math.inf, rel_tol: float = 0.0,
                  isa: str = "auto", threads: int = 0, out: Optional[npt.NDArray[np.void]] = None,
                  solid: bool = False) -> MeshDistance:
    P, world = _poses_for(poses, pose_a, pose_b, "distance")
    r = _ttd.mesh_distance(a, b, P, upper_bound=upper_bound, rel_tol=rel_tol, isa=isa, threads=threads, out=out,
                           solid=solid)
    if world is None:
        return r
    return r._replace(p=_to_world(r.p, *world), q=_to_world(r.q, *world))


def mesh_contacts(a: Mesh, b: Mesh, poses: Optional[npt.ArrayLike] = None, margin: float = _REQUIRED, *,
                  pose_a: Optional[npt.ArrayLike] = None, pose_b: Optional[npt.ArrayLike] = None, isa: str = "auto",
                  threads: int = 0) -> MeshContacts:
    if margin is _REQUIRED:
        raise TypeError("mesh_contacts() missing required argument 'margin'")
    P, world = _poses_for(poses, pose_a, pose_b, "contacts")
    c = _ttd.mesh_contacts(a, b, P, margin, isa=isa, threads=threads)
    if world is None:
        return c
    return c._replace(p=_to_world(c.p, *world, index=c.pose), q=_to_world(c.q, *world, index=c.pose))


def mesh_closest(a: Mesh, b: Mesh, poses: Optional[npt.ArrayLike] = None, margin: float = _REQUIRED, *,
                 pose_a: Optional[npt.ArrayLike] = None, pose_b: Optional[npt.ArrayLike] = None, for_a: bool = True,
                 for_b: bool = True, isa: str = "auto", threads: int = 0,
                 out: Optional[Tuple[Optional[npt.NDArray[np.void]], Optional[npt.NDArray[np.void]]]] = None
                 ) -> MeshClosest:
    if margin is _REQUIRED:
        raise TypeError("mesh_closest() missing required argument 'margin'")
    P, world = _poses_for(poses, pose_a, pose_b, "closest")
    r = _ttd.mesh_closest(a, b, P, margin, for_a=for_a, for_b=for_b, isa=isa, threads=threads, out=out)
    if world is None:
        return r
    def moved(s: Optional[ClosestPartners]) -> Optional[ClosestPartners]:
        return None if s is None else s._replace(p=_to_world(s.p, *world), q=_to_world(s.q, *world))

    return r._replace(for_a=moved(r.for_a), for_b=moved(r.for_b))


def mesh_collide(a: Mesh, b: Mesh, poses: Optional[npt.ArrayLike] = None, margin: float = 0.0, *,
                 pose_a: Optional[npt.ArrayLike] = None, pose_b: Optional[npt.ArrayLike] = None, isa: str = "auto",
                 threads: int = 0, out: Optional[npt.NDArray[np.void]] = None, solid: bool = False) -> MeshCollision:
    P, _ = _poses_for(poses, pose_a, pose_b, "collide")
    return _ttd.mesh_collide(a, b, P, margin, isa=isa, threads=threads, out=out, solid=solid)


_WORLD = """
poses is b's pose in a's frame (the C library's convention): (K, 4, 4) or (K, 3, 4), or one
(4, 4) / (3, 4) pose; None (the default) is the identity. Instead of poses, world poses of
both meshes may be given: pose_a, pose_b (each one pose or K; None: the identity); b's pose in
a's frame is then inv(pose_a) @ pose_b (computed in float64), each world pose is checked as a
rotation (every entry of R^T R - I within 1e-6, det R > 0), and the result's points are mapped
to the world frame (new arrays, in the meshes' dtype). Without pose_a and pose_b the result is
exactly the extension's (views of the C library's records), in a's frame.

The extension's documentation follows.

"""
for _f in (mesh_distance, mesh_contacts, mesh_closest, mesh_collide):
    _doc = (getattr(_ttd, _f.__name__).__doc__ or "").split("--\n\n", 1)[-1]
    _f.__doc__ = f"{_f.__name__}: the mesh query, with world poses if wanted.\n" + _WORLD + _doc
del _f, _doc


def load_mesh(path: Any, *, precision: str = "float64", strict: bool = False, weld: Optional[float] = None
              ) -> Tuple[npt.NDArray[np.floating], npt.NDArray[np.uint32]]:
    """(vertices, faces) of the OBJ, STL, PLY, OFF, glTF or 3MF file at path, read by the C library's reader
    (docs/mesh-files.md): vertices (N, 3) float64 (or float32 with precision="float32"),
    faces (M, 3) uint32. OBJ lines that are not OBJ statements (FCL's header line of two counts,
    say) are skipped with a warning saying how many (strict=True refuses them). weld=tol merges
    the vertices within tol of each other as ttd.weld does (an STL soup becomes closed). A
    malformed file is a ValueError naming FILE:LINE or the byte."""
    vertices, faces, skipped, _dropped = _ttd.load_mesh(path, precision=precision, strict=strict, weld=weld)
    if skipped:
        import warnings

        warnings.warn(f"{path}: skipped {skipped} line(s) that are not OBJ statements (strict=True refuses them)",
                      stacklevel=2)
    return vertices, faces

