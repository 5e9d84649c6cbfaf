/* SPDX-License-Identifier: MIT */
/* The body of tests/test_lanes.c for one precision (included after tests/precision_open.h).
 * Every lane operation is run through an ISA's probe (src/simd/probe.h) and compared lane by
 * lane with the same operation in scalar C. The value under test sits in a random lane among
 * random neighbours (SLEEF's tester3 idea), so a lane mix-up or a wrong constant for one lane
 * shows; a second pass fills the neighbours with NaN and infinities and checks that the lane
 * under test does not change. */

typedef int (*TTD_SFX(probe_fn))(int op, const real *a, const real *b, const real *c, real *out);

/* Same value: bit-identical, or both NaN. */
static int TTD_SFX(same)(real x, real y)
{
    if (x != x && y != y)
        return 1;
    return memcmp(&x, &y, sizeof x) == 0;
}

/* Values worth putting in the lane under test. */
static real TTD_SFX(interesting)(uint64_t *st)
{
    const real list[] = {0, -(real)0, 1, -1, (real)0.5, 3, (real)1 / 3, -(real)2.75, TTD_REAL_MIN,
                         TTD_REAL_MIN / 4, -TTD_REAL_MIN / 8, TTD_REAL_MAX, -TTD_REAL_MAX,
                         TTD_REAL_EPS, (real)1e-3, (real)-7e4};
    const unsigned n = (unsigned)(sizeof list / sizeof list[0]);
    const uint64_t r = lanes_rng(st);
    if (r % 3 == 0)
        return list[(r >> 8) % n];
    return (real)lanes_uniform(st, -10.0, 10.0) * TTD_LDEXP((real)1, (int)((r >> 16) % 40) - 20);
}

/* The scalar meaning of one op in lane i (masks as 1/0). */
static real TTD_SFX(scalar_op)(int op, int has_fma, real a, real b, real c, int lane, real a0)
{
    switch (op) {
    case TTDW_OP_ADD: return a + b;
    case TTDW_OP_SUB: return a - b;
    case TTDW_OP_MUL: return a * b;
    case TTDW_OP_DIV: return a / b;
    case TTDW_OP_NEG: return -a;
    case TTDW_OP_FMA: return has_fma ? TTD_FMA(a, b, c) : a * b + c;
    case TTDW_OP_MIN: return a < b ? a : b;
    case TTDW_OP_MAX: return a > b ? a : b;
    case TTDW_OP_SQRT: return TTD_SQRT(a);
    case TTDW_OP_ABS: return TTD_FABS(a);
    case TTDW_OP_POW2: {
        if (!(TTD_FABS(a) >= TTD_REAL_MIN))
            return 0;
        if (TTD_FABS(a) > TTD_REAL_MAX)
            return TTD_FABS(a);
        int e;
        (void)TTD_FREXP(a, &e);
        return TTD_LDEXP((real)1, e - 1);
    }
    case TTDW_OP_LT: return a < b;
    case TTDW_OP_LE: return a <= b;
    case TTDW_OP_GT: return a > b;
    case TTDW_OP_GE: return a >= b;
    case TTDW_OP_EQ: return a == b;
    case TTDW_OP_SEL: return c < 0 ? a : b;
    case TTDW_OP_MAND: return (a < 0) && (b < 0);
    case TTDW_OP_MOR: return (a < 0) || (b < 0);
    case TTDW_OP_MANDNOT: return (a < 0) && !(b < 0);
    case TTDW_OP_MNOT: return !(a < 0);
    case TTDW_OP_MTRUE: return 1;
    case TTDW_OP_MFIRST: return lane < (int)a0;
    case TTDW_OP_SET1: return a0;
    case TTDW_OP_ZERO: return 0;
    default: return 0;
    }
}

/* Ops that work lane by lane, with the input domain each is checked on. */
static const struct { int op; const char *name; int nonneg_a; int no_nan_in; } TTD_SFX(lane_ops)[] = {
    {TTDW_OP_ADD, "add", 0, 0}, {TTDW_OP_SUB, "sub", 0, 0}, {TTDW_OP_MUL, "mul", 0, 0},
    {TTDW_OP_DIV, "div", 0, 0}, {TTDW_OP_NEG, "neg", 0, 0}, {TTDW_OP_FMA, "fma", 0, 0},
    {TTDW_OP_MIN, "min", 0, 1}, {TTDW_OP_MAX, "max", 0, 1}, {TTDW_OP_SQRT, "sqrt", 1, 0},
    {TTDW_OP_ABS, "abs", 0, 0}, {TTDW_OP_POW2, "pow2", 0, 1}, {TTDW_OP_LT, "lt", 0, 0},
    {TTDW_OP_LE, "le", 0, 0}, {TTDW_OP_GT, "gt", 0, 0}, {TTDW_OP_GE, "ge", 0, 0},
    {TTDW_OP_EQ, "eq", 0, 0}, {TTDW_OP_SEL, "sel", 0, 0}, {TTDW_OP_MAND, "mand", 0, 0},
    {TTDW_OP_MOR, "mor", 0, 0}, {TTDW_OP_MANDNOT, "mandnot", 0, 0}, {TTDW_OP_MNOT, "mnot", 0, 0},
    {TTDW_OP_MTRUE, "mtrue", 0, 0}, {TTDW_OP_MFIRST, "mfirst", 0, 1}, {TTDW_OP_SET1, "set1", 0, 1},
    {TTDW_OP_ZERO, "zero", 0, 0},
};

#define LANES_MAXW 16

/* Every lane-by-lane op, `trials` times, value in a random lane; then with NaN/inf neighbours. */
static int TTD_SFX(check_lane_ops)(const char *isa, TTD_SFX(probe_fn) probe, int has_fma, uint64_t *st,
                                   int trials)
{
    real zero1[LANES_MAXW] = {0};
    const int W = probe(TTDW_OP_ZERO, zero1, zero1, zero1, zero1);
    ENSURE_MSG(W >= 1 && W <= LANES_MAXW, "%s: %d lanes", isa, W);
    const int nops = (int)(sizeof TTD_SFX(lane_ops) / sizeof TTD_SFX(lane_ops)[0]);
    for (int o = 0; o < nops; ++o) {
        const int op = TTD_SFX(lane_ops)[o].op;
        for (int trial = 0; trial < trials; ++trial) {
            const int nasty = trial % 4 == 3 && !TTD_SFX(lane_ops)[o].no_nan_in; /* NaN/inf neighbours */
            real a[LANES_MAXW], b[LANES_MAXW], c[LANES_MAXW], out[LANES_MAXW];
            const int L = (int)(lanes_rng(st) % (uint64_t)W);
            for (int i = 0; i < W; ++i) {
                if (nasty && i != L) {
                    const real bad[3] = {(real)NAN, (real)INFINITY, -(real)INFINITY};
                    a[i] = bad[lanes_rng(st) % 3];
                    b[i] = bad[lanes_rng(st) % 3];
                    c[i] = bad[lanes_rng(st) % 3];
                } else {
                    a[i] = TTD_SFX(interesting)(st);
                    b[i] = TTD_SFX(interesting)(st);
                    c[i] = TTD_SFX(interesting)(st);
                }
                if (TTD_SFX(lane_ops)[o].nonneg_a)
                    a[i] = TTD_FABS(a[i]);
            }
            if (op == TTDW_OP_MFIRST || op == TTDW_OP_SET1)
                a[0] = op == TTDW_OP_MFIRST ? (real)(lanes_rng(st) % (uint64_t)(W + 2)) : a[L];
            ENSURE(probe(op, a, b, c, out) == W);
            for (int i = 0; i < W; ++i) {
                if (nasty && i != L)
                    continue;
                const real want = TTD_SFX(scalar_op)(op, has_fma, a[i], b[i], c[i], i, a[0]);
                int ok = TTD_SFX(same)(out[i], want);
                if (op == TTDW_OP_MIN || op == TTDW_OP_MAX) /* +0 vs -0 may come back either way */
                    ok = out[i] == want;
                ENSURE_MSG(ok, "%s %s: lane %d of %d: a=%.9g b=%.9g c=%.9g got %.17g want %.17g",
                           isa, TTD_SFX(lane_ops)[o].name, i, W, (double)a[i], (double)b[i],
                           (double)c[i], (double)out[i], (double)want);
            }
        }
    }
    return 0;
}

/* any/all/none/mbits: cross-lane by design, checked against the bits of every lane. Masks
 * with one lane set or clear (in a random lane) are the interesting ones. */
static int TTD_SFX(check_reductions)(const char *isa, TTD_SFX(probe_fn) probe, uint64_t *st, int trials)
{
    real z[LANES_MAXW] = {0}, out[LANES_MAXW];
    const int W = probe(TTDW_OP_ZERO, z, z, z, out);
    for (int trial = 0; trial < trials; ++trial) {
        real a[LANES_MAXW];
        const int kind = trial % 4, L = (int)(lanes_rng(st) % (uint64_t)W);
        unsigned bits = 0;
        for (int i = 0; i < W; ++i) {
            int neg = kind == 0 ? i == L : kind == 1 ? i != L : kind == 2 ? 0 : (int)(lanes_rng(st) & 1);
            a[i] = neg ? -(real)lanes_uniform(st, 0.5, 2.0) : (real)lanes_uniform(st, 0.0, 2.0);
            bits |= (unsigned)neg << i;
        }
        ENSURE(probe(TTDW_OP_MBITS, a, z, z, out) == W);
        ENSURE_MSG((unsigned)out[0] == bits, "%s mbits: got %u want %u", isa, (unsigned)out[0], bits);
        probe(TTDW_OP_ANY, a, z, z, out);
        ENSURE_MSG((out[0] != 0) == (bits != 0), "%s any: bits %x", isa, bits);
        probe(TTDW_OP_NONE, a, z, z, out);
        ENSURE_MSG((out[0] != 0) == (bits == 0), "%s none: bits %x", isa, bits);
    }
    return 0;
}

/* The transposition, from every misalignment of the source. */
static int TTD_SFX(check_transpose)(const char *isa, TTD_SFX(probe_fn) probe, uint64_t *st)
{
    real z[LANES_MAXW] = {0}, tmp[LANES_MAXW];
    const int W = probe(TTDW_OP_ZERO, z, z, z, tmp);
    real src[9 * LANES_MAXW + 8], out[9 * LANES_MAXW + 8];
    for (int off = 0; off < 8; ++off) {
        real *p = src + off;
        for (int i = 0; i < 9 * W; ++i)
            p[i] = (real)lanes_uniform(st, -1.0, 1.0);
        ENSURE(probe(TTDW_OP_LOAD_AOS9, p, z, z, out + off) == W);
        for (int i = 0; i < W; ++i)
            for (int k = 0; k < 9; ++k)
                ENSURE_MSG(TTD_SFX(same)(out[off + k * W + i], p[9 * i + k]),
                           "%s load_aos9 offset %d: triangle %d coordinate %d", isa, off, i, k);
    }
    return 0;
}

#ifdef TTD_PRECISION_FLOAT
/* f2d_lo/f2d_hi/d2f: every float lane goes to double and comes back in its own lane; the
 * probe multiplies by 2^100 and 2^-100 in between, which would overflow in float. */
static int check_widen_f(const char *isa, TTD_SFX(probe_fn) probe, uint64_t *st)
{
    real z[LANES_MAXW] = {0}, out[LANES_MAXW];
    const int W = probe(TTDW_OP_ZERO, z, z, z, out);
    for (int trial = 0; trial < 200; ++trial) {
        real a[LANES_MAXW];
        for (int i = 0; i < W; ++i)
            a[i] = TTD_SFX(interesting)(st);
        ENSURE(probe(TTDW_OP_WIDEN, a, z, z, out) == W);
        for (int i = 0; i < W; ++i)
            ENSURE_MSG(TTD_SFX(same)(out[i], a[i]), "%s widen: lane %d: %.9g came back as %.9g", isa, i,
                       (double)a[i], (double)out[i]);
    }
    return 0;
}
#endif
