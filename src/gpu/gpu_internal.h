/* SPDX-License-Identifier: MIT */
/* Between the GPU library's translation units: the launchers of gpu_d.cu / gpu_f.cu, called by
 * gpu_api.cu after its checks. Each returns a cudaError_t as an int (0: launched). */
#ifndef TTD_GPU_INTERNAL_H
#define TTD_GPU_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "core/kernels.h"
#include "ttd/ttd.h"

#ifdef __cplusplus
extern "C" {
#endif

int ttd_gpu_launch_exact_d(size_t n, const double *s, const double *t, double *distance, ttd_result_d *results,
                           void *stream);
int ttd_gpu_launch_exact_f(size_t n, const float *s, const float *t, float *distance, ttd_result_f *results,
                           void *stream);
/* k node tests (query q[i] against node y[i]); lb2 and sep get 8k reals, child j of test i at 8i + j */
int ttd_gpu_launch_node_d(size_t k, const ttd_box_query_d *q, const ttd_node_d *y, double *lb2, double *sep,
                          void *stream);
int ttd_gpu_launch_node_f(size_t k, const ttd_box_query_f *q, const ttd_node_f *y, float *lb2, float *sep,
                          void *stream);

/* An uploaded mesh (gpu_api.cu, ttd_gpu_mesh): device pointers to the CPU's arrays copied as they
 * are (nodes: ttd_node_d or _f), and what the walk needs beside them (gpu_walk_impl.h, gw_mesh). */
typedef struct ttd_gpu_mesh_view {
    int bytes;             /* 8: double, 4: float */
    const void *nodes;
    const void *verts;
    const uint32_t *tris;
    double origin[3];
    double radius;
    int32_t height;        /* node levels below the root's box */
    const void *pnodes;    /* the point queries' data (points/points.h), or NULL when the mesh had none */
    const void *blocks;
    double pscale, pstretch;
    /* signed distances (gpu_signed_impl.h): the ray nodes, the largest vertex coordinate, and how
     * the side is decided (gpu_sign_mode.h: 0 refused, 1 unsigned, 2 the ray count) */
    const void *rnodes;
    double coord_max;
    int sign_mode;
} ttd_gpu_mesh_view;

/* A mesh on the host as an upload reads it (gpu_mesh.c, from mesh/mesh.h's struct ttd_mesh). */
typedef struct ttd_gpu_mesh_host {
    int bytes;
    size_t nv, nt, nnodes, node_size;
    const void *verts, *nodes;
    const uint32_t *tris;
    double origin[3];
    double radius;
    int32_t height;
    /* the point data (ttd_points_data) when the mesh has made it (a point query ran), else NULL */
    const void *pnodes, *blocks;
    size_t npnodes, pnode_size, blocks_bytes;
    double pscale, pstretch;
    /* signed distances: the ray nodes (npnodes of rnode_size), coord_max, sign_mode as the view's */
    const void *rnodes;
    size_t rnode_size;
    double coord_max;
    int sign_mode;
} ttd_gpu_mesh_host;

void ttd_gpu_mesh_describe(const ttd_mesh *m, ttd_gpu_mesh_host *d);

/* The most node levels (h_a + h_b) a pose query's two meshes may have: the walk's stack holds
 * 1 + 7 (h_a + h_b) items (gpu_walk_impl.h, GW_STACK = 256). */
#define TTD_GPU_MAX_HEIGHTS 36

/* k poses of b against a, one thread each: distance records (collide 0, limit = upper_bound) or
 * ttd_collision (collide 1, limit = margin) into out */
int ttd_gpu_launch_mesh_d(const ttd_gpu_mesh_view *a, const ttd_gpu_mesh_view *b, size_t k, const double *poses,
                          double limit, int collide, void *out, void *stream);
int ttd_gpu_launch_mesh_f(const ttd_gpu_mesh_view *a, const ttd_gpu_mesh_view *b, size_t k, const float *poses,
                          float limit, int collide, void *out, void *stream);

/* n points' closest points on mesh m (its point data uploaded), one thread each */
int ttd_gpu_launch_points_d(const ttd_gpu_mesh_view *m, size_t n, const double *points, double upper_bound,
                            ttd_point_result_d *out, void *stream);
int ttd_gpu_launch_points_f(const ttd_gpu_mesh_view *m, size_t n, const float *points, float upper_bound,
                            ttd_point_result_f *out, void *stream);

/* n points' signed distances on mesh m (its point data and ray nodes uploaded, sign_mode 1 or 2),
 * one thread each; distance or out may be NULL */
int ttd_gpu_launch_signed_d(const ttd_gpu_mesh_view *m, size_t n, const double *points, double upper_bound,
                            double *distance, ttd_point_result_d *out, void *stream);
int ttd_gpu_launch_signed_f(const ttd_gpu_mesh_view *m, size_t n, const float *points, float upper_bound,
                            float *distance, ttd_point_result_f *out, void *stream);

/* 0 (cudaSuccess) when the current device runs the kernels built here, else the cudaError_t of
 * cudaFuncGetAttributes on one of them (no kernel image for the device, no driver, ...) */
int ttd_gpu_kernel_loads(void);

/* registers a thread of the distance-only exact kernel (0 when they cannot be read), and the
 * launch configuration the kernels were built with */
int ttd_gpu_kernel_registers_d(void);
int ttd_gpu_kernel_registers_f(void);
int ttd_gpu_block_threads(void);
int ttd_gpu_min_blocks(void);

/* ---- continuous collision (gpu_ccd.cu; docs/ccd.md, section 14) ---- */
/* n queries of kind TTD_CCD_VF (1), TTD_CCD_EE (2) or triangles (3), the arrays float when is_float,
 * else double (the layout of ttd_ccd_vertex_face_d etc.), one thread each */
int ttd_gpu_launch_ccd(int kind, int is_float, size_t n, const void *a0, const void *b0, const void *a1,
                       const void *b1, double delta, ttd_ccd_result *out, void *stream);
/* ---- end of continuous collision ---- */

#ifdef __cplusplus
}
#endif

#endif /* TTD_GPU_INTERNAL_H */
