/* SPDX-License-Identifier: MIT */
/* The block runner: one method's kernel in one precision, resolved once per call from the
 * configuration (dispatch.h), with the method's parameters and traits. It runs one block of at
 * most TTD_BLOCK_PAIRS finite pairs as core/kernels.h describes, and knows nothing of threads or
 * of where the pairs come from: the batch engine feeds it blocks from the caller's arrays or
 * from indexed meshes, a mesh traversal from the candidate pairs it finds. */
#ifndef TTD_ENGINE_RUNNER_H
#define TTD_ENGINE_RUNNER_H

#include "core/kernels.h"
#include "engine/batch.h"
#include "engine/dispatch.h"

typedef struct ttd_runner_d {
    ttd_kernel_d_fn fn;
    ttd_params params;
    int need_flags; ///< the method may flag TTD_PAIR_NOT_CONVERGED: per-pair results are needed to report it
} ttd_runner_d;

typedef struct ttd_runner_f {
    ttd_kernel_f_fn fn;
    ttd_params params;
    int need_flags;
} ttd_runner_f;

static inline ttd_runner_d ttd_runner_make_d(const ttd_engine_config *cfg)
{
    ttd_runner_d r = {ttd_dispatch_kernel_d(cfg->isa, cfg->method), cfg->params,
                      ttd_method_traits_of(cfg->method)->may_not_converge};
    return r;
}

static inline ttd_runner_f ttd_runner_make_f(const ttd_engine_config *cfg)
{
    ttd_runner_f r = {ttd_dispatch_kernel_f(cfg->isa, cfg->method), cfg->params,
                      ttd_method_traits_of(cfg->method)->may_not_converge};
    return r;
}

#endif /* TTD_ENGINE_RUNNER_H */
