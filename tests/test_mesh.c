/* SPDX-License-Identifier: MIT */
/* The mesh queries (ttd_mesh_*) against brute force: the exact method over every triangle pair
 * (ttd_batch_d/f), with b's vertices moved into a's frame exactly as include/ttd/ttd.h documents
 * ((r0 x + r1 y) + r2 z) + t, so that every pair's distance is the very number the query's
 * kernel computes. On small generated meshes (gen/meshes.h) under random poses and chosen
 * placements: touching, interpenetrating, nested, identical at the identity, degenerate and
 * sliver triangles, a single triangle, far apart, huge offsets. Checked:
 *   - minimum distance: equal to the brute-force minimum (bit for bit: the same kernel on the
 *     same numbers); the reported pair realises it; p and q lie on their triangles and
 *     |p - q| = d, p == q when d = 0; an upper bound just above or below; rel_tol's promise;
 *   - contacts within a margin: the set of pairs equals the brute-force set, with the same
 *     distances and points as the single-pair entry gives;
 *   - the per-triangle closest partner: the brute-force reduction (nearest, then smallest index);
 *   - collision: yes exactly when the brute-force minimum is within the margin, and the witness
 *     pair is within it;
 *   - many poses equal a loop of single poses; 1 and 2 threads and every instruction set give the
 *     same results, bit for bit;
 *   - tiny meshes and meshes near the coordinate range (where squared bounds underflow or would
 *     overflow) against brute force; coordinates beyond the range refused;
 *   - bad input at every entry gets its status and never a crash. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh_brute.h"
#include "meshes.h"
#include "test_macros.h"
#include "ttd/ttd.h"

/* ---- the cases -------------------------------------------------------------------------- */

/* A mesh pair and a pose: the test cases share them. */
typedef struct mcase {
    const char *name;
    ttd_gen_mesh a, b;
    double pose[12];
} mcase;

enum { MAX_CASES = 64 };
static mcase cases[MAX_CASES];
static int ncases;

static const double identity[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};

static void add_case(const char *name, const ttd_gen_mesh *a, const ttd_gen_mesh *b, const double pose[12])
{
    if (ncases == MAX_CASES)
        abort();
    mcase *c = &cases[ncases++];
    c->name = name;
    if (ttd_gen_mesh_copy(a, &c->a) || ttd_gen_mesh_copy(b, &c->b))
        abort();
    memcpy(c->pose, pose, sizeof c->pose);
}

static void scale_mesh(ttd_gen_mesh *m, double s, const double shift[3])
{
    for (size_t i = 0; i < m->nv; ++i)
        for (int c = 0; c < 3; ++c)
            m->verts[3 * i + c] = m->verts[3 * i + c] * s + (shift ? shift[c] : 0);
}

/* A mesh of slivers and degenerate triangles: a fan of needles, caps, a segment and a point. */
static void sliver_mesh(ttd_gen_mesh *m)
{
    static const double v[] = {0, 0, 0, 1, 0, 0, 1, 1e-9, 0, 0.5, 1e-7, 1e-8, 0.2, 0.3, 0.1,
                               0.2, 0.3, 0.1, 0.4, 0.6, 0.2, 0.6, 0.9, 0.3, -0.3, 0.2, 0.4};
    static const uint32_t t[] = {0, 1, 2, 0, 1, 3, 4, 5, 4, 4, 6, 7, 8, 8, 8, 0, 8, 3, 2, 3, 6};
    m->nv = sizeof v / sizeof v[0] / 3;
    m->nt = sizeof t / sizeof t[0] / 3;
    m->verts = malloc(sizeof v);
    m->tris = malloc(sizeof t);
    if (!m->verts || !m->tris)
        abort();
    memcpy(m->verts, v, sizeof v);
    memcpy(m->tris, t, sizeof t);
}

static void build_cases(void)
{
    ttd_gen_mesh ico, ico2, torus, cube, tet, tri, grid, degen, nonman, dup, sliver, big;
    if (ttd_gen_icosphere(1, &ico) || ttd_gen_icosphere(2, &ico2) || ttd_gen_torus(1.0, 0.35, 14, 9, &torus) ||
        ttd_gen_mesh_cube(&cube) || ttd_gen_mesh_tetrahedron(&tet) || ttd_gen_mesh_triangle(&tri) ||
        ttd_gen_grid(7, &grid) || ttd_gen_mesh_degenerate(&degen) || ttd_gen_mesh_nonmanifold(&nonman) ||
        ttd_gen_mesh_duplicate_vertices(&dup))
        abort();
    sliver_mesh(&sliver);
    double pose[12];
    /* random poses at several scales, every mesh pair kind */
    const ttd_gen_mesh *kinds[] = {&ico, &torus, &cube, &tet, &tri, &grid, &degen, &nonman, &dup, &sliver};
    const char *names[] = {"ico", "torus", "cube", "tet", "tri", "grid", "degenerate", "nonmanifold", "duplicates", "slivers"};
    for (int i = 0; i < 10; ++i) {
        ttd_gen_pose(11, (uint64_t)i, 1.5, pose);
        add_case(names[i], kinds[i], kinds[(i + 3) % 10], pose);
        ttd_gen_pose(12, (uint64_t)i, 0.4, pose);
        add_case(names[i], kinds[i], kinds[i], pose);
    }
    /* placements: far, near, touching (gap 0), interpenetrating */
    const double gaps[] = {2.0, 0.03, 0.0, -0.2};
    for (int g = 0; g < 4; ++g) {
        if (ttd_gen_pose_gap(&ico2, &torus, 5, (uint64_t)g, NULL, gaps[g], pose))
            abort();
        add_case("ico/torus placed", &ico2, &torus, pose);
        if (ttd_gen_pose_gap(&cube, &grid, 6, (uint64_t)g, NULL, gaps[g], pose))
            abort();
        add_case("cube/grid placed", &cube, &grid, pose);
    }
    /* touching exactly: a cube on a cube, face to face, and edge to edge */
    const double on_top[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1};
    add_case("cube on cube", &cube, &cube, on_top);
    const double edge[12] = {1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 0};
    add_case("cube edge to cube edge", &cube, &cube, edge);
    /* identical meshes at the identity: every triangle touches itself */
    add_case("identical", &torus, &torus, identity);
    /* nested: a small sphere inside a big one, not touching */
    if (ttd_gen_mesh_copy(&ico2, &big))
        abort();
    scale_mesh(&big, 4.0, NULL);
    add_case("nested", &big, &ico, identity);
    /* far apart and at a huge offset */
    ttd_gen_pose(13, 0, 0, pose);
    pose[3] = 1e6;
    pose[7] = -3e5;
    add_case("far 1e6", &ico, &torus, pose);
    const double shift[3] = {2e5, -1e5, 7e5};
    ttd_gen_mesh offa, offb;
    if (ttd_gen_mesh_copy(&ico, &offa) || ttd_gen_mesh_copy(&torus, &offb))
        abort();
    scale_mesh(&offa, 1.0, shift);
    scale_mesh(&offb, 1.0, shift);
    ttd_gen_pose(14, 0, 0, pose);
    for (int c = 0; c < 3; ++c) /* rotate b about the shift point and move it 2.5 along x */
        pose[4 * c + 3] = shift[c] - (pose[4 * c] * shift[0] + pose[4 * c + 1] * shift[1] + pose[4 * c + 2] * shift[2]) +
                          (c == 0 ? 2.5 : 0);
    add_case("offset 1e5", &offa, &offb, pose);
    ttd_gen_mesh *all[] = {&ico, &ico2, &torus, &cube, &tet, &tri, &grid, &degen, &nonman, &dup, &sliver, &big, &offa, &offb};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; ++i)
        ttd_gen_mesh_free(all[i]);
}

static double mesh_size(const ttd_gen_mesh *m)
{
    double lo[3], hi[3];
    ttd_gen_mesh_bounds(m, lo, hi);
    return sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

/* ---- tests ------------------------------------------------------------------------------ */

/* The minimum, its pair and points, against brute force; upper bound and rel_tol. */
static int distance_matches_brute_force(void)
{
    for (int ci = 0; ci < ncases; ++ci) {
        const mcase *c = &cases[ci];
        ttd_mesh *a, *b;
        ENSURE(ttd_mesh_create_d(NULL, c->a.verts, c->a.nv, c->a.tris, c->a.nt, &a) == TTD_OK);
        ENSURE(ttd_mesh_create_d(NULL, c->b.verts, c->b.nv, c->b.tris, c->b.nt, &b) == TTD_OK);
        ttd_result_d *all = brute_d(&c->a, &c->b, c->pose);
        double best = HUGE_VAL;
        for (size_t i = 0; i < c->a.nt * c->b.nt; ++i)
            best = fmin(best, all[i].distance);
        ttd_mesh_result_d r;
        ENSURE(ttd_mesh_distance_d(NULL, a, b, 1, c->pose, HUGE_VAL, 0, &r) == TTD_OK);
        ENSURE_MSG(r.distance == best, "%s (case %d): %.17g, brute force %.17g", c->name, ci, r.distance, best);
        ENSURE(r.tri_a < c->a.nt && r.tri_b < c->b.nt);
        const ttd_result_d *pr = &all[(size_t)r.tri_a * c->b.nt + r.tri_b];
        ENSURE_MSG(pr->distance == best, "%s: the reported pair is at %.17g", c->name, pr->distance);
        const double size = fmax(mesh_size(&c->a), mesh_size(&c->b));
        for (int k = 0; k < 3; ++k)
            ENSURE(r.p[k] == pr->p[k]);
        if (r.distance == 0) {
            ENSURE(r.flags == TTD_MESH_INTERSECTING);
            for (int k = 0; k < 3; ++k)
                ENSURE(r.q[k] == r.p[k]);
        } else {
            ENSURE(r.flags == 0);
            const double pq = sqrt((r.p[0] - r.q[0]) * (r.p[0] - r.q[0]) + (r.p[1] - r.q[1]) * (r.p[1] - r.q[1]) +
                                   (r.p[2] - r.q[2]) * (r.p[2] - r.q[2]));
            ENSURE_NEAR(pq, r.distance, 1e-12 * size);
        }
        ENSURE(r.feature_a == pr->feature_p && r.feature_b == pr->feature_q);
        /* an upper bound just above the minimum changes nothing; just below, it is exceeded */
        ttd_mesh_result_d u;
        ENSURE(ttd_mesh_distance_d(NULL, a, b, 1, c->pose, nextafter(best, HUGE_VAL), 0, &u) == TTD_OK);
        ENSURE(u.distance == best && u.tri_a == r.tri_a && u.tri_b == r.tri_b);
        if (best > 0) {
            ENSURE(ttd_mesh_distance_d(NULL, a, b, 1, c->pose, nextafter(best, 0), 0, &u) == TTD_OK);
            ENSURE(u.flags == TTD_MESH_ABOVE_BOUND && isinf(u.distance) && u.tri_a == UINT32_MAX);
        }
        /* rel_tol: a pair within the promised factor, which brute force confirms */
        ENSURE(ttd_mesh_distance_d(NULL, a, b, 1, c->pose, HUGE_VAL, 0.25, &u) == TTD_OK);
        ENSURE(u.distance >= best && u.distance <= 1.25 * best + 1e-12 * size);
        ENSURE(all[(size_t)u.tri_a * c->b.nt + u.tri_b].distance == u.distance);
        free(all);
        ttd_mesh_destroy(a);
        ttd_mesh_destroy(b);
    }
    printf("  %d mesh pairs and poses\n", ncases);
    return 0;
}

/* The same in float, against a float brute force. */
static int distance_float_matches_brute_force(void)
{
    for (int ci = 0; ci < ncases; ++ci) {
        const mcase *c = &cases[ci];
        mesh_f fa = to_float(&c->a), fb = to_float(&c->b);
        float pose[12];
        for (int k = 0; k < 12; ++k)
            pose[k] = (float)c->pose[k];
        ttd_mesh *a, *b;
        ENSURE(ttd_mesh_create_f(NULL, fa.verts, fa.nv, fa.tris, fa.nt, &a) == TTD_OK);
        ENSURE(ttd_mesh_create_f(NULL, fb.verts, fb.nv, fb.tris, fb.nt, &b) == TTD_OK);
        ttd_result_f *all = brute_f(&fa, &fb, pose);
        float best = INFINITY;
        for (size_t i = 0; i < fa.nt * fb.nt; ++i)
            best = fminf(best, all[i].distance);
        ttd_mesh_result_f r;
        ENSURE(ttd_mesh_distance_f(NULL, a, b, 1, pose, INFINITY, 0, &r) == TTD_OK);
        ENSURE_MSG(r.distance == best, "%s (case %d): %.9g, brute force %.9g", c->name, ci, (double)r.distance, (double)best);
        ENSURE(all[(size_t)r.tri_a * fb.nt + r.tri_b].distance == best);
        /* contacts at a margin a little above the minimum: the brute-force count */
        const float margin = best * 1.5f + 0.01f;
        size_t want = 0;
        for (size_t i = 0; i < fa.nt * fb.nt; ++i)
            want += all[i].distance <= margin;
        ttd_contacts_f set = {0};
        ENSURE(ttd_mesh_contacts_f(NULL, a, b, 1, pose, margin, &set) == TTD_OK);
        ENSURE_MSG(set.count == want, "%s: %zu float contacts, brute force %zu", c->name, set.count, want);
        for (size_t i = 0; i < set.count; ++i)
            ENSURE(all[(size_t)set.pairs[i].tri_a * fb.nt + set.pairs[i].tri_b].distance == set.pairs[i].distance);
        ttd_contacts_free_f(&set);
        ttd_collision col;
        ENSURE(ttd_mesh_collide_f(NULL, a, b, 1, pose, margin, &col) == TTD_OK && col.hit == 1);
        free(all);
        free(fa.verts);
        free(fb.verts);
        ttd_mesh_destroy(a);
        ttd_mesh_destroy(b);
    }
    return 0;
}

static int contact_cmp(const void *x, const void *y)
{
    const ttd_contact_d *a = x, *b = y;
    if (a->tri_a != b->tri_a)
        return a->tri_a < b->tri_a ? -1 : 1;
    return a->tri_b < b->tri_b ? -1 : (a->tri_b > b->tri_b);
}

/* Contacts within margins around the minimum: the brute-force set, pair for pair; the
 * per-triangle closest partners; collision. */
static int contacts_and_collision_match_brute_force(void)
{
    size_t pairs_checked = 0;
    ttd_contacts_d set = {0};
    for (int ci = 0; ci < ncases; ++ci) {
        const mcase *c = &cases[ci];
        ttd_mesh *a, *b;
        ENSURE(ttd_mesh_create_d(NULL, c->a.verts, c->a.nv, c->a.tris, c->a.nt, &a) == TTD_OK);
        ENSURE(ttd_mesh_create_d(NULL, c->b.verts, c->b.nv, c->b.tris, c->b.nt, &b) == TTD_OK);
        ttd_result_d *all = brute_d(&c->a, &c->b, c->pose);
        const size_t n = c->a.nt * c->b.nt;
        double best = HUGE_VAL;
        for (size_t i = 0; i < n; ++i)
            best = fmin(best, all[i].distance);
        const double size = fmax(mesh_size(&c->a), mesh_size(&c->b));
        /* margins: 0, exactly the minimum (boundary pairs included), and wider */
        const double margins[] = {0, best, best + 0.05 * size, best + 0.3 * size};
        for (int mi = 0; mi < 4; ++mi) {
            const double margin = margins[mi];
            ENSURE(ttd_mesh_contacts_d(NULL, a, b, 1, c->pose, margin, &set) == TTD_OK);
            ENSURE(set.poses == 1 && set.pose_start[0] == 0 && set.pose_start[1] == set.count);
            if (set.count > 0)
                qsort(set.pairs, set.count, sizeof *set.pairs, contact_cmp);
            size_t want = 0, k = 0;
            for (size_t i = 0; i < n; ++i) {
                if (!(all[i].distance <= margin))
                    continue;
                ++want;
                ENSURE_MSG(k < set.count && set.pairs[k].tri_a == i / c->b.nt && set.pairs[k].tri_b == i % c->b.nt,
                           "%s margin %.17g: pair (%zu, %zu) at %.17g missing", c->name, margin, i / c->b.nt,
                           i % c->b.nt, all[i].distance);
                const ttd_contact_d *p = &set.pairs[k++];
                ENSURE(p->distance == all[i].distance);
                for (int q = 0; q < 3; ++q) {
                    ENSURE(p->p[q] == all[i].p[q]);
                    ENSURE(p->q[q] == (all[i].distance == 0 ? all[i].p[q] : all[i].q[q]));
                }
            }
            ENSURE_MSG(set.count == want, "%s margin %.17g: %zu pairs, brute force %zu", c->name, margin, set.count, want);
            size_t counted = SIZE_MAX; /* the count without the pairs */
            ENSURE(ttd_mesh_contacts_count_d(NULL, a, b, 1, c->pose, margin, &counted) == TTD_OK);
            ENSURE_MSG(counted == want, "%s margin %.17g: counted %zu, brute force %zu", c->name, margin, counted, want);
            pairs_checked += want;
            /* collision with this margin */
            ttd_collision col;
            ENSURE(ttd_mesh_collide_d(NULL, a, b, 1, c->pose, margin, &col) == TTD_OK);
            ENSURE((col.hit == 1) == (best <= margin));
            if (col.hit)
                ENSURE(all[(size_t)col.tri_a * c->b.nt + col.tri_b].distance <= margin);
            else
                ENSURE(col.tri_a == UINT32_MAX && col.tri_b == UINT32_MAX);
            /* per-triangle closest partners */
            ttd_closest_d *fa = malloc(c->a.nt * sizeof *fa), *fb = malloc(c->b.nt * sizeof *fb);
            ENSURE(fa && fb);
            ENSURE(ttd_mesh_closest_d(NULL, a, b, 1, c->pose, margin, fa, fb) == TTD_OK);
            for (size_t i = 0; i < c->a.nt; ++i) {
                size_t bj = SIZE_MAX;
                for (size_t j = 0; j < c->b.nt; ++j)
                    if (all[i * c->b.nt + j].distance <= margin &&
                        (bj == SIZE_MAX || all[i * c->b.nt + j].distance < all[i * c->b.nt + bj].distance))
                        bj = j;
                ENSURE(fa[i].partner == (bj == SIZE_MAX ? UINT32_MAX : (uint32_t)bj));
                if (bj != SIZE_MAX)
                    ENSURE(fa[i].distance == all[i * c->b.nt + bj].distance && fa[i].p[0] == all[i * c->b.nt + bj].p[0]);
                else
                    ENSURE(isinf(fa[i].distance));
            }
            for (size_t j = 0; j < c->b.nt; ++j) {
                size_t bi = SIZE_MAX;
                for (size_t i = 0; i < c->a.nt; ++i)
                    if (all[i * c->b.nt + j].distance <= margin &&
                        (bi == SIZE_MAX || all[i * c->b.nt + j].distance < all[bi * c->b.nt + j].distance))
                        bi = i;
                ENSURE(fb[j].partner == (bi == SIZE_MAX ? UINT32_MAX : (uint32_t)bi));
                if (bi != SIZE_MAX) /* p is on b's triangle: the pair's q */
                    ENSURE(fb[j].distance == all[bi * c->b.nt + j].distance && fb[j].q[1] == all[bi * c->b.nt + j].p[1]);
            }
            free(fa);
            free(fb);
        }
        free(all);
        ttd_mesh_destroy(a);
        ttd_mesh_destroy(b);
    }
    ttd_contacts_free_d(&set);
    ENSURE(set.pairs == NULL && set.count == 0);
    printf("  %zu pairs within margins checked\n", pairs_checked);
    return 0;
}

/* Many poses in one call equal single calls; thread counts and instruction sets give the same
 * bits for every query. */
static int poses_threads_isas_identical(void)
{
    ttd_gen_mesh ico, torus;
    ENSURE(ttd_gen_icosphere(2, &ico) == 0 && ttd_gen_torus(1.0, 0.3, 24, 12, &torus) == 0);
    ttd_gen_normalize(&ico);
    ttd_gen_normalize(&torus);
    enum { K = 40 };
    double poses[12 * K];
    for (int i = 0; i < K; ++i)
        ttd_gen_pose(21, (uint64_t)i, 0.8, poses + 12 * i);
    ttd_mesh *a, *b;
    ENSURE(ttd_mesh_create_d(NULL, ico.verts, ico.nv, ico.tris, ico.nt, &a) == TTD_OK);
    ENSURE(ttd_mesh_create_d(NULL, torus.verts, torus.nv, torus.tris, torus.nt, &b) == TTD_OK);
    ttd_mesh_result_d ref[K], got[K];
    ttd_collision cref[K], cgot[K];
    ttd_contacts_d sref = {0}, sgot = {0};
    ttd_options o = ttd_default_options();
    o.isa = TTD_ISA_SCALAR;
    o.threads = 1;
    ENSURE(ttd_mesh_distance_d(&o, a, b, K, poses, HUGE_VAL, 0, ref) == TTD_OK);
    ENSURE(ttd_mesh_collide_d(&o, a, b, K, poses, 0.01, cref) == TTD_OK);
    ENSURE(ttd_mesh_contacts_d(&o, a, b, K, poses, 0.05, &sref) == TTD_OK);
    size_t counts[K]; /* each pose's count without the pairs, at 1 and 2 threads */
    for (int threads = 1; threads <= 2; ++threads) {
        ttd_options oc = o;
        oc.threads = threads;
        ENSURE(ttd_mesh_contacts_count_d(&oc, a, b, K, poses, 0.05, counts) == TTD_OK);
        for (int i = 0; i < K; ++i)
            ENSURE(counts[i] == sref.pose_start[i + 1] - sref.pose_start[i]);
    }
    {
        float pf[12 * K];
        for (int i = 0; i < 12 * K; ++i)
            pf[i] = (float)poses[i];
        ENSURE(ttd_mesh_contacts_count_f(&o, a, b, K, pf, 0.05f, counts) == TTD_ERR_PRECISION_MISMATCH);
        ENSURE(ttd_mesh_contacts_count_d(&o, a, b, K, poses, 0.05, NULL) == TTD_ERR_NULL_POINTER);
        ENSURE(ttd_mesh_contacts_count_d(&o, a, b, K, poses, -1.0, counts) == TTD_ERR_BAD_OPTIONS);
    }
    for (int i = 0; i < K; ++i) { /* a loop of single poses */
        ENSURE(ttd_mesh_distance_d(&o, a, b, 1, poses + 12 * i, HUGE_VAL, 0, &got[i]) == TTD_OK);
        ENSURE(memcmp(&got[i], &ref[i], sizeof got[i]) == 0);
        ENSURE(ttd_mesh_contacts_d(&o, a, b, 1, poses + 12 * i, 0.05, &sgot) == TTD_OK);
        ENSURE(sgot.count == sref.pose_start[i + 1] - sref.pose_start[i]);
        ENSURE(sgot.count == 0 || memcmp(sgot.pairs, sref.pairs + sref.pose_start[i], sgot.count * sizeof *sgot.pairs) == 0);
    }
    int isas = 0;
    for (int isa = 1; isa < TTD_ISA_COUNT; ++isa) {
        if (!ttd_isa_available((ttd_isa)isa))
            continue;
        for (int threads = 1; threads <= 3; ++threads) {
            o.isa = (ttd_isa)isa;
            o.threads = threads;
            ENSURE(ttd_mesh_distance_d(&o, a, b, K, poses, HUGE_VAL, 0, got) == TTD_OK);
            ENSURE_MSG(memcmp(got, ref, sizeof got) == 0, "%s, %d threads: distances differ", ttd_isa_name((ttd_isa)isa), threads);
            ENSURE(ttd_mesh_collide_d(&o, a, b, K, poses, 0.01, cgot) == TTD_OK);
            ENSURE(memcmp(cgot, cref, sizeof cgot) == 0);
            ENSURE(ttd_mesh_contacts_d(&o, a, b, K, poses, 0.05, &sgot) == TTD_OK);
            ENSURE(sgot.count == sref.count && memcmp(sgot.pairs, sref.pairs, sgot.count * sizeof *sgot.pairs) == 0);
            ENSURE(memcmp(sgot.pose_start, sref.pose_start, (K + 1) * sizeof(size_t)) == 0);
            /* one pose: its contacts are cut into sub-walks that run on the threads */
            ENSURE(ttd_mesh_contacts_d(&o, a, b, 1, poses + 12 * 3, 0.3, &sgot) == TTD_OK);
            ttd_options o1 = o;
            o1.threads = 1;
            o1.isa = TTD_ISA_SCALAR;
            ENSURE(ttd_mesh_contacts_d(&o1, a, b, 1, poses + 12 * 3, 0.3, &sref) == TTD_OK);
            ENSURE(sgot.count == sref.count && memcmp(sgot.pairs, sref.pairs, sgot.count * sizeof *sgot.pairs) == 0);
            ENSURE(ttd_mesh_contacts_d(&o1, a, b, K, poses, 0.05, &sref) == TTD_OK); /* the reference again */
        }
        ++isas;
    }
    /* a set far larger than a task's first chunk: the joined chunks of three threads equal the
     * one thread's set, written in place */
    for (int threads = 1; threads <= 3; threads += 2) {
        o.isa = TTD_ISA_AUTO;
        o.threads = threads;
        ENSURE(ttd_mesh_contacts_d(&o, a, b, 2, poses, 2.0, threads == 1 ? &sref : &sgot) == TTD_OK);
    }
    ENSURE(sref.count == (size_t)2 * ico.nt * torus.nt && sgot.count == sref.count);
    ENSURE(memcmp(sgot.pairs, sref.pairs, sgot.count * sizeof *sgot.pairs) == 0);
    ENSURE(memcmp(sgot.pose_start, sref.pose_start, 3 * sizeof(size_t)) == 0);
    printf("  %d instruction sets x 1..3 threads: identical\n", isas);
    ttd_contacts_free_d(&sref);
    ttd_contacts_free_d(&sgot);
    ttd_mesh_destroy(a);
    ttd_mesh_destroy(b);
    ttd_gen_mesh_free(&ico);
    ttd_gen_mesh_free(&torus);
    return 0;
}

/* Every entry answers bad input with its status. */
static int bad_input(void)
{
    ttd_gen_mesh m;
    ENSURE(ttd_gen_mesh_tetrahedron(&m) == 0);
    float vf[12];
    for (int i = 0; i < 12; ++i)
        vf[i] = (float)m.verts[i];
    ttd_mesh *a = NULL, *f = NULL, *x = (ttd_mesh *)&m;
    /* building */
    ENSURE(ttd_mesh_create_d(NULL, m.verts, m.nv, m.tris, m.nt, NULL) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_mesh_create_d(NULL, NULL, m.nv, m.tris, m.nt, &x) == TTD_ERR_NULL_POINTER && x == NULL);
    ENSURE(ttd_mesh_create_d(NULL, m.verts, m.nv, NULL, m.nt, &a) == TTD_ERR_NULL_POINTER && a == NULL);
    ENSURE(ttd_mesh_create_d(NULL, m.verts, 0, m.tris, m.nt, &a) == TTD_ERR_EMPTY);
    ENSURE(ttd_mesh_create_d(NULL, m.verts, m.nv, m.tris, 0, &a) == TTD_ERR_EMPTY);
    ENSURE(ttd_mesh_create_d(NULL, m.verts, 3, m.tris, m.nt, &a) == TTD_ERR_INDEX_OUT_OF_RANGE && a == NULL);
    ENSURE(ttd_mesh_create_d(NULL, m.verts, SIZE_MAX / 2, m.tris, m.nt, &a) == TTD_ERR_TOO_LARGE);
    ttd_options bad = ttd_default_options();
    bad.internal_cookie = 0;
    ENSURE(ttd_mesh_create_d(&bad, m.verts, m.nv, m.tris, m.nt, &a) == TTD_ERR_BAD_OPTIONS);
    bad = ttd_default_options();
    bad.method = TTD_METHOD_PENALTY;
    ENSURE(ttd_mesh_create_d(&bad, m.verts, m.nv, m.tris, m.nt, &a) == TTD_ERR_BAD_OPTIONS);
    const double keep = m.verts[4];
    m.verts[4] = (double)NAN;
    ENSURE(ttd_mesh_create_d(NULL, m.verts, m.nv, m.tris, m.nt, &a) == TTD_ERR_NONFINITE_MESH && a == NULL);
    m.verts[4] = -HUGE_VAL;
    ENSURE(ttd_mesh_create_d(NULL, m.verts, m.nv, m.tris, m.nt, &a) == TTD_ERR_NONFINITE_MESH);
    m.verts[4] = keep;
    vf[7] = INFINITY;
    ENSURE(ttd_mesh_create_f(NULL, vf, m.nv, m.tris, m.nt, &f) == TTD_ERR_NONFINITE_MESH);
    vf[7] = (float)m.verts[7];
    ENSURE(ttd_mesh_create_d(NULL, m.verts, m.nv, m.tris, m.nt, &a) == TTD_OK && a != NULL);
    ENSURE(ttd_mesh_create_f(NULL, vf, m.nv, m.tris, m.nt, &f) == TTD_OK && f != NULL);
    ENSURE(ttd_mesh_triangle_count(a) == m.nt && ttd_mesh_vertex_count(a) == m.nv && ttd_mesh_node_count(a) >= 1);
    ENSURE(ttd_mesh_triangle_count(NULL) == 0 && ttd_mesh_node_count(NULL) == 0);
    ttd_mesh_destroy(NULL);

    /* queries */
    double pose[12];
    memcpy(pose, identity, sizeof pose);
    pose[3] = 5;
    float posef[12];
    for (int i = 0; i < 12; ++i)
        posef[i] = (float)pose[i];
    ttd_mesh_result_d r;
    ttd_mesh_result_f rf;
    ttd_collision col;
    ttd_contacts_d set = {0};
    ttd_closest_d cl[4];
    ENSURE(ttd_mesh_distance_d(NULL, a, a, 1, pose, HUGE_VAL, 0, &r) == TTD_OK);
    ENSURE(ttd_mesh_distance_d(NULL, NULL, a, 1, pose, HUGE_VAL, 0, &r) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_mesh_distance_d(NULL, a, a, 1, NULL, HUGE_VAL, 0, &r) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_mesh_distance_d(NULL, a, a, 1, pose, HUGE_VAL, 0, NULL) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_mesh_distance_d(NULL, a, a, 0, pose, HUGE_VAL, 0, &r) == TTD_ERR_EMPTY);
    ENSURE(ttd_mesh_distance_d(NULL, a, a, 1, pose, -1, 0, &r) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_mesh_distance_d(NULL, a, a, 1, pose, (double)NAN, 0, &r) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_mesh_distance_d(NULL, a, a, 1, pose, HUGE_VAL, -0.5, &r) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_mesh_distance_d(NULL, a, a, 1, pose, HUGE_VAL, HUGE_VAL, &r) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_mesh_distance_d(NULL, a, f, 1, pose, HUGE_VAL, 0, &r) == TTD_ERR_PRECISION_MISMATCH);
    ENSURE(ttd_mesh_distance_f(NULL, f, a, 1, posef, INFINITY, 0, &rf) == TTD_ERR_PRECISION_MISMATCH);
    ENSURE(ttd_mesh_distance_f(NULL, f, f, 1, posef, INFINITY, 0, &rf) == TTD_OK && rf.distance > 0);
    ENSURE(ttd_mesh_collide_d(NULL, a, a, 1, pose, -0.1, &col) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_mesh_collide_d(NULL, a, a, 1, pose, HUGE_VAL, &col) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_mesh_contacts_d(NULL, a, a, 1, pose, (double)NAN, &set) == TTD_ERR_BAD_OPTIONS && set.count == 0);
    ENSURE(ttd_mesh_contacts_d(NULL, a, a, 1, pose, 1, NULL) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_mesh_closest_d(NULL, a, a, 1, pose, 1, NULL, NULL) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_mesh_closest_d(NULL, a, a, 1, pose, 1, cl, NULL) == TTD_OK);
    /* poses that are not rigid motions: NaN, inf, scale, shear, reflection; the tolerance */
    const struct {
        int entry;
        double value;
        ttd_status want;
    } bad_poses[] = {
        {0, (double)NAN, TTD_ERR_BAD_POSE},   {3, HUGE_VAL, TTD_ERR_BAD_POSE}, {0, 1.001, TTD_ERR_BAD_POSE},
        {1, 0.01, TTD_ERR_BAD_POSE},  {0, -1, TTD_ERR_BAD_POSE},       {10, 1 + 4e-7, TTD_OK},
        {10, 1 + 2e-6, TTD_ERR_BAD_POSE},
    };
    for (size_t i = 0; i < sizeof bad_poses / sizeof bad_poses[0]; ++i) {
        double p[24];
        memcpy(p, pose, sizeof pose);
        memcpy(p + 12, pose, sizeof pose);
        p[12 + bad_poses[i].entry] = bad_poses[i].value; /* the second of two poses */
        ttd_mesh_result_d r2[2];
        ENSURE_MSG(ttd_mesh_distance_d(NULL, a, a, 2, p, HUGE_VAL, 0, r2) == bad_poses[i].want, "bad pose %zu", i);
        ENSURE(ttd_mesh_collide_d(NULL, a, a, 2, p, 0, (ttd_collision[2]){{0}}) == bad_poses[i].want);
    }
    posef[5] = NAN;
    ENSURE(ttd_mesh_distance_f(NULL, f, f, 1, posef, INFINITY, 0, &rf) == TTD_ERR_BAD_POSE);
    /* ttd_mesh_check_poses: the first refused pose, or k when no pose is at fault */
    size_t which = 0;
    ENSURE(ttd_mesh_check_poses_f(f, f, 1, posef, &which) == TTD_ERR_BAD_POSE && which == 0);
    ENSURE(ttd_mesh_check_poses_d(f, a, 1, pose, &which) == TTD_ERR_PRECISION_MISMATCH && which == 1);
    ENSURE(ttd_mesh_check_poses_d(a, a, 0, pose, &which) == TTD_ERR_EMPTY && which == 0);
    ENSURE(ttd_mesh_check_poses_d(a, NULL, 1, pose, &which) == TTD_ERR_NULL_POINTER && which == 1);
    ENSURE(ttd_mesh_check_poses_d(a, a, 1, pose, NULL) == TTD_ERR_NULL_POINTER);
    ttd_contacts_free_d(&set);
    ttd_contacts_free_d(NULL);
    ttd_mesh_destroy(a);
    ttd_mesh_destroy(f);
    ttd_gen_mesh_free(&m);
    return 0;
}

/* A scaled copy of m. */
static ttd_gen_mesh scaled(const ttd_gen_mesh *m, double s)
{
    ttd_gen_mesh c;
    if (ttd_gen_mesh_copy(m, &c))
        abort();
    scale_mesh(&c, s, NULL);
    return c;
}

/* Meshes and distances at the ends of the range (tiny, and just inside the coordinate range),
 * where a squared bound could underflow or overflow: the minimum equals brute force, and the
 * collision test agrees with it, in both precisions. */
static int extreme_scales_match_brute_force(void)
{
    ttd_gen_mesh ico, torus;
    ENSURE(ttd_gen_icosphere(2, &ico) == 0 && ttd_gen_torus(1.0, 0.35, 14, 9, &torus) == 0);
    /* b reaches 1.35 s from its origin and the pose moves it by about 3 s: 4.4 s in all */
    const double sd[] = {1e-300, 1e-150, 1e100, 1e152}, sf[] = {1e-30, 1e-15, 1e15, 2e17};
    for (int i = 0; i < 8; ++i) {
        const int dbl = i < 4;
        const double s = dbl ? sd[i] : sf[i - 4];
        ttd_gen_mesh a = scaled(&ico, s), b = scaled(&torus, s);
        double pose[12];
        ttd_gen_pose(21, (uint64_t)i, 0, pose);
        pose[3] = 3 * s;
        pose[7] = 0.3 * s;
        ttd_mesh *ma, *mb;
        ttd_collision col[2];
        if (dbl) {
            ENSURE(ttd_mesh_create_d(NULL, a.verts, a.nv, a.tris, a.nt, &ma) == TTD_OK);
            ENSURE(ttd_mesh_create_d(NULL, b.verts, b.nv, b.tris, b.nt, &mb) == TTD_OK);
            ttd_result_d *all = brute_d(&a, &b, pose);
            double best = HUGE_VAL;
            for (size_t j = 0; j < a.nt * b.nt; ++j)
                best = fmin(best, all[j].distance);
            ttd_mesh_result_d r;
            ENSURE(ttd_mesh_distance_d(NULL, ma, mb, 1, pose, HUGE_VAL, 0, &r) == TTD_OK);
            ENSURE_MSG(r.distance == best, "scale %g: %.17g, brute force %.17g", s, r.distance, best);
            ENSURE(best > 0.5 * s && best < 3 * s);
            ENSURE(ttd_mesh_collide_d(NULL, ma, mb, 1, pose, nextafter(best, HUGE_VAL), &col[0]) == TTD_OK);
            ENSURE(ttd_mesh_collide_d(NULL, ma, mb, 1, pose, nextafter(best, 0), &col[1]) == TTD_OK);
            free(all);
        } else {
            mesh_f fa = to_float(&a), fb = to_float(&b);
            float posef[12];
            for (int k = 0; k < 12; ++k)
                posef[k] = (float)pose[k];
            ENSURE(ttd_mesh_create_f(NULL, fa.verts, fa.nv, fa.tris, fa.nt, &ma) == TTD_OK);
            ENSURE(ttd_mesh_create_f(NULL, fb.verts, fb.nv, fb.tris, fb.nt, &mb) == TTD_OK);
            ttd_result_f *all = brute_f(&fa, &fb, posef);
            float best = INFINITY;
            for (size_t j = 0; j < fa.nt * fb.nt; ++j)
                best = fminf(best, all[j].distance);
            ttd_mesh_result_f r;
            ENSURE(ttd_mesh_distance_f(NULL, ma, mb, 1, posef, INFINITY, 0, &r) == TTD_OK);
            ENSURE_MSG(r.distance == best, "float scale %g: %.9g, brute force %.9g", s, (double)r.distance, (double)best);
            ENSURE((double)best > 0.5 * s && (double)best < 3 * s);
            ENSURE(ttd_mesh_collide_f(NULL, ma, mb, 1, posef, nextafterf(best, INFINITY), &col[0]) == TTD_OK);
            ENSURE(ttd_mesh_collide_f(NULL, ma, mb, 1, posef, nextafterf(best, 0), &col[1]) == TTD_OK);
            free(all);
            free(fa.verts);
            free(fb.verts);
        }
        ENSURE_MSG(col[0].hit == 1 && col[1].hit == 0, "scale %g: collisions %d %d", s, col[0].hit, col[1].hit);
        ttd_mesh_destroy(ma);
        ttd_mesh_destroy(mb);
        ttd_gen_mesh_free(&a);
        ttd_gen_mesh_free(&b);
    }
    ttd_gen_mesh_free(&ico);
    ttd_gen_mesh_free(&torus);
    return 0;
}

/* Beyond the coordinate range: a vertex at build, or b moved there by a pose, is refused. */
static int coordinate_range_refused(void)
{
    ttd_gen_mesh tri;
    ENSURE(ttd_gen_mesh_triangle(&tri) == 0);
    const double lim[2] = {0x1p60, 0x1p508};
    for (int dbl = 0; dbl < 2; ++dbl) {
        const double L = lim[dbl];
        /* a vertex at the limit builds; just beyond, the build is refused */
        for (int beyond = 0; beyond < 2; ++beyond) {
            ttd_gen_mesh m;
            ENSURE(ttd_gen_mesh_copy(&tri, &m) == 0);
            m.verts[4] = beyond ? (dbl ? nextafter(L, HUGE_VAL) : (double)nextafterf((float)L, INFINITY)) : -L;
            ttd_mesh *x = NULL;
            mesh_f f = to_float(&m);
            const ttd_status st = dbl ? ttd_mesh_create_d(NULL, m.verts, m.nv, m.tris, m.nt, &x)
                                      : ttd_mesh_create_f(NULL, f.verts, f.nv, f.tris, f.nt, &x);
            ENSURE_MSG(st == (beyond ? TTD_ERR_COORDINATE_RANGE : TTD_OK), "precision %d, beyond %d: %d", dbl, beyond, st);
            ENSURE((x == NULL) == beyond);
            ttd_mesh_destroy(x);
            free(f.verts);
            ttd_gen_mesh_free(&m);
        }
        /* a pose that moves b beyond the range: refused, the other poses of the call too */
        ttd_mesh *x;
        mesh_f f = to_float(&tri);
        ENSURE((dbl ? ttd_mesh_create_d(NULL, tri.verts, tri.nv, tri.tris, tri.nt, &x)
                    : ttd_mesh_create_f(NULL, f.verts, f.nv, f.tris, f.nt, &x)) == TTD_OK);
        double pose[24] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
        float posef[24];
        ttd_collision col[2];
        for (int far = 0; far < 2; ++far) {
            pose[12 + 11] = far ? 2 * L : L / 4;
            for (int k = 0; k < 24; ++k)
                posef[k] = (float)pose[k];
            const ttd_status want = far ? TTD_ERR_COORDINATE_RANGE : TTD_OK;
            const ttd_status st = dbl ? ttd_mesh_collide_d(NULL, x, x, 2, pose, 0, col)
                                      : ttd_mesh_collide_f(NULL, x, x, 2, posef, 0, col);
            ENSURE_MSG(st == want, "precision %d, far %d: %d", dbl, far, st);
            /* the check alone names the pose */
            size_t bad = 99;
            ENSURE((dbl ? ttd_mesh_check_poses_d(x, x, 2, pose, &bad) : ttd_mesh_check_poses_f(x, x, 2, posef, &bad)) == want);
            ENSURE(bad == (far ? 1u : 2u));
        }
        ttd_mesh_destroy(x);
        free(f.verts);
    }
    ttd_gen_mesh_free(&tri);
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    build_cases();
    RUN_TEST(distance_matches_brute_force);
    RUN_TEST(distance_float_matches_brute_force);
    RUN_TEST(contacts_and_collision_match_brute_force);
    RUN_TEST(poses_threads_isas_identical);
    RUN_TEST(bad_input);
    RUN_TEST(extreme_scales_match_brute_force);
    RUN_TEST(coordinate_range_refused);
    for (int i = 0; i < ncases; ++i) {
        ttd_gen_mesh_free(&cases[i].a);
        ttd_gen_mesh_free(&cases[i].b);
    }
    TEST_MAIN_END();
}
