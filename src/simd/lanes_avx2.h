/* SPDX-License-Identifier: MIT */
/* lanes.h on AVX2 with FMA: 4 doubles or 8 floats per vector; masks are 64- or 32-bit
 * integer lanes of all ones / all zeros (what vcmppd/vcmpps produce), merged with vblendv.
 * The transposition of 4 double triangles is done in registers (two 4x4 transposes plus one
 * column); float uses an 8x8 transpose plus one column. */
#ifndef TTD_SIMD_LANES_AVX2_H
#define TTD_SIMD_LANES_AVX2_H

#if !defined(__AVX2__) || !defined(__FMA__)
#error "lanes_avx2.h needs -mavx2 -mfma"
#endif
#include <immintrin.h>

#define TTDW_LANES_D 4
#define TTDW_LANES_F 8
#define TTDW_HAVE_FMA 1

typedef __m256d ttdw_vd;
typedef __m256 ttdw_vf;
typedef __m256i ttdw_md;
typedef __m256i ttdw_mf;

/* ---- double ---- */
static inline ttdw_vd ttdw_set1_d(double x) { return _mm256_set1_pd(x); }
static inline ttdw_vd ttdw_zero_d(void) { return _mm256_setzero_pd(); }
static inline ttdw_vd ttdw_loadu_d(const double *p) { return _mm256_loadu_pd(p); }
static inline void ttdw_storeu_d(double *p, ttdw_vd v) { _mm256_storeu_pd(p, v); }
static inline ttdw_vd ttdw_fma_d(ttdw_vd a, ttdw_vd b, ttdw_vd c) { return _mm256_fmadd_pd(a, b, c); }
static inline ttdw_vd ttdw_min_d(ttdw_vd a, ttdw_vd b) { return _mm256_min_pd(a, b); }
static inline ttdw_vd ttdw_max_d(ttdw_vd a, ttdw_vd b) { return _mm256_max_pd(a, b); }
static inline ttdw_vd ttdw_sqrt_d(ttdw_vd a) { return _mm256_sqrt_pd(a); }
static inline ttdw_vd ttdw_abs_d(ttdw_vd a) { return _mm256_andnot_pd(_mm256_set1_pd(-0.0), a); }
static inline ttdw_vd ttdw_pow2_d(ttdw_vd a) { return _mm256_and_pd(a, _mm256_castsi256_pd(_mm256_set1_epi64x(0x7FF0000000000000LL))); }
static inline ttdw_md ttdw_lt_d(ttdw_vd a, ttdw_vd b) { return _mm256_castpd_si256(_mm256_cmp_pd(a, b, _CMP_LT_OQ)); }
static inline ttdw_md ttdw_le_d(ttdw_vd a, ttdw_vd b) { return _mm256_castpd_si256(_mm256_cmp_pd(a, b, _CMP_LE_OQ)); }
static inline ttdw_md ttdw_gt_d(ttdw_vd a, ttdw_vd b) { return _mm256_castpd_si256(_mm256_cmp_pd(a, b, _CMP_GT_OQ)); }
static inline ttdw_md ttdw_ge_d(ttdw_vd a, ttdw_vd b) { return _mm256_castpd_si256(_mm256_cmp_pd(a, b, _CMP_GE_OQ)); }
static inline ttdw_md ttdw_eq_d(ttdw_vd a, ttdw_vd b) { return _mm256_castpd_si256(_mm256_cmp_pd(a, b, _CMP_EQ_OQ)); }
static inline ttdw_vd ttdw_sel_d(ttdw_md m, ttdw_vd a, ttdw_vd b) { return _mm256_blendv_pd(b, a, _mm256_castsi256_pd(m)); }
static inline ttdw_md ttdw_mand_d(ttdw_md a, ttdw_md b) { return _mm256_and_si256(a, b); }
static inline ttdw_md ttdw_mor_d(ttdw_md a, ttdw_md b) { return _mm256_or_si256(a, b); }
static inline ttdw_md ttdw_mandnot_d(ttdw_md a, ttdw_md b) { return _mm256_andnot_si256(b, a); }
static inline ttdw_md ttdw_mtrue_d(void) { return _mm256_set1_epi64x(-1); }
static inline ttdw_md ttdw_mnot_d(ttdw_md a) { return _mm256_xor_si256(a, _mm256_set1_epi64x(-1)); }
static inline ttdw_md ttdw_mfirst_d(int k) { return _mm256_cmpgt_epi64(_mm256_set1_epi64x(k), _mm256_setr_epi64x(0, 1, 2, 3)); }
static inline unsigned ttdw_mbits_d(ttdw_md m) { return (unsigned)_mm256_movemask_pd(_mm256_castsi256_pd(m)); }
static inline int ttdw_any_d(ttdw_md m) { return !_mm256_testz_si256(m, m); }

/* ---- float ---- */
static inline ttdw_vf ttdw_set1_f(float x) { return _mm256_set1_ps(x); }
static inline ttdw_vf ttdw_zero_f(void) { return _mm256_setzero_ps(); }
static inline ttdw_vf ttdw_loadu_f(const float *p) { return _mm256_loadu_ps(p); }
static inline void ttdw_storeu_f(float *p, ttdw_vf v) { _mm256_storeu_ps(p, v); }
static inline ttdw_vf ttdw_fma_f(ttdw_vf a, ttdw_vf b, ttdw_vf c) { return _mm256_fmadd_ps(a, b, c); }
static inline ttdw_vf ttdw_min_f(ttdw_vf a, ttdw_vf b) { return _mm256_min_ps(a, b); }
static inline ttdw_vf ttdw_max_f(ttdw_vf a, ttdw_vf b) { return _mm256_max_ps(a, b); }
static inline ttdw_vf ttdw_sqrt_f(ttdw_vf a) { return _mm256_sqrt_ps(a); }
static inline ttdw_vf ttdw_abs_f(ttdw_vf a) { return _mm256_andnot_ps(_mm256_set1_ps(-0.0f), a); }
static inline ttdw_vf ttdw_pow2_f(ttdw_vf a) { return _mm256_and_ps(a, _mm256_castsi256_ps(_mm256_set1_epi32(0x7F800000))); }
static inline ttdw_mf ttdw_lt_f(ttdw_vf a, ttdw_vf b) { return _mm256_castps_si256(_mm256_cmp_ps(a, b, _CMP_LT_OQ)); }
static inline ttdw_mf ttdw_le_f(ttdw_vf a, ttdw_vf b) { return _mm256_castps_si256(_mm256_cmp_ps(a, b, _CMP_LE_OQ)); }
static inline ttdw_mf ttdw_gt_f(ttdw_vf a, ttdw_vf b) { return _mm256_castps_si256(_mm256_cmp_ps(a, b, _CMP_GT_OQ)); }
static inline ttdw_mf ttdw_ge_f(ttdw_vf a, ttdw_vf b) { return _mm256_castps_si256(_mm256_cmp_ps(a, b, _CMP_GE_OQ)); }
static inline ttdw_mf ttdw_eq_f(ttdw_vf a, ttdw_vf b) { return _mm256_castps_si256(_mm256_cmp_ps(a, b, _CMP_EQ_OQ)); }
static inline ttdw_vf ttdw_sel_f(ttdw_mf m, ttdw_vf a, ttdw_vf b) { return _mm256_blendv_ps(b, a, _mm256_castsi256_ps(m)); }
static inline ttdw_mf ttdw_mand_f(ttdw_mf a, ttdw_mf b) { return _mm256_and_si256(a, b); }
static inline ttdw_mf ttdw_mor_f(ttdw_mf a, ttdw_mf b) { return _mm256_or_si256(a, b); }
static inline ttdw_mf ttdw_mandnot_f(ttdw_mf a, ttdw_mf b) { return _mm256_andnot_si256(b, a); }
static inline ttdw_mf ttdw_mtrue_f(void) { return _mm256_set1_epi32(-1); }
static inline ttdw_mf ttdw_mnot_f(ttdw_mf a) { return _mm256_xor_si256(a, _mm256_set1_epi32(-1)); }
static inline ttdw_mf ttdw_mfirst_f(int k) { return _mm256_cmpgt_epi32(_mm256_set1_epi32(k), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)); }
static inline unsigned ttdw_mbits_f(ttdw_mf m) { return (unsigned)_mm256_movemask_ps(_mm256_castsi256_ps(m)); }
static inline int ttdw_any_f(ttdw_mf m) { return !_mm256_testz_si256(m, m); }

/* ---- precision conversion (float lanes = 2 x double lanes) ---- */
static inline ttdw_vd ttdw_f2d_lo(ttdw_vf a) { return _mm256_cvtps_pd(_mm256_castps256_ps128(a)); }
static inline ttdw_vd ttdw_f2d_hi(ttdw_vf a) { return _mm256_cvtps_pd(_mm256_extractf128_ps(a, 1)); }
static inline ttdw_vf ttdw_d2f(ttdw_vd lo, ttdw_vd hi)
{
    return _mm256_insertf128_ps(_mm256_castps128_ps256(_mm256_cvtpd_ps(lo)), _mm256_cvtpd_ps(hi), 1);
}

/* ---- transposition ---- */

/* 4x4 transpose of rows r0..r3 (in place). */
static inline void ttdw_transpose4_d(ttdw_vd *r0, ttdw_vd *r1, ttdw_vd *r2, ttdw_vd *r3)
{
    __m256d t0 = _mm256_unpacklo_pd(*r0, *r1); /* r0[0] r1[0] r0[2] r1[2] */
    __m256d t1 = _mm256_unpackhi_pd(*r0, *r1); /* r0[1] r1[1] r0[3] r1[3] */
    __m256d t2 = _mm256_unpacklo_pd(*r2, *r3);
    __m256d t3 = _mm256_unpackhi_pd(*r2, *r3);
    *r0 = _mm256_permute2f128_pd(t0, t2, 0x20);
    *r1 = _mm256_permute2f128_pd(t1, t3, 0x20);
    *r2 = _mm256_permute2f128_pd(t0, t2, 0x31);
    *r3 = _mm256_permute2f128_pd(t1, t3, 0x31);
}

#define TTDW_HAVE_LOAD_AOS9_D 1
static inline void ttdw_load_aos9_d(const double *p, ttdw_vd out[9])
{
    /* Coordinates 0-3 and 4-7 of each triangle are one row each; coordinate 8 is gathered
     * from four scalars. Every load stays inside the 36 reals. */
    for (int h = 0; h < 2; ++h) {
        ttdw_vd r0 = _mm256_loadu_pd(p + 4 * h), r1 = _mm256_loadu_pd(p + 9 + 4 * h);
        ttdw_vd r2 = _mm256_loadu_pd(p + 18 + 4 * h), r3 = _mm256_loadu_pd(p + 27 + 4 * h);
        ttdw_transpose4_d(&r0, &r1, &r2, &r3);
        out[4 * h + 0] = r0; out[4 * h + 1] = r1; out[4 * h + 2] = r2; out[4 * h + 3] = r3;
    }
    out[8] = _mm256_setr_pd(p[8], p[17], p[26], p[35]);
}

#define TTDW_HAVE_LOAD_AOS9_F 1
static inline void ttdw_load_aos9_f(const float *p, ttdw_vf out[9])
{
    /* 8x8 transpose of coordinates 0-7 of the 8 triangles, then coordinate 8 by a gather. */
    __m256 r[8], t[8], u[8];
    for (int i = 0; i < 8; ++i)
        r[i] = _mm256_loadu_ps(p + 9 * i);
    for (int i = 0; i < 8; i += 2) {
        t[i] = _mm256_unpacklo_ps(r[i], r[i + 1]);
        t[i + 1] = _mm256_unpackhi_ps(r[i], r[i + 1]);
    }
    for (int i = 0; i < 8; i += 4) {
        u[i + 0] = _mm256_shuffle_ps(t[i], t[i + 2], 0x44);
        u[i + 1] = _mm256_shuffle_ps(t[i], t[i + 2], 0xEE);
        u[i + 2] = _mm256_shuffle_ps(t[i + 1], t[i + 3], 0x44);
        u[i + 3] = _mm256_shuffle_ps(t[i + 1], t[i + 3], 0xEE);
    }
    for (int k = 0; k < 4; ++k) {
        out[k] = _mm256_permute2f128_ps(u[k], u[k + 4], 0x20);
        out[k + 4] = _mm256_permute2f128_ps(u[k], u[k + 4], 0x31);
    }
    out[8] = _mm256_i32gather_ps(p + 8, _mm256_setr_epi32(0, 9, 18, 27, 36, 45, 54, 63), 4);
}

#endif /* TTD_SIMD_LANES_AVX2_H */
