/* SPDX-License-Identifier: MIT */
/* What the files of `ttd bench` share: the machine description, the probes of peak arithmetic
 * and memory bandwidth, the timer, the FCL side program and `ttd dist` timed in-process. The
 * pair rows and the run's settings, which bench.c fills and output.c writes, are in rows.h.
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

/// What bench_time_alternating measured: rounds of one sample of a, then one of b beside it.
typedef struct bench_alternation {
    double ratio_med, ratio_lo, ratio_hi; ///< a's sample / b's in the same round: median, min, max
    double a_med_s, a_min_s, b_med_s, b_min_s; ///< seconds per call of each
    int rounds;
    long passes[2];           ///< calls per sample of a and of b
} bench_alternation;

/// Times fa(a) and fb(b) alternately, a's sample then b's, in rounds, so that both see the same
/// load; the ratio of two rows timed apart moves with whatever else the machine did between them.
/// One warm-up call each, then samples of enough calls to last min_s (one call with min_s 0), at
/// least min_rounds and at most max_rounds (at most 64) rounds, stopping once the samples
/// took max_s. thread_cpu: the calling thread's CPU time instead of the monotonic clock (only
/// for calls that run on the calling thread alone). Returns 0, or -1 when a call failed or a
/// sample read no time (a clock too coarse for it).
int bench_time_alternating(int (*fa)(void *), void *a, int (*fb)(void *), void *b, int thread_cpu, double min_s,
                           int min_rounds, int max_rounds, double max_s, bench_alternation *out);

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

/// The best instruction set available here among those in mask (bit i: ttd_isa i), the portable
/// row ranked just above scalar; TTD_ISA_AUTO if none is.
ttd_isa bench_best_isa(unsigned mask);


#endif /* TTD_BENCH_INTERNAL_H */
