/* SPDX-License-Identifier: MIT */
/* What the files of `ttd bench` share: one measured row, the machine description, the
 * probes of peak arithmetic and memory bandwidth, the FCL side program and the writers.
 * Times are medians of several samples; ratios are formed only between rows of one run. */
#ifndef TTD_BENCH_INTERNAL_H
#define TTD_BENCH_INTERNAL_H

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include "ttd/ttd.h"

/// NaN and infinity as doubles (the <math.h> macros are floats, which -Wdouble-promotion flags).
#define BENCH_NAN ((double)NAN)
#define BENCH_INF ((double)INFINITY)

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

/// The machine and the build, for the header; NaN where a probe was not run.
typedef struct bench_machine {
    char cpu[128];
    char cpu_isas[256];       ///< the x86/arm SIMD flags the kernel reports
    char ttd_isas[64];        ///< instruction sets built into ttd and runnable here
    char isa_auto[16];        ///< what TTD_ISA_AUTO picks
    char os[200];
    char load_start[64];      ///< /proc/loadavg when the run began
    char load_end[64];        ///< and when it ended (other work on the machine skews timings)
    double load1_start;       ///< the 1-minute load average at the start, NaN if unknown
    double load1_end;         ///< and at the end (it includes the benchmark's own threads)
    char priority[96];        ///< this process's nice value and its scheduler autogroup's
    int cores;
    double mem_gib;
    double ghz;               ///< core clock estimated from a dependent add chain
    double peak_gflops_d[TTD_ISA_COUNT]; ///< one core, double, per ISA (FMA where it has one)
    double copy_gbs[2];       ///< stream copy, bytes read + written: 1 thread, all cores
    double read_gbs[2];       ///< stream read: 1 thread, all cores
} bench_machine;

/// Fills everything but the probes (which are set to NaN).
void bench_machine_describe(bench_machine *m);
/// Writes the 1, 5 and 15-minute load averages ("?" where unknown) and returns the 1-minute
/// one (NaN where unknown). Read from /proc/loadavg, or from the file $TTD_BENCH_LOADAVG names.
double bench_load_average(char *out, size_t size);
/// 1 when the 1-minute load average at the start or the end exceeds the online cores: other
/// work then competed for the CPU and the timings are not to be trusted.
int bench_load_exceeds_cores(const bench_machine *m);
/// Runs the probes; seconds is roughly how long each one runs.
void bench_machine_probe(bench_machine *m, double seconds, size_t stream_bytes);

/// Monotonic time in seconds.
double bench_now(void);

/// What bench_time_call measured: seconds per call (median and fastest sample), samples, calls per sample.
typedef struct bench_timing {
    double med_s, min_s;
    int samples;
    long passes;
} bench_timing;

/// Times fn(arg) as the pair rows are timed: a warm-up call (a call of a second or more is its
/// own warm-up and first sample), then `samples` samples (at most 64; fewer, at least 3, when
/// they would take more than max_row_s; with single_long, one when a single call of a second or
/// more already would) of enough calls each to last min_s. Returns 0, or -1 when fn failed.
int bench_time_call(int (*fn)(void *arg), void *arg, double min_s, double max_row_s, int samples, int single_long,
                    bench_timing *out);

/// Relative error above which a pair counts as a disagreement with the exact method.
static inline double bench_disagree_tol(int bytes) { return bytes == 8 ? 1e-9 : 1e-4; }

/// Path of ttd_fcl_bench: explicit (may be NULL), $TTD_FCL_BENCH, or next to this program.
/// Returns 0 and writes path when found and executable.
int bench_fcl_find(const char *explicit_path, char *path, size_t size);
/// The same search for any of the FCL side programs: explicit, $env_var, or name next to this
/// program (bench/fcl_mesh_link.c finds ttd_fcl_mesh_bench with it).
int bench_fcl_find_program(const char *name, const char *env_var, const char *explicit_path, char *path,
                           size_t size);
/// Runs FCL on n pairs (9n reals each in s and t, precision bytes); writes the distances
/// (as double) to dist and the median and fastest ns per pair. Returns 0 on success.
int bench_fcl_run(const char *program, int bytes, size_t n, const void *s, const void *t,
                  double min_sample_s, int samples, double *dist, double *ns_median, double *ns_min);

/// Times `ttd dist` in-process on n pairs (9n reals each in s and t, precision bytes), text or
/// binary (--binary-in --binary-out), distances only, one thread on instruction set isa:
/// one pass whose output is read back into dist (n doubles), then `samples` timed passes.
/// Writes the median and fastest ns per pair. Returns 0, or -1 when a pass failed or its
/// output did not hold n distances.
int bench_cli_run(int bytes, int binary, const char *isa, size_t n, const void *s, const void *t, int samples,
                  double *dist, double *ns_median, double *ns_min);

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


/// The best instruction set available here among those in mask (bit i: ttd_isa i), the portable
/// row ranked just above scalar; TTD_ISA_AUTO if none is.
ttd_isa bench_best_isa(unsigned mask);


#endif /* TTD_BENCH_INTERNAL_H */
