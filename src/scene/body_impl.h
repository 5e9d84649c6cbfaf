/* SPDX-License-Identifier: MIT */
/* What the scene's walk (scene/query_impl.h) and its manifold (scene/manifold_impl.h,
 * normal_impl.h) both read of the bodies, precision-generic: poses and world vertices, the
 * solids' inside test, the relative pose's defect, a caller's growable array, the contacts'
 * triangle order. Included once per precision, before either. */
#ifndef TTD_SCENE_BODY_IMPL_H
#define TTD_SCENE_BODY_IMPL_H

#ifdef TTD_SCENE_ALLOC_HOOK
/* Tests only (tests/CMakeLists.txt, test_scene_nomem): the scene queries' allocations through the
 * test's hooks, which can fail any one of them; the library's build has no hook. */
void *ttd_scene_hook_malloc(size_t n);
void *ttd_scene_hook_calloc(size_t n, size_t size);
void *ttd_scene_hook_realloc(void *p, size_t n);
#define malloc(n) ttd_scene_hook_malloc(n)
#define calloc(n, size) ttd_scene_hook_calloc(n, size)
#define realloc(p, n) ttd_scene_hook_realloc(p, n)
#endif

/* The pose of body id in the scene's precision. */
static const real *body_pose(const struct ttd_scene *s, uint32_t id)
{
#ifdef TTD_PRECISION_DOUBLE
    return s->body[id].pose;
#else
    return s->body[id].pose_f;
#endif
}

/* Vertex v of body id in the world, as the kernel computes it: ((r0 x + r1 y) + r2 z) + t per
 * coordinate, in the scene's precision. */
static void body_vertex(const struct ttd_scene *s, uint32_t id, uint32_t v, real out[3])
{
    const struct ttd_mesh *m = s->body[id].mesh;
    const real *src = (const real *)m->verts + 3 * (size_t)v, *pose = body_pose(s, id);
    for (int r = 0; r < 3; ++r)
        out[r] = ((pose[4 * r] * src[0] + pose[4 * r + 1] * src[1]) + pose[4 * r + 2] * src[2]) + pose[4 * r + 3];
}

/* ---- solids (ttd_scene_set_solid; docs/scenes.md, section 5b) ------------------------------ */

/* Whether bodies i and j are both solids. */
static int solid_pair(const struct ttd_scene *s, uint32_t i, uint32_t j)
{
    return s->body[i].solid && s->body[j].solid;
}

/* Whether world point x (the scene's precision) lies inside solid body id: x moved into its
 * mesh's frame as the point queries move points (points/points.h), then the mesh's certified
 * winding number (ttd_points_inside). */
static int body_inside(const struct ttd_scene *s, uint32_t id, const real x[3])
{
    const real *P = body_pose(s, id);
    real y[3];
    TTD_POINT_INTO(P, x, y)
    const double yd[3] = {(double)y[0], (double)y[1], (double)y[2]};
    return ttd_points_inside(s->body[id].mesh, yd);
}

/* Solid bodies i and j whose surfaces are apart: 1 when j lies inside i, 2 when i lies inside j,
 * 0 when neither; at[] gets the inner body's first vertex (of its triangle 0) in the world.
 * Surfaces that do not meet leave one body wholly inside the other or wholly outside it, so one
 * vertex each way decides (as for the mesh queries' ttd_options.solid). */
static int solid_nested(const struct ttd_scene *s, uint32_t i, uint32_t j, real at[3])
{
    for (int side = 0; side < 2; ++side) {
        const uint32_t inner = side ? i : j, outer = side ? j : i;
        body_vertex(s, inner, s->body[inner].mesh->tris[0], at);
        if (body_inside(s, outer, at))
            return side ? 2 : 1;
    }
    return 0;
}

/* How far from a rotation body j's pose in body i's frame, R_i^T R_j, may be: with R_i^T R_i =
 * I + E_i (entries within d_i), |R_i R_i^T - I| <= 3 d_i in norm, so the relative pose's entries
 * are within d_j + 3 d_i (1 + 3 d_j). */
static double pair_defect(const struct ttd_scene *s, uint32_t i, uint32_t j)
{
    const double di = s->body[i].defect, dj = s->body[j].defect;
    return dj + 3 * di * (1 + 3 * dj);
}

/* One thread per body pair: the mesh queries inside run on one thread each. */
static ttd_engine_config one_thread(const ttd_engine_config *cfg)
{
    ttd_engine_config c = *cfg;
    c.threads = 1;
    return c;
}

/* Contacts by triangles: (tri_i, tri_j). */
static int scene_contact_cmp(const void *x, const void *y)
{
    const ttd_scene_contact *a = x, *b = y;
    if (a->tri_i != b->tri_i)
        return a->tri_i < b->tri_i ? -1 : 1;
    return (a->tri_j > b->tri_j) - (a->tri_j < b->tri_j);
}

/* p grown to hold n > *cap items of `size` bytes, its capacity *cap (items) doubled from *cap, or
 * from `first` when 0, until it holds them: the new array, or NULL out of memory or where n items
 * do not fit a size_t (then p and *cap are kept). The one grow of the scene's growable arrays: a
 * caller's array, a worker's contact block, the manifold's records and scratch. Not inlined: the
 * pushes that call it on their rare growth stay small enough to inline into their loops (inlined,
 * the manifold ran 0.2% more instructions, key_push and all_push then out of line). */
static __attribute__((noinline)) void *array_grow(void *p, size_t *cap, size_t n, size_t size, size_t first)
{
    const size_t most = SIZE_MAX / size;
    if (n > most)
        return NULL;
    size_t c = *cap ? *cap : first;
    while (c < n)
        c = c > most / 2 ? n : 2 * c; /* doubled, but never past what c * size can count */
    void *q = realloc(p, c * size);
    if (q != NULL)
        *cap = c;
    return q;
}

/* Room for n items of `size` bytes in a caller's array. Its capacity counts bytes: one array
 * may serve queries whose items differ in size (contacts, then a manifold's larger points), and
 * a capacity in items of the last query's size overflowed the next one's (issue 32). */
static int array_reserve(ttd_scene_array *a, size_t n, size_t size)
{
    if (n > SIZE_MAX / size)
        return 0;
    const size_t need = n * size;
    if (need <= a->capacity)
        return 1;
    void *v = array_grow(a->data, &a->capacity, need, 1, 64 * size);
    if (v == NULL)
        return 0;
    a->data = v;
    return 1;
}

#endif /* TTD_SCENE_BODY_IMPL_H */
