/* SPDX-License-Identifier: MIT */
/* Deterministic mesh generators and rigid poses for the mesh-vs-mesh queries: the tests, the
 * CLI and the benchmark build their meshes and poses here. A mesh is indexed: 3 doubles per
 * vertex, 3 uint32 vertex indices per triangle, triangles oriented counter-clockwise seen from
 * outside (closed meshes have a positive signed volume).
 *
 * Determinism: everything is built from IEEE basic operations and sqrt, so a call gives the
 * same bits on every platform with -ffp-contract=off (as gen/pairs.c), EXCEPT ttd_gen_torus and
 * ttd_gen_folded_sheet, which need sin and cos: their vertices may differ in the last bit
 * between libm versions (their connectivity never does). New vertices are numbered in a fixed traversal order, never in the
 * order of a hash table.
 *
 * Every function returning int returns 0 on success and -1 on bad arguments or allocation
 * failure; it never aborts. On failure *out is left empty (all zero), so ttd_gen_mesh_free on
 * it is harmless. Output meshes are allocated with malloc; free them with ttd_gen_mesh_free.
 *
 * Poses: 12 doubles, the 3x4 matrix [R | t] row by row (r00 r01 r02 t0 r10 r11 r12 t1 r20 r21
 * r22 t2). A pose maps the second mesh's coordinates into the first's frame: x_A = R x_B + t.
 */
#ifndef TTD_GEN_MESHES_H
#define TTD_GEN_MESHES_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/// An indexed triangle mesh: verts holds 3 nv doubles (x y z), tris 3 nt indices below nv.
typedef struct ttd_gen_mesh {
    double *verts;
    size_t nv;
    uint32_t *tris;
    size_t nt;
} ttd_gen_mesh;

/// Frees the arrays and zeroes *m (NULL is allowed).
void ttd_gen_mesh_free(ttd_gen_mesh *m);

/// A copy of in (out may not alias in).
int ttd_gen_mesh_copy(const ttd_gen_mesh *in, ttd_gen_mesh *out);

/* ---- closed surfaces ----------------------------------------------------------------- */

/// The unit sphere: level 0 is the icosahedron (12 vertices, 20 triangles); each level splits
/// every triangle 4:1 at its edge midpoints, which are shared between the two triangles of an
/// edge and pushed out to radius 1. Level L has 20*4^L triangles and 10*4^L + 2 vertices, and
/// its first vertices are those of level L-1. level in 0..10 (20,971,520 triangles).
int ttd_gen_icosphere(int level, ttd_gen_mesh *out);

/// A torus around the z axis: tube centre radius R, tube radius r (0 < r < R), nu segments
/// around z and nv around the tube (each >= 3, nu*nv < 2^32): nu*nv vertices, 2*nu*nv
/// triangles, closed, every vertex shared. Vertex (i, j) = index i*nv + j is at
/// ((R + r cos b) cos a, (R + r cos b) sin a, r sin b), a = 2 pi i/nu, b = 2 pi j/nv.
/// Uses sin and cos (see the determinism note above).
int ttd_gen_torus(double R, double r, size_t nu, size_t nv, ttd_gen_mesh *out);

/* ---- small meshes for tests ---------------------------------------------------------- */

/// One triangle (0,0,0) (1,0,0) (0,1,0).
int ttd_gen_mesh_triangle(ttd_gen_mesh *out);
/// The tetrahedron (0,0,0) (1,0,0) (0,1,0) (0,0,1): 4 triangles, closed.
int ttd_gen_mesh_tetrahedron(ttd_gen_mesh *out);
/// The unit cube [0,1]^3: 8 vertices (vertex x + 2y + 4z), 12 triangles, closed.
int ttd_gen_mesh_cube(ttd_gen_mesh *out);
/// The unit cube with every face's 4 corners its own vertices (24 vertices, 12 triangles):
/// vertices with the same coordinates and different indices, as in files with per-face
/// normals. Geometrically the cube of ttd_gen_mesh_cube, triangle for triangle.
int ttd_gen_mesh_duplicate_vertices(ttd_gen_mesh *out);
/// A mesh of trouble: a plain triangle (0,0,0) (1,0,0) (0,1,0), then a triangle with a
/// repeated vertex index (a segment), a point (one index three times), three distinct vertices
/// exactly on the x axis, a triangle whose two distinct vertices have the same coordinates, a
/// needle (one edge 1e-10 long) and a flat cap (a vertex 1e-10 from the opposite edge). Open.
int ttd_gen_mesh_degenerate(ttd_gen_mesh *out);
/// Three triangles on one edge (vertices 0 and 1): an edge that is not manifold.
int ttd_gen_mesh_nonmanifold(ttd_gen_mesh *out);
/// The unit square [0,1]^2 at z = 0 as n x n quads, each split along its diagonal from
/// (i, j) to (i+1, j+1): (n+1)^2 vertices (vertex (i, j) = index j*(n+1) + i at (i/n, j/n, 0)),
/// 2 n^2 triangles, normals +z. n >= 1, (n+1)^2 < 2^32.
int ttd_gen_grid(size_t n, ttd_gen_mesh *out);

/// ttd_gen_grid(n) folded like a paper: the square's x axis laid along a path in the xz-plane of
/// `layers` straight runs (1..64) joined by arcs of radius gap/2 that turn by t pi, left and
/// right in turn (t in [0, 2]: 0 flat, 1 folded flat into layers gap apart, above 1 the layers
/// pass through one another); y unchanged. The self-contact tests' and benchmark's deforming
/// sheet. Uses sin and cos (see the determinism note above). Fails when the arcs would be longer
/// than the sheet.
int ttd_gen_folded_sheet(size_t n, int layers, double gap, double t, ttd_gen_mesh *out);
/// The same fold on a strip of nx x ny square quads of edge 1/nx (x in [0, 1] along the fold's
/// path, y in [0, ny/nx]; vertex (i, j) = index j*(nx+1) + i; nx, ny in 1..65534): ttd_gen_folded_sheet
/// is ttd_gen_folded_strip(n, n, ...). The benchmark's 7-layer sheet is 595 x 85 (101,150
/// triangles, layers of about 85 x 85 quads).
int ttd_gen_folded_strip(size_t nx, size_t ny, int layers, double gap, double t, ttd_gen_mesh *out);

/* ---- operations ---------------------------------------------------------------------- */

/// Flat subdivision: levels times, every triangle (a, b, c) becomes (a, ab, ca), (ab, b, bc),
/// (ca, bc, c), (ab, bc, ca), where ab = 0.5 a + 0.5 b is one new vertex per distinct edge
/// (shared by every triangle on that edge). The surface does not change (up to the rounding of
/// the midpoints); triangles multiply by 4 per level, vertices grow by the number of edges.
/// The old vertices keep their indices. levels in 0..16 (0 copies); out may be the same as in.
/// Fails when an index is out of range or the result would need 2^32 vertices or more.
int ttd_gen_subdivide(const ttd_gen_mesh *in, int levels, ttd_gen_mesh *out);

/// Moves and scales m in place: bounding-box centre to the origin, bounding-box diagonal 1
/// (both to rounding). Fails (m unchanged) when m has no vertex, a non-finite coordinate, a
/// zero diagonal, or a diagonal that overflows.
int ttd_gen_normalize(ttd_gen_mesh *m);

/// The axis-aligned bounding box of m's vertices; -1 when m has no vertex.
int ttd_gen_mesh_bounds(const ttd_gen_mesh *m, double lo[3], double hi[3]);

/// out = in with every vertex x replaced by R x + t (pose as above); out may be the same as in.
int ttd_gen_mesh_transform(const ttd_gen_mesh *in, const double pose[12], ttd_gen_mesh *out);

/* ---- poses --------------------------------------------------------------------------- */

/// Pose number i of the stream seed: a uniformly distributed rotation (ttd_gen_rng_rotation,
/// a random unit quaternion) and a translation uniform in [-scale, scale)^3. Depends only on
/// (seed, i). scale = 0 gives a pure rotation.
void ttd_gen_pose(uint64_t seed, uint64_t i, double scale, double pose[12]);

/// A pose that puts mesh b next to mesh a at a chosen gap along a direction, for benchmarks
/// that need far, near, touching and overlapping placements. b is rotated by the rotation of
/// ttd_gen_pose(seed, i, ...), its bounding-box centre put on a's, then it is moved along the
/// unit vector u = dir/|dir| (dir NULL: a random direction drawn from (seed, i)) until the two
/// meshes' extents along u are separated by gap: every vertex x of a has u.x <= h and every
/// vertex of b placed by the pose has u.x >= h + gap, equality attained, up to the rounding
/// of the pose (a few ulps of the meshes' coordinates).
/// So for gap > 0 the meshes are at least gap apart; the true distance is usually larger
/// (how much depends on the shapes near the supporting points) and must be measured by the
/// caller. For gap <= 0 the slabs overlap by -gap; the meshes may or may not intersect.
/// With normalized meshes (diagonal 1), gap = 1, 0.01, 0.002 and -0.05 give the "far", "near",
/// "contact" and "overlapping" placements. Fails on empty meshes, non-finite gap or a
/// zero or non-finite dir.
int ttd_gen_pose_gap(const ttd_gen_mesh *a, const ttd_gen_mesh *b, uint64_t seed, uint64_t i,
                     const double dir[3], double gap, double pose[12]);

#ifdef __cplusplus
}
#endif
#endif /* TTD_GEN_MESHES_H */
