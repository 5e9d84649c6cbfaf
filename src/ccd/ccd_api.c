/* SPDX-License-Identifier: MIT */
/* The public continuous-collision entries (ttd.h, the block "Continuous collision detection"):
 * argument checks, the batch over threads (blocks of queries; each query's answer depends on its
 * inputs alone, so not on the threads), the float entries widened to double, and the
 * triangle-triangle query as its 15 sub-queries. A batch screens its queries first, in SIMD lanes
 * on the options' instruction set (simd/kernel_ccd.h; the scalar screen on the scalar row, the
 * same bits), and searches only those the screen does not prove free (docs/ccd.md, section 11). What
 * a query of a batch does beside the screen (reading it, the non-finite answer, the 15 sub-queries) is
 * ccd_batch_impl.h, which the device runs too (docs/ccd.md, section 14). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ccd/ccd.h"
#include "ccd/ccd_batch_impl.h"
#include "engine/dispatch.h"
#include "engine/parallel.h"

enum { CCD_BLOCK = 64 };

/* What a batch reads: the four arrays in one precision, how many floats one primitive has. */
typedef struct ccd_batch {
    int kind;             /* TTD_CCD_VF, TTD_CCD_EE, or 3 for triangles */
    int is_float;
    const void *a0, *b0, *a1, *b1;
    size_t n;
    double delta;
    ttd_ccd_result *out;
    ttd_ccd_screen_fn screen; /* the row's screen in lanes, NULL: the scalar screen */
} ccd_batch;

/* Bit i: query i of count (kind na; x0, x1 12 reals a query) proved free by the screen, the row's
 * lanes or the scalar screen (the same bits). */
static unsigned screen_mask(ttd_ccd_screen_fn screen, int na, int count, const double *x0, const double *x1,
                            double delta, double t_max)
{
    if (screen != NULL)
        return screen(na, count, x0, x1, delta, t_max);
    unsigned m = 0;
    for (int i = 0; i < count; ++i)
        m |= (unsigned)ttd_ccd_screen(na, x0 + 12 * i, x1 + 12 * i, delta, t_max) << i;
    return m;
}

/* The triangle-triangle query: 6 vertex-face and 9 edge-edge, the screen first on all 15 over
 * [0, t_max] in the row's lanes (one evaluation each for those it proves free), then the others
 * searched in turn (ccdb_tri_finish, the device's code too). */
static void triangles_one(double a0[3][3], double b0[3][3], double a1[3][3], double b1[3][3], const ttd_ccd_params *base,
                          ttd_ccd_screen_fn screen, ttd_ccd_result *out)
{
    double x0[15][12], x1[15][12];
    ccdb_tri_subs(a0, b0, a1, b1, x0, x1);
    const unsigned free_subs = screen_mask(screen, TTD_CCD_VF, 6, x0[0], x1[0], base->delta, base->t_max) |
                               screen_mask(screen, TTD_CCD_EE, 8, x0[6], x1[6], base->delta, base->t_max) << 6 |
                               screen_mask(screen, TTD_CCD_EE, 1, x0[14], x1[14], base->delta, base->t_max) << 14;
    ccdb_tri_finish(x0, x1, free_subs, base, out);
}

static void ccd_block(void *ctx, size_t block, int worker)
{
    (void)worker;
    ccd_batch *b = ctx;
    ttd_ccd_params p = ttd_ccd_default_params();
    p.delta = b->delta;
    const size_t end = (block + 1) * CCD_BLOCK < b->n ? (block + 1) * CCD_BLOCK : b->n;
    if (b->kind == 3) {
        for (size_t q = block * CCD_BLOCK; q < end; ++q) {
            double a0[3][3], b0[3][3], a1[3][3], b1[3][3];
            const int finite = ccdb_load(b->is_float, b->a0, q, 3, a0) & ccdb_load(b->is_float, b->b0, q, 3, b0) &
                               ccdb_load(b->is_float, b->a1, q, 3, a1) & ccdb_load(b->is_float, b->b1, q, 3, b1);
            if (finite)
                triangles_one(a0, b0, a1, b1, &p, b->screen, &b->out[q]);
            else
                ccdb_nonfinite(&b->out[q]);
        }
        return;
    }
    /* Vertex-face and edge-edge: groups of TTD_NODE_WIDTH queries, the screen in lanes on the group
     * where the row has it, the scalar search on the queries it does not prove free. */
    const int na = b->kind, nb = 4 - b->kind;
    for (size_t g = block * CCD_BLOCK; g < end; g += TTD_NODE_WIDTH) {
        const int count = end - g < TTD_NODE_WIDTH ? (int)(end - g) : TTD_NODE_WIDTH;
        double x0[TTD_NODE_WIDTH][12], x1[TTD_NODE_WIDTH][12];
        unsigned finite = 0;
        for (int i = 0; i < count; ++i) {
            double(*p0)[3] = (double(*)[3])x0[i], (*p1)[3] = (double(*)[3])x1[i];
            const size_t q = g + (size_t)i;
            const int f = ccdb_load(b->is_float, b->a0, q, na, p0) & ccdb_load(b->is_float, b->b0, q, nb, p0 + na) &
                          ccdb_load(b->is_float, b->a1, q, na, p1) & ccdb_load(b->is_float, b->b1, q, nb, p1 + na);
            finite |= (unsigned)f << i;
        }
        /* The scalar row searches every query: its first interval runs the screen's tests itself
         * (the same answer for a query the screen proves: no hit after one evaluation). */
        const unsigned proved = b->screen != NULL ? b->screen(na, count, x0[0], x1[0], p.delta, p.t_max) : 0;
        for (int i = 0; i < count; ++i) {
            ttd_ccd_result *r = &b->out[g + (size_t)i];
            if (!((finite >> i) & 1u)) {
                ccdb_nonfinite(r);
            } else if ((proved >> i) & 1u) {
                ccdb_screened(r);
            } else {
                ttd_ccd_query(b->kind, x0[i], x1[i], &p, r);
                r->sub = 0;
            }
        }
    }
}

static ttd_status ccd_run(const ttd_options *opt, int kind, int is_float, size_t n, const void *a0,
                          const void *b0, const void *a1, const void *b1, double delta,
                          ttd_ccd_result *out)
{
    int threads = 0;
    ttd_isa isa_req = TTD_ISA_AUTO, isa;
    if (opt != NULL) {
        if (opt->internal_cookie != ttd_default_options().internal_cookie || opt->threads < 0)
            return TTD_ERR_BAD_OPTIONS;
        threads = opt->threads;
        isa_req = opt->isa;
    }
    const ttd_status st = ttd_dispatch_resolve(isa_req, &isa);
    if (st != TTD_OK)
        return st;
    if (a0 == NULL || b0 == NULL || a1 == NULL || b1 == NULL || out == NULL)
        return TTD_ERR_NULL_POINTER;
    if (n == 0)
        return TTD_ERR_EMPTY;
    if (!(delta >= 0) || !isfinite(delta))
        return TTD_ERR_BAD_OPTIONS;
    if (n > SIZE_MAX / (12 * sizeof(double)))
        return TTD_ERR_TOO_LARGE;
    const ttd_kernels_d *row = ttd_dispatch_row_d(isa);
    ccd_batch b = {kind, is_float, a0, b0, a1, b1, n, delta, out, row != NULL ? row->ccd_screen : NULL};
    const size_t blocks = (n + CCD_BLOCK - 1) / CCD_BLOCK;
    ttd_parallel_for(blocks, threads, ccd_block, &b);
    for (size_t q = 0; q < n; ++q)
        if (out[q].flags & TTD_CCD_NONFINITE)
            return TTD_ERR_NONFINITE_INPUT;
    return TTD_OK;
}

ttd_status ttd_ccd_vertex_face_d(const ttd_options *opt, size_t n, const double *v_t0, const double *f_t0,
                                 const double *v_t1, const double *f_t1, double min_separation,
                                 ttd_ccd_result *out)
{
    return ccd_run(opt, TTD_CCD_VF, 0, n, v_t0, f_t0, v_t1, f_t1, min_separation, out);
}

ttd_status ttd_ccd_vertex_face_f(const ttd_options *opt, size_t n, const float *v_t0, const float *f_t0,
                                 const float *v_t1, const float *f_t1, double min_separation,
                                 ttd_ccd_result *out)
{
    return ccd_run(opt, TTD_CCD_VF, 1, n, v_t0, f_t0, v_t1, f_t1, min_separation, out);
}

ttd_status ttd_ccd_edge_edge_d(const ttd_options *opt, size_t n, const double *ea_t0, const double *eb_t0,
                               const double *ea_t1, const double *eb_t1, double min_separation,
                               ttd_ccd_result *out)
{
    return ccd_run(opt, TTD_CCD_EE, 0, n, ea_t0, eb_t0, ea_t1, eb_t1, min_separation, out);
}

ttd_status ttd_ccd_edge_edge_f(const ttd_options *opt, size_t n, const float *ea_t0, const float *eb_t0,
                               const float *ea_t1, const float *eb_t1, double min_separation,
                               ttd_ccd_result *out)
{
    return ccd_run(opt, TTD_CCD_EE, 1, n, ea_t0, eb_t0, ea_t1, eb_t1, min_separation, out);
}

ttd_status ttd_ccd_triangles_d(const ttd_options *opt, size_t n, const double *ta_t0, const double *tb_t0,
                               const double *ta_t1, const double *tb_t1, double min_separation,
                               ttd_ccd_result *out)
{
    return ccd_run(opt, 3, 0, n, ta_t0, tb_t0, ta_t1, tb_t1, min_separation, out);
}

ttd_status ttd_ccd_triangles_f(const ttd_options *opt, size_t n, const float *ta_t0, const float *tb_t0,
                               const float *ta_t1, const float *tb_t1, double min_separation,
                               ttd_ccd_result *out)
{
    return ccd_run(opt, 3, 1, n, ta_t0, tb_t0, ta_t1, tb_t1, min_separation, out);
}
