/* SPDX-License-Identifier: MIT */
/* Qualifiers of the functions a CUDA kernel calls as well as the CPU (the lane vocabulary, the
 * kernels' helpers, the device walks and small geometry checks): host and device code under
 * nvcc, plain C otherwise. TTDW_FN is `static inline` for both. Kept apart from simd/lanes.h so
 * that code outside the lanes (core checks) can be shared with the device without an ISA. */
#ifndef TTD_CORE_DEVICE_FN_H
#define TTD_CORE_DEVICE_FN_H

#if defined(__CUDACC__)
#define TTD_DEVICE __host__ __device__
#else
#define TTD_DEVICE
#endif
#define TTDW_FN static inline TTD_DEVICE

#endif
