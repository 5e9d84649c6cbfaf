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
#include "mesh/mesh.h"
#include "points/points.h"
#include "cuda_host.h"

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

/* The device walk's view of a mesh: the CPU's arrays as they are (src/gpu/ copies them). */
static gw_mesh host_view(const struct ttd_mesh *m)
{
    gw_mesh g = {(const ttd_node *)m->nodes, (const real *)m->verts, m->tris, {m->origin[0], m->origin[1], m->origin[2]},
                 m->radius, 0};
    g.height = gw_tree_height(g.nodes, 0);
    return g;
}

int ttd_cuda_host_mesh_height_d(const struct ttd_mesh *m)
{
    return host_view(m).height;
}

void ttd_cuda_host_mesh_distance_d(const struct ttd_mesh *a, const struct ttd_mesh *b, size_t k, const double *poses,
                                     double upper_bound, uint64_t vote, ttd_mesh_result_d *out)
{
    const gw_mesh ga = host_view(a), gb = host_view(b);
    for (size_t i = 0; i < k; ++i) /* what thread i of src/gpu/'s pose kernel runs */
        gw_distance_pose(&ga, &gb, poses + 12 * i, upper_bound, vote ? vote + i : 0, &out[i]);
}

void ttd_cuda_host_mesh_collide_d(const struct ttd_mesh *a, const struct ttd_mesh *b, size_t k, const double *poses,
                                    double margin, uint64_t vote, ttd_collision *out)
{
    const gw_mesh ga = host_view(a), gb = host_view(b);
    for (size_t i = 0; i < k; ++i)
        gw_collide_pose(&ga, &gb, poses + 12 * i, margin, vote ? vote + i : 0, &out[i]);
}

int ttd_cuda_host_closest_d(const struct ttd_mesh *m, size_t n, const double *points, double upper_bound,
                              ttd_point_result_d *out)
{
    const ttd_points_data *pd = ttd_points_data_get(m, 1); /* the CPU's point data, as an upload would copy */
    if (pd == NULL)
        return -1;
    const gp_mesh g = {pd->pnodes, (const real *)pd->blocks, {m->origin[0], m->origin[1], m->origin[2]}, m->radius,
                       pd->scale, pd->stretch};
    for (size_t i = 0; i < n; ++i) /* what thread i of a device point kernel would run */
        gp_closest(&g, points + 3 * i, upper_bound, &out[i]);
    return 0;
}
