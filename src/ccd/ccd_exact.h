/* SPDX-License-Identifier: MIT */
/* Exact signs of polynomials in t over a time interval, for the continuous-collision search
 * (ccd_search_impl.h; docs/ccd.md, section 3). A polynomial is a multilinear form of difference vectors of the
 * query's four moving points; its coefficients in t are formed once, exactly, as floating-point
 * expansions (sums of doubles, no tolerance, no library), and its Bernstein coefficients on an
 * interval [ta, tb] from them, exactly. */
#ifndef TTD_CCD_CCD_EXACT_H
#define TTD_CCD_CCD_EXACT_H

/// The forms: det(v0, v1, v2) (the coplanarity cubic) and (v0 x v1).(v2 x v3) (a contact
/// condition, degree 4). v_k(t) = point pts[k][0] - point pts[k][1] at time t, the points moving
/// linearly from x0 to x1 (x0[3i..3i+2] the point i at t = 0).
enum { TTD_CCD_FORM_DET = 3, TTD_CCD_FORM_CROSS_DOT = 4 };

/// An expansion: nonoverlapping doubles in increasing magnitude, their exact sum its value.
enum { TTD_CCD_XE_CAP = 40 };
typedef struct ttd_ccd_xe {
    int n, bad;
    double v[TTD_CCD_XE_CAP + 2];
} ttd_ccd_xe;

/// A polynomial of degree deg in t, c[k] the coefficient of t^k exactly; bad where the exact
/// arithmetic cannot be trusted (a product underflowed, numbers too large, an expansion too long).
typedef struct ttd_ccd_xpoly {
    int deg, bad;
    ttd_ccd_xe c[5];
    double a[5]; ///< the coefficients rounded to double (each within 4u of c[k]), for a first filter
} ttd_ccd_xpoly;

/* The operations (ccd_exact_impl.h, TTDW_FN, shared by the CPU and the device):
 * ccdx_xpoly_make(p, form, pts, x0, x1) forms the polynomial of a form over the query's motion;
 * ccdx_xpoly_sign(p, ta, tb, want): +1 when every Bernstein coefficient of p on [ta, tb] is > 0 (p is
 * then > 0 on the whole interval), -1 when every one is < 0, 0 otherwise, 2 where the arithmetic
 * cannot be trusted; want (+1 or -1) names the sign sought: the answer is 0 as soon as it cannot be
 * that one; want 0 seeks the sign of p(ta);
 * ccdx_xpoly_sign_at(p, t): the exact sign (-1, 0, +1) of p(t), or 2 where the arithmetic cannot be
 * trusted. */

#endif /* TTD_CCD_CCD_EXACT_H */
