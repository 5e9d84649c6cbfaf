/* SPDX-License-Identifier: MIT */
/* The GPU kernels in float (gpu_kernels_impl.cuh) and their exported launchers. */
#define TTD_PRECISION_FLOAT
#include "gpu/gpu_kernels_impl.cuh"

extern "C" int ttd_gpu_launch_exact_f(size_t n, const float *s, const float *t, float *distance, ttd_result_f *results,
                                      void *stream)
{
    return gpu_launch_exact(n, s, t, distance, results, stream);
}

extern "C" int ttd_gpu_launch_mesh_f(const ttd_gpu_mesh_view *a, const ttd_gpu_mesh_view *b, size_t k,
                                     const float *poses, float limit, int collide, void *out, void *stream)
{
    return gpu_launch_mesh(a, b, k, poses, limit, collide, out, stream);
}

extern "C" int ttd_gpu_launch_points_f(const ttd_gpu_mesh_view *m, size_t n, const float *points,
                                       float upper_bound, ttd_point_result_f *out, void *stream)
{
    return gpu_launch_points(m, n, points, upper_bound, out, stream);
}

extern "C" int ttd_gpu_launch_node_f(size_t k, const ttd_box_query_f *q, const ttd_node_f *y, float *lb2, float *sep,
                                     void *stream)
{
    return gpu_launch_node(k, q, y, lb2, sep, stream);
}

extern "C" int ttd_gpu_kernel_registers_f(void)
{
    cudaFuncAttributes a;
    return cudaFuncGetAttributes(&a, gpu_exact_dist_kernel) == cudaSuccess ? a.numRegs : 0;
}

/* ---- signed distances of points ---- */

extern "C" int ttd_gpu_launch_signed_f(const ttd_gpu_mesh_view *m, size_t n, const float *points, float upper_bound,
                                       float *distance, ttd_point_result_f *out, void *stream)
{
    return gpu_launch_signed(m, n, points, upper_bound, distance, out, stream);
}
