/* SPDX-License-Identifier: MIT */
/* lanes.h on AVX-512F/DQ: 8 doubles or 16 floats per vector; masks are k-registers
 * (__mmask8 / __mmask16), so a select is one vblendm and any/all are a kortest. The
 * transposition is an 8x8 transpose in registers (float: two of them side by side, one per
 * 256-bit half) plus a gather for the ninth coordinate. */
#ifndef TTD_SIMD_LANES_AVX512_H
#define TTD_SIMD_LANES_AVX512_H

#if !defined(__AVX512F__) || !defined(__AVX512DQ__)
#error "lanes_avx512.h needs -mavx512f -mavx512dq"
#endif
#include <immintrin.h>

#define TTDW_LANES_D 8
#define TTDW_LANES_F 16
#define TTDW_HAVE_FMA 1

typedef __m512d ttdw_vd;
typedef __m512 ttdw_vf;
typedef __mmask8 ttdw_md;
typedef __mmask16 ttdw_mf;

/* ---- double ---- */
static inline ttdw_vd ttdw_set1_d(double x) { return _mm512_set1_pd(x); }
static inline ttdw_vd ttdw_zero_d(void) { return _mm512_setzero_pd(); }
static inline ttdw_vd ttdw_loadu_d(const double *p) { return _mm512_loadu_pd(p); }
static inline void ttdw_storeu_d(double *p, ttdw_vd v) { _mm512_storeu_pd(p, v); }
static inline ttdw_vd ttdw_fma_d(ttdw_vd a, ttdw_vd b, ttdw_vd c) { return _mm512_fmadd_pd(a, b, c); }
static inline ttdw_vd ttdw_min_d(ttdw_vd a, ttdw_vd b) { return _mm512_min_pd(a, b); }
static inline ttdw_vd ttdw_max_d(ttdw_vd a, ttdw_vd b) { return _mm512_max_pd(a, b); }
static inline ttdw_vd ttdw_sqrt_d(ttdw_vd a) { return _mm512_sqrt_pd(a); }
static inline ttdw_vd ttdw_abs_d(ttdw_vd a) { return _mm512_abs_pd(a); }
static inline ttdw_vd ttdw_pow2_d(ttdw_vd a) { return _mm512_and_pd(a, _mm512_castsi512_pd(_mm512_set1_epi64(0x7FF0000000000000LL))); }
static inline ttdw_md ttdw_lt_d(ttdw_vd a, ttdw_vd b) { return _mm512_cmp_pd_mask(a, b, _CMP_LT_OQ); }
static inline ttdw_md ttdw_le_d(ttdw_vd a, ttdw_vd b) { return _mm512_cmp_pd_mask(a, b, _CMP_LE_OQ); }
static inline ttdw_md ttdw_gt_d(ttdw_vd a, ttdw_vd b) { return _mm512_cmp_pd_mask(a, b, _CMP_GT_OQ); }
static inline ttdw_md ttdw_ge_d(ttdw_vd a, ttdw_vd b) { return _mm512_cmp_pd_mask(a, b, _CMP_GE_OQ); }
static inline ttdw_md ttdw_eq_d(ttdw_vd a, ttdw_vd b) { return _mm512_cmp_pd_mask(a, b, _CMP_EQ_OQ); }
static inline ttdw_vd ttdw_sel_d(ttdw_md m, ttdw_vd a, ttdw_vd b) { return _mm512_mask_blend_pd(m, b, a); }
static inline ttdw_md ttdw_mand_d(ttdw_md a, ttdw_md b) { return (ttdw_md)(a & b); }
static inline ttdw_md ttdw_mor_d(ttdw_md a, ttdw_md b) { return (ttdw_md)(a | b); }
static inline ttdw_md ttdw_mandnot_d(ttdw_md a, ttdw_md b) { return (ttdw_md)(a & ~b); }
static inline ttdw_md ttdw_mtrue_d(void) { return (ttdw_md)0xFFu; }
static inline ttdw_md ttdw_mnot_d(ttdw_md a) { return (ttdw_md)~a; }
static inline ttdw_md ttdw_mfirst_d(int k) { return k <= 0 ? (ttdw_md)0 : k >= 8 ? (ttdw_md)0xFFu : (ttdw_md)((1u << k) - 1u); }
static inline unsigned ttdw_mbits_d(ttdw_md m) { return (unsigned)m; }
static inline int ttdw_any_d(ttdw_md m) { return m != 0; }

/* ---- float ---- */
static inline ttdw_vf ttdw_set1_f(float x) { return _mm512_set1_ps(x); }
static inline ttdw_vf ttdw_zero_f(void) { return _mm512_setzero_ps(); }
static inline ttdw_vf ttdw_loadu_f(const float *p) { return _mm512_loadu_ps(p); }
static inline void ttdw_storeu_f(float *p, ttdw_vf v) { _mm512_storeu_ps(p, v); }
static inline ttdw_vf ttdw_fma_f(ttdw_vf a, ttdw_vf b, ttdw_vf c) { return _mm512_fmadd_ps(a, b, c); }
static inline ttdw_vf ttdw_min_f(ttdw_vf a, ttdw_vf b) { return _mm512_min_ps(a, b); }
static inline ttdw_vf ttdw_max_f(ttdw_vf a, ttdw_vf b) { return _mm512_max_ps(a, b); }
static inline ttdw_vf ttdw_sqrt_f(ttdw_vf a) { return _mm512_sqrt_ps(a); }
static inline ttdw_vf ttdw_abs_f(ttdw_vf a) { return _mm512_abs_ps(a); }
static inline ttdw_vf ttdw_pow2_f(ttdw_vf a) { return _mm512_and_ps(a, _mm512_castsi512_ps(_mm512_set1_epi32(0x7F800000))); }
static inline ttdw_mf ttdw_lt_f(ttdw_vf a, ttdw_vf b) { return _mm512_cmp_ps_mask(a, b, _CMP_LT_OQ); }
static inline ttdw_mf ttdw_le_f(ttdw_vf a, ttdw_vf b) { return _mm512_cmp_ps_mask(a, b, _CMP_LE_OQ); }
static inline ttdw_mf ttdw_gt_f(ttdw_vf a, ttdw_vf b) { return _mm512_cmp_ps_mask(a, b, _CMP_GT_OQ); }
static inline ttdw_mf ttdw_ge_f(ttdw_vf a, ttdw_vf b) { return _mm512_cmp_ps_mask(a, b, _CMP_GE_OQ); }
static inline ttdw_mf ttdw_eq_f(ttdw_vf a, ttdw_vf b) { return _mm512_cmp_ps_mask(a, b, _CMP_EQ_OQ); }
static inline ttdw_vf ttdw_sel_f(ttdw_mf m, ttdw_vf a, ttdw_vf b) { return _mm512_mask_blend_ps(m, b, a); }
static inline ttdw_mf ttdw_mand_f(ttdw_mf a, ttdw_mf b) { return (ttdw_mf)(a & b); }
static inline ttdw_mf ttdw_mor_f(ttdw_mf a, ttdw_mf b) { return (ttdw_mf)(a | b); }
static inline ttdw_mf ttdw_mandnot_f(ttdw_mf a, ttdw_mf b) { return (ttdw_mf)(a & ~b); }
static inline ttdw_mf ttdw_mtrue_f(void) { return (ttdw_mf)0xFFFFu; }
static inline ttdw_mf ttdw_mnot_f(ttdw_mf a) { return (ttdw_mf)~a; }
static inline ttdw_mf ttdw_mfirst_f(int k) { return k <= 0 ? (ttdw_mf)0 : k >= 16 ? (ttdw_mf)0xFFFFu : (ttdw_mf)((1u << k) - 1u); }
static inline unsigned ttdw_mbits_f(ttdw_mf m) { return (unsigned)m; }
static inline int ttdw_any_f(ttdw_mf m) { return m != 0; }

/* ---- precision conversion (float lanes = 2 x double lanes) ---- */
static inline ttdw_vd ttdw_f2d_lo(ttdw_vf a) { return _mm512_cvtps_pd(_mm512_castps512_ps256(a)); }
static inline ttdw_vd ttdw_f2d_hi(ttdw_vf a) { return _mm512_cvtps_pd(_mm512_extractf32x8_ps(a, 1)); }
static inline ttdw_vf ttdw_d2f(ttdw_vd lo, ttdw_vd hi)
{
    return _mm512_insertf32x8(_mm512_castps256_ps512(_mm512_cvtpd_ps(lo)), _mm512_cvtpd_ps(hi), 1);
}

/* ---- transposition ---- */
/* Forced inline: gcc 12 keeps these two out of line in the exact kernel (too big to inline by
 * its heuristics). The call then passes 9 zmm through the stack, with a vzeroupper each way,
 * and the exact float kernel ran at 15 or at 23-25 ns per pair depending on unrelated code
 * changes (docs/simd.md 7.1a). Inlined, it stays at 15. */
#define TTDW_HAVE_LOAD_AOS9_D 1
static inline __attribute__((always_inline)) void ttdw_load_aos9_d(const double *p, ttdw_vd out[9])
{
    __m512d r[8], t[8], u[8];
    for (int i = 0; i < 8; ++i)
        r[i] = _mm512_loadu_pd(p + 9 * i); /* coordinates 0-7 of triangle i */
    for (int i = 0; i < 8; i += 2) {
        t[i] = _mm512_unpacklo_pd(r[i], r[i + 1]);     /* coordinates 0 2 4 6 of rows i, i+1 */
        t[i + 1] = _mm512_unpackhi_pd(r[i], r[i + 1]); /* coordinates 1 3 5 7 */
    }
    const __m512i even = _mm512_setr_epi64(0, 1, 8, 9, 4, 5, 12, 13);
    const __m512i odd = _mm512_setr_epi64(2, 3, 10, 11, 6, 7, 14, 15);
    for (int i = 0; i < 8; i += 4) {
        u[i + 0] = _mm512_permutex2var_pd(t[i], even, t[i + 2]);    /* coordinates 0 | 4 of 4 rows */
        u[i + 1] = _mm512_permutex2var_pd(t[i], odd, t[i + 2]);     /* 2 | 6 */
        u[i + 2] = _mm512_permutex2var_pd(t[i + 1], even, t[i + 3]); /* 1 | 5 */
        u[i + 3] = _mm512_permutex2var_pd(t[i + 1], odd, t[i + 3]);  /* 3 | 7 */
    }
    static const int coord[4] = {0, 2, 1, 3};
    for (int j = 0; j < 4; ++j) {
        out[coord[j]] = _mm512_shuffle_f64x2(u[j], u[j + 4], 0x44);
        out[coord[j] + 4] = _mm512_shuffle_f64x2(u[j], u[j + 4], 0xEE);
    }
    out[8] = _mm512_i32gather_pd(_mm256_setr_epi32(8, 17, 26, 35, 44, 53, 62, 71), p, 8);
}

#define TTDW_HAVE_LOAD_AOS9_F 1
static inline __attribute__((always_inline)) void ttdw_load_aos9_f(const float *p, ttdw_vf out[9])
{
    /* Row i holds coordinates 0-7 of triangle i in its low half and of triangle i+8 in its
     * high half; the 8x8 transpose then runs in both halves at once. */
    __m512 r[8], t[8], u[8];
    for (int i = 0; i < 8; ++i)
        r[i] = _mm512_insertf32x8(_mm512_castps256_ps512(_mm256_loadu_ps(p + 9 * i)),
                                  _mm256_loadu_ps(p + 9 * (i + 8)), 1);
    for (int i = 0; i < 8; i += 2) {
        t[i] = _mm512_unpacklo_ps(r[i], r[i + 1]);
        t[i + 1] = _mm512_unpackhi_ps(r[i], r[i + 1]);
    }
    for (int i = 0; i < 8; i += 4) {
        u[i + 0] = _mm512_shuffle_ps(t[i], t[i + 2], 0x44);
        u[i + 1] = _mm512_shuffle_ps(t[i], t[i + 2], 0xEE);
        u[i + 2] = _mm512_shuffle_ps(t[i + 1], t[i + 3], 0x44);
        u[i + 3] = _mm512_shuffle_ps(t[i + 1], t[i + 3], 0xEE);
    }
    /* u[k] blocks (128 bits): 0 = coordinate k rows 0-3, 1 = coordinate k+4 rows 0-3,
     * 2 and 3 the same for rows 8-11; u[k+4] the same for rows 4-7 and 12-15. */
    const __m512i lo = _mm512_setr_epi32(0, 1, 2, 3, 16, 17, 18, 19, 8, 9, 10, 11, 24, 25, 26, 27);
    const __m512i hi = _mm512_setr_epi32(4, 5, 6, 7, 20, 21, 22, 23, 12, 13, 14, 15, 28, 29, 30, 31);
    for (int k = 0; k < 4; ++k) {
        out[k] = _mm512_permutex2var_ps(u[k], lo, u[k + 4]);
        out[k + 4] = _mm512_permutex2var_ps(u[k], hi, u[k + 4]);
    }
    out[8] = _mm512_i32gather_ps(_mm512_setr_epi32(8, 17, 26, 35, 44, 53, 62, 71, 80, 89, 98, 107,
                                                   116, 125, 134, 143), p, 4);
}

#endif /* TTD_SIMD_LANES_AVX512_H */
