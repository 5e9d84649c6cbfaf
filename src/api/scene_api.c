/* SPDX-License-Identifier: MIT */
/* The public scene entries (ttd/ttd.h, "Scenes"): argument checks, then scene/. Every check
 * happens before anything changes: a refused call leaves the scene as it was. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "api/prepare.h"
#include "scene/scene.h"
#include <ttd/ttd.h>

static ttd_status scene_create(int bytes, ttd_scene **out)
{
    if (out == NULL)
        return TTD_ERR_NULL_POINTER;
    *out = calloc(1, sizeof **out);
    if (*out == NULL)
        return TTD_ERR_OUT_OF_MEMORY;
    (*out)->bytes = bytes;
    (*out)->order_stale = 1;
    (*out)->pool = ttd_pool_create();
    if ((*out)->pool == NULL) {
        free(*out);
        *out = NULL;
        return TTD_ERR_OUT_OF_MEMORY;
    }
    return TTD_OK;
}

ttd_status ttd_scene_create_d(ttd_scene **out)
{
    return scene_create(8, out);
}

ttd_status ttd_scene_create_f(ttd_scene **out)
{
    return scene_create(4, out);
}

void ttd_scene_destroy(ttd_scene *scene)
{
    if (scene == NULL)
        return;
    free(scene->body);
    free(scene->box);
    free(scene->sweep_d);
    free(scene->sweep_i);
    free(scene->sweep_b);
    free(scene->order);
    free(scene->excluded);
    if (scene->scratch_free != NULL)
        scene->scratch_free(scene->scratch);
    ttd_pool_destroy(scene->pool);
    free(scene);
}

/* Whether id names a present body. */
static int present(const ttd_scene *s, uint32_t id)
{
    return id < s->nbody && s->body[id].mesh != NULL;
}

/* The pose checks of the mesh queries, for body mesh m: TTD_OK and its defect. */
static ttd_status check_pose(const ttd_scene *s, const ttd_mesh *m, const void *pose, int bytes, double *defect)
{
    if (s->bytes != bytes || m->bytes != bytes)
        return TTD_ERR_PRECISION_MISMATCH;
    size_t bad;
    return ttd_check_poses(m, 1, pose, bytes, defect, &bad);
}

static ttd_status scene_add(ttd_scene *s, const ttd_mesh *mesh, const void *pose, int bytes, uint32_t *id)
{
    if (s == NULL || mesh == NULL || pose == NULL || id == NULL)
        return TTD_ERR_NULL_POINTER;
    double defect;
    const ttd_status st = check_pose(s, mesh, pose, bytes, &defect);
    if (st != TTD_OK)
        return st;
    if (s->nbody >= UINT32_MAX - 1)
        return TTD_ERR_TOO_LARGE;
    if (s->nbody == s->cap) {
        const size_t cap = s->cap ? 2 * s->cap : 16;
        scene_body *b = realloc(s->body, cap * sizeof *b);
        if (b != NULL)
            s->body = b;
        double *x = b != NULL ? realloc(s->box, 6 * cap * sizeof *x) : NULL;
        if (x == NULL)
            return TTD_ERR_OUT_OF_MEMORY; /* the scene as it was: both arrays still hold cap bodies */
        s->box = x;
        s->cap = cap;
    }
    const uint32_t k = (uint32_t)s->nbody;
    memset(&s->body[k], 0, sizeof s->body[k]);
    s->body[k].mesh = mesh;
    s->body[k].group = 1;
    s->body[k].mask = UINT32_MAX;
    ttd_scene_place(s, k, pose, defect);
    s->nbody++;
    s->present++;
    s->order_stale = 1;
    *id = k;
    return TTD_OK;
}

ttd_status ttd_scene_add_d(ttd_scene *scene, const ttd_mesh *mesh, const double pose[12], uint32_t *id)
{
    return scene_add(scene, mesh, pose, 8, id);
}

ttd_status ttd_scene_add_f(ttd_scene *scene, const ttd_mesh *mesh, const float pose[12], uint32_t *id)
{
    return scene_add(scene, mesh, pose, 4, id);
}

ttd_status ttd_scene_remove(ttd_scene *scene, uint32_t id)
{
    if (scene == NULL)
        return TTD_ERR_NULL_POINTER;
    if (!present(scene, id))
        return TTD_ERR_INDEX_OUT_OF_RANGE;
    scene->body[id].mesh = NULL;
    scene->present--;
    scene->order_stale = 1;
    return TTD_OK;
}

static ttd_status set_pose(ttd_scene *s, uint32_t id, const void *pose, int bytes)
{
    if (s == NULL || pose == NULL)
        return TTD_ERR_NULL_POINTER;
    if (!present(s, id))
        return TTD_ERR_INDEX_OUT_OF_RANGE;
    double defect;
    const ttd_status st = check_pose(s, s->body[id].mesh, pose, bytes, &defect);
    if (st == TTD_OK)
        ttd_scene_place(s, id, pose, defect);
    return st;
}

ttd_status ttd_scene_set_pose_d(ttd_scene *scene, uint32_t id, const double pose[12])
{
    return set_pose(scene, id, pose, 8);
}

ttd_status ttd_scene_set_pose_f(ttd_scene *scene, uint32_t id, const float pose[12])
{
    return set_pose(scene, id, pose, 4);
}

static ttd_status set_poses(ttd_scene *s, size_t n, const void *poses, int bytes)
{
    if (s == NULL || poses == NULL)
        return TTD_ERR_NULL_POINTER;
    if (n != s->nbody)
        return TTD_ERR_INDEX_OUT_OF_RANGE;
    if (s->bytes != bytes)
        return TTD_ERR_PRECISION_MISMATCH;
    const char *p = poses;
    /* every pose checked before any is set; the defects kept for the second pass (without room
     * for them, checked again there: the same function of the pose) */
    double *defects = malloc((n ? n : 1) * sizeof *defects);
    for (size_t id = 0; id < n; ++id) {
        if (s->body[id].mesh == NULL)
            continue;
        double defect;
        const ttd_status st = check_pose(s, s->body[id].mesh, p + 12 * (size_t)bytes * id, bytes, &defect);
        if (st != TTD_OK) {
            free(defects);
            return st;
        }
        if (defects != NULL)
            defects[id] = defect;
    }
    for (size_t id = 0; id < n; ++id) {
        if (s->body[id].mesh == NULL)
            continue;
        double defect;
        if (defects != NULL)
            defect = defects[id];
        else
            (void)check_pose(s, s->body[id].mesh, p + 12 * (size_t)bytes * id, bytes, &defect);
        ttd_scene_place(s, (uint32_t)id, p + 12 * (size_t)bytes * id, defect);
    }
    free(defects);
    return TTD_OK;
}

ttd_status ttd_scene_set_poses_d(ttd_scene *scene, size_t n, const double *poses)
{
    return set_poses(scene, n, poses, 8);
}

ttd_status ttd_scene_set_poses_f(ttd_scene *scene, size_t n, const float *poses)
{
    return set_poses(scene, n, poses, 4);
}

ttd_status ttd_scene_set_filter(ttd_scene *scene, uint32_t id, uint32_t group, uint32_t mask)
{
    if (scene == NULL)
        return TTD_ERR_NULL_POINTER;
    if (!present(scene, id))
        return TTD_ERR_INDEX_OUT_OF_RANGE;
    scene->body[id].group = group;
    scene->body[id].mask = mask;
    return TTD_OK;
}

ttd_status ttd_scene_set_solid(ttd_scene *scene, uint32_t id, int solid)
{
    if (scene == NULL)
        return TTD_ERR_NULL_POINTER;
    if (!present(scene, id))
        return TTD_ERR_INDEX_OUT_OF_RANGE;
    if (solid) {
        const int closed = ttd_mesh_closed(scene->body[id].mesh);
        if (closed < 0)
            return TTD_ERR_OUT_OF_MEMORY;
        if (!closed)
            return TTD_ERR_MESH_NOT_CLOSED;
    }
    scene->body[id].solid = solid != 0;
    return TTD_OK;
}

ttd_status ttd_scene_exclude_pair(ttd_scene *scene, uint32_t i, uint32_t j, int excluded)
{
    if (scene == NULL)
        return TTD_ERR_NULL_POINTER;
    if (i == j || !present(scene, i) || !present(scene, j))
        return TTD_ERR_INDEX_OUT_OF_RANGE;
    ttd_scene *s = scene;
    const uint64_t key = i < j ? (uint64_t)i << 32 | j : (uint64_t)j << 32 | i;
    size_t at = 0;
    while (at < s->nexcluded && s->excluded[at] < key)
        ++at;
    const int there = at < s->nexcluded && s->excluded[at] == key;
    if (excluded && !there) {
        if (s->nexcluded == s->excluded_cap) {
            const size_t cap = s->excluded_cap ? 2 * s->excluded_cap : 16;
            uint64_t *v = realloc(s->excluded, cap * sizeof *v);
            if (v == NULL)
                return TTD_ERR_OUT_OF_MEMORY;
            s->excluded = v;
            s->excluded_cap = cap;
        }
        memmove(s->excluded + at + 1, s->excluded + at, (s->nexcluded - at) * sizeof *s->excluded);
        s->excluded[at] = key;
        s->nexcluded++;
    } else if (!excluded && there) {
        memmove(s->excluded + at, s->excluded + at + 1, (s->nexcluded - at - 1) * sizeof *s->excluded);
        s->nexcluded--;
    }
    return TTD_OK;
}

size_t ttd_scene_body_count(const ttd_scene *scene)
{
    return scene ? scene->present : 0;
}

size_t ttd_scene_id_limit(const ttd_scene *scene)
{
    return scene ? scene->nbody : 0;
}

void ttd_scene_array_free(ttd_scene_array *array)
{
    if (array == NULL)
        return;
    free(array->data);
    *array = (ttd_scene_array){0};
}

/* ---- queries ----------------------------------------------------------------------------- */

/* Deforming bodies: every present body whose mesh's vertices moved (ttd_mesh_set_vertices_*)
 * since its world box was computed gets its pose checked again against the moved mesh (its
 * extent changed: TTD_ERR_COORDINATE_RANGE when the pose now moves it out of range, the body then
 * left as it was) and its world box recomputed; its id, pose and filters stay. One comparison
 * per body: linear in the bodies, as the sweep is. */
static ttd_status refresh_moved_bodies(ttd_scene *s)
{
    for (size_t id = 0; id < s->nbody; ++id) {
        const scene_body *b = &s->body[id];
        if (b->mesh == NULL || b->generation == b->mesh->generation)
            continue;
        const void *pose = s->bytes == 8 ? (const void *)b->pose : (const void *)b->pose_f;
        double defect;
        size_t bad;
        const ttd_status st = ttd_check_poses(b->mesh, 1, pose, s->bytes, &defect, &bad);
        if (st != TTD_OK)
            return st;
        ttd_scene_place(s, (uint32_t)id, pose, defect);
    }
    return TTD_OK;
}

/* The checks of every scene query: pointers, options (the exact method), the precision, and the
 * margin or bound (>= 0; +inf only where inf_ok); then the bodies whose meshes moved. */
static ttd_status query_prepare(const ttd_options *opt, ttd_scene *s, int out_ok, int bytes, double limit,
                                int inf_ok, ttd_engine_config *cfg)
{
    if (s != NULL) /* a query refused below leaves no stats of the last one (ttd_scene_get_stats) */
        s->stats = (ttd_scene_stats){0};
    const ttd_status st = ttd_prepare(opt, s != NULL && out_ok, 1, 0, cfg);
    if (st != TTD_OK)
        return st;
    if (cfg->method != TTD_METHOD_EXACT || !(limit >= 0) || (!inf_ok && !(limit < (double)INFINITY)))
        return TTD_ERR_BAD_OPTIONS;
    return s->bytes == bytes ? refresh_moved_bodies(s) : TTD_ERR_PRECISION_MISMATCH;
}

ttd_status ttd_scene_query_prepare(const ttd_options *opt, ttd_scene *s, int out_ok, int bytes, double limit,
                                   int inf_ok, ttd_engine_config *cfg)
{
    return query_prepare(opt, s, out_ok, bytes, limit, inf_ok, cfg);
}

#define TTD_SCENE_QUERY(bytes, out_ok, limit, inf_ok, call)                                         \
    ttd_engine_config cfg;                                                                     \
    const ttd_status st = query_prepare(opt, scene, out_ok, bytes, (double)(limit), inf_ok, &cfg); \
    return st != TTD_OK ? st : (call)

ttd_status ttd_scene_collide_d(const ttd_options *opt, ttd_scene *scene, double margin, ttd_scene_array *out)
{
    TTD_SCENE_QUERY(8, out != NULL, margin, 0, ttd_scene_query_collide_d(&cfg, scene, margin, out));
}

ttd_status ttd_scene_collide_f(const ttd_options *opt, ttd_scene *scene, float margin, ttd_scene_array *out)
{
    TTD_SCENE_QUERY(4, out != NULL, margin, 0, ttd_scene_query_collide_f(&cfg, scene, margin, out));
}

ttd_status ttd_scene_contacts_d(const ttd_options *opt, ttd_scene *scene, double margin, ttd_scene_array *out)
{
    TTD_SCENE_QUERY(8, out != NULL, margin, 0, ttd_scene_query_contacts_d(&cfg, scene, margin, out));
}

ttd_status ttd_scene_contacts_f(const ttd_options *opt, ttd_scene *scene, float margin, ttd_scene_array *out)
{
    TTD_SCENE_QUERY(4, out != NULL, margin, 0, ttd_scene_query_contacts_f(&cfg, scene, margin, out));
}

ttd_status ttd_scene_contacts_count_d(const ttd_options *opt, ttd_scene *scene, double margin, size_t *count)
{
    TTD_SCENE_QUERY(8, count != NULL, margin, 0, ttd_scene_query_contacts_count_d(&cfg, scene, margin, count));
}

ttd_status ttd_scene_contacts_count_f(const ttd_options *opt, ttd_scene *scene, float margin, size_t *count)
{
    TTD_SCENE_QUERY(4, count != NULL, margin, 0, ttd_scene_query_contacts_count_f(&cfg, scene, margin, count));
}

ttd_status ttd_scene_distance_d(const ttd_options *opt, ttd_scene *scene, double upper_bound,
                                ttd_scene_contact_d *closest, ttd_scene_contact_d *nearest)
{
    TTD_SCENE_QUERY(8, closest != NULL, upper_bound, 1,
                    ttd_scene_query_distance_d(&cfg, scene, upper_bound, closest, nearest));
}

ttd_status ttd_scene_distance_f(const ttd_options *opt, ttd_scene *scene, float upper_bound,
                                ttd_scene_contact_f *closest, ttd_scene_contact_f *nearest)
{
    TTD_SCENE_QUERY(4, closest != NULL, upper_bound, 1,
                    ttd_scene_query_distance_f(&cfg, scene, upper_bound, closest, nearest));
}

ttd_status ttd_scene_manifold_d(const ttd_options *opt, ttd_scene *scene, double margin, size_t max_points,
                                ttd_scene_array *out)
{
    TTD_SCENE_QUERY(8, out != NULL, margin, 0, ttd_scene_query_manifold_d(&cfg, scene, margin, max_points, out));
}

ttd_status ttd_scene_manifold_f(const ttd_options *opt, ttd_scene *scene, float margin, size_t max_points,
                                ttd_scene_array *out)
{
    TTD_SCENE_QUERY(4, out != NULL, margin, 0, ttd_scene_query_manifold_f(&cfg, scene, margin, max_points, out));
}

ttd_status ttd_scene_get_stats(const ttd_scene *scene, ttd_scene_stats *out)
{
    if (scene == NULL || out == NULL)
        return TTD_ERR_NULL_POINTER;
    *out = scene->stats;
    return TTD_OK;
}
