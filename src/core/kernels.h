/* SPDX-License-Identifier: MIT */
/* The contract between the code that feeds pairs (the batch engine, mesh traversals) and the
 * code that computes distances.
 *
 * A kernel computes n pairs of one contiguous block: s and t hold 9n coordinates in the
 * user's layout (pair i at 9i, no alignment promised). It is handed finite coordinates only
 * (the batch engine replaces a pair with NaN/inf by a placeholder and overwrites its outputs
 * afterwards), at most TTD_BLOCK_PAIRS pairs at a time. It writes the outputs that out names
 * (ttd_out_d/_f: distances, points, full results; any may be NULL, not all), and sets
 * results[i].flags from TTD_PAIR_DEGENERATE_*, TTD_PAIR_INTERSECTING, TTD_PAIR_NOT_CONVERGED
 * and TTD_PAIR_FALLBACK (certified mode) only.
 *
 * bound says which pairs the caller cares about: those at distance <= bound (INFINITY: all of
 * them). For a pair farther apart than bound a kernel may write any distance above bound, in
 * distance[i] and results[i].distance, and leave that pair's points and other result fields
 * unspecified; every pair at distance <= bound gets its exact outputs. A kernel may also ignore
 * bound and compute everything.
 *
 * Each instruction set provides one table row per precision (ttd_kernels_d, ttd_kernels_f). A
 * NULL entry means "not written for this ISA": the engine then uses the scalar row for that
 * method. */
#ifndef TTD_CORE_KERNELS_H
#define TTD_CORE_KERNELS_H

#include <stddef.h>
#include <stdint.h>
#include "ttd/ttd.h"

/// Pairs per block: bounds per-thread scratch, and is a multiple of every lane count.
#define TTD_BLOCK_PAIRS 256

/// The iterative methods' parameters, resolved from ttd_options (float kernels convert).
typedef struct ttd_params {
    double rho;
    double tol;
    int max_iterations;
} ttd_params;

/// Where a kernel writes one block's outputs; each may be NULL, not all three.
typedef struct ttd_out_d {
    double *distance;      ///< n distances
    double *points;        ///< 6n reals: p (3) then q (3) of each pair, the record a margin query keeps
    ttd_result_d *results; ///< n full results
} ttd_out_d;

/// ttd_out_d in single precision.
typedef struct ttd_out_f {
    float *distance;
    float *points;
    ttd_result_f *results;
} ttd_out_f;

typedef void (*ttd_kernel_d_fn)(size_t n, const double *s, const double *t, const ttd_params *prm,
                                double bound, const ttd_out_d *out);
typedef void (*ttd_kernel_f_fn)(size_t n, const float *s, const float *t, const ttd_params *prm,
                                float bound, const ttd_out_f *out);

/* ---- The mesh queries' node test ----------------------------------------------------------
 * A mesh hierarchy (src/mesh/) is a tree of nodes with up to TTD_NODE_WIDTH children, each
 * child bounded by an oriented box: centre c, orthonormal axes u (row i = axis i) and half
 * extents e, in its mesh's frame (relative to the mesh's origin). The node test bounds the
 * distance between one box X and every child box of a node Y from below. Y's frame is mapped
 * into X's box frame by the query: x -> M x + v (M = U_X R, v = U_X (t - c_X) for the pose
 * (R, t) of Y's mesh relative to X's), so the test sees X as the axis-aligned box [-e, e]. For
 * child j it takes the larger of two separating-axis bounds (simd/kernel_node.h): along X's
 * faces, and along the direction from X's point nearest the child's centre to that centre; it
 * returns the square. Both are true lower bounds up to the rounding of this
 * arithmetic, which the caller covers with a margin. Every row computes it with the same
 * operations in the same order (no FMA), so every ISA returns the same bits. Lanes past a
 * node's count hold zeros and their bounds are ignored. */

/// Children per node of a mesh hierarchy.
#define TTD_NODE_WIDTH 8

/// One node of a mesh hierarchy (double precision): its children's boxes, one array per
/// coordinate, and what each child is.
typedef struct ttd_node_d {
    double c[3][TTD_NODE_WIDTH];   ///< box centres
    double u[9][TTD_NODE_WIDTH];   ///< box axes: u[3i + k] = component k of axis i
    double e[3][TTD_NODE_WIDTH];   ///< half extents along the axes
    int32_t child[TTD_NODE_WIDTH]; ///< >= 0: a node; < 0: triangle -1 - child
    int32_t count;                 ///< children used (the rest hold zeros)
} ttd_node_d;

/// ttd_node_d in single precision.
typedef struct ttd_node_f {
    float c[3][TTD_NODE_WIDTH];
    float u[9][TTD_NODE_WIDTH];
    float e[3][TTD_NODE_WIDTH];
    int32_t child[TTD_NODE_WIDTH];
    int32_t count;
} ttd_node_f;

/// The box X of a node test, with Y's frame mapped into X's box frame (x -> m x + v).
typedef struct ttd_box_query_d {
    double m[9];  ///< row-major
    double v[3];
    double e[3];  ///< X's half extents
} ttd_box_query_d;

/// ttd_box_query_d in single precision.
typedef struct ttd_box_query_f {
    float m[9];
    float v[3];
    float e[3];
} ttd_box_query_f;

/// lb2[j] = the squared lower bound between box x and child j of node y (j < TTD_NODE_WIDTH);
/// sep[j] = the largest of the six face axes' gaps, negative when the boxes overlap along all
/// of them (how deep: a traversal walks the deepest overlaps first, where surfaces likely cross).
typedef void (*ttd_node_test_d_fn)(const ttd_box_query_d *x, const ttd_node_d *y, double lb2[TTD_NODE_WIDTH],
                                   double sep[TTD_NODE_WIDTH]);
typedef void (*ttd_node_test_f_fn)(const ttd_box_query_f *x, const ttd_node_f *y, float lb2[TTD_NODE_WIDTH],
                                   float sep[TTD_NODE_WIDTH]);
/// The node test, and the mask of the children j whose lb2[j] is not past lim2 (bit j, NaN within):
/// the same bits on every row.
typedef unsigned (*ttd_node_within_d_fn)(const ttd_box_query_d *x, const ttd_node_d *y, double lim2,
                                     double lb2[TTD_NODE_WIDTH], double sep[TTD_NODE_WIDTH]);
typedef unsigned (*ttd_node_within_f_fn)(const ttd_box_query_f *x, const ttd_node_f *y, float lim2,
                                     float lb2[TTD_NODE_WIDTH], float sep[TTD_NODE_WIDTH]);

/* ---- The point queries' kernels (src/points/, docs/points.md) ------------------------------
 * point_node (float rows only; the double walk calls the float row's): lb2[j] = a lower bound on
 * the squared distance from point p (in the frame of the walk's nodes, core/point_layout.h) to
 * child box j of walk node y, up to rounding the caller's margin covers, the same bits on every
 * row; returns the mask of children (bit j) with lb2[j] <= lim2 (an unused slot is never within). point_block: d[j] = the exact distance from
 * point p (the mesh's coordinates) to triangle j of a prepared block (core/point_layout.h:
 * TTD_PT_ROWS rows of TTD_PT_LANES reals), and par[0..2][j] the candidate that gives it (id, u, v):
 * the scalar reference's bits (scalar/point_impl.h's point_select). */
struct ttd_pnode;
struct ttd_rnode;
/* ray_node (float rows only): the mask of the child slots of ray node y whose boxes meet the box
 * [lo, hi] across axis k (the other two coordinates) and reach lo[k] (sigma > 0) or hi[k] (sigma <
 * 0) along it: exact comparisons, the same on every row. */
typedef unsigned (*ttd_ray_node_fn)(const float lo[3], const float hi[3], int k, int sigma, const struct ttd_rnode *y);
typedef unsigned (*ttd_point_node_fn)(const float p[3], const struct ttd_pnode *y, float lim2, float lb2[TTD_NODE_WIDTH]);
typedef void (*ttd_point_block_d_fn)(const double p[3], const double *block, double d[TTD_NODE_WIDTH],
                                     double par[3][TTD_NODE_WIDTH]);
typedef void (*ttd_point_block_f_fn)(const float p[3], const float *block, float d[TTD_NODE_WIDTH],
                                     float par[3][TTD_NODE_WIDTH]);
/* point_lanes: d[i] as point_block's for point i of 8 (P[c][i]) against one prepared triangle f
 * (stride 1), and the closest point q[c][i] and weights w[c][i] of its candidate (point_rebuild's
 * bits): points per lane, for meshes of a few triangles. */
typedef void (*ttd_point_lanes_d_fn)(const double *f, const double P[3][TTD_NODE_WIDTH], double d[TTD_NODE_WIDTH],
                                     double q[3][TTD_NODE_WIDTH], double w[3][TTD_NODE_WIDTH]);
typedef void (*ttd_point_lanes_f_fn)(const float *f, const float P[3][TTD_NODE_WIDTH], float d[TTD_NODE_WIDTH],
                                     float q[3][TTD_NODE_WIDTH], float w[3][TTD_NODE_WIDTH]);

/* tri_fit (double rows only; NULL on the scalar row): the boxes of triangles 0..count-1 of a leaf
 * (p[3k + c][i]: coordinate c of vertex k of triangle i, relative to the mesh's origin; radius:
 * the mesh's), as mesh/build.c's triangle_fit fits them, bit for bit: axes u[9], centre c[3],
 * extents e[3], lane i each, and the triangle's terms of its leaf's sums (terms[0..12][i]: mesh/build.c's
 * fitsum_terms, the same bits; those of a triangle outside the mask are the caller's to redo). Returns the mask of the triangles (bit i)
 * it fitted: the common case only (simd/kernel_trifit.h); the caller fits the others itself. */
typedef unsigned (*ttd_tri_fit_fn)(const double *const p[9], int count, double radius, double u[9][TTD_NODE_WIDTH],
                                   double c[3][TTD_NODE_WIDTH], double e[3][TTD_NODE_WIDTH],
                                   double terms[13][TTD_NODE_WIDTH]);

/* leaf_span (double rows only; NULL on the scalar row): the range [mn[a], mx[a]] of u_a . v over
 * the vertices v of triangles 0..count-1 (p as tri_fit's), as mesh/build.c's fit_extents computes
 * it, bit for bit. */
typedef void (*ttd_leaf_span_fn)(const double *const p[9], int count, const double u[9], double mn[3], double mx[3]);

/* leaf_axes (double rows only; NULL on the scalar row): the refitted axes u[9][i] of up to 8 leaves'
 * boxes (bit i of live), from their sums s[14][i] (mesh/build.c's fitsum: n[3], nlen, m[10]) and
 * their axes before the move old[9][i], as mesh/build.c's refit_axes computes them, bit for bit,
 * in its flat case. Returns the mask of the leaves it did (simd/kernel_trifit.h); the caller does
 * the others itself. */
typedef unsigned (*ttd_leaf_axes_fn)(const double s[14][TTD_NODE_WIDTH], const double old[9][TTD_NODE_WIDTH],
                                     unsigned live, double u[9][TTD_NODE_WIDTH]);

/* box_span (double rows only; NULL on the scalar row): for a double mesh's node whose rows are
 * yc, yu, ye (count boxes), the first pass of mesh/build.c's store_box_of_boxes about axes ua, bit
 * for bit: each child's slack[k] and spread[a][k], and the children's range [lo[a], hi[a]] along
 * the axes (simd/kernel_trifit.h). */
typedef void (*ttd_box_span_fn)(const double yc[3][TTD_NODE_WIDTH], const double yu[9][TTD_NODE_WIDTH],
                                const double ye[3][TTD_NODE_WIDTH], int count, const double ua[9], double lo[3],
                                double hi[3], double spread[3][TTD_NODE_WIDTH], double slack[TTD_NODE_WIDTH]);

/* self_screen (double rows only; NULL on the scalar row, whose loops are in
 * mesh/self_grid_impl.h): a self-contact query's screens, in double for both precisions (float
 * coordinates convert exactly). Boxes are axis-aligned: lo the minima of a triangle's vertices,
 * hi the maxima raised by the query's limit L (fl(hi + L)); padding lanes hold lo = +inf, hi =
 * -inf. A lane is near a box q (q[0..2] its lo, q[3..5] its raised hi) when on every axis lo[c] <=
 * q[3 + c] and q[c] <= hi[c]: comparisons only, the same bits on every row.
 * self_screen: every triangle i of leaf g against the 8 triangles of leaf h (with same, g is h and
 * only lanes j > i count; rows i whose box is not near h's leaf box are skipped, out[i] = 0):
 * out[i] gets, bits 0-7, the lanes whose box is near triangle i's, that share no vertex index with
 * it and are near it on each diagonal direction d (h's dg[d] <= g's dg[6 + d] and g's dg[d] <= h's
 * dg[6 + d]); bits 8-15, the lanes whose box is near that share one or more (the caller applies
 * the diagonal test to those it keeps); returns the rows: bit i where out[i] has a bit 0-7, bit
 * 8 + i where it has a bit 8-15 (the caller visits only the rows it keeps). */
typedef struct ttd_self_block {
    double lo[3][TTD_NODE_WIDTH], hi[3][TTD_NODE_WIDTH];
    double ix[3][TTD_NODE_WIDTH]; /* vertex indices (exact in double); -1 in padding lanes */
    uint32_t iv[3][TTD_NODE_WIDTH]; /* the same as 32-bit integers (0xFFFFFFFF in padding lanes), 8 to
                                     a vector where a row compares them so (AVX2) */
    double dg[12][TTD_NODE_WIDTH]; /* projections on x + y, x - y, x + z, x - z, y + z, y - z:
                                     minima (d), maxima raised by R (6 + d); 0 in padding lanes */
    double box[6];                /* the leaf's box: its lanes' lo minima and raised hi maxima */
} ttd_self_block;
typedef unsigned (*ttd_self_screen_fn)(const ttd_self_block *g, const ttd_self_block *h, int same, uint16_t out[TTD_NODE_WIDTH]);
/* box_list (double rows only; NULL on the scalar row): box q (as self_screen's boxes) against boxes 0..n-1,
 * n <= 64, of the six arrays at b, c apart (lo x, y, z, raised hi x, y, z; readable to the next
 * multiple of TTD_NODE_WIDTH past n): writes the near boxes' positions to at, in increasing order,
 * and returns their count; 8 boxes a step, all in one call. */
typedef unsigned (*ttd_box_list_fn)(const double *b, size_t c, unsigned n, const double q[6], uint8_t at[64]);
/* self_fill (double rows only; NULL on the scalar row): a leaf's 8 triangles, v[3 k + c][lane] the
 * coordinate c of vertex k, into their boxes (b->lo, b->hi: minima, and maxima + L) and their
 * projections on the six diagonal directions x + y, x - y, x + z, x - z, y + z, y - z (b->dg[d]:
 * minima, b->dg[6 + d]: maxima + R), by min(a, b) = a < b ? a : b and max(a, b) = a > b ? a : b
 * over the vertices in order and one rounded sum or difference each: the scalar loops' numbers
 * (what the screens compare; a zero's sign may differ, which no comparison sees). It writes no
 * other field of b: b->ix, filled once per mesh, is read by later queries (self_grid_impl.h). */
typedef void (*ttd_self_fill_fn)(const double v[9][TTD_NODE_WIDTH], double L, double R, ttd_self_block *b);

/* ccd_screen (double rows only; NULL on the scalar row): the continuous-collision screen in lanes
 * (simd/kernel_ccd.h), the bits of ccd/ccd.c's ttd_ccd_screen for queries 0..count-1 (count <=
 * TTD_NODE_WIDTH) of kind na (1 vertex-face, 2 edge-edge), each 12 reals in x0 and in x1 (the four
 * points at t = 0 and at t = 1); bit i set: query i proved free of contact on [0, t_max]. A query
 * whose largest coordinate magnitude is TTD_CCD_SCREEN_MAX or more, or not finite, is not proved. */
#define TTD_CCD_SCREEN_MAX 0x1p400
typedef unsigned (*ttd_ccd_screen_fn)(int na, int count, const double *x0, const double *x1, double delta,
                                      double t_max);

/* tri_apart (double rows only; NULL on the scalar row): mesh self-CCD's whole-pair proof
 * (meshccd/meshccd.c, tri_pair_apart; simd/kernel_tri_apart.h) on triangle pairs 0..count-1
 * (count <= TTD_NODE_WIDTH), one a lane: x[(18 e + 3 i + c) TTD_NODE_WIDTH + lane] is coordinate c
 * of point i (0..2 the first triangle, 3..5 the second) at t = e (36 rows), S[lane] the largest
 * coordinate magnitude among them; bit i set: pair i proved more than delta apart over the step,
 * the same bits as the scalar proof's. Every lane of x and S is read (fill the lanes past count
 * with finite numbers). */
typedef unsigned (*ttd_tri_apart_fn)(int count, const double *x, const double *S, double delta);
/* tri_apart_at (double rows only; NULL on the scalar row): the same proof with the points read
 * from the vertex arrays: pair l's point i (0..2 the first triangle, 3..5 the second) is vertex
 * v[i TTD_NODE_WIDTH + l], at x0 + 3 v (t = 0) and x1 + 3 v (t = 1), and S the largest of the six
 * vmag[v] (taken as a running maximum from 0 in the order i = 0..5); bit i as tri_apart's for those
 * numbers. Every lane of v is read (fill the lanes past count with valid vertices). */
typedef unsigned (*ttd_tri_apart_at_fn)(int count, const uint32_t *v, const double *x0, const double *x1,
                                        const double *vmag, double delta);

/* leaf_screen (double rows only; NULL on the scalar row): mesh self-CCD's leaf pairs
 * (meshccd/meshccd.c, leaf_pair_self; simd/kernel_tri_apart.h): boxes i = 0..na-1 (na <=
 * TTD_NODE_WIDTH) of the columns ra[c][i] against the TTD_NODE_WIDTH boxes of the columns rb[c][j]
 * (c = 0..2 the minima, 3..5 the maxima; every lane of rb is read): out[i] gets bit j where on
 * every axis rb[c][j] <= ra[3 + c][i] and ra[c][i] <= rb[3 + c][j] (comparisons only: the same bits
 * on every row); returns the rows i whose out[i] is not 0, as bits. */
typedef unsigned (*ttd_leaf_screen_fn)(const double *const ra[6], int na, const double *const rb[6],
                                       uint8_t out[TTD_NODE_WIDTH]);

/// One instruction set's kernels for one precision, indexed by ttd_method, and its node test
/// (one translation unit per ISA and precision defines each: src/isa/<isa>_d.c, _f.c;
/// scalar/kernels.c).
typedef struct ttd_kernels_d {
    ttd_isa isa;
    int lanes;                          ///< double lanes per vector (1 for scalar)
    ttd_kernel_d_fn fn[TTD_METHOD_COUNT];
    ttd_node_test_d_fn node_test;       ///< never NULL
    ttd_node_within_d_fn node_within;   ///< never NULL
    ttd_point_block_d_fn point_block;   ///< never NULL
    ttd_point_lanes_d_fn point_lanes;   ///< never NULL
    ttd_tri_fit_fn tri_fit;             ///< NULL on the scalar row
    ttd_leaf_span_fn leaf_span;         ///< NULL on the scalar row
    ttd_leaf_axes_fn leaf_axes;         ///< NULL on the scalar row
    ttd_box_span_fn box_span;           ///< NULL on the scalar row
    ttd_self_screen_fn self_screen;     ///< NULL on the scalar row
    ttd_box_list_fn box_list;           ///< NULL on the scalar row
    ttd_self_fill_fn self_fill;         ///< NULL on the scalar row
    ttd_ccd_screen_fn ccd_screen;       ///< NULL on the scalar row
    ttd_tri_apart_fn tri_apart;         ///< NULL on the scalar row
    ttd_tri_apart_at_fn tri_apart_at;   ///< NULL on the scalar row
    ttd_leaf_screen_fn leaf_screen;     ///< NULL on the scalar row
} ttd_kernels_d;

/// ttd_kernels_d for float.
typedef struct ttd_kernels_f {
    ttd_isa isa;
    int lanes;                          ///< float lanes per vector (1 for scalar)
    ttd_kernel_f_fn fn[TTD_METHOD_COUNT];
    ttd_node_test_f_fn node_test;
    ttd_node_within_f_fn node_within;
    ttd_point_node_fn point_node;         ///< never NULL; the double walk's too
    ttd_ray_node_fn ray_node;             ///< never NULL
    ttd_point_block_f_fn point_block;
    ttd_point_lanes_f_fn point_lanes;
} ttd_kernels_f;

/// What the engine must know of a method beyond its kernels (ttd_method_traits in core/traits.c).
typedef struct ttd_method_traits {
    unsigned char may_not_converge;    ///< may flag TTD_PAIR_NOT_CONVERGED, which the engine reports in the call's status
} ttd_method_traits;

/// The traits of method (a valid ttd_method).
const ttd_method_traits *ttd_method_traits_of(ttd_method method);

/* Rows; the scalar ones always exist, the others when CMake defines TTD_HAVE_<ISA>. */
extern const ttd_kernels_d ttd_kernels_scalar_d;
extern const ttd_kernels_f ttd_kernels_scalar_f;
extern const ttd_kernels_d ttd_kernels_sse2_d;
extern const ttd_kernels_f ttd_kernels_sse2_f;
extern const ttd_kernels_d ttd_kernels_avx2_d;
extern const ttd_kernels_f ttd_kernels_avx2_f;
extern const ttd_kernels_d ttd_kernels_avx512_d;
extern const ttd_kernels_f ttd_kernels_avx512_f;
extern const ttd_kernels_d ttd_kernels_neon_d;
extern const ttd_kernels_f ttd_kernels_neon_f;
extern const ttd_kernels_d ttd_kernels_portable_d;
extern const ttd_kernels_f ttd_kernels_portable_f;

#endif /* TTD_CORE_KERNELS_H */
