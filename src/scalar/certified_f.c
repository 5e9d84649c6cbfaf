/* SPDX-License-Identifier: MIT */
/* ttd_certified_pair_f: the certified mode in float. The optimised penalty method, then the
 * exact solution on its final active set, checked for optimality; pairs that fail the check
 * go to the exact method. The code is precision-generic, in certified_impl.h; the thresholds
 * are in core/certified_tol.h, the argument in docs/certified-mode.md. */
#include <stdint.h>

#define TTD_PRECISION_FLOAT
#include "core/precision.h"
#include "core/certified_tol.h"
#include "scalar/scalar.h"
#include "scalar/certified_impl.h"

void ttd_certified_pair_f(const float s[9], const float t[9], const ttd_params *prm, ttd_result_f *r)
{
    certified_pair(s, t, prm, r);
}
