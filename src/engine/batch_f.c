/* SPDX-License-Identifier: MIT */
/* The batch engine (engine/batch.h) in float: engine/batch_impl.h compiled for this precision,
 * and its two entries written out. */
#include <math.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define TTD_PRECISION_FLOAT
#include "core/precision.h"
#include "engine/batch.h"
#include "engine/batch_bits.h"
#include "engine/runner.h"
#include "engine/parallel.h"

typedef ttd_mesh_f engine_mesh;
#define TTD_UBITS uint32_t
#define TTD_EXP_BITS UINT32_C(0x7f800000)
#define TTD_RUNNER ttd_runner_f
#define TTD_RUNNER_MAKE ttd_runner_make_f
#include "engine/batch_impl.h"

ttd_status ttd_engine_batch_f(const ttd_engine_config *cfg, size_t n, const float *s, const float *t,
                              float *distance, ttd_result_f *results)
{
    return engine_batch(cfg, n, s, t, distance, results);
}

ttd_status ttd_engine_mesh_f(const ttd_engine_config *cfg, const ttd_mesh_f *m1, const ttd_mesh_f *m2,
                             size_t n, const uint32_t *pairs, float *distance, ttd_result_f *results)
{
    return engine_indexed(cfg, m1, m2, n, pairs, distance, results);
}
