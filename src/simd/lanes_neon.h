/* SPDX-License-Identifier: MIT */
/* lanes.h on AArch64 Advanced SIMD (NEON): 2 doubles or 4 floats per vector; masks are
 * unsigned integer lanes of all ones / all zeros (what vcltq etc. produce), merged with vbsl.
 * AArch64 only: double vectors, vsqrtq and the across-lane reductions (vmaxvq) do not exist on
 * 32-bit ARM. The transposition uses vld3 (3 coordinates per vertex). */
#ifndef TTD_SIMD_LANES_NEON_H
#define TTD_SIMD_LANES_NEON_H

#if !defined(__aarch64__)
#error "lanes_neon.h needs AArch64"
#endif
#include <arm_neon.h>

#define TTDW_LANES_D 2
#define TTDW_LANES_F 4
#define TTDW_HAVE_FMA 1

typedef float64x2_t ttdw_vd;
typedef float32x4_t ttdw_vf;
typedef uint64x2_t ttdw_md;
typedef uint32x4_t ttdw_mf;

/* ---- double ---- */
static inline ttdw_vd ttdw_set1_d(double x) { return vdupq_n_f64(x); }
static inline ttdw_vd ttdw_zero_d(void) { return vdupq_n_f64(0.0); }
static inline ttdw_vd ttdw_loadu_d(const double *p) { return vld1q_f64(p); }
static inline void ttdw_storeu_d(double *p, ttdw_vd v) { vst1q_f64(p, v); }
static inline ttdw_vd ttdw_fma_d(ttdw_vd a, ttdw_vd b, ttdw_vd c) { return vfmaq_f64(c, a, b); }
static inline ttdw_vd ttdw_min_d(ttdw_vd a, ttdw_vd b) { return vminq_f64(a, b); }
static inline ttdw_vd ttdw_max_d(ttdw_vd a, ttdw_vd b) { return vmaxq_f64(a, b); }
static inline ttdw_vd ttdw_sqrt_d(ttdw_vd a) { return vsqrtq_f64(a); }
static inline ttdw_vd ttdw_abs_d(ttdw_vd a) { return vabsq_f64(a); }
static inline ttdw_vd ttdw_pow2_d(ttdw_vd a) { return vreinterpretq_f64_u64(vandq_u64(vreinterpretq_u64_f64(a), vdupq_n_u64(0x7FF0000000000000ULL))); }
static inline ttdw_md ttdw_lt_d(ttdw_vd a, ttdw_vd b) { return vcltq_f64(a, b); }
static inline ttdw_md ttdw_le_d(ttdw_vd a, ttdw_vd b) { return vcleq_f64(a, b); }
static inline ttdw_md ttdw_gt_d(ttdw_vd a, ttdw_vd b) { return vcgtq_f64(a, b); }
static inline ttdw_md ttdw_ge_d(ttdw_vd a, ttdw_vd b) { return vcgeq_f64(a, b); }
static inline ttdw_md ttdw_eq_d(ttdw_vd a, ttdw_vd b) { return vceqq_f64(a, b); }
static inline ttdw_vd ttdw_sel_d(ttdw_md m, ttdw_vd a, ttdw_vd b) { return vbslq_f64(m, a, b); }
static inline ttdw_md ttdw_mand_d(ttdw_md a, ttdw_md b) { return vandq_u64(a, b); }
static inline ttdw_md ttdw_mor_d(ttdw_md a, ttdw_md b) { return vorrq_u64(a, b); }
static inline ttdw_md ttdw_mandnot_d(ttdw_md a, ttdw_md b) { return vbicq_u64(a, b); }
static inline ttdw_md ttdw_mtrue_d(void) { return vdupq_n_u64(~(uint64_t)0); }
static inline ttdw_md ttdw_mnot_d(ttdw_md a) { return vreinterpretq_u64_u32(vmvnq_u32(vreinterpretq_u32_u64(a))); }
static inline ttdw_md ttdw_mfirst_d(int k)
{
    const uint64_t idx[2] = {0, 1};
    return vcltq_u64(vld1q_u64(idx), vdupq_n_u64((uint64_t)(k < 0 ? 0 : k)));
}
static inline unsigned ttdw_mbits_d(ttdw_md m)
{
    return (unsigned)(vgetq_lane_u64(m, 0) & 1u) | (unsigned)((vgetq_lane_u64(m, 1) & 1u) << 1);
}
static inline int ttdw_any_d(ttdw_md m) { return vmaxvq_u32(vreinterpretq_u32_u64(m)) != 0; }

/* ---- float ---- */
static inline ttdw_vf ttdw_set1_f(float x) { return vdupq_n_f32(x); }
static inline ttdw_vf ttdw_zero_f(void) { return vdupq_n_f32(0.0f); }
static inline ttdw_vf ttdw_loadu_f(const float *p) { return vld1q_f32(p); }
static inline void ttdw_storeu_f(float *p, ttdw_vf v) { vst1q_f32(p, v); }
static inline ttdw_vf ttdw_fma_f(ttdw_vf a, ttdw_vf b, ttdw_vf c) { return vfmaq_f32(c, a, b); }
static inline ttdw_vf ttdw_min_f(ttdw_vf a, ttdw_vf b) { return vminq_f32(a, b); }
static inline ttdw_vf ttdw_max_f(ttdw_vf a, ttdw_vf b) { return vmaxq_f32(a, b); }
static inline ttdw_vf ttdw_sqrt_f(ttdw_vf a) { return vsqrtq_f32(a); }
static inline ttdw_vf ttdw_abs_f(ttdw_vf a) { return vabsq_f32(a); }
static inline ttdw_vf ttdw_pow2_f(ttdw_vf a) { return vreinterpretq_f32_u32(vandq_u32(vreinterpretq_u32_f32(a), vdupq_n_u32(0x7F800000u))); }
static inline ttdw_mf ttdw_lt_f(ttdw_vf a, ttdw_vf b) { return vcltq_f32(a, b); }
static inline ttdw_mf ttdw_le_f(ttdw_vf a, ttdw_vf b) { return vcleq_f32(a, b); }
static inline ttdw_mf ttdw_gt_f(ttdw_vf a, ttdw_vf b) { return vcgtq_f32(a, b); }
static inline ttdw_mf ttdw_ge_f(ttdw_vf a, ttdw_vf b) { return vcgeq_f32(a, b); }
static inline ttdw_mf ttdw_eq_f(ttdw_vf a, ttdw_vf b) { return vceqq_f32(a, b); }
static inline ttdw_vf ttdw_sel_f(ttdw_mf m, ttdw_vf a, ttdw_vf b) { return vbslq_f32(m, a, b); }
static inline ttdw_mf ttdw_mand_f(ttdw_mf a, ttdw_mf b) { return vandq_u32(a, b); }
static inline ttdw_mf ttdw_mor_f(ttdw_mf a, ttdw_mf b) { return vorrq_u32(a, b); }
static inline ttdw_mf ttdw_mandnot_f(ttdw_mf a, ttdw_mf b) { return vbicq_u32(a, b); }
static inline ttdw_mf ttdw_mtrue_f(void) { return vdupq_n_u32(~0u); }
static inline ttdw_mf ttdw_mnot_f(ttdw_mf a) { return vmvnq_u32(a); }
static inline ttdw_mf ttdw_mfirst_f(int k)
{
    const uint32_t idx[4] = {0, 1, 2, 3};
    return vcltq_u32(vld1q_u32(idx), vdupq_n_u32((uint32_t)(k < 0 ? 0 : k)));
}
static inline unsigned ttdw_mbits_f(ttdw_mf m)
{
    const uint32_t w[4] = {1, 2, 4, 8};
    return (unsigned)vaddvq_u32(vandq_u32(m, vld1q_u32(w)));
}
static inline int ttdw_any_f(ttdw_mf m) { return vmaxvq_u32(m) != 0; }

/* ---- precision conversion (float lanes = 2 x double lanes) ---- */
static inline ttdw_vd ttdw_f2d_lo(ttdw_vf a) { return vcvt_f64_f32(vget_low_f32(a)); }
static inline ttdw_vd ttdw_f2d_hi(ttdw_vf a) { return vcvt_high_f64_f32(a); }
static inline ttdw_vf ttdw_d2f(ttdw_vd lo, ttdw_vd hi) { return vcvt_high_f32_f64(vcvt_f32_f64(lo), hi); }

/* ---- transposition ---- */
#define TTDW_HAVE_LOAD_AOS9_F 1
static inline void ttdw_load_aos9_f(const float *p, ttdw_vf out[9])
{
    /* 4 triangles = 12 vertices of 3 coordinates. vld3q de-interleaves 4 vertices (x, y, z);
     * three of them load every vertex, vertex j of triangle i landing in load (3i + j) / 4,
     * lane (3i + j) % 4. A table lookup would do; four lanes are few enough to zip. */
    float32x4x3_t a = vld3q_f32(p), b = vld3q_f32(p + 12), c = vld3q_f32(p + 24);
    /* vertex v = 3i + j: A0 B0 C0 A1 | B1 C1 A2 B2 | C2 A3 B3 C3 (a | b | c) */
    for (int k = 0; k < 3; ++k) {
        float32x4_t va = a.val[k], vb = b.val[k], vc = c.val[k];
        /* vertex A of triangles 0..3: a0 a3 b2 c1 */
        float32x4_t A = vsetq_lane_f32(vgetq_lane_f32(vc, 1),
                        vsetq_lane_f32(vgetq_lane_f32(vb, 2),
                        vsetq_lane_f32(vgetq_lane_f32(va, 3), vdupq_n_f32(vgetq_lane_f32(va, 0)), 1), 2), 3);
        /* vertex B: a1 b0 b3 c2 */
        float32x4_t B = vsetq_lane_f32(vgetq_lane_f32(vc, 2),
                        vsetq_lane_f32(vgetq_lane_f32(vb, 3),
                        vsetq_lane_f32(vgetq_lane_f32(vb, 0), vdupq_n_f32(vgetq_lane_f32(va, 1)), 1), 2), 3);
        /* vertex C: a2 b1 c0 c3 */
        float32x4_t C = vsetq_lane_f32(vgetq_lane_f32(vc, 3),
                        vsetq_lane_f32(vgetq_lane_f32(vc, 0),
                        vsetq_lane_f32(vgetq_lane_f32(vb, 1), vdupq_n_f32(vgetq_lane_f32(va, 2)), 1), 2), 3);
        out[k] = A;
        out[3 + k] = B;
        out[6 + k] = C;
    }
}

#define TTDW_HAVE_LOAD_AOS9_D 1
static inline void ttdw_load_aos9_d(const double *p, ttdw_vd out[9])
{
    for (int k = 0; k < 9; ++k)
        out[k] = vcombine_f64(vld1_f64(p + k), vld1_f64(p + 9 + k));
}

#endif /* TTD_SIMD_LANES_NEON_H */
