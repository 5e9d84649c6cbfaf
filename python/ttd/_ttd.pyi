# SPDX-License-Identifier: MIT
# Type hints for the C extension ttd._ttd (python/src/), re-exported by the ttd package:
# the pair API, then the mesh objects and queries, then scenes of many bodies.
from typing import Any, Literal, NamedTuple, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

MethodName = Literal["exact", "penalty", "penalty-ref", "barrier", "certified"]
IsaName = Literal["auto", "scalar", "sse2", "avx2", "avx512", "neon", "portable"]
Precision = Union[None, Literal["float32", "float64", "single", "double"], type, np.dtype]
Real = Union[np.float32, np.float64]

version: str
VERSION_MAJOR: int
VERSION_MINOR: int
VERSION_PATCH: int
METHODS: Tuple[str, ...]
ISAS: Tuple[str, ...]
PAIR_NONFINITE: int
PAIR_DEGENERATE_S: int
PAIR_DEGENERATE_T: int
PAIR_INTERSECTING: int
PAIR_NOT_CONVERGED: int
PAIR_FALLBACK: int
RESULT_DTYPE_FLOAT64: np.dtype
RESULT_DTYPE_FLOAT32: np.dtype

class IsaUnavailableError(RuntimeError): ...
class NonFiniteInputWarning(RuntimeWarning): ...
class NotConvergedWarning(RuntimeWarning): ...

class PairResult(NamedTuple):
    """Everything ttd knows about each pair; arrays (numpy scalars for one pair)."""

    distance: Union[npt.NDArray[np.floating], Real]
    p: npt.NDArray[np.floating]
    q: npt.NDArray[np.floating]
    bary_p: npt.NDArray[np.floating]
    bary_q: npt.NDArray[np.floating]
    flags: Union[npt.NDArray[np.uint32], np.uint32]
    feature_p: Union[npt.NDArray[np.uint8], np.uint8]
    feature_q: Union[npt.NDArray[np.uint8], np.uint8]
    iterations: Union[npt.NDArray[np.uint16], np.uint16]

@overload
def distance(
    S: npt.ArrayLike,
    T: npt.ArrayLike,
    *,
    method: Union[MethodName, str] = "exact",
    precision: Precision = None,
    points: Literal[False] = False,
    isa: Union[IsaName, str] = "auto",
    threads: int = 0,
    rho: Optional[float] = None,
    tol: Optional[float] = None,
    max_iterations: Optional[int] = None,
    out: Optional[npt.NDArray[np.floating]] = None,
) -> Union[npt.NDArray[np.floating], Real]: ...
@overload
def distance(
    S: npt.ArrayLike,
    T: npt.ArrayLike,
    *,
    method: Union[MethodName, str] = "exact",
    precision: Precision = None,
    points: Literal[True],
    isa: Union[IsaName, str] = "auto",
    threads: int = 0,
    rho: Optional[float] = None,
    tol: Optional[float] = None,
    max_iterations: Optional[int] = None,
    out: Optional[npt.NDArray[np.void]] = None,
) -> PairResult: ...
def isa_available(isa: Union[IsaName, str]) -> bool: ...
def isa_selected(isa: Union[IsaName, str] = "auto") -> str: ...
def isa_lanes(isa: Union[IsaName, str] = "auto", precision: Precision = "float64") -> int: ...

# ---- meshes --------------------------------------------------------------------------------

MESH_INTERSECTING: int
MESH_ABOVE_BOUND: int
MESH_CONTAINED: int
NO_TRIANGLE: int
MESH_RESULT_DTYPE_FLOAT64: np.dtype
MESH_RESULT_DTYPE_FLOAT32: np.dtype
CONTACT_DTYPE_FLOAT64: np.dtype
CONTACT_DTYPE_FLOAT32: np.dtype
CLOSEST_DTYPE_FLOAT64: np.dtype
CLOSEST_DTYPE_FLOAT32: np.dtype
COLLISION_DTYPE: np.dtype

class Mesh:
    """A triangle mesh and its hierarchy; its faces fixed, its vertices movable (set_vertices);
    pickles as (vertices, faces)."""

    def __init__(
        self,
        vertices: npt.ArrayLike,
        faces: npt.ArrayLike,
        *,
        precision: Precision = None,
        threads: int = 0,
    ) -> None: ...
    @property
    def vertices(self) -> npt.NDArray[np.floating]: ...
    @property
    def faces(self) -> npt.NDArray[np.uint32]: ...
    @property
    def dtype(self) -> np.dtype: ...
    @property
    def vertex_count(self) -> int: ...
    @property
    def triangle_count(self) -> int: ...
    @property
    def node_count(self) -> int: ...
    @property
    def generation(self) -> int: ...
    @property
    def rebuilds(self) -> int: ...
    @property
    def orientation(self) -> Literal["outward", "inward", "inconsistent", "open", "flat"]: ...
    def set_vertices(self, vertices: npt.ArrayLike, *, threads: int = 0) -> None: ...
    def __reduce__(self) -> Tuple[type, Tuple[npt.NDArray[np.floating], npt.NDArray[np.uint32]]]: ...
    @classmethod
    def from_file(cls, path: Any, *, precision: str = "float64", threads: int = 0, strict: bool = False,
                  weld: Optional[float] = None) -> "Mesh": ...

def load_mesh(
    path: Any, *, precision: str = "float64", strict: bool = False, weld: Optional[float] = None
) -> Tuple[npt.NDArray[np.floating], npt.NDArray[np.uint32], int, int]: ...

@overload
def weld(
    vertices: npt.ArrayLike, faces: npt.ArrayLike, tolerance: float, *, precision: Optional[str] = None,
    return_index: Literal[False] = ...
) -> Tuple[npt.NDArray[np.floating], npt.NDArray[np.uint32]]: ...
@overload
def weld(
    vertices: npt.ArrayLike, faces: npt.ArrayLike, tolerance: float, *, precision: Optional[str] = None,
    return_index: Literal[True]
) -> Tuple[npt.NDArray[np.floating], npt.NDArray[np.uint32], npt.NDArray[np.uint32]]: ...

Floats = Union[npt.NDArray[np.floating], Real]

class MeshDistance(NamedTuple):
    """ttd.mesh_distance's result: arrays over the K poses (numpy scalars for one pose)."""

    distance: Floats
    p: npt.NDArray[np.floating]
    q: npt.NDArray[np.floating]
    tri_a: Union[npt.NDArray[np.uint32], np.uint32]
    tri_b: Union[npt.NDArray[np.uint32], np.uint32]
    feature_a: Union[npt.NDArray[np.uint8], np.uint8]
    feature_b: Union[npt.NDArray[np.uint8], np.uint8]
    flags: Union[npt.NDArray[np.uint16], np.uint16]
    node_tests: Union[npt.NDArray[np.uint32], np.uint32]
    pair_tests: Union[npt.NDArray[np.uint64], np.uint64]

class MeshCollision(NamedTuple):
    """ttd.mesh_collide's result: arrays over the K poses (numpy scalars for one pose)."""

    hit: Union[npt.NDArray[np.bool_], np.bool_]
    tri_a: Union[npt.NDArray[np.uint32], np.uint32]
    tri_b: Union[npt.NDArray[np.uint32], np.uint32]
    node_tests: Union[npt.NDArray[np.uint32], np.uint32]
    pair_tests: Union[npt.NDArray[np.uint64], np.uint64]

class MeshContacts(NamedTuple):
    """ttd.mesh_contacts's result: n contacts of all poses; pose k's are pose_start[k]:pose_start[k+1]."""

    pose: npt.NDArray[np.intp]
    tri_a: npt.NDArray[np.uint32]
    tri_b: npt.NDArray[np.uint32]
    distance: npt.NDArray[np.floating]
    p: npt.NDArray[np.floating]
    q: npt.NDArray[np.floating]
    pose_start: npt.NDArray[np.intp]

class ClosestPartners(NamedTuple):
    """Per triangle of one mesh and pose, its closest partner within the margin: (K, m) arrays."""

    partner: npt.NDArray[np.uint32]
    distance: npt.NDArray[np.floating]
    p: npt.NDArray[np.floating]
    q: npt.NDArray[np.floating]

class MeshClosest(NamedTuple):
    """ttd.mesh_closest's result."""

    for_a: Optional[ClosestPartners]
    for_b: Optional[ClosestPartners]

def mesh_distance(
    a: Mesh,
    b: Mesh,
    poses: npt.ArrayLike,
    *,
    upper_bound: float = ...,
    rel_tol: float = 0.0,
    isa: Union[IsaName, str] = "auto",
    threads: int = 0,
    out: Optional[npt.NDArray[np.void]] = None,
    solid: bool = False,
) -> MeshDistance: ...
def mesh_contacts(
    a: Mesh,
    b: Mesh,
    poses: npt.ArrayLike,
    margin: float,
    *,
    isa: Union[IsaName, str] = "auto",
    threads: int = 0,
) -> MeshContacts: ...
class SelfContacts(NamedTuple):
    """ttd.mesh_self_contacts' result: arrays over the n pairs of one mesh, tri_i < tri_j."""

    tri_i: npt.NDArray[np.uint32]
    tri_j: npt.NDArray[np.uint32]
    distance: npt.NDArray[np.floating]
    p: npt.NDArray[np.floating]
    q: npt.NDArray[np.floating]

class SelfCollision(NamedTuple):
    """ttd.mesh_self_collide's result."""

    hit: bool
    tri_i: int
    tri_j: int

def mesh_self_contacts(
    mesh: Mesh,
    margin: float,
    *,
    shared_vertex: bool = False,
    isa: Union[IsaName, str] = "auto",
    threads: int = 0,
) -> SelfContacts: ...
def mesh_self_collide(
    mesh: Mesh,
    margin: float = 0.0,
    *,
    shared_vertex: bool = False,
    isa: Union[IsaName, str] = "auto",
    threads: int = 0,
) -> SelfCollision: ...
def mesh_closest(
    a: Mesh,
    b: Mesh,
    poses: npt.ArrayLike,
    margin: float,
    *,
    for_a: bool = True,
    for_b: bool = True,
    isa: Union[IsaName, str] = "auto",
    threads: int = 0,
    out: Optional[Tuple[Optional[npt.NDArray[np.void]], Optional[npt.NDArray[np.void]]]] = None,
) -> MeshClosest: ...
def mesh_collide(
    a: Mesh,
    b: Mesh,
    poses: npt.ArrayLike,
    margin: float = 0.0,
    *,
    isa: Union[IsaName, str] = "auto",
    threads: int = 0,
    out: Optional[npt.NDArray[np.void]] = None,
    solid: bool = False,
) -> MeshCollision: ...

# ---- scenes ----------------------------------------------------------------------------------

SCENE_HIT_DTYPE: np.dtype
SCENE_CONTACT_DTYPE_FLOAT64: np.dtype
SCENE_CONTACT_DTYPE_FLOAT32: np.dtype
SCENE_POINT_DTYPE_FLOAT64: np.dtype
SCENE_POINT_DTYPE_FLOAT32: np.dtype

class SceneCollision(NamedTuple):
    """Scene.collide's result: each body pair (i < j) within the margin and one witness pair of triangles."""

    i: npt.NDArray[np.uint32]
    j: npt.NDArray[np.uint32]
    tri_i: npt.NDArray[np.uint32]
    tri_j: npt.NDArray[np.uint32]

class SceneContacts(NamedTuple):
    """Scene.contacts's result (and Scene.distance's nearest): parallel (n,) arrays, world frame."""

    i: npt.NDArray[np.uint32]
    j: npt.NDArray[np.uint32]
    tri_i: npt.NDArray[np.uint32]
    tri_j: npt.NDArray[np.uint32]
    distance: npt.NDArray[np.floating]
    p: npt.NDArray[np.floating]
    q: npt.NDArray[np.floating]

class SceneDistance(NamedTuple):
    """Scene.distance's result: the closest body pair (numpy scalars, (3,) points), and nearest."""

    i: np.uint32
    j: np.uint32
    tri_i: np.uint32
    tri_j: np.uint32
    distance: Real
    p: npt.NDArray[np.floating]
    q: npt.NDArray[np.floating]
    nearest: Optional[SceneContacts]

class SceneManifold(NamedTuple):
    """Scene.manifold's result: at most max_points points per body pair, grouped by (i, j), drawn
    from the contacts and the corners of flat contact (a box on a box: the corners of the faces'
    overlap); no two within 1e-3 of the smaller body's radius; normals from the bodies' shapes
    (face normals where a face lies within the margin, across real edges only; docs/scenes.md,
    section 5a)."""

    i: npt.NDArray[np.uint32]
    j: npt.NDArray[np.uint32]
    tri_i: npt.NDArray[np.uint32]
    tri_j: npt.NDArray[np.uint32]
    point: npt.NDArray[np.floating]
    normal: npt.NDArray[np.floating]
    """Unit, from body i towards body j, from the bodies' shapes (docs/scenes.md, section 5a)."""
    distance: npt.NDArray[np.floating]
    depth: npt.NDArray[np.floating]
    point_i: npt.NDArray[np.floating]
    """The point of body i (point is the midpoint of point_i and point_j)."""
    point_j: npt.NDArray[np.floating]
    key: npt.NDArray[np.uint64]
    """The features of both bodies the point lies on: the same while the contact persists."""

class MassProperties(NamedTuple):
    """ttd.mass_properties' result (docs/mass-properties.md)."""

    mass: float
    volume: float
    """Signed: negative for a mesh wound inward."""
    area: float
    center: npt.NDArray[np.float64]
    inertia: npt.NDArray[np.float64]
    """(3, 3), about the centre of mass."""

def mass_properties(mesh: Mesh, density: float = 1.0) -> MassProperties: ...

class Scene:
    """Bodies (ttd.Mesh objects at world poses) and the queries over every eligible pair of bodies."""

    def __init__(
        self,
        meshes: Union[None, Mesh, Sequence[Mesh]] = None,
        poses: Optional[npt.ArrayLike] = None,
        *,
        precision: Precision = None,
    ) -> None: ...
    def __len__(self) -> int: ...
    @property
    def id_limit(self) -> int: ...
    @property
    def dtype(self) -> Optional[np.dtype]: ...
    @property
    def meshes(self) -> Tuple[Optional[Mesh], ...]: ...
    @property
    def ids(self) -> npt.NDArray[np.intp]: ...
    def add(self, mesh: Mesh, pose: Optional[npt.ArrayLike] = None) -> int: ...
    def remove(self, id: int, /) -> None: ...
    def set_pose(self, id: int, pose: npt.ArrayLike, /) -> None: ...
    def set_poses(self, poses: npt.ArrayLike, /) -> None: ...
    def set_filter(self, id: int, group: int, mask: int, /) -> None: ...
    def exclude(self, i: int, j: int, excluded: bool = True) -> None: ...
    def set_solid(self, id: int, solid: bool = True) -> None: ...
    def collide(
        self, margin: float = 0.0, *, isa: Union[IsaName, str] = "auto", threads: int = 0
    ) -> SceneCollision: ...
    def distance(
        self,
        upper_bound: float = ...,
        *,
        nearest: bool = False,
        isa: Union[IsaName, str] = "auto",
        threads: int = 0,
    ) -> SceneDistance: ...
    def contacts(self, margin: float, *, isa: Union[IsaName, str] = "auto", threads: int = 0) -> SceneContacts: ...
    def manifold(
        self,
        margin: float,
        max_points: int = 4,
        *,
        isa: Union[IsaName, str] = "auto",
        threads: int = 0,
    ) -> SceneManifold: ...
    def ccd(
        self,
        poses_t1: npt.ArrayLike,
        *,
        min_separation: float = 0.0,
        isa: Union[IsaName, str] = "auto",
        threads: int = 0,
    ) -> Any: ...

# ---- point queries (python/src/ttd_points.c) -------------------------------------------------
POINT_NONFINITE: int
POINT_ABOVE_BOUND: int
POINT_INSIDE: int
POINT_SIGN_UNPROVEN: int
POINT_DEGENERATE: int
POINT_RESULT_DTYPE_FLOAT64: np.dtype
POINT_RESULT_DTYPE_FLOAT32: np.dtype

class ClosestPoints(NamedTuple):
    """ttd.closest_points' result: arrays over the points' shape (...)."""

    distance: npt.NDArray[np.floating]
    point: npt.NDArray[np.floating]
    triangle: npt.NDArray[np.uint32]
    bary: npt.NDArray[np.floating]
    feature: npt.NDArray[np.uint8]
    flags: npt.NDArray[np.uint8]
    node_tests: npt.NDArray[np.uint32]
    triangle_tests: npt.NDArray[np.uint32]

class SignedDistance(NamedTuple):
    """ttd.signed_distance's result: arrays over the points' shape (...)."""

    distance: npt.NDArray[np.floating]
    point: npt.NDArray[np.floating]
    triangle: npt.NDArray[np.uint32]
    inside: npt.NDArray[np.bool_]
    flags: npt.NDArray[np.uint8]

class WindingNumber(NamedTuple):
    """ttd.winding_number's result."""

    winding: npt.NDArray[np.float64]
    inside: npt.NDArray[np.bool_]

class Containment(NamedTuple):
    """ttd.contains' result."""

    inside: npt.NDArray[np.bool_]

def closest_points(
    mesh: Mesh,
    points: npt.ArrayLike,
    *,
    pose: Optional[npt.ArrayLike] = None,
    upper_bound: Optional[float] = None,
    isa: Union[IsaName, str] = "auto",
    threads: int = 0,
) -> ClosestPoints: ...
def signed_distance(
    mesh: Mesh,
    points: npt.ArrayLike,
    *,
    pose: Optional[npt.ArrayLike] = None,
    upper_bound: Optional[float] = None,
    isa: Union[IsaName, str] = "auto",
    threads: int = 0,
) -> SignedDistance: ...
def winding_number(
    mesh: Mesh,
    points: npt.ArrayLike,
    *,
    pose: Optional[npt.ArrayLike] = None,
    isa: Union[IsaName, str] = "auto",
    threads: int = 0,
) -> WindingNumber: ...
def contains(
    mesh: Mesh,
    points: npt.ArrayLike,
    *,
    pose: Optional[npt.ArrayLike] = None,
    isa: Union[IsaName, str] = "auto",
    threads: int = 0,
) -> Containment: ...
def sdf_grid(
    mesh: Mesh,
    origin: npt.ArrayLike,
    step: Union[float, npt.ArrayLike],
    shape: Sequence[int],
    *,
    isa: Union[IsaName, str] = "auto",
    threads: int = 0,
) -> npt.NDArray[np.floating]: ...

# Continuous collision: the private entry behind ttd.ccd (ttd/_ccd.py); arrays float64, C-contiguous.
def _ccd(
    kind: int, a0: Any, b0: Any, a1: Any, b1: Any, min_separation: float, threads: int, /
) -> Tuple[Any, Any, Any, Any, Any, Any]: ...

# Mesh CCD: the private entry behind ttd.mesh_ccd and ttd.mesh_self_ccd (ttd/_ccd.py); b None: self.
def _mesh_ccd(
    a: Mesh, a1: Any, b: Optional[Mesh], b1: Any, min_separation: float, shared: int, threads: int, /
) -> Tuple[float, Any, Any, Any, Any, Any, Any, int, int, int]: ...

# Rigid mesh CCD: the private entries behind ttd.mesh_ccd_rigid and ttd.rigid_pose_at (ttd/_rigid.py).
def _mesh_ccd_rigid(
    a: Mesh, a_poses: Any, b: Mesh, b_poses: Any, min_separation: float, /
) -> Tuple[float, bool, float, float, int, int, int, int]: ...
def _rigid_pose_at(p0: Tuple[float, ...], p1: Tuple[float, ...], t: float, /) -> Tuple[float, ...]: ...
