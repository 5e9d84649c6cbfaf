/* SPDX-License-Identifier: MIT */
/* The GPU library of a build without CUDA (TTD_CUDA=OFF, or AUTO without a CUDA toolkit): the
 * entry points of include/ttd/ttd_gpu.h, each saying TTD_GPU_ERR_NOT_BUILT, so that programs
 * (the ttd CLI, the tests) link and run the same with or without the GPU part. */
#include <string.h>

#include "ttd/ttd_gpu.h"

ttd_gpu_status ttd_gpu_query(ttd_gpu_info *info)
{
    if (!info)
        return TTD_GPU_ERR_NULL_POINTER;
    memset(info, 0, sizeof *info);
    info->device = -1;
    strcpy(info->message, "built without CUDA");
    return TTD_GPU_ERR_NOT_BUILT;
}

ttd_gpu_status ttd_gpu_batch_d(size_t n, const double *s, const double *t, double *distance, ttd_result_d *results,
                               void *stream)
{
    (void)n, (void)s, (void)t, (void)distance, (void)results, (void)stream;
    return TTD_GPU_ERR_NOT_BUILT;
}

ttd_gpu_status ttd_gpu_batch_f(size_t n, const float *s, const float *t, float *distance, ttd_result_f *results,
                               void *stream)
{
    (void)n, (void)s, (void)t, (void)distance, (void)results, (void)stream;
    return TTD_GPU_ERR_NOT_BUILT;
}

ttd_gpu_status ttd_gpu_batch_host_d(size_t n, const double *s, const double *t, double *distance, ttd_result_d *results)
{
    (void)n, (void)s, (void)t, (void)distance, (void)results;
    return TTD_GPU_ERR_NOT_BUILT;
}

ttd_gpu_status ttd_gpu_batch_host_f(size_t n, const float *s, const float *t, float *distance, ttd_result_f *results)
{
    (void)n, (void)s, (void)t, (void)distance, (void)results;
    return TTD_GPU_ERR_NOT_BUILT;
}

void ttd_gpu_mesh_free(ttd_gpu_mesh *mesh)
{
    (void)mesh;
}

ttd_gpu_status ttd_gpu_mesh_upload(const ttd_mesh *mesh, ttd_gpu_mesh **out)
{
    (void)mesh;
    if (out)
        *out = NULL;
    return TTD_GPU_ERR_NOT_BUILT;
}

ttd_gpu_status ttd_gpu_mesh_distance_d(const ttd_gpu_mesh *a, const ttd_gpu_mesh *b, size_t k, const double *poses,
                                       double upper_bound, ttd_mesh_result_d *out, void *stream)
{
    (void)a, (void)b, (void)k, (void)poses, (void)upper_bound, (void)out, (void)stream;
    return TTD_GPU_ERR_NOT_BUILT;
}

ttd_gpu_status ttd_gpu_mesh_distance_f(const ttd_gpu_mesh *a, const ttd_gpu_mesh *b, size_t k, const float *poses,
                                       float upper_bound, ttd_mesh_result_f *out, void *stream)
{
    (void)a, (void)b, (void)k, (void)poses, (void)upper_bound, (void)out, (void)stream;
    return TTD_GPU_ERR_NOT_BUILT;
}

ttd_gpu_status ttd_gpu_mesh_collide_d(const ttd_gpu_mesh *a, const ttd_gpu_mesh *b, size_t k, const double *poses,
                                      double margin, ttd_collision *out, void *stream)
{
    (void)a, (void)b, (void)k, (void)poses, (void)margin, (void)out, (void)stream;
    return TTD_GPU_ERR_NOT_BUILT;
}

ttd_gpu_status ttd_gpu_mesh_collide_f(const ttd_gpu_mesh *a, const ttd_gpu_mesh *b, size_t k, const float *poses,
                                      float margin, ttd_collision *out, void *stream)
{
    (void)a, (void)b, (void)k, (void)poses, (void)margin, (void)out, (void)stream;
    return TTD_GPU_ERR_NOT_BUILT;
}

ttd_gpu_status ttd_gpu_points_closest_d(const ttd_gpu_mesh *mesh, size_t n, const double *points, double upper_bound,
                                        ttd_point_result_d *out, void *stream)
{
    (void)mesh, (void)n, (void)points, (void)upper_bound, (void)out, (void)stream;
    return TTD_GPU_ERR_NOT_BUILT;
}

ttd_gpu_status ttd_gpu_points_closest_f(const ttd_gpu_mesh *mesh, size_t n, const float *points, float upper_bound,
                                        ttd_point_result_f *out, void *stream)
{
    (void)mesh, (void)n, (void)points, (void)upper_bound, (void)out, (void)stream;
    return TTD_GPU_ERR_NOT_BUILT;
}

/* ---- signed distances of points (ttd_gpu.h) ---- */

ttd_gpu_status ttd_gpu_points_signed_distance_d(const ttd_gpu_mesh *mesh, size_t n, const double *points,
                                                double upper_bound, double *distance, ttd_point_result_d *results,
                                                void *stream)
{
    (void)mesh, (void)n, (void)points, (void)upper_bound, (void)distance, (void)results, (void)stream;
    return TTD_GPU_ERR_NOT_BUILT;
}

ttd_gpu_status ttd_gpu_points_signed_distance_f(const ttd_gpu_mesh *mesh, size_t n, const float *points,
                                                float upper_bound, float *distance, ttd_point_result_f *results,
                                                void *stream)
{
    (void)mesh, (void)n, (void)points, (void)upper_bound, (void)distance, (void)results, (void)stream;
    return TTD_GPU_ERR_NOT_BUILT;
}

/* ---- continuous collision (docs/ccd.md, section 14) ---- */
#define TTD_GPU_CCD_STUB(name, real)                                                                        \
    ttd_gpu_status name(size_t n, const real *a0, const real *b0, const real *a1, const real *b1, double delta, \
                        ttd_ccd_result *out, void *stream)                                                  \
    {                                                                                                       \
        (void)n, (void)a0, (void)b0, (void)a1, (void)b1, (void)delta, (void)out, (void)stream;              \
        return TTD_GPU_ERR_NOT_BUILT;                                                                       \
    }
TTD_GPU_CCD_STUB(ttd_gpu_ccd_vertex_face_d, double)
TTD_GPU_CCD_STUB(ttd_gpu_ccd_vertex_face_f, float)
TTD_GPU_CCD_STUB(ttd_gpu_ccd_edge_edge_d, double)
TTD_GPU_CCD_STUB(ttd_gpu_ccd_edge_edge_f, float)
TTD_GPU_CCD_STUB(ttd_gpu_ccd_triangles_d, double)
TTD_GPU_CCD_STUB(ttd_gpu_ccd_triangles_f, float)
/* ---- end of continuous collision ---- */
