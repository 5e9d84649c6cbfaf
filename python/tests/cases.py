# SPDX-License-Identifier: MIT
"""Triangle pairs for the tests: random ones, and configurations whose answer is known by
construction (distance, closest points and features worked out by hand)."""
import numpy as np


def random_pairs(n, seed, dtype=np.float64):
    """The benchmark's workload: vertices uniform in [0,1)^3, the second triangle shifted by
    one offset uniform in [-0.5,0.5)^3 (about 10% of pairs intersect); shape (n, 3, 3)."""
    rng = np.random.default_rng(seed)
    S = rng.random((n, 3, 3))
    T = rng.random((n, 3, 3)) + (rng.random((n, 1, 3)) - 0.5)
    return S.astype(dtype), T.astype(dtype)
