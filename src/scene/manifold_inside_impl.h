/* SPDX-License-Identifier: MIT */
/* Section 5b: the vertices of each solid of a pair inside the other, found from the
 * contacts' triangles outward, each at minus its exact distance to the other's surface. Part of a body pair's manifold
 * (scene/manifold_impl.h, which includes it once per precision; docs/scenes.md, section 5). */

/* ---- 5b: the points of solids inside each other --------------------------------------------- */

/* Room for side's flags over nw places and a queue of nw places. */
static int inner_reserve(manifold_work *w, int side, size_t nw)
{
    if (nw + 1 > w->inner_cap[side]) {
        unsigned char *f = realloc(w->inner[side], nw + 1);
        if (f == NULL)
            return 0;
        w->inner[side] = f;
        w->inner_cap[side] = nw + 1;
    }
    if (nw + 1 > w->queue_cap) {
        uint32_t *q = realloc(w->queue, (nw + 1) * sizeof *q);
        if (q == NULL)
            return 0;
        w->queue = q;
        w->queue_cap = nw + 1;
    }
    if (nw + 1 > w->pts_cap) {
        real *p = realloc(w->pts, 3 * (nw + 1) * sizeof *p);
        if (p != NULL)
            w->pts = p;
        uint32_t *pl = p != NULL ? realloc(w->pts_place, (nw + 1) * sizeof *pl) : NULL;
        if (pl != NULL)
            w->pts_place = pl;
        ttd_point_result *r = pl != NULL ? realloc(w->res, (nw + 1) * sizeof *r) : NULL;
        if (r == NULL)
            return 0;
        w->res = r;
        w->pts_cap = nw + 1;
    }
    return 1;
}

/* The vertex at place pl of a mesh (edge information E, triangles tris): a corner of the first
 * triangle around it, that triangle into *tri. */
static uint32_t place_vertex(const ttd_mesh_edges *E, const uint32_t *tris, uint32_t pl, uint32_t *tri)
{
    const uint32_t t = E->ring[E->ring_start[pl]];
    *tri = t;
    for (int k = 0; k < 3; ++k)
        if (E->weld[tris[3 * (size_t)t + (size_t)k]] == pl)
            return tris[3 * (size_t)t + (size_t)k];
    return tris[3 * (size_t)t];
}

/* The vertices of one body of solid pair (i, j) inside the other (side 0: body i's inside j; 1:
 * j's inside i), each with its closest point on the other's surface at a negative distance,
 * into w->all. nested: the body lies wholly inside the other (every vertex); else the vertices
 * of its triangles in the contacts c[0..n) and, from those found inside, their neighbours, as
 * long as they are inside: the part of a surface inside the other solid is bounded where the
 * surfaces cross, at triangles that are contacts. Inside: the winding number of the other body
 * about the vertex moved into its frame as the point queries move points; the distance: the
 * point query's exact distance there (the closest point moved back into the world). */
static int solid_side(const struct ttd_scene *s, const ttd_engine_config *cfg, uint32_t i, uint32_t j, int side,
                      const ttd_scene_contact *c, size_t n, int nested, manifold_work *w)
{
    const uint32_t b = side ? j : i, a = side ? i : j;
    const struct ttd_mesh *mb = s->body[b].mesh;
    const ttd_mesh_edges *E = ttd_mesh_edges_made(mb);
    if (!inner_reserve(w, side, E->nw))
        return 0;
    unsigned char *state = w->inner[side];
    memset(state, 0, E->nw);
    size_t nq = 0, nin = 0;
    if (nested) {
        for (uint32_t pl = 0; pl < E->nw; ++pl)
            if (E->ring_start[pl] < E->ring_start[pl + 1]) {
                state[pl] = 2;
                w->queue[nin++] = pl;
            }
    } else {
        for (size_t k = 0; k < n; ++k) {
            const uint32_t t = side ? c[k].tri_j : c[k].tri_i;
            for (int v = 0; v < 3; ++v) {
                const uint32_t pl = E->weld[mb->tris[3 * (size_t)t + (size_t)v]];
                if (state[pl] == 0) {
                    state[pl] = 1;
                    w->queue[nq++] = pl;
                }
            }
        }
        /* breadth first over the places asked: those inside go to the front of the queue */
        for (size_t head = 0; head < nq; ++head) {
            const uint32_t pl = w->queue[head];
            uint32_t tri;
            real x[3];
            body_vertex(s, b, place_vertex(E, mb->tris, pl, &tri), x);
            if (!body_inside(s, a, x))
                continue;
            state[pl] = 2;
            for (uint32_t r = E->ring_start[pl]; r < E->ring_start[pl + 1]; ++r)
                for (int v = 0; v < 3; ++v) {
                    const uint32_t q = E->weld[mb->tris[3 * (size_t)E->ring[r] + (size_t)v]];
                    if (state[q] == 0) {
                        state[q] = 1;
                        w->queue[nq++] = q;
                    }
                }
        }
        for (size_t k = 0; k < nq; ++k)
            if (state[w->queue[k]] == 2)
                w->queue[nin++] = w->queue[k];
    }
    if (nin == 0)
        return 1;
    const real *P = body_pose(s, a);
    for (size_t k = 0; k < nin; ++k) {
        uint32_t tri;
        real x[3];
        body_vertex(s, b, place_vertex(E, mb->tris, w->queue[k], &tri), x);
        TTD_POINT_INTO(P, x, w->pts + 3 * k)
        w->pts_place[k] = tri;
    }
    if (TTD_POINTS_CLOSEST(cfg, s->body[a].mesh, nin, w->pts, (real)INFINITY, w->res) != TTD_OK)
        return 0;
    for (size_t k = 0; k < nin; ++k) {
        const ttd_point_result *r = &w->res[k];
        if (!(r->distance > 0))
            continue; /* on the surface: a contact */
        uint32_t tri;
        real x[3], y[3] = {r->point[0], r->point[1], r->point[2]};
        const uint32_t v = place_vertex(E, mb->tris, w->queue[k], &tri);
        body_vertex(s, b, v, x);
        TTD_POINT_BACK(real, P, y);
        ttd_scene_contact rec = {i, j, side ? r->triangle : tri, side ? tri : r->triangle, -r->distance, {0, 0, 0}, {0, 0, 0}};
        memcpy(rec.p, side ? y : x, sizeof rec.p);
        memcpy(rec.q, side ? x : y, sizeof rec.q);
        unsigned fv = 0; /* the vertex's corner of tri */
        for (int t = 0; t < 3; ++t)
            fv |= mb->tris[3 * (size_t)tri + (size_t)t] == v ? 1u << t : 0;
        if (!all_push(w, &rec, side, side ? r->feature : fv, side ? fv : r->feature))
            return 0;
    }
    return 1;
}

/* ---- 5b: the deepest points of edges inside the other solid ------------------------------------ */

/* Where two solids cross with no vertex of either inside the other (rods crossing at right
 * angles, sunk into each other), their vertices say nothing of the depth: the edges of each that
 * pass through the other do. Each edge of a contact's triangle that crosses the other body's
 * triangle of a contact at d = 0 is cut at its crossings; each piece whose midpoint is inside
 * the other body and lies between two crossings (a piece ending at a vertex inside has that
 * vertex's point) contributes its deepest point, the point of the piece farthest from the other's
 * surface (the point query's exact distance; found by EDGE_SAMPLES samples and a golden-section
 * search of EDGE_STEPS steps about the best, which is the maximum wherever the distance along
 * the piece has one peak: always inside a convex body), at minus that distance.
 * Where some vertex is inside (its depth vdepth >= 0), a vertex just inside can stand beside an
 * edge crossing far deeper (a tetrahedron's edge sunk into a face, a corner of the other body
 * grazing it): then every piece with a crossing at one end or both (those ending at a vertex
 * inside too) is searched, and its deepest point kept only where deeper than vdepth, so that the
 * vertices' points stay the manifold's wherever they measure the depth. A piece's depth is at
 * most its length from a crossing end (half its length between two): shorter pieces are not
 * searched. */
#define EDGE_SAMPLES 8
#define EDGE_STEPS 64

/* An edge of body b to cut: its places (smaller first), the triangle and index that name it. */
typedef struct inside_edge {
    uint64_t key;  /* places, smaller << 32 | larger */
    uint32_t tri;  /* a triangle of b with the edge */
    int k;         /* its edge k: corners k and k + 1 */
    double t;      /* a crossing's parameter from the smaller place's end, or -1 for none */
} inside_edge;

static int inside_edge_cmp(const void *x, const void *y)
{
    const inside_edge *a = x, *b = y;
    if (a->key != b->key)
        return a->key < b->key ? -1 : 1;
    return (a->t > b->t) - (a->t < b->t);
}

/* The parameter t in (0, 1) where segment p + t (q - p) crosses triangle x (3 points), or -1. */
static double segment_crossing(const double p[3], const double q[3], double x[3][3])
{
    double e1[3], e2[3], d[3], h[3], sv[3], qv[3];
    for (int r = 0; r < 3; ++r) {
        e1[r] = x[1][r] - x[0][r];
        e2[r] = x[2][r] - x[0][r];
        d[r] = q[r] - p[r];
        sv[r] = p[r] - x[0][r];
    }
    cross3d(d, e2, h);
    const double a = dot3d(e1, h);
    if (!(fabs(a) > 0))
        return -1; /* parallel to the plane: the other crossings bound the piece */
    const double f = 1 / a, u = f * dot3d(sv, h);
    if (!(u >= 0 && u <= 1))
        return -1;
    cross3d(sv, e1, qv);
    const double v = f * dot3d(d, qv);
    if (!(v >= 0 && u + v <= 1))
        return -1;
    const double t = f * dot3d(e2, qv);
    return t > 0 && t < 1 ? t : -1;
}

/* Body b's world point at parameter t of the segment from x0 to x1. */
static void edge_point(const real x0[3], const real x1[3], double t, real out[3])
{
    for (int r = 0; r < 3; ++r)
        out[r] = (real)((double)x0[r] + t * ((double)x1[r] - (double)x0[r]));
}

/* The exact distance from world point x to body a's surface, its closest point into *res. 0 on
 * failure (out of memory). */
static int edge_depth(const struct ttd_scene *s, const ttd_engine_config *cfg, uint32_t a, const real x[3],
                      ttd_point_result *res)
{
    real y[3];
    TTD_POINT_INTO(body_pose(s, a), x, y)
    return TTD_POINTS_CLOSEST(cfg, s->body[a].mesh, 1, y, (real)INFINITY, res) == TTD_OK;
}

static int solid_edges(const struct ttd_scene *s, const ttd_engine_config *cfg, uint32_t i, uint32_t j, int side,
                       const ttd_scene_contact *c, size_t n, double vdepth, manifold_work *w)
{
    const uint32_t b = side ? j : i, a = side ? i : j;
    const struct ttd_mesh *mb = s->body[b].mesh;
    const ttd_mesh_edges *E = ttd_mesh_edges_made(mb);
    inside_edge *v = NULL;
    size_t nv = 0, cap = 0;
    int ok = 1;
    for (size_t q = 0; q < n && ok; ++q) {
        if (c[q].distance != 0)
            continue;
        const uint32_t t = side ? c[q].tri_j : c[q].tri_i, u = side ? c[q].tri_i : c[q].tri_j;
        real xt[9], xu[9];
        world_triangle(s, b, t, xt);
        world_triangle(s, a, u, xu);
        double X[3][3];
        for (int k = 0; k < 9; ++k)
            X[k / 3][k % 3] = (double)xu[k];
        for (int k = 0; k < 3 && ok; ++k) {
            const int k1 = (k + 1) % 3;
            const uint64_t pa = E->weld[mb->tris[3 * (size_t)t + (size_t)k]], pb = E->weld[mb->tris[3 * (size_t)t + (size_t)k1]];
            if (pa == pb)
                continue;
            /* from the smaller place's end, so that both triangles of the edge give one parameter */
            const int flip = pa > pb;
            double P[3], Q[3];
            for (int r = 0; r < 3; ++r) {
                P[r] = (double)xt[3 * (flip ? k1 : k) + r];
                Q[r] = (double)xt[3 * (flip ? k : k1) + r];
            }
            const double tc = segment_crossing(P, Q, X);
            if (nv + 2 > cap) {
                cap = cap ? 2 * cap : 64;
                inside_edge *g = realloc(v, cap * sizeof *v);
                if (g == NULL) {
                    ok = 0;
                    break;
                }
                v = g;
            }
            const uint64_t key = flip ? pb << 32 | pa : pa << 32 | pb;
            v[nv++] = (inside_edge){key, t, k, -1};
            if (tc > 0)
                v[nv++] = (inside_edge){key, t, k, tc};
        }
    }
    if (!ok) {
        free(v);
        return 0;
    }
    if (nv > 1)
        qsort(v, nv, sizeof *v, inside_edge_cmp);
    static const double golden = 0.61803398874989484820;
    for (size_t e = 0; e < nv && ok;) {
        size_t f = e;
        while (f < nv && v[f].key == v[e].key)
            ++f;
        /* the edge's ends from the triangle that names it first; its cuts, each once */
        const uint32_t t = v[e].tri;
        const int k = v[e].k, k1 = (k + 1) % 3;
        const uint32_t va = mb->tris[3 * (size_t)t + (size_t)k], vb = mb->tris[3 * (size_t)t + (size_t)k1];
        const int flip = E->weld[va] > E->weld[vb];
        real x0[3], x1[3];
        body_vertex(s, b, flip ? vb : va, x0);
        body_vertex(s, b, flip ? va : vb, x1);
        double cuts[66];
        size_t nc = 0;
        cuts[nc++] = 0;
        for (size_t g = e; g < f && nc < 65; ++g)
            if (v[g].t > 0 && v[g].t > cuts[nc - 1])
                cuts[nc++] = v[g].t;
        cuts[nc++] = 1;
        for (size_t piece = 0; piece + 1 < nc && ok; ++piece) {
            /* with no vertex inside, the pieces between two crossings; with one inside, those
             * ending at a vertex too (that vertex has its point from solid_side), their points
             * kept only where deeper than every vertex's, which they would otherwise crowd out
             * of the merge where the vertices measure the depth */
            const double lo = cuts[piece], hi = cuts[piece + 1];
            const int ends = (piece == 0) + (piece + 2 == nc); /* ends at the edge's vertices: 0, 1 or 2 */
            if (!(hi - lo > 0x1p-30) || (vdepth < 0 ? ends != 0 : ends == 2))
                continue;
            if (vdepth >= 0) { /* 1-Lipschitz from the crossing ends: no deeper than this */
                double len = 0;
                for (int r = 0; r < 3; ++r)
                    len += ((double)x1[r] - (double)x0[r]) * ((double)x1[r] - (double)x0[r]);
                if (!(sqrt(len) * (hi - lo) * (ends ? 1.0 : 0.5) > vdepth))
                    continue;
            }
            real x[3];
            edge_point(x0, x1, 0.5 * (lo + hi), x);
            if (!body_inside(s, a, x))
                continue;
            /* samples, then a golden-section search about the best */
            ttd_point_result r, best_r = {0};
            double best_t = 0.5 * (lo + hi), best = -1;
            for (int m = 0; m < EDGE_SAMPLES && ok; ++m) {
                const double tt = lo + (hi - lo) * (m + 0.5) / EDGE_SAMPLES;
                edge_point(x0, x1, tt, x);
                ok = edge_depth(s, cfg, a, x, &r);
                if (ok && (double)r.distance > best) {
                    best = (double)r.distance;
                    best_t = tt;
                    best_r = r;
                }
            }
            double L = fmax(lo, best_t - (hi - lo) / EDGE_SAMPLES), H = fmin(hi, best_t + (hi - lo) / EDGE_SAMPLES);
            for (int step = 0; step < EDGE_STEPS && ok; ++step) {
                const double m1 = H - golden * (H - L), m2 = L + golden * (H - L);
                ttd_point_result r1, r2;
                edge_point(x0, x1, m1, x);
                ok = edge_depth(s, cfg, a, x, &r1);
                edge_point(x0, x1, m2, x);
                ok = ok && edge_depth(s, cfg, a, x, &r2);
                if (!ok)
                    break;
                if ((double)r1.distance > best) {
                    best = (double)r1.distance;
                    best_t = m1;
                    best_r = r1;
                }
                if ((double)r2.distance > best) {
                    best = (double)r2.distance;
                    best_t = m2;
                    best_r = r2;
                }
                if ((double)r1.distance >= (double)r2.distance)
                    H = m2;
                else
                    L = m1;
            }
            if (!ok || !(best > 0) || !(best > vdepth))
                continue;
            real px[3], y[3] = {best_r.point[0], best_r.point[1], best_r.point[2]};
            edge_point(x0, x1, best_t, px);
            TTD_POINT_BACK(real, body_pose(s, a), y);
            ttd_scene_contact rec = {i, j, side ? best_r.triangle : t, side ? t : best_r.triangle, -best_r.distance,
                                     {0, 0, 0}, {0, 0, 0}};
            memcpy(rec.p, side ? y : px, sizeof rec.p);
            memcpy(rec.q, side ? px : y, sizeof rec.q);
            const unsigned fe = 1u << k | 1u << k1; /* the edge of t */
            ok = all_push(w, &rec, side, side ? best_r.feature : fe, side ? fe : best_r.feature);
        }
        e = f;
    }
    free(v);
    return ok;
}
