/* SPDX-License-Identifier: MIT */
/* One source, two precisions, one precision per translation unit (SLEEF's sleefsimddp.c /
 * sleefsimdsp.c arrangement). Precision-generic code (foo_impl.h) is compiled by two thin
 * files, foo_d.c and foo_f.c, each of which says
 *
 *     #define TTD_PRECISION_DOUBLE            (or TTD_PRECISION_FLOAT)
 *     #include "core/precision.h"
 *     #include "foo_impl.h"
 *
 * and then defines the exported names by hand (ttd_foo_d calls the file's static foo), so
 * every exported symbol is written out where it is defined. Inside foo_impl.h, write `real`,
 * `ttd_result`, `ttd_out` and the math wrappers below, never double/float directly. These names exist
 * only in ttd's own translation units: no public or shared header includes this file. */
#ifndef TTD_CORE_PRECISION_H
#define TTD_CORE_PRECISION_H

#if defined(TTD_PRECISION_DOUBLE) == defined(TTD_PRECISION_FLOAT)
#error "define exactly one of TTD_PRECISION_DOUBLE and TTD_PRECISION_FLOAT before core/precision.h"
#endif

#include <float.h>
#include <math.h>

#include "core/kernels.h"
#include "ttd/ttd.h"

#ifdef TTD_PRECISION_DOUBLE
typedef double real;
typedef ttd_result_d ttd_result;
typedef ttd_out_d ttd_out;
typedef ttd_node_d ttd_node;
typedef ttd_box_query_d ttd_box_query;
#define TTD_REAL_EPS DBL_EPSILON
#define TTD_REAL_MIN DBL_MIN
#define TTD_REAL_MAX DBL_MAX
#define TTD_SQRT sqrt
#define TTD_FABS fabs
#define TTD_FMA fma
#define TTD_FREXP frexp
#define TTD_LDEXP ldexp
#else
typedef float real;
typedef ttd_result_f ttd_result;
typedef ttd_out_f ttd_out;
typedef ttd_node_f ttd_node;
typedef ttd_box_query_f ttd_box_query;
#define TTD_REAL_EPS FLT_EPSILON
#define TTD_REAL_MIN FLT_MIN
#define TTD_REAL_MAX FLT_MAX
#define TTD_SQRT sqrtf
#define TTD_FABS fabsf
#define TTD_FMA fmaf
#define TTD_FREXP frexpf
#define TTD_LDEXP ldexpf
#endif

#endif /* TTD_CORE_PRECISION_H */
