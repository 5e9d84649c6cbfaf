/* SPDX-License-Identifier: MIT */
/* The penalty method in float: the paper's reference ttd1 (ttd_penalty_ref_pair_f) and the
 * optimised, safeguarded form (ttd_penalty_pair_f). The code is precision-generic, in
 * penalty_impl.h; the parameter caps of this precision come from core/defaults.h. */
#include <stdint.h>
#include <string.h>

#define TTD_PRECISION_FLOAT
#include "core/precision.h"
#include "core/defaults.h"
#include "scalar/scalar.h"
#define TTD_REAL_RHO_MAX TTD_FLOAT_RHO_MAX
#define TTD_REAL_TOL_MIN TTD_FLOAT_TOL_MIN
#include "scalar/penalty_impl.h"

void ttd_penalty_ref_pair_f(const float s[9], const float t[9], const ttd_params *prm, ttd_result_f *r)
{
    penalty_ref_pair(s, t, prm, r);
}

void ttd_penalty_pair_f(const float s[9], const float t[9], const ttd_params *prm, ttd_result_f *r)
{
    penalty_pair(s, t, prm, r);
}
