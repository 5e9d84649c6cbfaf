/* SPDX-License-Identifier: MIT */
/* Step 0's screen of edge questions far from a corner (scene/manifold_corners_impl.h, corner_ask's
 * callers), precision-generic on `real`, with dot3d from its includer (scene/normal_impl.h's). No
 * include guard: scene/manifold_corners_impl.h includes it once per precision's translation unit,
 * tests/test_manifold_exact_dups.c once per precision under other names. */

/* How thin a triangle or how near parallel two edges may be and still be screened (sine). */
#define SCREEN_THIN 1e-3

/* Whether edges a and b (2 points each) surely have no pair of closest points inside both:
 * the closest points of their lines lie beyond an end of one of them by SCREEN_OUT of its
 * length, the edges far from parallel (at least SCREEN_THIN in sine) and their distance apart
 * within 1 / SCREEN_THIN of the shorter. u, v and w are each one correctly rounded difference
 * (relative error 2^-53 of itself, however far from the origin), so den's cancellation costs at
 * most 2^-53 / SCREEN_THIN^2 of uu vv and the numerators' 2^-53 |u| |v|^2 |w|: the parameters
 * are known to about 2^-19, leaving most of SCREEN_OUT (2^-6.6) for the
 * exact method's own rounding of the same parameters. It then finds no pair inside both
 * (its edge-edge candidate needs both parameters in [0, 1]; its others are at an end).
 * Double only: the float method's parameters carry 2^-24 where this carries 2^-53, times the
 * same conditioning (up to 1e12), far beyond SCREEN_OUT; tests/test_manifold_exact_dups.c found
 * float edges it screened where the float method put a pair inside both. */
#define SCREEN_OUT 0.01
static int edges_miss(const real *a, const real *b)
{
    if (sizeof(real) < sizeof(double))
        return 0;
    double u[3], v[3], w[3];
    for (int r = 0; r < 3; ++r) {
        u[r] = (double)a[3 + r] - (double)a[r];
        v[r] = (double)b[3 + r] - (double)b[r];
        w[r] = (double)a[r] - (double)b[r];
    }
    const double uu = dot3d(u, u), vv = dot3d(v, v), uv = dot3d(u, v), uw = dot3d(u, w), vw = dot3d(v, w);
    const double ww = dot3d(w, w), den = uu * vv - uv * uv, shorter = uu < vv ? uu : vv, longer = uu < vv ? vv : uu;
    if (!(den > SCREEN_THIN * SCREEN_THIN * uu * vv) || !(ww < shorter / (SCREEN_THIN * SCREEN_THIN)) ||
        !(longer < shorter / (SCREEN_THIN * SCREEN_THIN)))
        return 0;
    const double s = (uv * vw - vv * uw) / den, t = (uu * vw - uv * uw) / den;
    return s < -SCREEN_OUT || s > 1 + SCREEN_OUT || t < -SCREEN_OUT || t > 1 + SCREEN_OUT;
}
