/* SPDX-License-Identifier: MIT */
/* The optimised penalty method, one pair per lane: scalar/penalty_impl.h's penalty_pair
 * step for step (same operations, same order, so each lane rounds as the scalar code does).
 * Read the two side by side; the scalar code was written to be ported this way (one loop,
 * selects instead of branches). The scalar function is cut in three here: kp_frame (the
 * frame and hf, before the loop), kp_step (one pass of the loop body) and kp_finish (after
 * the loop).
 *
 * SPMD shape. A lane's iterate is frozen by select once it has converged (after its update,
 * as in the scalar `break`) or reached max_iterations. The line-search bracket, which the
 * scalar code runs only when phi'(1) > 0, runs here when any active lane has phi'(1) > 0, and
 * likewise the search beyond t = 1; their results are selected per lane.
 *
 * Groups of W consecutive pairs iterate together, so a group runs as long as its slowest
 * pair: lane occupancy 0.75 at 8 lanes and 0.70 at 16 on random pairs (docs/simd.md). A
 * version where finished lanes take the next pair of the block (commit 67cfaf5) raised
 * occupancy to 0.78 at 16 lanes but ran 20-25% slower per pair, measured: not kept. */

/* scalar: pen_pos. max(0, v) as (v + |v|) / 2 */
static inline vreal kp_pos(vreal v)
{
    return (v + vabs(v)) * vset1((real)0.5);
}

/* scalar: pen_clamp_bary3. Negative weights of (c, a, b) become 0, renormalised to sum 1. */
static inline void kp_clamp_bary3(vreal c, vreal a, vreal b, vreal w[3])
{
    const vreal zero = vzero(), one = vset1((real)1);
    const vreal w0 = kp_pos(c), w1 = kp_pos(a), w2 = kp_pos(b);
    const vreal sum = w0 + w1 + w2;
    const vmask pos = vgt(sum, zero);
    const vreal inv = one / vsel(pos, sum, one);
    w[0] = vsel(pos, w0 * inv, one);
    w[1] = w1 * inv;
    w[2] = w2 * inv;
}

/* Per-lane data that does not change during the iteration (scalar: before the loop). */
typedef struct kp_frame {
    vreal BA[3], CA[3], DA[3], ED[3], FD[3]; /* the pair in the frame: A at 0, unit size */
    vreal unscale;                           /* 2^(e-lift), then ... */
    vreal unpre;                             /* ... 1 / pre: back to the input's scale (2^e / pre can overflow) */
} kp_frame;

typedef struct kp_hf {
    vreal f00, f01, f02, f03, f11, f12, f13, f22, f23, f33;
} kp_hf;

/* The iterate (scalar: a, b, ca, g, d, cg, prev_err2). */
typedef struct kp_state {
    vreal a, b, ca, g, d, cg, prev_err2;
} kp_state;

typedef struct kp_consts {
    vreal rho, tol2, eps;
} kp_consts;

static inline kp_consts kp_consts_of(const ttd_params *prm)
{
    /* scalar: rho capped and tol floored in float (core/defaults.h) */
#ifdef TTD_PRECISION_DOUBLE
    const double rho_max = TTD_DOUBLE_RHO_MAX, tol_min = TTD_DOUBLE_TOL_MIN;
#else
    const double rho_max = TTD_FLOAT_RHO_MAX, tol_min = TTD_FLOAT_TOL_MIN;
#endif
    const double rho_d = prm->rho < rho_max ? prm->rho : rho_max;
    const double tol_d = prm->tol > tol_min ? prm->tol : tol_min;
    const real rho_s = (real)rho_d;
    /* scalar: eps, a few ulps of the unit frame (not 1/rho^2) */
    const real eps_s = (real)TTD_PENALTY_EPS_ULPS * TTD_REAL_EPS;
    kp_consts c;
    c.rho = vset1(rho_s);
    c.tol2 = vset1((real)(tol_d * tol_d));
    c.eps = vset1(eps_s);
    return c;
}

/* scalar: the frame. Origin at A, scaled by 2^-e (e from frexp of the largest relative
 * coordinate, at least emin); pre guards the differences near REAL_MAX. Why pre's threshold
 * and factor and the lift's constants are what they are: scalar/penalty_impl.h. */
static inline void kp_frame_of(const vreal S[9], const vreal T[9], kp_frame *F)
{
    const vreal zero = vzero(), one = vset1((real)1), two = vset1((real)2);
    vreal m0 = zero;
    for (int k = 0; k < 9; ++k)
        m0 = vmax(m0, vmax(vabs(S[k]), vabs(T[k])));
    const vreal pre = vsel(vgt(m0, vset1(TTD_REAL_MAX * (real)0.125)), vset1((real)0.0625), one);
    vreal size = zero;
    for (int k = 0; k < 3; ++k) {
        const vreal a = S[k] * pre;
        F->BA[k] = S[3 + k] * pre - a;
        F->CA[k] = S[6 + k] * pre - a;
        F->DA[k] = T[k] * pre - a;
        F->ED[k] = T[3 + k] * pre - T[k] * pre;
        F->FD[k] = T[6 + k] * pre - T[k] * pre;
        const vreal ea = T[3 + k] * pre - a, fa = T[6 + k] * pre - a;
        size = vmax(size, vmax(vmax(vabs(F->BA[k]), vabs(F->CA[k])), vmax(vabs(F->DA[k]), vmax(vabs(ea), vabs(fa)))));
    }
    /* e < emin is raised to emin: the same as raising size to 2^(emin-1). Since the lift a
     * nonzero size is at least 2^-474 (float 2^-89), so the floor acts only at size = 0, where
     * it keeps vpow2's argument normal and 0.5 / half finite (the scalar code keeps e = 0
     * there; every scaled difference is 0 either way and so is the distance). */
#ifdef TTD_PRECISION_DOUBLE
    const real size_floor = 0x1p-1020; /* 2^(DBL_MIN_EXP + 2 - 1) */
    const real tiny = 0x1p-900, lift_up = 0x1p600, lift_down = 0x1p-600;
#else
    const real size_floor = 0x1p-124f; /* 2^(FLT_MIN_EXP + 2 - 1) */
    const real tiny = 0x1p-100f, lift_up = 0x1p60f, lift_down = 0x1p-60f;
#endif
    /* scalar: a pair of subnormal size is lifted by an exact power of two first. */
    const vmask is_tiny = vlt(size, vset1(tiny));
    const vreal lift = vsel(is_tiny, vset1(lift_up), one);
    size = size * lift;
    const vreal half = vpow2(vmax(size, vset1(size_floor))); /* 2^(e-1) */
    const vreal scale = vset1((real)0.5) / half;              /* 2^-e */
    F->unscale = half * two * vsel(is_tiny, vset1(lift_down), one); /* 2^(e-lift) */
    F->unpre = one / pre;                                            /* 1 or 16, exact */
    for (int k = 0; k < 3; ++k) {
        F->BA[k] = F->BA[k] * lift * scale;
        F->CA[k] = F->CA[k] * lift * scale;
        F->DA[k] = F->DA[k] * lift * scale;
        F->ED[k] = F->ED[k] * lift * scale;
        F->FD[k] = F->FD[k] * lift * scale;
    }
}

/* scalar: hf, the Hessian of f, symmetric: hf(i,j) = 2 u_i . u_j, u = (BA, CA, -ED, -FD). */
static inline void kp_hf_of(const kp_frame *F, kp_hf *H)
{
    const vreal two = vset1((real)2), mtwo = vset1((real)-2);
    const vreal *BA = F->BA, *CA = F->CA, *ED = F->ED, *FD = F->FD;
    H->f00 = two * (BA[0] * BA[0] + BA[1] * BA[1] + BA[2] * BA[2]);
    H->f01 = two * (BA[0] * CA[0] + BA[1] * CA[1] + BA[2] * CA[2]);
    H->f02 = mtwo * (BA[0] * ED[0] + BA[1] * ED[1] + BA[2] * ED[2]);
    H->f03 = mtwo * (BA[0] * FD[0] + BA[1] * FD[1] + BA[2] * FD[2]);
    H->f11 = two * (CA[0] * CA[0] + CA[1] * CA[1] + CA[2] * CA[2]);
    H->f12 = mtwo * (CA[0] * ED[0] + CA[1] * ED[1] + CA[2] * ED[2]);
    H->f13 = mtwo * (CA[0] * FD[0] + CA[1] * FD[1] + CA[2] * FD[2]);
    H->f22 = two * (ED[0] * ED[0] + ED[1] * ED[1] + ED[2] * ED[2]);
    H->f23 = two * (ED[0] * FD[0] + ED[1] * FD[1] + ED[2] * FD[2]);
    H->f33 = two * (FD[0] * FD[0] + FD[1] * FD[1] + FD[2] * FD[2]);
}

/* scalar: the iterate's start, 1/3 each, and prev_err2 = REAL_MAX (in every lane). */
static inline void kp_init(kp_state *X)
{
    const vreal third = vset1((real)1 / 3);
    X->a = X->b = X->ca = X->g = X->d = X->cg = third;
    X->prev_err2 = vset1(TTD_REAL_MAX);
}

/* scalar: one pass of the loop body. Updates the active lanes' iterate; returns the active
 * lanes that converged. */
static inline vmask kp_step(const kp_consts *K, const kp_frame *F,
                                     const kp_hf *Hf, kp_state *X, vmask active)
{
    const vreal zero = vzero(), one = vset1((real)1), two = vset1((real)2), mtwo = vset1((real)-2);
    const vreal rho = K->rho, tol2 = K->tol2, eps = K->eps;
    const vreal *BA = F->BA, *CA = F->CA, *DA = F->DA, *ED = F->ED, *FD = F->FD;
    const vreal f00 = Hf->f00, f01 = Hf->f01, f02 = Hf->f02, f03 = Hf->f03, f11 = Hf->f11;
    const vreal f12 = Hf->f12, f13 = Hf->f13, f22 = Hf->f22, f23 = Hf->f23, f33 = Hf->f33;
    vreal a = X->a, b = X->b, ca = X->ca, g = X->g, d = X->d, cg = X->cg;
    /* XY = X - Y in the frame (A = 0). */
    const vreal xy0 = a * BA[0] + b * CA[0] - DA[0] - g * ED[0] - d * FD[0];
    const vreal xy1 = a * BA[1] + b * CA[1] - DA[1] - g * ED[1] - d * FD[1];
    const vreal xy2 = a * BA[2] + b * CA[2] - DA[2] - g * ED[2] - d * FD[2];

    /* Constraints, penalty terms v_i = max(0, h_i), m_i = rho where h_i >= 0. */
    const vreal h1 = -a, h2 = -b, h3 = -ca, h4 = -g, h5 = -d, h6 = -cg;
    const vreal v1 = kp_pos(h1), v2 = kp_pos(h2), v3 = kp_pos(h3);
    const vreal v4 = kp_pos(h4), v5 = kp_pos(h5), v6 = kp_pos(h6);
    const vmask a1 = vge(h1, zero), a2 = vge(h2, zero), a3 = vge(h3, zero);
    const vmask a4 = vge(h4, zero), a5 = vge(h5, zero), a6 = vge(h6, zero);
    const vreal m1 = vsel(a1, rho, zero), m2 = vsel(a2, rho, zero), m3 = vsel(a3, rho, zero);
    const vreal m4 = vsel(a4, rho, zero), m5 = vsel(a5, rho, zero), m6 = vsel(a6, rho, zero);

    /* Gradient and Hessian fused into a symmetric elimination without pivoting (SPD);
     * a pivot that rounding made <= eps is raised to eps. */
    const vreal gf0 = two * (BA[0] * xy0 + BA[1] * xy1 + BA[2] * xy2);
    vreal g0 = gf0 + rho * (v3 - v1);
    vreal H00 = f00 + m1 + m3 + eps;
    const vreal H01 = f01 + m3, H02 = f02, H03 = f03;
    H00 = vsel(vgt(H00, eps), H00, eps);
    const vreal i0 = one / H00;
    const vreal l10 = H01 * i0, l20 = H02 * i0, l30 = H03 * i0;

    const vreal gf1 = two * (CA[0] * xy0 + CA[1] * xy1 + CA[2] * xy2);
    vreal g1 = gf1 + rho * (v3 - v2);
    /* scalar: H11 as det/H00, the rho terms of det cancelled exactly */
    const vreal e00 = f00 + eps, e11 = f11 + eps;
    vreal H11 = ((e00 * e11 - f01 * f01) + m3 * (e00 + e11 - two * f01) + m1 * (e11 + m2 + m3) +
                 m2 * (e00 + m3)) * i0;
    const vreal H12 = f12 - l10 * H02, H13 = f13 - l10 * H03;
    g1 = g1 - l10 * g0;
    H11 = vsel(vgt(H11, eps), H11, eps);
    const vreal i1 = one / H11;
    const vreal l21 = H12 * i1, l31 = H13 * i1;

    const vreal gf2 = mtwo * (ED[0] * xy0 + ED[1] * xy1 + ED[2] * xy2);
    vreal g2 = gf2 + rho * (v6 - v4);
    /* scalar: rows 2, 3 reduced without their penalty terms (T); last pivot as a 2x2 det */
    const vreal T22 = f22 + eps - l20 * H02 - l21 * H12;
    const vreal T23 = f23 - l20 * H03 - l21 * H13;
    const vreal T33 = f33 + eps - l30 * H03 - l31 * H13;
    vreal H22 = T22 + m4 + m6;
    const vreal H23 = T23 + m6;
    g2 = g2 - (l20 * g0 + l21 * g1);
    H22 = vsel(vgt(H22, eps), H22, eps);
    const vreal i2 = one / H22;
    const vreal l32 = H23 * i2;

    const vreal gf3 = mtwo * (FD[0] * xy0 + FD[1] * xy1 + FD[2] * xy2);
    vreal g3 = gf3 + rho * (v6 - v5);
    vreal H33 = ((T22 * T33 - T23 * T23) + m6 * (T22 + T33 - two * T23) + m4 * (T33 + m5 + m6) +
                 m5 * (T22 + m6)) * i2;
    g3 = g3 - (l30 * g0 + l31 * g1 + l32 * g2);
    H33 = vsel(vgt(H33, eps), H33, eps);

    /* Back substitution: the Newton step dx = H^-1 grad. */
    const vreal d3 = g3 / H33;
    const vreal d2 = (g2 - H23 * d3) * i2;
    const vreal d1 = (g1 - H12 * d2 - H13 * d3) * i1;
    const vreal d0 = (g0 - H01 * d1 - H02 * d2 - H03 * d3) * i0;

    /* The step measured on the geometry (paper lines 19-21), squared. */
    const vreal DX0 = BA[0] * d0 + CA[0] * d1, DX1 = BA[1] * d0 + CA[1] * d1, DX2 = BA[2] * d0 + CA[2] * d1;
    const vreal DY0 = ED[0] * d2 + FD[0] * d3, DY1 = ED[1] * d2 + FD[1] * d3, DY2 = ED[2] * d2 + FD[2] * d3;
    const vreal err2 = DX0 * DX0 + DX1 * DX1 + DX2 * DX2 + DY0 * DY0 + DY1 * DY1 + DY2 * DY2;

    /* Exact line search along -dx (scalar: the phi'(t) bracket). */
    const vreal s1 = -d0, s2 = -d1, s3 = d0 + d1, s4 = -d2, s5 = -d3, s6 = d2 + d3;
    const vreal jd0 = DX0 - DY0, jd1 = DX1 - DY1, jd2 = DX2 - DY2;
    const vreal q = two * (jd0 * jd0 + jd1 * jd1 + jd2 * jd2);
    const vreal gfd = gf0 * d0 + gf1 * d1 + gf2 * d2 + gf3 * d3;
#define TTD_KP_SLOPE(t)                                                                         \
(-gfd + (t) * q -                                                                           \
 rho * (s1 * kp_pos(h1 - (t) * s1) + s2 * kp_pos(h2 - (t) * s2) +         \
        s3 * kp_pos(h3 - (t) * s3) + s4 * kp_pos(h4 - (t) * s4) +         \
        s5 * kp_pos(h5 - (t) * s5) + s6 * kp_pos(h6 - (t) * s6)))
    const vreal p0 = TTD_KP_SLOPE(zero);
    const vreal p1 = TTD_KP_SLOPE(one);
    vreal step = one;
    const vmask bracket = vgt(p1, zero);
    if (many(mand(active, bracket))) {
        vreal lo = zero, plo = p0, hi = one, phi = p1;
#define TTD_KP_BREAK(hh, ss)                                                                    \
{                                                                                           \
    const vreal tb = (hh) / (ss);                                                           \
    const vmask in = mand(vgt(tb, zero), vlt(tb, one));                                     \
    const vreal pb = TTD_KP_SLOPE(tb);                                                      \
    const vmask to_lo = mand(in, mand(vle(pb, zero), vgt(tb, lo)));                        \
    const vmask to_hi = mand(in, mand(vgt(pb, zero), vlt(tb, hi)));                         \
    lo = vsel(to_lo, tb, lo);                                                               \
    plo = vsel(to_lo, pb, plo);                                                             \
    hi = vsel(to_hi, tb, hi);                                                               \
    phi = vsel(to_hi, pb, phi);                                                             \
}
        TTD_KP_BREAK(h1, s1) TTD_KP_BREAK(h2, s2) TTD_KP_BREAK(h3, s3)
        TTD_KP_BREAK(h4, s4) TTD_KP_BREAK(h5, s5) TTD_KP_BREAK(h6, s6)
#undef TTD_KP_BREAK
        const vreal den = phi - plo;
        vreal fr = vsel(vgt(den, zero), -plo / den, zero);
        fr = vsel(vgt(fr, zero), fr, zero);
        fr = vsel(vlt(fr, one), fr, one);
        step = vsel(bracket, lo + (hi - lo) * fr, one);
    }
    /* scalar: the `else if (p1 < p0 * TTD_PENALTY_EXTEND)` search beyond t = 1 */
    const vmask extend = mand(mnot(bracket), vlt(p1, p0 * vset1((real)TTD_PENALTY_EXTEND)));
    if (many(mand(active, extend))) {
        const vreal rmax = vset1(TTD_REAL_MAX);
        vreal lo = one, plo = p1, hi = one, phi = zero;
        vmask found = vlt(one, zero); /* all false */
#define TTD_KP_BEYOND(hh, ss)                                                                   \
{                                                                                           \
    const vreal tb = (hh) / (ss);                                                           \
    const vmask in = mand(vgt(tb, one), vle(tb, rmax));                                     \
    const vreal pb = TTD_KP_SLOPE(tb);                                                      \
    const vmask to_lo = mand(in, mand(vle(pb, zero), vgt(tb, lo)));                        \
    const vmask to_hi = mand(in, mand(vgt(pb, zero), mor(mnot(found), vlt(tb, hi))));      \
    lo = vsel(to_lo, tb, lo);                                                               \
    plo = vsel(to_lo, pb, plo);                                                             \
    hi = vsel(to_hi, tb, hi);                                                               \
    phi = vsel(to_hi, pb, phi);                                                             \
    found = mor(found, to_hi);                                                              \
}
        TTD_KP_BEYOND(h1, s1) TTD_KP_BEYOND(h2, s2) TTD_KP_BEYOND(h3, s3)
        TTD_KP_BEYOND(h4, s4) TTD_KP_BEYOND(h5, s5) TTD_KP_BEYOND(h6, s6)
#undef TTD_KP_BEYOND
        const vreal t2 = two * lo;
        const vreal p2 = TTD_KP_SLOPE(t2);
        hi = vsel(found, hi, t2);
        phi = vsel(found, phi, p2);
        const vreal den = phi - plo;
        vreal fr = vsel(vgt(den, zero), -plo / den, zero);
        fr = vsel(vgt(fr, zero), fr, zero);
        fr = vsel(mor(vlt(fr, one), mnot(found)), fr, one);
        vreal st = lo + (hi - lo) * fr;
        st = vsel(vle(st, rmax), st, lo);
        step = vsel(extend, st, step);
    }
#undef TTD_KP_SLOPE
    /* The update, in active lanes only. */
    const vreal a_o = a, b_o = b, ca_o = ca, g_o = g, d_o = d, cg_o = cg;
    a = vsel(active, a - step * d0, a);
    b = vsel(active, b - step * d1, b);
    ca = vsel(active, ca + step * (d0 + d1), ca);
    g = vsel(active, g - step * d2, g);
    d = vsel(active, d - step * d3, d);
    cg = vsel(active, cg + step * (d2 + d3), cg);
    X->a = a;
    X->b = b;
    X->ca = ca;
    X->g = g;
    X->d = d;
    X->cg = cg;
    /* Convergence: a small step, unless it releases a constraint right after a large one. */
    const vmask released =
        mor(mor(mor(mand(a1, vlt(h1 + step * d0, zero)), mand(a2, vlt(h2 + step * d1, zero))),
                mor(mand(a3, vlt(h3 - step * (d0 + d1), zero)), mand(a4, vlt(h4 + step * d2, zero)))),
            mor(mand(a5, vlt(h5 + step * d3, zero)), mand(a6, vlt(h6 - step * (d2 + d3), zero))));
    /* scalar: a step with grad.dx below tol^2 or below rounding of |X - Y|^2 counts as
     * small; an iterate the update left unchanged has converged. */
    const vreal fx = xy0 * xy0 + xy1 * xy1 + xy2 * xy2;
    const vreal dec = -p0;
    const vmask flat = mor(vlt(dec, tol2), vlt(dec, vset1((real)TTD_PENALTY_FLAT_ULPS * TTD_REAL_EPS) * fx));
    const vreal errc = vsel(flat, zero, err2);
    const vmask stuck = mand(mand(mand(veq(a, a_o), veq(b, b_o)), mand(veq(ca, ca_o), veq(g, g_o))),
                             mand(veq(d, d_o), veq(cg, cg_o)));
    const vmask small_prev = vlt(X->prev_err2, tol2);
    X->prev_err2 = vsel(active, errc, X->prev_err2);
    return mand(active, mor(mand(vlt(errc, tol2), mor(mnot(released), small_prev)), stuck));
}

/* scalar: after the loop. Clamped weights and the distance |p - q| (in the frame, scaled back). */
static inline vreal kp_finish(const kp_frame *F, const kp_state *X, vreal wp[3],
                                       vreal wq[3])
{
    const vreal *BA = F->BA, *CA = F->CA, *DA = F->DA, *ED = F->ED, *FD = F->FD;
    kp_clamp_bary3(X->ca, X->a, X->b, wp);
    kp_clamp_bary3(X->cg, X->g, X->d, wq);
    /* p - q in the frame, from the clamped weights (A = 0). */
    const vreal xy0 = wp[1] * BA[0] + wp[2] * CA[0] - DA[0] - wq[1] * ED[0] - wq[2] * FD[0];
    const vreal xy1 = wp[1] * BA[1] + wp[2] * CA[1] - DA[1] - wq[1] * ED[1] - wq[2] * FD[1];
    const vreal xy2 = wp[1] * BA[2] + wp[2] * CA[2] - DA[2] - wq[1] * ED[2] - wq[2] * FD[2];
    return vsqrt(xy0 * xy0 + xy1 * xy1 + xy2 * xy2) * F->unscale * F->unpre;
}

/* scalar: pen_finish's points, p and q as convex combinations of the input vertices. */
static inline void kp_points(const vreal S[9], const vreal T[9], const vreal wp[3], const vreal wq[3],
                                      kw_out *o)
{
    const vreal big = vset1(TTD_REAL_MAX), mbig = vset1(-TTD_REAL_MAX); /* scalar: pen_clamp_max */
    for (int k = 0; k < 3; ++k) {
        o->p[k] = vmin(vmax(wp[0] * S[k] + wp[1] * S[3 + k] + wp[2] * S[6 + k], mbig), big);
        o->q[k] = vmin(vmax(wq[0] * T[k] + wq[1] * T[3 + k] + wq[2] * T[6 + k], mbig), big);
        o->bary_p[k] = wp[k];
        o->bary_q[k] = wq[k];
    }
    o->flags_int = 0;
    o->flags_ds = 0;
    o->flags_dt = 0;
}

/* Groups of W pairs: every lane of a group iterates until the slowest has finished. */
static void kernel_penalty(size_t n, const real *s, const real *t, const ttd_params *prm, real bound,
                           const ttd_out *out)
{
    (void)bound;
    const kp_consts K = kp_consts_of(prm);
    for (size_t i0 = 0; i0 < n; i0 += TTDW_LANES) {
        const int live = n - i0 < (size_t)TTDW_LANES ? (int)(n - i0) : TTDW_LANES;
        vreal S[9], T[9];
        kw_load_group(s + 9 * i0, t + 9 * i0, live, S, T);
        kp_frame F;
        kp_hf H;
        kp_state X;
        kp_frame_of(S, T, &F);
        kp_hf_of(&F, &H);
        kp_init(&X);
        vmask active = mfirst(live), converged = mnot(mtrue());
        vreal its = vzero();
        for (int it = 1; it <= prm->max_iterations && many(active); ++it) {
            its = vsel(active, vset1((real)it), its);
            const vmask done = kp_step(&K, &F, &H, &X, active);
            converged = mor(converged, done);
            active = mandnot(active, done);
        }
        kw_out o;
        vreal wp[3], wq[3];
        o.distance = kp_finish(&F, &X, wp, wq);
        kp_points(S, T, wp, wq, &o);
        o.iterations = its;
        o.flags_nc = ~mbits(converged);
        kw_store_group(&o, live, out, i0);
    }
}
