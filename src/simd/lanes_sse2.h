/* SPDX-License-Identifier: MIT */
/* lanes.h on SSE2 (the x86-64 baseline): 2 doubles or 4 floats per vector; masks are integer
 * lanes of all ones / all zeros, merged with and/andnot/or (SSE2 has no blendv). There is no
 * FMA: ttdw_fma_* rounds twice. */
#ifndef TTD_SIMD_LANES_SSE2_H
#define TTD_SIMD_LANES_SSE2_H

#if !defined(__SSE2__)
#error "lanes_sse2.h needs -msse2"
#endif
#include <emmintrin.h>

#define TTDW_LANES_D 2
#define TTDW_LANES_F 4
#define TTDW_HAVE_FMA 0

typedef __m128d ttdw_vd;
typedef __m128 ttdw_vf;
typedef __m128i ttdw_md;
typedef __m128i ttdw_mf;

/* ---- double ---- */
static inline ttdw_vd ttdw_set1_d(double x) { return _mm_set1_pd(x); }
static inline ttdw_vd ttdw_zero_d(void) { return _mm_setzero_pd(); }
static inline ttdw_vd ttdw_loadu_d(const double *p) { return _mm_loadu_pd(p); }
static inline void ttdw_storeu_d(double *p, ttdw_vd v) { _mm_storeu_pd(p, v); }
static inline ttdw_vd ttdw_fma_d(ttdw_vd a, ttdw_vd b, ttdw_vd c) { return _mm_add_pd(_mm_mul_pd(a, b), c); }
static inline ttdw_vd ttdw_min_d(ttdw_vd a, ttdw_vd b) { return _mm_min_pd(a, b); }
static inline ttdw_vd ttdw_max_d(ttdw_vd a, ttdw_vd b) { return _mm_max_pd(a, b); }
static inline ttdw_vd ttdw_sqrt_d(ttdw_vd a) { return _mm_sqrt_pd(a); }
static inline ttdw_vd ttdw_abs_d(ttdw_vd a) { return _mm_andnot_pd(_mm_set1_pd(-0.0), a); }
static inline ttdw_vd ttdw_pow2_d(ttdw_vd a) { return _mm_and_pd(a, _mm_castsi128_pd(_mm_set1_epi64x(0x7FF0000000000000LL))); }
static inline ttdw_md ttdw_lt_d(ttdw_vd a, ttdw_vd b) { return _mm_castpd_si128(_mm_cmplt_pd(a, b)); }
static inline ttdw_md ttdw_le_d(ttdw_vd a, ttdw_vd b) { return _mm_castpd_si128(_mm_cmple_pd(a, b)); }
static inline ttdw_md ttdw_gt_d(ttdw_vd a, ttdw_vd b) { return _mm_castpd_si128(_mm_cmpgt_pd(a, b)); }
static inline ttdw_md ttdw_ge_d(ttdw_vd a, ttdw_vd b) { return _mm_castpd_si128(_mm_cmpge_pd(a, b)); }
static inline ttdw_md ttdw_eq_d(ttdw_vd a, ttdw_vd b) { return _mm_castpd_si128(_mm_cmpeq_pd(a, b)); }
static inline ttdw_vd ttdw_sel_d(ttdw_md m, ttdw_vd a, ttdw_vd b)
{
    __m128d mm = _mm_castsi128_pd(m);
    return _mm_or_pd(_mm_and_pd(mm, a), _mm_andnot_pd(mm, b));
}
static inline ttdw_md ttdw_mand_d(ttdw_md a, ttdw_md b) { return _mm_and_si128(a, b); }
static inline ttdw_md ttdw_mor_d(ttdw_md a, ttdw_md b) { return _mm_or_si128(a, b); }
static inline ttdw_md ttdw_mandnot_d(ttdw_md a, ttdw_md b) { return _mm_andnot_si128(b, a); }
static inline ttdw_md ttdw_mtrue_d(void) { return _mm_set1_epi32(-1); }
static inline ttdw_md ttdw_mnot_d(ttdw_md a) { return _mm_xor_si128(a, _mm_set1_epi32(-1)); }
static inline ttdw_md ttdw_mfirst_d(int k)
{
    /* lanes are 64-bit; both 32-bit halves of lane i compare i < k */
    return _mm_cmpgt_epi32(_mm_set1_epi32(k), _mm_setr_epi32(0, 0, 1, 1));
}
static inline unsigned ttdw_mbits_d(ttdw_md m) { return (unsigned)_mm_movemask_pd(_mm_castsi128_pd(m)); }
static inline int ttdw_any_d(ttdw_md m) { return ttdw_mbits_d(m) != 0u; }

/* ---- float ---- */
static inline ttdw_vf ttdw_set1_f(float x) { return _mm_set1_ps(x); }
static inline ttdw_vf ttdw_zero_f(void) { return _mm_setzero_ps(); }
static inline ttdw_vf ttdw_loadu_f(const float *p) { return _mm_loadu_ps(p); }
static inline void ttdw_storeu_f(float *p, ttdw_vf v) { _mm_storeu_ps(p, v); }
static inline ttdw_vf ttdw_fma_f(ttdw_vf a, ttdw_vf b, ttdw_vf c) { return _mm_add_ps(_mm_mul_ps(a, b), c); }
static inline ttdw_vf ttdw_min_f(ttdw_vf a, ttdw_vf b) { return _mm_min_ps(a, b); }
static inline ttdw_vf ttdw_max_f(ttdw_vf a, ttdw_vf b) { return _mm_max_ps(a, b); }
static inline ttdw_vf ttdw_sqrt_f(ttdw_vf a) { return _mm_sqrt_ps(a); }
static inline ttdw_vf ttdw_abs_f(ttdw_vf a) { return _mm_andnot_ps(_mm_set1_ps(-0.0f), a); }
static inline ttdw_vf ttdw_pow2_f(ttdw_vf a) { return _mm_and_ps(a, _mm_castsi128_ps(_mm_set1_epi32(0x7F800000))); }
static inline ttdw_mf ttdw_lt_f(ttdw_vf a, ttdw_vf b) { return _mm_castps_si128(_mm_cmplt_ps(a, b)); }
static inline ttdw_mf ttdw_le_f(ttdw_vf a, ttdw_vf b) { return _mm_castps_si128(_mm_cmple_ps(a, b)); }
static inline ttdw_mf ttdw_gt_f(ttdw_vf a, ttdw_vf b) { return _mm_castps_si128(_mm_cmpgt_ps(a, b)); }
static inline ttdw_mf ttdw_ge_f(ttdw_vf a, ttdw_vf b) { return _mm_castps_si128(_mm_cmpge_ps(a, b)); }
static inline ttdw_mf ttdw_eq_f(ttdw_vf a, ttdw_vf b) { return _mm_castps_si128(_mm_cmpeq_ps(a, b)); }
static inline ttdw_vf ttdw_sel_f(ttdw_mf m, ttdw_vf a, ttdw_vf b)
{
    __m128 mm = _mm_castsi128_ps(m);
    return _mm_or_ps(_mm_and_ps(mm, a), _mm_andnot_ps(mm, b));
}
static inline ttdw_mf ttdw_mand_f(ttdw_mf a, ttdw_mf b) { return _mm_and_si128(a, b); }
static inline ttdw_mf ttdw_mor_f(ttdw_mf a, ttdw_mf b) { return _mm_or_si128(a, b); }
static inline ttdw_mf ttdw_mandnot_f(ttdw_mf a, ttdw_mf b) { return _mm_andnot_si128(b, a); }
static inline ttdw_mf ttdw_mtrue_f(void) { return _mm_set1_epi32(-1); }
static inline ttdw_mf ttdw_mnot_f(ttdw_mf a) { return _mm_xor_si128(a, _mm_set1_epi32(-1)); }
static inline ttdw_mf ttdw_mfirst_f(int k) { return _mm_cmpgt_epi32(_mm_set1_epi32(k), _mm_setr_epi32(0, 1, 2, 3)); }
static inline unsigned ttdw_mbits_f(ttdw_mf m) { return (unsigned)_mm_movemask_ps(_mm_castsi128_ps(m)); }
static inline int ttdw_any_f(ttdw_mf m) { return ttdw_mbits_f(m) != 0u; }

/* ---- precision conversion (float lanes = 2 x double lanes) ---- */
static inline ttdw_vd ttdw_f2d_lo(ttdw_vf a) { return _mm_cvtps_pd(a); }
static inline ttdw_vd ttdw_f2d_hi(ttdw_vf a) { return _mm_cvtps_pd(_mm_movehl_ps(a, a)); }
static inline ttdw_vf ttdw_d2f(ttdw_vd lo, ttdw_vd hi) { return _mm_movelh_ps(_mm_cvtpd_ps(lo), _mm_cvtpd_ps(hi)); }

/* ---- transposition ---- */
#define TTDW_HAVE_LOAD_AOS9_D 1
static inline void ttdw_load_aos9_d(const double *p, ttdw_vd out[9])
{
    /* two triangles: coordinate k of both is one unpack of two scalars */
    for (int k = 0; k < 9; ++k)
        out[k] = _mm_unpacklo_pd(_mm_load_sd(p + k), _mm_load_sd(p + 9 + k));
}

#define TTDW_HAVE_LOAD_AOS9_F 1
static inline void ttdw_load_aos9_f(const float *p, ttdw_vf out[9])
{
    /* 4x4 transposes of coordinates 0-3 and 4-7, then coordinate 8 from four scalars */
    for (int h = 0; h < 2; ++h) {
        __m128 r0 = _mm_loadu_ps(p + 4 * h), r1 = _mm_loadu_ps(p + 9 + 4 * h);
        __m128 r2 = _mm_loadu_ps(p + 18 + 4 * h), r3 = _mm_loadu_ps(p + 27 + 4 * h);
        _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
        out[4 * h + 0] = r0; out[4 * h + 1] = r1; out[4 * h + 2] = r2; out[4 * h + 3] = r3;
    }
    out[8] = _mm_setr_ps(p[8], p[17], p[26], p[35]);
}

#endif /* TTD_SIMD_LANES_SSE2_H */
