/* SPDX-License-Identifier: MIT */
/* Self queries (ttd_mesh_self_contacts_d/f, ttd_mesh_self_collide_d/f) against a brute force over
 * every pair i < j of one mesh's triangles, written here from the header's rules alone: the
 * vertices two triangles share counted as sets of indices; no shared vertex: the exact method on
 * (T_i, T_j) through ttd_batch_d/f; exactly one, v, and each triangle another vertex (with
 * TTD_SELF_SHARED_VERTEX): the smaller of (E_i, T_j) and (T_i, E_j), E the triangle's vertices
 * other than v in their order, the last repeated, E_i's when equal; otherwise nothing. The meshes:
 * sheets folded into 2 and 3 layers at gaps of 1e-2 and 1e-9 and folded past flat (through
 * themselves), flat and bumpy grids, a torus, an icosphere, the degenerate and duplicate-vertex
 * meshes, a soup of slivers (no vertex shared: every near pair counts), coplanar overlapping
 * sheets, at scales 1e-6 and 1e6 with offsets, both precisions; margins 0, at a pair's distance
 * (boundary pairs in) and wider. Checked: the set pair for pair with distances and points bit for
 * bit, tri_a < tri_b; collision (yes exactly when the brute-force minimum is within the margin,
 * with a witness within it); every instruction set and 1 and 2 threads give the scalar row's
 * bits, set order included; after refits along a folding sequence, the same against the brute
 * force; bad input. */
#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "engine/batch.h"
#include "meshes.h"
#include "mesh/mesh.h"
#include "self_brute.h"
#include "test_macros.h"
#include "ttd/ttd.h"

/* ---- checks -------------------------------------------------------------------------------- */

static int cmp_d(const void *x, const void *y)
{
    const ttd_contact_d *a = x, *b = y;
    return a->tri_a != b->tri_a ? (a->tri_a < b->tri_a ? -1 : 1) : (a->tri_b > b->tri_b) - (a->tri_b < b->tri_b);
}

static int cmp_f(const void *x, const void *y)
{
    const ttd_contact_f *a = x, *b = y;
    return a->tri_a != b->tri_a ? (a->tri_a < b->tri_a ? -1 : 1) : (a->tri_b > b->tri_b) - (a->tri_b < b->tri_b);
}

static size_t pairs_checked, collisions_checked;

/* The self queries of mesh m (vertices g's, or their floats when fl) at margin against the brute
 * force `all` (np pairs). */
static int check_margin(const char *what, const ttd_mesh *m, int fl, unsigned flags, const spair *all, size_t np,
                        double margin)
{
    double best = HUGE_VAL;
    for (size_t k = 0; k < np; ++k)
        best = fmin(best, all[k].d);
    ttd_collision col;
    size_t count = 0;
    if (!fl) {
        ttd_contacts_d set = {0};
        ENSURE(ttd_mesh_self_contacts_d(NULL, m, margin, flags, &set) == TTD_OK);
        ENSURE(set.poses == 1 && set.pose_start[0] == 0 && set.pose_start[1] == set.count);
        for (size_t k = 0; k < set.count; ++k)
            ENSURE(set.pairs[k].tri_a < set.pairs[k].tri_b);
        if (set.count > 1)
            qsort(set.pairs, set.count, sizeof *set.pairs, cmp_d);
        for (size_t k = 0; k < np; ++k) {
            if (!(all[k].d <= margin))
                continue;
            ENSURE_MSG(count < set.count && set.pairs[count].tri_a == all[k].i && set.pairs[count].tri_b == all[k].j,
                       "%s margin %.17g: pair (%u, %u) at %.17g missing", what, margin, all[k].i, all[k].j, all[k].d);
            const ttd_contact_d *c = &set.pairs[count++];
            ENSURE_MSG(c->distance == all[k].d, "%s: (%u, %u) at %.17g, brute force %.17g", what, c->tri_a, c->tri_b,
                       c->distance, all[k].d);
            ENSURE(memcmp(c->p, all[k].p, sizeof c->p) == 0 && memcmp(c->q, all[k].q, sizeof c->q) == 0);
        }
        ENSURE_MSG(count == set.count, "%s margin %.17g: %zu pairs, brute force %zu", what, margin, set.count, count);
        size_t counted = SIZE_MAX; /* the count without the pairs: the brute force's */
        ENSURE(ttd_mesh_self_contacts_count_d(NULL, m, margin, flags, &counted) == TTD_OK);
        ENSURE_MSG(counted == count, "%s margin %.17g: counted %zu, brute force %zu", what, margin, counted, count);
        ttd_contacts_free_d(&set);
        ENSURE(ttd_mesh_self_collide_d(NULL, m, margin, flags, &col) == TTD_OK);
    } else {
        ttd_contacts_f set = {0};
        ENSURE(ttd_mesh_self_contacts_f(NULL, m, (float)margin, flags, &set) == TTD_OK);
        if (set.count > 1)
            qsort(set.pairs, set.count, sizeof *set.pairs, cmp_f);
        for (size_t k = 0; k < np; ++k) {
            if (!(all[k].d <= (double)(float)margin))
                continue;
            ENSURE_MSG(count < set.count && set.pairs[count].tri_a == all[k].i && set.pairs[count].tri_b == all[k].j,
                       "%s (float) margin %.9g: pair (%u, %u) at %.9g missing", what, margin, all[k].i, all[k].j, all[k].d);
            const ttd_contact_f *c = &set.pairs[count++];
            ENSURE((double)c->distance == all[k].d && (double)c->p[0] == all[k].p[0] && (double)c->q[2] == all[k].q[2]);
        }
        ENSURE_MSG(count == set.count, "%s (float) margin %.9g: %zu pairs, brute force %zu", what, margin, set.count,
                   count);
        size_t counted = SIZE_MAX;
        ENSURE(ttd_mesh_self_contacts_count_f(NULL, m, (float)margin, flags, &counted) == TTD_OK);
        ENSURE_MSG(counted == count, "%s (float) margin %.9g: counted %zu, brute force %zu", what, margin, counted, count);
        ttd_contacts_free_f(&set);
        ENSURE(ttd_mesh_self_collide_f(NULL, m, (float)margin, flags, &col) == TTD_OK);
        margin = (double)(float)margin;
    }
    pairs_checked += count;
    ++collisions_checked;
    ENSURE_MSG(col.hit == (best <= margin), "%s margin %.17g: collide %u, brute-force minimum %.17g", what, margin,
               col.hit, best);
    if (col.hit) {
        ENSURE(col.tri_a < col.tri_b);
        size_t k = 0;
        while (k < np && !(all[k].i == col.tri_a && all[k].j == col.tri_b))
            ++k;
        ENSURE_MSG(k < np && all[k].d <= margin, "%s: witness (%u, %u) not within the margin", what, col.tri_a,
                   col.tri_b);
    } else {
        ENSURE(col.tri_a == UINT32_MAX && col.tri_b == UINT32_MAX);
    }
    return 0;
}

/* Both flag settings and precisions, margins 0, the k-th nearest pair's distance, and wider. */
static int check_mesh(const char *what, const ttd_gen_mesh *g, double wide)
{
    for (int fl = 0; fl < 2; ++fl) {
        ttd_mesh *m;
        if (!fl) {
            ENSURE(ttd_mesh_create_d(NULL, g->verts, g->nv, g->tris, g->nt, &m) == TTD_OK);
        } else {
            float *v = malloc(3 * g->nv * sizeof *v);
            ENSURE(v != NULL);
            for (size_t i = 0; i < 3 * g->nv; ++i)
                v[i] = (float)g->verts[i];
            ENSURE(ttd_mesh_create_f(NULL, v, g->nv, g->tris, g->nt, &m) == TTD_OK);
            free(v);
        }
        for (int shared = 0; shared < 2; ++shared) {
            size_t np;
            spair *all = brute_self(g->verts, g->tris, g->nt, fl, shared, &np);
            /* a boundary margin: the distance of a pair near the 5th percentile */
            double *d = malloc((np + 1) * sizeof *d), boundary = 0;
            ENSURE(d != NULL);
            size_t nd = 0;
            for (size_t k = 0; k < np; ++k)
                if (isfinite(all[k].d))
                    d[nd++] = all[k].d;
            for (size_t k = 0; k < nd && k < 64; ++k) /* a cheap order statistic: the smallest above 0 of a few */
                if (d[k] > 0 && (boundary == 0 || d[k] < boundary))
                    boundary = d[k];
            free(d);
            const double margins[4] = {0, boundary, wide, 4 * wide};
            char label[200];
            snprintf(label, sizeof label, "%s%s", what, shared ? " (shared vertex)" : "");
            for (int mi = 0; mi < 4; ++mi)
                if (check_margin(label, m, fl, shared ? TTD_SELF_SHARED_VERTEX : 0u, all, np, margins[mi]))
                    return 1;
            free(all);
        }
        ttd_mesh_destroy(m);
    }
    return 0;
}

/* ---- the meshes ----------------------------------------------------------------------------- */

static void transform(ttd_gen_mesh *g, double scale, double shift)
{
    for (size_t i = 0; i < 3 * g->nv; ++i)
        g->verts[i] = g->verts[i] * scale + shift;
}

/* Two grids in one plane, the second moved by half a cell: every triangle of one crosses some of
 * the other (coplanar overlaps), and nothing is shared by index. */
static void coplanar_sheets(ttd_gen_mesh *out)
{
    ttd_gen_mesh a;
    if (ttd_gen_grid(5, &a))
        abort();
    out->nv = 2 * a.nv;
    out->nt = 2 * a.nt;
    out->verts = malloc(3 * out->nv * sizeof *out->verts);
    out->tris = malloc(3 * out->nt * sizeof *out->tris);
    if (!out->verts || !out->tris)
        abort();
    for (size_t i = 0; i < a.nv; ++i)
        for (int c = 0; c < 3; ++c) {
            out->verts[3 * i + (size_t)c] = a.verts[3 * i + (size_t)c];
            out->verts[3 * (a.nv + i) + (size_t)c] = a.verts[3 * i + (size_t)c] + (c == 0 ? 0.1 : c == 1 ? 0.07 : 0);
        }
    for (size_t t = 0; t < 3 * a.nt; ++t) {
        out->tris[t] = a.tris[t];
        out->tris[3 * a.nt + t] = a.tris[t] + (uint32_t)a.nv;
    }
    ttd_gen_mesh_free(&a);
}

/* A soup of thin triangles (each its own vertices), some nearly touching. */
static void sliver_soup(ttd_gen_mesh *out)
{
    const size_t n = 90;
    out->nv = 3 * n;
    out->nt = n;
    out->verts = malloc(9 * n * sizeof *out->verts);
    out->tris = malloc(3 * n * sizeof *out->tris);
    if (!out->verts || !out->tris)
        abort();
    uint64_t st = 17;
    for (size_t i = 0; i < n; ++i) {
        double a[3], b[3];
        for (int c = 0; c < 3; ++c) {
            st = st * 6364136223846793005ull + 1442695040888963407ull;
            a[c] = (double)(st >> 11) * 0x1p-53;
            st = st * 6364136223846793005ull + 1442695040888963407ull;
            b[c] = a[c] + 0.3 * ((double)(st >> 11) * 0x1p-53 - 0.5);
        }
        const double w = i % 3 == 0 ? 1e-12 : i % 3 == 1 ? 1e-6 : 0.05;
        for (int c = 0; c < 3; ++c) {
            out->verts[9 * i + (size_t)c] = a[c];
            out->verts[9 * i + 3 + (size_t)c] = b[c];
            out->verts[9 * i + 6 + (size_t)c] = 0.5 * (a[c] + b[c]) + (c == 2 ? w : 0);
        }
        for (int k = 0; k < 3; ++k)
            out->tris[3 * i + (size_t)k] = (uint32_t)(3 * i + (size_t)k);
    }
}

/* Two pleated fans, one above the other: 40 triangles each around a centre vertex, their rims
 * compressed into a third of a turn and pleated up and down, so that triangles sharing only the
 * centre come within a margin of each other (without TTD_SELF_SHARED_VERTEX nothing of one fan
 * counts: a leaf of it skips every node test, mesh/query_impl.h self_leaf), and the second fan,
 * 0.03 above with its own centre, near the first (pairs that share nothing). */
static void pleated_fans(ttd_gen_mesh *out)
{
    const int n = 40, fans = 2;
    out->nv = (size_t)fans * (size_t)(n + 2);
    out->nt = (size_t)fans * (size_t)n;
    out->verts = malloc(3 * out->nv * sizeof *out->verts);
    out->tris = malloc(3 * out->nt * sizeof *out->tris);
    if (!out->verts || !out->tris)
        abort();
    for (int f = 0; f < fans; ++f) {
        double *c = out->verts + 3 * (size_t)f * (size_t)(n + 2);
        c[0] = 0.01 * f;
        c[1] = 0;
        c[2] = 0.03 * f;
        for (int k = 0; k <= n; ++k) {
            const double a = 2.0944 * k / n; /* a third of a turn */
            double *v = c + 3 * (size_t)(k + 1);
            v[0] = cos(a) + c[0];
            v[1] = sin(a);
            v[2] = (k % 2 ? 0.08 : -0.08) + c[2];
        }
        for (int k = 0; k < n; ++k) {
            uint32_t *t = out->tris + 3 * ((size_t)f * (size_t)n + (size_t)k);
            const uint32_t base = (uint32_t)(f * (n + 2));
            t[0] = base;
            t[1] = base + (uint32_t)k + 1;
            t[2] = base + (uint32_t)k + 2;
        }
    }
}

/* ---- tests ------------------------------------------------------------------------------------ */

static int self_contacts_match_brute_force(void)
{
    struct {
        const char *name;
        ttd_gen_mesh g;
        double wide;
    } cases[20];
    int n = 0;
    const double gaps[3] = {1e-2, 1e-9, 0};
    for (int gi = 0; gi < 3; ++gi)
        for (int layers = 2; layers <= 3; ++layers) {
            cases[n].name = gi == 0 ? "folded sheet, gap 1e-2" : gi == 1 ? "folded sheet, gap 1e-9" : "folded sheet, gap 0";
            if (ttd_gen_folded_sheet(10, layers, gaps[gi], 1.0, &cases[n].g))
                abort();
            cases[n++].wide = 0.03;
        }
    cases[n].name = "sheet folded past flat (through itself)";
    if (ttd_gen_folded_sheet(10, 3, 0.05, 1.15, &cases[n].g))
        abort();
    cases[n++].wide = 0.03;
    cases[n].name = "half-folded sheet";
    if (ttd_gen_folded_sheet(10, 2, 0.1, 0.5, &cases[n].g))
        abort();
    cases[n++].wide = 0.05;
    cases[n].name = "torus";
    if (ttd_gen_torus(1.0, 0.25, 16, 8, &cases[n].g))
        abort();
    cases[n++].wide = 0.2;
    cases[n].name = "icosphere";
    if (ttd_gen_icosphere(2, &cases[n].g))
        abort();
    cases[n++].wide = 0.3;
    cases[n].name = "degenerate";
    if (ttd_gen_mesh_degenerate(&cases[n].g))
        abort();
    cases[n++].wide = 0.1;
    cases[n].name = "duplicate vertices";
    if (ttd_gen_mesh_duplicate_vertices(&cases[n].g))
        abort();
    cases[n++].wide = 0.1;
    cases[n].name = "coplanar sheets";
    coplanar_sheets(&cases[n].g);
    cases[n++].wide = 0.05;
    cases[n].name = "sliver soup";
    sliver_soup(&cases[n].g);
    cases[n++].wide = 0.02;
    cases[n].name = "pleated fans";
    pleated_fans(&cases[n].g);
    cases[n++].wide = 0.05;
    cases[n].name = "folded sheet at scale 1e-6, offset 1";
    if (ttd_gen_folded_sheet(8, 3, 0.02, 1.0, &cases[n].g))
        abort();
    transform(&cases[n].g, 1e-6, 1.0);
    cases[n++].wide = 3e-8;
    cases[n].name = "folded sheet at scale 1e6, offset 1e7";
    if (ttd_gen_folded_sheet(8, 3, 0.02, 1.0, &cases[n].g))
        abort();
    transform(&cases[n].g, 1e6, 1e7);
    cases[n++].wide = 3e4;
    for (int i = 0; i < n; ++i) {
        if (check_mesh(cases[i].name, &cases[i].g, cases[i].wide))
            return 1;
        ttd_gen_mesh_free(&cases[i].g);
    }
    printf("  %d meshes: %zu pairs within margins, %zu collisions checked\n", n, pairs_checked, collisions_checked);
    return 0;
}

/* Contact records by (tri_a, tri_b). */
static int cmp_contact(const void *x, const void *y)
{
    const ttd_contact_d *a = x, *b = y;
    return a->tri_a != b->tri_a ? (a->tri_a < b->tri_a ? -1 : 1) : (a->tri_b > b->tri_b) - (a->tri_b < b->tri_b);
}

/* The query's set against the walk's (mesh/mesh.h, ttd_mesh_query_self_contacts_walk_d): the same
 * records, bit for bit, once sorted; with same_order, in the same order too (the query kept the
 * walk); the number of records in *n. */
static int query_equals_walk(const char *what, const ttd_mesh *m, double margin, unsigned flags, int same_order,
                             size_t *n)
{
    const ttd_engine_config cfg = {TTD_ISA_SCALAR, TTD_METHOD_EXACT, {0, 0, 1}, 1};
    ttd_options o = ttd_default_options();
    o.threads = 1;
    ttd_contacts_d got = {0}, walk = {0};
    ENSURE(ttd_mesh_self_contacts_d(&o, m, margin, flags, &got) == TTD_OK);
    ENSURE(ttd_mesh_query_self_contacts_walk_d(&cfg, m, margin, flags & TTD_SELF_SHARED_VERTEX, &walk) == TTD_OK);
    ENSURE_MSG(got.count == walk.count, "%s margin %.17g: %zu pairs, the walk %zu", what, margin, got.count, walk.count);
    if (same_order)
        ENSURE_MSG(got.count == 0 || memcmp(got.pairs, walk.pairs, got.count * sizeof *got.pairs) == 0,
                   "%s: not the walk's records in the walk's order", what);
    qsort(got.pairs, got.count, sizeof *got.pairs, cmp_contact);
    qsort(walk.pairs, walk.count, sizeof *walk.pairs, cmp_contact);
    ENSURE_MSG(got.count == 0 || memcmp(got.pairs, walk.pairs, got.count * sizeof *got.pairs) == 0,
               "%s margin %.17g: the records differ from the walk's", what, margin);
    *n = got.count;
    ttd_contacts_free_d(&got);
    ttd_contacts_free_d(&walk);
    return 0;
}

/* The ways a self-contact query goes (docs/mesh-queries.md, section 3b): the grid of leaves, on
 * issue 36's sheet folded into 7 layers (a smaller strip), the layers 1.5 and 0.8 margins apart,
 * against the brute force and the walk; a sheet with one triangle across all of it, whose leaf
 * the grid tests against every leaf (a large leaf), against the walk; and the walk itself, which
 * the query keeps when the leaves are so large alike that the grid would put them all in one
 * cell (6,000 slivers across a cube): its records come in the walk's order. */
static int grid_and_walk_match_brute_force(void)
{
    const size_t nx = 70, ny = 10;
    const double margin = 0.5 / (double)nx;
    for (int gi = 0; gi < 2; ++gi) {
        ttd_gen_mesh g;
        ENSURE(ttd_gen_folded_strip(nx, ny, 7, (gi ? 0.8 : 1.5) * margin, 1.0, &g) == 0);
        ENSURE(g.nt == 2 * nx * ny);
        if (check_mesh(gi ? "7 layers 0.8 margins apart (grid)" : "7 layers 1.5 margins apart (grid)", &g, margin))
            return 1;
        ttd_mesh *m;
        ENSURE(ttd_mesh_create_d(NULL, g.verts, g.nv, g.tris, g.nt, &m) == TTD_OK);
        for (int shared = 0; shared < 2; ++shared)
            for (int k = 0; k < 3; ++k) {
                size_t n;
                if (query_equals_walk("7 layers", m, margin * (k + 1), shared ? TTD_SELF_SHARED_VERTEX : 0u, 0, &n))
                    return 1;
                ENSURE(k > 0 || n > 0);
            }
        ttd_mesh_destroy(m);
        ttd_gen_mesh_free(&g);
    }
    /* 5,000 triangles and one across them all: the grid, with that triangle's leaf apart */
    ttd_gen_mesh g;
    ENSURE(ttd_gen_folded_sheet(50, 3, 0.01, 1.0, &g) == 0);
    double *v = realloc(g.verts, 3 * (g.nv + 3) * sizeof *v);
    ENSURE(v != NULL);
    g.verts = v;
    uint32_t *t = realloc(g.tris, 3 * (g.nt + 1) * sizeof *t);
    ENSURE(t != NULL);
    g.tris = t;
    const double big[9] = {-0.1, -0.1, 0.004, 1.2, -0.1, 0.004, -0.1, 1.2, 0.004};
    memcpy(g.verts + 3 * g.nv, big, sizeof big);
    for (int k = 0; k < 3; ++k)
        g.tris[3 * g.nt + (size_t)k] = (uint32_t)(g.nv + (size_t)k);
    g.nv += 3;
    g.nt += 1;
    ttd_mesh *m;
    ENSURE(ttd_mesh_create_d(NULL, g.verts, g.nv, g.tris, g.nt, &m) == TTD_OK);
    size_t n;
    for (int shared = 0; shared < 2; ++shared)
        if (query_equals_walk("sheet with one triangle across it", m, 0.011, shared ? TTD_SELF_SHARED_VERTEX : 0u, 0, &n))
            return 1;
    ENSURE(n > 5000);
    ttd_mesh_destroy(m);
    ttd_gen_mesh_free(&g);
    /* 6,000 slivers from z = 0 to z = 1 (750 leaves about as large as the cube, in one cell: past
     * the grid's work limit of 256 leaf tests a leaf): the walk */
    const size_t ns = 6000;
    double *sv = malloc(9 * ns * sizeof *sv);
    uint32_t *st = malloc(3 * ns * sizeof *st);
    ENSURE(sv != NULL && st != NULL);
    uint64_t r = 12345;
    for (size_t i = 0; i < 9 * ns; ++i) {
        r = r * 6364136223846793005u + 1442695040888963407u;
        sv[i] = (double)(r >> 11) * 0x1p-53;
    }
    for (size_t i = 0; i < ns; ++i) {
        sv[9 * i + 2] = 0, sv[9 * i + 5] = 1; /* from the floor to the ceiling */
        for (int k = 0; k < 3; ++k) /* the third vertex beside the second */
            sv[9 * i + 6 + k] = sv[9 * i + 3 + k] + 0.01 * (sv[9 * i + 6 + k] - 0.5);
        for (int k = 0; k < 3; ++k)
            st[3 * i + k] = (uint32_t)(3 * i + (size_t)k);
    }
    ENSURE(ttd_mesh_create_d(NULL, sv, 3 * ns, st, ns, &m) == TTD_OK);
    if (query_equals_walk("slivers across a cube", m, 1e-3, 0u, 1, &n))
        return 1;
    ENSURE(n > 1000);
    ttd_mesh_destroy(m);
    free(sv);
    free(st);
    return 0;
}

/* The grid's groups of triangles that share vertices (mesh/self_grid_impl.h, self_topo_make) on
 * meshes that stress their making, against the walk: a fan of 3,000 triangles around one vertex
 * (each visit of the centre looks at a bounded part of its list) with a second small fan apart
 * (a group cut short), with and without TTD_SELF_SHARED_VERTEX; and issue 36's 7-layer sheet with
 * its triangles shuffled (groups that do not follow the index order). */
static int topological_groups_match_walk(void)
{
    const int n = 3000, n2 = 5;
    ttd_gen_mesh g = {0};
    g.nv = (size_t)(n + 1 + n2 + 2);
    g.nt = (size_t)(n + n2);
    g.verts = malloc(3 * g.nv * sizeof *g.verts);
    g.tris = malloc(3 * g.nt * sizeof *g.tris);
    ENSURE(g.verts != NULL && g.tris != NULL);
    memset(g.verts, 0, 3 * sizeof *g.verts); /* the centre */
    for (int k = 0; k < n; ++k) {
        const double a = 6.283185307179586 * k / n;
        g.verts[3 * (size_t)(k + 1)] = cos(a);
        g.verts[3 * (size_t)(k + 1) + 1] = sin(a);
        g.verts[3 * (size_t)(k + 1) + 2] = 0;
        g.tris[3 * (size_t)k] = 0;
        g.tris[3 * (size_t)k + 1] = (uint32_t)k + 1;
        g.tris[3 * (size_t)k + 2] = (uint32_t)((k + 1) % n) + 1;
    }
    const uint32_t c2 = (uint32_t)n + 1; /* the small fan, 0.003 above the big one's rim */
    for (int k = 0; k <= n2 + 1; ++k) {
        double *v = g.verts + 3 * (size_t)(c2 + (uint32_t)k);
        v[0] = k == 0 ? 0.9 : 0.9 + 0.1 * cos(0.3 * k);
        v[1] = k == 0 ? 0 : 0.1 * sin(0.3 * k);
        v[2] = 0.003;
    }
    for (int k = 0; k < n2; ++k) {
        uint32_t *t = g.tris + 3 * (size_t)(n + k);
        t[0] = c2, t[1] = c2 + (uint32_t)k + 1, t[2] = c2 + (uint32_t)k + 2;
    }
    ttd_mesh *m;
    ENSURE(ttd_mesh_create_d(NULL, g.verts, g.nv, g.tris, g.nt, &m) == TTD_OK);
    size_t np;
    if (query_equals_walk("fan of 3,000", m, 0.005, TTD_SELF_SHARED_VERTEX, 0, &np))
        return 1;
    ENSURE(np > 3000);
    if (query_equals_walk("fan of 3,000", m, 0.005, 0u, 0, &np))
        return 1;
    ENSURE(np > 0);
    ttd_mesh_destroy(m);
    ttd_gen_mesh_free(&g);
    const size_t nx = 70, ny = 10;
    const double margin = 0.5 / (double)nx;
    ENSURE(ttd_gen_folded_strip(nx, ny, 7, 0.8 * margin, 1.0, &g) == 0);
    uint64_t r = 99;
    for (size_t i = g.nt - 1; i > 0; --i) { /* Fisher-Yates */
        r = r * 6364136223846793005u + 1442695040888963407u;
        const size_t j = (size_t)((r >> 33) % (i + 1));
        for (int k = 0; k < 3; ++k) {
            const uint32_t x = g.tris[3 * i + (size_t)k];
            g.tris[3 * i + (size_t)k] = g.tris[3 * j + (size_t)k];
            g.tris[3 * j + (size_t)k] = x;
        }
    }
    ENSURE(ttd_mesh_create_d(NULL, g.verts, g.nv, g.tris, g.nt, &m) == TTD_OK);
    for (int shared = 0; shared < 2; ++shared) {
        if (query_equals_walk("7 layers, triangles shuffled", m, margin, shared ? TTD_SELF_SHARED_VERTEX : 0u, 0, &np))
            return 1;
        ENSURE(np > 1000);
    }
    ttd_mesh_destroy(m);
    ttd_gen_mesh_free(&g);
    return 0;
}

/* A sheet folding over 30 steps, refitted each step, against the brute force every step. */
static int refitted_self_contacts_match_brute_force(void)
{
    ttd_gen_mesh g;
    ENSURE(ttd_gen_folded_sheet(9, 3, 0.03, 0, &g) == 0);
    ttd_mesh *m;
    ENSURE(ttd_mesh_create_d(NULL, g.verts, g.nv, g.tris, g.nt, &m) == TTD_OK);
    size_t found = 0;
    for (int step = 1; step <= 30; ++step) {
        ttd_gen_mesh s;
        ENSURE(ttd_gen_folded_sheet(9, 3, 0.03, step / 25.0, &s) == 0);
        ENSURE(ttd_mesh_set_vertices_d(NULL, m, s.verts) == TTD_OK);
        size_t np;
        spair *all = brute_self(s.verts, s.tris, s.nt, 0, 1, &np);
        char what[64];
        snprintf(what, sizeof what, "folding sheet, step %d", step);
        const size_t before = pairs_checked;
        if (check_margin(what, m, 0, TTD_SELF_SHARED_VERTEX, all, np, 0.04))
            return 1;
        found += pairs_checked - before;
        free(all);
        ttd_gen_mesh_free(&s);
    }
    ENSURE(found > 1000);
    printf("  30 steps, %zu pairs within the margin in all\n", found);
    ttd_mesh_destroy(m);
    ttd_gen_mesh_free(&g);
    return 0;
}

/* Every instruction set and 1 and 2 threads give the scalar row's bits, the order of the set and
 * the collision's witness included. */
static int self_queries_threads_isas_identical(void)
{
    ttd_gen_mesh g;
    ENSURE(ttd_gen_folded_sheet(40, 4, 0.01, 1.0, &g) == 0);
    ttd_mesh *m;
    ENSURE(ttd_mesh_create_d(NULL, g.verts, g.nv, g.tris, g.nt, &m) == TTD_OK);
    ttd_options o = ttd_default_options();
    o.isa = TTD_ISA_SCALAR;
    o.threads = 1;
    ttd_contacts_d ref = {0}, got = {0};
    ttd_collision cref, cgot;
    ENSURE(ttd_mesh_self_contacts_d(&o, m, 0.012, TTD_SELF_SHARED_VERTEX, &ref) == TTD_OK);
    ENSURE(ttd_mesh_self_collide_d(&o, m, 0.012, 0, &cref) == TTD_OK && cref.hit);
    ENSURE(ref.count > 5000);
    int rows = 0;
    for (int isa = 1; isa < TTD_ISA_COUNT; ++isa) {
        if (!ttd_isa_available((ttd_isa)isa))
            continue;
        ++rows;
        for (int threads = 1; threads <= 2; ++threads) {
            o.isa = (ttd_isa)isa;
            o.threads = threads;
            ENSURE(ttd_mesh_self_contacts_d(&o, m, 0.012, TTD_SELF_SHARED_VERTEX, &got) == TTD_OK);
            ENSURE_MSG(got.count == ref.count && memcmp(got.pairs, ref.pairs, got.count * sizeof *got.pairs) == 0,
                       "%s, %d threads: the set differs", ttd_isa_name((ttd_isa)isa), threads);
            ENSURE(ttd_mesh_self_collide_d(&o, m, 0.012, 0, &cgot) == TTD_OK);
            ENSURE(cgot.hit == cref.hit && cgot.tri_a == cref.tri_a && cgot.tri_b == cref.tri_b);
        }
    }
    printf("  %zu pairs, %d rows, 1 and 2 threads: the same bits and order\n", ref.count, rows);
    ttd_contacts_free_d(&ref);
    ttd_contacts_free_d(&got);
    ttd_mesh_destroy(m);
    ttd_gen_mesh_free(&g);
    return 0;
}

/* Four threads at once on one mesh, each query on one worker, two of them counting: the mesh's
 * kept arrays (ttd_mesh.self_scratch) are taken by one query at a time and the others make their
 * own; every answer equals the one-thread reference (run under ThreadSanitizer by
 * scripts/test-tsan.sh). */
#define CONC_SELF_THREADS 4
typedef struct {
    const ttd_mesh *m;
    int counting;
    const ttd_contacts_d *ref;
    int ok;
} conc_self_job;

static void *conc_self_run(void *p)
{
    conc_self_job *j = p;
    ttd_options o = ttd_default_options();
    o.threads = 1;
    j->ok = 1;
    for (int rep = 0; rep < 3; ++rep) {
        if (j->counting) {
            size_t n = 0;
            if (ttd_mesh_self_contacts_count_d(&o, j->m, 0.012, TTD_SELF_SHARED_VERTEX, &n) != TTD_OK ||
                n != j->ref->count)
                j->ok = 0;
        } else {
            ttd_contacts_d got = {0};
            if (ttd_mesh_self_contacts_d(&o, j->m, 0.012, TTD_SELF_SHARED_VERTEX, &got) != TTD_OK ||
                got.count != j->ref->count ||
                memcmp(got.pairs, j->ref->pairs, got.count * sizeof *got.pairs) != 0)
                j->ok = 0;
            ttd_contacts_free_d(&got);
        }
    }
    return NULL;
}

static int self_queries_concurrent(void)
{
    ttd_gen_mesh g;
    ENSURE(ttd_gen_folded_sheet(40, 4, 0.01, 1.0, &g) == 0);
    ttd_mesh *m;
    ENSURE(ttd_mesh_create_d(NULL, g.verts, g.nv, g.tris, g.nt, &m) == TTD_OK);
    ttd_options o = ttd_default_options();
    o.threads = 1;
    ttd_contacts_d ref = {0};
    ENSURE(ttd_mesh_self_contacts_d(&o, m, 0.012, TTD_SELF_SHARED_VERTEX, &ref) == TTD_OK);
    ENSURE(ref.count > 5000);
    conc_self_job jobs[CONC_SELF_THREADS];
    pthread_t th[CONC_SELF_THREADS];
    for (int t = 0; t < CONC_SELF_THREADS; ++t) {
        jobs[t] = (conc_self_job){m, t & 1, &ref, 0};
        ENSURE(pthread_create(&th[t], NULL, conc_self_run, &jobs[t]) == 0);
    }
    for (int t = 0; t < CONC_SELF_THREADS; ++t)
        ENSURE(pthread_join(th[t], NULL) == 0);
    for (int t = 0; t < CONC_SELF_THREADS; ++t)
        ENSURE_MSG(jobs[t].ok, "thread %d (%s): an answer differs from the one-thread reference", t,
                   jobs[t].counting ? "count" : "contacts");
    printf("  %d threads x 3 queries on one mesh: %zu pairs each\n", CONC_SELF_THREADS, ref.count);
    ttd_contacts_free_d(&ref);
    ttd_mesh_destroy(m);
    ttd_gen_mesh_free(&g);
    return 0;
}

static int bad_input_refused(void)
{
    ttd_gen_mesh g;
    ENSURE(ttd_gen_grid(3, &g) == 0);
    ttd_mesh *m, *mf;
    ENSURE(ttd_mesh_create_d(NULL, g.verts, g.nv, g.tris, g.nt, &m) == TTD_OK);
    const float vf[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t t[3] = {0, 1, 2};
    ENSURE(ttd_mesh_create_f(NULL, vf, 3, t, 1, &mf) == TTD_OK);
    ttd_contacts_d set = {0};
    ttd_contacts_f setf = {0};
    ttd_collision col;
    ENSURE(ttd_mesh_self_contacts_d(NULL, NULL, 0.1, 0, &set) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_mesh_self_contacts_d(NULL, m, 0.1, 0, NULL) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_mesh_self_collide_d(NULL, m, 0.1, 0, NULL) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_mesh_self_contacts_d(NULL, m, -1, 0, &set) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_mesh_self_contacts_d(NULL, m, (double)NAN, 0, &set) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_mesh_self_contacts_d(NULL, m, (double)INFINITY, 0, &set) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_mesh_self_contacts_d(NULL, m, 0.1, 4, &set) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_mesh_self_collide_d(NULL, m, (double)NAN, 0, &col) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_mesh_self_contacts_f(NULL, m, 0.1f, 0, &setf) == TTD_ERR_PRECISION_MISMATCH);
    ENSURE(ttd_mesh_self_contacts_d(NULL, mf, 0.1, 0, &set) == TTD_ERR_PRECISION_MISMATCH);
    ttd_options bad = ttd_default_options();
    bad.method = TTD_METHOD_PENALTY;
    ENSURE(ttd_mesh_self_contacts_d(&bad, m, 0.1, 0, &set) == TTD_ERR_BAD_OPTIONS);
    ENSURE(set.count == 0);
    /* the count-only query: the same checks */
    size_t n = 0;
    ENSURE(ttd_mesh_self_contacts_count_d(NULL, NULL, 0.1, 0, &n) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_mesh_self_contacts_count_d(NULL, m, 0.1, 0, NULL) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_mesh_self_contacts_count_d(NULL, m, -1, 0, &n) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_mesh_self_contacts_count_d(NULL, m, (double)NAN, 0, &n) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_mesh_self_contacts_count_d(NULL, m, 0.1, 4, &n) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_mesh_self_contacts_count_f(NULL, m, 0.1f, 0, &n) == TTD_ERR_PRECISION_MISMATCH);
    ENSURE(ttd_mesh_self_contacts_count_d(&bad, m, 0.1, 0, &n) == TTD_ERR_BAD_OPTIONS);
    /* one triangle: nothing; a flat grid at margin 0: nothing (neighbours share vertices) */
    ENSURE(ttd_mesh_self_contacts_f(NULL, mf, 1.0f, TTD_SELF_SHARED_VERTEX, &setf) == TTD_OK && setf.count == 0);
    ENSURE(ttd_mesh_self_collide_d(NULL, m, 0, TTD_SELF_SHARED_VERTEX, &col) == TTD_OK && col.hit == 0);
    ttd_contacts_free_d(&set);
    ttd_contacts_free_f(&setf);
    ttd_mesh_destroy(m);
    ttd_mesh_destroy(mf);
    ttd_gen_mesh_free(&g);
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(self_contacts_match_brute_force);
    RUN_TEST(grid_and_walk_match_brute_force);
    RUN_TEST(topological_groups_match_walk);
    RUN_TEST(refitted_self_contacts_match_brute_force);
    RUN_TEST(self_queries_threads_isas_identical);
    RUN_TEST(self_queries_concurrent);
    RUN_TEST(bad_input_refused);
    TEST_MAIN_END();
}
