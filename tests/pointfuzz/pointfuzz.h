/* SPDX-License-Identifier: MIT */
/* The point queries' differential fuzzer (docs/testing.md): cases drawn from a byte source (a
 * libFuzzer input, then a stream seeded by its hash; or a seeded stream alone), each a small mesh
 * of hostile triangles (needles down to 1e-15 wide, slivers, segments, points, duplicates, shared
 * vertices) at a scale of 1e-8..1e8 and an offset up to 1e6, in double or float, and points near
 * it (on faces, edges, vertices, 10^-k off them), around it and far away, with an optional upper
 * bound and pose. Every case checks, on the scalar row and the automatic choice with 1 and 2
 * threads: the closest point against the brute force over every triangle with ttd_point_triangle
 * (bit for bit, ties to the smallest index, the bound), the rows and thread counts against each
 * other, signed distances against the closest distance and the winding number's side, every
 * proven side against a long double sum of the solid angles (tests/ref_winding.h), and the
 * statuses. A third of the cases are a closed box (corners jittered by 0.1 of its size) wound
 * outward, inward (every face reversed), inconsistently (some faces reversed) or open (a face
 * removed): its ttd_mesh_orientation, contains equal to the inside rule on the reported winding
 * number, a closed box's winding number equal to the long double sum rounded (never flagged), an
 * inward box's contains and signs those of the outward one, and an inconsistent or open box's
 * sides those of the long double sum (off the surface; flagged unproven only within 1e-6 of
 * |w| = 1/2). A third of the boxes carry a tiny box (2^-4..2^-563 their size), a third are
 * unwelded (each triangle its own corners, moved by up to 2 ulps) and then welded back with
 * ttd_mesh_weld_* and checked again, and a quarter of all cases are scaled by 2^k across the
 * coordinate range (docs/testing.md). Used by tests/test_points_fuzz.c (CTest, seeded) and tests/fuzz/fuzz_points.c
 * (libFuzzer). */
#ifndef TTD_TESTS_POINTFUZZ_H
#define TTD_TESTS_POINTFUZZ_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

typedef struct pf_src {
    const uint8_t *data;
    size_t size, pos;
    uint64_t state;
    uint64_t *log;             /* when not NULL: the words drawn (caplog at most; nlog counts all) */
    size_t nlog, caplog;
    size_t nlog_first;         /* the words the first families' draws took (before pf_extras) */
} pf_src;

/// A source reading data first, then a stream seeded by its hash (data may be NULL).
void pf_src_init(pf_src *src, const uint8_t *data, size_t size, uint64_t seed);

/// The proven sides checked against the long double winding number so far (every case's mesh):
/// points 1e-9 of the mesh's size (1e-5 in float) or more off it, and as far off a tiny box
/// relative to its size.
extern size_t pf_sides_checked;

/// What the cases drawn so far held: boxes with a tiny box, unwelded boxes, of those welded back
/// and checked again, cases scaled by a power of two (the least and largest exponent), and closed
/// meshes' winding numbers checked equal to the rounded long double sum.
typedef struct pf_counts {
    size_t tiny, unwelded, welded, scaled, exact;
    int exp_lo, exp_hi;
} pf_counts;
extern pf_counts pf_count;

/// Runs one case; prints what failed to out (with the case when dump is set). Returns the number
/// of failed checks (0: the case passed). *points, when not NULL, gets the points checked.
int pf_run_case(pf_src *src, FILE *out, int dump, size_t *points);

/// The words (8 bytes each) a case drawn from data (or from seed alone, data NULL) takes, into
/// words (cap at most); returns their count, *first the count before the later families' draws.
/// Written out, they are an input that draws the same case from its bytes alone: how
/// `test_points_fuzz --write` keeps a seeded case, and `--extend` an input found before the later
/// families (tests/fuzz/corpus/points/), in the corpus.
size_t pf_case_words(const uint8_t *data, size_t size, uint64_t seed, uint64_t *words, size_t cap, size_t *first);

#endif /* TTD_TESTS_POINTFUZZ_H */
