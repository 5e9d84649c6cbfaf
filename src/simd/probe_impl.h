/* SPDX-License-Identifier: MIT */
/* The body of ttd_lanes_probe_<isa>_d/f (simd/probe.h) for the translation unit's ISA and
 * precision: each row file (src/isa/<isa>_<p>.c) exports it under its own name. */
static int lanes_probe(int op, const real *a, const real *b, const real *c, real *out)
{
    const vreal one = vset1((real)1), zero = vzero();
    vreal va = vloadu(a), vb = vloadu(b), vc = vloadu(c), r = zero;
    vreal tr[9];
    const vmask ma = vlt(va, zero), mb = vlt(vb, zero);
    switch (op) {
    case TTDW_OP_ADD: r = va + vb; break;
    case TTDW_OP_SUB: r = va - vb; break;
    case TTDW_OP_MUL: r = va * vb; break;
    case TTDW_OP_DIV: r = va / vb; break;
    case TTDW_OP_NEG: r = -va; break;
    case TTDW_OP_FMA: r = vfma(va, vb, vc); break;
    case TTDW_OP_MIN: r = vmin(va, vb); break;
    case TTDW_OP_MAX: r = vmax(va, vb); break;
    case TTDW_OP_SQRT: r = vsqrt(va); break;
    case TTDW_OP_ABS: r = vabs(va); break;
    case TTDW_OP_POW2: r = vpow2(va); break;
    case TTDW_OP_LT: r = vsel(vlt(va, vb), one, zero); break;
    case TTDW_OP_LE: r = vsel(vle(va, vb), one, zero); break;
    case TTDW_OP_GT: r = vsel(vgt(va, vb), one, zero); break;
    case TTDW_OP_GE: r = vsel(vge(va, vb), one, zero); break;
    case TTDW_OP_EQ: r = vsel(veq(va, vb), one, zero); break;
    case TTDW_OP_SEL: r = vsel(vlt(vc, zero), va, vb); break;
    case TTDW_OP_MAND: r = vsel(mand(ma, mb), one, zero); break;
    case TTDW_OP_MOR: r = vsel(mor(ma, mb), one, zero); break;
    case TTDW_OP_MANDNOT: r = vsel(mandnot(ma, mb), one, zero); break;
    case TTDW_OP_MNOT: r = vsel(mnot(ma), one, zero); break;
    case TTDW_OP_MTRUE: r = vsel(mtrue(), one, zero); break;
    case TTDW_OP_MFIRST: r = vsel(mfirst((int)a[0]), one, zero); break;
    case TTDW_OP_MBITS: vstoreu(out, zero); out[0] = (real)mbits(ma); return TTDW_LANES;
    case TTDW_OP_ANY: vstoreu(out, zero); out[0] = (real)many(ma); return TTDW_LANES;
    case TTDW_OP_NONE: vstoreu(out, zero); out[0] = (real)mnone(ma); return TTDW_LANES;
    case TTDW_OP_SET1: r = vset1(a[0]); break;
    case TTDW_OP_ZERO: r = vzero(); break;
    case TTDW_OP_LOAD_AOS9:
        vload_aos9(a, tr);
        for (int k = 0; k < 9; ++k)
            vstoreu(out + k * TTDW_LANES, tr[k]);
        return TTDW_LANES;
    case TTDW_OP_WIDEN:
#ifdef TTD_PRECISION_FLOAT
    {
        /* x 2^100 x 2^-100 is the identity in double and overflows in float */
        const ttdw_vd up = ttdw_set1_d(0x1p100), down = ttdw_set1_d(0x1p-100);
        vstoreu(out, ttdw_d2f(ttdw_f2d_lo(va) * up * down, ttdw_f2d_hi(va) * up * down));
        return TTDW_LANES;
    }
#else
        return -1;
#endif
    default: return -1;
    }
    vstoreu(out, r);
    return TTDW_LANES;
}
