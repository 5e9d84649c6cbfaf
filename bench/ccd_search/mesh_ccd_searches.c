/* SPDX-License-Identifier: MIT */
/* The primitive searches of one self-CCD step of `ttd bench ccd --mesh-only`'s folding sheet,
 * recorded and timed one by one (docs/ccd-speed.md, "The step through the layers"). Built by hand
 * (it compiles src/meshccd/meshccd.c into itself with a hook after each search, so the library
 * itself is unchanged):
 *
 *   cc -O2 -ffp-contract=off -Isrc -Iinclude -I. bench/ccd_search/mesh_ccd_searches.c \
 *      build/src/libttd.a build/gen/libttd_gen.a -lm -lpthread -o mesh_ccd_searches
 *   ./mesh_ccd_searches [N [STEP [OUTDIR [EVERY]]]]
 *
 * N: the sheet's grid (default 224: 100,352 triangles); STEP: `layers` (1 -> 1.05, the step
 * through the layers, the default) or k in 0..59 (the closing step 0.85 + 0.15 k / 60 -> the
 * next). Prints the searches by kind and by how many intervals each took, with their CPU time
 * (each search run again under a thread CPU clock, as the mesh query ran it: up to the earliest
 * toi found so far). With OUTDIR, writes in the CCD
 * benchmark's CSV format (8 rows a query, exact rationals, the 7th column this build's answer to
 * the whole query, t_stop HUGE_VAL):
 * OUTDIR/sample/{vertex-face,edge-edge}/data.csv every EVERY-th search (default 500) and
 * OUTDIR/slowest/{vertex-face,edge-edge}/data.csv the 8 slowest of each kind, which
 * `ttd bench ccd --queries OUTDIR/sample --sheet 0` times with any build of the search. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "ccd/ccd.h"

static void searched(int kind, const double *x0, const double *x1, const ttd_ccd_params *prm,
                     const ttd_ccd_result *r);
#define MESHCCD_SEARCHED(kind, x0, x1, prm, r) searched(kind, x0, x1, prm, r)
#define ttd_meshccd_run searches_meshccd_run
#define meshccd_tri_apart searches_tri_apart /* (the library has its own copy of each) */
#include "src/meshccd/meshccd.c"

#include "gen/meshes.h"

enum { NBUCKET = 6, NSLOW = 8 };
static const unsigned bucket_lo[NBUCKET] = {1, 2, 5, 17, 65, 257};

typedef struct rec {
    double x0[12], x1[12], us;
    unsigned evals, hit;
} rec;

static struct {
    size_t n[3][NBUCKET], hits[3];
    double us[3][NBUCKET];
    rec slow[3][NSLOW];
    size_t nslow[3], count[3], every;
    FILE *sample[3];
} S;

static double thread_cpu(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* One coordinate as numerator,denominator (exact: m 2^e with m odd). */
static void put_rational(FILE *f, double x)
{
    if (x == 0) {
        fputs("0,1", f);
        return;
    }
    int e;
    double m = frexp(x, &e); /* x = m 2^e, 0.5 <= |m| < 1 */
    m = ldexp(m, 53);
    e -= 53;
    while (fmod(m, 2) == 0) {
        m /= 2;
        ++e;
    }
    if (e >= 0)
        fprintf(f, "%.0f,1", ldexp(m, e));
    else
        fprintf(f, "%.0f,%.0f", m, ldexp(1, -e));
}

static void put_query(FILE *f, const double *x0, const double *x1, unsigned truth)
{
    for (int row = 0; row < 8; ++row) {
        const double *p = (row < 4 ? x0 : x1) + 3 * (row % 4);
        for (int k = 0; k < 3; ++k) {
            put_rational(f, p[k]);
            fputc(',', f);
        }
        fprintf(f, "%u\n", truth);
    }
}

/* 1 vertex-face, 2 edge-edge with the edges parallel at both ends (to 1e-9 of their lengths'
 * product: parallel edges are always coplanar, so the coplanarity cubic proves nothing), 0 other
 * edge-edge. */
static int klass(int kind, const double *x0, const double *x1)
{
    if (kind == TTD_CCD_VF)
        return 1;
    for (int end = 0; end < 2; ++end) {
        const double *x = end ? x1 : x0;
        double a[3], b[3], c[3];
        for (int k = 0; k < 3; ++k)
            a[k] = x[3 + k] - x[k], b[k] = x[9 + k] - x[6 + k];
        cross3(a, b, c);
        const double cc = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        const double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        const double lb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
        if (!(cc <= 1e-9 * la * lb))
            return 0;
    }
    return 2;
}

static void searched(int kind, const double *x0, const double *x1, const ttd_ccd_params *prm,
                     const ttd_ccd_result *r)
{
    /* timed as the mesh query ran it (t_stop: the earliest toi found so far + the tolerance) */
    ttd_ccd_result again;
    const double c0 = thread_cpu();
    ttd_ccd_query(kind, x0, x1, prm, &again);
    const double us = 1e6 * (thread_cpu() - c0);
    /* a file's query is searched whole (t_stop HUGE_VAL): its answer there, the 7th column */
    ttd_ccd_params p = *prm;
    p.t_stop = HUGE_VAL;
    ttd_ccd_result whole;
    ttd_ccd_query(kind, x0, x1, &p, &whole);
    const int c = klass(kind, x0, x1);
    int b = 0;
    while (b + 1 < NBUCKET && again.evals >= bucket_lo[b + 1])
        ++b;
    ++S.n[c][b];
    S.us[c][b] += us;
    S.hits[c] += again.hit;
    (void)r;
    const int file = kind == TTD_CCD_VF ? 0 : 1;
    if (S.sample[file] != NULL && S.count[file]++ % S.every == 0)
        put_query(S.sample[file], x0, x1, whole.hit);
    /* the slowest NSLOW of each kind (file): replace the fastest kept */
    rec *keep = S.slow[file];
    size_t *nk = &S.nslow[file], at = *nk;
    if (*nk == NSLOW) {
        at = 0;
        for (size_t i = 1; i < NSLOW; ++i)
            if (keep[i].us < keep[at].us)
                at = i;
        if (keep[at].us >= us)
            return;
    } else {
        ++*nk;
    }
    memcpy(keep[at].x0, x0, sizeof keep[at].x0);
    memcpy(keep[at].x1, x1, sizeof keep[at].x1);
    keep[at].us = us;
    keep[at].evals = again.evals;
    keep[at].hit = whole.hit;
}

static FILE *open_csv(const char *dir, const char *set, const char *kind)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, set);
    mkdir(dir, 0755);
    mkdir(path, 0755);
    snprintf(path, sizeof path, "%s/%s/%s", dir, set, kind);
    mkdir(path, 0755);
    snprintf(path, sizeof path, "%s/%s/%s/data.csv", dir, set, kind);
    FILE *f = fopen(path, "w");
    if (f == NULL)
        perror(path);
    return f;
}

int main(int argc, char **argv)
{
    const size_t n = argc > 1 ? (size_t)strtoul(argv[1], NULL, 10) : 224;
    const char *step = argc > 2 ? argv[2] : "layers";
    const char *dir = argc > 3 ? argv[3] : NULL;
    S.every = argc > 4 ? (size_t)strtoul(argv[4], NULL, 10) : 500;
    if (S.every == 0)
        S.every = 1;
    const int steps = 60;
    double f0 = 1.0, f1 = 1.05;
    if (strcmp(step, "layers") != 0) {
        const int k = atoi(step);
        f0 = 0.85 + 0.15 * k / steps;
        f1 = 0.85 + 0.15 * (k + 1) / steps;
    }
    const double gap = 1.0 / (double)n;
    ttd_gen_mesh a, b;
    if (n < 2 || ttd_gen_folded_sheet(n, 4, gap, f0, &a) != 0 || ttd_gen_folded_sheet(n, 4, gap, f1, &b) != 0) {
        fprintf(stderr, "mesh_ccd_searches: bad sheet\n");
        return 1;
    }
    if (dir != NULL) {
        S.sample[0] = open_csv(dir, "sample", "vertex-face");
        S.sample[1] = open_csv(dir, "sample", "edge-edge");
    }
    const meshccd_side side = {a.verts, b.verts, a.tris, a.nv, a.nt};
    ttd_mesh_ccd_result out;
    const double c0 = thread_cpu();
    ttd_isa isa = TTD_ISA_SCALAR; /* TTD_ISA picks the row, as in the library */
    if (ttd_dispatch_resolve(TTD_ISA_AUTO, &isa) != TTD_OK)
        isa = TTD_ISA_SCALAR;
    const ttd_status st = searches_meshccd_run(1, isa, &side, NULL, 0.0, 0, &out);
    const double total = thread_cpu() - c0;
    if (st != TTD_OK) {
        fprintf(stderr, "mesh_ccd_searches: status %d\n", (int)st);
        return 1;
    }
    printf("sheet %zu (%zu triangles), fold %.4f -> %.4f: %.3f s CPU with the timing (each search run three times); "
           "triangle pairs %llu, primitive pairs %llu, searched %llu, hits kept %zu, toi %.6g\n",
           n, a.nt, f0, f1, total, (unsigned long long)out.triangle_pairs, (unsigned long long)out.queries,
           (unsigned long long)out.searches, out.count, out.toi);
    static const char *cname[3] = {"edge-edge, not parallel", "vertex-face", "edge-edge, parallel"};
    double all = 0;
    for (int c = 0; c < 3; ++c)
        for (int bk = 0; bk < NBUCKET; ++bk)
            all += S.us[c][bk];
    for (int c = 0; c < 3; ++c) {
        size_t cn = 0;
        double cu = 0;
        for (int bk = 0; bk < NBUCKET; ++bk)
            cn += S.n[c][bk], cu += S.us[c][bk];
        printf("%-24s %9zu searches, %7zu hits, %9.1f ms (%4.1f%%), %.2f us each\n", cname[c], cn, S.hits[c], cu / 1e3,
               all > 0 ? 100 * cu / all : 0, cn ? cu / (double)cn : 0);
        for (int bk = 0; bk < NBUCKET; ++bk)
            if (S.n[c][bk])
                printf("    intervals >= %3u: %9zu searches, %9.1f ms, %.2f us each\n", bucket_lo[bk], S.n[c][bk],
                       S.us[c][bk] / 1e3, S.us[c][bk] / (double)S.n[c][bk]);
    }
    if (dir != NULL) {
        for (int f = 0; f < 2; ++f) {
            if (S.sample[f])
                fclose(S.sample[f]);
            FILE *o = open_csv(dir, "slowest", f ? "edge-edge" : "vertex-face");
            if (o == NULL)
                continue;
            for (size_t i = 0; i < S.nslow[f]; ++i) {
                put_query(o, S.slow[f][i].x0, S.slow[f][i].x1, S.slow[f][i].hit);
                printf("slowest %s %zu: %.1f us, %u intervals, hit %u\n", f ? "edge-edge" : "vertex-face", i,
                       S.slow[f][i].us, S.slow[f][i].evals, S.slow[f][i].hit);
            }
            fclose(o);
        }
    }
    ttd_mesh_ccd_free(&out);
    ttd_gen_mesh_free(&a);
    ttd_gen_mesh_free(&b);
    return 0;
}
