/* SPDX-License-Identifier: MIT */
/* lanes.h on GCC/clang vector extensions, for any target: 4 doubles or 8 floats per vector
 * (32 bytes; the compiler maps them onto whatever vector registers the target has, or onto
 * scalar code). It is the row for machines without a hand-written ISA header, and on x86 and
 * ARM a second implementation of the lane vocabulary that the tests hold to the same contract.
 *
 * Operators on vector_size types are IEEE operations lane by lane, and with -ffp-contract=off
 * they round like the scalar code. Comparisons give integer lanes of -1 / 0 of the element's
 * width; C (unlike C++) has no ?: on vectors, so a select is a bitwise blend. sqrt and the mask
 * reductions are loops over lanes, which compilers turn into vector instructions where the
 * target has them. There is no FMA: ttdw_fma_* rounds twice (as on SSE2). */
#ifndef TTD_SIMD_LANES_PORTABLE_H
#define TTD_SIMD_LANES_PORTABLE_H

#if !defined(__GNUC__)
#error "lanes_portable.h needs GCC or clang vector extensions"
#endif
#include <stdint.h>
#include <string.h>

#define TTDW_LANES_D 4
#define TTDW_LANES_F 8
#define TTDW_HAVE_FMA 0

typedef double ttdw_vd __attribute__((vector_size(32)));
typedef float ttdw_vf __attribute__((vector_size(32)));
typedef int64_t ttdw_md __attribute__((vector_size(32)));
typedef int32_t ttdw_mf __attribute__((vector_size(32)));

/* ---- double ---- */
static inline ttdw_vd ttdw_set1_d(double x) { return (ttdw_vd){x, x, x, x}; }
static inline ttdw_vd ttdw_zero_d(void) { return (ttdw_vd){0, 0, 0, 0}; }
static inline ttdw_vd ttdw_loadu_d(const double *p) { ttdw_vd v; memcpy(&v, p, sizeof v); return v; }
static inline void ttdw_storeu_d(double *p, ttdw_vd v) { memcpy(p, &v, sizeof v); }
static inline ttdw_vd ttdw_fma_d(ttdw_vd a, ttdw_vd b, ttdw_vd c) { return a * b + c; }
static inline ttdw_md ttdw_lt_d(ttdw_vd a, ttdw_vd b) { return (ttdw_md)(a < b); }
static inline ttdw_md ttdw_le_d(ttdw_vd a, ttdw_vd b) { return (ttdw_md)(a <= b); }
static inline ttdw_md ttdw_gt_d(ttdw_vd a, ttdw_vd b) { return (ttdw_md)(a > b); }
static inline ttdw_md ttdw_ge_d(ttdw_vd a, ttdw_vd b) { return (ttdw_md)(a >= b); }
static inline ttdw_md ttdw_eq_d(ttdw_vd a, ttdw_vd b) { return (ttdw_md)(a == b); }
static inline ttdw_vd ttdw_sel_d(ttdw_md m, ttdw_vd a, ttdw_vd b) { return (ttdw_vd)(((ttdw_md)a & m) | ((ttdw_md)b & ~m)); }
/* x86's min/max: the second operand unless the comparison holds (the kernels rely on it) */
static inline ttdw_vd ttdw_min_d(ttdw_vd a, ttdw_vd b) { return ttdw_sel_d(ttdw_lt_d(a, b), a, b); }
static inline ttdw_vd ttdw_max_d(ttdw_vd a, ttdw_vd b) { return ttdw_sel_d(ttdw_gt_d(a, b), a, b); }
static inline ttdw_vd ttdw_sqrt_d(ttdw_vd a)
{
    for (int i = 0; i < TTDW_LANES_D; ++i)
        a[i] = __builtin_sqrt(a[i]);
    return a;
}
static inline ttdw_vd ttdw_abs_d(ttdw_vd a) { return (ttdw_vd)((ttdw_md)a & INT64_MAX); }
static inline ttdw_vd ttdw_pow2_d(ttdw_vd a) { return (ttdw_vd)((ttdw_md)a & 0x7FF0000000000000LL); }
static inline ttdw_md ttdw_mand_d(ttdw_md a, ttdw_md b) { return a & b; }
static inline ttdw_md ttdw_mor_d(ttdw_md a, ttdw_md b) { return a | b; }
static inline ttdw_md ttdw_mandnot_d(ttdw_md a, ttdw_md b) { return a & ~b; }
static inline ttdw_md ttdw_mtrue_d(void) { return (ttdw_md){-1, -1, -1, -1}; }
static inline ttdw_md ttdw_mnot_d(ttdw_md a) { return ~a; }
static inline ttdw_md ttdw_mfirst_d(int k) { return (ttdw_md)((ttdw_vd){0, 1, 2, 3} < (double)k); }
static inline unsigned ttdw_mbits_d(ttdw_md m)
{
    unsigned bits = 0;
    for (int i = 0; i < TTDW_LANES_D; ++i)
        bits |= (m[i] != 0) ? 1u << i : 0u;
    return bits;
}
static inline int ttdw_any_d(ttdw_md m) { return ttdw_mbits_d(m) != 0u; }

/* ---- float ---- */
static inline ttdw_vf ttdw_set1_f(float x) { return (ttdw_vf){x, x, x, x, x, x, x, x}; }
static inline ttdw_vf ttdw_zero_f(void) { return (ttdw_vf){0, 0, 0, 0, 0, 0, 0, 0}; }
static inline ttdw_vf ttdw_loadu_f(const float *p) { ttdw_vf v; memcpy(&v, p, sizeof v); return v; }
static inline void ttdw_storeu_f(float *p, ttdw_vf v) { memcpy(p, &v, sizeof v); }
static inline ttdw_vf ttdw_fma_f(ttdw_vf a, ttdw_vf b, ttdw_vf c) { return a * b + c; }
static inline ttdw_mf ttdw_lt_f(ttdw_vf a, ttdw_vf b) { return (ttdw_mf)(a < b); }
static inline ttdw_mf ttdw_le_f(ttdw_vf a, ttdw_vf b) { return (ttdw_mf)(a <= b); }
static inline ttdw_mf ttdw_gt_f(ttdw_vf a, ttdw_vf b) { return (ttdw_mf)(a > b); }
static inline ttdw_mf ttdw_ge_f(ttdw_vf a, ttdw_vf b) { return (ttdw_mf)(a >= b); }
static inline ttdw_mf ttdw_eq_f(ttdw_vf a, ttdw_vf b) { return (ttdw_mf)(a == b); }
static inline ttdw_vf ttdw_sel_f(ttdw_mf m, ttdw_vf a, ttdw_vf b) { return (ttdw_vf)(((ttdw_mf)a & m) | ((ttdw_mf)b & ~m)); }
static inline ttdw_vf ttdw_min_f(ttdw_vf a, ttdw_vf b) { return ttdw_sel_f(ttdw_lt_f(a, b), a, b); }
static inline ttdw_vf ttdw_max_f(ttdw_vf a, ttdw_vf b) { return ttdw_sel_f(ttdw_gt_f(a, b), a, b); }
static inline ttdw_vf ttdw_sqrt_f(ttdw_vf a)
{
    for (int i = 0; i < TTDW_LANES_F; ++i)
        a[i] = __builtin_sqrtf(a[i]);
    return a;
}
static inline ttdw_vf ttdw_abs_f(ttdw_vf a) { return (ttdw_vf)((ttdw_mf)a & INT32_MAX); }
static inline ttdw_vf ttdw_pow2_f(ttdw_vf a) { return (ttdw_vf)((ttdw_mf)a & 0x7F800000); }
static inline ttdw_mf ttdw_mand_f(ttdw_mf a, ttdw_mf b) { return a & b; }
static inline ttdw_mf ttdw_mor_f(ttdw_mf a, ttdw_mf b) { return a | b; }
static inline ttdw_mf ttdw_mandnot_f(ttdw_mf a, ttdw_mf b) { return a & ~b; }
static inline ttdw_mf ttdw_mtrue_f(void) { return (ttdw_mf){-1, -1, -1, -1, -1, -1, -1, -1}; }
static inline ttdw_mf ttdw_mnot_f(ttdw_mf a) { return ~a; }
static inline ttdw_mf ttdw_mfirst_f(int k) { return (ttdw_mf)((ttdw_vf){0, 1, 2, 3, 4, 5, 6, 7} < (float)k); }
static inline unsigned ttdw_mbits_f(ttdw_mf m)
{
    unsigned bits = 0;
    for (int i = 0; i < TTDW_LANES_F; ++i)
        bits |= (m[i] != 0) ? 1u << i : 0u;
    return bits;
}
static inline int ttdw_any_f(ttdw_mf m) { return ttdw_mbits_f(m) != 0u; }

/* ---- precision conversion (float lanes = 2 x double lanes) ---- */
static inline ttdw_vd ttdw_f2d_lo(ttdw_vf a) { return (ttdw_vd){(double)a[0], (double)a[1], (double)a[2], (double)a[3]}; }
static inline ttdw_vd ttdw_f2d_hi(ttdw_vf a) { return (ttdw_vd){(double)a[4], (double)a[5], (double)a[6], (double)a[7]}; }
static inline ttdw_vf ttdw_d2f(ttdw_vd lo, ttdw_vd hi)
{
    return (ttdw_vf){(float)lo[0], (float)lo[1], (float)lo[2], (float)lo[3],
                     (float)hi[0], (float)hi[1], (float)hi[2], (float)hi[3]};
}

#endif /* TTD_SIMD_LANES_PORTABLE_H */
