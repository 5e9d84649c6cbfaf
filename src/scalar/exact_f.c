/* SPDX-License-Identifier: MIT */
/* ttd_exact_pair_f: the exact method in float (the code is precision-generic, in
 * exact_impl.h; the method and its accuracy argument in docs/exact-method.md). */
#define TTD_PRECISION_FLOAT
#include "core/precision.h"
#include "scalar/scalar.h"
#include "scalar/exact_impl.h"

void ttd_exact_pair_f(const float s[9], const float t[9], ttd_result_f *r)
{
    exact_pair(s, t, r);
}

float ttd_exact_lower_bound_f(const float s[9], const float t[9])
{
    return exact_lower_bound(s, t);
}
