/* SPDX-License-Identifier: MIT */
/* `ttd bench`: times ttd's methods on the paper's workload (one pair replicated 1000 times,
 * section 4 and Figure 3 of the paper) and on generated families (gen/pairs.h), in both
 * precisions, on the scalar code and on every instruction set this machine runs, across
 * thread counts and working-set sizes, with FCL's triangle distance beside it on the same
 * data (bench/fcl/). Each row is a warm-up pass, then the median of several samples, each
 * sample being enough passes over the data to last --min-time; every ratio (speedup over
 * scalar, over one thread, over FCL) is between rows of this same run. Approximate methods
 * are checked against the exact method, in double, on the same (rounded) input.
 *
 * Timing passes ask for distances only (the common use); a separate untimed pass with full
 * results gives the accuracy, the iteration counts and the lane occupancy. */
#define _POSIX_C_SOURCE 200809L
#include "bench.h"
#include "bench_internal.h"
#include "rows.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"
#include "mesh_bench.h"
#include "deform_bench.h"
#include "points_bench.h"
#include "ccd_bench.h"
#include "scene_bench.h"
#include "mesh_workload.h"
#include "output.h"
#include "pairs.h"

/* What is run on a workload. */
enum {
    W_ALL_METHODS = 1u << 0, /* every method (else exact, penalty and certified) */
    W_ALL_ISAS = 1u << 1,    /* every SIMD ISA (else the best one) */
    W_SCALAR = 1u << 2,      /* scalar rows (the speedup baseline) */
    W_FCL = 1u << 3,         /* FCL beside */
    W_ACCURACY = 1u << 4,    /* untimed pass with results: errors, iterations, occupancy */
    W_THREADS = 1u << 5,     /* 1..all threads for exact and penalty (scalar and best ISA) */
    W_MULTI = 1u << 6,       /* best ISA also on all threads */
    W_CLI = 1u << 7,         /* `ttd dist` itself, text and binary (bench/cli_io.c) */
    W_MESH = 1u << 8         /* candidate pairs of a mesh query (bench/mesh_workload.c): the exact
                              * kernel's outputs and bound */
};

typedef struct workload_spec {
    const char *name;
    ttd_gen_family family;
    size_t n_full, n_quick;  /* 0: not in that mode's default list; W_MESH: poses */
    unsigned flags;
    double mesh_distance;    /* W_MESH: the copies' distance, relative to the mesh's size */
} workload_spec;

/* The mesh pair workloads' broad-phase margin and the bound of their bounded rows, relative to
 * the mesh's size (its bounding-box diagonal, 1), and the flat subdivisions of their mesh. */
#define BENCH_MESH_MARGIN 0.01
#define BENCH_MESH_LEVELS 2

#define BENCH_BIG_DEFAULT ((size_t)24000000)

static const workload_spec workloads[] = {
    {"paper", TTD_GEN_PAPER, 1000, 1000, W_ALL_METHODS | W_ALL_ISAS | W_SCALAR | W_FCL | W_ACCURACY, 0},
    {"random", TTD_GEN_RANDOM, 1000000, 10000,
     W_ALL_METHODS | W_ALL_ISAS | W_SCALAR | W_FCL | W_ACCURACY | W_THREADS, 0},
    /* The other families: exact, penalty and certified (penalty-ref and barrier are there for the
     * comparison with the paper, on its workload and on random pairs). */
    {"far", TTD_GEN_FAR, 250000, 0, W_ALL_ISAS | W_SCALAR | W_FCL | W_ACCURACY, 0},
    {"near_parallel_edges", TTD_GEN_NEAR_PARALLEL_EDGES, 250000, 0, W_ALL_ISAS | W_SCALAR | W_FCL | W_ACCURACY, 0},
    {"near_parallel_faces", TTD_GEN_NEAR_PARALLEL_FACES, 250000, 0, W_ALL_ISAS | W_SCALAR | W_FCL | W_ACCURACY, 0},
    /* The working-set sweep: 144 bytes of input per pair in double, so 1k pairs sit in L2,
     * 32k in L3 and 256k just beyond it; "random" is the 1M point and random-big the end. */
    {"random-1k", TTD_GEN_RANDOM, 1000, 0, W_SCALAR | W_ACCURACY | W_MULTI, 0},
    {"random-32k", TTD_GEN_RANDOM, 32000, 0, W_SCALAR | W_ACCURACY | W_MULTI, 0},
    {"random-256k", TTD_GEN_RANDOM, 256000, 0, W_SCALAR | W_ACCURACY | W_MULTI, 0},
    {"random-big", TTD_GEN_RANDOM, BENCH_BIG_DEFAULT, 0, W_MULTI, 0},
    /* The command line's own cost: random pairs through `ttd dist` as text and as binary
     * (rows cli-text and cli-binary; the random workload's exact rows are the same work
     * without the input and output). About a second in all. */
    {"cli", TTD_GEN_RANDOM, 50000, 10000, W_CLI | W_ACCURACY, 0},
    /* Candidate pairs of a margin query (margin 1% of the mesh's size) between two copies of a
     * mesh 1% and 0.2% of its size apart (16 and 4 poses; 1 with --quick), docs/benchmark.md. */
    {"mesh-near", TTD_GEN_RANDOM, 16, 0, W_MESH | W_ALL_ISAS | W_SCALAR | W_FCL | W_ACCURACY, 0.01},
    {"mesh-contact", TTD_GEN_RANDOM, 4, 1, W_MESH | W_ALL_ISAS | W_SCALAR | W_FCL | W_ACCURACY, 0.002},
};
#define N_WORKLOADS (sizeof workloads / sizeof workloads[0])

#define MAX_ROWS 1024

typedef struct bench_ctx {
    bench_settings st;
    double max_row_s;        /* stop adding samples past this much time per row */
    int max_threads;
    int quiet;
    int precisions[2];       /* bytes; 0 = unused slot */
    unsigned method_mask;
    unsigned isa_mask;
    int fcl_ok;
    char fcl_path[512];
    const char *save_pairs;  /* --save-pairs DIR: each pair workload's input written there, or NULL */
    int save_failed;         /* a --save-pairs file could not be written: exit status 1 */
    const char *pair_bunny;  /* the pair workloads' mesh file (the mesh section's bunny); NULL: an icosphere */
    ttd_gen_mesh pair_mesh, pair_mesh_coarse;
    char pair_mesh_desc[160];
    bench_row rows[MAX_ROWS];
    size_t nrows;
    double t_start;
} bench_ctx;

/* A workload's data, in both precisions, with the reference distances. */
typedef struct bench_data {
    const workload_spec *spec;
    size_t n;
    double *sd, *td;
    float *sf, *tf;
    double *ref[2], *size[2];   /* [0] double input, [1] float-rounded input; NULL if no accuracy */
    void *dist;                 /* n doubles: distance-only output of timed passes */
    void *results;              /* n ttd_result_d: untimed pass */
    double *scratch;            /* n doubles: per-pair errors */
} bench_data;

static const char *prec_name(int bytes) { return bytes == 8 ? "double" : "float"; }
static int prec_slot(int bytes) { return bytes == 8 ? 0 : 1; }

/* One line of progress on standard error, with the time since the start. */
__attribute__((format(printf, 2, 3))) static void progress(const bench_ctx *cx, const char *fmt, ...)
{
    va_list ap;
    if (cx->quiet)
        return;
    fprintf(stderr, "ttd bench [%6.1f s] ", bench_now() - cx->t_start);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
}

/* ---- small statistics ----------------------------------------------------------------- */

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median_of(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* The k-th smallest of v[0..n) (v is reordered), by quickselect. */
static double select_kth(double *v, size_t n, size_t k)
{
    size_t lo = 0, hi = n - 1;
    while (lo < hi) {
        double pivot = v[lo + (hi - lo) / 2];
        size_t i = lo, j = hi;
        while (i <= j) {
            while (v[i] < pivot)
                ++i;
            while (v[j] > pivot)
                --j;
            if (i <= j) {
                double tmp = v[i];
                v[i] = v[j];
                v[j] = tmp;
                ++i;
                if (j == 0)
                    break;
                --j;
            }
        }
        if (k <= j)
            hi = j;
        else if (k >= i)
            lo = i;
        else
            return v[k];
    }
    return v[k];
}

/* The size of a pair, for relative errors: the longest edge of either triangle. */
static double pair_size(const double *s, const double *t)
{
    double m = 0.0;
    for (int tri = 0; tri < 2; ++tri) {
        const double *v = tri ? t : s;
        for (int a = 0; a < 3; ++a) {
            int b = (a + 1) % 3;
            double dx = v[3 * a] - v[3 * b], dy = v[3 * a + 1] - v[3 * b + 1], dz = v[3 * a + 2] - v[3 * b + 2];
            double e = sqrt(dx * dx + dy * dy + dz * dz);
            if (e > m)
                m = e;
        }
    }
    return m;
}

/* Errors of dist (n values, as double) against the reference of precision bytes. With a finite
 * bound (a kernel's), a pair that both the reference and dist put above it has no error (the
 * kernel may report any distance above its bound there); the others are compared as usual. */
static void accuracy_bounded(bench_data *d, int bytes, const double *dist, double bound, bench_row *row)
{
    const double *ref = d->ref[prec_slot(bytes)], *size = d->size[prec_slot(bytes)];
    double tol = bench_disagree_tol(bytes), max_rel = 0.0, max_abs = 0.0;
    size_t disagree = 0;
    for (size_t i = 0; i < d->n; ++i) {
        if (ref[i] > bound && dist[i] > bound) {
            d->scratch[i] = 0.0;
            continue;
        }
        double abs_err = fabs(dist[i] - ref[i]);
        double scale = fmax(fmax(ref[i], size[i]), 1e-300);
        double rel = abs_err / scale;
        if (!(rel == rel)) /* NaN counts as the worst possible */
            rel = abs_err = BENCH_INF;
        d->scratch[i] = rel;
        if (rel > max_rel)
            max_rel = rel;
        if (abs_err > max_abs)
            max_abs = abs_err;
        disagree += rel > tol;
    }
    size_t k = (size_t)ceil(0.999 * (double)d->n) - 1;
    row->has_accuracy = 1;
    row->max_rel_err = max_rel;
    row->max_abs_err = max_abs;
    row->disagree = disagree;
    row->p999_rel_err = select_kth(d->scratch, d->n, k < d->n ? k : d->n - 1);
}

static void accuracy(bench_data *d, int bytes, const double *dist, bench_row *row)
{
    accuracy_bounded(d, bytes, dist, BENCH_INF, row);
}

/* ---- running ttd ---------------------------------------------------------------------- */

static ttd_status run_batch(const bench_data *d, int bytes, const ttd_options *o, size_t n, void *dist,
                            void *results)
{
    if (bytes == 8)
        return ttd_batch_d(o, n, d->sd, d->td, dist, results);
    return ttd_batch_f(o, n, d->sf, d->tf, dist, results);
}

static int simd_kernel_exists(ttd_isa isa, ttd_method m, int bytes)
{
    return isa == TTD_ISA_SCALAR || ttd_method_lanes(m, isa, bytes) > 1;
}

/* A row's timing from one measurement: samples, passes per sample (0: not counted), the median
 * and fastest sample in ns per pair. */
static void row_times(bench_row *r, int samples, long passes, double ns, double ns_min)
{
    r->samples = samples;
    r->passes = passes;
    r->ns_per_pair = ns;
    r->ns_min = ns_min;
    r->pairs_per_s = 1e9 / ns;
}

static bench_row *new_row(bench_ctx *cx, const bench_data *d, const char *method, int bytes,
                          const char *isa, int lanes, int threads)
{
    if (cx->nrows >= MAX_ROWS)
        return NULL;
    bench_row *r = &cx->rows[cx->nrows++];
    memset(r, 0, sizeof *r);
    snprintf(r->workload, sizeof r->workload, "%s", d->spec->name);
    snprintf(r->method, sizeof r->method, "%s", method);
    snprintf(r->isa, sizeof r->isa, "%s", isa);
    r->bytes = bytes;
    r->lanes = lanes;
    r->threads = threads;
    r->pairs = d->n;
    r->speedup_vs_scalar = r->lane_fraction = r->thread_speedup = r->speedup_vs_fcl = BENCH_NAN;
    r->max_rel_err = r->p999_rel_err = r->max_abs_err = BENCH_NAN;
    r->mean_iterations = r->occupancy = BENCH_NAN;
    return r;
}

static double time_passes(const bench_data *d, int bytes, const ttd_options *o, long passes, ttd_status *st)
{
    double t0 = bench_now();
    for (long k = 0; k < passes; ++k)
        *st = run_batch(d, bytes, o, d->n, d->dist, NULL);
    return bench_now() - t0;
}

/* Pairs in the warm-up pass: enough to load the code, start the threads and reach the steady
 * state, without doubling the time of the rows that take seconds per pass. */
#define BENCH_WARMUP_PAIRS ((size_t)65536)

/* Times one configuration and appends its row. Returns 0, or -1 when ttd refused it. */
static int measure(bench_ctx *cx, bench_data *d, int bytes, ttd_method m, ttd_isa isa, int threads)
{
    ttd_options o = ttd_default_options();
    o.method = m;
    o.isa = isa;
    o.threads = threads;
    ttd_status st = run_batch(d, bytes, &o, d->n < BENCH_WARMUP_PAIRS ? d->n : BENCH_WARMUP_PAIRS, d->dist, NULL);
    if (st >= TTD_ERR_FIRST_FATAL) {
        fprintf(stderr, "ttd bench: %s %s %s %s: %s\n", d->spec->name, ttd_method_name(m), prec_name(bytes),
                ttd_isa_name(isa), ttd_status_string(st));
        return -1;
    }
    /* One full pass decides how many passes make a sample; when it is long enough it is the
     * first sample itself. Rows of many seconds per pass get fewer samples (at least 3). */
    double t[64];
    int have = 0;
    double one = time_passes(d, bytes, &o, 1, &st);
    long passes = 1;
    if (one >= cx->st.min_sample_s)
        t[have++] = one * 1e9 / (double)d->n;
    else
        passes = (long)fmin(ceil(cx->st.min_sample_s / fmax(one, 1e-9)), 1e8);
    int samples = cx->st.samples;
    while (samples > 3 && one * (double)passes * samples > cx->max_row_s)
        --samples;
    while (have < samples) {
        t[have++] = time_passes(d, bytes, &o, passes, &st) * 1e9 / ((double)passes * (double)d->n);
    }
    double fastest = t[0];
    for (int k = 1; k < samples; ++k)
        fastest = fmin(fastest, t[k]);

    bench_row *r = new_row(cx, d, ttd_method_name(m), bytes, ttd_isa_name(isa), ttd_isa_lanes(isa, bytes), threads);
    if (!r)
        return -1;
    r->samples = samples;
    r->passes = passes;
    r->ns_per_pair = median_of(t, samples);
    r->ns_min = fastest;
    r->pairs_per_s = 1e9 / r->ns_per_pair;

    if ((d->spec->flags & W_ACCURACY) && d->results) {
        run_batch(d, bytes, &o, d->n, NULL, d->results);
        double *dist = (double *)d->dist;
        size_t nc = 0, fb = 0;
        double it_sum = 0.0, blockmax_sum = 0.0;
        int lanes = r->lanes > 0 ? r->lanes : 1;
        for (size_t b = 0; b < d->n; b += (size_t)lanes) {
            size_t e = b + (size_t)lanes < d->n ? b + (size_t)lanes : d->n;
            unsigned mx = 0;
            for (size_t i = b; i < e; ++i) {
                unsigned it, flags;
                if (bytes == 8) {
                    const ttd_result_d *x = (const ttd_result_d *)d->results + i;
                    dist[i] = x->distance;
                    it = x->iterations;
                    flags = x->flags;
                } else {
                    const ttd_result_f *x = (const ttd_result_f *)d->results + i;
                    dist[i] = (double)x->distance;
                    it = x->iterations;
                    flags = x->flags;
                }
                nc += (flags & TTD_PAIR_NOT_CONVERGED) != 0;
                fb += (flags & TTD_PAIR_FALLBACK) != 0;
                it_sum += it;
                mx = it > mx ? it : mx;
            }
            blockmax_sum += (double)mx * (double)(e - b);
        }
        accuracy(d, bytes, dist, r);
        r->not_converged = nc;
        r->fallback = fb;
        if (m != TTD_METHOD_EXACT) {
            r->has_iterations = 1;
            r->mean_iterations = it_sum / (double)d->n;
            r->occupancy = lanes > 1 && blockmax_sum > 0.0 ? it_sum / blockmax_sum : BENCH_NAN;
        }
    }
    progress(cx, "%s %s %s %s %dt: %.2f ns/pair", d->spec->name, ttd_method_name(m), prec_name(bytes),
             ttd_isa_name(isa), threads, r->ns_per_pair);
    return 0;
}

static void measure_fcl(bench_ctx *cx, bench_data *d, int bytes)
{
    double ns = BENCH_NAN, ns_min = BENCH_NAN;
    const void *s = bytes == 8 ? (const void *)d->sd : (const void *)d->sf;
    const void *t = bytes == 8 ? (const void *)d->td : (const void *)d->tf;
    if (bench_fcl_run(cx->fcl_path, bytes, d->n, s, t, cx->st.min_sample_s, cx->st.samples, d->dist, &ns,
                      &ns_min) != 0) {
        fprintf(stderr, "ttd bench: FCL (%s) failed on %s %s; its rows are left out\n", cx->fcl_path,
                d->spec->name, prec_name(bytes));
        return;
    }
    bench_row *r = new_row(cx, d, "fcl", bytes, "scalar", 1, 1);
    if (!r)
        return;
    row_times(r, cx->st.samples, 0, ns, ns_min);
    if (d->ref[prec_slot(bytes)])
        accuracy(d, bytes, d->dist, r);
    progress(cx, "%s fcl %s: %.2f ns/pair", d->spec->name, prec_name(bytes), ns);
}

/* ---- workloads ------------------------------------------------------------------------ */

static void free_data(bench_data *d)
{
    free(d->sd);
    free(d->td);
    free(d->sf);
    free(d->tf);
    for (int k = 0; k < 2; ++k) {
        free(d->ref[k]);
        free(d->size[k]);
    }
    free(d->dist);
    free(d->results);
    free(d->scratch);
    memset(d, 0, sizeof *d);
}

/* Exact distances in double on the input as given (k = 0) or rounded to float (k = 1). */
static int make_reference(bench_data *d, int k)
{
    size_t n = d->n;
    double *s = d->sd, *t = d->td, *rs = NULL, *rt = NULL;
    if (k == 1) {
        rs = malloc(9 * n * sizeof *rs);
        rt = malloc(9 * n * sizeof *rt);
        if (!rs || !rt) {
            free(rs);
            free(rt);
            return -1;
        }
        for (size_t i = 0; i < 9 * n; ++i) {
            rs[i] = (double)d->sf[i];
            rt[i] = (double)d->tf[i];
        }
        s = rs;
        t = rt;
    }
    d->ref[k] = malloc(n * sizeof(double));
    d->size[k] = malloc(n * sizeof(double));
    int rc = -1;
    if (d->ref[k] && d->size[k]) {
        ttd_options o = ttd_default_options();
        o.isa = TTD_ISA_SCALAR;
        ttd_status st = ttd_batch_d(&o, n, s, t, d->ref[k], NULL);
        if (st < TTD_ERR_FIRST_FATAL) {
            for (size_t i = 0; i < n; ++i)
                d->size[k][i] = pair_size(s + 9 * i, t + 9 * i);
            rc = 0;
        }
    }
    free(rs);
    free(rt);
    return rc;
}

/* Bytes of memory the kernel reports as available, or 0 when unknown. */
static double mem_available(void)
{
    FILE *f = fopen("/proc/meminfo", "r");
    char line[256];
    double kb = 0.0;
    if (!f)
        return 0.0;
    while (fgets(line, sizeof line, f))
        if (sscanf(line, "MemAvailable: %lf kB", &kb) == 1)
            break;
    fclose(f);
    return kb * 1024.0;
}

/* The mesh workload w with `poses` poses (the mesh is loaded on first need): its pairs into
 * d->sd and d->td, d->n set. */
static int mesh_pairs(bench_ctx *cx, const workload_spec *w, size_t poses, bench_data *d)
{
    if (!cx->pair_mesh.nt) {
        if (bench_cand_mesh_load(cx->pair_bunny, BENCH_MESH_LEVELS, &cx->pair_mesh, &cx->pair_mesh_coarse,
                                 cx->pair_mesh_desc, sizeof cx->pair_mesh_desc) != 0)
            return -1;
        snprintf(cx->st.pair_mesh, sizeof cx->st.pair_mesh, "%s; margin %g of its size", cx->pair_mesh_desc,
                 BENCH_MESH_MARGIN);
        progress(cx, "mesh pair workloads: %s", cx->st.pair_mesh);
    }
    bench_cand_set set;
    if (bench_cand_make(&cx->pair_mesh, &cx->pair_mesh_coarse, cx->pair_mesh_desc, w->mesh_distance, BENCH_MESH_MARGIN,
                            (int)poses, cx->st.seed, (size_t)20000000, &set) != 0 ||
        set.n == 0) {
        bench_cand_free(&set);
        return -1;
    }
    progress(cx, "%s: %zu candidate pairs from %d poses, %zu (%.1f%%) within the margin", w->name, set.n, set.poses,
             set.within, 100.0 * (double)set.within / (double)set.n);
    d->n = set.n;
    d->sd = set.s;
    d->td = set.t;
    set.s = set.t = NULL;
    bench_cand_free(&set);
    return 0;
}

static int load_data(bench_ctx *cx, const workload_spec *w, size_t n, bench_data *d)
{
    int accuracy_wanted = (w->flags & (W_ACCURACY | W_FCL)) != 0;
    memset(d, 0, sizeof *d);
    d->spec = w;
    if (w->flags & W_MESH) {
        if (mesh_pairs(cx, w, n, d) != 0)
            return -1;
        n = d->n;
    }
    d->n = n;
    if (!(w->flags & W_MESH)) {
        d->sd = malloc(9 * n * sizeof *d->sd);
        d->td = malloc(9 * n * sizeof *d->td);
    }
    d->sf = malloc(9 * n * sizeof *d->sf);
    d->tf = malloc(9 * n * sizeof *d->tf);
    d->dist = malloc(n * sizeof(double));
    if (!d->sd || !d->td || !d->sf || !d->tf || !d->dist)
        return -1;
    if (!(w->flags & W_MESH) && ttd_gen(w->family, cx->st.seed, n, d->sd, d->td) != n)
        return -1;
    for (size_t i = 0; i < 9 * n; ++i) {
        d->sf[i] = (float)d->sd[i];
        d->tf[i] = (float)d->td[i];
    }
    if (accuracy_wanted) {
        d->results = malloc(n * sizeof(ttd_result_d));
        d->scratch = malloc(n * sizeof(double));
        if (!d->results || !d->scratch || make_reference(d, 0) != 0 || make_reference(d, 1) != 0)
            return -1;
    }
    return 0;
}

static ttd_isa best_simd(void)
{
    return bench_best_isa(~0u);
}

/* Rows cli-text and cli-binary: `ttd dist` on the workload's pairs, exact method, one thread,
 * the best instruction set --isa allows; the distances it printed are checked against the
 * reference like any other row's. */
static void measure_cli(bench_ctx *cx, bench_data *d)
{
    const ttd_isa isa = bench_best_isa(cx->isa_mask);
    if (isa == TTD_ISA_AUTO || !(cx->method_mask & (1u << TTD_METHOD_EXACT)))
        return;
    const int samples = cx->st.samples < 3 ? cx->st.samples : 3;
    for (int form_p = 0; form_p < 4; ++form_p) {
        const int binary = form_p / 2, bytes = cx->precisions[form_p % 2];
        if (!bytes)
            continue;
        const void *s = bytes == 8 ? (const void *)d->sd : (const void *)d->sf;
        const void *t = bytes == 8 ? (const void *)d->td : (const void *)d->tf;
        double ns = BENCH_NAN, ns_min = BENCH_NAN;
        const char *form = binary ? "cli-binary" : "cli-text";
        if (bench_cli_run(bytes, binary, ttd_isa_name(isa), d->n, s, t, samples, d->dist, &ns, &ns_min) != 0) {
            fprintf(stderr, "ttd bench: %s %s failed; its row is left out\n", form, prec_name(bytes));
            continue;
        }
        bench_row *r = new_row(cx, d, "exact", bytes, ttd_isa_name(isa), ttd_isa_lanes(isa, bytes), 1);
        if (!r)
            return;
        snprintf(r->workload, sizeof r->workload, "%s", form);
        row_times(r, samples, 1, ns, ns_min);
        accuracy(d, bytes, d->dist, r);
        progress(cx, "%s exact %s %s 1t: %.2f ns/pair", form, prec_name(bytes), ttd_isa_name(isa), ns);
    }
}

/* The rows of a mesh workload, in one precision: ttd's exact kernel called directly (the public
 * API has neither points alone nor a bound) for each output and with and without the margin as
 * its bound, on every instruction set (the scalar row: distances only), one thread. */
static void measure_mesh(bench_ctx *cx, bench_data *d, int bytes)
{
    static const struct {
        const char *method;
        int output;  /* bench_cand_time: 0 distances, 1 and points, 2 full results */
        int bounded; /* the margin as the kernel's bound */
    } variants[] = {{"exact", 0, 0}, {"exact+pts", 1, 0}, {"exact+full", 2, 0}, {"exact@m", 0, 1}, {"exact+pts@m", 1, 1}};
    const void *s = bytes == 8 ? (const void *)d->sd : (const void *)d->sf;
    const void *t = bytes == 8 ? (const void *)d->td : (const void *)d->tf;
    if (!(cx->method_mask & (1u << TTD_METHOD_EXACT)))
        return;
    for (int i = TTD_ISA_SCALAR; i < TTD_ISA_COUNT; ++i) {
        const ttd_isa isa = (ttd_isa)i;
        if (!(cx->isa_mask & (1u << i)) || !ttd_isa_available(isa))
            continue;
        for (size_t v = 0; v < sizeof variants / sizeof variants[0]; ++v) {
            if (isa == TTD_ISA_SCALAR && v > 0)
                continue;
            const double bound = variants[v].bounded ? BENCH_MESH_MARGIN : BENCH_INF;
            double ns = BENCH_NAN, ns_min = BENCH_NAN;
            if (bench_cand_time(d->n, s, t, bytes, isa, variants[v].output, bound, cx->st.samples, cx->st.min_sample_s,
                                (double *)d->dist, &ns, &ns_min) != 0) {
                fprintf(stderr, "ttd bench: %s %s %s %s failed; its row is left out\n", d->spec->name,
                        variants[v].method, prec_name(bytes), ttd_isa_name(isa));
                continue;
            }
            bench_row *r = new_row(cx, d, variants[v].method, bytes, ttd_isa_name(isa), ttd_isa_lanes(isa, bytes), 1);
            if (!r)
                return;
            row_times(r, cx->st.samples, 0, ns, ns_min);
            accuracy_bounded(d, bytes, (const double *)d->dist, bytes == 8 ? bound : (double)(float)bound, r);
            progress(cx, "%s %s %s %s 1t: %.2f ns/pair", d->spec->name, variants[v].method, prec_name(bytes),
                     ttd_isa_name(isa), ns);
        }
    }
}

/* --save-pairs DIR: the workload's pairs as `ttd dist --binary-in` reads them (18 numbers a
 * pair, S's 9 then T's 9), DIR/NAME.f64 in double and DIR/NAME.f32 rounded to float, so that a
 * row's kernel can be profiled on the very pairs it timed (bench/instr_mix.sh FAMILY file:PATH). */
static void save_pairs(bench_ctx *cx, const bench_data *d)
{
    for (int p = 0; p < 2; ++p) {
        char path[1100];
        snprintf(path, sizeof path, "%s/%s.%s", cx->save_pairs, d->spec->name, p ? "f32" : "f64");
        FILE *f = fopen(path, "wb");
        int ok = f != NULL;
        for (size_t i = 0; ok && i < d->n; ++i)
            ok = p ? fwrite(d->sf + 9 * i, sizeof(float), 9, f) == 9 && fwrite(d->tf + 9 * i, sizeof(float), 9, f) == 9
                   : fwrite(d->sd + 9 * i, sizeof(double), 9, f) == 9 &&
                         fwrite(d->td + 9 * i, sizeof(double), 9, f) == 9;
        if ((f && fclose(f) != 0) || !ok) {
            fprintf(stderr, "ttd bench: cannot write %s: %s\n", path, strerror(errno));
            cx->save_failed = 1;
        } else
            progress(cx, "%s: %zu pairs written to %s", d->spec->name, d->n, path);
    }
}

static void run_workload(bench_ctx *cx, const workload_spec *w, size_t n)
{
    bench_data d;
    double t0 = bench_now();
    if (load_data(cx, w, n, &d) != 0) {
        fprintf(stderr, "ttd bench: cannot set up %s (%zu pairs): out of memory or bad family; skipped\n",
                w->name, n);
        free_data(&d);
        return;
    }
    progress(cx, "%s: data and reference ready in %.2f s", w->name, bench_now() - t0);
    if (cx->save_pairs)
        save_pairs(cx, &d);
    ttd_isa best = best_simd();
    if (w->flags & W_CLI) {
        measure_cli(cx, &d);
        free_data(&d);
        return;
    }
    for (int p = 0; p < 2; ++p) {
        int bytes = cx->precisions[p];
        if (!bytes)
            continue;
        if ((w->flags & W_FCL) && cx->fcl_ok)
            measure_fcl(cx, &d, bytes);
        if (w->flags & W_MESH) {
            measure_mesh(cx, &d, bytes);
            continue;
        }
        for (int m = 0; m < TTD_METHOD_COUNT; ++m) {
            if (!(cx->method_mask & (1u << m)))
                continue;
            if (!(w->flags & W_ALL_METHODS) && m != TTD_METHOD_EXACT && m != TTD_METHOD_PENALTY &&
                m != TTD_METHOD_CERTIFIED)
                continue;
            for (int i = TTD_ISA_SCALAR; i < TTD_ISA_COUNT; ++i) {
                ttd_isa isa = (ttd_isa)i;
                if (!(cx->isa_mask & (1u << i)) || !ttd_isa_available(isa))
                    continue;
                if (isa == TTD_ISA_SCALAR && !(w->flags & W_SCALAR))
                    continue;
                if (isa != TTD_ISA_SCALAR && !(w->flags & W_ALL_ISAS) && isa != best)
                    continue;
                if (!simd_kernel_exists(isa, (ttd_method)m, bytes))
                    continue; /* the engine would run the scalar row: nothing new to time */
                if (measure(cx, &d, bytes, (ttd_method)m, isa, 1) != 0)
                    continue;
                int scaling = (w->flags & W_THREADS) && (isa == best || isa == TTD_ISA_SCALAR) &&
                              (m == TTD_METHOD_EXACT || m == TTD_METHOD_PENALTY);
                int multi = (w->flags & W_MULTI) && isa == best;
                for (int th = 2; th <= cx->max_threads; ++th)
                    if (scaling || (multi && th == cx->max_threads))
                        measure(cx, &d, bytes, (ttd_method)m, isa, th);
            }
        }
    }
    free_data(&d);
}

/* ---- ratios between rows -------------------------------------------------------------- */

static const bench_row *find_row(const bench_ctx *cx, const bench_row *like, const char *method,
                                 const char *isa, int threads)
{
    for (size_t i = 0; i < cx->nrows; ++i) {
        const bench_row *r = &cx->rows[i];
        if (strcmp(r->workload, like->workload) == 0 && r->bytes == like->bytes &&
            strcmp(r->method, method) == 0 && strcmp(r->isa, isa) == 0 && r->threads == threads)
            return r;
    }
    return NULL;
}

static void derive_ratios(bench_ctx *cx)
{
    for (size_t i = 0; i < cx->nrows; ++i) {
        bench_row *r = &cx->rows[i];
        const bench_row *scalar = find_row(cx, r, r->method, "scalar", 1);
        const bench_row *one = find_row(cx, r, r->method, r->isa, 1);
        const bench_row *fcl = find_row(cx, r, "fcl", "scalar", 1);
        if (scalar) {
            r->speedup_vs_scalar = scalar->ns_per_pair / r->ns_per_pair;
            r->lane_fraction = r->speedup_vs_scalar / (double)(r->lanes * r->threads);
        }
        if (one)
            r->thread_speedup = one->ns_per_pair / r->ns_per_pair;
        if (fcl)
            r->speedup_vs_fcl = fcl->ns_per_pair / r->ns_per_pair;
    }
}

/* ---- command line --------------------------------------------------------------------- */

static void usage(FILE *f)
{
    fputs("usage: ttd bench [options]\n"
          "Times ttd's methods (exact, penalty, penalty-ref, barrier, certified) in double and float, scalar\n"
          "and on every SIMD instruction set this machine runs, on the paper's workload (one pair\n"
          "x1000) and on generated families, with FCL beside it when ttd_fcl_bench is built.\n"
          "\n"
          "  --quick              a run of a few seconds (CI smoke test): paper, 10k random pairs, cli\n"
          "  --json               write JSON to standard output instead of the table\n"
          "  --csv                write CSV to standard output instead of the table\n"
          "  --out DIR            also write DIR/bench.txt, DIR/bench.json and DIR/bench.csv\n"
          "  --workloads LIST     comma-separated, from: paper random far near_parallel_edges\n"
          "                       near_parallel_faces random-1k random-32k random-256k random-big\n"
          "                       cli (ttd dist itself on random pairs, text and binary: rows\n"
          "                       cli-text and cli-binary) mesh-near mesh-contact (candidate pairs of\n"
          "                       a mesh query: rows exact, exact+pts, exact+full, exact@m, exact+pts@m)\n"
          "                       (the mesh: the bunny as the mesh section finds it, subdivided twice;\n"
          "                       an icosphere without it and with --quick)\n"
          "  --pairs N            pairs in the random workload (default 1000000; --quick 10000)\n"
          "  --big N              pairs in random-big (default 24000000, less if memory is short)\n"
          "  --methods LIST       comma-separated method names (default: all)\n"
          "  --precision LIST     double,float (default both)\n"
          "  --isa LIST           scalar,sse2,avx2,avx512,neon (default: every one available); one this\n"
          "                       machine cannot run is an error (exit status 2)\n"
          "  --threads N          most threads in the scaling rows (default: all cores)\n"
          "  --samples N          timed samples per row, median reported (default 5; --quick 3)\n"
          "  --min-time S         seconds per sample at least (default 0.1; --quick 0.005)\n"
          "  --seed N             generator seed (default 1)\n"
          "  --fcl PATH           the ttd_fcl_bench program (default: next to ttd, or $TTD_FCL_BENCH)\n"
          "  --no-fcl             leave FCL out\n"
          "  --save-pairs DIR     also write each pair workload's pairs to DIR/NAME.f64 and NAME.f32 in the\n"
          "                       format of `ttd dist --binary-in` (for bench/instr_mix.sh FAMILY file:PATH)\n"
          "  --no-probes          skip the clock, peak-arithmetic and bandwidth probes\n"
          "  --quiet              no progress on standard error\n"
          "\n"
          "When the 1-minute load average exceeds the online cores at the start or the end, a warning goes\n"
          "to standard error and into the header (other work competed for the CPU: do not trust the\n"
          "timings). TTD_BENCH_LOADAVG=FILE reads the load averages from FILE instead of /proc/loadavg\n"
          "(for tests). Exit status: 0 done, 1 nothing measured or a file not written, 2 bad options.\n",
          f);
    bench_mesh_usage(f);
    bench_scene_usage(f);
    bench_deform_usage(f);
}

static const char *isa_name_of(int i) { return i == TTD_ISA_AUTO ? NULL : ttd_isa_name((ttd_isa)i); }

/* A comma-separated list of names into a mask (instruction sets in any letter case). */
static int parse_list(const char *arg, const char *kind, unsigned *mask, const char *(*name_of)(int), int count)
{
    char buf[256];
    snprintf(buf, sizeof buf, "%s", arg);
    *mask = 0;
    for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
        int found = -1;
        for (int i = 0; i < count; ++i) {
            const char *nm = name_of(i);
            if (nm && (strcmp(nm, tok) == 0 || (name_of == isa_name_of && ttd_isa_from_name(tok) == (ttd_isa)i)))
                found = i;
        }
        if (found < 0) {
            fprintf(stderr, "ttd bench: unknown %s '%s'\n", kind, tok);
            return -1;
        }
        *mask |= 1u << found;
    }
    return 0;
}

static const char *method_name_of(int i) { return ttd_method_name((ttd_method)i); }
static const char *workload_name_of(int i) { return i < (int)N_WORKLOADS ? workloads[i].name : NULL; }

static int parse_size(const char *s, size_t *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (errno || end == s || *end || !(v >= 1.0) || v > 4e9)
        return -1;
    *out = (size_t)v;
    return 0;
}

static int write_file(const char *dir, const char *name, bench_ctx *cx, const bench_machine *m, int kind)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "ttd bench: cannot write %s: %s\n", path, strerror(errno));
        return -1;
    }
    if (kind == 0)
        bench_write_table(f, m, &cx->st, cx->rows, cx->nrows);
    else if (kind == 1)
        bench_write_json(f, m, &cx->st, cx->rows, cx->nrows);
    else if (kind == 2)
        bench_write_csv(f, cx->rows, cx->nrows);
    else if (kind == 3)
        bench_mesh_write_csv(f, cx->st.mesh);
    else
        bench_scene_write_csv(f, cx->st.scene);
    if (fclose(f) != 0) {
        fprintf(stderr, "ttd bench: cannot write %s\n", path);
        return -1;
    }
    return 0;
}

int ttd_bench_main(int argc, char **argv)
{
    if (argc > 1 && strcmp(argv[1], "points") == 0) /* the point queries' section (points_bench.c) */
        return bench_points_main(argc - 1, argv + 1);
    if (argc > 1 && strcmp(argv[1], "ccd") == 0) /* continuous collision (ccd_bench.c) */
        return bench_ccd_main(argc - 1, argv + 1);
    bench_ctx *cx = calloc(1, sizeof *cx);
    bench_machine machine;
    int want_json = 0, want_csv = 0, no_fcl = 0, probes = 1, rc = 0;
    const char *out_dir = NULL, *fcl_arg = NULL;
    unsigned workload_mask = 0;
    size_t pairs = 0, big = BENCH_BIG_DEFAULT;
    int samples = 0;
    double min_time = -1.0;
    bench_mesh_config mesh_cfg;
    bench_mesh_results *mesh = NULL;
    bench_scene_config scene_cfg;
    bench_scene_results *scene = NULL;
    bench_deform_config deform_cfg;
    bench_deform_results *deform = NULL;
    memset(&deform_cfg, 0, sizeof deform_cfg);
    memset(&mesh_cfg, 0, sizeof mesh_cfg);
    memset(&scene_cfg, 0, sizeof scene_cfg);
    if (!cx) {
        fprintf(stderr, "ttd bench: out of memory\n");
        return 1;
    }
    cx->st.seed = 1;
    snprintf(cx->st.pair_mesh, sizeof cx->st.pair_mesh, "not run");
    cx->method_mask = (1u << TTD_METHOD_COUNT) - 1;
    cx->isa_mask = ~0u;
    cx->precisions[0] = 8;
    cx->precisions[1] = 4;
    bench_machine_describe(&machine);
    cx->max_threads = machine.cores;
    {
        size_t used = 0;
        for (int i = 0; i < argc && used < sizeof cx->st.command; ++i) {
            int k = snprintf(cx->st.command + used, sizeof cx->st.command - used, "%s%s", i ? " " : "ttd ",
                             argv[i]);
            if (k < 0)
                break;
            used += (size_t)k;
        }
    }

    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        int takes = 1, took;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            usage(stdout);
            free(cx);
            return 0;
        } else if (strcmp(a, "--quick") == 0) {
            cx->st.quick = 1;
            takes = 0;
        } else if (strcmp(a, "--json") == 0) {
            want_json = 1;
            takes = 0;
        } else if (strcmp(a, "--csv") == 0) {
            want_csv = 1;
            takes = 0;
        } else if (strcmp(a, "--no-fcl") == 0) {
            no_fcl = 1;
            takes = 0;
        } else if (strcmp(a, "--no-probes") == 0) {
            probes = 0;
            takes = 0;
        } else if (strcmp(a, "--quiet") == 0) {
            cx->quiet = 1;
            takes = 0;
        } else if (bench_deform_option(&deform_cfg, a)) {
            takes = 0;
        } else if ((took = bench_mesh_option(&mesh_cfg, a, v)) != 0) {
            rc = took < 0 ? 3 : rc;
            takes = took - 1;
        } else if ((took = bench_scene_option(&scene_cfg, a, v)) != 0) {
            rc = took < 0 ? 3 : rc;
            takes = took - 1;
        } else if (!v) {
            fprintf(stderr, "ttd bench: unknown option or missing value: %s (see ttd bench --help)\n", a);
            rc = 2;
        } else if (strcmp(a, "--out") == 0) {
            out_dir = v;
        } else if (strcmp(a, "--fcl") == 0) {
            fcl_arg = v;
        } else if (strcmp(a, "--save-pairs") == 0) {
            cx->save_pairs = v;
        } else if (strcmp(a, "--workloads") == 0) {
            rc = parse_list(v, "workload", &workload_mask, workload_name_of, (int)N_WORKLOADS) ? 2 : rc;
        } else if (strcmp(a, "--methods") == 0) {
            rc = parse_list(v, "method", &cx->method_mask, method_name_of, TTD_METHOD_COUNT) ? 2 : rc;
        } else if (strcmp(a, "--isa") == 0) {
            rc = parse_list(v, "instruction set", &cx->isa_mask, isa_name_of, TTD_ISA_COUNT) ? 2 : rc;
        } else if (strcmp(a, "--precision") == 0) {
            cx->precisions[0] = strstr(v, "double") ? 8 : 0;
            cx->precisions[1] = strstr(v, "float") ? 4 : 0;
            if (!cx->precisions[0] && !cx->precisions[1]) {
                fprintf(stderr, "ttd bench: --precision takes double, float or double,float\n");
                rc = 2;
            }
        } else if (strcmp(a, "--pairs") == 0) {
            rc = parse_size(v, &pairs) ? 2 : rc;
        } else if (strcmp(a, "--big") == 0) {
            rc = parse_size(v, &big) ? 2 : rc;
        } else if (strcmp(a, "--threads") == 0) {
            cx->max_threads = atoi(v);
            if (cx->max_threads < 1 || cx->max_threads > 1024)
                rc = 2;
        } else if (strcmp(a, "--samples") == 0) {
            samples = atoi(v);
            if (samples < 1 || samples > 64)
                rc = 2;
        } else if (strcmp(a, "--min-time") == 0) {
            min_time = atof(v);
            if (!(min_time >= 0.0 && min_time <= 60.0))
                rc = 2;
        } else if (strcmp(a, "--seed") == 0) {
            cx->st.seed = strtoull(v, NULL, 0);
        } else {
            fprintf(stderr, "ttd bench: unknown option %s (see ttd bench --help)\n", a);
            rc = 3;
        }
        if (rc) {
            if (rc == 2 && takes && v)
                fprintf(stderr, "ttd bench: bad value for %s: %s\n", a, v);
            free(cx);
            return 2;
        }
        i += takes;
    }
    ttd_cli_warn_isa_env("bench");
    /* An instruction set named in --isa that this machine cannot run is an error, as in
     * `ttd dist --isa`: its rows would silently be missing. */
    for (int i = TTD_ISA_SCALAR; i < TTD_ISA_COUNT && cx->isa_mask != ~0u; ++i) {
        if ((cx->isa_mask & (1u << i)) && !ttd_isa_available((ttd_isa)i)) {
            fprintf(stderr, "ttd bench: --isa %s is not available here; this machine has:\n",
                    ttd_isa_name((ttd_isa)i));
            ttd_cli_print_isas(stderr);
            free(cx);
            return 2;
        }
    }
    cx->st.samples = samples ? samples : (cx->st.quick ? 3 : 5);
    cx->st.min_sample_s = min_time >= 0.0 ? min_time : (cx->st.quick ? 0.005 : 0.1);
    cx->max_row_s = cx->st.quick ? 0.5 : 8.0;
    cx->t_start = bench_now();
    if (bench_load_exceeds_cores(&machine))
        fprintf(stderr, "ttd bench: warning: the 1-minute load average (%.2f) exceeds the %d online cores: other "
                        "work competes for the CPU, the timings are not to be trusted\n",
                machine.load1_start, machine.cores);

    if (no_fcl) {
        snprintf(cx->st.fcl, sizeof cx->st.fcl, "left out (--no-fcl)");
    } else if (bench_fcl_find(fcl_arg, cx->fcl_path, sizeof cx->fcl_path) == 0) {
        cx->fcl_ok = 1;
        snprintf(cx->st.fcl, sizeof cx->st.fcl, "%s", cx->fcl_path);
    } else {
        snprintf(cx->st.fcl, sizeof cx->st.fcl,
                 "not found (install FCL with `apt-get install libfcl-dev` and rebuild; "
                 "or pass --fcl PATH)");
        if (!cx->quiet)
            fprintf(stderr, "ttd bench: FCL's program ttd_fcl_bench %s\n", cx->st.fcl);
    }

    if (probes) {
        progress(cx, "probing clock, peak arithmetic and memory bandwidth");
        bench_machine_probe(&machine, cx->st.quick ? 0.01 : 0.1,
                            cx->st.quick ? ((size_t)64 << 20) : ((size_t)512 << 20));
    }

    /* The mesh pair workloads' mesh: the bunny where the mesh section looks for it first
     * (--bunny, $TTD_BUNNY, build/data/bunny.obj); with --quick, as there, generated meshes only. */
    if (!cx->st.quick) {
        const char *env = getenv("TTD_BUNNY");
        cx->pair_bunny = mesh_cfg.bunny[0] ? mesh_cfg.bunny : (env && *env) ? env : "build/data/bunny.obj";
    }

    for (size_t w = 0; w < N_WORKLOADS && !deform_cfg.only && (workload_mask || (!mesh_cfg.named && !scene_cfg.named));
         ++w) {
        const workload_spec *ws = &workloads[w];
        size_t n = cx->st.quick ? ws->n_quick : ws->n_full;
        if (workload_mask) {
            if (!(workload_mask & (1u << w)))
                continue;
            if (n == 0)
                n = ws->n_full;
        } else if (n == 0) {
            continue;
        }
        if (strcmp(ws->name, "random") == 0 && pairs)
            n = pairs;
        if (ws->family == TTD_GEN_RANDOM && ws->n_full == BENCH_BIG_DEFAULT) {
            /* input in both precisions plus the output: about 224 bytes a pair */
            double avail = mem_available();
            n = big;
            if (avail > 0.0 && (double)n * 224.0 > 0.5 * avail) {
                size_t fit = (size_t)(0.5 * avail / 224.0);
                fprintf(stderr, "ttd bench: %s reduced from %zu to %zu pairs to fit in memory\n", ws->name, n, fit);
                n = fit;
            }
        }
        if (n > 0)
            run_workload(cx, ws, n);
    }
    if (!deform_cfg.only && bench_mesh_wanted(&mesh_cfg, workload_mask != 0 || scene_cfg.named)) {
        bench_mesh_env env = {&cx->st, cx->max_threads, cx->isa_mask, no_fcl, cx->precisions[0] != 0,
                              cx->precisions[1] != 0, cx->quiet, cx->t_start};
        cx->st.mesh = mesh = bench_mesh_run(&mesh_cfg, &env);
    }
    if (!deform_cfg.only && bench_scene_wanted(&scene_cfg, workload_mask != 0 || mesh_cfg.named)) {
        bench_scene_env env = {&cx->st, cx->max_threads, cx->isa_mask, no_fcl, cx->precisions[1] != 0,
                               cx->quiet, cx->t_start, &mesh_cfg};
        cx->st.scene = scene = bench_scene_run(&scene_cfg, &env);
    }
    /* the deforming-mesh section: by default with the others, unless sections were named */
    if (!deform_cfg.disabled && (deform_cfg.only || !(workload_mask || mesh_cfg.named || scene_cfg.named))) {
        bench_deform_env env = {&cx->st, no_fcl, cx->quiet, cx->t_start};
        cx->st.deform = deform = bench_deform_run(&deform_cfg, &env);
    }
    derive_ratios(cx);
    machine.load1_end = bench_load_average(machine.load_end, sizeof machine.load_end);
    if (machine.load1_end > (double)machine.cores)
        fprintf(stderr, "ttd bench: warning: the 1-minute load average at the end (%.2f, with this benchmark's "
                        "own threads) exceeds the %d online cores: the timings are not to be trusted\n",
                machine.load1_end, machine.cores);

    if (want_json)
        bench_write_json(stdout, &machine, &cx->st, cx->rows, cx->nrows);
    else if (want_csv)
        bench_write_csv(stdout, cx->rows, cx->nrows);
    else
        bench_write_table(stdout, &machine, &cx->st, cx->rows, cx->nrows);
    if (out_dir) {
        if (mkdir(out_dir, 0777) != 0 && errno != EEXIST) {
            fprintf(stderr, "ttd bench: cannot create %s: %s\n", out_dir, strerror(errno));
            rc = 1;
        } else if (write_file(out_dir, "bench.txt", cx, &machine, 0) || write_file(out_dir, "bench.json", cx, &machine, 1) ||
                   write_file(out_dir, "bench.csv", cx, &machine, 2) ||
                   (cx->st.mesh && write_file(out_dir, "bench-mesh.csv", cx, &machine, 3)) ||
                   (cx->st.scene && write_file(out_dir, "bench-scene.csv", cx, &machine, 4))) {
            rc = 1;
        }
    }
    if (cx->save_failed)
        rc = 1;
    if (cx->nrows == 0 && bench_mesh_row_count(cx->st.mesh) == 0 && bench_scene_row_count(cx->st.scene) == 0 &&
        bench_deform_row_count(cx->st.deform) == 0) {
        fprintf(stderr, "ttd bench: no rows were measured: the chosen methods have no kernel of their own on the "
                        "chosen instruction sets (the barrier method is scalar only), or every workload failed\n");
        rc = 1;
    }
    progress(cx, "done: %zu rows",
             cx->nrows + bench_mesh_row_count(cx->st.mesh) + bench_scene_row_count(cx->st.scene) +
                 bench_deform_row_count(cx->st.deform));
    bench_deform_free(deform);
    bench_mesh_free(mesh);
    bench_scene_free(scene);
    ttd_gen_mesh_free(&cx->pair_mesh);
    ttd_gen_mesh_free(&cx->pair_mesh_coarse);
    free(cx);
    return rc;
}
