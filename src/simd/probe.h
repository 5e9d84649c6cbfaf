/* SPDX-License-Identifier: MIT */
/* A window onto the lane layer for tests/test_lanes.c: each ISA file exports
 * ttd_lanes_probe_<isa>_d/f, which applies one lane operation (TTDW_OP_*) to plain arrays, so
 * that the test, built with baseline flags, checks the code exactly as the ISA's translation
 * unit compiled it. Not part of the public API. */
#ifndef TTD_SIMD_PROBE_H
#define TTD_SIMD_PROBE_H

/* Inputs a, b, c hold one vector each (W reals); out receives one vector; masks come back as
 * 1.0 / 0.0 per lane; any/none/mbits come back in out[0]. LOAD_AOS9 reads 9W reals from a
 * (the user's layout) and writes 9 vectors to out. MFIRST uses k = (int)a[0]. WIDEN (float only; -1 for double) rounds each
 * lane of a through double and back: d2f(f2d_lo(a) * 2^100 * 2^-100, the same for hi), which
 * is a in every lane only if the widening, the lane order and the narrowing are right. */
enum {
    TTDW_OP_ADD, TTDW_OP_SUB, TTDW_OP_MUL, TTDW_OP_DIV, TTDW_OP_NEG, TTDW_OP_FMA, TTDW_OP_MIN,
    TTDW_OP_MAX, TTDW_OP_SQRT, TTDW_OP_ABS, TTDW_OP_POW2, TTDW_OP_LT, TTDW_OP_LE, TTDW_OP_GT, TTDW_OP_GE,
    TTDW_OP_EQ, TTDW_OP_SEL, TTDW_OP_MAND, TTDW_OP_MOR, TTDW_OP_MANDNOT, TTDW_OP_MNOT,
    TTDW_OP_MTRUE, TTDW_OP_MFIRST, TTDW_OP_MBITS, TTDW_OP_ANY, TTDW_OP_NONE,
    TTDW_OP_SET1, TTDW_OP_ZERO, TTDW_OP_LOAD_AOS9, TTDW_OP_WIDEN,
    TTDW_OP_COUNT
};

/* Returns the lane count, or -1 for an unknown op. has_fma (may be NULL) receives
 * TTDW_HAVE_FMA. */
typedef int (*ttd_lanes_probe_d_fn)(int op, const double *a, const double *b, const double *c, double *out);
typedef int (*ttd_lanes_probe_f_fn)(int op, const float *a, const float *b, const float *c, float *out);

int ttd_lanes_probe_sse2_d(int op, const double *a, const double *b, const double *c, double *out);
int ttd_lanes_probe_sse2_f(int op, const float *a, const float *b, const float *c, float *out);
int ttd_lanes_probe_avx2_d(int op, const double *a, const double *b, const double *c, double *out);
int ttd_lanes_probe_avx2_f(int op, const float *a, const float *b, const float *c, float *out);
int ttd_lanes_probe_avx512_d(int op, const double *a, const double *b, const double *c, double *out);
int ttd_lanes_probe_avx512_f(int op, const float *a, const float *b, const float *c, float *out);
int ttd_lanes_probe_neon_d(int op, const double *a, const double *b, const double *c, double *out);
int ttd_lanes_probe_neon_f(int op, const float *a, const float *b, const float *c, float *out);
int ttd_lanes_probe_portable_d(int op, const double *a, const double *b, const double *c, double *out);
int ttd_lanes_probe_portable_f(int op, const float *a, const float *b, const float *c, float *out);

#endif /* TTD_SIMD_PROBE_H */
