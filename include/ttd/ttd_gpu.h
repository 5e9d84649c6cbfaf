/* SPDX-License-Identifier: MIT */
/* ttd on an NVIDIA GPU: the exact method on pairs that live in device memory, one pair per CUDA
 * thread, from the same kernel source as the CPU rows (docs/gpu.md). A separate library,
 * ttd_gpu (libttd_gpu), so that ttd itself never depends on CUDA: when ttd was built with its
 * GPU part (CMake -DTTD_CUDA=AUTO found a CUDA toolkit, or ON), libttd_gpu holds the CUDA code
 * and the CUDA runtime (linked statically: it loads the driver at run time, so a machine without
 * a GPU driver runs programs linked with it and gets TTD_GPU_ERR_NO_DEVICE); otherwise it is a
 * stub whose every call returns TTD_GPU_ERR_NOT_BUILT. C and C++; no CUDA header needed. */
#ifndef TTD_TTD_GPU_H
#define TTD_TTD_GPU_H

#include <stddef.h>

#include "ttd/ttd.h"

#ifdef __cplusplus
extern "C" {
#endif

/// What a GPU call did.
typedef enum ttd_gpu_status {
    TTD_GPU_OK = 0,
    TTD_GPU_ERR_NOT_BUILT = 1,         ///< this ttd was built without its GPU part (no CUDA toolkit, or TTD_CUDA=OFF)
    TTD_GPU_ERR_NO_DEVICE = 2,         ///< no usable CUDA device: no driver, a driver older than the runtime, no GPU, or none that runs the built code
    TTD_GPU_ERR_NULL_POINTER = 3,      ///< s or t NULL, or both outputs NULL, or info NULL
    TTD_GPU_ERR_NOT_DEVICE_MEMORY = 4, ///< an array the device cannot access (plain host memory); nothing launched
    TTD_GPU_ERR_CUDA = 5,              ///< the CUDA runtime failed (a launch, the device); ttd_gpu_query's message says what
    TTD_GPU_ERR_BAD_ARGUMENT = 6       ///< a NaN or negative bound or margin, meshes of two precisions, or a mesh whose hierarchy is deeper than the device walk takes
} ttd_gpu_status;

/// A short English description of status (never NULL).
TTD_API const char *ttd_gpu_status_string(ttd_gpu_status status);

/// What ttd_gpu_query found.
typedef struct ttd_gpu_info {
    int built;              ///< 1 when this ttd has its GPU part
    int device;             ///< the current CUDA device, -1 when none
    int device_count;       ///< CUDA devices visible
    int cc_major, cc_minor; ///< compute capability of the current device
    int runtime_version;    ///< CUDA runtime (1000 major + 10 minor), 0 when not built
    int driver_version;     ///< CUDA driver, 0 when none
    int block_threads;      ///< CUDA threads a block of the kernels (0 when not built)
    int min_blocks;         ///< the kernels' __launch_bounds__ minimum of resident blocks an SM
    int registers_d, registers_f; ///< registers a thread of the distance kernels, double and float (0 when unknown)
    char name[128];         ///< the current device's name, "" when none
    char message[192];      ///< why no device is usable, or the last CUDA error; "" when none
} ttd_gpu_info;

/// Whether a GPU is usable for the calls below: TTD_GPU_OK with the current device's details in
/// *info, TTD_GPU_ERR_NOT_BUILT or TTD_GPU_ERR_NO_DEVICE (info->message says why).
TTD_API ttd_gpu_status ttd_gpu_query(ttd_gpu_info *info);

/// The exact method on n pairs in device memory, one CUDA thread per pair: s and t hold 9n
/// reals (the layout of ttd_batch_d), distance n reals, results n ttd_result_d; either output may
/// be NULL, not both; all three arrays on the current device (device or managed memory).
/// Each pair's result has the bits the CPU's ttd_batch_d gives it (with the exact method), on
/// every instruction set; a pair with a NaN or infinite coordinate gets NaN outputs and
/// TTD_PAIR_NONFINITE (not reported in the status). stream is a cudaStream_t (NULL: the
/// default stream); the call returns after the launch, and the outputs are ready when the stream
/// is. n = 0 launches nothing and returns TTD_GPU_OK.
TTD_API ttd_gpu_status ttd_gpu_batch_d(size_t n, const double *s, const double *t, double *distance,
                                       ttd_result_d *results, void *stream);
/// ttd_gpu_batch_d in single precision (ttd_batch_f's bits).
TTD_API ttd_gpu_status ttd_gpu_batch_f(size_t n, const float *s, const float *t, float *distance,
                                       ttd_result_f *results, void *stream);

/// The exact method on n pairs in host memory (the arrays of ttd_batch_d, any alignment): the
/// pairs go to the current device in chunks, each chunk's copies overlapped with another's kernel
/// on a second stream, and the call returns when every output is written. Arrays the caller has
/// page-locked (cudaHostRegister, cudaMallocHost) are copied by DMA in place, at the bus's speed;
/// plain pageable arrays pass through small pinned staging buffers, at the speed of a host copy
/// (docs/gpu.md has both, measured). Results as ttd_gpu_batch_d's (the CPU's bits). Either output
/// may be NULL, not both; n = 0 does nothing. TTD_GPU_ERR_NO_DEVICE without a usable GPU,
/// TTD_GPU_ERR_CUDA when the runtime fails (pinned or device memory cannot be had, say): the
/// outputs are then indeterminate.
TTD_API ttd_gpu_status ttd_gpu_batch_host_d(size_t n, const double *s, const double *t, double *distance,
                                            ttd_result_d *results);
/// ttd_gpu_batch_host_d in single precision.
TTD_API ttd_gpu_status ttd_gpu_batch_host_f(size_t n, const float *s, const float *t, float *distance,
                                            ttd_result_f *results);

/* ---- Meshes on the device: many poses (docs/gpu.md, section 6) ---------------------------- */

/// A mesh and its hierarchy copied to the device (ttd_gpu_mesh_upload), read by the pose queries
/// below; owned by the caller until ttd_gpu_mesh_free.
typedef struct ttd_gpu_mesh ttd_gpu_mesh;

/// A pose the CPU entry would refuse (not finite, not a rotation within ttd's tolerance, det <= 0,
/// or b moved past the coordinate range): on the device each pose is checked alone, and such a
/// pose gets this bit in ttd_mesh_result_d.flags (distance NaN, no triangles), or this value in
/// ttd_collision.hit (non-zero: read as a collision), instead of the CPU's error for the call.
#define TTD_GPU_POSE_REFUSED 0x8000u

/// Copies mesh (its vertices, triangles and hierarchy as built on the CPU, double or float, and
/// the point queries' data when the mesh has made it: after any point query on the CPU, such as
/// ttd_points_closest_d on one point) to the current device, once; *out is the handle (NULL on failure). TTD_GPU_ERR_NULL_POINTER,
/// TTD_GPU_ERR_NOT_BUILT, TTD_GPU_ERR_NO_DEVICE, TTD_GPU_ERR_CUDA (out of device memory). The
/// device copy is a snapshot: a later ttd_mesh_set_vertices is not seen until uploaded again.
TTD_API ttd_gpu_status ttd_gpu_mesh_upload(const ttd_mesh *mesh, ttd_gpu_mesh **out);
/// Frees an uploaded mesh (NULL: nothing). Waits for nothing: no query on it may be in flight.
TTD_API void ttd_gpu_mesh_free(ttd_gpu_mesh *mesh);

/// Minimum distance between the surfaces of a and b under each of k poses (12k reals, as
/// ttd_mesh_distance_d takes them), one CUDA thread a pose: poses and out (k records) in device
/// or managed memory, asynchronous on stream (a cudaStream_t; NULL: the default stream). Each
/// record's distance and flags have the bits ttd_mesh_distance_d gives (rel_tol 0, no solid
/// option); where several pairs are equally near, tri_a/tri_b (and so p, q and the features) may
/// be another of them; node_tests and pair_tests count the device walk's own work. upper_bound as
/// the CPU's (INFINITY: none). k = 0 does nothing. TTD_GPU_ERR_BAD_ARGUMENT for a NaN or negative
/// upper_bound, meshes not both double (a and b from ttd_mesh_create_d), or hierarchies too deep
/// for the walk's stack (none of ttd's builds of up to millions of triangles).
TTD_API ttd_gpu_status ttd_gpu_mesh_distance_d(const ttd_gpu_mesh *a, const ttd_gpu_mesh *b, size_t k,
                                               const double *poses, double upper_bound, ttd_mesh_result_d *out,
                                               void *stream);
/// ttd_gpu_mesh_distance_d in single precision (meshes from ttd_mesh_create_f).
TTD_API ttd_gpu_status ttd_gpu_mesh_distance_f(const ttd_gpu_mesh *a, const ttd_gpu_mesh *b, size_t k,
                                               const float *poses, float upper_bound, ttd_mesh_result_f *out,
                                               void *stream);
/// Collision of a and b with margin >= 0 under each of k poses, as ttd_mesh_collide_d (surfaces):
/// hit is the CPU's verdict for every pose; the witness pair may be another pair within the
/// margin. Arrays and stream as ttd_gpu_mesh_distance_d.
TTD_API ttd_gpu_status ttd_gpu_mesh_collide_d(const ttd_gpu_mesh *a, const ttd_gpu_mesh *b, size_t k,
                                              const double *poses, double margin, ttd_collision *out, void *stream);
/// ttd_gpu_mesh_collide_d in single precision.
TTD_API ttd_gpu_status ttd_gpu_mesh_collide_f(const ttd_gpu_mesh *a, const ttd_gpu_mesh *b, size_t k,
                                              const float *poses, float margin, ttd_collision *out, void *stream);

/// For each of n points (3n reals in device memory, the mesh's frame), the closest point of the
/// mesh into out[i] (device memory), one CUDA thread a point, asynchronous on stream: the whole
/// result ttd_points_closest_d gives (pose NULL), bit for bit (its ties go to the smallest
/// triangle index), but node_tests and triangle_tests, which count the device walk's work. A NaN
/// or infinite point gets NaN and TTD_POINT_NONFINITE (not reported in the status). upper_bound
/// as the CPU's. TTD_GPU_ERR_BAD_ARGUMENT for a NaN or negative bound, a mesh of the other
/// precision, or one uploaded before its point data existed (run one point query on the CPU, then
/// upload). n = 0 does nothing.
TTD_API ttd_gpu_status ttd_gpu_points_closest_d(const ttd_gpu_mesh *mesh, size_t n, const double *points,
                                                double upper_bound, ttd_point_result_d *out, void *stream);
/// ttd_gpu_points_closest_d in single precision.
TTD_API ttd_gpu_status ttd_gpu_points_closest_f(const ttd_gpu_mesh *mesh, size_t n, const float *points,
                                                float upper_bound, ttd_point_result_f *out, void *stream);

/* ---- Signed distances of points on the device (docs/gpu.md, section 6) -------------------- */

/// A point whose side the device could not decide as the CPU does (the exact ray count could not
/// be made exact: products below the subnormal range, or a hierarchy too deep for its stack;
/// there the CPU goes on with the hierarchical winding number): set in its result's flags, its
/// signed distance NaN (the result's distance and closest point are still the CPU's).
#define TTD_GPU_POINT_SIDE_REFUSED 0x80u

/// For each of n points (3n reals in device memory, the mesh's frame), the signed distance into
/// distance[i] and/or the closest point into results[i] (device memory; either may be NULL, not
/// both), one CUDA thread a point, asynchronous on stream: ttd_points_signed_distance_d's answer
/// (pose NULL) bit for bit, TTD_POINT_INSIDE included (results as ttd_gpu_points_closest_d's:
/// node_tests and triangle_tests count the device's work). The side is the CPU's exact ray count
/// (points/ray_impl.h, one source): the mesh must be closed, or open with a boundary that cancels
/// by coordinates, or one triangle (unsigned), and known to be so when uploaded (run one
/// ttd_points_signed_distance_d on the CPU, then upload); any other mesh, like a NaN or negative
/// upper_bound or the other precision, gives TTD_GPU_ERR_BAD_ARGUMENT (an open mesh's winding
/// number goes through atan2, whose last bits differ between the host's libm and CUDA).
/// A point the ray cannot count exactly gets TTD_GPU_POINT_SIDE_REFUSED. n = 0 does nothing.
TTD_API ttd_gpu_status ttd_gpu_points_signed_distance_d(const ttd_gpu_mesh *mesh, size_t n, const double *points,
                                                        double upper_bound, double *distance,
                                                        ttd_point_result_d *results, void *stream);
/// ttd_gpu_points_signed_distance_d in single precision.
TTD_API ttd_gpu_status ttd_gpu_points_signed_distance_f(const ttd_gpu_mesh *mesh, size_t n, const float *points,
                                                        float upper_bound, float *distance,
                                                        ttd_point_result_f *results, void *stream);

/* ---- Continuous collision of moving primitives on the device (issue 33; docs/ccd.md, section 14) ---- */
/// The CPU's ttd_ccd_vertex_face_d on n queries in device (or managed) memory, one CUDA thread a
/// query, asynchronous on stream (a cudaStream_t; NULL: the default stream): the arrays' layout
/// is the CPU entry's (v_t0, v_t1 3n reals, f_t0, f_t1 9n), out n records in device memory, each
/// the record ttd_ccd_vertex_face_d gives, bit for bit (hit, toi, gap, flags, sub, evals): the
/// same search with its exact fallback runs on the device. A query with a NaN or infinite
/// coordinate gets toi NaN and TTD_CCD_NONFINITE (not reported in the status, where the CPU
/// returns TTD_ERR_NONFINITE_INPUT). TTD_GPU_ERR_BAD_ARGUMENT for a NaN, negative or infinite
/// min_separation; n = 0 does nothing and returns TTD_GPU_OK.
TTD_API ttd_gpu_status ttd_gpu_ccd_vertex_face_d(size_t n, const double *v_t0, const double *f_t0, const double *v_t1,
                                                 const double *f_t1, double min_separation, ttd_ccd_result *out,
                                                 void *stream);
/// ttd_gpu_ccd_vertex_face_d on float arrays (widened to double exactly, as ttd_ccd_vertex_face_f).
TTD_API ttd_gpu_status ttd_gpu_ccd_vertex_face_f(size_t n, const float *v_t0, const float *f_t0, const float *v_t1,
                                                 const float *f_t1, double min_separation, ttd_ccd_result *out,
                                                 void *stream);
/// The CPU's ttd_ccd_edge_edge_d on device arrays (ea, eb 6n reals each), as ttd_gpu_ccd_vertex_face_d.
TTD_API ttd_gpu_status ttd_gpu_ccd_edge_edge_d(size_t n, const double *ea_t0, const double *eb_t0, const double *ea_t1,
                                               const double *eb_t1, double min_separation, ttd_ccd_result *out,
                                               void *stream);
/// ttd_gpu_ccd_edge_edge_d on float arrays.
TTD_API ttd_gpu_status ttd_gpu_ccd_edge_edge_f(size_t n, const float *ea_t0, const float *eb_t0, const float *ea_t1,
                                               const float *eb_t1, double min_separation, ttd_ccd_result *out,
                                               void *stream);
/// The CPU's ttd_ccd_triangles_d on device arrays (9n reals each), as ttd_gpu_ccd_vertex_face_d.
TTD_API ttd_gpu_status ttd_gpu_ccd_triangles_d(size_t n, const double *ta_t0, const double *tb_t0, const double *ta_t1,
                                               const double *tb_t1, double min_separation, ttd_ccd_result *out,
                                               void *stream);
/// ttd_gpu_ccd_triangles_d on float arrays.
TTD_API ttd_gpu_status ttd_gpu_ccd_triangles_f(size_t n, const float *ta_t0, const float *tb_t0, const float *ta_t1,
                                               const float *tb_t1, double min_separation, ttd_ccd_result *out,
                                               void *stream);
/* ---- end of continuous collision ---- */

#ifdef __cplusplus
}
#endif

#endif /* TTD_TTD_GPU_H */
