/* SPDX-License-Identifier: MIT */
/* lanes.h for CUDA: one lane per thread. A "vector" is one real (ttdw_vd = double, ttdw_vf =
 * float), a mask one bool; the warp is the SIMD machine, and a kernel's per-lane code is what
 * each thread runs for its own pair. The same header, compiled by the host C compiler, is a
 * valid 1-lane row (tests/cuda_host_d.c, _f.c): that is how CI, which has no GPU and may have
 * no nvcc, tests the device source (docs/gpu.md).
 *
 * Every function is TTDW_FN: `__host__ __device__ inline` under nvcc, `static inline` in C.
 * Every operation is the one the CPU rows compute, rounded once, so that a thread's result is
 * the scalar row's to the bit:
 *  - + - * / and sqrt are IEEE-correctly rounded on both sides: the device code is compiled
 *    with -fmad=false (no contraction of a*b+c), -prec-div=true, -prec-sqrt=true and
 *    -ftz=false (subnormals kept), the host code with -ffp-contract=off;
 *  - vfma is fma(): one rounding, so TTDW_HAVE_FMA = 1 and the exact kernel's compensated
 *    products (kx_prod_err) take their FMA path, which gives the same bits as Dekker's split by
 *    construction (both are the exact error);
 *  - select is the conditional m ? a : b on a bool (selp on the device, no branch), and min,
 *    max are the x86 expressions a < b ? a : b, a > b ? a : b written as such (not fmin/fmax,
 *    which differ on signed zeros);
 *  - abs and pow2 clear bits (fabs; the exponent mask on the bit pattern).
 * Masks are bools, so mbits is bit 0 only and mfirst(k) is k > 0.
 *
 * One exception to lanes.h's contract: W_f = W_d = 1 here, not W_f = 2 W_d. f2d_lo widens the
 * one lane, f2d_hi returns the same (its results are computed and dropped: d2f(lo, hi) narrows
 * lo alone), so the kernels' two-halves code runs one real half. */
#ifndef TTD_SIMD_LANES_CUDA_H
#define TTD_SIMD_LANES_CUDA_H

#include <math.h>
#include <stdint.h>
#include <string.h>
#ifndef __cplusplus
#include <stdbool.h>
#endif

#define TTDW_LANES_D 1
#define TTDW_LANES_F 1
#define TTDW_HAVE_FMA 1

typedef double ttdw_vd;
typedef float ttdw_vf;
typedef bool ttdw_md;
typedef bool ttdw_mf;

/* The bit pattern of a real and back (memcpy: exact in C; nvcc makes it a register move). */
TTDW_FN uint64_t ttdw_cuda_bits_d(double x)
{
    uint64_t u;
    memcpy(&u, &x, sizeof u);
    return u;
}
TTDW_FN double ttdw_cuda_real_d(uint64_t u)
{
    double x;
    memcpy(&x, &u, sizeof x);
    return x;
}
TTDW_FN uint32_t ttdw_cuda_bits_f(float x)
{
    uint32_t u;
    memcpy(&u, &x, sizeof u);
    return u;
}
TTDW_FN float ttdw_cuda_real_f(uint32_t u)
{
    float x;
    memcpy(&x, &u, sizeof x);
    return x;
}

/* ---- double ---- */
TTDW_FN ttdw_vd ttdw_set1_d(double x) { return x; }
TTDW_FN ttdw_vd ttdw_zero_d(void) { return 0.0; }
TTDW_FN ttdw_vd ttdw_loadu_d(const double *p) { return *p; }
TTDW_FN void ttdw_storeu_d(double *p, ttdw_vd v) { *p = v; }
TTDW_FN ttdw_vd ttdw_fma_d(ttdw_vd a, ttdw_vd b, ttdw_vd c) { return fma(a, b, c); }
TTDW_FN ttdw_md ttdw_lt_d(ttdw_vd a, ttdw_vd b) { return a < b; }
TTDW_FN ttdw_md ttdw_le_d(ttdw_vd a, ttdw_vd b) { return a <= b; }
TTDW_FN ttdw_md ttdw_gt_d(ttdw_vd a, ttdw_vd b) { return a > b; }
TTDW_FN ttdw_md ttdw_ge_d(ttdw_vd a, ttdw_vd b) { return a >= b; }
TTDW_FN ttdw_md ttdw_eq_d(ttdw_vd a, ttdw_vd b) { return a == b; }
TTDW_FN ttdw_vd ttdw_sel_d(ttdw_md m, ttdw_vd a, ttdw_vd b) { return m ? a : b; }
/* x86's min/max: the second operand unless the comparison holds (the kernels rely on it) */
TTDW_FN ttdw_vd ttdw_min_d(ttdw_vd a, ttdw_vd b) { return a < b ? a : b; }
TTDW_FN ttdw_vd ttdw_max_d(ttdw_vd a, ttdw_vd b) { return a > b ? a : b; }
TTDW_FN ttdw_vd ttdw_sqrt_d(ttdw_vd a) { return sqrt(a); }
TTDW_FN ttdw_vd ttdw_abs_d(ttdw_vd a) { return fabs(a); }
TTDW_FN ttdw_vd ttdw_pow2_d(ttdw_vd a) { return ttdw_cuda_real_d(ttdw_cuda_bits_d(a) & UINT64_C(0x7FF0000000000000)); }
TTDW_FN ttdw_md ttdw_mand_d(ttdw_md a, ttdw_md b) { return a && b; }
TTDW_FN ttdw_md ttdw_mor_d(ttdw_md a, ttdw_md b) { return a || b; }
TTDW_FN ttdw_md ttdw_mandnot_d(ttdw_md a, ttdw_md b) { return a && !b; }
TTDW_FN ttdw_md ttdw_mtrue_d(void) { return true; }
TTDW_FN ttdw_md ttdw_mnot_d(ttdw_md a) { return !a; }
TTDW_FN ttdw_md ttdw_mfirst_d(int k) { return k > 0; }
TTDW_FN unsigned ttdw_mbits_d(ttdw_md m) { return m ? 1u : 0u; }
TTDW_FN int ttdw_any_d(ttdw_md m) { return m ? 1 : 0; }

/* ---- float ---- */
TTDW_FN ttdw_vf ttdw_set1_f(float x) { return x; }
TTDW_FN ttdw_vf ttdw_zero_f(void) { return 0.0f; }
TTDW_FN ttdw_vf ttdw_loadu_f(const float *p) { return *p; }
TTDW_FN void ttdw_storeu_f(float *p, ttdw_vf v) { *p = v; }
TTDW_FN ttdw_vf ttdw_fma_f(ttdw_vf a, ttdw_vf b, ttdw_vf c) { return fmaf(a, b, c); }
TTDW_FN ttdw_mf ttdw_lt_f(ttdw_vf a, ttdw_vf b) { return a < b; }
TTDW_FN ttdw_mf ttdw_le_f(ttdw_vf a, ttdw_vf b) { return a <= b; }
TTDW_FN ttdw_mf ttdw_gt_f(ttdw_vf a, ttdw_vf b) { return a > b; }
TTDW_FN ttdw_mf ttdw_ge_f(ttdw_vf a, ttdw_vf b) { return a >= b; }
TTDW_FN ttdw_mf ttdw_eq_f(ttdw_vf a, ttdw_vf b) { return a == b; }
TTDW_FN ttdw_vf ttdw_sel_f(ttdw_mf m, ttdw_vf a, ttdw_vf b) { return m ? a : b; }
TTDW_FN ttdw_vf ttdw_min_f(ttdw_vf a, ttdw_vf b) { return a < b ? a : b; }
TTDW_FN ttdw_vf ttdw_max_f(ttdw_vf a, ttdw_vf b) { return a > b ? a : b; }
TTDW_FN ttdw_vf ttdw_sqrt_f(ttdw_vf a) { return sqrtf(a); }
TTDW_FN ttdw_vf ttdw_abs_f(ttdw_vf a) { return fabsf(a); }
TTDW_FN ttdw_vf ttdw_pow2_f(ttdw_vf a) { return ttdw_cuda_real_f(ttdw_cuda_bits_f(a) & UINT32_C(0x7F800000)); }
TTDW_FN ttdw_mf ttdw_mand_f(ttdw_mf a, ttdw_mf b) { return a && b; }
TTDW_FN ttdw_mf ttdw_mor_f(ttdw_mf a, ttdw_mf b) { return a || b; }
TTDW_FN ttdw_mf ttdw_mandnot_f(ttdw_mf a, ttdw_mf b) { return a && !b; }
TTDW_FN ttdw_mf ttdw_mtrue_f(void) { return true; }
TTDW_FN ttdw_mf ttdw_mnot_f(ttdw_mf a) { return !a; }
TTDW_FN ttdw_mf ttdw_mfirst_f(int k) { return k > 0; }
TTDW_FN unsigned ttdw_mbits_f(ttdw_mf m) { return m ? 1u : 0u; }
TTDW_FN int ttdw_any_f(ttdw_mf m) { return m ? 1 : 0; }

/* ---- precision conversion (one lane each: see the note at the top) ---- */
TTDW_FN ttdw_vd ttdw_f2d_lo(ttdw_vf a) { return (double)a; }
TTDW_FN ttdw_vd ttdw_f2d_hi(ttdw_vf a) { return (double)a; }
TTDW_FN ttdw_vf ttdw_d2f(ttdw_vd lo, ttdw_vd hi)
{
    (void)hi;
    return (float)lo;
}

/* the transposition of one triangle: out[k] = p[k] */
#define TTDW_HAVE_LOAD_AOS9_D 1
#define TTDW_HAVE_LOAD_AOS9_F 1
TTDW_FN void ttdw_load_aos9_d(const double *p, ttdw_vd out[9])
{
    for (int k = 0; k < 9; ++k)
        out[k] = p[k];
}
TTDW_FN void ttdw_load_aos9_f(const float *p, ttdw_vf out[9])
{
    for (int k = 0; k < 9; ++k)
        out[k] = p[k];
}

#endif /* TTD_SIMD_LANES_CUDA_H */
