/* SPDX-License-Identifier: MIT */
/* The "cuda-host" row in double, for the tests only: the lane-generic kernels compiled by the host C
 * compiler through the CUDA lane vocabulary (simd/lanes_cuda.h: one lane, a real per "vector", a
 * bool per mask), the same source that src/gpu/ compiles as device code with nvcc. CI has no GPU
 * and may have no nvcc; this row is how it tests that source (tests/isa_rows.h lists it, so
 * test_isa_kernels and test_lanes hold it to every other row's contract, and test_isa_kernels
 * requires the scalar row's bits of it). Not part of the library: the dispatcher never sees it. */
#define TTDW_USE_CUDA 1
#define TTD_PRECISION_DOUBLE
#include "simd/kernels_all.h"
#include "gpu/gpu_pair_impl.h"
#include "gpu/gpu_walk_impl.h"
#include "gpu/gpu_points_impl.h"
#include "gpu/gpu_signed_impl.h"
#include "gpu/gpu_sign_mode.h"
#include "mesh/mesh.h"
#include "points/points.h"
#include "cuda_host.h"
#include "cuda_host_impl.h"

const ttd_kernels_d ttd_kernels_cuda_host_d = TTD_LANE_ROW(TTD_ISA_SCALAR);

int ttd_lanes_probe_cuda_host_d(int op, const double *a, const double *b, const double *c, double *out)
{
    return lanes_probe(op, a, b, c, out);
}

void ttd_cuda_host_batch_d(size_t n, const double *s, const double *t, double *distance, ttd_result_d *results)
{
    for (size_t i = 0; i < n; ++i) /* what thread i of src/gpu/'s kernel runs */
        gpu_pair(i, s, t, distance, results);
}


int ttd_cuda_host_mesh_height_d(const struct ttd_mesh *m)
{
    return host_view(m).height;
}

void ttd_cuda_host_mesh_distance_d(const struct ttd_mesh *a, const struct ttd_mesh *b, size_t k, const double *poses,
                                     double upper_bound, uint64_t vote, ttd_mesh_result_d *out)
{
    host_mesh_distance(a, b, k, poses, upper_bound, vote, out);
}

void ttd_cuda_host_mesh_collide_d(const struct ttd_mesh *a, const struct ttd_mesh *b, size_t k, const double *poses,
                                    double margin, uint64_t vote, ttd_collision *out)
{
    host_mesh_collide(a, b, k, poses, margin, vote, out);
}

int ttd_cuda_host_closest_d(const struct ttd_mesh *m, size_t n, const double *points, double upper_bound,
                              ttd_point_result_d *out)
{
    return host_closest(m, n, points, upper_bound, out);
}

int ttd_cuda_host_signed_d(const struct ttd_mesh *m, size_t n, const double *points, double upper_bound, double *distance,
                           ttd_point_result_d *out)
{
    return host_signed(m, n, points, upper_bound, distance, out);
}
