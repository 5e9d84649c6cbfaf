/* SPDX-License-Identifier: MIT */
/* The GPU kernels in double (gpu_kernels_impl.cuh) and their exported launchers. */
#define TTD_PRECISION_DOUBLE
#include "gpu/gpu_kernels_impl.cuh"

extern "C" int ttd_gpu_launch_exact_d(size_t n, const double *s, const double *t, double *distance, ttd_result_d *results,
                                      void *stream)
{
    return gpu_launch_exact(n, s, t, distance, results, stream);
}

extern "C" int ttd_gpu_launch_mesh_d(const ttd_gpu_mesh_view *a, const ttd_gpu_mesh_view *b, size_t k,
                                     const double *poses, double limit, int collide, void *out, void *stream)
{
    return gpu_launch_mesh(a, b, k, poses, limit, collide, out, stream);
}

extern "C" int ttd_gpu_launch_points_d(const ttd_gpu_mesh_view *m, size_t n, const double *points,
                                       double upper_bound, ttd_point_result_d *out, void *stream)
{
    return gpu_launch_points(m, n, points, upper_bound, out, stream);
}

extern "C" int ttd_gpu_launch_node_d(size_t k, const ttd_box_query_d *q, const ttd_node_d *y, double *lb2, double *sep,
                                     void *stream)
{
    return gpu_launch_node(k, q, y, lb2, sep, stream);
}

extern "C" int ttd_gpu_kernel_loads(void)
{
    cudaFuncAttributes a;
    return (int)cudaFuncGetAttributes(&a, gpu_exact_dist_kernel);
}

extern "C" int ttd_gpu_kernel_registers_d(void)
{
    cudaFuncAttributes a;
    return cudaFuncGetAttributes(&a, gpu_exact_dist_kernel) == cudaSuccess ? a.numRegs : 0;
}

extern "C" int ttd_gpu_block_threads(void)
{
    return GPU_BLOCK;
}

extern "C" int ttd_gpu_min_blocks(void)
{
    return TTD_GPU_MIN_BLOCKS;
}

/* ---- signed distances of points ---- */

extern "C" int ttd_gpu_launch_signed_d(const ttd_gpu_mesh_view *m, size_t n, const double *points, double upper_bound,
                                       double *distance, ttd_point_result_d *out, void *stream)
{
    return gpu_launch_signed(m, n, points, upper_bound, distance, out, stream);
}
