/* SPDX-License-Identifier: MIT */
/* A scene's bodies, their world boxes and the broad phase over them (scene/scene.h). */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene.h"

/* The root box of a mesh (node 0, slot 0): centre relative to the mesh's origin, axes, extents. */
static void root_box(const struct ttd_mesh *m, double c[3], double u[9], double e[3])
{
    if (m->bytes == 8) {
        const ttd_node_d *n = (const ttd_node_d *)m->nodes;
        for (int i = 0; i < 3; ++i) {
            c[i] = n->c[i][0];
            e[i] = n->e[i][0];
        }
        for (int i = 0; i < 9; ++i)
            u[i] = n->u[i][0];
    } else {
        const ttd_node_f *n = (const ttd_node_f *)m->nodes;
        for (int i = 0; i < 3; ++i) {
            c[i] = (double)n->c[i][0];
            e[i] = (double)n->e[i][0];
        }
        for (int i = 0; i < 9; ++i)
            u[i] = (double)n->u[i][0];
    }
}

/* The world box of body b: its mesh's root box moved by the pose, as an axis-aligned box (the
 * half extents are sum_a |R u_a| e_a, so a rotated body's box stays tight, unlike the cube
 * around its bounding sphere). Widened by a margin that covers what the box does not see: the
 * kernel's world coordinates are b's vertices moved by the pose in the scene's precision (within
 * a few eps of |v| + |t| of exact), the root box holds the vertices less the origin rounded to
 * double, and its axes are orthonormal to a few eps (docs/mesh-queries.md, section 4). */
static void world_box(scene_body *b, int bytes)
{
    const struct ttd_mesh *m = b->mesh;
    double c[3], u[9], e[3];
    root_box(m, c, u, e);
    const double *p = b->pose;
    double reach = 0, t1 = 0;
    for (int i = 0; i < 3; ++i) {
        reach += fabs(m->origin[i]);
        t1 += fabs(p[4 * i + 3]);
    }
    const double eps = bytes == 8 ? DBL_EPSILON : (double)FLT_EPSILON;
    const double pad = 16 * eps * (reach + 2 * m->radius + t1 + e[0] + e[1] + e[2]);
    for (int i = 0; i < 3; ++i) {
        double ci = p[4 * i + 3], h = 0;
        for (int k = 0; k < 3; ++k)
            ci += p[4 * i + k] * (m->origin[k] + c[k]);
        for (int a = 0; a < 3; ++a) /* |row i of R . axis a| e_a */
            h += fabs(p[4 * i] * u[3 * a] + p[4 * i + 1] * u[3 * a + 1] + p[4 * i + 2] * u[3 * a + 2]) * e[a];
        b->lo[i] = ci - h - pad;
        b->hi[i] = ci + h + pad;
    }
}

void ttd_scene_place(struct ttd_scene *s, uint32_t id, const void *pose, double defect)
{
    scene_body *b = &s->body[id];
    for (int k = 0; k < 12; ++k) {
        if (s->bytes == 8) {
            b->pose[k] = ((const double *)pose)[k];
        } else {
            b->pose_f[k] = ((const float *)pose)[k];
            b->pose[k] = (double)b->pose_f[k];
        }
    }
    b->defect = defect;
    world_box(b, s->bytes);
}

int ttd_scene_eligible(const struct ttd_scene *s, uint32_t i, uint32_t j)
{
    const scene_body *a = &s->body[i], *b = &s->body[j];
    if (!(a->group & b->mask) || !(b->group & a->mask))
        return 0;
    const uint64_t key = i < j ? (uint64_t)i << 32 | j : (uint64_t)j << 32 | i;
    size_t lo = 0, hi = s->nexcluded;
    while (lo < hi) {
        const size_t mid = lo + (hi - lo) / 2;
        if (s->excluded[mid] < key)
            lo = mid + 1;
        else
            hi = mid;
    }
    return !(lo < s->nexcluded && s->excluded[lo] == key);
}

double ttd_scene_extent(const struct ttd_scene *s)
{
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (size_t id = 0; id < s->nbody; ++id) {
        const scene_body *b = &s->body[id];
        if (b->mesh == NULL)
            continue;
        for (int k = 0; k < 3; ++k) {
            lo[k] = b->lo[k] < lo[k] ? b->lo[k] : lo[k];
            hi[k] = b->hi[k] > hi[k] ? b->hi[k] : hi[k];
        }
    }
    double d2 = 0;
    for (int k = 0; k < 3; ++k)
        d2 += hi[k] > lo[k] ? (hi[k] - lo[k]) * (hi[k] - lo[k]) : 0;
    return sqrt(d2);
}

/* Whether body x comes before body y in the sweep's order: lower box end, then id. */
static int sweep_before(const struct ttd_scene *s, uint32_t x, uint32_t y)
{
    const double a = s->body[x].lo[s->axis], b = s->body[y].lo[s->axis];
    return a < b || (a == b && x < y);
}

/* The sweep's order: rebuilt after bodies come or go (the axis then the one along which the
 * boxes' centres spread most), otherwise repaired by insertion sort (poses that moved a little
 * leave it nearly sorted: linear time). */
static int sweep_order(struct ttd_scene *s)
{
    if (s->order_stale) {
        uint32_t *o = realloc(s->order, (s->present ? s->present : 1) * sizeof *o);
        if (o == NULL)
            return 0;
        s->order = o;
        s->norder = 0;
        double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
        for (size_t id = 0; id < s->nbody; ++id) {
            if (s->body[id].mesh == NULL)
                continue;
            o[s->norder++] = (uint32_t)id;
            for (int k = 0; k < 3; ++k) {
                const double c = 0.5 * s->body[id].lo[k] + 0.5 * s->body[id].hi[k];
                sum[k] += c;
                sum2[k] += c * c;
            }
        }
        s->axis = 0;
        double best = -1;
        for (int k = 0; k < 3; ++k) {
            const double n = (double)(s->norder ? s->norder : 1);
            const double var = sum2[k] / n - (sum[k] / n) * (sum[k] / n);
            if (var > best) {
                best = var;
                s->axis = k;
            }
        }
        s->order_stale = 0;
    }
    uint32_t *o = s->order;
    for (size_t a = 1; a < s->norder; ++a) {
        const uint32_t x = o[a];
        size_t b = a;
        while (b > 0 && sweep_before(s, x, o[b - 1])) {
            o[b] = o[b - 1];
            --b;
        }
        o[b] = x;
    }
    return 1;
}

static int pair_cmp(const void *x, const void *y)
{
    const scene_pair *a = x, *b = y;
    if (a->i != b->i)
        return a->i < b->i ? -1 : 1;
    return (a->j > b->j) - (a->j < b->j);
}

int ttd_scene_sweep(struct ttd_scene *s, double margin, const unsigned char *only, scene_pair **out, size_t *n)
{
    *out = NULL;
    *n = 0;
    if (!sweep_order(s))
        return 0;
    size_t cap = 0, count = 0;
    scene_pair *v = NULL;
    const int ax = s->axis, o1 = (ax + 1) % 3, o2 = (ax + 2) % 3;
    for (size_t a = 0; a < s->norder; ++a) {
        const uint32_t x = s->order[a];
        const scene_body *bx = &s->body[x];
        const double reach = bx->hi[ax] + margin;
        /* the bodies after x whose boxes start within the margin of its end: one body that is
         * huge (a floor) meets every other here once, and only here */
        for (size_t b = a + 1; b < s->norder && s->body[s->order[b]].lo[ax] <= reach; ++b) {
            const uint32_t y = s->order[b];
            const scene_body *by = &s->body[y];
            double gap = by->lo[ax] - bx->hi[ax];
            const double g1 = fmax(by->lo[o1] - bx->hi[o1], bx->lo[o1] - by->hi[o1]);
            const double g2 = fmax(by->lo[o2] - bx->hi[o2], bx->lo[o2] - by->hi[o2]);
            if (!(g1 <= margin && g2 <= margin))
                continue;
            if (only != NULL && !only[x] && !only[y])
                continue;
            if (!ttd_scene_eligible(s, x, y))
                continue;
            if (count == cap) {
                cap = cap ? 2 * cap : 256;
                scene_pair *w = realloc(v, cap * sizeof *w);
                if (w == NULL) {
                    free(v);
                    return 0;
                }
                v = w;
            }
            gap = fmax(fmax(gap, 0), fmax(g1, g2));
            v[count++] = (scene_pair){x < y ? x : y, x < y ? y : x, gap};
        }
    }
    if (count > 1)
        qsort(v, count, sizeof *v, pair_cmp);
    *out = v;
    *n = count;
    return 1;
}
