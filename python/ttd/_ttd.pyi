# SPDX-License-Identifier: MIT
# Type hints for the C extension ttd._ttd (python/src/), re-exported by the ttd package.
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
