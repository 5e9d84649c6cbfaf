/* SPDX-License-Identifier: MIT */
/* ttd_exact_pair_d: the exact method in double (the code is precision-generic, in
 * exact_impl.h; the method and its accuracy argument in docs/exact-method.md). */
#define TTD_PRECISION_DOUBLE
#include "core/precision.h"
#include "scalar/scalar.h"
#include "scalar/exact_impl.h"

void ttd_exact_pair_d(const double s[9], const double t[9], ttd_result_d *r)
{
    exact_pair(s, t, r);
}

double ttd_exact_lower_bound_d(const double s[9], const double t[9])
{
    return exact_lower_bound(s, t);
}
