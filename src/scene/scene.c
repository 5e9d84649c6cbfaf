/* SPDX-License-Identifier: MIT */
/* A scene's bodies, their world boxes and the broad phase over them (scene/scene.h). */
#include <float.h>
#include <math.h>
#include <stdatomic.h>
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
static void world_box(const scene_body *b, int bytes, double box[6])
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
    /* the sphere around the vertices too (the mesh's origin and radius, which R may stretch by
     * its defect): on a round body it is the tighter bound, on a long one the box is; each holds
     * the mesh, so their intersection, axis by axis, does */
    const double r = m->radius * (1 + 2 * b->defect) * (1 + 4 * DBL_EPSILON);
    for (int i = 0; i < 3; ++i) {
        double ci = p[4 * i + 3], h = 0, si = p[4 * i + 3];
        for (int k = 0; k < 3; ++k) {
            ci += p[4 * i + k] * (m->origin[k] + c[k]);
            si += p[4 * i + k] * m->origin[k];
        }
        for (int a = 0; a < 3; ++a) /* |row i of R . axis a| e_a */
            h += fabs(p[4 * i] * u[3 * a] + p[4 * i + 1] * u[3 * a + 1] + p[4 * i + 2] * u[3 * a + 2]) * e[a];
        const double lo_box = ci - h, hi_box = ci + h, lo_ball = si - r, hi_ball = si + r;
        box[i] = (lo_box > lo_ball ? lo_box : lo_ball) - pad;
        box[3 + i] = (hi_box < hi_ball ? hi_box : hi_ball) + pad;
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
    b->generation = b->mesh->generation;
    world_box(b, s->bytes, s->box + 6 * (size_t)id);
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
            const double *x = s->box + 6 * id;
            lo[k] = x[k] < lo[k] ? x[k] : lo[k];
            hi[k] = x[3 + k] > hi[k] ? x[3 + k] : hi[k];
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
    const double a = s->box[6 * (size_t)x + (size_t)s->axis], b = s->box[6 * (size_t)y + (size_t)s->axis];
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
                const double c = 0.5 * s->box[6 * id + (size_t)k] + 0.5 * s->box[6 * id + 3 + (size_t)k];
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

/* Sorts the n pairs of v (distinct, i < j < nbody) by (i, j): a radix sort on i nbody + j, a
 * byte at a time up to the largest key's bytes, with tmp as scratch; returns the sorted array (v
 * or tmp). It runs on the caller before the body pairs go to the threads: the comparison sort it
 * replaces (qsort, a call per comparison) was 1.8% of the pile's motion step, all of it serial
 * (docs/scene-speed.md, section 13). */
static scene_pair *pair_sort(scene_pair *v, scene_pair *tmp, size_t n, uint64_t nbody)
{
    const uint64_t largest = nbody * nbody - 1;
    for (int shift = 0; shift < 64 && (largest >> shift) != 0; shift += 8) {
        size_t count[257] = {0};
        for (size_t k = 0; k < n; ++k)
            count[(((uint64_t)v[k].i * nbody + v[k].j) >> shift & 255) + 1]++;
        if (count[(((uint64_t)v[0].i * nbody + v[0].j) >> shift & 255) + 1] == n)
            continue; /* one digit: this pass would not move anything */
        for (int d = 0; d < 256; ++d)
            count[d + 1] += count[d];
        for (size_t k = 0; k < n; ++k)
            tmp[count[((uint64_t)v[k].i * nbody + v[k].j) >> shift & 255]++] = v[k];
        scene_pair *t = v;
        v = tmp;
        tmp = t;
    }
    return v;
}

/* Slabs along the second axis: how many, and their base and width. A sweep along one axis meets
 * every body whose box overlaps along that axis, most of them far apart along the others (in a
 * sparse scene of n bodies, about n times the bodies' size over the scene's, per body); sweeping
 * within slabs of the second axis divides that by the number of slabs. Slabs about twice the
 * typical body wide (the median of a sample of the boxes' widths, so that a few huge bodies do
 * not count), at most 64. */
static int slab_count(const double *lo, const double *hi, size_t m, double margin, double *base, double *width)
{
    double mn = HUGE_VAL, mx = -HUGE_VAL, sample[65];
    int ns = 0;
    for (size_t a = 0; a < m; ++a) {
        mn = lo[a] - margin < mn ? lo[a] - margin : mn;
        mx = hi[a] > mx ? hi[a] : mx;
    }
    const size_t step = m / 64 + 1;
    for (size_t a = 0; a < m && ns < 65; a += step)
        sample[ns++] = hi[a] - lo[a] + margin;
    for (int i = 1; i < ns; ++i) /* insertion sort of at most 65 widths */
        for (int j = i; j > 0 && sample[j] < sample[j - 1]; --j) {
            const double t = sample[j];
            sample[j] = sample[j - 1];
            sample[j - 1] = t;
        }
    const double typical = ns ? sample[ns / 2] : 0;
    int count = typical > 0 && isfinite(mx - mn) ? (int)fmin(64, (mx - mn) / (2 * typical)) : 1;
    count = count < 1 ? 1 : count;
    *base = mn;
    *width = (mx - mn) / count;
    return count;
}

/* The slab of value x (clamped: the same function for every body, so a pair's slabs agree; it is
 * monotone in x, so a body's interval maps to a run of slabs). */
static int slab_of(double x, double base, double width, int count)
{
    const double k = (x - base) / width;
    /* NaN (an infinite margin: every body in the one slab) and below 1: slab 0; above 0 the
     * conversion truncates, which is the floor (floor() itself is a call without SSE4.1) */
    return !(k >= 1) ? 0 : (k >= count ? count - 1 : (int)k);
}

/* Scratch memory kept in the scene between sweeps: at least n items of `size` bytes at *p
 * (grown, never shrunk; the sweep's arrays are large, and fresh ones each step cost page faults
 * that took a third of a 5,000-body sweep). NULL when it cannot grow. */
static void *scratch(void **p, size_t *cap, size_t n, size_t size)
{
    if (n > *cap) {
        void *v = realloc(*p, n * size);
        if (v == NULL)
            return NULL;
        *p = v;
        *cap = n;
    }
    return *p;
}

/* The sweep's inner loop in pieces: a piece is up to SWEEP_PIECE members of one slab (as body a)
 * with the pairs it finds in its own array; pieces run on the scene's pool and are joined in piece
 * order, then sorted, so the pairs do not depend on the threads. On the pile's motion the loop was
 * most of the sweep, and the sweep most of what the caller does alone (docs/scene-speed.md,
 * section 13). */
#define SWEEP_PIECE 128

typedef struct sweep_piece {
    int slab;
    size_t a0, a1;   /* members [a0, a1) of the slab */
    scene_pair *v;   /* its pairs (malloc'd) */
    size_t count, cap;
} sweep_piece;

typedef struct sweep_job {
    const struct ttd_scene *s;
    const unsigned char *only;
    double margin, base, width;
    int nslab;
    const size_t *first, *member;
    const double *sbox, *lo1; /* the members' boxes in sweep axes; lo along the second axis */
    sweep_piece *piece;
    atomic_int nomem;
} sweep_job;

static void sweep_task(void *ctx, size_t t, int worker)
{
    (void)worker;
    sweep_job *J = ctx;
    sweep_piece *P = &J->piece[t];
    const int k = P->slab, nslab = J->nslab;
    const double margin = J->margin, base = J->base, width = J->width;
    const size_t *in = J->member + J->first[k], nin = J->first[k + 1] - J->first[k];
    const double *box = J->sbox + 6 * J->first[k];
    const struct ttd_scene *s = J->s;
    for (size_t ia = P->a0; ia < P->a1; ++ia) {
        /* the bodies after a whose boxes start within the margin of its end: one body that is
         * huge (a floor) meets every other here once per slab. The bounds with the margin
         * added are rounded, but rounding is monotone: a gap at most the margin passes. */
        const size_t a = in[ia];
        const double *xa = box + 6 * ia;
        const double reach = xa[3] + margin;
        const double l1 = xa[1] - margin, h1 = xa[4] + margin, l2 = xa[2] - margin, h2 = xa[5] + margin;
        for (size_t ib = ia + 1; ib < nin && box[6 * ib] <= reach; ++ib) {
            const double *xb = box + 6 * ib;
            if (!(xb[1] <= h1 && xb[4] >= l1 && xb[2] <= h2 && xb[5] >= l2))
                continue;
            const size_t b = in[ib];
            /* a pair is reported in one slab: the one holding the later start of their
             * intervals, a point both intervals hold */
            const double start = J->lo1[a] > J->lo1[b] ? J->lo1[a] : J->lo1[b];
            if (slab_of(start - margin, base, width, nslab) != k)
                continue;
            const uint32_t x = s->order[a], y = s->order[b];
            if ((J->only != NULL && !J->only[x] && !J->only[y]) || !ttd_scene_eligible(s, x, y))
                continue;
            if (P->count == P->cap) {
                const size_t cap = P->cap ? 2 * P->cap : 64;
                scene_pair *w = realloc(P->v, cap * sizeof *w);
                if (w == NULL) {
                    atomic_store(&J->nomem, 1);
                    return;
                }
                P->v = w;
                P->cap = cap;
            }
            P->v[P->count++] = (scene_pair){x < y ? x : y, x < y ? y : x};
        }
    }
}

int ttd_scene_sweep(struct ttd_scene *s, double margin, const unsigned char *only, scene_pair **out, size_t *n)
{
    return ttd_scene_sweep_on(s, 1, margin, only, out, n);
}

int ttd_scene_sweep_on(struct ttd_scene *s, int threads, double margin, const unsigned char *only, scene_pair **out,
                       size_t *n)
{
    *out = NULL;
    *n = 0;
    if (!sweep_order(s))
        return 0;
    const size_t m = s->norder;
    /* the boxes in sweep order, one array per bound and axis: the inner loop reads them in order
     * (a body's record is 300 bytes, of which it needs 48) */
    double *lo[3], *hi[3];
    double *block = scratch(&s->sweep_d, &s->sweep_d_cap, 6 * m + 1, sizeof *block);
    if (block == NULL)
        return 0;
    const int ax = s->axis, o1 = (ax + 1) % 3, o2 = (ax + 2) % 3;
    const int axes[3] = {ax, o1, o2};
    for (int k = 0; k < 3; ++k) {
        lo[k] = block + (size_t)(2 * k) * m;
        hi[k] = block + (size_t)(2 * k + 1) * m;
        for (size_t a = 0; a < m; ++a) {
            lo[k][a] = s->box[6 * (size_t)s->order[a] + (size_t)axes[k]];
            hi[k][a] = s->box[6 * (size_t)s->order[a] + 3 + (size_t)axes[k]];
        }
    }
    /* each slab's bodies, in sweep order (a stable pass over the order keeps it): a body is in
     * every slab that its interval [lo - margin, hi] along the second axis meets */
    double base, width;
    const int nslab = slab_count(lo[1], hi[1], m, margin, &base, &width);
    size_t *first = calloc((size_t)nslab + 1, sizeof *first), total = 0;
    for (size_t a = 0; first != NULL && a < m; ++a) {
        const int k0 = slab_of(lo[1][a] - margin, base, width, nslab), k1 = slab_of(hi[1][a], base, width, nslab);
        for (int k = k0; k <= k1; ++k)
            first[k + 1]++;
        total += (size_t)(k1 - k0 + 1);
    }
    /* each slab's members, and their boxes side by side (lo[3], hi[3] in sweep axes): the inner
     * loop below then reads one slab's boxes in order, where reading them from the six arrays
     * by index cost a cache line each (measured: 11 ns an iteration, most of a sparse query) */
    size_t *member = first != NULL ? scratch(&s->sweep_i, &s->sweep_i_cap, total + 1, sizeof *member) : NULL, *fill = NULL;
    double *sbox = member != NULL ? scratch(&s->sweep_b, &s->sweep_b_cap, 6 * total + 1, sizeof *sbox) : NULL;
    if (sbox != NULL) {
        for (int k = 0; k < nslab; ++k)
            first[k + 1] += first[k];
        fill = malloc(((size_t)nslab + 1) * sizeof *fill);
    }
    if (fill == NULL) {
        free(first);
        return 0;
    }
    memcpy(fill, first, (size_t)nslab * sizeof *fill);
    for (size_t a = 0; a < m; ++a) {
        const int k0 = slab_of(lo[1][a] - margin, base, width, nslab), k1 = slab_of(hi[1][a], base, width, nslab);
        for (int k = k0; k <= k1; ++k) {
            const size_t at = fill[k]++;
            member[at] = a;
            double *x = sbox + 6 * at;
            x[0] = lo[0][a], x[1] = lo[1][a], x[2] = lo[2][a], x[3] = hi[0][a], x[4] = hi[1][a], x[5] = hi[2][a];
        }
    }
    size_t npiece = 0;
    for (int k = 0; k < nslab; ++k)
        npiece += (first[k + 1] - first[k] + SWEEP_PIECE - 1) / SWEEP_PIECE;
    sweep_piece *piece = calloc(npiece ? npiece : 1, sizeof *piece);
    if (piece == NULL) {
        free(first);
        free(fill);
        return 0;
    }
    npiece = 0;
    for (int k = 0; k < nslab; ++k)
        for (size_t a0 = 0; a0 < first[k + 1] - first[k]; a0 += SWEEP_PIECE) {
            const size_t a1 = a0 + SWEEP_PIECE;
            piece[npiece++] = (sweep_piece){k, a0, a1 < first[k + 1] - first[k] ? a1 : first[k + 1] - first[k], NULL, 0, 0};
        }
    sweep_job J = {s, only, margin, base, width, nslab, first, member, sbox, lo[1], piece, 0};
    atomic_init(&J.nomem, 0);
    ttd_pool_tasks(s->pool, npiece, threads, sweep_task, &J);
    size_t count = 0;
    for (size_t t = 0; t < npiece; ++t)
        count += piece[t].count;
    int ok = !atomic_load(&J.nomem);
    scene_pair *v = ok ? malloc((count ? count : 1) * sizeof *v) : NULL;
    ok = v != NULL;
    for (size_t t = 0, at = 0; t < npiece; ++t) {
        if (ok && piece[t].count)
            memcpy(v + at, piece[t].v, piece[t].count * sizeof *v);
        at += piece[t].count;
        free(piece[t].v);
    }
    free(piece);
    free(first);
    free(fill);
    if (!ok) {
        free(v);
        return 0;
    }
    if (count > 1) {
        scene_pair *tmp = malloc(count * sizeof *tmp);
        if (tmp == NULL) {
            free(v);
            return 0;
        }
        scene_pair *sorted = pair_sort(v, tmp, count, (uint64_t)s->nbody);
        free(sorted == v ? tmp : v);
        v = sorted;
    }
    *out = v;
    *n = count;
    return 1;
}

size_t ttd_scene_scratch_held(const struct ttd_scene *s)
{
    return s->scratch != NULL ? s->scratch_held(s->scratch) : 0;
}
