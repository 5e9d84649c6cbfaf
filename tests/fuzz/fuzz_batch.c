/* SPDX-License-Identifier: MIT */
/* libFuzzer target: the batch API (ttd_batch_d / ttd_batch_f) fed arbitrary bytes.
 *
 * Input layout: byte 0 method, byte 1 instruction set, byte 2 mode bits (bit 0 float, bits
 * 1-2 which outputs: distances, results or both, bit 3 grid coordinates, bits 4-5 threads),
 * then coordinates: raw IEEE values (any bits: NaN, inf, subnormal, huge) or, in grid mode,
 * 16-bit integers / 64 (exact small values, so that touching, parallel and degenerate pairs
 * are common). Buffers are allocated to their exact size, so AddressSanitizer sees any read or
 * write past them.
 *
 * Checked: the status is the one the input calls for; a pair with NaN/inf is flagged and all
 * NaN; a finite pair never gives NaN, its points are finite, and its distance is infinite only
 * when a coordinate is near the overflow limit; a batch pair equals its single-pair call bit
 * for bit; in grid mode the exact method agrees with the quad reference (1e-12 of the pair's
 * size in double, 1e-5 in float on the float input). Build and run: scripts/fuzz.sh. */
#define _POSIX_C_SOURCE 200809L

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ref_distance.h"
#include "ttd/ttd.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define CHECK(c)                                                                        \
    do {                                                                                \
        if (!(c)) {                                                                     \
            fprintf(stderr, "fuzz_batch: check failed at line %d: %s\n", __LINE__, #c); \
            abort();                                                                    \
        }                                                                               \
    } while (0)

enum { MAX_PAIRS = 64, REF_PAIRS = 4 };

static int finite18(const double *s, const double *t)
{
    for (int k = 0; k < 9; ++k)
        if (!isfinite(s[k]) || !isfinite(t[k]))
            return 0;
    return 1;
}

static double max_abs18(const double *s, const double *t)
{
    double m = 0;
    for (int k = 0; k < 9; ++k)
        m = fmax(m, fmax(fabs(s[k]), fabs(t[k])));
    return m;
}

/* One pair's result, widened to double, checked against its input (widened too). */
static void check_pair(int finite, const double *s, const double *t, double d, const double *p, const double *q,
                       uint32_t flags, double real_max)
{
    if (!finite) {
        CHECK(flags == TTD_PAIR_NONFINITE && isnan(d) && isnan(p[0]) && isnan(q[2]));
        return;
    }
    CHECK(!(flags & TTD_PAIR_NONFINITE));
    CHECK(!isnan(d) && d >= 0);
    CHECK(!isinf(d) || max_abs18(s, t) > real_max / 8);
    for (int k = 0; k < 3; ++k)
        CHECK(isfinite(p[k]) && isfinite(q[k]));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 3)
        return 0;
    const int method = data[0] % TTD_METHOD_COUNT, isa = data[1] % TTD_ISA_COUNT;
    const int is_float = data[2] & 1, outputs = 1 + (data[2] >> 1) % 3, grid = (data[2] >> 3) & 1;
    const int threads = (data[2] >> 4) & 3;
    data += 3, size -= 3;
    const size_t bytes_per_coord = grid ? 2 : (is_float ? 4 : 8);
    size_t n = size / (18 * bytes_per_coord);
    if (n > MAX_PAIRS)
        n = MAX_PAIRS;

    ttd_options o = ttd_default_options();
    o.method = (ttd_method)method;
    o.isa = (ttd_isa)isa;
    o.threads = threads;

    /* Coordinates, widened to double for the checks (exact for float). */
    double *sd = malloc(9 * n * sizeof(double) + 1), *td = malloc(9 * n * sizeof(double) + 1);
    CHECK(sd && td);
    int any_nonfinite = 0;
    for (size_t i = 0; i < 18 * n; ++i) {
        const uint8_t *b = data + i * bytes_per_coord;
        double v;
        if (grid) {
            int16_t g;
            memcpy(&g, b, 2);
            v = (double)g / 64;
            if (is_float)
                v = (double)(float)v;
        } else if (is_float) {
            float f;
            memcpy(&f, b, 4);
            v = (double)f;
        } else {
            memcpy(&v, b, 8);
        }
        *(i < 9 * n ? &sd[i] : &td[i - 9 * n]) = v;
    }

    ttd_status st;
    double *dd = NULL;
    ttd_result_d *rd = NULL;
    float *sf = NULL, *tf = NULL, *df = NULL;
    ttd_result_f *rf = NULL;
    if (is_float) {
        /* exact sizes: a zero-pair batch still gets valid (one-byte) pointers */
        sf = malloc(9 * n * sizeof(float) + 1), tf = malloc(9 * n * sizeof(float) + 1);
        df = (outputs & 1) ? malloc(n * sizeof(float) + 1) : NULL;
        rf = (outputs & 2) ? malloc(n * sizeof(ttd_result_f) + 1) : NULL;
        CHECK(sf && tf);
        for (size_t i = 0; i < 9 * n; ++i)
            sf[i] = (float)sd[i], tf[i] = (float)td[i];
        st = ttd_batch_f(&o, n, sf, tf, df, rf);
    } else {
        dd = (outputs & 1) ? malloc(n * sizeof(double) + 1) : NULL;
        rd = (outputs & 2) ? malloc(n * sizeof(ttd_result_d) + 1) : NULL;
        st = ttd_batch_d(&o, n, sd, td, dd, rd);
    }

    if (n == 0) {
        CHECK(st == TTD_ERR_EMPTY);
    } else if (isa != TTD_ISA_AUTO && !ttd_isa_available((ttd_isa)isa)) {
        CHECK(st == TTD_ERR_ISA_UNAVAILABLE);
    } else {
        for (size_t i = 0; i < n; ++i)
            any_nonfinite |= !finite18(sd + 9 * i, td + 9 * i);
        CHECK(any_nonfinite ? st == TTD_ERR_NONFINITE_INPUT : (st == TTD_OK || st == TTD_WARN_NOT_CONVERGED));
        const double real_max = is_float ? (double)FLT_MAX : DBL_MAX;
        for (size_t i = 0; i < n; ++i) {
            const double *s = sd + 9 * i, *t = td + 9 * i;
            const int finite = finite18(s, t);
            double d, p[3], q[3];
            uint32_t flags = 0;
            if (is_float) {
                ttd_result_f one;
                ttd_status st1 = ttd_distance_f(&o, sf + 9 * i, tf + 9 * i, &one);
                CHECK(finite ? st1 < TTD_ERR_NONFINITE_INPUT : st1 == TTD_ERR_NONFINITE_INPUT);
                if (rf) {
                    CHECK(memcmp(&one, &rf[i], sizeof one) == 0);
                    CHECK(!df || memcmp(&df[i], &rf[i].distance, sizeof df[i]) == 0);
                } else {
                    CHECK(memcmp(&df[i], &one.distance, sizeof df[i]) == 0);
                }
                d = (double)one.distance, flags = one.flags;
                for (int k = 0; k < 3; ++k)
                    p[k] = (double)one.p[k], q[k] = (double)one.q[k];
            } else {
                ttd_result_d one;
                ttd_status st1 = ttd_distance_d(&o, s, t, &one);
                CHECK(finite ? st1 < TTD_ERR_NONFINITE_INPUT : st1 == TTD_ERR_NONFINITE_INPUT);
                if (rd) {
                    CHECK(memcmp(&one, &rd[i], sizeof one) == 0);
                    CHECK(!dd || memcmp(&dd[i], &rd[i].distance, sizeof dd[i]) == 0);
                } else {
                    CHECK(memcmp(&dd[i], &one.distance, sizeof dd[i]) == 0);
                }
                d = one.distance, flags = one.flags;
                for (int k = 0; k < 3; ++k)
                    p[k] = one.p[k], q[k] = one.q[k];
            }
            check_pair(finite, s, t, d, p, q, flags, real_max);
            /* Differential: the exact method against the quad reference on grid input. */
            if (grid && finite && method == TTD_METHOD_EXACT && i < REF_PAIRS) {
                ttd_ref_result ref;
                ttd_ref_distance(s, t, &ref);
                double scale = fmax(ref.distance, ttd_ref_size(s, t));
                double tol = (is_float ? 1e-5 : 1e-12) * scale;
                if (!(fabs(d - ref.distance) <= tol)) {
                    fprintf(stderr, "fuzz_batch: exact %s d %.17g, reference %.17g\n", is_float ? "float" : "double",
                            d, ref.distance);
                    abort();
                }
            }
        }
    }
    free(sd), free(td), free(dd), free(rd), free(sf), free(tf), free(df), free(rf);
    return 0;
}
