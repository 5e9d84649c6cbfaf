/* SPDX-License-Identifier: MIT */
/* The public mesh entries of include/ttd/ttd.h: every argument is checked here, in the order
 * the pair entries use (pointers, options, counts, sizes, instruction set; api/prepare.h), then
 * what only meshes have (indices, finite vertices, the meshes' precision, the poses, the margin
 * and bounds), before src/mesh/ builds or queries anything. */
#include <math.h>
#include <string.h>
#include <stdint.h>
#include <stdlib.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "api/prepare.h"
#include "core/rotation.h"
#include "mesh/mesh.h"
#include "points/points.h"
#include "ttd/ttd.h"

/* Poses whose R^T R - I has an entry larger than this are not rotations. */
#define TTD_POSE_TOLERANCE 1e-6

/* Mesh sizes the hierarchy can index (triangles are children -1 - t of int32 slots). */
#define TTD_MESH_MAX_TRIANGLES ((size_t)INT32_MAX / 2)

/* ---- building ---------------------------------------------------------------------------- */

/* 1 where some coordinate of type T is not finite or beyond range (NaN fails the comparison): one
 * pass without a branch per coordinate, for the common case (every refit of a deforming mesh
 * checks its vertices: a branch and a test of the precision per coordinate were 4% of a refit). */
#define ANY_OUT(T)                                                                                 \
    do {                                                                                           \
        const T *v = vertices;                                                                     \
        for (size_t i = 0; i < 3 * nv; ++i)                                                        \
            out |= !(fabs((double)v[i]) <= range);                                                 \
    } while (0)

/* ANY_OUT(double) over n coordinates, two at a step where SSE2 is the baseline: !(|x| <= range)
 * is cmpnle, true for NaN (scalar, 9 instructions a coordinate: 3% of a refit at 10k triangles) */
static int any_out_d(const double *v, size_t n, double range)
{
    int out = 0;
    size_t i = 0;
#if defined(__SSE2__)
    const __m128d r = _mm_set1_pd(range), sign = _mm_set1_pd(-0.0);
    __m128d bad0 = _mm_setzero_pd(), bad1 = _mm_setzero_pd();
    for (; i + 4 <= n; i += 4) {
        bad0 = _mm_or_pd(bad0, _mm_cmpnle_pd(_mm_andnot_pd(sign, _mm_loadu_pd(v + i)), r));
        bad1 = _mm_or_pd(bad1, _mm_cmpnle_pd(_mm_andnot_pd(sign, _mm_loadu_pd(v + i + 2)), r));
    }
    out = _mm_movemask_pd(_mm_or_pd(bad0, bad1)) != 0;
#endif
    for (; i < n; ++i)
        out |= !(fabs(v[i]) <= range);
    return out;
}

/* The build's checks of vertex coordinates: finite, then within the range. */
static ttd_status check_vertices(int bytes, const void *vertices, size_t nv)
{
    const double range = ttd_mesh_range(bytes);
    int out = 0;
    if (bytes == 8)
        out = any_out_d(vertices, 3 * nv, range);
    else
        ANY_OUT(float);
    if (!out)
        return TTD_OK;
    /* which status: a coordinate not finite anywhere comes first */
    for (size_t i = 0; i < 3 * nv; ++i) {
        const double x = bytes == 8 ? ((const double *)vertices)[i] : (double)((const float *)vertices)[i];
        if (!isfinite(x))
            return TTD_ERR_NONFINITE_MESH;
    }
    for (size_t i = 0; i < 3 * nv; ++i) {
        const double x = bytes == 8 ? ((const double *)vertices)[i] : (double)((const float *)vertices)[i];
        if (fabs(x) > range)
            return TTD_ERR_COORDINATE_RANGE;
    }
    return TTD_OK;
}
#undef ANY_OUT

static ttd_status mesh_create(const ttd_options *opt, int bytes, const void *vertices, size_t nv,
                              const uint32_t *triangles, size_t nt, ttd_mesh **out)
{
    if (out == NULL)
        return TTD_ERR_NULL_POINTER;
    *out = NULL;
    ttd_engine_config cfg;
    ttd_status st = ttd_prepare(opt, vertices && triangles, nv == 0 ? 0 : nt,
                                ttd_too_large(nv, 3, (size_t)bytes) || ttd_too_large(nt, 3, sizeof(uint32_t)) ||
                                    nt > TTD_MESH_MAX_TRIANGLES,
                                &cfg);
    if (st != TTD_OK)
        return st;
    if (cfg.method != TTD_METHOD_EXACT)
        return TTD_ERR_BAD_OPTIONS;
    for (size_t i = 0; i < 3 * nt; ++i)
        if (triangles[i] >= nv)
            return TTD_ERR_INDEX_OUT_OF_RANGE;
    st = check_vertices(bytes, vertices, nv);
    return st == TTD_OK ? ttd_mesh_build(&cfg, bytes, vertices, nv, triangles, nt, out) : st;
}

ttd_status ttd_mesh_create_d(const ttd_options *opt, const double *vertices, size_t nv, const uint32_t *triangles,
                             size_t nt, ttd_mesh **out)
{
    return mesh_create(opt, 8, vertices, nv, triangles, nt, out);
}

ttd_status ttd_mesh_create_f(const ttd_options *opt, const float *vertices, size_t nv, const uint32_t *triangles,
                             size_t nt, ttd_mesh **out)
{
    return mesh_create(opt, 4, vertices, nv, triangles, nt, out);
}

void ttd_mesh_destroy(ttd_mesh *mesh)
{
    ttd_mesh_free(mesh);
}

static ttd_status set_vertices(const ttd_options *opt, int bytes, ttd_mesh *mesh, const void *vertices)
{
    ttd_engine_config cfg;
    ttd_status st = ttd_prepare(opt, mesh && vertices, 1, 0, &cfg);
    if (st != TTD_OK)
        return st;
    if (cfg.method != TTD_METHOD_EXACT)
        return TTD_ERR_BAD_OPTIONS;
    if (mesh->bytes != bytes)
        return TTD_ERR_PRECISION_MISMATCH;
    st = check_vertices(bytes, vertices, mesh->nv);
    if (st == TTD_OK)
        st = ttd_mesh_refit(&cfg, mesh, vertices);
    if (st == TTD_OK) /* the point queries' data, where a point query made it (after a rebuild: none) */
        ttd_points_data_refresh(mesh, cfg.threads);
    return st;
}

ttd_status ttd_mesh_set_vertices_d(const ttd_options *opt, ttd_mesh *mesh, const double *vertices)
{
    return set_vertices(opt, 8, mesh, vertices);
}

ttd_status ttd_mesh_set_vertices_f(const ttd_options *opt, ttd_mesh *mesh, const float *vertices)
{
    return set_vertices(opt, 4, mesh, vertices);
}

ttd_status ttd_mesh_get_refit_info(const ttd_mesh *mesh, ttd_mesh_refit_info *info)
{
    if (mesh == NULL || info == NULL)
        return TTD_ERR_NULL_POINTER;
    *info = (ttd_mesh_refit_info){mesh->generation, mesh->rebuilds, mesh->quality, mesh->quality_built};
    return TTD_OK;
}

size_t ttd_mesh_triangle_count(const ttd_mesh *mesh)
{
    return mesh ? mesh->nt : 0;
}

size_t ttd_mesh_vertex_count(const ttd_mesh *mesh)
{
    return mesh ? mesh->nv : 0;
}

size_t ttd_mesh_node_count(const ttd_mesh *mesh)
{
    return mesh ? mesh->nnodes : 0;
}

/* ---- queries ----------------------------------------------------------------------------- */

/* How far the 3x3 part of a pose (12 reals of bytes each) is from a rotation: max |R^T R - I|;
 * -1 when it is not finite or det R <= 0. */
static double pose_defect(const void *poses, size_t i, int bytes)
{
    double p[12];
    for (int j = 0; j < 12; ++j) {
        p[j] = bytes == 8 ? ((const double *)poses)[12 * i + (size_t)j] : (double)((const float *)poses)[12 * i + (size_t)j];
        if (!isfinite(p[j]))
            return -1;
    }
    const double r[9] = {p[0], p[1], p[2], p[4], p[5], p[6], p[8], p[9], p[10]};
    return ttd_rotation_det(r) > 0 ? ttd_rotation_defect(r) : -1;
}

/* A bound on |R x + t| over b's vertices x for pose i of defect `defect`: they lie within
 * b's radius of its origin o, and |R (x - o)| <= sqrt(1 + 3 defect) |x - o| <= (1 + 2 defect)
 * |x - o|, so within that of R o + t (computed in double, rounded up by a few ulps). */
static double pose_reach(const ttd_mesh *b, const void *poses, size_t i, int bytes, double defect)
{
    double p[12], c2 = 0;
    for (int j = 0; j < 12; ++j)
        p[j] = bytes == 8 ? ((const double *)poses)[12 * i + (size_t)j] : (double)((const float *)poses)[12 * i + (size_t)j];
    for (int r = 0; r < 3; ++r) {
        const double c = p[4 * r] * b->origin[0] + p[4 * r + 1] * b->origin[1] + p[4 * r + 2] * b->origin[2] + p[4 * r + 3];
        c2 += c * c;
    }
    return (sqrt(c2) + (1 + 2 * defect) * b->radius) * (1 + 8 * DBL_EPSILON);
}

/* Every pose's check: a rotation within the tolerance, and b moved within the range. Fills
 * defects[i] (when defects is not NULL); on a refused pose, *bad is its index. */
ttd_status ttd_check_poses(const struct ttd_mesh *b, size_t k, const void *poses, int bytes, double *defects, size_t *bad)
{
    const double range = ttd_mesh_range(bytes);
    for (size_t i = 0; i < k; ++i) {
        const double defect = pose_defect(poses, i, bytes);
        const ttd_status st = !(defect >= 0 && defect <= TTD_POSE_TOLERANCE)        ? TTD_ERR_BAD_POSE
                              : pose_reach(b, poses, i, bytes, defect) > range ? TTD_ERR_COORDINATE_RANGE
                                                                                   : TTD_OK;
        if (st != TTD_OK) {
            *bad = i;
            return st;
        }
        if (defects != NULL)
            defects[i] = defect;
    }
    return TTD_OK;
}

static ttd_status check_poses_entry(const ttd_mesh *a, const ttd_mesh *b, size_t k, const void *poses, int bytes,
                                    size_t *bad)
{
    if (bad != NULL)
        *bad = k;
    if (a == NULL || b == NULL || poses == NULL || bad == NULL)
        return TTD_ERR_NULL_POINTER;
    if (k == 0)
        return TTD_ERR_EMPTY;
    if (a->bytes != bytes || b->bytes != bytes)
        return TTD_ERR_PRECISION_MISMATCH;
    return ttd_check_poses(b, k, poses, bytes, NULL, bad);
}

ttd_status ttd_mesh_check_poses_d(const ttd_mesh *a, const ttd_mesh *b, size_t k, const double *poses, size_t *bad)
{
    return check_poses_entry(a, b, k, poses, 8, bad);
}

ttd_status ttd_mesh_check_poses_f(const ttd_mesh *a, const ttd_mesh *b, size_t k, const float *poses, size_t *bad)
{
    return check_poses_entry(a, b, k, poses, 4, bad);
}

/* Poses whose defects fit on the stack (most calls: one pose). */
#define TTD_DEFECTS_INLINE 32

/* The checks of every query. On TTD_OK, *defects holds k pose defects: inline (TTD_DEFECTS_INLINE
 * of them) or allocated (the caller frees it when it is not inline). */
static ttd_status query_prepare(const ttd_options *opt, const ttd_mesh *a, const ttd_mesh *b, size_t k,
                                const void *poses, int bytes, int out_ok, ttd_engine_config *cfg, double **defects,
                                double *inline_defects)
{
    *defects = NULL;
    ttd_status st = ttd_prepare(opt, a && b && poses && out_ok, k, ttd_too_large(k, 12, (size_t)bytes), cfg);
    if (st != TTD_OK)
        return st;
    if (cfg->method != TTD_METHOD_EXACT)
        return TTD_ERR_BAD_OPTIONS;
    if (a->bytes != bytes || b->bytes != bytes)
        return TTD_ERR_PRECISION_MISMATCH;
    double *d = k <= TTD_DEFECTS_INLINE ? inline_defects : malloc(k * sizeof *d);
    if (d == NULL)
        return TTD_ERR_OUT_OF_MEMORY;
    size_t bad;
    st = ttd_check_poses(b, k, poses, bytes, d, &bad);
    if (st != TTD_OK) {
        if (d != inline_defects)
            free(d);
        return st;
    }
    *defects = d;
    return TTD_OK;
}

/* A margin or bound: finite (or, for an upper bound, +inf) and >= 0. */
static int ttd_nonneg(double x, int inf_ok)
{
    return x >= 0 && (inf_ok || x < (double)INFINITY);
}

#define TTD_QUERY_BEGIN(bytes, out_ok, params_ok)                                                  \
    ttd_engine_config cfg;                                                                     \
    double *defects, inline_defects[TTD_DEFECTS_INLINE];                                      \
    ttd_status st = query_prepare(opt, a, b, k, poses, bytes, out_ok, &cfg, &defects, inline_defects); \
    if (st != TTD_OK)                                                                          \
        return st;                                                                             \
    if (!(params_ok)) {                                                                        \
        TTD_QUERY_END();                                                                       \
        return TTD_ERR_BAD_OPTIONS;                                                            \
    }

/* Frees what TTD_QUERY_BEGIN allocated. */
#define TTD_QUERY_END()                                                                            \
    do {                                                                                       \
        if (defects != inline_defects)                                                         \
            free(defects);                                                                     \
    } while (0)

ttd_status ttd_mesh_orientation(const ttd_mesh *mesh, ttd_orientation *orientation)
{
    if (mesh == NULL || orientation == NULL)
        return TTD_ERR_NULL_POINTER;
    const ttd_orientation o = ttd_mesh_orientation_of(mesh);
    if ((int)o < 0)
        return TTD_ERR_OUT_OF_MEMORY;
    *orientation = o;
    return TTD_OK;
}

/* ---- solids (ttd_options.solid) ----------------------------------------------------------- */

/* TTD_OK when opt does not ask for solids or both meshes are closed. */
static ttd_status solid_check(const ttd_options *opt, const ttd_mesh *a, const ttd_mesh *b)
{
    if (opt == NULL || !opt->solid)
        return TTD_OK;
    const int ca = ttd_mesh_closed(a), cb = ca == 1 ? ttd_mesh_closed(b) : 1;
    if (ca < 0 || cb < 0)
        return TTD_ERR_OUT_OF_MEMORY;
    return ca && cb ? TTD_OK : TTD_ERR_MESH_NOT_CLOSED;
}

/* A vertex of a mesh: the first of its triangle 0. */
static void first_vertex(const ttd_mesh *m, double x[3])
{
    for (int c = 0; c < 3; ++c)
        x[c] = m->bytes == 8 ? ((const double *)m->verts)[3 * (size_t)m->tris[0] + (size_t)c]
                             : (double)((const float *)m->verts)[3 * (size_t)m->tris[0] + (size_t)c];
}


/* Under pose i (b into a's frame; 12 reals of `bytes`), with the surfaces apart: 1 when b lies
 * inside a, 2 when a lies inside b, 0 otherwise; at[] gets the inner mesh's first vertex in a's
 * frame (b's moved by the pose in the query's precision, as the kernel moves it). Surfaces that do
 * not meet leave one mesh wholly inside the other's solid or wholly outside it, so one vertex
 * each way decides. */
static int nested(const ttd_mesh *a, const ttd_mesh *b, const void *poses, size_t i, int bytes, double at[3])
{
    double P[12], vb[3], va[3];
    for (int k = 0; k < 12; ++k)
        P[k] = bytes == 8 ? ((const double *)poses)[12 * i + (size_t)k] : (double)((const float *)poses)[12 * i + (size_t)k];
    first_vertex(b, vb);
    for (int r = 0; r < 3; ++r) {
        if (bytes == 8) {
            at[r] = ((P[4 * r] * vb[0] + P[4 * r + 1] * vb[1]) + P[4 * r + 2] * vb[2]) + P[4 * r + 3];
        } else {
            const float x = (float)vb[0], y = (float)vb[1], z = (float)vb[2];
            at[r] = (double)((((float)P[4 * r] * x + (float)P[4 * r + 1] * y) + (float)P[4 * r + 2] * z) + (float)P[4 * r + 3]);
        }
    }
    if (ttd_points_inside(a, at))
        return 1;
    first_vertex(a, va);
    double inb[3]; /* a's vertex in b's frame: R^T (x - t) */
    for (int r = 0; r < 3; ++r)
        inb[r] = P[r] * (va[0] - P[3]) + P[4 + r] * (va[1] - P[7]) + P[8 + r] * (va[2] - P[11]);
    if (ttd_points_inside(b, inb)) {
        memcpy(at, va, sizeof va);
        return 2;
    }
    return 0;
}

/* Marks result r contained (side 1: b inside a; 2: a inside b) at the inner vertex `at`. */
#define TTD_SOLID_RESULT(r, side, at, real)                                                       \
    do {                                                                                       \
        (r)->distance = 0;                                                                     \
        for (int c_ = 0; c_ < 3; ++c_)                                                         \
            (r)->p[c_] = (r)->q[c_] = (real)(at)[c_];                                          \
        (r)->tri_a = (side) == 2 ? 0 : UINT32_MAX;                                             \
        (r)->tri_b = (side) == 1 ? 0 : UINT32_MAX;                                             \
        (r)->feature_a = (side) == 2 ? 1 : 0;                                                  \
        (r)->feature_b = (side) == 1 ? 1 : 0;                                                  \
        (r)->flags = TTD_MESH_INTERSECTING | TTD_MESH_CONTAINED;                               \
    } while (0)

/* The solid pass of a distance query: every pose whose surfaces are apart, nested or not. */
#define TTD_SOLID_DISTANCE(real, bytes)                                                            \
    for (size_t i_ = 0; st == TTD_OK && opt != NULL && opt->solid && i_ < k; ++i_) {             \
        double at_[3];                                                                         \
        int side_;                                                                             \
        if (!(out[i_].distance > 0) || (side_ = nested(a, b, poses, i_, bytes, at_)) == 0)      \
            continue;                                                                          \
        TTD_SOLID_RESULT(&out[i_], side_, at_, real);                                          \
    }

/* The solid pass of a collision query. */
#define TTD_SOLID_COLLIDE(bytes)                                                                   \
    for (size_t i_ = 0; st == TTD_OK && opt != NULL && opt->solid && i_ < k; ++i_) {             \
        double at_[3];                                                                         \
        int side_;                                                                             \
        if (out[i_].hit || (side_ = nested(a, b, poses, i_, bytes, at_)) == 0)                  \
            continue;                                                                          \
        out[i_].hit = 1;                                                                       \
        out[i_].tri_a = side_ == 2 ? 0 : UINT32_MAX;                                           \
        out[i_].tri_b = side_ == 1 ? 0 : UINT32_MAX;                                           \
    }

ttd_status ttd_mesh_distance_d(const ttd_options *opt, const ttd_mesh *a, const ttd_mesh *b, size_t k,
                               const double *poses, double upper_bound, double rel_tol, ttd_mesh_result_d *out)
{
    TTD_QUERY_BEGIN(8, out != NULL, ttd_nonneg(upper_bound, 1) && ttd_nonneg(rel_tol, 0))
    st = solid_check(opt, a, b);
    if (st == TTD_OK)
        st = ttd_mesh_query_distance_d(&cfg, a, b, k, poses, NULL, defects, upper_bound, rel_tol, out);
    TTD_SOLID_DISTANCE(double, 8)
    TTD_QUERY_END();
    return st;
}

ttd_status ttd_mesh_distance_f(const ttd_options *opt, const ttd_mesh *a, const ttd_mesh *b, size_t k,
                               const float *poses, float upper_bound, float rel_tol, ttd_mesh_result_f *out)
{
    TTD_QUERY_BEGIN(4, out != NULL, ttd_nonneg((double)upper_bound, 1) && ttd_nonneg((double)rel_tol, 0))
    st = solid_check(opt, a, b);
    if (st == TTD_OK)
        st = ttd_mesh_query_distance_f(&cfg, a, b, k, poses, NULL, defects, upper_bound, rel_tol, out);
    TTD_SOLID_DISTANCE(float, 4)
    TTD_QUERY_END();
    return st;
}

ttd_status ttd_mesh_collide_d(const ttd_options *opt, const ttd_mesh *a, const ttd_mesh *b, size_t k,
                              const double *poses, double margin, ttd_collision *out)
{
    TTD_QUERY_BEGIN(8, out != NULL, ttd_nonneg(margin, 0))
    st = solid_check(opt, a, b);
    if (st == TTD_OK)
        st = ttd_mesh_query_collide_d(&cfg, a, b, k, poses, NULL, defects, margin, out);
    TTD_SOLID_COLLIDE(8)
    TTD_QUERY_END();
    return st;
}

ttd_status ttd_mesh_collide_f(const ttd_options *opt, const ttd_mesh *a, const ttd_mesh *b, size_t k,
                              const float *poses, float margin, ttd_collision *out)
{
    TTD_QUERY_BEGIN(4, out != NULL, ttd_nonneg((double)margin, 0))
    st = solid_check(opt, a, b);
    if (st == TTD_OK)
        st = ttd_mesh_query_collide_f(&cfg, a, b, k, poses, NULL, defects, margin, out);
    TTD_SOLID_COLLIDE(4)
    TTD_QUERY_END();
    return st;
}

ttd_status ttd_mesh_contacts_d(const ttd_options *opt, const ttd_mesh *a, const ttd_mesh *b, size_t k,
                               const double *poses, double margin, ttd_contacts_d *out)
{
    if (out != NULL)
        out->count = 0;
    TTD_QUERY_BEGIN(8, out != NULL, ttd_nonneg(margin, 0))
    st = ttd_mesh_query_contacts_d(&cfg, a, b, k, poses, NULL, defects, margin, out);
    TTD_QUERY_END();
    return st;
}

ttd_status ttd_mesh_contacts_f(const ttd_options *opt, const ttd_mesh *a, const ttd_mesh *b, size_t k,
                               const float *poses, float margin, ttd_contacts_f *out)
{
    if (out != NULL)
        out->count = 0;
    TTD_QUERY_BEGIN(4, out != NULL, ttd_nonneg((double)margin, 0))
    st = ttd_mesh_query_contacts_f(&cfg, a, b, k, poses, NULL, defects, margin, out);
    TTD_QUERY_END();
    return st;
}

ttd_status ttd_mesh_contacts_count_d(const ttd_options *opt, const ttd_mesh *a, const ttd_mesh *b, size_t k,
                                     const double *poses, double margin, size_t *counts)
{
    TTD_QUERY_BEGIN(8, counts != NULL, ttd_nonneg(margin, 0))
    st = ttd_mesh_query_contacts_count_d(&cfg, a, b, k, poses, defects, margin, counts);
    TTD_QUERY_END();
    return st;
}

ttd_status ttd_mesh_contacts_count_f(const ttd_options *opt, const ttd_mesh *a, const ttd_mesh *b, size_t k,
                                     const float *poses, float margin, size_t *counts)
{
    TTD_QUERY_BEGIN(4, counts != NULL, ttd_nonneg((double)margin, 0))
    st = ttd_mesh_query_contacts_count_f(&cfg, a, b, k, poses, defects, margin, counts);
    TTD_QUERY_END();
    return st;
}

/* ---- self queries ------------------------------------------------------------------------ */

/* The checks of the self queries: pointers, options (the exact method), the precision, the
 * margin, the flags. */
static ttd_status self_prepare(const ttd_options *opt, const ttd_mesh *m, int bytes, int out_ok, double margin,
                               unsigned flags, ttd_engine_config *cfg)
{
    const ttd_status st = ttd_prepare(opt, m != NULL && out_ok, 1, 0, cfg);
    if (st != TTD_OK)
        return st;
    if (cfg->method != TTD_METHOD_EXACT || !ttd_nonneg(margin, 0) || (flags & ~(unsigned)TTD_SELF_SHARED_VERTEX))
        return TTD_ERR_BAD_OPTIONS;
    return m->bytes == bytes ? TTD_OK : TTD_ERR_PRECISION_MISMATCH;
}

ttd_status ttd_mesh_self_contacts_d(const ttd_options *opt, const ttd_mesh *mesh, double margin, unsigned flags,
                                    ttd_contacts_d *out)
{
    if (out != NULL)
        out->count = 0;
    ttd_engine_config cfg;
    const ttd_status st = self_prepare(opt, mesh, 8, out != NULL, margin, flags, &cfg);
    return st == TTD_OK ? ttd_mesh_query_self_contacts_d(&cfg, mesh, margin, flags & TTD_SELF_SHARED_VERTEX, out) : st;
}

ttd_status ttd_mesh_self_contacts_count_d(const ttd_options *opt, const ttd_mesh *mesh, double margin, unsigned flags,
                                          size_t *count)
{
    ttd_engine_config cfg;
    const ttd_status st = self_prepare(opt, mesh, 8, count != NULL, margin, flags, &cfg);
    return st == TTD_OK ? ttd_mesh_query_self_contacts_count_d(&cfg, mesh, margin, flags & TTD_SELF_SHARED_VERTEX, count)
                        : st;
}

ttd_status ttd_mesh_self_contacts_count_f(const ttd_options *opt, const ttd_mesh *mesh, float margin, unsigned flags,
                                          size_t *count)
{
    ttd_engine_config cfg;
    const ttd_status st = self_prepare(opt, mesh, 4, count != NULL, (double)margin, flags, &cfg);
    return st == TTD_OK ? ttd_mesh_query_self_contacts_count_f(&cfg, mesh, margin, flags & TTD_SELF_SHARED_VERTEX, count)
                        : st;
}

ttd_status ttd_mesh_self_contacts_f(const ttd_options *opt, const ttd_mesh *mesh, float margin, unsigned flags,
                                    ttd_contacts_f *out)
{
    if (out != NULL)
        out->count = 0;
    ttd_engine_config cfg;
    const ttd_status st = self_prepare(opt, mesh, 4, out != NULL, (double)margin, flags, &cfg);
    return st == TTD_OK ? ttd_mesh_query_self_contacts_f(&cfg, mesh, margin, flags & TTD_SELF_SHARED_VERTEX, out) : st;
}

ttd_status ttd_mesh_self_collide_d(const ttd_options *opt, const ttd_mesh *mesh, double margin, unsigned flags,
                                   ttd_collision *out)
{
    ttd_engine_config cfg;
    const ttd_status st = self_prepare(opt, mesh, 8, out != NULL, margin, flags, &cfg);
    return st == TTD_OK ? ttd_mesh_query_self_collide_d(&cfg, mesh, margin, flags & TTD_SELF_SHARED_VERTEX, out) : st;
}

ttd_status ttd_mesh_self_collide_f(const ttd_options *opt, const ttd_mesh *mesh, float margin, unsigned flags,
                                   ttd_collision *out)
{
    ttd_engine_config cfg;
    const ttd_status st = self_prepare(opt, mesh, 4, out != NULL, (double)margin, flags, &cfg);
    return st == TTD_OK ? ttd_mesh_query_self_collide_f(&cfg, mesh, margin, flags & TTD_SELF_SHARED_VERTEX, out) : st;
}

void ttd_contacts_free_d(ttd_contacts_d *contacts)
{
    if (contacts == NULL)
        return;
    free(contacts->pairs);
    free(contacts->pose_start);
    *contacts = (ttd_contacts_d){0};
}

void ttd_contacts_free_f(ttd_contacts_f *contacts)
{
    if (contacts == NULL)
        return;
    free(contacts->pairs);
    free(contacts->pose_start);
    *contacts = (ttd_contacts_f){0};
}

/* ---- per-triangle closest partners: the contact set reduced ------------------------------- */

/* Keeps contact (partner, d, p, q) in rec when it is nearer, or as near with a smaller partner. */
#define TTD_CLOSEST_KEEP(rec, partner_, d_, p_, q_)                                                 \
    do {                                                                                       \
        if ((d_) < (rec)->distance || ((d_) == (rec)->distance && (partner_) < (rec)->partner)) { \
            (rec)->partner = (partner_);                                                       \
            (rec)->distance = (d_);                                                            \
            for (int c_ = 0; c_ < 3; ++c_) {                                                   \
                (rec)->p[c_] = (p_)[c_];                                                       \
                (rec)->q[c_] = (q_)[c_];                                                       \
            }                                                                                  \
        }                                                                                      \
    } while (0)

#define TTD_CLOSEST_BODY(real, contacts_t, closest_t, query_fn, free_fn)                           \
    TTD_QUERY_BEGIN((int)sizeof(real), for_a != NULL || for_b != NULL, ttd_nonneg((double)margin, 0)) \
    contacts_t set = {0};                                                                      \
    st = query_fn(&cfg, a, b, k, poses, NULL, defects, margin, &set);                          \
    TTD_QUERY_END();                                                                           \
    if (st != TTD_OK) {                                                                        \
        free_fn(&set);                                                                         \
        return st;                                                                             \
    }                                                                                          \
    const closest_t none = {UINT32_MAX, (real)INFINITY, {(real)NAN, (real)NAN, (real)NAN},      \
                            {(real)NAN, (real)NAN, (real)NAN}};                                \
    for (size_t i = 0; for_a && i < k * a->nt; ++i)                                            \
        for_a[i] = none;                                                                       \
    for (size_t i = 0; for_b && i < k * b->nt; ++i)                                            \
        for_b[i] = none;                                                                       \
    for (size_t i = 0; i < k; ++i)                                                             \
        for (size_t j = set.pose_start[i]; j < set.pose_start[i + 1]; ++j) {                   \
            const __typeof__(set.pairs[0]) *c = &set.pairs[j];                                 \
            if (for_a)                                                                         \
                TTD_CLOSEST_KEEP(&for_a[i * a->nt + c->tri_a], c->tri_b, c->distance, c->p, c->q); \
            if (for_b)                                                                         \
                TTD_CLOSEST_KEEP(&for_b[i * b->nt + c->tri_b], c->tri_a, c->distance, c->q, c->p); \
        }                                                                                      \
    free_fn(&set);                                                                             \
    return TTD_OK;

ttd_status ttd_mesh_closest_d(const ttd_options *opt, const ttd_mesh *a, const ttd_mesh *b, size_t k,
                              const double *poses, double margin, ttd_closest_d *for_a, ttd_closest_d *for_b)
{
    TTD_CLOSEST_BODY(double, ttd_contacts_d, ttd_closest_d, ttd_mesh_query_contacts_d, ttd_contacts_free_d)
}

ttd_status ttd_mesh_closest_f(const ttd_options *opt, const ttd_mesh *a, const ttd_mesh *b, size_t k,
                              const float *poses, float margin, ttd_closest_f *for_a, ttd_closest_f *for_b)
{
    TTD_CLOSEST_BODY(float, ttd_contacts_f, ttd_closest_f, ttd_mesh_query_contacts_f, ttd_contacts_free_f)
}
