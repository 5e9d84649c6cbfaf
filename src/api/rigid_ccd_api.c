/* SPDX-License-Identifier: MIT */
/* Continuous collision of two rigid meshes between two poses each (ttd.h, ttd_mesh_ccd_rigid_d;
 * docs/ccd.md section 13): conservative advancement. At time t the exact mesh distance d(t) under
 * both bodies' poses; no point of either body moves faster than its speed bound, so the distance
 * cannot fall faster than the two bounds' sum V, and the interval [t, t + (d - mu - delta) / V]
 * is proved to stay above delta (mu bounds the rounding of the poses and of the distance). The
 * walk stops with a hit once d + mu <= delta + eta (the distance tolerance), with none once the
 * proved intervals reach t = 1, and with a conservative hit after TTD_RIGID_CCD_MAX_STEPS. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "api/prepare.h"
#include "api/rigid_ccd.h"
#include "mesh/mesh.h"

void rigid_body_make(rigid_body *body, const ttd_mesh *mesh, const void *pose0, const void *pose1, int bytes)
{
    double p0[12], p1[12];
    for (int i = 0; i < 12; ++i) {
        p0[i] = bytes == 8 ? ((const double *)pose0)[i] : (double)((const float *)pose0)[i];
        p1[i] = bytes == 8 ? ((const double *)pose1)[i] : (double)((const float *)pose1)[i];
    }
    body->mesh = mesh;
    rigid_motion_make(p0, p1, &body->motion);
    body->radius = rigid_radius(mesh->verts, mesh->nv, mesh->bytes);
    body->speed = rigid_speed(&body->motion, body->radius);
    double n0 = 0, n1 = 0;
    for (int i = 0; i < 3; ++i) {
        n0 += p0[4 * i + 3] * p0[4 * i + 3];
        n1 += p1[4 * i + 3] * p1[4 * i + 3];
    }
    body->reach = sqrt(fmax(n0, n1)) * (1 + 4 * DBL_EPSILON);
}

/* b's pose in a's frame at time t: Ra^T Rb and Ra^T (Tb - Ta). The motions' rotations are
 * orthonormal to a few ulps (rigid_motion_make replaces poses further off by their nearest
 * rotations), so Ra^T stands for Ra's inverse within the margin mu and Ra^T Rb passes the mesh
 * query's pose check. */
static void relative_pose(const rigid_body *a, const rigid_body *b, double t, double rel[12])
{
    double pa[12], pb[12];
    rigid_motion_at(&a->motion, t, pa);
    rigid_motion_at(&b->motion, t, pb);
    const double d[3] = {pb[3] - pa[3], pb[7] - pa[7], pb[11] - pa[11]};
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j)
            rel[4 * i + j] = pa[i] * pb[j] + pa[4 + i] * pb[4 + j] + pa[8 + i] * pb[8 + j];
        rel[4 * i + 3] = pa[i] * d[0] + pa[4 + i] * d[1] + pa[8 + i] * d[2];
    }
}

/* The exact mesh distance at time t, at most `bound` (else +inf). */
static ttd_status distance_at(const ttd_options *opt, const rigid_body *a, const rigid_body *b, int bytes, double t,
                              double bound, double *d, uint32_t *tri_a, uint32_t *tri_b)
{
    double rel[12];
    relative_pose(a, b, t, rel);
    ttd_status st;
    if (bytes == 8) {
        ttd_mesh_result_d r;
        st = ttd_mesh_distance_d(opt, a->mesh, b->mesh, 1, rel, bound, 0, &r);
        *d = r.distance;
        *tri_a = r.tri_a;
        *tri_b = r.tri_b;
    } else {
        float relf[12];
        for (int i = 0; i < 12; ++i)
            relf[i] = (float)rel[i];
        ttd_mesh_result_f r;
        const float bf = bound < (double)FLT_MAX ? nextafterf((float)bound, INFINITY) : INFINITY;
        st = ttd_mesh_distance_f(opt, a->mesh, b->mesh, 1, relf, bf, 0, &r);
        *d = (double)r.distance; /* exact: a float widens to double without rounding */
        *tri_a = r.tri_a;
        *tri_b = r.tri_b;
    }
    return st;
}

ttd_status ttd_rigid_ccd_pair(const ttd_options *opt, const rigid_body *a, const rigid_body *b, int bytes,
                              double delta, ttd_mesh_ccd_rigid_result *out)
{
    memset(out, 0, sizeof *out);
    out->toi = HUGE_VAL;
    out->distance = HUGE_VAL;
    out->tri_a = out->tri_b = UINT32_MAX;
    /* S bounds every coordinate and distance the query meets in a's frame; mu the rounding of
     * the poses at t (Rodrigues, products), of b's vertices moved by the relative pose and of
     * the exact distance: a few tens of ulps of S, taken with a wide margin. */
    const double S = a->radius + b->radius + a->reach + b->reach;
    const double mu = S * (bytes == 8 ? 0x1p-40 : 0x1p-17);
    const double eta = S * (bytes == 8 ? 0x1p-30 : 0x1p-14);
    const double V = (a->speed + b->speed) * (1 + 4 * DBL_EPSILON);
    out->tolerance = eta;
    double t = 0;
    for (uint32_t step = 0;; ++step) {
        if (step == TTD_RIGID_CCD_MAX_STEPS) {
            /* Every time before t is proved apart; t itself is not: a conservative hit. */
            out->toi = t;
            out->hit = 1;
            out->flags = TTD_CCD_BUDGET;
            return TTD_OK;
        }
        /* Beyond delta + mu + V (1 - t) the rest of the step is proved in one go: a bound lets
         * the walk stop early. */
        const double bound = (delta + mu + V * (1 - t)) * (1 + 8 * DBL_EPSILON);
        double d;
        uint32_t ta, tb;
        const ttd_status st = distance_at(opt, a, b, bytes, t, bound, &d, &ta, &tb);
        out->steps = step + 1;
        if (st != TTD_OK)
            return st;
        if (d + mu <= delta + eta) {
            out->toi = t;
            out->hit = 1;
            out->distance = d;
            out->tri_a = ta;
            out->tri_b = tb;
            return TTD_OK;
        }
        /* d - mu > delta + eta - 2 mu > 0 here, so the step is positive. */
        const double gap = (d - mu - delta) * (1 - 4 * DBL_EPSILON);
        if (!(V > 0) || gap >= V * (1 - t) * (1 + 8 * DBL_EPSILON))
            return TTD_OK; /* apart until t = 1 (V = 0: no motion, apart throughout) */
        /* gap / V < (1 - t) (1 + 9 ulps) here, so t + the step can round a few ulps above 1:
         * the motion ends at 1, and a toi must not lie beyond it. */
        const double next = fmin(nextafter(t + (gap / V) * (1 - 4 * DBL_EPSILON), 0), 1);
        if (!(next > t)) {
            /* A step below the times' resolution: stop here, conservatively. */
            out->toi = t;
            out->hit = 1;
            out->flags = TTD_CCD_BUDGET;
            return TTD_OK;
        }
        t = next;
    }
}

/* The checks: pointers, options (the mesh queries'), delta, precision, each pose a rotation and
 * its mesh moved by it within the coordinate range. */
static ttd_status rigid_entry(const ttd_options *opt, int bytes, const ttd_mesh *a, const void *a_poses,
                              const ttd_mesh *b, const void *b_poses, double delta, ttd_mesh_ccd_rigid_result *out)
{
    if (out == NULL)
        return TTD_ERR_NULL_POINTER;
    memset(out, 0, sizeof *out);
    out->toi = HUGE_VAL;
    out->distance = HUGE_VAL;
    out->tri_a = out->tri_b = UINT32_MAX;
    ttd_engine_config cfg;
    ttd_status st = ttd_prepare(opt, a && b && a_poses && b_poses, 1, 0, &cfg);
    if (st != TTD_OK)
        return st;
    if (cfg.method != TTD_METHOD_EXACT || !(delta >= 0) || !isfinite(delta))
        return TTD_ERR_BAD_OPTIONS;
    if (a->bytes != bytes || b->bytes != bytes)
        return TTD_ERR_PRECISION_MISMATCH;
    size_t bad;
    if ((st = ttd_check_poses(a, 2, a_poses, bytes, NULL, &bad)) != TTD_OK ||
        (st = ttd_check_poses(b, 2, b_poses, bytes, NULL, &bad)) != TTD_OK)
        return st;
    rigid_body ba, bb;
    const char *pa = a_poses, *pb = b_poses;
    rigid_body_make(&ba, a, pa, pa + 12 * bytes, bytes);
    rigid_body_make(&bb, b, pb, pb + 12 * bytes, bytes);
    return ttd_rigid_ccd_pair(opt, &ba, &bb, bytes, delta, out);
}

ttd_status ttd_mesh_ccd_rigid_d(const ttd_options *opt, const ttd_mesh *a, const double *a_poses, const ttd_mesh *b,
                                const double *b_poses, double min_separation, ttd_mesh_ccd_rigid_result *out)
{
    return rigid_entry(opt, 8, a, a_poses, b, b_poses, min_separation, out);
}

ttd_status ttd_mesh_ccd_rigid_f(const ttd_options *opt, const ttd_mesh *a, const float *a_poses, const ttd_mesh *b,
                                const float *b_poses, double min_separation, ttd_mesh_ccd_rigid_result *out)
{
    return rigid_entry(opt, 4, a, a_poses, b, b_poses, min_separation, out);
}

ttd_status ttd_rigid_pose_at_d(const double *pose_t0, const double *pose_t1, double t, double *pose)
{
    if (pose_t0 == NULL || pose_t1 == NULL || pose == NULL)
        return TTD_ERR_NULL_POINTER;
    for (int i = 0; i < 12; ++i)
        if (!isfinite(pose_t0[i]) || !isfinite(pose_t1[i]))
            return TTD_ERR_BAD_POSE;
    if (!(t >= 0 && t <= 1))
        return TTD_ERR_BAD_OPTIONS;
    rigid_motion m;
    rigid_motion_make(pose_t0, pose_t1, &m);
    rigid_motion_at(&m, t, pose);
    return TTD_OK;
}
