/* SPDX-License-Identifier: MIT */
/* What every lane kernel shares, precision-generic (included once per precision after
 * simd/lanes_precision.h): reading a group of W pairs from the user's layout (tails padded
 * with a harmless pair), the |v| of a 3-vector with the scalar code's power-of-two scaling,
 * and writing a group's outputs back to the caller's arrays (only live lanes).
 *
 * W below is TTDW_LANES (lanes per vector in this precision). */

/* A harmless pair for the lanes past the end of a block: two unit right triangles one apart
 * in z. Every method converges on it in a few iterations, and its outputs are never stored.
 * A one-lane row (lanes_cuda.h) has no tail, hence no padding (and no file-scope data, which
 * device code could not read). */
#if TTDW_LANES > 1
static const real kw_pad_s[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
static const real kw_pad_t[9] = {0, 0, 1, 1, 0, 1, 0, 1, 1};
#endif

/* S[k], T[k] lane i = coordinate k of pair i of the group starting at s, t; live pairs are
 * 1..W. Full groups are transposed straight from the caller's arrays. */
TTDW_FN void kw_load_group(const real *s, const real *t, int live, vreal S[9], vreal T[9])
{
    if (live == TTDW_LANES) {
        vload_aos9(s, S);
        vload_aos9(t, T);
        return;
    }
#if TTDW_LANES > 1
    real bs[9 * TTDW_LANES], bt[9 * TTDW_LANES];
    for (int i = 0; i < TTDW_LANES; ++i)
        for (int k = 0; k < 9; ++k) {
            bs[9 * i + k] = i < live ? s[9 * i + k] : kw_pad_s[k];
            bt[9 * i + k] = i < live ? t[9 * i + k] : kw_pad_t[k];
        }
    vload_aos9(bs, S);
    vload_aos9(bt, T);
#endif
}

/* |(x, y, z)| as scalar/penalty_impl.h's pen_norm3: divide by 2^e, where m = max|.| =
 * f 2^e with f in [0.5, 1) (frexp), take the root, multiply back. 2^(e-1) is m with its
 * mantissa bits cleared; the divisions and products by it are exact except where a result
 * is subnormal, which only touches components whose squares vanish anyway (and distances
 * below REAL_MIN). m = 0 and m = inf come back unchanged, as in the scalar code. */
TTDW_FN vreal kw_norm3(vreal x, vreal y, vreal z)
{
    const vreal zero = vzero();
    vreal ax = vabs(x), ay = vabs(y), az = vabs(z);
    vreal m = ax;
    m = vsel(vgt(ay, m), ay, m);
    m = vsel(vgt(az, m), az, m);
    /* subnormal m: lift by 2^(mantissa bits + 2) first, so that m has an exponent field */
    const vmask tiny = vlt(m, vset1(TTD_REAL_MIN));
#ifdef TTD_PRECISION_DOUBLE
    const real lift = 0x1p54, unlift = 0x1p-54;
#else
    const real lift = 0x1p25f, unlift = 0x1p-25f;
#endif
    const vreal up = vsel(tiny, vset1(lift), vset1((real)1));
    x = x * up;
    y = y * up;
    z = z * up;
    vreal mm = m * up;
    /* half = 2^(e-1): keep the exponent bits of mm (and with +inf's bit pattern) */
    const vreal half = vpow2(mm);
    const vreal inv = vset1((real)0.5) / half; /* 2^-e, exact: a power of two in range */
    x = x * inv;
    y = y * inv;
    z = z * inv;
    vreal r = vsqrt(x * x + y * y + z * z);
    r = r * half * vset1((real)2);
    r = r * vsel(tiny, vset1(unlift), vset1((real)1));
    const vmask special = mor(veq(m, zero), vgt(m, vset1(TTD_REAL_MAX)));
    return vsel(special, m, r);
}

/* The outputs of one group, lane by lane, before they are written to the caller's arrays. */
typedef struct kw_out {
    vreal distance;
    vreal p[3], q[3];
    vreal bary_p[3], bary_q[3];
    vreal iterations;       /* a small integer, exact in either precision */
    unsigned flags_nc;      /* lane bits: TTD_PAIR_NOT_CONVERGED */
    unsigned flags_int;     /* lane bits: TTD_PAIR_INTERSECTING */
    unsigned flags_ds;      /* lane bits: TTD_PAIR_DEGENERATE_S */
    unsigned flags_dt;      /* lane bits: TTD_PAIR_DEGENERATE_T */
} kw_out;

/* Writes the first `live` lanes of d to distance[0..live). */
TTDW_FN void kw_store_distance(vreal d, int live, real *distance)
{
    if (live == TTDW_LANES) {
        vstoreu(distance, d);
        return;
    }
    real buf[TTDW_LANES];
    vstoreu(buf, d);
    for (int i = 0; i < live; ++i)
        distance[i] = buf[i];
}

/* Writes the first `live` lanes of o's points (p then q, 6 reals a pair) to points and, when
 * distance is not NULL, its distances to distance. */
TTDW_FN void kw_store_points(const kw_out *o, int live, real *distance, real *points)
{
    real buf[6][TTDW_LANES] TTDW_ALIGN(64);
    for (int k = 0; k < 3; ++k) {
        vstoreu(buf[k], o->p[k]);
        vstoreu(buf[3 + k], o->q[k]);
    }
    for (int i = 0; i < live; ++i)
        for (int k = 0; k < 6; ++k)
            points[6 * i + k] = buf[k][i];
    if (distance)
        kw_store_distance(o->distance, live, distance);
}

/* kw_store_points with lane i's outputs at index idx[i] of points (6 reals an index) and, when
 * not NULL, of distance. */
TTDW_FN void kw_store_points_at(const kw_out *o, int live, const size_t *idx, real *distance, real *points)
{
    real buf[7][TTDW_LANES] TTDW_ALIGN(64);
    for (int k = 0; k < 3; ++k) {
        vstoreu(buf[k], o->p[k]);
        vstoreu(buf[3 + k], o->q[k]);
    }
    vstoreu(buf[6], o->distance);
    for (int i = 0; i < live; ++i) {
        real *pt = points + 6 * idx[i];
        for (int k = 0; k < 6; ++k)
            pt[k] = buf[k][i];
        if (distance)
            distance[idx[i]] = buf[6][i];
    }
}

/* Writes the first `live` lanes of o to the outputs out names, at pair offset i0: distances,
 * points (p then q, 6 reals a pair) and results. feature bits follow the scalar code: bit i
 * when weight i > 0. */
TTDW_FN void kw_store_group(const kw_out *o, int live, const ttd_out *out, size_t i0)
{
    ttd_result *results = out->results ? out->results + i0 : NULL;
    if (out->points)
        kw_store_points(o, live, NULL, out->points + 6 * i0);
    if (out->distance)
        kw_store_distance(o->distance, live, out->distance + i0);
    if (!results)
        return;
    real buf[14][TTDW_LANES] TTDW_ALIGN(64);
    vstoreu(buf[0], o->distance);
    for (int k = 0; k < 3; ++k) {
        vstoreu(buf[1 + k], o->p[k]);
        vstoreu(buf[4 + k], o->q[k]);
        vstoreu(buf[7 + k], o->bary_p[k]);
        vstoreu(buf[10 + k], o->bary_q[k]);
    }
    vstoreu(buf[13], o->iterations);
    const vreal zero = vzero();
    const unsigned fp0 = mbits(vgt(o->bary_p[0], zero)), fp1 = mbits(vgt(o->bary_p[1], zero));
    const unsigned fp2 = mbits(vgt(o->bary_p[2], zero)), fq0 = mbits(vgt(o->bary_q[0], zero));
    const unsigned fq1 = mbits(vgt(o->bary_q[1], zero)), fq2 = mbits(vgt(o->bary_q[2], zero));
    for (int i = 0; i < live; ++i) {
        ttd_result *r = &results[i];
        r->distance = buf[0][i];
        for (int k = 0; k < 3; ++k) {
            r->p[k] = buf[1 + k][i];
            r->q[k] = buf[4 + k][i];
            r->bary_p[k] = buf[7 + k][i];
            r->bary_q[k] = buf[10 + k][i];
        }
        r->iterations = (uint16_t)buf[13][i];
        r->flags = (((o->flags_nc >> i) & 1u) ? (uint32_t)TTD_PAIR_NOT_CONVERGED : 0u) |
                   (((o->flags_int >> i) & 1u) ? (uint32_t)TTD_PAIR_INTERSECTING : 0u) |
                   (((o->flags_ds >> i) & 1u) ? (uint32_t)TTD_PAIR_DEGENERATE_S : 0u) |
                   (((o->flags_dt >> i) & 1u) ? (uint32_t)TTD_PAIR_DEGENERATE_T : 0u);
        r->feature_p = (uint8_t)(((fp0 >> i) & 1u) | (((fp1 >> i) & 1u) << 1) | (((fp2 >> i) & 1u) << 2));
        r->feature_q = (uint8_t)(((fq0 >> i) & 1u) | (((fq1 >> i) & 1u) << 1) | (((fq2 >> i) & 1u) << 2));
    }
}
