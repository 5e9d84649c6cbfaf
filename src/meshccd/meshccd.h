/* SPDX-License-Identifier: MIT */
/* Continuous collision of deforming meshes (ttd_mesh_ccd_d, ttd_mesh_self_ccd_d; docs/ccd.md,
 * section 10): the swept-box hierarchy's broad phase (sweep_tree.h), each primitive pair of the
 * candidate triangle pairs once (by an owner rule, no sort), the primitive query of src/ccd/ on
 * each, and the earliest time with the pairs at it. From checked arguments (src/api/). */
#ifndef TTD_MESHCCD_MESHCCD_H
#define TTD_MESHCCD_MESHCCD_H

#include <stddef.h>
#include <stdint.h>

#include "ttd/ttd.h"

/// One side: nv vertices at t = 0 (x0) and t = 1 (x1), 3 nv finite doubles each; nt >= 1
/// triangles of indices below nv.
typedef struct meshccd_side {
    const double *x0, *x1;
    const uint32_t *tris;
    size_t nv, nt;
} meshccd_side;

/// a against b (b not NULL), or a against itself (b NULL, shared: TTD_SELF_SHARED_VERTEX or 0);
/// delta >= 0 finite; threads as ttd_options.threads; isa a built one (the self query's whole-pair
/// proof runs in its row's lanes where it has them; the answer is the same on every row). Fills
/// *out (pairs allocated here). TTD_OK or TTD_ERR_OUT_OF_MEMORY (out->count 0, pairs NULL).
ttd_status ttd_meshccd_run(int threads, ttd_isa isa, const meshccd_side *a, const meshccd_side *b, double delta,
                           unsigned shared, ttd_mesh_ccd_result *out);

/// The self query's whole-pair proof (scalar): points x0[0..3) of one triangle and x0[3..6) of the
/// other at t = 0, x1 likewise at t = 1, S their largest coordinate magnitude: non-zero when a
/// direction proves the triangles more than delta apart over the whole step. The lanes'
/// (core/kernels.h, tri_apart) give the same bits; the tests compare them.
int meshccd_tri_apart(const double *const x0[6], const double *const x1[6], double S, double delta);

#endif /* TTD_MESHCCD_MESHCCD_H */
