/* SPDX-License-Identifier: MIT */
/* The deforming-mesh section of `ttd bench` (bench/deform_bench.h). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "deform_bench.h"
#include "fcl_mesh_link.h"
#include "json.h"
#include "meshes.h"
#include <ttd/ttd.h>

enum { NREFIT = 3, NSELF = 4, NTARGET = 8 };

typedef struct refit_row {
    const char *workload;
    size_t tris;
    int runs;
    double build_ms, refit_ms;         /* ttd: a rebuild (ttd_mesh_create_d), a refit; medians */
    double build_cpu_ms, refit_cpu_ms; /* the same calls' CPU time (the calling thread's): steadier
                                          than wall-clock time on a loaded machine */
    double b2b_cpu_ms;                 /* a refit's CPU time with refits back to back (no build
                                          between them): a simulation refitting every step */
    double fcl_build_ms, fcl_refit_ms; /* FCL 0.7 BVHModel<OBBRSS>; NaN without FCL */
    unsigned long long rebuilds;       /* rebuilds the refits triggered */
    char fcl_note[600];
} refit_row;

typedef struct self_row {
    const char *workload;
    size_t tris;
    int steps, layers;
    double fold0;                      /* the fold at the first step (1 at the last; 1 throughout: a
                                          sheet folded flat, queried steps times) */
    double margin, gap;
    double ttd_ms, refit_ms, grid_ms;  /* per step, medians: self-contacts, the refit, the grid */
    double ttd_cpu_ms;                 /* self-contacts' CPU time (the calling thread's), median */
    double pairs_mean, candidates_mean; /* contacts per step; the grid's candidate pairs per step */
    int agree;                         /* every step: the same pairs */
    int grid_run;                      /* the grid brute force was run (not --no-self-grid) */
    uint64_t fnv_set, fnv_ord;         /* FNV-1a 64 (a word at a time) of every step's records (pair,
                                          distance, points: their bits): sorted by pair, and in the
                                          order given */
} self_row;

typedef struct target {
    const char *what, *need;
    double measured;                   /* NaN: not measured */
    int met;
} target;

struct bench_deform_results {
    int quick;
    char fcl[640];
    refit_row refit[NREFIT];
    int nrefit;
    self_row self[NSELF];
    int nself;
    target targets[NTARGET];
};

int bench_deform_option(bench_deform_config *c, const char *a)
{
    if (strcmp(a, "--no-deform") == 0)
        c->disabled = 1;
    else if (strcmp(a, "--deform-only") == 0)
        c->only = 1;
    else if (strcmp(a, "--refit-only") == 0)
        c->only = c->refit_only = 1;
    else if (strcmp(a, "--self-only") == 0)
        c->only = c->self_only = 1;
    else if (strcmp(a, "--sheet7-only") == 0)
        c->only = c->self_only = c->sheet7_only = 1;
    else if (strcmp(a, "--no-self-grid") == 0)
        c->no_self_grid = 1;
    else
        return 0;
    return 1;
}

void bench_deform_usage(FILE *f)
{
    fputs("  --no-deform          leave out the deforming-mesh section (refit against rebuild and FCL's\n"
          "                       refit on tori of 10k-1M triangles; self-contacts on a folding 100k sheet\n"
          "                       against a uniform-grid brute force)\n"
          "  --deform-only        run that section alone\n"
          "  --refit-only         run that section's refit rows alone (no self-contacts)\n"
          "  --self-only          run that section's self-contact rows alone (no refit rows)\n"
          "  --sheet7-only        run the self-contact rows of the 7-layer sheet alone (issue 36)\n"
          "  --no-self-grid       leave out the self-contact rows' grid brute force (its time and the\n"
          "                       pair-for-pair check; the records' hashes are still printed)\n",
          f);
}

size_t bench_deform_row_count(const bench_deform_results *r)
{
    size_t n = r ? (size_t)r->nrefit : 0;
    for (int i = 0; r && i < r->nself; ++i)
        n += r->self[i].workload != NULL;
    return n;
}

void bench_deform_free(bench_deform_results *r)
{
    free(r);
}

static void say(const bench_deform_env *env, const char *fmt, ...)
{
    if (env->quiet)
        return;
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "ttd bench [%6.1f s] deform: ", bench_now() - env->t_start);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
}

static int cmp_double(const void *x, const void *y)
{
    const double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static ttd_options one_thread(void)
{
    ttd_options o = ttd_default_options();
    o.threads = 1;
    return o;
}

/* ---- refit against rebuild and FCL's refit ------------------------------------------------ */

/* g's vertices twisted about the x axis by an angle growing along x (0.3 over the extent) and
 * stretched by 2% along it, into out: every triangle moves and turns, the tree's grouping stays
 * good (a simulation step moves far less). */
static void twist(const ttd_gen_mesh *g, double *out)
{
    double lo[3], hi[3];
    ttd_gen_mesh_bounds(g, lo, hi);
    for (size_t i = 0; i < g->nv; ++i) {
        const double *x = g->verts + 3 * i;
        const double a = 0.3 * (x[0] - lo[0]) / (hi[0] - lo[0]);
        out[3 * i] = 1.02 * x[0];
        out[3 * i + 1] = x[1] * cos(a) - x[2] * sin(a);
        out[3 * i + 2] = x[1] * sin(a) + x[2] * cos(a);
    }
}

/* The calling thread's CPU time in seconds (the library's calls run on it with one thread). */
static double thread_cpu_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void refit_row_run(const bench_deform_env *env, const char *name, size_t nu, int runs, const char *fcl,
                          refit_row *r)
{
    memset(r, 0, sizeof *r);
    r->workload = name;
    r->runs = runs;
    r->build_ms = r->refit_ms = r->fcl_build_ms = r->fcl_refit_ms = BENCH_NAN;
    r->build_cpu_ms = r->refit_cpu_ms = r->b2b_cpu_ms = BENCH_NAN;
    ttd_gen_mesh g;
    if (ttd_gen_torus(1.0, 0.3, nu, nu / 2, &g) != 0)
        return;
    r->tris = g.nt;
    double *moved = malloc(3 * g.nv * sizeof *moved), t[32], tr[32], tc[32], trc[32];
    const ttd_options o = one_thread();
    ttd_mesh *m = NULL;
    if (moved == NULL || ttd_mesh_create_d(&o, g.verts, g.nv, g.tris, g.nt, &m) != TTD_OK) {
        free(moved);
        ttd_gen_mesh_free(&g);
        return;
    }
    twist(&g, moved);
    say(env, "%s: %zu triangles, %d rebuilds and refits, alternating", name, g.nt, runs);
    /* a rebuild (what a caller without refit does each step), then a refit (to the twist and back,
     * in turn): alternating, so that both see the same load */
    for (int k = 0; k < runs; ++k) {
        ttd_mesh *fresh = NULL;
        double a = bench_now(), ac = thread_cpu_s();
        ttd_status st = ttd_mesh_create_d(&o, k % 2 ? g.verts : moved, g.nv, g.tris, g.nt, &fresh);
        tc[k] = (thread_cpu_s() - ac) * 1e3;
        t[k] = (bench_now() - a) * 1e3;
        ttd_mesh_destroy(fresh);
        if (st != TTD_OK)
            goto done;
        a = bench_now(), ac = thread_cpu_s();
        st = ttd_mesh_set_vertices_d(&o, m, k % 2 ? g.verts : moved);
        trc[k] = (thread_cpu_s() - ac) * 1e3;
        tr[k] = (bench_now() - a) * 1e3;
        if (st != TTD_OK)
            goto done;
    }
    r->build_ms = median(t, runs);
    r->build_cpu_ms = median(tc, runs);
    r->refit_cpu_ms = median(trc, runs);
    r->refit_ms = median(tr, runs);
    /* then refits back to back, as a simulation refits its meshes every step: the alternating
     * rows above start each refit with the caches full of the build's data (docs/benchmark.md) */
    for (int k = 0; k < runs; ++k) {
        const double ac = thread_cpu_s();
        const ttd_status st = ttd_mesh_set_vertices_d(&o, m, k % 2 ? g.verts : moved);
        trc[k] = (thread_cpu_s() - ac) * 1e3;
        if (st != TTD_OK)
            goto done;
    }
    r->b2b_cpu_ms = median(trc, runs);
    ttd_mesh_refit_info info;
    if (ttd_mesh_get_refit_info(m, &info) == TTD_OK)
        r->rebuilds = info.rebuilds;
    if (fcl != NULL) {
        say(env, "%s: FCL's build and %d refits", name, runs);
        const double pose[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
        bench_fcl_mesh_job job = {{g.verts, g.nv, g.tris, g.nt}, {moved, g.nv, g.tris, g.nt}, pose, 1,
                                  BENCH_FCL_MESH_REFIT, (uint32_t)runs, 0};
        bench_fcl_mesh_result fr;
        memset(&fr, 0, sizeof fr);
        if (bench_fcl_mesh_run(fcl, &job, 0, &fr) == BENCH_FCL_MESH_OK && fr.nposes == 1) {
            r->fcl_build_ms = fr.build_ms[0];
            r->fcl_refit_ms = fr.poses[0].median_ms;
        } else {
            snprintf(r->fcl_note, sizeof r->fcl_note, "FCL failed: %s", fr.error);
        }
        bench_fcl_mesh_result_free(&fr);
    }
done:
    ttd_mesh_destroy(m);
    free(moved);
    ttd_gen_mesh_free(&g);
}

/* ---- self-contacts against a uniform-grid brute force --------------------------------------- */

typedef struct grid_pair {
    uint32_t i, j;
} grid_pair;

typedef struct grid_scratch {
    double *box;       /* 6 per triangle: lo, hi, inflated by margin / 2 */
    size_t *start;     /* per cell, then its members */
    uint32_t *member;
    size_t cap_cells, cap_members;
    grid_pair *cand;
    size_t cap_cand;
    double *s, *t, *d;
    size_t cap_pairs;
} grid_scratch;

static int grow(void **p, size_t *cap, size_t need, size_t size)
{
    if (need <= *cap)
        return 1;
    size_t c = *cap ? *cap : 1024;
    while (c < need)
        c *= 2;
    void *q = realloc(*p, c * size);
    if (q == NULL)
        return 0;
    *p = q;
    *cap = c;
    return 1;
}

static int cmp_pair(const void *x, const void *y)
{
    const grid_pair *a = x, *b = y;
    return a->i != b->i ? (a->i < b->i ? -1 : 1) : (a->j > b->j) - (a->j < b->j);
}

/* What a user writes by hand: each triangle's box grown by margin / 2, hashed into a uniform
 * grid of cells about twice the typical box (counting sort over the cells of the boxes' bounding
 * box); every two triangles of a cell whose boxes overlap make a candidate, counted in one cell
 * (the one holding the low corner of the boxes' overlap) and kept when they share no vertex;
 * the candidates through the exact kernel (ttd_batch_d, distances only, one thread). The pairs
 * within the margin into *out (sorted by (i, j)); their count, or -1 out of memory. */
static long grid_self_contacts(const double *v, const uint32_t *tri, size_t nt, double margin, grid_scratch *G,
                               grid_pair **out, size_t *candidates)
{
    double *box = realloc(G->box, 6 * nt * sizeof *G->box);
    if (box == NULL)
        return -1;
    G->box = box;
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}, size = 0;
    for (size_t k = 0; k < nt; ++k) {
        double *b = G->box + 6 * k;
        for (int c = 0; c < 3; ++c) {
            const double x = v[3 * tri[3 * k] + c], y = v[3 * tri[3 * k + 1] + c], z = v[3 * tri[3 * k + 2] + c];
            b[c] = fmin(x, fmin(y, z)) - 0.5 * margin;
            b[3 + c] = fmax(x, fmax(y, z)) + 0.5 * margin;
            lo[c] = fmin(lo[c], b[c]);
            hi[c] = fmax(hi[c], b[3 + c]);
        }
        size += fmax(b[3] - b[0], fmax(b[4] - b[1], b[5] - b[2]));
    }
    double cell = 2 * size / (double)nt;
    size_t dim[3], cells;
    for (;;) {
        cells = 1;
        for (int c = 0; c < 3; ++c) {
            dim[c] = (size_t)((hi[c] - lo[c]) / cell) + 1;
            cells *= dim[c];
        }
        if (cells <= ((size_t)1 << 22))
            break;
        cell *= 1.5;
    }
    if (!grow((void **)&G->start, &G->cap_cells, cells + 1, sizeof *G->start))
        return -1;
    memset(G->start, 0, (cells + 1) * sizeof *G->start);
#define CELL_RANGE(k, r)                                                                            \
    size_t r[6];                                                                                   \
    for (int c_ = 0; c_ < 3; ++c_) {                                                               \
        r[c_] = (size_t)((G->box[6 * (k) + c_] - lo[c_]) / cell);                                  \
        r[3 + c_] = (size_t)((G->box[6 * (k) + 3 + c_] - lo[c_]) / cell);                          \
        r[3 + c_] = r[3 + c_] < dim[c_] ? r[3 + c_] : dim[c_] - 1;                                 \
    }
    size_t members = 0;
    for (size_t k = 0; k < nt; ++k) {
        CELL_RANGE(k, r)
        for (size_t z = r[2]; z <= r[5]; ++z)
            for (size_t y = r[1]; y <= r[4]; ++y)
                for (size_t x = r[0]; x <= r[3]; ++x, ++members)
                    G->start[(z * dim[1] + y) * dim[0] + x + 1]++;
    }
    for (size_t c = 0; c < cells; ++c)
        G->start[c + 1] += G->start[c];
    if (!grow((void **)&G->member, &G->cap_members, members, sizeof *G->member))
        return -1;
    for (size_t k = 0; k < nt; ++k) { /* start[c] runs to the end of cell c, then is cell c + 1's start */
        CELL_RANGE(k, r)
        for (size_t z = r[2]; z <= r[5]; ++z)
            for (size_t y = r[1]; y <= r[4]; ++y)
                for (size_t x = r[0]; x <= r[3]; ++x)
                    G->member[G->start[(z * dim[1] + y) * dim[0] + x]++] = (uint32_t)k;
    }
    size_t ncand = 0;
    for (size_t c = 0, first = 0; c < cells; first = G->start[c++]) {
        const size_t last = G->start[c], cz = c / (dim[0] * dim[1]), cy = c / dim[0] % dim[1], cx = c % dim[0];
        for (size_t a = first; a < last; ++a)
            for (size_t b = a + 1; b < last; ++b) {
                const uint32_t i = G->member[a], j = G->member[b];
                const double *p = G->box + 6 * (size_t)i, *q = G->box + 6 * (size_t)j;
                if (p[0] > q[3] || q[0] > p[3] || p[1] > q[4] || q[1] > p[4] || p[2] > q[5] || q[2] > p[5])
                    continue;
                const size_t ox = (size_t)((fmax(p[0], q[0]) - lo[0]) / cell), oy = (size_t)((fmax(p[1], q[1]) - lo[1]) / cell),
                             oz = (size_t)((fmax(p[2], q[2]) - lo[2]) / cell);
                if (ox != cx || oy != cy || oz != cz)
                    continue; /* counted in the cell of the overlap's low corner */
                const uint32_t *ti = tri + 3 * (size_t)i, *tj = tri + 3 * (size_t)j;
                int shared = 0;
                for (int u = 0; u < 3; ++u)
                    shared |= ti[u] == tj[0] || ti[u] == tj[1] || ti[u] == tj[2];
                if (shared)
                    continue;
                if (!grow((void **)&G->cand, &G->cap_cand, ncand + 1, sizeof *G->cand))
                    return -1;
                G->cand[ncand++] = (grid_pair){i < j ? i : j, i < j ? j : i};
            }
    }
#undef CELL_RANGE
    *candidates = ncand;
    if (ncand + 1 > G->cap_pairs) {
        const size_t cap = 2 * ncand + 1;
        double *s = realloc(G->s, 9 * cap * sizeof *s);
        if (s != NULL)
            G->s = s;
        double *t = s ? realloc(G->t, 9 * cap * sizeof *t) : NULL;
        if (t != NULL)
            G->t = t;
        double *d = t ? realloc(G->d, cap * sizeof *d) : NULL;
        if (d == NULL)
            return -1;
        G->d = d;
        G->cap_pairs = cap;
    }
    for (size_t e = 0; e < ncand; ++e)
        for (int k = 0; k < 3; ++k) {
            memcpy(G->s + 9 * e + 3 * k, v + 3 * (size_t)tri[3 * (size_t)G->cand[e].i + (size_t)k], 3 * sizeof(double));
            memcpy(G->t + 9 * e + 3 * k, v + 3 * (size_t)tri[3 * (size_t)G->cand[e].j + (size_t)k], 3 * sizeof(double));
        }
    const ttd_options o = one_thread();
    if (ncand > 0 && ttd_batch_d(&o, ncand, G->s, G->t, G->d, NULL) != TTD_OK)
        return -1;
    size_t n = 0;
    for (size_t e = 0; e < ncand; ++e)
        if (G->d[e] <= margin)
            G->cand[n++] = G->cand[e];
    qsort(G->cand, n, sizeof *G->cand, cmp_pair);
    *out = G->cand;
    return (long)n;
}

/* FNV-1a 64 over a record's fields, a 64-bit word at a time (the word in place of the byte:
 * quick enough for a million records a step). */
static uint64_t fnv_word(uint64_t h, uint64_t w)
{
    return (h ^ w) * 0x100000001b3ull;
}

static uint64_t fnv_real(uint64_t h, double x)
{
    uint64_t w;
    memcpy(&w, &x, sizeof w);
    return fnv_word(h, w);
}

static uint64_t fnv_contact(uint64_t h, const ttd_contact_d *c)
{
    h = fnv_word(h, (uint64_t)c->tri_a << 32 | c->tri_b);
    h = fnv_real(h, c->distance);
    for (int k = 0; k < 3; ++k)
        h = fnv_real(fnv_real(h, c->p[k]), c->q[k]);
    return h;
}

static int cmp_contact(const void *x, const void *y)
{
    const ttd_contact_d *a = x, *b = y;
    return a->tri_a != b->tri_a ? (a->tri_a > b->tri_a) - (a->tri_a < b->tri_a)
                                : (a->tri_b > b->tri_b) - (a->tri_b < b->tri_b);
}

/* A sheet of nx x ny quads (edge 1/nx) folded into `layers`, the layers gap_over_margin margins
 * apart, margin half an edge; steps refits from fold0 of the fold to 1 (or, with fold0 = 1, the
 * sheet folded flat, refitted to itself), each followed by one self-contact query. */
static void self_row_run(const bench_deform_env *env, const char *name, size_t nx, size_t ny, int layers, double fold0,
                         double gap_over_margin, int steps, int with_grid, self_row *r)
{
    memset(r, 0, sizeof *r);
    r->grid_run = with_grid;
    r->fnv_set = r->fnv_ord = 0xcbf29ce484222325ull;
    r->workload = name;
    r->steps = steps;
    r->layers = layers;
    r->fold0 = fold0;
    r->margin = 0.5 / (double)nx; /* half an edge of the sheet's grid */
    r->gap = gap_over_margin * r->margin;
    r->ttd_ms = r->refit_ms = r->grid_ms = r->ttd_cpu_ms = BENCH_NAN;
    ttd_gen_mesh g;
    if (ttd_gen_folded_strip(nx, ny, layers, r->gap, fold0, &g) != 0)
        return;
    r->tris = g.nt;
    const ttd_options o = one_thread();
    ttd_mesh *m = NULL;
    grid_scratch G;
    memset(&G, 0, sizeof G);
    ttd_contacts_d set = {0};
    double tt[64], tr[64], tg[64], tc[64];
    grid_pair *mine = NULL;
    r->agree = 1;
    if (ttd_mesh_create_d(&o, g.verts, g.nv, g.tris, g.nt, &m) != TTD_OK)
        goto done;
    say(env, "%s: %zu triangles, %d steps of the fold, margin %.3g, layers %.3g apart", name, g.nt, steps, r->margin,
        r->gap);
    for (int k = 0; k < steps; ++k) {
        ttd_gen_mesh s;
        if (ttd_gen_folded_strip(nx, ny, layers, r->gap, fold0 + (1 - fold0) * k / (steps - 1), &s) != 0)
            goto done;
        double a = bench_now();
        ttd_status st = ttd_mesh_set_vertices_d(&o, m, s.verts);
        tr[k] = (bench_now() - a) * 1e3;
        a = bench_now();
        const double c0 = thread_cpu_s();
        if (st == TTD_OK)
            st = ttd_mesh_self_contacts_d(&o, m, r->margin, 0, &set);
        tc[k] = (thread_cpu_s() - c0) * 1e3;
        tt[k] = (bench_now() - a) * 1e3;
        if (st != TTD_OK) {
            ttd_gen_mesh_free(&s);
            goto done;
        }
        for (size_t e = 0; e < set.count; ++e)
            r->fnv_ord = fnv_contact(r->fnv_ord, &set.pairs[e]);
        if (set.count > 1)
            qsort(set.pairs, set.count, sizeof *set.pairs, cmp_contact);
        for (size_t e = 0; e < set.count; ++e)
            r->fnv_set = fnv_contact(r->fnv_set, &set.pairs[e]);
        r->pairs_mean += (double)set.count / steps;
        tg[k] = BENCH_NAN;
        if (!with_grid) {
            ttd_gen_mesh_free(&s);
            continue;
        }
        size_t cand = 0;
        grid_pair *found = NULL;
        a = bench_now();
        const long ng = grid_self_contacts(s.verts, s.tris, s.nt, r->margin, &G, &found, &cand);
        tg[k] = (bench_now() - a) * 1e3;
        if (ng < 0) {
            ttd_gen_mesh_free(&s);
            goto done;
        }
        r->candidates_mean += (double)cand / steps;
        /* the same pairs? */
        grid_pair *v = realloc(mine, (set.count + 1) * sizeof *v);
        if (v == NULL) {
            ttd_gen_mesh_free(&s);
            goto done;
        }
        mine = v;
        for (size_t e = 0; e < set.count; ++e)
            mine[e] = (grid_pair){set.pairs[e].tri_a, set.pairs[e].tri_b};
        qsort(mine, set.count, sizeof *mine, cmp_pair);
        r->agree &= (size_t)ng == set.count && (ng == 0 || memcmp(mine, found, set.count * sizeof *mine) == 0);
        ttd_gen_mesh_free(&s);
    }
    r->ttd_ms = median(tt, steps);
    r->ttd_cpu_ms = median(tc, steps);
    r->refit_ms = median(tr, steps);
    r->grid_ms = with_grid ? median(tg, steps) : BENCH_NAN;
    if (!with_grid)
        r->candidates_mean = BENCH_NAN;
done:
    free(mine);
    free(G.box), free(G.start), free(G.member), free(G.cand), free(G.s), free(G.t), free(G.d);
    ttd_contacts_free_d(&set);
    ttd_mesh_destroy(m);
    ttd_gen_mesh_free(&g);
}

/* ---- the section ----------------------------------------------------------------------------- */

bench_deform_results *bench_deform_run(const bench_deform_config *c, const bench_deform_env *env)
{
    bench_deform_results *R = calloc(1, sizeof *R);
    if (R == NULL)
        return NULL;
    R->quick = env->st->quick;
    char path[600];
    const char *fcl = NULL;
    if (env->no_fcl)
        snprintf(R->fcl, sizeof R->fcl, "left out (--no-fcl)");
    else if (bench_fcl_mesh_find(NULL, path, sizeof path) == BENCH_FCL_MESH_OK)
        fcl = path, snprintf(R->fcl, sizeof R->fcl, "%s", path);
    else
        snprintf(R->fcl, sizeof R->fcl, "not found (FCL absent when ttd was built)");
    static const char *const names[NREFIT] = {"torus-10k", "torus-100k", "torus-1m"};
    static const size_t nu[NREFIT] = {100, 316, 1000}; /* 2 nu (nu / 2) triangles */
    R->nrefit = c->self_only ? 0 : R->quick ? 2 : 3;
    for (int i = 0; i < R->nrefit; ++i)
        refit_row_run(env, names[i], nu[i], i == 2 ? 5 : R->quick ? 7 : 15, fcl, &R->refit[i]);
    const size_t n = R->quick ? 100 : 224; /* 2 n^2 triangles: 20,000 or 100,352 */
    /* issue 36's sheet: 7 layers of about 85 x 85 quads (595 x 85: 101,150 triangles), folded flat */
    const size_t nx7 = R->quick ? 266 : 595, ny7 = R->quick ? 38 : 85;
    const int steps = R->quick ? 5 : 10;
    R->nself = c->refit_only ? 0 : NSELF;
    if (c->refit_only) {
        for (int i = 0; i < NSELF; ++i)
            R->self[i].ttd_ms = R->self[i].grid_ms = R->self[i].ttd_cpu_ms = BENCH_NAN;
    } else {
        const int grid = !c->no_self_grid;
        if (c->sheet7_only) {
            for (int i = 0; i < 2; ++i) {
                memset(&R->self[i], 0, sizeof R->self[i]);
                R->self[i].workload = NULL; /* not run */
                R->self[i].ttd_ms = R->self[i].grid_ms = R->self[i].ttd_cpu_ms = BENCH_NAN;
            }
        } else {
            self_row_run(env, R->quick ? "sheet-20k, apart" : "sheet-100k, apart", n, n, 4, 0.85, 1.5, steps, grid,
                         &R->self[0]);
            self_row_run(env, R->quick ? "sheet-20k, touching" : "sheet-100k, touching", n, n, 4, 0.85, 0.8, steps, grid,
                         &R->self[1]);
        }
        self_row_run(env, R->quick ? "sheet7-20k, apart" : "sheet7-101k, apart", nx7, ny7, 7, 1.0, 1.5, steps, grid,
                     &R->self[2]);
        self_row_run(env, R->quick ? "sheet7-20k, touching" : "sheet7-101k, touching", nx7, ny7, 7, 1.0, 0.8, steps,
                     grid, &R->self[3]);
    }

    /* the targets (issue 25) */
    double worst_rebuild = HUGE_VAL, worst_fcl = HUGE_VAL, worst_cpu = HUGE_VAL, worst_b2b = HUGE_VAL;
    int fcl_rows = 0;
    for (int i = 0; i < R->nrefit; ++i) {
        const refit_row *r = &R->refit[i];
        worst_rebuild = fmin(worst_rebuild, r->build_ms / r->refit_ms);
        worst_cpu = fmin(worst_cpu, r->build_cpu_ms / r->refit_cpu_ms);
        worst_b2b = fmin(worst_b2b, r->build_cpu_ms / r->b2b_cpu_ms);
        if (isfinite(r->fcl_refit_ms))
            worst_fcl = fmin(worst_fcl, r->fcl_refit_ms / r->refit_ms), ++fcl_rows;
    }
    const self_row *big = &R->self[0];
    R->targets[0] = (target){"refit against a rebuild, every torus", ">= 5x", worst_rebuild, worst_rebuild >= 5};
    R->targets[1] = (target){"refit against FCL's refit, every torus", "> 1x", fcl_rows ? worst_fcl : BENCH_NAN,
                             fcl_rows && worst_fcl > 1};
    R->targets[2] = (target){"self-contacts per step, folded sheet, one core", "< 10 ms", big->ttd_ms, big->ttd_ms < 10};
    R->targets[3] = (target){"self-contacts against the grid brute force", "(no target)",
                             big->grid_ms / big->ttd_ms, 1};
    /* issue 36, target 1: the 7-layer sheet, CPU time of one thread */
    const self_row *s7 = &R->self[2], *t7 = &R->self[3];
    R->targets[4] = (target){"self-contacts, 7 layers 1.5 margins apart (CPU)", "<= 10 ms", s7->ttd_cpu_ms,
                             s7->ttd_cpu_ms <= 10};
    const double ns_pair = t7->pairs_mean > 0 ? t7->ttd_cpu_ms * 1e6 / t7->pairs_mean : BENCH_NAN;
    R->targets[5] = (target){"self-contacts, 7 layers 0.8 margins apart, a pair (CPU)", "<= 50 ns", ns_pair,
                             ns_pair <= 50};
    /* issue 36, target 2 in CPU time (x_cpu), a build before each refit and refits back to back */
    R->targets[6] = (target){"refit against a rebuild, every torus (CPU)", ">= 5x", worst_cpu, worst_cpu >= 5};
    R->targets[7] = (target){"refits back to back against a rebuild (CPU)", ">= 5x", worst_b2b, worst_b2b >= 5};
    return R;
}

void bench_deform_write_table(FILE *f, const bench_deform_results *R)
{
    if (R == NULL)
        return;
    char b[8][40];
    fprintf(f, "\nDeforming meshes (issue 25), one thread%s:\n", R->quick ? " (--quick: smaller meshes)" : "");
    fprintf(f, "refit: ttd_mesh_set_vertices_d against ttd_mesh_create_d on the moved vertices (a rebuild) and FCL "
               "0.7's BVHModel<OBBRSS> refit (beginUpdateModel / updateSubModel / endUpdateModel, bottom-up), each "
               "to a torus twisted by 0.3 along its length (and stretched 2%%) and back in turn; medians\n");
    fprintf(f, "FCL mesh program: %s\n", R->fcl);
    fprintf(f, "(cpu_*: the calling thread's CPU time of the same calls, x_cpu their ratio: steadier than wall-clock "
               "time when other work shares the cores; a rebuild and a refit alternate; cpu_b2b, x_b2b: a refit's CPU "
               "time with refits back to back after them, no build between, and cpu_build over it)\n");
    fprintf(f, "\n%-12s %9s %5s %10s %10s %10s %10s %9s %9s %9s %9s %9s %9s %9s %8s  %s\n", "workload", "tris", "runs",
            "rebuild_ms", "refit_ms", "fcl_build", "fcl_refit", "x_rebuild", "x_fcl", "cpu_build", "cpu_refit", "x_cpu",
            "cpu_b2b", "x_b2b", "rebuilds", "note");
    for (int i = 0; i < R->nrefit; ++i) {
        const refit_row *r = &R->refit[i];
        char slower[64], c[5][40];
        bench_slower_note(slower, sizeof slower, r->fcl_refit_ms / r->refit_ms, "FCL's refit");
        fprintf(f, "%-12s %9zu %5d %10s %10s %10s %10s %9s %9s %9s %9s %9s %9s %9s %8llu  %s%s%s\n", r->workload, r->tris,
                r->runs,
                bench_num(b[0], 40, r->build_ms, "%.3f"), bench_num(b[1], 40, r->refit_ms, "%.3f"),
                bench_num(b[2], 40, r->fcl_build_ms, "%.3f"), bench_num(b[3], 40, r->fcl_refit_ms, "%.3f"),
                bench_num(b[4], 40, r->build_ms / r->refit_ms, "%.2f"), bench_num(b[5], 40, r->fcl_refit_ms / r->refit_ms, "%.2f"),
                bench_num(c[0], 40, r->build_cpu_ms, "%.3f"), bench_num(c[1], 40, r->refit_cpu_ms, "%.3f"),
                bench_num(c[2], 40, r->build_cpu_ms / r->refit_cpu_ms, "%.2f"), bench_num(c[3], 40, r->b2b_cpu_ms, "%.3f"),
                bench_num(c[4], 40, r->build_cpu_ms / r->b2b_cpu_ms, "%.2f"), r->rebuilds, r->fcl_note,
                r->fcl_note[0] && slower[0] ? "; " : "", slower);
    }
    fprintf(f, "\nself-contacts: sheets folded into 4 layers (gen: ttd_gen_folded_sheet, the fold going from 0.85 to "
               "1 of flat over the steps) and into 7 layers (ttd_gen_folded_strip 595 x 85 quads, folded flat, "
               "queried at each step), margin half an edge, the layers 1.5 or 0.8 margins apart; per step: "
               "ttd_mesh_set_vertices_d, then ttd_mesh_self_contacts_d (pairs sharing no vertex); the grid: the same "
               "pairs by a uniform grid of triangles' boxes and the exact kernel on its candidates; medians per step; "
               "self_cpu: the query's CPU time (the calling thread's), ns_pair: self_cpu per pair found; fnv_set, "
               "fnv_ord: FNV-1a 64 (a word at a time) of every step's records (pair, distance and points, their bits) sorted by pair and "
               "in the order the query gave them\n");
    fprintf(f, "\n%-22s %9s %5s %9s %9s %9s %9s %9s %9s %11s %8s %11s %7s %16s %16s\n", "workload", "tris", "steps",
            "margin", "self_ms", "self_cpu", "refit_ms", "grid_ms", "x_grid", "pairs", "ns_pair", "grid_cand", "same",
            "fnv_set", "fnv_ord");
    for (int i = 0; i < R->nself; ++i) {
        const self_row *r = &R->self[i];
        if (r->workload == NULL)
            continue;
        fprintf(f, "%-22s %9zu %5d %9.3g %9s %9s %9s %9s %9s %11.0f %8s %11s %7s %016llx %016llx\n", r->workload,
                r->tris, r->steps,
                r->margin, bench_num(b[0], 40, r->ttd_ms, "%.2f"), bench_num(b[4], 40, r->ttd_cpu_ms, "%.2f"),
                bench_num(b[1], 40, r->refit_ms, "%.2f"), bench_num(b[2], 40, r->grid_ms, "%.2f"),
                bench_num(b[3], 40, r->grid_ms / r->ttd_ms, "%.2f"), r->pairs_mean,
                bench_num(b[5], 40, r->pairs_mean > 0 ? r->ttd_cpu_ms * 1e6 / r->pairs_mean : BENCH_NAN, "%.0f"),
                bench_num(b[6], 40, r->candidates_mean, "%.0f"), !r->grid_run ? "-" : r->agree ? "yes" : "NO", (unsigned long long)r->fnv_set,
                (unsigned long long)r->fnv_ord);
    }
    fprintf(f, "\ndeforming-mesh targets, issues 25 and 36 (ratios of this run; the benchmark measures, it does not fail on "
               "them):\n");
    for (int i = 0; i < NTARGET; ++i) {
        const target *t = &R->targets[i];
        char slower[64] = "";
        if (i == 1)
            bench_slower_note(slower, sizeof slower, t->measured, "FCL's refit");
        else if (i == 3)
            bench_slower_note(slower, sizeof slower, t->measured, "the grid");
        fprintf(f, "  %-50s %-12s measured %9s  %s%s%s\n", t->what, t->need,
                bench_num(b[0], 40, t->measured, i == 2 || i == 4 ? "%.2f ms" : i == 5 ? "%.1f ns" : "%.2fx"),
                i == 3 ? "" : !isfinite(t->measured) ? "not measured" : t->met ? "met" : "MISSED",
                slower[0] && i != 3 ? "; " : "", slower);
    }
}

static void json_num(FILE *f, const char *key, double v)
{
    fprintf(f, "\"%s\": ", key);
    if (isfinite(v))
        fprintf(f, "%.6g", v);
    else
        fputs("null", f);
}

void bench_deform_write_json(FILE *f, const bench_deform_results *R)
{
    if (R == NULL) {
        fputs("null", f);
        return;
    }
    fprintf(f, "{\"quick\": %d, \"fcl\": ", R->quick);
    bench_json_string(f, R->fcl);
    fputs(", \"refit\": [", f);
    for (int i = 0; i < R->nrefit; ++i) {
        const refit_row *r = &R->refit[i];
        fprintf(f, "%s{\"workload\": \"%s\", \"triangles\": %zu, \"runs\": %d, ", i ? ", " : "", r->workload, r->tris,
                r->runs);
        json_num(f, "rebuild_ms", r->build_ms), fputs(", ", f);
        json_num(f, "refit_ms", r->refit_ms), fputs(", ", f);
        json_num(f, "rebuild_cpu_ms", r->build_cpu_ms), fputs(", ", f);
        json_num(f, "refit_cpu_ms", r->refit_cpu_ms), fputs(", ", f);
        json_num(f, "refit_b2b_cpu_ms", r->b2b_cpu_ms), fputs(", ", f);
        json_num(f, "fcl_build_ms", r->fcl_build_ms), fputs(", ", f);
        json_num(f, "fcl_refit_ms", r->fcl_refit_ms);
        fprintf(f, ", \"rebuilds\": %llu}", r->rebuilds);
    }
    fputs("], \"self\": [", f);
    for (int i = 0, first = 1; i < R->nself; ++i) {
        const self_row *r = &R->self[i];
        if (r->workload == NULL)
            continue;
        fprintf(f, "%s{\"workload\": \"%s\", \"triangles\": %zu, \"steps\": %d, ", first ? "" : ", ", r->workload,
                r->tris, r->steps);
        first = 0;
        json_num(f, "margin", r->margin), fputs(", ", f);
        json_num(f, "gap", r->gap), fputs(", ", f);
        json_num(f, "self_ms", r->ttd_ms), fputs(", ", f);
        json_num(f, "self_cpu_ms", r->ttd_cpu_ms), fputs(", ", f);
        fprintf(f, "\"layers\": %d, ", r->layers);
        json_num(f, "refit_ms", r->refit_ms), fputs(", ", f);
        json_num(f, "grid_ms", r->grid_ms), fputs(", ", f);
        json_num(f, "pairs", r->pairs_mean), fputs(", ", f);
        json_num(f, "grid_candidates", r->candidates_mean);
        fprintf(f, ", \"same_pairs\": %s, \"fnv_set\": \"%016llx\", \"fnv_ord\": \"%016llx\"}",
                !r->grid_run ? "null" : r->agree ? "true" : "false", (unsigned long long)r->fnv_set,
                (unsigned long long)r->fnv_ord);
    }
    fputs("], \"targets\": [", f);
    for (int i = 0; i < NTARGET; ++i) {
        const target *t = &R->targets[i];
        fprintf(f, "%s{\"what\": \"%s\", \"need\": \"%s\", ", i ? ", " : "", t->what, t->need);
        json_num(f, "measured", t->measured);
        fprintf(f, ", \"met\": %s}", t->met ? "true" : "false");
    }
    fputs("]}", f);
}
