/* SPDX-License-Identifier: MIT */
/* The GPU library's entry points (include/ttd/ttd_gpu.h) over the CUDA runtime: the device
 * query, the argument and memory checks, then the launchers of gpu_d.cu / gpu_f.cu. The runtime
 * is linked statically and loads the driver (libcuda) when first called: without a driver or a
 * GPU every call here returns TTD_GPU_ERR_NO_DEVICE, and nothing else in ttd is affected. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cuda_runtime.h>

#include "ttd/ttd_gpu.h"
#include "gpu/gpu_internal.h"

static void gpu_message(ttd_gpu_info *info, const char *what, cudaError_t err)
{
    snprintf(info->message, sizeof info->message, "%s: %s (%s)", what, cudaGetErrorString(err), cudaGetErrorName(err));
}

extern "C" ttd_gpu_status ttd_gpu_query(ttd_gpu_info *info)
{
    if (!info)
        return TTD_GPU_ERR_NULL_POINTER;
    memset(info, 0, sizeof *info);
    info->built = 1;
    info->device = -1;
    info->block_threads = ttd_gpu_block_threads();
    info->min_blocks = ttd_gpu_min_blocks();
    cudaRuntimeGetVersion(&info->runtime_version);
    cudaError_t err = cudaDriverGetVersion(&info->driver_version);
    if (err != cudaSuccess || info->driver_version == 0) {
        snprintf(info->message, sizeof info->message, "no CUDA driver");
        return TTD_GPU_ERR_NO_DEVICE;
    }
    err = cudaGetDeviceCount(&info->device_count);
    if (err != cudaSuccess || info->device_count == 0) {
        info->device_count = 0;
        if (err != cudaSuccess)
            gpu_message(info, "no device", err);
        else
            snprintf(info->message, sizeof info->message, "no CUDA device");
        return TTD_GPU_ERR_NO_DEVICE;
    }
    int dev = 0;
    if ((err = cudaGetDevice(&dev)) != cudaSuccess) {
        gpu_message(info, "cudaGetDevice", err);
        return TTD_GPU_ERR_NO_DEVICE;
    }
    info->device = dev;
    cudaDeviceProp prop;
    if ((err = cudaGetDeviceProperties(&prop, dev)) != cudaSuccess) {
        gpu_message(info, "cudaGetDeviceProperties", err);
        return TTD_GPU_ERR_NO_DEVICE;
    }
    snprintf(info->name, sizeof info->name, "%s", prop.name);
    info->cc_major = prop.major;
    info->cc_minor = prop.minor;
    /* does this device run the built code (sm_90, or compute_90 PTX it can compile)? */
    if ((err = (cudaError_t)ttd_gpu_kernel_loads()) != cudaSuccess) {
        gpu_message(info, "the kernels do not load on this device", err);
        return TTD_GPU_ERR_NO_DEVICE;
    }
    info->registers_d = ttd_gpu_kernel_registers_d();
    info->registers_f = ttd_gpu_kernel_registers_f();
    return TTD_GPU_OK;
}

/* TTD_GPU_OK when p is memory the current device can read and write in a kernel. */
static ttd_gpu_status gpu_check_pointer(const void *p)
{
    cudaPointerAttributes a;
    const cudaError_t err = cudaPointerGetAttributes(&a, p);
    if (err != cudaSuccess) {
        cudaGetLastError(); /* clear it */
        return err == cudaErrorInvalidValue ? TTD_GPU_ERR_NOT_DEVICE_MEMORY : TTD_GPU_ERR_NO_DEVICE;
    }
    if (a.type == cudaMemoryTypeDevice || a.type == cudaMemoryTypeManaged)
        return TTD_GPU_OK;
    if (a.type == cudaMemoryTypeHost && a.devicePointer == p) /* mapped pinned host memory */
        return TTD_GPU_OK;
    return TTD_GPU_ERR_NOT_DEVICE_MEMORY;
}

static ttd_gpu_status gpu_checks(size_t n, const void *s, const void *t, const void *distance, const void *results,
                                 size_t real_size)
{
    if (!s || !t || (!distance && !results))
        return TTD_GPU_ERR_NULL_POINTER;
    if (n > SIZE_MAX / (9 * real_size) / 2)
        return TTD_GPU_ERR_NOT_DEVICE_MEMORY; /* arrays that size exist nowhere */
    const void *ptrs[4] = {s, t, distance, results};
    for (int i = 0; i < 4; ++i) {
        if (!ptrs[i])
            continue;
        const ttd_gpu_status st = gpu_check_pointer(ptrs[i]);
        if (st != TTD_GPU_OK)
            return st;
    }
    return TTD_GPU_OK;
}

static ttd_gpu_status gpu_launched(int err)
{
    if (err == cudaSuccess)
        return TTD_GPU_OK;
    if (err == cudaErrorNoKernelImageForDevice || err == cudaErrorInsufficientDriver || err == cudaErrorNoDevice)
        return TTD_GPU_ERR_NO_DEVICE;
    return TTD_GPU_ERR_CUDA;
}

extern "C" ttd_gpu_status ttd_gpu_batch_d(size_t n, const double *s, const double *t, double *distance,
                                          ttd_result_d *results, void *stream)
{
    const ttd_gpu_status st = gpu_checks(n, s, t, distance, results, sizeof(double));
    if (st != TTD_GPU_OK || n == 0)
        return st;
    return gpu_launched(ttd_gpu_launch_exact_d(n, s, t, distance, results, stream));
}

extern "C" ttd_gpu_status ttd_gpu_batch_f(size_t n, const float *s, const float *t, float *distance,
                                          ttd_result_f *results, void *stream)
{
    const ttd_gpu_status st = gpu_checks(n, s, t, distance, results, sizeof(float));
    if (st != TTD_GPU_OK || n == 0)
        return st;
    return gpu_launched(ttd_gpu_launch_exact_f(n, s, t, distance, results, stream));
}

/* The host entries: chunks of at most HOST_CHUNK pairs, two slots on two streams, so that one
 * chunk's copies overlap the other's kernel. Arrays the caller has page-locked (cudaHostRegister,
 * cudaMallocHost) are copied by DMA straight from and into place; plain pageable arrays go through
 * a slot's pinned staging buffers (a host copy each way), and a chunk's outputs then reach the
 * caller when its slot comes round again (or at the end). The staging is allocated per call, so
 * it is kept small: 2^17 pairs a slot (19 MB of inputs in double). */
enum { HOST_CHUNK = 1 << 17 };

template <typename R, typename Res> struct host_slot {
    cudaStream_t stream;
    R *pin_in, *dev_in;   /* 18 m reals: s's 9 m, then t's */
    R *pin_dist, *dev_dist;
    Res *pin_res, *dev_res;
    size_t off, m;        /* the chunk whose outputs wait in the staging buffers (m = 0: none) */
};

/* 1 when p is page-locked host memory the device can copy from by DMA */
static int host_pinned(const void *p)
{
    cudaPointerAttributes a;
    if (cudaPointerGetAttributes(&a, p) != cudaSuccess) {
        cudaGetLastError();
        return 0;
    }
    return a.type == cudaMemoryTypeHost;
}

template <typename R, typename Res>
static void host_slot_drain(host_slot<R, Res> *sl, R *distance, Res *results)
{
    if (distance && sl->pin_dist)
        memcpy(distance + sl->off, sl->pin_dist, sl->m * sizeof(R));
    if (results && sl->pin_res)
        memcpy(results + sl->off, sl->pin_res, sl->m * sizeof(Res));
    sl->m = 0;
}

template <typename R, typename Res>
static ttd_gpu_status host_batch(size_t n, const R *s, const R *t, R *distance, Res *results,
                                 int (*launch)(size_t, const R *, const R *, R *, Res *, void *))
{
    if (!s || !t || (!distance && !results))
        return TTD_GPU_ERR_NULL_POINTER;
    if (n == 0)
        return TTD_GPU_OK;
    int dev;
    if (cudaGetDevice(&dev) != cudaSuccess || ttd_gpu_kernel_loads() != cudaSuccess) {
        cudaGetLastError();
        return TTD_GPU_ERR_NO_DEVICE;
    }
    const int direct_in = host_pinned(s) && host_pinned(t);
    const int direct_dist = distance && host_pinned(distance), direct_res = results && host_pinned(results);
    const size_t chunk = n < HOST_CHUNK ? n : HOST_CHUNK;
    host_slot<R, Res> slot[2];
    memset(slot, 0, sizeof slot);
    cudaError_t err = cudaSuccess;
    for (int k = 0; k < 2 && err == cudaSuccess; ++k) {
        host_slot<R, Res> *sl = &slot[k];
        err = cudaStreamCreateWithFlags(&sl->stream, cudaStreamNonBlocking);
        if (err == cudaSuccess && !direct_in)
            err = cudaMallocHost((void **)&sl->pin_in, 18 * chunk * sizeof(R));
        if (err == cudaSuccess)
            err = cudaMalloc((void **)&sl->dev_in, 18 * chunk * sizeof(R));
        if (err == cudaSuccess && distance && !direct_dist)
            err = cudaMallocHost((void **)&sl->pin_dist, chunk * sizeof(R));
        if (err == cudaSuccess && distance)
            err = cudaMalloc((void **)&sl->dev_dist, chunk * sizeof(R));
        if (err == cudaSuccess && results && !direct_res)
            err = cudaMallocHost((void **)&sl->pin_res, chunk * sizeof(Res));
        if (err == cudaSuccess && results)
            err = cudaMalloc((void **)&sl->dev_res, chunk * sizeof(Res));
    }
    for (size_t off = 0, c = 0; off < n && err == cudaSuccess; off += chunk, ++c) {
        host_slot<R, Res> *sl = &slot[c & 1];
        const size_t m = n - off < chunk ? n - off : chunk;
        /* the slot's previous chunk must be done before its buffers are reused */
        if ((err = cudaStreamSynchronize(sl->stream)) != cudaSuccess)
            break;
        if (sl->m)
            host_slot_drain(sl, distance, results);
        if (direct_in) {
            err = cudaMemcpyAsync(sl->dev_in, s + 9 * off, 9 * m * sizeof(R), cudaMemcpyHostToDevice, sl->stream);
            if (err == cudaSuccess)
                err = cudaMemcpyAsync(sl->dev_in + 9 * m, t + 9 * off, 9 * m * sizeof(R), cudaMemcpyHostToDevice,
                                      sl->stream);
        } else {
            memcpy(sl->pin_in, s + 9 * off, 9 * m * sizeof(R));
            memcpy(sl->pin_in + 9 * m, t + 9 * off, 9 * m * sizeof(R));
            err = cudaMemcpyAsync(sl->dev_in, sl->pin_in, 18 * m * sizeof(R), cudaMemcpyHostToDevice, sl->stream);
        }
        if (err == cudaSuccess)
            err = (cudaError_t)launch(m, sl->dev_in, sl->dev_in + 9 * m, sl->dev_dist, sl->dev_res, sl->stream);
        if (err == cudaSuccess && distance)
            err = cudaMemcpyAsync(direct_dist ? distance + off : sl->pin_dist, sl->dev_dist, m * sizeof(R),
                                  cudaMemcpyDeviceToHost, sl->stream);
        if (err == cudaSuccess && results)
            err = cudaMemcpyAsync(direct_res ? results + off : sl->pin_res, sl->dev_res, m * sizeof(Res),
                                  cudaMemcpyDeviceToHost, sl->stream);
        sl->off = off;
        sl->m = m;
    }
    for (int k = 0; k < 2; ++k) {
        host_slot<R, Res> *sl = &slot[k];
        if (sl->stream) {
            const cudaError_t e = cudaStreamSynchronize(sl->stream);
            if (err == cudaSuccess)
                err = e;
            if (err == cudaSuccess && sl->m)
                host_slot_drain(sl, distance, results);
            cudaStreamDestroy(sl->stream);
        }
        cudaFreeHost(sl->pin_in);
        cudaFree(sl->dev_in);
        cudaFreeHost(sl->pin_dist);
        cudaFree(sl->dev_dist);
        cudaFreeHost(sl->pin_res);
        cudaFree(sl->dev_res);
    }
    if (err != cudaSuccess)
        cudaGetLastError();
    return gpu_launched((int)err);
}

extern "C" ttd_gpu_status ttd_gpu_batch_host_d(size_t n, const double *s, const double *t, double *distance,
                                               ttd_result_d *results)
{
    return host_batch(n, s, t, distance, results, ttd_gpu_launch_exact_d);
}

extern "C" ttd_gpu_status ttd_gpu_batch_host_f(size_t n, const float *s, const float *t, float *distance,
                                               ttd_result_f *results)
{
    return host_batch(n, s, t, distance, results, ttd_gpu_launch_exact_f);
}

/* ---- meshes on the device: many poses -------------------------------------------------------- */

/* An uploaded mesh: its arrays in device memory, and the walk's view of them. */
struct ttd_gpu_mesh {
    ttd_gpu_mesh_view view;
    void *nodes, *verts, *tris;
    void *pnodes, *blocks; /* the point data, when the mesh had it */
    void *rnodes;          /* signed distances: the ray nodes, with the point data */
};

extern "C" void ttd_gpu_mesh_free(ttd_gpu_mesh *mesh)
{
    if (!mesh)
        return;
    cudaFree(mesh->nodes);
    cudaFree(mesh->verts);
    cudaFree(mesh->tris);
    cudaFree(mesh->pnodes);
    cudaFree(mesh->blocks);
    cudaFree(mesh->rnodes);
    cudaGetLastError();
    free(mesh);
}

extern "C" ttd_gpu_status ttd_gpu_mesh_upload(const ttd_mesh *mesh, ttd_gpu_mesh **out)
{
    if (!out)
        return TTD_GPU_ERR_NULL_POINTER;
    *out = NULL;
    if (!mesh)
        return TTD_GPU_ERR_NULL_POINTER;
    int dev;
    if (cudaGetDevice(&dev) != cudaSuccess || ttd_gpu_kernel_loads() != cudaSuccess) {
        cudaGetLastError();
        return TTD_GPU_ERR_NO_DEVICE;
    }
    ttd_gpu_mesh_host h;
    ttd_gpu_mesh_describe(mesh, &h);
    ttd_gpu_mesh *g = (ttd_gpu_mesh *)calloc(1, sizeof *g);
    if (!g)
        return TTD_GPU_ERR_CUDA;
    const size_t real_size = (size_t)h.bytes;
    const size_t sizes[5] = {h.nnodes * h.node_size, 3 * h.nv * real_size, 3 * h.nt * sizeof(uint32_t),
                             h.npnodes * h.pnode_size, h.blocks_bytes};
    const void *src[5] = {h.nodes, h.verts, h.tris, h.pnodes, h.blocks};
    void **dst[5] = {&g->nodes, &g->verts, &g->tris, &g->pnodes, &g->blocks};
    cudaError_t err = cudaSuccess;
    for (int i = 0; i < 5 && err == cudaSuccess; ++i) {
        if (src[i] == NULL || sizes[i] == 0)
            continue;
        err = cudaMalloc(dst[i], sizes[i]);
        if (err == cudaSuccess)
            err = cudaMemcpy(*dst[i], src[i], sizes[i], cudaMemcpyHostToDevice);
    }
    /* signed distances: the ray nodes, one for each point node */
    if (err == cudaSuccess && h.rnodes != NULL && h.npnodes > 0) {
        err = cudaMalloc(&g->rnodes, h.npnodes * h.rnode_size);
        if (err == cudaSuccess)
            err = cudaMemcpy(g->rnodes, h.rnodes, h.npnodes * h.rnode_size, cudaMemcpyHostToDevice);
    }
    if (err != cudaSuccess) {
        ttd_gpu_mesh_free(g);
        return gpu_launched((int)err);
    }
    g->view.rnodes = g->rnodes;
    g->view.coord_max = h.coord_max;
    g->view.sign_mode = g->rnodes != NULL ? h.sign_mode : 0;
    g->view.bytes = h.bytes;
    g->view.nodes = g->nodes;
    g->view.verts = g->verts;
    g->view.tris = (const uint32_t *)g->tris;
    for (int i = 0; i < 3; ++i)
        g->view.origin[i] = h.origin[i];
    g->view.radius = h.radius;
    g->view.height = h.height;
    g->view.pnodes = g->pnodes;
    g->view.blocks = g->blocks;
    g->view.pscale = h.pscale;
    g->view.pstretch = h.pstretch;
    *out = g;
    return TTD_GPU_OK;
}

/* The checks of a pose query: pointers, the limit, the meshes' precision and heights, device
 * memory. */
static ttd_gpu_status mesh_checks(const ttd_gpu_mesh *a, const ttd_gpu_mesh *b, size_t k, const void *poses,
                                  double limit, const void *out, int bytes)
{
    if (!a || !b || !poses || !out)
        return TTD_GPU_ERR_NULL_POINTER;
    if (!(limit >= 0) || a->view.bytes != bytes || b->view.bytes != bytes ||
        a->view.height + b->view.height > TTD_GPU_MAX_HEIGHTS)
        return TTD_GPU_ERR_BAD_ARGUMENT;
    if (k > SIZE_MAX / (12 * (size_t)bytes) / 2)
        return TTD_GPU_ERR_NOT_DEVICE_MEMORY;
    if (k == 0)
        return TTD_GPU_OK;
    ttd_gpu_status st = gpu_check_pointer(poses);
    if (st == TTD_GPU_OK)
        st = gpu_check_pointer(out);
    return st;
}

extern "C" ttd_gpu_status ttd_gpu_mesh_distance_d(const ttd_gpu_mesh *a, const ttd_gpu_mesh *b, size_t k,
                                                  const double *poses, double upper_bound, ttd_mesh_result_d *out,
                                                  void *stream)
{
    const ttd_gpu_status st = mesh_checks(a, b, k, poses, upper_bound, out, 8);
    if (st != TTD_GPU_OK || k == 0)
        return st;
    return gpu_launched(ttd_gpu_launch_mesh_d(&a->view, &b->view, k, poses, upper_bound, 0, out, stream));
}

extern "C" ttd_gpu_status ttd_gpu_mesh_distance_f(const ttd_gpu_mesh *a, const ttd_gpu_mesh *b, size_t k,
                                                  const float *poses, float upper_bound, ttd_mesh_result_f *out,
                                                  void *stream)
{
    const ttd_gpu_status st = mesh_checks(a, b, k, poses, upper_bound, out, 4);
    if (st != TTD_GPU_OK || k == 0)
        return st;
    return gpu_launched(ttd_gpu_launch_mesh_f(&a->view, &b->view, k, poses, upper_bound, 0, out, stream));
}

extern "C" ttd_gpu_status ttd_gpu_mesh_collide_d(const ttd_gpu_mesh *a, const ttd_gpu_mesh *b, size_t k,
                                                 const double *poses, double margin, ttd_collision *out, void *stream)
{
    const ttd_gpu_status st = mesh_checks(a, b, k, poses, margin, out, 8);
    if (st != TTD_GPU_OK || k == 0)
        return st;
    return gpu_launched(ttd_gpu_launch_mesh_d(&a->view, &b->view, k, poses, margin, 1, out, stream));
}

extern "C" ttd_gpu_status ttd_gpu_mesh_collide_f(const ttd_gpu_mesh *a, const ttd_gpu_mesh *b, size_t k,
                                                 const float *poses, float margin, ttd_collision *out, void *stream)
{
    const ttd_gpu_status st = mesh_checks(a, b, k, poses, margin, out, 4);
    if (st != TTD_GPU_OK || k == 0)
        return st;
    return gpu_launched(ttd_gpu_launch_mesh_f(&a->view, &b->view, k, poses, margin, 1, out, stream));
}

/* The checks of a point query: pointers, the bound, the mesh's precision and point data, memory. */
static ttd_gpu_status points_checks(const ttd_gpu_mesh *m, size_t n, const void *points, double upper_bound,
                                    const void *out, int bytes)
{
    if (!m || !points || !out)
        return TTD_GPU_ERR_NULL_POINTER;
    if (!(upper_bound >= 0) || m->view.bytes != bytes || m->view.pnodes == NULL)
        return TTD_GPU_ERR_BAD_ARGUMENT;
    if (n > SIZE_MAX / (3 * (size_t)bytes) / 2)
        return TTD_GPU_ERR_NOT_DEVICE_MEMORY;
    if (n == 0)
        return TTD_GPU_OK;
    ttd_gpu_status st = gpu_check_pointer(points);
    if (st == TTD_GPU_OK)
        st = gpu_check_pointer(out);
    return st;
}

extern "C" ttd_gpu_status ttd_gpu_points_closest_d(const ttd_gpu_mesh *mesh, size_t n, const double *points,
                                                   double upper_bound, ttd_point_result_d *out, void *stream)
{
    const ttd_gpu_status st = points_checks(mesh, n, points, upper_bound, out, 8);
    if (st != TTD_GPU_OK || n == 0)
        return st;
    return gpu_launched(ttd_gpu_launch_points_d(&mesh->view, n, points, upper_bound, out, stream));
}

extern "C" ttd_gpu_status ttd_gpu_points_closest_f(const ttd_gpu_mesh *mesh, size_t n, const float *points,
                                                   float upper_bound, ttd_point_result_f *out, void *stream)
{
    const ttd_gpu_status st = points_checks(mesh, n, points, upper_bound, out, 4);
    if (st != TTD_GPU_OK || n == 0)
        return st;
    return gpu_launched(ttd_gpu_launch_points_f(&mesh->view, n, points, upper_bound, out, stream));
}

/* ---- signed distances of points ---- */

/* The checks of a signed distance: those of a point query, either output, and a mesh whose side
 * the device decides as the CPU does (gpu_sign_mode.h). */
static ttd_gpu_status signed_checks(const ttd_gpu_mesh *m, size_t n, const void *points, double upper_bound,
                                    const void *distance, const void *results, int bytes)
{
    if (!m || !points || (!distance && !results))
        return TTD_GPU_ERR_NULL_POINTER;
    if (!(upper_bound >= 0) || m->view.bytes != bytes || m->view.pnodes == NULL || m->view.sign_mode == 0)
        return TTD_GPU_ERR_BAD_ARGUMENT;
    if (n > SIZE_MAX / (3 * (size_t)bytes) / 2)
        return TTD_GPU_ERR_NOT_DEVICE_MEMORY;
    if (n == 0)
        return TTD_GPU_OK;
    ttd_gpu_status st = gpu_check_pointer(points);
    if (st == TTD_GPU_OK && distance)
        st = gpu_check_pointer(distance);
    if (st == TTD_GPU_OK && results)
        st = gpu_check_pointer(results);
    return st;
}

extern "C" ttd_gpu_status ttd_gpu_points_signed_distance_d(const ttd_gpu_mesh *mesh, size_t n, const double *points,
                                                           double upper_bound, double *distance,
                                                           ttd_point_result_d *results, void *stream)
{
    const ttd_gpu_status st = signed_checks(mesh, n, points, upper_bound, distance, results, 8);
    if (st != TTD_GPU_OK || n == 0)
        return st;
    return gpu_launched(ttd_gpu_launch_signed_d(&mesh->view, n, points, upper_bound, distance, results, stream));
}

extern "C" ttd_gpu_status ttd_gpu_points_signed_distance_f(const ttd_gpu_mesh *mesh, size_t n, const float *points,
                                                           float upper_bound, float *distance,
                                                           ttd_point_result_f *results, void *stream)
{
    const ttd_gpu_status st = signed_checks(mesh, n, points, upper_bound, distance, results, 4);
    if (st != TTD_GPU_OK || n == 0)
        return st;
    return gpu_launched(ttd_gpu_launch_signed_f(&mesh->view, n, points, upper_bound, distance, results, stream));
}

/* ---- continuous collision (gpu_ccd.cu; docs/ccd.md, section 14) ---- */
#include <float.h>

/* The checks of a CCD call: pointers, the separation (finite, >= 0, as the CPU's), sizes, device
 * memory; then the launch. kind: 1 vertex-face, 2 edge-edge, 3 triangles. */
static ttd_gpu_status ccd_call(int kind, size_t real_size, size_t n, const void *a0,
                               const void *b0, const void *a1, const void *b1, double delta, ttd_ccd_result *out,
                               void *stream)
{
    if (!a0 || !b0 || !a1 || !b1 || !out)
        return TTD_GPU_ERR_NULL_POINTER;
    if (!(delta >= 0 && delta <= DBL_MAX))
        return TTD_GPU_ERR_BAD_ARGUMENT;
    if (n > SIZE_MAX / (9 * real_size) / 2 || n > SIZE_MAX / sizeof(ttd_ccd_result) / 2)
        return TTD_GPU_ERR_NOT_DEVICE_MEMORY; /* arrays that size exist nowhere */
    if (n == 0)
        return TTD_GPU_OK;
    const void *ptrs[5] = {a0, b0, a1, b1, out};
    for (int i = 0; i < 5; ++i) {
        const ttd_gpu_status st = gpu_check_pointer(ptrs[i]);
        if (st != TTD_GPU_OK)
            return st;
    }
    return gpu_launched(ttd_gpu_launch_ccd(kind, real_size == sizeof(float), n, a0, b0, a1, b1, delta, out, stream));
}

/* The six entries (include/ttd/ttd_gpu.h): R the precision's coordinates, kind as ccd_call's. */
#define TTD_GPU_CCD_ENTRY(name, kind, R)                                                                     \
    extern "C" ttd_gpu_status name(size_t n, const R *a_t0, const R *b_t0, const R *a_t1, const R *b_t1,     \
                                   double min_separation, ttd_ccd_result *out, void *stream)                 \
    {                                                                                                        \
        return ccd_call(kind, sizeof(R), n, a_t0, b_t0, a_t1, b_t1, min_separation, out, stream);            \
    }

TTD_GPU_CCD_ENTRY(ttd_gpu_ccd_vertex_face_d, 1, double)
TTD_GPU_CCD_ENTRY(ttd_gpu_ccd_vertex_face_f, 1, float)
TTD_GPU_CCD_ENTRY(ttd_gpu_ccd_edge_edge_d, 2, double)
TTD_GPU_CCD_ENTRY(ttd_gpu_ccd_edge_edge_f, 2, float)
TTD_GPU_CCD_ENTRY(ttd_gpu_ccd_triangles_d, 3, double)
TTD_GPU_CCD_ENTRY(ttd_gpu_ccd_triangles_f, 3, float)
#undef TTD_GPU_CCD_ENTRY
/* ---- end of continuous collision ---- */
