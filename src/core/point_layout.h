/* SPDX-License-Identifier: MIT */
/* A triangle prepared for point queries: what the scalar reference (scalar/point_impl.h) and the
 * lane kernel (simd/kernel_point.h) must agree on, in one place. The preparation depends on the
 * triangle only, so a mesh computes it once per triangle (src/points/prepare.c) and every point
 * query reuses it; only the per-point part runs per point, the same operations in the same
 * order in the scalar code and in every lane row.
 *
 * A prepared triangle is TTD_PT_COUNT reals, field f at f * stride (stride 1 for one triangle,
 * TTD_PT_LANES for a block of triangles side by side, one per lane). The triangle's frame: the
 * origin at vertex 0 (its caller coordinates, TTD_PT_V0), scaled by s = 2^-e, 2^e the power of two
 * above its extent (the largest side of its bounding box), so that the scaled edges lie in [-1, 1]
 * with the largest beyond 1/2. s = 0 marks a point triangle (every vertex equal). */
#ifndef TTD_CORE_POINT_LAYOUT_H
#define TTD_CORE_POINT_LAYOUT_H

#include <stdint.h>

enum {
    TTD_PT_V0 = 0,     /* 3: vertex 0, unscaled */
    TTD_PT_S = 3,      /* s = 2^-e (0: a point triangle) */
    TTD_PT_G = 4,      /* g = 2^e = 1/s (1 for a point triangle) */
    TTD_PT_E = 5,      /* 9: scaled edges, e[i] = (v[i+1] - v[i]) s, coordinate c at 5 + 3i + c */
    TTD_PT_IEE = 14,   /* 3: 1 / |e[i]|^2, 0 for an edge too short to divide by */
    TTD_PT_K = 17,     /* k, the longest edge (0, 1 or 2, first on ties), as a real */
    TTD_PT_L = 18,     /* 3: L = e[k] */
    TTD_PT_U = 21,     /* 3: cross(n, L) / |n|^2: the across-weight c of a point r is dot(r, u) */
    TTD_PT_N = 24,     /* 3: n = cross(L, M), M = v[k+2] - v[k], computed accurately */
    TTD_PT_ML = 27,    /* dot(M, L) */
    TTD_PT_IEEK = 28,  /* 1 / |L|^2 (0 when L is too short) */
    TTD_PT_INN = 29,   /* 1 / |n|^2, 0 when the triangle has no face (a segment or a point) */
    TTD_PT_COUNT = 30
};

/* Triangles per prepared block: one per child slot of a mesh node (TTD_NODE_WIDTH). A block holds
 * TTD_PT_COUNT + 1 rows of TTD_PT_LANES reals: the extra row lets a float row with 16 lanes read
 * a whole vector from the last field. */
#define TTD_PT_LANES 8
#define TTD_PT_ROWS (TTD_PT_COUNT + 1)

/* The point walk's node (src/points/, docs/points.md section 3): a mesh node's child boxes in
 * float, in the mesh's frame moved to its origin and scaled by a power of two
 * (ttd_points_data.scale), in the slab form of the mesh's boxes ({x : |u_a . (x - c)| <= e_a}),
 * the extents widened so that each holds what the mesh's box holds about the rounded centre and
 * axes; 576 bytes, so that a node is nine cache lines instead of the double mesh node's sixteen.
 * An unused slot has e = -inf: no point is within it. */
typedef struct ttd_pnode {
    float c[3][8];     /* c[k][j]: slot j's centre, coordinate k */
    float u[9][8];     /* u[3a + k][j]: component k of axis a */
    float e[3][8];     /* half extents along the axes */
    int32_t child[8];  /* the mesh node's: >= 0 a node, < 0 triangle -1 - child, 0 unused */
    int32_t block;     /* the node's prepared triangle block (points/points.h), -1 when none */
    uint32_t tmask;    /* the slots that hold triangles (bit j) */
    uint32_t ntri;     /* how many (bits in tmask) */
    uint32_t nslots;   /* slots in use */
    int32_t pad[12];
} ttd_pnode;

/* The ray walk's node (src/points/ray.c): a mesh node's child slots as axis-aligned float boxes in the
 * walk nodes' frame (ttd_points_data.scale), rounded outward around the vertices as the tree sees
 * them; an unused slot holds the empty box (lo = +inf, hi = -inf). 256 bytes. */
typedef struct ttd_rnode {
    float lo[3][8];
    float hi[3][8];
    int32_t child[8]; /* the mesh node's (0 in an unused slot) */
    int32_t pad[8];
} ttd_rnode;

/* Beyond this scaled distance from vertex 0 (2^400 in double, 2^40 in float) the triangle is
 * smaller than the rounding of the distance: the point is measured to vertex 0, which avoids
 * squaring numbers that could overflow. */
#define TTD_PT_FAR_D 0x1p400
#define TTD_PT_FAR_F 0x1p40f

#endif /* TTD_CORE_POINT_LAYOUT_H */
