/* SPDX-License-Identifier: MIT */
/* Mesh-like triangle pairs for the kernel tests: the candidate pairs a box-based broad phase
 * hands the narrow phase (gen/mesh_pairs.h) for an icosphere and copies of it posed at gaps of
 * 1%, 0.2%, 0 and -0.2% of its size (gen/meshes.h ttd_gen_pose_gap): neighbouring, nearly
 * parallel, touching and crossing triangles, most of them separated by about their own size.
 * Deterministic in (seed, n). */
#ifndef TTD_TEST_MESH_LIKE_PAIRS_H
#define TTD_TEST_MESH_LIKE_PAIRS_H

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mesh_pairs.h"
#include "meshes.h"

/// Fills s and t (9n doubles each) with n mesh-like pairs; pose after pose (gap 0.01, 0.002, 0,
/// -0.002, ...) until n are there. Returns 0, or -1 when a generator failed.
static inline int mesh_like_pairs(uint64_t seed, size_t n, double *s, double *t)
{
    static const double gaps[4] = {0.01, 0.002, 0.0, -0.002};
    ttd_gen_mesh coarse = {NULL, 0, NULL, 0}, m = {NULL, 0, NULL, 0};
    if (ttd_gen_icosphere(2, &coarse) != 0 || ttd_gen_subdivide(&coarse, 1, &m) != 0 || ttd_gen_normalize(&m) != 0) {
        ttd_gen_mesh_free(&coarse);
        ttd_gen_mesh_free(&m);
        return -1;
    }
    ttd_gen_mesh_free(&coarse);
    size_t have = 0;
    int rc = 0;
    for (uint64_t pose = 0; have < n && pose < 1000; ++pose) {
        double P[12];
        ttd_gen_mesh b = {NULL, 0, NULL, 0};
        uint32_t *pairs = NULL;
        size_t np = 0;
        if (ttd_gen_pose_gap(&m, &m, seed, pose, NULL, gaps[pose % 4], P) != 0 || ttd_gen_mesh_transform(&m, P, &b) != 0 ||
            ttd_gen_mesh_pairs(&m, &b, 0.02, (size_t)1 << 24, &pairs, &np) != 0) {
            ttd_gen_mesh_free(&b);
            rc = -1;
            break;
        }
        if (np > n - have)
            np = n - have;
        ttd_gen_mesh_pair_coords(&m, &b, pairs, np, s + 9 * have, t + 9 * have);
        have += np;
        free(pairs);
        ttd_gen_mesh_free(&b);
    }
    ttd_gen_mesh_free(&m);
    return rc == 0 && have == n ? 0 : -1;
}

#endif /* TTD_TEST_MESH_LIKE_PAIRS_H */
