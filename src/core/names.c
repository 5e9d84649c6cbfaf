/* SPDX-License-Identifier: MIT */
/* The names of statuses, methods and instruction sets (the public ttd_*_name functions). They
 * live in core/ because the dispatcher needs them too (TTD_ISA is read by name) and must not
 * call up into the API layer. */
#include "ttd/ttd.h"

const char *ttd_status_string(ttd_status status)
{
    switch (status) {
    case TTD_OK: return "ok";
    case TTD_WARN_NOT_CONVERGED: return "some pairs did not converge within max_iterations (flagged)";
    case TTD_ERR_NONFINITE_INPUT: return "some pairs had NaN or infinite coordinates (flagged, outputs NaN)";
    case TTD_ERR_NULL_POINTER: return "a required pointer was NULL";
    case TTD_ERR_EMPTY: return "n is 0: nothing to compute";
    case TTD_ERR_BAD_OPTIONS: return "options not from ttd_default_options(), or a field out of range";
    case TTD_ERR_ISA_UNAVAILABLE: return "the requested instruction set is not built in or not supported by this CPU";
    case TTD_ERR_INDEX_OUT_OF_RANGE: return "a mesh triangle or vertex index is out of range";
    case TTD_ERR_OUT_OF_MEMORY: return "out of memory for per-thread scratch";
    case TTD_ERR_TOO_LARGE: return "a count is too large for its arrays to exist";
    case TTD_ERR_NONFINITE_MESH: return "a mesh vertex coordinate is NaN or infinite";
    case TTD_ERR_BAD_POSE: return "a pose is not a finite rotation (R^T R = I within 1e-6, det R > 0) and translation";
    case TTD_ERR_PRECISION_MISMATCH: return "a mesh was built in the other precision";
    case TTD_ERR_COORDINATE_RANGE: return "a mesh coordinate (or one moved by a pose) beyond 2^60 in float or 2^508 in double";
    case TTD_ERR_MESH_NOT_CLOSED: return "a mesh is not closed (an edge not shared by exactly two oppositely oriented triangles), so it has no inside";
    }
    return "unknown status";
}

const char *ttd_method_name(ttd_method method)
{
    static const char *const names[TTD_METHOD_COUNT] = {
        [TTD_METHOD_EXACT] = "exact",
        [TTD_METHOD_PENALTY] = "penalty",
        [TTD_METHOD_PENALTY_REFERENCE] = "penalty-ref",
        [TTD_METHOD_BARRIER] = "barrier",
        [TTD_METHOD_CERTIFIED] = "certified",
    };
    return (int)method >= 0 && (int)method < TTD_METHOD_COUNT ? names[method] : NULL;
}

const char *ttd_isa_name(ttd_isa isa)
{
    static const char *const names[TTD_ISA_COUNT] = {
        [TTD_ISA_AUTO] = "auto",   [TTD_ISA_SCALAR] = "scalar", [TTD_ISA_SSE2] = "sse2",
        [TTD_ISA_AVX2] = "avx2",   [TTD_ISA_AVX512] = "avx512", [TTD_ISA_NEON] = "neon",
        [TTD_ISA_PORTABLE] = "portable",
    };
    return (int)isa >= 0 && (int)isa < TTD_ISA_COUNT ? names[isa] : NULL;
}

const char *ttd_orientation_string(ttd_orientation orientation)
{
    switch (orientation) {
    case TTD_ORIENTATION_OUTWARD: return "outward";
    case TTD_ORIENTATION_INWARD: return "inward";
    case TTD_ORIENTATION_INCONSISTENT: return "inconsistent";
    case TTD_ORIENTATION_OPEN: return "open";
    case TTD_ORIENTATION_FLAT: return "flat";
    }
    return "unknown";
}
