/* SPDX-License-Identifier: MIT */
/* A self-contact query's screens (core/kernels.h, self_screen and box_screen; mesh/self_grid_impl.h):
 * a triangle's box against a leaf's 8 triangles' boxes with their vertex indices, and a leaf's box
 * against 8 leaves' boxes, a lane each. Comparisons only (no arithmetic), so every row gives the
 * scalar loops' bits. Double rows only: both precisions screen in double. */
#ifdef TTD_PRECISION_DOUBLE

/* The lanes of boxes lo[c][j..], hi[c][j..] near box q. */
TTDW_FN ttdw_md screen_near(const double *const lo[3], const double *const hi[3], int j, const double q[6])
{
    ttdw_md m = ttdw_mand_d(ttdw_le_d(ttdw_loadu_d(lo[0] + j), ttdw_set1_d(q[3])),
                            ttdw_le_d(ttdw_set1_d(q[0]), ttdw_loadu_d(hi[0] + j)));
    for (int c = 1; c < 3; ++c)
        m = ttdw_mand_d(m, ttdw_mand_d(ttdw_le_d(ttdw_loadu_d(lo[c] + j), ttdw_set1_d(q[3 + c])),
                                       ttdw_le_d(ttdw_set1_d(q[c]), ttdw_loadu_d(hi[c] + j))));
    return m;
}

static unsigned self_screen(const ttd_self_block *g, const ttd_self_block *h, int same, uint16_t out[TTD_NODE_WIDTH])
{
    const double *const lo[3] = {h->lo[0], h->lo[1], h->lo[2]}, *const hi[3] = {h->hi[0], h->hi[1], h->hi[2]};
    /* the rows of g near h's leaf box (on a sheet, those along the leaves' common border) */
    const double *const glo[3] = {g->lo[0], g->lo[1], g->lo[2]}, *const ghi[3] = {g->hi[0], g->hi[1], g->hi[2]};
    unsigned rows = 0;
    for (int j = 0; j < TTD_NODE_WIDTH; j += TTDW_LANES_D)
        rows |= ttdw_mbits_d(screen_near(glo, ghi, j, h->box)) << j;
    if (same) /* only lanes j > i count: the last row has none */
        rows &= (1u << (TTD_NODE_WIDTH - 1)) - 1;
    unsigned found = 0; /* the rows with a pair of each kind (core/kernels.h) */
    memset(out, 0, TTD_NODE_WIDTH * sizeof *out);
    for (; rows != 0; rows &= rows - 1) {
        const int i = __builtin_ctz(rows);
        const double q[6] = {g->lo[0][i], g->lo[1][i], g->lo[2][i], g->hi[0][i], g->hi[1][i], g->hi[2][i]};
        const ttdw_vd i0 = ttdw_set1_d(g->ix[0][i]), i1 = ttdw_set1_d(g->ix[1][i]), i2 = ttdw_set1_d(g->ix[2][i]);
        unsigned n = 0, s = 0;
        for (int j = 0; j < TTD_NODE_WIDTH; j += TTDW_LANES_D) {
            const ttdw_md near = screen_near(lo, hi, j, q);
            ttdw_md share = ttdw_eq_d(ttdw_loadu_d(h->ix[0] + j), i0);
            for (int c = 0; c < 3; ++c) {
                const ttdw_vd x = ttdw_loadu_d(h->ix[c] + j);
                share = ttdw_mor_d(share, ttdw_mor_d(ttdw_eq_d(x, i0), ttdw_mor_d(ttdw_eq_d(x, i1), ttdw_eq_d(x, i2))));
            }
            ttdw_md pair = ttdw_mandnot_d(near, share); /* near, sharing no vertex */
            if (ttdw_mbits_d(pair)) /* the diagonal directions (self_grid_impl.h, the diagonal screen) */
                for (int d = 0; d < 6; ++d)
                    pair = ttdw_mand_d(pair, ttdw_mand_d(ttdw_le_d(ttdw_loadu_d(h->dg[d] + j), ttdw_set1_d(g->dg[6 + d][i])),
                                                         ttdw_le_d(ttdw_set1_d(g->dg[d][i]), ttdw_loadu_d(h->dg[6 + d] + j))));
            n |= ttdw_mbits_d(pair) << j;
            s |= ttdw_mbits_d(ttdw_mand_d(near, share)) << j;
        }
        if (same) {
            const unsigned after = (0xFEu << i) & 0xFFu;
            n &= after;
            s &= after;
        }
        out[i] = (uint16_t)(n | s << 8);
        found |= (unsigned)(n != 0) << i | (unsigned)(s != 0) << (8 + i);
    }
    return found;
}

static unsigned box_screen(const double *const lo[3], const double *const hi[3], const double q[6])
{
    unsigned n = 0;
    for (int j = 0; j < TTD_NODE_WIDTH; j += TTDW_LANES_D)
        n |= ttdw_mbits_d(screen_near(lo, hi, j, q)) << j;
    return n;
}

/* A leaf's triangles' boxes and diagonal projections, 8 lanes (core/kernels.h, self_fill). */
static void self_fill(const double v[9][TTD_NODE_WIDTH], double L, double R, ttd_self_block *b)
{
    const ttdw_vd l = ttdw_set1_d(L), r = ttdw_set1_d(R);
    for (int j = 0; j < TTD_NODE_WIDTH; j += TTDW_LANES_D) {
        ttdw_vd x[3][3]; /* vertex k, coordinate c */
        for (int k = 0; k < 3; ++k)
            for (int c = 0; c < 3; ++c)
                x[k][c] = ttdw_loadu_d(v[3 * k + c] + j);
        for (int c = 0; c < 3; ++c) {
            /* the scalar loops: mn = x0 < x1 ? x0 : x1, mx = x0 < x1 ? x1 : x0, then x2 */
            const ttdw_vd mn = ttdw_min_d(x[2][c], ttdw_min_d(x[0][c], x[1][c]));
            const ttdw_vd mx = ttdw_max_d(x[2][c], ttdw_max_d(x[1][c], x[0][c]));
            ttdw_storeu_d(b->lo[c] + j, mn);
            ttdw_storeu_d(b->hi[c] + j, mx + l);
        }
        for (int d = 0; d < 6; ++d) {
            const int a = d < 4 ? 0 : 1, e = d < 2 ? 1 : 2; /* x +- y, x +- z, y +- z */
            ttdw_vd p[3];
            for (int k = 0; k < 3; ++k)
                p[k] = d % 2 ? x[k][a] - x[k][e] : x[k][a] + x[k][e];
            ttdw_storeu_d(b->dg[d] + j, ttdw_min_d(p[2], ttdw_min_d(p[1], p[0])));
            ttdw_storeu_d(b->dg[6 + d] + j, ttdw_max_d(p[2], ttdw_max_d(p[1], p[0])) + r);
        }
    }
}

#define TTD_LANE_ROW_SELF_SCREEN .self_screen = self_screen, .box_screen = box_screen, .self_fill = self_fill,
#else
#define TTD_LANE_ROW_SELF_SCREEN
#endif
