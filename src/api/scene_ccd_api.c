/* SPDX-License-Identifier: MIT */
/* Continuous collision over a scene's bodies (ttd.h, ttd_scene_ccd_d; docs/ccd.md section 13):
 * each body moves rigidly from its pose in the scene (t = 0) to a pose given for t = 1. Broad
 * phase: a world box around each body's whole sweep (below), sweep and prune along the axis of
 * largest spread, the scene's filters and exclusions; narrow phase: each candidate pair's
 * conservative advancement (rigid_ccd_api.c) as one task on the scene's threads, each writing
 * its own slot, so the answer does not depend on the threads. The scene is not changed. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "api/prepare.h"
#include "api/rigid_ccd.h"
#include "scene/scene.h"

/* The box around every place body b takes in [0, 1], widened for rounding. Two bounds, and the
 * box is their intersection:
 * - every point is within (1 + 2 defect) r of the origin's place T(t), which runs on a segment;
 * - every point is within (1 + 2 defect) rho of c(t) = R(t) o + T(t), o and rho the mesh's
 *   bounding sphere; R(t) o = Rot(u, t theta) (R0 o) runs on a circular arc of angle theta <= pi
 *   from a0 = R0 o to a1, which keeps within its sagitta |a0| (1 - cos(theta / 2)) of the chord
 *   [a0, a1], so c(t) lies in the box of the corners a_i + T_j widened by it. */
static void swept_box(const rigid_body *b, double box[6])
{
    const rigid_motion *m = &b->motion;
    const ttd_mesh *mesh = b->mesh;
    const double *r = m->r0;
    double defect = 0;
    for (int x = 0; x < 3; ++x)
        for (int y = 0; y < 3; ++y)
            defect = fmax(defect, fabs(r[x] * r[y] + r[3 + x] * r[3 + y] + r[6 + x] * r[6 + y] - (x == y)));
    const double grow = 1 + 2 * defect;
    double p1[12], a0[3], a1[3];
    rigid_motion_at(m, 1, p1);
    const double *o = mesh->origin;
    for (int i = 0; i < 3; ++i) {
        a0[i] = r[3 * i] * o[0] + r[3 * i + 1] * o[1] + r[3 * i + 2] * o[2];
        a1[i] = p1[4 * i] * o[0] + p1[4 * i + 1] * o[1] + p1[4 * i + 2] * o[2];
    }
    const double na0 = sqrt(a0[0] * a0[0] + a0[1] * a0[1] + a0[2] * a0[2]);
    const double sag = na0 * (1 - cos(m->theta / 2)) * (1 + 1e-12) + na0 * 0x1p-45;
    const double wa = grow * b->radius, wb = sag + grow * mesh->radius;
    /* Rounding: every term above is a few ulps of this scale; 2^-40 of it covers them. */
    const double scale = b->reach + b->radius + na0 + mesh->radius;
    const double eps = scale * 0x1p-40;
    for (int i = 0; i < 3; ++i) {
        const double tlo = fmin(m->t0[i], m->t1[i]), thi = fmax(m->t0[i], m->t1[i]);
        const double lo_a = tlo - wa, hi_a = thi + wa;
        const double lo_b = fmin(a0[i], a1[i]) + tlo - wb, hi_b = fmax(a0[i], a1[i]) + thi + wb;
        box[i] = fmax(lo_a, lo_b) - eps;
        box[3 + i] = fmin(hi_a, hi_b) + eps;
    }
}

typedef struct ccd_job {
    const rigid_body *body;
    const scene_pair *pairs;
    const int *solid;
    ttd_options opt;
    int bytes;
    double delta;
    ttd_mesh_ccd_rigid_result *res;
    ttd_status *st;
} ccd_job;

static void pair_task(void *ctx, size_t k, int worker)
{
    (void)worker;
    const ccd_job *J = ctx;
    const scene_pair p = J->pairs[k];
    ttd_options o = J->opt;
    o.solid = J->solid[p.i] && J->solid[p.j];
    J->st[k] = ttd_rigid_ccd_pair(&o, &J->body[p.i], &J->body[p.j], J->bytes, J->delta, &J->res[k]);
}

/* qsort has no context argument in C11: the sweep sorts (lo, id) records instead. */
typedef struct sweep_item {
    double lo;
    uint32_t id;
} sweep_item;
static int item_cmp(const void *x, const void *y)
{
    const sweep_item *a = x, *b = y;
    return a->lo < b->lo ? -1 : a->lo > b->lo ? 1 : a->id < b->id ? -1 : a->id > b->id;
}
static int pair_cmp(const void *x, const void *y)
{
    const scene_pair *a = x, *b = y;
    return a->i != b->i ? (a->i < b->i ? -1 : 1) : a->j < b->j ? -1 : a->j > b->j;
}

/* The eligible pairs whose swept boxes are within delta + band[i] + band[j] on every axis (the
 * pair query also answers hits within its tolerance above delta: without the bands the scene
 * would drop them), sorted by (i, j). */
static int sweep(const ttd_scene *s, const double *box, const double *band, double delta, scene_pair **out,
                 size_t *n)
{
    double band_max = 0;
    for (size_t id = 0; id < s->nbody; ++id)
        if (s->body[id].mesh != NULL)
            band_max = fmax(band_max, band[id]);
    *out = NULL;
    *n = 0;
    size_t m = 0;
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (size_t id = 0; id < s->nbody; ++id)
        if (s->body[id].mesh != NULL) {
            ++m;
            for (int c = 0; c < 3; ++c) {
                const double mid = 0.5 * box[6 * id + c] + 0.5 * box[6 * id + 3 + c];
                lo[c] = fmin(lo[c], mid);
                hi[c] = fmax(hi[c], mid);
            }
        }
    int axis = 0;
    for (int c = 1; c < 3; ++c)
        if (hi[c] - lo[c] > hi[axis] - lo[axis])
            axis = c;
    sweep_item *it = malloc((m ? m : 1) * sizeof *it);
    if (it == NULL)
        return 0;
    m = 0;
    for (size_t id = 0; id < s->nbody; ++id)
        if (s->body[id].mesh != NULL)
            it[m++] = (sweep_item){box[6 * id + axis], (uint32_t)id};
    qsort(it, m, sizeof *it, item_cmp);
    scene_pair *v = NULL;
    size_t count = 0, cap = 0;
    int ok = 1;
    for (size_t k = 0; ok && k < m; ++k) {
        const double *bk = box + 6 * (size_t)it[k].id;
        const double reach_k = (delta + band[it[k].id] + band_max) * (1 + 4 * DBL_EPSILON);
        for (size_t l = k + 1; l < m && it[l].lo <= bk[3 + axis] + reach_k; ++l) {
            const double *bl = box + 6 * (size_t)it[l].id;
            const double gap = (delta + band[it[k].id] + band[it[l].id]) * (1 + 4 * DBL_EPSILON);
            int near = 1;
            for (int c = 0; c < 3; ++c)
                near &= bl[c] <= bk[3 + c] + gap && bk[c] <= bl[3 + c] + gap;
            const uint32_t x = it[k].id < it[l].id ? it[k].id : it[l].id, y = it[k].id ^ it[l].id ^ x;
            if (!near || !ttd_scene_eligible(s, x, y))
                continue;
            if (count == cap) {
                cap = cap ? 2 * cap : 64;
                scene_pair *w = realloc(v, cap * sizeof *w);
                if (w == NULL) {
                    ok = 0;
                    break;
                }
                v = w;
            }
            v[count++] = (scene_pair){x, y};
        }
    }
    free(it);
    if (!ok) {
        free(v);
        return 0;
    }
    if (count > 1) /* v is NULL when no pair is near: qsort must not be given it */
        qsort(v, count, sizeof *v, pair_cmp);
    *out = v;
    *n = count;
    return 1;
}

static ttd_status scene_ccd(const ttd_options *opt, ttd_scene *s, size_t n, const void *poses_t1, int bytes,
                            double delta, ttd_scene_array *out)
{
    if (out != NULL)
        out->count = 0;
    ttd_engine_config cfg;
    ttd_status st = ttd_scene_query_prepare(opt, s, out != NULL && poses_t1 != NULL, bytes, delta, 0, &cfg);
    if (st != TTD_OK)
        return st;
    if (n != s->nbody)
        return TTD_ERR_INDEX_OUT_OF_RANGE;
    const size_t stride = 12 * (size_t)bytes;
    for (size_t id = 0; id < s->nbody; ++id) {
        size_t bad;
        if (s->body[id].mesh != NULL &&
            (st = ttd_check_poses(s->body[id].mesh, 1, (const char *)poses_t1 + id * stride, bytes, NULL, &bad)) !=
                TTD_OK)
            return st;
    }
    s->stats = (ttd_scene_stats){0};
    rigid_body *body = malloc((s->nbody ? s->nbody : 1) * sizeof *body);
    double *box = malloc((s->nbody ? s->nbody : 1) * 7 * sizeof *box); /* 6 per body, then the bands */
    int *solid = malloc((s->nbody ? s->nbody : 1) * sizeof *solid);
    scene_pair *pairs = NULL;
    size_t np = 0;
    ttd_mesh_ccd_rigid_result *res = NULL;
    ttd_status *pst = NULL;
    st = TTD_ERR_OUT_OF_MEMORY;
    if (body == NULL || box == NULL || solid == NULL)
        goto done;
    for (size_t id = 0; id < s->nbody; ++id) {
        const scene_body *b = &s->body[id];
        solid[id] = b->solid;
        if (b->mesh == NULL)
            continue;
        const void *p0 = bytes == 8 ? (const void *)b->pose : (const void *)b->pose_f;
        rigid_body_make(&body[id], b->mesh, p0, (const char *)poses_t1 + id * stride, bytes);
        swept_box(&body[id], box + 6 * id);
        box[6 * s->nbody + id] = rigid_band(&body[id], bytes);
    }
    if (!sweep(s, box, box + 6 * s->nbody, delta, &pairs, &np))
        goto done;
    res = malloc((np ? np : 1) * sizeof *res);
    pst = malloc((np ? np : 1) * sizeof *pst);
    if (res == NULL || pst == NULL)
        goto done;
    ccd_job J = {body, pairs, solid, opt != NULL ? *opt : ttd_default_options(), bytes, delta, res, pst};
    J.opt.threads = 1;
    ttd_pool_tasks(s->pool, np, cfg.threads, pair_task, &J);
    size_t hits = 0;
    st = TTD_OK;
    for (size_t k = 0; k < np; ++k) {
        if (pst[k] != TTD_OK) {
            st = pst[k]; /* the first failing pair in (i, j) order */
            goto done;
        }
        hits += res[k].hit != 0;
    }
    const size_t need = hits * sizeof(ttd_scene_ccd_hit); /* capacity in bytes, as the other queries keep it */
    if (need > out->capacity) {
        void *w = realloc(out->data, need);
        if (w == NULL) {
            st = TTD_ERR_OUT_OF_MEMORY;
            goto done;
        }
        out->data = w;
        out->capacity = need;
    }
    for (size_t k = 0; k < np; ++k)
        if (res[k].hit)
            ((ttd_scene_ccd_hit *)out->data)[out->count++] =
                (ttd_scene_ccd_hit){pairs[k].i, pairs[k].j, res[k].tri_a, res[k].tri_b, res[k].flags,
                                    res[k].steps, res[k].toi, res[k].distance};
    s->stats.body_pairs = np;
    s->stats.results = out->count;
done:
    if (st != TTD_OK) {
        out->count = 0;
        s->stats = (ttd_scene_stats){0};
    }
    free(body);
    free(box);
    free(solid);
    free(pairs);
    free(res);
    free(pst);
    return st;
}

ttd_status ttd_scene_ccd_d(const ttd_options *opt, ttd_scene *scene, size_t n, const double *poses_t1,
                           double min_separation, ttd_scene_array *out)
{
    return scene_ccd(opt, scene, n, poses_t1, 8, min_separation, out);
}

ttd_status ttd_scene_ccd_f(const ttd_options *opt, ttd_scene *scene, size_t n, const float *poses_t1,
                           double min_separation, ttd_scene_array *out)
{
    return scene_ccd(opt, scene, n, poses_t1, 4, min_separation, out);
}
