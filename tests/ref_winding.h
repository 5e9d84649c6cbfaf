/* SPDX-License-Identifier: MIT */
/* Independent references for a point's side of a mesh, written apart from the library, for the
 * point tests and the point fuzzer: the winding number as every triangle's solid angle (van
 * Oosterom and Strackee) summed in long double (64-bit significand on x86: 11 bits beyond double,
 * and an exponent range wide enough that no length, product or square over- or underflows for
 * doubles of any scale). Header-only, static functions. */
#ifndef TTD_TESTS_REF_WINDING_H
#define TTD_TESTS_REF_WINDING_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

/* The winding number about x of the nt triangles tris (three vertex indices each) over verts. */
static inline long double ref_winding_ld(const double *verts, const uint32_t *tris, size_t nt, const double x[3])
{
    long double sum = 0;
    for (size_t t = 0; t < nt; ++t) {
        long double a[3][3], l[3];
        for (int k = 0; k < 3; ++k) {
            for (int c = 0; c < 3; ++c)
                a[k][c] = (long double)verts[3 * tris[3 * t + (size_t)k] + (size_t)c] - (long double)x[c];
            l[k] = sqrtl(a[k][0] * a[k][0] + a[k][1] * a[k][1] + a[k][2] * a[k][2]);
        }
        const long double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                                a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                                a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
        const long double ab = a[0][0] * a[1][0] + a[0][1] * a[1][1] + a[0][2] * a[1][2];
        const long double ac = a[0][0] * a[2][0] + a[0][1] * a[2][1] + a[0][2] * a[2][2];
        const long double bc = a[1][0] * a[2][0] + a[1][1] * a[2][1] + a[1][2] * a[2][2];
        sum += 2 * atan2l(det, l[0] * l[1] * l[2] + ab * l[2] + ac * l[1] + bc * l[0]);
    }
    return sum / (4 * 3.14159265358979323846264338327950288L);
}

#endif /* TTD_TESTS_REF_WINDING_H */
