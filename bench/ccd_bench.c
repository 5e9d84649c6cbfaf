/* SPDX-License-Identifier: MIT */
/* `ttd bench ccd` (issue 33; docs/ccd.md, section 6): continuous collision on the CCD benchmark's
 * sample queries (a folder of its CSV files: the kept subset tests/data/ccd, or a clone of the
 * whole set with --queries DIR) and on generated families, beside a naive floating-point cubic
 * (the coplanarity cubic's roots in double, then an inside test in double): false negatives and
 * false positives against the files' truth, and time per query (mean, median, worst), one thread;
 * and Tight-Inclusion on the same queries where its helper program ttd_ti_ccd_bench was built
 * (bench/ti/; optional, a message says when it is absent).
 * Then deforming meshes (issue 34; docs/ccd.md, section 10): self-CCD of a sheet folding into
 * layers, step by step, one thread. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <errno.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "bench_internal.h"
#include "ccd_bench.h"
#include "ccd_rigid_bench.h"
#include "cli.h"
#include "meshes.h"

#ifndef TTD_CCD_SUBSET_DIR
#define TTD_CCD_SUBSET_DIR "tests/data/ccd"
#endif

/* ---- the naive cubic ------------------------------------------------------------------------ */

static void nsub(double r[3], const double a[3], const double b[3])
{
    for (int k = 0; k < 3; ++k)
        r[k] = a[k] - b[k];
}
static double ndot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
static void ncross(double r[3], const double a[3], const double b[3])
{
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
}

/* Positions at t of the 4 points. */
static void npos(const double *x0, const double *x1, double t, double x[4][3])
{
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k)
            x[i][k] = x0[3 * i + k] + t * (x1[3 * i + k] - x0[3 * i + k]);
}

/* The coplanarity determinant at t (VF: b - a, c - a, p - a; EE: a1 - a0, b0 - a0, b1 - a0). */
static double ncoplanar(int kind, const double *x0, const double *x1, double t)
{
    double x[4][3], u[3], v[3], w[3], c[3];
    npos(x0, x1, t, x);
    if (kind == 1) {
        nsub(u, x[2], x[1]), nsub(v, x[3], x[1]), nsub(w, x[0], x[1]);
    } else {
        nsub(u, x[1], x[0]), nsub(v, x[2], x[0]), nsub(w, x[3], x[0]);
    }
    ncross(c, u, v);
    return ndot(c, w);
}

/* Whether the (nearly coplanar) primitives touch at t, in double without tolerance. */
static int ninside(int kind, const double *x0, const double *x1, double t)
{
    double x[4][3], n[3], e[3], w[3], c[3];
    npos(x0, x1, t, x);
    if (kind == 1) {
        double u[3], v[3];
        nsub(u, x[2], x[1]), nsub(v, x[3], x[1]);
        ncross(n, u, v);
        for (int i = 0; i < 3; ++i) {
            nsub(e, x[1 + (i + 1) % 3], x[1 + i]);
            nsub(w, x[0], x[1 + i]);
            ncross(c, e, w);
            if (ndot(c, n) < 0)
                return 0;
        }
        return ndot(n, n) > 0;
    }
    double ea[3], eb[3];
    nsub(ea, x[1], x[0]), nsub(eb, x[3], x[2]), nsub(w, x[2], x[0]);
    ncross(n, ea, eb);
    const double nn = ndot(n, n);
    if (!(nn > 0))
        return 0;
    ncross(c, w, eb);
    const double s = ndot(c, n) / nn;
    ncross(c, w, ea);
    const double u = ndot(c, n) / nn;
    return s >= 0 && s <= 1 && u >= 0 && u <= 1;
}

/* The naive method: the cubic f(t) from its values at 0, 1/3, 2/3, 1, in double; split at the
 * roots of its derivative; each sign change bisected 60 times on the power form; the first root where the inside test
 * passes is the hit. Coplanar throughout (f = 0 everywhere): no root, no hit. */
static double naive_ccd(int kind, const double *x0, const double *x1)
{
    /* f's power-basis coefficients from its values at 0, 1/3, 2/3, 1 (Lagrange). */
    const double f0 = ncoplanar(kind, x0, x1, 0), f1 = ncoplanar(kind, x0, x1, 1.0 / 3);
    const double f2 = ncoplanar(kind, x0, x1, 2.0 / 3), f3 = ncoplanar(kind, x0, x1, 1);
    const double a = 4.5 * (-f0 + 3 * f1 - 3 * f2 + f3), b = 4.5 * (2 * f0 - 5 * f1 + 4 * f2 - f3);
    const double c = -5.5 * f0 + 9 * f1 - 4.5 * f2 + f3;
    double cuts[4] = {0, 0, 0, 0};
    int nc = 0;
    /* f' = 3a t^2 + 2b t + c. */
    const double A = 3 * a, B = 2 * b, disc = B * B - 4 * A * c;
    if (A != 0 && disc >= 0) {
        const double q = -0.5 * (B + copysign(sqrt(disc), B));
        const double r1 = q / A, r2 = q != 0 ? c / q : r1;
        if (r1 > 0 && r1 < 1)
            cuts[nc++] = r1;
        if (r2 > 0 && r2 < 1)
            cuts[nc++] = r2;
        if (nc == 2 && cuts[0] > cuts[1]) {
            const double t = cuts[0];
            cuts[0] = cuts[1], cuts[1] = t;
        }
    } else if (A == 0 && B != 0 && -c / B > 0 && -c / B < 1) {
        cuts[nc++] = -c / B;
    }
    double pts[6] = {0};
    int np = 0;
    pts[np++] = 0;
    for (int i = 0; i < nc; ++i)
        pts[np++] = cuts[i];
    pts[np++] = 1;
    for (int i = 0; i + 1 < np; ++i) {
        double lo = pts[i], hi = pts[i + 1];
        double flo = ((a * lo + b) * lo + c) * lo + f0, fhi = ((a * hi + b) * hi + c) * hi + f0;
        if (flo == 0 && ninside(kind, x0, x1, lo))
            return lo;
        if ((flo < 0) == (fhi < 0) && fhi != 0)
            continue;
        for (int it = 0; it < 60; ++it) {
            const double m = 0.5 * (lo + hi), fm = ((a * m + b) * m + c) * m + f0;
            if ((fm < 0) == (flo < 0) && fm != 0)
                lo = m, flo = fm;
            else
                hi = m;
        }
        if (ninside(kind, x0, x1, hi))
            return hi;
    }
    return INFINITY;
}

/* ---- queries and timing --------------------------------------------------------------------- */

typedef struct qset {
    char name[128];
    int kind;
    size_t n;
    double *x0, *x1;
    int *truth; /* NULL for generated families */
} qset;

typedef struct stats {
    size_t n, hits, fn, fp;
    double total, median, worst, mean;
} stats;

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* A set's figures from each query's time and answer: hits, false negatives and positives against
 * the truth where the set has one, total, mean, median (times are sorted here) and worst. */
static void set_stats(const qset *s, double *times, const unsigned char *hit, stats *st)
{
    memset(st, 0, sizeof *st);
    st->n = s->n;
    for (size_t q = 0; q < s->n; ++q) {
        st->hits += hit[q];
        if (s->truth) {
            st->fn += s->truth[q] && !hit[q];
            st->fp += !s->truth[q] && hit[q];
        }
        st->total += times[q];
        st->worst = times[q] > st->worst ? times[q] : st->worst;
    }
    st->mean = st->total / (double)s->n;
    qsort(times, s->n, sizeof *times, cmp_double);
    st->median = times[s->n / 2];
}

/* Times every query alone (the fastest of reps runs), one thread. method 0 ttd, 1 naive. */
static void time_set(const qset *s, int method, int reps, stats *st, double *times, unsigned char *hit)
{
    ttd_options o = ttd_default_options();
    o.threads = 1;
    const int na = s->kind, nb = 4 - s->kind;
    for (size_t q = 0; q < s->n; ++q) {
        const double *x0 = s->x0 + 12 * q, *x1 = s->x1 + 12 * q;
        double best = INFINITY;
        int h = 0;
        for (int r = 0; r < reps; ++r) {
            ttd_ccd_result res;
            const double t0 = bench_now();
            if (method == 0) {
                if (s->kind == 1)
                    ttd_ccd_vertex_face_d(&o, 1, x0, x0 + 3 * na, x1, x1 + 3 * na, 0, &res);
                else
                    ttd_ccd_edge_edge_d(&o, 1, x0, x0 + 3 * na, x1, x1 + 3 * na, 0, &res);
                h = (int)res.hit;
            } else {
                h = isfinite(naive_ccd(s->kind, x0, x1));
            }
            const double dt = bench_now() - t0;
            best = dt < best ? dt : best;
        }
        (void)nb;
        times[q] = best;
        hit[q] = (unsigned char)h;
    }
    set_stats(s, times, hit, st);
}

/* ---- Tight-Inclusion, through its helper program (bench/ti/ti_ccd_bench.cpp) ------------------- */

extern char **environ;

/* Runs TI on the set's queries: 0 with times and hits filled, -1 where the program fails. */
static int ti_run(const char *program, const qset *s, int reps, double *times, unsigned char *hit)
{
    const char *dir = getenv("TMPDIR");
    char in_name[512], out_name[512];
    snprintf(in_name, sizeof in_name, "%s/ttd-bench-ccd-XXXXXX", dir && *dir ? dir : "/tmp");
    snprintf(out_name, sizeof out_name, "%s/ttd-bench-ccd-ti-XXXXXX", dir && *dir ? dir : "/tmp");
    const int fd = mkstemp(in_name);
    if (fd < 0)
        return -1;
    const int fo = mkstemp(out_name);
    if (fo < 0) {
        close(fd);
        unlink(in_name);
        return -1;
    }
    close(fo);
    FILE *f = fdopen(fd, "wb");
    const int32_t kind = s->kind, r32 = reps;
    const uint64_t n = s->n;
    int ok = f != NULL && fwrite("TTDCCDQ1", 1, 8, f) == 8 && fwrite(&kind, sizeof kind, 1, f) == 1 &&
             fwrite(&r32, sizeof r32, 1, f) == 1 && fwrite(&n, sizeof n, 1, f) == 1;
    for (size_t q = 0; ok && q < s->n; ++q)
        ok = fwrite(s->x0 + 12 * q, sizeof(double), 12, f) == 12 && fwrite(s->x1 + 12 * q, sizeof(double), 12, f) == 12;
    ok = (f != NULL && fclose(f) == 0) && ok;
    if (f == NULL)
        close(fd);
    pid_t pid;
    char prog[4096];
    snprintf(prog, sizeof prog, "%s", program);
    char *argv[] = {prog, in_name, out_name, NULL};
    int status = 0;
    if (ok && posix_spawn(&pid, program, NULL, NULL, argv, environ) == 0) {
        while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
        }
        ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    } else {
        ok = 0;
    }
    FILE *g = ok ? fopen(out_name, "rb") : NULL;
    for (size_t q = 0; g != NULL && ok && q < s->n; ++q) {
        double rec[3];
        ok = fread(rec, sizeof(double), 3, g) == 3;
        hit[q] = rec[0] != 0;
        times[q] = rec[2];
    }
    if (g != NULL)
        fclose(g);
    unlink(in_name);
    unlink(out_name);
    return ok && g != NULL ? 0 : -1;
}

/* TI's counts and times for a set, as time_set gives ttd's. */
static int ti_set(const char *program, const qset *s, int reps, stats *st, double *times, unsigned char *hit)
{
    if (ti_run(program, s, reps, times, hit) != 0)
        return -1;
    set_stats(s, times, hit, st);
    return 0;
}

/* Every CSV file under dir (recursively) whose path names its kind. */
static int collect(const char *dir, size_t root, qset **sets, size_t *ns, size_t *cap)
{
    DIR *d = opendir(dir);
    if (d == NULL)
        return -1;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.')
            continue;
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        struct stat sb;
        if (stat(path, &sb) != 0)
            continue;
        if (S_ISDIR(sb.st_mode)) {
            collect(path, root, sets, ns, cap);
            continue;
        }
        const size_t len = strlen(path);
        if (len < 4 || strcmp(path + len - 4, ".csv") != 0)
            continue;
        if (!strstr(path, "vertex-face") && !strstr(path, "edge-edge"))
            continue;
        if (*ns == *cap) {
            *cap = *cap ? 2 * *cap : 32;
            qset *nsets = realloc(*sets, *cap * sizeof **sets);
            if (nsets == NULL)
                break;
            *sets = nsets;
        }
        qset *s = &(*sets)[*ns];
        size_t inexact;
        if (ttd_cli_ccd_read(path, 0, &s->kind, &s->n, &s->x0, &s->x1, &s->truth, &inexact) != 0)
            continue;
        snprintf(s->name, sizeof s->name, "%s", path + root + (path[root] == '/'));
        ++*ns;
    }
    closedir(d);
    return 0;
}

/* Generated families (no truth): hits and time only. Each family draws from its own seed, so that
 * a family's queries are the same whichever families a run selects (--families). */
static uint64_t bench_rng = 88172645463325252ull;
enum { CCD_FAMILIES = 8 };
static const char *const ccd_family[CCD_FAMILIES] = {"random", "coplanar motion", "parallel edges",
                                                    "touching at t = 1", "scaled 1e-8..1e8", "offset 1e6",
                                                    "near-degenerate 1e-12", "touching at t = 0"};
static const char *family_filter = NULL; /* --families SUBSTR: only the families whose name holds it */
static int family_selected(const char *name)
{
    return family_filter == NULL || strstr(name, family_filter) != NULL;
}
static double brand(void)
{
    bench_rng ^= bench_rng << 13;
    bench_rng ^= bench_rng >> 7;
    bench_rng ^= bench_rng << 17;
    return (double)(bench_rng >> 11) * 0x1p-53 * 2 - 1;
}

static void make_family(qset *s, const char *name, int kind, size_t n, int what)
{
    snprintf(s->name, sizeof s->name, "%s", name);
    bench_rng = 88172645463325252ull ^ (0x9e3779b97f4a7c15ull * (uint64_t)(16 * kind + what + 1));
    s->kind = kind;
    s->n = n;
    s->truth = NULL;
    s->x0 = malloc(n * 12 * sizeof(double));
    s->x1 = malloc(n * 12 * sizeof(double));
    for (size_t q = 0; q < n; ++q) {
        double *a = s->x0 + 12 * q, *b = s->x1 + 12 * q;
        for (int i = 0; i < 12; ++i) {
            a[i] = brand();
            b[i] = a[i] + 0.5 * brand();
        }
        if (what == 1) /* coplanar motion: everything in z = 0 */
            for (int i = 0; i < 4; ++i)
                a[3 * i + 2] = b[3 * i + 2] = 0;
        if (what == 2 && kind == 2) /* parallel edges: b = a shifted, both translating */
            for (int k = 0; k < 3; ++k) {
                a[6 + k] = a[k] + 1e-3 * brand(), a[9 + k] = a[3 + k] + a[6 + k] - a[k];
                b[k] = a[k] + 0.3, b[3 + k] = a[3 + k] + 0.3;
                b[6 + k] = a[6 + k] + 0.2 * brand(), b[9 + k] = a[9 + k] + b[6 + k] - a[6 + k];
            }
        if (what == 3) /* touching at the end: B's first point at t = 1 is A's first */
            for (int k = 0; k < 3; ++k)
                b[3 * kind + k] = b[k];
        if (what == 7) /* touching at the start: B's first point at t = 0 is A's first */
            for (int k = 0; k < 3; ++k)
                a[3 * kind + k] = a[k];
        if (what == 4) /* scaled by 1e-8 .. 1e8 */ {
            const double sc = pow(10.0, 8 * brand());
            for (int i = 0; i < 12; ++i)
                a[i] *= sc, b[i] *= sc;
        }
        if (what == 5) /* offset to 1e6 */
            for (int i = 0; i < 12; ++i)
                a[i] += 1e6, b[i] += 1e6;
        if (what == 6) /* near-degenerate: B's path shifted to pass 1e-12 from A's first point */
            for (int k = 0; k < 3; ++k) {
                const double d = a[3 * kind + k] - a[k];
                a[3 * kind + k] -= d, b[3 * kind + k] -= d;
                a[3 * kind + k] += 1e-12 * brand(), b[3 * kind + k] += 1e-12 * brand();
            }
    }
}

static void print_row(const char *name, const stats *t, const stats *nv, int truth, const stats *ti)
{
    if (truth) {
        printf("%-44s %6zu %5zu | %3zu %4zu %8.3f %7.3f %9.1f | %3zu %4zu %7.3f %8.3f | %6.1fx", name, t->n,
               t->hits, t->fn, t->fp, 1e6 * t->mean, 1e6 * t->median, 1e6 * t->worst, nv->fn, nv->fp,
               1e6 * nv->mean, 1e6 * nv->worst, t->total / nv->total);
        if (ti)
            printf(" | %3zu %4zu %10.3f %7.3f %11.1f", ti->fn, ti->fp, 1e6 * ti->mean, 1e6 * ti->median,
                   1e6 * ti->worst);
        printf("\n");
    }
    else
        printf("%-44s %6zu %5zu |   -    - %8.3f %7.3f %9.1f |   -    - %7.3f %8.3f | %6.1fx\n", name, t->n,
               t->hits, 1e6 * t->mean, 1e6 * t->median, 1e6 * t->worst, 1e6 * nv->mean, 1e6 * nv->worst,
               t->total / nv->total);
}


static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ---- the slowest queries (docs/ccd-speed.md) ---------------------------------------------------
 * --slowest K: every sample query timed again alone (CPU time of 10 calls, the fastest of reps), and
 * the K slowest listed with the intervals their search examined. */
typedef struct slow_query {
    double us;
    const qset *set;
    size_t q;
    ttd_ccd_result r;
} slow_query;

static void bench_slowest(const qset *sets, size_t ns, size_t k, int reps, const char *what)
{
    slow_query *top = calloc(k + 1, sizeof *top);
    if (top == NULL || k == 0) {
        free(top);
        return;
    }
    size_t have = 0;
    ttd_options o = ttd_default_options();
    o.threads = 1;
    for (size_t i = 0; i < ns; ++i) {
        const qset *s = &sets[i];
        const int na = s->kind;
        for (size_t q = 0; q < s->n; ++q) {
            const double *x0 = s->x0 + 12 * q, *x1 = s->x1 + 12 * q;
            double best = INFINITY;
            ttd_ccd_result r;
            for (int rep = 0; rep < reps; ++rep) {
                const double c0 = cpu_now();
                for (int j = 0; j < 10; ++j) {
                    if (na == 1)
                        ttd_ccd_vertex_face_d(&o, 1, x0, x0 + 3 * na, x1, x1 + 3 * na, 0, &r);
                    else
                        ttd_ccd_edge_edge_d(&o, 1, x0, x0 + 3 * na, x1, x1 + 3 * na, 0, &r);
                }
                best = fmin(best, (cpu_now() - c0) / 10);
            }
            /* insert into the sorted list, slowest first */
            size_t j = have < k ? have++ : k;
            for (; j > 0 && top[j - 1].us < 1e6 * best; --j)
                top[j] = top[j - 1];
            if (j < k)
                top[j] = (slow_query){1e6 * best, s, q, r};
        }
    }
    printf("  the %zu slowest %s (CPU time, the fastest of %d runs of 10 calls; intervals: evals)\n", have, what, reps);
    for (size_t j = 0; j < have; ++j)
        printf("  %8.1f us  %4u intervals  %s  %s query %zu (truth %d)\n", top[j].us, top[j].r.evals,
               top[j].r.hit ? "hit " : "miss", top[j].set->name, top[j].q, top[j].set->truth ? top[j].set->truth[top[j].q] : -1);
    free(top);
}

/* ---- batches: the screen in SIMD lanes against the scalar path ---------------------------------
 * (docs/ccd.md, section 11) A set as one batch call of the public entry: on the scalar row and on the
 * best instruction set here, one thread (CPU time a query, and their ratio), and on the best with all
 * cores (wall time a query, and the speedup: the one-thread wall time over it); each figure the
 * fastest of reps, each run repeating the batch until it has taken 50 ms of wall time. The answers of
 * the three are compared field by field. */

/* The set in the entry's layout: A's points of every query, then B's. */
static void lanes_layout(const qset *s, double *a0, double *a1)
{
    const size_t na = (size_t)s->kind, nb = 4 - na;
    for (size_t q = 0; q < s->n; ++q)
        for (size_t i = 0; i < 12; ++i) {
            const size_t dst = i < 3 * na ? 3 * na * q + i : 3 * na * s->n + 3 * nb * q + (i - 3 * na);
            a0[dst] = s->x0[12 * q + i];
            a1[dst] = s->x1[12 * q + i];
        }
}

static void lanes_call(const qset *s, const double *a0, const double *a1, ttd_isa isa, int threads, ttd_ccd_result *out)
{
    ttd_options o = ttd_default_options();
    o.isa = isa;
    o.threads = threads;
    const size_t na = (size_t)s->kind, n = s->n;
    if (s->kind == 1)
        ttd_ccd_vertex_face_d(&o, n, a0, a0 + 3 * na * n, a1, a1 + 3 * na * n, 0, out);
    else
        ttd_ccd_edge_edge_d(&o, n, a0, a0 + 3 * na * n, a1, a1 + 3 * na * n, 0, out);
}

/* Seconds a query, CPU time and wall time, each the fastest of reps runs. */
static void lanes_time(const qset *s, const double *a0, const double *a1, ttd_isa isa, int threads, int reps,
                       ttd_ccd_result *out, double *cpu, double *wall)
{
    *cpu = *wall = INFINITY;
    for (int r = 0; r < reps; ++r) {
        const double w0 = bench_now(), c0 = cpu_now();
        size_t calls = 0;
        double w, c;
        do {
            lanes_call(s, a0, a1, isa, threads, out);
            ++calls;
            w = bench_now() - w0;
            c = cpu_now() - c0;
        } while (w < 0.05);
        *cpu = fmin(*cpu, c / (double)(calls * s->n));
        *wall = fmin(*wall, w / (double)(calls * s->n));
    }
}

static int lanes_same(const ttd_ccd_result *a, const ttd_ccd_result *b, size_t n)
{
    for (size_t q = 0; q < n; ++q)
        if (memcmp(&a[q].toi, &b[q].toi, sizeof(double)) != 0 || memcmp(&a[q].gap, &b[q].gap, sizeof(double)) != 0 ||
            a[q].hit != b[q].hit || a[q].flags != b[q].flags || a[q].sub != b[q].sub || a[q].evals != b[q].evals)
            return 0;
    return 1;
}

static void lanes_row(const char *name, const qset *s, ttd_isa best, int reps)
{
    double *a0 = malloc(s->n * 12 * sizeof(double)), *a1 = malloc(s->n * 12 * sizeof(double));
    ttd_ccd_result *r0 = malloc(s->n * sizeof *r0), *r1 = malloc(s->n * sizeof *r1), *r2 = malloc(s->n * sizeof *r2);
    if (a0 == NULL || a1 == NULL || r0 == NULL || r1 == NULL || r2 == NULL) {
        printf("%-44s out of memory\n", name);
    } else {
        lanes_layout(s, a0, a1);
        double ts, tl, tt, ws, wl, wt;
        lanes_time(s, a0, a1, TTD_ISA_SCALAR, 1, reps, r0, &ts, &ws);
        lanes_time(s, a0, a1, best, 1, reps, r1, &tl, &wl);
        lanes_time(s, a0, a1, best, 0, reps, r2, &tt, &wt);
        size_t one = 0;
        for (size_t q = 0; q < s->n; ++q)
            one += !r0[q].hit && r0[q].evals == 1;
        printf("%-44s %6zu %6.1f%% | %9.3f %9.3f %7.2fx | %9.3f %6.2fx | %s\n", name, s->n, 100.0 * (double)one / (double)s->n,
               1e6 * ts, 1e6 * tl, ts / tl, 1e6 * wt, wl / wt, lanes_same(r0, r1, s->n) && lanes_same(r0, r2, s->n) ? "yes" : "NO");
    }
    free(a0), free(a1), free(r0), free(r1), free(r2);
}

/* The table: the sample queries (vertex-face and edge-edge, each as one batch) and the generated
 * families (fam_n queries each, made again by make_family). */
static void bench_lanes(const qset *sets, size_t ns, size_t fam_n, int reps)
{
    ttd_options o = ttd_default_options();
    const ttd_isa best = ttd_isa_selected(&o);
    printf("\nbatches: the screen in SIMD lanes (%s, %d doubles a vector) against the scalar path, one call a set\n",
           ttd_isa_name(best), ttd_isa_lanes(best, 8));
    printf("(us a query; one thread: CPU time; threads: all %d cores, wall time, speedup over one thread's wall time;\n"
           " fastest of %d; '1 step': the scalar search's answers of no hit in one evaluation; 'same': every answer's bits equal)\n",
           (int)sysconf(_SC_NPROCESSORS_ONLN), reps);
    printf("%-44s %6s %7s | %9s %9s %8s | %9s %7s | %s\n", "queries", "n", "1 step", "scalar", "lanes", "ratio",
           "threads", "speedup", "same");
    for (int kind = 1; kind <= 2; ++kind) {
        qset all = {"", kind, 0, NULL, NULL, NULL};
        for (size_t i = 0; i < ns; ++i)
            all.n += sets[i].kind == kind ? sets[i].n : 0;
        if (all.n == 0)
            continue;
        all.x0 = malloc(all.n * 12 * sizeof(double));
        all.x1 = malloc(all.n * 12 * sizeof(double));
        size_t off = 0;
        for (size_t i = 0; i < ns && all.x0 && all.x1; ++i)
            if (sets[i].kind == kind) {
                memcpy(all.x0 + 12 * off, sets[i].x0, sets[i].n * 12 * sizeof(double));
                memcpy(all.x1 + 12 * off, sets[i].x1, sets[i].n * 12 * sizeof(double));
                off += sets[i].n;
            }
        if (all.x0 && all.x1)
            lanes_row(kind == 1 ? "sample queries, vertex-face" : "sample queries, edge-edge", &all, best, reps);
        free(all.x0), free(all.x1);
    }
    for (int kind = 1; kind <= 2; ++kind)
        for (int w = 0; w < CCD_FAMILIES; ++w) {
            qset s;
            char name[128];
            snprintf(name, sizeof name, "%s %s", kind == 1 ? "vertex-face" : "edge-edge", ccd_family[w]);
            if ((w == 2 && kind == 1) || !family_selected(name))
                continue;
            make_family(&s, name, kind, fam_n, w);
            lanes_row(name, &s, best, reps);
            free(s.x0), free(s.x1);
        }
}

/* ---- deforming meshes ----------------------------------------------------------------------- */


/* Self-CCD of ttd_gen_folded_sheet(n) with 4 layers one grid edge (1/n) apart, the fold going from
 * 0.85 to 1 of flat in `steps` steps (the layers close in, no contact), then a step from 1 to 1.05
 * (the layers pass through one another; a long step, the ends moving about 0.02). Each step: ttd_mesh_self_ccd_d from the mesh at the
 * step's start to the next positions (the mesh moved there by ttd_mesh_set_vertices_d after,
 * untimed), one thread, the fastest of reps runs, in wall and CPU time. */
/* A digest of a mesh CCD answer (toi, and every pair's kind, ids, toi, gap and flags, bit for bit):
 * equal digests before and after a change to the query show it answers the same. FNV-1a. */
static uint64_t mesh_ccd_digest(const ttd_mesh_ccd_result *r)
{
    uint64_t h = 1469598103934665603ull;
    const unsigned char *p = (const unsigned char *)&r->toi;
    for (size_t i = 0; i < sizeof r->toi; ++i)
        h = (h ^ p[i]) * 1099511628211ull;
    for (size_t k = 0; k < r->count; ++k) {
        const ttd_mesh_ccd_pair *q = &r->pairs[k];
        const uint64_t f[8] = {q->kind, q->a[0], q->a[1], q->b[0], q->b[1], q->flags, 0, 0};
        double d[2] = {q->toi, q->gap};
        uint64_t w[10];
        memcpy(w, f, sizeof f);
        memcpy(w + 8, d, sizeof d);
        for (int j = 0; j < 10; ++j)
            for (int b = 0; b < 8; ++b)
                h = (h ^ ((w[j] >> (8 * b)) & 0xffu)) * 1099511628211ull;
    }
    return h;
}

static int bench_mesh_sheet(size_t n, int steps, int reps, unsigned flags, int closing_only)
{
    const int layers = 4;
    const double gap = 1.0 / (double)n;
    ttd_options o = ttd_default_options();
    o.threads = 1;
    ttd_gen_mesh g;
    if (ttd_gen_folded_sheet(n, layers, gap, 0.85, &g) != 0)
        return -1;
    ttd_mesh *m = NULL;
    if (ttd_mesh_create_d(&o, g.verts, g.nv, g.tris, g.nt, &m) != TTD_OK) {
        ttd_gen_mesh_free(&g);
        return -1;
    }
    printf("\nself-CCD of a folding sheet: %zu triangles, %d layers %.3g apart (one grid edge), %s; per step the "
           "fastest of %d runs, one thread\n",
           g.nt, layers, gap, flags ? "with the shared-vertex pairs" : "triangle pairs sharing no vertex", reps);
    printf("%-18s %10s %10s %12s %12s %10s %6s %10s %8s\n", "step (fold)", "wall_ms", "cpu_ms", "tri_pairs", "queries",
           "searched", "pairs", "toi", "digest");
    double sum_wall = 0, sum_cpu = 0;
    int rc = 0;
    for (int k = 0; k <= (closing_only ? steps - 1 : steps) && rc == 0; ++k) {
        /* the last step from flat to 1.05: through the other layers, a long step */
        const double f0 = k < steps ? 0.85 + 0.15 * k / steps : 1.0;
        const double f1 = k < steps ? 0.85 + 0.15 * (k + 1) / steps : 1.05;
        ttd_gen_mesh a, b;
        if (ttd_gen_folded_sheet(n, layers, gap, f0, &a) != 0 || ttd_gen_folded_sheet(n, layers, gap, f1, &b) != 0) {
            rc = -1;
            break;
        }
        double best_w = INFINITY, best_c = INFINITY;
        ttd_mesh_ccd_result r = {0};
        if (ttd_mesh_set_vertices_d(&o, m, a.verts) != TTD_OK)
            rc = -1;
        for (int rep = 0; rep < reps && rc == 0; ++rep) {
            ttd_mesh_ccd_free(&r);
            const double w0 = bench_now(), c0 = cpu_now();
            if (ttd_mesh_self_ccd_d(&o, m, b.verts, 0.0, flags, &r) != TTD_OK)
                rc = -1;
            const double c = cpu_now() - c0, w = bench_now() - w0;
            best_w = fmin(best_w, w);
            best_c = fmin(best_c, c);
        }
        if (rc == 0) {
            char name[32];
            snprintf(name, sizeof name, "%.3f -> %.3f", f0, f1);
            printf("%-18s %10.2f %10.2f %12llu %12llu %10llu %6zu %10.4g %08llx\n", name, best_w * 1e3, best_c * 1e3,
                   (unsigned long long)r.triangle_pairs, (unsigned long long)r.queries,
                   (unsigned long long)r.searches, r.count, r.toi,
                   (unsigned long long)(mesh_ccd_digest(&r) & 0xffffffffu));
            if (k < steps)
                sum_wall += best_w, sum_cpu += best_c;
        }
        ttd_mesh_ccd_free(&r);
        ttd_gen_mesh_free(&a);
        ttd_gen_mesh_free(&b);
    }
    if (rc == 0)
        printf("mean of the %d closing steps: %.2f ms wall, %.2f ms CPU (the issue's target: 20 ms a step of about "
               "100k triangles, one core)\n",
               steps, sum_wall * 1e3 / steps, sum_cpu * 1e3 / steps);
    ttd_mesh_destroy(m);
    ttd_gen_mesh_free(&g);
    return rc;
}

int bench_ccd_main(int argc, char **argv)
{
    const char *dir = TTD_CCD_SUBSET_DIR;
    int reps = 3, mesh_only = 0, steps = 60, use_ti = 1, closing_only = 0;
    size_t fam_n = 2000, sheet = 224, slowest = 0;
    const char *ti_path = NULL;
    for (int i = 1; i < argc; ++i) /* rigid bodies between two poses: their own rows (ccd_rigid_bench.c) */
        if (strcmp(argv[i], "--rigid") == 0)
            return bench_ccd_rigid_main(argc, argv);
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--queries") == 0 && i + 1 < argc)
            dir = argv[++i];
        else if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc)
            reps = atoi(argv[++i]) > 0 ? atoi(argv[i]) : 1;
        else if (strcmp(argv[i], "--family-size") == 0 && i + 1 < argc)
            fam_n = (size_t)strtoul(argv[++i], NULL, 10);
        else if (strcmp(argv[i], "--sheet") == 0 && i + 1 < argc)
            sheet = (size_t)strtoul(argv[++i], NULL, 10);
        else if (strcmp(argv[i], "--steps") == 0 && i + 1 < argc)
            steps = atoi(argv[++i]) > 0 ? atoi(argv[i]) : 1;
        else if (strcmp(argv[i], "--slowest") == 0 && i + 1 < argc)
            slowest = (size_t)strtoul(argv[++i], NULL, 10);
        else if (strcmp(argv[i], "--families") == 0 && i + 1 < argc)
            family_filter = argv[++i];
        else if (strcmp(argv[i], "--mesh-only") == 0)
            mesh_only = 1;
        else if (strcmp(argv[i], "--closing-only") == 0)
            mesh_only = closing_only = 1;
        else if (strcmp(argv[i], "--ti") == 0 && i + 1 < argc)
            ti_path = argv[++i];
        else if (strcmp(argv[i], "--no-ti") == 0)
            use_ti = 0;
        else {
            printf("usage: ttd bench ccd [--queries DIR] [--reps N] [--family-size N] [--ti PROGRAM | --no-ti]\n"
                   "                     [--sheet N] [--steps K] [--mesh-only | --closing-only] [--slowest K]\n"
                   "                     [--families SUBSTR]\n"
                   "       ttd bench ccd --rigid [--help for its options]: rigid bodies between two poses\n"
                   "  DIR: CSV files of the CCD benchmark's sample queries, searched recursively (a clone of\n"
                   "  Continuous-Collision-Detection/Sample-Queries; default the kept subset %s).\n"
                   "  Each query is timed alone, one thread, the fastest of N runs (default 3).\n"
                   "  Tight-Inclusion runs on the same queries through ttd_ti_ccd_bench (beside ttd, or\n"
                   "  $TTD_TI_BENCH, or --ti; built with cmake -DTTD_TIGHT_INCLUSION_DIR=<checkout>, see\n"
                   "  scripts/get-tight-inclusion.sh); skipped with a message when it is absent.\n"
                   "  Then self-CCD of a folding sheet of 2 N^2 triangles (default N 224: 100,352), K closing\n"
                   "  steps (default 60: the sheet's ends move about half a grid edge a step) and one step\n"
                   "  through itself; --mesh-only: that alone; --closing-only: the closing steps alone, pairs\n"
                   "  sharing no vertex (for profiling). --slowest K: the K slowest sample queries listed\n"
                   "  after their table, and each generated family's after its row (CPU time, intervals\n"
                   "  examined). --families SUBSTR: only the generated families whose name holds SUBSTR\n"
                   "  (\"touching\", \"edge-edge parallel\"; each family's queries are the same either way).\n",
                   TTD_CCD_SUBSET_DIR);
            return strcmp(argv[i], "--help") == 0 ? 0 : 2;
        }
    }
    bench_machine m;
    bench_machine_describe(&m);
    printf("ttd bench ccd: %s, %d cores, load %s, one thread, fastest of %d runs a query\n", m.cpu, m.cores,
           m.load_start, reps);
    if (mesh_only) {
        const int rc = sheet < 2 || bench_mesh_sheet(sheet, steps, reps, 0, closing_only) != 0 ||
                       (!closing_only && bench_mesh_sheet(sheet, steps, reps, TTD_SELF_SHARED_VERTEX, 0) != 0);
        char load_end[64];
        bench_load_average(load_end, sizeof load_end);
        printf("\nload at the end %s\n", load_end);
        return rc;
    }
    qset *sets = NULL;
    size_t ns = 0, cap = 0;
    if (collect(dir, strlen(dir), &sets, &ns, &cap) != 0 || ns == 0) {
        fprintf(stderr, "ttd bench ccd: no query files under '%s'\n", dir);
        free(sets);
        return 1;
    }
    /* Sorted by name for a stable table. */
    for (size_t i = 1; i < ns; ++i)
        for (size_t j = i; j > 0 && strcmp(sets[j - 1].name, sets[j].name) > 0; --j) {
            qset t = sets[j];
            sets[j] = sets[j - 1], sets[j - 1] = t;
        }
    char ti_prog[4096];
    const int have_ti = use_ti && bench_fcl_find_program("ttd_ti_ccd_bench", "TTD_TI_BENCH", ti_path, ti_prog,
                                                         sizeof ti_prog) == 0;
    if (!use_ti)
        printf("Tight-Inclusion: skipped (--no-ti)\n");
    else if (!have_ti)
        printf("Tight-Inclusion: skipped: ttd_ti_ccd_bench not found beside ttd (configure with "
               "-DTTD_TIGHT_INCLUSION_DIR=<checkout>; scripts/get-tight-inclusion.sh fetches one)\n");
    else
        printf("Tight-Inclusion: %s (double, err -1, minimum separation 0, tolerance 1e-6, max_itr 1e6), "
               "the same queries, fastest of %d runs\n", ti_prog, reps);
    printf("\n%-44s %6s %5s | %3s %4s %8s %7s %9s | %3s %4s %7s %8s | %7s%s\n", "queries (us a query)", "n", "hits",
           "FN", "FP", "mean", "median", "worst", "FN", "FP", "mean", "worst", "ttd/naive",
           have_ti ? " |  FN   FP       mean  median       worst" : "");
    printf("%-44s %6s %5s | %-32s | %-24s |%s\n", "", "", "", "ttd", "naive cubic",
           have_ti ? "         | Tight-Inclusion" : "");
    stats all_ti = {0};
    int ti_ok = have_ti;
    stats all_t = {0}, all_n = {0};
    size_t total = 0;
    for (size_t i = 0; i < ns; ++i)
        total += sets[i].n;
    double *all_times = malloc(total * sizeof(double)), *times = malloc(total * sizeof(double));
    unsigned char *hit = malloc(total);
    double *ti_times = malloc(total * sizeof(double));
    size_t ti_off = 0;
    size_t off = 0;
    for (size_t i = 0; i < ns; ++i) {
        stats t, nv;
        time_set(&sets[i], 0, reps, &t, times, hit);
        /* time_set sorted its times: keep them for the overall median. */
        memcpy(all_times + off, times, sets[i].n * sizeof(double));
        off += sets[i].n;
        time_set(&sets[i], 1, reps, &nv, times, hit);
        stats ti;
        if (ti_ok && ti_set(ti_prog, &sets[i], reps, &ti, times, hit) != 0) {
            printf("Tight-Inclusion: %s failed on %s; the rows go on without it\n", ti_prog, sets[i].name);
            ti_ok = 0;
        }
        if (ti_ok) {
            memcpy(ti_times + ti_off, times, sets[i].n * sizeof(double));
            ti_off += sets[i].n;
            all_ti.n += ti.n, all_ti.hits += ti.hits, all_ti.fn += ti.fn, all_ti.fp += ti.fp, all_ti.total += ti.total;
            all_ti.worst = fmax(all_ti.worst, ti.worst);
        }
        print_row(sets[i].name, &t, &nv, 1, ti_ok ? &ti : NULL);
        all_t.n += t.n, all_t.hits += t.hits, all_t.fn += t.fn, all_t.fp += t.fp, all_t.total += t.total;
        all_t.worst = fmax(all_t.worst, t.worst);
        all_n.n += nv.n, all_n.hits += nv.hits, all_n.fn += nv.fn, all_n.fp += nv.fp, all_n.total += nv.total;
        all_n.worst = fmax(all_n.worst, nv.worst);
    }
    all_t.mean = all_t.total / (double)all_t.n;
    all_n.mean = all_n.total / (double)all_n.n;
    qsort(all_times, total, sizeof(double), cmp_double);
    all_t.median = all_times[total / 2];
    if (ti_ok) {
        all_ti.mean = all_ti.total / (double)all_ti.n;
        qsort(ti_times, ti_off, sizeof(double), cmp_double);
        all_ti.median = ti_times[ti_off / 2];
    }
    print_row("all sample queries", &all_t, &all_n, 1, ti_ok ? &all_ti : NULL);
    if (ti_ok)
        printf("(Tight-Inclusion: total %.3f s, %.0fx ttd's; ttd's false positives %zu against its %zu)\n",
               all_ti.total, all_ti.total / all_t.total, all_t.fp, all_ti.fp);
    size_t positives = 0;
    for (size_t i = 0; i < ns; ++i)
        for (size_t q = 0; q < sets[i].n; ++q)
            positives += sets[i].truth[q] != 0;
    printf("(%zu files, %zu queries, %zu positive; the issue's targets: 0 FN, total time at most 50x the naive "
           "cubic's, no query over 50 us)\n",
           ns, total, positives);

    bench_slowest(sets, ns, slowest, reps, "sample queries");

    printf("\ngenerated families (no truth: hits and time only)\n");
    for (int kind = 1; kind <= 2; ++kind)
        for (int w = 0; w < CCD_FAMILIES; ++w) {
            qset s;
            char name[128];
            snprintf(name, sizeof name, "%s %s", kind == 1 ? "vertex-face" : "edge-edge", ccd_family[w]);
            if ((w == 2 && kind == 1) || !family_selected(name))
                continue;
            make_family(&s, name, kind, fam_n, w);
            double *ft = malloc(fam_n * sizeof(double));
            unsigned char *fh = malloc(fam_n);
            stats t, nv;
            time_set(&s, 0, reps, &t, ft, fh);
            time_set(&s, 1, reps, &nv, ft, fh);
            print_row(name, &t, &nv, 0, NULL);
            bench_slowest(&s, 1, slowest, reps, name);
            free(ft), free(fh), free(s.x0), free(s.x1);
        }
    bench_lanes(sets, ns, fam_n, reps);
    if (sheet >= 2 && (bench_mesh_sheet(sheet, steps, reps, 0, 0) != 0 ||
                       bench_mesh_sheet(sheet, steps, reps, TTD_SELF_SHARED_VERTEX, 0) != 0))
        fprintf(stderr, "ttd bench ccd: the folding sheet failed\n");
    char load_end[64];
    bench_load_average(load_end, sizeof load_end);
    printf("\nload at the end %s\n", load_end);
    for (size_t i = 0; i < ns; ++i)
        free(sets[i].x0), free(sets[i].x1), free(sets[i].truth);
    free(sets), free(all_times), free(times), free(hit), free(ti_times);
    return 0;
}
