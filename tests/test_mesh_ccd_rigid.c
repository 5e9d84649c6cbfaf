/* SPDX-License-Identifier: MIT */
/* Continuous collision of rigid bodies between two poses (ttd_mesh_ccd_rigid_d/f, ttd.h;
 * docs/ccd.md section 13). References: (a) pure translations against the deforming path
 * (ttd_mesh_ccd_d on the world vertices, linear paths); (b) rotations against the exact mesh
 * distance sampled at 513 times along the motion built here independently (long double
 * Rodrigues from an axis and angle the test chose), with the most the distance can change
 * between samples, which brackets the time of impact; (c) degenerate motions: none, touching at
 * t = 0 and t = 1, a half turn, huge and tiny scales, sliding in contact (the step bound); (d)
 * float against double; the checks; the motion itself (ttd_rigid_pose_at_d). */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "boxes.h"
#include "meshes.h"
#include "test_macros.h"
#include "ttd/ttd.h"

#define M_PI 3.14159265358979323846

#define TEST_RAND_SEED 0x9e3779b97f4a7c15ull
#include "test_rand.h"
static void unit_vector(double u[3])
{
    double n;
    do {
        for (int i = 0; i < 3; ++i)
            u[i] = srand1();
        n = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    } while (n < 0.1);
    for (int i = 0; i < 3; ++i)
        u[i] /= n;
}

/* Rot(u, a) in long double, Rodrigues' formula written out here. */
static void rot_ld(const double u[3], long double a, long double R[9])
{
    const long double c = cosl(a), s = sinl(a), k = 1 - c;
    const long double x = u[0], y = u[1], z = u[2];
    const long double r[9] = {c + k * x * x,     k * x * y - s * z, k * x * z + s * y, k * y * x + s * z, c + k * y * y,
                              k * y * z - s * x, k * z * x - s * y, k * z * y + s * x, c + k * z * z};
    memcpy(R, r, sizeof r);
}

/* A motion chosen by the test: R(t) = Rot(u, t theta) R0, T(t) = (1 - t) T0 + t T1. */
typedef struct motion {
    long double r0[9];
    double u[3], theta, t0[3], t1[3];
} motion;

static void motion_pose(const motion *m, long double t, long double P[12])
{
    long double Q[9];
    rot_ld(m->u, t * (long double)m->theta, Q);
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j)
            P[4 * i + j] = Q[3 * i] * m->r0[j] + Q[3 * i + 1] * m->r0[3 + j] + Q[3 * i + 2] * m->r0[6 + j];
        P[4 * i + 3] = (1 - t) * m->t0[i] + t * m->t1[i];
    }
}
/* The 24 reals the query takes: the pose at 0 and at 1, rounded to double. */
static void motion_poses(const motion *m, double out[24])
{
    long double P[12];
    for (int k = 0; k < 2; ++k) {
        motion_pose(m, k, P);
        for (int i = 0; i < 12; ++i)
            out[12 * k + i] = (double)P[i];
    }
}
static void motion_random(motion *m, double theta, const double t0[3], const double t1[3])
{
    double v[3];
    unit_vector(v);
    rot_ld(v, (long double)(M_PI * urand()), m->r0);
    unit_vector(m->u);
    m->theta = theta;
    memcpy(m->t0, t0, sizeof m->t0);
    memcpy(m->t1, t1, sizeof m->t1);
}

/* b's pose in a's frame at t, in long double, rounded. */
static void relative(const motion *a, const motion *b, long double t, double rel[12])
{
    long double pa[12], pb[12];
    motion_pose(a, t, pa);
    motion_pose(b, t, pb);
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j)
            rel[4 * i + j] = (double)(pa[i] * pb[j] + pa[4 + i] * pb[4 + j] + pa[8 + i] * pb[8 + j]);
        rel[4 * i + 3] = (double)(pa[i] * (pb[3] - pa[3]) + pa[4 + i] * (pb[7] - pa[7]) + pa[8 + i] * (pb[11] - pa[11]));
    }
}

static double radius_of(const ttd_gen_mesh *g)
{
    double r = 0;
    for (size_t i = 0; i < g->nv; ++i) {
        const double *x = g->verts + 3 * i;
        r = fmax(r, sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]));
    }
    return r;
}
static double norm3(const double x[3])
{
    return sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
}
static double speed_of(const motion *m, double r)
{
    const double d[3] = {m->t1[0] - m->t0[0], m->t1[1] - m->t0[1], m->t1[2] - m->t0[2]};
    return norm3(d) + m->theta * r;
}

/* The exact mesh distance at t along the test's motions (double or float meshes). */
static double distance_at(const ttd_mesh *a, const ttd_mesh *b, int bytes, const motion *ma, const motion *mb, double t)
{
    double rel[12];
    relative(ma, mb, t, rel);
    if (bytes == 8) {
        ttd_mesh_result_d r;
        if (ttd_mesh_distance_d(NULL, a, b, 1, rel, INFINITY, 0, &r) != TTD_OK)
            return NAN;
        return r.distance;
    }
    float f[12];
    for (int i = 0; i < 12; ++i)
        f[i] = (float)rel[i];
    ttd_mesh_result_f r;
    if (ttd_mesh_distance_f(NULL, a, b, 1, f, INFINITY, 0, &r) != TTD_OK)
        return NAN;
    return r.distance;
}

static ttd_status rigid(int bytes, const ttd_mesh *a, const double pa[24], const ttd_mesh *b, const double pb[24],
                        double delta, ttd_mesh_ccd_rigid_result *r)
{
    if (bytes == 8)
        return ttd_mesh_ccd_rigid_d(NULL, a, pa, b, pb, delta, r);
    float fa[24], fb[24];
    for (int i = 0; i < 24; ++i) {
        fa[i] = (float)pa[i];
        fb[i] = (float)pb[i];
    }
    return ttd_mesh_ccd_rigid_f(NULL, a, fa, b, fb, delta, r);
}

#define SAMPLES 512

/* (b): the query against the distance sampled at SAMPLES + 1 times along the test's motion.
 * V bounds |d'(t)| (each body's |T1 - T0| + theta r), so between samples i and i + 1 the
 * distance is at least (d_i + d_i+1 - V h) / 2. Asserted: (1) no sample before toi (all, without
 * a hit) at distance <= delta - e: no contact missed, toi never after the first sampled contact;
 * (2) with a hit, the distance at toi at most delta + tolerance + e; (3) toi not inside the
 * leading run of intervals whose lower bound exceeds delta + tolerance + e. e is the rounding
 * between the test's motion and the library's (a few ulps of the scale, taken as 2^-36 of it). */
typedef struct sampled {
    uint32_t hit, steps;
    double toi, dmin; /* the least sampled distance */
} sampled;

static int against_samples(int bytes, const ttd_gen_mesh *ga, const ttd_gen_mesh *gb, const motion *ma,
                           const motion *mb, double delta, const char *what, int *hits, double *bracket_width,
                           sampled *rec)
{
    ttd_mesh *a = test_mesh_of(bytes, ga->verts, ga->nv, ga->tris, ga->nt);
    ttd_mesh *b = test_mesh_of(bytes, gb->verts, gb->nv, gb->tris, gb->nt);
    ENSURE(a != NULL && b != NULL);
    double pa[24], pb[24];
    motion_poses(ma, pa);
    motion_poses(mb, pb);
    ttd_mesh_ccd_rigid_result r;
    ENSURE(rigid(bytes, a, pa, b, pb, delta, &r) == TTD_OK);
    ENSURE_MSG(r.flags == 0, "%s: flags %u after %u steps", what, r.flags, r.steps);
    const double ra = radius_of(ga), rb = radius_of(gb);
    const double S = ra + rb + fmax(norm3(ma->t0), norm3(ma->t1)) + fmax(norm3(mb->t0), norm3(mb->t1));
    const double e = S * (bytes == 8 ? 0x1p-36 : 0x1p-15);
    const double V = (speed_of(ma, ra) + speed_of(mb, rb)) * 1.001;
    const double h = 1.0 / SAMPLES;
    double d[SAMPLES + 1];
    for (int i = 0; i <= SAMPLES; ++i) {
        d[i] = distance_at(a, b, bytes, ma, mb, i * h);
        ENSURE(d[i] >= 0);
    }
    int first_contact = -1, lead = 0;
    if (rec) {
        rec->hit = r.hit;
        rec->steps = r.steps;
        rec->toi = r.toi;
        rec->dmin = INFINITY;
        for (int i = 0; i <= SAMPLES; ++i)
            rec->dmin = fmin(rec->dmin, d[i]);
    }
    for (int i = 0; i <= SAMPLES; ++i)
        if (first_contact < 0 && d[i] <= delta - e)
            first_contact = i;
    while (lead < SAMPLES && (d[lead] + d[lead + 1] - V * h) / 2 > delta + r.tolerance + e)
        ++lead;
    for (int i = 0; i <= SAMPLES; ++i)
        if (!r.hit || i * h < r.toi)
            ENSURE_MSG(d[i] > delta - e, "%s: sample t = %g at %.17g <= delta %g before toi %.17g (hit %u)", what,
                       i * h, d[i], delta, r.toi, r.hit);
    if (r.hit) {
        ENSURE(r.toi >= 0 && r.toi <= 1);
        const double dt = distance_at(a, b, bytes, ma, mb, r.toi);
        ENSURE_MSG(dt <= delta + r.tolerance + e, "%s: at toi %.17g the distance %.17g > delta %g + tolerance %g", what,
                   r.toi, dt, delta, r.tolerance);
        ENSURE_MSG(lead == SAMPLES || r.toi >= lead * h, "%s: toi %.17g before %g, proved beyond the tolerance", what,
                   r.toi, lead * h);
        ENSURE(r.distance <= delta + r.tolerance);
        ++*hits;
        if (first_contact >= 0 && bracket_width)
            *bracket_width = fmax(*bracket_width, first_contact * h - r.toi);
    } else {
        ENSURE(isinf(r.toi) && first_contact < 0);
    }
    ttd_mesh_destroy(a);
    ttd_mesh_destroy(b);
    return 0;
}

/* A torus turning about a random axis (and drifting), a sphere set off its own origin turning and
 * passing by or through it: about half meet. The same cases in double and float (the generator
 * restarted): where the two decide differently, the least sampled distance must lie within the
 * float tolerance and the sampling's reach of delta (a borderline case). */
#define ROT_CASES 40
static int rotations_sampled_at(int bytes, sampled *rec)
{
    rng_state = 0x2545f4914f6cdd1dull;
    ttd_gen_mesh torus, ball;
    ENSURE(ttd_gen_torus(1.0, 0.3, 16, 8, &torus) == 0);
    ENSURE(ttd_gen_icosphere(2, &ball) == 0);
    for (size_t i = 0; i < 3 * ball.nv; ++i)
        ball.verts[i] = 0.3 * ball.verts[i] + (i % 3 == 0 ? 0.5 : 0);
    int hits = 0;
    double width = 0, steps = 0;
    uint32_t most = 0;
    for (int it = 0; it < ROT_CASES; ++it) {
        motion ma, mb;
        const double z0[3] = {0, 0, 0}, z1[3] = {0.2 * srand1(), 0.2 * srand1(), 0.2 * srand1()};
        motion_random(&ma, M_PI * urand(), z0, z1);
        double dir[3], side[3];
        unit_vector(dir);
        unit_vector(side);
        const double off = 2.5 * urand();
        const double b0[3] = {3 * dir[0] + off * side[0], 3 * dir[1] + off * side[1], 3 * dir[2] + off * side[2]};
        const double b1[3] = {-dir[0] + off * side[0], -dir[1] + off * side[1], -dir[2] + off * side[2]};
        motion_random(&mb, M_PI * urand(), b0, b1);
        const double delta = it % 4 == 3 ? 0.05 : 0;
        char what[64];
        snprintf(what, sizeof what, "%s case %d", bytes == 8 ? "double" : "float", it);
        if (against_samples(bytes, &torus, &ball, &ma, &mb, delta, what, &hits, &width, &rec[it]))
            return 1;
        rec[it].dmin -= delta;
        steps += rec[it].steps;
        most = rec[it].steps > most ? rec[it].steps : most;
    }
    printf("  %s: %d of %d cases hit; toi at most %.3g before the first sampled contact; steps mean %.1f, most %u\n",
           bytes == 8 ? "double" : "float", hits, ROT_CASES, width, steps / ROT_CASES, most);
    ENSURE(hits >= 8 && hits <= ROT_CASES - 8);
    ttd_gen_mesh_free(&torus);
    ttd_gen_mesh_free(&ball);
    return 0;
}
static int rotations_sampled(void)
{
    sampled d[ROT_CASES], f[ROT_CASES];
    if (rotations_sampled_at(8, d) || rotations_sampled_at(4, f))
        return 1;
    int differ = 0;
    for (int i = 0; i < ROT_CASES; ++i) {
        if (d[i].hit == f[i].hit) {
            if (d[i].hit)
                ENSURE_MSG(fabs(d[i].toi - f[i].toi) <= 0.01, "case %d: toi %.17g (double) %.17g (float)", i, d[i].toi,
                           f[i].toi);
            continue;
        }
        ++differ;
        ENSURE_MSG(fabs(d[i].dmin) <= 0.02, "case %d: double hit %u, float %u, least sampled gap %g", i, d[i].hit,
                   f[i].hit, d[i].dmin);
    }
    printf("  float and double decide alike on %d of %d cases\n", ROT_CASES - differ, ROT_CASES);
    return 0;
}

/* (a): pure translations against the deforming path on the same world vertices (each vertex on
 * a straight line): the same hit decision; the rigid toi never after the deforming one (beyond
 * the world coordinates' rounding) and at it the distance within the tolerance. */
static int translation_matches_deforming(void)
{
    int hits = 0, cases = 30;
    double worst = 0;
    for (int it = 0; it < cases; ++it) {
        ttd_gen_mesh ga, gb;
        ENSURE(ttd_gen_icosphere(1, &ga) == 0);
        if (it % 2)
            ENSURE(ttd_gen_torus(0.8, 0.25, 12, 6, &gb) == 0);
        else
            ENSURE(ttd_gen_icosphere(1, &gb) == 0);
        motion ma, mb;
        const double a0[3] = {0.1 * srand1(), 0.1 * srand1(), 0.1 * srand1()};
        const double a1[3] = {0.5 + 0.3 * srand1(), 0.3 * srand1(), 0.3 * srand1()};
        const double b0[3] = {2.6 + 0.3 * urand(), 0.6 * srand1(), 0.6 * srand1()};
        const double b1[3] = {b0[0] - 0.5 - 0.5 * urand(), b0[1] + 0.3 * srand1(), b0[2] + 0.3 * srand1()};
        motion_random(&ma, 0, a0, a1);
        motion_random(&mb, 0, b0, b1);
        const double delta = it % 3 == 2 ? 0.02 : 0;
        double pa[24], pb[24];
        motion_poses(&ma, pa);
        motion_poses(&mb, pb);
        for (int i = 0; i < 12; ++i) /* the same rotation at both ends, to the bit */
            ENSURE(i % 4 == 3 || (pa[i] == pa[12 + i] && pb[i] == pb[12 + i]));
        /* World vertices at t = 0 and 1, as the query's convention computes them. */
        double *wa0 = malloc(3 * ga.nv * sizeof *wa0), *wa1 = malloc(3 * ga.nv * sizeof *wa1);
        double *wb0 = malloc(3 * gb.nv * sizeof *wb0), *wb1 = malloc(3 * gb.nv * sizeof *wb1);
        ENSURE(wa0 && wa1 && wb0 && wb1);
        for (size_t v = 0; v < ga.nv; ++v) {
            test_pose_apply(pa, ga.verts + 3 * v, wa0 + 3 * v);
            test_pose_apply(pa + 12, ga.verts + 3 * v, wa1 + 3 * v);
        }
        for (size_t v = 0; v < gb.nv; ++v) {
            test_pose_apply(pb, gb.verts + 3 * v, wb0 + 3 * v);
            test_pose_apply(pb + 12, gb.verts + 3 * v, wb1 + 3 * v);
        }
        ttd_mesh *a = test_mesh_of(8, ga.verts, ga.nv, ga.tris, ga.nt), *b = test_mesh_of(8, gb.verts, gb.nv, gb.tris, gb.nt);
        ttd_mesh *wa = test_mesh_of(8, wa0, ga.nv, ga.tris, ga.nt), *wb = test_mesh_of(8, wb0, gb.nv, gb.tris, gb.nt);
        ENSURE(a && b && wa && wb);
        ttd_mesh_ccd_rigid_result r;
        ttd_mesh_ccd_result def;
        ENSURE(ttd_mesh_ccd_rigid_d(NULL, a, pa, b, pb, delta, &r) == TTD_OK);
        ENSURE(ttd_mesh_ccd_d(NULL, wa, wa1, wb, wb1, delta, &def) == TTD_OK);
        const double slack = 1e-12; /* world vertices rounded once: ~1e-16 of 3 in distance */
        const int def_hit = def.count > 0;
        ENSURE_MSG((int)r.hit == def_hit, "case %d: rigid hit %u (toi %.17g), deforming %d (toi %.17g)", it, r.hit,
                   r.toi, def_hit, def.toi);
        if (def_hit) {
            ENSURE_MSG(r.toi <= def.toi + slack, "case %d: rigid toi %.17g after deforming %.17g", it, r.toi, def.toi);
            double rel[12];
            relative(&ma, &mb, r.toi, rel);
            ttd_mesh_result_d m;
            ENSURE(ttd_mesh_distance_d(NULL, a, b, 1, rel, INFINITY, 0, &m) == TTD_OK);
            ENSURE_MSG(m.distance <= delta + r.tolerance + 1e-12, "case %d: distance %.17g at toi", it, m.distance);
            worst = fmax(worst, def.toi - r.toi);
            ++hits;
        }
        ttd_mesh_ccd_free(&def);
        ttd_mesh_destroy(a);
        ttd_mesh_destroy(b);
        ttd_mesh_destroy(wa);
        ttd_mesh_destroy(wb);
        free(wa0);
        free(wa1);
        free(wb0);
        free(wb1);
        ttd_gen_mesh_free(&ga);
        ttd_gen_mesh_free(&gb);
    }
    printf("  %d of %d translations hit; rigid toi at most %.3g before the deforming one\n", hits, cases, worst);
    ENSURE(hits >= 5 && hits <= cases - 5);
    return 0;
}

/* The motion: at 0 the first pose to the bit, at 1 the second within rounding, between them the
 * test's own Rot(u, t theta) R0 for random axes and angles up to pi; a half turn diag(1, -1, -1)
 * goes about +x (the sign rule), about -x never. */
static int motion_between_poses(void)
{
    for (int it = 0; it < 200; ++it) {
        motion m;
        const double t0[3] = {srand1(), srand1(), srand1()}, t1[3] = {srand1(), srand1(), srand1()};
        motion_random(&m, it == 0 ? 0 : M_PI * (it < 190 ? urand() : 1 - 1e-9 * urand()), t0, t1);
        double p[24], q[12];
        motion_poses(&m, p);
        ENSURE(ttd_rigid_pose_at_d(p, p + 12, 0, q) == TTD_OK);
        ENSURE(memcmp(q, p, sizeof q) == 0);
        for (int k = 1; k <= 8; ++k) {
            const double t = k / 8.0;
            ENSURE(ttd_rigid_pose_at_d(p, p + 12, t, q) == TTD_OK);
            long double P[12];
            motion_pose(&m, t, P);
            for (int i = 0; i < 12; ++i)
                ENSURE_MSG(fabs(q[i] - (double)P[i]) <= 1e-13 * (m.theta < M_PI - 1e-6 ? 1 : 1e4),
                           "case %d t %g entry %d: %.17g vs %.17g (theta %.17g)", it, t, i, q[i], (double)P[i],
                           m.theta);
        }
    }
    const double p0[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    const double p1[12] = {1, 0, 0, 0, 0, -1, 0, 0, 0, 0, -1, 0};
    double q[12];
    ENSURE(ttd_rigid_pose_at_d(p0, p1, 0.5, q) == TTD_OK);
    /* Rot(+x, pi/2): y -> z, z -> -y. */
    ENSURE_NEAR(q[9], 1, 1e-15);  /* R[2][1] */
    ENSURE_NEAR(q[6], -1, 1e-15); /* R[1][2] */
    ENSURE(ttd_rigid_pose_at_d(p0, p1, 1, q) == TTD_OK);
    for (int i = 0; i < 12; ++i)
        ENSURE_NEAR(q[i], p1[i], 1e-15);
    return 0;
}

/* A ball's mesh (level-1 icosphere) and a unit cube. */
static int degenerate(void)
{
    ttd_gen_mesh cube, ball;
    ENSURE(ttd_gen_mesh_cube(&cube) == 0);
    ENSURE(ttd_gen_icosphere(1, &ball) == 0);
    ttd_mesh *c = test_mesh_of(8, cube.verts, cube.nv, cube.tris, cube.nt);
    ttd_mesh *s = test_mesh_of(8, ball.verts, ball.nv, ball.tris, ball.nt);
    ENSURE(c && s);
    const double id[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    double pa[24], pb[24];
    memcpy(pa, id, sizeof id);
    memcpy(pa + 12, id, sizeof id);
    ttd_mesh_ccd_rigid_result r;
    /* No motion, apart: one distance query, no hit; touching (cube on cube, face to face): 0. */
    memcpy(pb, id, sizeof id);
    pb[3] = 1.5;
    memcpy(pb + 12, pb, sizeof id);
    ENSURE(ttd_mesh_ccd_rigid_d(NULL, c, pa, c, pb, 0, &r) == TTD_OK);
    ENSURE(!r.hit && isinf(r.toi) && r.steps == 1);
    ENSURE(ttd_mesh_ccd_rigid_d(NULL, c, pa, c, pb, 0.5, &r) == TTD_OK);
    ENSURE(r.hit && r.toi == 0 && r.steps == 1);
    pb[3] = pb[15] = 1;
    ENSURE(ttd_mesh_ccd_rigid_d(NULL, c, pa, c, pb, 0, &r) == TTD_OK);
    ENSURE(r.hit && r.toi == 0 && r.distance == 0);
    /* Touching at t = 0 and moving away. */
    pb[15] = 3;
    ENSURE(ttd_mesh_ccd_rigid_d(NULL, c, pa, c, pb, 0, &r) == TTD_OK);
    ENSURE(r.hit && r.toi == 0);
    /* Touching at t = 1 exactly, from 2 apart: a hit within the tolerance of 1 (time: the
     * tolerance over the closing speed 2). */
    pb[3] = 3;
    pb[15] = 1;
    ENSURE(ttd_mesh_ccd_rigid_d(NULL, c, pa, c, pb, 0, &r) == TTD_OK);
    ENSURE_MSG(r.hit && r.toi <= 1 && r.toi >= 1 - r.tolerance / 2 * 1.01, "toi %.17g tolerance %g", r.toi, r.tolerance);
    printf("  touching at t = 1: toi 1 - %.3g in %u steps\n", 1 - r.toi, r.steps);
    /* Stopping just short: 1e-6 apart at t = 1, no hit; with delta 2e-6 a hit. */
    pb[15] = 1 + 1e-6;
    ENSURE(ttd_mesh_ccd_rigid_d(NULL, c, pa, c, pb, 0, &r) == TTD_OK);
    ENSURE(!r.hit);
    ENSURE(ttd_mesh_ccd_rigid_d(NULL, c, pa, c, pb, 2e-6, &r) == TTD_OK);
    ENSURE(r.hit && r.toi < 1);
    /* A half turn of a cube about +x through its corner at the origin, a ball above the far
     * side (y in [1, 2]): diag(1, -1, -1) turns about +x (the rule), so the cube sweeps up
     * through y > 0 ... no: about +x, y goes to z first: the cube rises into z > 0 and the
     * ball at z = 1.2 above y = 0.5 is met; about -x it would sweep z < 0 and miss. */
    const double half[12] = {1, 0, 0, 0, 0, -1, 0, 0, 0, 0, -1, 0};
    memcpy(pa + 12, half, sizeof half);
    const double ballpose[12] = {0.2, 0, 0, 0.5, 0, 0.2, 0, -0.5, 0, 0, 0.2, 1.3};
    memcpy(pb, ballpose, sizeof ballpose);
    memcpy(pb + 12, ballpose, sizeof ballpose);
    /* ballpose is not a rotation (scale 0.2): refused; scale the ball's mesh instead. */
    ENSURE(ttd_mesh_ccd_rigid_d(NULL, c, pa, s, pb, 0, &r) == TTD_ERR_BAD_POSE);
    for (size_t i = 0; i < 3 * ball.nv; ++i)
        ball.verts[i] *= 0.2;
    ttd_mesh *small = test_mesh_of(8, ball.verts, ball.nv, ball.tris, ball.nt);
    for (int k = 0; k < 2; ++k) {
        memcpy(pb + 12 * k, id, sizeof id);
        pb[12 * k + 3] = 0.5;
        pb[12 * k + 7] = -0.5;
        pb[12 * k + 11] = 1.3;
    }
    ENSURE(ttd_mesh_ccd_rigid_d(NULL, c, pa, small, pb, 0, &r) == TTD_OK);
    ENSURE_MSG(r.hit && r.toi > 0.1 && r.toi < 0.6, "half turn: hit %u toi %g", r.hit, r.toi);
    pb[7] = pb[19] = 0.5;
    pb[11] = pb[23] = -1.3; /* on the side the other sign would sweep: missed */
    ENSURE(ttd_mesh_ccd_rigid_d(NULL, c, pa, small, pb, 0, &r) == TTD_OK);
    ENSURE_MSG(!r.hit, "half turn the other way: toi %g", r.toi);
    ttd_mesh_destroy(small);
    ttd_mesh_destroy(c);
    ttd_mesh_destroy(s);
    ttd_gen_mesh_free(&cube);
    ttd_gen_mesh_free(&ball);
    return 0;
}

/* The same motion at scales 2^-300 .. 2^300 (double) and 2^-40 .. 2^40 (float): the same hit and
 * toi within the tolerance's time (all scale-free). */
static int scales(void)
{
    ttd_gen_mesh torus0, ball0;
    ENSURE(ttd_gen_torus(1.0, 0.3, 16, 8, &torus0) == 0);
    ENSURE(ttd_gen_icosphere(1, &ball0) == 0);
    for (int bytes = 8; bytes >= 4; bytes -= 4) {
        double toi1 = NAN;
        const int top = bytes == 8 ? 300 : 40;
        for (int e = -top; e <= top; e += top / 2) {
            const double k = ldexp(1, e);
            ttd_gen_mesh torus, ball;
            ENSURE(ttd_gen_mesh_copy(&torus0, &torus) == 0 && ttd_gen_mesh_copy(&ball0, &ball) == 0);
            for (size_t i = 0; i < 3 * torus.nv; ++i)
                torus.verts[i] *= k;
            for (size_t i = 0; i < 3 * ball.nv; ++i)
                ball.verts[i] *= 0.25 * k;
            const double z[3] = {0, 0, 0};
            const double b0[3] = {3 * k, 0.2 * k, 0.1 * k}, b1[3] = {-3 * k, 0.2 * k, 0.3 * k};
            motion ma = {.r0 = {1, 0, 0, 0, 1, 0, 0, 0, 1}, .u = {0, 0.6, 0.8}, .theta = 2.0};
            motion mb = {.r0 = {1, 0, 0, 0, 1, 0, 0, 0, 1}, .u = {1, 0, 0}, .theta = 0.5};
            memcpy(ma.t0, z, sizeof z);
            memcpy(ma.t1, z, sizeof z);
            memcpy(mb.t0, b0, sizeof b0);
            memcpy(mb.t1, b1, sizeof b1);
            int hits = 0;
            char what[48];
            snprintf(what, sizeof what, "scale 2^%d bytes %d", e, bytes);
            if (against_samples(bytes, &torus, &ball, &ma, &mb, 0, what, &hits, NULL, NULL))
                return 1;
            ENSURE_MSG(hits == 1, "%s: no hit", what);
            ttd_mesh *a = test_mesh_of(bytes, torus.verts, torus.nv, torus.tris, torus.nt);
            ttd_mesh *b = test_mesh_of(bytes, ball.verts, ball.nv, ball.tris, ball.nt);
            double pa[24], pb[24];
            motion_poses(&ma, pa);
            motion_poses(&mb, pb);
            ttd_mesh_ccd_rigid_result r;
            ENSURE(rigid(bytes, a, pa, b, pb, 0, &r) == TTD_OK);
            if (e == -top)
                toi1 = r.toi;
            ENSURE_MSG(fabs(r.toi - toi1) <= (bytes == 8 ? 1e-8 : 1e-3), "%s: toi %.17g vs %.17g", what, r.toi, toi1);
            ttd_mesh_destroy(a);
            ttd_mesh_destroy(b);
            ttd_gen_mesh_free(&torus);
            ttd_gen_mesh_free(&ball);
        }
    }
    ttd_gen_mesh_free(&torus0);
    ttd_gen_mesh_free(&ball0);
    return 0;
}

/* Sliding in contact: a cube sliding along another at a constant gap just above delta plus the
 * tolerance: no time comes within delta, yet no step is long. The query ends after
 * TTD_RIGID_CCD_MAX_STEPS with a conservative hit (flagged) at a time before which it proved every
 * time apart. */
static int step_bound(void)
{
    ttd_gen_mesh cube;
    ENSURE(ttd_gen_mesh_cube(&cube) == 0);
    ttd_mesh *c = test_mesh_of(8, cube.verts, cube.nv, cube.tris, cube.nt);
    const double id[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    double pa[24], pb[24];
    memcpy(pa, id, sizeof id);
    memcpy(pa + 12, id, sizeof id);
    memcpy(pb, id, sizeof id);
    memcpy(pb + 12, id, sizeof id);
    pb[11] = pb[23] = 1.25; /* 0.25 above */
    pb[3] = -0.5;
    pb[15] = 0.5; /* sliding in x */
    ttd_mesh_ccd_rigid_result r;
    ENSURE(ttd_mesh_ccd_rigid_d(NULL, c, pa, c, pb, 0, &r) == TTD_OK);
    const double delta = 0.25 - 3 * r.tolerance;
    ENSURE(ttd_mesh_ccd_rigid_d(NULL, c, pa, c, pb, delta, &r) == TTD_OK);
    ENSURE_MSG(r.hit && r.flags == TTD_CCD_BUDGET && r.steps == TTD_RIGID_CCD_MAX_STEPS && r.toi > 0 && r.toi < 1,
               "hit %u flags %u steps %u toi %g", r.hit, r.flags, r.steps, r.toi);
    ENSURE(isinf(r.distance) && r.tri_a == UINT32_MAX && r.tri_b == UINT32_MAX);
    printf("  sliding at delta + 3 tolerances: conservative hit at %.3g after %u steps\n", r.toi, r.steps);
    ttd_mesh_destroy(c);
    ttd_gen_mesh_free(&cube);
    return 0;
}

static int checks(void)
{
    ttd_gen_mesh cube;
    ENSURE(ttd_gen_mesh_cube(&cube) == 0);
    ttd_mesh *c = test_mesh_of(8, cube.verts, cube.nv, cube.tris, cube.nt);
    ttd_mesh *cf = test_mesh_of(4, cube.verts, cube.nv, cube.tris, cube.nt);
    const double id[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    double p[24], q[24];
    memcpy(p, id, sizeof id);
    memcpy(p + 12, id, sizeof id);
    memcpy(q, p, sizeof p);
    q[3] = 2;
    ttd_mesh_ccd_rigid_result r;
    ENSURE(ttd_mesh_ccd_rigid_d(NULL, c, p, c, q, 0, NULL) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_mesh_ccd_rigid_d(NULL, NULL, p, c, q, 0, &r) == TTD_ERR_NULL_POINTER && isinf(r.toi) && !r.hit);
    ENSURE(ttd_mesh_ccd_rigid_d(NULL, c, NULL, c, q, 0, &r) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_mesh_ccd_rigid_d(NULL, c, p, c, NULL, 0, &r) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_mesh_ccd_rigid_d(NULL, c, p, c, q, -1, &r) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_mesh_ccd_rigid_d(NULL, c, p, c, q, NAN, &r) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_mesh_ccd_rigid_d(NULL, c, p, c, q, INFINITY, &r) == TTD_ERR_BAD_OPTIONS);
    ttd_options o = ttd_default_options();
    o.method = TTD_METHOD_PENALTY;
    ENSURE(ttd_mesh_ccd_rigid_d(&o, c, p, c, q, 0, &r) == TTD_ERR_BAD_OPTIONS);
    ttd_options bad = {0};
    ENSURE(ttd_mesh_ccd_rigid_d(&bad, c, p, c, q, 0, &r) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_mesh_ccd_rigid_d(NULL, cf, p, c, q, 0, &r) == TTD_ERR_PRECISION_MISMATCH);
    for (int k = 0; k < 24; ++k) { /* NaN and inf anywhere in either body's poses */
        double pp[24];
        memcpy(pp, p, sizeof pp);
        pp[k] = k % 2 ? NAN : -INFINITY;
        ENSURE_MSG(ttd_mesh_ccd_rigid_d(NULL, c, pp, c, q, 0, &r) == TTD_ERR_BAD_POSE && !r.hit, "entry %d", k);
        ENSURE_MSG(ttd_mesh_ccd_rigid_d(NULL, c, q, c, pp, 0, &r) == TTD_ERR_BAD_POSE, "entry %d", k);
    }
    double s[24];
    memcpy(s, q, sizeof s);
    s[12] = s[17] = s[22] = 2; /* a scaled second pose */
    ENSURE(ttd_mesh_ccd_rigid_d(NULL, c, p, c, s, 0, &r) == TTD_ERR_BAD_POSE);
    memcpy(s, q, sizeof s);
    s[0] = -1; /* a reflection */
    ENSURE(ttd_mesh_ccd_rigid_d(NULL, c, p, c, s, 0, &r) == TTD_ERR_BAD_POSE);
    memcpy(s, q, sizeof s);
    s[15] = 1e300; /* beyond the coordinate range */
    ENSURE(ttd_mesh_ccd_rigid_d(NULL, c, p, c, s, 0, &r) == TTD_ERR_COORDINATE_RANGE);
    double out[12];
    ENSURE(ttd_rigid_pose_at_d(NULL, id, 0, out) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_rigid_pose_at_d(id, id, NAN, out) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_rigid_pose_at_d(id, id, 1.5, out) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_rigid_pose_at_d(s, id, 0.5, out) == TTD_OK);
    s[4] = NAN;
    ENSURE(ttd_rigid_pose_at_d(s, id, 0.5, out) == TTD_ERR_BAD_POSE);
    float pf[24], qf[24];
    for (int i = 0; i < 24; ++i) {
        pf[i] = (float)p[i];
        qf[i] = (float)q[i];
    }
    ENSURE(ttd_mesh_ccd_rigid_f(NULL, cf, pf, cf, qf, 0, &r) == TTD_OK && r.hit && r.toi <= 0.5 && r.toi > 0.499);
    ENSURE(ttd_mesh_ccd_rigid_f(NULL, c, pf, cf, qf, 0, &r) == TTD_ERR_PRECISION_MISMATCH);
    qf[5] = NAN;
    ENSURE(ttd_mesh_ccd_rigid_f(NULL, cf, pf, cf, qf, 0, &r) == TTD_ERR_BAD_POSE);
    ttd_mesh_destroy(c);
    ttd_mesh_destroy(cf);
    ttd_gen_mesh_free(&cube);
    return 0;
}

/* Poses within the pose check's 1e-6 but not rotations to the last bits (R = Q diag(1 + e_k),
 * Q exact): the motion uses their nearest rotations Q (docs/ccd.md section 13). (1) a triangle at
 * z = 1000 under R = diag(1 + e) and a vertical one crossing z = 1000 by 2e-4, both still: under
 * the nearest rotations they intersect, so both argument orders must answer a hit at t = 0 (with
 * R^T taken for R's inverse, b lay 1000 e above a in a's frame: no hit; checked). (2) the same
 * body under the same such pose twice: each pose passes ttd_mesh_check_poses, so the query must
 * answer (the relative pose R^T R of the old code had twice the defect: TTD_ERR_BAD_POSE; checked). */
static int near_rotations_at(int bytes)
{
    const double h = 1000;
    const double va[9] = {-1, -1, h, 2, -1, h, -1, 2, h};
    const double vb[9] = {0, 0, h - 2e-4, 0.5, 0, h + 2e-4, 0, 0.5, h + 2e-4};
    const uint32_t tri[3] = {0, 1, 2};
    ttd_mesh *a = test_mesh_of(bytes, va, 3, tri, 1);
    ttd_mesh *b = test_mesh_of(bytes, vb, 3, tri, 1);
    ENSURE(a && b);
    const double ev[4][3] = {{4.9e-7, 4.9e-7, 4.9e-7}, {4.9e-7, -4.9e-7, 4.9e-7}, {-4.9e-7, 0, 3e-7}, {0, 0, 0}};
    for (int c = 0; c < 4; ++c) {
        for (int q = 0; q < 2; ++q) { /* Q = I, or a quarter turn about z (exact) */
            double R[9] = {0};
            for (int k = 0; k < 3; ++k)
                R[4 * k] = 1 + ev[c][k];
            if (q) { /* Q diag: rows (0, -1, 0), (1, 0, 0), (0, 0, 1) times the diagonal */
                const double d0 = R[0], d1 = R[4];
                R[0] = 0, R[1] = -d1, R[3] = d0, R[4] = 0;
            }
            double pa[24] = {0}, pb[24] = {0};
            for (int k = 0; k < 2; ++k)
                for (int i = 0; i < 3; ++i) {
                    for (int j = 0; j < 3; ++j)
                        pa[12 * k + 4 * i + j] = R[3 * i + j];
                    pb[12 * k + 5 * i] = 1;
                }
            /* b's vertical triangle carried by Q too, so it still crosses a's plane */
            if (q)
                for (int k = 0; k < 2; ++k) {
                    pb[12 * k + 0] = 0, pb[12 * k + 1] = -1, pb[12 * k + 4] = 1, pb[12 * k + 5] = 0;
                }
            float fa[24], fb[24];
            for (int i = 0; i < 24; ++i) {
                fa[i] = (float)pa[i];
                fb[i] = (float)pb[i];
            }
            size_t bad;
            ENSURE(bytes == 8 ? ttd_mesh_check_poses_d(a, a, 2, pa, &bad) == TTD_OK
                              : ttd_mesh_check_poses_f(a, a, 2, fa, &bad) == TTD_OK);
            for (int order = 0; order < 2; ++order) {
                ttd_mesh_ccd_rigid_result r;
                ttd_status st;
                if (bytes == 8)
                    st = order ? ttd_mesh_ccd_rigid_d(NULL, b, pb, a, pa, 0, &r) : ttd_mesh_ccd_rigid_d(NULL, a, pa, b, pb, 0, &r);
                else
                    st = order ? ttd_mesh_ccd_rigid_f(NULL, b, fb, a, fa, 0, &r) : ttd_mesh_ccd_rigid_f(NULL, a, fa, b, fb, 0, &r);
                ENSURE_MSG(st == TTD_OK && r.hit && r.toi == 0, "bytes %d case %d q %d order %d: status %d hit %d toi %g",
                           bytes, c, q, order, (int)st, r.hit, r.toi);
                /* (2) a body against itself under the same near-rotation twice */
                st = bytes == 8 ? ttd_mesh_ccd_rigid_d(NULL, a, pa, a, pa, 0, &r) : ttd_mesh_ccd_rigid_f(NULL, a, fa, a, fa, 0, &r);
                ENSURE_MSG(st == TTD_OK && r.hit && r.toi == 0, "bytes %d case %d q %d self: status %d", bytes, c, q, (int)st);
            }
        }
    }
    ttd_mesh_destroy(a);
    ttd_mesh_destroy(b);
    return 0;
}

static int near_rotations(void)
{
    return near_rotations_at(8) || near_rotations_at(4);
}

/* toi never beyond 1: a triangle closing on a parallel one at speed 1 from D = 1 + mu + k ulps,
 * k in [-64, 256] (around where the walk's first step reaches t = 1), double and float: every
 * hit has toi in [0, 1]. A guard for the clamp of the step to t <= 1: it did not fail without
 * the clamp (the upper bound handed to the first distance query already stops such steps). */
static int toi_at_most_one(void)
{
    const double v[9] = {0, 0, 0, 0, 1, 0, 0, 0, 1};
    const uint32_t tri[3] = {0, 1, 2};
    int beyond = 0, hits = 0;
    for (int bytes = 8; bytes >= 4; bytes -= 4) {
        ttd_mesh *m = test_mesh_of(bytes, v, 3, tri, 1);
        ENSURE(m);
        for (int k = -64; k <= 256; ++k) {
            /* mu = S 2^-40 (S about 3 here) is 3 2^12 ulps of 1 in double, 3 2^6 in float */
            const double D = bytes == 8 ? 1 + (3 * 4096 + k) * DBL_EPSILON : (double)(1.0f + (float)(192 + k) * FLT_EPSILON);
            double pa[24] = {0}, pb[24] = {0};
            for (int j = 0; j < 2; ++j)
                for (int i = 0; i < 3; ++i)
                    pa[12 * j + 5 * i] = pb[12 * j + 5 * i] = 1;
            pb[3] = D;
            pb[12 + 3] = D - 1;
            float fa[24], fb[24];
            for (int i = 0; i < 24; ++i) {
                fa[i] = (float)pa[i];
                fb[i] = (float)pb[i];
            }
            ttd_mesh_ccd_rigid_result r;
            ENSURE((bytes == 8 ? ttd_mesh_ccd_rigid_d(NULL, m, pa, m, pb, 0, &r) : ttd_mesh_ccd_rigid_f(NULL, m, fa, m, fb, 0, &r)) == TTD_OK);
            hits += r.hit;
            if (r.hit && !(r.toi >= 0 && r.toi <= 1)) {
                ++beyond;
                printf("  bytes %d D = 1 + %d ulps: toi 1 + %.3g\n", bytes, k, r.toi - 1);
            }
        }
        ttd_mesh_destroy(m);
    }
    printf("  %d hits of %d, %d with toi beyond 1\n", hits, 2 * 321, beyond);
    ENSURE(beyond == 0);
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(checks);
    RUN_TEST(motion_between_poses);
    RUN_TEST(translation_matches_deforming);
    RUN_TEST(rotations_sampled);
    RUN_TEST(degenerate);
    RUN_TEST(scales);
    RUN_TEST(step_bound);
    RUN_TEST(near_rotations);
    RUN_TEST(toi_at_most_one);
    TEST_MAIN_END();
}
