/* SPDX-License-Identifier: MIT */
/* Mesh self-CCD's whole-pair proof in lanes (core/kernels.h, tri_apart; docs/ccd.md, section 10):
 * one triangle pair a lane, meshccd.c's tri_pair_apart computed with the same operations in the
 * same order (no FMA: the build has -ffp-contract=off; its ternary minima and maxima as selects of
 * the same comparisons, so a NaN is passed over as there), so every row proves exactly the pairs
 * that the scalar proof proves. Each lane tries its own directions (its facing edge first, chosen
 * per lane as the scalar code chooses it); a group of lanes stops at the first direction after
 * which every live lane is proved. The file also holds leaf_screen, a pair of self leaves' boxes
 * compared in one call (each row's box broadcast against the other leaf's 8). Double rows only
 * (the mesh query is in double). */
#ifdef TTD_PRECISION_DOUBLE

/* meshccd.c's gap_proves on lanes: the two triangles (points 0..2 and 3..5 of x0 and x1) apart
 * by more than delta |n| along n at t = 0 and t = 1, beyond the rounding bound. */
TTDW_FN ttdw_md tri_apart_gap(const ccdw3 n, ccdw3 *x0, ccdw3 *x1, ttdw_vd S, double delta)
{
    const double u = 0x1p-53;
    const ttdw_vd huge = ttdw_set1_d(HUGE_VAL);
    const ttdw_vd n1 = ttdw_abs_d(n[0]) + ttdw_abs_d(n[1]) + ttdw_abs_d(n[2]);
    const ttdw_md ok = ttdw_mand_d(ttdw_mand_d(ttdw_gt_d(n1, ttdw_zero_d()), ttdw_lt_d(n1, huge)),
                                   ttdw_lt_d(n1 * S, ttdw_set1_d(0x1p1000))); /* as gap_proves: no overflow */
    const ttdw_vd nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    const ttdw_vd need = delta != 0 ? ttdw_set1_d(delta) * ttdw_sqrt_d(nn) * ttdw_set1_d(1 + 0x1p-40)
                                    : ttdw_zero_d() * nn;
    const ttdw_vd base = ttdw_set1_d(8 * u) * n1 * S + ttdw_set1_d(0x1p-1000);
    const ttdw_vd two_u = ttdw_set1_d(2 * u);
    ttdw_md ok_pos = ok, ok_neg = ok;
    for (int t = 0; t < 2; ++t) {
        ccdw3 *y = t ? x1 : x0;
        ttdw_vd amin = huge, amax = -huge, bmin = huge, bmax = -huge;
        for (int i = 0; i < 6; ++i) {
            const ttdw_vd d = n[0] * y[i][0] + n[1] * y[i][1] + n[2] * y[i][2];
            if (i < 3) {
                amin = ttdw_sel_d(ttdw_lt_d(d, amin), d, amin);
                amax = ttdw_sel_d(ttdw_gt_d(d, amax), d, amax);
            } else {
                bmin = ttdw_sel_d(ttdw_lt_d(d, bmin), d, bmin);
                bmax = ttdw_sel_d(ttdw_gt_d(d, bmax), d, bmax);
            }
        }
        const ttdw_vd gp = amin - bmax, gn = bmin - amax;
        ok_pos = ttdw_mand_d(ok_pos, ttdw_gt_d(gp - (base + two_u * ttdw_abs_d(gp)), need));
        ok_neg = ttdw_mand_d(ok_neg, ttdw_gt_d(gn - (base + two_u * ttdw_abs_d(gn)), need));
    }
    return ttdw_mor_d(ok_pos, ok_neg);
}

/* e x (w x e), as meshccd.c's perp3. */
TTDW_FN void tri_apart_perp(ccdw3 r, const ccdw3 e, const ccdw3 w)
{
    ccdw3 c;
    ccdw_cross(c, w, e);
    ccdw_cross(r, e, c);
}

/* The lanes of points p0, p1 (live: those below count): the mask of those proved. The
 * directions in the scalar order (end 0 then 1; per end the first triangle's three edges from its
 * facing one, the second's likewise, then the two normals); a lane proved early is simply
 * proved again by later ones, which changes nothing (which pairs are proved does not depend on
 * the order at all: a pair is proved when any of its directions proves it). */
TTDW_FN ttdw_md tri_apart_proof(ccdw3 *p0, ccdw3 *p1, const ttdw_vd S, ttdw_md live, double delta)
{
    ttdw_md proved = ttdw_mnot_d(live); /* padding counts as done */
    for (int end = 0; end < 2; ++end) {
        ccdw3 *p = end ? p1 : p0;
        ccdw3 d;
        for (int k = 0; k < 3; ++k)
            d[k] = (p[3][k] + p[4][k] + p[5][k]) - (p[0][k] + p[1][k] + p[2][k]);
        ccdw3 e[2][3];
        for (int sd = 0; sd < 2; ++sd) {
            for (int q = 0; q < 3; ++q)
                ccdw_sub(e[sd][q], p[3 * sd + (q + 1) % 3], p[3 * sd + q]);
            /* the vertex furthest back along d (the first strictly least of sg (v . d)) */
            const ttdw_vd sg = ttdw_set1_d(sd ? -1.0 : 1.0);
            ttdw_vd back = ttdw_zero_d(), best = ttdw_set1_d(HUGE_VAL);
            for (int i = 0; i < 3; ++i) {
                const ttdw_vd a = sg * ccdw_dot(p[3 * sd + i], d);
                const ttdw_md lt = ttdw_lt_d(a, best);
                best = ttdw_sel_d(lt, a, best);
                back = ttdw_sel_d(lt, ttdw_set1_d((double)i), back);
            }
            for (int jj = 0; jj < 3; ++jj) {
                /* edge q = (back + 1 + 2 jj) mod 3, and edge (q + 2) mod 3 towards the third vertex */
                ttdw_vd q = back + ttdw_set1_d((double)(1 + 2 * jj));
                q = ttdw_sel_d(ttdw_ge_d(q, ttdw_set1_d(3.0)), q - ttdw_set1_d(3.0), q);
                q = ttdw_sel_d(ttdw_ge_d(q, ttdw_set1_d(3.0)), q - ttdw_set1_d(3.0), q);
                const ttdw_md is0 = ttdw_eq_d(q, ttdw_zero_d()), is1 = ttdw_eq_d(q, ttdw_set1_d(1.0));
                ccdw3 E, W, m, t1, t2;
                ccdw_sel3(t1, is1, e[sd][1], e[sd][2]);
                ccdw_sel3(E, is0, e[sd][0], t1);
                ccdw_sel3(t2, is1, e[sd][0], e[sd][1]);
                ccdw_sel3(W, is0, e[sd][2], t2);
                tri_apart_perp(m, E, W);
                proved = ttdw_mor_d(proved, tri_apart_gap(m, p0, p1, S, delta));
                if (ttdw_mbits_d(ttdw_mnot_d(proved)) == 0)
                    return proved;
            }
        }
        for (int sd = 0; sd < 2; ++sd) {
            ccdw3 n;
            ccdw_cross(n, e[sd][0], e[sd][1]);
            proved = ttdw_mor_d(proved, tri_apart_gap(n, p0, p1, S, delta));
            if (ttdw_mbits_d(ttdw_mnot_d(proved)) == 0)
                return proved;
        }
    }
    return proved;
}

/* The lanes j .. j + TTDW_LANES_D - 1 of points given in the row's layout (tri_apart). */
TTDW_FN ttdw_md tri_apart_lanes(const double *x, const double *S_, int j, ttdw_md live, double delta)
{
    ccdw3 p0[6], p1[6];
    for (int i = 0; i < 6; ++i)
        for (int c = 0; c < 3; ++c) {
            p0[i][c] = ttdw_loadu_d(x + (3 * i + c) * TTD_NODE_WIDTH + j);
            p1[i][c] = ttdw_loadu_d(x + (18 + 3 * i + c) * TTD_NODE_WIDTH + j);
        }
    return tri_apart_proof(p0, p1, ttdw_loadu_d(S_ + j), live, delta);
}

static unsigned tri_apart(int count, const double *x, const double *S, double delta)
{
    unsigned out = 0;
    for (int j = 0; j < count; j += TTDW_LANES_D) {
        const ttdw_md live = ttdw_mfirst_d(count - j);
        out |= ttdw_mbits_d(ttdw_mand_d(tri_apart_lanes(x, S, j, live, delta), live)) << j;
    }
    return out;
}

/* The points of TTDW_LANES_D vertices, x[3 v[l] ..], and vmag[v[l]], lane l from vertex v[l].
 * On AVX2 and AVX-512 by loads, 4 lanes at a time (x, y with one 128-bit load, z with one 64-bit
 * load, joined by unpacks): on this project's AMD machines the four- and eight-lane gathers cost
 * several times these loads (docs/ccd-speed.md, changes 20 and 22). Elsewhere one lane at a time.
 * The same numbers in the same lanes either way. */
#if defined(TTDW_USE_AVX2) || defined(TTDW_USE_AVX512)
#define TTD_TRI_APART_LOADS 1
static inline void tri_apart_load4(const double *x, const uint32_t *v, __m256d p[3])
{
    const double *a = x + 3 * (size_t)v[0], *b = x + 3 * (size_t)v[1], *c = x + 3 * (size_t)v[2],
                 *d = x + 3 * (size_t)v[3];
    const __m128d xa = _mm_loadu_pd(a), xb = _mm_loadu_pd(b), xc = _mm_loadu_pd(c), xd = _mm_loadu_pd(d);
    const __m128d zab = _mm_loadh_pd(_mm_load_sd(a + 2), b + 2), zcd = _mm_loadh_pd(_mm_load_sd(c + 2), d + 2);
    p[0] = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_unpacklo_pd(xa, xb)), _mm_unpacklo_pd(xc, xd), 1);
    p[1] = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_unpackhi_pd(xa, xb)), _mm_unpackhi_pd(xc, xd), 1);
    p[2] = _mm256_insertf128_pd(_mm256_castpd128_pd256(zab), zcd, 1);
}
static inline __m256d tri_apart_load1x4(const double *m, const uint32_t *v)
{
    return _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadh_pd(_mm_load_sd(m + v[0]), m + v[1])),
                                _mm_loadh_pd(_mm_load_sd(m + v[2]), m + v[3]), 1);
}
#if defined(TTDW_USE_AVX2)
static inline void tri_apart_load(const double *x, const uint32_t *v, ttdw_vd p[3]) { tri_apart_load4(x, v, p); }
static inline ttdw_vd tri_apart_load1(const double *m, const uint32_t *v) { return tri_apart_load1x4(m, v); }
#else
static inline void tri_apart_load(const double *x, const uint32_t *v, ttdw_vd p[3])
{
    __m256d lo[3], hi[3];
    tri_apart_load4(x, v, lo);
    tri_apart_load4(x, v + 4, hi);
    for (int c = 0; c < 3; ++c)
        p[c] = _mm512_insertf64x4(_mm512_castpd256_pd512(lo[c]), hi[c], 1);
}
static inline ttdw_vd tri_apart_load1(const double *m, const uint32_t *v)
{
    return _mm512_insertf64x4(_mm512_castpd256_pd512(tri_apart_load1x4(m, v)), tri_apart_load1x4(m, v + 4), 1);
}
#endif
#else
typedef struct {
    size_t k[TTDW_LANES_D];
} tri_apart_ix;
TTDW_FN tri_apart_ix tri_apart_index(const uint32_t *v, int m)
{
    tri_apart_ix i;
    for (int l = 0; l < TTDW_LANES_D; ++l)
        i.k[l] = (size_t)m * v[l];
    return i;
}
TTDW_FN ttdw_vd tri_apart_gather(const double *base, tri_apart_ix i)
{
    double t[TTDW_LANES_D];
    for (int l = 0; l < TTDW_LANES_D; ++l)
        t[l] = base[i.k[l]];
    return ttdw_loadu_d(t);
}
#endif

/* tri_apart with the points read from the vertex arrays (core/kernels.h, tri_apart_at): the
 * points and S the numbers the caller would have copied in, S the same running maximum of the
 * six vmag entries in the same order, so the same bits as tri_apart's. */
static unsigned tri_apart_at(int count, const uint32_t *v, const double *x0, const double *x1, const double *vmag,
                             double delta)
{
    unsigned out = 0;
    for (int j = 0; j < count; j += TTDW_LANES_D) {
        const ttdw_md live = ttdw_mfirst_d(count - j);
        ccdw3 p0[6], p1[6];
        ttdw_vd S = ttdw_zero_d();
        for (int i = 0; i < 6; ++i) {
#if defined(TTD_TRI_APART_LOADS)
            tri_apart_load(x0, v + i * TTD_NODE_WIDTH + j, p0[i]);
            tri_apart_load(x1, v + i * TTD_NODE_WIDTH + j, p1[i]);
            const ttdw_vd m = tri_apart_load1(vmag, v + i * TTD_NODE_WIDTH + j);
#else
            const tri_apart_ix k = tri_apart_index(v + i * TTD_NODE_WIDTH + j, 3);
            for (int c = 0; c < 3; ++c) {
                p0[i][c] = tri_apart_gather(x0 + c, k);
                p1[i][c] = tri_apart_gather(x1 + c, k);
            }
            const ttdw_vd m = tri_apart_gather(vmag, tri_apart_index(v + i * TTD_NODE_WIDTH + j, 1));
#endif
            S = ttdw_sel_d(ttdw_gt_d(m, S), m, S);
        }
        out |= ttdw_mbits_d(ttdw_mand_d(tri_apart_proof(p0, p1, S, live, delta), live)) << j;
    }
    return out;
}

/* Mesh self-CCD's leaf pair (core/kernels.h, leaf_screen): b's boxes held in registers across
 * a's rows, one row's bounds broadcast against them (the pair of leaves in one call, where a call
 * of box_screen a row loaded both again). */
static unsigned leaf_screen(const double *const ra[6], int na, const double *const rb[6], uint8_t out[TTD_NODE_WIDTH])
{
    enum { NB = TTD_NODE_WIDTH / TTDW_LANES_D };
    ttdw_vd lo[3][NB], hi[3][NB];
    for (int c = 0; c < 3; ++c)
        for (int j = 0; j < NB; ++j) {
            lo[c][j] = ttdw_loadu_d(rb[c] + j * TTDW_LANES_D);
            hi[c][j] = ttdw_loadu_d(rb[3 + c] + j * TTDW_LANES_D);
        }
    /* the columns' addresses in locals: out's bytes may alias ra[], so ra[c] would be read again
     * after each row's store */
    const double *const a0 = ra[0], *const a1 = ra[1], *const a2 = ra[2], *const a3 = ra[3], *const a4 = ra[4],
                        *const a5 = ra[5];
    unsigned rows = 0;
    for (int i = 0; i < na; ++i) {
        const ttdw_vd q0 = ttdw_set1_d(a0[i]), q1 = ttdw_set1_d(a1[i]), q2 = ttdw_set1_d(a2[i]);
        const ttdw_vd q3 = ttdw_set1_d(a3[i]), q4 = ttdw_set1_d(a4[i]), q5 = ttdw_set1_d(a5[i]);
        unsigned n = 0;
        for (int j = 0; j < NB; ++j) {
            const ttdw_md m = ttdw_mand_d(
                ttdw_mand_d(ttdw_mand_d(ttdw_le_d(lo[0][j], q3), ttdw_le_d(q0, hi[0][j])),
                            ttdw_mand_d(ttdw_le_d(lo[1][j], q4), ttdw_le_d(q1, hi[1][j]))),
                ttdw_mand_d(ttdw_le_d(lo[2][j], q5), ttdw_le_d(q2, hi[2][j])));
            n |= ttdw_mbits_d(m) << (j * TTDW_LANES_D);
        }
        out[i] = (uint8_t)n;
        rows |= (unsigned)(n != 0) << i;
    }
    return rows;
}

#define TTD_LANE_ROW_TRI_APART .tri_apart = tri_apart, .tri_apart_at = tri_apart_at, .leaf_screen = leaf_screen,
#else
#define TTD_LANE_ROW_TRI_APART
#endif
