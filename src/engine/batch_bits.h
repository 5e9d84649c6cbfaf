/* SPDX-License-Identifier: MIT */
/* What the two precisions of the batch engine (engine/batch_d.c, batch_f.c) share: the bits a
 * block reports and the status they become, and an unaligned index load. */
#ifndef TTD_ENGINE_BATCH_BITS_H
#define TTD_ENGINE_BATCH_BITS_H

#include <stdint.h>
#include <string.h>

#include "ttd/ttd.h"

/* What the blocks of one call saw. */
#define TTD_BATCH_NONFINITE 1u
#define TTD_BATCH_NOT_CONVERGED 2u
#define TTD_BATCH_NOMEM 4u

static inline ttd_status ttd_batch_status(unsigned bits)
{
    if (bits & TTD_BATCH_NOMEM)
        return TTD_ERR_OUT_OF_MEMORY;
    if (bits & TTD_BATCH_NONFINITE)
        return TTD_ERR_NONFINITE_INPUT;
    if (bits & TTD_BATCH_NOT_CONVERGED)
        return TTD_WARN_NOT_CONVERGED;
    return TTD_OK;
}

/* Element k of a uint32 array at p, whatever p's alignment. */
static inline uint32_t ttd_load_u32(const unsigned char *p, size_t k)
{
    uint32_t v;
    memcpy(&v, p + k * sizeof v, sizeof v);
    return v;
}

#endif /* TTD_ENGINE_BATCH_BITS_H */
