/* SPDX-License-Identifier: MIT */
/* Hostile input to the public API, on every method and every available instruction set
 * (tests/test_api.c covers the error statuses, NULL pointers, n = 0, option checks and the
 * alignment of the default ISA; this file adds what a user can throw at the numerical paths):
 *   - magnitudes whose squares or differences overflow: +-1e300 mixes, DBL_MAX against
 *     -DBL_MAX (a distance beyond DBL_MAX), edges longer than DBL_MAX, FLT_MAX-ish floats;
 *   - subnormal coordinates (squares underflow to 0), double and float;
 *   - NaN (quiet, signalling, negative) and +-inf in every one of the 18 coordinates and in
 *     every lane position of a vector;
 *   - all of these mixed into one batch with ordinary pairs: every pair of the batch equals its
 *     single-pair result bit for bit, nothing is written past n, and the status is the one the
 *     worst pair calls for;
 *   - counts whose result array (not only the coordinates) would overflow size_t.
 * What is asserted: never a NaN for finite input; closest points finite and on their
 * triangles; the exact method's distance within 1e-12 of the quad reference evaluated on the
 * input scaled by a power of two into range (a scaling that is exact), so the reference never
 * sees an overflow itself. */
#define _POSIX_C_SOURCE 200809L

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "pairs.h"
#include "ref_distance.h"
#include "test_macros.h"
#include "ttd/ttd.h"

static ttd_gen_rng rng; /* each test seeds it: seed(k) */
static void seed(uint64_t x)
{
    rng = ttd_gen_rng_make(x, 0);
}

static double rnd(void) /* uniform [0, 1), gen/pairs.h's splitmix64 */
{
    return ttd_gen_rng_uniform(&rng);
}

static int computed(ttd_status st)
{
    return st == TTD_OK || st == TTD_WARN_NOT_CONVERGED;
}

static ttd_options opts(int m, int isa)
{
    ttd_options o = ttd_default_options();
    o.method = (ttd_method)m;
    o.isa = (ttd_isa)isa;
    o.threads = 1;
    return o;
}

/* Distance from x to triangle tri, both scaled by 2^e first (exact for the powers used here),
 * in those scaled units: the quad reference on input it can hold without overflow. */
static double ref_point_triangle_scaled(const double x[3], const double tri[9], int e)
{
    double xs[3], ts[9];
    for (int k = 0; k < 3; ++k)
        xs[k] = ldexp(x[k], e);
    for (int k = 0; k < 9; ++k)
        ts[k] = ldexp(tri[k], e);
    return ttd_ref_point_triangle(xs, ts);
}

/* ---- the hostile pairs -------------------------------------------------------------------- */

enum { NCASES = 17 };
/* Case c of the double cases; e receives a power-of-two exponent that brings it into the
 * reference's comfortable range (0 if none is needed). */
static void hostile_case_d(int c, double s[9], double t[9], int *e)
{
    for (int k = 0; k < 9; ++k) {
        s[k] = rnd();
        t[k] = rnd() + 0.5 * (k % 3 == 0);
    }
    *e = 0;
    switch (c) {
    case 0: /* +1e300 against -1e300: the difference 2e300 is finite, its square is not */
        for (int k = 0; k < 9; ++k)
            s[k] = s[k] * 1e300, t[k] = -t[k] * 1e300;
        *e = -1000;
        break;
    case 1: /* mixed signs inside each triangle at 1e300 */
        for (int k = 0; k < 9; ++k)
            s[k] = (s[k] - 0.5) * 1e300, t[k] = (t[k] - 0.5) * 1e300;
        *e = -1000;
        break;
    case 2: /* near DBL_MAX, both triangles on the same side: distance representable */
        for (int k = 0; k < 9; ++k)
            s[k] = DBL_MAX * (0.5 + 0.25 * s[k]), t[k] = DBL_MAX * (0.5 + 0.25 * t[k] / 1.5);
        *e = -1020;
        break;
    case 3: /* an edge longer than DBL_MAX (-DBL_MAX to DBL_MAX), the other triangle near 0 */
        s[0] = -DBL_MAX, s[3] = DBL_MAX, s[6] = 0, s[7] = DBL_MAX / 2;
        *e = -1020;
        break;
    case 4: /* every coordinate subnormal */
        for (int k = 0; k < 9; ++k)
            s[k] = s[k] * 0x1p-1040, t[k] = t[k] * 0x1p-1040;
        *e = 1040;
        break;
    case 5: /* subnormal triangles far apart relative to their size */
        for (int k = 0; k < 9; ++k)
            s[k] = s[k] * 0x1p-1060, t[k] = t[k] * 0x1p-1060 + (k % 3 == 1 ? 0x1p-1030 : 0);
        *e = 1060;
        break;
    case 6: /* tiny (subnormal-size) triangles at 1e300 from the origin: all one point in double */
        for (int k = 0; k < 9; ++k)
            s[k] = 1e300 + s[k] * 1e-300, t[k] = -1e300 + t[k] * 1e-300;
        *e = -1000;
        break;
    case 7: /* both triangles the same point at -DBL_MAX */
        for (int k = 0; k < 9; ++k)
            s[k] = t[k] = -DBL_MAX;
        *e = -1020;
        break;
    case 8: /* a 1e-300 triangle against a 1e300 one */
        for (int k = 0; k < 9; ++k)
            s[k] = s[k] * 1e-300, t[k] = t[k] * 1e300;
        *e = -1000;
        break;
    case 9: /* zero and negative zero, degenerate everything */
        for (int k = 0; k < 9; ++k)
            s[k] = (k & 1) ? -0.0 : 0.0, t[k] = (k & 2) ? -0.0 : 0.0;
        break;
    case 10: /* smallest subnormal steps: a segment of length 1 ulp of 0 */
        memset(s, 0, 9 * sizeof(double));
        memset(t, 0, 9 * sizeof(double));
        s[3] = 4.9406564584124654e-324;
        t[1] = 3 * 4.9406564584124654e-324, t[4] = t[1], t[6] = 2 * 4.9406564584124654e-324, t[7] = t[1];
        *e = 1070;
        break;
    case 11: /* a DBL_MAX-size triangle with a unit triangle inside it, coplanar: distance 0 */
        s[0] = -DBL_MAX, s[1] = -DBL_MAX, s[2] = 0, s[3] = DBL_MAX, s[4] = -DBL_MAX, s[5] = 0;
        s[6] = 0, s[7] = DBL_MAX, s[8] = 0;
        t[2] = t[5] = t[8] = 0;
        *e = -1020;
        break;
    case 12: /* a segment from -DBL_MAX to the origin touching a unit triangle there: distance 0 */
        memset(s, 0, 9 * sizeof(double));
        s[0] = -DBL_MAX;
        t[0] = t[1] = t[2] = 0;
        *e = -1020;
        break;
    case 13: { /* a segment at DBL_MAX height (found by fuzz_batch): q rounded past DBL_MAX to inf */
        static const double s13[9] = {0.3, 0.3, -0x1p1023, 3.433227539062499e-05, 1.0, 0.5, 1.2, 0.4, 4.010117110756019e-304};
        memcpy(s, s13, sizeof s13);
        for (int k = 0; k < 9; ++k)
            t[k] = DBL_MAX;
        t[0] = 0;
        *e = -1020;
        break;
    }
    case 14: { /* a unit triangle against one near (DBL_MAX, DBL_MAX, DBL_MAX) (fuzz_batch): the
                * penalty method's q rounded past DBL_MAX */
        static const double s14[9] = {0.00029296875, 0.2999389654258266, 0.5, 1, 0.5, 1.2, 0.4, 1.1, 0.9};
        static const double t14[9] = {DBL_MAX, DBL_MAX, DBL_MAX, DBL_MAX, DBL_MAX, 1.797254241588399e+308,
                                      DBL_MAX, -1.3605594387537141e+306, 1.7976926024339806e+308};
        memcpy(s, s14, sizeof s14);
        memcpy(t, t14, sizeof t14);
        *e = -1020;
        break;
    }
    case 15: /* case 9 of the float cases in double: a point near (DBL_MAX, DBL_MAX, DBL_MAX) against
              * a tiny segment, where the reference penalty iterate can overflow to -inf */
        for (int k = 0; k < 9; ++k)
            s[k] = 0x1.fefefefefefefp+1023, t[k] = k == 0 ? -0x1.000016p-43 : -0x1.555554p-42;
        *e = -1020;
        break;
    default: /* an ordinary pair, for comparison inside mixed batches */
        break;
    }
}

/* Checks one double result on a finite hostile pair: no NaN, points finite and on their
 * triangles, |p - q| consistent, and for the exact method the distance against the reference. */
static int check_result_d(const char *what, int m, const double *s, const double *t, int e, const ttd_result_d *r)
{
    ENSURE_MSG(!(r->flags & TTD_PAIR_NONFINITE), "%s: finite input flagged non-finite", what);
    ENSURE_MSG(!isnan(r->distance) && r->distance >= 0, "%s: distance %g", what, r->distance);
    for (int k = 0; k < 3; ++k)
        ENSURE_MSG(isfinite(r->p[k]) && isfinite(r->q[k]) && isfinite(r->bary_p[k]) && isfinite(r->bary_q[k]),
                   "%s: non-finite point or weight (p %g %g %g, q %g %g %g)", what, r->p[0], r->p[1], r->p[2],
                   r->q[0], r->q[1], r->q[2]);
    /* In reference units (scaled by 2^e). */
    double ss[9], ts[9];
    for (int k = 0; k < 9; ++k)
        ss[k] = ldexp(s[k], e), ts[k] = ldexp(t[k], e);
    ttd_ref_result ref;
    ttd_ref_distance(ss, ts, &ref);
    double scale = fmax(ref.distance, ttd_ref_size(ss, ts));
    double mag = 0;
    for (int k = 0; k < 9; ++k)
        mag = fmax(mag, fmax(fabs(ss[k]), fabs(ts[k])));
    /* p and q: on their triangles, and |p - q| = d, within the method's documented distance
     * target (docs/accuracy.md; 16 eps for penalty-ref, which has none: every method clamps or
     * projects its points), plus the rounding of forming p and q at the coordinates' magnitude
     * (8 eps |x|, eps = DBL_EPSILON / 2, as in tests/accuracy/accuracy.c), plus for subnormal
     * input 8 subnormal spacings (a few roundings of p's formation, each at most one spacing),
     * scaled. Measured on every case, method and ISA (AVX-512 machine): the worst is within
     * 8 eps |x| (under 1.5 subnormal spacings on the subnormal cases 4, 5 and 10), so the
     * target term is spare on these cases. */
    static const double target[TTD_METHOD_COUNT] = {
        [TTD_METHOD_EXACT] = 1e-12, [TTD_METHOD_PENALTY] = 1e-10, [TTD_METHOD_PENALTY_REFERENCE] = 16 * (DBL_EPSILON / 2),
        [TTD_METHOD_BARRIER] = 1e-8, [TTD_METHOD_CERTIFIED] = 1e-12};
    double allow = target[m] * scale + 8 * (DBL_EPSILON / 2) * mag + ldexp(8 * 4.9406564584124654e-324, e);
    double off_p = ref_point_triangle_scaled(r->p, s, e), off_q = ref_point_triangle_scaled(r->q, t, e);
    if (!(off_p <= allow && off_q <= allow)) {
        print_pair("input", s, t);
        ENSURE_MSG(0, "%s: p or q off its triangle by %g, %g (allowed %g, reference units)", what, off_p, off_q, allow);
    }
    /* Every method: the distance is finite unless the true one is beyond DBL_MAX, and it is
     * |p - q| (compared in reference units, where |p - q| cannot overflow). */
    if (isinf(r->distance)) {
        if (!(ldexp(ref.distance, -e) > DBL_MAX))
            print_pair("input", s, t);
        ENSURE_MSG(ldexp(ref.distance, -e) > DBL_MAX, "%s: distance inf, reference %g * 2^%d", what, ref.distance, -e);
        return 0;
    }
    double d = ldexp(r->distance, e), pq = 0;
    for (int k = 0; k < 3; ++k)
        pq += (ldexp(r->p[k], e) - ldexp(r->q[k], e)) * (ldexp(r->p[k], e) - ldexp(r->q[k], e));
    pq = sqrt(pq);
    if (!(fabs(pq - d) <= allow)) {
        print_pair("input", s, t);
        ENSURE_MSG(0, "%s: distance %.17g but |p - q| %.17g (reference units), allowed %g", what, d, pq, allow);
    }
    if (m != TTD_METHOD_EXACT && m != TTD_METHOD_CERTIFIED)
        return 0;
    /* The exact method (and the certified one, which promises its accuracy): the distance. */
    double tol = 1e-12 * scale + ldexp(4 * 4.9406564584124654e-324, e);
    if (!(fabs(d - ref.distance) <= tol)) {
        print_pair("input", s, t);
        ENSURE_MSG(0, "%s: distance %.17g, reference %.17g (both * 2^%d), |diff| %.3g > %.3g", what, d, ref.distance,
                   e, fabs(d - ref.distance), tol);
    }
    return 0;
}

/* Every method and ISA, every double hostile case, alone: finite and right. */
static int hostile_double_cases(void)
{
    seed(1);
    for (int c = 0; c < NCASES; ++c) {
        double s[9], t[9];
        int e;
        for (int rep = 0; rep < 8; ++rep) {
            hostile_case_d(c, s, t, &e);
            for (int m = 0; m < TTD_METHOD_COUNT; ++m)
                for (int isa = TTD_ISA_SCALAR; isa < TTD_ISA_COUNT; ++isa) {
                    if (!ttd_isa_available((ttd_isa)isa))
                        continue;
                    ttd_options o = opts(m, isa);
                    ttd_result_d r;
                    ttd_status st = ttd_distance_d(&o, s, t, &r);
                    char what[96];
                    snprintf(what, sizeof what, "case %d rep %d %s %s", c, rep, ttd_method_name((ttd_method)m),
                             ttd_isa_name((ttd_isa)isa));
                    ENSURE_MSG(computed(st), "%s: status %d", what, (int)st);
                    if (check_result_d(what, m, s, t, e, &r))
                        return 1;
                }
        }
    }
    return 0;
}

/* Float: FLT_MAX-ish magnitudes, opposite signs, subnormals; against the reference on the
 * float input (widened exactly), scaled into range. */
static int hostile_float_cases(void)
{
    seed(2);
    for (int c = 0; c < 10; ++c) {
        for (int rep = 0; rep < 8; ++rep) {
            float sf[9], tf[9];
            int e = 0;
            for (int k = 0; k < 9; ++k) {
                float a = (float)rnd(), b = (float)rnd();
                switch (c) {
                case 0: sf[k] = a * 1e38f, tf[k] = -b * 1e38f, e = -120; break;       /* difference ~2e38 */
                case 1: sf[k] = FLT_MAX * (0.5f + 0.5f * a), tf[k] = -FLT_MAX * (0.5f + 0.5f * b), e = -120; break;
                case 2: sf[k] = (a - 0.5f) * 3e38f, tf[k] = (b - 0.5f) * 3e38f, e = -120; break;
                case 3: sf[k] = a * 0x1p-140f, tf[k] = b * 0x1p-140f, e = 140; break;  /* subnormal */
                case 4: sf[k] = a * 0x1p-149f * 8, tf[k] = b * 0x1p-149f * 8 + 0x1p-147f, e = 149; break;
                case 5: sf[k] = 1e30f + a * 1e23f, tf[k] = 1e30f + b * 1e23f, e = -90; break;
                case 6: sf[k] = (k % 3) ? 0.0f : -FLT_MAX, tf[k] = (k % 3) ? 0.0f : FLT_MAX, e = -120; break;
                case 8: /* a unit triangle against one at FLT_MAX height: q rounded to inf */
                    sf[k] = (float)((const double[]){0, 0, 0, 1, 0, 0, 0, 1, 0}[k]);
                    tf[k] = k == 0 ? 0.0f : (k == 6 ? 1e38f : FLT_MAX), e = -120;
                    break;
                case 9: /* a point near (FLT_MAX, FLT_MAX, FLT_MAX) against a tiny segment (found by
                         * fuzz_batch): the reference penalty iterate ran off to -inf, its weights NaN */
                    sf[k] = 0x1.fefefep+127f;
                    tf[k] = k == 0 ? -0x1.000016p-43f : -0x1.555554p-42f, e = -120;
                    break;
                default: /* a FLT_MAX-size triangle with a unit one inside, coplanar */
                    sf[k] = (float)((const double[]){-1, -1, 0, 1, -1, 0, 0, 1, 0}[k]) * FLT_MAX;
                    tf[k] = k % 3 == 2 ? 0.0f : b, e = -120;
                    break;
                }
            }
            double s[9], t[9];
            for (int k = 0; k < 9; ++k)
                s[k] = (double)sf[k], t[k] = (double)tf[k];
            for (int m = 0; m < TTD_METHOD_COUNT; ++m)
                for (int isa = TTD_ISA_SCALAR; isa < TTD_ISA_COUNT; ++isa) {
                    if (!ttd_isa_available((ttd_isa)isa))
                        continue;
                    ttd_options o = opts(m, isa);
                    ttd_result_f r;
                    ttd_status st = ttd_distance_f(&o, sf, tf, &r);
                    char what[96];
                    snprintf(what, sizeof what, "float case %d rep %d %s %s", c, rep, ttd_method_name((ttd_method)m),
                             ttd_isa_name((ttd_isa)isa));
                    ENSURE_MSG(computed(st), "%s: status %d", what, (int)st);
                    ENSURE_MSG(!(r.flags & TTD_PAIR_NONFINITE), "%s: flagged non-finite", what);
                    ENSURE_MSG(!isnan(r.distance) && r.distance >= 0, "%s: distance %g", what, (double)r.distance);
                    double p[3], q[3];
                    for (int k = 0; k < 3; ++k) {
                        ENSURE_MSG(isfinite(r.p[k]) && isfinite(r.q[k]) && isfinite(r.bary_p[k]) &&
                                       isfinite(r.bary_q[k]),
                                   "%s: non-finite point or weight", what);
                        p[k] = (double)r.p[k], q[k] = (double)r.q[k];
                    }
                    double ss[9], ts[9];
                    for (int k = 0; k < 9; ++k)
                        ss[k] = ldexp(s[k], e), ts[k] = ldexp(t[k], e);
                    ttd_ref_result ref;
                    ttd_ref_distance(ss, ts, &ref);
                    double scale = fmax(ref.distance, ttd_ref_size(ss, ts)), mag = 0;
                    for (int k = 0; k < 9; ++k)
                        mag = fmax(mag, fmax(fabs(ss[k]), fabs(ts[k])));
                    double sub = ldexp(64 * 0x1p-149, e); /* float subnormal spacing, scaled */
                    double allow = 2e-4 * scale + 64 * (double)FLT_EPSILON * mag + sub;
                    double off_p = ref_point_triangle_scaled(p, s, e), off_q = ref_point_triangle_scaled(q, t, e);
                    if (!(off_p <= allow && off_q <= allow)) {
                        print_pair("input", s, t);
                        ENSURE_MSG(0, "%s: p or q off by %g, %g (allowed %g)", what, off_p, off_q, allow);
                    }
                    if (isinf(r.distance)) {
                        ENSURE_MSG(ldexp(ref.distance, -e) > (double)FLT_MAX, "%s: inf, reference %g", what,
                                   ldexp(ref.distance, -e));
                        continue;
                    }
                    if (m != TTD_METHOD_EXACT && m != TTD_METHOD_CERTIFIED)
                        continue;
                    double d = ldexp((double)r.distance, e), tol = 1e-5 * scale + 4 * sub;
                    if (!(fabs(d - ref.distance) <= tol)) {
                        print_pair("input", s, t);
                        ENSURE_MSG(0, "%s: distance %.9g, reference %.9g (* 2^%d)", what, d, ref.distance, e);
                    }
                }
        }
    }
    return 0;
}

/* NaN (quiet, signalling, negative, with payload) and +-inf in each of the 18 coordinates,
 * in each lane position: that pair flagged and all-NaN, every other pair as computed alone. */
static int nonfinite_every_position(void)
{
    seed(3);
    enum { N = 40 };
    uint64_t bits[] = {0x7ff8000000000000u, 0x7ff0000000000001u, 0xfff8000000000000u, 0x7ff4000000abcdefu};
    double poison[6];
    for (int k = 0; k < 4; ++k)
        memcpy(&poison[k], &bits[k], sizeof poison[k]);
    poison[4] = (double)INFINITY, poison[5] = -(double)INFINITY;
    static double s[9 * N], t[9 * N], d[N + 4];
    static ttd_result_d r[N + 4];
    static float sf[9 * N], tf[9 * N], df[N + 4];
    static ttd_result_f rf[N + 4];
    for (int m = 0; m < TTD_METHOD_COUNT; ++m)
        for (int isa = TTD_ISA_SCALAR; isa < TTD_ISA_COUNT; ++isa) {
            if (!ttd_isa_available((ttd_isa)isa))
                continue;
            ttd_options o = opts(m, isa);
            for (int pos = 0; pos < 18; ++pos) {
                for (int k = 0; k < 9 * N; ++k)
                    s[k] = rnd(), t[k] = rnd() + 0.3;
                /* pairs pos % 17, 17 + pos % 8 and 39 get the poison: lanes 0..16 of a vector */
                const int bad[3] = {pos % 17, 17 + pos % 8, N - 1};
                for (int b = 0; b < 3; ++b)
                    (pos < 9 ? s : t)[9 * bad[b] + pos % 9] = poison[(pos + b) % 6];
                for (int k = 0; k < 9 * N; ++k)
                    sf[k] = (float)s[k], tf[k] = (float)t[k];
                for (int k = 0; k < N + 4; ++k)
                    df[k] = 12345.0f, d[k] = 12345.0, rf[k].distance = 6789.0f, r[k].distance = 6789.0;
                ENSURE(ttd_batch_d(&o, N, s, t, d, r) == TTD_ERR_NONFINITE_INPUT);
                ENSURE(ttd_batch_f(&o, N, sf, tf, df, rf) == TTD_ERR_NONFINITE_INPUT);
                for (int k = N; k < N + 4; ++k) /* nothing written past n */
                    ENSURE(d[k] == 12345.0 && df[k] == 12345.0f && r[k].distance == 6789.0 && rf[k].distance == 6789.0f);
                for (int i = 0; i < N; ++i) {
                    int is_bad = i == bad[0] || i == bad[1] || i == bad[2];
                    ttd_result_d one;
                    ttd_result_f onef;
                    ttd_status st = ttd_distance_d(&o, s + 9 * i, t + 9 * i, &one);
                    ttd_status stf = ttd_distance_f(&o, sf + 9 * i, tf + 9 * i, &onef);
                    if (is_bad) {
                        ENSURE_MSG(st == TTD_ERR_NONFINITE_INPUT && stf == TTD_ERR_NONFINITE_INPUT &&
                                       (r[i].flags & TTD_PAIR_NONFINITE) && (rf[i].flags & TTD_PAIR_NONFINITE) &&
                                       isnan(d[i]) && isnan(df[i]) && isnan(r[i].p[0]) && isnan(rf[i].q[2]),
                                   "%s %s coordinate %d pair %d", ttd_method_name((ttd_method)m),
                                   ttd_isa_name((ttd_isa)isa), pos, i);
                    } else {
                        ENSURE_MSG(computed(st) && computed(stf) && memcmp(&one, &r[i], sizeof one) == 0 &&
                                       memcmp(&onef, &rf[i], sizeof onef) == 0 &&
                                       memcmp(&d[i], &r[i].distance, sizeof d[i]) == 0 &&
                                       memcmp(&df[i], &rf[i].distance, sizeof df[i]) == 0,
                                   "%s %s coordinate %d: neighbour pair %d differs from its single-pair result",
                                   ttd_method_name((ttd_method)m), ttd_isa_name((ttd_isa)isa), pos, i);
                    }
                }
            }
        }
    return 0;
}

/* Every hostile case mixed into one batch with ordinary pairs, at misaligned addresses: each
 * pair equals its single-pair result bit for bit on the same ISA. */
static int mixed_batch_equals_single(void)
{
    seed(4);
    enum { N = 150 };
    static double s[9 * N], t[9 * N], d[N];
    static ttd_result_d r[N];
    static unsigned char bs[9 * N * 8 + 16], bt[9 * N * 8 + 16], bd[N * 8 + 16], br[N * sizeof(ttd_result_d) + 16];
    for (int i = 0; i < N; ++i) {
        int e;
        hostile_case_d(i % (NCASES + 3), s + 9 * i, t + 9 * i, &e); /* cases >= NCASES - 1 are ordinary */
    }
    s[9 * 77 + 4] = (double)NAN; /* and one non-finite pair */
    for (int m = 0; m < TTD_METHOD_COUNT; ++m)
        for (int isa = TTD_ISA_SCALAR; isa < TTD_ISA_COUNT; ++isa) {
            if (!ttd_isa_available((ttd_isa)isa))
                continue;
            ttd_options o = opts(m, isa);
            o.threads = 2;
            ENSURE(ttd_batch_d(&o, N, s, t, d, r) == TTD_ERR_NONFINITE_INPUT);
            const size_t off = 3; /* odd byte offsets: no alignment at all */
            memcpy(bs + off, s, sizeof s);
            memcpy(bt + off, t, sizeof t);
            ENSURE(ttd_batch_d(&o, N, (const double *)(void *)(bs + off), (const double *)(void *)(bt + off),
                               (double *)(void *)(bd + off), (ttd_result_d *)(void *)(br + off)) ==
                   TTD_ERR_NONFINITE_INPUT);
            ENSURE_MSG(memcmp(bd + off, d, sizeof d) == 0 && memcmp(br + off, r, sizeof r) == 0,
                       "%s %s: misaligned batch differs", ttd_method_name((ttd_method)m), ttd_isa_name((ttd_isa)isa));
            for (int i = 0; i < N; ++i) {
                ttd_result_d one;
                ttd_status st = ttd_distance_d(&o, s + 9 * i, t + 9 * i, &one);
                ENSURE(i == 77 ? st == TTD_ERR_NONFINITE_INPUT : computed(st));
                ENSURE_MSG(memcmp(&one, &r[i], sizeof one) == 0 && memcmp(&d[i], &r[i].distance, sizeof d[i]) == 0,
                           "%s %s: pair %d (case %d) in a batch differs from alone", ttd_method_name((ttd_method)m),
                           ttd_isa_name((ttd_isa)isa), i, i % (NCASES + 3));
            }
        }
    return 0;
}

/* Counts for which only the result array (not the coordinates) would overflow size_t, and
 * counts just past the coordinates' limit: refused before anything is read or written. */
static int huge_counts_refused(void)
{
    double s[9] = {0}, t[9] = {0}, d[1] = {42};
    float sf[9] = {0}, tf[9] = {0}, df[1] = {42};
    ttd_result_d r[1];
    ttd_result_f rf[1];
    const size_t counts[] = {SIZE_MAX / sizeof(ttd_result_d) + 1, SIZE_MAX / (9 * sizeof(double)) + 1,
                             SIZE_MAX / (9 * sizeof(float)) + 1, SIZE_MAX / 2 + 1, SIZE_MAX};
    for (size_t c = 0; c < sizeof counts / sizeof counts[0]; ++c) {
        ENSURE_MSG(ttd_batch_d(NULL, counts[c], s, t, NULL, r) == TTD_ERR_TOO_LARGE, "n = %zu", counts[c]);
        ENSURE_MSG(ttd_batch_d(NULL, counts[c], s, t, d, NULL) == TTD_ERR_TOO_LARGE, "n = %zu", counts[c]);
        ENSURE_MSG(ttd_batch_f(NULL, counts[c], sf, tf, NULL, rf) == TTD_ERR_TOO_LARGE, "n = %zu", counts[c]);
        ENSURE_MSG(ttd_batch_f(NULL, counts[c], sf, tf, df, NULL) == TTD_ERR_TOO_LARGE, "n = %zu", counts[c]);
    }
    ENSURE(d[0] == 42 && df[0] == 42);
    /* A thread count far beyond the cores is capped, not obeyed. */
    ttd_options o = ttd_default_options();
    o.threads = 1 << 30;
    enum { N = 3000 };
    static double bs[9 * N], bt[9 * N], bd[N], bd1[N];
    for (int k = 0; k < 9 * N; ++k)
        bs[k] = rnd(), bt[k] = rnd();
    ENSURE(ttd_batch_d(&o, N, bs, bt, bd, NULL) == TTD_OK);
    o.threads = 1;
    ENSURE(ttd_batch_d(&o, N, bs, bt, bd1, NULL) == TTD_OK);
    ENSURE(memcmp(bd, bd1, sizeof bd) == 0);
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    printf("reference: %s\n", ttd_ref_precision());
    RUN_TEST(hostile_double_cases);
    RUN_TEST(hostile_float_cases);
    RUN_TEST(nonfinite_every_position);
    RUN_TEST(mixed_batch_equals_single);
    RUN_TEST(huge_counts_refused);
    TEST_MAIN_END();
}
