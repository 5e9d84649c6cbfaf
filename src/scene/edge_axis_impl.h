/* SPDX-License-Identifier: MIT */
/* Step 0's screen of edge questions on edges along coordinate axes (scene/manifold_corners_impl.h,
 * corner_ask), precision-generic on `real`. No include guard: scene/manifold_corners_impl.h includes
 * it once per precision's translation unit, tests/test_manifold_exact_dups.c once per precision
 * under other names. */

/* The axis along which edge e (its ends e[0..2], e[3..5]) lies: the one coordinate in which its
 * ends differ; -1 where they differ in none or in more than one (or a coordinate is NaN). */
static int edge_axis(const real *e)
{
    int ax = -1;
    for (int r = 0; r < 3; ++r)
        if (e[r] != e[3 + r]) {
            if (ax >= 0 || e[r] != e[r] || e[3 + r] != e[3 + r])
                return -1;
            ax = r;
        }
    return ax;
}

/* Whether the edge question on segments s and t (each a degenerate triangle (a, b, b), s the
 * exact method's first triangle) surely has no corner: both edges along coordinate axes, and
 * either along the same one, or t's coordinate on s's axis not strictly between s's ends. The
 * exact method then finds no pair of closest points inside both (corner_ask's test), whatever
 * its rounding. It works on the points normalised (translated, scaled by powers of two:
 * coordinates equal stay equal and order is kept, rounding being monotone), so there too each
 * edge vector has exactly one non-zero component, and no candidate but an edge-edge one can put
 * both points inside their edges (a vertex-edge candidate has its vertex at an end; neither
 * triangle has a face). Its edge-edge candidate (exact_ee_candidate) of s's edge P + s d1
 * against t's edge Q + t d2: along one axis, d1 x d2 has only products with a 0 factor, so nn =
 * 0 and the candidate is rejected. Along axes a and b, s = (w x d2) . n / nn with n = d1 x d2,
 * w = Q - P: n's only non-zero component is +-fl(A B) (A = d1_a, B = d2_b) and (w x d2)'s in
 * that axis +-fl(w_a B) with the same sign, every other product having a 0 factor, so s =
 * fl(fl(fl(w_a B) fl(A B)) / fl(fl(A B)^2)) (nn >= REAL_MIN, else rejected). Where Q_a is not
 * strictly between s's ends, either w_a and A differ in sign or one is 0 (Q_a on P's side),
 * then s <= 0: rejected, or -0 or 0 (at P); or |w_a| >= |A| with A's sign (Q_a at or beyond the
 * far end; w_a = fl(Q_a - P_a) and A = fl(far_a - P_a) keep that order), then s >= 1: rejected,
 * or 1 (at the far end). A point at an end of s has its weight of s's first vertex 0 or 1
 * exactly (edge 0: 1 - sc; edge 2: sc), which corner_ask rejects. Tested against the exact
 * method itself (tests/test_manifold_exact_dups.c). 0 only in a test's build
 * (tests/CMakeLists.txt, ttd_manifold_no_screen), whose answers must be the same bits. */
#ifndef MANIFOLD_EDGE_AXIS_SCREEN
#define MANIFOLD_EDGE_AXIS_SCREEN 1
#endif
static int edges_axis_apart(const real *s, const real *t)
{
    const int a = edge_axis(s), b = edge_axis(t);
    if (a < 0 || b < 0)
        return 0;
    if (a == b)
        return 1;
    const real lo = s[a] < s[3 + a] ? s[a] : s[3 + a], hi = s[a] < s[3 + a] ? s[3 + a] : s[a];
    return t[a] <= lo || t[a] >= hi;
}
