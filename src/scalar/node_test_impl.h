/* SPDX-License-Identifier: MIT */
/* The mesh queries' node test (core/kernels.h), one child at a time: the reference for the lane
 * kernel simd/kernel_node.h, which performs these operations in this order (see there for what
 * they bound). node_test_d.c and node_test_f.c compile it once each. */

static real node_max(real a, real b)
{
    return a > b ? a : b;
}

static real node_min(real a, real b)
{
    return a < b ? a : b;
}

static void node_test(const ttd_box_query *x, const ttd_node *y, real lb2[TTD_NODE_WIDTH], real sep[TTD_NODE_WIDTH])
{
    const real *m = x->m, *v = x->v, *ex = x->e;
    for (int j = 0; j < TTD_NODE_WIDTH; ++j) {
        real c[3], w[9], e[3], d[3], C[9], A[9];
        for (int i = 0; i < 3; ++i) {
            c[i] = y->c[i][j];
            e[i] = y->e[i][j];
        }
        for (int i = 0; i < 9; ++i)
            w[i] = y->u[i][j];
        for (int i = 0; i < 3; ++i)
            d[i] = ((m[3 * i] * c[0] + m[3 * i + 1] * c[1]) + m[3 * i + 2] * c[2]) + v[i];
        for (int i = 0; i < 3; ++i)
            for (int k = 0; k < 3; ++k) {
                C[3 * i + k] = (m[3 * i] * w[3 * k] + m[3 * i + 1] * w[3 * k + 1]) + m[3 * i + 2] * w[3 * k + 2];
                A[3 * i + k] = TTD_FABS(C[3 * i + k]);
            }
        real sx = 0, gmax = -TTD_REAL_MAX;
        for (int i = 0; i < 3; ++i) {
            const real g = (TTD_FABS(d[i]) - ex[i]) - ((A[3 * i] * e[0] + A[3 * i + 1] * e[1]) + A[3 * i + 2] * e[2]);
            const real gp = node_max(g, 0);
            sx = sx + gp * gp;
            gmax = node_max(gmax, g);
        }
        real n[3], cn[3];
        for (int i = 0; i < 3; ++i)
            n[i] = d[i] - node_min(node_max(d[i], -ex[i]), ex[i]);
        for (int k = 0; k < 3; ++k)
            cn[k] = (C[k] * n[0] + C[3 + k] * n[1]) + C[6 + k] * n[2];
        const real nn = (n[0] * n[0] + n[1] * n[1]) + n[2] * n[2];
        const real gn = node_max(nn - ((e[0] * TTD_FABS(cn[0]) + e[1] * TTD_FABS(cn[1])) + e[2] * TTD_FABS(cn[2])), 0);
        const real sn = gn * (gn / node_max(nn, TTD_REAL_MIN)); /* gn <= nn: no fourth power */
        lb2[j] = node_max(sx, sn);
        sep[j] = gmax;
    }
}

/* node_within (core/kernels.h): node_test, and the mask of the lanes whose bound is not past lim2. */
static unsigned node_within(const ttd_box_query *x, const ttd_node *y, real lim2, real lb2[TTD_NODE_WIDTH],
                            real sep[TTD_NODE_WIDTH])
{
    node_test(x, y, lb2, sep);
    unsigned bits = 0;
    for (int j = 0; j < TTD_NODE_WIDTH; ++j)
        bits |= (unsigned)!(lb2[j] > lim2) << j;
    return bits;
}
