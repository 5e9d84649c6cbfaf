/* SPDX-License-Identifier: MIT */
/* Open meshes (with boundary) for the point queries' tests and benchmark (docs/points.md,
 * section 5.4): deterministic stand-ins for the models users hold whose inside is not closed
 * off: a CAD-like part with holes, a chair of open boxes, a capsule open at one end, a noisy
 * scan with holes, a torus with holes. Each is made from the closed generators of meshes.h and
 * the operations below; the capsule and the torus use sin and cos (meshes.h's determinism note). */
#ifndef TTD_GEN_OPEN_MESHES_H
#define TTD_GEN_OPEN_MESHES_H

#include <stddef.h>
#include <stdint.h>

#include "meshes.h"

#ifdef __cplusplus
extern "C" {
#endif

/// in with `count` holes punched: centres at the centroids of triangles drawn from (seed), every
/// triangle whose centroid lies within `radius` of a centre removed (vertices kept). Fails when
/// every triangle would go.
int ttd_gen_punch_holes(const ttd_gen_mesh *in, int count, double radius, uint64_t seed, ttd_gen_mesh *out);

/// a and b in one mesh (b's vertices after a's); out may not alias a or b.
int ttd_gen_mesh_concat(const ttd_gen_mesh *a, const ttd_gen_mesh *b, ttd_gen_mesh *out);

/// The open families, by name: "cad" (a plate 1 x 0.6 x 0.12 whose faces are gridded into long
/// thin triangles, aspect about 12, with 7 holes of radius 0.05 punched through its top and
/// bottom: 38,400 triangles before the holes), "chair" (a seat, four legs and a back, boxes
/// overlapping one another, each subdivided 4 times; the legs' bottoms and the back's top
/// left open), "capsule" (a cylinder of radius 0.25 and length 1 with a hemisphere at one end,
/// open at the other, 128 x 160 quads, with a slot punched in its side), "scan" (the level-6
/// icosphere, 81,920 triangles, each vertex moved radially by a uniform amount in +-1%, with 12
/// holes of radius 0.15), "torus-holes" (ttd_gen_torus(1, 0.35, 200, 64), 25,600 triangles, with
/// 9 holes of radius 0.2). Every one normalised (ttd_gen_normalize). -1 on an unknown name.
int ttd_gen_open_mesh(const char *name, ttd_gen_mesh *out);

#ifdef __cplusplus
}
#endif
#endif /* TTD_GEN_OPEN_MESHES_H */
