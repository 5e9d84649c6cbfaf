/* SPDX-License-Identifier: MIT */
/* ttd_barrier_pair_d: the log-barrier method in double, for comparison with the penalty
 * method (the code is precision-generic, in barrier_impl.h). */
#include <stdint.h>

#define TTD_PRECISION_DOUBLE
#include "core/precision.h"
#include "scalar/scalar.h"
#include "scalar/barrier_impl.h"

void ttd_barrier_pair_d(const double s[9], const double t[9], const ttd_params *prm, ttd_result_d *r)
{
    barrier_pair(s, t, prm, r);
}
