/* SPDX-License-Identifier: MIT */
/* A differential fuzzer for the mesh queries (ttd_mesh_distance / contacts / closest / collide).
 *
 * A case is two small meshes a and b and k poses of b, drawn from a family (degenerate soups,
 * thin triangles, contacts, gaps, scales, rotations at the orthogonality tolerance, grids) by a
 * byte source: a seeded splitmix64 stream (tests/test_mesh_fuzz.c) or a libFuzzer input
 * (tests/fuzz/fuzz_mesh.c, the stream continuing from the input's hash once it runs out). Every
 * query is run on every available instruction set with 1 and 2 threads and checked against a
 * brute force over all triangle pairs (the exact method on the scalar row, b moved exactly as
 * ttd.h documents); the brute force itself is checked on a sample of pairs against the quad
 * reference (tests/reference/). Half of the cases build their meshes from other vertices (the
 * case's permuted, jittered, rotated or collapsed to a point) and move them to the case's with
 * ttd_mesh_set_vertices_*, so that every query also runs on refitted (or rebuilt) trees; and each
 * mesh of up to 200 triangles is checked against itself (self-contacts at three margins with and
 * without shared-vertex pairs, self-collision) against tests/self_brute.h on every row and
 * thread count. docs/testing.md describes the checks. */
#ifndef TTD_TESTS_MESHFUZZ_H
#define TTD_TESTS_MESHFUZZ_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

/// The families of cases.
typedef enum mf_family {
    MF_COLLINEAR,  ///< exactly collinear triangles c = a + t(b - a), rounded, among ordinary ones
    MF_POINT,      ///< triangles a = b = c
    MF_SEGMENT,    ///< triangles with a repeated vertex (two equal coordinates)
    MF_REPEATED,   ///< repeated vertex indices and repeated vertex records
    MF_SLIVER,     ///< third vertex 1e-3..1e-15 of the length off the long edge
    MF_NEEDLE,     ///< one edge 1e-3..1e-15 of the length
    MF_DUPLICATE,  ///< duplicate triangles (same indices, permuted, or copied vertices)
    MF_COPLANAR,   ///< sheets in one plane, overlapping, touching or a hair apart
    MF_TOUCH,      ///< a vertex, an edge or a face of b on a vertex, an edge or a face of a
    MF_GAP,        ///< the same features 1e-15..1e-3 of the size apart
    MF_SCALED,     ///< soups scaled by 1e-8..1e8 and offset by 1e6
    MF_TOLERANCE,  ///< poses whose R^T R - I is near (within) the 1e-6 limit
    MF_GRID,       ///< a grid (up to ~100k triangles) against one triangle
    MF_MIXED,      ///< every triangle kind in one soup
    MF_COUNT
} mf_family;

/// What was checked (one counter each, per family).
typedef enum mf_query {
    MFQ_POSE,        ///< a pose within the tolerance is accepted
    MFQ_REFERENCE,   ///< a brute-force pair against the quad reference
    MFQ_DISTANCE,    ///< minimum distance, its pair, points, features, flags
    MFQ_BOUND,       ///< distance with an upper bound at or just below the minimum
    MFQ_RELTOL,      ///< distance with rel_tol
    MFQ_CONTACTS,    ///< the contact set at a margin
    MFQ_CLOSEST,     ///< the per-triangle closest partners at a margin
    MFQ_COLLIDE,     ///< collision at a margin
    MFQ_POSES,       ///< k poses in one call equal k single calls
    MFQ_THREADS,     ///< 2 threads equal 1 thread
    MFQ_ISA,         ///< every instruction set equals the scalar row
    MFQ_REFIT,       ///< a mesh built from other vertices takes the case's (ttd_mesh_set_vertices_*)
    MFQ_SELF,        ///< self-contacts and self-collision of each mesh (both flag settings)
    MFQ_COUNT
} mf_query;

/// Counters and settings of a run; zero-initialise, then set the settings.
typedef struct mf_run {
    /* settings */
    int verbose;           ///< print every case and dump failing cases' meshes and poses
    int max_printed;       ///< failures printed in full (the rest only counted); 0 = 20
    int allow_big;         ///< grids of ~100k triangles may be drawn (seeded runs)
    int one_isa;           ///< check only the scalar row and the automatic choice (fast fuzzing)
    int small;             ///< at most 24 triangles a mesh (libFuzzer under the sanitizers)
    int dump_failures;     ///< print a failing case's meshes and poses (--verbose does too)
    FILE *out;             ///< where failures go (NULL: stdout)
    /* counters */
    uint64_t checks, failures, cases, poses;
    uint64_t family_checks[MF_COUNT], family_failures[MF_COUNT];
    uint64_t query_failures[MF_COUNT][MFQ_COUNT];
    int isas_run[8];       ///< which instruction sets were run (indexed by ttd_isa)
    int float_cases, double_cases;
} mf_run;

/// A byte source: data first (a libFuzzer input), then splitmix64 from seed.
typedef struct mf_src {
    const uint8_t *data;
    size_t size, pos;
    uint64_t state;
} mf_src;

/// The source for case `index` of a seeded run: its own stream, so a case can be rerun alone.
void mf_src_seeded(mf_src *src, uint64_t seed, uint64_t index);
/// The source reading a libFuzzer input, continuing from its hash.
void mf_src_bytes(mf_src *src, const uint8_t *data, size_t size);

const char *mf_family_name(int family);
/// The family called name, or -1.
int mf_family_from_name(const char *name);
const char *mf_query_name(int query);

/// Draws one case of family (or, for family < 0, a family drawn from src), runs every query on
/// it and checks them. seed and index only label the failures printed. Returns the failures.
uint64_t mf_run_case(mf_run *run, mf_src *src, int family, uint64_t seed, uint64_t index);

/// Prints the per-family table and the one-line summary; returns non-zero when anything failed.
int mf_summary(const mf_run *run, FILE *f);

#endif /* TTD_TESTS_MESHFUZZ_H */
