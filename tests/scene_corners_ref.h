/* SPDX-License-Identifier: MIT */
/* The corners a manifold adds to a body pair's contacts (docs/scenes.md, section 5, step 0), by
 * brute force, for tests/test_scene.c and tests/test_scene_contacts.c. Nothing here reads the
 * library's edge information: each mesh's shape is found by comparing every triangle with every
 * other (places by equal coordinates, the triangle across each edge, flat edges and vertices by
 * the angle between unit normals), and no cheap test rules a point out before the exact method
 * is asked (the library's plane test must never drop a point this finds).
 *
 * For each contact (triangle a of body i, b of body j, within the margin) whose triangles lie face
 * on face (both have a normal, their world normals opposite within CORNER_REF_ANGLE):
 *   - each vertex of a whose place is not inside a flat part: the exact method on the vertex (as
 *     a triangle of three equal vertices) and b; within the margin, a point (the vertex, its
 *     closest point on b); the same for b's vertices against a;
 *   - each edge of a not between coplanar triangles, and each such edge of b: the exact method
 *     on the two edges (each from its smaller end, the smaller first); a point where their
 *     closest points lie inside both edges, within the margin.
 * The same question (a vertex's place and the other triangle; two edges' places) is kept once,
 * with the smallest triangles that ask it; each vertex once, at its smallest distance (ties: the
 * smaller triangle of the other body). Touching points (d = 0) put both points at the vertex or
 * at the first edge's point. */
#ifndef TTD_TESTS_SCENE_CORNERS_REF_H
#define TTD_TESTS_SCENE_CORNERS_REF_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <ttd/ttd.h>

#define CORNER_REF_FLAT_ANGLE 1e-3 /* mesh/edges.h's TTD_FLAT_ANGLE, as documented */
#define CORNER_REF_ANGLE 0.1       /* face on face (docs/scenes.md, section 5, step 0) */

/* A mesh's shape around each corner and edge of each triangle. */
typedef struct corner_mesh {
    size_t nt;
    uint32_t *place;            /* 3 nt: the smallest corner index 3 t + k at the same point */
    uint32_t *first;            /* 3 nt: the smallest triangle with a corner at that point */
    unsigned char *flat_vertex; /* 3 nt */
    unsigned char *flat_edge;   /* 3 nt: edge k of t, from corner k to k + 1 */
    uint32_t *across;           /* 3 nt: the triangle across a convex or concave edge, else UINT32_MAX */
    unsigned char *has_normal;  /* nt */
    unsigned char *planar;      /* nt: the triangle's flat piece (triangles joined by flat edges) is
                                 * planar: every vertex of it within 2^-36 of the mesh's scale (the
                                 * power of two at or above its largest coordinate) of the plane of
                                 * its largest triangle */
} corner_mesh;

static void corner_mesh_free(corner_mesh *m)
{
    free(m->place);
    free(m->first);
    free(m->flat_vertex);
    free(m->flat_edge);
    free(m->across);
    free(m->has_normal);
    free(m->planar);
    memset(m, 0, sizeof *m);
}

/* The unit normal of triangle x (9 coordinates) at unit scale; 0 when |e1 x e2| is within 64
 * eps of |e1| |e2| (mesh/edges.c's rule). */
static int corner_ref_normal(const double *x, double n[3])
{
    double e1[3], e2[3], m = 0;
    for (int r = 0; r < 3; ++r) {
        e1[r] = x[3 + r] - x[r];
        e2[r] = x[6 + r] - x[r];
        m = fmax(m, fmax(fabs(e1[r]), fabs(e2[r])));
    }
    if (!(m > 0))
        return 0;
    for (int r = 0; r < 3; ++r) {
        e1[r] /= m;
        e2[r] /= m;
    }
    const double c[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    const double l = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    const double l1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]), l2 = sqrt(e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]);
    if (!(l > 64 * 2.220446049250313e-16 * l1 * l2))
        return 0;
    for (int r = 0; r < 3; ++r)
        n[r] = c[r] / l;
    return 1;
}

/* The shape of the mesh of triangles tris[3 nt] over verts (its own coordinates, the values its
 * precision holds). 0 out of memory. */
static int corner_mesh_make(const double *verts, const uint32_t *tris, size_t nt, corner_mesh *m)
{
    memset(m, 0, sizeof *m);
    m->nt = nt;
    m->place = malloc(3 * nt * sizeof *m->place);
    m->first = malloc(3 * nt * sizeof *m->first);
    m->flat_vertex = malloc(3 * nt);
    m->flat_edge = malloc(3 * nt);
    m->across = malloc(3 * nt * sizeof *m->across);
    double *n = malloc(3 * nt * sizeof *n), *x = malloc(9 * nt * sizeof *x);
    unsigned char *has = malloc(nt);
    if (!m->place || !m->first || !m->flat_vertex || !m->flat_edge || !m->across || !n || !x || !has) {
        free(n);
        free(x);
        free(has);
        corner_mesh_free(m);
        return 0;
    }
    for (size_t t = 0; t < nt; ++t)
        for (int k = 0; k < 3; ++k)
            memcpy(x + 9 * t + 3 * k, verts + 3 * (size_t)tris[3 * t + (size_t)k], 3 * sizeof *x);
    for (size_t c = 0; c < 3 * nt; ++c) {
        size_t e = 0;
        while (!(x[3 * e] == x[3 * c] && x[3 * e + 1] == x[3 * c + 1] && x[3 * e + 2] == x[3 * c + 2]))
            ++e;
        m->place[c] = (uint32_t)e;
    }
    for (size_t c = 0; c < 3 * nt; ++c) { /* the first triangle with a corner there */
        size_t e = 0;
        while (m->place[e] != m->place[c])
            ++e;
        m->first[c] = (uint32_t)(e / 3);
    }
    for (size_t t = 0; t < nt; ++t) {
        const uint32_t *pl = m->place + 3 * t;
        has[t] = pl[0] != pl[1] && pl[1] != pl[2] && pl[0] != pl[2] && corner_ref_normal(x + 9 * t, n + 3 * t);
    }
    const double cos_flat = cos(CORNER_REF_FLAT_ANGLE);
    int *cls = malloc(3 * nt * sizeof *cls); /* 0 flat, 1 real, 2 open */
    uint32_t *flat_to = malloc(3 * nt * sizeof *flat_to), *piece = malloc(nt * sizeof *piece);
    m->planar = malloc(nt);
    if (cls == NULL || flat_to == NULL || piece == NULL || m->planar == NULL) {
        free(cls);
        free(flat_to);
        free(piece);
        free(n);
        free(x);
        free(has);
        corner_mesh_free(m);
        return 0;
    }
    for (size_t t = 0; t < nt; ++t)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = m->place[3 * t + (size_t)k], b = m->place[3 * t + (size_t)((k + 1) % 3)];
            size_t count = 0, found = 0;
            int reversed = 0;
            for (size_t u = 0; has[t] && u < nt; ++u) {
                int ia = -1, ib = -1;
                for (int q = 0; q < 3 && u != t; ++q) {
                    ia = m->place[3 * u + (size_t)q] == a ? q : ia;
                    ib = m->place[3 * u + (size_t)q] == b ? q : ib;
                }
                if (ia < 0 || ib < 0)
                    continue;
                ++count;
                found = u;
                reversed = (ib + 1) % 3 == ia;
            }
            int c = 2;
            m->across[3 * t + (size_t)k] = UINT32_MAX;
            flat_to[3 * t + (size_t)k] = UINT32_MAX;
            if (count == 1 && reversed && has[found]) {
                const double *nt_ = n + 3 * t, *nu = n + 3 * found;
                double side = 0;
                for (int q = 0; q < 3; ++q) {
                    const uint32_t pq = m->place[3 * found + (size_t)q];
                    if (pq != a && pq != b)
                        for (int r = 0; r < 3; ++r)
                            side += (x[9 * found + 3 * (size_t)q + (size_t)r] - x[9 * t + 3 * (size_t)k + (size_t)r]) * nt_[r];
                }
                if (nt_[0] * nu[0] + nt_[1] * nu[1] + nt_[2] * nu[2] >= cos_flat)
                    c = 0;
                else if (side != 0)
                    c = 1;
                if (c == 1)
                    m->across[3 * t + (size_t)k] = (uint32_t)found;
                if (c == 0)
                    flat_to[3 * t + (size_t)k] = (uint32_t)found;
            }
            cls[3 * t + (size_t)k] = c;
            m->flat_edge[3 * t + (size_t)k] = c == 0;
        }
    for (size_t c = 0; c < 3 * nt; ++c) {
        /* flat: every triangle around the place has a normal within the flat angle of the first
         * one's, and every edge at the place is flat */
        int flat = 1;
        const size_t t0 = m->first[c];
        for (size_t u = 0; u < nt && flat; ++u)
            for (int q = 0; q < 3 && flat; ++q) {
                if (m->place[3 * u + (size_t)q] != m->place[c])
                    continue;
                flat = has[u] && has[t0] &&
                       n[3 * u] * n[3 * t0] + n[3 * u + 1] * n[3 * t0 + 1] + n[3 * u + 2] * n[3 * t0 + 2] >= cos_flat &&
                       cls[3 * u + (size_t)q] == 0 && cls[3 * u + (size_t)((q + 2) % 3)] == 0;
            }
        m->flat_vertex[c] = (unsigned char)flat;
    }
    /* pieces: the smallest triangle reached through flat edges, by relaxing until nothing moves */
    for (size_t t = 0; t < nt; ++t)
        piece[t] = (uint32_t)t;
    for (int moved = 1; moved;) {
        moved = 0;
        for (size_t c = 0; c < 3 * nt; ++c)
            if (flat_to[c] != UINT32_MAX && piece[flat_to[c]] != piece[c / 3]) {
                const uint32_t lo = piece[flat_to[c]] < piece[c / 3] ? piece[flat_to[c]] : piece[c / 3];
                piece[flat_to[c]] = piece[c / 3] = lo;
                moved = 1;
            }
    }
    /* planar pieces: the plane of the piece's largest triangle, every vertex of the piece near it */
    double top = 0;
    for (size_t c = 0; c < 9 * nt; ++c)
        top = fmax(top, fabs(x[c]));
    int es = 0;
    if (top > 0)
        frexp(top, &es);
    const double tol = ldexp(1.0, es - 36);
    for (size_t t = 0; t < nt; ++t) {
        size_t big = t;
        double best = -1;
        for (size_t u = 0; u < nt; ++u) {
            if (piece[u] != piece[t])
                continue;
            const double *y = x + 9 * u;
            const double e1[3] = {y[3] - y[0], y[4] - y[1], y[5] - y[2]}, e2[3] = {y[6] - y[0], y[7] - y[1], y[8] - y[2]};
            const double c3[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
            const double a = sqrt(c3[0] * c3[0] + c3[1] * c3[1] + c3[2] * c3[2]);
            if (a > best) {
                best = a;
                big = u;
            }
        }
        double pn[3];
        int planar = has[t] && corner_ref_normal(x + 9 * big, pn);
        for (size_t u = 0; u < nt && planar; ++u)
            for (int k = 0; k < 3 && piece[u] == piece[t]; ++k) {
                const double *y = x + 9 * u + 3 * k, *o = x + 9 * big;
                const double h = pn[0] * (y[0] - o[0]) + pn[1] * (y[1] - o[1]) + pn[2] * (y[2] - o[2]);
                planar &= has[u] && fabs(h) <= tol;
            }
        m->planar[t] = (unsigned char)planar;
    }
    free(cls);
    free(flat_to);
    free(piece);
    free(n);
    free(x);
    m->has_normal = has;
    return 1;
}

/* Which of a body pair's n contacts (triangles ti[k] of body i, tj[k] of body j, distance d[k];
 * mi, mj their shapes, wi, wj their world triangles) are of flat contact (docs/scenes.md,
 * section 5, step 0): face on face (as corner_refs tests it) with both triangles' pieces planar,
 * none when one such contact has distance 0. Their region's corners stand for them: they are not
 * points. Into flat[0..n); returns how many. For pairs of surfaces (a solid's pairs keep every
 * contact; the callers' scenes have no solids). */
static size_t corner_ref_flat(const corner_mesh *mi, const double *wi, const corner_mesh *mj, const double *wj, size_t n,
                              const uint32_t *ti, const uint32_t *tj, const double *d, unsigned char *flat)
{
    size_t count = 0;
    int touching = 0;
    for (size_t k = 0; k < n; ++k) {
        double na[3], nb[3];
        flat[k] = mi->has_normal[ti[k]] && mj->has_normal[tj[k]] && corner_ref_normal(wi + 9 * (size_t)ti[k], na) &&
                  corner_ref_normal(wj + 9 * (size_t)tj[k], nb) &&
                  na[0] * nb[0] + na[1] * nb[1] + na[2] * nb[2] <= -cos(CORNER_REF_ANGLE) && mi->planar[ti[k]] &&
                  mj->planar[tj[k]];
        count += flat[k];
        touching |= flat[k] && !(d[k] > 0);
    }
    if (touching) {
        memset(flat, 0, n);
        count = 0;
    }
    return count;
}

/* One point: triangles (ti of body i, tj of body j), distance d, p on i, q on j. */
typedef struct corner_rec {
    uint32_t ti, tj;
    double d, p[3], q[3];
} corner_rec;

/* The exact method on s and t (9 coordinates each, the values of precision `bytes`) on the
 * scalar row. */
static int corner_ref_exact(int bytes, const double s[9], const double t[9], double *d, double p[3], double q[3],
                            double *wp, double *wq)
{
    ttd_options opt = ttd_default_options();
    opt.isa = TTD_ISA_SCALAR;
    if (bytes == 8) {
        ttd_result_d r;
        if (ttd_distance_d(&opt, s, t, &r) != TTD_OK)
            return 0;
        *d = r.distance;
        memcpy(p, r.p, sizeof r.p);
        memcpy(q, r.q, sizeof r.q);
        *wp = r.bary_p[0];
        *wq = r.bary_q[0];
        return 1;
    }
    float sf[9], tf[9];
    for (int k = 0; k < 9; ++k) {
        sf[k] = (float)s[k];
        tf[k] = (float)t[k];
    }
    ttd_result_f r;
    if (ttd_distance_f(&opt, sf, tf, &r) != TTD_OK)
        return 0;
    *d = (double)r.distance;
    for (int k = 0; k < 3; ++k) {
        p[k] = (double)r.p[k];
        q[k] = (double)r.q[k];
    }
    *wp = (double)r.bary_p[0];
    *wq = (double)r.bary_q[0];
    return 1;
}

static int corner_ref_after(const double *x, const double *y)
{
    for (int r = 0; r < 3; ++r)
        if (x[r] != y[r])
            return x[r] > y[r];
    return 0;
}

/* Appends r to the growable array *v (n, cap). 0 out of memory. */
static int corner_rec_push(corner_rec **v, size_t *n, size_t *cap, const corner_rec *r)
{
    if (*n == *cap) {
        *cap = *cap ? 2 * *cap : 64;
        corner_rec *x = realloc(*v, *cap * sizeof *x);
        if (x == NULL)
            return 0;
        *v = x;
    }
    (*v)[(*n)++] = *r;
    return 1;
}

/* The corners of body pair (i, j): mi, mj their shapes; wi, wj their world triangles (9 per
 * triangle, the values of precision `bytes`); contact[a * nt_j + b] whether triangles a and b
 * are a contact within margin. Into *out (malloc'd); returns how many, or SIZE_MAX out of
 * memory. */
static size_t corner_refs(const corner_mesh *mi, const double *wi, const corner_mesh *mj, const double *wj,
                          const unsigned char *contact, double margin, int bytes, corner_rec **out)
{
    /* every question every face-on-face contact asks, with its answer; then each question once
     * (for its smallest triangles) and each vertex once */
    typedef struct ask {
        int kind;              /* 0 vertex of i, 1 vertex of j, 2 edges */
        uint32_t a[2], b[2];   /* vertex: its place, the other triangle; edges: their places, smaller first */
        int within;
        corner_rec r;
    } ask;
    ask *q = NULL;
    size_t nq = 0, capq = 0;
    corner_rec *v = NULL;
    size_t n = 0, cap = 0;
    const corner_mesh *m[2] = {mi, mj};
    const double *w[2] = {wi, wj};
    for (size_t a = 0; a < mi->nt; ++a)
        for (size_t b = 0; b < mj->nt; ++b) {
            double na[3], nb[3];
            if (!contact[a * mj->nt + b] || !mi->has_normal[a] || !mj->has_normal[b] ||
                !corner_ref_normal(wi + 9 * a, na) || !corner_ref_normal(wj + 9 * b, nb) ||
                !(na[0] * nb[0] + na[1] * nb[1] + na[2] * nb[2] <= -cos(CORNER_REF_ANGLE)))
                continue;
            const size_t t[2] = {a, b};
            for (int kind = 0; kind < 3; ++kind)
                for (int k = 0; k < 3; ++k)
                    for (int l = 0; l < (kind == 2 ? 3 : 1); ++l) {
                        ask x = {kind, {0, 0}, {0, 0}, 0, {(uint32_t)a, (uint32_t)b, 0, {0}, {0}}};
                        double d, p[3], qq[3], wp, wq;
                        if (kind < 2) {
                            const int side = kind;
                            const size_t c = 3 * t[side] + (size_t)k;
                            if (m[side]->flat_vertex[c])
                                continue;
                            const double *y = w[side] + 9 * t[side] + 3 * k;
                            const double pt[9] = {y[0], y[1], y[2], y[0], y[1], y[2], y[0], y[1], y[2]};
                            if (!corner_ref_exact(bytes, pt, w[!side] + 9 * t[!side], &d, p, qq, &wp, &wq))
                                goto fail;
                            x.a[0] = m[side]->place[c];
                            x.b[0] = (uint32_t)t[!side];
                            x.within = d <= margin;
                            x.r.d = d;
                            for (int r = 0; r < 3; ++r) {
                                const double other = d == 0 ? y[r] : qq[r];
                                x.r.p[r] = side ? other : y[r];
                                x.r.q[r] = side ? y[r] : other;
                            }
                        } else {
                            const size_t ca = 3 * a + (size_t)k, cb = 3 * b + (size_t)l;
                            const size_t ca1 = 3 * a + (size_t)((k + 1) % 3), cb1 = 3 * b + (size_t)((l + 1) % 3);
                            if (mi->flat_edge[ca] || mj->flat_edge[cb] || mi->place[ca] == mi->place[ca1] ||
                                mj->place[cb] == mj->place[cb1])
                                continue;
                            x.a[0] = mi->place[ca] < mi->place[ca1] ? mi->place[ca] : mi->place[ca1];
                            x.a[1] = mi->place[ca] < mi->place[ca1] ? mi->place[ca1] : mi->place[ca];
                            x.b[0] = mj->place[cb] < mj->place[cb1] ? mj->place[cb] : mj->place[cb1];
                            x.b[1] = mj->place[cb] < mj->place[cb1] ? mj->place[cb1] : mj->place[cb];
                            const double *a0 = wi + 9 * a + 3 * k, *a1 = wi + 9 * a + 3 * ((k + 1) % 3);
                            const double *b0 = wj + 9 * b + 3 * l, *b1 = wj + 9 * b + 3 * ((l + 1) % 3);
                            double seg[2][9];
                            const double *e[2][2] = {{a0, a1}, {b0, b1}};
                            for (int g = 0; g < 2; ++g) {
                                const int f = corner_ref_after(e[g][0], e[g][1]);
                                for (int r = 0; r < 3; ++r) {
                                    seg[g][r] = e[g][f][r];
                                    seg[g][3 + r] = seg[g][6 + r] = e[g][!f][r];
                                }
                            }
                            const int second = corner_ref_after(seg[0], seg[1]) ||
                                               (memcmp(seg[0], seg[1], 3 * sizeof(double)) == 0 &&
                                                corner_ref_after(seg[0] + 3, seg[1] + 3));
                            if (!corner_ref_exact(bytes, seg[second], seg[!second], &d, p, qq, &wp, &wq))
                                goto fail;
                            x.within = d <= margin && wp > 0 && wp < 1 && wq > 0 && wq < 1;
                            x.r.d = d;
                            for (int r = 0; r < 3; ++r) {
                                const double first = p[r], other = d == 0 ? p[r] : qq[r];
                                x.r.p[r] = second ? other : first;
                                x.r.q[r] = second ? first : other;
                            }
                        }
                        if (nq == capq) {
                            capq = capq ? 2 * capq : 64;
                            ask *y = realloc(q, capq * sizeof *y);
                            if (y == NULL)
                                goto fail;
                            q = y;
                        }
                        q[nq++] = x;
                    }
        }
    for (size_t x = 0; x < nq; ++x) {
        if (!q[x].within)
            continue;
        int keep = 1;
        for (size_t y = 0; y < nq && keep; ++y) {
            if (y == x || q[y].kind != q[x].kind || q[y].a[0] != q[x].a[0] || (q[x].kind == 2 && q[y].a[1] != q[x].a[1]))
                continue;
            const int same = q[y].b[0] == q[x].b[0] && q[y].b[1] == q[x].b[1];
            if (same) /* the same question: asked for the smallest triangles */
                keep = q[x].r.ti < q[y].r.ti || (q[x].r.ti == q[y].r.ti && q[x].r.tj < q[y].r.tj);
            else if (q[x].kind < 2 && q[y].within) /* one vertex, another triangle: the closest */
                keep = q[x].r.d < q[y].r.d || (q[x].r.d == q[y].r.d && q[x].b[0] < q[y].b[0]);
        }
        if (keep && !corner_rec_push(&v, &n, &cap, &q[x].r))
            goto fail;
    }
    free(q);
    *out = v;
    return n;
fail:
    free(q);
    free(v);
    *out = NULL;
    return SIZE_MAX;
}

#endif /* TTD_TESTS_SCENE_CORNERS_REF_H */
