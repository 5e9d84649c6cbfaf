/* SPDX-License-Identifier: MIT */
/* The lane vocabulary: what a lane-generic kernel (src/simd/kernel_*.h) may use, written once
 * and implemented per instruction set (lanes_sse2.h, lanes_avx2.h, lanes_avx512.h,
 * lanes_neon.h), and once for any target on compiler vector extensions (lanes_portable.h). A
 * kernel is ISPC's SPMD model written in C: one triangle pair per lane, both sides of every
 * branch computed and merged with a mask, loops that run while any lane is still active.
 *
 * Include this file once per translation unit after defining exactly one of TTDW_USE_SSE2,
 * TTDW_USE_AVX2, TTDW_USE_AVX512, TTDW_USE_NEON, TTDW_USE_PORTABLE (src/isa/<isa>_<p>.c
 * does), or TTDW_USE_CUDA (lanes_cuda.h: one lane per CUDA thread, src/gpu/, docs/gpu.md). It defines, for both precisions (suffix _d = double, _f = float):
 *
 *   TTDW_LANES_D / TTDW_LANES_F    lanes per vector (compile-time constants)
 *   ttdw_vd / ttdw_vf              a vector of reals. + - * / and unary - work as operators,
 *                                  lane by lane, rounded like the scalar operation (the build
 *                                  has -ffp-contract=off, so a*b+c is two roundings)
 *   ttdw_md / ttdw_mf              a mask: one boolean per lane. An integer vector of the
 *                                  lane's width (all ones / all zeros) on SSE2, AVX2 and NEON,
 *                                  a k-register (__mmask8/16) on AVX-512. Only the functions
 *                                  below touch masks, so kernels never see the difference.
 *
 * and these static inline functions (shown for _d; _f is the same with float):
 *
 *   set1(x)            every lane = x                 zero()          every lane = +0
 *   loadu(p)/storeu(p, v)  W reals, any alignment
 *   fma(a, b, c)       a*b + c; one rounding where the ISA has FMA (TTDW_HAVE_FMA = 1),
 *                      two roundings otherwise (SSE2): kernels use it only where either is fine
 *   min(a, b), max(a, b)   a < b ? a : b and a > b ? a : b for non-NaN input (NaN: unspecified)
 *   sqrt(a)            correctly rounded              abs(a)          |a| (clears the sign bit)
 *   pow2(a)            a with sign and mantissa bits cleared: 2^floor(log2|a|) for normal a,
 *                      0 for 0 and subnormals, inf for inf
 *   lt le gt ge eq(a, b) -> mask   ordered compares: false when either lane is NaN
 *   sel(m, a, b)       lane i = m_i ? a_i : b_i
 *   mand mor mandnot(a, b) (= a & ~b) mnot(a); mtrue(); mfirst(k) = lanes 0..k-1 set
 *   any(m) none(m) -> int;   mbits(m) -> unsigned, bit i = lane i
 *   f2d_lo(vf), f2d_hi(vf) -> vd   float lanes 0..W_d-1 / W_d..W_f-1 widened (W_f = 2 W_d
 *                      on every ISA; on CUDA W_f = W_d = 1 and f2d_hi repeats f2d_lo, whose
 *                      half d2f drops); d2f(lo, hi) -> vf narrows back, rounding to nearest
 *   load_aos9(p, out[9])  transposition: p holds W triangles of 9 reals each, the user's
 *                      layout (triangle i at p + 9i, any alignment); out[k] lane i = p[9i + k]
 *
 * Vector types never cross a translation unit (their ABI depends on -m flags): kernels take
 * and return plain arrays. lanes_precision.h maps the short names kernels use (vreal, vmask,
 * vfma, vsel, ...) onto one precision, in the same way as core/precision.h. */
#ifndef TTD_SIMD_LANES_H
#define TTD_SIMD_LANES_H

#include <stddef.h>

/* TTD_DEVICE and TTDW_FN: the qualifiers of functions the CPU and a CUDA kernel share. */
#include "core/device_fn.h"

#if defined(TTDW_USE_SSE2)
#include "simd/lanes_sse2.h"
#elif defined(TTDW_USE_AVX2)
#include "simd/lanes_avx2.h"
#elif defined(TTDW_USE_AVX512)
#include "simd/lanes_avx512.h"
#elif defined(TTDW_USE_NEON)
#include "simd/lanes_neon.h"
#elif defined(TTDW_USE_PORTABLE)
#include "simd/lanes_portable.h"
#elif defined(TTDW_USE_CUDA)
#include "simd/lanes_cuda.h"
#else
#error "define one of TTDW_USE_SSE2, TTDW_USE_AVX2, TTDW_USE_AVX512, TTDW_USE_NEON, TTDW_USE_PORTABLE, TTDW_USE_CUDA before lanes.h"
#endif

#if defined(__GNUC__)
#define TTDW_ALIGN(n) __attribute__((aligned(n)))
#else
#define TTDW_ALIGN(n)
#endif

/* Portable transpositions, used where an ISA header has no register version: W triangles
 * go through an aligned stack buffer (the loads and stores forward in the store buffer). */
#ifndef TTDW_HAVE_LOAD_AOS9_D
static inline void ttdw_load_aos9_d(const double *p, ttdw_vd out[9])
{
    double buf[9][TTDW_LANES_D] TTDW_ALIGN(64);
    for (int i = 0; i < TTDW_LANES_D; ++i)
        for (int k = 0; k < 9; ++k)
            buf[k][i] = p[9 * i + k];
    for (int k = 0; k < 9; ++k)
        out[k] = ttdw_loadu_d(buf[k]);
}
#endif
#ifndef TTDW_HAVE_LOAD_AOS9_F
static inline void ttdw_load_aos9_f(const float *p, ttdw_vf out[9])
{
    float buf[9][TTDW_LANES_F] TTDW_ALIGN(64);
    for (int i = 0; i < TTDW_LANES_F; ++i)
        for (int k = 0; k < 9; ++k)
            buf[k][i] = p[9 * i + k];
    for (int k = 0; k < 9; ++k)
        out[k] = ttdw_loadu_f(buf[k]);
}
#endif

TTDW_FN int ttdw_none_d(ttdw_md m) { return !ttdw_any_d(m); }
TTDW_FN int ttdw_none_f(ttdw_mf m) { return !ttdw_any_f(m); }

#endif /* TTD_SIMD_LANES_H */
