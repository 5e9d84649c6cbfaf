/* SPDX-License-Identifier: MIT */
/* Continuous collision over a scene (ttd_scene_ccd_d/f, ttd.h; docs/ccd.md section 13) against a
 * brute force over every body pair: each present pair that the test's own copy of the filters and
 * exclusions allows, run through ttd_mesh_ccd_rigid_d/f (a pair of solids as solids). The same
 * hits, to the bit, with 1, 2 and 3 threads; bodies whose meshes sit far from their origins
 * swinging through half turns (the swept boxes' arcs), a removed body, filters, exclusions, solids,
 * min_separation > 0, float scenes, a fast small body through a thin plate; the checks. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "boxes.h"
#include "meshes.h"
#include "test_macros.h"
#include "ttd/ttd.h"

#define PI 3.14159265358979323846

#define TEST_RAND_SEED 0x6a09e667f3bcc909ull
#include "test_rand.h"

static void random_rotation(double R[9], double max_angle)
{
    double u[3], n;
    do {
        for (int i = 0; i < 3; ++i)
            u[i] = srand1();
        n = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    } while (n < 0.1);
    for (int i = 0; i < 3; ++i)
        u[i] /= n;
    const double a = max_angle * urand(), c = cos(a), s = sin(a), k = 1 - c;
    const double r[9] = {c + k * u[0] * u[0],        k * u[0] * u[1] - s * u[2], k * u[0] * u[2] + s * u[1],
                         k * u[1] * u[0] + s * u[2], c + k * u[1] * u[1],        k * u[1] * u[2] - s * u[0],
                         k * u[2] * u[0] - s * u[1], k * u[2] * u[1] + s * u[0], c + k * u[2] * u[2]};
    memcpy(R, r, sizeof r);
}
static void make_pose(const double R[9], const double t[3], double P[12])
{
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j)
            P[4 * i + j] = R[3 * i + j];
        P[4 * i + 3] = t[i];
    }
}

#define NB 28

typedef struct world {
    ttd_gen_mesh g[4];
    ttd_mesh *m[2][4]; /* [float, double][kind] */
    int kind[NB];
    double p0[NB][12], p1[NB][12];
    uint32_t group[NB], mask[NB];
    int removed[NB], solid[NB];
    uint32_t excl[8][2];
    int nexcl;
} world;

/* Meshes: a sphere, a torus, a cube, and a small sphere set 2.5 off its origin (a pendulum). */
static int world_make(world *w)
{
    memset(w, 0, sizeof *w);
    ENSURE(ttd_gen_icosphere(1, &w->g[0]) == 0);
    ENSURE(ttd_gen_torus(0.8, 0.25, 12, 6, &w->g[1]) == 0);
    ENSURE(ttd_gen_mesh_cube(&w->g[2]) == 0);
    ENSURE(ttd_gen_icosphere(1, &w->g[3]) == 0);
    for (size_t i = 0; i < 3 * w->g[0].nv; ++i)
        w->g[0].verts[i] *= 0.6;
    for (size_t i = 0; i < 3 * w->g[3].nv; ++i)
        w->g[3].verts[i] = 0.3 * w->g[3].verts[i] + (i % 3 == 0 ? 2.5 : 0);
    for (int k = 0; k < 4; ++k)
        for (int b = 0; b < 2; ++b) {
            w->m[b][k] = test_mesh_of(b ? 8 : 4, w->g[k].verts, w->g[k].nv, w->g[k].tris, w->g[k].nt);
            ENSURE(w->m[b][k] != NULL);
        }
    for (int i = 0; i < NB; ++i) {
        w->kind[i] = i % 4;
        double R0[9], R1[9], t0[3], t1[3];
        random_rotation(R0, PI);
        random_rotation(R1, PI);
        for (int c = 0; c < 3; ++c) {
            t0[c] = 7 * urand();
            t1[c] = t0[c] + 1.2 * srand1();
        }
        make_pose(R0, t0, w->p0[i]);
        make_pose(R1, t1, w->p1[i]);
        w->group[i] = 1u << (i % 3);
        w->mask[i] = i % 7 == 5 ? ~(1u << 1) : UINT32_MAX; /* some refuse group 2 */
        w->solid[i] = (w->kind[i] == 0 || w->kind[i] == 2) && i % 3 == 0;
    }
    w->removed[9] = 1;
    for (int e = 0; e < 8; ++e) {
        w->excl[e][0] = (uint32_t)(3 * e);
        w->excl[e][1] = (uint32_t)(3 * e + 4);
    }
    w->nexcl = 8;
    return 0;
}
static void world_free(world *w)
{
    for (int k = 0; k < 4; ++k) {
        ttd_gen_mesh_free(&w->g[k]);
        for (int b = 0; b < 2; ++b)
            ttd_mesh_destroy(w->m[b][k]);
    }
}

static int eligible(const world *w, int i, int j)
{
    if (w->removed[i] || w->removed[j] || !(w->group[i] & w->mask[j]) || !(w->group[j] & w->mask[i]))
        return 0;
    for (int e = 0; e < w->nexcl; ++e)
        if ((w->excl[e][0] == (uint32_t)i && w->excl[e][1] == (uint32_t)j) ||
            (w->excl[e][0] == (uint32_t)j && w->excl[e][1] == (uint32_t)i))
            return 0;
    return 1;
}

static ttd_scene *scene_of(const world *w, int bytes)
{
    ttd_scene *s = NULL;
    if ((bytes == 8 ? ttd_scene_create_d(&s) : ttd_scene_create_f(&s)) != TTD_OK)
        return NULL;
    for (int i = 0; i < NB; ++i) {
        uint32_t id;
        float pf[12];
        for (int k = 0; k < 12; ++k)
            pf[k] = (float)w->p0[i][k];
        const ttd_mesh *m = w->m[bytes == 8][w->kind[i]];
        if ((bytes == 8 ? ttd_scene_add_d(s, m, w->p0[i], &id) : ttd_scene_add_f(s, m, pf, &id)) != TTD_OK)
            return NULL;
        ttd_scene_set_filter(s, id, w->group[i], w->mask[i]);
        if (w->solid[i] && ttd_scene_set_solid(s, id, 1) != TTD_OK)
            return NULL;
    }
    for (int e = 0; e < w->nexcl; ++e)
        ttd_scene_exclude_pair(s, w->excl[e][0], w->excl[e][1], 1);
    for (int i = 0; i < NB; ++i)
        if (w->removed[i])
            ttd_scene_remove(s, (uint32_t)i);
    return s;
}

static ttd_status scene_ccd(int bytes, int threads, ttd_scene *s, const world *w, double delta, ttd_scene_array *out)
{
    ttd_options o = ttd_default_options();
    o.threads = threads;
    if (bytes == 8)
        return ttd_scene_ccd_d(&o, s, NB, &w->p1[0][0], delta, out);
    float pf[NB * 12];
    for (int i = 0; i < NB * 12; ++i)
        pf[i] = (float)(&w->p1[0][0])[i];
    return ttd_scene_ccd_f(&o, s, NB, pf, delta, out);
}

/* Every eligible pair through the pair query: hits into ref (count *n). */
static int brute(const world *w, int bytes, double delta, ttd_scene_ccd_hit *ref, size_t *n, size_t *pairs)
{
    *n = *pairs = 0;
    for (int i = 0; i < NB; ++i)
        for (int j = i + 1; j < NB; ++j) {
            if (!eligible(w, i, j))
                continue;
            ++*pairs;
            ttd_options o = ttd_default_options();
            o.solid = w->solid[i] && w->solid[j];
            double a[24], b[24];
            memcpy(a, w->p0[i], 12 * sizeof(double));
            memcpy(a + 12, w->p1[i], 12 * sizeof(double));
            memcpy(b, w->p0[j], 12 * sizeof(double));
            memcpy(b + 12, w->p1[j], 12 * sizeof(double));
            ttd_mesh_ccd_rigid_result r;
            const ttd_mesh *ma = w->m[bytes == 8][w->kind[i]], *mb = w->m[bytes == 8][w->kind[j]];
            if (bytes == 8) {
                ENSURE(ttd_mesh_ccd_rigid_d(&o, ma, a, mb, b, delta, &r) == TTD_OK);
            } else {
                float af[24], bf[24];
                for (int k = 0; k < 24; ++k) {
                    af[k] = (float)a[k];
                    bf[k] = (float)b[k];
                }
                ENSURE(ttd_mesh_ccd_rigid_f(&o, ma, af, mb, bf, delta, &r) == TTD_OK);
            }
            if (r.hit)
                ref[(*n)++] = (ttd_scene_ccd_hit){(uint32_t)i, (uint32_t)j, r.tri_a, r.tri_b, r.flags, r.steps,
                                                  r.toi, r.distance};
        }
    return 0;
}

static int same_hits(const ttd_scene_array *got, const ttd_scene_ccd_hit *ref, size_t n, const char *what)
{
    ENSURE_MSG(got->count == n, "%s: %zu hits, brute force %zu", what, got->count, n);
    const ttd_scene_ccd_hit *h = got->data;
    for (size_t k = 0; k < n; ++k)
        ENSURE_MSG(memcmp(&h[k], &ref[k], sizeof h[k]) == 0,
                   "%s: hit %zu: (%u, %u) toi %.17g vs brute (%u, %u) toi %.17g", what, k, h[k].i, h[k].j, h[k].toi,
                   ref[k].i, ref[k].j, ref[k].toi);
    return 0;
}

static int against_brute_at(int bytes)
{
    int total_hits = 0;
    for (int round = 0; round < 3; ++round) {
        world w;
        if (world_make(&w))
            return 1;
        ttd_scene *s = scene_of(&w, bytes);
        ENSURE(s != NULL);
        for (int d = 0; d < 2; ++d) {
            const double delta = d ? 0.1 : 0;
            ttd_scene_ccd_hit ref[NB * NB];
            size_t n, pairs;
            if (brute(&w, bytes, delta, ref, &n, &pairs))
                return 1;
            ttd_scene_array out[3] = {{0}, {0}, {0}};
            char what[64];
            for (int t = 0; t < 3; ++t) {
                ENSURE(scene_ccd(bytes, t + 1, s, &w, delta, &out[t]) == TTD_OK);
                snprintf(what, sizeof what, "%s round %d delta %g threads %d", bytes == 8 ? "double" : "float", round,
                         delta, t + 1);
                if (same_hits(&out[t], ref, n, what))
                    return 1;
            }
            ttd_scene_stats st;
            ENSURE(ttd_scene_get_stats(s, &st) == TTD_OK);
            printf("  %s: %zu eligible pairs, %llu candidates, %zu hit\n", what, pairs,
                   (unsigned long long)st.body_pairs, n);
            ENSURE(st.body_pairs < pairs && st.body_pairs >= n && st.results == n);
            ENSURE(n > 0 && n < pairs);
            total_hits += (int)n;
            for (int t = 0; t < 3; ++t)
                ttd_scene_array_free(&out[t]);
        }
        /* The scene is unchanged: its poses are still the t = 0 ones. */
        ttd_scene_array c = {0};
        ENSURE((bytes == 8 ? ttd_scene_collide_d(NULL, s, 0, &c) : ttd_scene_collide_f(NULL, s, 0, &c)) == TTD_OK);
        ttd_scene_array_free(&c);
        ttd_scene_destroy(s);
        world_free(&w);
    }
    return total_hits > 0 ? 0 : 1;
}
static int against_brute(void)
{
    return against_brute_at(8);
}
static int against_brute_float(void)
{
    return against_brute_at(4);
}

/* A small ball crossing a plate 0.1 thick in one step at 40 m/s and 60 Hz (0.67 m): no pose at
 * either end touches, the step does. */
static int fast_ball_through_plate(void)
{
    test_box plate;
    ENSURE(test_box_make(2, 2, 0.1, 1, &plate) == 0);
    ttd_gen_mesh ball;
    ENSURE(ttd_gen_icosphere(2, &ball) == 0);
    for (size_t i = 0; i < 3 * ball.nv; ++i)
        ball.verts[i] *= 0.05;
    ttd_mesh *mp = test_mesh_of(8, plate.v, plate.nv, plate.t, plate.nt);
    ttd_mesh *mb = test_mesh_of(8, ball.verts, ball.nv, ball.tris, ball.nt);
    ENSURE(mp && mb);
    ttd_scene *s;
    ENSURE(ttd_scene_create_d(&s) == TTD_OK);
    const double id[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    double p0[12], p1[24];
    memcpy(p0, id, sizeof id);
    p0[11] = 0.4;
    uint32_t a, b;
    ENSURE(ttd_scene_add_d(s, mp, id, &a) == TTD_OK && ttd_scene_add_d(s, mb, p0, &b) == TTD_OK);
    memcpy(p1, id, sizeof id);
    memcpy(p1 + 12, p0, sizeof p0);
    p1[12 + 11] = 0.4 - 40.0 / 60;
    ttd_scene_array c = {0}, out = {0};
    ENSURE(ttd_scene_collide_d(NULL, s, 0, &c) == TTD_OK && c.count == 0);
    ENSURE(ttd_scene_set_pose_d(s, b, p1 + 12) == TTD_OK);
    ENSURE(ttd_scene_collide_d(NULL, s, 0, &c) == TTD_OK && c.count == 0); /* tunnels */
    ENSURE(ttd_scene_set_pose_d(s, b, p0) == TTD_OK);
    ENSURE(ttd_scene_ccd_d(NULL, s, 2, p1, 0, &out) == TTD_OK);
    ENSURE(out.count == 1);
    const ttd_scene_ccd_hit *h = out.data;
    /* The plate's top is at z = 0.05 (the box is centred): the ball's lowest vertex reaches it
     * after 0.4 + zmin - 0.05 of the 0.667 travelled. */
    double zmin = 0;
    for (size_t i = 0; i < ball.nv; ++i)
        zmin = fmin(zmin, ball.verts[3 * i + 2]);
    const double exact = (0.4 + zmin - 0.05) / (40.0 / 60);
    ENSURE_MSG(h->i == a && h->j == b && h->toi <= exact + 1e-12 && h->toi > exact - 1e-6, "toi %.17g vs %.17g", h->toi,
               exact);
    printf("  ball at 40 m/s through a 0.1 plate: toi %.6f (the ball's lowest vertex reaches the plate at %.6f)\n",
           h->toi, exact);
    ttd_scene_array_free(&c);
    ttd_scene_array_free(&out);
    ttd_scene_destroy(s);
    ttd_mesh_destroy(mp);
    ttd_mesh_destroy(mb);
    test_box_free(&plate);
    ttd_gen_mesh_free(&ball);
    return 0;
}

/* A pendulum (a ball 2.5 from its body's origin) swung through a half turn about +z: its sweep
 * bulges 2.5 off the chord between its two places: the swept box must hold the arc (its bound
 * around the origin's segment does, and the bound around the chord widened by the sagitta;
 * with the first halved and the sagitta left out this test fails: checked). A small ball at the arc's middle is met before t = 0.5, one on the other side (the
 * way the other axis sign would swing) is not. */
static int pendulum_arc(void)
{
    ttd_gen_mesh g, small;
    ENSURE(ttd_gen_icosphere(1, &g) == 0 && ttd_gen_icosphere(1, &small) == 0);
    for (size_t i = 0; i < 3 * g.nv; ++i)
        g.verts[i] = 0.3 * g.verts[i] + (i % 3 == 0 ? 2.5 : 0);
    for (size_t i = 0; i < 3 * small.nv; ++i)
        small.verts[i] *= 0.1;
    ttd_mesh *mp = test_mesh_of(8, g.verts, g.nv, g.tris, g.nt), *ms = test_mesh_of(8, small.verts, small.nv, small.tris, small.nt);
    ENSURE(mp && ms);
    const double id[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    const double half[12] = {-1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1, 0};
    for (int side = 0; side < 2; ++side) {
        ttd_scene *s;
        ENSURE(ttd_scene_create_d(&s) == TTD_OK);
        double pb[12];
        memcpy(pb, id, sizeof id);
        pb[7] = side ? -2.5 : 2.5;
        uint32_t a, b;
        ENSURE(ttd_scene_add_d(s, mp, id, &a) == TTD_OK && ttd_scene_add_d(s, ms, pb, &b) == TTD_OK);
        double p1[24];
        memcpy(p1, half, sizeof half);
        memcpy(p1 + 12, pb, sizeof pb);
        ttd_scene_array out = {0};
        ENSURE(ttd_scene_ccd_d(NULL, s, 2, p1, 0, &out) == TTD_OK);
        const ttd_scene_ccd_hit *h = out.data;
        if (side == 0)
            ENSURE_MSG(out.count == 1 && h->toi > 0.3 && h->toi < 0.5, "count %zu", out.count);
        else
            ENSURE(out.count == 0);
        ttd_scene_array_free(&out);
        ttd_scene_destroy(s);
    }
    ttd_mesh_destroy(mp);
    ttd_mesh_destroy(ms);
    ttd_gen_mesh_free(&g);
    ttd_gen_mesh_free(&small);
    return 0;
}

static int checks(void)
{
    world w;
    if (world_make(&w))
        return 1;
    ttd_scene *s = scene_of(&w, 8);
    ENSURE(s != NULL);
    ttd_scene_array out = {0};
    const double *p1 = &w.p1[0][0];
    ENSURE(ttd_scene_ccd_d(NULL, NULL, NB, p1, 0, &out) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_scene_ccd_d(NULL, s, NB, NULL, 0, &out) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_scene_ccd_d(NULL, s, NB, p1, 0, NULL) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_scene_ccd_d(NULL, s, NB - 1, p1, 0, &out) == TTD_ERR_INDEX_OUT_OF_RANGE);
    ENSURE(ttd_scene_ccd_d(NULL, s, NB, p1, -1, &out) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_scene_ccd_d(NULL, s, NB, p1, NAN, &out) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_scene_ccd_d(NULL, s, NB, p1, INFINITY, &out) == TTD_ERR_BAD_OPTIONS);
    float pf[NB * 12] = {0};
    ENSURE(ttd_scene_ccd_f(NULL, s, NB, pf, 0, &out) == TTD_ERR_PRECISION_MISMATCH);
    double bad[NB][12];
    memcpy(bad, w.p1, sizeof bad);
    bad[3][5] = NAN;
    ENSURE(ttd_scene_ccd_d(NULL, s, NB, &bad[0][0], 0, &out) == TTD_ERR_BAD_POSE && out.count == 0);
    memcpy(bad, w.p1, sizeof bad);
    bad[4][0] = 2; /* not a rotation */
    ENSURE(ttd_scene_ccd_d(NULL, s, NB, &bad[0][0], 0, &out) == TTD_ERR_BAD_POSE);
    memcpy(bad, w.p1, sizeof bad);
    bad[9][0] = NAN; /* the removed body's entry is ignored */
    ENSURE(ttd_scene_ccd_d(NULL, s, NB, &bad[0][0], 0, &out) == TTD_OK);
    bad[5][3] = 1e300;
    ENSURE(ttd_scene_ccd_d(NULL, s, NB, &bad[0][0], 0, &out) == TTD_ERR_COORDINATE_RANGE && out.count == 0);
    ttd_scene_array_free(&out);
    ttd_scene_destroy(s);
    /* An empty scene: nothing, no error. */
    ENSURE(ttd_scene_create_d(&s) == TTD_OK);
    ENSURE(ttd_scene_ccd_d(NULL, s, 0, p1, 0, &out) == TTD_OK && out.count == 0);
    ttd_scene_destroy(s);
    world_free(&w);
    return 0;
}

/* Two overlapping cubes, each under the pose diag(1 + 4.9e-7) at both times (within the pose
 * check's 1e-6, so the scene takes it): one hit at t = 0, double and float. The old pair query
 * passed the relative pose R^T R (defect about 2e-6) to the checked mesh distance and the whole
 * query failed with TTD_ERR_BAD_POSE (checked). */
static int near_rotations(void)
{
    ttd_gen_mesh cube;
    ENSURE(ttd_gen_mesh_cube(&cube) == 0);
    for (int bytes = 8; bytes >= 4; bytes -= 4) {
        ttd_mesh *m = test_mesh_of(bytes, cube.verts, cube.nv, cube.tris, cube.nt);
        ENSURE(m);
        double p[24] = {0};
        float pf[24];
        for (int k = 0; k < 2; ++k)
            for (int i = 0; i < 3; ++i)
                p[12 * k + 5 * i] = 1 + 4.9e-7;
        p[12 + 3] = 0.5; /* the second body half a cube along x */
        for (int i = 0; i < 24; ++i)
            pf[i] = (float)p[i];
        ttd_scene *s;
        uint32_t a, b;
        ENSURE((bytes == 8 ? ttd_scene_create_d(&s) : ttd_scene_create_f(&s)) == TTD_OK);
        ENSURE(bytes == 8 ? ttd_scene_add_d(s, m, p, &a) == TTD_OK && ttd_scene_add_d(s, m, p + 12, &b) == TTD_OK
                          : ttd_scene_add_f(s, m, pf, &a) == TTD_OK && ttd_scene_add_f(s, m, pf + 12, &b) == TTD_OK);
        ttd_scene_array out = {0};
        const ttd_status st = bytes == 8 ? ttd_scene_ccd_d(NULL, s, 2, p, 0, &out) : ttd_scene_ccd_f(NULL, s, 2, pf, 0, &out);
        ENSURE_MSG(st == TTD_OK && out.count == 1, "bytes %d: status %d count %zu", bytes, (int)st, out.count);
        const ttd_scene_ccd_hit *h = out.data;
        ENSURE(h->i == a && h->j == b && h->toi == 0);
        ttd_scene_array_free(&out);
        ttd_scene_destroy(s);
        ttd_mesh_destroy(m);
    }
    ttd_gen_mesh_free(&cube);
    return 0;
}

/* Two parallel needle triangles (size 1e-7 / 1e-3) at x = 1000, a gap g apart (1e-6 in double, 0.05 in float:
 * below the pair's tolerance, about 1.9e-6 and 0.12), one sliding along x: the pair query answers
 * a hit at t = 0 (within delta + tolerance), so the scene must list the pair too. Its broad phase
 * kept only boxes within delta and gave 0 hits (checked). Held still, the pair answers no hit
 * (the upper bound handed to the distance query, delta + mu, cuts the band off): the scene too. */
static int tolerance_band(void)
{
    for (int bytes = 8; bytes >= 4; bytes -= 4) {
        const double g = bytes == 8 ? 1e-6 : 0.05;
        const double L = bytes == 8 ? 1e-7 : 1e-3; /* the needles' size: their swept boxes stay thin in y */
        const double va[9] = {1000, 0, 0, 1000 + L, 0, 0, 1000, 0, L};
        const double vb[9] = {1000, g, 0, 1000 + L, g, 0, 1000, g, L};
        const uint32_t tri[3] = {0, 1, 2};
        ttd_mesh *a = test_mesh_of(bytes, va, 3, tri, 1), *b = test_mesh_of(bytes, vb, 3, tri, 1);
        ENSURE(a && b);
        for (int still = 0; still < 2; ++still) {
            double p[24] = {0};
            float pf[24];
            for (int k = 0; k < 2; ++k)
                for (int i = 0; i < 3; ++i)
                    p[12 * k + 5 * i] = 1;
            double q[24];
            memcpy(q, p, sizeof q);
            q[12 + 3] = still ? 0 : 0.5; /* b's second pose: half a unit along x */
            ttd_mesh_ccd_rigid_result r;
            float qf[24];
            for (int i = 0; i < 24; ++i) {
                pf[i] = (float)p[i];
                qf[i] = (float)q[i];
            }
            ENSURE((bytes == 8 ? ttd_mesh_ccd_rigid_d(NULL, a, p, b, q, 0, &r) : ttd_mesh_ccd_rigid_f(NULL, a, pf, b, qf, 0, &r)) ==
                   TTD_OK);
            ENSURE_MSG(r.hit == !still && g < r.tolerance, "bytes %d still %d: hit %d tolerance %g", bytes, still, r.hit,
                       r.tolerance);
            ttd_scene *s;
            uint32_t ia, ib;
            ENSURE((bytes == 8 ? ttd_scene_create_d(&s) : ttd_scene_create_f(&s)) == TTD_OK);
            ENSURE(bytes == 8 ? ttd_scene_add_d(s, a, p, &ia) == TTD_OK && ttd_scene_add_d(s, b, q, &ib) == TTD_OK
                              : ttd_scene_add_f(s, a, pf, &ia) == TTD_OK && ttd_scene_add_f(s, b, qf, &ib) == TTD_OK);
            double t1[24];
            memcpy(t1, p, 12 * sizeof *t1);
            memcpy(t1 + 12, q + 12, 12 * sizeof *t1);
            float t1f[24];
            for (int i = 0; i < 24; ++i)
                t1f[i] = (float)t1[i];
            ttd_scene_array out = {0};
            ENSURE((bytes == 8 ? ttd_scene_ccd_d(NULL, s, 2, t1, 0, &out) : ttd_scene_ccd_f(NULL, s, 2, t1f, 0, &out)) ==
                   TTD_OK);
            ENSURE_MSG(out.count == (size_t)r.hit, "bytes %d still %d: scene %zu hits, pair query %d", bytes, still,
                       out.count, r.hit);
            if (r.hit) {
                const ttd_scene_ccd_hit *h = out.data;
                ENSURE(h->i == ia && h->j == ib && h->toi == r.toi && h->distance == r.distance);
            }
            ttd_scene_array_free(&out);
            ttd_scene_destroy(s);
        }
        ttd_mesh_destroy(a);
        ttd_mesh_destroy(b);
    }
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(checks);
    RUN_TEST(fast_ball_through_plate);
    RUN_TEST(pendulum_arc);
    RUN_TEST(against_brute);
    RUN_TEST(against_brute_float);
    RUN_TEST(near_rotations);
    RUN_TEST(tolerance_band);
    TEST_MAIN_END();
}
