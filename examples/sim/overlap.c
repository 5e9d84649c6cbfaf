/* SPDX-License-Identifier: MIT */
/* Interpenetration measured without the manifold. For two convex pieces the penetration depth
 * (the shortest translation that separates them) is the smallest overlap of their projections
 * over the face normals of both and the cross products of an edge of each: those directions hold
 * every face normal of their Minkowski difference. A shape is a union of convex pieces (a box
 * or an icosphere is one; a torus one per segment), and two bodies overlap at least as deep as
 * their deepest pair of pieces: that is the figure reported. */
#include "sim.h"
#include "vec.h"

#include <stdlib.h>
#include <string.h>

/// The interval of a piece's world vertices (3 n at w) along axis.
static void project(const double *w, size_t n, const double axis[3], double *lo, double *hi)
{
    double a = HUGE_VAL, b = -HUGE_VAL;
    for (size_t k = 0; k < n; ++k) {
        double d = v3_dot(w + 3 * k, axis);
        a = fmin(a, d);
        b = fmax(b, d);
    }
    *lo = a;
    *hi = b;
}

/// The overlap of the two vertex sets along a unit axis (< 0: a gap).
static double axis_overlap(const double *wp, size_t np, const double *wq, size_t nq, const double axis[3])
{
    double lp, hp, lq, hq;
    project(wp, np, axis, &lp, &hp);
    project(wq, nq, axis, &lq, &hq);
    return fmin(hp - lq, hq - lp);
}

double sim_piece_overlap(const sim_piece *p, const double pose_p[12], const sim_piece *q, const double pose_q[12])
{
    double *wp = malloc(3 * (p->nv + q->nv + p->ne + q->ne) * sizeof(double));
    if (!wp)
        return HUGE_VAL; /* no memory: say the worst rather than nothing */
    double *wq = wp + 3 * p->nv, *ep = wq + 3 * q->nv, *eq = ep + 3 * p->ne;
    for (size_t k = 0; k < p->nv; ++k)
        pose_apply(pose_p, p->v + 3 * k, wp + 3 * k);
    for (size_t k = 0; k < q->nv; ++k)
        pose_apply(pose_q, q->v + 3 * k, wq + 3 * k);
    for (size_t k = 0; k < p->ne; ++k)
        pose_rotate(pose_p, p->edge + 3 * k, ep + 3 * k);
    for (size_t k = 0; k < q->ne; ++k)
        pose_rotate(pose_q, q->edge + 3 * k, eq + 3 * k);
    double best = HUGE_VAL, axis[3];
    /* face normals first: a separating one ends the test soonest */
    for (int side = 0; side < 2 && best > 0; ++side) {
        const sim_piece *s = side ? q : p;
        const double *pose = side ? pose_q : pose_p;
        for (size_t k = 0; k < s->nn && best > 0; ++k) {
            pose_rotate(pose, s->normal + 4 * k, axis);
            best = fmin(best, axis_overlap(wp, p->nv, wq, q->nv, axis));
        }
    }
    for (size_t i = 0; i < p->ne && best > 0; ++i)
        for (size_t j = 0; j < q->ne && best > 0; ++j) {
            v3_cross(ep + 3 * i, eq + 3 * j, axis);
            double len = v3_norm(axis);
            if (!(len > 1e-9 * v3_norm(ep + 3 * i) * v3_norm(eq + 3 * j)))
                continue; /* parallel edges: their planes' normals are among the faces' */
            for (int c = 0; c < 3; ++c)
                axis[c] /= len;
            best = fmin(best, axis_overlap(wp, p->nv, wq, q->nv, axis));
        }
    free(wp);
    return best;
}

/// The deepest overlap of any piece of a with any piece of b (0 when none overlap).
static double body_overlap(const sim_body *a, const sim_body *b)
{
    double pa[12], pb[12], deepest = 0;
    sim_body_pose(a, pa);
    sim_body_pose(b, pb);
    for (size_t i = 0; i < a->shape->npieces; ++i) {
        const sim_piece *p = a->shape->pieces + i;
        double cp[3], cq[3], d[3];
        pose_apply(pa, p->centre, cp);
        for (size_t j = 0; j < b->shape->npieces; ++j) {
            const sim_piece *q = b->shape->pieces + j;
            pose_apply(pb, q->centre, cq);
            v3_sub(cp, cq, d);
            if (v3_norm(d) > p->radius + q->radius)
                continue;
            deepest = fmax(deepest, sim_piece_overlap(p, pa, q, pb));
        }
    }
    return deepest;
}

/// Whether world point x lies inside some piece of body b.
static int inside(const sim_body *b, const double x[3])
{
    double d[3], local[3];
    v3_sub(x, b->x, d);
    m3_tmul_v(b->R, d, local);
    for (size_t i = 0; i < b->shape->npieces; ++i) {
        const sim_piece *p = b->shape->pieces + i;
        size_t k = 0;
        while (k < p->nn && v3_dot(p->normal + 4 * k, local) <= p->normal[4 * k + 3])
            ++k;
        if (k == p->nn)
            return 1;
    }
    return 0;
}

int sim_world_overlap(sim_world *w, double *depth, uint32_t *pair_a, uint32_t *pair_b, size_t *touching)
{
    ttd_scene_array hits = {0};
    if (ttd_scene_collide_d(&w->opt, w->scene, 0.0, &hits) != TTD_OK)
        return -1;
    const ttd_scene_hit *h = hits.data;
    *depth = 0;
    *pair_a = *pair_b = UINT32_MAX;
    /* surfaces touching or crossing; a solid pair held one inside the other is a hit too, its
       witness the outer body's UINT32_MAX, and not counted here */
    *touching = 0;
    for (size_t k = 0; k < hits.count; ++k)
        *touching += (size_t)(h[k].tri_i != UINT32_MAX && h[k].tri_j != UINT32_MAX);
    size_t next = 0; /* hits are sorted by (i, j), as this loop meets the pairs */
    for (uint32_t i = 0; i < w->n; ++i)
        for (uint32_t j = i + 1; j < w->n; ++j) {
            const sim_body *a = w->body + i, *b = w->body + j;
            int hit = next < hits.count && h[next].i == i && h[next].j == j;
            next += (size_t)hit;
            if (a->is_static && b->is_static)
                continue;
            if (!hit) {
                /* surfaces apart: overlapping only if one holds the other, and then each holds
                 * the other's vertex 0 or is held whole (test a vertex of each) */
                double d[3], va[3], vb[3], pa[12], pb[12];
                v3_sub(a->x, b->x, d);
                if (v3_norm(d) > a->shape->radius + b->shape->radius)
                    continue;
                sim_body_pose(a, pa);
                sim_body_pose(b, pb);
                pose_apply(pa, a->shape->v, va);
                pose_apply(pb, b->shape->v, vb);
                if (!inside(b, va) && !inside(a, vb))
                    continue;
            }
            double o = body_overlap(a, b);
            if (o > *depth) {
                *depth = o;
                *pair_a = i;
                *pair_b = j;
            }
        }
    ttd_scene_array_free(&hits);
    return 0;
}
