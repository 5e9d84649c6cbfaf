/* SPDX-License-Identifier: MIT */
/* Section 5c: a manifold point's key, the features of both bodies its two points lie
 * on, named by the body (place, edge, flat piece) rather than the triangle. Part of a body pair's manifold
 * (scene/manifold_impl.h, which includes it once per precision; docs/scenes.md, section 5). */

/* ---- 5c: persistent keys --------------------------------------------------------------------- */

/* A feature's 30-bit number: its own where it fits, else folded (a key then stands for several
 * features of a mesh of over 2^30 places, edges or pieces: keys may collide, never change). */
static uint32_t key_fold(uint64_t x)
{
    if (x < ((uint64_t)1 << 30))
        return (uint32_t)x;
    x = (x ^ (x >> 31)) * 0x9e3779b97f4a7c15ULL;
    return (uint32_t)(x >> 34);
}

/* The feature of a body that a point on triangle t lies on (bits: the exact method's feature
 * bits of t), as 32 bits: 2 bits of kind (KEY_VERTEX, KEY_EDGE, KEY_FACE) above 30 of number.
 * A feature is named by what the mesh's edge information says about its place on the body, not
 * by the triangle: a vertex by its place (mesh/edges.h: the same for every triangle around it);
 * an edge by the smaller of its two triangles and its index there; a face by its flat piece. A
 * vertex inside a flat part, or an edge between coplanar triangles, is of the face: a point
 * sliding over a triangulated face keeps its key whichever triangle it crosses. */
enum { KEY_VERTEX = 0, KEY_EDGE = 1, KEY_FACE = 2 };
static uint32_t feature_key(const struct ttd_mesh *m, const ttd_mesh_edges *E, uint32_t t, unsigned bits)
{
    bits &= 7;
    if (t == UINT32_MAX || bits == 0)
        return (uint32_t)3 << 30; /* none (not reached: every point lies on a triangle) */
    const uint32_t face = (uint32_t)KEY_FACE << 30 | key_fold(E->piece[t]);
    if (bits == 1 || bits == 2 || bits == 4) {
        const int k = bits == 1 ? 0 : bits == 2 ? 1 : 2;
        if (ttd_vertex_class(E, t, k) == TTD_VERTEX_FLAT)
            return face;
        return (uint32_t)KEY_VERTEX << 30 | key_fold(E->weld[m->tris[3 * (size_t)t + (size_t)k]]);
    }
    if (bits == 7)
        return face;
    const int k = bits == 3 ? 0 : bits == 6 ? 1 : 2; /* edge k joins corners k and k + 1 */
    if (ttd_edge_class(E, t, k) == TTD_EDGE_FLAT)
        return face;
    uint64_t id = 3 * (uint64_t)t + (uint64_t)k;
    const uint32_t u = E->across[3 * (size_t)t + (size_t)k];
    if (u != TTD_NO_TRIANGLE && u < t) /* the same edge named from the other side */
        for (int l = 0; l < 3; ++l)
            if (E->across[3 * (size_t)u + (size_t)l] == t) {
                id = 3 * (uint64_t)u + (uint64_t)l;
                break;
            }
    return (uint32_t)KEY_EDGE << 30 | key_fold(id);
}

/* Point x's key (section 5c): body i's feature in the high half, body j's in the low. A contact
 * whose features are not known (a triangle pair's closest points) asks its pair again. */
static uint64_t point_key(const struct ttd_scene *s, const manifold_rec *x)
{
    unsigned fi = x->feat[0], fj = x->feat[1];
    if (fi == 0 || fj == 0) {
        real a[9], b[9];
        ttd_result r;
        world_triangle(s, x->c.i, x->c.tri_i, a);
        world_triangle(s, x->c.j, x->c.tri_j, b);
        TTD_EXACT_PAIR(a, b, &r);
        fi = r.feature_p;
        fj = r.feature_q;
    }
    const struct ttd_mesh *mi = s->body[x->c.i].mesh, *mj = s->body[x->c.j].mesh;
    return (uint64_t)feature_key(mi, ttd_mesh_edges_made(mi), x->c.tri_i, fi) << 32 |
           feature_key(mj, ttd_mesh_edges_made(mj), x->c.tri_j, fj);
}
