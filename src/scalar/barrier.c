/* SPDX-License-Identifier: MIT */
/* The log-barrier method in both precisions (ttd_barrier_pair_*), for comparison with the
 * penalty method. The code is in barrier_impl.h, written once against core/precision.h. */
#include <math.h>
#include <stdint.h>

#include "scalar/scalar.h"

#define TTD_PRECISION_DOUBLE
#include "core/precision.h"
#include "scalar/barrier_impl.h"
#include "core/precision_end.h"

#define TTD_PRECISION_FLOAT
#include "core/precision.h"
#include "scalar/barrier_impl.h"
#include "core/precision_end.h"
