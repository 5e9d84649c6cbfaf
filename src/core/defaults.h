/* SPDX-License-Identifier: MIT */
/* Default parameters of the iterative methods (ttd_default_options). The penalty and
 * barrier methods run on the pair translated and scaled (by a power of two) to unit size,
 * so these values do not depend on the triangles' scale. How they were chosen (measured on
 * random pairs against an exact reference): docs/penalty-method.md.
 *
 * rho 1e6 with the final clamping gives a distance error ~2/rho^2 = 2e-12 of the pair's
 * size in double, in 4.55 Newton iterations on average in double and 4.59 in float
 * (1,000,000 random pairs, ttd bench: docs/benchmark/bench.txt); tol 1e-12 is the step
 * length, on the unit-size geometry, below which the iteration stops. The cap is the
 * paper's. */
#ifndef TTD_CORE_DEFAULTS_H
#define TTD_CORE_DEFAULTS_H

#include "ttd/ttd.h"

#define TTD_DEFAULT_RHO 1.0e6
#define TTD_DEFAULT_TOL 1.0e-12
#define TTD_DEFAULT_MAX_ITERATIONS 99

/* The optimised penalty method's regularisation eps*I (also its pivot floor) is
 * TTD_PENALTY_EPS_ULPS * REAL_EPS of the unit-size frame, whatever rho: the listing's 1/rho^2
 * (1e-12 at rho 1e6) is larger than the curvature along nearly parallel edges and faces and
 * made the iteration crawl (11% of near_parallel_edges pairs hit the cap); at 4 ulps the
 * steps along hf's null space (noise/eps) made a few pairs cycle. A step also
 * counts as small when grad.dx (twice its promised decrease of the objective) is below
 * tol^2 or below TTD_PENALTY_FLAT_ULPS * REAL_EPS * |X - Y|^2: a step whose effect on the
 * objective is below the rounding of |X - Y|^2 (flat directions of f, where the step is
 * long and the distance does not change) would otherwise repeat until the cap. 16 ulps
 * leaves a margin over that rounding (the only value measured); adding the test took
 * near_touching from 6.0% unconverged to 0 (double, 50,000 pairs). Measurements:
 * docs/penalty-method.md, "Near-parallel families" (item 3 and the ablation table). */
#define TTD_PENALTY_EPS_ULPS 16
#define TTD_PENALTY_FLAT_ULPS 16
/* The exact line search continues beyond the Newton step (t > 1) when phi'(1) is still below
 * TTD_PENALTY_EXTEND * phi'(0) (< 0): the step was made by a pivot far above the curvature
 * along it (a valley flatter than eps). Without it 0.9% of near_parallel_edges pairs crawled
 * to the cap; with it none (250k pairs, both precisions). */
#define TTD_PENALTY_EXTEND 0.5

/* Float kernels clamp the parameters they are given. With a penalised constraint the
 * Hessian has entries ~rho, and a pivot below ~rho*FLT_EPSILON (a sliver triangle) is lost
 * to rounding: at rho 1024 sliver pairs came out up to 58% off, at 256 within 7e-5 (while
 * random pairs go from 2e-6 to 3e-5). A step tolerance below ~1e-6 of the unit size is
 * below the step's own rounding, so the iteration would never stop. Double kernels use
 * the values as given (rho 1e8 would be more accurate on random pairs but loses slivers
 * the same way; 1e6 keeps them to 1e-8 edge/size). */
#define TTD_FLOAT_RHO_MAX 256.0
#define TTD_FLOAT_TOL_MIN 1.0e-6
/* The largest rho accepted at all: the optimised step's expanded 2x2 pivots hold rho^2, which
 * must stay finite (above ~1.3e154 it did not, and a coordinate's step was silently zeroed). */
#define TTD_DOUBLE_RHO_MAX TTD_RHO_MAX /* ttd/ttd.h */

/* The paper's ttd1 reference keeps rho as given, except that in float it must stay finite
 * with its square (the I/rho^2 term): rho = 1e150 became inf, and inf * 0 gave NaN. */
#define TTD_FLOAT_REF_RHO_MAX 1.0e18
/* No floor on tol in double: the double kernels use it as given (see the float caps). A tol
 * below the double step's rounding (~1e-16 of the unit frame) only costs iterations up to
 * the cap, flagged not converged (tol 0: 60% of 5,000 random pairs), which is the caller's
 * choice. The name exists so that both precisions share one max(). */
#define TTD_DOUBLE_TOL_MIN 0.0

#endif /* TTD_CORE_DEFAULTS_H */
