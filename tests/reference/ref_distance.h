/* SPDX-License-Identifier: MIT */
/* An independent, high-precision reference for the distance between two triangles, for the
 * tests and the accuracy harness only (slow: about 100x the library's scalar code).
 *
 * Method (deliberately unlike the library's candidate-and-clamp scheme): the distance is the
 * minimum of a convex quadratic over the product of the two triangles, a polytope whose faces
 * are the pairs (feature of S, feature of T), each feature a vertex, an edge or the face: 7 x 7
 * pairs. On each pair the problem restricted to the affine hulls is an unconstrained least-
 * squares problem in k <= 3 unknowns (face-face, k = 4, is always singular in 3D and skipped);
 * it is solved in closed form with cross and triple products, the solution is kept only when
 * its weights are feasible (non-negative), and the smallest residual wins. Pairs whose system
 * is singular (parallel edges, an edge parallel to a face, degenerate features) are skipped:
 * a convex quadratic that is flat along a direction keeps its minimum on the boundary, which is
 * a lower-dimensional pair that is enumerated too. So no tolerance decides the answer except
 * the singularity test, which is relative and set far below any tested angle.
 *
 * Arithmetic is __float128 or an IEEE-quad long double (113-bit significand) where available: the
 * difference of two doubles within 2^60 of each other is then exact, a product of two such is
 * exact, so cross products are correctly rounded and the distance carries ~1e-30 relative
 * error on every family the tests use. Elsewhere it falls back to long double (64-bit
 * significand on x86), a weaker reference: ttd_ref_precision() says which.
 *
 * Each result carries a certificate: p - q defines two parallel planes that separate the
 * triangles, and lower_bound is the distance those planes prove. distance - lower_bound is the
 * duality gap, so a small gap proves the distance right without trusting the enumeration. */
#ifndef TTD_TESTS_REF_DISTANCE_H
#define TTD_TESTS_REF_DISTANCE_H

#include <float.h>

/* The reference's number type: __float128 where the compiler has it (gcc and clang on
 * x86-64; its + - * / come from the compiler's runtime, sqrt is ours, so libquadmath is not
 * needed), else long double, which is IEEE quad on aarch64 Linux and 64-bit extended on x86. */
#if defined(__SIZEOF_FLOAT128__) && !defined(TTD_REF_FORCE_LONG_DOUBLE)
#define TTD_REF_FLOAT128 1
__extension__ typedef __float128 ttd_qreal;
#else
typedef long double ttd_qreal;
#endif

/// The reference's answer for one pair (s = A B C, t = D E F, 9 doubles each).
typedef struct ttd_ref_result {
    double distance;     ///< the distance, rounded from distance_q
    double p[3];         ///< closest point on the first triangle (a common point when touching)
    double q[3];         ///< closest point on the second triangle
    double bary_p[3];    ///< weights of A, B, C giving p (non-negative, sum 1)
    double bary_q[3];    ///< weights of D, E, F giving q
    unsigned feature_p;  ///< bit i set when vertex i has a non-zero weight in p
    unsigned feature_q;  ///< the same for q
    double lower_bound;  ///< distance proved by the separating planes normal to p - q (0 when touching)
    ttd_qreal distance_q; ///< the distance in the reference's precision
} ttd_ref_result;

/// "__float128", "long double (IEEE quad)" or "long double (64-bit significand: weaker reference)".
const char *ttd_ref_precision(void);

/// The reference's unit roundoff (about 1e-34 in quad, 5e-20 in x86 long double), for tests
/// whose tolerances follow the reference's precision.
double ttd_ref_epsilon(void);

/// The reference distance between the triangles s and t, with closest points and certificate.
void ttd_ref_distance(const double s[9], const double t[9], ttd_ref_result *out);

/// The 15 classic sub-distances, in the reference's precision, rounded to double:
/// out[0..2] vertices A, B, C to triangle t; out[3..5] vertices D, E, F to triangle s;
/// out[6 + 3i + j] edge i of s (AB, BC, CA) to edge j of t (DE, EF, FD).
void ttd_ref_sub_distances(const double s[9], const double t[9], double out[15]);

/// How robustly the triangles cross: the largest, over the 6 edges of either triangle, of the
/// smallest of the 5 orientation determinants that show the edge passing through the other
/// triangle's interior, divided by size^3. Positive only when some edge strictly crosses the
/// interior; a value m means the crossing survives moving every vertex by about m * size.
/// 0 when no edge strictly crosses (separate, touching, or coplanar).
double ttd_ref_intersection_margin(const double s[9], const double t[9]);

/// The size of a pair: the longest of the 6 edges (0 when both triangles are one point each).
double ttd_ref_size(const double s[9], const double t[9]);

/// The distance from point x to triangle tri (reference precision, rounded to double).
double ttd_ref_point_triangle(const double x[3], const double tri[9]);

#endif /* TTD_TESTS_REF_DISTANCE_H */
