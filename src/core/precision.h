/* SPDX-License-Identifier: MIT */
/* One source, two precisions (FFTW's X() idea). A file that holds precision-generic code
 * (foo_impl.h) is included once per precision by its .c file:
 *
 *     #define TTD_PRECISION_DOUBLE
 *     #include "core/precision.h"
 *     #include "foo_impl.h"
 *     #include "core/precision_end.h"
 *     #define TTD_PRECISION_FLOAT
 *     ... the same again
 *
 * Inside, write `real`, `TTD_SFX(name)` (-> name_d / name_f), `ttd_result` and the math
 * wrappers below, never double/float directly. */
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
#endif
