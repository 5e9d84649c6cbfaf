/* SPDX-License-Identifier: MIT */
/* The GPU library's entry points (include/ttd/ttd_gpu.h) over the CUDA runtime: the device
 * query, the argument and memory checks, then the launchers of gpu_d.cu / gpu_f.cu. The runtime
 * is linked statically and loads the driver (libcuda) when first called: without a driver or a
 * GPU every call here returns TTD_GPU_ERR_NO_DEVICE, and nothing else in ttd is affected. */
#include <stdio.h>
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
