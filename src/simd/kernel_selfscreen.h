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

static int self_screen(const ttd_self_block *g, const ttd_self_block *h, int same, uint16_t out[TTD_NODE_WIDTH])
{
    const double *const lo[3] = {h->lo[0], h->lo[1], h->lo[2]}, *const hi[3] = {h->hi[0], h->hi[1], h->hi[2]};
    /* the rows of g near h's leaf box (on a sheet, those along the leaves' common border) */
    const double *const glo[3] = {g->lo[0], g->lo[1], g->lo[2]}, *const ghi[3] = {g->hi[0], g->hi[1], g->hi[2]};
    unsigned rows = 0;
    for (int j = 0; j < TTD_NODE_WIDTH; j += TTDW_LANES_D)
        rows |= ttdw_mbits_d(screen_near(glo, ghi, j, h->box)) << j;
    unsigned any = 0;
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
            n |= ttdw_mbits_d(near) << j;
            s |= ttdw_mbits_d(ttdw_mand_d(near, share)) << j;
        }
        if (same) {
            const unsigned after = (0xFEu << i) & 0xFFu;
            n &= after;
            s &= after;
        }
        out[i] = (uint16_t)((n & ~s) | s << 8);
        any |= out[i];
    }
    return any != 0;
}

static unsigned box_screen(const double *const lo[3], const double *const hi[3], const double q[6])
{
    unsigned n = 0;
    for (int j = 0; j < TTD_NODE_WIDTH; j += TTDW_LANES_D)
        n |= ttdw_mbits_d(screen_near(lo, hi, j, q)) << j;
    return n;
}

#define TTD_LANE_ROW_SELF_SCREEN .self_screen = self_screen, .box_screen = box_screen,
#else
#define TTD_LANE_ROW_SELF_SCREEN
#endif
