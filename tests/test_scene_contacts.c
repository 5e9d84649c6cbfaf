/* SPDX-License-Identifier: MIT */
/* Scene manifolds as a simulator uses them (docs/scenes.md, section 5; issue 23):
 *   - stacks: a cube resting on a cube, flush and at gaps below the margin, offset and turned
 *     about z, in five triangulations (two diagonal choices, centre fans, faces split 3 x 3,
 *     faces without shared vertices), either body first: every point's normal is +z from the
 *     lower to the upper, in double and float;
 *   - a box on a box, turned and offset: the four points are four corners of the faces' overlap
 *     (unturned: exactly its rectangle's), K = 0 holds every corner of it, and no two points of
 *     any manifold are within the merge tolerance;
 *   - a sphere near a floor's diagonal edge (and on a grid floor): every normal is the floor's;
 *   - a ball resting in a groove (one body of two plates): K = 4 holds each side's touching point;
 *   - symmetry: the same scene with its bodies in the other order gives each contact the
 *     negated normal, bit for bit, over random scenes;
 *   - the normal rule's properties over random scenes, against features and cones found here
 *     independently (the exact method's weights, adjacency by comparing every triangle pair):
 *     unit length; a face normal where one side's feature is a face; one of the two faces'
 *     normals or their mean where both are; otherwise a direction in both cones whenever the
 *     triangles' normals, the direction between the points or an edge cross product lies in
 *     both.
 * Every instruction set and 1 or 2 threads give the same bits (the manifolds compared whole). */
#define _POSIX_C_SOURCE 200809L
#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "boxes.h"
#include "meshes.h"
#include "pairs.h"
#include "scene_corners_ref.h"
#include "test_macros.h"
#include <ttd/ttd.h>

/* ---- cubes in several triangulations ------------------------------------------------------ */

enum { CUBE_DIAG_A, CUBE_DIAG_B, CUBE_FAN, CUBE_SPLIT3, CUBE_UNSHARED, CUBE_KINDS };
static const char *cube_name[CUBE_KINDS] = {"12 triangles", "12 triangles, other diagonals", "centre fans",
                                            "faces split 3x3", "no shared vertices"};

typedef struct builder {
    double *v;
    uint32_t *t;
    size_t nv, nt, cap_v, cap_t;
} builder;

static void add_vertex(builder *b, const double x[3])
{
    if (b->nv == b->cap_v) {
        b->cap_v = b->cap_v ? 2 * b->cap_v : 64;
        b->v = realloc(b->v, 3 * b->cap_v * sizeof *b->v);
    }
    memcpy(b->v + 3 * b->nv++, x, 3 * sizeof *x);
}

static void add_triangle(builder *b, const double x[3], const double y[3], const double z[3])
{
    if (b->nt == b->cap_t) {
        b->cap_t = b->cap_t ? 2 * b->cap_t : 64;
        b->t = realloc(b->t, 3 * b->cap_t * sizeof *b->t);
    }
    const double *p[3] = {x, y, z};
    for (int k = 0; k < 3; ++k) {
        add_vertex(b, p[k]);
        b->t[3 * b->nt + (size_t)k] = (uint32_t)(b->nv - 1);
    }
    b->nt++;
}

/* The unit cube [0,1]^3, faces wound outward, in triangulation `kind`; every kind but
 * CUBE_UNSHARED shares vertices by index. */
static int cube_mesh(int kind, ttd_gen_mesh *g)
{
    static const double face[6][9] = {
        {0, 0, 0, 0, 1, 0, 1, 0, 0}, {0, 0, 1, 1, 0, 0, 0, 1, 0}, {0, 0, 0, 0, 0, 1, 0, 1, 0},
        {1, 0, 0, 0, 1, 0, 0, 0, 1}, {0, 0, 0, 1, 0, 0, 0, 0, 1}, {0, 1, 0, 0, 0, 1, 1, 0, 0}}; /* origin, U, V */
    builder b = {0};
    for (int f = 0; f < 6; ++f) {
        const double *o = face[f], *U = face[f] + 3, *V = face[f] + 6;
        const int n = kind == CUBE_SPLIT3 ? 3 : 1;
        for (int ia = 0; ia < n; ++ia)
            for (int ib = 0; ib < n; ++ib) {
                double P[2][2][3], C[3];
                for (int da = 0; da < 2; ++da)
                    for (int db = 0; db < 2; ++db)
                        for (int r = 0; r < 3; ++r)
                            P[da][db][r] = o[r] + (double)(ia + da) / n * U[r] + (double)(ib + db) / n * V[r];
                for (int r = 0; r < 3; ++r)
                    C[r] = 0.5 * (P[0][0][r] + P[1][1][r]);
                if (kind == CUBE_FAN) {
                    add_triangle(&b, P[0][0], P[1][0], C);
                    add_triangle(&b, P[1][0], P[1][1], C);
                    add_triangle(&b, P[1][1], P[0][1], C);
                    add_triangle(&b, P[0][1], P[0][0], C);
                } else if (kind == CUBE_DIAG_B || (kind == CUBE_SPLIT3 && (ia + ib) % 2)) {
                    add_triangle(&b, P[0][0], P[1][0], P[0][1]);
                    add_triangle(&b, P[1][0], P[1][1], P[0][1]);
                } else {
                    add_triangle(&b, P[0][0], P[1][0], P[1][1]);
                    add_triangle(&b, P[0][0], P[1][1], P[0][1]);
                }
            }
    }
    if (kind != CUBE_UNSHARED) { /* share vertices at equal coordinates */
        size_t nv = 0;
        uint32_t *map = malloc(b.nv * sizeof *map);
        ENSURE(map != NULL);
        for (size_t i = 0; i < b.nv; ++i) {
            size_t k = 0;
            while (k < nv && memcmp(b.v + 3 * k, b.v + 3 * i, 3 * sizeof(double)) != 0)
                ++k;
            if (k == nv)
                memmove(b.v + 3 * nv++, b.v + 3 * i, 3 * sizeof(double));
            map[i] = (uint32_t)k;
        }
        for (size_t i = 0; i < 3 * b.nt; ++i)
            b.t[i] = map[b.t[i]];
        b.nv = nv;
        free(map);
    }
    g->verts = b.v;
    g->nv = b.nv;
    g->tris = b.t;
    g->nt = b.nt;
    return 0;
}

static ttd_mesh *make_mesh(const ttd_gen_mesh *g, int bytes)
{
    ttd_mesh *m = NULL;
    if (bytes == 8) {
        if (ttd_mesh_create_d(NULL, g->verts, g->nv, g->tris, g->nt, &m) != TTD_OK)
            return NULL;
        return m;
    }
    float *v = malloc(3 * g->nv * sizeof *v);
    if (v == NULL)
        return NULL;
    for (size_t i = 0; i < 3 * g->nv; ++i)
        v[i] = (float)g->verts[i];
    if (ttd_mesh_create_f(NULL, v, g->nv, g->tris, g->nt, &m) != TTD_OK)
        m = NULL;
    free(v);
    return m;
}

/* A manifold widened to double. */
typedef struct mpoint {
    uint32_t i, j, ti, tj;
    double x[3], n[3], d, depth;
} mpoint;

static size_t ask_manifold(ttd_scene *s, int bytes, const ttd_options *opt, double margin, size_t k, mpoint **out)
{
    ttd_scene_array a = {0};
    size_t n = 0;
    *out = NULL;
    if (bytes == 8) {
        if (ttd_scene_manifold_d(opt, s, margin, k, &a) != TTD_OK)
            return SIZE_MAX;
        n = a.count;
        *out = malloc((n + 1) * sizeof **out);
        for (size_t q = 0; q < n; ++q) {
            const ttd_scene_point_d *p = (const ttd_scene_point_d *)a.data + q;
            mpoint m = {p->i, p->j, p->tri_i, p->tri_j, {0}, {0}, p->distance, p->depth};
            memcpy(m.x, p->point, sizeof m.x);
            memcpy(m.n, p->normal, sizeof m.n);
            (*out)[q] = m;
        }
    } else {
        if (ttd_scene_manifold_f(opt, s, (float)margin, k, &a) != TTD_OK)
            return SIZE_MAX;
        n = a.count;
        *out = malloc((n + 1) * sizeof **out);
        for (size_t q = 0; q < n; ++q) {
            const ttd_scene_point_f *p = (const ttd_scene_point_f *)a.data + q;
            mpoint m = {p->i, p->j, p->tri_i, p->tri_j, {0}, {0}, p->distance, p->depth};
            for (int r = 0; r < 3; ++r) {
                m.x[r] = p->point[r];
                m.n[r] = p->normal[r];
            }
            (*out)[q] = m;
        }
    }
    ttd_scene_array_free(&a);
    return n;
}

static int add_body(ttd_scene *s, int bytes, const ttd_mesh *m, const double pose[12])
{
    uint32_t id;
    if (bytes == 8)
        return ttd_scene_add_d(s, m, pose, &id) == TTD_OK ? 0 : 1;
    float pf[12];
    for (int k = 0; k < 12; ++k)
        pf[k] = (float)pose[k];
    return ttd_scene_add_f(s, m, pf, &id) == TTD_OK ? 0 : 1;
}

/* Pose of a unit cube turned by yaw (radians) about its centre, the centre then at c. */
static void cube_pose(double yaw, const double c[3], double pose[12])
{
    const double cs = cos(yaw), sn = sin(yaw);
    const double R[9] = {cs, -sn, 0, sn, cs, 0, 0, 0, 1};
    for (int r = 0; r < 3; ++r) {
        pose[4 * r] = R[3 * r];
        pose[4 * r + 1] = R[3 * r + 1];
        pose[4 * r + 2] = R[3 * r + 2];
        pose[4 * r + 3] = c[r] - (R[3 * r] * 0.5 + R[3 * r + 1] * 0.5 + R[3 * r + 2] * 0.5);
    }
}

/* The smallest distance between two points of body pair (i, j)'s points in m[0..n). */
static double closest_two(const mpoint *m, size_t n)
{
    double best = INFINITY;
    for (size_t a = 0; a < n; ++a)
        for (size_t b = a + 1; b < n; ++b) {
            if (m[a].i != m[b].i || m[a].j != m[b].j)
                continue;
            const double d[3] = {m[a].x[0] - m[b].x[0], m[a].x[1] - m[b].x[1], m[a].x[2] - m[b].x[2]};
            best = fmin(best, sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
        }
    return best;
}

/* ---- stacks --------------------------------------------------------------------------------- */

static int stacks_normals_up(void)
{
    static const double gaps[] = {0, 1e-3, 4e-3, 9.9e-3};
    static const double offsets[][2] = {{0, 0}, {0.5, 0.25}, {0.01, -0.015}, {-0.3, 0.6}, {0.004, 0}, {-0.0099, 0.0099}};
    static const double yaws[] = {0, 30, 7, 90, 45};
    const double margin = 0.01;
    size_t scenes = 0, points = 0;
    for (int bytes = 8; bytes >= 4; bytes -= 4) {
        ttd_gen_mesh g[CUBE_KINDS];
        ttd_mesh *m[CUBE_KINDS];
        for (int k = 0; k < CUBE_KINDS; ++k) {
            ENSURE(cube_mesh(k, &g[k]) == 0);
            ENSURE((m[k] = make_mesh(&g[k], bytes)) != NULL);
        }
        /* float: the yaws' rotations rounded to float are rotations only to 1e-7, and the gap
         * below the float rounding of 1 + gap is not a gap: the float rows take the exact ones */
        const double tol = bytes == 8 ? 1e-12 : 1e-6;
        for (int kb = 0; kb < CUBE_KINDS; ++kb)
            for (int kt = 0; kt < CUBE_KINDS; ++kt)
                for (size_t gi = 0; gi < sizeof gaps / sizeof gaps[0]; ++gi)
                    for (size_t oi = 0; oi < sizeof offsets / sizeof offsets[0]; ++oi)
                        for (size_t yi = 0; yi < sizeof yaws / sizeof yaws[0]; ++yi) {
                            if (bytes == 4 && (kb + kt + (int)gi + (int)oi + (int)yi) % 4 != 0)
                                continue; /* float: a quarter of the cases */
                            const double lower_c[3] = {0.5, 0.5, 0.5};
                            const double upper_c[3] = {0.5 + offsets[oi][0], 0.5 + offsets[oi][1], 1.5 + gaps[gi]};
                            double lower[12], upper[12];
                            cube_pose(yi % 2 ? 0.25 * yaws[yi] * 3.14159265358979323846 / 180 : 0, lower_c, lower);
                            cube_pose(yaws[yi] * 3.14159265358979323846 / 180, upper_c, upper);
                            for (int order = 0; order < 2; ++order) {
                                ttd_scene *s;
                                ENSURE((bytes == 8 ? ttd_scene_create_d(&s) : ttd_scene_create_f(&s)) == TTD_OK);
                                ENSURE(add_body(s, bytes, m[order ? kt : kb], order ? upper : lower) == 0);
                                ENSURE(add_body(s, bytes, m[order ? kb : kt], order ? lower : upper) == 0);
                                for (size_t K = 0; K <= 4; K += 4) {
                                    mpoint *p;
                                    const size_t n = ask_manifold(s, bytes, NULL, margin, K, &p);
                                    ENSURE(n != SIZE_MAX && n >= 1);
                                    const double up = order ? -1 : 1; /* from body 0 towards body 1 */
                                    for (size_t q = 0; q < n; ++q) {
                                        ENSURE_MSG(fabs(p[q].n[0]) <= tol && fabs(p[q].n[1]) <= tol &&
                                                       fabs(p[q].n[2] - up) <= tol,
                                                   "%s on %s, %s, gap %g, offset (%g, %g), yaw %g, K %zu: point %zu "
                                                   "(triangles %u, %u) at (%.9g, %.9g, %.9g): normal (%.3g, %.3g, %.17g)",
                                                   cube_name[kt], cube_name[kb], bytes == 8 ? "double" : "float",
                                                   gaps[gi], offsets[oi][0], offsets[oi][1], yaws[yi], K, q, p[q].ti,
                                                   p[q].tj, p[q].x[0], p[q].x[1], p[q].x[2], p[q].n[0], p[q].n[1],
                                                   p[q].n[2]);
                                    }
                                    /* no two points within the merge tolerance, 1e-3 of the smaller radius
                                     * (sqrt(3)/2 for the unit cube) */
                                    ENSURE(closest_two(p, n) > 1e-3 * sqrt(3) / 2 * (1 - 1e-9));
                                    points += n;
                                    free(p);
                                }
                                ttd_scene_destroy(s);
                                ++scenes;
                            }
                        }
        for (int k = 0; k < CUBE_KINDS; ++k) {
            ttd_mesh_destroy(m[k]);
            ttd_gen_mesh_free(&g[k]);
        }
    }
    printf("  %zu stacks, %zu manifold points: every normal +z from the lower cube to the upper\n", scenes, points);
    return 0;
}

/* How many points a manifold of two-body scene s (double, bodies 0 and 1: meshes g[0], g[1] at
 * poses pose[0], pose[1]) keeps at K = 0 (docs/scenes.md, section 5, steps 0 to 2): its contacts
 * (the contacts query, which tests/test_scene.c checks against brute force) and the corners they
 * add (scene_corners_ref.h), in depth order (distance, triangles, midpoint), a point within tol
 * of one kept before it dropped. SIZE_MAX on failure. */
static size_t merged_count(ttd_scene *s, const ttd_gen_mesh *g, const double (*pose)[12], double margin, double tol)
{
    ttd_scene_array ca = {0};
    if (ttd_scene_contacts_d(NULL, s, margin, &ca) != TTD_OK)
        return SIZE_MAX;
    const ttd_scene_contact_d *c = ca.data;
    double *w[2];
    corner_mesh shape[2];
    unsigned char *in = calloc(g[0].nt * g[1].nt, 1);
    for (int b = 0; b < 2; ++b) {
        w[b] = malloc(9 * g[b].nt * sizeof *w[b]);
        if (w[b] == NULL || !corner_mesh_make(g[b].verts, g[b].tris, g[b].nt, &shape[b]))
            return SIZE_MAX;
        for (size_t t = 0; t < g[b].nt; ++t)
            for (int k = 0; k < 3; ++k)
                for (int r = 0; r < 3; ++r) {
                    const double *x = g[b].verts + 3 * (size_t)g[b].tris[3 * t + (size_t)k], *P = pose[b];
                    w[b][9 * t + 3 * (size_t)k + (size_t)r] = ((P[4 * r] * x[0] + P[4 * r + 1] * x[1]) + P[4 * r + 2] * x[2]) + P[4 * r + 3];
                }
    }
    if (in == NULL)
        return SIZE_MAX;
    for (size_t a = 0; a < ca.count; ++a)
        in[(size_t)c[a].tri_i * g[1].nt + c[a].tri_j] = 1;
    corner_rec *corner;
    const size_t nc = corner_refs(&shape[0], w[0], &shape[1], w[1], in, margin, 8, &corner);
    if (nc == SIZE_MAX)
        return SIZE_MAX;
    /* the contacts of flat contact are no points: their region's corners stand for them */
    uint32_t *ti = malloc((ca.count + 1) * sizeof *ti), *tj = malloc((ca.count + 1) * sizeof *tj);
    double *cd = malloc((ca.count + 1) * sizeof *cd);
    unsigned char *flat = malloc(ca.count + 1);
    if (ti == NULL || tj == NULL || cd == NULL || flat == NULL)
        return SIZE_MAX;
    for (size_t a = 0; a < ca.count; ++a) {
        ti[a] = c[a].tri_i;
        tj[a] = c[a].tri_j;
        cd[a] = c[a].distance;
    }
    const size_t nflat = corner_ref_flat(&shape[0], w[0], &shape[1], w[1], ca.count, ti, tj, cd, flat);
    const size_t n = ca.count - nflat + nc;
    corner_rec *rec = malloc((n + 1) * sizeof *rec);
    double (*kept)[3] = malloc((n + 1) * sizeof *kept);
    if (rec == NULL || kept == NULL)
        return SIZE_MAX;
    size_t at = 0;
    for (size_t a = 0; a < ca.count; ++a) {
        if (flat[a])
            continue;
        corner_rec r = {c[a].tri_i, c[a].tri_j, c[a].distance, {0}, {0}};
        memcpy(r.p, c[a].p, sizeof r.p);
        memcpy(r.q, c[a].q, sizeof r.q);
        rec[at++] = r;
    }
    free(ti);
    free(tj);
    free(cd);
    free(flat);
    if (nc > 0)
        memcpy(rec + at, corner, nc * sizeof *rec);
    for (size_t a = 1; a < n; ++a) /* depth order: distance, triangles, midpoint */
        for (size_t b = a; b > 0; --b) {
            const corner_rec *x = &rec[b], *y = &rec[b - 1];
            int before = x->d != y->d ? x->d < y->d : x->ti != y->ti ? x->ti < y->ti : x->tj != y->tj ? x->tj < y->tj : 0;
            if (x->d == y->d && x->ti == y->ti && x->tj == y->tj)
                for (int r = 2; r >= 0; --r)
                    if (0.5 * x->p[r] + 0.5 * x->q[r] != 0.5 * y->p[r] + 0.5 * y->q[r])
                        before = 0.5 * x->p[r] + 0.5 * x->q[r] < 0.5 * y->p[r] + 0.5 * y->q[r];
            if (!before)
                break;
            const corner_rec t = rec[b];
            rec[b] = rec[b - 1];
            rec[b - 1] = t;
        }
    size_t want = 0;
    for (size_t a = 0; a < n; ++a) {
        double x[3];
        int near = 0;
        for (int r = 0; r < 3; ++r)
            x[r] = 0.5 * rec[a].p[r] + 0.5 * rec[a].q[r];
        for (size_t b = 0; b < want && !near; ++b)
            near = hypot(hypot(x[0] - kept[b][0], x[1] - kept[b][1]), x[2] - kept[b][2]) <= tol;
        if (!near)
            memcpy(kept[want++], x, sizeof x);
    }
    free(rec);
    free(kept);
    free(corner);
    free(in);
    for (int b = 0; b < 2; ++b) {
        free(w[b]);
        corner_mesh_free(&shape[b]);
    }
    ttd_scene_array_free(&ca);
    return want;
}

static double hull_area_xy(const double (*x)[3], size_t n);

/* The rotation about unit axis a by angle t, into pose's 3x3 part, the centre c of a unit cube
 * kept at c (cube_pose's convention). */
static void tilted_cube_pose(const double a[3], double t, const double c[3], double pose[12])
{
    const double cs = cos(t), sn = sin(t), v = 1 - cs;
    const double R[9] = {cs + a[0] * a[0] * v,        a[0] * a[1] * v - a[2] * sn, a[0] * a[2] * v + a[1] * sn,
                         a[1] * a[0] * v + a[2] * sn, cs + a[1] * a[1] * v,        a[1] * a[2] * v - a[0] * sn,
                         a[2] * a[0] * v - a[1] * sn, a[2] * a[1] * v + a[0] * sn, cs + a[2] * a[2] * v};
    for (int r = 0; r < 3; ++r) {
        pose[4 * r] = R[3 * r];
        pose[4 * r + 1] = R[3 * r + 1];
        pose[4 * r + 2] = R[3 * r + 2];
        pose[4 * r + 3] = c[r] - (R[3 * r] * 0.5 + R[3 * r + 1] * 0.5 + R[3 * r + 2] * 0.5);
    }
}

/* Stacks whose cubes are tilted by a hair (1e-7 to 1e-4 rad, what one step of a simulated stack
 * leaves): corners over corners and edges over edges, whose normal cones meet only in the
 * vertical ray when aligned and miss each other once tilted. Every normal within the tilts
 * (plus the flat angle, 1e-3) of +z. The simulator of examples/sim found (-1, 0, 0) at a corner
 * after one step (its poses are the last case); the cones now count as meeting when they miss by
 * less than the flat angle (src/scene/normal_impl.h, CONE_LOOSE). */
static int tilted_stacks_normals_up(void)
{
    static const double tilts[] = {1e-7, 1e-6, 1e-5, 1e-4};
    static const double axes[][3] = {{1, 0, 0}, {0, 1, 0}, {0.6, 0.8, 0}, {0.48, 0.6, 0.64}};
    static const double offsets[][2] = {{0, 0}, {1e-5, -1e-5}, {0.3, 0.2}};
    /* gap, margin: apart (crossing bodies, d = 0 at points on their intersection, are the solids' case) */
    static const double gaps[][2] = {{0.01, 0.04}, {0.001, 0.01}, {0.004, 0.01}};
    size_t scenes = 0, points = 0;
    double worst = 0;
    ttd_gen_mesh g[CUBE_KINDS];
    ttd_mesh *m[CUBE_KINDS];
    for (int k = 0; k < CUBE_KINDS; ++k) {
        ENSURE(cube_mesh(k, &g[k]) == 0);
        ENSURE((m[k] = make_mesh(&g[k], 8)) != NULL);
    }
    for (int kb = 0; kb < CUBE_KINDS; ++kb)
        for (int kt = 0; kt < CUBE_KINDS; ++kt)
            for (size_t ti = 0; ti < sizeof tilts / sizeof tilts[0]; ++ti)
                for (size_t ai = 0; ai < sizeof axes / sizeof axes[0]; ++ai)
                    for (size_t oi = 0; oi < sizeof offsets / sizeof offsets[0]; ++oi) {
                        const size_t gi = (ti + ai + oi + (size_t)kb) % (sizeof gaps / sizeof gaps[0]);
                        const double lower_c[3] = {0.5, 0.5, 0.5};
                        const double upper_c[3] = {0.5 + offsets[oi][0], 0.5 + offsets[oi][1], 1.5 + gaps[gi][0]};
                        const double *other = axes[(ai + 1) % (sizeof axes / sizeof axes[0])];
                        double lower[12], upper[12];
                        tilted_cube_pose(other, -0.5 * tilts[ti], lower_c, lower);
                        tilted_cube_pose(axes[ai], tilts[ti], upper_c, upper);
                        ttd_scene *s;
                        ENSURE(ttd_scene_create_d(&s) == TTD_OK);
                        ENSURE(add_body(s, 8, m[kb], lower) == 0);
                        ENSURE(add_body(s, 8, m[kt], upper) == 0);
                        mpoint *p;
                        const size_t n = ask_manifold(s, 8, NULL, gaps[gi][1], 4, &p);
                        ENSURE(n != SIZE_MAX && n >= 1);
                        const double limit = 1e-3 + 2 * tilts[ti];
                        for (size_t q = 0; q < n; ++q) {
                            const double off = acos(fmin(1.0, p[q].n[2]));
                            worst = fmax(worst, off);
                            ENSURE_MSG(off <= limit,
                                       "%s on %s, tilt %g about (%g, %g, %g), offset (%g, %g), gap %g: point %zu "
                                       "(triangles %u, %u) at (%.9g, %.9g, %.9g): normal (%.3g, %.3g, %.17g)",
                                       cube_name[kt], cube_name[kb], tilts[ti], axes[ai][0], axes[ai][1], axes[ai][2],
                                       offsets[oi][0], offsets[oi][1], gaps[gi][0], q, p[q].ti, p[q].tj, p[q].x[0],
                                       p[q].x[1], p[q].x[2], p[q].n[0], p[q].n[1], p[q].n[2]);
                        }
                        points += n;
                        free(p);
                        ttd_scene_destroy(s);
                        ++scenes;
                    }
    /* the simulator's two boxes after one step (docs/simulator.md), the 12-triangle cube centred */
    {
        static const double step1[2][12] = {
            {0.99999999999601441, -4.0581818028281941e-07, 2.7940023696132233e-06, -1.6755089336489047e-06,
             4.0582053126103198e-07, 0.99999999999956368, -8.4143692854671585e-07, -1.5607188907867611e-06,
             -2.794002028141601e-06, 8.4143806240688817e-07, 0.99999999999574274, 0.50998728181903719},
            {0.99999999999847911, -2.7477712565268328e-07, 1.7222880665239525e-06, -3.9130060061552404e-07,
             2.7477648550773414e-07, 0.9999999999998932, 3.7168308260064119e-07, -2.4638608639301593e-06,
             -1.7222881686537774e-06, -3.7168260935581392e-07, 0.9999999999984478, 1.5199711245388927}};
        ttd_gen_mesh c = {NULL, 0, NULL, 0};
        ENSURE(cube_mesh(0, &c) == 0);
        for (size_t v = 0; v < 3 * c.nv; ++v) /* centred */
            c.verts[v] -= 0.5;
        ttd_mesh *mc = make_mesh(&c, 8);
        ENSURE(mc != NULL);
        ttd_scene *s;
        ENSURE(ttd_scene_create_d(&s) == TTD_OK);
        ENSURE(add_body(s, 8, mc, step1[0]) == 0 && add_body(s, 8, mc, step1[1]) == 0);
        mpoint *p;
        const size_t n = ask_manifold(s, 8, NULL, 0.04, 4, &p);
        ENSURE(n == 4);
        for (size_t q = 0; q < n; ++q)
            ENSURE_MSG(acos(fmin(1.0, p[q].n[2])) <= 1e-5, "the simulator's step: point %zu normal (%.3g, %.3g, %.17g)", q,
                       p[q].n[0], p[q].n[1], p[q].n[2]);
        free(p);
        ttd_scene_destroy(s);
        ttd_mesh_destroy(mc);
        ttd_gen_mesh_free(&c);
    }
    for (int k = 0; k < CUBE_KINDS; ++k) {
        ttd_mesh_destroy(m[k]);
        ttd_gen_mesh_free(&g[k]);
    }
    printf("  %zu tilted stacks and the simulator's step, %zu points: every normal within the tilts and the flat "
           "angle of +z (worst %.3g rad)\n",
           scenes, points, worst);
    return 0;
}

/* A torus lying on a floor inside the margin: its points are spread over the contacts of the
 * deepest level (the ring resting on the floor), not over the speculative ones farther inside the
 * margin (the simulator saw one point at the resting level and three 0.02 above it, and the torus
 * rocked): every point within a quarter of the margin left below the deepest, and the four span
 * the ring (their hull's area at least a third of the square inscribed in the ring's middle
 * circle). */
static int torus_on_floor_level(void)
{
    ttd_gen_mesh torus = {NULL, 0, NULL, 0}, floor_g = {NULL, 0, NULL, 0};
    ENSURE(ttd_gen_torus(1.0, 0.25, 48, 16, &torus) == 0);
    ENSURE(cube_mesh(0, &floor_g) == 0);
    for (size_t v = 0; v < floor_g.nv; ++v) { /* a 8 x 8 x 1 slab, top at z = 0 */
        floor_g.verts[3 * v] = 8 * floor_g.verts[3 * v] - 4;
        floor_g.verts[3 * v + 1] = 8 * floor_g.verts[3 * v + 1] - 4;
        floor_g.verts[3 * v + 2] -= 1;
    }
    ttd_mesh *mt = make_mesh(&torus, 8), *mf = make_mesh(&floor_g, 8);
    ENSURE(mt && mf);
    static const double gaps[] = {0.002, 0.01}, margins[] = {0.02, 0.04};
    size_t cases = 0;
    for (size_t gi = 0; gi < 2; ++gi)
        for (size_t mi = 0; mi < 2; ++mi)
            for (int turn = 0; turn < 4; ++turn) {
                const double t = 0.1 * turn, cs = cos(t), sn = sin(t);
                const double pt[12] = {cs, -sn, 0, 0.1 * turn, sn, cs, 0, -0.05 * turn, 0, 0, 1, 0.25 + gaps[gi]};
                const double pf[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
                ttd_scene *s;
                ENSURE(ttd_scene_create_d(&s) == TTD_OK);
                ENSURE(add_body(s, 8, mf, pf) == 0 && add_body(s, 8, mt, pt) == 0);
                mpoint *p;
                const size_t n = ask_manifold(s, 8, NULL, margins[mi], 4, &p);
                ENSURE(n == 4);
                double d0 = INFINITY;
                for (size_t q = 0; q < n; ++q)
                    d0 = fmin(d0, p[q].d);
                for (size_t q = 0; q < n; ++q)
                    ENSURE_MSG(p[q].d - d0 <= 0.25 * (margins[mi] - d0), "gap %g, margin %g, turn %d: point %zu at %g, "
                               "the deepest at %g", gaps[gi], margins[mi], turn, q, p[q].d, d0);
                const double x[4][3] = {{p[0].x[0], p[0].x[1], 0}, {p[1].x[0], p[1].x[1], 0}, {p[2].x[0], p[2].x[1], 0},
                                        {p[3].x[0], p[3].x[1], 0}};
                const double area = hull_area_xy(x, 4);
                ENSURE_MSG(area >= 2.0 / 3, "gap %g, margin %g, turn %d: the points' hull %g", gaps[gi], margins[mi],
                           turn, area);
                free(p);
                ttd_scene_destroy(s);
                ++cases;
            }
    ttd_mesh_destroy(mt);
    ttd_mesh_destroy(mf);
    ttd_gen_mesh_free(&torus);
    ttd_gen_mesh_free(&floor_g);
    printf("  %zu tori on a floor: four points of the resting level spanning the ring\n", cases);
    return 0;
}

/* Stacks at the ends of the double range (1e-300 .. 1e150; issue 23 found sideways normals at
 * 1e70 and 1e-78, a touching pair lost at 1e-163 and squared distances underflowing near
 * 1e-160): every normal +z, and as many points as the contacts and corners at that scale merged (K = 0;
 * at most 4 with K = 4). (Not the same points as at size 1: where faces lie on faces a
 * contact's closest point is one of many, and which one follows the rounding.) */
static int stacks_at_extreme_scales(void)
{
    static const double scales[] = {1e-300, 1e-163, 1e-160, 1e-78, 1e70, 1e150};
    static const int kinds[][2] = {{CUBE_DIAG_A, CUBE_DIAG_B}, {CUBE_FAN, CUBE_SPLIT3}, {CUBE_DIAG_A, CUBE_DIAG_A}};
    static const double gaps[] = {0, 4e-3};
    static const double offsets[][2] = {{0.5, 0.25}, {0.01, -0.015}};
    static const double yaws[] = {0, 30};
    size_t cases = 0;
    for (size_t ki = 0; ki < sizeof kinds / sizeof kinds[0]; ++ki)
        for (size_t gi = 0; gi < 2; ++gi)
            for (size_t oi = 0; oi < 2; ++oi)
                for (size_t yi = 0; yi < 2; ++yi) {
                    for (size_t sc = 0; sc <= sizeof scales / sizeof scales[0]; ++sc) {
                        const double scale = sc == 0 ? 1 : scales[sc - 1];
                        ttd_gen_mesh g[2];
                        ttd_mesh *m[2];
                        for (int k = 0; k < 2; ++k) {
                            ENSURE(cube_mesh(kinds[ki][k], &g[k]) == 0);
                            for (size_t i = 0; i < 3 * g[k].nv; ++i)
                                g[k].verts[i] *= scale;
                            ENSURE((m[k] = make_mesh(&g[k], 8)) != NULL);
                        }
                        const double lower_c[3] = {0.5, 0.5, 0.5};
                        const double upper_c[3] = {0.5 + offsets[oi][0], 0.5 + offsets[oi][1], 1.5 + gaps[gi]};
                        double lower[12], upper[12];
                        cube_pose(0, lower_c, lower);
                        cube_pose(yaws[yi] * 3.14159265358979323846 / 180, upper_c, upper);
                        for (int r = 0; r < 3; ++r) { /* the poses about the scaled cubes */
                            lower[4 * r + 3] *= scale;
                            upper[4 * r + 3] *= scale;
                        }
                        ttd_scene *s;
                        ENSURE(ttd_scene_create_d(&s) == TTD_OK);
                        ENSURE(add_body(s, 8, m[0], lower) == 0 && add_body(s, 8, m[1], upper) == 0);
                        for (size_t K = 0; K <= 4; K += 4) {
                            mpoint *p;
                            const size_t n = ask_manifold(s, 8, NULL, 0.01 * scale, K, &p);
                            ENSURE(n != SIZE_MAX && n >= 1);
                            /* the contacts and their corners at this scale, merged as docs/scenes.md says
                             * (within 1e-3 of the cube's radius sqrt(3)/2 of a point kept): K = 0 keeps
                             * them all, K = 4 min(4, them) */
                            double both[2][12];
                            memcpy(both[0], lower, sizeof lower);
                            memcpy(both[1], upper, sizeof upper);
                            const size_t want = merged_count(s, g, (const double (*)[12])both, 0.01 * scale, 1e-3 * sqrt(3) / 2 * scale);
                            ENSURE(want != SIZE_MAX);
                            ENSURE_MSG(n == (K == 0 || want < K ? want : K), "scale %g: %zu points, %zu kept", scale, n, want);
                            for (size_t q = 0; q < n; ++q)
                                ENSURE_MSG(fabs(p[q].n[0]) <= 1e-12 && fabs(p[q].n[1]) <= 1e-12 && fabs(p[q].n[2] - 1) <= 1e-12,
                                           "scale %g, kinds %d on %d, gap %g, offset (%g, %g), yaw %g, K %zu: point %zu normal "
                                           "(%g, %g, %.17g)", scale, kinds[ki][1], kinds[ki][0], gaps[gi], offsets[oi][0],
                                           offsets[oi][1], yaws[yi], K, q, p[q].n[0], p[q].n[1], p[q].n[2]);
                            free(p);
                        }
                        ttd_scene_destroy(s);
                        for (int k = 0; k < 2; ++k) {
                            ttd_mesh_destroy(m[k]);
                            ttd_gen_mesh_free(&g[k]);
                        }
                        ++cases;
                    }
                }
    printf("  %zu stacks at scales 1e-300 to 1e150 and 1: every normal +z, the merged contacts' count\n", cases);
    return 0;
}

/* The area of the convex hull of points x[0..n) projected on the xy plane (Andrew's chain). */
static double hull_area_xy(const double (*x)[3], size_t n)
{
    size_t *o = malloc((n + 1) * sizeof *o), *h = malloc((2 * n + 2) * sizeof *h), k = 0;
    for (size_t a = 0; a < n; ++a)
        o[a] = a;
    for (size_t a = 1; a < n; ++a) /* by x, then y */
        for (size_t b = a; b > 0 && (x[o[b]][0] < x[o[b - 1]][0] ||
                                     (x[o[b]][0] == x[o[b - 1]][0] && x[o[b]][1] < x[o[b - 1]][1]));
             --b) {
            const size_t t = o[b];
            o[b] = o[b - 1];
            o[b - 1] = t;
        }
#define CROSS(a, b, c) ((x[b][0] - x[a][0]) * (x[c][1] - x[a][1]) - (x[b][1] - x[a][1]) * (x[c][0] - x[a][0]))
    for (size_t a = 0; a < n; ++a) {
        while (k >= 2 && CROSS(h[k - 2], h[k - 1], o[a]) <= 0)
            --k;
        h[k++] = o[a];
    }
    for (size_t a = n - 1, t = k + 1; a-- > 0;) {
        while (k >= t && CROSS(h[k - 2], h[k - 1], o[a]) <= 0)
            --k;
        h[k++] = o[a];
    }
#undef CROSS
    double area = 0;
    for (size_t a = 0; a + 1 < k; ++a)
        area += x[h[a]][0] * x[h[a + 1]][1] - x[h[a]][1] * x[h[a + 1]][0];
    free(o);
    free(h);
    return 0.5 * fabs(area);
}

/* The distance from xy point x to convex polygon v[0..n) (counter-clockwise; 0 inside). */
static double polygon_distance(const double (*v)[2], size_t n, const double x[2])
{
    int inside = 1;
    double best = INFINITY;
    for (size_t e = 0; e < n; ++e) {
        const double *p = v[e], *q = v[(e + 1) % n];
        const double d[2] = {q[0] - p[0], q[1] - p[1]}, w[2] = {x[0] - p[0], x[1] - p[1]};
        inside &= d[0] * w[1] - d[1] * w[0] >= 0;
        const double L = d[0] * d[0] + d[1] * d[1];
        double t = L > 0 ? (d[0] * w[0] + d[1] * w[1]) / L : 0;
        t = t < 0 ? 0 : t > 1 ? 1 : t;
        best = fmin(best, hypot(w[0] - t * d[0], w[1] - t * d[1]));
    }
    return inside ? 0 : best;
}

/* A box on a box, flush and at gaps up to the margin, offset and turned about z, in every
 * triangulation, either body first: the contact region is the overlap of the lower box's top face
 * and the upper box's bottom face (a convex polygon, found here by clipping), offset from the
 * lower box's edges by more than the margin. Unturned, K = 4 gives the rectangle's four corners;
 * turned, four points within the margin of four of its corners (where rims cross near a corner,
 * points of either face within the margin of the other body's side lie beyond it). K = 0 gives
 * every corner, and no point farther from the region than the margin (those points, and triangle
 * pairs' closest points on a side face's diagonal below the top).
 * (Before the corners of flat contact, step 0 of the reduction, 15 of 200 unturned cases missed a
 * corner: a contact's point is its triangle pair's closest point, one of many where faces lie on
 * faces.) */
static int box_on_box_corners(void)
{
    static const double gaps[] = {0, 2e-3, 9.9e-3};
    static const double offsets[][2] = {{0.5, 0.25}, {-0.3, 0.6}, {0, 0}, {0.2, -0.7}, {0.04, 0.3}, {-0.45, -0.45}};
    static const double yaws[] = {0, 30, 7, 45};
    size_t cases = 0, corners = 0, rects = 0;
    ttd_gen_mesh g[CUBE_KINDS];
    ttd_mesh *m[CUBE_KINDS];
    for (int k = 0; k < CUBE_KINDS; ++k) {
        ENSURE(cube_mesh(k, &g[k]) == 0);
        ENSURE((m[k] = make_mesh(&g[k], 8)) != NULL);
    }
    for (int kb = 0; kb < CUBE_KINDS; ++kb)
        for (int kt = 0; kt < CUBE_KINDS; ++kt)
            for (size_t gi = 0; gi < sizeof gaps / sizeof gaps[0]; ++gi)
                for (size_t oi = 0; oi < sizeof offsets / sizeof offsets[0]; ++oi)
                    for (size_t yi = 0; yi < sizeof yaws / sizeof yaws[0]; ++yi) {
                        if ((kb + kt + (int)gi + (int)oi + (int)yi) % 2 != 0 && yi != 0)
                            continue; /* turned: half the cases */
                        const int order = (kb + (int)oi) % 2;
                        const double lower_c[3] = {0.5, 0.5, 0.5};
                        const double upper_c[3] = {0.5 + offsets[oi][0], 0.5 + offsets[oi][1], 1.5 + gaps[gi]};
                        double pose[2][12];
                        cube_pose(yi == 2 ? 0.3 * yaws[yi] * 3.14159265358979323846 / 180 : 0, lower_c, pose[0]);
                        cube_pose(yaws[yi] * 3.14159265358979323846 / 180, upper_c, pose[1]);
                        /* the faces' squares in the world (xy), counter-clockwise, and their overlap */
                        static const double sq[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
                        double face[2][4][2], region[16][2];
                        for (int b = 0; b < 2; ++b)
                            for (int k = 0; k < 4; ++k)
                                for (int r = 0; r < 2; ++r)
                                    face[b][k][r] = pose[b][4 * r] * sq[k][0] + pose[b][4 * r + 1] * sq[k][1] + pose[b][4 * r + 3];
                        const size_t nr = test_clip_polygon((const double (*)[2])face[1], 4, (const double (*)[2])face[0], 4, region);
                        ENSURE(nr >= 3);
                        ttd_scene *s;
                        ENSURE(ttd_scene_create_d(&s) == TTD_OK);
                        ENSURE(add_body(s, 8, m[order ? kt : kb], pose[order]) == 0);
                        ENSURE(add_body(s, 8, m[order ? kb : kt], pose[!order]) == 0);
                        mpoint *p, *all;
                        const size_t n = ask_manifold(s, 8, NULL, 0.01, 4, &p), na = ask_manifold(s, 8, NULL, 0.01, 0, &all);
                        ENSURE(n == 4 && na != SIZE_MAX && na >= 4);
                        char what[200];
                        snprintf(what, sizeof what, "%s on %s, gap %g, offset (%g, %g), yaw %g, %s first", cube_name[kt],
                                 cube_name[kb], gaps[gi], offsets[oi][0], offsets[oi][1], yaws[yi], order ? "upper" : "lower");
                        /* K = 4: four corners of the region (turned: where rims cross near a corner, points of
                         * either face within the margin of the other body's side lie beyond it; four points
                         * within the margin of four different corners) */
                        double x4[4][3];
                        int near_corner[4];
                        for (size_t q = 0; q < 4; ++q) {
                            double best = INFINITY;
                            for (size_t c = 0; c < nr; ++c) {
                                const double dc = hypot(p[q].x[0] - region[c][0], p[q].x[1] - region[c][1]);
                                if (dc < best) {
                                    best = dc;
                                    near_corner[q] = (int)c;
                                }
                            }
                            ENSURE_MSG(best <= (yi == 0 ? 1e-12 : 0.01), "%s: K = 4 point %zu at (%.17g, %.17g) is %.3g from the "
                                       "region's nearest corner", what, q, p[q].x[0], p[q].x[1], best);
                            for (size_t r = 0; r < q; ++r)
                                ENSURE_MSG(near_corner[r] != near_corner[q], "%s: K = 4 points %zu and %zu at one corner", what, r, q);
                            memcpy(x4[q], p[q].x, sizeof x4[q]);
                        }
                        if (yi == 0) { /* a rectangle: all four corners, its area */
                            double y[4][3] = {{0}};
                            ENSURE(nr == 4);
                            for (size_t c = 0; c < 4; ++c)
                                memcpy(y[c], region[c], sizeof region[c]);
                            ENSURE_NEAR(hull_area_xy((const double (*)[3])x4, 4), hull_area_xy((const double (*)[3])y, 4), 1e-12);
                            ++rects;
                        }
                        /* K = 0: every corner, nothing off the region, at heights between the faces */
                        for (size_t c = 0; c < nr; ++c) {
                            double best = INFINITY;
                            for (size_t q = 0; q < na; ++q)
                                best = fmin(best, hypot(all[q].x[0] - region[c][0], all[q].x[1] - region[c][1]));
                            ENSURE_MSG(best <= 1e-12, "%s: the region's corner (%.17g, %.17g) is %.3g from every K = 0 point",
                                       what, region[c][0], region[c][1], best);
                        }
                        for (size_t q = 0; q < na; ++q) {
                            ENSURE_MSG(polygon_distance((const double (*)[2])region, nr, all[q].x) <= 0.01 &&
                                           all[q].x[2] >= 1 - 0.01 && all[q].x[2] <= 1 + gaps[gi] + 0.01,
                                       "%s: K = 0 point (%.17g, %.17g, %.17g) off the region", what, all[q].x[0], all[q].x[1],
                                       all[q].x[2]);
                            ENSURE(all[q].d <= 0.01 && all[q].d >= gaps[gi] - 1e-12);
                        }
                        corners += nr;
                        free(all);
                        free(p);
                        ttd_scene_destroy(s);
                        ++cases;
                    }
    for (int k = 0; k < CUBE_KINDS; ++k) {
        ttd_mesh_destroy(m[k]);
        ttd_gen_mesh_free(&g[k]);
    }
    printf("  %zu boxes on boxes: K = 4 gives four corners of the overlap (%zu unturned: exactly its rectangle's), "
           "K = 0 all %zu corners\n", cases, rects, corners);
    return 0;
}

/* A box resting on a box, faces parallel at the gap, the upper one shifted and turned a little
 * (a simulated stack's boxes: 0.02 and up to 3 degrees, ttd_sim's stacks) with the simulator's
 * margin: K = 4 are four points of the resting level, each at the gap (to rounding), spanning
 * at least half the faces' overlap. Where the upper box's edge overhangs the lower one's near a
 * corner, the pair of a side triangle and the overhanging edge has its closest points beside
 * the corner at a distance a little over the gap; before the level's slope rule the spread took
 * it for that corner (it adds a little more area), and the box rested on three points and crept
 * (ttd_sim's stacks drifted 0.047 of a box in 10 s). */
static int box_on_box_level(void)
{
    const double gap = 0.01, margin = 0.04;
    size_t cases = 0;
    ttd_gen_mesh g[CUBE_KINDS];
    ttd_mesh *m[CUBE_KINDS];
    for (int k = 0; k < CUBE_KINDS; ++k) {
        ENSURE(cube_mesh(k, &g[k]) == 0);
        ENSURE((m[k] = make_mesh(&g[k], 8)) != NULL);
    }
    for (int kb = 0; kb < CUBE_KINDS; ++kb)
        for (int kt = 0; kt < CUBE_KINDS; ++kt)
            for (int k = 0; k < 9; ++k) { /* ttd_sim's stack: box k + 1 on box k */
                double c[2][3], pose[2][12];
                for (int b = 0; b < 2; ++b) {
                    c[b][0] = 0.02 * cos(1.7 * (k + b));
                    c[b][1] = 0.02 * sin(1.7 * (k + b));
                    c[b][2] = 0.5 + (k + b) * (1 + gap);
                    cube_pose(0.05 * sin(2.3 * (k + b)), c[b], pose[b]);
                }
                static const double sq[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
                double face[2][4][2], region[16][2];
                for (int b = 0; b < 2; ++b)
                    for (int v = 0; v < 4; ++v)
                        for (int r = 0; r < 2; ++r)
                            face[b][v][r] = pose[b][4 * r] * sq[v][0] + pose[b][4 * r + 1] * sq[v][1] + pose[b][4 * r + 3];
                const size_t nr = test_clip_polygon((const double (*)[2])face[1], 4, (const double (*)[2])face[0], 4, region);
                ENSURE(nr >= 3);
                double area = 0;
                for (size_t v = 0; v < nr; ++v)
                    area += region[v][0] * region[(v + 1) % nr][1] - region[(v + 1) % nr][0] * region[v][1];
                area = fabs(area) / 2;
                ttd_scene *s;
                ENSURE(ttd_scene_create_d(&s) == TTD_OK);
                ENSURE(add_body(s, 8, m[kb], pose[0]) == 0 && add_body(s, 8, m[kt], pose[1]) == 0);
                mpoint *p;
                const size_t n = ask_manifold(s, 8, NULL, margin, 4, &p);
                ENSURE(n == 4);
                double x[4][3];
                for (size_t q = 0; q < n; ++q) {
                    ENSURE_MSG(fabs(p[q].d - gap) <= 1e-12, "%s on %s, box %d: point %zu (%g, %g) at %.17g, not at the gap",
                               cube_name[kt], cube_name[kb], k + 1, q, p[q].x[0], p[q].x[1], p[q].d);
                    x[q][0] = p[q].x[0];
                    x[q][1] = p[q].x[1];
                    x[q][2] = 0;
                }
                const double spanned = hull_area_xy((const double (*)[3])x, 4);
                ENSURE_MSG(spanned >= 0.5 * area, "%s on %s, box %d: the points span %g of an overlap of %g",
                           cube_name[kt], cube_name[kb], k + 1, spanned, area);
                free(p);
                ttd_scene_destroy(s);
                ++cases;
            }
    for (int k = 0; k < CUBE_KINDS; ++k) {
        ttd_mesh_destroy(m[k]);
        ttd_gen_mesh_free(&g[k]);
    }
    printf("  %zu boxes on boxes as ttd_sim stacks them: four points at the gap, spanning the overlap\n", cases);
    return 0;
}

/* A ball (icosphere, 5120 triangles, radius 1) resting in a groove of two plates (one body of
 * two boxes) at the gap on both sides, the groove's sides 35 to 60 degrees from horizontal, the
 * ball turned about z: K = 4 holds a point of each side touching (within 1/64 of the margin left
 * above the gap: 4.7e-4), with that side's normal; K = 0 one at the gap (to 1e-9). The
 * deepest level (a quarter of the margin left) holds the ball's vertices around each side's
 * touching one, millimetres above it; spread over the whole level, the four points went to the
 * far ones and left a side with no point within 4.7e-4 of the gap (in ttd_sim's bin, an
 * icosphere on two parts of a torus and a box on a torus's ring rested on one side and crept). */
static int ball_in_groove(void)
{
    const double gap = 0.01, margin = 0.04, touch = (margin - gap) / 64; /* docs/scenes.md: touching */
    ttd_gen_mesh ball = {NULL, 0, NULL, 0}, cube = {NULL, 0, NULL, 0};
    ENSURE(ttd_gen_icosphere(4, &ball) == 0 && cube_mesh(CUBE_DIAG_A, &cube) == 0);
    ttd_mesh *mb = make_mesh(&ball, 8);
    ENSURE(mb != NULL);
    size_t cases = 0;
    for (int ai = 0; ai < 3; ++ai)
        for (int turn = 0; turn < 4; ++turn) {
            const double a = (35.0 + 12.5 * ai) * 3.141592653589793 / 180, t = 0.37 * turn;
            const double pose[12] = {cos(t), -sin(t), 0, 0, sin(t), cos(t), 0, 0, 0, 0, 1, 0};
            /* side k's normal n (towards the ball), its plate's top face at gap below the ball's
             * lowest vertex along -n */
            double n[2][3] = {{0, -sin(a), cos(a)}, {0, sin(a), cos(a)}};
            builder b = {0};
            for (int k = 0; k < 2; ++k) {
                double h = -INFINITY;
                for (size_t v = 0; v < ball.nv; ++v) {
                    double x[3];
                    for (int r = 0; r < 3; ++r)
                        x[r] = pose[4 * r] * ball.verts[3 * v] + pose[4 * r + 1] * ball.verts[3 * v + 1] +
                               pose[4 * r + 2] * ball.verts[3 * v + 2];
                    h = fmax(h, -(x[0] * n[k][0] + x[1] * n[k][1] + x[2] * n[k][2]));
                }
                const double e1[3] = {1, 0, 0}, e2[3] = {0, n[k][2], -n[k][1]}; /* e1 x e2 = n */
                for (size_t f = 0; f < cube.nt; ++f) {
                    double x[3][3];
                    for (int c = 0; c < 3; ++c) {
                        const double *X = cube.verts + 3 * cube.tris[3 * f + (size_t)c];
                        const double u = 3 * X[0] - 1.5, w = 1.6 * X[1] - 0.8, z = 0.2 * X[2] - 0.2;
                        for (int r = 0; r < 3; ++r)
                            x[c][r] = -(h + gap) * n[k][r] + u * e1[r] + w * e2[r] + z * n[k][r];
                    }
                    add_triangle(&b, x[0], x[1], x[2]);
                }
            }
            ttd_mesh *mp;
            ENSURE(ttd_mesh_create_d(NULL, b.v, b.nv, b.t, b.nt, &mp) == TTD_OK);
            free(b.v);
            free(b.t);
            const double id[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
            ttd_scene *s;
            ENSURE(ttd_scene_create_d(&s) == TTD_OK);
            ENSURE(add_body(s, 8, mb, pose) == 0 && add_body(s, 8, mp, id) == 0);
            for (int all = 1; all >= 0; --all) { /* K = 0 holds both (the test's own check), then K = 4 */
                mpoint *p;
                const size_t np = ask_manifold(s, 8, NULL, margin, all ? 0 : 4, &p);
                ENSURE(np != SIZE_MAX && (all || np == 4));
                for (int k = 0; k < 2; ++k) {
                    int held = 0;
                    for (size_t q = 0; q < np; ++q) /* the normal from the ball (body 0) to the plate: -n */
                        held |= p[q].d - gap <= (all ? 1e-9 : touch) &&
                                -(p[q].n[0] * n[k][0] + p[q].n[1] * n[k][1] + p[q].n[2] * n[k][2]) >= cos(0.1);
                    ENSURE_MSG(held, "groove at %.1f degrees, turn %d, K = %d: no point touching side %d (of %zu)",
                               a * 180 / 3.141592653589793, turn, all ? 0 : 4, k, np);
                }
                free(p);
            }
            ttd_scene_destroy(s);
            ttd_mesh_destroy(mp);
            ++cases;
        }
    ttd_mesh_destroy(mb);
    ttd_gen_mesh_free(&ball);
    ttd_gen_mesh_free(&cube);
    printf("  %zu balls in grooves: four points hold a touching point of each side\n", cases);
    return 0;
}

/* An icosphere near a floor's diagonal edge (two triangles; and a grid of 32), touching and at
 * gaps, turned at random: every point's normal is the floor's. */
static int sphere_on_floor_diagonal(void)
{
    size_t points = 0;
    for (int bytes = 8; bytes >= 4; bytes -= 4) {
        ttd_gen_mesh sphere, floors[2];
        ENSURE(ttd_gen_icosphere(2, &sphere) == 0);
        for (size_t i = 0; i < 3 * sphere.nv; ++i)
            sphere.verts[i] *= 0.5;
        {
            builder b = {0};
            const double a[3] = {-2, -2, 0}, c[3] = {2, -2, 0}, d[3] = {2, 2, 0}, e[3] = {-2, 2, 0};
            add_triangle(&b, a, c, d); /* diagonal from (-2, -2) to (2, 2) */
            add_triangle(&b, a, d, e);
            floors[0] = (ttd_gen_mesh){b.v, b.nv, b.t, b.nt};
            ENSURE(ttd_gen_grid(4, &floors[1]) == 0);
            for (size_t i = 0; i < floors[1].nv; ++i) {
                floors[1].verts[3 * i] = 4 * floors[1].verts[3 * i] - 2;
                floors[1].verts[3 * i + 1] = 4 * floors[1].verts[3 * i + 1] - 2;
            }
        }
        ttd_mesh *ms = make_mesh(&sphere, bytes), *mf[2] = {make_mesh(&floors[0], bytes), make_mesh(&floors[1], bytes)};
        ENSURE(ms && mf[0] && mf[1]);
        static const double gaps[] = {0, 1e-3, 5e-3};
        for (int fl = 0; fl < 2; ++fl)
            for (size_t gi = 0; gi < 3; ++gi)
                for (int k = 0; k < 12; ++k) {
                    double pose[12];
                    ttd_gen_pose(23, (uint64_t)k, 0, pose);
                    /* the sphere's lowest vertex under this rotation, put at the gap */
                    double low = INFINITY;
                    for (size_t v = 0; v < sphere.nv; ++v) {
                        const double *x = sphere.verts + 3 * v;
                        low = fmin(low, pose[8] * x[0] + pose[9] * x[1] + pose[10] * x[2]);
                    }
                    const double t = -1.2 + 0.2 * k;
                    pose[3] = t + (k % 3 == 0 ? 0 : k % 3 == 1 ? 0.01 : -0.03);
                    pose[7] = t;
                    pose[11] = gaps[gi] - low + (bytes == 4 ? 1e-6 : 0);
                    const double id[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
                    for (int order = 0; order < 2; ++order) {
                        ttd_scene *s;
                        ENSURE((bytes == 8 ? ttd_scene_create_d(&s) : ttd_scene_create_f(&s)) == TTD_OK);
                        ENSURE(add_body(s, bytes, order ? ms : mf[fl], order ? pose : id) == 0);
                        ENSURE(add_body(s, bytes, order ? mf[fl] : ms, order ? id : pose) == 0);
                        for (size_t K = 0; K <= 4; K += 4) {
                            mpoint *p;
                            const size_t n = ask_manifold(s, bytes, NULL, 0.01, K, &p);
                            ENSURE(n != SIZE_MAX && n >= 1);
                            for (size_t q = 0; q < n; ++q)
                                ENSURE_MSG(p[q].n[0] == 0 && p[q].n[1] == 0 && p[q].n[2] == (order ? -1 : 1),
                                           "%s floor %d, gap %g, pose %d, K %zu: point (%g, %g, %g) d %g: normal (%g, %g, %g)",
                                           bytes == 8 ? "double" : "float", fl, gaps[gi], k, K, p[q].x[0], p[q].x[1],
                                           p[q].x[2], p[q].d, p[q].n[0], p[q].n[1], p[q].n[2]);
                            points += n;
                            free(p);
                        }
                        ttd_scene_destroy(s);
                    }
                }
        ttd_mesh_destroy(ms);
        ttd_mesh_destroy(mf[0]);
        ttd_mesh_destroy(mf[1]);
        ttd_gen_mesh_free(&sphere);
        ttd_gen_mesh_free(&floors[0]);
        ttd_gen_mesh_free(&floors[1]);
    }
    printf("  spheres on floors, %zu points: every normal the floor's\n", points);
    return 0;
}

/* ---- the rule's properties over random scenes --------------------------------------------- */

/* The unit normal of a world triangle (double), 0 when it has none to speak of. */
static int tri_normal(const double x[9], double n[3])
{
    const double e1[3] = {x[3] - x[0], x[4] - x[1], x[5] - x[2]}, e2[3] = {x[6] - x[0], x[7] - x[1], x[8] - x[2]};
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    const double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const double l1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]), l2 = sqrt(e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]);
    if (!(l > 1e-6 * l1 * l2))
        return 0;
    for (int r = 0; r < 3; ++r)
        n[r] /= l;
    return 1;
}

/* Whether x lies inside triangle t (9 coordinates) by more than 1e-6 of it in every weight. */
static int strictly_inside(const double t[9], const double x[3])
{
    const double e1[3] = {t[3] - t[0], t[4] - t[1], t[5] - t[2]}, e2[3] = {t[6] - t[0], t[7] - t[1], t[8] - t[2]};
    const double d[3] = {x[0] - t[0], x[1] - t[1], x[2] - t[2]};
    const double a = e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2], b = e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2];
    const double c = e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2];
    const double p = d[0] * e1[0] + d[1] * e1[1] + d[2] * e1[2], q = d[0] * e2[0] + d[1] * e2[1] + d[2] * e2[2];
    const double den = a * c - b * b;
    if (!(den > 1e-12 * a * c))
        return 0;
    const double v = (c * p - b * q) / den, w = (a * q - b * p) / den;
    return v > 1e-6 && w > 1e-6 && 1 - v - w > 1e-6;
}

/* Whether manifold point x is its triangle pair's own point: the midpoint of that pair's points in
 * contacts con (p and q into p, q); 0 for a corner (step 0 of the reduction). */
static int own_point(const ttd_scene_array *con, int bytes, const mpoint *x, double p[3], double q[3])
{
    for (size_t c = 0; c < con->count; ++c) {
        uint32_t k[4];
        double d;
        if (bytes == 8) {
            const ttd_scene_contact_d *y = (const ttd_scene_contact_d *)con->data + c;
            memcpy(k, y, sizeof k);
            d = y->distance;
            memcpy(p, y->p, 3 * sizeof *p);
            memcpy(q, y->q, 3 * sizeof *q);
        } else {
            const ttd_scene_contact_f *y = (const ttd_scene_contact_f *)con->data + c;
            memcpy(k, y, sizeof k);
            d = (double)y->distance;
            for (int r = 0; r < 3; ++r)
                p[r] = y->p[r], q[r] = y->q[r];
        }
        if (k[0] != x->i || k[1] != x->j || k[2] != x->ti || k[3] != x->tj)
            continue;
        int same = d == x->d;
        for (int r = 0; r < 3; ++r) {
            const double mid = 0.5 * p[r] + 0.5 * q[r];
            same &= (bytes == 8 ? mid : (double)(float)mid) == x->x[r];
        }
        return same;
    }
    return 0;
}

/* Random scenes of icospheres, cubes in two triangulations and a torus placed at gaps and
 * overlaps near the margin, both body orders, K = 0, double and float:
 *   - every normal unit;
 *   - swapping the bodies negates it: bit for bit wherever the exact method gives the swapped
 *     triangle pair the same points (swapped), to 1e-9 where its points differ by a rounding;
 *   - where a contact's point lies well inside its triangle and the points differ (that face
 *     speaks for it), the normal is that face's normal, the other triangle's (negated) or their
 *     mean: the face rule, whichever side's face it is. */
static int random_scenes_rule(void)
{
    size_t points = 0, matched = 0, near_matched = 0, faces = 0, corners_matched = 0;
    for (int bytes = 8; bytes >= 4; bytes -= 4) {
        ttd_gen_mesh g[5];
        ENSURE(ttd_gen_icosphere(1, &g[0]) == 0 && ttd_gen_icosphere(2, &g[1]) == 0);
        ENSURE(cube_mesh(CUBE_DIAG_A, &g[2]) == 0 && cube_mesh(CUBE_FAN, &g[3]) == 0);
        ENSURE(ttd_gen_torus(0.6, 0.25, 16, 8, &g[4]) == 0);
        for (int k = 0; k < 5; ++k)
            ENSURE(ttd_gen_normalize(&g[k]) == 0);
        ttd_mesh *m[5];
        for (int k = 0; k < 5; ++k)
            ENSURE((m[k] = make_mesh(&g[k], bytes)) != NULL);
        const int scenes = bytes == 8 ? 40 : 10;
        for (int sc = 0; sc < scenes; ++sc) {
            enum { NB = 6 };
            int mesh_of[NB];
            double pose[NB][12];
            ttd_gen_rng rng = ttd_gen_rng_make(1000 + (uint64_t)sc, (uint64_t)bytes);
            for (int b = 0; b < NB; ++b) {
                mesh_of[b] = (int)(ttd_gen_rng_u64(&rng) % 5);
                if (b == 0) {
                    ttd_gen_pose(77 + (uint64_t)sc, 0, 0, pose[0]);
                    continue;
                }
                const int near = (int)(ttd_gen_rng_u64(&rng) % (uint64_t)b);
                const double gap = -0.01 + 0.025 * ttd_gen_rng_uniform(&rng);
                double rel[12];
                ENSURE(ttd_gen_pose_gap(&g[mesh_of[near]], &g[mesh_of[b]], 91 + (uint64_t)sc, (uint64_t)b, NULL, gap, rel) == 0);
                for (int r = 0; r < 3; ++r) /* pose[b] = pose[near] . rel */
                    for (int c = 0; c < 4; ++c) {
                        double v = c == 3 ? pose[near][4 * r + 3] : 0;
                        for (int k = 0; k < 3; ++k)
                            v += pose[near][4 * r + k] * rel[4 * k + c];
                        pose[b][4 * r + c] = v;
                    }
            }
            if (bytes == 4)
                for (int b = 0; b < NB; ++b)
                    for (int k = 0; k < 12; ++k)
                        pose[b][k] = (double)(float)pose[b][k];
            mpoint *got[2];
            size_t n[2];
            ttd_scene_array con[2] = {{0}, {0}};
            for (int order = 0; order < 2; ++order) {
                ttd_scene *s;
                ENSURE((bytes == 8 ? ttd_scene_create_d(&s) : ttd_scene_create_f(&s)) == TTD_OK);
                for (int b = 0; b < NB; ++b) {
                    const int id = order ? NB - 1 - b : b;
                    ENSURE(add_body(s, bytes, m[mesh_of[id]], pose[id]) == 0);
                }
                n[order] = ask_manifold(s, bytes, NULL, 0.02, 0, &got[order]);
                ENSURE(n[order] != SIZE_MAX);
                ENSURE((bytes == 8 ? ttd_scene_contacts_d(NULL, s, 0.02, &con[order])
                                   : ttd_scene_contacts_f(NULL, s, 0.02f, &con[order])) == TTD_OK);
                ttd_scene_destroy(s);
            }
            for (size_t a = 0; a < n[0]; ++a) {
                const mpoint *x = &got[0][a];
                ENSURE_NEAR(x->n[0] * x->n[0] + x->n[1] * x->n[1] + x->n[2] * x->n[2], 1, 1e-6);
                /* the point is its triangle pair's own (the midpoint of the contact's points), or a
                 * corner (step 0 of the reduction) */
                double p0[3], q0[3];
                const int own0 = own_point(&con[0], bytes, x, p0, q0);
                for (size_t b = 0; b < n[1]; ++b) {
                    const mpoint *y = &got[1][b];
                    if (y->i != NB - 1 - x->j || y->j != NB - 1 - x->i || y->ti != x->tj || y->tj != x->ti)
                        continue;
                    double p1[3], q1[3];
                    const int own1 = own_point(&con[1], bytes, y, p1, q1);
                    if (own0 != own1 || (!own0 && (memcmp(x->x, y->x, sizeof x->x) != 0 || x->d != y->d)))
                        continue; /* another point of the pair */
                    /* the same points, swapped? (where a pair's closest points are not unique, as
                     * for parallel edges, the exact method may pick others, or the same ones to
                     * the last bit or not, with the triangles swapped; a corner's are computed
                     * the same way for either order) */
                    int same = 2;
                    if (own0) {
                        double off = 0;
                        for (int r = 0; r < 3; ++r)
                            off = fmax(off, fmax(fabs(p0[r] - q1[r]), fabs(q0[r] - p1[r])));
                        same = off == 0 ? 2 : off <= (bytes == 8 ? 1e-13 : 1e-6) ? 1 : -1;
                    }
                    if (same == 1) { /* points a rounding apart: normals too */
                        const double tol = bytes == 8 ? 1e-9 : 1e-3;
                        ENSURE_MSG(fabs(y->n[0] + x->n[0]) <= tol && fabs(y->n[1] + x->n[1]) <= tol && fabs(y->n[2] + x->n[2]) <= tol,
                                   "%s scene %d, bodies (%u, %u) triangles (%u, %u): (%.17g, %.17g, %.17g) swapped "
                                   "(%.17g, %.17g, %.17g)", bytes == 8 ? "double" : "float", sc, x->i, x->j, x->ti,
                                   x->tj, x->n[0], x->n[1], x->n[2], y->n[0], y->n[1], y->n[2]);
                        ++near_matched;
                    } else if (same == 2) {
                        ENSURE_MSG(y->n[0] == -x->n[0] && y->n[1] == -x->n[1] && y->n[2] == -x->n[2],
                                   "%s scene %d, bodies (%u, %u) triangles (%u, %u)%s: (%.17g, %.17g, %.17g) swapped "
                                   "(%.17g, %.17g, %.17g)", bytes == 8 ? "double" : "float", sc, x->i, x->j, x->ti,
                                   x->tj, own0 ? "" : ", a corner", x->n[0], x->n[1], x->n[2], y->n[0], y->n[1], y->n[2]);
                        ++matched;
                        corners_matched += !own0;
                    }
                    break;
                }
                /* the face rule: the contact's points from the contacts query (its own p and q) */
                double ti[9], tj[9];
                const ttd_gen_mesh *gi = &g[mesh_of[x->i]], *gj = &g[mesh_of[x->j]];
                for (int k = 0; k < 3; ++k)
                    for (int r = 0; r < 3; ++r) {
                        const double *vi = gi->verts + 3 * gi->tris[3 * x->ti + (uint32_t)k];
                        const double *vj = gj->verts + 3 * gj->tris[3 * x->tj + (uint32_t)k];
                        const double *Pi = pose[x->i], *Pj = pose[x->j];
                        ti[3 * k + r] = ((Pi[4 * r] * vi[0] + Pi[4 * r + 1] * vi[1]) + Pi[4 * r + 2] * vi[2]) + Pi[4 * r + 3];
                        tj[3 * k + r] = ((Pj[4 * r] * vj[0] + Pj[4 * r + 1] * vj[1]) + Pj[4 * r + 2] * vj[2]) + Pj[4 * r + 3];
                    }
                double ni[3], nj[3], res[9];
                if (own0 && x->d > 0 && tri_normal(ti, ni) && tri_normal(tj, nj)) {
                    ttd_result_d r;
                    ENSURE(ttd_distance_d(NULL, ti, tj, &r) == TTD_OK);
                    if (strictly_inside(ti, r.p) || strictly_inside(tj, r.q)) {
                        const double mean[3] = {ni[0] - nj[0], ni[1] - nj[1], ni[2] - nj[2]};
                        const double ml = sqrt(mean[0] * mean[0] + mean[1] * mean[1] + mean[2] * mean[2]);
                        for (int r2 = 0; r2 < 3; ++r2) {
                            res[r2] = ni[r2];
                            res[3 + r2] = -nj[r2];
                            res[6 + r2] = ml > 0 ? mean[r2] / ml : 0;
                        }
                        int ok = 0;
                        const double tol = bytes == 8 ? 1e-9 : 1e-4;
                        for (int c = 0; c < 3; ++c)
                            ok |= fabs(x->n[0] - res[3 * c]) <= tol && fabs(x->n[1] - res[3 * c + 1]) <= tol &&
                                  fabs(x->n[2] - res[3 * c + 2]) <= tol;
                        ENSURE_MSG(ok, "%s scene %d, bodies (%u, %u) triangles (%u, %u), d %g: a point inside a face "
                                   "but the normal (%.9g, %.9g, %.9g) is neither face's", bytes == 8 ? "double" : "float",
                                   sc, x->i, x->j, x->ti, x->tj, x->d, x->n[0], x->n[1], x->n[2]);
                        ++faces;
                    }
                }
            }
            points += n[0];
            free(got[0]);
            free(got[1]);
            ttd_scene_array_free(&con[0]);
            ttd_scene_array_free(&con[1]);
        }
        for (int k = 0; k < 5; ++k) {
            ttd_mesh_destroy(m[k]);
            ttd_gen_mesh_free(&g[k]);
        }
    }
    ENSURE(matched * 5 >= points && (matched + near_matched) * 2 >= points && faces > 0);
    printf("  random scenes: %zu points; %zu at the same points swapped (normals negated bit for bit; %zu of them corners), "
           "%zu at points a rounding apart (negated to 1e-9); %zu inside a face\n", points, matched, corners_matched,
           near_matched, faces);
    return 0;
}

/* ---- solids (docs/scenes.md, section 5b) -------------------------------------------------- */

/* Scales mesh g about the origin by f (in place). */
static void scale_mesh(ttd_gen_mesh *g, double f)
{
    for (size_t i = 0; i < 3 * g->nv; ++i)
        g->verts[i] *= f;
}

/* A cube half the size of the unit cube sunk 0.1 into a unit cube (both solid), centred, turned
 * by yaws, in four triangulations of each (faces without shared vertices are not closed), either
 * body first: the deepest point is at depth M + 0.1 (to 1e-12), and every point at that depth (a
 * vertex of the sunk face) has normal +z from the lower cube to the upper; K = 4 gives the sunk
 * face's four corners. */
static int sunk_cube_depth(void)
{
    static const double yaws[] = {0, 20, 45};
    const double M = 0.01;
    size_t cases = 0;
    ttd_gen_mesh g[CUBE_KINDS], h[CUBE_KINDS];
    ttd_mesh *m[CUBE_KINDS], *mh[CUBE_KINDS];
    for (int k = 0; k < CUBE_KINDS; ++k) {
        ENSURE(cube_mesh(k, &g[k]) == 0 && cube_mesh(k, &h[k]) == 0);
        scale_mesh(&h[k], 0.5);
        ENSURE((m[k] = make_mesh(&g[k], 8)) != NULL && (mh[k] = make_mesh(&h[k], 8)) != NULL);
    }
    for (int kb = 0; kb < CUBE_KINDS; ++kb)
        for (int kt = 0; kt < CUBE_KINDS; ++kt)
            for (size_t yi = 0; yi < sizeof yaws / sizeof yaws[0]; ++yi)
                for (int order = 0; order < 2; ++order) {
                    if (kb == CUBE_UNSHARED || kt == CUBE_UNSHARED)
                        continue; /* closed by vertex index only: not a solid (ttd_mesh_closed) */
                    double lower[12], upper[12];
                    const double lc[3] = {0.5, 0.5, 0.5}, uc[3] = {0.5, 0.5, 1 + 0.25 - 0.1};
                    cube_pose(0, lc, lower);
                    /* the small cube: cube_pose turns about the unit cube's centre (0.5, 0.5, 0.5);
                     * the half cube's centre is (0.25, 0.25, 0.25) */
                    const double yaw = yaws[yi] * 3.14159265358979323846 / 180, cs = cos(yaw), sn = sin(yaw);
                    const double R[9] = {cs, -sn, 0, sn, cs, 0, 0, 0, 1};
                    for (int r = 0; r < 3; ++r) {
                        for (int q = 0; q < 3; ++q)
                            upper[4 * r + q] = R[3 * r + q];
                        upper[4 * r + 3] = uc[r] - (R[3 * r] * 0.25 + R[3 * r + 1] * 0.25 + R[3 * r + 2] * 0.25);
                    }
                    ttd_scene *s;
                    ENSURE(ttd_scene_create_d(&s) == TTD_OK);
                    ENSURE(add_body(s, 8, order ? mh[kt] : m[kb], order ? upper : lower) == 0);
                    ENSURE(add_body(s, 8, order ? m[kb] : mh[kt], order ? lower : upper) == 0);
                    ENSURE(ttd_scene_set_solid(s, 0, 1) == TTD_OK && ttd_scene_set_solid(s, 1, 1) == TTD_OK);
                    const double up = order ? -1 : 1; /* from body 0 towards body 1 */
                    for (size_t K = 0; K <= 4; K += 4) {
                        mpoint *p;
                        const size_t n = ask_manifold(s, 8, NULL, M, K, &p);
                        ENSURE(n != SIZE_MAX && n >= 4);
                        size_t below = 0;
                        for (size_t q = 0; q < n; ++q) {
                            ENSURE(p[q].depth == M - p[q].d);
                            if (!(fabs(p[q].d + 0.1) <= 1e-12))
                                continue; /* not of the sunk face (a lower cube's vertex inside the upper: shallower) */
                            ++below;
                            ENSURE_MSG(fabs(p[q].n[0]) <= 1e-12 && fabs(p[q].n[1]) <= 1e-12 && fabs(p[q].n[2] - up) <= 1e-12,
                                       "%s in %s, yaw %g, K %zu: point %zu normal (%g, %g, %g)", cube_name[kt], cube_name[kb],
                                       yaws[yi], K, q, p[q].n[0], p[q].n[1], p[q].n[2]);
                            ENSURE(fabs(p[q].x[2] - 0.95) <= 1e-12); /* between the corner and the top face */
                        }
                        ENSURE_MSG(fabs(p[0].depth - (M + 0.1)) <= 1e-12, "%s in %s, yaw %g, K %zu: the deepest at %.17g",
                                   cube_name[kt], cube_name[kb], yaws[yi], K, p[0].depth);
                        /* the sunk face's vertices, first (the deepest); at K = 4 its four corners */
                        ENSURE_MSG(below >= 4 && p[0].d < 0 && (K == 0 || n == 4), "%s in %s, yaw %g, K %zu: %zu points below 0 of %zu",
                                   cube_name[kt], cube_name[kb], yaws[yi], K, below, n);
                        if (K == 4) {
                            double x4[4][3];
                            for (size_t q = 0; q < 4; ++q) {
                                ENSURE(p[q].d < 0);
                                memcpy(x4[q], p[q].x, sizeof x4[q]);
                            }
                            ENSURE_NEAR(hull_area_xy((const double (*)[3])x4, 4), 0.25, 1e-12);
                        }
                        free(p);
                    }
                    ttd_scene_destroy(s);
                    ++cases;
                }
    for (int k = 0; k < CUBE_KINDS; ++k) {
        ttd_mesh_destroy(m[k]);
        ttd_mesh_destroy(mh[k]);
        ttd_gen_mesh_free(&g[k]);
        ttd_gen_mesh_free(&h[k]);
    }
    printf("  %zu cubes sunk 0.1 into cubes (solids): depth M + 0.1 at the four sunk corners, normal +z\n", cases);
    return 0;
}

/* Whether world point x lies inside the closed triangle soup w[0..nt) (9 per triangle), by the
 * parity of a ray's crossings (a fixed, general direction; a ray through an edge or a vertex is
 * not expected at these points): an inside test of its own, beside the library's winding number. */
static int ray_inside(const double *w, size_t nt, const double x[3])
{
    const double dir[3] = {0.5773502691896258, 0.5773502691896257, 0.5773502691896259};
    int crossings = 0;
    for (size_t t = 0; t < nt; ++t) {
        const double *a = w + 9 * t, *b = a + 3, *c = a + 6;
        const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        const double pv[3] = {dir[1] * e2[2] - dir[2] * e2[1], dir[2] * e2[0] - dir[0] * e2[2], dir[0] * e2[1] - dir[1] * e2[0]};
        const double det = e1[0] * pv[0] + e1[1] * pv[1] + e1[2] * pv[2];
        if (fabs(det) < 1e-300)
            continue;
        const double tv[3] = {x[0] - a[0], x[1] - a[1], x[2] - a[2]};
        const double u = (tv[0] * pv[0] + tv[1] * pv[1] + tv[2] * pv[2]) / det;
        const double qv[3] = {tv[1] * e1[2] - tv[2] * e1[1], tv[2] * e1[0] - tv[0] * e1[2], tv[0] * e1[1] - tv[1] * e1[0]};
        const double v = (dir[0] * qv[0] + dir[1] * qv[1] + dir[2] * qv[2]) / det;
        const double h = (e2[0] * qv[0] + e2[1] * qv[1] + e2[2] * qv[2]) / det;
        crossings += u >= 0 && v >= 0 && u + v <= 1 && h > 0;
    }
    return crossings % 2;
}

/* Solid bodies interpenetrating or nested, against a brute force: icospheres, cubes and a torus at
 * random rotations, sunk 0.02 to 0.3 into each other, a small icosphere wholly inside a cube and a
 * cube inside a large icosphere; both precisions, either order. The manifold's points below 0 at
 * K = 0 are the vertices of each body inside the other (the ray test here, leaving out
 * vertices within 1e-9 of the surface), each at minus its exact distance to the other's surface
 * (the point-triangle distance over all of the other's triangles, the vertex moved into its
 * frame as the point queries move points), bit for bit, with normals of unit length that point
 * out of the other body (positive along the surface point minus the vertex; pairs with the torus
 * excepted: their points carry their contact region's direction, 5b); or, where an edge's
 * deepest point lies deeper than every vertex and within the merge's reach of one (5b), that
 * deeper point in its place; and beyond them only points deeper than every vertex inside (the
 * edges' deepest points). A nested pair is found by collide at 0 (the inner body's triangle 0 as
 * witness) and gets distance 0. */
static int solid_pairs_brute_force(void)
{
    size_t pairs = 0, inside_points = 0, nested = 0, edge_points = 0, folded_points = 0, region_against = 0, region_points = 0;
    for (int bytes = 8; bytes >= 4; bytes -= 4) {
        ttd_gen_mesh g[5];
        ENSURE(ttd_gen_icosphere(2, &g[0]) == 0 && cube_mesh(CUBE_DIAG_A, &g[1]) == 0);
        ENSURE(ttd_gen_torus(0.6, 0.25, 16, 8, &g[2]) == 0 && ttd_gen_icosphere(1, &g[3]) == 0);
        ENSURE(cube_mesh(CUBE_SPLIT3, &g[4]) == 0);
        for (int k = 0; k < 5; ++k)
            ENSURE(ttd_gen_normalize(&g[k]) == 0);
        scale_mesh(&g[3], 0.3); /* a small icosphere, to go inside a cube */
        scale_mesh(&g[0], 2.2);  /* and a large one, to hold a cube */
        if (bytes == 4)
            for (int k = 0; k < 5; ++k)
                for (size_t i = 0; i < 3 * g[k].nv; ++i)
                    g[k].verts[i] = (double)(float)g[k].verts[i];
        ttd_mesh *m[5];
        for (int k = 0; k < 5; ++k)
            ENSURE((m[k] = make_mesh(&g[k], bytes)) != NULL);
        static const int kinds[][2] = {{0, 1}, {1, 2}, {2, 4}, {4, 1}, {0, 2}, {3, 1}, {4, 3}, {0, 4}};
        for (size_t ki = 0; ki < sizeof kinds / sizeof kinds[0]; ++ki)
            for (int trial = 0; trial < (bytes == 8 ? 4 : 2); ++trial) {
                const int a = kinds[ki][0], b = kinds[ki][1];
                const int nest = (a == 3 || b == 3 || (a == 0 && b != 2)) && trial % 2 == 0;
                double pose[2][12];
                ttd_gen_pose(500 + ki, (uint64_t)trial, 0, pose[0]);
                for (int r = 0; r < 3; ++r)
                    pose[0][4 * r + 3] = 0.1 * r;
                if (nest) { /* the smaller inside the larger: the same centre, turned */
                    ttd_gen_pose(600 + ki, (uint64_t)trial, 0, pose[1]);
                    for (int r = 0; r < 3; ++r)
                        pose[1][4 * r + 3] = pose[0][4 * r + 3];
                } else {
                    double rel[12];
                    const double sink = -(0.02 + 0.07 * trial);
                    ENSURE(ttd_gen_pose_gap(&g[a], &g[b], 700 + ki, (uint64_t)trial, NULL, sink, rel) == 0);
                    for (int r = 0; r < 3; ++r) /* pose[1] = pose[0] . rel */
                        for (int c = 0; c < 4; ++c) {
                            double v = c == 3 ? pose[0][4 * r + 3] : 0;
                            for (int k = 0; k < 3; ++k)
                                v += pose[0][4 * r + k] * rel[4 * k + c];
                            pose[1][4 * r + c] = v;
                        }
                }
                if (bytes == 4)
                    for (int q = 0; q < 2; ++q)
                        for (int k = 0; k < 12; ++k)
                            pose[q][k] = (double)(float)pose[q][k];
                for (int order = 0; order < 2; ++order) {
                    const int mi = order ? b : a, mj = order ? a : b;
                    const double *Pi = pose[order], *Pj = pose[!order];
                    ttd_scene *s;
                    ENSURE((bytes == 8 ? ttd_scene_create_d(&s) : ttd_scene_create_f(&s)) == TTD_OK);
                    ENSURE(add_body(s, bytes, m[mi], Pi) == 0 && add_body(s, bytes, m[mj], Pj) == 0);
                    ENSURE(ttd_scene_set_solid(s, 0, 1) == TTD_OK && ttd_scene_set_solid(s, 1, 1) == TTD_OK);
                    /* the bodies' world triangles and vertices, as the library computes them */
                    const ttd_gen_mesh *gm[2] = {&g[mi], &g[mj]};
                    const double *P[2] = {Pi, Pj};
                    double *wt[2], *wv[2];
                    for (int q = 0; q < 2; ++q) {
                        wt[q] = malloc(9 * gm[q]->nt * sizeof *wt[q]);
                        wv[q] = malloc(3 * gm[q]->nv * sizeof *wv[q]);
                        ENSURE(wt[q] && wv[q]);
                        for (size_t v = 0; v < gm[q]->nv; ++v)
                            for (int r = 0; r < 3; ++r) {
                                const double *x = gm[q]->verts + 3 * v, *Q = P[q];
                                if (bytes == 8) {
                                    wv[q][3 * v + (size_t)r] = ((Q[4 * r] * x[0] + Q[4 * r + 1] * x[1]) + Q[4 * r + 2] * x[2]) + Q[4 * r + 3];
                                } else {
                                    const float f = (((float)Q[4 * r] * (float)x[0] + (float)Q[4 * r + 1] * (float)x[1]) +
                                                     (float)Q[4 * r + 2] * (float)x[2]) + (float)Q[4 * r + 3];
                                    wv[q][3 * v + (size_t)r] = (double)f;
                                }
                            }
                        for (size_t t = 0; t < gm[q]->nt; ++t)
                            for (int k = 0; k < 3; ++k)
                                memcpy(wt[q] + 9 * t + 3 * k, wv[q] + 3 * (size_t)gm[q]->tris[3 * t + (size_t)k], 3 * sizeof(double));
                    }
                    mpoint *pt;
                    const size_t n = ask_manifold(s, bytes, NULL, 0.01, 0, &pt);
                    ENSURE(n != SIZE_MAX);
                    /* every vertex inside the other body: its point, at minus its exact distance */
                    size_t want = 0, found = 0, folded = 0;
                    double deepest_vertex = 0;
                    for (int q = 0; q < 2; ++q) {
                        const ttd_gen_mesh *o = gm[!q];
                        for (size_t v = 0; v < gm[q]->nv; ++v) {
                            const double *x = wv[q] + 3 * v;
                            if (!ray_inside(wt[!q], o->nt, x))
                                continue;
                            /* x in the other's frame (ttd.h, "Point queries"), the exact distance there */
                            const double *Q = P[!q];
                            double y[3], best = INFINITY, at[3] = {0, 0, 0};
                            float yf[3];
                            for (int c = 0; c < 3; ++c) {
                                y[c] = (Q[c] * (x[0] - Q[3]) + Q[4 + c] * (x[1] - Q[7])) + Q[8 + c] * (x[2] - Q[11]);
                                yf[c] = ((float)Q[c] * ((float)x[0] - (float)Q[3]) + (float)Q[4 + c] * ((float)x[1] - (float)Q[7])) +
                                        (float)Q[8 + c] * ((float)x[2] - (float)Q[11]);
                            }
                            for (size_t t = 0; t < o->nt; ++t) {
                                double tri[9];
                                for (int k = 0; k < 3; ++k)
                                    memcpy(tri + 3 * k, o->verts + 3 * (size_t)o->tris[3 * t + (size_t)k], 3 * sizeof(double));
                                double d;
                                if (bytes == 8) {
                                    ttd_point_result_d r;
                                    ENSURE(ttd_point_triangle_d(y, tri, &r) == TTD_OK);
                                    d = r.distance;
                                } else {
                                    float trf[9];
                                    for (int k = 0; k < 9; ++k)
                                        trf[k] = (float)tri[k];
                                    ttd_point_result_f r;
                                    ENSURE(ttd_point_triangle_f(yf, trf, &r) == TTD_OK);
                                    d = (double)r.distance;
                                }
                                if (d < best)
                                    best = d;
                            }
                            if (!(best > 1e-9))
                                continue; /* on the surface, to rounding: no inside point asked of it */
                            memcpy(at, x, sizeof at);
                            ++want;
                            /* its point: the midpoint of the vertex and its closest point, at -best */
                            int got = 0;
                            for (size_t k = 0; k < n && !got; ++k) {
                                if (!(pt[k].d < 0))
                                    continue;
                                const double h = hypot(hypot(pt[k].x[0] - at[0], pt[k].x[1] - at[1]), pt[k].x[2] - at[2]);
                                if (pt[k].d == -best && fabs(h - 0.5 * best) <= (bytes == 8 ? 1e-9 : 1e-5)) {
                                    got = 1;
                                    /* the normal out of the other body: from the vertex towards the surface
                                     * for body j's vertex (j pushed out of i along +n); the other way for i's */
                                    const double away[3] = {pt[k].x[0] - at[0], pt[k].x[1] - at[1], pt[k].x[2] - at[2]};
                                    const double dot = (q == 1 ? 1 : -1) * (away[0] * pt[k].n[0] + away[1] * pt[k].n[1] + away[2] * pt[k].n[2]);
                                    ENSURE_NEAR(pt[k].n[0] * pt[k].n[0] + pt[k].n[1] * pt[k].n[1] + pt[k].n[2] * pt[k].n[2], 1, 1e-6);
                                    /* with the torus (kind 2) a pair is not convex: its points below 0 take their
                                     * contact region's direction, its deepest point's (5b), which need not lead
                                     * out at every vertex (a tube crossed: one wall's vertices, the other's);
                                     * tests/test_scene_regions.c checks those regions against a reference */
                                    if (a != 2 && b != 2)
                                        ENSURE_MSG(dot > 0, "%s pair %d (%d, %d) order %d: an inside point's normal points into "
                                                   "the other body", bytes == 8 ? "double" : "float", (int)ki, a, b, order);
                                    else {
                                        region_against += !(dot > 0);
                                        ++region_points;
                                    }
                                }
                            }
                            /* else folded by the merge (1e-3 of the smaller radius, 2.2 at most)
                               into a deeper point nearby: an edge's deepest point */
                            for (size_t k = 0; k < n && !got; ++k) {
                                const double h = hypot(hypot(pt[k].x[0] - at[0], pt[k].x[1] - at[1]), pt[k].x[2] - at[2]);
                                if (pt[k].d < -best && h <= 0.5 * (-pt[k].d) + 0.5 * best + 5e-3)
                                    got = 2;
                            }
                            folded += got == 2;
                            found += got != 0;
                            deepest_vertex = fmax(deepest_vertex, best);
                        }
                    }
                    size_t below = 0, beyond = 0;
                    for (size_t k = 0; k < n; ++k) {
                        below += pt[k].d < 0;
                        /* a point below 0 that is no vertex's: an edge's, deeper than every vertex */
                        int vertex_point = 0;
                        for (int q = 0; q < 2 && pt[k].d < 0 && !vertex_point; ++q)
                            for (size_t v = 0; v < gm[q]->nv && !vertex_point; ++v) {
                                const double *x = wv[q] + 3 * v;
                                const double h = hypot(hypot(pt[k].x[0] - x[0], pt[k].x[1] - x[1]), pt[k].x[2] - x[2]);
                                vertex_point = fabs(h + 0.5 * pt[k].d) <= (bytes == 8 ? 1e-9 : 1e-5);
                            }
                        if (pt[k].d < 0 && !vertex_point) {
                            ++beyond;
                            ENSURE_MSG(want == 0 || -pt[k].d > deepest_vertex - (bytes == 8 ? 1e-12 : 1e-6),
                                       "%s pair %d: a point at %.9g that is no vertex's, not deeper than the deepest "
                                       "vertex inside, %.9g", bytes == 8 ? "double" : "float", (int)ki, pt[k].d, deepest_vertex);
                        }
                    }
                    edge_points += beyond;
                    /* the points below 0 beyond the vertices: the deepest points of edges inside
                     * the other body (5b; checked against separating axes in test_scene_depth.c) */
                    ENSURE_MSG(found == want && below >= want - folded,
                               "%s pair %d (%d in %d) trial %d order %d: %zu vertices inside, %zu found, %zu points below 0",
                               bytes == 8 ? "double" : "float", (int)ki, a, b, trial, order, want, found, below);
                    inside_points += found;
                    folded_points += folded;
                    /* every instruction set and 1 or 2 threads: the same manifold, bit for bit */
                    for (int isa = TTD_ISA_SCALAR; isa < TTD_ISA_COUNT; ++isa) {
                        if (!ttd_isa_available((ttd_isa)isa))
                            continue;
                        for (int threads = 1; threads <= 2; ++threads) {
                            ttd_options opt = ttd_default_options();
                            opt.isa = (ttd_isa)isa;
                            opt.threads = threads;
                            mpoint *other;
                            const size_t no = ask_manifold(s, bytes, &opt, 0.01, 0, &other);
                            ENSURE(no == n && (n == 0 || memcmp(other, pt, n * sizeof *pt) == 0));
                            free(other);
                        }
                    }
                    if (nest) { /* collide at 0 and distance see the nested pair */
                        ttd_scene_array hits = {0};
                        ENSURE((bytes == 8 ? ttd_scene_collide_d(NULL, s, 0, &hits) : ttd_scene_collide_f(NULL, s, 0, &hits)) == TTD_OK);
                        ENSURE(hits.count == 1);
                        const ttd_scene_hit *hh = hits.data;
                        ENSURE((hh->tri_i == 0 && hh->tri_j == UINT32_MAX) || (hh->tri_i == UINT32_MAX && hh->tri_j == 0));
                        ttd_scene_array_free(&hits);
                        if (bytes == 8) {
                            ttd_scene_contact_d c, near[2];
                            ENSURE(ttd_scene_distance_d(NULL, s, INFINITY, &c, near) == TTD_OK);
                            ENSURE(c.distance == 0 && near[0].distance == 0 && near[1].distance == 0);
                            ENSURE(ttd_scene_distance_d(NULL, s, INFINITY, &c, NULL) == TTD_OK && c.distance == 0);
                            ENSURE(memcmp(c.p, c.q, sizeof c.p) == 0 && (c.tri_i == 0 || c.tri_j == 0));
                        } else {
                            ttd_scene_contact_f c;
                            ENSURE(ttd_scene_distance_f(NULL, s, INFINITY, &c, NULL) == TTD_OK && c.distance == 0);
                        }
                        ++nested;
                    }
                    free(pt);
                    for (int q = 0; q < 2; ++q) {
                        free(wt[q]);
                        free(wv[q]);
                    }
                    ttd_scene_destroy(s);
                    ++pairs;
                }
            }
        for (int k = 0; k < 5; ++k) {
            ttd_mesh_destroy(m[k]);
            ttd_gen_mesh_free(&g[k]);
        }
    }
    ENSURE(inside_points > 100 && nested > 0);
    printf("  %zu solid pairs (%zu nested): %zu vertices inside the other body, each a point at minus its exact "
           "distance, normals out of the other body but for %zu of the %zu of pairs with the torus, which carry "
           "their region's direction (%zu folded into a deeper edge point); %zu edge points, each deeper than every vertex inside\n",
           pairs, nested, inside_points, region_against, region_points, folded_points, edge_points);
    return 0;
}

/* ---- the edge information, made on first use ---------------------------------------------- */

typedef struct edges_job {
    const ttd_mesh *m[2];
    const double *pose[2];
    mpoint *got;
    size_t n;
} edges_job;

static void *edges_worker(void *ctx)
{
    edges_job *J = ctx;
    ttd_scene *s;
    J->n = SIZE_MAX;
    if (ttd_scene_create_d(&s) != TTD_OK)
        return NULL;
    if (add_body(s, 8, J->m[0], J->pose[0]) == 0 && add_body(s, 8, J->m[1], J->pose[1]) == 0) {
        ttd_options opt = ttd_default_options();
        opt.threads = 1;
        J->n = ask_manifold(s, 8, &opt, 0.01, 0, &J->got);
    }
    ttd_scene_destroy(s);
    return NULL;
}

/* Fresh meshes whose edge information no query has made yet, asked for manifolds by four threads
 * at once (each its own scene): every thread gets the manifold one thread gets alone, from meshes
 * made afresh, bit for bit (under ThreadSanitizer, scripts/test-tsan.sh, the race of the first
 * use is checked too). */
static int edges_made_on_first_use(void)
{
    ttd_gen_mesh g[2];
    ENSURE(cube_mesh(CUBE_SPLIT3, &g[0]) == 0 && cube_mesh(CUBE_FAN, &g[1]) == 0);
    const double lc[3] = {0.5, 0.5, 0.5}, uc[3] = {0.7, 0.6, 1.5 + 0.002};
    double lower[12], upper[12];
    cube_pose(0, lc, lower);
    cube_pose(0.3, uc, upper);
    mpoint *want = NULL;
    size_t nwant = 0;
    for (int round = 0; round < 3; ++round) {
        ttd_mesh *m[2];
        for (int k = 0; k < 2; ++k)
            ENSURE((m[k] = make_mesh(&g[k], 8)) != NULL);
        enum { NT = 4 };
        edges_job J[NT];
        pthread_t th[NT];
        for (int t = 0; t < NT; ++t) {
            J[t] = (edges_job){{m[0], m[1]}, {lower, upper}, NULL, 0};
            ENSURE(pthread_create(&th[t], NULL, edges_worker, &J[t]) == 0);
        }
        for (int t = 0; t < NT; ++t)
            ENSURE(pthread_join(th[t], NULL) == 0);
        for (int t = 0; t < NT; ++t) {
            ENSURE(J[t].n != SIZE_MAX && J[t].n >= 4);
            if (want == NULL) {
                want = J[t].got;
                nwant = J[t].n;
                continue;
            }
            ENSURE(J[t].n == nwant && memcmp(J[t].got, want, nwant * sizeof *want) == 0);
            free(J[t].got);
        }
        for (int k = 0; k < 2; ++k)
            ttd_mesh_destroy(m[k]);
    }
    free(want);
    for (int k = 0; k < 2; ++k)
        ttd_gen_mesh_free(&g[k]);
    printf("  three rounds of fresh meshes, four threads each: the same manifold (%zu points)\n", nwant);
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(stacks_normals_up);
    RUN_TEST(tilted_stacks_normals_up);
    RUN_TEST(stacks_at_extreme_scales);
    RUN_TEST(box_on_box_corners);
    RUN_TEST(box_on_box_level);
    RUN_TEST(sphere_on_floor_diagonal);
    RUN_TEST(torus_on_floor_level);
    RUN_TEST(ball_in_groove);
    RUN_TEST(random_scenes_rule);
    RUN_TEST(sunk_cube_depth);
    RUN_TEST(solid_pairs_brute_force);
    RUN_TEST(edges_made_on_first_use);
    TEST_MAIN_END();
}
