/* SPDX-License-Identifier: MIT */
/* Deterministic triangle-pair generators, shared by the tests, the benchmark and the accuracy
 * harness. Every family writes n pairs in the library's layout: s and t hold 9n doubles each,
 * pair i at offset 9i (vertices A B C of the first triangle, D E F of the second, x y z each).
 * Float callers round the doubles themselves.
 *
 * Determinism: pair i depends only on (family, seed, i), through a private splitmix64 stream,
 * and is built from IEEE basic operations and sqrt only (no libm transcendental functions), so
 * the same call gives bit-identical pairs on every platform with -ffp-contract=off, and a
 * prefix of a longer run equals a shorter run.
 *
 * Families (the size of a triangle is about 1 unless said otherwise):
 *   random               A B C uniform in [0,1)^3; D E F uniform in [0,1)^3 plus one offset
 *                        uniform in [-0.5,0.5)^3 shared by D E F. About 10% intersect. THE
 *                        benchmark workload.
 *   paper                one fixed, plainly separated pair replicated n times:
 *                        S = (0,0,0) (1,0,0) (0,1,0), T = (0.3,0.3,0.5) (1,0.5,1.2) (0.4,1.1,0.9);
 *                        distance 0.5 (vertex D over the face of S).
 *   far                  random unit-size triangles, the second moved along a random direction
 *                        by L in [1e1, 1e8) (decade uniform, then mantissa uniform in [1,10)).
 *   near_parallel_edges  an edge of each triangle, the two at an angle 10^-k (k in 0..10, and
 *                        exactly 0 for one pair in 12, then moved exactly), gap 10^-j (j in 0..6), overlapping along
 *                        their length, the triangles extending away from each other; then a
 *                        random rotation and translation.
 *   near_parallel_faces  the second triangle in a plane tilted by 10^-k (k in 0..10, or exactly
 *                        0 and moved exactly) from the first's, overlapping in projection, gap 10^-j (j in 0..6);
 *                        then a random rotation and translation.
 *   near_touching        vertex-face, edge-edge (crossing), edge-face (parallel) and face-face
 *                        (parallel) contacts at gap g = +-10^-k (k in 0..12; one pair in four
 *                        has g < 0, a slight penetration); then a random rotation and
 *                        translation.
 *   intersecting         pierce (an edge through the other's interior), coplanar overlap, edge
 *                        through edge, vertex on face, vertex on edge, shared vertex, shared
 *                        edge. The contact is exact: coordinates are on a dyadic grid and only
 *                        exact motions are applied (axis permutations, sign flips, dyadic
 *                        translations). Distance 0 for every pair.
 *   degenerate           one or both triangles a segment (collinear, exactly), a point (three
 *                        equal vertices) or with two repeated vertices; the other random or
 *                        degenerate too; exact dyadic coordinates.
 *   sliver               needles (two vertices 10^-k apart) and flat caps (a vertex 10^-k from
 *                        the opposite edge), k in 0..10, for one or both triangles, randomly
 *                        rotated, placed as in random.
 *   scaled               random pairs scaled about the origin by a factor in [1e-6, 1e6) (decade uniform,
 *                        mantissa uniform).
 *   offset               random pairs, both triangles translated by the same vector of length
 *                        L in [1, 1e6) (as above), random direction.
 *   features             pair i has feature pairing i mod 15 as its unique closest pair, the
 *                        vertex labels kept (no shuffling): 0..2 vertex i of S over the face
 *                        of T; 3..5 vertex i-3 of T over the face of S; 6..14 edge (i-6)/3 of S
 *                        (AB, BC, CA) crossing over edge (i-6)%3 of T (DE, EF, FD); gap in
 *                        [1e-3, 1); then a random rotation and translation.
 *                        ttd_gen_features_expected gives the expected feature masks.
 *
 * "Down to 10^-k" above means a value in (10^-k/2, 10^-k] with k uniform in the range.
 */
#ifndef TTD_GEN_PAIRS_H
#define TTD_GEN_PAIRS_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/// The families, in the order of the name table.
typedef enum ttd_gen_family {
    TTD_GEN_RANDOM = 0,
    TTD_GEN_PAPER,
    TTD_GEN_FAR,
    TTD_GEN_NEAR_PARALLEL_EDGES,
    TTD_GEN_NEAR_PARALLEL_FACES,
    TTD_GEN_NEAR_TOUCHING,
    TTD_GEN_INTERSECTING,
    TTD_GEN_DEGENERATE,
    TTD_GEN_SLIVER,
    TTD_GEN_SCALED,
    TTD_GEN_OFFSET,
    TTD_GEN_FEATURES,
    TTD_GEN_COUNT
} ttd_gen_family;

/// Writes n pairs of family f into s and t (9n doubles each). Returns n, or 0 when f is out
/// of range or s/t is NULL.
size_t ttd_gen(ttd_gen_family f, uint64_t seed, size_t n, double *s, double *t);

/// "random", "paper", "far", ... (the names above); NULL when out of range.
const char *ttd_gen_name(ttd_gen_family f);

/// The family called name, or -1.
int ttd_gen_family_from_name(const char *name);

/* One function per family, each the same as ttd_gen with that family. */
size_t ttd_gen_random(uint64_t seed, size_t n, double *s, double *t);
size_t ttd_gen_paper(uint64_t seed, size_t n, double *s, double *t);
size_t ttd_gen_far(uint64_t seed, size_t n, double *s, double *t);
size_t ttd_gen_near_parallel_edges(uint64_t seed, size_t n, double *s, double *t);
size_t ttd_gen_near_parallel_faces(uint64_t seed, size_t n, double *s, double *t);
size_t ttd_gen_near_touching(uint64_t seed, size_t n, double *s, double *t);
size_t ttd_gen_intersecting(uint64_t seed, size_t n, double *s, double *t);
size_t ttd_gen_degenerate(uint64_t seed, size_t n, double *s, double *t);
size_t ttd_gen_sliver(uint64_t seed, size_t n, double *s, double *t);
size_t ttd_gen_scaled(uint64_t seed, size_t n, double *s, double *t);
size_t ttd_gen_offset(uint64_t seed, size_t n, double *s, double *t);
size_t ttd_gen_features(uint64_t seed, size_t n, double *s, double *t);

/// The closest features of pair i of the features family, as vertex masks (bit k = vertex
/// k; 1 bit a vertex, 2 an edge, 7 the face), as in ttd_result_*.feature_p / feature_q.
void ttd_gen_features_expected(size_t i, unsigned *feature_s, unsigned *feature_t);

/// A small deterministic generator (splitmix64), exposed for tests that need random numbers.
typedef struct ttd_gen_rng {
    uint64_t state;
} ttd_gen_rng;

/// A stream for (seed, stream); different streams are independent for practical purposes.
ttd_gen_rng ttd_gen_rng_make(uint64_t seed, uint64_t stream);
uint64_t ttd_gen_rng_u64(ttd_gen_rng *r);
/// Uniform in [0, 1) with 53 random bits.
double ttd_gen_rng_uniform(ttd_gen_rng *r);
/// A uniformly random rotation matrix (row-major 3x3), from a unit quaternion.
void ttd_gen_rng_rotation(ttd_gen_rng *r, double m[9]);

#ifdef __cplusplus
}
#endif
#endif /* TTD_GEN_PAIRS_H */
