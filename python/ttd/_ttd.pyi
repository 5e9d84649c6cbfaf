# SPDX-License-Identifier: MIT
# Type hints for the C extension ttd._ttd (python/src/), re-exported by the ttd package:
# the pair API, then the mesh objects and queries.
from typing import Literal, NamedTuple, Optional, Tuple, Union, overload

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
NO_TRIANGLE: int
MESH_RESULT_DTYPE_FLOAT64: np.dtype
MESH_RESULT_DTYPE_FLOAT32: np.dtype
CONTACT_DTYPE_FLOAT64: np.dtype
CONTACT_DTYPE_FLOAT32: np.dtype
CLOSEST_DTYPE_FLOAT64: np.dtype
CLOSEST_DTYPE_FLOAT32: np.dtype
COLLISION_DTYPE: np.dtype

class Mesh:
    """A triangle mesh and its hierarchy, built once, immutable; pickles as (vertices, faces)."""

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
    def __reduce__(self) -> Tuple[type, Tuple[npt.NDArray[np.floating], npt.NDArray[np.uint32]]]: ...

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
) -> MeshCollision: ...
