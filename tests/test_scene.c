/* SPDX-License-Identifier: MIT */
/* Scenes (ttd_scene_*) against a brute force over every eligible body pair and every pair of
 * their triangles, in the world frame (each triangle moved by its body's pose as ttd.h documents,
 * in the scene's precision, the exact method on the scalar row):
 *   - collide: exactly the body pairs whose minimum is within the margin, each with a witness
 *     pair of triangles that is within it;
 *   - contacts: the set of triangle pairs within the margin, in (i, j, tri_i, tri_j) order, with
 *     the brute force's distances and points, bit for bit;
 *   - distance: the closest body pair and each body's nearest, with their tie rules, with and
 *     without a bound;
 *   - manifold: per body pair, min(K, points kept by the merge) points, each a real contact with
 *     its depth, no two within the merge tolerance, the deepest first, the next ones spreading
 *     out over the deepest level (the farthest, the largest triangle), unit normals (the normal rule's properties:
 *     tests/test_scene_contacts.c);
 * on scenes of spheres, cubes, thin and degenerate triangles and a huge floor, in both
 * precisions, after bodies are removed and added, filters and exclusions set and every body
 * moved; every instruction set and 1 or 2 threads give the same bits. And bad input. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "boxes.h" /* test_mesh_of */
#include "meshes.h"
#include "pairs.h"
#include "scene/scene.h" /* the scratch's bound and its held bytes (ttd_scene_scratch_held) */
#include "scene_corners_ref.h"
#include "test_macros.h"
#include <ttd/ttd.h>

/* ---- the scene under test and its brute force -------------------------------------------- */

#define MAX_BODIES 40

typedef struct world {
    int bytes;
    ttd_gen_mesh gm[5];       /* the meshes, in double */
    ttd_mesh *mesh[5];
    size_t nbody;
    int mesh_of[MAX_BODIES];  /* -1: removed */
    double pose[MAX_BODIES][12];
    uint32_t group[MAX_BODIES], mask[MAX_BODIES];
    int excluded[MAX_BODIES][MAX_BODIES];
    ttd_scene *scene;
} world;

typedef struct pairinfo {
    uint32_t i, j;
    size_t nt_i, nt_j;
    double *d, *p, *q;        /* nt_i * nt_j results, pair (a, b) at a * nt_j + b */
} pairinfo;

typedef struct brute {
    pairinfo *pairs;          /* eligible body pairs, sorted by (i, j) */
    size_t n;
} brute;

static double round_to(int bytes, double x)
{
    return bytes == 8 ? x : (double)(float)x;
}

/* Vertex v of body id in the world, as the library computes it in the scene's precision. */
static void world_vertex(const world *W, size_t id, size_t v, double out[3])
{
    const ttd_gen_mesh *m = &W->gm[W->mesh_of[id]];
    const double *P = W->pose[id];
    for (int r = 0; r < 3; ++r) {
        if (W->bytes == 8) {
            out[r] = ((P[4 * r] * m->verts[3 * v] + P[4 * r + 1] * m->verts[3 * v + 1]) + P[4 * r + 2] * m->verts[3 * v + 2]) +
                     P[4 * r + 3];
        } else {
            const float x = (float)m->verts[3 * v], y = (float)m->verts[3 * v + 1], z = (float)m->verts[3 * v + 2];
            out[r] = (double)((((float)P[4 * r] * x + (float)P[4 * r + 1] * y) + (float)P[4 * r + 2] * z) + (float)P[4 * r + 3]);
        }
    }
}

static int eligible(const world *W, size_t i, size_t j)
{
    return W->mesh_of[i] >= 0 && W->mesh_of[j] >= 0 && (W->group[i] & W->mask[j]) && (W->group[j] & W->mask[i]) &&
           !W->excluded[i][j];
}

static void brute_free(brute *B)
{
    for (size_t k = 0; k < B->n; ++k) {
        free(B->pairs[k].d);
        free(B->pairs[k].p);
        free(B->pairs[k].q);
    }
    free(B->pairs);
    B->pairs = NULL;
    B->n = 0;
}

static int brute_force(const world *W, brute *B)
{
    B->pairs = calloc(W->nbody * W->nbody, sizeof *B->pairs);
    B->n = 0;
    ENSURE(B->pairs != NULL);
    ttd_options opt = ttd_default_options();
    opt.isa = TTD_ISA_SCALAR;
    for (size_t i = 0; i < W->nbody; ++i)
        for (size_t j = i + 1; j < W->nbody; ++j) {
            if (!eligible(W, i, j))
                continue;
            const ttd_gen_mesh *a = &W->gm[W->mesh_of[i]], *b = &W->gm[W->mesh_of[j]];
            const size_t n = a->nt * b->nt;
            pairinfo *P = &B->pairs[B->n++];
            *P = (pairinfo){(uint32_t)i, (uint32_t)j, a->nt, b->nt, malloc(n * sizeof(double)),
                            malloc(3 * n * sizeof(double)), malloc(3 * n * sizeof(double))};
            double *s = malloc(9 * n * sizeof *s), *t = malloc(9 * n * sizeof *t);
            ENSURE(P->d && P->p && P->q && s && t);
            for (size_t x = 0; x < a->nt; ++x)
                for (size_t y = 0; y < b->nt; ++y)
                    for (int k = 0; k < 3; ++k) {
                        world_vertex(W, i, a->tris[3 * x + (size_t)k], s + 9 * (x * b->nt + y) + 3 * k);
                        world_vertex(W, j, b->tris[3 * y + (size_t)k], t + 9 * (x * b->nt + y) + 3 * k);
                    }
            if (W->bytes == 8) {
                ttd_result_d *r = malloc(n * sizeof *r);
                ENSURE(r != NULL);
                ENSURE(ttd_batch_d(&opt, n, s, t, NULL, r) == TTD_OK);
                for (size_t k = 0; k < n; ++k) {
                    P->d[k] = r[k].distance;
                    for (int c = 0; c < 3; ++c) {
                        P->p[3 * k + c] = r[k].p[c];
                        P->q[3 * k + c] = r[k].distance == 0 ? r[k].p[c] : r[k].q[c];
                    }
                }
                free(r);
            } else {
                float *sf = malloc(9 * n * sizeof *sf), *tf = malloc(9 * n * sizeof *tf);
                ttd_result_f *r = malloc(n * sizeof *r);
                ENSURE(sf && tf && r);
                for (size_t k = 0; k < 9 * n; ++k) {
                    sf[k] = (float)s[k];
                    tf[k] = (float)t[k];
                }
                ENSURE(ttd_batch_f(&opt, n, sf, tf, NULL, r) == TTD_OK);
                for (size_t k = 0; k < n; ++k) {
                    P->d[k] = (double)r[k].distance;
                    for (int c = 0; c < 3; ++c) {
                        P->p[3 * k + c] = (double)r[k].p[c];
                        P->q[3 * k + c] = (double)(r[k].distance == 0 ? r[k].p[c] : r[k].q[c]);
                    }
                }
                free(sf);
                free(tf);
                free(r);
            }
            free(s);
            free(t);
        }
    return 0;
}

static double pair_min(const pairinfo *P, size_t *arg)
{
    double best = INFINITY;
    *arg = SIZE_MAX;
    for (size_t k = 0; k < P->nt_i * P->nt_j; ++k)
        if (P->d[k] < best) {
            best = P->d[k];
            *arg = k;
        }
    return best;
}

/* ---- the queries' answers, widened to double ---------------------------------------------- */

typedef struct contact {
    uint32_t i, j, ti, tj;
    double d, p[3], q[3];
} contact;

typedef struct point {
    uint32_t i, j, ti, tj;
    double x[3], n[3], d, depth;
} point;

typedef struct answers {
    ttd_scene_hit *hits;
    size_t nhits;
    contact *contacts;
    size_t ncontacts;
    contact closest, bounded;
    contact nearest[MAX_BODIES];
    point *points;
    size_t npoints;
    ttd_scene_stats contact_stats; /* ttd_scene_get_stats after the contacts */
} answers;

static void answers_free(answers *A)
{
    free(A->hits);
    free(A->contacts);
    free(A->points);
    memset(A, 0, sizeof *A);
}

static contact widen_d(const ttd_scene_contact_d *c)
{
    contact x = {c->i, c->j, c->tri_i, c->tri_j, c->distance, {c->p[0], c->p[1], c->p[2]}, {c->q[0], c->q[1], c->q[2]}};
    return x;
}

static contact widen_f(const ttd_scene_contact_f *c)
{
    contact x = {c->i,
                 c->j,
                 c->tri_i,
                 c->tri_j,
                 (double)c->distance,
                 {(double)c->p[0], (double)c->p[1], (double)c->p[2]},
                 {(double)c->q[0], (double)c->q[1], (double)c->q[2]}};
    return x;
}

/* The scenes' size and where they sit: 1 and 0, or scaled and moved (scaled_scenes), the margin
 * and the bound with them. */
static double world_scale = 1, world_offset = 0;
#define MARGIN (0.02 * world_scale)
#define BOUND (0.05 * world_scale)
static const size_t MAX_POINTS = 4;

static int ask(const world *W, ttd_isa isa, int threads, answers *A)
{
    memset(A, 0, sizeof *A);
    ttd_options opt = ttd_default_options();
    opt.isa = isa;
    opt.threads = threads;
    ttd_scene_array hits = {0}, con = {0}, man = {0};
    if (W->bytes == 8) {
        ttd_scene_contact_d c, b, near[MAX_BODIES];
        ENSURE(ttd_scene_collide_d(&opt, W->scene, MARGIN, &hits) == TTD_OK);
        ENSURE(ttd_scene_contacts_d(&opt, W->scene, MARGIN, &con) == TTD_OK);
        ENSURE(ttd_scene_get_stats(W->scene, &A->contact_stats) == TTD_OK);
        /* the count alone: the stored query's number, and the same walks (the same stats) */
        size_t counted = SIZE_MAX;
        ttd_scene_stats count_stats;
        ENSURE(ttd_scene_contacts_count_d(&opt, W->scene, MARGIN, &counted) == TTD_OK);
        ENSURE(ttd_scene_get_stats(W->scene, &count_stats) == TTD_OK);
        ENSURE_MSG(counted == con.count && count_stats.results == A->contact_stats.results &&
                       count_stats.body_pairs == A->contact_stats.body_pairs &&
                       count_stats.node_tests == A->contact_stats.node_tests &&
                       count_stats.pair_tests == A->contact_stats.pair_tests,
                   "contacts count %zu, stored %zu", counted, con.count);
        ENSURE(ttd_scene_distance_d(&opt, W->scene, INFINITY, &c, near) == TTD_OK);
        ENSURE(ttd_scene_distance_d(&opt, W->scene, BOUND, &b, NULL) == TTD_OK);
        ENSURE(ttd_scene_manifold_d(&opt, W->scene, MARGIN, MAX_POINTS, &man) == TTD_OK);
        A->closest = widen_d(&c);
        A->bounded = widen_d(&b);
        for (size_t k = 0; k < W->nbody; ++k)
            A->nearest[k] = widen_d(&near[k]);
        A->ncontacts = con.count;
        A->contacts = malloc((con.count + 1) * sizeof *A->contacts);
        for (size_t k = 0; k < con.count; ++k)
            A->contacts[k] = widen_d((const ttd_scene_contact_d *)con.data + k);
        A->npoints = man.count;
        A->points = malloc((man.count + 1) * sizeof *A->points);
        for (size_t k = 0; k < man.count; ++k) {
            const ttd_scene_point_d *p = (const ttd_scene_point_d *)man.data + k;
            A->points[k] = (point){p->i, p->j, p->tri_i, p->tri_j, {p->point[0], p->point[1], p->point[2]},
                                   {p->normal[0], p->normal[1], p->normal[2]}, p->distance, p->depth};
        }
    } else {
        ttd_scene_contact_f c, b, near[MAX_BODIES];
        ENSURE(ttd_scene_collide_f(&opt, W->scene, (float)MARGIN, &hits) == TTD_OK);
        ENSURE(ttd_scene_contacts_f(&opt, W->scene, (float)MARGIN, &con) == TTD_OK);
        ENSURE(ttd_scene_get_stats(W->scene, &A->contact_stats) == TTD_OK);
        /* the count alone: the stored query's number, and the same walks (the same stats) */
        size_t counted = SIZE_MAX;
        ttd_scene_stats count_stats;
        ENSURE(ttd_scene_contacts_count_f(&opt, W->scene, (float)MARGIN, &counted) == TTD_OK);
        ENSURE(ttd_scene_get_stats(W->scene, &count_stats) == TTD_OK);
        ENSURE_MSG(counted == con.count && count_stats.results == A->contact_stats.results &&
                       count_stats.body_pairs == A->contact_stats.body_pairs &&
                       count_stats.node_tests == A->contact_stats.node_tests &&
                       count_stats.pair_tests == A->contact_stats.pair_tests,
                   "contacts count %zu, stored %zu", counted, con.count);
        ENSURE(ttd_scene_distance_f(&opt, W->scene, INFINITY, &c, near) == TTD_OK);
        ENSURE(ttd_scene_distance_f(&opt, W->scene, (float)BOUND, &b, NULL) == TTD_OK);
        ENSURE(ttd_scene_manifold_f(&opt, W->scene, (float)MARGIN, MAX_POINTS, &man) == TTD_OK);
        A->closest = widen_f(&c);
        A->bounded = widen_f(&b);
        for (size_t k = 0; k < W->nbody; ++k)
            A->nearest[k] = widen_f(&near[k]);
        A->ncontacts = con.count;
        A->contacts = malloc((con.count + 1) * sizeof *A->contacts);
        for (size_t k = 0; k < con.count; ++k)
            A->contacts[k] = widen_f((const ttd_scene_contact_f *)con.data + k);
        A->npoints = man.count;
        A->points = malloc((man.count + 1) * sizeof *A->points);
        for (size_t k = 0; k < man.count; ++k) {
            const ttd_scene_point_f *p = (const ttd_scene_point_f *)man.data + k;
            A->points[k] = (point){p->i,
                                   p->j,
                                   p->tri_i,
                                   p->tri_j,
                                   {(double)p->point[0], (double)p->point[1], (double)p->point[2]},
                                   {(double)p->normal[0], (double)p->normal[1], (double)p->normal[2]},
                                   (double)p->distance,
                                   (double)p->depth};
        }
    }
    /* the stats of the contacts: every result was a pair given to the kernel, and the body pairs
     * handed on hold every body pair of the answer (it is sorted by (i, j)) */
    const ttd_scene_stats *st = &A->contact_stats;
    size_t distinct = 0;
    for (size_t k = 0; k < A->ncontacts; ++k)
        distinct += k == 0 || A->contacts[k].i != A->contacts[k - 1].i || A->contacts[k].j != A->contacts[k - 1].j;
    ENSURE_MSG(st->results == A->ncontacts && st->pair_tests >= st->results && st->body_pairs >= distinct &&
                   (A->ncontacts == 0 || st->node_tests > 0),
               "contacts' stats: %llu results (%zu contacts), %llu pair tests, %llu body pairs (%zu in the answer)",
               (unsigned long long)st->results, A->ncontacts, (unsigned long long)st->pair_tests,
               (unsigned long long)st->body_pairs, distinct);
    A->nhits = hits.count;
    A->hits = malloc((hits.count + 1) * sizeof *A->hits);
    if (hits.count)
        memcpy(A->hits, hits.data, hits.count * sizeof *A->hits);
    ttd_scene_array_free(&hits);
    ttd_scene_array_free(&con);
    ttd_scene_array_free(&man);
    ENSURE(A->hits && A->contacts && A->points);
    return 0;
}

static int same_contact(const contact *a, const contact *b)
{
    return a->i == b->i && a->j == b->j && a->ti == b->ti && a->tj == b->tj &&
           memcmp(&a->d, &b->d, sizeof a->d) == 0 && memcmp(a->p, b->p, sizeof a->p) == 0 &&
           memcmp(a->q, b->q, sizeof a->q) == 0;
}

static int same_answers(const world *W, const answers *x, const answers *y)
{
    ENSURE(x->nhits == y->nhits && x->ncontacts == y->ncontacts && x->npoints == y->npoints);
    ENSURE(x->nhits == 0 || memcmp(x->hits, y->hits, x->nhits * sizeof *x->hits) == 0);
    for (size_t k = 0; k < x->ncontacts; ++k)
        ENSURE(same_contact(&x->contacts[k], &y->contacts[k]));
    ENSURE(x->npoints == 0 || memcmp(x->points, y->points, x->npoints * sizeof *x->points) == 0);
    ENSURE(same_contact(&x->closest, &y->closest) && same_contact(&x->bounded, &y->bounded));
    for (size_t k = 0; k < W->nbody; ++k)
        ENSURE(same_contact(&x->nearest[k], &y->nearest[k]));
    return 0;
}

/* A contact record equal to the brute force's pair (a, b) of body pair P, seen from body `me`. */
static int record_is(const pairinfo *P, size_t k, uint32_t me, const contact *c)
{
    const size_t a = k / P->nt_j, b = k % P->nt_j;
    const int swap = me != P->i;
    const contact want = {swap ? P->j : P->i,
                          swap ? P->i : P->j,
                          (uint32_t)(swap ? b : a),
                          (uint32_t)(swap ? a : b),
                          P->d[k],
                          {(swap ? P->q : P->p)[3 * k], (swap ? P->q : P->p)[3 * k + 1], (swap ? P->q : P->p)[3 * k + 2]},
                          {(swap ? P->p : P->q)[3 * k], (swap ? P->p : P->q)[3 * k + 1], (swap ? P->p : P->q)[3 * k + 2]}};
    return same_contact(&want, c);
}

/* The smallest (own triangle, other's triangle) at distance d of body pair P seen from me. */
static size_t smallest_at(const pairinfo *P, double d, uint32_t me)
{
    size_t best = SIZE_MAX;
    for (size_t k = 0; k < P->nt_i * P->nt_j; ++k) {
        if (P->d[k] != d)
            continue;
        const size_t a = k / P->nt_j, b = k % P->nt_j;
        if (best == SIZE_MAX) {
            best = k;
            continue;
        }
        const size_t ba = best / P->nt_j, bb = best % P->nt_j;
        const int before = me == P->i ? (a < ba || (a == ba && b < bb)) : (b < bb || (b == bb && a < ba));
        if (before)
            best = k;
    }
    return best;
}

/* What the library calls a mesh's radius: the distance from its vertices' bounding-box centre
 * to the farthest vertex, rounded up by 4 eps (src/mesh/build.c). */
static double mesh_radius(const ttd_gen_mesh *g)
{
    double lo[3], hi[3], c[3], r = 0;
    ttd_gen_mesh_bounds(g, lo, hi);
    for (int k = 0; k < 3; ++k)
        c[k] = 0.5 * lo[k] + 0.5 * hi[k];
    for (size_t v = 0; v < g->nv; ++v) {
        const double d[3] = {g->verts[3 * v] - c[0], g->verts[3 * v + 1] - c[1], g->verts[3 * v + 2] - c[2]};
        const double h = hypot(hypot(d[0], d[1]), d[2]); /* no square underflows at tiny scales */
        r = h > r ? h : r;
    }
    return r * (1 + 4 * DBL_EPSILON);
}

static double dist3(const double *a, const double *b)
{
    return hypot(hypot(a[0] - b[0], a[1] - b[1]), a[2] - b[2]);
}

static size_t npoints_corner; /* the corners the brute force found (scene_corners_ref.h), for the summary */

static int check_against_brute(const world *W, const brute *B, const answers *A)
{
    const double m = round_to(W->bytes, MARGIN);
    /* collide */
    size_t h = 0;
    for (size_t k = 0; k < B->n; ++k) {
        size_t arg;
        const pairinfo *P = &B->pairs[k];
        if (!(pair_min(P, &arg) <= m))
            continue;
        ENSURE_MSG(h < A->nhits && A->hits[h].i == P->i && A->hits[h].j == P->j, "collide: pair (%u, %u) missing", P->i,
                   P->j);
        ENSURE(A->hits[h].tri_i < P->nt_i && A->hits[h].tri_j < P->nt_j);
        ENSURE(P->d[A->hits[h].tri_i * P->nt_j + A->hits[h].tri_j] <= m);
        ++h;
    }
    ENSURE_MSG(h == A->nhits, "collide: %zu pairs, brute force %zu", A->nhits, h);
    /* contacts, in order */
    size_t c = 0;
    for (size_t k = 0; k < B->n; ++k) {
        const pairinfo *P = &B->pairs[k];
        for (size_t x = 0; x < P->nt_i * P->nt_j; ++x) {
            if (!(P->d[x] <= m))
                continue;
            ENSURE_MSG(c < A->ncontacts && record_is(P, x, P->i, &A->contacts[c]),
                       "contacts: entry %zu is not pair (%u, %u) triangles (%zu, %zu) at %.17g", c, P->i, P->j,
                       x / P->nt_j, x % P->nt_j, P->d[x]);
            ++c;
        }
    }
    ENSURE_MSG(c == A->ncontacts, "contacts: %zu, brute force %zu", A->ncontacts, c);
    /* closest pair (ties: smallest (i, j), then triangles), and within the bound */
    double best = INFINITY;
    size_t bk = SIZE_MAX;
    for (size_t k = 0; k < B->n; ++k) {
        size_t arg;
        const double d = pair_min(&B->pairs[k], &arg);
        if (d < best) {
            best = d;
            bk = k;
        }
    }
    if (bk == SIZE_MAX) {
        ENSURE(A->closest.i == UINT32_MAX && isinf(A->closest.d));
    } else {
        const pairinfo *P = &B->pairs[bk];
        ENSURE_MSG(record_is(P, smallest_at(P, best, P->i), P->i, &A->closest),
                   "closest: (%u, %u) at %.17g, brute force (%u, %u) at %.17g", A->closest.i, A->closest.j, A->closest.d,
                   P->i, P->j, best);
    }
    if (best <= round_to(W->bytes, BOUND))
        ENSURE(same_contact(&A->bounded, &A->closest));
    else
        ENSURE(isinf(A->bounded.d) && A->bounded.j == UINT32_MAX);
    /* each body's nearest (ties: smallest partner, then triangles) */
    for (size_t id = 0; id < W->nbody; ++id) {
        double nb = INFINITY;
        const pairinfo *np = NULL;
        uint32_t partner = UINT32_MAX;
        for (size_t k = 0; W->mesh_of[id] >= 0 && k < B->n; ++k) {
            const pairinfo *P = &B->pairs[k];
            if (P->i != id && P->j != id)
                continue;
            size_t arg;
            const double d = pair_min(P, &arg);
            const uint32_t o = P->i == id ? P->j : P->i;
            if (d < nb || (d == nb && o < partner)) {
                nb = d;
                np = P;
                partner = o;
            }
        }
        if (np == NULL) {
            ENSURE_MSG(isinf(A->nearest[id].d) && A->nearest[id].j == UINT32_MAX, "body %zu: a nearest where none", id);
        } else {
            ENSURE_MSG(record_is(np, smallest_at(np, nb, (uint32_t)id), (uint32_t)id, &A->nearest[id]),
                       "body %zu: nearest %u at %.17g, brute force %u at %.17g", id, A->nearest[id].j,
                       A->nearest[id].d, partner, nb);
        }
    }
    /* manifolds (docs/scenes.md, section 5): the contacts and the corners they add
     * (scene_corners_ref.h) merged in depth order (a point within 1e-3 of the smaller radius of a
     * point kept before it goes), min(K, those kept) points of them, the first within the seed's
     * window of the smallest distance, the second the farthest from it, the third the largest
     * triangle with those two; no two points within the tolerance; unit normals (their rule:
     * tests/test_scene_contacts.c) */
    size_t at = 0;
    const double eps = W->bytes == 8 ? DBL_EPSILON : (double)FLT_EPSILON;
    const double window = W->bytes == 8 ? 0x1p-30 : 0x1p-16;
    corner_mesh shape[5];
    for (int k = 0; k < 5; ++k)
        ENSURE(corner_mesh_make(W->gm[k].verts, W->gm[k].tris, W->gm[k].nt, &shape[k]));
    for (size_t k = 0; k < B->n; ++k) {
        const pairinfo *P = &B->pairs[k];
        const ttd_gen_mesh *gi = &W->gm[W->mesh_of[P->i]], *gj = &W->gm[W->mesh_of[P->j]];
        const double ri = mesh_radius(gi), rj = mesh_radius(gj);
        const double tol = 1e-3 * (ri < rj ? ri : rj), big = ri > rj ? ri : rj;
        /* the contacts and their corners */
        size_t nc = 0;
        unsigned char *in = malloc(P->nt_i * P->nt_j);
        ENSURE(in != NULL);
        for (size_t x = 0; x < P->nt_i * P->nt_j; ++x)
            nc += (in[x] = P->d[x] <= m);
        if (nc == 0) {
            free(in);
            continue;
        }
        double *wi = malloc(9 * P->nt_i * sizeof *wi), *wj = malloc(9 * P->nt_j * sizeof *wj);
        ENSURE(wi && wj);
        for (size_t t = 0; t < P->nt_i; ++t)
            for (int v = 0; v < 3; ++v)
                world_vertex(W, P->i, gi->tris[3 * t + (size_t)v], wi + 9 * t + 3 * v);
        for (size_t t = 0; t < P->nt_j; ++t)
            for (int v = 0; v < 3; ++v)
                world_vertex(W, P->j, gj->tris[3 * t + (size_t)v], wj + 9 * t + 3 * v);
        corner_rec *corner;
        const size_t ncorner = corner_refs(&shape[W->mesh_of[P->i]], wi, &shape[W->mesh_of[P->j]], wj, in, m, W->bytes, &corner);
        ENSURE(ncorner != SIZE_MAX);
        /* the contacts of flat contact are no points: their region's corners stand for them */
        uint32_t *cti = malloc(nc * sizeof *cti), *ctj = malloc(nc * sizeof *ctj);
        double *cdist = malloc(nc * sizeof *cdist);
        unsigned char *flat = malloc(nc);
        ENSURE(cti && ctj && cdist && flat);
        size_t nin = 0;
        for (size_t x = 0; x < P->nt_i * P->nt_j; ++x)
            if (P->d[x] <= m) {
                cti[nin] = (uint32_t)(x / P->nt_j);
                ctj[nin] = (uint32_t)(x % P->nt_j);
                cdist[nin++] = P->d[x];
            }
        corner_ref_flat(&shape[W->mesh_of[P->i]], wi, &shape[W->mesh_of[P->j]], wj, nin, cti, ctj, cdist, flat);
        free(cti);
        free(ctj);
        free(cdist);
        free(in);
        free(wi);
        free(wj);
        corner_rec *rec = malloc((nc + ncorner) * sizeof *rec);
        size_t *ord = malloc((nc + ncorner) * sizeof *ord), *kept = malloc((nc + ncorner) * sizeof *kept), nk = 0;
        double (*mid)[3] = malloc((nc + ncorner) * sizeof *mid), (*exact_mid)[3] = malloc((nc + ncorner) * sizeof *exact_mid);
        ENSURE(rec && ord && kept && mid && exact_mid);
        nc = 0;
        size_t ci = 0;
        for (size_t x = 0; x < P->nt_i * P->nt_j; ++x)
            if (P->d[x] <= m && !flat[ci++]) {
                corner_rec r = {(uint32_t)(x / P->nt_j), (uint32_t)(x % P->nt_j), P->d[x], {0}, {0}};
                memcpy(r.p, P->p + 3 * x, sizeof r.p);
                memcpy(r.q, P->q + 3 * x, sizeof r.q);
                rec[nc++] = r;
            }
        free(flat);
        if (ncorner > 0)
            memcpy(rec + nc, corner, ncorner * sizeof *rec);
        nc += ncorner;
        free(corner);
        for (size_t a = 0; a < nc; ++a) {
            ord[a] = a;
            for (int r = 0; r < 3; ++r)
                exact_mid[a][r] = 0.5 * rec[a].p[r] + 0.5 * rec[a].q[r];
        }
        /* depth order: distance, triangles, midpoint (insertion sort) */
        for (size_t a = 1; a < nc; ++a)
            for (size_t b = a; b > 0; --b) {
                const corner_rec *x = &rec[ord[b]], *y = &rec[ord[b - 1]];
                int before = x->d != y->d ? x->d < y->d : x->ti != y->ti ? x->ti < y->ti : x->tj != y->tj ? x->tj < y->tj : 0;
                if (x->d == y->d && x->ti == y->ti && x->tj == y->tj)
                    for (int r = 2; r >= 0; --r)
                        if (exact_mid[ord[b]][r] != exact_mid[ord[b - 1]][r])
                            before = exact_mid[ord[b]][r] < exact_mid[ord[b - 1]][r];
                if (!before)
                    break;
                const size_t t = ord[b];
                ord[b] = ord[b - 1];
                ord[b - 1] = t;
            }
        for (size_t a = 0; a < nc; ++a)
            for (int r = 0; r < 3; ++r) {
                volatile double x = exact_mid[ord[a]][r]; /* gcc 12 -O3 vectorised this loop wrongly: the
                                                           * last point kept its double value */
                mid[a][r] = round_to(W->bytes, x);
            }
        for (size_t a = 0; a < nc; ++a) {
            int near = 0;
            for (size_t b = 0; b < nk && !near; ++b)
                near = dist3(mid[a], mid[kept[b]]) <= tol;
            if (!near)
                kept[nk++] = a;
        }
        const size_t want = nk < MAX_POINTS ? nk : MAX_POINTS;
        /* the deepest level the spread works in first: within a quarter of the margin left below
         * the smallest distance (or the seed's window), each point rising above every deeper one
         * of the level by at most 0.1 of the distance between them (the seed's window whole) */
        const double d0 = rec[ord[kept[0]]].d;
        unsigned char *lvl = calloc(nk + 1, 1);
        ENSURE(lvl);
        size_t nl = 0;
        for (size_t b = 0; b < nk; ++b) {
            const double db = rec[ord[kept[b]]].d;
            if (db - d0 <= window * big) {
                lvl[b] = 1;
            } else if (db - d0 <= 0.25 * (m - d0)) {
                lvl[b] = 1;
                for (size_t a = 0; a < b && lvl[b]; ++a)
                    lvl[b] = !lvl[a] || db - rec[ord[kept[a]]].d <= 0.1 * dist3(mid[kept[a]], mid[kept[b]]);
            }
            nl += lvl[b];
        }
        /* of the level, the touching points: within 1/64 of the margin left above the smallest
         * distance; the spread is over them when MAX_POINTS or more touch */
        size_t nt = 0;
        for (size_t b = 0; b < nk; ++b)
            if (lvl[b] && rec[ord[kept[b]]].d - d0 <= (m - d0) / 64) {
                lvl[b] = 2;
                ++nt;
            }
        for (size_t n = 0; n < want; ++n, ++at) {
            ENSURE(at < A->npoints);
            const point *pt = &A->points[at];
            ENSURE(pt->i == P->i && pt->j == P->j && pt->ti < P->nt_i && pt->tj < P->nt_j);
            /* one of those kept by the merge: its triangles, point, distance and depth */
            size_t me = SIZE_MAX;
            for (size_t b = 0; b < nk && me == SIZE_MAX; ++b) {
                const corner_rec *x = &rec[ord[kept[b]]];
                me = x->ti == pt->ti && x->tj == pt->tj && x->d == pt->d && mid[kept[b]][0] == pt->x[0] &&
                             mid[kept[b]][1] == pt->x[1] && mid[kept[b]][2] == pt->x[2]
                         ? b
                         : me;
            }
            ENSURE_MSG(me != SIZE_MAX, "manifold (%u, %u): triangles (%u, %u) at (%.17g, %.17g, %.17g) d %.17g is none "
                       "of the contacts and corners kept by the merge", P->i, P->j, pt->ti, pt->tj, pt->x[0], pt->x[1],
                       pt->x[2], pt->d);
            ENSURE(pt->d <= m && pt->depth == round_to(W->bytes, m - pt->d));
            const double nn = pt->n[0] * pt->n[0] + pt->n[1] * pt->n[1] + pt->n[2] * pt->n[2];
            ENSURE_NEAR(nn, 1.0, 16 * eps);
            if (n == 0)
                ENSURE_MSG(pt->d - rec[ord[0]].d <= window * big, "manifold (%u, %u): first point not the deepest", P->i,
                           P->j);
            for (size_t b = at - n; b < at; ++b)
                ENSURE_MSG(dist3(pt->x, A->points[b].x) > tol * (1 - 1e-9), "manifold (%u, %u): points %zu and %zu within %g",
                           P->i, P->j, b - (at - n), n, tol);
            if (nk > MAX_POINTS && nl < MAX_POINTS && n < nl) /* a short level: all of it first */
                ENSURE_MSG(lvl[me], "manifold (%u, %u): point %zu not of the deepest level", P->i, P->j, n);
            if (nk > MAX_POINTS && nl >= MAX_POINTS && nt < MAX_POINTS) /* few touch: they first, then the level */
                ENSURE_MSG(n < nt ? lvl[me] == 2 : lvl[me] == 1, "manifold (%u, %u): point %zu not %s", P->i, P->j, n,
                           n < nt ? "touching" : "of the level");
            if (nk > MAX_POINTS && nt >= MAX_POINTS && (n == 1 || n == 2)) {
                /* within the touching points: farthest from the first; the largest triangle with
                 * the first two */
                ENSURE_MSG(lvl[me] == 2, "manifold (%u, %u): point %zu not touching", P->i, P->j, n);
                const double *x0 = A->points[at - n].x, *x1 = n == 2 ? A->points[at - 1].x : NULL;
                double mine = 0, other = 0;
                for (size_t b = 0; b < nk; ++b) {
                    if (lvl[b] != 2)
                        continue;
                    const double *y = mid[kept[b]];
                    double v;
                    if (n == 1) {
                        v = dist3(y, x0);
                    } else {
                        const double e1[3] = {x1[0] - x0[0], x1[1] - x0[1], x1[2] - x0[2]};
                        const double e2[3] = {y[0] - x0[0], y[1] - x0[1], y[2] - x0[2]};
                        const double cr[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                                              e1[0] * e2[1] - e1[1] * e2[0]};
                        v = sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
                    }
                    if (b == me)
                        mine = v;
                    other = v > other ? v : other;
                }
                /* a zero triangle (points on a line) falls back to the farthest point */
                if (!(n == 2 && other == 0))
                    ENSURE_MSG(mine >= other * (1 - 1e-9), "manifold (%u, %u): point %zu not the spread's choice (%g < %g)",
                               P->i, P->j, n, mine, other);
            }
        }
        npoints_corner += ncorner;
        free(lvl);
        free(rec);
        free(ord);
        free(kept);
        free(mid);
        free(exact_mid);
    }
    for (int k = 0; k < 5; ++k)
        corner_mesh_free(&shape[k]);
    ENSURE_MSG(at == A->npoints, "manifold: %zu points, expected %zu", A->npoints, at);
    return 0;
}

/* Every instruction set and 1 or 2 threads: the scalar row's answers, which equal the brute
 * force. Returns the number of contacts (so callers can see the scene is not empty). */
static int check_world(const world *W, const char *what, size_t *ncontacts)
{
    brute B;
    ENSURE(brute_force(W, &B) == 0);
    answers ref;
    ENSURE(ask(W, TTD_ISA_SCALAR, 1, &ref) == 0);
    npoints_corner = 0;
    const int bad = check_against_brute(W, &B, &ref);
    brute_free(&B);
    ENSURE_MSG(!bad, "%s (%s): scalar row against brute force", what, W->bytes == 8 ? "double" : "float");
    for (int isa = TTD_ISA_SCALAR; isa < TTD_ISA_COUNT; ++isa) {
        if (!ttd_isa_available((ttd_isa)isa))
            continue;
        for (int threads = 1; threads <= 2; ++threads) {
            if (isa == TTD_ISA_SCALAR && threads == 1)
                continue;
            answers A;
            ENSURE(ask(W, (ttd_isa)isa, threads, &A) == 0);
            /* the work behind the contacts is fixed by the scene too, not only the answer */
            const int diff = same_answers(W, &ref, &A) ||
                             memcmp(&ref.contact_stats, &A.contact_stats, sizeof ref.contact_stats) != 0;
            answers_free(&A);
            ENSURE_MSG(!diff, "%s: %s with %d threads differs from the scalar row", what, ttd_isa_name((ttd_isa)isa),
                       threads);
        }
    }
    *ncontacts = ref.ncontacts;
    printf("  %s, %s: %zu bodies, %zu colliding pairs, %zu contacts (and %zu corners), %zu manifold points, closest %.3g\n",
           what, W->bytes == 8 ? "double" : "float", W->nbody, ref.nhits, ref.ncontacts, npoints_corner, ref.npoints,
           ref.closest.d);
    answers_free(&ref);
    return 0;
}

/* ---- scenes ------------------------------------------------------------------------------ */

/* A soup of thin and degenerate triangles: collinear, needles, a segment, a point. */
static int thin_soup(ttd_gen_mesh *m)
{
    const size_t nt = 12;
    m->nv = 3 * nt;
    m->nt = nt;
    m->verts = malloc(9 * nt * sizeof *m->verts);
    m->tris = malloc(3 * nt * sizeof *m->tris);
    ENSURE(m->verts && m->tris);
    ttd_gen_rng r = ttd_gen_rng_make(99, 1);
    for (size_t k = 0; k < nt; ++k) {
        double a[3], b[3];
        for (int c = 0; c < 3; ++c) {
            a[c] = ttd_gen_rng_uniform(&r) - 0.5;
            b[c] = ttd_gen_rng_uniform(&r) - 0.5;
        }
        const double w = k % 4 == 0 ? 0 : pow(10, -(double)(3 * (k % 4) + 2)), f = 0.3;
        for (int c = 0; c < 3; ++c) {
            m->verts[9 * k + (size_t)c] = a[c];
            m->verts[9 * k + 3 + (size_t)c] = k == 5 ? a[c] : b[c];
            m->verts[9 * k + 6 + (size_t)c] = k == 5 ? a[c] : a[c] + f * (b[c] - a[c]) + w * (c == 0 ? 1 : -0.5);
        }
        for (int c = 0; c < 3; ++c)
            m->tris[3 * k + (size_t)c] = (uint32_t)(3 * k + (size_t)c);
    }
    return 0;
}

/* The floor's cells a side (ttd_gen_grid) and the cube's size (times the others'):
 * resting_cube_on_fine_floor makes both large. */
static size_t floor_cells = 4;
static double cube_size = 1;

static int make_world(world *W, int bytes, size_t nbody, double spread, int with_floor)
{
    memset(W, 0, sizeof *W);
    W->bytes = bytes;
    ENSURE(ttd_gen_icosphere(1, &W->gm[0]) == 0);
    ENSURE(ttd_gen_mesh_cube(&W->gm[1]) == 0);
    ENSURE(thin_soup(&W->gm[2]) == 0);
    ENSURE(ttd_gen_mesh_degenerate(&W->gm[3]) == 0);
    ENSURE(ttd_gen_grid(floor_cells, &W->gm[4]) == 0); /* the floor, scaled below */
    for (int k = 0; k < 4; ++k)
        ENSURE(ttd_gen_normalize(&W->gm[k]) == 0);
    for (size_t i = 0; i < 3 * W->gm[1].nv; ++i)
        W->gm[1].verts[i] *= cube_size;
    {
        const double big[12] = {20, 0, 0, 0, 0, 20, 0, 0, 0, 0, 20, 0};
        ENSURE(ttd_gen_normalize(&W->gm[4]) == 0);
        ENSURE(ttd_gen_mesh_transform(&W->gm[4], big, &W->gm[4]) == 0);
    }
    for (int k = 0; k < 5; ++k)
        for (size_t i = 0; i < 3 * W->gm[k].nv; ++i)
            W->gm[k].verts[i] *= world_scale;
    for (int k = 0; k < 5; ++k) {
        const ttd_gen_mesh *g = &W->gm[k];
        if (bytes == 8) {
            ENSURE(ttd_mesh_create_d(NULL, g->verts, g->nv, g->tris, g->nt, &W->mesh[k]) == TTD_OK);
        } else {
            float *v = malloc(3 * g->nv * sizeof *v);
            ENSURE(v != NULL);
            for (size_t i = 0; i < 3 * g->nv; ++i)
                v[i] = (float)g->verts[i];
            /* the test's world vertices read the double copy: keep it equal to the float one */
            for (size_t i = 0; i < 3 * g->nv; ++i)
                W->gm[k].verts[i] = (double)v[i];
            ENSURE(ttd_mesh_create_f(NULL, v, g->nv, g->tris, g->nt, &W->mesh[k]) == TTD_OK);
            free(v);
        }
    }
    ENSURE((bytes == 8 ? ttd_scene_create_d(&W->scene) : ttd_scene_create_f(&W->scene)) == TTD_OK);
    double unscaled_t[MAX_BODIES][3]; /* the translations before world_scale and world_offset */
    for (size_t id = 0; id < nbody; ++id) {
        /* bodies in a 2.5-wide box, a few of them touching or nearly (gaps 0..0.03 of the next
         * body's reach), the last one the floor under them all */
        const int floor = with_floor && id + 1 == nbody;
        W->mesh_of[id] = floor ? 4 : (int)(id % 4);
        ttd_gen_pose(7 + (uint64_t)bytes + (uint64_t)spread, id, spread, W->pose[id]);
        if (floor) {
            const double flat[12] = {1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, -1.3};
            memcpy(W->pose[id], flat, sizeof flat);
        } else if (id % 3 == 1 && id > 0 && with_floor) {
            for (int r = 0; r < 3; ++r)
                W->pose[id][4 * r + 3] = unscaled_t[id - 1][r] + (r == 0 ? 0.45 + 0.01 * (double)(id % 4) : 0.02);
        }
        for (int r = 0; r < 3; ++r) {
            unscaled_t[id][r] = W->pose[id][4 * r + 3];
            W->pose[id][4 * r + 3] = W->pose[id][4 * r + 3] * world_scale + world_offset;
        }
        for (int k = 0; k < 12; ++k)
            W->pose[id][k] = round_to(bytes, W->pose[id][k]);
        W->group[id] = 1;
        W->mask[id] = UINT32_MAX;
        uint32_t got;
        if (bytes == 8) {
            ENSURE(ttd_scene_add_d(W->scene, W->mesh[W->mesh_of[id]], W->pose[id], &got) == TTD_OK);
        } else {
            float pf[12];
            for (int k = 0; k < 12; ++k)
                pf[k] = (float)W->pose[id][k];
            ENSURE(ttd_scene_add_f(W->scene, W->mesh[W->mesh_of[id]], pf, &got) == TTD_OK);
        }
        ENSURE(got == id);
        W->nbody++;
    }
    return 0;
}

static void free_world(world *W)
{
    ttd_scene_destroy(W->scene);
    for (int k = 0; k < 5; ++k) {
        ttd_mesh_destroy(W->mesh[k]);
        ttd_gen_mesh_free(&W->gm[k]);
    }
}

static int set_all_poses(world *W)
{
    double all[MAX_BODIES * 12];
    float allf[MAX_BODIES * 12];
    for (size_t id = 0; id < W->nbody; ++id)
        for (int k = 0; k < 12; ++k) {
            all[12 * id + (size_t)k] = W->pose[id][k];
            allf[12 * id + (size_t)k] = (float)W->pose[id][k];
        }
    if (W->bytes == 8)
        ENSURE(ttd_scene_set_poses_d(W->scene, W->nbody, all) == TTD_OK);
    else
        ENSURE(ttd_scene_set_poses_f(W->scene, W->nbody, allf) == TTD_OK);
    return 0;
}

static int scenes_match_brute_force(void)
{
    for (int bytes = 8; bytes >= 4; bytes -= 4) {
        world W;
        ENSURE(make_world(&W, bytes, 24, 1.25, 1) == 0);
        size_t n0, n1, n2, n3;
        ENSURE(check_world(&W, "pile with floor", &n0) == 0);
        ENSURE(n0 > 0);
        /* remove two bodies, add one (a new id), exclude a pair, filter a body */
        ENSURE(ttd_scene_remove(W.scene, 3) == TTD_OK);
        ENSURE(ttd_scene_remove(W.scene, 3) == TTD_ERR_INDEX_OUT_OF_RANGE);
        W.mesh_of[3] = -1;
        ENSURE(ttd_scene_remove(W.scene, 10) == TTD_OK);
        W.mesh_of[10] = -1;
        W.mesh_of[W.nbody] = 2;
        memcpy(W.pose[W.nbody], W.pose[4], sizeof W.pose[4]);
        W.pose[W.nbody][11] = round_to(bytes, W.pose[W.nbody][11] + 0.01);
        W.group[W.nbody] = 1;
        W.mask[W.nbody] = UINT32_MAX;
        uint32_t got;
        if (bytes == 8) {
            ENSURE(ttd_scene_add_d(W.scene, W.mesh[2], W.pose[W.nbody], &got) == TTD_OK);
        } else {
            float pf[12];
            for (int k = 0; k < 12; ++k)
                pf[k] = (float)W.pose[W.nbody][k];
            ENSURE(ttd_scene_add_f(W.scene, W.mesh[2], pf, &got) == TTD_OK);
        }
        ENSURE(got == W.nbody);
        W.nbody++;
        ENSURE(ttd_scene_exclude_pair(W.scene, 5, 4, 1) == TTD_OK);
        W.excluded[4][5] = W.excluded[5][4] = 1;
        ENSURE(ttd_scene_exclude_pair(W.scene, 7, 6, 1) == TTD_OK);
        ENSURE(ttd_scene_exclude_pair(W.scene, 6, 7, 0) == TTD_OK); /* and included again */
        ENSURE(ttd_scene_set_filter(W.scene, 1, 2, 2) == TTD_OK);   /* body 1 meets group 2 only */
        W.group[1] = 2;
        W.mask[1] = 2;
        ENSURE(ttd_scene_set_filter(W.scene, 2, 3, UINT32_MAX) == TTD_OK);
        W.group[2] = 3;
        ENSURE(check_world(&W, "after removals, an addition, filters and an exclusion", &n1) == 0);
        /* every body moved a little: the broad phase's order repaired, not rebuilt */
        for (size_t id = 0; id < W.nbody; ++id)
            for (int r = 0; r < 3; ++r)
                W.pose[id][4 * r + 3] = round_to(bytes, W.pose[id][4 * r + 3] + 0.004 * (double)((id * 7 + (size_t)r) % 5) - 0.008);
        ENSURE(set_all_poses(&W) == 0);
        ENSURE(check_world(&W, "every body moved", &n2) == 0);
        /* one body moved alone, onto another */
        memcpy(W.pose[0], W.pose[5], sizeof W.pose[0]);
        if (bytes == 8) {
            ENSURE(ttd_scene_set_pose_d(W.scene, 0, W.pose[0]) == TTD_OK);
        } else {
            float pf[12];
            for (int k = 0; k < 12; ++k)
                pf[k] = (float)W.pose[0][k];
            ENSURE(ttd_scene_set_pose_f(W.scene, 0, pf) == TTD_OK);
        }
        ENSURE(check_world(&W, "one body onto another", &n3) == 0);
        free_world(&W);
    }
    return 0;
}

/* Cubes stacked face on face, tilted, turned, offset, flush and at a gap within the margin (the
 * pile's other bodies moved away): the manifolds, with their corners of flat contact, against the
 * brute force in both precisions, every instruction set and thread count. */
static int stacked_cubes_match_brute_force(void)
{
    for (int bytes = 8; bytes >= 4; bytes -= 4) {
        world W;
        ENSURE(make_world(&W, bytes, 12, 1.25, 0) == 0);
        double lo[3], hi[3];
        ENSURE(ttd_gen_mesh_bounds(&W.gm[1], lo, hi) == 0);
        const double side = hi[2] - lo[2];
        /* cubes (mesh 1) are bodies 1, 5 and 9: yaw about z after a tilt about x, centre */
        static const double place[3][4] = {{0, 0, 0, 0}, {0.4, 0.01, 0.05, 0.004}, {-0.3, 0, -0.04, 0}};
        double z = 0;
        for (size_t id = 0; id < W.nbody; ++id) {
            double *P = W.pose[id];
            if (W.mesh_of[id] != 1) {
                const double far[12] = {1, 0, 0, 10 + 3 * (double)id, 0, 1, 0, 0, 0, 0, 1, 0};
                memcpy(P, far, sizeof far);
            } else {
                const double *q = place[id / 4];
                const double cy = cos(q[0]), sy = sin(q[0]), ct = cos(q[1]), st = sin(q[1]);
                const double R[9] = {cy, -sy * ct, sy * st, sy, cy * ct, -cy * st, 0, st, ct};
                const double c[3] = {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])};
                const double at[3] = {q[2], -q[2], z};
                for (int r = 0; r < 3; ++r) {
                    for (int k = 0; k < 3; ++k)
                        P[4 * r + k] = R[3 * r + k];
                    P[4 * r + 3] = at[r] - (R[3 * r] * c[0] + R[3 * r + 1] * c[1] + R[3 * r + 2] * c[2]);
                }
                z += side + q[3] + 0.5 * side * fabs(q[1]) + 0.004; /* the next one's rest, within the margin */
            }
            for (int k = 0; k < 12; ++k)
                P[k] = round_to(bytes, P[k]);
        }
        ENSURE(set_all_poses(&W) == 0);
        size_t n;
        ENSURE(check_world(&W, "stacked cubes", &n) == 0);
        ENSURE(n > 0 && npoints_corner > 0);
        free_world(&W);
    }
    return 0;
}

/* A cube resting on a floor of many small cells, turned and just above it: one body pair with
 * hundreds of contacts and corners at its deepest level, so that the reduction's depth order runs
 * its radix sort (512 points or more, docs/scene-speed.md section 7), checked like every scene
 * against the brute force's contacts and corners in the reference's depth order. */
static int resting_cube_on_fine_floor(void)
{
    for (int bytes = 8; bytes >= 4; bytes -= 4) {
        world W;
        floor_cells = 64;
        cube_size = 8; /* 4.6 wide on a floor 14.1 wide in cells of 0.22: about 440 cells under it */
        const int made = make_world(&W, bytes, 3, 1.25, 1); /* an icosphere, a cube, the floor */
        floor_cells = 4;
        cube_size = 1;
        ENSURE(made == 0);
        ENSURE(ttd_scene_remove(W.scene, 0) == TTD_OK);
        W.mesh_of[0] = -1;
        double top = -HUGE_VAL, lo[3], hi[3];
        for (size_t v = 0; v < W.gm[4].nv; ++v) {
            double x[3];
            world_vertex(&W, 2, v, x);
            top = fmax(top, x[1]); /* the floor is the plane y = 0 (make_world's pose) */
        }
        ENSURE(ttd_gen_mesh_bounds(&W.gm[1], lo, hi) == 0);
        const double a = 0.3, c = cos(a), sn = sin(a);
        const double R[9] = {c, 0, sn, 0, 1, 0, -sn, 0, c}; /* turned about the floor's normal */
        const double ctr[3] = {0.5 * (lo[0] + hi[0]), lo[1], 0.5 * (lo[2] + hi[2])};
        const double at[3] = {0.137, top + 0.004, -1.3 - 0.211}; /* a face 0.004 off the floor, within the margin */
        double *P = W.pose[1];
        for (int r = 0; r < 3; ++r) {
            for (int k = 0; k < 3; ++k)
                P[4 * r + k] = R[3 * r + k];
            P[4 * r + 3] = at[r] - (R[3 * r] * ctr[0] + R[3 * r + 1] * ctr[1] + R[3 * r + 2] * ctr[2]);
        }
        for (int k = 0; k < 12; ++k)
            P[k] = round_to(bytes, P[k]);
        if (bytes == 8) {
            ENSURE(ttd_scene_set_pose_d(W.scene, 1, P) == TTD_OK);
        } else {
            float pf[12];
            for (int k = 0; k < 12; ++k)
                pf[k] = (float)P[k];
            ENSURE(ttd_scene_set_pose_f(W.scene, 1, pf) == TTD_OK);
        }
        size_t n;
        ENSURE(check_world(&W, "cube on a fine floor", &n) == 0);
        ENSURE(n + npoints_corner >= 512);
        free_world(&W);
    }
    return 0;
}

/* Bodies far apart (no contacts): the closest pair and each body's nearest come from margins
 * grown until they hold them, then best first per body (boxes' gaps as lower bounds); at unit
 * scale, tiny and huge scales and far from the origin, where the gaps' rounding and scaling
 * matter. */
static int sparse_scene_distances(void)
{
    static const struct { int bytes; double scale, offset; } cases[] = {
        {8, 1, 0}, {4, 1, 0}, {8, 1e-150, 0}, {8, 1e150, 0}, {8, 1, 1e6}, {4, 1e-15, 0}, {4, 1e15, 0}, {4, 1, 1e3}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        world_scale = cases[c].scale;
        world_offset = cases[c].offset;
        world W;
        char what[96];
        snprintf(what, sizeof what, "sparse at scale %g, offset %g", world_scale, world_offset);
        size_t n;
        const int bad = make_world(&W, cases[c].bytes, 14, 12, 0) != 0 || check_world(&W, what, &n) != 0;
        free_world(&W);
        world_scale = 1;
        world_offset = 0;
        ENSURE_MSG(!bad, "%s", what);
    }
    return 0;
}

/* A cube resting on another, offset: the manifold's normals are the face it rests on (+z from
 * the lower to the upper), also at the pairs where an edge of the lower cube's side faces meets
 * the upper cube's bottom (d = 0 gives no direction from p to q), and no point twice. */
static int resting_cube_normals(void)
{
    ttd_gen_mesh g;
    ENSURE(ttd_gen_mesh_cube(&g) == 0);
    double lo[3], hi[3];
    ENSURE(ttd_gen_mesh_bounds(&g, lo, hi) == 0);
    ttd_mesh *m;
    ENSURE(ttd_mesh_create_d(NULL, g.verts, g.nv, g.tris, g.nt, &m) == TTD_OK);
    ttd_scene *s;
    ENSURE(ttd_scene_create_d(&s) == TTD_OK);
    const double h = hi[2] - lo[2], w = hi[0] - lo[0];
    const double below[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    const double above[12] = {1, 0, 0, 0.25 * w, 0, 1, 0, 0.25 * w, 0, 0, 1, h};
    uint32_t id;
    ENSURE(ttd_scene_add_d(s, m, below, &id) == TTD_OK);
    ENSURE(ttd_scene_add_d(s, m, above, &id) == TTD_OK);
    ttd_scene_array out = {0};
    ENSURE(ttd_scene_manifold_d(NULL, s, 0, 8, &out) == TTD_OK);
    ENSURE(out.count >= 3 && out.count <= 8);
    const ttd_scene_point_d *p = out.data;
    for (size_t k = 0; k < out.count; ++k) {
        ENSURE_MSG(p[k].normal[0] == 0 && p[k].normal[1] == 0 && p[k].normal[2] == 1,
                   "point %zu (triangles %u, %u) at (%g, %g, %g): normal (%g, %g, %g)", k, p[k].tri_i, p[k].tri_j,
                   p[k].point[0], p[k].point[1], p[k].point[2], p[k].normal[0], p[k].normal[1], p[k].normal[2]);
        ENSURE(p[k].distance == 0 && p[k].point[2] == hi[2]);
        for (size_t l = 0; l < k; ++l)
            ENSURE(memcmp(p[k].point, p[l].point, sizeof p[k].point) != 0);
    }
    printf("  resting cube: %zu manifold points, every normal +z\n", out.count);
    ttd_scene_array_free(&out);
    ttd_scene_destroy(s);
    ttd_mesh_destroy(m);
    ttd_gen_mesh_free(&g);
    return 0;
}

/* Tiny and huge scenes, and scenes far from the origin: the pile with its floor at scales 1e-6
 * and 1e6, and at unit scale moved by 1e6 (the world boxes' rounding margin and the traversal's,
 * which grows with where the bodies sit), in double; float at 1e-3 and 1e3. */
static int scaled_scenes(void)
{
    static const struct { int bytes; double scale, offset; } cases[] = {
        {8, 1e-6, 0}, {8, 1e6, 0}, {8, 1, 1e6}, {8, 1e-6, 3e-4}, {4, 1e-3, 0}, {4, 1e3, 0}, {4, 1, 1e3},
        {8, 1e-163, 0}, {8, 1e70, 0}, {8, 1e-78, 0}, {8, 1e150, 0}, {8, 1e-300, 0}, {8, 1e-160, 1e-158}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        world_scale = cases[c].scale;
        world_offset = cases[c].offset;
        world W;
        char what[96];
        snprintf(what, sizeof what, "pile at scale %g, offset %g", world_scale, world_offset);
        size_t n;
        const int bad = make_world(&W, cases[c].bytes, 16, 1.25, 1) != 0 || check_world(&W, what, &n) != 0;
        free_world(&W);
        world_scale = 1;
        world_offset = 0;
        ENSURE_MSG(!bad, "%s", what);
        ENSURE(n > 0);
    }
    return 0;
}

/* The closest pair alone (no nearest[]) where the first touching pair in (i, j) order comes late
 * and early: a row of 120 unit cubes 2 apart (nothing touches) with cube 97 moved onto cube 60
 * and cube 119 onto cube 118, and then cube 1 onto cube 0. The closest-only query scans the first
 * bodies' boxes before it sweeps, and gives up on the first scene (the pair is past its budget),
 * finds the pair itself on the second; both must give the general path's answer (each body's
 * nearest asked too, which sweeps at growing margins): the pair, distance 0, its triangles and
 * point. Then every cube apart: no pair touches, the closest is (96, 97), 0.5 apart. */
static int closest_pair_order(void)
{
    ttd_gen_mesh g;
    ENSURE(ttd_gen_mesh_cube(&g) == 0);
    ttd_mesh *m;
    ENSURE(ttd_mesh_create_d(NULL, g.verts, g.nv, g.tris, g.nt, &m) == TTD_OK);
    ttd_scene *s;
    ENSURE(ttd_scene_create_d(&s) == TTD_OK);
    enum { N = 120 };
    double poses[12 * N];
    for (int k = 0; k < N; ++k) {
        const double p[12] = {1, 0, 0, 2.0 * k, 0, 1, 0, 0, 0, 0, 1, 0};
        memcpy(poses + 12 * k, p, sizeof p);
        uint32_t id;
        ENSURE(ttd_scene_add_d(s, m, p, &id) == TTD_OK);
    }
    poses[12 * 97 + 3] = 2.0 * 60 + 0.5;
    poses[12 * 119 + 3] = 2.0 * 118 + 0.25;
    ttd_scene_contact_d near[N];
    for (int round = 0; round < 3; ++round) {
        if (round == 1)
            poses[12 * 1 + 3] = 0.75;
        if (round == 2) /* apart again: 97 0.5 from 96, 1 and 119 back */
            poses[12 * 97 + 3] = 2.0 * 97 - 0.5, poses[12 * 1 + 3] = 2, poses[12 * 119 + 3] = 2.0 * 119;
        ENSURE(ttd_scene_set_poses_d(s, N, poses) == TTD_OK);
        for (int threads = 1; threads <= 2; ++threads) {
            ttd_options o = ttd_default_options();
            o.threads = threads;
            ttd_scene_contact_d alone, general;
            ENSURE(ttd_scene_distance_d(&o, s, INFINITY, &alone, NULL) == TTD_OK);
            ENSURE(ttd_scene_distance_d(&o, s, INFINITY, &general, near) == TTD_OK);
            const uint32_t wi = round == 0 ? 60 : round == 1 ? 0 : 96, wj = round == 0 ? 97 : round == 1 ? 1 : 97;
            ENSURE_MSG(alone.i == wi && alone.j == wj && alone.distance == (round == 2 ? 0.5 : 0),
                       "round %d: closest (%u, %u) at %g, want (%u, %u)", round, alone.i, alone.j, alone.distance, wi,
                       wj);
            ENSURE_MSG(memcmp(&alone, &general, sizeof alone) == 0,
                       "round %d: the closest pair alone differs from the general path's", round);
        }
    }
    ttd_scene_destroy(s);
    ttd_mesh_destroy(m);
    ttd_gen_mesh_free(&g);
    return 0;
}

/* Collide across the steps of a motion (the scene keeps its sweep's order between them, and a
 * bound kept between steps was tried there: docs/scene-speed.md). Six pairs, a sphere and an
 * ellipsoid (semi-axes 0.29, 0.12, 0.12) beside it diagonally (candidates: their boxes overlap,
 * 0.054 apart at first), the ellipsoid moving in small steps (at a different speed in each pair),
 * then turning about its own centre by 0.1 a step, so that the turn alone brings its tip within
 * the margin, with a jump back at step 12; at every step
 * the answer (pairs and witnesses) must equal a fresh scene's at the same poses, on 1 and 2
 * threads, in double and float. (With the kept bounds, it caught bounds that ignored the motion,
 * or the turn.) */
static int collide_across_steps(void)
{
    ttd_gen_mesh g;
    ENSURE(ttd_gen_icosphere(2, &g) == 0);
    ENSURE(ttd_gen_normalize(&g) == 0); /* diagonal 1: radius about 0.5 */
    ttd_mesh *md[2], *mf[2];
    float *vf = malloc(3 * g.nv * sizeof *vf);
    ENSURE(vf != NULL);
    for (int e = 0; e < 2; ++e) { /* the sphere, then the ellipsoid */
        for (size_t k = 0; e == 1 && k < g.nv; ++k)
            g.verts[3 * k + 1] *= 0.4, g.verts[3 * k + 2] *= 0.4;
        ENSURE(ttd_mesh_create_d(NULL, g.verts, g.nv, g.tris, g.nt, &md[e]) == TTD_OK);
        for (size_t k = 0; k < 3 * g.nv; ++k)
            vf[k] = (float)g.verts[k];
        ENSURE(ttd_mesh_create_f(NULL, vf, g.nv, g.tris, g.nt, &mf[e]) == TTD_OK);
    }
    enum { PAIRS = 6, N = 2 * PAIRS, STEPS = 24 };
    const double S0 = 0.38; /* the icosphere normalised: radius 0.289; 0.056 apart at first */
    const double margin = 0.01;
    for (int bytes = 8; bytes >= 4; bytes -= 4) {
        for (int threads = 1; threads <= 2; ++threads) {
            ttd_scene *kept;
            ENSURE((bytes == 8 ? ttd_scene_create_d(&kept) : ttd_scene_create_f(&kept)) == TTD_OK);
            ttd_options o = ttd_default_options();
            o.threads = threads;
            for (int step = 0; step < STEPS; ++step) {
                double poses[12 * N];
                const int t = step < 12 ? step : step - 12; /* the jump back */
                for (int p = 0; p < PAIRS; ++p) {
                    const double a[12] = {1, 0, 0, 3.0 * p, 0, 1, 0, 0, 0, 0, 1, 0};
                    /* steps of a simulation first (bounds reused), then turns of 0.1 about its centre
                     * that swing its tip within the margin (a bound that ignored them would not see it) */
                    const double at = S0 - 0.0002 * (p + 1) * (t < 7 ? t : 7), th = t < 7 ? 0.001 * t : 0.1 * (t - 7);
                    const double c = cos(th), sn = sin(th);
                    const double b[12] = {c, -sn, 0, 3.0 * p + at, sn, c, 0, at, 0, 0, 1, 0};
                    memcpy(poses + 24 * p, a, sizeof a);
                    memcpy(poses + 24 * p + 12, b, sizeof b);
                }
                float pf[12 * N];
                for (int k = 0; k < 12 * N; ++k)
                    pf[k] = (float)poses[k];
                ttd_scene *fresh;
                ENSURE((bytes == 8 ? ttd_scene_create_d(&fresh) : ttd_scene_create_f(&fresh)) == TTD_OK);
                for (int k = 0; k < N; ++k) {
                    uint32_t id;
                    ENSURE((bytes == 8 ? ttd_scene_add_d(fresh, md[k % 2], poses + 12 * k, &id)
                                       : ttd_scene_add_f(fresh, mf[k % 2], pf + 12 * k, &id)) == TTD_OK);
                    if (step == 0)
                        ENSURE((bytes == 8 ? ttd_scene_add_d(kept, md[k % 2], poses + 12 * k, &id)
                                           : ttd_scene_add_f(kept, mf[k % 2], pf + 12 * k, &id)) == TTD_OK);
                }
                ENSURE((bytes == 8 ? ttd_scene_set_poses_d(kept, N, poses) : ttd_scene_set_poses_f(kept, N, pf)) ==
                       TTD_OK);
                ttd_scene_array x = {0}, y = {0};
                ENSURE((bytes == 8 ? ttd_scene_collide_d(&o, kept, margin, &x)
                                   : ttd_scene_collide_f(&o, kept, (float)margin, &x)) == TTD_OK);
                ENSURE((bytes == 8 ? ttd_scene_collide_d(&o, fresh, margin, &y)
                                   : ttd_scene_collide_f(&o, fresh, (float)margin, &y)) == TTD_OK);
                ENSURE_MSG(x.count == y.count && (x.count == 0 || memcmp(x.data, y.data, x.count * sizeof(ttd_scene_hit)) == 0),
                           "%s, %d threads, step %d: %zu pairs after earlier steps, %zu in a fresh scene",
                           bytes == 8 ? "double" : "float", threads, step, x.count, y.count);
                if (step == 10 || step == 22)
                    ENSURE_MSG(x.count == PAIRS, "step %d: %zu pairs within the margin, want all %d", step, x.count,
                               PAIRS);
                if (step == 9 || step == 21)
                    ENSURE_MSG(x.count == 0, "step %d: %zu pairs within the margin, want none yet", step, x.count);
                ttd_scene_array_free(&x);
                ttd_scene_array_free(&y);
                ttd_scene_destroy(fresh);
            }
            ttd_scene_destroy(kept);
        }
    }
    free(vf);
    for (int e = 0; e < 2; ++e) {
        ttd_mesh_destroy(md[e]);
        ttd_mesh_destroy(mf[e]);
    }
    ttd_gen_mesh_free(&g);
    return 0;
}

/* One query of a scene's contacts (K < 0) or manifold (at most K points, 0 all) into *out, and
 * its element size; 0 on failure. */
static size_t ask_one(ttd_scene *s, int bytes, int threads, double margin, int K, ttd_scene_array *out)
{
    ttd_options o = ttd_default_options();
    o.threads = threads;
    ttd_status st;
    if (K < 0)
        st = bytes == 8 ? ttd_scene_contacts_d(&o, s, margin, out) : ttd_scene_contacts_f(&o, s, (float)margin, out);
    else
        st = bytes == 8 ? ttd_scene_manifold_d(&o, s, margin, (size_t)K, out)
                        : ttd_scene_manifold_f(&o, s, (float)margin, (size_t)K, out);
    if (st != TTD_OK)
        return 0;
    return K < 0 ? (bytes == 8 ? sizeof(ttd_scene_contact_d) : sizeof(ttd_scene_contact_f))
                 : (bytes == 8 ? sizeof(ttd_scene_point_d) : sizeof(ttd_scene_point_f));
}

/* A scene keeps its workers' contact blocks, contact sets, sort and manifold scratch between
 * queries (docs/scenes.md section 9), and frees them after a run of queries that need far less:
 * a scene asked in turn large and small queries (margins 0.3 and 0), contacts and manifolds,
 * on 1, 2 and 3 threads, some solid bodies (their manifold sorts its contacts), bodies moved
 * between queries, gives at each query the bytes a fresh scene in that state gives. */
static int scratch_across_queries(void)
{
    static const struct {
        double margin;
        int threads, K; /* K < 0: contacts */
    } step[] = {
        {0.3, 2, -1},    {0.3, 3, 4},     {0.0, 1, -1}, {0.3, 1, 0},     {0.0, 3, 4},  {0.0, 2, -1},
        {0.0, 1, 0},   {0.0, 3, -1},  {0.0, 2, 2},  {0.0, 1, -1},  {0.0, 3, 4},  {0.0, 2, 0},
        {0.0, 1, -1},  {0.0, 2, 4},   {0.3, 3, 0},    {0.3, 1, -1},    {0.0, 2, 4},  {0.3, 2, 4},
    };
    const size_t nstep = sizeof step / sizeof step[0];
    for (int bytes = 8; bytes >= 4; bytes -= 4) {
        world W;
        ENSURE(make_world(&W, bytes, 24, 1.25, 1) == 0);
        for (uint32_t id = 0; id < W.nbody; id += 5)
            if (W.mesh_of[id] <= 1) /* the icospheres and cubes: closed */
                ENSURE(ttd_scene_set_solid(W.scene, id, 1) == TTD_OK);
        size_t most = 0, least = SIZE_MAX;
        for (size_t k = 0; k < nstep; ++k) {
            if (k % 4 == 3) { /* every body moved a little */
                for (size_t id = 0; id < W.nbody; ++id)
                    for (int r = 0; r < 3; ++r)
                        W.pose[id][4 * r + 3] =
                            round_to(bytes, W.pose[id][4 * r + 3] + 0.002 * (double)((id * 7 + k + (size_t)r) % 5) - 0.004);
                ENSURE(set_all_poses(&W) == 0);
            }
            ttd_scene *fresh;
            ENSURE((bytes == 8 ? ttd_scene_create_d(&fresh) : ttd_scene_create_f(&fresh)) == TTD_OK);
            for (size_t id = 0; id < W.nbody; ++id) {
                float pf[12];
                for (int r = 0; r < 12; ++r)
                    pf[r] = (float)W.pose[id][r];
                uint32_t got;
                ENSURE((bytes == 8 ? ttd_scene_add_d(fresh, W.mesh[W.mesh_of[id]], W.pose[id], &got)
                                   : ttd_scene_add_f(fresh, W.mesh[W.mesh_of[id]], pf, &got)) == TTD_OK);
                if (id % 5 == 0 && W.mesh_of[id] <= 1)
                    ENSURE(ttd_scene_set_solid(fresh, got, 1) == TTD_OK);
            }
            ttd_scene_array x = {0}, y = {0};
            const size_t size = ask_one(W.scene, bytes, step[k].threads, step[k].margin, step[k].K, &x);
            ENSURE(size > 0 && ask_one(fresh, bytes, step[k].threads, step[k].margin, step[k].K, &y) == size);
            ENSURE_MSG(x.count == y.count && (x.count == 0 || memcmp(x.data, y.data, x.count * size) == 0),
                       "%s, query %zu (%s, K %d, margin %g, %d threads): %zu items after earlier queries, %zu from "
                       "a fresh scene",
                       bytes == 8 ? "double" : "float", k, step[k].K < 0 ? "contacts" : "manifold", step[k].K,
                       step[k].margin, step[k].threads, x.count, y.count);
            if (step[k].K < 0) {
                most = x.count > most ? x.count : most;
                least = x.count < least ? x.count : least;
            }
            ttd_scene_array_free(&x);
            ttd_scene_array_free(&y);
            ttd_scene_destroy(fresh);
        }
        /* the large queries far larger than the small ones (the scratch's bound frees it) */
        ENSURE_MSG(least > 0 && most > 8 * least, "contacts from %zu to %zu: want small ones under an eighth", least,
                   most);
        free_world(&W);
    }
    return 0;
}

/* The scratch's bound (docs/scenes.md section 9): after a large query, the scene keeps its
 * contact blocks through SCRATCH_THIN_QUERIES - 1 queries that fill under a quarter of them, and
 * frees them at the SCRATCH_THIN_QUERIES-th; a query that fills more starts the count again; a
 * query after the free gives the bytes it gave before. Two icospheres 0.05 apart (1,280
 * triangles each): 22,450 contacts within 0.2, 210 within 0.06, on one thread, contacts and
 * manifolds. */
static int scratch_thin_bound(void)
{
    ttd_gen_mesh g;
    ENSURE(ttd_gen_icosphere(3, &g) == 0 && ttd_gen_normalize(&g) == 0);
    double lo[3], hi[3];
    ENSURE(ttd_gen_mesh_bounds(&g, lo, hi) == 0);
    const double gap = hi[2] - lo[2] + 0.05;
    for (int bytes = 8; bytes >= 4; bytes -= 4) {
        ttd_mesh *m = test_mesh_of(bytes, g.verts, g.nv, g.tris, g.nt);
        ttd_scene *s;
        ENSURE(m != NULL);
        ENSURE((bytes == 8 ? ttd_scene_create_d(&s) : ttd_scene_create_f(&s)) == TTD_OK);
        for (int b = 0; b < 2; ++b) {
            const double pose[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, b * gap};
            float pf[12];
            for (int r = 0; r < 12; ++r)
                pf[r] = (float)pose[r];
            uint32_t id;
            ENSURE((bytes == 8 ? ttd_scene_add_d(s, m, pose, &id) : ttd_scene_add_f(s, m, pf, &id)) == TTD_OK);
        }
        const size_t csize = bytes == 8 ? sizeof(ttd_scene_contact_d) : sizeof(ttd_scene_contact_f);
        ttd_scene_array x = {0}, first = {0};
        ENSURE(ask_one(s, bytes, 1, 0.06, -1, &first) > 0 && first.count > 0);
        ENSURE(ttd_scene_scratch_held(s) > 0);
        for (int round = 0; round < 3; ++round) {
            ENSURE(ask_one(s, bytes, 1, 0.2, round == 1 ? 4 : -1, &x) > 0);
            const size_t held = ttd_scene_scratch_held(s);
            /* the test's premise: the large query's blocks are past the small ones' exemption,
             * and the small queries fill under a quarter of them */
            ENSURE_MSG(held > SCRATCH_SMALL * csize && 4 * first.count * csize < held,
                       "%zu bytes held after the large query, %zu contacts in a small one", held, first.count);
            /* rounds 0 and 1: one small query fewer than the bound, then the count starts again */
            const int small = round < 2 ? SCRATCH_THIN_QUERIES - 1 : SCRATCH_THIN_QUERIES;
            for (int k = 1; k <= small; ++k) {
                ENSURE(ask_one(s, bytes, 1, 0.06, k % 2 ? -1 : 4, &x) > 0);
                const size_t now = ttd_scene_scratch_held(s);
                if (k < SCRATCH_THIN_QUERIES)
                    ENSURE_MSG(now == held, "%s, round %d: %zu bytes held after %d small queries, %zu before",
                               bytes == 8 ? "double" : "float", round, now, k, held);
                else
                    ENSURE_MSG(now == 0, "%s: %zu bytes held after %d small queries (of %zu), want them freed",
                               bytes == 8 ? "double" : "float", now, k, held);
            }
        }
        /* made again, to the small query's size, and the same bytes */
        ENSURE(ask_one(s, bytes, 1, 0.06, -1, &x) > 0 && x.count == first.count);
        ENSURE(memcmp(x.data, first.data, x.count * csize) == 0);
        ENSURE(ttd_scene_scratch_held(s) > 0 && ttd_scene_scratch_held(s) <= SCRATCH_SMALL * csize);
        ttd_scene_array_free(&x);
        ttd_scene_array_free(&first);
        ttd_scene_destroy(s);
        ttd_mesh_destroy(m);
    }
    ttd_gen_mesh_free(&g);
    return 0;
}

/* A scene of one body, and of none: nothing collides, no closest pair. */
static int small_scenes(void)
{
    ttd_gen_mesh g;
    ENSURE(ttd_gen_mesh_cube(&g) == 0);
    ttd_mesh *m;
    ENSURE(ttd_mesh_create_d(NULL, g.verts, g.nv, g.tris, g.nt, &m) == TTD_OK);
    ttd_scene *s;
    ENSURE(ttd_scene_create_d(&s) == TTD_OK);
    ttd_scene_array out = {0};
    ttd_scene_contact_d c, near[2];
    ENSURE(ttd_scene_collide_d(NULL, s, 0, &out) == TTD_OK && out.count == 0);
    ENSURE(ttd_scene_distance_d(NULL, s, INFINITY, &c, near) == TTD_OK && isinf(c.distance) && c.i == UINT32_MAX);
    const double id[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    uint32_t b;
    ENSURE(ttd_scene_add_d(s, m, id, &b) == TTD_OK && b == 0);
    ENSURE(ttd_scene_contacts_d(NULL, s, 1, &out) == TTD_OK && out.count == 0);
    size_t counted = SIZE_MAX;
    ENSURE(ttd_scene_contacts_count_d(NULL, s, 1, &counted) == TTD_OK && counted == 0);
    ENSURE(ttd_scene_distance_d(NULL, s, INFINITY, &c, near) == TTD_OK && isinf(c.distance));
    ENSURE(near[0].i == 0 && near[0].j == UINT32_MAX && isinf(near[0].distance));
    ENSURE(ttd_scene_body_count(s) == 1 && ttd_scene_id_limit(s) == 1);
    ttd_scene_array_free(&out);
    ttd_scene_destroy(s);
    ttd_mesh_destroy(m);
    ttd_gen_mesh_free(&g);
    return 0;
}

static int bad_input(void)
{
    ttd_gen_mesh g;
    ENSURE(ttd_gen_mesh_cube(&g) == 0);
    ttd_mesh *m, *mf;
    ENSURE(ttd_mesh_create_d(NULL, g.verts, g.nv, g.tris, g.nt, &m) == TTD_OK);
    float v[3 * 8];
    for (size_t i = 0; i < 3 * g.nv && i < 24; ++i)
        v[i] = (float)g.verts[i];
    ENSURE(ttd_mesh_create_f(NULL, v, g.nv, g.tris, g.nt, &mf) == TTD_OK);
    ttd_scene *s;
    ENSURE(ttd_scene_create_d(NULL) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_scene_create_d(&s) == TTD_OK);
    const double id[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    const double skew[12] = {1, 0.01, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    const double mirror[12] = {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    const double nan_t[12] = {1, 0, 0, NAN, 0, 1, 0, 0, 0, 0, 1, 0};
    const double far_t[12] = {1, 0, 0, 1e300, 0, 1, 0, 0, 0, 0, 1, 0};
    uint32_t b;
    ENSURE(ttd_scene_add_d(s, NULL, id, &b) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_scene_add_d(s, m, NULL, &b) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_scene_add_d(s, m, skew, &b) == TTD_ERR_BAD_POSE);
    ENSURE(ttd_scene_add_d(s, m, mirror, &b) == TTD_ERR_BAD_POSE);
    ENSURE(ttd_scene_add_d(s, m, nan_t, &b) == TTD_ERR_BAD_POSE);
    ENSURE(ttd_scene_add_d(s, m, far_t, &b) == TTD_ERR_COORDINATE_RANGE);
    ENSURE(ttd_scene_add_d(s, mf, id, &b) == TTD_ERR_PRECISION_MISMATCH);
    const float idf[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    ENSURE(ttd_scene_add_f(s, mf, idf, &b) == TTD_ERR_PRECISION_MISMATCH);
    /* solids: a closed mesh only, a present body only; a refused call leaves the body as it was */
    {
        ttd_gen_mesh tri;
        ENSURE(ttd_gen_mesh_triangle(&tri) == 0);
        ttd_mesh *open_m;
        ENSURE(ttd_mesh_create_d(NULL, tri.verts, tri.nv, tri.tris, tri.nt, &open_m) == TTD_OK);
        uint32_t bc, bo;
        ttd_scene *ss;
        ENSURE(ttd_scene_create_d(&ss) == TTD_OK);
        ENSURE(ttd_scene_add_d(ss, m, id, &bc) == TTD_OK && ttd_scene_add_d(ss, open_m, id, &bo) == TTD_OK);
        ENSURE(ttd_scene_set_solid(NULL, bc, 1) == TTD_ERR_NULL_POINTER);
        ENSURE(ttd_scene_set_solid(ss, bo + 1, 1) == TTD_ERR_INDEX_OUT_OF_RANGE);
        ENSURE(ttd_scene_set_solid(ss, bo, 1) == TTD_ERR_MESH_NOT_CLOSED);
        ENSURE(ttd_scene_set_solid(ss, bo, 0) == TTD_OK); /* a surface may always be a surface */
        ENSURE(ttd_scene_set_solid(ss, bc, 1) == TTD_OK && ttd_scene_set_solid(ss, bc, 0) == TTD_OK);
        ENSURE(ttd_scene_remove(ss, bo) == TTD_OK && ttd_scene_remove(ss, bc) == TTD_OK);
        ENSURE(ttd_scene_set_solid(ss, bc, 1) == TTD_ERR_INDEX_OUT_OF_RANGE);
        ttd_scene_destroy(ss);
        ttd_mesh_destroy(open_m);
        ttd_gen_mesh_free(&tri);
    }
    ENSURE(ttd_scene_body_count(s) == 0 && ttd_scene_id_limit(s) == 0); /* nothing was added */
    ENSURE(ttd_scene_add_d(s, m, id, &b) == TTD_OK && b == 0);
    ENSURE(ttd_scene_add_d(s, m, id, &b) == TTD_OK && b == 1);
    ENSURE(ttd_scene_set_pose_d(s, 2, id) == TTD_ERR_INDEX_OUT_OF_RANGE);
    ENSURE(ttd_scene_set_pose_d(s, 1, skew) == TTD_ERR_BAD_POSE);
    double two[24];
    memcpy(two, id, sizeof id);
    memcpy(two + 12, skew, sizeof skew);
    ENSURE(ttd_scene_set_poses_d(s, 1, two) == TTD_ERR_INDEX_OUT_OF_RANGE);
    ENSURE(ttd_scene_set_poses_d(s, 2, two) == TTD_ERR_BAD_POSE);
    ENSURE(ttd_scene_exclude_pair(s, 0, 0, 1) == TTD_ERR_INDEX_OUT_OF_RANGE);
    ENSURE(ttd_scene_exclude_pair(s, 0, 5, 1) == TTD_ERR_INDEX_OUT_OF_RANGE);
    ENSURE(ttd_scene_set_filter(s, 9, 1, 1) == TTD_ERR_INDEX_OUT_OF_RANGE);
    ttd_scene_array out = {0};
    ttd_scene_contact_d c;
    ENSURE(ttd_scene_collide_d(NULL, s, -1, &out) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_scene_collide_d(NULL, s, NAN, &out) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_scene_contacts_d(NULL, s, INFINITY, &out) == TTD_ERR_BAD_OPTIONS);
    size_t counted;
    ENSURE(ttd_scene_contacts_count_d(NULL, s, INFINITY, &counted) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_scene_contacts_count_d(NULL, s, -1, &counted) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_scene_contacts_count_d(NULL, s, 0, NULL) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_scene_contacts_count_f(NULL, s, 0, &counted) == TTD_ERR_PRECISION_MISMATCH);
    ENSURE(ttd_scene_contacts_count_d(NULL, NULL, 0, &counted) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_scene_distance_d(NULL, s, -1, &c, NULL) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_scene_collide_f(NULL, s, 0, &out) == TTD_ERR_PRECISION_MISMATCH);
    ENSURE(ttd_scene_collide_d(NULL, NULL, 0, &out) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_scene_manifold_d(NULL, s, 0, 4, NULL) == TTD_ERR_NULL_POINTER);
    ttd_options bad = ttd_default_options();
    bad.method = TTD_METHOD_PENALTY;
    ENSURE(ttd_scene_collide_d(&bad, s, 0, &out) == TTD_ERR_BAD_OPTIONS);
    /* the two identical cubes touch: one pair, distance 0 */
    ttd_scene_stats stats;
    ENSURE(ttd_scene_get_stats(NULL, &stats) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_scene_get_stats(s, NULL) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_scene_collide_d(NULL, s, 0, &out) == TTD_OK && out.count == 1);
    ENSURE(ttd_scene_contacts_d(NULL, s, 0, &out) == TTD_OK && out.count > 0);
    ENSURE(ttd_scene_contacts_count_d(NULL, s, 0, &counted) == TTD_OK && counted == out.count);
    ENSURE(ttd_scene_collide_d(NULL, s, 0, &out) == TTD_OK && out.count == 1);
    ENSURE(ttd_scene_get_stats(s, &stats) == TTD_OK && stats.body_pairs == 1 && stats.results == 1 &&
           stats.pair_tests >= 1);
    /* a query refused at its checks leaves the stats at 0, not the last query's (ttd.h) */
    ENSURE(ttd_scene_collide_d(NULL, s, -1, &out) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_scene_get_stats(s, &stats) == TTD_OK && stats.body_pairs == 0 && stats.node_tests == 0 &&
           stats.pair_tests == 0 && stats.results == 0);
    ENSURE(ttd_scene_collide_d(NULL, s, 0, &out) == TTD_OK && out.count == 1);
    ENSURE(ttd_scene_contacts_f(NULL, s, 0, &out) == TTD_ERR_PRECISION_MISMATCH);
    ENSURE(ttd_scene_get_stats(s, &stats) == TTD_OK && stats.body_pairs == 0 && stats.results == 0);
    ENSURE(ttd_scene_distance_d(NULL, s, INFINITY, &c, NULL) == TTD_OK && c.distance == 0 && c.i == 0 && c.j == 1);
    ttd_scene_array_free(&out);
    ttd_scene_destroy(s);
    ttd_mesh_destroy(m);
    ttd_mesh_destroy(mf);
    ttd_gen_mesh_free(&g);
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(scenes_match_brute_force);
    RUN_TEST(stacked_cubes_match_brute_force);
    RUN_TEST(resting_cube_on_fine_floor);
    RUN_TEST(sparse_scene_distances);
    RUN_TEST(scaled_scenes);
    RUN_TEST(resting_cube_normals);
    RUN_TEST(small_scenes);
    RUN_TEST(closest_pair_order);
    RUN_TEST(collide_across_steps);
    RUN_TEST(scratch_across_queries);
    RUN_TEST(scratch_thin_bound);
    RUN_TEST(bad_input);
    TEST_MAIN_END();
}
