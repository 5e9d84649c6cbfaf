/* SPDX-License-Identifier: MIT */
/* A self-contact query's screens (core/kernels.h, self_screen and box_list; mesh/self_grid_impl.h):
 * a triangle's box against a leaf's 8 triangles' boxes with their vertex indices, and a leaf's box
 * against up to 64 leaves' boxes, a lane each. Comparisons only (no arithmetic), so every row gives the
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

/* The lanes j.. of h whose diagonal projection e (self_grid_impl.h, the diagonal screen) overlaps
 * g's triangle i's. */
TTDW_FN ttdw_md screen_diagonal(const ttd_self_block *g, const ttd_self_block *h, int i, int j, int e)
{
    return ttdw_mand_d(ttdw_le_d(ttdw_loadu_d(h->dg[e] + j), ttdw_set1_d(g->dg[6 + e][i])),
                       ttdw_le_d(ttdw_set1_d(g->dg[e][i]), ttdw_loadu_d(h->dg[6 + e] + j)));
}

#if defined(__AVX2__) && !defined(__AVX512F__) && TTDW_LANES_D == 4
#include <immintrin.h>
#define SELF_SHARE_I32 1
/* The lanes of h that share a vertex index with g's triangle i, as bits: the 32-bit indices, 8 to
 * a vector (two vectors of 4 doubles a comparison otherwise). */
static inline unsigned self_share_bits(const ttd_self_block *g, const ttd_self_block *h, int i)
{
    const __m256i a = _mm256_set1_epi32((int)g->iv[0][i]), b = _mm256_set1_epi32((int)g->iv[1][i]),
                  c = _mm256_set1_epi32((int)g->iv[2][i]);
    __m256i s = _mm256_setzero_si256();
    for (int k = 0; k < 3; ++k) {
        const __m256i x = _mm256_loadu_si256((const __m256i *)h->iv[k]);
        s = _mm256_or_si256(s, _mm256_or_si256(_mm256_cmpeq_epi32(x, a), _mm256_or_si256(_mm256_cmpeq_epi32(x, b), _mm256_cmpeq_epi32(x, c))));
    }
    return (unsigned)_mm256_movemask_ps(_mm256_castsi256_ps(s));
}
#endif

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
        unsigned n = 0, s = 0;
#ifdef SELF_SHARE_I32
        unsigned nb = 0; /* the same lanes as below, the vertex indices compared 8 at a time */
        for (int j = 0; j < TTD_NODE_WIDTH; j += TTDW_LANES_D)
            nb |= ttdw_mbits_d(screen_near(lo, hi, j, q)) << j;
        if (nb == 0)
            continue;
        const unsigned sb = self_share_bits(g, h, i);
        s = nb & sb;
        for (int j = 0; j < TTD_NODE_WIDTH; j += TTDW_LANES_D) {
            unsigned p = (nb & ~sb) >> j & ((1u << TTDW_LANES_D) - 1); /* near, sharing no vertex */
            for (int d = 0; d < 6 && p != 0; d += 2) /* the diagonal stages, as below */
                for (int e = d; e < d + 2; ++e)
                    p &= ttdw_mbits_d(screen_diagonal(g, h, i, j, e));
            n |= p << j;
        }
#else
        const ttdw_vd i0 = ttdw_set1_d(g->ix[0][i]), i1 = ttdw_set1_d(g->ix[1][i]), i2 = ttdw_set1_d(g->ix[2][i]);
        for (int j = 0; j < TTD_NODE_WIDTH; j += TTDW_LANES_D) {
            const ttdw_md near = screen_near(lo, hi, j, q);
            if (!ttdw_any_d(near)) /* no lane of this vector near: nothing to share or to part */
                continue;
            ttdw_md share = ttdw_eq_d(ttdw_loadu_d(h->ix[0] + j), i0);
            for (int c = 0; c < 3; ++c) {
                const ttdw_vd x = ttdw_loadu_d(h->ix[c] + j);
                share = ttdw_mor_d(share, ttdw_mor_d(ttdw_eq_d(x, i0), ttdw_mor_d(ttdw_eq_d(x, i1), ttdw_eq_d(x, i2))));
            }
            ttdw_md pair = ttdw_mandnot_d(near, share); /* near, sharing no vertex */
            /* the diagonal directions (self_grid_impl.h, the diagonal screen), two at a time, stopping
               once no lane is left: on a flat sheet the in-plane pair (x +- y) parts most lanes */
            for (int d = 0; d < 6 && ttdw_mbits_d(pair); d += 2)
                for (int e = d; e < d + 2; ++e)
                    pair = ttdw_mand_d(pair, screen_diagonal(g, h, i, j, e));
            n |= ttdw_mbits_d(pair) << j;
            s |= ttdw_mbits_d(ttdw_mand_d(near, share)) << j;
        }
#endif
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

/* Box q against up to 64 boxes (core/kernels.h, box_list): q's bounds broadcast once a call. */
static unsigned box_list(const double *b, size_t c, unsigned n, const double q[6], uint8_t at[64])
{
    const ttdw_vd l0 = ttdw_set1_d(q[0]), l1 = ttdw_set1_d(q[1]), l2 = ttdw_set1_d(q[2]);
    const ttdw_vd h0 = ttdw_set1_d(q[3]), h1 = ttdw_set1_d(q[4]), h2 = ttdw_set1_d(q[5]);
    const double *const x0 = b, *const y0 = b + c, *const z0 = b + 2 * c; /* pointers, so that a load's */
    const double *const x1 = b + 3 * c, *const y1 = b + 4 * c, *const z1 = b + 5 * c; /* address is one add */
    unsigned k = 0;
    for (size_t r = 0; r < n; r += TTD_NODE_WIDTH) {
        unsigned m = 0;
        for (size_t j = r; j < r + TTD_NODE_WIDTH; j += TTDW_LANES_D) {
            const ttdw_md x = ttdw_mand_d(ttdw_le_d(ttdw_loadu_d(x0 + j), h0), ttdw_le_d(l0, ttdw_loadu_d(x1 + j)));
            const ttdw_md y = ttdw_mand_d(ttdw_le_d(ttdw_loadu_d(y0 + j), h1), ttdw_le_d(l1, ttdw_loadu_d(y1 + j)));
            const ttdw_md z = ttdw_mand_d(ttdw_le_d(ttdw_loadu_d(z0 + j), h2), ttdw_le_d(l2, ttdw_loadu_d(z1 + j)));
            m |= ttdw_mbits_d(ttdw_mand_d(x, ttdw_mand_d(y, z))) << (j - r);
        }
        if (n - r < TTD_NODE_WIDTH)
            m &= (1u << (n - r)) - 1;
        for (; m != 0; m &= m - 1)
            at[k++] = (uint8_t)(r + (unsigned)__builtin_ctz(m));
    }
    return k;
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

#define TTD_LANE_ROW_SELF_SCREEN .self_screen = self_screen, .box_list = box_list, .self_fill = self_fill,
#else
#define TTD_LANE_ROW_SELF_SCREEN
#endif
