/* SPDX-License-Identifier: MIT */
/* The GPU statuses' descriptions (include/ttd/ttd_gpu.h), in the GPU library with or without CUDA. */
#include "ttd/ttd_gpu.h"

const char *ttd_gpu_status_string(ttd_gpu_status status)
{
    switch (status) {
    case TTD_GPU_OK: return "ok";
    case TTD_GPU_ERR_NOT_BUILT: return "ttd was built without its GPU part (no CUDA toolkit, or -DTTD_CUDA=OFF)";
    case TTD_GPU_ERR_NO_DEVICE: return "no usable CUDA device (no GPU, no driver, a driver too old, or none that runs sm_90 code)";
    case TTD_GPU_ERR_NULL_POINTER: return "a required pointer was NULL";
    case TTD_GPU_ERR_NOT_DEVICE_MEMORY: return "an array is not memory the current CUDA device can access";
    case TTD_GPU_ERR_CUDA: return "the CUDA runtime reported an error";
    case TTD_GPU_ERR_BAD_ARGUMENT: return "a bad argument: a NaN or negative bound or margin, meshes of two precisions, a hierarchy too deep for the device walk, or a mesh whose side the device cannot decide as the CPU does";
    }
    return "unknown status";
}
