/* SPDX-License-Identifier: MIT */
/* The penalty method in double: the paper's reference ttd1 (ttd_penalty_ref_pair_d) and the
 * optimised, safeguarded form (ttd_penalty_pair_d). The code is precision-generic, in
 * penalty_impl.h; the parameter caps of this precision come from core/defaults.h. */
#include <stdint.h>
#include <string.h>

#define TTD_PRECISION_DOUBLE
#include "core/precision.h"
#include "core/defaults.h"
#include "scalar/scalar.h"
#define TTD_REAL_RHO_MAX TTD_DOUBLE_RHO_MAX
#define TTD_REAL_TOL_MIN TTD_DOUBLE_TOL_MIN
#include "scalar/penalty_impl.h"

void ttd_penalty_ref_pair_d(const double s[9], const double t[9], const ttd_params *prm, ttd_result_d *r)
{
    penalty_ref_pair(s, t, prm, r);
}

void ttd_penalty_pair_d(const double s[9], const double t[9], const ttd_params *prm, ttd_result_d *r)
{
    penalty_pair(s, t, prm, r);
}
