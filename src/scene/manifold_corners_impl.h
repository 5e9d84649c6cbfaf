/* SPDX-License-Identifier: MIT */
/* Step 0: the corners of flat contact a face lying on a face adds to its contacts
 * (the vertices within the margin of the other triangle, the crossings of edges), each asked once
 * with the exact method; cheap screens first where the exact method surely finds none. Part of a body pair's manifold
 * (scene/manifold_impl.h, which includes it once per precision; docs/scenes.md, section 5). */

/* ---- step 0: the corners of flat contact ---------------------------------------------------- */

/* Two triangles lie face on face when their normals are opposite within this angle (radians):
 * about 5.7 degrees, a box resting on a box or a floor however it has settled. Curved bodies'
 * triangles rarely are (an icosphere of 1,280 triangles: 0.2% of the contacts of a pile). */
#define CORNER_ANGLE 0.1

/* A world triangle's plane for a cheap test that a point is farther than the margin from the
 * triangle (it is at least as far from its plane): the unit normal n about the first vertex a;
 * err bounds how far a computed height may be off, per unit of the point's distance from a
 * (the normal's direction is known to about 16 eps |e1| |e2| / |e1 x e2|). ok = 0 where the
 * triangle has no plane to speak of (a direction known no better than 2^-20): no test. */
typedef struct corner_plane {
    double a[3], n[3], err, size;
    int ok;
} corner_plane;

static void corner_plane_make(const real x[9], corner_plane *P)
{
    double v[3][3], cr[3], e11, e22;
    P->ok = 0;
    for (int k = 0; k < 9; ++k)
        v[k / 3][k % 3] = (double)x[k];
    memcpy(P->a, v[0], sizeof P->a);
    if (!unit_cross((const double (*)[3])v, cr, &e11, &e22, &P->size))
        return;
    const double l = sqrt(dot3d(cr, cr)), l12 = sqrt(e11) * sqrt(e22);
    if (!(l > 0x1p-20 * l12))
        return;
    for (int r = 0; r < 3; ++r)
        P->n[r] = cr[r] / l;
    P->err = (16 * l12 / l + 8) * DBL_EPSILON;
    P->ok = 1;
}

/* Whether world point y may lie within lim of plane P's triangle: +1 or -1 when it is farther
 * than lim above or below the plane (surely, with every rounding of the height, of y's world
 * coordinates and of the exact method's distance allowed for), 0 when it may not be. */
static int corner_side(const corner_plane *P, const real y[3], double lim)
{
    if (!P->ok)
        return 0;
    double d[3], far = 0;
    for (int r = 0; r < 3; ++r) {
        d[r] = (double)y[r] - P->a[r];
        far = fabs(d[r]) > far ? fabs(d[r]) : far; /* fmax's value (no NaN here), without its call */
    }
    const double h = dot3d(d, P->n), slack = 2 * (far + P->size) * (P->err + 64 * (double)TTD_REAL_EPS);
    return h > lim + slack ? 1 : h < -(lim + slack) ? -1 : 0;
}

/* Cheap tests that a question of step 0 has no corner, asked before the exact method: each
 * only where the exact method surely agrees, whatever its rounding. That method works on the
 * points relative to one of them and scaled to their box (scalar/exact_impl.h), so its distance
 * may be off by a few ulps of real times the box's extent: SCREEN_SLACK of them is allowed, on
 * top of 16 ulps of the margin. */
#define SCREEN_SLACK 1024

/* The distance within which the exact method may find points whose true distance is beyond it
 * by at most margin: margin, its rounding, the method's rounding on a box of extent ext. */
static double screen_lim(real margin, double ext)
{
    return (double)margin * (1 + 16 * (double)TTD_REAL_EPS) + SCREEN_SLACK * (double)TTD_REAL_EPS * ext + 0x1p-400;
}

/* The box of na points a (3 reals each): made once per triangle (corner_tri), vertex and edge
 * of a contact, where it was made again for every question asked of them. */
typedef struct screen_box {
    double lo[3], hi[3];
} screen_box;

static void box_of(const real *a, int na, screen_box *b)
{
    for (int r = 0; r < 3; ++r) {
        b->lo[r] = b->hi[r] = (double)a[r];
        for (int k = 1; k < na; ++k) {
            const double x = (double)a[3 * k + r];
            b->lo[r] = x < b->lo[r] ? x : b->lo[r];
            b->hi[r] = x > b->hi[r] ? x : b->hi[r];
        }
    }
}

/* The largest side of the box around boxes a and b. */
static double boxes_ext(const screen_box *a, const screen_box *b)
{
    double ext = 0;
    for (int r = 0; r < 3; ++r) {
        const double l = a->lo[r] < b->lo[r] ? a->lo[r] : b->lo[r], h = a->hi[r] > b->hi[r] ? a->hi[r] : b->hi[r];
        ext = h - l > ext ? h - l : ext;
    }
    return ext;
}

/* Whether the boxes a and b (of a's and b's points) lie so far apart along an axis that the
 * exact method finds the points' hulls farther apart than the margin; ext: boxes_ext(a, b). */
static int boxes_apart(const screen_box *a, const screen_box *b, double ext, real margin)
{
    const double lim = screen_lim(margin, ext);
    for (int r = 0; r < 3; ++r)
        if (b->lo[r] - a->hi[r] > lim || a->lo[r] - b->hi[r] > lim)
            return 1;
    return 0;
}

#include "scene/edges_miss_impl.h" /* SCREEN_THIN, and the edge questions' screen */

/* Whether vertex y lies beyond an edge of triangle x (outward in the triangle's plane) by more
 * than the margin, so surely that the exact method finds it farther than the margin from the
 * triangle (the triangle lies inside each edge's half-space). ext: the largest side of the box
 * around y and x (boxes_ext). Triangles whose normal is known poorly (thinner than SCREEN_THIN)
 * are not screened. */
/* Triangle x's part of that test, made once per triangle where many vertices are screened
 * against it (piece_corners): its corners, each edge's outward direction and its length's
 * factor; ok = 0 for a triangle not screened. The same operations as made per vertex, so the
 * same bits. */
typedef struct beside_tri {
    double v[3][3], o[3][3], len[3];
    int ok;
} beside_tri;

static inline void beside_prep(const real *x, beside_tri *B)
{
    double e[3][3];
    B->ok = 0;
    for (int k = 0; k < 3; ++k)
        for (int r = 0; r < 3; ++r)
            B->v[k][r] = (double)x[3 * k + r];
    for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k)
            e[k][r] = B->v[(k + 1) % 3][r] - B->v[k][r];
    double N[3];
    cross3d(e[0], e[1], N);
    const double nn = dot3d(N, N), l0 = dot3d(e[0], e[0]), l1 = dot3d(e[1], e[1]), l2 = dot3d(e[2], e[2]);
    if (!(nn > SCREEN_THIN * SCREEN_THIN * l0 * l1))
        return;
    const double nl = sqrt(nn);
    for (int k = 0; k < 3; ++k) {
        cross3d(e[k], N, B->o[k]); /* outward from edge k for a counter-clockwise triangle about N */
        const double lk = k == 0 ? l0 : k == 1 ? l1 : l2;
        B->len[k] = sqrt(lk) * nl;
    }
    B->ok = 1;
}

static inline int beside_test(const beside_tri *B, const real *y, double ext, real margin)
{
    if (!B->ok)
        return 0;
    double p[3], far = 0;
    for (int r = 0; r < 3; ++r) {
        p[r] = (double)y[r];
        far = fabs(p[r] - B->v[0][r]) > far ? fabs(p[r] - B->v[0][r]) : far;
    }
    const double lim = screen_lim(margin, ext);
    /* each height formed with a relative error of some 8 ulps of double per factor, the
     * normal's direction known to 1 / SCREEN_THIN of that: 2^-30 of the lengths covers it */
    const double err = 0x1p-30 * (far + ext);
    for (int k = 0; k < 3; ++k) {
        double d[3];
        for (int r = 0; r < 3; ++r)
            d[r] = p[r] - B->v[k][r];
        const double h = dot3d(d, B->o[k]) / B->len[k];
        if (h > lim + err)
            return 1;
    }
    return 0;
}

static int vertex_beside(const real *y, const real *x, double ext, real margin)
{
    beside_tri B;
    beside_prep(x, &B);
    return beside_test(&B, y, ext, margin);
}

/* Whether 3 reals x come after y (lexicographically). */
static int point_after(const real *x, const real *y)
{
    for (int r = 0; r < 3; ++r)
        if (x[r] != y[r])
            return x[r] > y[r];
    return 0;
}

static int key_push(manifold_work *w, const corner_key *k)
{
    if (w->key_n == w->key_cap) {
        corner_key *v = array_grow(w->key, &w->key_cap, w->key_n + 1, sizeof *v, 64);
        if (v == NULL)
            return 0;
        w->key = v;
    }
    w->key[w->key_n++] = *k;
    return 1;
}

/* Whether key u comes before key v: by the question (kind, a, b), then the triangles that ask it. */
static int corner_key_before(const corner_key *u, const corner_key *v)
{
    if (u->kind != v->kind)
        return u->kind < v->kind;
    if (u->a != v->a)
        return u->a < v->a;
    if (u->b != v->b)
        return u->b < v->b;
    if (u->ti != v->ti)
        return u->ti < v->ti;
    return u->tj < v->tj;
}

/* w->key[0..key_n) in corner_key_before's order, stably (equal keys as pushed): a merge sort
 * with the comparison inline, where the C library's qsort called a function per comparison.
 * 0 out of memory. */
static int corner_keys_sort(manifold_work *w)
{
    const size_t n = w->key_n;
    if (n > w->key_tmp_cap) {
        corner_key *t = realloc(w->key_tmp, n * sizeof *t);
        if (t == NULL)
            return 0;
        w->key_tmp = t;
        w->key_tmp_cap = n;
    }
    corner_key *a = w->key, *b = w->key_tmp;
    for (size_t run = 1; run < n; run *= 2) {
        for (size_t lo = 0; lo < n; lo += 2 * run) {
            const size_t mid = lo + run < n ? lo + run : n, hi = lo + 2 * run < n ? lo + 2 * run : n;
            size_t x = lo, y = mid, o = lo;
            while (x < mid && y < hi)
                b[o++] = corner_key_before(&a[y], &a[x]) ? a[y++] : a[x++];
            while (x < mid)
                b[o++] = a[x++];
            while (y < hi)
                b[o++] = a[y++];
        }
        corner_key *t = a;
        a = b;
        b = t;
    }
    if (a != w->key) { /* the sorted keys trade places with the scratch */
        w->key_tmp = w->key;
        w->key = a;
        const size_t c = w->key_cap;
        w->key_cap = w->key_tmp_cap;
        w->key_tmp_cap = c;
    }
    return 1;
}

/* A triangle of a body in the world, its plane and box, kept for the pair's other contacts on it
 * (a face on a face meets many triangles of the other face: in a tower of sliver-cut boxes each
 * triangle was made and measured again for every contact, a fifth of step 0). Direct-mapped by
 * triangle, a table a side; tag: the pass's number (manifold_work.stamp) and the triangle. */
#define CORNER_CACHE 256
typedef struct corner_tri {
    uint64_t tag;
    real x[9];
    corner_plane P;
    screen_box box;
} corner_tri;

static const corner_tri *corner_tri_get(const struct ttd_scene *s, manifold_work *w, int side, uint32_t id, uint32_t tri)
{
    corner_tri *e = &w->ctri[(size_t)side * CORNER_CACHE + (tri & (CORNER_CACHE - 1))];
    const uint64_t tag = w->stamp << 32 | tri;
    if (e->tag != tag) {
        world_triangle(s, id, tri, e->x);
        corner_plane_make(e->x, &e->P);
        box_of(e->x, 3, &e->box);
        e->tag = tag;
    }
    return e;
}

/* A vertex question of step 0 met in this pass (tag: manifold_work.stamp): its key's place
 * in w->key, or SIZE_MAX where its screens found no corner. A vertex is asked by every triangle
 * around it that meets the other triangle (a sliver fan's corner by 24): its screens depend on
 * the vertex's place and the other triangle alone, so they are run once, and one key is kept,
 * that of the smallest asking triangles (the key the sort and its dedup kept before). */
typedef struct corner_seen {
    uint64_t tag, a, b;
    uint32_t kind;
    size_t at;
} corner_seen;

static size_t seen_slot(const corner_seen *t, size_t cap, uint64_t tag, uint32_t kind, uint64_t a, uint64_t b)
{
    uint64_t h = (a + 1) * 0x9e3779b97f4a7c15ULL ^ (b + 1) * 0xc2b2ae3d27d4eb4fULL ^ (uint64_t)kind * 0x165667b19e3779f9ULL;
    h = (h ^ (h >> 29)) * 0xbf58476d1ce4e5b9ULL;
    h ^= h >> 32;
    size_t at = (size_t)h & (cap - 1);
    while (t[at].tag == tag && !(t[at].kind == kind && t[at].a == a && t[at].b == b))
        at = (at + 1) & (cap - 1);
    return at;
}

/* The entry of vertex question q in this pair's table: found (its `tag` is the pair's), or a free
 * slot to fill (the table grown to keep it at most half full). NULL out of memory. */
static corner_seen *seen_get(manifold_work *w, const corner_key *q)
{
    if (2 * (w->seen_n + 1) > w->seen_cap) {
        const size_t cap = w->seen_cap ? 2 * w->seen_cap : 1024;
        corner_seen *t = calloc(cap, sizeof *t);
        if (t == NULL)
            return NULL;
        for (size_t k = 0; k < w->seen_cap; ++k)
            if (w->seen[k].tag == w->stamp)
                t[seen_slot(t, cap, w->stamp, w->seen[k].kind, w->seen[k].a, w->seen[k].b)] = w->seen[k];
        free(w->seen);
        w->seen = t;
        w->seen_cap = cap;
    }
    return &w->seen[seen_slot(w->seen, w->seen_cap, w->stamp, q->kind, q->a, q->b)];
}

/* The questions contact c asks (step 0), into w->key: the contact's triangles lie face on face
 * (pair_flat), and a vertex or an edge may lie within the margin of the other triangle. 0 out of
 * memory. */
static int contact_corners(const struct ttd_scene *s, const ttd_scene_contact *c, real margin, manifold_work *w)
{
    const uint32_t id[2] = {c->i, c->j}, tri[2] = {c->tri_i, c->tri_j};
    const corner_tri *T[2] = {corner_tri_get(s, w, 0, c->i, c->tri_i), corner_tri_get(s, w, 1, c->j, c->tri_j)};
    const real *x[2] = {T[0]->x, T[1]->x};
    const ttd_mesh_edges *E[2];
    const uint32_t *tris[2];
    for (int side = 0; side < 2; ++side) {
        E[side] = ttd_mesh_edges_made(s->body[id[side]].mesh);
        tris[side] = s->body[id[side]].mesh->tris + 3 * (size_t)tri[side];
    }
    int h[2][3]; /* each vertex's side of the other triangle's plane beyond the margin, or 0 */
    for (int side = 0; side < 2; ++side)
        for (int k = 0; k < 3; ++k)
            h[side][k] = corner_side(&T[!side]->P, x[side] + 3 * k, (double)margin);
    /* vertices not inside a flat part that may lie within the margin of the other triangle */
    for (int side = 0; side < 2; ++side)
        for (int k = 0; k < 3; ++k) {
            if (h[side][k] != 0 || ttd_vertex_class(E[side], tri[side], k) == TTD_VERTEX_FLAT)
                continue;
            const corner_key key = {(uint32_t)side, E[side]->weld[tris[side][k]], tri[!side], c->tri_i, c->tri_j, k, 0};
            corner_seen *seen = seen_get(w, &key);
            if (seen == NULL)
                return 0;
            if (seen->tag == w->stamp) { /* met before: keep the smallest asking triangles */
                corner_key *e = seen->at == SIZE_MAX ? NULL : &w->key[seen->at];
                if (e != NULL && (key.ti < e->ti || (key.ti == e->ti && key.tj < e->tj))) {
                    e->ti = key.ti;
                    e->tj = key.tj;
                    e->k = key.k;
                }
                continue;
            }
            *seen = (corner_seen){w->stamp, key.a, key.b, key.kind, SIZE_MAX};
            w->seen_n++;
            screen_box vb;
            box_of(x[side] + 3 * k, 1, &vb);
            const double ext = boxes_ext(&vb, &T[!side]->box);
            if (!boxes_apart(&vb, &T[!side]->box, ext, margin) && !vertex_beside(x[side] + 3 * k, x[!side], ext, margin)) {
                seen->at = w->key_n;
                if (!key_push(w, &key))
                    return 0;
            }
        }
    /* each edge's box (edge k from vertex k to k + 1), for the screens below */
    screen_box eb[2][3];
    for (int side = 0; side < 2; ++side)
        for (int k = 0; k < 3; ++k) {
            const int k1 = (k + 1) % 3;
            const real e[6] = {x[side][3 * k], x[side][3 * k + 1], x[side][3 * k + 2],
                               x[side][3 * k1], x[side][3 * k1 + 1], x[side][3 * k1 + 2]};
            box_of(e, 2, &eb[side][k]);
        }
    /* real edges (not between coplanar triangles), each of which may come within the margin of
     * the other triangle's plane */
    for (int k = 0; k < 3; ++k) {
        const int k1 = (k + 1) % 3;
        if (ttd_edge_class(E[0], tri[0], k) == TTD_EDGE_FLAT || (h[0][k] != 0 && h[0][k] == h[0][k1]))
            continue;
        const uint64_t pa = E[0]->weld[tris[0][k]], pb = E[0]->weld[tris[0][k1]];
        if (pa == pb)
            continue;
        for (int l = 0; l < 3; ++l) {
            const int l1 = (l + 1) % 3;
            if (ttd_edge_class(E[1], tri[1], l) == TTD_EDGE_FLAT || (h[1][l] != 0 && h[1][l] == h[1][l1]))
                continue;
            const uint64_t qa = E[1]->weld[tris[1][l]], qb = E[1]->weld[tris[1][l1]];
            if (qa == qb)
                continue;
            const real ek[6] = {x[0][3 * k], x[0][3 * k + 1], x[0][3 * k + 2], x[0][3 * k1], x[0][3 * k1 + 1], x[0][3 * k1 + 2]};
            const real el[6] = {x[1][3 * l], x[1][3 * l + 1], x[1][3 * l + 2], x[1][3 * l1], x[1][3 * l1 + 1], x[1][3 * l1 + 2]};
            if (boxes_apart(&eb[0][k], &eb[1][l], boxes_ext(&eb[0][k], &eb[1][l]), margin) || edges_miss(ek, el))
                continue;
            const corner_key key = {2, pa < pb ? pa << 32 | pb : pb << 32 | pa, qa < qb ? qa << 32 | qb : qb << 32 | qa,
                                    c->tri_i, c->tri_j, k, l};
            if (!key_push(w, &key))
                return 0;
        }
    }
    return 1;
}

/* ---- step 0 once per pair of planar pieces ------------------------------------------------------ */

/* The questions a contact asks depend on its two triangles alone: a vertex question on the vertex
 * and the other triangle (its side of that triangle's plane, its screens), an edge question on the
 * two edges and the two triangles' planes; each is kept for the smallest triangles asking it. On a
 * face lying on a face nearly every triangle of one meets nearly every triangle of the other, so
 * contact_corners met each vertex question about once per contact (docs/scene-speed.md, section 9).
 * For the flat contacts of one pair of planar pieces (a group) the same questions are found from
 * the pieces' rims instead: each rim corner (a vertex not inside a flat part) of a triangle met
 * against each triangle of the other piece met, each real edge against each of the other's, a box
 * screen first, then the group's contacts (a table by triangle pair) for the smallest triangles
 * asking; every screen after that as contact_corners runs it. Same keys, same smallest triangles. */

/* A group's flat contact: its pieces (body i's, body j's) and its place among the pair's contacts. */
typedef struct piece_item {
    uint32_t pi, pj;
    size_t k;
} piece_item;

/* A rim corner: corner k of triangle t (local number loc) at place v. */
typedef struct piece_vslot {
    uint32_t v, t, loc;
    int k;
} piece_vslot;

/* A real edge: edge k of the triangle of local number loc, its ends' places pa, pb, its box. */
typedef struct piece_eslot {
    uint32_t loc, pa, pb;
    int k;
    screen_box box;
} piece_eslot;

/* *p grown to hold n items of `size` bytes (its capacity *cap): the array, or NULL out of memory
 * (*p kept). */
static void *piece_grow(void *p, size_t *cap, size_t n, size_t size)
{
    if (n == 0)
        n = 1;
    return p != NULL && n <= *cap ? p : array_grow(p, cap, n, size, 64);
}

static int piece_item_cmp(const void *x, const void *y)
{
    const piece_item *a = x, *b = y;
    if (a->pi != b->pi)
        return a->pi < b->pi ? -1 : 1;
    if (a->pj != b->pj)
        return a->pj < b->pj ? -1 : 1;
    return a->k < b->k ? -1 : a->k > b->k;
}

/* Whether rim corner a comes before b: by place, triangle, corner. */
static int piece_vslot_before(const piece_vslot *a, const piece_vslot *b)
{
    if (a->v != b->v)
        return a->v < b->v;
    if (a->t != b->t)
        return a->t < b->t;
    return a->k < b->k;
}

/* w->pv[side][0..n) in piece_vslot_before's order: a merge sort with the comparison inline
 * (qsort's call per comparison cost as much as the rest of a group's corners). 0 out of memory. */
static int piece_vslots_sort(manifold_work *w, int side, size_t n)
{
    piece_vslot *t = piece_grow(w->pvtmp, &w->pvtmp_cap, n, sizeof *t);
    if (t == NULL)
        return 0;
    w->pvtmp = t;
    piece_vslot *a = w->pv[side], *b = t;
    for (size_t run = 1; run < n; run *= 2) {
        for (size_t lo = 0; lo < n; lo += 2 * run) {
            const size_t mid = lo + run < n ? lo + run : n, hi = lo + 2 * run < n ? lo + 2 * run : n;
            size_t x = lo, y = mid, o = lo;
            while (x < mid && y < hi)
                b[o++] = piece_vslot_before(&a[y], &a[x]) ? a[y++] : a[x++];
            while (x < mid)
                b[o++] = a[x++];
            while (y < hi)
                b[o++] = a[y++];
        }
        piece_vslot *u = a;
        a = b;
        b = u;
    }
    if (a != w->pv[side]) { /* the sorted slots trade places with the scratch */
        w->pvtmp = w->pv[side];
        w->pv[side] = a;
        const size_t c = w->pv_cap[side];
        w->pv_cap[side] = w->pvtmp_cap;
        w->pvtmp_cap = c;
    }
    return 1;
}

/* A group costs about one box screen per rim corner and triangle of the other side, per pair of
 * real edges and per triangle pair; contact_corners some 800 instructions a contact, about
 * PIECE_GAIN box screens: a group whose pieces' rims are long beside its contacts (two finely cut
 * plates overlapping at their rims) goes contact by contact. */
#ifndef PIECE_GAIN
#define PIECE_GAIN 16
#endif
/* A group goes contact by contact where it has fewer than this many contacts per triangle met:
 * its set-up (each triangle's copy and screen part, the slots, the table) is per triangle. */
#ifndef PIECE_FEW
#define PIECE_FEW 2
#endif
#define PIECE_MIN (4 * PIECE_FEW * PIECE_FEW) /* fewer contacts in a group: contact by contact */

/* Vertex question q of step 0, its triangles' screens passed but the box's and the side's (asked
 * first by the caller), as contact_corners keeps it: once per pair, for the smallest triangles;
 * y the vertex, B the other triangle, ext their boxes' extent. 0 out of memory. */
static int vertex_keep(manifold_work *w, const corner_key *key, const real *y, const beside_tri *B, double ext, real margin)
{
    corner_seen *seen = seen_get(w, key);
    if (seen == NULL)
        return 0;
    if (seen->tag == w->stamp) {
        corner_key *e = seen->at == SIZE_MAX ? NULL : &w->key[seen->at];
        if (e != NULL && (key->ti < e->ti || (key->ti == e->ti && key->tj < e->tj))) {
            e->ti = key->ti;
            e->tj = key->tj;
            e->k = key->k;
        }
        return 1;
    }
    *seen = (corner_seen){w->stamp, key->a, key->b, key->kind, SIZE_MAX};
    w->seen_n++;
    if (!beside_test(B, y, ext, margin)) {
        seen->at = w->key_n;
        if (!key_push(w, key))
            return 0;
    }
    return 1;
}

/* The questions of the m contacts of one group (c[it[q].k], flat contacts of one pair of planar
 * pieces, each asking), into w->key as contact_corners would put them: 1; -1 where the group
 * should go contact by contact (nothing added); 0 out of memory. */
static int piece_corners(const struct ttd_scene *s, const ttd_scene_contact *c, const piece_item *it, size_t m,
                         real margin, manifold_work *w)
{
    const uint32_t id[2] = {c[it[0].k].i, c[it[0].k].j};
    const ttd_mesh_edges *E[2];
    const uint32_t *tris[2];
    size_t nt[2] = {0, 0}, nv[2] = {0, 0}, ne[2] = {0, 0}, dv[2] = {0, 0};
    if (++w->ptag == 0) { /* the stamps wrapped: clear them */
        for (int side = 0; side < 2; ++side)
            if (w->pstamp_cap[side] > 0)
                memset(w->pstamp[side], 0, w->pstamp_cap[side] * sizeof *w->pstamp[side]);
        w->ptag = 1;
    }
    for (int side = 0; side < 2; ++side) {
        const struct ttd_mesh *mesh = s->body[id[side]].mesh;
        E[side] = ttd_mesh_edges_made(mesh);
        tris[side] = mesh->tris;
        if (mesh->nt > w->pstamp_cap[side]) {
            uint32_t *st = calloc(mesh->nt, sizeof *st), *lo = malloc(mesh->nt * sizeof *lo);
            if (st == NULL || lo == NULL) {
                free(st);
                free(lo);
                return 0;
            }
            free(w->pstamp[side]);
            free(w->ploc[side]);
            w->pstamp[side] = st;
            w->ploc[side] = lo;
            w->pstamp_cap[side] = mesh->nt;
        }
    }
    /* each side's triangles met, numbered in the order met */
    for (size_t q = 0; q < m; ++q)
        for (int side = 0; side < 2; ++side) {
            const uint32_t t = side ? c[it[q].k].tri_j : c[it[q].k].tri_i;
            if (w->pstamp[side][t] == w->ptag)
                continue;
            uint32_t *v = piece_grow(w->ptid[side], &w->ptid_cap[side], nt[side] + 1, sizeof *v);
            if (v == NULL)
                return 0;
            w->ptid[side] = v;
            v[nt[side]] = t;
            w->pstamp[side][t] = w->ptag;
            w->ploc[side][t] = (uint32_t)nt[side]++;
        }
    /* few contacts for its triangles (two facing triangles of curved bodies, a face of two
     * triangles on another): contact by contact costs less than the group's set-up */
    if (m < PIECE_FEW * (nt[0] + nt[1]))
        return -1;
    /* their world triangles, and their part of the vertex screen */
    for (int side = 0; side < 2; ++side) {
        corner_tri *v = piece_grow(w->ptri[side], &w->ptri_cap[side], nt[side], sizeof *v);
        if (v == NULL)
            return 0;
        w->ptri[side] = v;
        beside_tri *bv = piece_grow(w->pbes[side], &w->pbes_cap[side], nt[side], sizeof *bv);
        if (bv == NULL)
            return 0;
        w->pbes[side] = bv;
        for (size_t loc = 0; loc < nt[side]; ++loc) {
            v[loc] = *corner_tri_get(s, w, side, id[side], w->ptid[side][loc]);
            beside_prep(v[loc].x, &bv[loc]);
        }
    }
    /* their rim corners and real edges */
    for (int side = 0; side < 2; ++side) {
        piece_vslot *pv = piece_grow(w->pv[side], &w->pv_cap[side], 3 * nt[side], sizeof *pv);
        if (pv == NULL)
            return 0;
        w->pv[side] = pv;
        piece_eslot *pe = piece_grow(w->pe[side], &w->pe_cap[side], 3 * nt[side], sizeof *pe);
        if (pe == NULL)
            return 0;
        w->pe[side] = pe;
        for (size_t loc = 0; loc < nt[side]; ++loc) {
            const corner_tri *T = &w->ptri[side][loc];
            const uint32_t t = (uint32_t)T->tag, *tv = tris[side] + 3 * (size_t)t;
            for (int k = 0; k < 3; ++k)
                if (ttd_vertex_class(E[side], t, k) != TTD_VERTEX_FLAT)
                    pv[nv[side]++] = (piece_vslot){E[side]->weld[tv[k]], t, (uint32_t)loc, k};
            for (int k = 0; k < 3; ++k) {
                const int k1 = (k + 1) % 3;
                const uint32_t pa = E[side]->weld[tv[k]], pb = E[side]->weld[tv[k1]];
                if (ttd_edge_class(E[side], t, k) == TTD_EDGE_FLAT || pa == pb)
                    continue;
                const real e[6] = {T->x[3 * k], T->x[3 * k + 1], T->x[3 * k + 2], T->x[3 * k1], T->x[3 * k1 + 1], T->x[3 * k1 + 2]};
                pe[ne[side]] = (piece_eslot){(uint32_t)loc, pa, pb, k, {{0, 0, 0}, {0, 0, 0}}};
                box_of(e, 2, &pe[ne[side]++].box);
            }
        }
        if (!piece_vslots_sort(w, side, nv[side]))
            return 0;
        pv = w->pv[side];
        for (size_t r = 0; r < nv[side]; ++r)
            dv[side] += r == 0 || pv[r].v != pv[r - 1].v;
    }
    /* what the group would cost, against contact by contact (all sizes below 2^32 here, the
     * products in double) */
    const double cost = (double)dv[0] * (double)nt[1] + (double)dv[1] * (double)nt[0] + (double)ne[0] * (double)ne[1] +
                        (double)nt[0] * (double)nt[1];
    if (cost > PIECE_GAIN * (double)m + 256)
        return -1;
    /* the group's contacts by their triangles' local numbers */
    unsigned char *mat = piece_grow(w->pmat, &w->pmat_cap, nt[0] * nt[1], 1);
    if (mat == NULL)
        return 0;
    w->pmat = mat;
    memset(mat, 0, nt[0] * nt[1]);
    for (size_t q = 0; q < m; ++q)
        mat[(size_t)w->ploc[0][c[it[q].k].tri_i] * nt[1] + w->ploc[1][c[it[q].k].tri_j]] = 1;
    /* vertex questions: each rim corner's place against each triangle of the other side met */
    for (int side = 0; side < 2; ++side) {
        const int o = !side;
        const piece_vslot *pv = w->pv[side];
        for (size_t r0 = 0, r1; r0 < nv[side]; r0 = r1) {
            for (r1 = r0 + 1; r1 < nv[side] && pv[r1].v == pv[r0].v;)
                ++r1;
            real y[3];
            memcpy(y, w->ptri[side][pv[r0].loc].x + 3 * pv[r0].k, sizeof y);
            screen_box vb;
            box_of(y, 1, &vb);
            for (size_t lb = 0; lb < nt[o]; ++lb) {
                const corner_tri *B = &w->ptri[o][lb];
                const double ext = boxes_ext(&vb, &B->box);
                if (boxes_apart(&vb, &B->box, ext, margin))
                    continue;
                size_t r = r0; /* the smallest triangle at the place that meets B: by (t, k) */
                while (r < r1 && !mat[side ? lb * nt[1] + pv[r].loc : (size_t)pv[r].loc * nt[1] + lb])
                    ++r;
                if (r == r1 || corner_side(&B->P, y, (double)margin) != 0)
                    continue;
                const uint32_t bt = (uint32_t)B->tag;
                const corner_key key = {(uint32_t)side, pv[r].v, bt, side ? bt : pv[r].t, side ? pv[r].t : bt, pv[r].k, 0};
                if (!vertex_keep(w, &key, y, &w->pbes[o][lb], ext, margin))
                    return 0;
            }
        }
    }
    /* edge questions: each real edge of body i's triangles met against each of body j's, in
     * contact_corners' order within a triangle pair (k, then l) */
    for (size_t a = 0; a < ne[0]; ++a) {
        const piece_eslot *A = &w->pe[0][a];
        const corner_tri *T0 = &w->ptri[0][A->loc];
        const int k = A->k, k1 = (k + 1) % 3;
        for (size_t b = 0; b < ne[1]; ++b) {
            const piece_eslot *Bq = &w->pe[1][b];
            if (!mat[(size_t)A->loc * nt[1] + Bq->loc] || boxes_apart(&A->box, &Bq->box, boxes_ext(&A->box, &Bq->box), margin))
                continue;
            const corner_tri *T1 = &w->ptri[1][Bq->loc];
            const int l = Bq->k, l1 = (l + 1) % 3;
            const int hk = corner_side(&T1->P, T0->x + 3 * k, (double)margin), hk1 = corner_side(&T1->P, T0->x + 3 * k1, (double)margin);
            if (hk != 0 && hk == hk1)
                continue;
            const int hl = corner_side(&T0->P, T1->x + 3 * l, (double)margin), hl1 = corner_side(&T0->P, T1->x + 3 * l1, (double)margin);
            if (hl != 0 && hl == hl1)
                continue;
            const real ek[6] = {T0->x[3 * k], T0->x[3 * k + 1], T0->x[3 * k + 2], T0->x[3 * k1], T0->x[3 * k1 + 1], T0->x[3 * k1 + 2]};
            const real el[6] = {T1->x[3 * l], T1->x[3 * l + 1], T1->x[3 * l + 2], T1->x[3 * l1], T1->x[3 * l1 + 1], T1->x[3 * l1 + 2]};
            if (edges_miss(ek, el))
                continue;
            const uint64_t pa = A->pa, pb = A->pb, qa = Bq->pa, qb = Bq->pb;
            const corner_key key = {2, pa < pb ? pa << 32 | pb : pb << 32 | pa, qa < qb ? qa << 32 | qb : qb << 32 | qa,
                                    (uint32_t)T0->tag, (uint32_t)T1->tag, k, l};
            if (!key_push(w, &key))
                return 0;
        }
    }
    return 1;
}

/* Step 0's questions of the pair's n contacts c (those face on face and, with reach, within it;
 * see pair_corners) into w->key: the flat contacts by pair of planar pieces (piece_corners), the
 * others one by one. 0 out of memory. */
static int pair_questions(const struct ttd_scene *s, const ttd_scene_contact *c, size_t n, real margin,
                          const double *reach, manifold_work *w)
{
    /* the flat contacts asking into w->pitem[0..m), by pieces; the others' places into
     * w->pone[0..one) (a single call of contact_corners below, which the compiler inlines) */
    size_t m = 0, one = 0;
    for (size_t k = 0; k < n; ++k) {
        if (!(w->face[k] & FACE_ON_FACE) || !(reach == NULL || (double)c[k].distance - reach[0] <= reach[1]))
            continue;
        if (!(w->face[k] & FACE_FLAT)) {
            size_t *v = piece_grow(w->pone, &w->pone_cap, one + 1, sizeof *v);
            if (v == NULL)
                return 0;
            w->pone = v;
            v[one++] = k;
            continue;
        }
        piece_item *v = piece_grow(w->pitem, &w->pitem_cap, m + 1, sizeof *v);
        if (v == NULL)
            return 0;
        w->pitem = v;
        const ttd_mesh_edges *Ei = ttd_mesh_edges_made(s->body[c[k].i].mesh), *Ej = ttd_mesh_edges_made(s->body[c[k].j].mesh);
        v[m++] = (piece_item){Ei->piece[c[k].tri_i], Ej->piece[c[k].tri_j], k};
    }
    /* a group takes its own path only with PIECE_FEW * (nt_i + nt_j) contacts or more, and its
     * m contacts have nt_i + nt_j >= 2 sqrt(m) triangles: so with fewer than PIECE_MIN none does */
    int same = 1; /* a single pair of pieces (the usual case): no sort */
    for (size_t q = 1; q < m && same && m >= PIECE_MIN; ++q)
        same = w->pitem[q].pi == w->pitem[0].pi && w->pitem[q].pj == w->pitem[0].pj;
    if (!same)
        qsort(w->pitem, m, sizeof *w->pitem, piece_item_cmp);
    for (size_t q0 = 0, q1; q0 < m; q0 = q1) {
        for (q1 = q0 + 1; q1 < m && w->pitem[q1].pi == w->pitem[q0].pi && w->pitem[q1].pj == w->pitem[q0].pj;)
            ++q1;
        const int got = q1 - q0 < PIECE_MIN ? -1 : piece_corners(s, c, w->pitem + q0, q1 - q0, margin, w);
        if (got == 0)
            return 0;
        if (got < 0) { /* contact by contact */
            size_t *v = piece_grow(w->pone, &w->pone_cap, one + (q1 - q0), sizeof *v);
            if (v == NULL)
                return 0;
            w->pone = v;
            for (size_t q = q0; q < q1; ++q)
                v[one++] = w->pitem[q].k;
        }
    }
    for (size_t q = 0; q < one; ++q)
        if (!contact_corners(s, &c[w->pone[q]], margin, w))
            return 0;
    return 1;
}

/* A triangle of body j's normal turned into body i's frame (R_i^T R_j n_j), kept for the pair's
 * other contacts on it: a direct-mapped table by triangle, stamped with the pair's number
 * (work_stamp's low 32 bits). */
#define FLAT_CACHE 256
typedef struct flat_normal {
    uint32_t pair, tri;
    double u[3];
} flat_normal;

/* A new number for step 0's stamps (each pass's triangles, vertex questions and turned normals:
 * one counter for the three tables), whose low 32 bits are never 0 (an entry never filled). Where
 * those wrap (a scene keeps w across queries), the tables stamped with 32 bits forget all. */
static uint64_t work_stamp(manifold_work *w)
{
    if ((uint32_t)++w->stamp == 0) {
        if (w->ctri != NULL)
            memset(w->ctri, 0, 2 * CORNER_CACHE * sizeof *w->ctri);
        if (w->fnorm != NULL)
            memset(w->fnorm, 0, FLAT_CACHE * sizeof *w->fnorm);
        ++w->stamp;
    }
    return w->stamp;
}

/* Step 0's bits of the pair's n contacts c into w->face (FACE_ON_FACE, FACE_FLAT); the number of
 * contacts of flat contact into *nflat. Face on face: the triangles' normals opposite within
 * CORNER_ANGLE (the meshes' normals, in body i's frame). Flat: face on face, both triangles' flat
 * pieces planar (mesh/edges.h), neither body a solid, and no face-on-face contact of planar pieces
 * in the pair at distance 0 (two pieces that touch or cross: the overlap's corners need not hold
 * the deepest point, which may lie where they cross). The smallest distance into *dmin (HUGE_VAL:
 * none; read here rather than in a scan of its own). 0 out of memory. */
static int pair_flat(const struct ttd_scene *s, const ttd_scene_contact *c, size_t n, manifold_work *w, size_t *nflat,
                     double *dmin)
{
    *nflat = 0;
    *dmin = HUGE_VAL;
    if (n == 0)
        return 1;
    if (n > w->face_cap) {
        unsigned char *f = realloc(w->face, n);
        if (f == NULL)
            return 0;
        w->face = f;
        w->face_cap = n;
    }
    if (w->fnorm == NULL && (w->fnorm = calloc(FLAT_CACHE, sizeof *w->fnorm)) == NULL)
        return 0;
    const uint32_t stamp = (uint32_t)work_stamp(w);
    double rel[9]; /* R_i^T R_j */
    const double *pi = s->body[c[0].i].pose, *pj = s->body[c[0].j].pose;
    for (int r = 0; r < 3; ++r)
        for (int q = 0; q < 3; ++q)
            rel[3 * r + q] = pi[r] * pj[q] + pi[4 + r] * pj[4 + q] + pi[8 + r] * pj[8 + q];
    const ttd_mesh_edges *Ei = ttd_mesh_edges_made(s->body[c[0].i].mesh), *Ej = ttd_mesh_edges_made(s->body[c[0].j].mesh);
    /* a solid of an inward mesh faces the other way (edges.h, inward) */
    const double flip = (Ei->inward && s->body[c[0].i].solid) != (Ej->inward && s->body[c[0].j].solid) ? -1 : 1;
    const double lim = -cos(CORNER_ANGLE);
    /* a solid's pairs keep every contact (with them, examples/sim's bin of solid tori and balls
     * drifted, as it also does from 1e-12 nudges of the old rule's start: a chaotic check, not a
     * wrong point; docs/scene-speed.md, section 8) */
    const int solid = s->body[c[0].i].solid || s->body[c[0].j].solid;
    int touching = solid;
    size_t m = 0;
    double d0 = HUGE_VAL;
    for (size_t k = 0; k < n; ++k) {
        if ((double)c[k].distance < d0)
            d0 = (double)c[k].distance;
        const float *ni = Ei->normal + 3 * (size_t)c[k].tri_i;
        /* n_i . (R_i^T R_j n_j), n_j turned once per triangle j (the same products, the same bits) */
        flat_normal *e = &w->fnorm[c[k].tri_j & (FLAT_CACHE - 1)];
        if (e->pair != stamp || e->tri != c[k].tri_j) {
            const float *nj = Ej->normal + 3 * (size_t)c[k].tri_j;
            for (int r = 0; r < 3; ++r)
                e->u[r] = rel[3 * r] * (double)nj[0] + rel[3 * r + 1] * (double)nj[1] + rel[3 * r + 2] * (double)nj[2];
            e->pair = stamp;
            e->tri = c[k].tri_j;
        }
        double facing = 0;
        for (int r = 0; r < 3; ++r)
            facing += (double)ni[r] * e->u[r];
        unsigned char f = 0;
        if (flip * facing <= lim) {
            f = FACE_ON_FACE;
            if (Ei->piece_planar[Ei->piece[c[k].tri_i]] && Ej->piece_planar[Ej->piece[c[k].tri_j]]) {
                f |= FACE_FLAT;
                touching |= !(c[k].distance > 0);
                ++m;
            }
        }
        w->face[k] = f;
    }
    if (touching) {
        for (size_t k = 0; k < n; ++k)
            w->face[k] &= (unsigned char)~FACE_FLAT;
        m = 0;
    }
    *nflat = m;
    *dmin = d0;
    return 1;
}

#include "scene/edge_axis_impl.h"

/* Asks the question of key q (step 0): a corner within the margin into *out (1), or none (0). */
static int corner_ask(const struct ttd_scene *s, manifold_work *w, uint32_t i, uint32_t j, const corner_key *q,
                      real margin, ttd_scene_contact *out, uint8_t feat[2])
{
    const real *x[2] = {corner_tri_get(s, w, 0, i, q->ti)->x, corner_tri_get(s, w, 1, j, q->tj)->x};
    *out = (ttd_scene_contact){i, j, q->ti, q->tj, 0, {0, 0, 0}, {0, 0, 0}};
    ttd_result r;
    if (q->kind < 2) {
        const int side = (int)q->kind;
        const real *v = x[side] + 3 * q->k;
        const real pt[9] = {v[0], v[1], v[2], v[0], v[1], v[2], v[0], v[1], v[2]};
        TTD_EXACT_PAIR_DUPS(pt, x[!side], &r);
        if (!(r.distance <= margin))
            return 0;
        out->distance = r.distance;
        feat[side] = (uint8_t)(1u << q->k);
        feat[!side] = r.feature_q;
        for (int t = 0; t < 3; ++t) {
            const real other = r.distance == 0 ? v[t] : r.q[t]; /* touching: the vertex itself */
            out->p[t] = side ? other : v[t];
            out->q[t] = side ? v[t] : other;
        }
        return 1;
    }
    /* each edge from its smaller end, the smaller edge first: the same call when the bodies swap */
    real seg[2][9];
    const real *e[2][2] = {{x[0] + 3 * q->k, x[0] + 3 * ((q->k + 1) % 3)}, {x[1] + 3 * q->l, x[1] + 3 * ((q->l + 1) % 3)}};
    for (int g = 0; g < 2; ++g) {
        const int f = point_after(e[g][0], e[g][1]);
        for (int t = 0; t < 3; ++t) {
            seg[g][t] = e[g][f][t];
            seg[g][3 + t] = seg[g][6 + t] = e[g][!f][t];
        }
    }
    const int second = point_after(seg[0], seg[1]) ||
                       (memcmp(seg[0], seg[1], 3 * sizeof(real)) == 0 && point_after(seg[0] + 3, seg[1] + 3));
    if (MANIFOLD_EDGE_AXIS_SCREEN && edges_axis_apart(seg[second], seg[!second]))
        return 0; /* box edges side by side or meeting at an end (docs/scene-speed.md, section 22) */
    TTD_EXACT_PAIR_DUPS(seg[second], seg[!second], &r);
    if (!(r.distance <= margin) || !(r.bary_p[0] > 0 && r.bary_p[0] < 1) || !(r.bary_q[0] > 0 && r.bary_q[0] < 1))
        return 0;
    out->distance = r.distance;
    feat[0] = (uint8_t)(1u << q->k | 1u << (q->k + 1) % 3);
    feat[1] = (uint8_t)(1u << q->l | 1u << (q->l + 1) % 3);
    for (int t = 0; t < 3; ++t) {
        const real on_first = r.p[t], on_second = r.distance == 0 ? r.p[t] : r.q[t];
        out->p[t] = second ? on_second : on_first; /* body i's edge is seg[0] */
        out->q[t] = second ? on_first : on_second;
    }
    return 1;
}

/* An answer of step 0 (corner_ask's) to question q: ok, and where ok the corner and its features.
 * It depends on q whole (its triangles too) and the pair alone, so a pair's later pass takes it
 * from the memo of its last pass where it asks the same key (the same bits as asked again). */
typedef struct corner_memo {
    corner_key q;
    ttd_scene_contact got;
    uint8_t f[2];
    int ok;
} corner_memo;

static int corner_key_same(const corner_key *u, const corner_key *v)
{
    return u->kind == v->kind && u->a == v->a && u->b == v->b && u->ti == v->ti && u->tj == v->tj && u->k == v->k &&
           u->l == v->l;
}

/* Step 0: the corners the pair's n contacts c add (those face on face: w->face, pair_flat), into w->all (a solid pair's vertices found
 * inside the other body left out: they have their negative distances). reach: NULL, or those
 * of the contacts alone whose distance is within reach[1] of reach[0] (a corner lies no nearer
 * than each contact that asks for it, so these are all the corners within that reach, each
 * asked for the same smallest triangles and kept at the same distance). 0 out of memory. */
static int pair_corners(const struct ttd_scene *s, const ttd_scene_contact *c, size_t n, real margin,
                        const double *reach, manifold_work *w)
{
    w->key_n = 0;
    if (n == 0)
        return 1;
    if (w->ctri == NULL && (w->ctri = calloc(2 * CORNER_CACHE, sizeof *w->ctri)) == NULL)
        return 0;
    work_stamp(w); /* the triangles kept are another pair's (or another pose's) */
    w->seen_n = 0;  /* and so are the vertex questions met */
    if (!pair_questions(s, c, n, margin, reach, w))
        return 0;
    if (w->key_n == 0)
        return 1;
    /* each question once, for its smallest triangles; each vertex kept once, at its smallest
     * distance (ties: the smaller triangle of the other body) */
    if (!corner_keys_sort(w))
        return 0;
    int have = 0; /* a vertex corner waiting in `best` */
    ttd_scene_contact best = c[0];
    uint8_t best_f[2] = {0, 0};
    const corner_key *best_q = NULL;
    /* this pass's answers into w->memo_next (at most one per key), the last pass's looked up in
     * w->memo: both in corner_key_before's order, so one cursor mc walks it */
    if (w->key_n > w->memo_next_cap) {
        corner_memo *v = realloc(w->memo_next, w->key_n * sizeof *v);
        if (v == NULL)
            return 0;
        w->memo_next = v;
        w->memo_next_cap = w->key_n;
    }
    w->memo_next_n = 0;
    size_t mc = 0;
    for (size_t k = 0; k < w->key_n; ++k) {
        const corner_key *q = &w->key[k];
        if (k > 0 && q->kind == q[-1].kind && q->a == q[-1].a && q->b == q[-1].b)
            continue; /* asked already */
        if (q->kind < 2 && w->solid && w->inner[q->kind][q->a] == 2)
            continue; /* a solid's vertex inside the other */
        if (have && (q->kind != best_q->kind || q->a != best_q->a)) {
            if (!all_push(w, &best, -1, best_f[0], best_f[1]))
                return 0;
            have = 0;
        }
        while (mc < w->memo_n && corner_key_before(&w->memo[mc].q, q))
            ++mc;
        size_t at = mc; /* keys equal in that order but for k, l: a triangle with a corner twice */
        while (at < w->memo_n && !corner_key_before(q, &w->memo[at].q) && !corner_key_same(&w->memo[at].q, q))
            ++at;
        corner_memo *e = &w->memo_next[w->memo_next_n++];
        if (at < w->memo_n && !corner_key_before(q, &w->memo[at].q))
            *e = w->memo[at];
        else {
            e->q = *q;
            e->ok = corner_ask(s, w, c[0].i, c[0].j, q, margin, &e->got, e->f);
        }
        if (!e->ok)
            continue;
        const ttd_scene_contact got = e->got;
        const uint8_t f[2] = {e->f[0], e->f[1]};
        if (q->kind == 2) {
            if (!all_push(w, &got, -1, f[0], f[1]))
                return 0;
        } else if (!have || got.distance < best.distance) { /* keys come in the order of the other triangle */
            best = got;
            best_f[0] = f[0];
            best_f[1] = f[1];
            best_q = q;
            have = 1;
        }
    }
    /* this pass's answers are the next pass's memo (a later pass asks a superset of the questions,
     * each for the same or smaller triangles) */
    corner_memo *t = w->memo;
    const size_t tc = w->memo_cap;
    w->memo = w->memo_next;
    w->memo_cap = w->memo_next_cap;
    w->memo_n = w->memo_next_n;
    w->memo_next = t;
    w->memo_next_cap = tc;
    return !have || all_push(w, &best, -1, best_f[0], best_f[1]);
}
