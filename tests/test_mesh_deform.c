/* SPDX-License-Identifier: MIT */
/* Deforming meshes (ttd_mesh_set_vertices_d/f): after a refit, every query equals the brute force
 * over all triangle pairs of the moved vertices (tests/mesh_brute.h), as it does for a mesh built
 * from them. The deformations: bends and twists of a grid, a torus and an icosphere, jitter of
 * 1e-3 .. 1e-12 of the size, scaling to 1e-6 and 1e6 with offsets, collapse onto a plane (every
 * triangle coplanar) and onto a line (no area: the axes' fallback), every vertex onto one point,
 * degenerate and duplicate-vertex meshes moved, and sequences of many small steps; both
 * precisions. Also checked:
 *   - a refit to the same vertices gives the build's triangle boxes bit for bit, and a refit
 *     gives the same tree on 1, 2 and 9 threads (so the same answers);
 *   - a scramble (vertex positions permuted) rebuilds the tree (ttd_mesh_get_refit_info), a small
 *     step does not; both answer exactly;
 *   - every query after a refit is identical on every instruction set and thread count;
 *   - bad input (NULL, NaN, coordinates beyond the range, the other precision, bad options) gets
 *     its status and leaves the mesh as it was;
 *   - refits at 1e30, 1e-30 and mixed scales, of one triangle and of degenerate ones, twice in a
 *     row, and a refit on a rebuilt tree: each as a fresh build (distance, contacts,
 *     self-contacts) and the brute force;
 *   - the refit's scratch kept with the mesh (through refused refits and a rebuild): the same
 *     nodes and measure as without them, the measure the nodes' own;
 *   - solid queries see moved vertices (a sphere moved inside another is contained, and out);
 *   - scenes of deforming bodies: a scene's contacts, step after step of meshes moved (one of
 *     them shared by two bodies), against the brute force over every body pair in the world;
 *     ids kept; a mesh moved out of range under its body's pose refused by the query. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh/mesh.h"
#include "mesh_brute.h"
#include "meshes.h"
#include "test_macros.h"
#include "ttd/ttd.h"

static uint64_t rng = 1;

static double urand(void)
{
    rng = rng * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(rng >> 11) * 0x1p-53;
}

/* ---- deformations --------------------------------------------------------------------- */

enum { DEF_BEND, DEF_TWIST, DEF_JITTER, DEF_SCALE_TINY, DEF_SCALE_HUGE, DEF_PLANE, DEF_LINE, DEF_POINT,
       DEF_SCRAMBLE, DEF_COUNT };
static const char *def_names[DEF_COUNT] = {"bend", "twist", "jitter", "scaled 1e-6", "scaled 1e6 + offset",
                                           "collapsed onto a plane", "collapsed onto a line", "one point",
                                           "scrambled"};

/* m's vertices, deformed by family `def` with strength t in [0, 1], into out (3 nv doubles). */
static void deform(const ttd_gen_mesh *m, int def, double t, double *out)
{
    double lo[3], hi[3];
    ttd_gen_mesh_bounds(m, lo, hi);
    const double size = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
    for (size_t i = 0; i < m->nv; ++i) {
        const double *x = m->verts + 3 * i;
        double *y = out + 3 * i;
        const double u = (x[0] - lo[0]) / (size > 0 ? size : 1);
        switch (def) {
        case DEF_BEND: { /* the x axis bent round a circle: the far end folds back over the near one */
            const double a = 3.0 * t * u, r = size / (3.0 * t + 1e-9);
            y[0] = lo[0] + r * sin(a) + x[2] * sin(a);
            y[1] = x[1];
            y[2] = r * (1 - cos(a)) + x[2] * cos(a);
            break;
        }
        case DEF_TWIST: {
            const double a = 2.5 * t * u;
            y[0] = x[0];
            y[1] = x[1] * cos(a) - x[2] * sin(a);
            y[2] = x[1] * sin(a) + x[2] * cos(a);
            break;
        }
        case DEF_JITTER: {
            const double amp = size * pow(10.0, -3.0 - 9.0 * t);
            for (int c = 0; c < 3; ++c)
                y[c] = x[c] + amp * (urand() - 0.5);
            break;
        }
        case DEF_SCALE_TINY:
            for (int c = 0; c < 3; ++c)
                y[c] = x[c] * 1e-6 * (1 + t);
            break;
        case DEF_SCALE_HUGE:
            for (int c = 0; c < 3; ++c)
                y[c] = x[c] * 1e6 * (1 + t) + (c == 0 ? 3e7 : -1e7);
            break;
        case DEF_PLANE:
            y[0] = x[0];
            y[1] = x[1] + x[2];
            y[2] = 0.25 * size;
            break;
        case DEF_LINE:
            for (int c = 0; c < 3; ++c)
                y[c] = (x[0] + x[1] + x[2]) * (c + 1);
            break;
        case DEF_POINT:
            for (int c = 0; c < 3; ++c)
                y[c] = 0.5 + c;
            break;
        default: /* DEF_SCRAMBLE: positions permuted (filled below) */
            break;
        }
    }
    if (def == DEF_SCRAMBLE) {
        memcpy(out, m->verts, 3 * m->nv * sizeof *out);
        for (size_t i = m->nv; i > 1; --i) {
            const size_t j = (size_t)(urand() * (double)i);
            for (int c = 0; c < 3; ++c) {
                const double s = out[3 * (i - 1) + (size_t)c];
                out[3 * (i - 1) + (size_t)c] = out[3 * j + (size_t)c];
                out[3 * j + (size_t)c] = s;
            }
        }
    }
}

/* ---- every query against the brute force -------------------------------------------------- */

static int contact_cmp_d(const void *x, const void *y)
{
    const ttd_contact_d *a = x, *b = y;
    if (a->tri_a != b->tri_a)
        return a->tri_a < b->tri_a ? -1 : 1;
    return a->tri_b < b->tri_b ? -1 : (a->tri_b > b->tri_b);
}

static int contact_cmp_f(const void *x, const void *y)
{
    const ttd_contact_f *a = x, *b = y;
    if (a->tri_a != b->tri_a)
        return a->tri_a < b->tri_a ? -1 : 1;
    return a->tri_b < b->tri_b ? -1 : (a->tri_b > b->tri_b);
}

static size_t pairs_checked;

/* Distance, contacts at three margins, collision and the per-triangle closest partners of meshes
 * ma, mb (built, perhaps refitted, from ga, gb's vertices) under pose, against the brute force. */
static int check_d(const char *what, const ttd_gen_mesh *ga, const ttd_gen_mesh *gb, const ttd_mesh *ma,
                   const ttd_mesh *mb, const double pose[12])
{
    ttd_result_d *all = brute_d(ga, gb, pose);
    const size_t n = ga->nt * gb->nt;
    double best = HUGE_VAL, far = 0;
    for (size_t i = 0; i < n; ++i) {
        best = fmin(best, all[i].distance);
        far = fmax(far, all[i].distance);
    }
    ttd_mesh_result_d r;
    ENSURE(ttd_mesh_distance_d(NULL, ma, mb, 1, pose, HUGE_VAL, 0, &r) == TTD_OK);
    ENSURE_MSG(r.distance == best, "%s: distance %.17g, brute force %.17g", what, r.distance, best);
    ENSURE(all[(size_t)r.tri_a * gb->nt + r.tri_b].distance == best);
    const double margins[3] = {best, best + 0.05 * (far - best), best + 0.3 * (far - best)};
    ttd_contacts_d set = {0};
    ttd_closest_d *ca = malloc(ga->nt * sizeof *ca);
    ENSURE(ca != NULL);
    for (int mi = 0; mi < 3; ++mi) {
        const double margin = margins[mi];
        ENSURE(ttd_mesh_contacts_d(NULL, ma, mb, 1, pose, margin, &set) == TTD_OK);
        if (set.count > 1)
            qsort(set.pairs, set.count, sizeof *set.pairs, contact_cmp_d);
        size_t k = 0;
        for (size_t i = 0; i < n; ++i) {
            if (!(all[i].distance <= margin))
                continue;
            ENSURE_MSG(k < set.count && set.pairs[k].tri_a == i / gb->nt && set.pairs[k].tri_b == i % gb->nt,
                       "%s margin %.17g: pair (%zu, %zu) at %.17g missing", what, margin, i / gb->nt, i % gb->nt,
                       all[i].distance);
            ENSURE(set.pairs[k].distance == all[i].distance && set.pairs[k].p[0] == all[i].p[0] &&
                   set.pairs[k].p[2] == all[i].p[2]);
            ++k;
        }
        ENSURE_MSG(k == set.count, "%s margin %.17g: %zu pairs, brute force %zu", what, margin, set.count, k);
        pairs_checked += k;
        ttd_collision col;
        ENSURE(ttd_mesh_collide_d(NULL, ma, mb, 1, pose, margin, &col) == TTD_OK);
        ENSURE(col.hit == 1 && all[(size_t)col.tri_a * gb->nt + col.tri_b].distance <= margin);
        ENSURE(ttd_mesh_collide_d(NULL, ma, mb, 1, pose, nextafter(best, 0) > 0 ? nextafter(best, 0) : 0, &col) ==
               TTD_OK);
        ENSURE(col.hit == (best == 0));
        ENSURE(ttd_mesh_closest_d(NULL, ma, mb, 1, pose, margin, ca, NULL) == TTD_OK);
        for (size_t i = 0; i < ga->nt; ++i) {
            double d = HUGE_VAL;
            for (size_t j = 0; j < gb->nt; ++j)
                d = all[i * gb->nt + j].distance <= margin ? fmin(d, all[i * gb->nt + j].distance) : d;
            ENSURE(ca[i].distance == d);
        }
    }
    free(ca);
    ttd_contacts_free_d(&set);
    free(all);
    return 0;
}

/* The same in float, from float vertices. */
static int check_f(const char *what, const mesh_f *fa, const mesh_f *fb, const ttd_mesh *ma, const ttd_mesh *mb,
                   const float pose[12])
{
    ttd_result_f *all = brute_f(fa, fb, pose);
    const size_t n = fa->nt * fb->nt;
    float best = INFINITY, far = 0;
    for (size_t i = 0; i < n; ++i) {
        best = fminf(best, all[i].distance);
        far = fmaxf(far, all[i].distance);
    }
    ttd_mesh_result_f r;
    ENSURE(ttd_mesh_distance_f(NULL, ma, mb, 1, pose, INFINITY, 0, &r) == TTD_OK);
    ENSURE_MSG(r.distance == best, "%s (float): distance %.9g, brute force %.9g", what, (double)r.distance,
               (double)best);
    const float margin = best + 0.1f * (far - best);
    ttd_contacts_f set = {0};
    ENSURE(ttd_mesh_contacts_f(NULL, ma, mb, 1, pose, margin, &set) == TTD_OK);
    if (set.count > 1)
        qsort(set.pairs, set.count, sizeof *set.pairs, contact_cmp_f);
    size_t k = 0;
    for (size_t i = 0; i < n; ++i) {
        if (!(all[i].distance <= margin))
            continue;
        ENSURE_MSG(k < set.count && set.pairs[k].tri_a == i / fb->nt && set.pairs[k].tri_b == i % fb->nt,
                   "%s (float): pair (%zu, %zu) missing", what, i / fb->nt, i % fb->nt);
        ENSURE(set.pairs[k].distance == all[i].distance);
        ++k;
    }
    ENSURE_MSG(k == set.count, "%s (float): %zu pairs, brute force %zu", what, set.count, k);
    pairs_checked += k;
    ttd_contacts_free_f(&set);
    free(all);
    return 0;
}

/* ---- tests ------------------------------------------------------------------------------- */

static void load_meshes(ttd_gen_mesh *m)
{
    if (ttd_gen_grid(9, &m[0]) || ttd_gen_torus(1.0, 0.35, 16, 8, &m[1]) || ttd_gen_icosphere(2, &m[2]) ||
        ttd_gen_mesh_degenerate(&m[3]) || ttd_gen_mesh_duplicate_vertices(&m[4]))
        abort();
}
enum { NMESH = 5 };
static const char *mesh_names[NMESH] = {"grid", "torus", "icosphere", "degenerate", "duplicate vertices"};

/* Every deformation of every mesh, refitted, against the brute force: a deformed against its
 * undeformed self under a near pose, and against itself deformed otherwise; both precisions. */
static int refit_queries_match_brute_force(void)
{
    ttd_gen_mesh base[NMESH];
    load_meshes(base);
    int cases = 0;
    for (int mi = 0; mi < NMESH; ++mi)
        for (int def = 0; def < DEF_COUNT; ++def)
            for (int step = 0; step < 2; ++step) {
                rng = (uint64_t)(100 * mi + 10 * def + step + 1);
                const double t = step == 0 ? 0.35 : 1.0;
                ttd_gen_mesh ga, gb;
                ENSURE(ttd_gen_mesh_copy(&base[mi], &ga) == 0 && ttd_gen_mesh_copy(&base[(mi + 1) % NMESH], &gb) == 0);
                ttd_mesh *ma, *mb;
                ENSURE(ttd_mesh_create_d(NULL, ga.verts, ga.nv, ga.tris, ga.nt, &ma) == TTD_OK);
                ENSURE(ttd_mesh_create_d(NULL, gb.verts, gb.nv, gb.tris, gb.nt, &mb) == TTD_OK);
                deform(&base[mi], def, t, ga.verts);
                deform(&base[(mi + 1) % NMESH], (def + 3) % DEF_COUNT, 1 - t, gb.verts);
                ENSURE(ttd_mesh_set_vertices_d(NULL, ma, ga.verts) == TTD_OK);
                ENSURE(ttd_mesh_set_vertices_d(NULL, mb, gb.verts) == TTD_OK);
                double lo[3], hi[3], pose[12];
                ttd_gen_mesh_bounds(&ga, lo, hi);
                const double size = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
                ttd_gen_pose(31, (uint64_t)(mi * DEF_COUNT + def), 0.3 * size, pose);
                for (int c = 0; c < 3; ++c) /* b near a's middle */
                    pose[4 * c + 3] += 0.5 * (lo[c] + hi[c]);
                char what[160];
                snprintf(what, sizeof what, "%s %s (t %.2f) vs %s", mesh_names[mi], def_names[def], t,
                         mesh_names[(mi + 1) % NMESH]);
                if (check_d(what, &ga, &gb, ma, mb, pose))
                    return 1;
                if (check_d(what, &ga, &ga, ma, ma, pose)) /* the deformed mesh against itself */
                    return 1;
                ttd_mesh_destroy(ma);
                ttd_mesh_destroy(mb);
                /* float: built from the undeformed vertices, refitted to the deformed ones */
                mesh_f fa0 = to_float(&base[mi]), fb0 = to_float(&base[(mi + 1) % NMESH]);
                mesh_f fa = to_float(&ga), fb = to_float(&gb);
                ENSURE(ttd_mesh_create_f(NULL, fa0.verts, fa0.nv, fa0.tris, fa0.nt, &ma) == TTD_OK);
                ENSURE(ttd_mesh_create_f(NULL, fb0.verts, fb0.nv, fb0.tris, fb0.nt, &mb) == TTD_OK);
                ENSURE(ttd_mesh_set_vertices_f(NULL, ma, fa.verts) == TTD_OK);
                ENSURE(ttd_mesh_set_vertices_f(NULL, mb, fb.verts) == TTD_OK);
                float posef[12];
                for (int k = 0; k < 12; ++k)
                    posef[k] = (float)pose[k];
                if (def != DEF_SCALE_HUGE && check_f(what, &fa, &fb, ma, mb, posef))
                    return 1;
                ttd_mesh_destroy(ma);
                ttd_mesh_destroy(mb);
                free(fa0.verts);
                free(fb0.verts);
                free(fa.verts);
                free(fb.verts);
                ttd_gen_mesh_free(&ga);
                ttd_gen_mesh_free(&gb);
                ++cases;
            }
    for (int mi = 0; mi < NMESH; ++mi)
        ttd_gen_mesh_free(&base[mi]);
    printf("  %d deformed mesh pairs, %zu pairs within margins checked\n", cases, pairs_checked);
    return 0;
}

/* Sixty small steps of a bend and a twist, refitted each step (no rebuild), against the brute
 * force every fifth step and against a fresh build every step (the same distances and sets). */
static int refit_sequences_match_brute_force(void)
{
    ttd_gen_mesh g, moved;
    ENSURE(ttd_gen_grid(12, &g) == 0 && ttd_gen_mesh_copy(&g, &moved) == 0);
    ttd_mesh *m;
    ENSURE(ttd_mesh_create_d(NULL, g.verts, g.nv, g.tris, g.nt, &m) == TTD_OK);
    const double pose[12] = {1, 0, 0, 0.02, 0, 1, 0, 0.01, 0, 0, 1, 0.005};
    ttd_contacts_d s1 = {0}, s2 = {0};
    for (int step = 1; step <= 60; ++step) {
        deform(&g, step % 2 ? DEF_BEND : DEF_TWIST, step / 60.0, moved.verts);
        ENSURE(ttd_mesh_set_vertices_d(NULL, m, moved.verts) == TTD_OK);
        ttd_mesh *fresh;
        ENSURE(ttd_mesh_create_d(NULL, moved.verts, moved.nv, moved.tris, moved.nt, &fresh) == TTD_OK);
        ttd_mesh_result_d r1, r2;
        ENSURE(ttd_mesh_distance_d(NULL, m, m, 1, pose, HUGE_VAL, 0, &r1) == TTD_OK);
        ENSURE(ttd_mesh_distance_d(NULL, fresh, fresh, 1, pose, HUGE_VAL, 0, &r2) == TTD_OK);
        ENSURE(r1.distance == r2.distance);
        ENSURE(ttd_mesh_contacts_d(NULL, m, fresh, 1, pose, 0.05, &s1) == TTD_OK);
        ENSURE(ttd_mesh_contacts_d(NULL, fresh, fresh, 1, pose, 0.05, &s2) == TTD_OK);
        ENSURE(s1.count == s2.count);
        if (s1.count > 1) {
            qsort(s1.pairs, s1.count, sizeof *s1.pairs, contact_cmp_d);
            qsort(s2.pairs, s2.count, sizeof *s2.pairs, contact_cmp_d);
        }
        ENSURE(s1.count == 0 || memcmp(s1.pairs, s2.pairs, s1.count * sizeof *s1.pairs) == 0);
        if (step % 5 == 0 && check_d("grid bend/twist sequence", &moved, &moved, m, m, pose))
            return 1;
        ttd_mesh_destroy(fresh);
    }
    ttd_mesh_refit_info info;
    ENSURE(ttd_mesh_get_refit_info(m, &info) == TTD_OK);
    ENSURE(info.generation == 60);
    printf("  60 steps; %llu rebuilds, measure %.3g (built %.3g)\n", (unsigned long long)info.rebuilds, info.quality,
           info.quality_built);
    ttd_contacts_free_d(&s1);
    ttd_contacts_free_d(&s2);
    ttd_mesh_destroy(m);
    ttd_gen_mesh_free(&g);
    ttd_gen_mesh_free(&moved);
    return 0;
}

static size_t node_bytes(const ttd_mesh *m)
{
    return m->nnodes * (m->bytes == 8 ? sizeof(ttd_node_d) : sizeof(ttd_node_f));
}

/* Whether node n of two meshes' node arrays (x, y, of the same precision) holds the same boxes
 * and children, bit for bit (its padding is never written, so not memcmp). */
#define NODE_EQUAL(x, y)                                                                           \
    ((x)->count == (y)->count && memcmp((x)->child, (y)->child, sizeof (x)->child) == 0 &&         \
     memcmp((x)->c, (y)->c, sizeof (x)->c) == 0 && memcmp((x)->u, (y)->u, sizeof (x)->u) == 0 &&  \
     memcmp((x)->e, (y)->e, sizeof (x)->e) == 0)

static int node_equal(int bytes, const void *xs, const void *ys, size_t n)
{
    if (bytes == 8)
        return NODE_EQUAL((const ttd_node_d *)xs + n, (const ttd_node_d *)ys + n);
    return NODE_EQUAL((const ttd_node_f *)xs + n, (const ttd_node_f *)ys + n);
}

static int nodes_equal(const ttd_mesh *a, const ttd_mesh *b)
{
    for (size_t n = 0; n < a->nnodes; ++n)
        if (!node_equal(a->bytes, a->nodes, b->nodes, n))
            return 0;
    return a->nnodes == b->nnodes;
}

/* A refit to the build's own vertices gives the build's triangle boxes bit for bit; a refit's
 * tree is the same on 1, 2 and 9 threads, in both precisions. */
static int refit_bits(void)
{
    ttd_gen_mesh g, moved;
    ENSURE(ttd_gen_torus(1.0, 0.3, 60, 30, &g) == 0 && ttd_gen_mesh_copy(&g, &moved) == 0);
    deform(&g, DEF_TWIST, 0.2, moved.verts);
    for (int prec = 0; prec < 2; ++prec) {
        mesh_f f = to_float(&g), fm = to_float(&moved);
        ttd_mesh *m[3];
        const int threads[3] = {1, 2, 9};
        for (int k = 0; k < 3; ++k) {
            ttd_options o = ttd_default_options();
            o.threads = threads[k];
            ENSURE((prec == 0 ? ttd_mesh_create_d(&o, g.verts, g.nv, g.tris, g.nt, &m[k])
                              : ttd_mesh_create_f(&o, f.verts, f.nv, f.tris, f.nt, &m[k])) == TTD_OK);
        }
        /* the same vertices: triangles as built */
        void *built = malloc(node_bytes(m[0]));
        ENSURE(built != NULL);
        memcpy(built, m[0]->nodes, node_bytes(m[0]));
        for (int k = 0; k < 3; ++k)
            ENSURE((prec == 0 ? ttd_mesh_set_vertices_d(NULL, m[k], g.verts)
                              : ttd_mesh_set_vertices_f(NULL, m[k], f.verts)) == TTD_OK);
        size_t leaves = 0;
        for (size_t n = 1; n < m[0]->nnodes; ++n) {
            const int32_t c0 = prec == 0 ? ((const ttd_node_d *)built)[n].child[0] : ((const ttd_node_f *)built)[n].child[0];
            if (c0 < 0) { /* a leaf: its triangles' boxes */
                ENSURE(node_equal(m[0]->bytes, built, m[0]->nodes, n));
                ++leaves;
            }
        }
        ENSURE(leaves > 100);
        free(built);
        /* a deformation: the same tree on every thread count (the same history: a refit starts
         * each box's axes from the last ones) */
        for (int k = 0; k < 3; ++k) {
            ttd_options o = ttd_default_options();
            o.threads = threads[k];
            ENSURE((prec == 0 ? ttd_mesh_set_vertices_d(&o, m[k], moved.verts)
                              : ttd_mesh_set_vertices_f(&o, m[k], fm.verts)) == TTD_OK);
            if (k > 0)
                ENSURE(nodes_equal(m[k], m[0]));
        }
        for (int k = 0; k < 3; ++k)
            ttd_mesh_destroy(m[k]);
        free(f.verts);
        free(fm.verts);
    }
    ttd_gen_mesh_free(&g);
    ttd_gen_mesh_free(&moved);
    return 0;
}

/* A soup of the icosphere of that level: each triangle its own three vertices, in the
 * icosphere's order; 0, or -1 (nothing to free). */
static int icosphere_soup(int level, ttd_gen_mesh *soup)
{
    ttd_gen_mesh ico;
    if (ttd_gen_icosphere(level, &ico) != 0)
        return -1;
    soup->nt = ico.nt;
    soup->nv = 3 * ico.nt;
    soup->verts = malloc(3 * soup->nv * sizeof *soup->verts);
    soup->tris = malloc(3 * soup->nt * sizeof *soup->tris);
    if (soup->verts == NULL || soup->tris == NULL) {
        free(soup->verts);
        free(soup->tris);
        ttd_gen_mesh_free(&ico);
        return -1;
    }
    for (size_t t = 0; t < soup->nt; ++t)
        for (int k = 0; k < 3; ++k) {
            soup->tris[3 * t + (size_t)k] = (uint32_t)(3 * t + (size_t)k);
            memcpy(soup->verts + 9 * t + 3 * k, ico.verts + 3 * (size_t)ico.tris[3 * t + (size_t)k],
                   3 * sizeof(double));
        }
    ttd_gen_mesh_free(&ico);
    return 0;
}

/* Moves a soup's nt triangles (9 coordinates each) to one another's places: a shuffle drawn from
 * rng, which leaves every triangle's box as it was but scatters the tree's groups. */
static void scatter_soup(double *verts, size_t nt)
{
    for (size_t t = nt; t > 1; --t) {
        const size_t u = (size_t)(urand() * (double)t);
        double x[9];
        memcpy(x, verts + 9 * (t - 1), sizeof x);
        memcpy(verts + 9 * (t - 1), verts + 9 * u, sizeof x);
        memcpy(verts + 9 * u, x, sizeof x);
    }
}

/* A soup (each triangle its own three vertices) of an icosphere's triangles: triangles moved to
 * one another's places (a permutation) leave every triangle's box as it was but make every group
 * of the tree a scatter, so the measure grows and the tree is rebuilt; moved back, the tree built
 * for the scatter is as poor, and is rebuilt again. Jitter rebuilds nothing. */
static int degraded_trees_rebuild(void)
{
    ttd_gen_mesh g, moved;
    ENSURE(icosphere_soup(3, &g) == 0);
    ENSURE(ttd_gen_mesh_copy(&g, &moved) == 0);
    ttd_mesh *m;
    ENSURE(ttd_mesh_create_d(NULL, g.verts, g.nv, g.tris, g.nt, &m) == TTD_OK);
    ttd_mesh_refit_info info;
    rng = 5;
    deform(&g, DEF_JITTER, 0, moved.verts);
    ENSURE(ttd_mesh_set_vertices_d(NULL, m, moved.verts) == TTD_OK);
    ENSURE(ttd_mesh_get_refit_info(m, &info) == TTD_OK);
    ENSURE_MSG(info.generation == 1 && info.rebuilds == 0 && info.quality <= 2 * info.quality_built,
               "jitter: measure %.4g, built %.4g", info.quality, info.quality_built);
    const double built = info.quality_built;
    scatter_soup(moved.verts, g.nt); /* triangles to one another's places */
    ENSURE(ttd_mesh_set_vertices_d(NULL, m, moved.verts) == TTD_OK);
    ENSURE(ttd_mesh_get_refit_info(m, &info) == TTD_OK);
    ENSURE_MSG(info.generation == 2 && info.rebuilds == 1 && info.quality == info.quality_built,
               "scramble: %llu rebuilds, measure %.4g, built %.4g", (unsigned long long)info.rebuilds, info.quality,
               info.quality_built);
    const double pose[12] = {1, 0, 0, 0.3, 0, 1, 0, 0, 0, 0, 1, 0};
    if (check_d("scattered icosphere soup", &moved, &moved, m, m, pose))
        return 1;
    ENSURE(ttd_mesh_set_vertices_d(NULL, m, g.verts) == TTD_OK);
    ENSURE(ttd_mesh_get_refit_info(m, &info) == TTD_OK);
    ENSURE_MSG(info.rebuilds == 2, "back: measure %.4g, built %.4g", info.quality, info.quality_built);
    if (check_d("icosphere soup", &g, &g, m, m, pose))
        return 1;
    printf("  icosphere soup: measure %.3g as built; scattered: rebuilt (measure %.3g), and back\n", built,
           info.quality_built);
    ttd_mesh_destroy(m);
    ttd_gen_mesh_free(&g);
    ttd_gen_mesh_free(&moved);
    return 0;
}

/* The triangles' boxes of a refit are fitted 8 at a time in lanes on the SIMD rows
 * (simd/kernel_trifit.h) and one by one on the scalar row (mesh/build.c, triangle_fit): every
 * node the same bits on every row, over every deformation family (planes, lines and points
 * included: their triangles take the scalar fallback inside a lane row), in both precisions,
 * along a sequence (each refit starts its boxes' axes from the last ones). */
static int refit_bits_every_isa(void)
{
    ttd_gen_mesh g, moved;
    ENSURE(ttd_gen_torus(1.0, 0.3, 30, 15, &g) == 0 && ttd_gen_mesh_copy(&g, &moved) == 0);
    int rows = 0;
    for (int prec = 0; prec < 2; ++prec)
        for (int isa = 1; isa < TTD_ISA_COUNT; ++isa) {
            if (!ttd_isa_available((ttd_isa)isa))
                continue;
            ttd_options o = ttd_default_options(), os = ttd_default_options();
            o.isa = (ttd_isa)isa;
            os.isa = TTD_ISA_SCALAR;
            mesh_f f = to_float(&g);
            ttd_mesh *m, *ms;
            ENSURE((prec == 0 ? ttd_mesh_create_d(&o, g.verts, g.nv, g.tris, g.nt, &m)
                              : ttd_mesh_create_f(&o, f.verts, f.nv, f.tris, f.nt, &m)) == TTD_OK);
            ENSURE((prec == 0 ? ttd_mesh_create_d(&os, g.verts, g.nv, g.tris, g.nt, &ms)
                              : ttd_mesh_create_f(&os, f.verts, f.nv, f.tris, f.nt, &ms)) == TTD_OK);
            for (int def = 0; def < DEF_COUNT; ++def)
                for (int step = 1; step <= 2; ++step) {
                    rng = (uint64_t)(100 * def + step);
                    deform(&g, def, 0.4 * step, moved.verts);
                    mesh_f fm = to_float(&moved);
                    ENSURE((prec == 0 ? ttd_mesh_set_vertices_d(&o, m, moved.verts)
                                      : ttd_mesh_set_vertices_f(&o, m, fm.verts)) == TTD_OK);
                    ENSURE((prec == 0 ? ttd_mesh_set_vertices_d(&os, ms, moved.verts)
                                      : ttd_mesh_set_vertices_f(&os, ms, fm.verts)) == TTD_OK);
                    ENSURE_MSG(nodes_equal(m, ms), "%s, step %d, %s row, %s", def_names[def], step,
                               ttd_isa_name((ttd_isa)isa), prec == 0 ? "double" : "float");
                    free(fm.verts);
                }
            ttd_mesh_destroy(m);
            ttd_mesh_destroy(ms);
            free(f.verts);
            ++rows;
        }
    printf("  %d rows and precisions: every refitted node the scalar row's bits\n", rows);
    ttd_gen_mesh_free(&g);
    ttd_gen_mesh_free(&moved);
    return 0;
}

/* After a refit, every query gives the same bits on every instruction set and thread count. */
static int refit_threads_isas_identical(void)
{
    ttd_gen_mesh g, moved;
    ENSURE(ttd_gen_torus(1.0, 0.3, 40, 20, &g) == 0 && ttd_gen_mesh_copy(&g, &moved) == 0);
    deform(&g, DEF_BEND, 0.8, moved.verts);
    ttd_mesh *m;
    ENSURE(ttd_mesh_create_d(NULL, g.verts, g.nv, g.tris, g.nt, &m) == TTD_OK);
    ENSURE(ttd_mesh_set_vertices_d(NULL, m, moved.verts) == TTD_OK);
    enum { K = 12 };
    double poses[12 * K];
    for (int i = 0; i < K; ++i)
        ttd_gen_pose(41, (uint64_t)i, 0.5, poses + 12 * i);
    ttd_options o = ttd_default_options();
    o.isa = TTD_ISA_SCALAR;
    o.threads = 1;
    ttd_mesh_result_d ref[K], got[K];
    ttd_contacts_d sref = {0}, sgot = {0};
    ENSURE(ttd_mesh_distance_d(&o, m, m, K, poses, HUGE_VAL, 0, ref) == TTD_OK);
    ENSURE(ttd_mesh_contacts_d(&o, m, m, K, poses, 0.05, &sref) == TTD_OK);
    for (int isa = 1; isa < TTD_ISA_COUNT; ++isa) {
        if (!ttd_isa_available((ttd_isa)isa))
            continue;
        for (int threads = 1; threads <= 2; ++threads) {
            o.isa = (ttd_isa)isa;
            o.threads = threads;
            ENSURE(ttd_mesh_distance_d(&o, m, m, K, poses, HUGE_VAL, 0, got) == TTD_OK);
            ENSURE(memcmp(got, ref, sizeof got) == 0);
            ENSURE(ttd_mesh_contacts_d(&o, m, m, K, poses, 0.05, &sgot) == TTD_OK);
            ENSURE(sgot.count == sref.count && memcmp(sgot.pairs, sref.pairs, sgot.count * sizeof *sgot.pairs) == 0);
        }
    }
    printf("  %zu contacts over %d poses, every row and thread count the same\n", sref.count, K);
    ttd_contacts_free_d(&sref);
    ttd_contacts_free_d(&sgot);
    ttd_mesh_destroy(m);
    ttd_gen_mesh_free(&g);
    ttd_gen_mesh_free(&moved);
    return 0;
}

/* Bad input: its status, and the mesh as it was. */
static int bad_vertices_refused(void)
{
    ttd_gen_mesh g;
    ENSURE(ttd_gen_icosphere(1, &g) == 0);
    ttd_mesh *m, *mf;
    ENSURE(ttd_mesh_create_d(NULL, g.verts, g.nv, g.tris, g.nt, &m) == TTD_OK);
    mesh_f f = to_float(&g);
    ENSURE(ttd_mesh_create_f(NULL, f.verts, f.nv, f.tris, f.nt, &mf) == TTD_OK);
    const double pose[12] = {1, 0, 0, 2.5, 0, 1, 0, 0, 0, 0, 1, 0};
    ttd_mesh_result_d before, after;
    ENSURE(ttd_mesh_distance_d(NULL, m, m, 1, pose, HUGE_VAL, 0, &before) == TTD_OK);
    double *v = malloc(3 * g.nv * sizeof *v);
    ENSURE(v != NULL);
    ENSURE(ttd_mesh_set_vertices_d(NULL, NULL, g.verts) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_mesh_set_vertices_d(NULL, m, NULL) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_mesh_set_vertices_f(NULL, m, f.verts) == TTD_ERR_PRECISION_MISMATCH);
    ENSURE(ttd_mesh_set_vertices_d(NULL, mf, g.verts) == TTD_ERR_PRECISION_MISMATCH);
    ttd_options bad = ttd_default_options();
    bad.method = TTD_METHOD_PENALTY;
    ENSURE(ttd_mesh_set_vertices_d(&bad, m, g.verts) == TTD_ERR_BAD_OPTIONS);
    const double nasty[3] = {(double)NAN, (double)INFINITY, 0x1p509};
    const ttd_status want[3] = {TTD_ERR_NONFINITE_MESH, TTD_ERR_NONFINITE_MESH, TTD_ERR_COORDINATE_RANGE};
    for (int k = 0; k < 3; ++k) {
        memcpy(v, g.verts, 3 * g.nv * sizeof *v);
        v[3 * (g.nv - 1) + 2] = nasty[k];
        ENSURE(ttd_mesh_set_vertices_d(NULL, m, v) == want[k]);
    }
    float *vf = malloc(3 * g.nv * sizeof *vf);
    ENSURE(vf != NULL);
    memcpy(vf, f.verts, 3 * g.nv * sizeof *vf);
    vf[4] = 0x1p61f;
    ENSURE(ttd_mesh_set_vertices_f(NULL, mf, vf) == TTD_ERR_COORDINATE_RANGE);
    ENSURE(ttd_mesh_distance_d(NULL, m, m, 1, pose, HUGE_VAL, 0, &after) == TTD_OK);
    ENSURE(memcmp(&before, &after, sizeof before) == 0);
    ttd_mesh_refit_info info;
    ENSURE(ttd_mesh_get_refit_info(m, &info) == TTD_OK && info.generation == 0);
    ENSURE(ttd_mesh_get_refit_info(NULL, &info) == TTD_ERR_NULL_POINTER && ttd_mesh_get_refit_info(m, NULL) == TTD_ERR_NULL_POINTER);
    free(v);
    free(vf);
    free(f.verts);
    ttd_mesh_destroy(m);
    ttd_mesh_destroy(mf);
    ttd_gen_mesh_free(&g);
    return 0;
}

/* Solid queries (options.solid) on moved meshes: the closed flag stays (the triangles are the
 * same), the containment test sees the new vertices. A small sphere moved inside a large one is
 * contained (distance 0, TTD_MESH_CONTAINED), moved out again it is not, and its surface distance
 * is the brute force's either way. */
static int solids_after_refit(void)
{
    ttd_gen_mesh big, small, moved;
    ENSURE(ttd_gen_icosphere(2, &big) == 0 && ttd_gen_icosphere(1, &small) == 0 && ttd_gen_mesh_copy(&small, &moved) == 0);
    for (size_t v = 0; v < 3 * big.nv; ++v)
        big.verts[v] *= 3;
    ttd_mesh *a, *b;
    ENSURE(ttd_mesh_create_d(NULL, big.verts, big.nv, big.tris, big.nt, &a) == TTD_OK);
    for (size_t v = 0; v < small.nv; ++v) /* built far outside */
        moved.verts[3 * v] = small.verts[3 * v] + 10;
    ENSURE(ttd_mesh_create_d(NULL, moved.verts, moved.nv, moved.tris, moved.nt, &b) == TTD_OK);
    ttd_options solid = ttd_default_options();
    solid.solid = 1;
    const double id[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    ttd_mesh_result_d r;
    ENSURE(ttd_mesh_distance_d(&solid, a, b, 1, id, HUGE_VAL, 0, &r) == TTD_OK && r.flags == 0 && r.distance > 5);
    const double shifts[2] = {0.4, 10};
    for (int k = 0; k < 2; ++k) {
        for (size_t v = 0; v < small.nv; ++v)
            moved.verts[3 * v] = small.verts[3 * v] + shifts[k];
        ENSURE(ttd_mesh_set_vertices_d(NULL, b, moved.verts) == TTD_OK);
        ENSURE(ttd_mesh_distance_d(&solid, a, b, 1, id, HUGE_VAL, 0, &r) == TTD_OK);
        if (k == 0) {
            ENSURE_MSG(r.distance == 0 && r.flags == (TTD_MESH_INTERSECTING | TTD_MESH_CONTAINED),
                       "moved inside: distance %.17g, flags %u", r.distance, (unsigned)r.flags);
        } else {
            ENSURE(r.flags == 0 && r.distance > 5);
        }
        ttd_collision c;
        ENSURE(ttd_mesh_collide_d(&solid, a, b, 1, id, 0, &c) == TTD_OK && c.hit == (k == 0));
        if (check_d(k == 0 ? "small sphere moved inside" : "moved out again", &big, &moved, a, b, id))
            return 1;
    }
    ttd_mesh_destroy(a);
    ttd_mesh_destroy(b);
    ttd_gen_mesh_free(&big);
    ttd_gen_mesh_free(&small);
    ttd_gen_mesh_free(&moved);
    return 0;
}

/* ---- data derived from the vertices: edge information and the point queries' data ---------- */

/* What a refit must recompute beside the tree (src/mesh/build.c, refit_derived): the edge
 * information the scene's contact normals read (mesh/edges.c) and the point queries' data
 * (src/points/, made on a mesh's first point query). A scene's manifold is a function of the
 * contact set (tree-independent) and of the edge information, so with refitted meshes it must
 * equal, bit for bit, the manifold with meshes freshly built from the same vertices; a closest
 * point is the brute force's, so it must equal the fresh mesh's too; and the winding number of a
 * point moved with the mesh must follow it (stale moments would leave it where the mesh was). */
static int derived_data_after_refit(void)
{
    ttd_gen_mesh torus, now;
    ENSURE(ttd_gen_torus(0.5, 0.2, 24, 12, &torus) == 0 && ttd_gen_mesh_copy(&torus, &now) == 0);
    ttd_mesh *m;
    ENSURE(ttd_mesh_create_d(NULL, torus.verts, torus.nv, torus.tris, torus.nt, &m) == TTD_OK);
    /* the point data made before the refit */
    const double centre_tube[3] = {0.5, 0, 0};
    double w;
    ENSURE(ttd_points_winding_number_d(NULL, m, 1, centre_tube, NULL, &w) == TTD_OK);
    ENSURE_MSG(fabs(w - 1) < 0.05, "the tube's centre: winding number %.17g", w);
    size_t manifolds = 0, points = 0;
    for (int def = DEF_BEND; def <= DEF_JITTER; ++def)
        for (int step = 1; step <= 3; ++step) {
            const double t = step / 3.0, shift = 2.0 * step;
            deform(&torus, def, t, now.verts);
            for (size_t v = 0; v < now.nv; ++v)
                now.verts[3 * v + 1] += shift; /* moved away from where it was */
            ENSURE(ttd_mesh_set_vertices_d(NULL, m, now.verts) == TTD_OK);
            ttd_mesh *fresh;
            ENSURE(ttd_mesh_create_d(NULL, now.verts, now.nv, now.tris, now.nt, &fresh) == TTD_OK);
            /* manifolds: two bodies of the refitted mesh against the same with fresh meshes */
            const double pa[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
            const double pb[12] = {1, 0, 0, 0.05, 0, 1, 0, 0.02, 0, 0, 1, 0.15}; /* the copy moved a little: crossing */
            ttd_scene_array ar = {0}, af = {0};
            for (int k = 0; k < 2; ++k) {
                ttd_scene *s;
                uint32_t id;
                ttd_mesh *use = k ? fresh : m;
                ENSURE(ttd_scene_create_d(&s) == TTD_OK);
                ENSURE(ttd_scene_add_d(s, use, pa, &id) == TTD_OK && ttd_scene_add_d(s, use, pb, &id) == TTD_OK);
                ENSURE(ttd_scene_manifold_d(NULL, s, 0.05, 0, k ? &af : &ar) == TTD_OK);
                ttd_scene_destroy(s);
            }
            ENSURE_MSG(ar.count > 0, "%s, t %g: no manifold point (fresh: %zu)", def_names[def], t, af.count);
            ENSURE_MSG(ar.count == af.count && memcmp(ar.data, af.data, ar.count * sizeof(ttd_scene_point_d)) == 0,
                       "%s, t %g: the refitted mesh's manifold (%zu points) differs from a fresh mesh's (%zu)",
                       def_names[def], t, ar.count, af.count);
            manifolds++;
            ttd_scene_array_free(&ar);
            ttd_scene_array_free(&af);
            /* closest points: the fresh mesh's, bit for bit; the winding number follows the mesh */
            enum { NP = 64 };
            double P[3 * NP];
            for (size_t i = 0; i < 3 * NP; ++i)
                P[i] = 1.6 * (urand() - 0.5) + (i % 3 == 1 ? shift : 0);
            ttd_point_result_d rr[NP], rf[NP];
            ENSURE(ttd_points_closest_d(NULL, m, NP, P, NULL, INFINITY, rr) == TTD_OK);
            ENSURE(ttd_points_closest_d(NULL, fresh, NP, P, NULL, INFINITY, rf) == TTD_OK);
            for (size_t i = 0; i < NP; ++i)
                ENSURE_MSG(rr[i].distance == rf[i].distance && rr[i].triangle == rf[i].triangle &&
                               memcmp(rr[i].point, rf[i].point, sizeof rr[i].point) == 0,
                           "%s, t %g: point %zu: refitted %.17g (triangle %u), fresh %.17g (triangle %u)", def_names[def],
                           t, i, rr[i].distance, rr[i].triangle, rf[i].distance, rf[i].triangle);
            double wr[NP], wf[NP];
            ENSURE(ttd_points_winding_number_d(NULL, m, NP, P, NULL, wr) == TTD_OK);
            ENSURE(ttd_points_winding_number_d(NULL, fresh, NP, P, NULL, wf) == TTD_OK);
            for (size_t i = 0; i < NP; ++i)
                ENSURE_MSG(fabs(wr[i] - wf[i]) < 0.05 || rf[i].distance < 1e-2,
                           "%s, t %g: point %zu (at %.3g from the surface): winding %.6g refitted, %.6g fresh",
                           def_names[def], t, i, rf[i].distance, wr[i], wf[i]);
            points += NP;
            ttd_mesh_destroy(fresh);
        }
    ttd_mesh_destroy(m);
    ttd_gen_mesh_free(&torus);
    ttd_gen_mesh_free(&now);
    printf("  %zu refits: manifolds equal to fresh meshes' bit for bit; %zu points' closest points equal, winding "
           "numbers within 0.05 (both the far field's approximations)\n",
           manifolds, points);
    return 0;
}

/* ---- scenes of deforming bodies ---------------------------------------------------------------- */

/* Body b's triangle t in the world: its mesh's vertices (verts) moved by its pose, as the header
 * documents ((r0 x + r1 y) + r2 z) + t. */
static void world_tri(const double *verts, const uint32_t *tris, size_t t, const double pose[12], double out[9])
{
    for (int k = 0; k < 3; ++k)
        pose_apply_d(pose, verts + 3 * (size_t)tris[3 * t + (size_t)k], out + 3 * k);
}

typedef struct dbody {
    const ttd_gen_mesh *g; /* its mesh's current vertices */
    double pose[12];
} dbody;

/* The scene's contacts at margin against every triangle pair of every body pair in the world. */
static int check_scene(const char *what, ttd_scene *scene, const dbody *bodies, int n, double margin)
{
    ttd_scene_array arr = {0};
    ENSURE(ttd_scene_contacts_d(NULL, scene, margin, &arr) == TTD_OK);
    const ttd_scene_contact_d *got = arr.data;
    size_t k = 0;
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j) {
            const dbody *a = &bodies[i], *b = &bodies[j];
            const size_t np = a->g->nt * b->g->nt;
            double *s = malloc(9 * np * sizeof *s), *t = malloc(9 * np * sizeof *t);
            ttd_result_d *r = malloc(np * sizeof *r);
            ENSURE(s && t && r);
            for (size_t x = 0; x < a->g->nt; ++x)
                for (size_t y = 0; y < b->g->nt; ++y) {
                    world_tri(a->g->verts, a->g->tris, x, a->pose, s + 9 * (x * b->g->nt + y));
                    world_tri(b->g->verts, b->g->tris, y, b->pose, t + 9 * (x * b->g->nt + y));
                }
            ENSURE(ttd_batch_d(NULL, np, s, t, NULL, r) == TTD_OK);
            for (size_t e = 0; e < np; ++e) {
                if (!(r[e].distance <= margin))
                    continue;
                ENSURE_MSG(k < arr.count && got[k].i == (uint32_t)i && got[k].j == (uint32_t)j &&
                               got[k].tri_i == e / b->g->nt && got[k].tri_j == e % b->g->nt,
                           "%s: bodies (%d, %d), triangles (%zu, %zu) at %.17g missing", what, i, j, e / b->g->nt,
                           e % b->g->nt, r[e].distance);
                ENSURE(got[k].distance == r[e].distance && memcmp(got[k].p, r[e].p, sizeof got[k].p) == 0);
                ++k;
            }
            free(s);
            free(t);
            free(r);
        }
    ENSURE_MSG(k == arr.count, "%s: %zu contacts, brute force %zu", what, arr.count, k);
    pairs_checked += k;
    ttd_scene_array_free(&arr);
    return 0;
}

/* A scene of four bodies: two of one grid mesh (a shared mesh moves for both), one of a torus,
 * and a floor. Over 12 steps the grid bends and grows and the torus twists (their vertices moved
 * with ttd_mesh_set_vertices_d), bodies move now and then: every step's contacts equal the brute
 * force of the moved vertices at their poses, the ids stay (id_limit 4); a grid grown out of its
 * old world box touches what only the new box reaches; a mesh moved out of the coordinate range
 * under its pose makes the query refuse. */
static int deforming_bodies_in_a_scene(void)
{
    ttd_gen_mesh grid, torus, floor_g, grid_now, torus_now;
    ENSURE(ttd_gen_grid(6, &grid) == 0 && ttd_gen_torus(0.5, 0.15, 10, 6, &torus) == 0 && ttd_gen_grid(3, &floor_g) == 0);
    ENSURE(ttd_gen_mesh_copy(&grid, &grid_now) == 0 && ttd_gen_mesh_copy(&torus, &torus_now) == 0);
    for (size_t v = 0; v < floor_g.nv; ++v) { /* the floor: 6 x 6 at z = -0.4 */
        floor_g.verts[3 * v] = 6 * floor_g.verts[3 * v] - 3;
        floor_g.verts[3 * v + 1] = 6 * floor_g.verts[3 * v + 1] - 3;
        floor_g.verts[3 * v + 2] = -0.4;
    }
    ttd_mesh *mg, *mt, *mf;
    ENSURE(ttd_mesh_create_d(NULL, grid.verts, grid.nv, grid.tris, grid.nt, &mg) == TTD_OK);
    ENSURE(ttd_mesh_create_d(NULL, torus.verts, torus.nv, torus.tris, torus.nt, &mt) == TTD_OK);
    ENSURE(ttd_mesh_create_d(NULL, floor_g.verts, floor_g.nv, floor_g.tris, floor_g.nt, &mf) == TTD_OK);
    dbody bodies[4] = {{&grid_now, {1, 0, 0, -1.2, 0, 1, 0, 0, 0, 0, 1, 0}},
                       {&grid_now, {0, -1, 0, 2.2, 1, 0, 0, 0, 0, 0, 1, 0.1}},
                       {&torus_now, {1, 0, 0, 0.3, 0, 1, 0, 0.5, 0, 0, 1, 0}},
                       {&floor_g, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0}}};
    ttd_scene *scene;
    ENSURE(ttd_scene_create_d(&scene) == TTD_OK);
    ttd_mesh *meshes[4] = {mg, mg, mt, mf};
    for (int i = 0; i < 4; ++i) {
        uint32_t id;
        ENSURE(ttd_scene_add_d(scene, meshes[i], bodies[i].pose, &id) == TTD_OK && id == (uint32_t)i);
    }
    /* grown threefold about its corner, body 0's grid reaches the torus only through a new box */
    for (size_t v = 0; v < 3 * grid.nv; ++v)
        grid_now.verts[v] = 3 * grid.verts[v];
    ttd_scene_array arr = {0};
    ENSURE(ttd_scene_contacts_d(NULL, scene, 0.05, &arr) == TTD_OK);
    const size_t before = arr.count;
    ENSURE(ttd_mesh_set_vertices_d(NULL, mg, grid_now.verts) == TTD_OK);
    ENSURE(ttd_scene_contacts_d(NULL, scene, 0.05, &arr) == TTD_OK);
    ENSURE_MSG(arr.count > before, "the grown grid: %zu contacts, %zu before", arr.count, before);
    ttd_scene_array_free(&arr);
    if (check_scene("grown grid", scene, bodies, 4, 0.05))
        return 1;
    for (int step = 1; step <= 12; ++step) {
        deform(&grid, step % 2 ? DEF_BEND : DEF_TWIST, step / 10.0, grid_now.verts);
        for (size_t v = 0; v < 3 * grid.nv; ++v)
            grid_now.verts[v] *= 2.5;
        deform(&torus, DEF_TWIST, step / 8.0, torus_now.verts);
        ENSURE(ttd_mesh_set_vertices_d(NULL, mg, grid_now.verts) == TTD_OK);
        ENSURE(ttd_mesh_set_vertices_d(NULL, mt, torus_now.verts) == TTD_OK);
        if (step % 4 == 0) { /* and a move */
            bodies[2].pose[3] += 0.2;
            ENSURE(ttd_scene_set_pose_d(scene, 2, bodies[2].pose) == TTD_OK);
        }
        char what[64];
        snprintf(what, sizeof what, "deforming scene, step %d", step);
        if (check_scene(what, scene, bodies, 4, 0.08))
            return 1;
        ttd_scene_array hits = {0};
        ENSURE(ttd_scene_collide_d(NULL, scene, 0.08, &hits) == TTD_OK);
        ttd_scene_array_free(&hits);
    }
    ENSURE(ttd_scene_id_limit(scene) == 4 && ttd_scene_body_count(scene) == 4);
    /* moved out of range under body 1's pose (translation 2.2): the query refuses, and accepts
     * again once the mesh is back */
    for (size_t v = 0; v < 3 * grid.nv; ++v)
        grid_now.verts[v] = grid.verts[v] + (v % 3 == 0 ? 0x1p508 - 3 : 0);
    ENSURE(ttd_mesh_set_vertices_d(NULL, mg, grid_now.verts) == TTD_OK);
    ENSURE(ttd_scene_contacts_d(NULL, scene, 0.08, &arr) == TTD_ERR_COORDINATE_RANGE);
    ENSURE(ttd_mesh_set_vertices_d(NULL, mg, grid.verts) == TTD_OK);
    memcpy(grid_now.verts, grid.verts, 3 * grid.nv * sizeof *grid.verts);
    if (check_scene("back in range", scene, bodies, 4, 0.08))
        return 1;
    printf("  13 steps of a scene of deforming bodies: every contact set the brute force's\n");
    ttd_scene_array_free(&arr);
    ttd_scene_destroy(scene);
    ttd_mesh_destroy(mg);
    ttd_mesh_destroy(mt);
    ttd_mesh_destroy(mf);
    ttd_gen_mesh *all[5] = {&grid, &torus, &floor_g, &grid_now, &torus_now};
    for (int i = 0; i < 5; ++i)
        ttd_gen_mesh_free(all[i]);
    return 0;
}

/* The same pairs, in any order, with the same bits (contacts sorted by contact_cmp_d). */
static int same_sets_d(ttd_contacts_d *x, ttd_contacts_d *y)
{
    if (x->count != y->count)
        return 0;
    if (x->count > 1) {
        qsort(x->pairs, x->count, sizeof *x->pairs, contact_cmp_d);
        qsort(y->pairs, y->count, sizeof *y->pairs, contact_cmp_d);
    }
    return x->count == 0 || memcmp(x->pairs, y->pairs, x->count * sizeof *x->pairs) == 0;
}

/* m (refitted to g's vertices) against a mesh built afresh from them: the same distance, the same
 * contacts and the same self-contacts, pair for pair with their bits; and every query against the
 * brute force (check_d). */
static int refitted_as_fresh(const char *what, const ttd_gen_mesh *g, const ttd_mesh *m)
{
    ttd_mesh *fresh;
    ENSURE(ttd_mesh_create_d(NULL, g->verts, g->nv, g->tris, g->nt, &fresh) == TTD_OK);
    double lo[3], hi[3], pose[12];
    ttd_gen_mesh_bounds(g, lo, hi);
    const double size = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
    ttd_gen_pose(53, 1, 0.3 * size, pose);
    for (int c = 0; c < 3; ++c) /* near its own middle */
        pose[4 * c + 3] += 0.5 * (lo[c] + hi[c]);
    ttd_mesh_result_d r1, r2;
    ENSURE(ttd_mesh_distance_d(NULL, m, m, 1, pose, HUGE_VAL, 0, &r1) == TTD_OK);
    ENSURE(ttd_mesh_distance_d(NULL, fresh, fresh, 1, pose, HUGE_VAL, 0, &r2) == TTD_OK);
    ENSURE_MSG(r1.distance == r2.distance, "%s: distance %.17g, fresh %.17g", what, r1.distance, r2.distance);
    ttd_contacts_d s1 = {0}, s2 = {0};
    const double margin = r1.distance + 0.1 * size;
    ENSURE(ttd_mesh_contacts_d(NULL, m, m, 1, pose, margin, &s1) == TTD_OK);
    ENSURE(ttd_mesh_contacts_d(NULL, fresh, fresh, 1, pose, margin, &s2) == TTD_OK);
    ENSURE_MSG(same_sets_d(&s1, &s2), "%s: contacts %zu, fresh %zu", what, s1.count, s2.count);
    ENSURE(ttd_mesh_self_contacts_d(NULL, m, 0.05 * size, 0, &s1) == TTD_OK);
    ENSURE(ttd_mesh_self_contacts_d(NULL, fresh, 0.05 * size, 0, &s2) == TTD_OK);
    ENSURE_MSG(same_sets_d(&s1, &s2), "%s: self-contacts %zu, fresh %zu", what, s1.count, s2.count);
    ttd_contacts_free_d(&s1);
    ttd_contacts_free_d(&s2);
    ttd_mesh_destroy(fresh);
    return check_d(what, g, g, m, m, pose);
}

/* Refits at the ends of the range and after a rebuild, each against a fresh build and the brute
 * force: a torus, a mesh of degenerate triangles and a mesh of one triangle scaled to 1e30 and to
 * 1e-30, and mixed (x scaled to 1e30, y and z to 1e-30; and a small shape at an offset of 1e30,
 * whose triangles round to segments and points), each refitted twice in a row (a refit after a
 * refit: the leaves' vertex indices kept from the first, docs/mesh-queries.md 2b); float vertices
 * at 1e30 refused (beyond float's range) with the mesh as it was. After a rebuild (a soup
 * scattered, as degraded_trees_rebuild), a small move is refitted on the rebuilt tree: its
 * leaves' vertex indices must be the new tree's, not the old one's. */
static int refit_extremes_and_after_rebuild(void)
{
    ttd_gen_mesh base[3];
    ENSURE(ttd_gen_torus(1.0, 0.35, 16, 8, &base[0]) == 0 && ttd_gen_mesh_degenerate(&base[1]) == 0);
    base[2].nv = 3;
    base[2].nt = 1;
    base[2].verts = malloc(9 * sizeof *base[2].verts);
    base[2].tris = malloc(3 * sizeof *base[2].tris);
    ENSURE(base[2].verts != NULL && base[2].tris != NULL);
    const double one[9] = {0.1, 0.2, 0.3, 1.1, 0.25, -0.2, 0.4, 0.9, 0.6};
    memcpy(base[2].verts, one, sizeof one);
    for (uint32_t k = 0; k < 3; ++k)
        base[2].tris[k] = k;
    static const char *const names[3] = {"torus", "degenerate", "one triangle"};
    static const char *const scales[4] = {"1e30", "1e-30", "x 1e30, y z 1e-30", "offset 1e30"};
    int cases = 0;
    for (int mi = 0; mi < 3; ++mi)
        for (int sc = 0; sc < 4; ++sc) {
            ttd_gen_mesh g;
            ENSURE(ttd_gen_mesh_copy(&base[mi], &g) == 0);
            ttd_mesh *m;
            ENSURE(ttd_mesh_create_d(NULL, base[mi].verts, base[mi].nv, base[mi].tris, base[mi].nt, &m) == TTD_OK);
            for (int step = 1; step <= 2; ++step) {
                for (size_t i = 0; i < g.nv; ++i)
                    for (int c = 0; c < 3; ++c) {
                        const double x = base[mi].verts[3 * i + (size_t)c] * (step == 1 ? 1.0 : 1.0 + 0.1 * c);
                        double *y = &g.verts[3 * i + (size_t)c];
                        if (sc == 0)
                            *y = 1e30 * x;
                        else if (sc == 1)
                            *y = 1e-30 * x;
                        else if (sc == 2)
                            *y = c == 0 ? 1e30 * x : 1e-30 * x;
                        else
                            *y = 1e30 + x;
                    }
                ENSURE(ttd_mesh_set_vertices_d(NULL, m, g.verts) == TTD_OK);
                char what[96];
                snprintf(what, sizeof what, "%s, %s, refit %d", names[mi], scales[sc], step);
                if (refitted_as_fresh(what, &g, m))
                    return 1;
                ++cases;
            }
            ttd_mesh_refit_info info;
            ENSURE(ttd_mesh_get_refit_info(m, &info) == TTD_OK && info.generation == 2);
            ttd_mesh_destroy(m);
            if (sc == 0) { /* float: 1e30 is beyond its range */
                mesh_f f0 = to_float(&base[mi]), f = to_float(&g);
                ttd_mesh *mf;
                ENSURE(ttd_mesh_create_f(NULL, f0.verts, f0.nv, f0.tris, f0.nt, &mf) == TTD_OK);
                ENSURE(ttd_mesh_set_vertices_f(NULL, mf, f.verts) == TTD_ERR_COORDINATE_RANGE);
                ttd_mesh_refit_info info_f;
                ENSURE(ttd_mesh_get_refit_info(mf, &info_f) == TTD_OK && info_f.generation == 0);
                ttd_mesh_destroy(mf);
                free(f0.verts);
                free(f.verts);
            }
            ttd_gen_mesh_free(&g);
        }
    for (int mi = 0; mi < 3; ++mi)
        ttd_gen_mesh_free(&base[mi]);

    /* a refit on a rebuilt tree */
    ttd_gen_mesh g, moved;
    ENSURE(icosphere_soup(2, &g) == 0);
    ENSURE(ttd_gen_mesh_copy(&g, &moved) == 0);
    ttd_mesh *m;
    ENSURE(ttd_mesh_create_d(NULL, g.verts, g.nv, g.tris, g.nt, &m) == TTD_OK);
    ENSURE(ttd_mesh_set_vertices_d(NULL, m, g.verts) == TTD_OK); /* the first tree's indices made */
    rng = 7;
    scatter_soup(moved.verts, g.nt); /* triangles to one another's places */
    ENSURE(ttd_mesh_set_vertices_d(NULL, m, moved.verts) == TTD_OK);
    ttd_mesh_refit_info info;
    ENSURE(ttd_mesh_get_refit_info(m, &info) == TTD_OK && info.rebuilds == 1);
    for (int step = 1; step <= 2; ++step) {
        ttd_gen_mesh now;
        ENSURE(ttd_gen_mesh_copy(&moved, &now) == 0);
        for (size_t i = 0; i < now.nv; ++i)
            now.verts[3 * i] *= 1 + 0.01 * step;
        ENSURE(ttd_mesh_set_vertices_d(NULL, m, now.verts) == TTD_OK);
        ENSURE(ttd_mesh_get_refit_info(m, &info) == TTD_OK && info.rebuilds == 1); /* refitted, not rebuilt */
        if (refitted_as_fresh("scattered soup, refitted after its rebuild", &now, m))
            return 1;
        ttd_gen_mesh_free(&now);
        ++cases;
    }
    printf("  %d refits at 1e30, 1e-30, mixed and after a rebuild: each as a fresh build and the brute force\n",
           cases);
    ttd_mesh_destroy(m);
    ttd_gen_mesh_free(&g);
    ttd_gen_mesh_free(&moved);
    return 0;
}

/* The tree's measure as section 2b of docs/mesh-queries.md defines it, from the nodes' boxes as
 * they are now: each node's slots' box areas (subtrees and triangles apart) in slot order, the
 * nodes' sums in node order (the refit's own order, so the same bits). */
static double measure_of_nodes(const ttd_mesh *m)
{
    double sub = 0, tri = 0;
    for (size_t n = 0; n < m->nnodes; ++n) {
        double a[2] = {0, 0};
        const ttd_node_d *nd = (const ttd_node_d *)m->nodes + n;
        for (int j = 0; j < nd->count; ++j) {
            const double *e0 = nd->e[0], *e1 = nd->e[1], *e2 = nd->e[2];
            a[nd->child[j] >= 0 ? 0 : 1] += 4 * (e0[j] * e1[j] + e1[j] * e2[j] + e2[j] * e0[j]);
        }
        sub += a[0];
        tri += a[1];
    }
    return tri > 0 ? sub / tri : 0;
}

/* The refit's scratch (per-node sums and measure parts) is kept with the mesh from its first
 * refit on, through a rebuild, and carries nothing from one refit to the next: a mesh refitted
 * through a sequence with its scratch kept, and a refused refit (NaN, inf) in the middle, ends
 * with the same nodes and measure, bit for bit, as a mesh given the same sequence without the
 * refused refits, and its measure after every refit is the one the nodes define. A refused
 * refit leaves everything as it was (nodes, vertices, generation, measure, scratch). After a
 * rebuild (the scattered soup of refit_extremes_and_after_rebuild) the scratch is kept and the
 * next refits' measure is again the nodes'. */
static int refit_scratch_reused(void)
{
    ttd_gen_mesh g, moved;
    ENSURE(ttd_gen_torus(1.0, 0.3, 40, 20, &g) == 0 && ttd_gen_mesh_copy(&g, &moved) == 0);
    ttd_mesh *a, *b;
    ENSURE(ttd_mesh_create_d(NULL, g.verts, g.nv, g.tris, g.nt, &a) == TTD_OK);
    ENSURE(ttd_mesh_create_d(NULL, g.verts, g.nv, g.tris, g.nt, &b) == TTD_OK);
    ENSURE(a->refit_scratch == NULL);
    const size_t node_bytes = a->nnodes * sizeof(ttd_node_d);
    void *before = malloc(node_bytes);
    double *bad = malloc(3 * g.nv * sizeof *bad);
    ENSURE(before != NULL && bad != NULL);
    const void *scratch = NULL;
    int refits = 0;
    for (int step = 0; step < 8; ++step) {
        deform(&g, step % 2 ? DEF_BEND : DEF_TWIST, 0.1 * (step + 1), moved.verts);
        ENSURE(ttd_mesh_set_vertices_d(NULL, a, moved.verts) == TTD_OK);
        ENSURE(ttd_mesh_set_vertices_d(NULL, b, moved.verts) == TTD_OK);
        ++refits;
        if (scratch == NULL)
            scratch = a->refit_scratch;
        ENSURE_MSG(scratch != NULL && a->refit_scratch == scratch, "step %d: the scratch not kept", step);
        ENSURE_MSG(a->quality == measure_of_nodes(a), "step %d: measure %.17g, the nodes' %.17g", step, a->quality,
                   measure_of_nodes(a));
        /* a refit refused: NaN, then inf, at a vertex the first leaf and the last read */
        ttd_mesh_refit_info i0, i1;
        ENSURE(ttd_mesh_get_refit_info(a, &i0) == TTD_OK);
        memcpy(before, a->nodes, node_bytes);
        memcpy(bad, moved.verts, 3 * g.nv * sizeof *bad);
        bad[3 * (size_t)(step % 2 ? 0 : g.nv - 1) + 1] = step % 2 ? (double)INFINITY : (double)NAN;
        ENSURE(ttd_mesh_set_vertices_d(NULL, a, bad) == TTD_ERR_NONFINITE_MESH);
        ENSURE(ttd_mesh_get_refit_info(a, &i1) == TTD_OK);
        ENSURE_MSG(i1.generation == i0.generation && i1.rebuilds == i0.rebuilds && i1.quality == i0.quality,
                   "step %d: a refused refit changed the refit info", step);
        ENSURE_MSG(memcmp(before, a->nodes, node_bytes) == 0, "step %d: a refused refit changed the nodes", step);
        ENSURE(memcmp(a->verts, moved.verts, 3 * g.nv * sizeof *bad) == 0 && a->refit_scratch == scratch);
        ENSURE_MSG(nodes_equal(a, b) && a->quality == b->quality, "step %d: nodes or measure differ", step);
    }
    ttd_mesh_destroy(a);
    ttd_mesh_destroy(b);

    /* through a rebuild: triangles of a soup moved to one another's places */
    ttd_gen_mesh ico, soup, now;
    ENSURE(ttd_gen_icosphere(2, &ico) == 0);
    soup.nt = ico.nt;
    soup.nv = 3 * ico.nt;
    soup.verts = malloc(3 * soup.nv * sizeof *soup.verts);
    soup.tris = malloc(3 * soup.nt * sizeof *soup.tris);
    ENSURE(soup.verts != NULL && soup.tris != NULL);
    for (size_t t = 0; t < soup.nt; ++t)
        for (int k = 0; k < 3; ++k) {
            soup.tris[3 * t + (size_t)k] = (uint32_t)(3 * t + (size_t)k);
            memcpy(soup.verts + 9 * t + 3 * k, ico.verts + 3 * (size_t)ico.tris[3 * t + (size_t)k], 3 * sizeof(double));
        }
    ENSURE(ttd_gen_mesh_copy(&soup, &now) == 0);
    ttd_mesh *m;
    ENSURE(ttd_mesh_create_d(NULL, soup.verts, soup.nv, soup.tris, soup.nt, &m) == TTD_OK);
    ENSURE(ttd_mesh_set_vertices_d(NULL, m, soup.verts) == TTD_OK);
    scratch = m->refit_scratch;
    rng = 11;
    for (size_t t = soup.nt; t > 1; --t) {
        const size_t u = (size_t)(urand() * (double)t);
        double x[9];
        memcpy(x, now.verts + 9 * (t - 1), sizeof x);
        memcpy(now.verts + 9 * (t - 1), now.verts + 9 * u, sizeof x);
        memcpy(now.verts + 9 * u, x, sizeof x);
    }
    ENSURE(ttd_mesh_set_vertices_d(NULL, m, now.verts) == TTD_OK);
    ttd_mesh_refit_info info;
    ENSURE(ttd_mesh_get_refit_info(m, &info) == TTD_OK && info.rebuilds == 1);
    ENSURE_MSG(m->refit_scratch == scratch, "the scratch not kept through the rebuild");
    ENSURE(m->quality == measure_of_nodes(m) && m->quality == m->quality_built);
    for (int step = 1; step <= 3; ++step) {
        for (size_t i = 0; i < now.nv; ++i)
            now.verts[3 * i + 1] *= 1 + 0.02 * step;
        ENSURE(ttd_mesh_set_vertices_d(NULL, m, now.verts) == TTD_OK);
        ENSURE(ttd_mesh_get_refit_info(m, &info) == TTD_OK && info.rebuilds == 1);
        ENSURE_MSG(m->quality == measure_of_nodes(m), "after the rebuild, refit %d: measure %.17g, the nodes' %.17g",
                   step, m->quality, measure_of_nodes(m));
        ++refits;
    }
    printf("  %d refits with the scratch kept (and 8 refused between them): the same nodes and measure\n", refits);
    ttd_mesh_destroy(m);
    free(before);
    free(bad);
    ttd_gen_mesh_free(&ico);
    ttd_gen_mesh_free(&soup);
    ttd_gen_mesh_free(&now);
    ttd_gen_mesh_free(&g);
    ttd_gen_mesh_free(&moved);
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(refit_queries_match_brute_force);
    RUN_TEST(refit_sequences_match_brute_force);
    RUN_TEST(refit_bits);
    RUN_TEST(degraded_trees_rebuild);
    RUN_TEST(refit_threads_isas_identical);
    RUN_TEST(refit_bits_every_isa);
    RUN_TEST(bad_vertices_refused);
    RUN_TEST(refit_extremes_and_after_rebuild);
    RUN_TEST(refit_scratch_reused);
    RUN_TEST(solids_after_refit);
    RUN_TEST(derived_data_after_refit);
    RUN_TEST(deforming_bodies_in_a_scene);
    TEST_MAIN_END();
}
