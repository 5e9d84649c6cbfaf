/* SPDX-License-Identifier: MIT */
/* The contract between the batch engine and the code that computes distances.
 *
 * A kernel computes n pairs of one contiguous block: s and t hold 9n coordinates in the
 * user's layout (pair i at 9i, no alignment promised). The engine hands a kernel finite
 * coordinates only (a pair with NaN/inf is replaced by a placeholder and its outputs are
 * overwritten afterwards), at most TTD_BLOCK_PAIRS pairs at a time. distance and results
 * may each be NULL (not both); a kernel writes whichever is given, and sets results[i].flags
 * from TTD_PAIR_DEGENERATE_*, TTD_PAIR_INTERSECTING, TTD_PAIR_NOT_CONVERGED and
 * TTD_PAIR_FALLBACK (certified mode) only.
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

typedef void (*ttd_kernel_d_fn)(size_t n, const double *s, const double *t, const ttd_params *prm,
                                double *distance, ttd_result_d *results);
typedef void (*ttd_kernel_f_fn)(size_t n, const float *s, const float *t, const ttd_params *prm,
                                float *distance, ttd_result_f *results);

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
