# SPDX-License-Identifier: MIT
"""ttd: minimum distance between 3D triangles, millions of pairs at a time, on SIMD hardware.

numpy arrays in, numpy arrays out::

    import numpy as np, ttd
    S = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], float)   # one triangle: rows A, B, C
    T = S + [0, 0, 2]
    ttd.distance(S, T)                      # 2.0 (one pair: a numpy scalar)
    r = ttd.distance(Ss, Ts, points=True)   # (n, 3, 3) arrays: a ttd.PairResult of arrays
    r.distance, r.p, r.q, r.flags & ttd.Flag.INTERSECTING

What is here: distance() (the pair API), the enums Method, Isa and Flag, the instruction-set
queries isa_available(), isa_selected(), isa_lanes(), version, the exception
IsaUnavailableError and the warnings NonFiniteInputWarning and NotConvergedWarning.
ttd.dask runs batches larger than memory on a Dask cluster. Mesh objects and mesh queries
(ttd.Mesh) will join this module as the C library gains them (docs/python.md).
"""
import enum

try:
    from ._ttd import (
        ISAS,
        METHODS,
        RESULT_DTYPE_FLOAT32,
        RESULT_DTYPE_FLOAT64,
        IsaUnavailableError,
        NonFiniteInputWarning,
        NotConvergedWarning,
        PairResult,
        distance,
        isa_available,
        isa_lanes,
        isa_selected,
        version,
    )
    from . import _ttd
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
    """Instruction sets for ttd.distance(isa=...); each member is also its name as a str."""

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


__all__ = [
    "Flag",
    "ISAS",
    "Isa",
    "IsaUnavailableError",
    "METHODS",
    "Method",
    "NonFiniteInputWarning",
    "NotConvergedWarning",
    "PairResult",
    "RESULT_DTYPE_FLOAT32",
    "RESULT_DTYPE_FLOAT64",
    "__version__",
    "distance",
    "isa_available",
    "isa_lanes",
    "isa_selected",
    "version",
]
