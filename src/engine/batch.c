/* SPDX-License-Identifier: MIT */
/* The batch engine (engine/batch.h) in both precisions: engine/batch_impl.h, included twice. */
#include "engine/batch.h"

#include <math.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "engine/parallel.h"

/* What the blocks of one call saw. */
#define TTD_BATCH_NONFINITE 1u
#define TTD_BATCH_NOT_CONVERGED 2u
#define TTD_BATCH_NOMEM 4u
#define TTD_BATCH_BAD_INDEX 8u

static ttd_status ttd_batch_status(unsigned bits)
{
    if (bits & TTD_BATCH_BAD_INDEX)
        return TTD_ERR_INDEX_OUT_OF_RANGE;
    if (bits & TTD_BATCH_NOMEM)
        return TTD_ERR_OUT_OF_MEMORY;
    if (bits & TTD_BATCH_NONFINITE)
        return TTD_ERR_NONFINITE_INPUT;
    if (bits & TTD_BATCH_NOT_CONVERGED)
        return TTD_WARN_NOT_CONVERGED;
    return TTD_OK;
}

/* Element k of a uint32 array at p, whatever p's alignment. */
static uint32_t ttd_load_u32(const unsigned char *p, size_t k)
{
    uint32_t v;
    memcpy(&v, p + k * sizeof v, sizeof v);
    return v;
}

#define TTD_PRECISION_DOUBLE
#include "core/precision.h"
#define TTD_UBITS uint64_t
#define TTD_EXP_BITS UINT64_C(0x7ff0000000000000)
#define TTD_KERNEL_FN ttd_kernel_d_fn
#define TTD_ROW_COL d
#include "engine/batch_impl.h"
#undef TTD_UBITS
#undef TTD_EXP_BITS
#undef TTD_KERNEL_FN
#undef TTD_ROW_COL
#include "core/precision_end.h"

#define TTD_PRECISION_FLOAT
#include "core/precision.h"
#define TTD_UBITS uint32_t
#define TTD_EXP_BITS UINT32_C(0x7f800000)
#define TTD_KERNEL_FN ttd_kernel_f_fn
#define TTD_ROW_COL f
#include "engine/batch_impl.h"
#undef TTD_UBITS
#undef TTD_EXP_BITS
#undef TTD_KERNEL_FN
#undef TTD_ROW_COL
#include "core/precision_end.h"
