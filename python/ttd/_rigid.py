# SPDX-License-Identifier: MIT
"""Continuous collision of rigid bodies between two poses (docs/ccd.md, section 13).

Each body has a world pose at t = 0 and one at t = 1 (``x_world = R x + t``, (3, 4) or (4, 4)
arrays as ttd.pose makes them). Between them its origin moves on a straight line and it turns
about one fixed axis at a constant rate: ``R(t) = Rot(u, t theta) R0`` with ``R1 R0^T = Rot(u,
theta)``, theta in [0, pi] (at a half turn, the axis whose largest component is positive).
``ttd.rigid_pose_at`` gives the pose at any t.
"""
import math
from typing import NamedTuple

import numpy as np

from . import _ttd
from ._poses import _world


class RigidCCDResult(NamedTuple):
    """Continuous collision of two rigid meshes (ttd.mesh_ccd_rigid)."""

    toi: float  #: conservative time of impact in [0, 1]; inf when the bodies stay beyond min_separation
    hit: bool  #: they come within min_separation (or within ``tolerance`` of it)
    distance: float  #: the exact mesh distance computed at toi; inf without a hit or with flags 1
    tolerance: float  #: at toi the distance is at most min_separation + tolerance
    flags: int  #: 1 (TTD_CCD_BUDGET): the step bound was reached; toi is then a conservative hit
    steps: int  #: mesh distance queries made (conservative advancement's steps)
    tri_a: int  #: the closest triangle of a at toi (-1 without a hit)
    tri_b: int  #: the closest triangle of b at toi (-1 without a hit)


RigidCCDResult.__module__ = "ttd"


class SceneCCDResult(NamedTuple):
    """Continuous collision over a scene's step (ttd.Scene.ccd): one entry per body pair that
    comes within min_separation, sorted by (i, j)."""

    i: np.ndarray  #: (n,) uint32: the first body
    j: np.ndarray  #: (n,) uint32: the second body, j > i
    toi: np.ndarray  #: (n,) float64: the pair's conservative time of impact (ttd.mesh_ccd_rigid's)
    tri_i: np.ndarray  #: (n,) uint32: the closest triangle of body i at toi (2**32 - 1 with flags 1)
    tri_j: np.ndarray  #: (n,) uint32: the closest triangle of body j at toi
    flags: np.ndarray  #: (n,) uint32: 1: the step bound was reached (a conservative hit)
    steps: np.ndarray  #: (n,) uint32: the pair's conservative-advancement steps
    distance: np.ndarray  #: (n,) float64: the exact distance computed at toi


SceneCCDResult.__module__ = "ttd"


def _two_poses(mesh, p0, p1, name):
    if not isinstance(mesh, _ttd.Mesh):
        raise TypeError(f"ttd: the mesh must be a ttd.Mesh, not {type(mesh).__name__}")
    out = np.empty((2, 3, 4))
    for k, p in enumerate((p0, p1)):
        R, t, single = _world(p, f"{name}{k}")
        if not single:
            raise ValueError(f"ttd: {name}{k} must be one pose, (3, 4) or (4, 4)")
        out[k, :, :3] = R[0]
        out[k, :, 3] = t[0]
    return np.ascontiguousarray(out, dtype=mesh.dtype)


def mesh_ccd_rigid(a, pose_a0, pose_a1, b, pose_b0, pose_b1, *, min_separation=0.0):
    """Two rigid meshes, each moving from its pose at t = 0 to its pose at t = 1: the earliest
    time their distance comes to ``min_separation`` (>= 0) or less, by conservative advancement
    with the exact mesh distance. No contact is missed; ``toi`` is never after the true first
    time, and at toi the distance is at most min_separation + ``tolerance``. Returns a
    RigidCCDResult; ``toi`` inf where there is no hit. A float32 mesh takes its poses in float32."""
    pa = _two_poses(a, pose_a0, pose_a1, "pose_a")
    pb = _two_poses(b, pose_b0, pose_b1, "pose_b")
    if a.dtype != b.dtype:
        raise ValueError(f"ttd: both meshes must have one dtype, not {a.dtype} and {b.dtype}")
    if isinstance(min_separation, (bool, np.bool_)) or not isinstance(min_separation, (int, float, np.number)):
        raise TypeError("ttd: min_separation must be a real number")
    d = float(min_separation)
    if not (d >= 0 and math.isfinite(d)):
        raise ValueError(f"ttd: min_separation must be finite and >= 0 (got {d})")
    return RigidCCDResult(*_ttd._mesh_ccd_rigid(a, pa, b, pb, d))


def rigid_pose_at(pose0, pose1, t):
    """The (3, 4) pose at time t in [0, 1] of the rigid motion from pose0 to pose1, each one pose
    ((3, 4) or (4, 4); a batch raises ValueError) (the motion
    mesh_ccd_rigid and Scene.ccd assume)."""
    R0, t0, single0 = _world(pose0, "pose0")
    R1, t1, single1 = _world(pose1, "pose1")
    if not (single0 and single1):  # a batch (K, 3, 4) would silently use its first pose
        raise ValueError("ttd: pose0 and pose1 must each be one pose, (3, 4) or (4, 4)")
    p0 = np.concatenate([R0[0], t0[0][:, None]], axis=1).ravel()
    p1 = np.concatenate([R1[0], t1[0][:, None]], axis=1).ravel()
    return np.array(_ttd._rigid_pose_at(tuple(map(float, p0)), tuple(map(float, p1)), float(t))).reshape(3, 4)
