# SPDX-License-Identifier: MIT
"""ttd: minimum distance between 3D triangles and triangle meshes, on SIMD hardware.

numpy arrays in, numpy arrays out::

    import numpy as np, ttd
    S = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], float)   # one triangle: rows A, B, C
    T = S + [0, 0, 2]
    ttd.distance(S, T)                      # 2.0 (one pair: a numpy scalar)
    r = ttd.distance(Ss, Ts, points=True)   # (n, 3, 3) arrays: a ttd.PairResult of arrays
    r.distance, r.p, r.q, r.flags & ttd.Flag.INTERSECTING

    A = ttd.Mesh(vertices, faces)           # (n, 3) float32/float64, (m, 3) integers
    A = ttd.Mesh.from_file("bunny.obj")     # or an OBJ, STL, PLY, OFF, glTF or 3MF file (ttd.load_mesh reads one)
    B = ttd.Mesh(vertices2, faces2)
    d = ttd.mesh_distance(A, B, poses)      # poses (K, 4, 4) or (K, 3, 4): B in A's frame
    d.distance, d.p, d.q, d.tri_a, d.tri_b  # (K,), (K, 3), (K, 3), (K,), (K,)
    c = ttd.mesh_contacts(A, B, poses, 0.01)  # every triangle pair within 0.01, all poses
    ttd.mesh_collide(A, B, poses).hit       # (K,) bool

    scene = ttd.Scene([A, B, B], world_poses)   # bodies: meshes at world poses (N, 4, 4)
    scene.set_poses(new_poses)              # each step
    scene.collide(), scene.distance(), scene.contacts(0.01), scene.manifold(0.01, 4)

What is here: distance() (the pair API); Mesh and the mesh queries mesh_distance(),
mesh_contacts(), mesh_closest(), mesh_collide() with their result types (b's poses in a's
frame, or world poses pose_a= and pose_b= with results in the world frame); deforming meshes
(Mesh.set_vertices) and one mesh against itself (mesh_self_contacts(), mesh_self_collide());
pose() and
orthonormalize() for poses as users hold them (quaternions, matrices printed with few digits);
Scene, bodies of meshes at world poses, with the queries over every pair of bodies (collide,
distance, contacts, manifold) and their result types; the enums Method,
Isa, Flag and MeshFlag; the instruction-set queries isa_available(), isa_selected(),
isa_lanes(), version; the exception IsaUnavailableError and the warnings NonFiniteInputWarning
and NotConvergedWarning. ttd.dask runs batches of pairs and of poses larger than memory on a
Dask cluster.
"""
import enum

try:
    from ._ttd import (
        CLOSEST_DTYPE_FLOAT32,
        CLOSEST_DTYPE_FLOAT64,
        COLLISION_DTYPE,
        CONTACT_DTYPE_FLOAT32,
        CONTACT_DTYPE_FLOAT64,
        ISAS,
        MESH_RESULT_DTYPE_FLOAT32,
        MESH_RESULT_DTYPE_FLOAT64,
        METHODS,
        NO_TRIANGLE,
        RESULT_DTYPE_FLOAT32,
        RESULT_DTYPE_FLOAT64,
        SCENE_CONTACT_DTYPE_FLOAT32,
        SCENE_CONTACT_DTYPE_FLOAT64,
        SCENE_HIT_DTYPE,
        SCENE_POINT_DTYPE_FLOAT32,
        SCENE_POINT_DTYPE_FLOAT64,
        ClosestPartners,
        IsaUnavailableError,
        Mesh,
        MeshClosest,
        MeshCollision,
        MeshContacts,
        MeshDistance,
        NonFiniteInputWarning,
        NotConvergedWarning,
        PairResult,
        POINT_ABOVE_BOUND,
        POINT_DEGENERATE,
        POINT_INSIDE,
        POINT_NONFINITE,
        POINT_SIGN_UNPROVEN,
        POINT_RESULT_DTYPE_FLOAT32,
        POINT_RESULT_DTYPE_FLOAT64,
        ClosestPoints,
        Containment,
        SignedDistance,
        WindingNumber,
        closest_points,
        contains,
        sdf_grid,
        signed_distance,
        winding_number,
        MassProperties,
        Scene,
        SceneCollision,
        SceneContacts,
        SceneDistance,
        SceneManifold,
        SelfCollision,
        SelfContacts,
        distance,
        isa_available,
        isa_lanes,
        isa_selected,
        weld,
        mass_properties,
        mesh_self_collide,
        mesh_self_contacts,
        version,
    )
    from . import _ttd
    from ._poses import load_mesh, mesh_closest, mesh_collide, mesh_contacts, mesh_distance, orthonormalize, pose
    from ._ccd import (
        MESH_CCD_EE,
        MESH_CCD_FV,
        MESH_CCD_VF,
        CCDResult,
        MeshCCDResult,
        ccd_edge_edge,
        ccd_triangles,
        ccd_vertex_face,
        mesh_ccd,
        mesh_self_ccd,
    )
    from ._rigid import RigidCCDResult, SceneCCDResult, mesh_ccd_rigid, rigid_pose_at
except ImportError as e:  # pragma: no cover - only without a built extension
    raise ImportError(
        "ttd's C extension (ttd._ttd) is not built or not importable: install the package with "
        "`pip install --no-build-isolation ./python` from the repository root (python/README.md). "
        "Running from inside python/ makes the source folder shadow the installed package."
    ) from e

__version__ = version


class Method(str, enum.Enum):
    """The methods of ttd.distance(method=...); each member is also its name as a str."""

    EXACT = "exact"  #: exact to rounding (6 vertex-face, 9 edge-edge, 6 edge-face crossing tests)
    PENALTY = "penalty"  #: the paper's quasi-Newton penalty method, optimised and safeguarded
    PENALTY_REFERENCE = "penalty-ref"  #: the paper's MATLAB ttd1, step for step
    BARRIER = "barrier"  #: log-barrier Newton, the paper's first attempt
    CERTIFIED = "certified"  #: penalty, checked for optimality, failures sent to the exact method

    def __str__(self) -> str:
        return self.value


class Isa(str, enum.Enum):
    """Instruction sets for the isa= argument of every call; each member is also its name as a str."""

    AUTO = "auto"  #: the best one built and supported (or the one TTD_ISA names)
    SCALAR = "scalar"  #: plain C, one pair at a time
    SSE2 = "sse2"
    AVX2 = "avx2"  #: AVX2 with FMA
    AVX512 = "avx512"  #: AVX-512 F, DQ and VL
    NEON = "neon"
    PORTABLE = "portable"  #: GCC/clang vector extensions, any target

    def __str__(self) -> str:
        return self.value


class Flag(enum.IntFlag):
    """Per-pair flag bits, in PairResult.flags (the TTD_PAIR_* bits of the C library)."""

    NONFINITE = _ttd.PAIR_NONFINITE  #: input had NaN or inf: every output of the pair is NaN
    DEGENERATE_S = _ttd.PAIR_DEGENERATE_S  #: S has zero area (a segment or a point)
    DEGENERATE_T = _ttd.PAIR_DEGENERATE_T  #: T has zero area
    INTERSECTING = _ttd.PAIR_INTERSECTING  #: the triangles touch or cross: distance 0
    NOT_CONVERGED = _ttd.PAIR_NOT_CONVERGED  #: iterative method hit max_iterations
    FALLBACK = _ttd.PAIR_FALLBACK  #: certified method: computed by the exact method


class MeshFlag(enum.IntFlag):
    """Flag bits of a mesh distance, in MeshDistance.flags (the TTD_MESH_* bits of the C library)."""

    INTERSECTING = _ttd.MESH_INTERSECTING  #: the meshes touch or cross: distance 0, p == q
    ABOVE_BOUND = _ttd.MESH_ABOVE_BOUND  #: no pair within upper_bound: distance inf, no points or triangles
    CONTAINED = _ttd.MESH_CONTAINED  #: solid=True: one mesh inside the other (also INTERSECTING)


del enum  # used above only: not part of the package's namespace

__all__ = [
    "CCDResult",
    "ccd_edge_edge",
    "ccd_triangles",
    "ccd_vertex_face",
    "MeshCCDResult",
    "MESH_CCD_VF",
    "MESH_CCD_FV",
    "MESH_CCD_EE",
    "mesh_ccd",
    "mesh_ccd_rigid",
    "RigidCCDResult",
    "SceneCCDResult",
    "rigid_pose_at",
    "mesh_self_ccd",
    "CLOSEST_DTYPE_FLOAT32",
    "CLOSEST_DTYPE_FLOAT64",
    "COLLISION_DTYPE",
    "CONTACT_DTYPE_FLOAT32",
    "CONTACT_DTYPE_FLOAT64",
    "ClosestPartners",
    "Flag",
    "ISAS",
    "Isa",
    "IsaUnavailableError",
    "MESH_RESULT_DTYPE_FLOAT32",
    "MESH_RESULT_DTYPE_FLOAT64",
    "METHODS",
    "Mesh",
    "MeshClosest",
    "MeshCollision",
    "MeshContacts",
    "MeshDistance",
    "MeshFlag",
    "Method",
    "NO_TRIANGLE",
    "NonFiniteInputWarning",
    "NotConvergedWarning",
    "PairResult",
    "POINT_ABOVE_BOUND",
    "POINT_DEGENERATE",
    "POINT_INSIDE",
    "POINT_NONFINITE",
    "POINT_SIGN_UNPROVEN",
    "POINT_RESULT_DTYPE_FLOAT32",
    "POINT_RESULT_DTYPE_FLOAT64",
    "ClosestPoints",
    "Containment",
    "SignedDistance",
    "WindingNumber",
    "closest_points",
    "contains",
    "sdf_grid",
    "signed_distance",
    "winding_number",
    "RESULT_DTYPE_FLOAT32",
    "RESULT_DTYPE_FLOAT64",
    "SCENE_CONTACT_DTYPE_FLOAT32",
    "SCENE_CONTACT_DTYPE_FLOAT64",
    "SCENE_HIT_DTYPE",
    "SCENE_POINT_DTYPE_FLOAT32",
    "SCENE_POINT_DTYPE_FLOAT64",
    "MassProperties",
    "Scene",
    "SceneCollision",
    "SceneContacts",
    "SceneDistance",
    "SceneManifold",
    "SelfCollision",
    "SelfContacts",
    "__version__",
    "distance",
    "isa_available",
    "isa_lanes",
    "isa_selected",
    "load_mesh",
    "mass_properties",
    "mesh_closest",
    "mesh_collide",
    "mesh_contacts",
    "mesh_distance",
    "mesh_self_collide",
    "mesh_self_contacts",
    "orthonormalize",
    "pose",
    "version",
    "weld",
]
