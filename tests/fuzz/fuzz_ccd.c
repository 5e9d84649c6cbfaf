/* SPDX-License-Identifier: MIT */
/* libFuzzer target: continuous collision (src/ccd/) against the exact rational reference
 * (tests/ccd_ref/, GMP). The bytes pick the kind and the 24 coordinates from small dyadic values
 * (multiples of 1/8 in [-2, 2], so that coplanar, parallel, collinear, touching and still motions
 * come up often), optionally nudged by one ulp and scaled by a power of two. Checked: no contact
 * the reference finds is missed, toi is never after it, and t_stop's promise (ccd/ccd.h): with
 * t_stop at the toi, or a fraction of the way from it to 1 picked by the bytes, the whole search's
 * answer bit for bit; with t_stop before the toi, or where there is none, no hit at or before it.
 * A failure prints the query and aborts, so libFuzzer keeps the input. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ccd/ccd.h"
#include "ccd_ref.h"
#include "ttd/ttd.h"

/* t_stop's promise on one query (the search itself, ttd_ccd_query, at delta 0): 0 where it holds. */
static int tstop_holds(int kind, const double *x0, const double *x1, double frac)
{
    ttd_ccd_params p = ttd_ccd_default_params();
    ttd_ccd_result whole, r;
    ttd_ccd_query(kind, x0, x1, &p, &whole);
    if (whole.hit && whole.toi <= 1) {
        const double at[2] = {whole.toi, whole.toi + frac * (1 - whole.toi)};
        for (int i = 0; i < 2; ++i) {
            p.t_stop = at[i];
            ttd_ccd_query(kind, x0, x1, &p, &r);
            if (r.hit != whole.hit || r.flags != whole.flags || memcmp(&r.toi, &whole.toi, sizeof r.toi) != 0 ||
                memcmp(&r.gap, &whole.gap, sizeof r.gap) != 0) {
                fprintf(stderr, "fuzz_ccd: whole toi %.17g, with t_stop %.17g: hit %u toi %.17g\n", whole.toi, at[i], r.hit,
                        r.toi);
                return 1;
            }
        }
    }
    p.t_stop = whole.hit && whole.toi <= 1 ? frac * whole.toi : frac;
    if (whole.hit && !(p.t_stop < whole.toi))
        return 0;
    ttd_ccd_query(kind, x0, x1, &p, &r);
    if (r.hit && r.toi <= p.t_stop) {
        fprintf(stderr, "fuzz_ccd: whole hit %u toi %.17g, with t_stop %.17g before it: toi %.17g\n", whole.hit,
                whole.toi, p.t_stop, r.toi);
        return 1;
    }
    return 0;
}

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
    /* data[1]'s high bits: where t_stop goes, a fraction of the way (1/16 .. 1). */
    if (!bad)
        bad = tstop_holds(kind, x0, x1, (double)(1 + (data[1] >> 4)) / 16);
    if (bad) {
        fprintf(stderr, "fuzz_ccd: kind %d, status %d, hit %u toi %.17g, reference %d [%.17g, %.17g]\n", kind,
                (int)st, r.hit, r.toi, ref, lo, hi);
        for (int i = 0; i < 12; ++i)
            fprintf(stderr, "  %a %a\n", x0[i], x1[i]);
        abort();
    }
    return 0;
}
