/* SPDX-License-Identifier: MIT */
/* The results of a `ttd bench` run as bench.c fills them and output.c writes them: one measured
 * pair row, the run's settings (which the mesh and scene sections read too), and the tolerance
 * that counts a disagreement. It sits below bench.c, output.c and the sections and includes
 * none of them: bench.c calls output.c's writers, and output.c needs of bench.c's work only
 * what is declared here. */
#ifndef TTD_BENCH_ROWS_H
#define TTD_BENCH_ROWS_H

#include <stddef.h>

/// One line of the results: a workload timed with one method, precision, ISA and thread count.
typedef struct bench_row {
    char workload[32];
    char method[16];          ///< ttd_method_name(), or "fcl"
    int bytes;                ///< 8 = double, 4 = float
    char isa[16];             ///< ttd_isa_name(); FCL rows say "scalar"
    int lanes;                ///< pairs per vector for this ISA and precision
    int threads;
    size_t pairs;
    int samples;              ///< timed samples (after the warm-up)
    long passes;              ///< passes over the data per sample
    double ns_per_pair;       ///< median sample
    double ns_min;            ///< fastest sample
    double pairs_per_s;
    double speedup_vs_scalar; ///< scalar row (same workload, method, precision, 1 thread) / this; NaN if none
    double lane_fraction;     ///< speedup_vs_scalar / (lanes * threads)
    double thread_speedup;    ///< same ISA on 1 thread / this; NaN if none
    double speedup_vs_fcl;    ///< FCL (same workload, precision) / this; NaN if none
    int has_accuracy;         ///< the next five fields are set
    double max_rel_err;       ///< max |d - d_exact| / max(d_exact, size)
    double p999_rel_err;      ///< its 99.9th percentile
    double max_abs_err;       ///< max |d - d_exact|
    size_t disagree;          ///< pairs whose relative error exceeds bench_disagree_tol()
    size_t not_converged;     ///< pairs flagged TTD_PAIR_NOT_CONVERGED
    size_t fallback;          ///< certified method: pairs flagged TTD_PAIR_FALLBACK (sent to the exact method)
    int has_iterations;       ///< the next two fields are set
    double mean_iterations;   ///< mean Newton iterations per pair
    double occupancy;         ///< mean iterations / mean over lane-blocks of the block's maximum
} bench_row;

/// Relative error above which a pair counts as a disagreement with the exact method.
static inline double bench_disagree_tol(int bytes) { return bytes == 8 ? 1e-9 : 1e-4; }

/// Output settings echoed into the JSON and the table header.
typedef struct bench_settings {
    int quick;
    int samples;
    double min_sample_s;
    unsigned long long seed;
    char fcl[512];            ///< path of the FCL program, or a reason it is absent
    char pair_mesh[200];      ///< the mesh-near/mesh-contact pair workloads' mesh and margin, or "not run"
    char command[512];        ///< the command line
    const struct bench_mesh_results *mesh; ///< the mesh section (bench/mesh_bench.h), NULL when not run
    const struct bench_scene_results *scene; ///< the scene section (bench/scene_bench.h), NULL when not run
    const struct bench_deform_results *deform; ///< the deforming-mesh section (bench/deform_bench.h), NULL when not run
} bench_settings;

#endif /* TTD_BENCH_ROWS_H */
