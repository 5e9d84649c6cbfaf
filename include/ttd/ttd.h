/* SPDX-License-Identifier: MIT */
/* ttd: minimum distance between 3D triangles, many pairs at a time, on SIMD hardware. */
#ifndef TTD_TTD_H
#define TTD_TTD_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(_WIN32) && defined(TTD_BUILD_SHARED)
#define TTD_API __declspec(dllexport)
#elif defined(__GNUC__)
#define TTD_API __attribute__((visibility("default")))
#else
#define TTD_API
#endif

#define TTD_VERSION_MAJOR 0
#define TTD_VERSION_MINOR 1
#define TTD_VERSION_PATCH 0

/** @defgroup ttd ttd public API
 * A triangle is 9 coordinates: vertices A, B, C (first triangle, "S") or D, E, F (second,
 * "T"), x y z each. A batch of n pairs is two arrays of 9n numbers, pair i at offset 9i.
 * Every entry returns a ttd_status; the library never aborts, keeps no global mutable state
 * (beyond a cached word of CPU features that every thread computes alike), and may be called
 * from many threads at once.
 * @{ */

/// What a call did. Values below TTD_ERR_FIRST_FATAL still computed every finite pair.
typedef enum ttd_status {
    TTD_OK = 0,                   ///< every pair computed
    TTD_WARN_NOT_CONVERGED = 1,   ///< an iterative method hit its cap on some pairs (flagged)
    /// Some pairs had NaN/inf coordinates: flagged, outputs NaN; the rest computed. Takes
    /// precedence over TTD_WARN_NOT_CONVERGED: check the per-pair flags for that too.
    TTD_ERR_NONFINITE_INPUT = 2,
    TTD_ERR_FIRST_FATAL = 16,     ///< marker: from here on nothing was computed (but see OUT_OF_MEMORY)
    TTD_ERR_NULL_POINTER = 16,    ///< a required pointer was NULL
    TTD_ERR_EMPTY = 17,           ///< n == 0: nothing to compute
    TTD_ERR_BAD_OPTIONS = 18,     ///< options not from ttd_default_options(), or a field out of range
    /// The forced instruction set (options.isa, or TTD_ISA with AUTO) is not built in, not
    /// supported here, or (TTD_ISA) not a name that ttd_isa_name() gives.
    TTD_ERR_ISA_UNAVAILABLE = 19,
    TTD_ERR_INDEX_OUT_OF_RANGE = 20, ///< mesh entry: a triangle or vertex index is out of range; nothing written
    TTD_ERR_OUT_OF_MEMORY = 21,   ///< a per-thread scratch allocation failed; outputs partly written, indeterminate
    TTD_ERR_TOO_LARGE = 22        ///< n (or a mesh size) so large that its arrays cannot exist in memory
} ttd_status;

/// How the distance is computed.
typedef enum ttd_method {
    TTD_METHOD_EXACT = 0,             ///< 6 vertex-face, 9 edge-edge and 6 edge-face crossing tests; exact to rounding
    TTD_METHOD_PENALTY = 1,           ///< the paper's quasi-Newton penalty method, optimised and safeguarded
    /// The paper's MATLAB ttd1 step for step, for comparison: raw coordinates, so rho and tol
    /// are absolute as published (not scale-invariant; pairs far from unit size may stop early).
    TTD_METHOD_PENALTY_REFERENCE = 2,
    TTD_METHOD_BARRIER = 3,           ///< log-barrier Newton method, the paper's first attempt (for comparison)
    /// the penalty method, its answer checked for optimality on the final active set and
    /// solved there exactly; pairs that fail the check are computed by the exact method
    TTD_METHOD_CERTIFIED = 4,
    TTD_METHOD_COUNT = 5
} ttd_method;

/// Instruction sets; TTD_ISA_AUTO picks the best one that is built and that the CPU and OS support.
typedef enum ttd_isa {
    TTD_ISA_AUTO = 0,
    TTD_ISA_SCALAR = 1, ///< the plain C reference, one pair at a time
    TTD_ISA_SSE2 = 2,
    TTD_ISA_AVX2 = 3,   ///< AVX2 with FMA
    TTD_ISA_AVX512 = 4, ///< AVX-512 F, DQ and VL
    TTD_ISA_NEON = 5,
    /// GCC/clang vector extensions, 4 doubles or 8 floats per vector, on any target: the row
    /// for machines without a hand-written one (after them in the automatic choice)
    TTD_ISA_PORTABLE = 6,
    TTD_ISA_COUNT = 7
} ttd_isa;

/// Per-pair flags, in ttd_result_*.flags.
enum {
    TTD_PAIR_NONFINITE = 1u << 0,     ///< input had NaN or inf: every output of the pair is NaN
    TTD_PAIR_DEGENERATE_S = 1u << 1,  ///< the first triangle has zero area (a segment or a point)
    TTD_PAIR_DEGENERATE_T = 1u << 2,  ///< the second triangle has zero area
    TTD_PAIR_INTERSECTING = 1u << 3,  ///< the triangles touch or cross: distance 0
    TTD_PAIR_NOT_CONVERGED = 1u << 4, ///< iterative method: hit max_iterations; points still lie on their triangles
    TTD_PAIR_FALLBACK = 1u << 5       ///< certified mode: this pair failed the optimality check and was computed by the exact method
};

/// Everything known about one pair (double precision).
typedef struct ttd_result_d {
    double distance;   ///< |p - q|
    double p[3];       ///< closest point on the first triangle
    double q[3];       ///< closest point on the second triangle (== p up to rounding when they intersect)
    double bary_p[3];  ///< weights of A, B, C that give p (non-negative, sum 1)
    double bary_q[3];  ///< weights of D, E, F that give q
    uint32_t flags;    ///< TTD_PAIR_* bits
    uint8_t feature_p; ///< bit i set when vertex i has a non-zero weight in p: 1 bit = vertex, 2 = edge, 3 = face
    uint8_t feature_q; ///< the same for q
    uint16_t iterations; ///< Newton iterations used (0 for the exact method)
} ttd_result_d;

/// Everything known about one pair (single precision).
typedef struct ttd_result_f {
    float distance;    ///< |p - q|
    float p[3];        ///< closest point on the first triangle
    float q[3];        ///< closest point on the second triangle
    float bary_p[3];   ///< weights of A, B, C that give p
    float bary_q[3];   ///< weights of D, E, F that give q
    uint32_t flags;    ///< TTD_PAIR_* bits
    uint8_t feature_p; ///< as in ttd_result_d
    uint8_t feature_q; ///< as in ttd_result_d
    uint16_t iterations; ///< Newton iterations used (0 for the exact method)
} ttd_result_f;

/// The largest penalty weight ttd_options.rho accepts (its expanded pivots hold rho^2).
#define TTD_RHO_MAX 1.0e150
/// The largest step tolerance ttd_options.tol accepts (the methods work in a unit-size frame).
#define TTD_TOL_MAX 1.0

/// Options for every call. Get them from ttd_default_options(), then change fields.
typedef struct ttd_options {
    ttd_method method;  ///< default TTD_METHOD_EXACT
    /// Default TTD_ISA_AUTO; with AUTO the environment variable TTD_ISA (a name from
    /// ttd_isa_name(); empty or "auto" = best) may force one.
    ttd_isa isa;
    int threads;        ///< worker threads for batches, >= 0; 0 (default) = all online cores; at most 256 used
    /// Penalty weight, in (0, 1e150] (default 1e6). The barrier method lowers its weight to
    /// 1/rho^2. The float penalty and certified kernels use min(rho, 256) (a larger weight
    /// loses sliver pivots to rounding); the float ttd1 reference min(rho, 1e18).
    double rho;
    /// Newton step length below which an iteration stops, in [0, 1] (default 1e-12), measured
    /// on the pair translated and scaled to unit size (the paper's ttd1 reference: raw
    /// coordinates). The float penalty and certified kernels use max(tol, 1e-6).
    double tol;
    int max_iterations; ///< Newton iteration cap, 1..65535 (default 99, the paper's)
    uint32_t internal_cookie; ///< set by ttd_default_options(); calls reject options without it
} ttd_options;

/// The defaults: exact method, best instruction set, all cores, documented penalty parameters.
TTD_API ttd_options ttd_default_options(void);

/// Distance between one pair. opt may be NULL (defaults). s and t hold 9 coordinates each.
TTD_API ttd_status ttd_distance_d(const ttd_options *opt, const double s[9], const double t[9],
                                  ttd_result_d *out);
/// Single-precision ttd_distance_d.
TTD_API ttd_status ttd_distance_f(const ttd_options *opt, const float s[9], const float t[9],
                                  ttd_result_f *out);

/// Distances of n pairs: s and t hold 9n coordinates each (pair i at 9i; any alignment).
/// distance (n values) and results (n structs) are outputs; either may be NULL, not both.
/// opt may be NULL (defaults), here and in every entry below.
TTD_API ttd_status ttd_batch_d(const ttd_options *opt, size_t n, const double *s, const double *t,
                               double *distance, ttd_result_d *results);
/// Single-precision ttd_batch_d.
TTD_API ttd_status ttd_batch_f(const ttd_options *opt, size_t n, const float *s, const float *t,
                               float *distance, ttd_result_f *results);

/// Distances of candidate pairs between two indexed meshes, without copying triangles out.
/// Mesh k has nv_k vertices (3 coordinates each) and nt_k triangles (3 vertex indices each).
/// pairs holds 2n indices: triangle pairs[2i] of mesh 1 against triangle pairs[2i+1] of mesh 2.
/// Outputs as in ttd_batch_d (either may be NULL, not both). Every index is checked first:
/// one out of range gives TTD_ERR_INDEX_OUT_OF_RANGE and nothing is written.
TTD_API ttd_status ttd_mesh_batch_d(const ttd_options *opt,
                                    const double *verts1, size_t nv1, const uint32_t *tris1, size_t nt1,
                                    const double *verts2, size_t nv2, const uint32_t *tris2, size_t nt2,
                                    size_t n, const uint32_t *pairs,
                                    double *distance, ttd_result_d *results);
/// Single-precision ttd_mesh_batch_d.
TTD_API ttd_status ttd_mesh_batch_f(const ttd_options *opt,
                                    const float *verts1, size_t nv1, const uint32_t *tris1, size_t nt1,
                                    const float *verts2, size_t nv2, const uint32_t *tris2, size_t nt2,
                                    size_t n, const uint32_t *pairs,
                                    float *distance, ttd_result_f *results);

/// A short English sentence for a status.
TTD_API const char *ttd_status_string(ttd_status status);
/// "exact", "penalty", "penalty-ref", "barrier", "certified"; NULL when out of range.
TTD_API const char *ttd_method_name(ttd_method method);
/// "auto", "scalar", "sse2", "avx2", "avx512", "neon", "portable"; NULL when out of range.
TTD_API const char *ttd_isa_name(ttd_isa isa);
/// Non-zero when isa is built into this library and supported by this CPU and OS.
TTD_API int ttd_isa_available(ttd_isa isa);
/// Non-zero when the kernels of isa are compiled into this library (scalar: always).
TTD_API int ttd_isa_built(ttd_isa isa);
/// Non-zero when this CPU and operating system can run isa, built or not (scalar: always).
TTD_API int ttd_isa_supported(ttd_isa isa);
/// The instruction set a call with these options would use (opt may be NULL); TTD_ISA_AUTO on error.
TTD_API ttd_isa ttd_isa_selected(const ttd_options *opt);
/// SIMD lanes of an instruction set for one precision (bytes_per_real 4 = float, 8 = double);
/// 1 for scalar; AUTO means the one ttd_isa_selected(NULL) gives; 0 for anything invalid.
TTD_API int ttd_isa_lanes(ttd_isa isa, int bytes_per_real);
/// Lanes that method uses on isa for one precision (bytes_per_real 4 or 8): the ISA's lane count
/// where the method has a lane kernel there, 1 where it runs the scalar code (the barrier
/// method everywhere); 0 when isa is not built or an argument is invalid.
TTD_API int ttd_method_lanes(ttd_method method, ttd_isa isa, int bytes_per_real);
/// "0.1.0".
TTD_API const char *ttd_version_string(void);

/** @} */

#ifdef __cplusplus
}
#endif
#endif /* TTD_TTD_H */
