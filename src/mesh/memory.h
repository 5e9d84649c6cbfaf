/* SPDX-License-Identifier: MIT */
/* Large arrays of the mesh code (trees, build scratch, contact lists) on huge pages where the
 * system gives them on request (Linux's transparent huge pages in "madvise" mode, the common
 * default). At 4 KiB a page, a 1M-triangle build faults on ~90,000 pages the first time it
 * writes them, a third of its time on this project's VM; with 2 MiB pages, a few hundred, and a
 * query walking a large tree misses the TLB less. Elsewhere: plain aligned allocations. */
#ifndef TTD_MESH_MEMORY_H
#define TTD_MESH_MEMORY_H

#include <stddef.h>

/// size bytes, 64-byte aligned, uninitialised; NULL if size is 0 or too large, or on failure.
/// Freed with free().
void *ttd_big_alloc(size_t size);

/// Grows *p (from ttd_big_alloc or NULL, holding `used` bytes) to at least `size` bytes: 0 on
/// success, -1 with *p unchanged on failure.
int ttd_big_grow(void **p, size_t used, size_t size);

#endif /* TTD_MESH_MEMORY_H */
