/* SPDX-License-Identifier: MIT */
/* The log-barrier method in both precisions (ttd_barrier_pair_*), for comparison with the
 * penalty method. The code is in barrier_impl.h, written once against common/precision.h. */
#include <math.h>
#include <stdint.h>

#include "scalar/scalar.h"

#define TTD_PRECISION_DOUBLE
#include "common/precision.h"
#include "scalar/barrier_impl.h"
#include "common/precision_end.h"

#define TTD_PRECISION_FLOAT
#include "common/precision.h"
#include "scalar/barrier_impl.h"
#include "common/precision_end.h"
