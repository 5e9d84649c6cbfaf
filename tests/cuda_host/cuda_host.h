/* SPDX-License-Identifier: MIT */
/* The test-only "cuda-host" row (cuda_host_d.c, cuda_host_f.c): src/simd/lanes_cuda.h compiled
 * for the host, one lane, and the GPU batch's per-thread body on it. */
#ifndef TTD_TEST_CUDA_HOST_H
#define TTD_TEST_CUDA_HOST_H

#include <stdint.h>

#include "core/kernels.h"
#include "ttd/ttd.h"

extern const ttd_kernels_d ttd_kernels_cuda_host_d;
extern const ttd_kernels_f ttd_kernels_cuda_host_f;
int ttd_lanes_probe_cuda_host_d(int op, const double *a, const double *b, const double *c, double *out);
int ttd_lanes_probe_cuda_host_f(int op, const float *a, const float *b, const float *c, float *out);
/* What the GPU batch (src/gpu/) runs, thread i for pair i, run here by a loop over i: the one
 * source (src/gpu/gpu_pair_impl.h) compiled for the host. */
void ttd_cuda_host_batch_d(size_t n, const double *s, const double *t, double *distance, ttd_result_d *results);
void ttd_cuda_host_batch_f(size_t n, const float *s, const float *t, float *distance, ttd_result_f *results);

/* What the GPU pose queries (src/gpu/gpu_walk_impl.h) run, thread i for pose i, run here by a loop:
 * the device walk on the CPU's mesh arrays. vote 0: the walk's own order; else the seed of the
 * host's stand-in for the warp vote (another order of the same work). */
void ttd_cuda_host_mesh_distance_d(const struct ttd_mesh *a, const struct ttd_mesh *b, size_t k, const double *poses,
                                   double upper_bound, uint64_t vote, ttd_mesh_result_d *out);
void ttd_cuda_host_mesh_distance_f(const struct ttd_mesh *a, const struct ttd_mesh *b, size_t k, const float *poses,
                                   float upper_bound, uint64_t vote, ttd_mesh_result_f *out);
void ttd_cuda_host_mesh_collide_d(const struct ttd_mesh *a, const struct ttd_mesh *b, size_t k, const double *poses,
                                  double margin, uint64_t vote, ttd_collision *out);
void ttd_cuda_host_mesh_collide_f(const struct ttd_mesh *a, const struct ttd_mesh *b, size_t k, const float *poses,
                                  float margin, uint64_t vote, ttd_collision *out);
/* The closest point on the host build of the device walk (src/gpu/gpu_points_impl.h), point i as
 * thread i would, on the mesh's point data as the CPU made it; -1 when it cannot be made. */
int ttd_cuda_host_closest_d(const struct ttd_mesh *m, size_t n, const double *points, double upper_bound,
                            ttd_point_result_d *out);
int ttd_cuda_host_closest_f(const struct ttd_mesh *m, size_t n, const float *points, float upper_bound,
                            ttd_point_result_f *out);
/* The signed distance on the host build of the device code (src/gpu/gpu_signed_impl.h), point i as
 * thread i would, on the mesh's point data as the CPU made it: the sign mode the device would use
 * (1 unsigned, 2 the ray count), 0 where the device entry would refuse the mesh, -1 when the point
 * data cannot be made. distance may be NULL. */
int ttd_cuda_host_signed_d(const struct ttd_mesh *m, size_t n, const double *points, double upper_bound,
                           double *distance, ttd_point_result_d *out);
int ttd_cuda_host_signed_f(const struct ttd_mesh *m, size_t n, const float *points, float upper_bound,
                           float *distance, ttd_point_result_f *out);
/* The node levels below a mesh's root box, as the device entries check them against the stack. */
int ttd_cuda_host_mesh_height_d(const struct ttd_mesh *m);
int ttd_cuda_host_mesh_height_f(const struct ttd_mesh *m);

/* ---- continuous collision (cuda_host_ccd.c) ---- */
/* What the device's CCD kernels (src/gpu/gpu_ccd.cu) run, thread i for query i: kind 1 vertex-face,
 * 2 edge-edge, 3 triangles; the arrays as the CPU entries take them, float when is_float. */
void ttd_cuda_host_ccd(int kind, int is_float, size_t n, const void *a0, const void *b0, const void *a1,
                       const void *b1, double delta, ttd_ccd_result *out);
/* ---- end of continuous collision ---- */

#endif /* TTD_TEST_CUDA_HOST_H */
