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

/* Field i of a prepared triangle: one triangle per lane (a block, lanes from f on) or one triangle
 * in every lane (bcast: f is one triangle, stride 1). */
TTDW_FN vreal pk_f(const real *f, int i, int bcast)
{
    return bcast ? vset1(f[i]) : vloadu(&f[(size_t)i * TTD_PT_LANES]);
}

/* The per-point part of point_select (scalar/point_impl.h), the same operations in the same order:
 * the distance from the points (px, py, pz) to the triangles f, lane by lane, and the candidate
 * that gives it (id, u, v). */
TTDW_FN void pk_select(const real *f, int bcast, vreal px, vreal py, vreal pz, vreal *dist_out, vreal *id_out,
                       vreal *pu_out, vreal *pv_out)
{
#ifdef TTD_PRECISION_DOUBLE
    const real far_limit = TTD_PT_FAR_D;
#else
    const real far_limit = TTD_PT_FAR_F;
#endif
#define PK(i) pk_f(f, (i), bcast)
    const vreal zero = vzero(), one = vset1((real)1);
    const vreal P[3] = {px, py, pz};
    const vmask live = bcast || TTDW_LANES <= TTD_NODE_WIDTH ? mtrue() : mfirst(TTD_NODE_WIDTH);
    const vreal s = PK(TTD_PT_S);
    vreal r0[3], far = zero;
    for (int c = 0; c < 3; ++c) {
        r0[c] = (P[c] - PK(TTD_PT_V0 + c)) * s;
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
        const vreal dv = kw_norm3(P[0] - PK(TTD_PT_V0), P[1] - PK(TTD_PT_V0 + 1), P[2] - PK(TTD_PT_V0 + 2));
        dist = vsel(vertex, dv, dist);
        id = vsel(vertex, vset1((real)4), id);
        pu = vsel(vertex, zero, pu);
        pv = vsel(vertex, zero, pv);
    }
#undef PK
    *dist_out = dist;
    *id_out = id;
    *pu_out = pu;
    *pv_out = pv;
}

static TTD_DEVICE void point_block(const real P[3], const real *blk, real d[TTD_NODE_WIDTH], real par[3][TTD_NODE_WIDTH])
{
    for (int j0 = 0; j0 < TTD_NODE_WIDTH; j0 += TTDW_LANES) {
        vreal dist, id, pu, pv;
        pk_select(blk + j0, 0, vset1(P[0]), vset1(P[1]), vset1(P[2]), &dist, &id, &pu, &pv);
        pk_store(d, j0, dist);
        pk_store(par[0], j0, id);
        pk_store(par[1], j0, pu);
        pk_store(par[2], j0, pv);
    }
}

/* point_rebuild (scalar/point_impl.h) in the lanes, for one prepared triangle f (stride 1) and
 * each lane's candidate (id, u, v): the same operations on the selected values, so the same bits. */
TTDW_FN void pk_rebuild(const real *f, vreal id, vreal u, vreal v, vreal q[3], vreal w[3])
{
    const vreal zero = vzero(), one = vset1((real)1);
    const vmask e0 = veq(id, zero), e1 = veq(id, one), e2 = veq(id, vset1((real)2)), face = veq(id, vset1((real)3));
    const vmask vtx = veq(id, vset1((real)4));
    const int k = (int)f[TTD_PT_K];
    const vreal kv = vset1(f[TTD_PT_K]);
    vreal vj[3][3], x[3];
    for (int c = 0; c < 3; ++c) { /* vertex j in the frame: v_0 = 0, v_1 = e_0, v_2 = -e_2 */
        vj[0][c] = zero;
        vj[1][c] = vset1(f[TTD_PT_E + c]);
        vj[2][c] = vset1(-f[TTD_PT_E + 6 + c]);
    }
    for (int c = 0; c < 3; ++c) {
        /* an edge: vj[id] + u e[id]; the face: vj[k] + u L + v (-e[k + 2]) */
        const vreal base = vsel(e0, vj[0][c], vsel(e1, vj[1][c], vj[2][c]));
        const vreal dir = vsel(e0, vset1(f[TTD_PT_E + c]), vsel(e1, vset1(f[TTD_PT_E + 3 + c]), vset1(f[TTD_PT_E + 6 + c])));
        const vreal xe = base + u * dir;
        const vreal xf = vj[k][c] + u * vset1(f[TTD_PT_L + c]) + v * vset1(-f[TTD_PT_E + 3 * ((k + 2) % 3) + c]);
        x[c] = vsel(face, xf, xe);
    }
    for (int j = 0; j < 3; ++j) {
        const vreal jv = vset1((real)j), jp = vset1((real)((j + 2) % 3)), jn = vset1((real)((j + 1) % 3));
        /* an edge id: w[id] = 1 - u, w[id + 1] = u, w[id + 2] = 0 */
        const vreal we = vsel(veq(id, jv), one - u, vsel(veq(id, jp), u, zero));
        /* the face: w[k] = 1 - u - v, w[k + 1] = u, w[k + 2] = v */
        const vreal wf = vsel(veq(kv, jv), one - u - v, vsel(veq(kv, jp), u, vsel(veq(kv, jn), v, zero)));
        w[j] = vsel(vtx, j == 0 ? one : zero, vsel(face, wf, we));
    }
    const vreal big = vset1(TTD_REAL_MAX), g = vset1(f[TTD_PT_G]);
    for (int c = 0; c < 3; ++c) {
        const vreal v0 = vset1(f[TTD_PT_V0 + c]);
        const vreal y = vmin(vmax(x[c] * g + v0, zero - big), big);
        q[c] = vsel(vtx, v0, y);
    }
    (void)e2;
}

/* One prepared triangle f (stride 1) against 8 points, one per lane (P[c][i]: coordinate c of point
 * i), with each lane's closest point and weights: the points per lane the meshes of a few triangles
 * are measured with. */
static TTD_DEVICE void point_lanes(const real *f, const real P[3][TTD_NODE_WIDTH], real d[TTD_NODE_WIDTH],
                                   real q[3][TTD_NODE_WIDTH], real w[3][TTD_NODE_WIDTH])
{
    for (int j0 = 0; j0 < TTD_NODE_WIDTH; j0 += TTDW_LANES) {
        vreal dist, id, pu, pv, pc[3], qv[3], wv[3];
        for (int c = 0; c < 3; ++c) {
            if (TTDW_LANES <= TTD_NODE_WIDTH - j0) {
                pc[c] = vloadu(&P[c][j0]);
            } else { /* a float row with 16 lanes: 8 points and copies of the first */
                real buf[TTDW_LANES];
                for (int i = 0; i < TTDW_LANES; ++i)
                    buf[i] = P[c][j0 + i < TTD_NODE_WIDTH ? j0 + i : 0];
                pc[c] = vloadu(buf);
            }
        }
        pk_select(f, 1, pc[0], pc[1], pc[2], &dist, &id, &pu, &pv);
        pk_rebuild(f, id, pu, pv, qv, wv);
        pk_store(d, j0, dist);
        for (int c = 0; c < 3; ++c) {
            pk_store(q[c], j0, qv[c]);
            pk_store(w[c], j0, wv[c]);
        }
    }
}
