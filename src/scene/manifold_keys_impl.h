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

/* Point x's key (section 5c) from the features fi of tri_i and fj of tri_j: body i's feature in
 * the high half, body j's in the low. */
static uint64_t features_key(const struct ttd_scene *s, const manifold_rec *x, unsigned fi, unsigned fj)
{
    const struct ttd_mesh *mi = s->body[x->c.i].mesh, *mj = s->body[x->c.j].mesh;
    return (uint64_t)feature_key(mi, ttd_mesh_edges_made(mi), x->c.tri_i, fi) << 32 |
           feature_key(mj, ttd_mesh_edges_made(mj), x->c.tri_j, fj);
}

/* The keys' triangle pairs asked through the ISA row's exact kernel (1), or one exact_pair call
 * each (0: only in a test's build, tests/CMakeLists.txt, ttd_manifold_no_screen, whose answers
 * must be the same bits). */
#ifndef MANIFOLD_KEY_LANES
#define MANIFOLD_KEY_LANES 1
#endif
#define KEY_BLOCK 16

/* The keys of the ns points pt chosen (pt[k] from rc[kept[sel[k]]]). A contact whose features are
 * not known (a triangle pair's closest points) asks its pair again: in blocks through the exact
 * kernel of the query's ISA, whose whole results (features too) are the scalar row's bits on
 * every row (tests/test_isa_kernels.c, rows_exact_bits_on_families), so exact_pair's features. */
static void points_keys(const struct ttd_scene *s, const ttd_engine_config *cfg, const manifold_rec *rc,
                        const size_t *kept, const size_t *sel, ttd_scene_point *pt, size_t ns)
{
    real a[9 * KEY_BLOCK], b[9 * KEY_BLOCK];
    ttd_result r[KEY_BLOCK];
    size_t at[KEY_BLOCK];
    size_t m = 0;
    const ttd_exact_kernel_fn kern = MANIFOLD_KEY_LANES ? TTD_EXACT_KERNEL(cfg->isa) : NULL;
    for (size_t k = 0; k <= ns; ++k) {
        if (k < ns) {
            const manifold_rec *x = &rc[kept[sel[k]]];
            unsigned fi = x->feat[0], fj = x->feat[1];
            if (fi == 0 || fj == 0) {
                world_triangle(s, x->c.i, x->c.tri_i, a + 9 * m);
                world_triangle(s, x->c.j, x->c.tri_j, b + 9 * m);
                if (kern != NULL) {
                    at[m++] = k;
                } else {
                    TTD_EXACT_PAIR(a, b, &r[0]);
                    fi = r[0].feature_p;
                    fj = r[0].feature_q;
                }
            }
            if ((fi != 0 && fj != 0) || kern == NULL)
                pt[k].key = features_key(s, x, fi, fj);
        }
        if (m > 0 && (m == KEY_BLOCK || k == ns)) {
            const ttd_kernel_out o = {NULL, NULL, r};
            kern(m, a, b, &cfg->params, (real)INFINITY, &o);
            for (size_t q = 0; q < m; ++q)
                pt[at[q]].key = features_key(s, &rc[kept[sel[at[q]]]], r[q].feature_p, r[q].feature_q);
            m = 0;
        }
    }
}
