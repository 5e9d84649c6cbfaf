/* SPDX-License-Identifier: MIT */
/* The public point entries of include/ttd/ttd.h ("Point queries"): every argument is checked here,
 * in the order the other entries use (api/prepare.h: pointers, options, counts, sizes, instruction
 * set), then what only points have (the mesh's precision, the pose, the points' range), before
 * src/points/ computes anything. The pose is applied here: the points are moved into the mesh's
 * frame before the query and the closest points moved back after it. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "api/prepare.h"
#include "core/point_layout.h"
#include "points/points.h"
#include "scalar/scalar.h"
#include "ttd/ttd.h"

/* What the checks leave for the query: the points in the mesh's frame (the caller's, or a moved
 * copy) and how many are not finite. */
typedef struct pts_in {
    const void *pts;
    void *moved;
    size_t nonfinite;
} pts_in;

static void pts_end(pts_in *in)
{
    free(in->moved);
    in->moved = NULL;
}

/* Every check of a point entry, in order; on TTD_OK, *in holds the points for the query. */
static ttd_status pts_begin(const ttd_options *opt, const ttd_mesh *mesh, size_t n, const void *points, const void *pose,
                            int bytes, int out_ok, size_t out_size, int params_ok, ttd_engine_config *cfg, pts_in *in)
{
    memset(in, 0, sizeof *in);
    ttd_status st = ttd_prepare(opt, mesh && points && out_ok, n,
                                ttd_too_large(n, 3, (size_t)bytes) || ttd_too_large(n, 1, out_size), cfg);
    if (st != TTD_OK)
        return st;
    if (cfg->method != TTD_METHOD_EXACT || !params_ok)
        return TTD_ERR_BAD_OPTIONS;
    if (mesh->bytes != bytes)
        return TTD_ERR_PRECISION_MISMATCH;
    in->pts = points;
    if (pose != NULL) {
        size_t bad;
        if ((st = ttd_check_poses(mesh, 1, pose, bytes, NULL, &bad)) != TTD_OK)
            return st;
        in->moved = malloc(3 * n * (size_t)bytes);
        if (in->moved == NULL)
            return TTD_ERR_OUT_OF_MEMORY;
        for (size_t i = 0; i < n; ++i) {
            if (bytes == 8) {
                TTD_POINT_INTO((const double *)pose, (const double *)points + 3 * i, (double *)in->moved + 3 * i)
            } else {
                TTD_POINT_INTO((const float *)pose, (const float *)points + 3 * i, (float *)in->moved + 3 * i)
            }
        }
        in->pts = in->moved;
    }
    const double range = ttd_mesh_range(bytes);
    for (size_t i = 0; i < n; ++i) {
        double x[3];
        for (int c = 0; c < 3; ++c)
            x[c] = bytes == 8 ? ((const double *)in->pts)[3 * i + (size_t)c] : (double)((const float *)in->pts)[3 * i + (size_t)c];
        if (!(isfinite(x[0]) && isfinite(x[1]) && isfinite(x[2]))) {
            /* a finite point that the pose moved past the floating-point range is out of range,
             * not a NaN input */
            int given_finite = 1;
            for (int c = 0; c < 3; ++c) {
                const double g = bytes == 8 ? ((const double *)points)[3 * i + (size_t)c]
                                            : (double)((const float *)points)[3 * i + (size_t)c];
                given_finite &= isfinite(g) != 0;
            }
            if (given_finite) {
                pts_end(in);
                return TTD_ERR_COORDINATE_RANGE;
            }
            ++in->nonfinite;
        } else if (fabs(x[0]) > range || fabs(x[1]) > range || fabs(x[2]) > range) {
            pts_end(in);
            return TTD_ERR_COORDINATE_RANGE;
        }
    }
    return TTD_OK;
}

/* The call's status once the query returned st. */
static ttd_status pts_status(ttd_status st, const pts_in *in)
{
    return st == TTD_OK && in->nonfinite ? TTD_ERR_NONFINITE_INPUT : st;
}

/* ---- the reference: one point, one triangle ----------------------------------------------- */

#define TTD_POINT_TRIANGLE(real, sfx, REAL_EPS_)                                                   \
    ttd_status ttd_point_triangle_##sfx(const real p[3], const real tri[9], ttd_point_result_##sfx *out) \
    {                                                                                          \
        if (p == NULL || tri == NULL || out == NULL)                                           \
            return TTD_ERR_NULL_POINTER;                                                       \
        memset(out, 0, sizeof *out);                                                           \
        const double range = ttd_mesh_range((int)sizeof(real));                               \
        int finite = 1;                                                                        \
        for (int i = 0; i < 12; ++i) {                                                         \
            const real x = i < 3 ? p[i] : tri[i - 3];                                          \
            finite &= isfinite(x) != 0;                                                        \
            if (isfinite(x) && fabs((double)x) > range)                                        \
                return TTD_ERR_COORDINATE_RANGE;                                               \
        }                                                                                      \
        if (!finite) {                                                                         \
            out->distance = (real)NAN;                                                         \
            for (int c = 0; c < 3; ++c)                                                        \
                out->point[c] = out->bary[c] = (real)NAN;                                      \
            out->triangle = UINT32_MAX;                                                        \
            out->flags = TTD_POINT_NONFINITE;                                                  \
            return TTD_ERR_NONFINITE_INPUT;                                                    \
        }                                                                                      \
        real f[TTD_PT_COUNT];                                                                  \
        ttd_point_prepare_##sfx(tri, f, 1);                                                    \
        out->distance = ttd_point_eval_##sfx(f, 1, p, out->point, out->bary);                 \
        out->feature = (uint8_t)((out->bary[0] > 0 ? 1u : 0u) | (out->bary[1] > 0 ? 2u : 0u) | \
                                 (out->bary[2] > 0 ? 4u : 0u));                                \
        out->flags = f[TTD_PT_INN] > 0 ? 0 : TTD_POINT_DEGENERATE;                             \
        return TTD_OK;                                                                         \
    }

TTD_POINT_TRIANGLE(double, d, DBL_EPSILON)
TTD_POINT_TRIANGLE(float, f, FLT_EPSILON)

/* ---- closest points ----------------------------------------------------------------------- */

#define TTD_POINTS_CLOSEST(real, sfx)                                                              \
    ttd_status ttd_points_closest_##sfx(const ttd_options *opt, const ttd_mesh *mesh, size_t n, const real *points, \
                                        const real *pose, real upper_bound, ttd_point_result_##sfx *results) \
    {                                                                                          \
        ttd_engine_config cfg;                                                                 \
        pts_in in;                                                                             \
        ttd_status st = pts_begin(opt, mesh, n, points, pose, (int)sizeof(real), results != NULL, \
                                  sizeof *results, upper_bound >= 0, &cfg, &in);               \
        if (st != TTD_OK)                                                                      \
            return st;                                                                         \
        st = ttd_points_query_closest_##sfx(&cfg, mesh, n, in.pts, upper_bound, results);      \
        for (size_t i = 0; st == TTD_OK && pose != NULL && i < n; ++i)                         \
            TTD_POINT_BACK(real, pose, results[i].point);                                            \
        pts_end(&in);                                                                          \
        return pts_status(st, &in);                                                            \
    }

TTD_POINTS_CLOSEST(double, d)
TTD_POINTS_CLOSEST(float, f)

/* ---- winding numbers, inside, signed distances ------------------------------------------- */

/* The winding numbers of the checked points into w (n doubles, allocated here when *w is NULL);
 * with proven not NULL, for their side of 1/2 (points/points.h), and whether it is proven. */
static ttd_status pts_winding(const ttd_engine_config *cfg, const ttd_mesh *mesh, size_t n, const pts_in *in, double **w,
                              uint8_t *proven)
{
    if (*w == NULL && (*w = malloc(n * sizeof **w)) == NULL)
        return TTD_ERR_OUT_OF_MEMORY;
    return ttd_points_query_winding(cfg, mesh, n, in->pts, *w, proven);
}

ttd_status ttd_points_winding_number_d(const ttd_options *opt, const ttd_mesh *mesh, size_t n, const double *points,
                                       const double *pose, double *winding)
{
    ttd_engine_config cfg;
    pts_in in;
    ttd_status st = pts_begin(opt, mesh, n, points, pose, 8, winding != NULL, sizeof(double), 1, &cfg, &in);
    if (st != TTD_OK)
        return st;
    st = pts_winding(&cfg, mesh, n, &in, &winding, NULL);
    pts_end(&in);
    return pts_status(st, &in);
}

ttd_status ttd_points_winding_number_f(const ttd_options *opt, const ttd_mesh *mesh, size_t n, const float *points,
                                       const float *pose, float *winding)
{
    ttd_engine_config cfg;
    pts_in in;
    ttd_status st = pts_begin(opt, mesh, n, points, pose, 4, winding != NULL, sizeof(double), 1, &cfg, &in);
    if (st != TTD_OK)
        return st;
    double *w = NULL;
    st = pts_winding(&cfg, mesh, n, &in, &w, NULL);
    for (size_t i = 0; st == TTD_OK && i < n; ++i) {
        /* rounded to float on its side of the inside rule: |w| just below 1/2 must not become 1/2 */
        float f = (float)w[i];
        if (ttd_winding_inside((double)f) != ttd_winding_inside(w[i]))
            f = nextafterf(f, 0.0f);
        winding[i] = f;
    }
    free(w);
    pts_end(&in);
    return pts_status(st, &in);
}

#define TTD_POINTS_CONTAINS(real, sfx)                                                             \
    ttd_status ttd_points_contains_##sfx(const ttd_options *opt, const ttd_mesh *mesh, size_t n, const real *points, \
                                         const real *pose, uint8_t *inside)                    \
    {                                                                                          \
        ttd_engine_config cfg;                                                                 \
        pts_in in;                                                                             \
        ttd_status st = pts_begin(opt, mesh, n, points, pose, (int)sizeof(real), inside != NULL, sizeof(double), 1, \
                                  &cfg, &in);                                                  \
        if (st != TTD_OK)                                                                      \
            return st;                                                                         \
        double *w = NULL;                                                                      \
        st = pts_winding(&cfg, mesh, n, &in, &w, inside);                                      \
        for (size_t i = 0; st == TTD_OK && i < n; ++i)                                         \
            inside[i] = (uint8_t)ttd_winding_inside(w[i]);                                     \
        free(w);                                                                               \
        pts_end(&in);                                                                          \
        return pts_status(st, &in);                                                            \
    }

TTD_POINTS_CONTAINS(double, d)
TTD_POINTS_CONTAINS(float, f)

/* Signed distances of the checked points (in the mesh's frame) into distance and r (r required
 * here: the caller's or scratch); points of r stay in the mesh's frame. */
#define TTD_SIGNED_BODY(real, sfx)                                                                 \
    static ttd_status signed_##sfx(const ttd_engine_config *cfg, const ttd_mesh *mesh, size_t n, const pts_in *in, \
                                   real upper_bound, real *distance, ttd_point_result_##sfx *r)   \
    {                                                                                          \
        ttd_status st = ttd_points_query_closest_##sfx(cfg, mesh, n, in->pts, upper_bound, r);  \
        double *w = NULL;                                                                      \
        uint8_t *proven = NULL;                                                                \
        /* a mesh of one triangle contains no point (its |w| is below 1/2): no winding number */ \
        const int one = mesh->nt == 1;                                                         \
        if (st == TTD_OK && !one)                                                              \
            st = (proven = malloc(n ? n : 1)) ? pts_winding(cfg, mesh, n, in, &w, proven) : TTD_ERR_OUT_OF_MEMORY; \
        for (size_t i = 0; st == TTD_OK && !one && i < n; ++i) {                               \
            const int inside = ttd_winding_inside(w[i]);                                       \
            if (inside)                                                                        \
                r[i].flags |= TTD_POINT_INSIDE;                                                \
            if (!proven[i] && !(r[i].flags & TTD_POINT_NONFINITE))                             \
                r[i].flags |= TTD_POINT_SIGN_UNPROVEN;                                         \
            if (distance)                                                                      \
                distance[i] = inside ? -r[i].distance : r[i].distance;                         \
        }                                                                                      \
        for (size_t i = 0; st == TTD_OK && one && distance && i < n; ++i)                      \
            distance[i] = r[i].distance;                                                       \
        free(w);                                                                               \
        free(proven);                                                                          \
        return st;                                                                             \
    }

TTD_SIGNED_BODY(double, d)
TTD_SIGNED_BODY(float, f)

/* Points per chunk of a signed distance without the caller's results. */
#define PTS_CHUNK 8192

#define TTD_POINTS_SIGNED(real, sfx)                                                               \
    ttd_status ttd_points_signed_distance_##sfx(const ttd_options *opt, const ttd_mesh *mesh, size_t n, \
                                                const real *points, const real *pose, real upper_bound, \
                                                real *distance, ttd_point_result_##sfx *results) \
    {                                                                                          \
        ttd_engine_config cfg;                                                                 \
        pts_in in;                                                                             \
        ttd_status st = pts_begin(opt, mesh, n, points, pose, (int)sizeof(real), distance || results, \
                                  sizeof(ttd_point_result_##sfx), upper_bound >= 0, &cfg, &in); \
        if (st != TTD_OK)                                                                      \
            return st;                                                                         \
        /* without the caller's results, a scratch of PTS_CHUNK results, reused chunk by chunk (it   \
         * stays in the cache, and a large one would cost its page faults on every call) */      \
        const size_t chunk = results ? (n ? n : 1) : (n < PTS_CHUNK ? (n ? n : 1) : PTS_CHUNK);  \
        ttd_point_result_##sfx *r = results ? results : malloc(chunk * sizeof *r);             \
        st = r ? TTD_OK : TTD_ERR_OUT_OF_MEMORY;                                               \
        /* more than one chunk: the chunks are runs of the whole batch's spatial order, gathered   \
         * (a chunk of scattered points would lose the closest point's seeds and the cache: 8,192  \
         * random points cost 1.3x a point of 50,000 in order); the answers are each point's own */ \
        const ttd_points_data *pd_ = st == TTD_OK && n > chunk ? ttd_points_data_get(mesh, cfg.threads) : NULL; \
        size_t *order = pd_ ? ttd_points_order(mesh, pd_, n, in.pts, (int)sizeof(real)) : NULL; \
        real *gp = order ? malloc(chunk * 4 * sizeof *gp) : NULL, *gd = gp ? gp + 3 * chunk : NULL; \
        for (size_t i0 = 0; st == TTD_OK && i0 < n; i0 += chunk) {                             \
            const size_t k = n - i0 < chunk ? n - i0 : chunk;                                  \
            pts_in part = {(const real *)in.pts + 3 * i0, NULL, 0};                            \
            real *dk = distance ? distance + i0 : NULL;                                        \
            if (gp != NULL) {                                                                  \
                for (size_t j = 0; j < k; ++j)                                                 \
                    memcpy(gp + 3 * j, (const real *)in.pts + 3 * order[i0 + j], 3 * sizeof *gp); \
                part.pts = gp;                                                                 \
                dk = distance ? gd : NULL;                                                     \
            }                                                                                  \
            st = signed_##sfx(&cfg, mesh, k, &part, upper_bound, dk, results ? results + i0 : r); \
            for (size_t j = 0; st == TTD_OK && gp != NULL && distance && j < k; ++j)           \
                distance[order[i0 + j]] = gd[j];                                               \
        }                                                                                      \
        free(gp);                                                                              \
        free(order);                                                                           \
        for (size_t i = 0; st == TTD_OK && results && pose != NULL && i < n; ++i)              \
            TTD_POINT_BACK(real, pose, results[i].point);                                            \
        if (r != results)                                                                      \
            free(r);                                                                           \
        pts_end(&in);                                                                          \
        return pts_status(st, &in);                                                            \
    }

TTD_POINTS_SIGNED(double, d)
TTD_POINTS_SIGNED(float, f)

/* ---- grids ------------------------------------------------------------------------------- */

/* One slab (i fixed) of ny nz points at a time: its points into scratch, then the signed distances
 * straight into out. */
#define TTD_SDF_GRID(real, sfx)                                                                    \
    ttd_status ttd_sdf_grid_##sfx(const ttd_options *opt, const ttd_mesh *mesh, const real origin[3], \
                                  const real step[3], const size_t dims[3], real *out)           \
    {                                                                                          \
        if (dims == NULL)                                                                      \
            return TTD_ERR_NULL_POINTER;                                                       \
        const size_t slab = dims[1] * dims[2];                                                 \
        const int big = (dims[2] != 0 && dims[1] > SIZE_MAX / dims[2]) ||                       \
                        (slab != 0 && dims[0] > SIZE_MAX / slab);                              \
        ttd_engine_config cfg;                                                                 \
        ttd_status st = ttd_prepare(opt, mesh && origin && step && out, big ? 1 : dims[0] * slab, \
                                    big || ttd_too_large(dims[0] * slab, 1, sizeof(real)) ||   \
                                        ttd_too_large(slab, 3, sizeof(real)),                  \
                                    &cfg);                                                     \
        if (st != TTD_OK)                                                                      \
            return st;                                                                         \
        int finite = 1; /* and each step > 0, as the CLI and Python ask: a grid runs forward */ \
        for (int c = 0; c < 3; ++c)                                                            \
            finite &= isfinite(origin[c]) && isfinite(step[c]) && step[c] > 0;                 \
        if (cfg.method != TTD_METHOD_EXACT || !finite)                                         \
            return TTD_ERR_BAD_OPTIONS;                                                        \
        if (mesh->bytes != (int)sizeof(real))                                                  \
            return TTD_ERR_PRECISION_MISMATCH;                                                 \
        const double range = ttd_mesh_range((int)sizeof(real));                               \
        for (int c = 0; c < 3; ++c) {                                                          \
            const real last = origin[c] + (real)(dims[c] - 1) * step[c];                       \
            if (!(fabs((double)origin[c]) <= range && fabs((double)last) <= range))            \
                return TTD_ERR_COORDINATE_RANGE;                                               \
        }                                                                                      \
        real *pts = malloc(3 * slab * sizeof *pts);                                            \
        ttd_point_result_##sfx *r = malloc(slab * sizeof *r);                                  \
        st = pts && r ? TTD_OK : TTD_ERR_OUT_OF_MEMORY;                                        \
        for (size_t i = 0; st == TTD_OK && i < dims[0]; ++i) {                                 \
            const real x = origin[0] + (real)i * step[0];                                      \
            for (size_t j = 0; j < dims[1]; ++j) {                                             \
                const real y = origin[1] + (real)j * step[1];                                  \
                for (size_t k = 0; k < dims[2]; ++k) {                                         \
                    real *p = pts + 3 * (j * dims[2] + k);                                     \
                    p[0] = x;                                                                  \
                    p[1] = y;                                                                  \
                    p[2] = origin[2] + (real)k * step[2];                                      \
                }                                                                              \
            }                                                                                  \
            const pts_in in = {pts, NULL, 0};                                                  \
            st = signed_##sfx(&cfg, mesh, slab, &in, (real)INFINITY, out + i * slab, r);      \
        }                                                                                      \
        free(pts);                                                                             \
        free(r);                                                                               \
        return st;                                                                             \
    }

TTD_SDF_GRID(double, d)
TTD_SDF_GRID(float, f)
