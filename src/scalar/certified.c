/* SPDX-License-Identifier: MIT */
/* The certified mode in both precisions (ttd_certified_pair_d/f): the optimised penalty
 * method, then the exact solution on its final active set, checked for optimality; pairs that
 * fail the check go to the exact method. The code is in certified_impl.h, the thresholds in
 * certified_tol.h, the argument in docs/certified-mode.md. */
#include <math.h>
#include <stdint.h>

#include "core/certified_tol.h"
#include "scalar/scalar.h"

#define TTD_PRECISION_DOUBLE
#include "core/precision.h"
#include "scalar/certified_impl.h"
#include "core/precision_end.h"

#define TTD_PRECISION_FLOAT
#include "core/precision.h"
#include "scalar/certified_impl.h"
#include "core/precision_end.h"
