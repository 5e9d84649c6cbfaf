/* SPDX-License-Identifier: MIT */
/* The closest point of a mesh to one point, the walk one CUDA thread would run for it, from one
 * source with the host (tests/cuda_host/), precision-generic: src/points/closest_impl.h's
 * closest_one without the seed (a seed only starts the limit nearer; the answer does not depend on
 * it). Included after simd/kernel_point.h for one precision with TTDW_USE_CUDA (one lane); every
 * function TTDW_FN.
 *
 * The walk reads the mesh's point data (points/points.h, ttd_points_data: float walk nodes and
 * prepared triangle blocks) as the CPU made it. The node test is the float rows' point_node,
 * written here as plain float arithmetic in the same order (a double query calls the float row's
 * test, and one translation unit holds one precision's lane kernels); the triangles are measured by
 * the row's point_block and the winner rebuilt by pk_rebuild, both the scalar reference's bits. The
 * tie rule is total (the smallest triangle index among the nearest), so the whole result is the
 * CPU's, bit for bit, but for the counts of tests.
 *
 * The device kernel is gpu_kernels_impl.cuh's gpu_points_closest_kernel (ttd_gpu_points_closest_d/f);
 * the tests run this body on the host (test_gpu_walk, points_closest; docs/gpu.md, section 6). */

#ifdef TTD_PRECISION_DOUBLE
typedef ttd_point_result_d gp_point_result;
#else
typedef ttd_point_result_f gp_point_result;
#endif

#ifdef __CUDA_ARCH__
#define GP_CTZ(x) (__ffs((int)(x)) - 1)
#else
#define GP_CTZ(x) __builtin_ctz(x)
#endif

/* Deepest stack a walk needs (closest_impl.h's CLOSEST_STACK). */
#define GP_STACK 128

/* The mesh as the walk reads it (struct ttd_mesh and its ttd_points_data). */
typedef struct gp_mesh {
    const ttd_pnode *pnodes;
    const real *blocks;     /* nblocks x TTD_PT_ROWS x TTD_PT_LANES reals */
    double origin[3];
    double radius;
    double scale, stretch;  /* the walk nodes' frame */
} gp_mesh;

typedef struct gp_best {
    real d;
    uint32_t t;
    int32_t node, blk, j;
    real par[3];
    double lim, delta, scale;
    float lim2f;
} gp_best;

/* kernel_point.h's point_node on one lane: the mask of child slots of y whose boxes are within
 * lim2 (squared) of p, lb2 their squared distances (or the largest gap where inside). */
TTDW_FN unsigned gp_point_node(const float p[3], const ttd_pnode *y, float lim2, float lb2[TTD_NODE_WIDTH])
{
    unsigned within = 0;
    for (int j = 0; j < TTD_NODE_WIDTH; ++j) {
        const float dx = p[0] - y->c[0][j], dy = p[1] - y->c[1][j], dz = p[2] - y->c[2][j];
        float s = 0, sep = 0;
        for (int a = 0; a < 3; ++a) {
            const float z = (y->u[3 * a][j] * dx + y->u[3 * a + 1][j] * dy) + y->u[3 * a + 2][j] * dz;
            const float gap = fabsf(z) - y->e[a][j], g = gap > 0.0f ? gap : 0.0f;
            s = a == 0 ? g * g : s + g * g;
            sep = a == 0 ? gap : (sep > gap ? sep : gap);
        }
        lb2[j] = s > 0.0f ? s : sep;
        within |= (unsigned)(s <= lim2) << j;
    }
    return within & ((1u << TTD_NODE_WIDTH) - 1);
}

/* closest_impl.h's closest_limit: ((lim + delta) scale)^2 rounded up to float, within
 * [2^-100, FLT_MAX]. */
TTDW_FN void gp_limit(gp_best *B)
{
    const double x = (B->lim + B->delta) * B->scale;
    double x2 = x * x * (1 + 4 * DBL_EPSILON);
    x2 = x2 > 0x1p-100 ? x2 : 0x1p-100;
    x2 = x2 < (double)FLT_MAX ? x2 : (double)FLT_MAX;
    float r = (float)x2;
    if ((double)r < x2) {
        uint32_t bits;
        memcpy(&bits, &r, sizeof r);
        ++bits;
        memcpy(&r, &bits, sizeof r);
    }
    B->lim2f = r;
}

/* closest_impl.h's closest_measure: node's triangles (slots tm) measured, the best kept (the
 * smallest distance within the bound, ties to the smallest triangle). */
TTDW_FN void gp_measure(const gp_mesh *m, const real P[3], int32_t node, unsigned tm, real ub, gp_best *B)
{
    const ttd_pnode *y = &m->pnodes[node];
    real d[TTD_NODE_WIDTH], par[3][TTD_NODE_WIDTH];
    point_block(P, m->blocks + (size_t)y->block * TTD_PT_ROWS * TTD_PT_LANES, d, par);
    int better = 0;
    for (; tm; tm &= tm - 1) {
        const int j = GP_CTZ(tm);
        if (!(d[j] <= B->d && d[j] <= ub))
            continue;
        const uint32_t t = (uint32_t)(-1 - y->child[j]);
        if (d[j] < B->d || t < B->t) {
            B->d = d[j];
            B->t = t;
            B->node = node;
            B->blk = y->block;
            B->j = j;
            for (int k = 0; k < 3; ++k)
                B->par[k] = par[k][j];
            better = 1;
        }
    }
    if (better) {
        B->lim = (double)B->d;
        gp_limit(B);
    }
}

TTDW_FN void gp_none(gp_point_result *r, real distance, uint8_t flags)
{
    r->distance = distance;
    for (int c = 0; c < 3; ++c)
        r->point[c] = r->bary[c] = (real)NAN;
    r->triangle = UINT32_MAX;
    r->feature = 0;
    r->flags = flags;
}

/* The closest point of mesh m to P within ub (>= 0) into *r: closest_impl.h's closest_one. */
TTDW_FN void gp_closest(const gp_mesh *m, const real P[3], real ub, gp_point_result *r)
{
    memset(r, 0, sizeof *r);
    if (!(P[0] - P[0] == 0 && P[1] - P[1] == 0 && P[2] - P[2] == 0)) { /* NaN or inf */
        gp_none(r, (real)NAN, TTD_POINT_NONFINITE);
        return;
    }
    float pf[3];
    double s2 = 0;
    for (int c = 0; c < 3; ++c) {
        const double x = (double)P[c] - m->origin[c];
        double xs = x * m->scale;
        xs = xs < -0x1p60 ? -0x1p60 : (xs > 0x1p60 ? 0x1p60 : xs);
        pf[c] = (float)xs;
        s2 += x * x;
    }
    const double S = sqrt(s2) + m->radius;
    gp_best B;
    B.d = (real)INFINITY;
    B.t = UINT32_MAX;
    B.node = B.blk = -1;
    B.j = 0;
    B.par[0] = B.par[1] = B.par[2] = 0;
    B.lim = (double)ub;
    B.delta = (64 * (double)TTD_REAL_EPS + 16 * (double)FLT_EPSILON) * S;
    B.scale = m->scale * m->stretch * (1 + 8 * (double)FLT_EPSILON);
    gp_limit(&B);
    uint32_t node_tests = 0, tri_tests = 0;
    int32_t stack_node[GP_STACK];
    float stack_key[GP_STACK];
    int sp = 0;
    int32_t node = 0;
    for (;;) {
        const ttd_pnode *y = &m->pnodes[node];
        float key[TTD_NODE_WIDTH];
        const unsigned within = gp_point_node(pf, y, B.lim2f, key);
        ++node_tests;
        if (within & y->tmask) {
            gp_measure(m, P, node, y->tmask, ub, &B);
            tri_tests += y->ntri;
        }
        int jbest = -1;
        float best = (float)INFINITY;
        for (unsigned nm = within & ~y->tmask; nm; nm &= nm - 1) {
            const int j = GP_CTZ(nm);
            if (key[j] > B.lim2f)
                continue;
            if (key[j] < best) {
                if (jbest >= 0 && sp < GP_STACK) {
                    stack_node[sp] = y->child[jbest];
                    stack_key[sp++] = best;
                }
                best = key[j];
                jbest = j;
            } else if (sp < GP_STACK) {
                stack_node[sp] = y->child[j];
                stack_key[sp++] = key[j];
            }
        }
        if (jbest >= 0) {
            node = y->child[jbest];
            continue;
        }
        while (sp > 0 && stack_key[sp - 1] > B.lim2f)
            --sp;
        if (sp == 0)
            break;
        node = stack_node[--sp];
    }
    r->node_tests = node_tests;
    r->triangle_tests = tri_tests;
    if (B.t == UINT32_MAX) {
        gp_none(r, (real)INFINITY, TTD_POINT_ABOVE_BOUND);
        return;
    }
    /* the winner rebuilt from its candidate: its prepared triangle gathered to stride 1 */
    const real *f = m->blocks + (size_t)B.blk * TTD_PT_ROWS * TTD_PT_LANES + B.j;
    real tri[TTD_PT_COUNT], q[3], w[3];
    for (int i = 0; i < TTD_PT_COUNT; ++i)
        tri[i] = f[(size_t)i * TTD_PT_LANES];
    pk_rebuild(tri, B.par[0], B.par[1], B.par[2], q, w);
    for (int c = 0; c < 3; ++c) {
        r->point[c] = q[c];
        r->bary[c] = w[c];
    }
    r->distance = B.d;
    r->triangle = B.t;
    r->feature = (uint8_t)((r->bary[0] > 0 ? 1u : 0u) | (r->bary[1] > 0 ? 2u : 0u) | (r->bary[2] > 0 ? 4u : 0u));
    r->flags = tri[TTD_PT_INN] > 0 ? 0 : TTD_POINT_DEGENERATE;
}
