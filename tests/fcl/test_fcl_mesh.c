/* SPDX-License-Identifier: MIT */
/* ttd_fcl_mesh_bench (bench/fcl/) through its C link (bench/fcl_mesh_link.c) against brute
 * force: for an icosphere and a torus of a few hundred triangles each, under random poses
 * (far, near and overlapping), every triangle pair's distance is computed with ttd's exact
 * method, independently of FCL. FCL's minimum distance must equal the minimum over all pairs,
 * its triangle ids must realise it and its points lie on those triangles; its collision answer
 * must agree with "some pair intersects"; its pairs within a margin must be the brute-force
 * set. Hostile workload files must be refused with a message naming the problem. Built and
 * run by CTest only when FCL is found; the program's path is the first argument.
 * The meshes are made here, so that the test does not depend on other mesh generators. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fcl_mesh_link.h"
#include "pairs.h"
#include "ttd/ttd.h"

/* The harness's filter is the second argument here: the first is the program. */
#include "test_macros.h"

static const char *program;

/* ---- meshes ------------------------------------------------------------------------------- */

typedef struct mesh {
    double *v;
    size_t nv;
    uint32_t *t;
    size_t nt;
    double center[3];
    double radius; /* every vertex within this of center */
} mesh;

static void mesh_free(mesh *m)
{
    free(m->v);
    free(m->t);
    memset(m, 0, sizeof *m);
}

static void finish_mesh(mesh *m, const double c[3])
{
    m->radius = 0.0;
    for (size_t i = 0; i < m->nv; ++i) {
        double r2 = 0.0;
        for (int k = 0; k < 3; ++k) {
            m->v[3 * i + k] += c[k];
            r2 += (m->v[3 * i + k] - c[k]) * (m->v[3 * i + k] - c[k]);
        }
        m->radius = fmax(m->radius, sqrt(r2));
    }
    memcpy(m->center, c, sizeof m->center);
}

/* Midpoint of edge (a, b), made once: the edge's key is looked up in an open-addressing table. */
typedef struct edge_table {
    uint64_t *key;
    uint32_t *mid;
    size_t mask;
} edge_table;

static uint32_t midpoint(edge_table *e, mesh *m, uint32_t a, uint32_t b, double r)
{
    uint64_t key = a < b ? ((uint64_t)a << 32 | b) : ((uint64_t)b << 32 | a);
    size_t h = (size_t)(key * UINT64_C(0x9E3779B97F4A7C15) >> 20) & e->mask;
    while (e->key[h] != UINT64_MAX && e->key[h] != key)
        h = (h + 1) & e->mask;
    if (e->key[h] == key)
        return e->mid[h];
    double p[3], n = 0.0;
    for (int k = 0; k < 3; ++k) {
        p[k] = 0.5 * (m->v[3 * a + k] + m->v[3 * b + k]);
        n += p[k] * p[k];
    }
    n = sqrt(n);
    uint32_t id = (uint32_t)m->nv++;
    for (int k = 0; k < 3; ++k)
        m->v[3 * id + k] = r * p[k] / n;
    e->key[h] = key;
    e->mid[h] = id;
    return id;
}

/* Icosahedron of circumradius r about c, each triangle split into 4 (vertices pushed out to
 * the sphere) `levels` times: 20 * 4^levels triangles. */
static mesh icosphere(int levels, double r, const double c[3])
{
    const double g = (1.0 + sqrt(5.0)) / 2.0;
    const double base[12][3] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                                {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    const uint32_t faces[20][3] = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                   {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                                   {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    size_t nt = 20, nv_max = 12;
    for (int l = 0; l < levels; ++l) {
        nv_max += 3 * nt / 2;
        nt *= 4;
    }
    mesh m = {0};
    m.v = malloc(3 * nv_max * sizeof *m.v);
    m.t = malloc(3 * nt * sizeof *m.t);
    uint32_t *tmp = malloc(3 * nt * sizeof *tmp);
    if (!m.v || !m.t || !tmp)
        abort();
    double s = r / sqrt(1.0 + g * g);
    for (int i = 0; i < 12; ++i)
        for (int k = 0; k < 3; ++k)
            m.v[3 * i + k] = s * base[i][k];
    m.nv = 12;
    memcpy(m.t, faces, sizeof faces);
    m.nt = 20;
    for (int l = 0; l < levels; ++l) {
        edge_table e;
        e.mask = 1;
        while (e.mask < 4 * m.nt)
            e.mask <<= 1;
        e.key = malloc(e.mask * sizeof *e.key);
        e.mid = malloc(e.mask * sizeof *e.mid);
        if (!e.key || !e.mid)
            abort();
        memset(e.key, 0xff, e.mask * sizeof *e.key);
        e.mask -= 1;
        for (size_t i = 0; i < m.nt; ++i) {
            uint32_t a = m.t[3 * i], b = m.t[3 * i + 1], c3 = m.t[3 * i + 2];
            uint32_t ab = midpoint(&e, &m, a, b, r), bc = midpoint(&e, &m, b, c3, r), ca = midpoint(&e, &m, c3, a, r);
            const uint32_t quad[12] = {a, ab, ca, b, bc, ab, c3, ca, bc, ab, bc, ca};
            memcpy(tmp + 12 * i, quad, sizeof quad);
        }
        m.nt *= 4;
        memcpy(m.t, tmp, 3 * m.nt * sizeof *m.t);
        free(e.key);
        free(e.mid);
    }
    free(tmp);
    finish_mesh(&m, c);
    return m;
}

/* Torus about c in the xy plane: tube radius r around a circle of radius R, nu x nv quads. */
static mesh torus(int nu, int nvv, double R, double r, const double c[3])
{
    mesh m = {0};
    m.nv = (size_t)nu * (size_t)nvv;
    m.nt = 2 * m.nv;
    m.v = malloc(3 * m.nv * sizeof *m.v);
    m.t = malloc(3 * m.nt * sizeof *m.t);
    if (!m.v || !m.t)
        abort();
    const double two_pi = 6.283185307179586;
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nvv; ++j) {
            double u = two_pi * i / nu, w = two_pi * j / nvv;
            double *p = m.v + 3 * ((size_t)i * nvv + j);
            p[0] = (R + r * cos(w)) * cos(u);
            p[1] = (R + r * cos(w)) * sin(u);
            p[2] = r * sin(w);
        }
    size_t k = 0;
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nvv; ++j) {
            uint32_t a = (uint32_t)(i * nvv + j), b = (uint32_t)(((i + 1) % nu) * nvv + j);
            uint32_t c2 = (uint32_t)(((i + 1) % nu) * nvv + (j + 1) % nvv), d = (uint32_t)(i * nvv + (j + 1) % nvv);
            const uint32_t two[6] = {a, b, c2, a, c2, d};
            memcpy(m.t + 6 * k++, two, sizeof two);
        }
    finish_mesh(&m, c);
    return m;
}

/* ---- brute force with ttd ------------------------------------------------------------------ */

typedef struct scene {
    mesh a, b;
    double size;      /* diagonal of the bounding box of both meshes' extents: the length scale */
    double tol;       /* 1e-12 of size */
    uint32_t *pairs;  /* every (i, j), i-major */
    double *bt;       /* B's vertices under a pose */
    double *dist;     /* every pair's distance under that pose */
} scene;

static bench_fcl_mesh as_fcl(const mesh *m)
{
    bench_fcl_mesh f = {m->v, m->nv, m->t, m->nt};
    return f;
}

static void apply_pose(const double pose[12], const double *x, double *y)
{
    for (int r = 0; r < 3; ++r)
        y[r] = pose[4 * r] * x[0] + pose[4 * r + 1] * x[1] + pose[4 * r + 2] * x[2] + pose[4 * r + 3];
}

/* Every pair's distance under the pose into s->dist; returns the minimum and its pair. */
static double brute_force(scene *s, const double pose[12], size_t *arg)
{
    for (size_t i = 0; i < s->b.nv; ++i)
        apply_pose(pose, s->b.v + 3 * i, s->bt + 3 * i);
    size_t n = s->a.nt * s->b.nt;
    ttd_status st = ttd_mesh_batch_d(NULL, s->a.v, s->a.nv, s->a.t, s->a.nt, s->bt, s->b.nv, s->b.t, s->b.nt, n,
                                     s->pairs, s->dist, NULL);
    if (st != TTD_OK) {
        fprintf(stderr, "ttd_mesh_batch_d: %s\n", ttd_status_string(st));
        abort();
    }
    size_t best = 0;
    for (size_t i = 1; i < n; ++i)
        if (s->dist[i] < s->dist[best])
            best = i;
    if (arg)
        *arg = best;
    return s->dist[best];
}

static void triangle_of(const double *v, const uint32_t *t, size_t i, double out[9])
{
    for (int k = 0; k < 3; ++k)
        memcpy(out + 3 * k, v + 3 * t[3 * i + k], 3 * sizeof *out);
}

/* Distance from point p to triangle i of a mesh (vertices v), with ttd's exact method on the
 * point as a degenerate triangle. */
static double point_triangle(const double *v, const uint32_t *t, size_t i, const double p[3])
{
    double tri[9], pt[9];
    triangle_of(v, t, i, tri);
    for (int k = 0; k < 3; ++k)
        memcpy(pt + 3 * k, p, 3 * sizeof *pt);
    ttd_result_d r;
    if (ttd_distance_d(NULL, tri, pt, &r) != TTD_OK)
        return (double)INFINITY;
    return r.distance;
}

static scene make_scene(mesh a, mesh b)
{
    scene s = {0};
    s.a = a;
    s.b = b;
    s.size = 2.0 * sqrt(3.0) * fmax(a.radius, b.radius);
    s.tol = 1e-12 * s.size;
    size_t n = a.nt * b.nt;
    s.pairs = malloc(2 * n * sizeof *s.pairs);
    s.dist = malloc(n * sizeof *s.dist);
    s.bt = malloc(3 * b.nv * sizeof *s.bt);
    if (!s.pairs || !s.dist || !s.bt)
        abort();
    for (size_t i = 0; i < a.nt; ++i)
        for (size_t j = 0; j < b.nt; ++j) {
            s.pairs[2 * (i * b.nt + j)] = (uint32_t)i;
            s.pairs[2 * (i * b.nt + j) + 1] = (uint32_t)j;
        }
    return s;
}

static void scene_free(scene *s)
{
    mesh_free(&s->a);
    mesh_free(&s->b);
    free(s->pairs);
    free(s->dist);
    free(s->bt);
}

/* ---- poses ------------------------------------------------------------------------------------ */

/* Pose with rotation R (row-major) that puts B's centre at distance `gap` from A's centre along
 * the unit direction u. */
static void pose_at(const scene *s, const double R[9], const double u[3], double gap, double pose[12])
{
    for (int r = 0; r < 3; ++r) {
        double rc = R[3 * r] * s->b.center[0] + R[3 * r + 1] * s->b.center[1] + R[3 * r + 2] * s->b.center[2];
        pose[4 * r] = R[3 * r];
        pose[4 * r + 1] = R[3 * r + 1];
        pose[4 * r + 2] = R[3 * r + 2];
        pose[4 * r + 3] = s->a.center[r] + gap * u[r] - rc;
    }
}

/* kinds: 0 far, 1 near (brute-force distance near 1% of size, by bisection), 2 overlapping. */
static void make_poses(scene *s, uint64_t seed, int per_kind, double *poses)
{
    ttd_gen_rng rng = ttd_gen_rng_make(seed, 0);
    double reach = s->a.radius + s->b.radius;
    for (int kind = 0; kind < 3; ++kind)
        for (int i = 0; i < per_kind; ++i) {
            double R[9], u[3], n = 0.0, *pose = poses + 12 * (kind * per_kind + i);
            ttd_gen_rng_rotation(&rng, R);
            do {
                n = 0.0;
                for (int k = 0; k < 3; ++k) {
                    u[k] = 2.0 * ttd_gen_rng_uniform(&rng) - 1.0;
                    n += u[k] * u[k];
                }
            } while (n > 1.0 || n < 1e-6);
            for (int k = 0; k < 3; ++k)
                u[k] /= sqrt(n);
            double far = reach * (1.1 + ttd_gen_rng_uniform(&rng));
            if (kind == 0) {
                pose_at(s, R, u, far, pose);
            } else if (kind == 2) {
                pose_at(s, R, u, 0.3 * ttd_gen_rng_uniform(&rng) * fmin(s->a.radius, s->b.radius), pose);
            } else {
                double lo = 0.0, hi = far, target = 0.01 * s->size;
                pose_at(s, R, u, lo, pose);
                if (brute_force(s, pose, NULL) <= target) {
                    for (int step = 0; step < 12; ++step) {
                        double mid = 0.5 * (lo + hi);
                        pose_at(s, R, u, mid, pose);
                        if (brute_force(s, pose, NULL) <= target)
                            lo = mid;
                        else
                            hi = mid;
                    }
                    pose_at(s, R, u, hi, pose);
                }
            }
        }
}

/* ---- the checks --------------------------------------------------------------------------------- */

typedef struct summary {
    int intersecting, separated;
    double max_d_err, max_point_err, max_gap_at_contact;
    uint64_t pairs, boundary;
    double fcl_ms[3];
} summary;

static int check_scene(scene *s, uint64_t seed, const char *name)
{
    enum { PER_KIND = 4, K = 3 * PER_KIND };
    double poses[12 * K];
    make_poses(s, seed, PER_KIND, poses);
    const double margin = 0.02 * s->size;
    bench_fcl_mesh_job job = {as_fcl(&s->a), as_fcl(&s->b), poses, K, BENCH_FCL_MESH_DISTANCE, 1, 0.0};
    bench_fcl_mesh_result q0, q1, q1m, q2;
    int rc0 = bench_fcl_mesh_run(program, &job, 0, &q0);
    ENSURE_MSG(rc0 == BENCH_FCL_MESH_OK, "%s", q0.error);
    job.query = BENCH_FCL_MESH_COLLIDE;
    int rc1 = bench_fcl_mesh_run(program, &job, 0, &q1);
    ENSURE_MSG(rc1 == BENCH_FCL_MESH_OK, "%s", q1.error);
    job.margin = margin;
    int rc1m = bench_fcl_mesh_run(program, &job, 0, &q1m);
    ENSURE_MSG(rc1m == BENCH_FCL_MESH_OK, "%s", q1m.error);
    job.query = BENCH_FCL_MESH_PAIRS;
    int rc2 = bench_fcl_mesh_run(program, &job, 1, &q2);
    ENSURE_MSG(rc2 == BENCH_FCL_MESH_OK, "%s", q2.error);
    ENSURE(q0.nposes == K && q1.nposes == K && q2.nposes == K);
    ENSURE(q0.build_ms[0] >= 0.0 && q0.build_ms[1] >= 0.0);

    size_t n = s->a.nt * s->b.nt;
    int32_t *in_fcl = malloc(n * sizeof *in_fcl);
    ENSURE(in_fcl);
    summary sum = {0};
    for (size_t k = 0; k < K; ++k) {
        const double *pose = poses + 12 * k;
        size_t arg;
        double d = brute_force(s, pose, &arg);
        const bench_fcl_mesh_pose *r0 = &q0.poses[k], *r1 = &q1.poses[k], *r1m = &q1m.poses[k], *r2 = &q2.poses[k];

        /* Query 0: the minimum, realised by the reported triangles, at the reported points. */
        ENSURE_MSG(fabs(r0->distance - d) <= s->tol, "%s pose %zu: FCL %.17g, brute force %.17g (pair %zu %zu)", name,
                   k, r0->distance, d, arg / s->b.nt, arg % s->b.nt);
        ENSURE(r0->ia >= 0 && (size_t)r0->ia < s->a.nt && r0->ib >= 0 && (size_t)r0->ib < s->b.nt);
        double d_ids = s->dist[(size_t)r0->ia * s->b.nt + (size_t)r0->ib];
        ENSURE_MSG(fabs(d_ids - d) <= s->tol, "%s pose %zu: pair (%lld, %lld) is %.17g apart, the minimum %.17g", name,
                   k, (long long)r0->ia, (long long)r0->ib, d_ids, d);
        sum.max_d_err = fmax(sum.max_d_err, fabs(r0->distance - d));
        double on_a = point_triangle(s->a.v, s->a.t, (size_t)r0->ia, r0->p);
        double on_b = point_triangle(s->bt, s->b.t, (size_t)r0->ib, r0->q);
        double gap = sqrt((r0->p[0] - r0->q[0]) * (r0->p[0] - r0->q[0]) + (r0->p[1] - r0->q[1]) * (r0->p[1] - r0->q[1]) +
                          (r0->p[2] - r0->q[2]) * (r0->p[2] - r0->q[2]));
        ENSURE_MSG(on_a <= s->tol && on_b <= s->tol, "%s pose %zu: p is %.3g from triangle %lld of A, q %.3g from "
                   "triangle %lld of B", name, k, on_a, (long long)r0->ia, on_b, (long long)r0->ib);
        sum.max_point_err = fmax(sum.max_point_err, fmax(on_a, on_b));
        if (d > s->tol) {
            ENSURE_MSG(fabs(gap - d) <= s->tol, "%s pose %zu: |p - q| = %.17g, distance %.17g", name, k, gap, d);
            sum.max_point_err = fmax(sum.max_point_err, fabs(gap - d));
        } else {
            /* Known FCL behaviour: at a contact the two points need not coincide. */
            sum.max_gap_at_contact = fmax(sum.max_gap_at_contact, gap);
        }
        ENSURE(r0->bv_tests >= 1 && r0->leaf_tests >= 1);

        /* Query 1: collision iff some pair intersects; the contact's triangles intersect. A
         * distance within rounding of 0 but not 0 is a touch either answer may call. */
        if (d > s->tol) {
            ++sum.separated;
            ENSURE_MSG(r1->collide == 0, "%s pose %zu: FCL collides, the meshes are %.3g apart", name, k, d);
            ENSURE(r1->ia == -1 && r1->ib == -1);
        } else if (d == 0.0) {
            ++sum.intersecting;
            ENSURE_MSG(r1->collide == 1, "%s pose %zu: FCL does not collide, pair %zu %zu intersects", name, k,
                       arg / s->b.nt, arg % s->b.nt);
            ENSURE(r1->ia >= 0 && (size_t)r1->ia < s->a.nt && r1->ib >= 0 && (size_t)r1->ib < s->b.nt);
            double dc = s->dist[(size_t)r1->ia * s->b.nt + (size_t)r1->ib];
            ENSURE_MSG(dc <= s->tol, "%s pose %zu: FCL's contact pair (%lld, %lld) is %.3g apart", name, k,
                       (long long)r1->ia, (long long)r1->ib, dc);
        }
        ENSURE(r1->margin_supported == 1);
        /* With a margin FCL 0.7 answers plain collision and says so. */
        ENSURE(r1m->margin_supported == 0 && r1m->collide == r1->collide);

        /* Query 2: the set of pairs within the margin, and FCL's distance of each. */
        for (size_t i = 0; i < n; ++i)
            in_fcl[i] = -1;
        ENSURE(r2->pairs == q2.pair_start[k + 1] - q2.pair_start[k]);
        for (size_t i = q2.pair_start[k]; i < q2.pair_start[k + 1]; ++i) {
            const bench_fcl_mesh_pair *p = &q2.pairs[i];
            ENSURE(p->ia < s->a.nt && p->ib < s->b.nt);
            size_t at = (size_t)p->ia * s->b.nt + p->ib;
            ENSURE_MSG(in_fcl[at] < 0, "%s pose %zu: pair (%u, %u) reported twice", name, k, p->ia, p->ib);
            in_fcl[at] = (int32_t)i;
            ENSURE_MSG(fabs(p->d - s->dist[at]) <= s->tol, "%s pose %zu: pair (%u, %u): FCL %.17g, ttd %.17g", name,
                       k, p->ia, p->ib, p->d, s->dist[at]);
            sum.max_d_err = fmax(sum.max_d_err, fabs(p->d - s->dist[at]));
        }
        for (size_t i = 0; i < n; ++i) {
            int brute_in = s->dist[i] <= margin, fcl_in = in_fcl[i] >= 0;
            if (brute_in != fcl_in) {
                ENSURE_MSG(fabs(s->dist[i] - margin) <= s->tol, "%s pose %zu: pair (%zu, %zu) at %.17g: brute force "
                           "%s, FCL %s (margin %.17g)", name, k, i / s->b.nt, i % s->b.nt, s->dist[i],
                           brute_in ? "in" : "out", fcl_in ? "in" : "out", margin);
                ++sum.boundary;
            }
        }
        ENSURE(r2->leaf_tests >= r2->pairs && r2->bv_tests >= 1);
        sum.pairs += r2->pairs;
        sum.fcl_ms[0] += r0->median_ms;
        sum.fcl_ms[1] += r1->median_ms;
        sum.fcl_ms[2] += r2->median_ms;
    }
    free(in_fcl);
    printf("  %s: %zu x %zu triangles, %d poses (%d separated, %d intersecting): max |d - brute| %.3g, points off "
           "%.3g (tolerance %.3g); at contacts |p - q| up to %.3g of size; %llu pairs within %.3g (%llu on the "
           "boundary); FCL ms per pose (not asserted): distance %.3g, collide %.3g, pairs %.3g\n",
           name, s->a.nt, s->b.nt, K, sum.separated, sum.intersecting, sum.max_d_err, sum.max_point_err, s->tol,
           sum.max_gap_at_contact / s->size, (unsigned long long)sum.pairs, margin, (unsigned long long)sum.boundary,
           sum.fcl_ms[0] / K, sum.fcl_ms[1] / K, sum.fcl_ms[2] / K);
    /* The poses must exercise both answers and the margin query, or the test proves little. */
    ENSURE(sum.separated >= PER_KIND && sum.intersecting >= 1 && sum.pairs > 0);
    bench_fcl_mesh_result_free(&q0);
    bench_fcl_mesh_result_free(&q1);
    bench_fcl_mesh_result_free(&q1m);
    bench_fcl_mesh_result_free(&q2);
    return 0;
}

static int sphere_against_torus(void)
{
    const double ca[3] = {0.3, -0.2, 0.1}, cb[3] = {-1.0, 2.0, 0.5};
    scene s = make_scene(icosphere(2, 1.0, ca), torus(24, 12, 1.0, 0.35, cb));
    int rc = check_scene(&s, 11, "icosphere-torus");
    scene_free(&s);
    return rc;
}

static int torus_against_torus(void)
{
    const double ca[3] = {0.0, 0.0, 0.0}, cb[3] = {5.0, 5.0, 5.0};
    scene s = make_scene(torus(20, 10, 1.0, 0.3, ca), torus(16, 12, 0.8, 0.25, cb));
    int rc = check_scene(&s, 12, "torus-torus");
    scene_free(&s);
    return rc;
}

/* ---- hostile input --------------------------------------------------------------------------- */

typedef struct file_bytes {
    unsigned char *b;
    size_t n;
} file_bytes;

static int load(const char *path, file_bytes *f)
{
    FILE *in = fopen(path, "rb");
    if (!in)
        return -1;
    fseek(in, 0, SEEK_END);
    long n = ftell(in);
    fseek(in, 0, SEEK_SET);
    f->b = malloc((size_t)n + 16);
    f->n = (size_t)n;
    int ok = f->b && fread(f->b, 1, f->n, in) == f->n;
    fclose(in);
    return ok ? 0 : -1;
}

static int save(const char *path, const unsigned char *b, size_t n)
{
    FILE *out = fopen(path, "wb");
    if (!out)
        return -1;
    int ok = fwrite(b, 1, n, out) == n;
    return fclose(out) == 0 && ok ? 0 : -1;
}

static void put_le(unsigned char *p, uint64_t x, int bytes)
{
    for (int i = 0; i < bytes; ++i)
        p[i] = (unsigned char)(x >> (8 * i));
}

static void put_double(unsigned char *p, double x)
{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    put_le(p, bits, 8);
}

/* The program must refuse a corrupted file with an error that contains `expect`. */
static int refused(const char *path, const file_bytes *good, size_t len, size_t at, const unsigned char *patch,
                   size_t patch_len, const char *expect)
{
    unsigned char *b = malloc(len + 1);
    ENSURE(b);
    memcpy(b, good->b, len < good->n ? len : good->n);
    if (len > good->n)
        memset(b + good->n, 0, len - good->n);
    if (patch)
        memcpy(b + at, patch, patch_len);
    ENSURE(save(path, b, len) == 0);
    free(b);
    bench_fcl_mesh_result r;
    int rc = bench_fcl_mesh_run_file(program, path, BENCH_FCL_MESH_DISTANCE, 1, 0, &r);
    ENSURE_MSG(rc == BENCH_FCL_MESH_ERROR, "a file that should fail with \"%s\" was accepted", expect);
    ENSURE_MSG(strstr(r.error, expect) != NULL, "error \"%s\" does not say \"%s\"", r.error, expect);
    ENSURE(r.poses == NULL && r.nposes == 0);
    return 0;
}

static int hostile_files(void)
{
    /* A single triangle each and one pose: offsets are easy to compute. */
    const double va[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, vb[9] = {0, 0, 0, 1, 0, 0, 0, 0, 1};
    const uint32_t t[3] = {0, 1, 2};
    const double pose[12] = {1, 0, 0, 0.1, 0, 1, 0, 0.2, 0, 0, 1, 2.0};
    bench_fcl_mesh_job job = {{va, 3, t, 1}, {vb, 3, t, 1}, pose, 1, BENCH_FCL_MESH_DISTANCE, 1, 0.0};
    char path[] = "/tmp/ttd-test-fcl-mesh-XXXXXX";
    int fd = mkstemp(path);
    ENSURE(fd >= 0);
    close(fd);
    char err[512];
    ENSURE(bench_fcl_mesh_write_job(path, &job, err, sizeof err) == BENCH_FCL_MESH_OK);
    file_bytes good;
    ENSURE(load(path, &good) == 0);
    /* magic 8, query 4, repetitions 4, margin 8, then A: counts at 24, 32; vertices at 40. */
    const size_t a_tris = 40 + 72, b_counts = a_tris + 12, pose_count = b_counts + 16 + 72 + 12;
    ENSURE(good.n == pose_count + 8 + 96);

    /* The good file runs, and gives the plain answer: B's corner (0.1, 0.2, 2) is 2 above A. */
    bench_fcl_mesh_result r;
    ENSURE(bench_fcl_mesh_run_file(program, path, BENCH_FCL_MESH_DISTANCE, 1, 0, &r) == BENCH_FCL_MESH_OK);
    ENSURE_NEAR(r.poses[0].distance, 2.0, 1e-15);
    bench_fcl_mesh_result_free(&r);
    /* query 3, FCL's refit of A to B's vertices (the same triangles) and back: one row of times,
     * B not built */
    bench_fcl_mesh_job refit = job;
    refit.query = BENCH_FCL_MESH_REFIT;
    refit.repetitions = 3;
    ENSURE(bench_fcl_mesh_run(program, &refit, 0, &r) == BENCH_FCL_MESH_OK);
    ENSURE(r.nposes == 1 && r.poses[0].median_ms >= 0 && r.poses[0].min_ms <= r.poses[0].median_ms && r.build_ms[1] == 0);
    bench_fcl_mesh_result_free(&r);
    const uint32_t t2[3] = {0, 2, 1}; /* B's triangles not A's: no refit */
    refit.b.triangles = t2;
    ENSURE(bench_fcl_mesh_run(program, &refit, 0, &r) == BENCH_FCL_MESH_ERROR);
    ENSURE_MSG(strstr(r.error, "B must hold A's triangles") != NULL, "error \"%s\"", r.error);
    bench_fcl_mesh_result_free(&r);

    unsigned char u32[4], u64[8], f64[8];
    int failed = 0;
    failed |= refused(path, &good, 0, 0, NULL, 0, "truncated");
    failed |= refused(path, &good, 5, 0, NULL, 0, "truncated");
    failed |= refused(path, &good, good.n, 0, (const unsigned char *)"TTDMESH2", 8, "magic");
    put_le(u32, 4, 4);
    failed |= refused(path, &good, good.n, 8, u32, 4, "query 4 unknown");
    put_le(u32, 0, 4);
    failed |= refused(path, &good, good.n, 12, u32, 4, "repetitions 0");
    put_double(f64, (double)NAN);
    failed |= refused(path, &good, good.n, 16, f64, 8, "margin");
    put_double(f64, -1.0);
    failed |= refused(path, &good, good.n, 16, f64, 8, "margin");
    put_le(u64, UINT64_C(1) << 40, 8);
    failed |= refused(path, &good, good.n, 24, u64, 8, "FCL's int counts");
    put_le(u64, UINT64_C(1) << 20, 8);
    failed |= refused(path, &good, good.n, 24, u64, 8, "truncated");
    put_le(u64, 0, 8);
    failed |= refused(path, &good, good.n, 32, u64, 8, "needs >= 3 and >= 1");
    put_double(f64, (double)INFINITY);
    failed |= refused(path, &good, good.n, 40 + 8 * 4, f64, 8, "vertex 1 has a non-finite coordinate");
    put_le(u32, 3, 4);
    failed |= refused(path, &good, good.n, a_tris + 8, u32, 4, "uses vertex 3, out of range");
    put_le(u32, 7, 4);
    failed |= refused(path, &good, good.n, b_counts + 16 + 72 + 4, u32, 4, "mesh B: triangle 0 uses vertex 7");
    put_le(u64, 0, 8);
    failed |= refused(path, &good, good.n, pose_count, u64, 8, "no poses");
    put_le(u64, UINT64_MAX, 8);
    failed |= refused(path, &good, good.n, pose_count, u64, 8, "truncated");
    put_double(f64, 2.0); /* R scaled: not a rotation */
    failed |= refused(path, &good, good.n, pose_count + 8, f64, 8, "not a rotation");
    put_double(f64, (double)NAN);
    failed |= refused(path, &good, good.n, pose_count + 8 + 8 * 11, f64, 8, "non-finite");
    failed |= refused(path, &good, good.n - 1, 0, NULL, 0, "truncated");
    failed |= refused(path, &good, good.n + 1, 0, NULL, 0, "1 bytes after the last pose");
    /* A mirror (det -1) is orthonormal but not a rotation. */
    put_double(f64, -1.0);
    failed |= refused(path, &good, good.n, pose_count + 8 + 8 * 10, f64, 8, "not a rotation");

    /* The pairs file belongs to query 2 only. */
    ENSURE(bench_fcl_mesh_run_file(program, path, BENCH_FCL_MESH_DISTANCE, 1, 1, &r) == BENCH_FCL_MESH_ERROR);
    free(good.b);
    unlink(path);
    return failed;
}

static int bad_jobs_and_missing_program(void)
{
    const double va[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t t[3] = {0, 1, 2}, t_bad[3] = {0, 1, 3};
    const double pose[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1};
    double shear[12];
    memcpy(shear, pose, sizeof shear);
    shear[1] = 0.5;
    double nan_v[9];
    memcpy(nan_v, va, sizeof nan_v);
    nan_v[4] = (double)NAN;
    bench_fcl_mesh_result r;
    bench_fcl_mesh_job job = {{va, 3, t, 1}, {va, 3, t, 1}, pose, 1, BENCH_FCL_MESH_DISTANCE, 1, 0.0};
    ENSURE(bench_fcl_mesh_run(program, &job, 0, &r) == BENCH_FCL_MESH_OK);
    ENSURE_NEAR(r.poses[0].distance, 1.0, 1e-15);
    bench_fcl_mesh_result_free(&r);

    bench_fcl_mesh_job bad = job;
    bad.b.triangles = t_bad;
    ENSURE(bench_fcl_mesh_run(program, &bad, 0, &r) == BENCH_FCL_MESH_ERROR && strstr(r.error, "out of"));
    bad = job;
    bad.a.vertices = nan_v;
    ENSURE(bench_fcl_mesh_run(program, &bad, 0, &r) == BENCH_FCL_MESH_ERROR && strstr(r.error, "non-finite"));
    bad = job;
    bad.poses = shear;
    ENSURE(bench_fcl_mesh_run(program, &bad, 0, &r) == BENCH_FCL_MESH_ERROR && strstr(r.error, "not a rotation"));
    bad = job;
    bad.a.vertices = NULL;
    ENSURE(bench_fcl_mesh_run(program, &bad, 0, &r) == BENCH_FCL_MESH_ERROR && strstr(r.error, "NULL"));
    bad = job;
    bad.repetitions = 0;
    ENSURE(bench_fcl_mesh_run(program, &bad, 0, &r) == BENCH_FCL_MESH_ERROR && strstr(r.error, "repetitions"));
    ENSURE(bench_fcl_mesh_run(program, NULL, 0, &r) == BENCH_FCL_MESH_ERROR);
    /* Pairs are for query 2 only. */
    ENSURE(bench_fcl_mesh_run(program, &job, 1, &r) == BENCH_FCL_MESH_ERROR);

    /* Without the program (this test is not next to `ttd`): missing, not an error. */
    char path[1024];
    ENSURE(setenv(BENCH_FCL_MESH_ENV, "/nonexistent/ttd_fcl_mesh_bench", 1) == 0);
    ENSURE(bench_fcl_mesh_find(NULL, path, sizeof path) == BENCH_FCL_MESH_MISSING);
    ENSURE(bench_fcl_mesh_run(NULL, &job, 0, &r) == BENCH_FCL_MESH_MISSING);
    ENSURE(strstr(r.error, "not found") != NULL && r.poses == NULL);
    ENSURE(setenv(BENCH_FCL_MESH_ENV, program, 1) == 0);
    ENSURE(bench_fcl_mesh_find(NULL, path, sizeof path) == BENCH_FCL_MESH_OK && strcmp(path, program) == 0);
    ENSURE(bench_fcl_mesh_run(NULL, &job, 0, &r) == BENCH_FCL_MESH_OK);
    bench_fcl_mesh_result_free(&r);
    ENSURE(unsetenv(BENCH_FCL_MESH_ENV) == 0);
    /* A path that is not a program: an error naming it. */
    ENSURE(bench_fcl_mesh_run("/nonexistent/ttd_fcl_mesh_bench", &job, 0, &r) == BENCH_FCL_MESH_ERROR);
    ENSURE(strstr(r.error, "/nonexistent/ttd_fcl_mesh_bench") != NULL);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s PATH/ttd_fcl_mesh_bench [test-name-filter]\n", argv[0]);
        return 2;
    }
    program = argv[1];
    TEST_MAIN_BEGIN(argc - 1, argv + 1);
    RUN_TEST(hostile_files);
    RUN_TEST(bad_jobs_and_missing_program);
    RUN_TEST(sphere_against_torus);
    RUN_TEST(torus_against_torus);
    TEST_MAIN_END();
}
