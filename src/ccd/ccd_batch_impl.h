/* SPDX-License-Identifier: MIT */
/* What a batch does with one query, one source for the CPU batch (ccd_api.c) and the device (one
 * query a CUDA thread, src/gpu/gpu_ccd.cu): read the query from the user's arrays (float widened
 * to double exactly), the answer of a query with a non-finite coordinate, the 15 sub-queries of a
 * triangle pair and their earliest hit. TTDW_FN throughout (ccd_search_impl.h). */
#ifndef TTD_CCD_CCD_BATCH_IMPL_H
#define TTD_CCD_CCD_BATCH_IMPL_H

#include <stddef.h>
#include <stdint.h>

#include "ccd/ccd_search_impl.h"

/* A query with a NaN or infinite coordinate: nothing computed. */
TTDW_FN void ccdb_nonfinite(ttd_ccd_result *r)
{
    r->hit = 0;
    r->toi = (double)NAN;
    r->gap = (double)NAN;
    r->flags = TTD_CCD_NONFINITE;
    r->sub = 0;
    r->evals = 0;
}

/* What a query the screen proves free answers (ttd_ccd_screen): no hit after one evaluation,
 * ttd_ccd_query's own answer for it. */
TTDW_FN void ccdb_screened(ttd_ccd_result *r)
{
    r->hit = 0;
    r->toi = HUGE_VAL;
    r->gap = HUGE_VAL;
    r->flags = 0;
    r->sub = 0;
    r->evals = 1;
}

/* The np points of query q of arr (float when is_float, else double: 3 np reals a query) into x;
 * 0 when one is not finite. */
TTDW_FN int ccdb_load(int is_float, const void *arr, size_t q, int np, double x[][3])
{
    int finite = 1;
    for (int i = 0; i < np; ++i)
        for (int k = 0; k < 3; ++k) {
            const size_t j = (q * (size_t)np + (size_t)i) * 3 + (size_t)k;
            x[i][k] = is_float ? (double)((const float *)arr)[j] : ((const double *)arr)[j];
            finite &= isfinite(x[i][k]) != 0;
        }
    return finite;
}

/* The 15 sub-queries of a triangle pair: 0..2 vertex i of a against b, 3..5 vertex i of b against
 * a, 6..14 edge i of a (vertices i, i + 1) against edge j of b, sub = 6 + 3i + j. */
TTDW_FN void ccdb_tri_subs(double a0[3][3], double b0[3][3], double a1[3][3], double b1[3][3], double x0[15][12],
                           double x1[15][12])
{
    for (int sub = 0; sub < 15; ++sub) {
        if (sub < 6) {
            double(*p0)[3] = sub < 3 ? a0 : b0, (*p1)[3] = sub < 3 ? a1 : b1;
            double(*f0)[3] = sub < 3 ? b0 : a0, (*f1)[3] = sub < 3 ? b1 : a1;
            const int v = sub % 3;
            memcpy(x0[sub], p0[v], sizeof(double) * 3);
            memcpy(x1[sub], p1[v], sizeof(double) * 3);
            memcpy(x0[sub] + 3, f0, sizeof(double) * 9);
            memcpy(x1[sub] + 3, f1, sizeof(double) * 9);
        } else {
            const int i = (sub - 6) / 3, j = (sub - 6) % 3;
            const size_t d = sizeof(double) * 3;
            memcpy(x0[sub], a0[i], d);
            memcpy(x0[sub] + 3, a0[(i + 1) % 3], d);
            memcpy(x0[sub] + 6, b0[j], d);
            memcpy(x0[sub] + 9, b0[(j + 1) % 3], d);
            memcpy(x1[sub], a1[i], d);
            memcpy(x1[sub] + 3, a1[(i + 1) % 3], d);
            memcpy(x1[sub] + 6, b1[j], d);
            memcpy(x1[sub] + 9, b1[(j + 1) % 3], d);
        }
    }
}

/* Bit sub set where the scalar screen proves sub-query sub free over [0, t_max] (the lanes' screen
 * of a CPU row gives the same bits: simd/kernel_ccd.h). */
TTDW_FN unsigned ccdb_tri_screen(double x0[15][12], double x1[15][12], double delta, double t_max)
{
    unsigned m = 0;
    for (int sub = 0; sub < 15; ++sub)
        m |= (unsigned)ccd_screen_one(sub < 6 ? TTD_CCD_VF : TTD_CCD_EE, x0[sub], x1[sub], delta, t_max) << sub;
    return m;
}

/* The triangle-triangle answer from the sub-queries and the screen's bits over [0, base->t_max]:
 * one evaluation each for those proved free, the others searched in turn, each only up to the
 * earliest hit so far (a later contact cannot be the first). */
TTDW_FN void ccdb_tri_finish(double x0[15][12], double x1[15][12], unsigned free_subs, const ttd_ccd_params *base,
                             ttd_ccd_result *out)
{
    ttd_ccd_params p = *base;
    ttd_ccd_result best = {HUGE_VAL, HUGE_VAL, 0, 0, 0, 0};
    uint32_t evals = 0;
    for (int sub = 0; sub < 15; ++sub) {
        if ((free_subs >> sub) & 1u) {
            ++evals;
            continue;
        }
        ttd_ccd_result r;
        ccd_query_one(sub < 6 ? TTD_CCD_VF : TTD_CCD_EE, x0[sub], x1[sub], &p, &r);
        evals += r.evals;
        /* A hit at toi strictly before the best so far replaces it (ties keep the lower sub). */
        if (r.hit && (!best.hit || r.toi < best.toi)) {
            best = r;
            best.sub = (uint32_t)sub;
            p.t_max = r.toi;
        }
        best.flags |= r.flags;
    }
    best.evals = evals;
    *out = best;
}

/* What one device thread runs for query q of a batch of vertex-face (kind TTD_CCD_VF) or edge-edge
 * (TTD_CCD_EE) queries (a0, b0, a1, b1 the user's arrays), with the default search limits and min
 * separation delta: the CPU batch's answer, bit for bit (the CPU screens groups in lanes first,
 * which gives the search's own answer for the queries it proves free). */
TTDW_FN void ccdb_query_pair(int kind, int is_float, const void *a0, const void *b0, const void *a1, const void *b1,
                             size_t q, double delta, ttd_ccd_result *out)
{
    ttd_ccd_params p = ccd_params_default();
    p.delta = delta;
    const int na = kind, nb = 4 - kind;
    double x0[12], x1[12]; /* the four points of the query, A's first */
    double(*p0)[3] = (double(*)[3])x0, (*p1)[3] = (double(*)[3])x1;
    const int finite = ccdb_load(is_float, a0, q, na, p0) & ccdb_load(is_float, b0, q, nb, p0 + na) &
                       ccdb_load(is_float, a1, q, na, p1) & ccdb_load(is_float, b1, q, nb, p1 + na);
    if (!finite) {
        ccdb_nonfinite(out);
        return;
    }
    ccd_query_one(kind, x0, x1, &p, out);
    out->sub = 0;
}

/* The same for a triangle pair: the 15 sub-queries, the scalar screen's bits, the earliest hit. */
TTDW_FN void ccdb_query_triangles(int is_float, const void *a0, const void *b0, const void *a1, const void *b1,
                                  size_t q, double delta, ttd_ccd_result *out)
{
    ttd_ccd_params p = ccd_params_default();
    p.delta = delta;
    double ta0[3][3], tb0[3][3], ta1[3][3], tb1[3][3];
    const int finite = ccdb_load(is_float, a0, q, 3, ta0) & ccdb_load(is_float, b0, q, 3, tb0) &
                       ccdb_load(is_float, a1, q, 3, ta1) & ccdb_load(is_float, b1, q, 3, tb1);
    if (!finite) {
        ccdb_nonfinite(out);
        return;
    }
    double x0[15][12], x1[15][12];
    ccdb_tri_subs(ta0, tb0, ta1, tb1, x0, x1);
    ccdb_tri_finish(x0, x1, ccdb_tri_screen(x0, x1, p.delta, p.t_max), &p, out);
}

/* Either, by kind (3: triangles). */
TTDW_FN void ccdb_query(int kind, int is_float, const void *a0, const void *b0, const void *a1, const void *b1,
                        size_t q, double delta, ttd_ccd_result *out)
{
    if (kind == 3)
        ccdb_query_triangles(is_float, a0, b0, a1, b1, q, delta, out);
    else
        ccdb_query_pair(kind, is_float, a0, b0, a1, b1, q, delta, out);
}

#endif /* TTD_CCD_CCD_BATCH_IMPL_H */
