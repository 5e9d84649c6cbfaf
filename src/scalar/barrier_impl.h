/* SPDX-License-Identifier: MIT */
/* The log-barrier method (paper, section 2: its first attempt), precision-generic; barrier_d.c
 * and barrier_f.c compile it once each. For comparison with the penalty method only: correct,
 * not tuned for speed.
 *
 * It minimises B(x) = f(x) - mu sum_i log(s_i) over x = (a, b, g, d), where f is the squared
 * distance |X(a,b) - Y(g,d)|^2 and the six slacks s = (a, b, 1-a-b, g, d, 1-g-d) are the
 * barycentric weights, kept strictly positive: every Newton step is shortened to stay
 * inside (fraction to the boundary) and then backtracked until B decreases. The barrier
 * weight mu starts at 1 and is divided by 10 once the iterate is centred (Newton decrement
 * below mu), down to 1/rho^2; the answer is then within 6 mu of the minimum of f (the
 * duality gap of the log barrier). Like the penalty method it runs on the pair translated
 * to A and scaled by a power of two to unit size (without the penalty's subnormal lift, see
 * the frame below), and keeps the third weight of each
 * triangle as a variable of its own so that it has full precision near 0.
 * Accuracy and iteration counts: docs/penalty-method.md. */

/* Squared distance, gradient and Hessian of f in the frame; x = (a, b, g, d). */
static real bar_f(real u[4][3], const real da[3], const real x[4])
{
    real f = 0;
    for (int k = 0; k < 3; ++k) {
        real v = x[0] * u[0][k] + x[1] * u[1][k] + x[2] * u[2][k] + x[3] * u[3][k] - da[k];
        f += v * v;
    }
    return f;
}

/* B at x with slacks sl[6]; REAL_MAX outside (any slack <= 0), and for a slack that is not
 * finite: a nearly singular Hessian (crossing triangles in float) can give a step so long that
 * a slack's update overflows, and log(inf) would make B -inf, accepted as a decrease (issue 12:
 * a NaN point and a wrong distance, unflagged). */
static real bar_value(real u[4][3], const real da[3], const real x[4], const real sl[6], real mu)
{
    real logs = 0;
    for (int i = 0; i < 6; ++i) {
        if (!(sl[i] > 0 && sl[i] <= TTD_REAL_MAX)) return TTD_REAL_MAX;
        logs += (real)log((double)sl[i]);
    }
    return bar_f(u, da, x) - mu * logs;
}

/* Solves the symmetric positive definite m x = r by elimination without pivoting; a pivot
 * below floor_ (rounding on a degenerate pair) is raised to it. */
static void bar_solve(real m[4][4], real r[4], real x[4], real floor_)
{
    for (int c = 0; c < 4; ++c) {
        if (!(m[c][c] > floor_)) m[c][c] = floor_;
        for (int i = c + 1; i < 4; ++i) {
            real l = m[i][c] / m[c][c];
            for (int j = c; j < 4; ++j) m[i][j] -= l * m[c][j];
            r[i] -= l * r[c];
        }
    }
    for (int i = 3; i >= 0; --i) {
        real acc = r[i];
        for (int j = i + 1; j < 4; ++j) acc -= m[i][j] * x[j];
        x[i] = acc / m[i][i];
    }
}

static real bar_norm3(real x, real y, real z)
{
    real m = TTD_FABS(x);
    if (TTD_FABS(y) > m) m = TTD_FABS(y);
    if (TTD_FABS(z) > m) m = TTD_FABS(z);
    if (!(m > 0) || !(m <= TTD_REAL_MAX)) return m;
    int e;
    (void)TTD_FREXP(m, &e);
    x = TTD_LDEXP(x, -e);
    y = TTD_LDEXP(y, -e);
    z = TTD_LDEXP(z, -e);
    return TTD_LDEXP(TTD_SQRT(x * x + y * y + z * z), e);
}

static void barrier_pair(const real s[9], const real t[9], const ttd_params *prm, ttd_result *r)
{
    /* Final barrier weight 1/rho^2 (the penalty method's error scale), not below what the
     * precision resolves. rho is not capped in float here: the barrier Hessian has no rho
     * terms, so the penalty's float cap does not apply. */
    double mu_end_d = 1.0 / (prm->rho * prm->rho);
    if (!(mu_end_d > 16.0 * (double)TTD_REAL_EPS * (double)TTD_REAL_EPS))
        mu_end_d = 16.0 * (double)TTD_REAL_EPS * (double)TTD_REAL_EPS;
    const real mu_end = (real)mu_end_d;

    /* Frame: origin at A, unit size by a power of two: the penalty method's frame without
     * its subnormal lift (e is clamped at emin instead), pre with the penalty's threshold
     * and factor for the reasons given in penalty_impl.h. For a pair of subnormal size the
     * frame stays below unit size while mu_end is absolute, so the barrier loses accuracy
     * there (2,000 random pairs, largest error over the pair's size: 7e-8 unscaled, 2e-3
     * scaled by 2^-1030, 0.9 by 2^-1040). */
    real m0 = 0;
    for (int k = 0; k < 9; ++k) {
        if (TTD_FABS(s[k]) > m0) m0 = TTD_FABS(s[k]);
        if (TTD_FABS(t[k]) > m0) m0 = TTD_FABS(t[k]);
    }
    const real pre = m0 > TTD_REAL_MAX * (real)0.125 ? (real)0.0625 : (real)1;
    real u[4][3], da[3], size = 0; /* u = (B-A, C-A, D-E, D-F), da = D-A */
    for (int k = 0; k < 3; ++k) {
        real a0 = s[k] * pre;
        u[0][k] = s[3 + k] * pre - a0;
        u[1][k] = s[6 + k] * pre - a0;
        u[2][k] = t[k] * pre - t[3 + k] * pre;
        u[3][k] = t[k] * pre - t[6 + k] * pre;
        da[k] = t[k] * pre - a0;
        real c[5] = {u[0][k], u[1][k], da[k], t[3 + k] * pre - a0, t[6 + k] * pre - a0};
        for (int i = 0; i < 5; ++i)
            if (TTD_FABS(c[i]) > size) size = TTD_FABS(c[i]);
    }
    int e = 0;
    (void)TTD_FREXP(size, &e);
    {
        const int emin = (int)sizeof(real) == (int)sizeof(double) ? DBL_MIN_EXP + 2 : FLT_MIN_EXP + 2;
        if (e < emin) e = emin;
    }
    for (int k = 0; k < 3; ++k) {
        for (int i = 0; i < 4; ++i) u[i][k] = TTD_LDEXP(u[i][k], -e);
        da[k] = TTD_LDEXP(da[k], -e);
    }
    real hf[4][4];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) hf[i][j] = 2 * (u[i][0] * u[j][0] + u[i][1] * u[j][1] + u[i][2] * u[j][2]);

    real x[4] = {(real)1 / 3, (real)1 / 3, (real)1 / 3, (real)1 / 3};
    real sl[6] = {x[0], x[1], (real)1 / 3, x[2], x[3], (real)1 / 3}; /* a b 1-a-b g d 1-g-d */
    real mu = 1;
    int it = 0, converged = 0, stalled = 0;
    while (it < prm->max_iterations) {
        ++it;
        real xy[3];
        for (int k = 0; k < 3; ++k) xy[k] = x[0] * u[0][k] + x[1] * u[1][k] + x[2] * u[2][k] + x[3] * u[3][k] - da[k];
        real g[4], H[4][4];
        for (int i = 0; i < 4; ++i) {
            g[i] = 2 * (u[i][0] * xy[0] + u[i][1] * xy[1] + u[i][2] * xy[2]);
            for (int j = 0; j < 4; ++j) H[i][j] = hf[i][j];
        }
        /* -mu log s_i: gradient -mu s_i'/s_i, Hessian mu s_i' s_i'^T / s_i^2. */
        real inv[6], inv2[6];
        for (int i = 0; i < 6; ++i) {
            inv[i] = 1 / sl[i];
            inv2[i] = mu * inv[i] * inv[i];
        }
        g[0] -= mu * (inv[0] - inv[2]);
        g[1] -= mu * (inv[1] - inv[2]);
        g[2] -= mu * (inv[3] - inv[5]);
        g[3] -= mu * (inv[4] - inv[5]);
        H[0][0] += inv2[0] + inv2[2];
        H[1][1] += inv2[1] + inv2[2];
        H[0][1] += inv2[2];
        H[1][0] += inv2[2];
        H[2][2] += inv2[3] + inv2[5];
        H[3][3] += inv2[4] + inv2[5];
        H[2][3] += inv2[5];
        H[3][2] += inv2[5];
        real rhs[4] = {g[0], g[1], g[2], g[3]}, dx[4];
        bar_solve(H, rhs, dx, mu * TTD_REAL_EPS);
        const real dec = g[0] * dx[0] + g[1] * dx[1] + g[2] * dx[2] + g[3] * dx[3];

        /* Step x - t dx: slack changes ds_i = s_i' . dx; stay inside (99% of the way to the
         * nearest boundary), then halve until B decreases. */
        const real ds[6] = {dx[0], dx[1], -dx[0] - dx[1], dx[2], dx[3], -dx[2] - dx[3]};
        real step = 1;
        for (int i = 0; i < 6; ++i)
            if (ds[i] > 0 && (real)0.99 * sl[i] < step * ds[i]) step = (real)0.99 * sl[i] / ds[i];
        const real b0 = bar_value(u, da, x, sl, mu);
        real xn[4], sn[6];
        for (int tries = 0; tries < 40; ++tries) {
            for (int i = 0; i < 4; ++i) xn[i] = x[i] - step * dx[i];
            for (int i = 0; i < 6; ++i) sn[i] = sl[i] - step * ds[i];
            if (bar_value(u, da, xn, sn, mu) <= b0) break;
            step *= (real)0.5;
        }
        if (bar_value(u, da, xn, sn, mu) <= b0) {
            for (int i = 0; i < 4; ++i) x[i] = xn[i];
            for (int i = 0; i < 6; ++i) sl[i] = sn[i];
        }
        /* Centred for this mu (decrement below mu, or below the rounding of B's terms), or
         * stalled (no step of useful length: a Hessian too ill-conditioned for this
         * precision, as for shallowly crossing triangles): lower mu, or stop at the last one.
         * A stall is remembered: an answer reached through one is not a converged one. */
        const real fcur = xy[0] * xy[0] + xy[1] * xy[1] + xy[2] * xy[2];
        const int centred = !(dec > mu) || !(dec > 16 * TTD_REAL_EPS * (fcur + mu));
        if (centred || step < TTD_REAL_EPS) {
            stalled |= !centred;
            if (mu <= mu_end) {
                converged = !stalled;
                break;
            }
            mu *= (real)0.1;
            if (mu < mu_end) mu = mu_end;
        }
    }

    /* Weights (feasible already; renormalised so that they sum to 1). */
    real wp[3] = {sl[2], sl[0], sl[1]}, wq[3] = {sl[5], sl[3], sl[4]};
    real sp = wp[0] + wp[1] + wp[2], sq = wq[0] + wq[1] + wq[2];
    for (int k = 0; k < 3; ++k) {
        wp[k] = wp[k] > 0 ? wp[k] / sp : (real)0;
        wq[k] = wq[k] > 0 ? wq[k] / sq : (real)0;
    }
    real xy[3];
    for (int k = 0; k < 3; ++k) {
        r->p[k] = wp[0] * s[k] + wp[1] * s[3 + k] + wp[2] * s[6 + k];
        r->q[k] = wq[0] * t[k] + wq[1] * t[3 + k] + wq[2] * t[6 + k];
        /* vertices at +-REAL_MAX: the weighted sum can round past it */
        r->p[k] = r->p[k] > TTD_REAL_MAX ? TTD_REAL_MAX : (r->p[k] < -TTD_REAL_MAX ? -TTD_REAL_MAX : r->p[k]);
        r->q[k] = r->q[k] > TTD_REAL_MAX ? TTD_REAL_MAX : (r->q[k] < -TTD_REAL_MAX ? -TTD_REAL_MAX : r->q[k]);
        r->bary_p[k] = wp[k];
        r->bary_q[k] = wq[k];
        xy[k] = wp[1] * u[0][k] + wp[2] * u[1][k] + wq[1] * u[2][k] + wq[2] * u[3][k] - da[k];
    }
    r->distance = TTD_LDEXP(bar_norm3(xy[0], xy[1], xy[2]), e) / pre; /* no 0 * inf */
    r->feature_p = (uint8_t)((wp[0] > 0) | ((wp[1] > 0) << 1) | ((wp[2] > 0) << 2));
    r->feature_q = (uint8_t)((wq[0] > 0) | ((wq[1] > 0) << 1) | ((wq[2] > 0) << 2));
    r->iterations = (uint16_t)it;
    r->flags = converged ? 0u : (uint32_t)TTD_PAIR_NOT_CONVERGED;
}
