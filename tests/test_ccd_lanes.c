/* SPDX-License-Identifier: MIT */
/* Continuous collision in SIMD lanes (simd/kernel_ccd.h, docs/ccd.md, section 11): every row's
 * screen (the cuda-host row's too) against the scalar screen ttd_ccd_screen, bit for bit, on the
 * generated families (random, near-degenerate, coplanar motion, parallel edges, touching at t = 0
 * and t = 1, scaled 1e-8..1e8, offsets to 1e6, zero-length edges and zero-area faces, no motion,
 * coordinates at the screen's limit, non-finite) and the kept sample queries of the CCD benchmark;
 * every query it proves free checked against the scalar search (no hit, one evaluation); and the
 * batch entries (vertex-face, edge-edge, triangles; double and float) on every instruction set and
 * thread count against the scalar search query by query, every output field to the bit. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ccd/ccd.h"
#include "isa_rows.h"
#include "test_macros.h"
#include "ttd/ttd.h"

#define TEST_RAND_SEED 0x2545f4914f6cdd1dull
#include "test_rand.h"
#include "ccd_families.h"

/* Every row's screen on the set against the scalar screen, in groups of 1 to 8 queries, at delta and
 * t_max; *proved counts the queries the scalar screen proves. Each proved query's search: no hit
 * after one evaluation (what the batch writes for it). */
static int screen_set(const char *name, const qset *s, double delta, double t_max, size_t *proved)
{
    unsigned char *want = malloc(s->n);
    for (size_t q = 0; q < s->n; ++q) {
        want[q] = (unsigned char)ttd_ccd_screen(s->kind, s->x0 + 12 * q, s->x1 + 12 * q, delta, t_max);
        *proved += want[q];
        if (want[q]) {
            ttd_ccd_params p = ttd_ccd_default_params();
            p.delta = delta;
            p.t_max = t_max;
            ttd_ccd_result r;
            ttd_ccd_query(s->kind, s->x0 + 12 * q, s->x1 + 12 * q, &p, &r);
            ENSURE_MSG(r.hit == 0 && r.evals == 1 && r.toi == HUGE_VAL, "%s query %zu: screened, search hit %u evals %u",
                       name, q, r.hit, r.evals);
        }
    }
    int rows = 0;
    for (const isa_row *row = isa_rows; row->name != NULL; ++row) {
        const char *why = "";
        if (!cpu_runs(row->name, &why))
            continue;
        ENSURE_MSG(row->d->ccd_screen != NULL, "row %s has no ccd_screen", row->name);
        ++rows;
        size_t q = 0;
        for (int g = 0; q < s->n; ++g) {
            const int count = (int)(s->n - q < (size_t)(1 + g % 8) ? s->n - q : (size_t)(1 + g % 8));
            const unsigned m = row->d->ccd_screen(s->kind, count, s->x0 + 12 * q, s->x1 + 12 * q, delta, t_max);
            for (int i = 0; i < count; ++i)
                ENSURE_MSG(((m >> i) & 1u) == want[q + (size_t)i], "%s, row %s, query %zu (delta %g, t_max %g): lanes %u, scalar %u",
                           name, row->name, q + (size_t)i, delta, t_max, (m >> i) & 1u, want[q + (size_t)i]);
            ENSURE_MSG((m >> count) == 0, "%s, row %s: bits past the group", name, row->name);
            q += (size_t)count;
        }
    }
    ENSURE(rows >= 2); /* cuda-host and at least one SIMD row on any machine the tests run on */
    free(want);
    return 0;
}

static int screen_rows(void)
{
    const double deltas[3] = {0, 1e-3, 0.05}, tmax[2] = {1.0, 0.37};
    for (int fam = 0; fam < F_COUNT; ++fam)
        for (int kind = 1; kind <= 2; ++kind) {
            qset s = make_set(fam, kind, 1500);
            size_t proved = 0, tried = 0;
            for (int d = 0; d < 3; ++d)
                for (int t = 0; t < 2; ++t) {
                    if (screen_set(family_name[fam], &s, deltas[d] * (fam == F_HUGE ? 0x1p399 : 1), tmax[t], &proved))
                        return 1;
                    tried += s.n;
                }
            printf("  %-10s %-36s screen proves %5.1f%%\n", kind == 1 ? "vertex-face" : "edge-edge", family_name[fam],
                   100.0 * (double)proved / (double)tried);
            /* The comparison means something only where the screen proves queries. */
            if (fam == F_RANDOM || fam == F_SCALED || fam == F_OFFSET)
                ENSURE(proved > tried / 2);
            if (fam == F_NONFINITE)
                ENSURE(proved == 0);
            free(s.x0), free(s.x1);
        }
    return 0;
}

/* A sample file: the screen on every row against the scalar screen, at delta 0 and 1e-4 (walk_csv's
 * fn; ctx: the counts). */
typedef struct screen_counts {
    size_t tot, proved;
} screen_counts;

static int screen_file(const char *path, const qset *s, void *ctx)
{
    screen_counts *c = ctx;
    c->tot += 2 * s->n;
    return screen_set(path, s, 0, 1, &c->proved) || screen_set(path, s, 1e-4, 1, &c->proved);
}

/* The kept sample queries of the CCD benchmark (tests/data/ccd), at delta 0 and 1e-4. */
static int screen_samples(void)
{
    size_t files = 0;
    screen_counts c = {0, 0};
    ENSURE(walk_csv(TTD_CCD_DATA, screen_file, &c, &files) == 0);
    const size_t tot = c.tot, proved = c.proved;
    printf("  sample queries: %zu files, %zu queries at two deltas, the screen proves %zu\n", files, tot, proved);
    ENSURE(files >= 20 && proved > tot / 4);
    return 0;
}

/* The scalar search of one query, as the batch writes it. */
static void reference(int kind, const double x0[12], const double x1[12], double delta, ttd_ccd_result *r)
{
    for (int i = 0; i < 12; ++i)
        if (!isfinite(x0[i]) || !isfinite(x1[i])) {
            memset(r, 0, sizeof *r);
            r->toi = r->gap = NAN;
            r->flags = TTD_CCD_NONFINITE;
            return;
        }
    ttd_ccd_params p = ttd_ccd_default_params();
    p.delta = delta;
    ttd_ccd_query(kind, x0, x1, &p, r);
    r->sub = 0;
}

static int same_result(const ttd_ccd_result *a, const ttd_ccd_result *b)
{
    return memcmp(&a->toi, &b->toi, sizeof a->toi) == 0 && memcmp(&a->gap, &b->gap, sizeof a->gap) == 0 &&
           a->hit == b->hit && a->flags == b->flags && a->sub == b->sub && a->evals == b->evals;
}

/* Runs one batch entry: kind 1 vertex-face, 2 edge-edge, 3 triangles; the arrays as x0/x1 of 12 (or 18
 * for triangles) reals a query, in double or (is_float) float. */
static ttd_status run_batch(int kind, int is_float, ttd_isa isa, int threads, size_t n, const double *x0,
                            const double *x1, const float *f0, const float *f1, double delta, ttd_ccd_result *out)
{
    ttd_options o = ttd_default_options();
    o.isa = isa;
    o.threads = threads;
    if (kind == 3) {
        /* a0 = x[0..9n), b0 = x[9n..18n): the arrays split in two halves */
        return is_float ? ttd_ccd_triangles_f(&o, n, f0, f0 + 9 * n, f1, f1 + 9 * n, delta, out)
                        : ttd_ccd_triangles_d(&o, n, x0, x0 + 9 * n, x1, x1 + 9 * n, delta, out);
    }
    const size_t na = (size_t)kind, nb = 4 - na;
    /* the user's layout: A's points of every query, then B's */
    double *a0 = malloc(n * 12 * sizeof(double)), *a1 = malloc(n * 12 * sizeof(double));
    float *g0 = malloc(n * 12 * sizeof(float)), *g1 = malloc(n * 12 * sizeof(float));
    for (size_t q = 0; q < n; ++q)
        for (size_t i = 0; i < 12; ++i) {
            const size_t dst = i < 3 * na ? 3 * na * q + i : 3 * na * n + 3 * nb * q + (i - 3 * na);
            a0[dst] = x0[12 * q + i];
            a1[dst] = x1[12 * q + i];
            if (is_float) {
                g0[dst] = f0[12 * q + i];
                g1[dst] = f1[12 * q + i];
            }
        }
    ttd_status st;
    if (kind == 1)
        st = is_float ? ttd_ccd_vertex_face_f(&o, n, g0, g0 + 3 * n, g1, g1 + 3 * n, delta, out)
                      : ttd_ccd_vertex_face_d(&o, n, a0, a0 + 3 * n, a1, a1 + 3 * n, delta, out);
    else
        st = is_float ? ttd_ccd_edge_edge_f(&o, n, g0, g0 + 6 * n, g1, g1 + 6 * n, delta, out)
                      : ttd_ccd_edge_edge_d(&o, n, a0, a0 + 6 * n, a1, a1 + 6 * n, delta, out);
    free(a0), free(a1), free(g0), free(g1);
    return st;
}

/* The batch entries on every instruction set and 1, 2, 3 threads against the scalar search, query by
 * query (vertex-face, edge-edge; the float entries against the search of the widened floats). */
static int batches(void)
{
    const int fams[] = {F_RANDOM, F_NEAR_DEGENERATE, F_COPLANAR, F_PARALLEL, F_TOUCH_T1, F_SCALED, F_DEGENERATE, F_HUGE};
    const size_t n = 600;
    int isas_run = 0;
    for (size_t fi = 0; fi < sizeof fams / sizeof fams[0]; ++fi)
        for (int kind = 1; kind <= 2; ++kind)
            for (int is_float = 0; is_float <= 1; ++is_float) {
                qset s = make_set(fams[fi], kind, n);
                float *f0 = malloc(n * 12 * sizeof(float)), *f1 = malloc(n * 12 * sizeof(float));
                for (size_t i = 0; i < 12 * n; ++i) {
                    f0[i] = (float)s.x0[i], f1[i] = (float)s.x1[i];
                    if (is_float) /* the reference searches the widened floats */
                        s.x0[i] = f0[i], s.x1[i] = f1[i];
                }
                const double delta = fi % 2 ? 0.0 : 1e-3;
                ttd_ccd_result *want = malloc(n * sizeof *want), *got = malloc(n * sizeof *got);
                for (size_t q = 0; q < n; ++q)
                    reference(kind, s.x0 + 12 * q, s.x1 + 12 * q, delta, &want[q]);
                for (int isa = TTD_ISA_SCALAR; isa < TTD_ISA_COUNT; ++isa)
                    for (int threads = 1; threads <= 3; ++threads) {
                        memset(got, 0xA5, n * sizeof *got);
                        const ttd_status st = run_batch(kind, is_float, (ttd_isa)isa, threads, n, s.x0, s.x1, f0, f1, delta, got);
                        if (st == TTD_ERR_ISA_UNAVAILABLE)
                            break;
                        isas_run += threads == 1;
                        ENSURE(st == TTD_OK || st == TTD_ERR_NONFINITE_INPUT);
                        for (size_t q = 0; q < n; ++q)
                            ENSURE_MSG(same_result(&got[q], &want[q]),
                                       "%s kind %d float %d isa %s threads %d query %zu: hit %u toi %.17g evals %u, scalar hit %u toi %.17g evals %u",
                                       family_name[fams[fi]], kind, is_float, ttd_isa_name((ttd_isa)isa), threads, q,
                                       got[q].hit, got[q].toi, got[q].evals, want[q].hit, want[q].toi, want[q].evals);
                    }
                free(want), free(got), free(f0), free(f1), free(s.x0), free(s.x1);
            }
    ENSURE(isas_run >= 2 * 8 * 2 * 2); /* the scalar row and at least one SIMD row each time */
    return 0;
}

/* Triangle-triangle batches (the 15 sub-queries screened in lanes) on every instruction set and 1, 2,
 * 3 threads against the scalar row's. */
static int triangles(void)
{
    const size_t n = 400;
    for (int fam = 0; fam < 3; ++fam)
        for (int is_float = 0; is_float <= 1; ++is_float) {
            double *x0 = malloc(n * 18 * sizeof(double)), *x1 = malloc(n * 18 * sizeof(double));
            float *f0 = malloc(n * 18 * sizeof(float)), *f1 = malloc(n * 18 * sizeof(float));
            for (size_t i = 0; i < 18 * n; ++i) {
                x0[i] = srand1() * (fam == 1 ? 1e5 : 1);
                x1[i] = x0[i] + (fam == 2 ? 0.0 : 0.6 * srand1()) * (fam == 1 ? 1e5 : 1);
                f0[i] = (float)x0[i], f1[i] = (float)x1[i];
            }
            const double delta = fam == 2 ? 0.01 : 0.0;
            ttd_ccd_result *want = malloc(n * sizeof *want), *got = malloc(n * sizeof *got);
            ENSURE(run_batch(3, is_float, TTD_ISA_SCALAR, 1, n, x0, x1, f0, f1, delta, want) == TTD_OK);
            size_t hits = 0;
            for (size_t q = 0; q < n; ++q)
                hits += want[q].hit;
            ENSURE(hits > 0 && hits < n);
            for (int isa = TTD_ISA_SCALAR; isa < TTD_ISA_COUNT; ++isa)
                for (int threads = 1; threads <= 3; ++threads) {
                    const ttd_status st = run_batch(3, is_float, (ttd_isa)isa, threads, n, x0, x1, f0, f1, delta, got);
                    if (st == TTD_ERR_ISA_UNAVAILABLE)
                        break;
                    ENSURE(st == TTD_OK);
                    for (size_t q = 0; q < n; ++q)
                        ENSURE_MSG(same_result(&got[q], &want[q]), "fam %d float %d isa %s threads %d pair %zu", fam,
                                   is_float, ttd_isa_name((ttd_isa)isa), threads, q);
                }
            free(want), free(got), free(x0), free(x1), free(f0), free(f1);
        }
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(screen_rows);
    RUN_TEST(screen_samples);
    RUN_TEST(batches);
    RUN_TEST(triangles);
    TEST_MAIN_END();
}
