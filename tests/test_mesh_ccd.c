/* SPDX-License-Identifier: MIT */
/* Continuous collision of deforming meshes (src/meshccd/, docs/ccd.md section 10) against the
 * brute force over every triangle pair (tests/mesh_ccd_brute.h): the same earliest toi and the
 * same pairs, bit for bit, on random deforming meshes, two meshes passing through each other, a
 * folding sheet (self, with and without the shared-vertex pairs), contact at t = 0 and t = 1,
 * min_separation > 0, degenerate triangles; threads, float against double, and the scalar row
 * against the lanes; the whole-pair proof in every row's lanes against the scalar proof; the
 * checks. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "isa_rows.h"
#include "meshccd/meshccd.h"
#include "meshes.h"
#include "mesh_ccd_brute.h"
#include "test_macros.h"
#include "ttd/ttd.h"

#define TEST_RAND_SEED 0x243f6a8885a308d3ull
#include "test_rand.h"

static ttd_options opts(int threads)
{
    ttd_options o = ttd_default_options();
    o.threads = threads;
    return o;
}

/* Two results the same, bit for bit (triangle_pairs and queries aside). */
static int same(const ttd_mesh_ccd_result *r, const ttd_mesh_ccd_result *s, const char *what)
{
    ENSURE_MSG(memcmp(&r->toi, &s->toi, sizeof r->toi) == 0, "%s: toi %.17g vs %.17g", what, r->toi, s->toi);
    ENSURE_MSG(r->count == s->count, "%s: %zu pairs vs %zu (toi %.17g)", what, r->count, s->count, r->toi);
    ENSURE_MSG(r->flags == s->flags, "%s: flags", what);
    for (size_t i = 0; i < r->count; ++i) {
        const ttd_mesh_ccd_pair *p = &r->pairs[i], *q = &s->pairs[i];
        ENSURE_MSG(memcmp(&p->toi, &q->toi, sizeof p->toi) == 0 && memcmp(&p->gap, &q->gap, sizeof p->gap) == 0 &&
                       p->kind == q->kind && p->flags == q->flags && p->a[0] == q->a[0] && p->a[1] == q->a[1] &&
                       p->b[0] == q->b[0] && p->b[1] == q->b[1],
                   "%s: pair %zu: kind %u (%u %u | %u %u) toi %.17g vs kind %u (%u %u | %u %u) toi %.17g", what, i,
                   p->kind, p->a[0], p->a[1], p->b[0], p->b[1], p->toi, q->kind, q->a[0], q->a[1], q->b[0], q->b[1],
                   q->toi);
    }
    return 0;
}

/* Every pair's own toi within the window; the earliest is one of them. */
static int well_formed(const ttd_mesh_ccd_result *r)
{
    if (r->count == 0) {
        ENSURE(isinf(r->toi));
        return 0;
    }
    ENSURE(r->toi >= 0 && r->toi <= 1);
    ENSURE(r->pairs[0].toi == r->toi);
    for (size_t i = 0; i < r->count; ++i)
        ENSURE(r->pairs[i].toi >= r->toi && r->pairs[i].toi <= r->toi + TTD_CCD_DEFAULT_T_TOL);
    return 0;
}

/* Mesh-mesh: the library with 1 and 3 threads and the brute force agree; counts hits into *hits. */
static int check_two(const ttd_gen_mesh *a, const double *a1, const ttd_gen_mesh *b, const double *b1, double delta,
                     const char *what, int *hits)
{
    ttd_mesh *ma = NULL, *mb = NULL;
    ENSURE(ttd_mesh_create_d(NULL, a->verts, a->nv, a->tris, a->nt, &ma) == TTD_OK);
    ENSURE(ttd_mesh_create_d(NULL, b->verts, b->nv, b->tris, b->nt, &mb) == TTD_OK);
    ttd_mesh_ccd_result r1, r3, ref;
    const ttd_options o1 = opts(1), o3 = opts(3);
    ENSURE(ttd_mesh_ccd_d(&o1, ma, a1, mb, b1, delta, &r1) == TTD_OK);
    ENSURE(ttd_mesh_ccd_d(&o3, ma, a1, mb, b1, delta, &r3) == TTD_OK);
    ENSURE(brute_mesh_ccd(a->verts, a1, a->tris, a->nt, b->verts, b1, b->tris, b->nt, delta, &ref) == 0);
    int rc = same(&r1, &ref, what) || same(&r3, &r1, what) || well_formed(&r1);
    if (hits)
        *hits += r1.count > 0;
    ttd_mesh_ccd_free(&r1);
    ttd_mesh_ccd_free(&r3);
    free(ref.pairs);
    ttd_mesh_destroy(ma);
    ttd_mesh_destroy(mb);
    return rc;
}

static int check_self(const ttd_gen_mesh *m, const double *x1, double delta, unsigned flags, const char *what,
                      int *hits)
{
    ttd_mesh *mm = NULL;
    ENSURE(ttd_mesh_create_d(NULL, m->verts, m->nv, m->tris, m->nt, &mm) == TTD_OK);
    ttd_mesh_ccd_result r1, r3, rs, ref;
    const ttd_options o1 = opts(1), o3 = opts(3);
    ttd_options os = opts(1);
    os.isa = TTD_ISA_SCALAR; /* the whole-pair proof without lanes (o1: the best row's lanes) */
    ENSURE(ttd_mesh_self_ccd_d(&o1, mm, x1, delta, flags, &r1) == TTD_OK);
    ENSURE(ttd_mesh_self_ccd_d(&o3, mm, x1, delta, flags, &r3) == TTD_OK);
    ENSURE(ttd_mesh_self_ccd_d(&os, mm, x1, delta, flags, &rs) == TTD_OK);
    ENSURE(brute_self_ccd(m->verts, x1, m->tris, m->nt, delta, (flags & TTD_SELF_SHARED_VERTEX) != 0, &ref) == 0);
    int rc = same(&r1, &ref, what) || same(&r3, &r1, what) || same(&rs, &r1, what) || well_formed(&r1);
    if (hits)
        *hits += r1.count > 0;
    ttd_mesh_ccd_free(&r1);
    ttd_mesh_ccd_free(&r3);
    ttd_mesh_ccd_free(&rs);
    free(ref.pairs);
    ttd_mesh_destroy(mm);
    return rc;
}

static double *moved(const ttd_gen_mesh *m, const double shift[3], double jitter)
{
    double *x = malloc(3 * m->nv * sizeof *x);
    for (size_t i = 0; i < 3 * m->nv; ++i)
        x[i] = m->verts[i] + shift[i % 3] + jitter * srand1();
    return x;
}

/* Two spheres (and a torus) with every vertex moving on its own random path, towards each other
 * from random gaps: some meet, some do not. */
static int random_meshes(void)
{
    int hits = 0, cases = 0;
    for (int it = 0; it < 24; ++it) {
        ttd_gen_mesh a, b;
        ENSURE(ttd_gen_icosphere(1, &a) == 0);
        if (it % 3 == 2)
            ENSURE(ttd_gen_torus(1.0, 0.3, 10, 6, &b) == 0);
        else
            ENSURE(ttd_gen_icosphere(1, &b) == 0);
        const double gap = 2.1 + 0.6 * urand();
        for (size_t i = 0; i < 3 * b.nv; i += 3)
            b.verts[i] += gap;
        for (size_t i = 0; i < 3 * a.nv; ++i)
            a.verts[i] += 0.05 * srand1();
        const double sa[3] = {0.3 + 0.2 * srand1(), 0.1 * srand1(), 0.1 * srand1()};
        const double sb[3] = {-0.3 + 0.2 * srand1(), 0.1 * srand1(), 0.1 * srand1()};
        double *a1 = moved(&a, sa, 0.1), *b1 = moved(&b, sb, 0.1);
        const double delta = it % 4 == 3 ? 0.05 : 0.0;
        char what[64];
        snprintf(what, sizeof what, "random %d", it);
        const int rc = check_two(&a, a1, &b, b1, delta, what, &hits);
        ++cases;
        free(a1);
        free(b1);
        ttd_gen_mesh_free(&a);
        ttd_gen_mesh_free(&b);
        if (rc)
            return 1;
    }
    printf("  random deforming meshes: %d of %d cases hit\n", hits, cases);
    ENSURE(hits > 3 && hits < cases); /* both kinds of case were exercised */
    return 0;
}

/* A sheet falling through another at an angle: the earliest contact is a known vertex's. */
static int sheets_through(void)
{
    ttd_gen_mesh a, b;
    ENSURE(ttd_gen_grid(6, &a) == 0 && ttd_gen_grid(5, &b) == 0);
    for (size_t i = 0; i < b.nv; ++i) {
        b.verts[3 * i] = 0.1 + 0.8 * b.verts[3 * i];
        b.verts[3 * i + 1] = 0.1 + 0.8 * b.verts[3 * i + 1];
        b.verts[3 * i + 2] = 0.5 + 0.25 * b.verts[3 * i]; /* tilted: the side x = 0.1 lowest */
    }
    double *a1 = malloc(3 * a.nv * sizeof *a1), *b1 = malloc(3 * b.nv * sizeof *b1);
    memcpy(a1, a.verts, 3 * a.nv * sizeof *a1);
    for (size_t i = 0; i < 3 * b.nv; ++i)
        b1[i] = b.verts[i] - (i % 3 == 2 ? 1.0 : 0.0);
    ttd_mesh *ma, *mb;
    ENSURE(ttd_mesh_create_d(NULL, a.verts, a.nv, a.tris, a.nt, &ma) == TTD_OK);
    ENSURE(ttd_mesh_create_d(NULL, b.verts, b.nv, b.tris, b.nt, &mb) == TTD_OK);
    ttd_mesh_ccd_result r;
    ENSURE(ttd_mesh_ccd_d(NULL, ma, a1, mb, b1, 0.0, &r) == TTD_OK);
    /* b's lowest vertices (x = 0.1, z = 0.525) reach z = 0 at t = 0.525 */
    ENSURE(r.count > 0);
    ENSURE(r.toi <= 0.525 && r.toi > 0.525 - 1e-9);
    ENSURE(r.pairs[0].kind == TTD_MESH_CCD_FV || r.pairs[0].kind == TTD_MESH_CCD_EE);
    ttd_mesh_ccd_free(&r);
    ttd_mesh_destroy(ma);
    ttd_mesh_destroy(mb);
    const int rc = check_two(&a, a1, &b, b1, 0.0, "sheets", NULL) || check_two(&a, a1, &b, b1, 0.01, "sheets d", NULL);
    free(a1);
    free(b1);
    ttd_gen_mesh_free(&a);
    ttd_gen_mesh_free(&b);
    return rc;
}

/* A sheet folded in three layers, folding on through itself (t 0.9 to 1.4, 0.95 to 1.25), and the fold
 * stopping short (0.6 to 0.9), with and without the shared-vertex pairs and min_separation. */
static int folding_sheet(void)
{
    const double fold[][2] = {{0.9, 1.4}, {0.6, 0.9}, {0.95, 1.25}};
    int hits = 0;
    for (int f = 0; f < 3; ++f) {
        ttd_gen_mesh m0, m1;
        ENSURE(ttd_gen_folded_sheet(12, 3, 0.1, fold[f][0], &m0) == 0);
        ENSURE(ttd_gen_folded_sheet(12, 3, 0.1, fold[f][1], &m1) == 0);
        ENSURE(m0.nv == m1.nv);
        for (unsigned flags = 0; flags < 2; ++flags)
            for (int d = 0; d < 2; ++d) {
                char what[64];
                snprintf(what, sizeof what, "fold %d flags %u delta %d", f, flags, d);
                if (check_self(&m0, m1.verts, d ? 0.02 : 0.0, flags, what, &hits)) {
                    ttd_gen_mesh_free(&m0);
                    ttd_gen_mesh_free(&m1);
                    return 1;
                }
            }
        ttd_gen_mesh_free(&m0);
        ttd_gen_mesh_free(&m1);
    }
    printf("  folding sheet: %d of 12 cases hit\n", hits);
    ENSURE(hits >= 4);
    return 0;
}

/* Random self motion: a sphere whose vertices move far and at random (it tangles), a grid
 * crumpling, the degenerate mesh (repeated indices, zero-area triangles). */
static int random_self(void)
{
    int hits = 0;
    for (int it = 0; it < 12; ++it) {
        ttd_gen_mesh m;
        if (it % 3 == 0)
            ENSURE(ttd_gen_icosphere(1, &m) == 0);
        else if (it % 3 == 1)
            ENSURE(ttd_gen_grid(7, &m) == 0);
        else
            ENSURE(ttd_gen_mesh_degenerate(&m) == 0);
        const double zero[3] = {0, 0, 0};
        double *x1 = moved(&m, zero, it % 3 == 0 ? 0.4 : 0.3);
        char what[64];
        snprintf(what, sizeof what, "self %d", it);
        const int rc = check_self(&m, x1, it % 2 ? 0.01 : 0.0, (unsigned)(it / 6), what, &hits);
        free(x1);
        ttd_gen_mesh_free(&m);
        if (rc)
            return 1;
    }
    printf("  random self motion: %d of 12 cases hit\n", hits);
    ENSURE(hits >= 3);
    return 0;
}

/* Self-CCD of a soup of separate triangles, one to a cell of a 5 x 4 x 3 grid of cells of side
 * 1 (60 triangles: full and partial leaves of the self tree), each shrunk about its cell's corner
 * at t = 0 and whole at t = 1, so that neighbours' swept boxes touch exactly (max of one = min of
 * the next, on every axis) and their corners meet exactly at t = 1; every other triangle stays
 * shrunk (those pairs never touch). The leaves' box test must count boxes that touch (closed
 * boxes): with a strict test these contacts are lost and the brute force disagrees. At delta 0
 * and 1/8 of a cell, and scaled by 2^100 and 2^-100 (about 1e30 and 1e-30: exact, dyadic). */
static int self_boxes_touch(void)
{
    const int nx = 5, ny = 4, nz = 3, n = nx * ny * nz;
    ttd_gen_mesh m = {malloc(9 * (size_t)n * sizeof(double)), 3 * (size_t)n, malloc(3 * (size_t)n * sizeof(uint32_t)),
                      (size_t)n};
    double *x1 = malloc(9 * (size_t)n * sizeof *x1);
    const double corner[3][3] = {{0, 0, 0}, {1, 0, 1}, {0, 1, 1}}; /* spans the cell on every axis */
    const double scales[3] = {1.0, 0x1p100, 0x1p-100};
    int hits = 0;
    for (int sc = 0; sc < 3; ++sc) {
        int t = 0;
        for (int k = 0; k < nz; ++k)
            for (int j = 0; j < ny; ++j)
                for (int i = 0; i < nx; ++i, ++t) {
                    const double c[3] = {i, j, k};
                    const int grows = (i + j + k) % 2 == 0 || t % 7 == 0;
                    for (int v = 0; v < 3; ++v) {
                        m.tris[3 * t + v] = (uint32_t)(3 * t + v);
                        for (int a = 0; a < 3; ++a) {
                            m.verts[9 * t + 3 * v + a] = scales[sc] * (c[a] + 0.25 + 0.5 * corner[v][a]);
                            x1[9 * t + 3 * v + a] = scales[sc] * (grows ? c[a] + corner[v][a] : c[a] + 0.25 + 0.5 * corner[v][a]);
                        }
                    }
                }
        for (int d = 0; d < 2; ++d) {
            char what[64];
            snprintf(what, sizeof what, "touching boxes scale %d delta %d", sc, d);
            if (check_self(&m, x1, d ? 0.125 * scales[sc] : 0.0, 0, what, &hits)) {
                ttd_gen_mesh_free(&m);
                free(x1);
                return 1;
            }
        }
    }
    printf("  touching boxes: %d of 6 cases hit\n", hits);
    ENSURE(hits == 6);
    ttd_gen_mesh_free(&m);
    free(x1);
    return 0;
}

/* Contact exactly at t = 0 (a vertex of b on a's face, moving away: toi 0) and exactly at t = 1
 * (arriving: toi within the tolerance of 1, never after). */
static int touching_ends(void)
{
    ttd_gen_mesh a, b;
    ENSURE(ttd_gen_grid(4, &a) == 0 && ttd_gen_mesh_tetrahedron(&b) == 0);
    /* the tetrahedron's vertex 0 at (0.375, 0.3125, 0): inside a face of the grid, exactly */
    for (size_t i = 0; i < b.nv; ++i) {
        b.verts[3 * i] = 0.375 + 0.25 * b.verts[3 * i];
        b.verts[3 * i + 1] = 0.3125 + 0.25 * b.verts[3 * i + 1];
        b.verts[3 * i + 2] = 0.25 * b.verts[3 * i + 2];
    }
    double *a1 = malloc(3 * a.nv * sizeof *a1), *b1 = malloc(3 * b.nv * sizeof *b1);
    memcpy(a1, a.verts, 3 * a.nv * sizeof *a1);
    for (size_t i = 0; i < 3 * b.nv; ++i)
        b1[i] = b.verts[i] + (i % 3 == 2 ? 0.5 : 0.0);
    ttd_mesh *ma, *mb;
    ENSURE(ttd_mesh_create_d(NULL, a.verts, a.nv, a.tris, a.nt, &ma) == TTD_OK);
    ENSURE(ttd_mesh_create_d(NULL, b.verts, b.nv, b.tris, b.nt, &mb) == TTD_OK);
    ttd_mesh_ccd_result r;
    ENSURE(ttd_mesh_ccd_d(NULL, ma, a1, mb, b1, 0.0, &r) == TTD_OK);
    ENSURE(r.toi == 0 && r.count >= 1);
    ttd_mesh_ccd_free(&r);
    int rc = check_two(&a, a1, &b, b1, 0.0, "touch t0", NULL);
    /* reversed: b comes down onto the grid and touches at t = 1 (b's t = 0 is the old t = 1) */
    ttd_gen_mesh b_up;
    ENSURE(ttd_gen_mesh_copy(&b, &b_up) == 0);
    memcpy(b_up.verts, b1, 3 * b.nv * sizeof *b1);
    ttd_mesh *mb_up;
    ENSURE(ttd_mesh_create_d(NULL, b_up.verts, b_up.nv, b_up.tris, b_up.nt, &mb_up) == TTD_OK);
    ENSURE(ttd_mesh_ccd_d(NULL, ma, a1, mb_up, b.verts, 0.0, &r) == TTD_OK);
    ENSURE(r.count >= 1 && r.toi <= 1 && r.toi >= 1 - 1e-12);
    ttd_mesh_ccd_free(&r);
    /* a gap of 0.1 kept at t = 1: a miss at delta 0.05, a hit at delta 0.1 exactly and 0.15 */
    double *b_near = malloc(3 * b.nv * sizeof *b_near);
    for (size_t i = 0; i < 3 * b.nv; ++i)
        b_near[i] = b.verts[i] + (i % 3 == 2 ? 0.125 : 0.0);
    ENSURE(ttd_mesh_ccd_d(NULL, ma, a1, mb_up, b_near, 0.0625, &r) == TTD_OK);
    ENSURE(r.count == 0 && isinf(r.toi));
    ENSURE(ttd_mesh_ccd_d(NULL, ma, a1, mb_up, b_near, 0.125, &r) == TTD_OK);
    ENSURE(r.count >= 1 && r.toi <= 1 && r.toi > 0.99);
    ttd_mesh_ccd_free(&r);
    ENSURE(ttd_mesh_ccd_d(NULL, ma, a1, mb_up, b_near, 0.25, &r) == TTD_OK);
    ENSURE(r.count >= 1 && r.toi < 1);
    ttd_mesh_ccd_free(&r);
    rc = rc || check_two(&a, a1, &b_up, b.verts, 0.0, "touch t1", NULL) ||
         check_two(&a, a1, &b_up, b_near, 0.125, "near t1", NULL);
    ttd_mesh_destroy(ma);
    ttd_mesh_destroy(mb);
    ttd_mesh_destroy(mb_up);
    free(a1);
    free(b1);
    free(b_near);
    ttd_gen_mesh_free(&a);
    ttd_gen_mesh_free(&b);
    ttd_gen_mesh_free(&b_up);
    return rc;
}

/* Triangles that repeat an index: a zero-length edge (0, 0) belongs only to a triangle that
 * repeats vertex 0, not to every triangle around 0 (found by fuzz_mesh_ccd: the edge of (0, 0, 0)
 * was given to (3, 0, 1) as its owner and never queried). Every vertex at one point, so that every
 * pair touches at t = 0 and every pair must be reported. */
static int repeated_indices(void)
{
    double va[18], vb[9], va1[18], vb1[9];
    for (int i = 0; i < 18; ++i)
        va[i] = va1[i] = -2.0;
    for (int i = 0; i < 9; ++i)
        vb[i] = vb1[i] = -2.0;
    va1[0] = 1.0; /* one vertex moves, the rest stay */
    uint32_t ta[15] = {1, 2, 1, 3, 0, 1, 0, 2, 4, 0, 0, 0, 0, 0, 0}, tb[3] = {0, 0, 0};
    ttd_gen_mesh a = {va, 6, ta, 5}, b = {vb, 3, tb, 1};
    int rc = check_two(&a, va1, &b, vb1, 0.0, "repeated two", NULL) || check_two(&b, vb1, &a, va1, 0.375, "repeated back", NULL);
    for (unsigned flags = 0; flags < 2 && !rc; ++flags)
        rc = check_self(&a, va1, 0.0, flags, "repeated self", NULL);
    /* self: (5, 0, 6) holds vertex 0 but not the edge (0, 0) of (0, 0, 0) */
    double vc[21], vc1[21];
    for (int i = 0; i < 21; ++i)
        vc[i] = vc1[i] = 0.5;
    vc1[20] = 3.0;
    uint32_t tc[9] = {5, 0, 6, 0, 0, 0, 1, 2, 3};
    ttd_gen_mesh c = {vc, 7, tc, 3};
    for (unsigned flags = 0; flags < 2 && !rc; ++flags)
        rc = check_self(&c, vc1, 0.0, flags, "repeated self 2", NULL);
    return rc;
}

/* Float meshes give the double answer on the widened numbers, bit for bit. */
static int float_matches_double(void)
{
    ttd_gen_mesh m0, m1;
    ENSURE(ttd_gen_folded_sheet(6, 3, 0.1, 0.9, &m0) == 0 && ttd_gen_folded_sheet(6, 3, 0.1, 1.4, &m1) == 0);
    const size_t n = 3 * m0.nv;
    float *f0 = malloc(n * sizeof *f0), *f1 = malloc(n * sizeof *f1);
    double *d0 = malloc(n * sizeof *d0), *d1 = malloc(n * sizeof *d1);
    for (size_t i = 0; i < n; ++i) {
        f0[i] = (float)m0.verts[i];
        f1[i] = (float)m1.verts[i];
        d0[i] = f0[i];
        d1[i] = f1[i];
    }
    ttd_mesh *mf, *md;
    ENSURE(ttd_mesh_create_f(NULL, f0, m0.nv, m0.tris, m0.nt, &mf) == TTD_OK);
    ENSURE(ttd_mesh_create_d(NULL, d0, m0.nv, m0.tris, m0.nt, &md) == TTD_OK);
    ttd_mesh_ccd_result rf, rd;
    ENSURE(ttd_mesh_self_ccd_f(NULL, mf, f1, 0.0, 0, &rf) == TTD_OK);
    ENSURE(ttd_mesh_self_ccd_d(NULL, md, d1, 0.0, 0, &rd) == TTD_OK);
    ENSURE(rd.count > 0);
    int rc = same(&rf, &rd, "float self");
    ttd_mesh_ccd_free(&rf);
    ttd_mesh_ccd_free(&rd);
    ENSURE(ttd_mesh_ccd_f(NULL, mf, f0, mf, f1, 0.0, &rf) == TTD_OK);
    ENSURE(ttd_mesh_ccd_d(NULL, md, d0, md, d1, 0.0, &rd) == TTD_OK);
    rc = rc || same(&rf, &rd, "float two");
    ENSURE(rd.count > 0 && rd.toi == 0); /* the mesh against a copy of itself touches at t = 0 */
    ttd_mesh_ccd_free(&rf);
    ttd_mesh_ccd_free(&rd);
    ttd_mesh_destroy(mf);
    ttd_mesh_destroy(md);
    free(f0), free(f1), free(d0), free(d1);
    ttd_gen_mesh_free(&m0);
    ttd_gen_mesh_free(&m1);
    return rc;
}

/* Results do not depend on the thread count (a larger sheet than the brute force can take). */
static int threads(void)
{
    ttd_gen_mesh m0, m1;
    ENSURE(ttd_gen_folded_sheet(40, 4, 0.05, 0.95, &m0) == 0 && ttd_gen_folded_sheet(40, 4, 0.05, 1.3, &m1) == 0);
    ttd_mesh *m;
    ENSURE(ttd_mesh_create_d(NULL, m0.verts, m0.nv, m0.tris, m0.nt, &m) == TTD_OK);
    ttd_mesh_ccd_result r[4];
    const int th[4] = {1, 2, 3, 8};
    for (int i = 0; i < 4; ++i) {
        const ttd_options o = opts(th[i]);
        ENSURE(ttd_mesh_self_ccd_d(&o, m, m1.verts, 0.001, TTD_SELF_SHARED_VERTEX, &r[i]) == TTD_OK);
    }
    ENSURE(r[0].count > 0);
    printf("  sheet of %zu triangles: toi %.17g, %zu pairs, %llu triangle pairs, %llu queries\n", m0.nt, r[0].toi,
           r[0].count, (unsigned long long)r[0].triangle_pairs, (unsigned long long)r[0].queries);
    int rc = 0;
    for (int i = 1; i < 4; ++i) {
        rc = rc || same(&r[i], &r[0], "threads");
        ENSURE(r[i].triangle_pairs == r[0].triangle_pairs && r[i].queries == r[0].queries);
    }
    for (int i = 0; i < 4; ++i)
        ttd_mesh_ccd_free(&r[i]);
    ttd_mesh_destroy(m);
    ttd_gen_mesh_free(&m0);
    ttd_gen_mesh_free(&m1);
    return rc;
}

static int checks(void)
{
    ttd_gen_mesh g;
    ENSURE(ttd_gen_grid(2, &g) == 0);
    ttd_mesh *m, *mf;
    ENSURE(ttd_mesh_create_d(NULL, g.verts, g.nv, g.tris, g.nt, &m) == TTD_OK);
    float fv[27];
    for (int i = 0; i < 27; ++i)
        fv[i] = (float)g.verts[i];
    ENSURE(ttd_mesh_create_f(NULL, fv, g.nv, g.tris, g.nt, &mf) == TTD_OK);
    double *x1 = g.verts;
    ttd_mesh_ccd_result r;
    ENSURE(ttd_mesh_ccd_d(NULL, m, x1, m, x1, 0.0, NULL) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_mesh_ccd_d(NULL, NULL, x1, m, x1, 0.0, &r) == TTD_ERR_NULL_POINTER && r.count == 0 && !r.pairs);
    ENSURE(ttd_mesh_ccd_d(NULL, m, NULL, m, x1, 0.0, &r) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_mesh_ccd_d(NULL, m, x1, NULL, x1, 0.0, &r) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_mesh_ccd_d(NULL, m, x1, m, NULL, 0.0, &r) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_mesh_self_ccd_d(NULL, m, NULL, 0.0, 0, &r) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_mesh_self_ccd_d(NULL, NULL, x1, 0.0, 0, &r) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_mesh_ccd_d(NULL, m, x1, m, x1, -1.0, &r) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_mesh_ccd_d(NULL, m, x1, m, x1, NAN, &r) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_mesh_ccd_d(NULL, m, x1, m, x1, INFINITY, &r) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_mesh_self_ccd_d(NULL, m, x1, 0.0, 2u, &r) == TTD_ERR_BAD_OPTIONS);
    ttd_options bad;
    memset(&bad, 0, sizeof bad);
    ENSURE(ttd_mesh_ccd_d(&bad, m, x1, m, x1, 0.0, &r) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_mesh_ccd_d(NULL, mf, x1, m, x1, 0.0, &r) == TTD_ERR_PRECISION_MISMATCH);
    ENSURE(ttd_mesh_ccd_f(NULL, m, fv, mf, fv, 0.0, &r) == TTD_ERR_PRECISION_MISMATCH);
    ENSURE(ttd_mesh_self_ccd_f(NULL, m, fv, 0.0, 0, &r) == TTD_ERR_PRECISION_MISMATCH);
    double y[27];
    memcpy(y, g.verts, sizeof y);
    y[13] = NAN;
    ENSURE(ttd_mesh_ccd_d(NULL, m, x1, m, y, 0.0, &r) == TTD_ERR_NONFINITE_MESH && r.count == 0);
    y[13] = -INFINITY;
    ENSURE(ttd_mesh_self_ccd_d(NULL, m, y, 0.0, 0, &r) == TTD_ERR_NONFINITE_MESH);
    fv[5] = INFINITY;
    ENSURE(ttd_mesh_self_ccd_f(NULL, mf, fv, 0.0, 0, &r) == TTD_ERR_NONFINITE_MESH);
    /* extreme but finite coordinates: answered, not refused */
    for (int i = 0; i < 27; ++i)
        y[i] = g.verts[i] * 1e300 - 1e300;
    ENSURE(ttd_mesh_self_ccd_d(NULL, m, y, 1e300, TTD_SELF_SHARED_VERTEX, &r) == TTD_OK);
    ENSURE(well_formed(&r) == 0);
    ttd_mesh_ccd_free(&r);
    ttd_mesh_ccd_free(NULL);
    ttd_mesh_destroy(m);
    ttd_mesh_destroy(mf);
    ttd_gen_mesh_free(&g);
    return 0;
}

/* ---- the whole-pair proof in lanes (core/kernels.h, tri_apart) against the scalar proof ---- */

enum { AP_FAMILIES = 7 };
static const char *const ap_family[AP_FAMILIES] = {"random",   "sheet neighbours", "layers",    "touching",
                                                   "degenerate", "scaled 2^-600..2^1000", "parallel motion"};

/* A random rotation (rows), applied to every point: the pair's numbers rounded as a sheet's are. */
static void ap_rotate(double p[2][6][3])
{
    double a = 6.283185307179586 * urand(), b = 6.283185307179586 * urand();
    const double r[3][3] = {{cos(a), -sin(a), 0}, {sin(a) * cos(b), cos(a) * cos(b), -sin(b)},
                            {sin(a) * sin(b), cos(a) * sin(b), cos(b)}};
    for (int e = 0; e < 2; ++e)
        for (int i = 0; i < 6; ++i) {
            const double x[3] = {p[e][i][0], p[e][i][1], p[e][i][2]};
            for (int c = 0; c < 3; ++c)
                p[e][i][c] = r[c][0] * x[0] + r[c][1] * x[1] + r[c][2] * x[2];
        }
}

/* Pair k of family f: p[e][i] point i (0..2 the first triangle, 3..5 the second) at t = e; *delta
 * the separation asked; returns 1 where the triangles do touch (within delta) during the step, so
 * that no proof may hold them apart. */
static int ap_pair(int f, double p[2][6][3], double *delta)
{
    static const double deltas[4] = {0.0, 1e-3, 0.05, 0x1p-40};
    *delta = deltas[(int)(4 * urand())];
    int touches = 0;
    switch (f) {
    case 0: /* random: apart or not, moving far or little */
    case 5: {
        const double r = 3 * urand(), mv = urand() < 0.5 ? 0.1 : 1.0;
        for (int i = 0; i < 6; ++i)
            for (int c = 0; c < 3; ++c) {
                p[0][i][c] = srand1() + (i >= 3 ? r * srand1() : 0);
                p[1][i][c] = p[0][i][c] + mv * srand1();
            }
        if (f == 5) { /* exact powers of two: huge (products overflow: never proved), tiny (underflow) */
            static const int sc[6] = {-600, -300, -60, 300, 500, 1000};
            const double k = ldexp(1.0, sc[(int)(6 * urand())]);
            for (int e = 0; e < 2; ++e)
                for (int i = 0; i < 6; ++i)
                    for (int c = 0; c < 3; ++c)
                        p[e][i][c] *= k;
            *delta *= k < 1 ? k : 1;
        }
        break;
    }
    case 1: { /* neighbours in a flat sheet across a gap g (0, around the rounding bound, or
                 larger), the sheet moving and turning a little; rotated */
        const double g = urand() < 0.2 ? 0.0 : ldexp(1.0, -(int)(60 * urand())) * (urand() < 0.1 ? -1 : 1);
        const double a[3][2] = {{0, 0}, {1, 0}, {0, 1}};
        const double mv[3] = {srand1(), srand1(), srand1()}, tilt = urand() < 0.5 ? 0 : 0.01 * srand1();
        for (int i = 0; i < 3; ++i)
            for (int e = 0; e < 2; ++e) {
                const double ax = a[i][0], ay = a[i][1];
                const double bx = 1 + g - ax, by = 1 + g - ay; /* the second, across the line x + y = 1 */
                p[e][i][0] = ax + e * mv[0];
                p[e][i][1] = ay + e * mv[1];
                p[e][i][2] = e * (mv[2] + tilt * ax);
                p[e][3 + i][0] = bx + e * mv[0];
                p[e][3 + i][1] = by + e * mv[1];
                p[e][3 + i][2] = e * (mv[2] + tilt * bx);
            }
        touches = g == 0; /* (two points of one at two of the other's) */
        ap_rotate(p);
        if (urand() < 0.3)
            *delta = 0;
        break;
    }
    case 2: { /* one triangle above the other at height h (h - delta about 0 half the time) */
        const double h = ldexp(urand() + 0.5, -(int)(30 * urand()));
        for (int i = 0; i < 3; ++i)
            for (int c = 0; c < 3; ++c)
                p[0][i][c] = c == 2 ? 0 : srand1();
        for (int i = 0; i < 3; ++i)
            for (int c = 0; c < 3; ++c)
                p[0][3 + i][c] = p[0][i][c] + (c == 2 ? h : 0.25 * srand1());
        const double mv[3] = {srand1(), srand1(), srand1()};
        for (int i = 0; i < 6; ++i)
            for (int c = 0; c < 3; ++c)
                p[1][i][c] = p[0][i][c] + mv[c];
        if (urand() < 0.5)
            *delta = h * (1 + ldexp(srand1(), -(int)(50 * urand())));
        ap_rotate(p);
        break;
    }
    case 3: { /* a vertex of each at one place, at t = 0 or at t = 1 (or an edge's point): must not be proved */
        for (int e = 0; e < 2; ++e)
            for (int i = 0; i < 6; ++i)
                for (int c = 0; c < 3; ++c)
                    p[e][i][c] = e == 0 ? srand1() : p[0][i][c] + 0.5 * srand1();
        const int e = urand() < 0.5, i = (int)(3 * urand()), j = 3 + (int)(3 * urand());
        const double w = urand() < 0.5 ? 0.0 : 0.5;
        for (int c = 0; c < 3; ++c) /* point j at vertex i, or at the middle of edge (i, i + 1) */
            p[e][j][c] = (1 - w) * p[e][i][c] + w * p[e][(i + 1) % 3][c];
        touches = w == 0; /* (the middle is rounded: within an ulp of the edge, not on it) */
        break;
    }
    case 4: { /* zero-area triangles: all three points at one place, or on one line */
        for (int e = 0; e < 2; ++e)
            for (int i = 0; i < 6; ++i)
                for (int c = 0; c < 3; ++c)
                    p[e][i][c] = srand1() + (i >= 3 ? 2 * urand() : 0);
        const int t = urand() < 0.5 ? 0 : 3, kind = (int)(3 * urand());
        for (int e = 0; e < 2; ++e)
            for (int c = 0; c < 3; ++c) {
                if (kind == 0)
                    p[e][t + 1][c] = p[e][t + 2][c] = p[e][t][c];
                else if (kind == 1)
                    p[e][t + 2][c] = p[e][t][c] + 2 * (p[e][t + 1][c] - p[e][t][c]);
                else
                    p[e][t + 1][c] = p[e][t][c];
            }
        break;
    }
    default: { /* both translate by one vector (gap constant), offset far from the origin */
        const double off = ldexp(1.0, (int)(40 * urand())), mv[3] = {srand1(), srand1(), srand1()};
        for (int i = 0; i < 6; ++i)
            for (int c = 0; c < 3; ++c) {
                p[0][i][c] = off + srand1() + (i >= 3 && c == 0 ? 2.5 * urand() : 0);
                p[1][i][c] = p[0][i][c] + mv[c];
            }
        break;
    }
    }
    return touches;
}

/* A direction whose dot products overflow proves nothing. Triangle A = (0, 0, 0), (X, -X, 0),
 * (X, -X, e) with X = 2^530, e = 2^-30 has normal (-2^500, -2^500, 0): |n|^2 and the rounding
 * bound (n1 S = 2^1031) are finite, but n.(X, -X, 0) is inf - inf = NaN. B has a vertex at A's
 * (X, -X, 0) and two at x + y = -2^520, far along -n: passing over the NaN points, B's set lay
 * 2^1020 beyond A's and the pair, which touches, was proved apart (the proof, each row's lanes,
 * and a self-CCD whose t = 1 vertices are these: t = 1 coordinates need only be finite). */
static int overflowing_directions(void)
{
    const double X = 0x1p530, Y = 0x1p520, e = 0x1p-30;
    const double v[18] = {0, 0, 0, X, -X, 0, X, -X, e, X, -X, 0, -Y, 0, 0, 0, -Y, 1};
    const double *x[6] = {v, v + 3, v + 6, v + 9, v + 12, v + 15};
    ENSURE(meshccd_tri_apart(x, x, X, 0) == 0);
    const double *y[6] = {v + 9, v + 12, v + 15, v, v + 3, v + 6}; /* B first */
    ENSURE(meshccd_tri_apart(y, y, X, 0) == 0);
    /* from t = 0 (within the meshes' range; B 2^490 along -n, beyond the bound there too) */
    double v0[18] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0, -0x1p490, 0, 0, 0, -0x1p490, 1};
    v0[9] = -0x1p490, v0[10] = -0x1p490;
    const uint32_t t[6] = {0, 1, 2, 3, 4, 5};
    ttd_mesh *m = NULL;
    ENSURE(ttd_mesh_create_d(NULL, v0, 6, t, 2, &m) == TTD_OK);
    ttd_mesh_ccd_result ref;
    ENSURE(brute_self_ccd(v0, v, t, 2, 0, 0, &ref) == 0 && ref.count > 0);
    for (int scalar = 0; scalar < 2; ++scalar) { /* the best row's lanes, the scalar proof */
        ttd_options o = opts(1);
        if (scalar)
            o.isa = TTD_ISA_SCALAR;
        ttd_mesh_ccd_result r;
        ENSURE(ttd_mesh_self_ccd_d(&o, m, v, 0, 0, &r) == TTD_OK);
        /* (not the brute force's list bit for bit: at 2^530 the primitive search also reports a
         * vertex 1 above a face as a conservative hit, which the walk's exact boxes rule out) */
        ENSURE_MSG(r.count > 0 && r.toi == ref.toi, "toi %.17g, brute force %.17g", r.toi, ref.toi);
        ENSURE(well_formed(&r) == 0);
        ttd_mesh_ccd_free(&r);
    }
    free(ref.pairs);
    ttd_mesh_destroy(m);
    for (const isa_row *row = isa_rows; row->name != NULL; ++row) {
        const char *why = "";
        if (!cpu_runs(row->name, &why) || row->d == NULL || row->d->tri_apart == NULL)
            continue;
        for (int swap = 0; swap < 2; ++swap) {
            double w[36 * TTD_NODE_WIDTH], S[TTD_NODE_WIDTH];
            for (int l = 0; l < TTD_NODE_WIDTH; ++l) {
                S[l] = X;
                for (int k = 0; k < 2; ++k)
                    for (int i = 0; i < 6; ++i)
                        for (int c = 0; c < 3; ++c)
                            w[(18 * k + 3 * i + c) * TTD_NODE_WIDTH + l] = (swap ? y : x)[i][c];
            }
            ENSURE_MSG(row->d->tri_apart(1, w, S, 0) == 0, "row %s: a touching pair proved apart", row->name);
            /* the same pair read from vertex arrays (tri_apart_at): vertices 0..5 in lane 0, the
             * other lanes every vertex 0 */
            double w0[18], vm[6];
            uint32_t vi[6 * TTD_NODE_WIDTH] = {0};
            for (int i = 0; i < 6; ++i) {
                vm[i] = X;
                vi[i * TTD_NODE_WIDTH] = (uint32_t)i;
                for (int c = 0; c < 3; ++c)
                    w0[3 * i + c] = (swap ? y : x)[i][c];
            }
            ENSURE_MSG(row->d->tri_apart_at(1, vi, w0, w0, vm, 0) == 0, "row %s: a touching pair proved apart (at)",
                       row->name);
        }
    }
    return 0;
}

static int tri_apart_lanes(void)
{
    enum { N = 6000 };
    static double P[N][2][6][3], D[N];
    static int want[N], touch[N];
    int rows = 0;
    for (int f = 0; f < AP_FAMILIES; ++f) {
        int proved = 0;
        for (int k = 0; k < N; ++k) {
            touch[k] = ap_pair(f, P[k], &D[k]);
            const double *x0[6], *x1[6];
            double S = 0;
            for (int i = 0; i < 6; ++i) {
                x0[i] = P[k][0][i];
                x1[i] = P[k][1][i];
                for (int c = 0; c < 3; ++c)
                    for (int e = 0; e < 2; ++e)
                        S = fabs(P[k][e][i][c]) > S ? fabs(P[k][e][i][c]) : S;
            }
            want[k] = meshccd_tri_apart(x0, x1, S, D[k]) != 0;
            ENSURE_MSG(!(want[k] && touch[k]), "%s pair %d: touching pair proved apart", ap_family[f], k);
            proved += want[k];
        }
        printf("  whole-pair proof, %s: %d of %d pairs proved\n", ap_family[f], proved, N);
        if (f != 3 && f != 4)
            ENSURE_MSG(proved > N / 20 && proved < N - N / 20, "%s: too one-sided a family (%d proved)", ap_family[f], proved);
        rows = 0;
        for (const isa_row *row = isa_rows; row->name != NULL; ++row) {
            const char *why = "";
            if (!cpu_runs(row->name, &why) || row->d == NULL)
                continue;
            ENSURE_MSG(row->d->tri_apart != NULL, "row %s has no tri_apart", row->name);
            ++rows;
            /* groups of 1 to 8 pairs of one delta; the lanes past the group hold another pair */
            for (int k = 0; k < N;) {
                const int most = 1 + (int)(TTD_NODE_WIDTH * urand());
                int count = 1;
                while (count < most && k + count < N && D[k + count] == D[k])
                    ++count;
                double x[36 * TTD_NODE_WIDTH], S[TTD_NODE_WIDTH];
                for (int l = 0; l < TTD_NODE_WIDTH; ++l) {
                    const int q = l < count ? k + l : (int)(N * urand());
                    S[l] = 0;
                    for (int e = 0; e < 2; ++e)
                        for (int i = 0; i < 6; ++i)
                            for (int c = 0; c < 3; ++c) {
                                x[(18 * e + 3 * i + c) * TTD_NODE_WIDTH + l] = P[q][e][i][c];
                                S[l] = fabs(P[q][e][i][c]) > S[l] ? fabs(P[q][e][i][c]) : S[l];
                            }
                }
                const unsigned m = row->d->tri_apart(count, x, S, D[k]);
                ENSURE_MSG((m >> count) == 0, "%s, row %s: bits past the group", ap_family[f], row->name);
                for (int l = 0; l < count; ++l)
                    ENSURE_MSG(((m >> l) & 1u) == (unsigned)want[k + l], "%s, row %s, pair %d (delta %g): lanes %u, scalar %d",
                               ap_family[f], row->name, k + l, D[k], (m >> l) & 1u, want[k + l]);
                /* the same lanes read from vertex arrays (tri_apart_at): the 6 points of each lane
                 * at shuffled places among 6 TTD_NODE_WIDTH vertices, vmag their own magnitude,
                 * so the lanes' S is the largest of the six as above */
                enum { NV = 6 * TTD_NODE_WIDTH };
                double v0[3 * NV], v1[3 * NV], vm[NV];
                uint32_t perm[NV], vi[NV];
                for (int i = 0; i < NV; ++i)
                    perm[i] = (uint32_t)i;
                for (int i = NV - 1; i > 0; --i) {
                    const int r = (int)((i + 1) * urand());
                    const uint32_t t = perm[i];
                    perm[i] = perm[r];
                    perm[r] = t;
                }
                for (int l = 0; l < TTD_NODE_WIDTH; ++l)
                    for (int i = 0; i < 6; ++i) {
                        const uint32_t v = perm[6 * l + i];
                        vi[i * TTD_NODE_WIDTH + l] = v;
                        vm[v] = 0;
                        for (int c = 0; c < 3; ++c) {
                            v0[3 * v + c] = x[(3 * i + c) * TTD_NODE_WIDTH + l];
                            v1[3 * v + c] = x[(18 + 3 * i + c) * TTD_NODE_WIDTH + l];
                            vm[v] = fabs(v0[3 * v + c]) > vm[v] ? fabs(v0[3 * v + c]) : vm[v];
                            vm[v] = fabs(v1[3 * v + c]) > vm[v] ? fabs(v1[3 * v + c]) : vm[v];
                        }
                    }
                ENSURE_MSG(row->d->tri_apart_at != NULL, "row %s has no tri_apart_at", row->name);
                const unsigned ma = row->d->tri_apart_at(count, vi, v0, v1, vm, D[k]);
                ENSURE_MSG(ma == m, "%s, row %s, pairs %d..%d (delta %g): read from the vertices %#x, copied in %#x",
                           ap_family[f], row->name, k, k + count - 1, D[k], ma, m);
                k += count;
            }
        }
    }
    ENSURE(rows >= 2); /* cuda-host and at least one SIMD row */
    return 0;
}

/* Every row's leaf_screen against the comparisons it stands for (core/kernels.h), on boxes whose
 * bounds come from a few values (so that boxes touch and coincide often), with NaN bounds now and
 * then (never near: a comparison with NaN is false), and 1 to 8 rows. */
static int leaf_screen_lanes(void)
{
    static const double vals[] = {-1.5, -1, -0.25, 0, 0x1p-1074, 0.25, 1, 1.5, NAN};
    int rows = 0;
    for (const isa_row *row = isa_rows; row->name != NULL; ++row) {
        const char *why = "";
        if (!cpu_runs(row->name, &why) || row->d == NULL)
            continue;
        ENSURE_MSG(row->d->leaf_screen != NULL, "row %s has no leaf_screen", row->name);
        ++rows;
        long near = 0;
        for (int it = 0; it < 4000; ++it) {
            double A[6][TTD_NODE_WIDTH], B[6][TTD_NODE_WIDTH];
            for (int c = 0; c < 6; ++c)
                for (int l = 0; l < TTD_NODE_WIDTH; ++l) {
                    const int nan = urand() < 0.01;
                    const int ia = (int)(8 * urand()), ib = (int)(8 * urand());
                    A[c][l] = nan ? (double)NAN : vals[ia] + (c >= 3 ? 0.5 * (double)(it % 3) : 0);
                    B[c][l] = urand() < 0.01 ? (double)NAN : vals[ib] + (c >= 3 ? 0.5 * (double)((it / 3) % 3) : 0);
                }
            const int na = 1 + it % TTD_NODE_WIDTH;
            const double *const ra[6] = {A[0], A[1], A[2], A[3], A[4], A[5]};
            const double *const rb[6] = {B[0], B[1], B[2], B[3], B[4], B[5]};
            uint8_t out[TTD_NODE_WIDTH];
            const unsigned got = row->d->leaf_screen(ra, na, rb, out);
            unsigned want_rows = 0;
            for (int i = 0; i < na; ++i) {
                unsigned want = 0;
                for (int j = 0; j < TTD_NODE_WIDTH; ++j) {
                    int ok = 1;
                    for (int c = 0; c < 3; ++c)
                        ok &= B[c][j] <= A[3 + c][i] && A[c][i] <= B[3 + c][j];
                    want |= (unsigned)ok << j;
                }
                near += __builtin_popcount(want);
                want_rows |= (unsigned)(want != 0) << i;
                ENSURE_MSG(out[i] == want, "row %s, case %d, row %d: lanes %#x, loop %#x", row->name, it, i,
                           (unsigned)out[i], want);
            }
            ENSURE_MSG(got == want_rows, "row %s, case %d: rows %#x, loop %#x", row->name, it, got, want_rows);
        }
        ENSURE_MSG(near > 1000, "row %s: too few near boxes (%ld)", row->name, near);
    }
    ENSURE(rows >= 2); /* cuda-host and at least one SIMD row */
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(checks);
    RUN_TEST(random_meshes);
    RUN_TEST(sheets_through);
    RUN_TEST(folding_sheet);
    RUN_TEST(random_self);
    RUN_TEST(touching_ends);
    RUN_TEST(self_boxes_touch);
    RUN_TEST(repeated_indices);
    RUN_TEST(float_matches_double);
    RUN_TEST(threads);
    RUN_TEST(overflowing_directions);
    RUN_TEST(tri_apart_lanes); /* after the others: its draws leave their cases as they were */
    RUN_TEST(leaf_screen_lanes);
    TEST_MAIN_END();
}
