/* SPDX-License-Identifier: MIT */
/* The paper's reference penalty method (MATLAB ttd1, Algorithm 1), one pair per lane. It is
 * scalar/penalty_impl.h's penalty_ref_pair step for step, with the same operations in
 * the same order, so that each lane rounds exactly as the scalar code does: read the two
 * side by side. Comments "ttd1 n" point to the paper's line numbers, "scalar:" to the
 * scalar function.
 *
 * The SPMD shape: the Newton loop runs while any lane is active. A lane leaves when its step
 * on the geometry is below tol (converged: its x is not updated, as in the scalar `break`),
 * when the step stops being finite (the scalar's second `break`), or at max_iterations.
 * Inactive lanes keep computing (their results are discarded by select), so a lane's
 * outputs depend only on its own pair. The scalar code's data-dependent branches (pivot
 * choice and row swaps in the 4x4 solve, the pivot floor) become compares and selects. */

/* scalar: the ternary h[j] > 0 ? h[j] : 0 in penalty_ref_pair's gradient sum (ttd1 12),
 * max(0, v) as a compare and a select. */
static inline vreal kpr_pos(vreal v)
{
    const vreal zero = vzero();
    return vsel(vgt(v, zero), v, zero);
}

/* scalar: pen_pos, (v + |v|) / 2, as pen_clamp_bary3 uses it. */
static inline vreal kpr_pos2(vreal v)
{
    return (v + vabs(v)) * vset1((real)0.5);
}

/* scalar: pen_clamp_bary3. Negative weights of (c, a, b) become 0 and the three are
 * renormalised to sum 1 (a zero sum gives vertex 0). */
static inline void kpr_clamp_bary3(vreal c, vreal a, vreal b, vreal w[3])
{
    const vreal zero = vzero(), one = vset1((real)1);
    const vreal w0 = kpr_pos2(c), w1 = kpr_pos2(a), w2 = kpr_pos2(b);
    const vreal sum = w0 + w1 + w2;
    const vmask pos = vgt(sum, zero);
    const vreal inv = one / vsel(pos, sum, one);
    w[0] = vsel(pos, w0 * inv, one);
    w[1] = w1 * inv;
    w[2] = w2 * inv;
}

/* scalar: pen_clamp_bary(a, b) = pen_clamp_bary3(1 - a - b, a, b), a and b bounded at
 * +-REAL_MAX/8 first (an iterate that overflowed to +-inf gives finite weights) */
static inline void kpr_clamp_bary(vreal a, vreal b, vreal w[3])
{
    const vreal big = vset1(TTD_REAL_MAX / 8), mbig = vset1(-(TTD_REAL_MAX / 8));
    a = vmin(vmax(a, mbig), big);
    b = vmin(vmax(b, mbig), big);
    kpr_clamp_bary3(vset1((real)1) - a - b, a, b, w);
}

/* scalar: pen_ref_solve. hes \ gra by Gaussian elimination with partial pivoting, the row
 * swaps done by select in every lane. m and rhs are overwritten. */
static inline void kpr_solve(vreal m[4][4], vreal rhs[4], vreal x[4])
{
    const vreal zero = vzero();
    vreal dmax = zero;
    for (int i = 0; i < 4; ++i) {
        const vreal a = vabs(m[i][i]);
        dmax = vsel(vgt(a, dmax), a, dmax);
    }
    vreal floor_ = dmax * vset1(TTD_REAL_EPS);
    floor_ = vsel(vgt(floor_, zero), floor_, vset1(TTD_REAL_MIN)); /* if !(floor_ > 0) */
    for (int c = 0; c < 4; ++c) {
        /* piv = the last row i >= c whose |m[i][c]| beats every row before it */
        vmask is[4];
        vreal best = vabs(m[c][c]);
        for (int i = c + 1; i < 4; ++i) {
            const vreal a = vabs(m[i][c]);
            is[i] = vgt(a, best);
            best = vsel(is[i], a, best);
            for (int j = c + 1; j < i; ++j)
                is[j] = mandnot(is[j], is[i]); /* a later winner replaces an earlier one */
        }
        /* swap rows c and piv (columns c.. and rhs; the columns left of c are never read) */
        for (int i = c + 1; i < 4; ++i) {
            for (int j = c; j < 4; ++j) {
                const vreal mc = m[c][j];
                m[c][j] = vsel(is[i], m[i][j], mc);
                m[i][j] = vsel(is[i], mc, m[i][j]);
            }
            const vreal rc = rhs[c];
            rhs[c] = vsel(is[i], rhs[i], rc);
            rhs[i] = vsel(is[i], rc, rhs[i]);
        }
        /* if (|m[c][c]| < floor_) m[c][c] = m[c][c] < 0 ? -floor_ : floor_ */
        const vmask low = vlt(vabs(m[c][c]), floor_);
        m[c][c] = vsel(low, vsel(vlt(m[c][c], zero), zero - floor_, floor_), m[c][c]);
        for (int i = c + 1; i < 4; ++i) {
            const vreal l = m[i][c] / m[c][c];
            for (int j = c; j < 4; ++j)
                m[i][j] = m[i][j] - l * m[c][j];
            rhs[i] = rhs[i] - l * rhs[c];
        }
    }
    for (int i = 3; i >= 0; --i) {
        vreal acc = rhs[i];
        for (int j = i + 1; j < 4; ++j)
            acc = acc - m[i][j] * x[j];
        x[i] = acc / m[i][i];
    }
}

/* One group of W pairs (S, T transposed: S[k] lane i = s[9i + k]). active: the live lanes. */
static inline void kpr_group(const vreal S[9], const vreal T[9], const ttd_params *prm,
                                      vmask active, kw_out *o)
{
#ifdef TTD_PRECISION_DOUBLE
    const vreal rho = vset1(prm->rho), tol = vset1(prm->tol);
#else
    /* scalar: rho capped so that rho^2 stays finite in float (core/defaults.h) */
    const vreal rho = vset1((real)fmin(prm->rho, TTD_FLOAT_REF_RHO_MAX)), tol = vset1((real)prm->tol);
#endif
    const vreal zero = vzero(), one = vset1((real)1), two = vset1((real)2), mtwo = vset1((real)-2);
    /* ttd1 1: BA = B-A; CA = C-A; ED = E-D; FD = F-D */
    vreal BA[3], CA[3], ED[3], FD[3];
    for (int k = 0; k < 3; ++k) {
        BA[k] = S[3 + k] - S[k];
        CA[k] = S[6 + k] - S[k];
        ED[k] = T[3 + k] - T[k];
        FD[k] = T[6 + k] - T[k];
    }
    /* ttd1 2-5: hf(i,j) = 2 sgn_i sgn_j u_i . u_j, u = (BA, CA, ED, FD), sgn = (1, 1, -1, -1);
     * 2 sgn_i sgn_j is +-2 exactly, as in the scalar code. */
    const vreal *u[4] = {BA, CA, ED, FD};
    vreal hf[4][4];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            const vreal c2 = ((i < 2) == (j < 2)) ? two : mtwo;
            /* + 0: the scalar code adds rho*0 + 0 to every entry, which turns -0 into +0 */
            hf[i][j] = c2 * (u[i][0] * u[j][0] + u[i][1] * u[j][1] + u[i][2] * u[j][2]) + zero;
        }
    /* ttd1 6: x = [0.33; 0.33; 0.33; 0.33] */
    vreal x[4];
    for (int i = 0; i < 4; ++i)
        x[i] = vset1((real)0.33);
    const vreal eps = one / (rho * rho); /* the I/rho^2 of ttd1 17 */
    vreal used = zero;
    vmask converged = mnot(mtrue());
    for (int it = 1; it <= prm->max_iterations && many(active); ++it) {
        used = vsel(active, vset1((real)it), used);
        /* ttd1 4-5: X = A + BA x1 + CA x2; Y = D + ED x3 + FD x4 */
        vreal XY[3];
        for (int k = 0; k < 3; ++k) {
            const vreal X = S[k] + BA[k] * x[0] + CA[k] * x[1];
            const vreal Y = T[k] + ED[k] * x[2] + FD[k] * x[3];
            XY[k] = X - Y;
        }
        /* ttd1 6: gf = 2 sgn_i (X-Y) . u_i */
        vreal gf[4];
        for (int i = 0; i < 4; ++i)
            gf[i] = (i < 2 ? two : mtwo) * (XY[0] * u[i][0] + XY[1] * u[i][1] + XY[2] * u[i][2]);
        /* ttd1 7: h = [-x1; -x2; x1+x2-1; -x3; -x4; x3+x4-1] */
        const vreal h[6] = {-x[0], -x[1], x[0] + x[1] - one, -x[2], -x[3], x[2] + x[3] - one};
        /* ttd1 10-11: mask = h' >= 0, dmax = dh .* mask; the non-zeros of dh are
         * dh(1,1) = dh(2,2) = dh(3,4) = dh(4,5) = -1 and dh(1,3) = dh(2,3) = dh(3,6) = dh(4,6) = 1 */
        vmask mk[6];
        vreal hp[6];
        for (int j = 0; j < 6; ++j) {
            mk[j] = vge(h[j], zero);
            hp[j] = kpr_pos(h[j]);
        }
        /* ttd1 12: gra = gf + rho * dmax * max(0, h). The scalar sum over j adds exact zeros
         * for the absent terms; what remains is (-hp_a) + hp_b in this order. */
        const vreal m1p = vsel(mk[0], -hp[0], zero), m2p = vsel(mk[1], -hp[1], zero);
        const vreal p3 = vsel(mk[2], hp[2], zero);
        const vreal m4p = vsel(mk[3], -hp[3], zero), m5p = vsel(mk[4], -hp[4], zero);
        const vreal p6 = vsel(mk[5], hp[5], zero);
        vreal gra[4];
        gra[0] = gf[0] + rho * (m1p + p3);
        gra[1] = gf[1] + rho * (m2p + p3);
        gra[2] = gf[2] + rho * (m4p + p6);
        gra[3] = gf[3] + rho * (m5p + p6);
        /* ttd1 17: hes = hf + rho dmax dmax' + I/rho^2. dmax dmax' counts active
         * constraints: (1,1): m1+m3, (2,2): m2+m3, (1,2): m3, (3,3): m4+m6, (4,4): m5+m6,
         * (3,4): m6, zero elsewhere (the scalar adds rho*0 and 0 there: exact no-ops). */
        const vreal c1 = vsel(mk[0], one, zero), c2 = vsel(mk[1], one, zero), c3 = vsel(mk[2], one, zero);
        const vreal c4 = vsel(mk[3], one, zero), c5 = vsel(mk[4], one, zero), c6 = vsel(mk[5], one, zero);
        vreal hes[4][4];
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                hes[i][j] = hf[i][j];
        hes[0][0] = hf[0][0] + rho * (c1 + c3) + eps;
        hes[1][1] = hf[1][1] + rho * (c2 + c3) + eps;
        hes[2][2] = hf[2][2] + rho * (c4 + c6) + eps;
        hes[3][3] = hf[3][3] + rho * (c5 + c6) + eps;
        hes[0][1] = hf[0][1] + rho * c3;
        hes[1][0] = hf[1][0] + rho * c3;
        hes[2][3] = hf[2][3] + rho * c6;
        hes[3][2] = hf[3][2] + rho * c6;
        /* ttd1 18: dx = hes \ gra */
        vreal dx[4];
        kpr_solve(hes, gra, dx);
        /* ttd1 19-21: error = |(DX, DY)| on the geometry */
        vreal e2 = zero;
        for (int k = 0; k < 3; ++k) {
            const vreal DX = BA[k] * dx[0] + CA[k] * dx[1];
            const vreal DY = ED[k] * dx[2] + FD[k] * dx[3];
            e2 = e2 + (DX * DX + DY * DY);
        }
        const vreal err = vsqrt(e2);
        /* ttd1 22: if error < tol, break (this lane: converged, x not updated) */
        const vmask done = mand(active, vlt(err, tol));
        converged = mor(converged, done);
        active = mandnot(active, done);
        /* scalar: a step that is not finite stops the lane, keeping the last finite x */
        const vreal sdx = vabs(dx[0]) + vabs(dx[1]) + vabs(dx[2]) + vabs(dx[3]);
        active = mand(active, vle(sdx, vset1(TTD_REAL_MAX)));
        /* ttd1 23: x = x - dx */
        for (int i = 0; i < 4; ++i)
            x[i] = vsel(active, x[i] - dx[i], x[i]);
    }
    /* scalar: clamp onto the triangles, p and q as convex combinations, distance |p - q| */
    vreal wp[3], wq[3];
    kpr_clamp_bary(x[0], x[1], wp);
    kpr_clamp_bary(x[2], x[3], wq);
    vreal xy[3];
    const vreal big = vset1(TTD_REAL_MAX), mbig = vset1(-TTD_REAL_MAX); /* scalar: pen_clamp_max */
    for (int k = 0; k < 3; ++k) {
        o->p[k] = wp[0] * S[k] + wp[1] * S[3 + k] + wp[2] * S[6 + k];
        o->q[k] = wq[0] * T[k] + wq[1] * T[3 + k] + wq[2] * T[6 + k];
        xy[k] = o->p[k] - o->q[k];
        o->p[k] = vmin(vmax(o->p[k], mbig), big);
        o->q[k] = vmin(vmax(o->q[k], mbig), big);
        o->bary_p[k] = wp[k];
        o->bary_q[k] = wq[k];
    }
    o->distance = kw_norm3(xy[0], xy[1], xy[2]);
    o->iterations = used;
    o->flags_nc = ~mbits(converged);
    o->flags_int = 0;
    o->flags_ds = 0;
    o->flags_dt = 0;
}

static void kernel_penalty_ref(size_t n, const real *s, const real *t, const ttd_params *prm, real bound,
                               const ttd_out *out)
{
    (void)bound;
    for (size_t i0 = 0; i0 < n; i0 += TTDW_LANES) {
        const int live = n - i0 < (size_t)TTDW_LANES ? (int)(n - i0) : TTDW_LANES;
        vreal S[9], T[9];
        kw_load_group(s + 9 * i0, t + 9 * i0, live, S, T);
        kw_out o;
        kpr_group(S, T, prm, mfirst(live), &o);
        kw_store_group(&o, live, out, i0);
    }
}
