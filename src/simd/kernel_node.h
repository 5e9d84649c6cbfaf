/* SPDX-License-Identifier: MIT */
/* The mesh queries' node test (core/kernels.h), one child box per lane: a separating-axis lower
 * bound between one box X and each child box of a node. Read it next to the scalar code,
 * scalar/node_test_impl.h: the same operations in the same order (no FMA), so every row returns
 * the scalar row's bits and a traversal visits the same nodes on every instruction set.
 *
 * With Y's frame mapped into X's box frame (x -> M x + v), child j has centre d = M c + v and
 * axes C = M W^T (column k is axis k of the child, row i its components along X's axes), and
 * A = |C|, so the child reaches sum_k A_ik e_k along X's axis i. Two bounds:
 *  - X's face axes: gaps |d_i| - eX_i - sum_k A_ik e_k; the sum of their squared positive parts
 *    is the squared distance between X and the child's bounding box in X's frame;
 *  - the direction n from X's point nearest the child's centre, clamp(d, -eX, eX), to that
 *    centre: X reaches that point along n, the child sum_k e_k |(C^T n)_k| / |n|, so
 *    |n| gap = |n|^2 - sum_k e_k |(C^T n)_k|. For boxes far apart compared with the child this is
 *    nearly their distance, where the face axes of two tilted boxes leave a slack of the
 *    child's width times the tilt.
 * The child's own face axes and the direction from it to X's centre were measured to add
 * little (at most 10% more node tests on the benchmark's meshes without them) for a third more
 * arithmetic, and are left out. sep is the largest face gap. */

/* Stores the first lanes of v to out[j0 .. TTD_NODE_WIDTH). */
TTDW_FN void node_store(real *out, int j0, vreal v)
{
    if (TTDW_LANES <= TTD_NODE_WIDTH - j0) {
        vstoreu(&out[j0], v);
    } else {
        real buf[TTDW_LANES];
        vstoreu(buf, v);
        for (int j = j0; j < TTD_NODE_WIDTH; ++j)
            out[j] = buf[j - j0];
    }
}

/* Lanes j0.. of the node test up to its one division: the face axes' sum sx and largest gap
 * gmax, and the direction bound's gap gn and squared length nn (the bound is gn^2 / nn). */
static TTD_DEVICE inline __attribute__((always_inline)) void node_lanes(const vreal m[9], const vreal v[3],
                                                                       const vreal ex[3], const ttd_node *y, int j0,
                                                                       vreal *sx_out, vreal *gmax_out, vreal *gn_out,
                                                                       vreal *nn_out)
{
    const vreal zero = vzero();
    vreal c[3], w[9], e[3], d[3], C[9], A[9];
    for (int i = 0; i < 3; ++i) {
        c[i] = vloadu(&y->c[i][j0]);
        e[i] = vloadu(&y->e[i][j0]);
    }
    for (int i = 0; i < 9; ++i)
        w[i] = vloadu(&y->u[i][j0]);
    for (int i = 0; i < 3; ++i)
        d[i] = ((m[3 * i] * c[0] + m[3 * i + 1] * c[1]) + m[3 * i + 2] * c[2]) + v[i];
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) {
            C[3 * i + k] = (m[3 * i] * w[3 * k] + m[3 * i + 1] * w[3 * k + 1]) + m[3 * i + 2] * w[3 * k + 2];
            A[3 * i + k] = vabs(C[3 * i + k]);
        }
    vreal sx = zero, gmax = vset1(-TTD_REAL_MAX);
    for (int i = 0; i < 3; ++i) {
        const vreal g = (vabs(d[i]) - ex[i]) - ((A[3 * i] * e[0] + A[3 * i + 1] * e[1]) + A[3 * i + 2] * e[2]);
        const vreal gp = vmax(g, zero);
        sx = sx + gp * gp;
        gmax = vmax(gmax, g);
    }
    vreal n[3], cn[3];
    for (int i = 0; i < 3; ++i)
        n[i] = d[i] - vmin(vmax(d[i], -ex[i]), ex[i]);
    for (int k = 0; k < 3; ++k)
        cn[k] = (C[k] * n[0] + C[3 + k] * n[1]) + C[6 + k] * n[2];
    const vreal nn = (n[0] * n[0] + n[1] * n[1]) + n[2] * n[2];
    *gn_out = vmax(nn - ((e[0] * vabs(cn[0]) + e[1] * vabs(cn[1])) + e[2] * vabs(cn[2])), zero);
    *nn_out = nn;
    *sx_out = sx;
    *gmax_out = gmax;
}

#define NODE_SETUP                                                                             \
    vreal m[9], v[3], ex[3];                                                                   \
    for (int i = 0; i < 9; ++i)                                                                \
        m[i] = vset1(x->m[i]);                                                                 \
    for (int i = 0; i < 3; ++i) {                                                              \
        v[i] = vset1(x->v[i]);                                                                 \
        ex[i] = vset1(x->e[i]);                                                                \
    }

static TTD_DEVICE void node_test(const ttd_box_query *x, const ttd_node *y, real lb2[TTD_NODE_WIDTH], real sep[TTD_NODE_WIDTH])
{
    NODE_SETUP
    /* A float row with more lanes than a node has children reads past each coordinate's array
     * into the next (within the node; the lanes are ignored) and stores through a buffer. */
    for (int j0 = 0; j0 < TTD_NODE_WIDTH; j0 += TTDW_LANES) {
        vreal sx, gmax, gn, nn;
        node_lanes(m, v, ex, y, j0, &sx, &gmax, &gn, &nn);
        const vreal sn = gn * (gn / vmax(nn, vset1(TTD_REAL_MIN))); /* gn <= nn: no fourth power */
        node_store(lb2, j0, vmax(sx, sn));
        node_store(sep, j0, gmax);
    }
}

/* node_within (core/kernels.h): node_test, and the mask of the lanes whose bound is not past lim2,
 * compared in the vector registers (the walk's scalar reloads of lb2 waited on the test's last
 * stores). */
static TTD_DEVICE inline unsigned node_within(const ttd_box_query *x, const ttd_node *y, real lim2,
                                              real lb2[TTD_NODE_WIDTH], real sep[TTD_NODE_WIDTH])
{
    NODE_SETUP
    const vreal L = vset1(lim2);
    unsigned bits = 0;
    for (int j0 = 0; j0 < TTD_NODE_WIDTH; j0 += TTDW_LANES) {
        vreal sx, gmax, gn, nn;
        node_lanes(m, v, ex, y, j0, &sx, &gmax, &gn, &nn);
        const vreal sn = gn * (gn / vmax(nn, vset1(TTD_REAL_MIN))); /* gn <= nn: no fourth power */
        const vreal lb = vmax(sx, sn);
        node_store(lb2, j0, lb);
        node_store(sep, j0, gmax);
        bits |= mbits(mnot(vgt(lb, L))) << j0;
    }
    return bits & ((1u << TTD_NODE_WIDTH) - 1u);
}
#undef NODE_SETUP
