/* SPDX-License-Identifier: MIT */
/* The exact triangle-triangle distance, scalar, in both precisions: exact_impl.h holds the
 * precision-generic code and is compiled once as double (ttd_exact_pair_d) and once as float
 * (ttd_exact_pair_f). The method and its accuracy argument are in docs/exact-method.md. */
#include <math.h>

#include "scalar/scalar.h"

#define TTD_PRECISION_DOUBLE
#include "core/precision.h"
#include "scalar/exact_impl.h"
#include "core/precision_end.h"

#define TTD_PRECISION_FLOAT
#include "core/precision.h"
#include "scalar/exact_impl.h"
#include "core/precision_end.h"
