/* SPDX-License-Identifier: MIT */
/* ttd_barrier_pair_f: the log-barrier method in float, for comparison with the penalty
 * method (the code is precision-generic, in barrier_impl.h). */
#include <stdint.h>

#define TTD_PRECISION_FLOAT
#include "core/precision.h"
#include "scalar/scalar.h"
#include "scalar/barrier_impl.h"

void ttd_barrier_pair_f(const float s[9], const float t[9], const ttd_params *prm, ttd_result_f *r)
{
    barrier_pair(s, t, prm, r);
}
