/* SPDX-License-Identifier: MIT */
/* The checks every public entry makes before it computes (api.c), shared by the pair entries
 * (api.c) and the mesh entries (mesh_api.c), so that both answer bad input the same way and in
 * the same order. */
#ifndef TTD_API_PREPARE_H
#define TTD_API_PREPARE_H

#include <stddef.h>

#include "engine/batch.h"

/// Non-zero when count elements of per x size bytes cannot exist in one object.
int ttd_too_large(size_t count, size_t per, size_t size);

/// The checks, in this order: pointers (TTD_ERR_NULL_POINTER), options (TTD_ERR_BAD_OPTIONS),
/// n == 0 (TTD_ERR_EMPTY), sizes (TTD_ERR_TOO_LARGE), the instruction set
/// (TTD_ERR_ISA_UNAVAILABLE). The caller says whether its pointers are there and whether its
/// arrays could exist; on TTD_OK, cfg is ready for the engine.
ttd_status ttd_prepare(const ttd_options *opt, int pointers_ok, size_t n, int too_large, ttd_engine_config *cfg);

#endif /* TTD_API_PREPARE_H */
