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

/// One instruction set's kernels for one precision, indexed by ttd_method (one translation
/// unit per ISA and precision defines each: src/isa/<isa>_d.c, _f.c; scalar/kernels.c).
typedef struct ttd_kernels_d {
    ttd_isa isa;
    int lanes;                          ///< double lanes per vector (1 for scalar)
    ttd_kernel_d_fn fn[TTD_METHOD_COUNT];
} ttd_kernels_d;

/// ttd_kernels_d for float.
typedef struct ttd_kernels_f {
    ttd_isa isa;
    int lanes;                          ///< float lanes per vector (1 for scalar)
    ttd_kernel_f_fn fn[TTD_METHOD_COUNT];
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
