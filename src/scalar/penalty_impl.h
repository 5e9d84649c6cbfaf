/* SPDX-License-Identifier: MIT */
/* The penalty method (paper, sections 2 and 3), precision-generic; penalty_d.c and
 * penalty_f.c compile it once each (core/precision.h). Two forms:
 *
 *  - penalty_ref_pair (ttd_penalty_ref_pair_d/f): the paper's MATLAB ttd1 step for step (raw coordinates, start at
 *    0.33, dense 6x4 constraint Jacobian, separate pivoting 4x4 solve). Only the outputs
 *    differ: the final parameters are clamped onto their triangles so that p and q lie on
 *    them and distance = |p - q|.
 *  - penalty_pair (ttd_penalty_pair_d/f): the optimised form the paper describes (symmetric Hessian, constraint
 *    derivatives kept as their non-zeros, branchless max, elimination fused with assembly),
 *    run on the pair translated to A and scaled by a power of two to unit size, with a
 *    one-dimensional line search that stops Newton from cycling between active sets, and the
 *    same final clamping. It is written to be ported line for line to one-pair-per-lane SIMD:
 *    one loop whose only data-dependent branches are the convergence test and the line
 *    search's two rarely taken blocks (the bracket when phi'(1) > 0, the search beyond the
 *    Newton step when phi'(1) stays steep), which a lane port runs when any lane needs them;
 *    every other decision is a select.
 *
 * Both minimise P(x) = |X(a,b) - Y(g,d)|^2 + (rho/2) sum_i max(0, h_i(x))^2 over
 * x = (a, b, g, d), with X = A + a(B-A) + b(C-A), Y = D + g(E-D) + d(F-D) and the six
 * constraints h = (-a, -b, a+b-1, -g, -d, g+d-1) <= 0. Measurements behind every choice:
 * docs/penalty-method.md. */

/// Branchless max(0, v) as (v + |v|)/2 (exact: doubling and halving are exact, v + |v| is
/// 2v or 0). The ternary form compiles to a branch in scalar x86 code; the SIMD port uses a
/// lane max. Arguments are bounded (|v| < REAL_MAX/2) wherever the result is used.
static inline real pen_pos(real v)
{
    return (v + TTD_FABS(v)) * (real)0.5;
}

/// Branch-free select c ? x : y through the bits (a lane blend in the SIMD port). Scalar x86
/// without SSE4.1 has no blend, and the compiler turns a ternary on reals into a branch,
/// which mispredicts on the line search's data.
static inline real pen_sel(int c, real x, real y)
{
#ifdef TTD_PRECISION_DOUBLE
    uint64_t bx, by, m = (uint64_t)0 - (uint64_t)(c != 0);
#else
    uint32_t bx, by, m = (uint32_t)0 - (uint32_t)(c != 0);
#endif
    memcpy(&bx, &x, sizeof bx);
    memcpy(&by, &y, sizeof by);
    bx = (bx & m) | (by & ~m);
    memcpy(&x, &bx, sizeof x);
    return x;
}

/// |v| of a 3-vector without overflow or underflow in the squares (power-of-two scaling).
static real pen_norm3(real x, real y, real z)
{
    real m = TTD_FABS(x);
    if (TTD_FABS(y) > m) m = TTD_FABS(y);
    if (TTD_FABS(z) > m) m = TTD_FABS(z);
    if (!(m > 0) || !(m <= TTD_REAL_MAX)) return m; /* 0, or inf when p - q overflowed */
    int e;
    (void)TTD_FREXP(m, &e);
    x = TTD_LDEXP(x, -e);
    y = TTD_LDEXP(y, -e);
    z = TTD_LDEXP(z, -e);
    return TTD_LDEXP(TTD_SQRT(x * x + y * y + z * z), e);
}

/* Clamps the barycentric weights (c, a, b) of one triangle (c ~ 1 - a - b) into the
 * triangle: negative weights become 0 and the three are renormalised to sum 1 (the sum is
 * ~>= 1 after clamping; a zero sum, impossible unless the iterate is garbage, gives vertex 0). The penalty iterate violates its constraints by O(1/rho); clamping
 * moves it back onto the triangle and turns the distance error from O(1/rho) into O(1/rho^2)
 * (docs/penalty-method.md). */
static void pen_clamp_bary3(real c, real a, real b, real w[3])
{
    const real w0 = pen_pos(c);
    const real w1 = pen_pos(a);
    const real w2 = pen_pos(b);
    const real sum = w0 + w1 + w2;
    const real inv = (real)1 / (sum > 0 ? sum : (real)1);
    w[0] = sum > 0 ? w0 * inv : (real)1;
    w[1] = w1 * inv;
    w[2] = w2 * inv;
}

/* The reference method's weights. Not in the paper: its iterate is unbounded, and where the
 * step is finite but x - dx overflows (coordinates near REAL_MAX) it reaches +-inf, which would
 * make 1 - a - b inf or NaN and the weights NaN. Bounded at REAL_MAX/8 first, 1 - a - b and the
 * clamped weights' sum stay finite; any iterate below the bound is untouched. (x is never NaN:
 * it starts at 0.33 and moves only by finite steps.) */
static void pen_clamp_bary(real a, real b, real w[3])
{
    const real big = TTD_REAL_MAX / 8;
    a = a > big ? big : (a < -big ? -big : a);
    b = b > big ? big : (b < -big ? -big : b);
    pen_clamp_bary3((real)1 - a - b, a, b, w);
}

/* Fills r from the clamped weights: p and q as convex combinations of the input vertices
 * (no overflow, on the triangle up to rounding), the feature bits, and the distance the
 * caller computed from p - q in its own frame. */
/* Vertices near +-REAL_MAX: a convex combination can round past it; REAL_MAX is then right
 * to that rounding and finite. */
static real pen_clamp_max(real x)
{
    return x > TTD_REAL_MAX ? TTD_REAL_MAX : (x < -TTD_REAL_MAX ? -TTD_REAL_MAX : x);
}

static void pen_finish(const real s[9], const real t[9], const real wp[3],
                                const real wq[3], real distance, ttd_result *r)
{
    for (int k = 0; k < 3; ++k) {
        r->p[k] = pen_clamp_max(wp[0] * s[k] + wp[1] * s[3 + k] + wp[2] * s[6 + k]);
        r->q[k] = pen_clamp_max(wq[0] * t[k] + wq[1] * t[3 + k] + wq[2] * t[6 + k]);
        r->bary_p[k] = wp[k];
        r->bary_q[k] = wq[k];
    }
    r->distance = distance;
    r->feature_p = (uint8_t)((wp[0] > 0) | ((wp[1] > 0) << 1) | ((wp[2] > 0) << 2));
    r->feature_q = (uint8_t)((wq[0] > 0) | ((wq[1] > 0) << 1) | ((wq[2] > 0) << 2));
}

/* ---------------------------------------------------------------------------------------- */
/* The reference: the paper's ttd1.                                                          */

/* hes \ gra by Gaussian elimination with partial pivoting, ttd's stand-in for MATLAB's
 * backslash (a Cholesky solve on this symmetric positive definite matrix, with LU and
 * least-squares fallbacks when it breaks down). A pivot below eps * max|diag| is raised to that
 * floor so that the step stays finite. With a penalised constraint max|diag| >= rho, so the
 * floor (>= rho eps) lies far above the listing's I/rho^2, and it fires often: on nearly
 * parallel, touching, degenerate and sliver pairs (14-57% of such pairs at rho 1e6) and on half
 * of random pairs at rho 1e8, changing their iterates; without it the step there is NaN or inf
 * (docs/penalty-method.md, "The pivot floor"). On random pairs at the default rho it never
 * fires. */
static void pen_ref_solve(real m[4][4], real rhs[4], real x[4])
{
    real dmax = 0;
    for (int i = 0; i < 4; ++i)
        if (TTD_FABS(m[i][i]) > dmax) dmax = TTD_FABS(m[i][i]);
    real floor_ = dmax * TTD_REAL_EPS;
    if (!(floor_ > 0)) floor_ = TTD_REAL_MIN;
    for (int c = 0; c < 4; ++c) {
        int piv = c;
        for (int i = c + 1; i < 4; ++i)
            if (TTD_FABS(m[i][c]) > TTD_FABS(m[piv][c])) piv = i;
        if (piv != c) {
            for (int j = 0; j < 4; ++j) {
                real tmp = m[c][j];
                m[c][j] = m[piv][j];
                m[piv][j] = tmp;
            }
            real tmp = rhs[c];
            rhs[c] = rhs[piv];
            rhs[piv] = tmp;
        }
        if (TTD_FABS(m[c][c]) < floor_) m[c][c] = m[c][c] < 0 ? -floor_ : floor_;
        for (int i = c + 1; i < 4; ++i) {
            real l = m[i][c] / m[c][c];
            for (int j = c; j < 4; ++j) m[i][j] -= l * m[c][j];
            rhs[i] -= l * rhs[c];
        }
    }
    for (int i = 3; i >= 0; --i) {
        real acc = rhs[i];
        for (int j = i + 1; j < 4; ++j) acc -= m[i][j] * x[j];
        x[i] = acc / m[i][i];
    }
}

static void penalty_ref_pair(const real s[9], const real t[9], const ttd_params *prm,
                                   ttd_result *r)
{
#ifdef TTD_PRECISION_DOUBLE
    const real rho = prm->rho, tol = prm->tol;
#else
    const real rho = (real)fmin(prm->rho, TTD_FLOAT_REF_RHO_MAX), tol = (real)prm->tol;
#endif
    const real *A = s, *D = t;
    real BA[3], CA[3], ED[3], FD[3];
    for (int k = 0; k < 3; ++k) {
        BA[k] = s[3 + k] - s[k];
        CA[k] = s[6 + k] - s[k];
        ED[k] = t[3 + k] - t[k];
        FD[k] = t[6 + k] - t[k];
    }
    /* hf(i,j) = 2 u_i . u_j with u = (BA, CA, -ED, -FD): the paper's lines 2-5. */
    const real *u[4] = {BA, CA, ED, FD};
    const real sgn[4] = {1, 1, -1, -1};
    real hf[4][4];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            hf[i][j] = 2 * sgn[i] * sgn[j] * (u[i][0] * u[j][0] + u[i][1] * u[j][1] + u[i][2] * u[j][2]);
    static const real dh[4][6] = {{-1, 0, 1, 0, 0, 0},
                                  {0, -1, 1, 0, 0, 0},
                                  {0, 0, 0, -1, 0, 1},
                                  {0, 0, 0, 0, -1, 1}};
    real x[4] = {(real)0.33, (real)0.33, (real)0.33, (real)0.33};
    int it, converged = 0, used = 0;
    for (it = 1; it <= prm->max_iterations; ++it) {
        used = it;
        real X[3], Y[3], XY[3];
        for (int k = 0; k < 3; ++k) {
            X[k] = A[k] + BA[k] * x[0] + CA[k] * x[1];
            Y[k] = D[k] + ED[k] * x[2] + FD[k] * x[3];
            XY[k] = X[k] - Y[k];
        }
        real gf[4];
        for (int i = 0; i < 4; ++i)
            gf[i] = 2 * sgn[i] * (XY[0] * u[i][0] + XY[1] * u[i][1] + XY[2] * u[i][2]);
        real h[6] = {-x[0], -x[1], x[0] + x[1] - 1, -x[2], -x[3], x[2] + x[3] - 1};
        real dmax[4][6];
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 6; ++j) dmax[i][j] = h[j] >= 0 ? dh[i][j] : 0; /* mask = h' >= 0 */
        real gra[4], hes[4][4];
        for (int i = 0; i < 4; ++i) {
            real acc = 0;
            for (int j = 0; j < 6; ++j) acc += dmax[i][j] * (h[j] > 0 ? h[j] : 0);
            gra[i] = gf[i] + rho * acc;
            for (int k = 0; k < 4; ++k) {
                real hk = 0;
                for (int j = 0; j < 6; ++j) hk += dmax[i][j] * dmax[k][j];
                hes[i][k] = hf[i][k] + rho * hk + (i == k ? (real)1 / (rho * rho) : 0);
            }
        }
        real dx[4];
        pen_ref_solve(hes, gra, dx);
        real e2 = 0;
        for (int k = 0; k < 3; ++k) {
            real DX = BA[k] * dx[0] + CA[k] * dx[1];
            real DY = ED[k] * dx[2] + FD[k] * dx[3];
            e2 += DX * DX + DY * DY;
        }
        real err = TTD_SQRT(e2);
        if (err < tol) {
            converged = 1;
            break;
        }
        /* Not in the paper: at coordinates whose squares overflow the step is not finite;
         * keep the last finite iterate rather than produce NaN. */
        if (!(TTD_FABS(dx[0]) + TTD_FABS(dx[1]) + TTD_FABS(dx[2]) + TTD_FABS(dx[3]) <= TTD_REAL_MAX))
            break;
        for (int i = 0; i < 4; ++i) x[i] -= dx[i];
    }
    real wp[3], wq[3];
    pen_clamp_bary(x[0], x[1], wp);
    pen_clamp_bary(x[2], x[3], wq);
    real xy[3];
    for (int k = 0; k < 3; ++k)
        xy[k] = (wp[0] * s[k] + wp[1] * s[3 + k] + wp[2] * s[6 + k]) -
                (wq[0] * t[k] + wq[1] * t[3 + k] + wq[2] * t[6 + k]);
    pen_finish(s, t, wp, wq, pen_norm3(xy[0], xy[1], xy[2]), r);
    r->iterations = (uint16_t)used;
    r->flags = converged ? 0u : (uint32_t)TTD_PAIR_NOT_CONVERGED;
}

/* ---------------------------------------------------------------------------------------- */
/* The optimised form.                                                                        */

static void penalty_pair(const real s[9], const real t[9], const ttd_params *prm,
                               ttd_result *r)
{
    /* In float, rho is capped and tol floored (defaults.h): a larger rho makes the pivots
     * rounding noise on degenerate pairs, a smaller tol is below the step's rounding. */
    const double rho_d = prm->rho < TTD_REAL_RHO_MAX ? prm->rho : TTD_REAL_RHO_MAX;
    const double tol_d = prm->tol > TTD_REAL_TOL_MIN ? prm->tol : TTD_REAL_TOL_MIN;
    const real rho = (real)rho_d;
    const real tol2 = (real)(tol_d * tol_d);
    /* Regularisation eps*I and pivot floor: a few ulps of the unit-size Hessian, not the
     * listing's 1/rho^2 (the paper's section 2 asks only for eps I, eps "suitably small"). On
     * nearly parallel edges or faces the valley's curvature (~angle^2)
     * lies below 1/rho^2 = 1e-12, and the regularised step then crawled along the valley
     * (grad/eps per iteration) to the cap (docs/penalty-method.md, Near-parallel families). */
    const real eps = (real)TTD_PENALTY_EPS_ULPS * TTD_REAL_EPS;
    const int max_it = prm->max_iterations;

    /* Frame: origin at A, scaled by 2^-e so that the largest coordinate of B, C, D, E, F
     * relative to A lies in [0.5, 1). rho and tol then mean the same at every scale and
     * position. pre guards the differences against overflow near REAL_MAX, with margin:
     * without it the differences stay below REAL_MAX/4 (e <= 1022 in double, 126 in float),
     * with it below REAL_MAX/8 (e <= 1021, 125). As |p - q| < 2 sqrt(3) < 4 in the frame,
     * dist * 2^e then stays finite before the division by pre (the lanes form 2^e as one
     * number). The exact method's 1/4 at REAL_MAX/4 only has to keep its differences
     * finite: it scales back by two factors. */
    real m0 = 0;
    for (int k = 0; k < 9; ++k) {
        if (TTD_FABS(s[k]) > m0) m0 = TTD_FABS(s[k]);
        if (TTD_FABS(t[k]) > m0) m0 = TTD_FABS(t[k]);
    }
    const real pre = m0 > TTD_REAL_MAX * (real)0.125 ? (real)0.0625 : (real)1;
    real BA[3], CA[3], DA[3], ED[3], FD[3];
    real size = 0;
    for (int k = 0; k < 3; ++k) {
        real a = s[k] * pre;
        BA[k] = s[3 + k] * pre - a;
        CA[k] = s[6 + k] * pre - a;
        DA[k] = t[k] * pre - a;
        ED[k] = t[3 + k] * pre - t[k] * pre;
        FD[k] = t[6 + k] * pre - t[k] * pre;
        real ea = t[3 + k] * pre - a, fa = t[6 + k] * pre - a;
        real mk = TTD_FABS(BA[k]);
        if (TTD_FABS(CA[k]) > mk) mk = TTD_FABS(CA[k]);
        if (TTD_FABS(DA[k]) > mk) mk = TTD_FABS(DA[k]);
        if (TTD_FABS(ea) > mk) mk = TTD_FABS(ea);
        if (TTD_FABS(fa) > mk) mk = TTD_FABS(fa);
        if (mk > size) size = mk;
    }
    /* A pair of subnormal size is lifted by an exact 2^lift first: 2^-e alone would not be
     * representable, and a frame left far below unit size changes what rho and tol mean.
     * The constants: a nonzero size below 2^-900 (float 2^-100) is at least 2^-1074
     * (2^-149), so lifted by 2^600 (2^60) it is at least 2^-474 (2^-89), e >= -473 (-88),
     * far above the emin clamp below (-1019, -123); the lifted size stays below 2^-300
     * (2^-40); and the scale back 2^(e-lift) >= 2^-1073 (2^-148) is representable. */
#ifdef TTD_PRECISION_DOUBLE
    const int lift = size < 0x1p-900 ? 600 : 0;
#else
    const int lift = size < 0x1p-100f ? 60 : 0;
#endif
    if (lift) {
        const real up = TTD_LDEXP((real)1, lift);
        size *= up;
        for (int k = 0; k < 3; ++k) {
            BA[k] *= up;
            CA[k] *= up;
            DA[k] *= up;
            ED[k] *= up;
            FD[k] *= up;
        }
    }
    int e = 0;
    (void)TTD_FREXP(size, &e);
    {
        /* Keeps 2^-e representable; since the lift it cannot trigger (a nonzero size gives
         * e >= -473 in double, -88 in float; size 0 gives e = 0). Kept as a guard. */
        const int emin = (int)sizeof(real) == (int)sizeof(double) ? DBL_MIN_EXP + 2 : FLT_MIN_EXP + 2;
        if (e < emin) e = emin;
    }
    const real scale = TTD_LDEXP((real)1, -e);
    for (int k = 0; k < 3; ++k) {
        BA[k] *= scale;
        CA[k] *= scale;
        DA[k] *= scale;
        ED[k] *= scale;
        FD[k] *= scale;
    }

    /* Hessian of f, symmetric: hf(i,j) = 2 u_i . u_j with u = (BA, CA, -ED, -FD). */
    const real f00 = 2 * (BA[0] * BA[0] + BA[1] * BA[1] + BA[2] * BA[2]);
    const real f01 = 2 * (BA[0] * CA[0] + BA[1] * CA[1] + BA[2] * CA[2]);
    const real f02 = -2 * (BA[0] * ED[0] + BA[1] * ED[1] + BA[2] * ED[2]);
    const real f03 = -2 * (BA[0] * FD[0] + BA[1] * FD[1] + BA[2] * FD[2]);
    const real f11 = 2 * (CA[0] * CA[0] + CA[1] * CA[1] + CA[2] * CA[2]);
    const real f12 = -2 * (CA[0] * ED[0] + CA[1] * ED[1] + CA[2] * ED[2]);
    const real f13 = -2 * (CA[0] * FD[0] + CA[1] * FD[1] + CA[2] * FD[2]);
    const real f22 = 2 * (ED[0] * ED[0] + ED[1] * ED[1] + ED[2] * ED[2]);
    const real f23 = 2 * (ED[0] * FD[0] + ED[1] * FD[1] + ED[2] * FD[2]);
    const real f33 = 2 * (FD[0] * FD[0] + FD[1] * FD[1] + FD[2] * FD[2]);

    /* The iterate, with the third barycentric weight of each triangle kept as a variable of
     * its own (ca = 1 - a - b, cg = 1 - g - d, updated by the same steps). h3 = -ca then has
     * full precision next to the edge BC: computed as a + b - 1 it is a multiple of the ulp
     * of 1, and in float a Newton step that should release the constraint (~gradient/rho
     * long) was rounded away, leaving the iterate stuck on the wrong edge. */
    real a = (real)1 / 3, b = (real)1 / 3, ca = (real)1 / 3;
    real g = (real)1 / 3, d = (real)1 / 3, cg = (real)1 / 3;
    real prev_err2 = TTD_REAL_MAX;
    int it = 0, converged = 0;
    while (it < max_it) {
        ++it;
        /* XY = X - Y in the frame (A = 0). */
        const real xy0 = a * BA[0] + b * CA[0] - DA[0] - g * ED[0] - d * FD[0];
        const real xy1 = a * BA[1] + b * CA[1] - DA[1] - g * ED[1] - d * FD[1];
        const real xy2 = a * BA[2] + b * CA[2] - DA[2] - g * ED[2] - d * FD[2];

        /* Constraints and their penalty terms; the derivatives of h are the non-zeros +-1
         * only, so they are written into the sums below instead of stored. v_i = max(0,h_i)
         * and m_i = rho when h_i >= 0 (the paper's mask), both by select. */
        const real h1 = -a, h2 = -b, h3 = -ca, h4 = -g, h5 = -d, h6 = -cg;
        const real v1 = pen_pos(h1), v2 = pen_pos(h2), v3 = pen_pos(h3);
        const real v4 = pen_pos(h4), v5 = pen_pos(h5), v6 = pen_pos(h6);
        const real m1 = pen_sel(h1 >= 0, rho, 0), m2 = pen_sel(h2 >= 0, rho, 0);
        const real m3 = pen_sel(h3 >= 0, rho, 0);
        const real m4 = pen_sel(h4 >= 0, rho, 0), m5 = pen_sel(h5 >= 0, rho, 0);
        const real m6 = pen_sel(h6 >= 0, rho, 0);

        /* Gradient and Hessian assembled row by row into a symmetric Gaussian elimination
         * (only the upper triangle is formed; row k is eliminated as soon as it exists).
         * No pivoting: H = hf + rho*dmax*dmax' + eps*I is symmetric positive definite
         * (hf = 2 J'J and dmax*dmax' are positive semi-definite, eps > 0), and elimination
         * without pivoting on an SPD matrix has positive pivots (they are the D of H = LDL')
         * that are >= the smallest eigenvalue >= eps. When rounding swallows eps (float, or a
         * degenerate triangle) a pivot can still come out ~0 or negative: it is raised to
         * eps, a select, so that the step stays finite. The elimination and the back
         * substitution divide four times: the pivot reciprocals i0, i1, i2 and g3 / H33.
         * The line search adds one division per breakpoint (h_i / s_i) and one for the
         * interpolation, in each of its blocks that runs. */
        const real gf0 = 2 * (BA[0] * xy0 + BA[1] * xy1 + BA[2] * xy2);
        real g0 = gf0 + rho * (v3 - v1);
        real H00 = f00 + m1 + m3 + eps;
        const real H01 = f01 + m3, H02 = f02, H03 = f03;
        H00 = pen_sel(H00 > eps, H00, eps);
        const real i0 = (real)1 / H00;
        const real l10 = H01 * i0, l20 = H02 * i0, l30 = H03 * i0;

        const real gf1 = 2 * (CA[0] * xy0 + CA[1] * xy1 + CA[2] * xy2);
        real g1 = gf1 + rho * (v3 - v2);
        /* The pivot H11 - H01^2/H00 as det/H00, with det = H00*H11 - H01^2 expanded so that
         * the rho^2 and rho*f terms of a penalised a+b <= 1 cancel exactly instead of in
         * rounding (that left noise ~rho*REAL_EPS in the pivot, far above the curvature
         * along the edge of a nearly parallel pair). */
        const real e00 = f00 + eps, e11 = f11 + eps;
        real H11 = ((e00 * e11 - f01 * f01) + m3 * (e00 + e11 - 2 * f01) + m1 * (e11 + m2 + m3) +
                    m2 * (e00 + m3)) * i0;
        real H12 = f12 - l10 * H02, H13 = f13 - l10 * H03;
        g1 -= l10 * g0;
        H11 = pen_sel(H11 > eps, H11, eps);
        const real i1 = (real)1 / H11;
        const real l21 = H12 * i1, l31 = H13 * i1;

        const real gf2 = -2 * (ED[0] * xy0 + ED[1] * xy1 + ED[2] * xy2);
        real g2 = gf2 + rho * (v6 - v4);
        /* Rows 2 and 3 reduced by rows 0 and 1 without their penalty terms (T), which rows
         * 0 and 1 do not touch; the last pivot is then a 2x2 determinant expanded as above. */
        const real T22 = f22 + eps - l20 * H02 - l21 * H12;
        const real T23 = f23 - l20 * H03 - l21 * H13;
        const real T33 = f33 + eps - l30 * H03 - l31 * H13;
        real H22 = T22 + m4 + m6;
        const real H23 = T23 + m6;
        g2 -= l20 * g0 + l21 * g1;
        H22 = pen_sel(H22 > eps, H22, eps);
        const real i2 = (real)1 / H22;
        const real l32 = H23 * i2;

        const real gf3 = -2 * (FD[0] * xy0 + FD[1] * xy1 + FD[2] * xy2);
        real g3 = gf3 + rho * (v6 - v5);
        real H33 = ((T22 * T33 - T23 * T23) + m6 * (T22 + T33 - 2 * T23) + m4 * (T33 + m5 + m6) +
                    m5 * (T22 + m6)) * i2;
        g3 -= l30 * g0 + l31 * g1 + l32 * g2;
        H33 = pen_sel(H33 > eps, H33, eps);

        /* Back substitution: the Newton step dx = H^-1 grad. */
        const real d3 = g3 / H33;
        const real d2 = (g2 - H23 * d3) * i2;
        const real d1 = (g1 - H12 * d2 - H13 * d3) * i1;
        const real d0 = (g0 - H01 * d1 - H02 * d2 - H03 * d3) * i0;

        /* The step measured on the geometry (paper line 19-21), squared. */
        const real DX0 = BA[0] * d0 + CA[0] * d1, DX1 = BA[1] * d0 + CA[1] * d1, DX2 = BA[2] * d0 + CA[2] * d1;
        const real DY0 = ED[0] * d2 + FD[0] * d3, DY1 = ED[1] * d2 + FD[1] * d3, DY2 = ED[2] * d2 + FD[2] * d3;
        const real err2 = DX0 * DX0 + DX1 * DX1 + DX2 * DX2 + DY0 * DY0 + DY1 * DY1 + DY2 * DY2;

        /* Safeguard: an exact line search along -dx. Plain Newton on P cycles between
         * active sets on ~3% of random pairs; damping, backtracking and one secant step
         * were measured and lost (docs/penalty-method.md). phi(t) = P(x - t dx) is convex
         * and piecewise quadratic in t, so its slope is piecewise linear and increasing:
         *   phi'(t) = -gf.dx + t dx'hf dx - rho sum_i s_i max(0, h_i - t s_i),
         * with s_i = h_i'.dx (the non-zeros of dh again) and dx'hf dx = 2|DX - DY|^2 since
         * J dx = DX - DY. phi'(0) = -grad.dx < 0. When phi'(1) > 0 the root of phi' is
         * bracketed between the breakpoints t_i = h_i/s_i in (0, 1) (the largest with
         * phi' <= 0, the smallest with phi' > 0; no breakpoint lies between them, so phi' is
         * linear there) and found by one interpolation. When phi'(1) <= 0 the full step is
         * taken, unless phi'(1) < TTD_PENALTY_EXTEND * phi'(0): then the search goes on
         * beyond t = 1 (the `else if` block below). Inside each block every decision is a
         * select; the SIMD port skips a block when no active lane needs it. */
        real step, dec;
        {
            const real s1 = -d0, s2 = -d1, s3 = d0 + d1, s4 = -d2, s5 = -d3, s6 = d2 + d3;
            const real jd0 = DX0 - DY0, jd1 = DX1 - DY1, jd2 = DX2 - DY2;
            const real q = 2 * (jd0 * jd0 + jd1 * jd1 + jd2 * jd2);
            const real gfd = gf0 * d0 + gf1 * d1 + gf2 * d2 + gf3 * d3;
#define TTD_PEN_SLOPE(t)                                                                     \
    (-gfd + (t) * q -                                                                        \
     rho * (s1 * pen_pos(h1 - (t) * s1) + s2 * pen_pos(h2 - (t) * s2) +    \
            s3 * pen_pos(h3 - (t) * s3) + s4 * pen_pos(h4 - (t) * s4) +    \
            s5 * pen_pos(h5 - (t) * s5) + s6 * pen_pos(h6 - (t) * s6)))
            const real p0 = TTD_PEN_SLOPE((real)0);
            const real p1 = TTD_PEN_SLOPE((real)1);
            dec = -p0; /* grad.dx: twice the decrease the full step promises */
            step = 1;
            /* One of the two branches besides the convergence test (the other is the
             * `else if` below, the search beyond t = 1): the bracket is needed on a
             * minority of iterations (docs/penalty-method.md), and it is cheap to skip.
             * In the SIMD port it becomes "if any active lane has phi'(1) > 0", with the
             * selects below per lane. A breakpoint outside (0, 1), or inf/NaN from s_i = 0,
             * fails the "in" test. */
            if (p1 > 0) {
                real lo = 0, plo = p0, hi = 1, phi = p1;
#define TTD_PEN_BREAK(hh, ss)                                                                \
    {                                                                                        \
        const real tb = (hh) / (ss);                                                         \
        const int in = (tb > 0) & (tb < 1);                                                  \
        const real pb = TTD_PEN_SLOPE(tb);                                                   \
        const int to_lo = in & (pb <= 0) & (tb > lo), to_hi = in & (pb > 0) & (tb < hi);     \
        lo = pen_sel(to_lo, tb, lo);                                                \
        plo = pen_sel(to_lo, pb, plo);                                              \
        hi = pen_sel(to_hi, tb, hi);                                                \
        phi = pen_sel(to_hi, pb, phi);                                              \
    }
                TTD_PEN_BREAK(h1, s1) TTD_PEN_BREAK(h2, s2) TTD_PEN_BREAK(h3, s3)
                TTD_PEN_BREAK(h4, s4) TTD_PEN_BREAK(h5, s5) TTD_PEN_BREAK(h6, s6)
#undef TTD_PEN_BREAK
                /* plo <= 0 < phi in exact arithmetic; near convergence both are rounding
                 * noise, so the fraction is guarded (no 0/0) and clamped into [0, 1]. */
                const real den = phi - plo;
                real fr = pen_sel(den > 0, -plo / den, 0);
                fr = pen_sel(fr > 0, fr, 0);
                fr = pen_sel(fr < 1, fr, 1);
                step = lo + (hi - lo) * fr;
            } else if (p1 < p0 * (real)TTD_PENALTY_EXTEND) {
                /* The full step still descends almost as steeply as t = 0 did: the
                 * curvature along dx is far below the pivot that made the step (a valley
                 * flatter than the eps floor, e.g. nearly parallel edges), and Newton would
                 * crawl along it. The exact line search goes on beyond t = 1: breakpoints
                 * t_i > 1 bracket the root as above; when none has phi' > 0, phi' is linear
                 * beyond the last one (lo) and a probe at 2*lo gives its root. Rare (the
                 * SIMD port runs it when any lane needs it). */
                real lo = 1, plo = p1, hi = 1, phi = 0;
                int found = 0;
#define TTD_PEN_BEYOND(hh, ss)                                                               \
    {                                                                                        \
        const real tb = (hh) / (ss);                                                         \
        const int in = (tb > 1) & (tb <= TTD_REAL_MAX);                                      \
        const real pb = TTD_PEN_SLOPE(tb);                                                   \
        const int to_lo = in & (pb <= 0) & (tb > lo);                                        \
        const int to_hi = in & (pb > 0) & ((!found) | (tb < hi));                            \
        lo = pen_sel(to_lo, tb, lo);                                                \
        plo = pen_sel(to_lo, pb, plo);                                              \
        hi = pen_sel(to_hi, tb, hi);                                                \
        phi = pen_sel(to_hi, pb, phi);                                              \
        found |= to_hi;                                                                      \
    }
                TTD_PEN_BEYOND(h1, s1) TTD_PEN_BEYOND(h2, s2) TTD_PEN_BEYOND(h3, s3)
                TTD_PEN_BEYOND(h4, s4) TTD_PEN_BEYOND(h5, s5) TTD_PEN_BEYOND(h6, s6)
#undef TTD_PEN_BEYOND
                const real t2 = 2 * lo;
                const real p2 = TTD_PEN_SLOPE(t2);
                hi = pen_sel(found, hi, t2);
                phi = pen_sel(found, phi, p2);
                const real den = phi - plo;
                real fr = pen_sel(den > 0, -plo / den, 0);
                fr = pen_sel(fr > 0, fr, 0);
                /* past hi only when hi is the probe (phi' is linear beyond lo) */
                fr = pen_sel((fr < 1) | !found, fr, 1);
                step = lo + (hi - lo) * fr;
                step = pen_sel(step <= TTD_REAL_MAX, step, lo);
            }
#undef TTD_PEN_SLOPE
        }
        const real a_o = a, b_o = b, ca_o = ca, g_o = g, d_o = d, cg_o = cg;
        a -= step * d0;
        b -= step * d1;
        ca += step * (d0 + d1);
        g -= step * d2;
        d -= step * d3;
        cg += step * (d2 + d3);
        /* A small step does not prove convergence while a penalised constraint is being
         * released: in that direction the Newton step is only ~gradient/rho long, and the
         * long step comes one iteration later. So a small step that releases a constraint
         * (h_i >= 0 before, < 0 after) converges only when the step before it was small
         * too (a constraint whose multiplier is ~0 may flip on rounding noise). */
        const int released = ((h1 >= 0) & (h1 + step * d0 < 0)) | ((h2 >= 0) & (h2 + step * d1 < 0)) |
                             ((h3 >= 0) & (h3 - step * (d0 + d1) < 0)) | ((h4 >= 0) & (h4 + step * d2 < 0)) |
                             ((h5 >= 0) & (h5 + step * d3 < 0)) | ((h6 >= 0) & (h6 - step * (d2 + d3) < 0));
        /* A step also counts as small when its effect on the objective is below tol^2 or
         * below rounding of f = |X - Y|^2 (a flat valley: the step is long, the distance does
         * not change). And an iterate the update left unchanged is a fixed point of this
         * iteration (the line search found no decrease along dx): it has converged as far
         * as it can. */
        const real fx = xy0 * xy0 + xy1 * xy1 + xy2 * xy2;
        const int flat = (dec < tol2) | (dec < (real)TTD_PENALTY_FLAT_ULPS * TTD_REAL_EPS * fx);
        const real errc = pen_sel(flat, 0, err2);
        const int stuck = (a == a_o) & (b == b_o) & (ca == ca_o) & (g == g_o) & (d == d_o) & (cg == cg_o);
        const int small_prev = prev_err2 < tol2;
        prev_err2 = errc;
        if (((errc < tol2) & ((!released) | small_prev)) | stuck) {
            converged = 1;
            break;
        }
    }

    real wp[3], wq[3];
    pen_clamp_bary3(ca, a, b, wp);
    pen_clamp_bary3(cg, g, d, wq);
    /* p - q in the frame, from the clamped weights (A = 0). */
    const real xy0 = wp[1] * BA[0] + wp[2] * CA[0] - DA[0] - wq[1] * ED[0] - wq[2] * FD[0];
    const real xy1 = wp[1] * BA[1] + wp[2] * CA[1] - DA[1] - wq[1] * ED[1] - wq[2] * FD[1];
    const real xy2 = wp[1] * BA[2] + wp[2] * CA[2] - DA[2] - wq[1] * ED[2] - wq[2] * FD[2];
    /* |p - q| in the frame (unit size: no overflow), back to the input's scale exactly: by
     * 2^e first, then by 1/pre (2^(e+4) alone can overflow next to REAL_MAX, and 0 * inf
     * would be NaN; a distance beyond REAL_MAX is inf, honestly). */
    const real dist_frame = TTD_SQRT(xy0 * xy0 + xy1 * xy1 + xy2 * xy2);
    pen_finish(s, t, wp, wq, TTD_LDEXP(dist_frame, e - lift) / pre, r);
    r->iterations = (uint16_t)it;
    r->flags = converged ? 0u : (uint32_t)TTD_PAIR_NOT_CONVERGED;
}
