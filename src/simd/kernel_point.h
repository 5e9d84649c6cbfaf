/* SPDX-License-Identifier: MIT */
/* The point queries' lane kernels (core/kernels.h, src/points/, docs/points.md). Read them next
 * to the scalar code, scalar/point_impl.h: the same operations in the same order (no FMA), so
 * every row returns the scalar row's bits and a query finds the same triangle on every
 * instruction set.
 *
 *  - point_node (float rows): one child box per lane, the distance from a point to each of a
 *    walk node's float boxes (core/point_layout.h). The point is taken into each box's frame
 *    (z = U (p - c)) and the box is [-e, e] there: the squared lower bound is the sum of the
 *    squared positive parts of |z_a| - e_a. The double walk uses the float row's too.
 *  - pk_block: one triangle per lane, the distance from a point to each triangle of a prepared
 *    block (core/point_layout.h): the per-point part of point_eval, everything that depends on
 *    the triangle alone having been computed once when the block was prepared.
 *
 * A float row with more lanes than a node has children (AVX-512: 16) reads past each array into
 * the next (within the node: e[2] into child[]; or into the block's spare row) and ignores those
 * lanes. */

/* Stores lanes 0 .. TTD_NODE_WIDTH - j0 - 1 of v to out[j0 ..]. */
TTDW_FN void pk_store(real *out, int j0, vreal v)
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

#ifndef TTD_PRECISION_DOUBLE
static TTD_DEVICE unsigned point_node(const float p[3], const ttd_pnode *y, float lim2, float lb2[TTD_NODE_WIDTH])
{
    const vreal zero = vzero(), vlim2 = vset1(lim2);
    unsigned within = 0;
    const vreal px = vset1(p[0]), py = vset1(p[1]), pz = vset1(p[2]);
    for (int j0 = 0; j0 < TTD_NODE_WIDTH; j0 += TTDW_LANES) {
        const vreal dx = px - vloadu(&y->c[0][j0]), dy = py - vloadu(&y->c[1][j0]), dz = pz - vloadu(&y->c[2][j0]);
        vreal s = zero, sep = zero;
        for (int a = 0; a < 3; ++a) {
            const vreal z = (vloadu(&y->u[3 * a][j0]) * dx + vloadu(&y->u[3 * a + 1][j0]) * dy) +
                            vloadu(&y->u[3 * a + 2][j0]) * dz;
            const vreal gap = vabs(z) - vloadu(&y->e[a][j0]), g = vmax(gap, zero);
            s = a == 0 ? g * g : s + g * g;
            sep = a == 0 ? gap : vmax(sep, gap);
        }
        pk_store(lb2, j0, vsel(vgt(s, zero), s, sep));
        within |= mbits(vle(s, vlim2)) << j0;
    }
    return within & ((1u << TTD_NODE_WIDTH) - 1);
}

static TTD_DEVICE unsigned ray_node(const float lo[3], const float hi[3], int k, int sigma, const ttd_rnode *y)
{
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const vreal li = vset1(lo[i]), hi_ = vset1(hi[i]), lj = vset1(lo[j]), hj = vset1(hi[j]);
    const vreal along = vset1(sigma > 0 ? lo[k] : hi[k]);
    unsigned hit = 0;
    for (int j0 = 0; j0 < TTD_NODE_WIDTH; j0 += TTDW_LANES) {
        const vmask across = mand(mand(vle(vloadu(&y->lo[i][j0]), hi_), vge(vloadu(&y->hi[i][j0]), li)),
                                  mand(vle(vloadu(&y->lo[j][j0]), hj), vge(vloadu(&y->hi[j][j0]), lj)));
        const vmask ahead = sigma > 0 ? vge(vloadu(&y->hi[k][j0]), along) : vle(vloadu(&y->lo[k][j0]), along);
        hit |= mbits(mand(across, ahead)) << j0;
    }
    return hit & ((1u << TTD_NODE_WIDTH) - 1);
}
#endif

TTDW_FN vreal pk_dot(vreal ax, vreal ay, vreal az, vreal bx, vreal by, vreal bz)
{
    return ax * bx + ay * by + az * bz;
}

static TTD_DEVICE void point_block(const real P[3], const real *blk, real d[TTD_NODE_WIDTH], real par[3][TTD_NODE_WIDTH])
{
#ifdef TTD_PRECISION_DOUBLE
    const real far_limit = TTD_PT_FAR_D;
#else
    const real far_limit = TTD_PT_FAR_F;
#endif
    const vreal zero = vzero(), one = vset1((real)1);
    for (int j0 = 0; j0 < TTD_NODE_WIDTH; j0 += TTDW_LANES) {
#define PK(i) vloadu(&blk[(size_t)(i) * TTD_PT_LANES + (size_t)j0])
        const vmask live = TTDW_LANES > TTD_NODE_WIDTH ? mfirst(TTD_NODE_WIDTH) : mtrue();
        const vreal s = PK(TTD_PT_S);
        vreal r0[3], far = zero;
        for (int c = 0; c < 3; ++c) {
            r0[c] = (vset1(P[c]) - PK(TTD_PT_V0 + c)) * s;
            far = vmax(far, vabs(r0[c]));
        }
        const vmask vertex = mand(live, mor(mnot(vgt(s, zero)), vgt(far, vset1(far_limit))));
        vreal w[3][3];
        for (int c = 0; c < 3; ++c) {
            w[0][c] = r0[c];
            w[1][c] = r0[c] - PK(TTD_PT_E + c);
            w[2][c] = r0[c] + PK(TTD_PT_E + 6 + c);
        }
        vreal best = vset1(TTD_REAL_MAX), id = zero, pu = zero, pv = zero;
        for (int j = 0; j < 3; ++j) {
            const vreal ex = PK(TTD_PT_E + 3 * j), ey = PK(TTD_PT_E + 3 * j + 1), ez = PK(TTD_PT_E + 3 * j + 2);
            const vreal t = kx_clamp01(pk_dot(w[j][0], w[j][1], w[j][2], ex, ey, ez) * PK(TTD_PT_IEE + j));
            const vreal qx = w[j][0] - t * ex, qy = w[j][1] - t * ey, qz = w[j][2] - t * ez;
            const vreal d2 = pk_dot(qx, qy, qz, qx, qy, qz);
            const vmask better = vlt(d2, best);
            best = vsel(better, d2, best);
            id = vsel(better, vset1((real)j), id);
            pu = vsel(better, t, pu);
        }
        const vreal k = PK(TTD_PT_K);
        const vmask k0 = veq(k, zero), k1 = veq(k, one);
        vreal wk[3];
        for (int c = 0; c < 3; ++c)
            wk[c] = vsel(k0, w[0][c], vsel(k1, w[1][c], w[2][c]));
        const vreal cc = pk_dot(wk[0], wk[1], wk[2], PK(TTD_PT_U), PK(TTD_PT_U + 1), PK(TTD_PT_U + 2));
        const vreal g = pk_dot(wk[0], wk[1], wk[2], PK(TTD_PT_L), PK(TTD_PT_L + 1), PK(TTD_PT_L + 2));
        const vreal h = pk_dot(PK(TTD_PT_N), PK(TTD_PT_N + 1), PK(TTD_PT_N + 2), wk[0], wk[1], wk[2]);
        const vreal b = (g - cc * PK(TTD_PT_ML)) * PK(TTD_PT_IEEK);
        const vreal a = one - b - cc;
        const vreal inn = PK(TTD_PT_INN);
        const vmask inside = mand(mand(vgt(inn, zero), vge(a, zero)), mand(vge(b, zero), vge(cc, zero)));
        const vreal d2f = (h * inn) * h;
        const vmask face = mand(inside, vlt(d2f, best));
        best = vsel(face, d2f, best);
        id = vsel(face, vset1((real)3), id);
        pu = vsel(face, b, pu);
        pv = vsel(face, cc, zero);
        vreal dist = vsqrt(best) * PK(TTD_PT_G);
        if (many(vertex)) { /* a point triangle, or a point far beyond a triangle's size: rare */
            const vreal dv = kw_norm3(vset1(P[0]) - PK(TTD_PT_V0), vset1(P[1]) - PK(TTD_PT_V0 + 1),
                                      vset1(P[2]) - PK(TTD_PT_V0 + 2));
            dist = vsel(vertex, dv, dist);
            id = vsel(vertex, vset1((real)4), id);
            pu = vsel(vertex, zero, pu);
            pv = vsel(vertex, zero, pv);
        }
        pk_store(d, j0, dist);
        pk_store(par[0], j0, id);
        pk_store(par[1], j0, pu);
        pk_store(par[2], j0, pv);
#undef PK
    }
}
