/* SPDX-License-Identifier: MIT */
/* The batch engine (engine/batch.h) in double: engine/batch_impl.h compiled for this precision,
 * and its two entries written out. */
#include <math.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define TTD_PRECISION_DOUBLE
#include "core/precision.h"
#include "engine/batch.h"
#include "engine/batch_bits.h"
#include "engine/runner.h"
#include "engine/parallel.h"

typedef ttd_mesh_d engine_mesh;
#define TTD_UBITS uint64_t
#define TTD_EXP_BITS UINT64_C(0x7ff0000000000000)
#define TTD_RUNNER ttd_runner_d
#define TTD_RUNNER_MAKE ttd_runner_make_d
#include "engine/batch_impl.h"

ttd_status ttd_engine_batch_d(const ttd_engine_config *cfg, size_t n, const double *s, const double *t,
                              double *distance, ttd_result_d *results)
{
    return engine_batch(cfg, n, s, t, distance, results);
}

ttd_status ttd_engine_mesh_d(const ttd_engine_config *cfg, const ttd_mesh_d *m1, const ttd_mesh_d *m2,
                             size_t n, const uint32_t *pairs, double *distance, ttd_result_d *results)
{
    return engine_indexed(cfg, m1, m2, n, pairs, distance, results);
}
