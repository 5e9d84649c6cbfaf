/* SPDX-License-Identifier: MIT */
/* A body pair's contacts reduced to a manifold (docs/scenes.md, section 5), precision-generic:
 * included by scene/query_impl.h. A function of the pair's contacts and the scene alone, so that
 * it may run wherever the pair's contacts are found.
 *
 * 0. The corners of flat contact: a contact's point is its triangle pair's closest point, and
 *    where a face lies on a face the pair's points within the margin are a whole region, of which
 *    the closest point is one. So each contact whose triangles lie face on face (CORNER_ANGLE)
 *    adds the other points of its region's rim that are points of the bodies: the vertices within
 *    the margin of the other triangle (each vertex once, at its smallest distance) and the
 *    crossings of edges within the margin (two edges, one of each body, whose closest points lie
 *    inside both), as clipping does in GImpact. Vertices inside a flat part and edges between
 *    coplanar triangles (mesh/edges.h) are never corners and are left out; a question asked by
 *    several contacts is asked once, for the smallest triangles. Each point carries the exact
 *    distance between its two points (the exact method on the vertex or the edges as degenerate
 *    triangles), so it is a real point of contact within the margin.
 * 1. Depth order: smaller distance first, ties by triangles, then by point.
 * 2. No point twice: in that order, a point is dropped when it lies within the merge
 *    tolerance (MERGE_FRACTION of the smaller body's radius) of a point kept before it; a grid
 *    of cells that wide finds the points near it. So no two points kept are that close, and
 *    each kept one is the deepest of those it stands for.
 * 3. The seed: the deepest, and among contacts within FEATURE_TOL of the larger radius of its
 *    depth (faces resting on faces: many at one depth), the one farthest from their centroid.
 * 4. Spread (when more than K remain), first over the contacts of the deepest level (within
 *    LEVEL_FRACTION of the rest of the margin, M - d, of the deepest distance d: where a body
 *    rests, rather than a speculative contact farther inside the margin; and on the resting
 *    plane, LEVEL_SLOPE, not a point across an edge beside a deeper one): the seed; the point
 *    farthest from it; the point making the largest triangle with those two; then, one at a
 *    time, the point that adds the most area to the polygon of those kept (on the plane of the
 *    first three), as PhysX's reduction keeps a box's four corners on a face; where no point
 *    adds area (points on a line, or inside), the point farthest from every point kept. Ties to
 *    the earlier in depth order. Of the level, the touching points come first (within
 *    TOUCH_FRACTION of the margin left above the deepest: where a body resting on two parts of
 *    the other is held): the spread is over them when they are K or more; when fewer, all of
 *    them, then the level's farthest from every point kept. When the level holds fewer than K,
 *    all of them, then the farthest from every point kept among the rest.
 * Distances between points are formed on coordinates relative to the deepest point, scaled by a
 * power of two to the larger body's size, so that no square underflows or overflows at any scale
 * of the coordinate range.
 * Cost (docs/scene-speed.md section 5): with K > 0, steps 0-4 run first on the deepest level's
 * points alone, which decide the answer wherever more than K of them are kept and K lie on the
 * level; step 0's questions are screened before the exact method where it surely finds no
 * corner. Neither changes a bit of the answer. */

#include "scene/body_impl.h"
#include "scene/normal_impl.h"

#define MERGE_FRACTION 1e-3
/* The deepest level of step 4: a quarter of the margin left below the deepest contact (a box
 * resting 0.01 inside a margin of 0.04 spreads its points over contacts within 0.0175, not over
 * the torus-side contacts at 0.03 that a simulator found rocking the body). */
#define LEVEL_FRACTION 0.25
/* The level's plane: a point of it rises above a deeper one by at most this times the distance
 * between them (the flat angle of step 0, CORNER_ANGLE, as a slope). */
#define LEVEL_SLOPE 0.1
/* The touching points of step 4's level: within this fraction of the margin left below the
 * deepest contact (M = 0.04 and a rest gap of 0.01: 4.7e-4; a resting body's supports agree to
 * far less, and a point a millimetre above them holds nothing) */
#define TOUCH_FRACTION (1.0 / 64)
/* The touching points' pass before the level's (reduce_pair); 0 only in a test's build
 * (tests/CMakeLists.txt, ttd_manifold_no_touch), whose answers must be the same bits. */
#ifndef MANIFOLD_TOUCH_PASS
#define MANIFOLD_TOUCH_PASS 1
#endif
/* A pair of at most this many contacts is reduced whole at once (K > 0), without the passes over
 * its deepest points first: on the pile such pairs failed the touching pass 412 times in 417 and
 * paid both (docs/scene-speed.md, section 17); the answer is the same either way. */
#ifndef MANIFOLD_PASS_SMALL
#define MANIFOLD_PASS_SMALL 64
#endif
#define HULL_MAX 64 /* the polygon of step 4 follows up to this many points; farthest points beyond */

/* Scratch kept across body pairs. */
typedef struct manifold_work {
    double *z;           /* 3 n: points, relative and scaled */
    size_t *kept;        /* kept contacts, in depth order */
    size_t *next;        /* grid: the next kept point in the same cell */
    size_t *cell_head;   /* grid: open addressing, one kept point per cell (or SIZE_MAX) */
    uint64_t *cell_key;
    size_t *sel;         /* the points chosen */
    size_t *ord;         /* step 4: the level's points by their first coordinate */
    unsigned char *taken;
    size_t cap, cell_cap;
    struct manifold_rec *all; /* the pair's points: its contacts, the corners they add (step 0),
                               * the points of solids inside each other (5b) */
    size_t all_n, all_cap;
    int solid;               /* the pair is a solid pair */
    unsigned char *inner[2]; /* solid pairs: the places of body i's (0) and j's (1) vertices found
                              * inside the other body (2), or outside (1), or not asked (0) */
    size_t inner_cap[2];
    uint32_t *queue;         /* 5b: places to ask, then those inside */
    real *pts;               /* 5b: the inside vertices in the other body's frame */
    uint32_t *pts_place;
    ttd_point_result *res;   /* 5b: their closest points */
    size_t queue_cap, pts_cap;
    double sat_n[3];         /* 5b: a convex solid pair's separating direction (inside = 2) */
    struct corner_key *key; /* step 0's vertices and edges to ask, before each is asked once */
    size_t key_n, key_cap;
    struct corner_key *key_tmp; /* step 0: scratch of the keys' sort */
    size_t key_tmp_cap;
    struct depth_key *keys;  /* step 1: the points' sort keys, and room to merge them */
    size_t keys_cap;
    uint32_t *radix_count;   /* step 1: the radix sort's counts, 16 digits of 256 */
    struct manifold_rec *near; /* the points of the deepest level (reduce_pair) */
    size_t near_cap;
    size_t *pick; /* reduce_pair: the contacts within a pass's reach, before they are copied */
    size_t pick_cap;
    struct corner_tri *ctri; /* step 0: each side's world triangles and planes, by triangle */
    uint64_t stamp;          /* step 0: the number of the pass those are of (work_stamp; tags) */
    unsigned char *face;      /* step 0: per contact, FACE_ON_FACE and FACE_FLAT bits */
    struct flat_normal *fnorm; /* step 0 (pair_flat): body j's triangles' normals in body i's frame,
                                * stamped with stamp's low 32 bits */
    size_t face_cap;
    struct corner_seen *seen; /* step 0: each vertex question met in this pair, screened once */
    size_t seen_n, seen_cap;
    /* step 0: the answers of the pair's last pass that asked (pair_corners), in the keys' order,
     * and this pass's; a later pass of the pair asks most of them again (reduce_pair) */
    struct corner_memo *memo, *memo_next;
    size_t memo_n, memo_cap, memo_next_n, memo_next_cap;
    /* step 0 per pair of planar pieces (piece_corners): the pair's flat contacts asking, by pieces;
     * each side's triangles met in a group (local numbers: by triangle, stamped with the group's
     * number), its rim corners and real edges; which triangle pairs of the group are contacts */
    struct piece_item *pitem;
    size_t pitem_cap;
    size_t *pone; /* the contacts asking one by one */
    size_t pone_cap;
    uint32_t *pstamp[2], *ploc[2];
    size_t pstamp_cap[2];
    uint32_t ptag;
    uint32_t *ptid[2];
    size_t ptid_cap[2];
    struct corner_tri *ptri[2];
    size_t ptri_cap[2];
    struct beside_tri *pbes[2];
    size_t pbes_cap[2];
    struct piece_vslot *pv[2], *pvtmp;
    size_t pv_cap[2], pvtmp_cap;
    struct piece_eslot *pe[2];
    size_t pe_cap[2];
    unsigned char *pmat;
    size_t pmat_cap;
    struct region_item *reg;  /* 5b regions: the pair's points below 0, by their first coordinate */
    uint32_t *reg_par;        /* 5b regions: union-find parents, then each point's deepest */
    double *reg_n;            /* 5b regions: each region's direction, by its number */
    size_t reg_cap;
} manifold_work;

/* Step 0's per-contact bits (manifold_work.face): the triangles lie face on face (the contact
 * asks for its corners); and the contact is of flat contact (face on face, both flat pieces
 * planar, in a pair whose flat contacts are all at a distance above 0): its region stands for
 * it by the corners, and it does not enter the reduction as a point (docs/scenes.md, section 5). */
enum { FACE_ON_FACE = 1, FACE_FLAT = 2 };

/* A point of a pair: a contact (the triangle pair's closest points), a corner, or a point of a
 * solid inside the other (inside 0: p, a vertex of body i inside body j; 1: q, a vertex of body j
 * inside body i; 2: a convex pair's point at its penetration depth, its normal w->sat_n; -1 for
 * the others), whose distance is then negative. */
typedef struct manifold_rec {
    ttd_scene_contact c;
    int inside;
    /* the features of tri_i (feat[0]) and tri_j (feat[1]) the points lie on, as the exact method's
     * feature bits (a vertex: one bit; an edge: two; the face: three), or 0 where not yet known
     * (a contact: its triangle pair asked again for the points chosen, section 5c) */
    uint8_t feat[2];
    /* 5b: the number of the contact region the point's direction is taken from (w->reg_n), or
     * UINT32_MAX: its own normal (section 5a) */
    uint32_t region;
} manifold_rec;

/* A vertex or a pair of edges step 0 asks about. A vertex: side 0 a vertex of body i (corner k of
 * its triangle ti), 1 of body j (corner k of tj), against the other body's triangle; its place
 * (mesh/edges.h) in a and the other triangle in b. Edges: edge k of ti and edge l of tj, their
 * ends' places (smaller first) in a and b. Equal keys ask the same question: it is asked once,
 * for the smallest triangles. */
typedef struct corner_key {
    uint32_t kind;       /* 0 vertex of i, 1 vertex of j, 2 edges */
    uint64_t a, b;
    uint32_t ti, tj;
    int k, l;
} corner_key;

static void manifold_work_free(manifold_work *w)
{
    free(w->z);
    free(w->kept);
    free(w->next);
    free(w->cell_head);
    free(w->cell_key);
    free(w->sel);
    free(w->ord);
    free(w->taken);
    free(w->all);
    free(w->inner[0]);
    free(w->inner[1]);
    free(w->queue);
    free(w->keys);
    free(w->radix_count);
    free(w->pts);
    free(w->pts_place);
    free(w->res);
    free(w->key);
    free(w->key_tmp);
    free(w->face);
    free(w->fnorm);
    free(w->near);
    free(w->pick);
    free(w->ctri);
    free(w->seen);
    free(w->memo);
    free(w->memo_next);
    free(w->pitem);
    free(w->pone);
    free(w->pmat);
    free(w->pvtmp);
    for (int side = 0; side < 2; ++side) {
        free(w->pstamp[side]);
        free(w->ploc[side]);
        free(w->ptid[side]);
        free(w->ptri[side]);
        free(w->pbes[side]);
        free(w->pv[side]);
        free(w->pe[side]);
    }
    free(w->reg);
    free(w->reg_par);
    free(w->reg_n);
    memset(w, 0, sizeof *w);
}

static int manifold_work_reserve(manifold_work *w, size_t n)
{
    if (n > w->cap) {
        size_t cap = w->cap ? w->cap : 64;
        while (cap < n)
            cap *= 2;
        double *z = realloc(w->z, 3 * cap * sizeof *z);
        if (z == NULL)
            return 0;
        w->z = z;
        size_t *k = realloc(w->kept, cap * sizeof *k);
        if (k == NULL)
            return 0;
        w->kept = k;
        size_t *nx = realloc(w->next, cap * sizeof *nx);
        if (nx == NULL)
            return 0;
        w->next = nx;
        size_t *sel = realloc(w->sel, cap * sizeof *sel);
        if (sel == NULL)
            return 0;
        w->sel = sel;
        size_t *ord = realloc(w->ord, cap * sizeof *ord);
        if (ord == NULL)
            return 0;
        w->ord = ord;
        unsigned char *tk = realloc(w->taken, cap);
        if (tk == NULL)
            return 0;
        w->taken = tk;
        w->cap = cap;
    }
    size_t cells = 64;
    while (cells < 2 * n)
        cells *= 2;
    if (cells > w->cell_cap) {
        size_t *h = realloc(w->cell_head, cells * sizeof *h);
        if (h == NULL)
            return 0;
        w->cell_head = h;
        uint64_t *key = realloc(w->cell_key, cells * sizeof *key);
        if (key == NULL)
            return 0;
        w->cell_key = key;
        w->cell_cap = cells;
    }
    return 1;
}

static int all_push(manifold_work *w, const ttd_scene_contact *c, int inside, unsigned fi, unsigned fj)
{
    if (w->all_n == w->all_cap) {
        manifold_rec *v = array_grow(w->all, &w->all_cap, w->all_n + 1, sizeof *v, 256);
        if (v == NULL)
            return 0;
        w->all = v;
    }
    w->all[w->all_n].c = *c;
    w->all[w->all_n].feat[0] = (uint8_t)fi;
    w->all[w->all_n].feat[1] = (uint8_t)fj;
    w->all[w->all_n].region = UINT32_MAX;
    w->all[w->all_n++].inside = inside;
    return 1;
}

/* The n contacts c into w->all before the points already there, but those of flat contact
 * (drop: the mask w->face, bit FACE_FLAT set: left out, section 5 step 0; NULL: every contact).
 * 0 out of memory. */
static int all_front(manifold_work *w, const ttd_scene_contact *c, size_t n, const unsigned char *drop)
{
    size_t m = n;
    for (size_t k = 0; drop != NULL && k < n; ++k)
        m -= (drop[k] & FACE_FLAT) != 0;
    if (w->all_n + m > w->all_cap) {
        manifold_rec *v = array_grow(w->all, &w->all_cap, w->all_n + m, sizeof *v, 256);
        if (v == NULL)
            return 0;
        w->all = v;
    }
    if (w->all_n > 0 && m > 0)
        memmove(w->all + m, w->all, w->all_n * sizeof *w->all);
    size_t o = 0;
    for (size_t k = 0; k < n; ++k) {
        if (drop != NULL && (drop[k] & FACE_FLAT))
            continue;
        w->all[o].c = c[k];
        w->all[o].inside = -1;
        w->all[o].region = UINT32_MAX;
        w->all[o].feat[0] = w->all[o].feat[1] = 0;
        ++o;
    }
    w->all_n += m;
    return 1;
}

#include "scene/manifold_corners_impl.h"

#include "scene/manifold_inside_impl.h"

#include "scene/manifold_sat_impl.h"

#include "scene/manifold_depth_impl.h"

#include "scene/manifold_regions_impl.h"

#include "scene/manifold_reduce_impl.h"

#include "scene/manifold_keys_impl.h"

/* Body pair p's manifold: its n0 contacts c0, the corners they add (step 0) and, for a solid
 * pair, the points of each body inside the other (5b), reduced to at most max points (0: all)
 * appended to out, in the order chosen. cfg: one thread. w: scratch. 0 out of memory. */
static int reduce_pair(const struct ttd_scene *s, const ttd_engine_config *cfg, const scene_pair *p,
                       const ttd_scene_contact *c0, size_t n0, real margin, size_t max, manifold_work *w,
                       ttd_scene_array *out)
{
    /* step 0's bits: which contacts are face on face, and which are of flat contact (their
     * region's corners stand for them: they are not points); then the points into w->all: the
     * contacts (where max > 0, only when all the points are needed, below), a solid pair's
     * inside points, the corners */
    size_t nflat;
    double dc; /* the contacts' smallest distance */
    w->memo_n = 0; /* step 0's answers are of this pair's triangles */
    if (!pair_flat(s, c0, n0, w, &nflat, &dc))
        return 0;
    const unsigned char *drop = nflat > 0 ? w->face : NULL;
again:
    w->all_n = 0;
    for (size_t k = 0; max == 0 && k < n0; ++k)
        if (!(drop != NULL && (drop[k] & FACE_FLAT)) && !all_push(w, &c0[k], -1, 0, 0))
            return 0;
    w->solid = solid_pair(s, p->i, p->j);
    if (w->solid) {
        real at[3];
        const int nest = n0 == 0 ? solid_nested(s, p->i, p->j, at) : 0;
        if (n0 == 0 && nest == 0)
            return 1;
        const size_t before = w->all_n;
        for (int side = 0; side < 2; ++side) {
            if (n0 == 0 && nest != (side ? 1 : 2)) {
                if (w->inner_cap[side]) /* memset(NULL, 0, 0) is undefined */
                    memset(w->inner[side], 0, w->inner_cap[side]);
                continue;
            }
            if (!solid_side(s, cfg, p->i, p->j, side, c0, n0, n0 == 0, w))
                return 0;
        }
        /* the edges' deepest points where the surfaces cross: with no vertex of either inside the
           other, every piece between two crossings; else the pieces deeper than the deepest
           vertex (vdepth: its depth; -1 when none is inside) */
        double vdepth = -1;
        for (size_t k = before; k < w->all_n; ++k)
            vdepth = fmax(vdepth, -(double)w->all[k].c.distance);
        for (int side = 0; side < 2 && n0 > 0; ++side)
            if (!solid_edges(s, cfg, p->i, p->j, side, c0, n0, vdepth, w))
                return 0;
        /* a convex pair found overlapping: its penetration depth along the separating direction */
        int added;
        if (w->all_n > before && !solid_sat(s, cfg, p->i, p->j, before, w, &added))
            return 0;
        /* other pairs: where the depth peaks inside a face */
        if (!solid_faces(s, cfg, p->i, p->j, before, c0, n0, w))
            return 0;
        /* other pairs' points below 0: one direction per contact region */
        if (!solid_regions(s, p->i, p->j, c0, n0, margin, before, w))
            return 0;
    }
    const double ri = s->body[p->i].mesh->radius, rj = s->body[p->j].mesh->radius;
    const double big = fmax(ri, rj), small = fmin(ri, rj);
    int ex = 0;
    if (big > 0 && isfinite(big))
        frexp(big, &ex);
    /* the points as a point record holds them, relative to the deepest, at the larger body's scale
     * (times 2^-ex: one multiplication, ldexp's bits, where 2^-ex is a normal number; two beyond) */
    const int one = ex >= -1021 && ex <= 1021;
    const double f1 = one ? ldexp(1.0, -ex) : ldexp(1.0, -ex / 2), f2 = one ? 1.0 : ldexp(1.0, -ex - (-ex / 2));
    const double tol = ldexp(MERGE_FRACTION * small, -ex);
    const size_t n_pre = w->all_n; /* the contacts (max = 0) and a solid pair's inside points */
    manifold_rec *rc = NULL;
    size_t nk = 0, ns = 0;
    int corners = 0; /* step 0 done for every contact */
    if (max > 0 && n0 + n_pre > 0) {
        /* the deepest level's points alone first (those within the seed's window or the level
         * of the smallest distance, step 4): the merge keeps a point by the points before it in
         * depth order and step 4 chooses among the level, so where more than max are kept and
         * max are on the level, the points beyond it change nothing; else all of them, as
         * without this. The smallest distance is a contact's or an inside point's: a corner
         * lies no nearer than the contact asking for it. */
        double d0 = dc;
        for (size_t k = 0; k < n_pre; ++k)
            if ((double)w->all[k].c.distance < d0)
                d0 = (double)w->all[k].c.distance;
        const double window = FEATURE_TOL * big, level = LEVEL_FRACTION * ((double)margin - d0);
        const double touch = TOUCH_FRACTION * ((double)margin - d0);
        /* first the touching points alone (within the seed's window or TOUCH_FRACTION): where K
         * or more of them are kept on the level, step 4 spreads over them alone, and the merge,
         * the seed and each one's slope test look only at deeper points, so the level's points
         * above them change nothing (on a curved pile's pair, about a sixteenth of the level's
         * points); else the level's, as below */
        const double reaches[2] = {window > touch ? window : touch, window > level ? window : level};
        const int first = MANIFOLD_TOUCH_PASS && reaches[0] < reaches[1] ? 0 : 1;
        const int few = n0 <= MANIFOLD_PASS_SMALL;
        for (int pass = first; pass < 2 && ns == 0 && !corners && !few; ++pass) {
            const double reach[2] = {d0, reaches[pass]};
            w->all_n = n_pre;
            if (!pair_corners(s, c0, n0, margin, reach, w))
                return 0;
            const size_t n = n0 - (drop != NULL ? nflat : 0) + w->all_n;
            if (!near_reserve(w, n, n0))
                return 0;
            size_t m = 0; /* in the order of w->all were the contacts in it: contacts, inside points, corners */
            size_t far_flat = 0; /* contacts of flat contact beyond the reach (not asked) */
            /* the contacts within the reach found first, without a jump on the distance (it
             * mispredicted: on the pile a pass's reach holds about half of them), then copied */
            size_t np = 0;
            for (size_t k = 0; k < n0; ++k) {
                const int flat = drop != NULL && (drop[k] & FACE_FLAT), in = (double)c0[k].distance - d0 <= reach[1];
                far_flat += (size_t)(flat & (in ^ 1));
                w->pick[np] = k;
                np += (size_t)(in & (flat ^ 1));
            }
            for (size_t e = 0; e < np; ++e) {
                w->near[m].c = c0[w->pick[e]];
                w->near[m].feat[0] = w->near[m].feat[1] = 0;
                w->near[m].region = UINT32_MAX;
                w->near[m++].inside = -1;
            }
            for (size_t k = 0; k < w->all_n; ++k)
                if ((double)w->all[k].c.distance - d0 <= reach[1])
                    w->near[m++] = w->all[k];
            corners = m == n && far_flat == 0; /* every contact asked */
            /* points beyond the reach: the contacts and corners there, and the corners of the flat
             * contacts there (not asked: they lie no nearer than their contacts) */
            if (m > 0 && (m < n || far_flat > 0)) {
                if ((nk = order_merge(w, w->near, m, f1, f2, tol)) == 0)
                    return 0;
                ns = choose_points(w, w->near, nk, margin, max, big, f1, f2, 1);
                rc = w->near;
                /* choose_points measures the touching points from the deepest kept: this pass
                 * holds all of them only where that is the d0 of its reach (with flat contacts
                 * left out, their corners may lie a rounding farther than the deepest contact) */
                if (pass == 0 && (double)rc[w->kept[0]].c.distance != d0) {
                    ns = 0;
                    continue;
                }
                /* the level holds the same touching points kept (nt of choose_points), and they
                 * are at most the nk kept here: it can find K of them only where nk = K */
                if (ns == 0 && nk != max)
                    break;
            }
        }
        if (ns == 0) {
            /* all the points: the contacts before the others, step 0 again unless done for all */
            if (!corners)
                w->all_n = n_pre;
            if (!all_front(w, c0, n0, drop))
                return 0;
        }
    }
    if (ns == 0) {
        if (!corners && !pair_corners(s, c0, n0, margin, NULL, w))
            return 0;
        if (w->all_n == 0 && drop != NULL) {
            /* flat contacts whose corners all lie beyond the margin by the exact method's
             * rounding (the region at the margin's edge): the contacts stand for themselves */
            drop = NULL;
            goto again;
        }
        if (w->all_n == 0)
            return 1;
        if ((nk = order_merge(w, w->all, w->all_n, f1, f2, tol)) == 0)
            return 0;
        rc = w->all;
        ns = choose_points(w, rc, nk, margin, max, big, f1, f2, 0);
    }
    if (!array_reserve(out, out->count + ns, sizeof(ttd_scene_point)))
        return 0;
    for (size_t k = 0; k < ns; ++k) {
        const manifold_rec *xr = &rc[w->kept[w->sel[k]]];
        const ttd_scene_contact *x = &xr->c;
        ttd_scene_point *pt = (ttd_scene_point *)out->data + out->count + k;
        double normal[3];
        if (xr->inside == 2)
            memcpy(normal, w->sat_n, sizeof normal);
        else if (xr->region != UINT32_MAX)
            memcpy(normal, w->reg_n + 3 * (size_t)xr->region, sizeof normal);
        else
            contact_normal(s, x, xr->inside, normal);
        pt->i = x->i;
        pt->j = x->j;
        pt->tri_i = x->tri_i;
        pt->tri_j = x->tri_j;
        for (int r = 0; r < 3; ++r) {
            pt->point[r] = (real)(0.5 * (double)x->p[r] + 0.5 * (double)x->q[r]);
            pt->normal[r] = (real)normal[r];
            pt->point_i[r] = x->p[r];
            pt->point_j[r] = x->q[r];
        }
        pt->distance = x->distance;
        pt->depth = margin - x->distance;
    }
    points_keys(s, cfg, rc, w->kept, w->sel, (ttd_scene_point *)out->data + out->count, ns);
    out->count += ns;
    return 1;
}
