/* SPDX-License-Identifier: MIT */
/* For tests that instantiate one test body for both precisions in one file (test_lanes.c,
 * test_isa_kernels.c): after #define TTD_PRECISION_DOUBLE or TTD_PRECISION_FLOAT, this opens a
 * section in which `real`, `ttd_result`, TTD_SFX(name) (-> name_d / name_f) and the math
 * wrappers name that precision; tests/precision_close.h closes it. The library itself compiles
 * one precision per translation unit (src/core/precision.h). */
#if defined(TTD_PRECISION_DOUBLE) == defined(TTD_PRECISION_FLOAT)
#error "define exactly one of TTD_PRECISION_DOUBLE and TTD_PRECISION_FLOAT"
#endif

#include <float.h>
#include <math.h>

#ifdef TTD_PRECISION_DOUBLE
#define real double
#define TTD_SFX(name) name##_d
#define ttd_result ttd_result_d
#define TTD_REAL_EPS DBL_EPSILON
#define TTD_REAL_MIN DBL_MIN
#define TTD_REAL_MAX DBL_MAX
#define TTD_SQRT sqrt
#define TTD_FABS fabs
#define TTD_FMA fma
#define TTD_FREXP frexp
#define TTD_LDEXP ldexp
#define TTD_NEXTAFTER nextafter
#else
#define real float
#define TTD_SFX(name) name##_f
#define ttd_result ttd_result_f
#define TTD_REAL_EPS FLT_EPSILON
#define TTD_REAL_MIN FLT_MIN
#define TTD_REAL_MAX FLT_MAX
#define TTD_SQRT sqrtf
#define TTD_FABS fabsf
#define TTD_FMA fmaf
#define TTD_FREXP frexpf
#define TTD_LDEXP ldexpf
#define TTD_NEXTAFTER nextafterf
#endif
