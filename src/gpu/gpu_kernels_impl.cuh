/* SPDX-License-Identifier: MIT */
/* The device kernels for one precision (gpu_d.cu, gpu_f.cu define TTD_PRECISION_* and the
 * exported names): the CPU rows' lane-generic kernels (simd/kernel_exact.h, kernel_node.h)
 * compiled through the CUDA lane vocabulary (simd/lanes_cuda.h), one pair per thread. Built with
 * -fmad=false -prec-div=true -prec-sqrt=true -ftz=false (src/gpu/CMakeLists.txt), so each
 * operation rounds as on the CPU (docs/gpu.md). */
#include <stdint.h>
#include <string.h>

#include <cuda_runtime.h>

#define TTDW_USE_CUDA 1
#include "core/precision.h"
#include "core/kernels.h"
#include "core/point_layout.h"
#include "simd/lanes.h"
#include "simd/lanes_precision.h"
#include "simd/kernel_common.h"
#include "simd/kernel_exact.h"
#include "simd/kernel_node.h"
#include "simd/kernel_point.h"
#include "gpu/gpu_pair_impl.h"
#include "gpu/gpu_walk_impl.h"
#include "gpu/gpu_points_impl.h"
#include "gpu/gpu_signed_impl.h"
#include "gpu/gpu_internal.h"

/* Threads a block and the blocks an SM must hold at once (__launch_bounds__'s second argument,
 * which caps the registers a thread may use at 65536 / (GPU_BLOCK * GPU_MIN_BLOCKS); 0: none). The
 * defaults were chosen on an H200 (docs/gpu.md, section 5); other values build for the tuning
 * runs of scripts/test-gpu-device.sh (-DTTD_GPU_BLOCK=..., -DTTD_GPU_MIN_BLOCKS=...). */
#ifndef TTD_GPU_BLOCK
#define TTD_GPU_BLOCK 128
#endif
#ifndef TTD_GPU_MIN_BLOCKS
#define TTD_GPU_MIN_BLOCKS 0
#endif
#define GPU_BLOCK TTD_GPU_BLOCK
#if TTD_GPU_MIN_BLOCKS > 0
#define GPU_BOUNDS __launch_bounds__(TTD_GPU_BLOCK, TTD_GPU_MIN_BLOCKS)
#else /* no minimum: the compiler's choice of registers */
#define GPU_BOUNDS __launch_bounds__(TTD_GPU_BLOCK)
#endif

/* The exact method, one pair per thread; a grid-stride loop for grids past the launch limit. */
__global__ void GPU_BOUNDS gpu_exact_kernel(size_t n, const real *s, const real *t,
                                                             real *distance, ttd_result *results)
{
    const size_t stride = (size_t)gridDim.x * blockDim.x;
    for (size_t i = (size_t)blockIdx.x * blockDim.x + threadIdx.x; i < n; i += stride)
        gpu_pair(i, s, t, distance, results);
}

/* The distance-only specialisation: no results pointer, so the compiler keeps only the running
 * minimum (kx_run_dist). */
__global__ void GPU_BOUNDS gpu_exact_dist_kernel(size_t n, const real *s, const real *t,
                                                                  real *distance)
{
    const size_t stride = (size_t)gridDim.x * blockDim.x;
    for (size_t i = (size_t)blockIdx.x * blockDim.x + threadIdx.x; i < n; i += stride)
        gpu_pair(i, s, t, distance, NULL);
}

/* The mesh queries' node test, one node test per thread: query q[i] against the 8 children of
 * node y[i], into lb2 and sep at 8i. Not yet used by an entry point (the GPU mesh queries are
 * still to come, issue 20); built so that the device compilation covers kernel_node.h. */
__global__ void GPU_BOUNDS gpu_node_kernel(size_t k, const ttd_box_query *q, const ttd_node *y,
                                                            real *lb2, real *sep)
{
    const size_t stride = (size_t)gridDim.x * blockDim.x;
    for (size_t i = (size_t)blockIdx.x * blockDim.x + threadIdx.x; i < k; i += stride)
        node_test(&q[i], &y[i], lb2 + TTD_NODE_WIDTH * i, sep + TTD_NODE_WIDTH * i);
}

/* Mesh against mesh, one pose per thread (gpu_walk_impl.h): the minimum distance, or collision. */
__global__ void GPU_BOUNDS gpu_mesh_distance_kernel(gw_mesh a, gw_mesh b, size_t k, const real *poses,
                                                    real upper_bound, gw_mesh_result *out)
{
    const size_t stride = (size_t)gridDim.x * blockDim.x;
    for (size_t i = (size_t)blockIdx.x * blockDim.x + threadIdx.x; i < k; i += stride)
        gw_distance_pose(&a, &b, poses + 12 * i, upper_bound, 0, &out[i]);
}

__global__ void GPU_BOUNDS gpu_mesh_collide_kernel(gw_mesh a, gw_mesh b, size_t k, const real *poses, real margin,
                                                   ttd_collision *out)
{
    const size_t stride = (size_t)gridDim.x * blockDim.x;
    for (size_t i = (size_t)blockIdx.x * blockDim.x + threadIdx.x; i < k; i += stride)
        gw_collide_pose(&a, &b, poses + 12 * i, margin, 0, &out[i]);
}

/* The closest point of a mesh, one point per thread (gpu_points_impl.h). */
__global__ void GPU_BOUNDS gpu_points_closest_kernel(gp_mesh m, size_t n, const real *points, real upper_bound,
                                                     gp_point_result *out)
{
    const size_t stride = (size_t)gridDim.x * blockDim.x;
    for (size_t i = (size_t)blockIdx.x * blockDim.x + threadIdx.x; i < n; i += stride)
        gp_closest(&m, points + 3 * i, upper_bound, &out[i]);
}

static unsigned gpu_grid(size_t n)
{
    const size_t blocks = (n + GPU_BLOCK - 1) / GPU_BLOCK;
    return blocks > 1u << 30 ? 1u << 30 : (unsigned)blocks;
}

static int gpu_launch_exact(size_t n, const real *s, const real *t, real *distance, ttd_result *results,
                            void *stream)
{
    cudaStream_t st = (cudaStream_t)stream;
    if (results)
        gpu_exact_kernel<<<gpu_grid(n), GPU_BLOCK, 0, st>>>(n, s, t, distance, results);
    else
        gpu_exact_dist_kernel<<<gpu_grid(n), GPU_BLOCK, 0, st>>>(n, s, t, distance);
    return (int)cudaGetLastError();
}

static int gpu_launch_node(size_t k, const ttd_box_query *q, const ttd_node *y, real *lb2, real *sep, void *stream)
{
    gpu_node_kernel<<<gpu_grid(k), GPU_BLOCK, 0, (cudaStream_t)stream>>>(k, q, y, lb2, sep);
    return (int)cudaGetLastError();
}

/* The device walk's view of an uploaded mesh (gpu_internal.h's ttd_gpu_mesh_view). */
static gw_mesh gpu_view(const ttd_gpu_mesh_view *v)
{
    gw_mesh g;
    g.nodes = (const ttd_node *)v->nodes;
    g.verts = (const real *)v->verts;
    g.tris = v->tris;
    for (int i = 0; i < 3; ++i)
        g.origin[i] = v->origin[i];
    g.radius = v->radius;
    g.height = v->height;
    return g;
}

static int gpu_launch_mesh(const ttd_gpu_mesh_view *a, const ttd_gpu_mesh_view *b, size_t k, const real *poses,
                           real limit, int collide, void *out, void *stream)
{
    cudaStream_t st = (cudaStream_t)stream;
    if (collide)
        gpu_mesh_collide_kernel<<<gpu_grid(k), GPU_BLOCK, 0, st>>>(gpu_view(a), gpu_view(b), k, poses, limit,
                                                                   (ttd_collision *)out);
    else
        gpu_mesh_distance_kernel<<<gpu_grid(k), GPU_BLOCK, 0, st>>>(gpu_view(a), gpu_view(b), k, poses, limit,
                                                                    (gw_mesh_result *)out);
    return (int)cudaGetLastError();
}

static int gpu_launch_points(const ttd_gpu_mesh_view *v, size_t n, const real *points, real upper_bound,
                             gp_point_result *out, void *stream)
{
    gp_mesh m;
    m.pnodes = (const ttd_pnode *)v->pnodes;
    m.blocks = (const real *)v->blocks;
    for (int i = 0; i < 3; ++i)
        m.origin[i] = v->origin[i];
    m.radius = v->radius;
    m.scale = v->pscale;
    m.stretch = v->pstretch;
    gpu_points_closest_kernel<<<gpu_grid(n), GPU_BLOCK, 0, (cudaStream_t)stream>>>(m, n, points, upper_bound, out);
    return (int)cudaGetLastError();
}

/* ---- signed distances of points (gpu_signed_impl.h) ---- */

__global__ void GPU_BOUNDS gpu_points_signed_kernel(gs_mesh m, size_t n, const real *points, real upper_bound,
                                                    real *distance, gp_point_result *out)
{
    const size_t stride = (size_t)gridDim.x * blockDim.x;
    for (size_t i = (size_t)blockIdx.x * blockDim.x + threadIdx.x; i < n; i += stride) {
        gp_point_result r;
        gs_signed(&m, points + 3 * i, upper_bound, distance ? &distance[i] : NULL, &r);
        if (out)
            out[i] = r;
    }
}

static int gpu_launch_signed(const ttd_gpu_mesh_view *v, size_t n, const real *points, real upper_bound,
                             real *distance, gp_point_result *out, void *stream)
{
    gs_mesh m;
    m.closest.pnodes = (const ttd_pnode *)v->pnodes;
    m.closest.blocks = (const real *)v->blocks;
    for (int i = 0; i < 3; ++i)
        m.closest.origin[i] = m.ray.origin[i] = v->origin[i];
    m.closest.radius = m.ray.radius = v->radius;
    m.closest.scale = m.ray.scale = v->pscale;
    m.closest.stretch = v->pstretch;
    m.ray.rnodes = (const ttd_rnode *)v->rnodes;
    m.ray.verts = v->verts;
    m.ray.tris = v->tris;
    m.ray.bytes = v->bytes;
    m.ray.coord_max = v->coord_max;
    m.mode = v->sign_mode;
    gpu_points_signed_kernel<<<gpu_grid(n), GPU_BLOCK, 0, (cudaStream_t)stream>>>(m, n, points, upper_bound, distance,
                                                                                  out);
    return (int)cudaGetLastError();
}
