/* SPDX-License-Identifier: MIT */
/* The penalty method in both precisions: the paper's reference ttd1 (ttd_penalty_ref_pair_*)
 * and the optimised, safeguarded form (ttd_penalty_pair_*). The code is in penalty_impl.h,
 * written once against core/precision.h. */
#include <stdint.h>
#include <string.h>

#include "core/defaults.h"
#include "scalar/scalar.h"

#define TTD_PRECISION_DOUBLE
#include "core/precision.h"
#define TTD_REAL_RHO_MAX TTD_DOUBLE_RHO_MAX
#define TTD_REAL_TOL_MIN TTD_DOUBLE_TOL_MIN
#include "scalar/penalty_impl.h"
#undef TTD_REAL_RHO_MAX
#undef TTD_REAL_TOL_MIN
#include "core/precision_end.h"

#define TTD_PRECISION_FLOAT
#include "core/precision.h"
#define TTD_REAL_RHO_MAX TTD_FLOAT_RHO_MAX
#define TTD_REAL_TOL_MIN TTD_FLOAT_TOL_MIN
#include "scalar/penalty_impl.h"
#undef TTD_REAL_RHO_MAX
#undef TTD_REAL_TOL_MIN
#include "core/precision_end.h"
