/* SPDX-License-Identifier: MIT */
/* Candidate triangle pairs of two meshes, as a broad phase hands them to the narrow phase: every
 * pair whose axis-aligned bounding boxes come within a margin of each other. The benchmark's
 * mesh workloads (docs/benchmark.md) and the kernel tests' mesh-like pairs are made here. This
 * is a workload generator (a uniform grid, deterministic), not ttd's mesh query: the pairs it
 * lists are the ones a box-based broad phase at that margin would have to test, mostly
 * neighbouring, nearly parallel and separated triangles.
 *
 * Determinism: box arithmetic only (min, max, +, -), so the same meshes give the same list in
 * the same order everywhere. */
#ifndef TTD_GEN_MESH_PAIRS_H
#define TTD_GEN_MESH_PAIRS_H

#include <stddef.h>
#include <stdint.h>

#include "meshes.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Every pair (i, j), triangle i of a and triangle j of b, whose bounding boxes overlap once
/// enlarged by margin (on every axis, the gap between the two boxes is at most margin), in
/// order of j and then i. Writes 2 n indices to *pairs (i then j; malloc'ed, free it) and n to
/// *n; stops with -1 when there would be more than max_pairs. Returns 0, or -1 on bad
/// arguments (invalid meshes, negative or non-finite margin), allocation failure or too many
/// pairs (then *pairs is NULL and *n is 0).
int ttd_gen_mesh_pairs(const ttd_gen_mesh *a, const ttd_gen_mesh *b, double margin, size_t max_pairs,
                       uint32_t **pairs, size_t *n);

/// The coordinates of n pairs from ttd_gen_mesh_pairs in the library's layout: pair k's
/// triangle of a at s + 9k, of b at t + 9k (vertices in the triangle's index order).
void ttd_gen_mesh_pair_coords(const ttd_gen_mesh *a, const ttd_gen_mesh *b, const uint32_t *pairs, size_t n,
                              double *s, double *t);

#ifdef __cplusplus
}
#endif
#endif /* TTD_GEN_MESH_PAIRS_H */
