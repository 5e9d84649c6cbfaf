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
