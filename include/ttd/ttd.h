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
    /// Some pairs had NaN/inf coordinates: flagged, outputs NaN; the rest computed. Not fatal,
    /// despite its name (below TTD_ERR_FIRST_FATAL, like the warning above): every finite pair
    /// has its outputs. Takes precedence over TTD_WARN_NOT_CONVERGED: check the per-pair flags
    /// for that too.
    TTD_ERR_NONFINITE_INPUT = 2,
    TTD_ERR_FIRST_FATAL = 16,     ///< marker: from here on nothing was computed (but see OUT_OF_MEMORY)
    TTD_ERR_NULL_POINTER = 16,    ///< a required pointer was NULL
    TTD_ERR_EMPTY = 17,           ///< n == 0: nothing to compute
    TTD_ERR_BAD_OPTIONS = 18,     ///< options not from ttd_default_options(), or a field out of range
    /// The instruction set forced by options.isa is not built in or not supported here (a
    /// TTD_ISA environment variable that cannot be used is ignored instead: ttd_isa_env_note).
    TTD_ERR_ISA_UNAVAILABLE = 19,
    TTD_ERR_INDEX_OUT_OF_RANGE = 20, ///< mesh entry: a triangle or vertex index is out of range; nothing written
    TTD_ERR_OUT_OF_MEMORY = 21,   ///< a per-thread scratch allocation failed; outputs partly written, indeterminate
    TTD_ERR_TOO_LARGE = 22,       ///< n (or a mesh size) so large that its arrays cannot exist in memory
    TTD_ERR_NONFINITE_MESH = 23,  ///< mesh build: a vertex coordinate is NaN or infinite; nothing built
    /// mesh queries: a pose is not a finite rotation and translation (see the mesh queries below)
    TTD_ERR_BAD_POSE = 24,
    TTD_ERR_PRECISION_MISMATCH = 25, ///< mesh queries: a mesh was built in the other precision
    /// mesh build or query: a vertex coordinate, or a vertex of b moved by a pose, beyond the
    /// meshes' range (magnitude 2^60 in float, 2^508 in double: see the mesh queries below)
    TTD_ERR_COORDINATE_RANGE = 26,
    /// mesh queries with ttd_options.solid: a mesh is not closed (some edge is not shared by
    /// exactly two triangles that run along it in opposite directions)
    TTD_ERR_MESH_NOT_CLOSED = 27
} ttd_status;

/// How the distance is computed.
typedef enum ttd_method {
    TTD_METHOD_EXACT = 0,             ///< 6 vertex-face, 9 edge-edge and 6 edge-face crossing tests; exact to rounding
    TTD_METHOD_PENALTY = 1,           ///< the paper's quasi-Newton penalty method, optimised and safeguarded
    /// The paper's MATLAB ttd1 step for step, for comparison: raw coordinates, so rho and tol are
    /// absolute (not scale-invariant; pairs far from unit size may stop early). The paper
    /// publishes neither: the defaults are ttd's. Off by up to ~1 on a few % of random pairs.
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
    /// the triangles touch or cross: distance 0. "Touch" includes a gap within 4 eps of the
    /// pair's extent (the coordinates' rounding cannot tell it from contact): p and q may then be
    /// that far apart, ~1e-15 of the pair's size in double, ~5e-7 in float
    TTD_PAIR_INTERSECTING = 1u << 3,
    /// iterative method: hit max_iterations, or (barrier) stalled on an ill-conditioned step before
    /// its last barrier weight; outputs are finite and points still lie on their triangles
    TTD_PAIR_NOT_CONVERGED = 1u << 4,
    TTD_PAIR_FALLBACK = 1u << 5       ///< certified mode: this pair failed the optimality check and was computed by the exact method
};

/// Everything known about one pair (double precision).
typedef struct ttd_result_d {
    double distance;   ///< |p - q|, or 0 with TTD_PAIR_INTERSECTING (see there)
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
    float distance;    ///< |p - q|, or 0 with TTD_PAIR_INTERSECTING (see there)
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
    /// Default TTD_ISA_AUTO: the best instruction set built and supported here; with AUTO the
    /// environment variable TTD_ISA (a name from ttd_isa_name() in any letter case; empty or
    /// "auto" = best) may force one. A TTD_ISA that is not a name, or names one that cannot run
    /// here, is ignored (the best one is used) rather than failing every call: ttd_isa_env_note()
    /// says so, and the ttd program warns. An isa set here explicitly that cannot run gives
    /// TTD_ERR_ISA_UNAVAILABLE.
    ttd_isa isa;
    int threads;        ///< worker threads for batches, >= 0; 0 (default) = all online cores; at most 256 used
    /// Penalty weight, in (0, 1e150] (default 1e6, ttd's choice: the paper publishes no rho or
    /// tol, only the 0.33 start and the 99-iteration cap). The barrier method lowers its weight to
    /// 1/rho^2. The float penalty and certified kernels use min(rho, 256) (a larger weight
    /// loses sliver pivots to rounding); the float ttd1 reference min(rho, 1e18).
    double rho;
    /// Newton step length below which an iteration stops, in [0, 1] (default 1e-12), measured
    /// on the pair translated and scaled to unit size (the paper's ttd1 reference: raw
    /// coordinates). The float penalty and certified kernels use max(tol, 1e-6).
    double tol;
    int max_iterations; ///< Newton iteration cap, 1..65535 (default 99, the paper's)
    /// Mesh distance and collision only: 0 (default) compares surfaces, so a mesh inside another
    /// is at the distance between their surfaces; 1 treats both meshes as solids (they must be
    /// closed, else TTD_ERR_MESH_NOT_CLOSED), so one inside the other collides at distance 0
    /// (TTD_MESH_CONTAINED). Contacts and closest partners are between surfaces either way.
    int solid;
    uint32_t internal_cookie; ///< set by ttd_default_options(); calls reject options without it
} ttd_options;

/// The defaults: exact method, best instruction set, all cores, ttd's penalty parameters.
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

/** @} */

/** @defgroup mesh Mesh queries
 * A ttd_mesh is a triangle mesh with a bounding-volume hierarchy over its triangles (oriented
 * boxes, 8 children per node). Its triangles are fixed when it is built; its vertices may move
 * (ttd_mesh_set_vertices_d, a deforming mesh), which refits the hierarchy in place. Between
 * such updates a mesh is read-only and may be queried from many threads at once; an update must
 * not run while anything else (a query, a scene query over a body of it, another update) uses
 * that mesh. Every query but the self queries (one mesh against itself, at the end of this
 * group) takes two meshes, a and b, and k >= 1 poses of b in the frame of
 * a. A pose is 12 reals, the 3x4 matrix [R | t] row by row (r00 r01 r02 t0 r10 r11 r12 t1 r20
 * r21 r22 t2), mapping b's coordinates into a's frame: x_a = R x_b + t, computed per coordinate
 * as ((r0*x + r1*y) + r2*z) + t, so that a brute force can reproduce it to the bit. R must be a
 * rotation: finite, with every entry of R^T R - I within 1e-6 and det R > 0; otherwise the call
 * returns TTD_ERR_BAD_POSE before computing anything. Results are in a's frame.
 *
 * Coordinates must stay within 2^60 (about 1.2e18) in magnitude in float and 2^508 (about
 * 8e152) in double: a's vertices, b's, and b's moved by every pose (checked on the sphere
 * around b's bounding-box centre that holds its vertices); beyond that the tree's squared bounds
 * could overflow, so the build or the query returns TTD_ERR_COORDINATE_RANGE instead. The pair functions above have no such limit.
 *
 * The queries compare surfaces, as FCL's mesh queries do: a mesh inside another, their surfaces
 * apart, is at the distance between the surfaces and does not collide. For closed meshes,
 * ttd_options.solid makes distance and collision treat them as solids.
 *
 * Every query is exact to the pair kernel's accuracy: it returns what the exact method over all
 * triangle pairs would (the tree only skips pairs it proves cannot matter, with a margin for the
 * rounding of its own bounds). Results do not depend on the thread count or the instruction
 * set. A query in double needs meshes built with ttd_mesh_create_d, in float with
 * ttd_mesh_create_f (TTD_ERR_PRECISION_MISMATCH otherwise). opt may be NULL; its method must be
 * TTD_METHOD_EXACT (the default) and its isa and threads apply; k poses are spread over the
 * threads.
 * @{ */

/// A triangle mesh and its hierarchy (opaque).
typedef struct ttd_mesh ttd_mesh;

/// Builds a mesh from nv vertices (3 coordinates each) and nt triangles (3 vertex indices each,
/// 0-based). The arrays are copied. Degenerate triangles, repeated vertices and non-manifold
/// meshes are fine. nv or nt of 0: TTD_ERR_EMPTY; an index >= nv: TTD_ERR_INDEX_OUT_OF_RANGE; a
/// NaN/inf coordinate: TTD_ERR_NONFINITE_MESH; one beyond the range above:
/// TTD_ERR_COORDINATE_RANGE; *out is NULL on any error. opt's threads apply.
TTD_API ttd_status ttd_mesh_create_d(const ttd_options *opt, const double *vertices, size_t nv,
                                     const uint32_t *triangles, size_t nt, ttd_mesh **out);
/// ttd_mesh_create_d with float vertices; the mesh is then queried in float.
TTD_API ttd_status ttd_mesh_create_f(const ttd_options *opt, const float *vertices, size_t nv,
                                     const uint32_t *triangles, size_t nt, ttd_mesh **out);
/// Frees a mesh (NULL is fine).
TTD_API void ttd_mesh_destroy(ttd_mesh *mesh);
/// Triangles of a mesh (0 for NULL).
TTD_API size_t ttd_mesh_triangle_count(const ttd_mesh *mesh);
/// Vertices of a mesh (0 for NULL).
TTD_API size_t ttd_mesh_vertex_count(const ttd_mesh *mesh);
/// Nodes of its hierarchy (0 for NULL).
TTD_API size_t ttd_mesh_node_count(const ttd_mesh *mesh);

/// New positions for a mesh's vertices, its triangles the same (a deforming mesh): vertices
/// holds 3 reals for each of its ttd_mesh_vertex_count vertices, copied, with the checks of
/// ttd_mesh_create_d (TTD_ERR_NONFINITE_MESH, TTD_ERR_COORDINATE_RANGE;
/// TTD_ERR_PRECISION_MISMATCH for a mesh built by ttd_mesh_create_f). The hierarchy keeps its
/// shape and every box is fitted again around the moved triangles (a refit, cheaper than a
/// build); when refitting has degraded it past a measure (the summed surface area of its
/// subtrees' boxes over that of its triangles' boxes, grown past twice what it was at the last
/// build: docs/mesh-queries.md, section 2b), it is rebuilt. Every query then answers for the new positions, exactly as for a mesh
/// built from them. The mesh stays the same object: every scene body of it moves with it (the
/// scene updates their world boxes on its next call). Must not run while the mesh is used by
/// anything else (see above). On an error (TTD_ERR_OUT_OF_MEMORY included) the mesh is as it
/// was. opt's threads apply. Memory: the first refit of a hierarchy keeps its leaves' vertex
/// indices in tree order with the mesh (96 bytes a node, about 17 bytes a triangle) for the next
/// refits, until a rebuild or ttd_mesh_destroy; the mesh's first refit also keeps the refit's
/// scratch (128 bytes a node) until ttd_mesh_destroy (through rebuilds).
TTD_API ttd_status ttd_mesh_set_vertices_d(const ttd_options *opt, ttd_mesh *mesh, const double *vertices);
/// ttd_mesh_set_vertices_d for a mesh built by ttd_mesh_create_f.
TTD_API ttd_status ttd_mesh_set_vertices_f(const ttd_options *opt, ttd_mesh *mesh, const float *vertices);

/// What vertex updates have done to a mesh's hierarchy.
typedef struct ttd_mesh_refit_info {
    uint64_t generation;  ///< ttd_mesh_set_vertices_* calls that changed the mesh (0 when built)
    uint64_t rebuilds;    ///< of those, the ones that rebuilt the hierarchy
    double quality;       ///< the hierarchy's measure now (docs/mesh-queries.md, section 2b)
    double quality_built; ///< the measure when it was last built; a refit past twice it rebuilds
} ttd_mesh_refit_info;

/// Fills *info for mesh (TTD_ERR_NULL_POINTER for NULL).
TTD_API ttd_status ttd_mesh_get_refit_info(const ttd_mesh *mesh, ttd_mesh_refit_info *info);

/// Welding: vertices within `tolerance` of each other become one vertex, for meshes whose
/// triangles each carry their own copies of shared corners with last-bit differences (STL and
/// many CAD exports), which are otherwise open (docs/mesh-files.md, "Welding").
///
/// - Within: Euclidean, |u - v| <= tolerance, evaluated in double as
///   (dx/t)^2 + (dy/t)^2 + (dz/t)^2 <= 1 with every |d| <= t first; tolerance 0 merges
///   vertices equal by value only (so -0 and +0 are one vertex).
/// - Chained: the classes are the connected pieces of "within" (u near v and v near w puts u,
///   v and w in one vertex, even when u and w are farther apart than tolerance). The classes
///   do not depend on the order of the vertices.
/// - Each class's vertex is its lexicographically smallest member by value (x, then y, then z),
///   coordinates copied exactly, a zero written as +0: the output's coordinates do not depend
///   on the order either. Classes are numbered by their smallest old index (the input's order
///   kept: with nothing to merge, the vertices come out as they went in, -0 made +0).
/// - Triangles keep their order and corner order, renumbered; one with two corners in one
///   class (collapsed to an edge or a point) is dropped: *nt_out = nt - dropped. Vertices used
///   by no triangle are kept.
///
/// verts_out has room for 3 nv reals and tris_out for 3 nt indices; each may be the same array
/// as its input (welding in place). vertex_map, when not NULL, receives nv entries: each old
/// vertex's new index. nt may be 0 (tris and tris_out may then be NULL). Statuses:
/// TTD_ERR_NULL_POINTER, TTD_ERR_EMPTY (nv = 0), TTD_ERR_BAD_OPTIONS (tolerance negative, NaN
/// or infinite), TTD_ERR_NONFINITE_MESH, TTD_ERR_INDEX_OUT_OF_RANGE (an index >= nv),
/// TTD_ERR_TOO_LARGE (nv >= 2^32), TTD_ERR_OUT_OF_MEMORY; nothing is written on an error. Time:
/// a sort, then a grid of cubes 0.577 tolerance wide, each cube one class without a test and a
/// pair of cubes already joined skipped, so a tolerance larger than the mesh costs about the sort.
TTD_API ttd_status ttd_mesh_weld_d(const double *verts, size_t nv, const uint32_t *tris, size_t nt,
                                   double tolerance, double *verts_out, size_t *nv_out, uint32_t *tris_out,
                                   size_t *nt_out, uint32_t *vertex_map);
/// ttd_mesh_weld_d on float vertices: the same classes, decided on the floats' exact values.
TTD_API ttd_status ttd_mesh_weld_f(const float *verts, size_t nv, const uint32_t *tris, size_t nt,
                                   float tolerance, float *verts_out, size_t *nv_out, uint32_t *tris_out,
                                   size_t *nt_out, uint32_t *vertex_map);
/// How a mesh's triangles are oriented (ttd_mesh_orientation). Closed: every directed edge (u, v)
/// of a triangle appears once and so does (v, u), by vertex index (what ttd_options.solid and
/// ttd_scene_set_solid require).
typedef enum ttd_orientation {
    TTD_ORIENTATION_OUTWARD = 0,      ///< closed, enclosing a positive volume: counter-clockwise seen from outside
    TTD_ORIENTATION_INWARD = 1,       ///< closed, enclosing a negative volume: every face wound the other way
    TTD_ORIENTATION_INCONSISTENT = 2, ///< every edge on exactly two triangles, but some edge run the same way by both
    TTD_ORIENTATION_OPEN = 3,         ///< some edge on one triangle (a boundary) or on more than two, or a
                                      ///< triangle with a repeated vertex index: no inside to orient
    TTD_ORIENTATION_FLAT = 4          ///< closed, but its volume is zero within rounding (e.g. a doubled sheet)
} ttd_orientation;

/// The orientation of mesh into *orientation: closedness by vertex indices (no welding), then the
/// sign of the enclosed volume (divergence theorem, compensated sum, with a bound on its rounding).
/// Computed on each call (O(n log n)): a vertex update can turn a mesh inside out. The inside of a
/// closed mesh does not depend on it (the point queries' rule, |winding number| >= 1/2, gives an
/// inward mesh the same inside as the outward one). TTD_ERR_NULL_POINTER, TTD_ERR_OUT_OF_MEMORY.
TTD_API ttd_status ttd_mesh_orientation(const ttd_mesh *mesh, ttd_orientation *orientation);
/// The orientation's name: "outward", "inward", "inconsistent", "open", "flat" ("unknown" else).
TTD_API const char *ttd_orientation_string(ttd_orientation orientation);

/// The one inside rule of every query that decides a side (point queries, the solid modes of the
/// mesh and scene queries): a point is inside when the magnitude of the mesh's winding number
/// about it is at least 1/2. Returns 1 or 0 (0 for NaN). For a closed mesh, whichever way it is
/// wound as a whole, that is its solid; a count of 2 (self-overlapping parts, overlapping shells)
/// is inside, unlike an odd-even ray count; a count of 0 (a cavity, shells of opposite windings
/// cancelling) is outside. docs/points.md, section 5.
TTD_API int ttd_winding_inside(double winding);
/// A closed mesh's mass properties as a solid of uniform density (docs/mass-properties.md).
typedef struct ttd_mass_properties {
    double mass;       ///< density * |volume|
    double volume;     ///< the signed volume: negative for a mesh wound inward (its orientation)
    double area;       ///< the surface's area
    double center[3];  ///< the centre of mass, in the mesh's coordinates
    double inertia[9]; ///< the inertia tensor about the centre (row-major, symmetric, kg m^2 if mass is kg)
} ttd_mass_properties;

/// The mass properties of a closed mesh (built by ttd_mesh_create_d; _f: by ttd_mesh_create_f)
/// of uniform density (finite, > 0) into *out, by the divergence theorem over its triangles
/// with compensated sums, in double (a float mesh's vertices are exact in double): each
/// quantity to a few roundings of its terms. Closed: every edge, between vertices' places (equal
/// coordinates are one place), runs once each way (a mesh wound inward is closed, its volume
/// negative; one with faces of both windings is not). Errors: NULL pointers, density not
/// finite or <= 0 (TTD_ERR_BAD_OPTIONS), the other precision's mesh, not closed
/// (TTD_ERR_MESH_NOT_CLOSED), out of memory; *out untouched. A closed mesh enclosing no
/// volume gives volume and mass 0 and a NaN centre and inertia.
TTD_API ttd_status ttd_mesh_mass_properties_d(const ttd_mesh *mesh, double density, ttd_mass_properties *out);
TTD_API ttd_status ttd_mesh_mass_properties_f(const ttd_mesh *mesh, double density, ttd_mass_properties *out);

/// Checks k poses of b in a's frame as every query does, computing nothing: TTD_OK, or the
/// status a query would return for them (TTD_ERR_BAD_POSE, TTD_ERR_COORDINATE_RANGE), with
/// *bad the index of the first pose refused. *bad is k when no pose is at fault (TTD_OK, or
/// TTD_ERR_NULL_POINTER, TTD_ERR_EMPTY for k = 0, TTD_ERR_PRECISION_MISMATCH for a mesh of the
/// other precision). For telling a caller which of many poses a query refused.
TTD_API ttd_status ttd_mesh_check_poses_d(const ttd_mesh *a, const ttd_mesh *b, size_t k, const double *poses,
                                          size_t *bad);
/// ttd_mesh_check_poses_d for float poses (meshes from ttd_mesh_create_f).
TTD_API ttd_status ttd_mesh_check_poses_f(const ttd_mesh *a, const ttd_mesh *b, size_t k, const float *poses,
                                          size_t *bad);

/// Flags of a mesh distance result.
enum {
    TTD_MESH_INTERSECTING = 1u << 0, ///< the meshes touch or cross: distance 0, p == q on both
    TTD_MESH_ABOVE_BOUND = 1u << 1,  ///< no pair within upper_bound: distance is +inf, no points or triangles
    /// with ttd_options.solid: one mesh lies inside the other without their surfaces meeting
    /// (also TTD_MESH_INTERSECTING, distance 0): p = q is the first vertex of the inner mesh's
    /// triangle 0, tri_a or tri_b is that triangle and the other is UINT32_MAX
    TTD_MESH_CONTAINED = 1u << 2
};

/// The minimum distance between two meshes under one pose (double precision).
typedef struct ttd_mesh_result_d {
    double distance;      ///< the minimum over all triangle pairs; 0 when they intersect
    double p[3];          ///< closest point on a, in a's frame
    double q[3];          ///< closest point on b, in a's frame; equal to p when the distance is 0
    uint32_t tri_a;       ///< the triangle of a that realises it (UINT32_MAX with TTD_MESH_ABOVE_BOUND)
    uint32_t tri_b;       ///< the triangle of b
    uint8_t feature_a;    ///< vertex bits of tri_a that p lies on, as ttd_result_d.feature_p
    uint8_t feature_b;    ///< vertex bits of tri_b that q lies on
    uint16_t flags;       ///< TTD_MESH_* bits
    uint32_t node_tests;  ///< box-against-node tests made (each against up to 8 boxes)
    uint64_t pair_tests;  ///< triangle pairs given to the exact method
} ttd_mesh_result_d;

/// ttd_mesh_result_d in single precision.
typedef struct ttd_mesh_result_f {
    float distance;
    float p[3];
    float q[3];
    uint32_t tri_a;
    uint32_t tri_b;
    uint8_t feature_a;
    uint8_t feature_b;
    uint16_t flags;
    uint32_t node_tests;
    uint64_t pair_tests;
} ttd_mesh_result_f;

/// Minimum distance between a and b under each of k poses (12k reals): out[i] for pose i.
/// upper_bound >= 0 (INFINITY for none): a pose whose distance exceeds it may stop early and
/// reports +inf with TTD_MESH_ABOVE_BOUND. rel_tol >= 0 (0 for exact): the reported pair may be
/// up to a factor 1 + rel_tol farther than the minimum (fewer pairs tested). NaN or negative
/// upper_bound, or rel_tol NaN, negative or infinite: TTD_ERR_BAD_OPTIONS.
TTD_API ttd_status ttd_mesh_distance_d(const ttd_options *opt, const ttd_mesh *a, const ttd_mesh *b, size_t k,
                                       const double *poses, double upper_bound, double rel_tol,
                                       ttd_mesh_result_d *out);
/// ttd_mesh_distance_d in single precision (meshes from ttd_mesh_create_f).
TTD_API ttd_status ttd_mesh_distance_f(const ttd_options *opt, const ttd_mesh *a, const ttd_mesh *b, size_t k,
                                       const float *poses, float upper_bound, float rel_tol,
                                       ttd_mesh_result_f *out);

/// One triangle pair within the margin: its distance and closest points (in a's frame).
typedef struct ttd_contact_d {
    uint32_t tri_a, tri_b;
    double distance;
    double p[3], q[3];
} ttd_contact_d;

/// ttd_contact_d in single precision.
typedef struct ttd_contact_f {
    uint32_t tri_a, tri_b;
    float distance;
    float p[3], q[3];
} ttd_contact_f;

/// The pairs a contact query found, in memory the library owns: start from {0} (or a set from an
/// earlier call, whose memory is reused), free with ttd_contacts_free_d. Pairs of pose i are
/// pairs[pose_start[i] .. pose_start[i + 1]); within a pose they come in an order that depends
/// only on the meshes and the pose (not on threads or instruction set).
typedef struct ttd_contacts_d {
    ttd_contact_d *pairs;
    size_t count;         ///< pairs in all
    size_t *pose_start;   ///< k + 1 offsets
    size_t poses;         ///< k of the last call
    size_t capacity;      ///< allocated pairs (library's business)
    size_t pose_capacity; ///< allocated offsets (library's business)
} ttd_contacts_d;

/// ttd_contacts_d in single precision.
typedef struct ttd_contacts_f {
    ttd_contact_f *pairs;
    size_t count;
    size_t *pose_start;
    size_t poses;
    size_t capacity;
    size_t pose_capacity;
} ttd_contacts_f;

/// Every triangle pair of a and b at distance <= margin (>= 0, finite) under each of k poses,
/// into out (see ttd_contacts_d). On an error out->count is 0.
TTD_API ttd_status ttd_mesh_contacts_d(const ttd_options *opt, const ttd_mesh *a, const ttd_mesh *b, size_t k,
                                       const double *poses, double margin, ttd_contacts_d *out);
/// ttd_mesh_contacts_d in single precision.
TTD_API ttd_status ttd_mesh_contacts_f(const ttd_options *opt, const ttd_mesh *a, const ttd_mesh *b, size_t k,
                                       const float *poses, float margin, ttd_contacts_f *out);
/// The number of pairs ttd_mesh_contacts_d finds under each of k poses, into counts[0 .. k),
/// without holding the pairs: the same walk, whose pairs are counted and dropped, so its memory
/// does not grow with the count. Same checks and statuses as ttd_mesh_contacts_d.
TTD_API ttd_status ttd_mesh_contacts_count_d(const ttd_options *opt, const ttd_mesh *a, const ttd_mesh *b, size_t k,
                                             const double *poses, double margin, size_t *counts);
/// ttd_mesh_contacts_count_d in single precision.
TTD_API ttd_status ttd_mesh_contacts_count_f(const ttd_options *opt, const ttd_mesh *a, const ttd_mesh *b, size_t k,
                                             const float *poses, float margin, size_t *counts);
/// Frees what a contact query allocated and zeroes the set (NULL is fine).
TTD_API void ttd_contacts_free_d(ttd_contacts_d *contacts);
TTD_API void ttd_contacts_free_f(ttd_contacts_f *contacts);

/// For one triangle, its closest partner within the margin (Hauser's per-triangle reduction).
typedef struct ttd_closest_d {
    uint32_t partner;    ///< triangle of the other mesh, UINT32_MAX when none is within the margin
    double distance;     ///< +inf when none
    double p[3], q[3];   ///< p on this triangle, q on the partner, in a's frame
} ttd_closest_d;

/// ttd_closest_d in single precision.
typedef struct ttd_closest_f {
    uint32_t partner;
    float distance;
    float p[3], q[3];
} ttd_closest_f;

/// For every triangle of a and of b, its closest partner in the other mesh within margin under
/// each of k poses: for_a holds k * (triangles of a) records (pose-major), for_b k * (triangles
/// of b); either may be NULL, not both. Ties go to the smaller partner index.
TTD_API ttd_status ttd_mesh_closest_d(const ttd_options *opt, const ttd_mesh *a, const ttd_mesh *b, size_t k,
                                      const double *poses, double margin, ttd_closest_d *for_a,
                                      ttd_closest_d *for_b);
/// ttd_mesh_closest_d in single precision.
TTD_API ttd_status ttd_mesh_closest_f(const ttd_options *opt, const ttd_mesh *a, const ttd_mesh *b, size_t k,
                                      const float *poses, float margin, ttd_closest_f *for_a,
                                      ttd_closest_f *for_b);

/// Whether two meshes come within a margin of each other.
typedef struct ttd_collision {
    uint32_t hit;         ///< 1 when some pair is at distance <= margin (0 = touching or crossing)
    uint32_t tri_a;       ///< the first such pair found (UINT32_MAX when none; with
                          ///< ttd_options.solid and one mesh inside the other: the inner
                          ///< mesh's triangle 0, and UINT32_MAX for the outer)
    uint32_t tri_b;
    uint32_t node_tests;  ///< as in ttd_mesh_result_d
    uint64_t pair_tests;
} ttd_collision;

/// Collision of a and b with a margin >= 0 and finite (0: do they touch or cross?) under each of
/// k poses; each pose stops at its first witness pair.
TTD_API ttd_status ttd_mesh_collide_d(const ttd_options *opt, const ttd_mesh *a, const ttd_mesh *b, size_t k,
                                      const double *poses, double margin, ttd_collision *out);
/// ttd_mesh_collide_d in single precision.
TTD_API ttd_status ttd_mesh_collide_f(const ttd_options *opt, const ttd_mesh *a, const ttd_mesh *b, size_t k,
                                      const float *poses, float margin, ttd_collision *out);

/// Flags of the self queries (ttd_mesh_self_contacts_d, ttd_mesh_self_collide_d).
enum {
    /// Also the pairs that share exactly one vertex, by how near they come away from it (see
    /// ttd_mesh_self_contacts_d): what a cloth solver needs where a sheet folds at a vertex.
    TTD_SELF_SHARED_VERTEX = 1u << 0
};

/// Self-contacts: every pair of triangles (i, j), i < j, of one mesh at distance <= margin
/// (>= 0, finite) that share no vertex (by index: triangles that share one are neighbours in the
/// mesh, touching by construction; duplicate vertices at one position with different indices do
/// not count as shared), into out as one pose: tri_a = i, tri_b = j, p on i and q on j, in the
/// mesh's frame (out->poses = 1, pose_start = {0, count}). Each pair is computed as the exact
/// method computes (T_i, T_j), i first.
/// With flags TTD_SELF_SHARED_VERTEX, also the pairs that share exactly one vertex v, when each
/// triangle has a vertex other than v: their distance is the smaller of d(E_i, T_j) and d(T_i,
/// E_j), E_i being triangle i's edge opposite v (its vertices other than v, by index, in their
/// order: a segment (r0, r1, r1), or a point (r0, r0, r0) when two of its indices are v; the
/// exact method on it as a degenerate triangle), with that pair's points (E_i's first when the
/// two are equal); so a pair is reported when the triangles come within margin away from v, as
/// when a sheet folds onto itself at a vertex. Pairs that share two or three vertices (an edge,
/// or the same vertices) are never reported; nor is a triangle with itself.
/// Exact (the brute force over all pairs i < j by these rules, bit for bit) and deterministic:
/// the set and its order depend on the mesh (its vertices and, through its tree, the history of
/// its vertex updates) alone, not on threads or instruction set. Unknown flag bits, a margin
/// out of range: TTD_ERR_BAD_OPTIONS. On an error out->count is 0.
/// Memory: the query's grid arrays (about 180 bytes a triangle) stay with the mesh for the next
/// self query until ttd_mesh_destroy; queries at once on one mesh are safe (one takes them, the
/// others make their own).
TTD_API ttd_status ttd_mesh_self_contacts_d(const ttd_options *opt, const ttd_mesh *mesh, double margin, unsigned flags,
                                            ttd_contacts_d *out);
/// ttd_mesh_self_contacts_d in single precision (a mesh from ttd_mesh_create_f).
TTD_API ttd_status ttd_mesh_self_contacts_f(const ttd_options *opt, const ttd_mesh *mesh, float margin, unsigned flags,
                                            ttd_contacts_f *out);
/// The number of pairs ttd_mesh_self_contacts_d finds, into *count, without holding them (as
/// ttd_mesh_contacts_count_d). Same checks and statuses as ttd_mesh_self_contacts_d.
TTD_API ttd_status ttd_mesh_self_contacts_count_d(const ttd_options *opt, const ttd_mesh *mesh, double margin,
                                                  unsigned flags, size_t *count);
/// ttd_mesh_self_contacts_count_d in single precision.
TTD_API ttd_status ttd_mesh_self_contacts_count_f(const ttd_options *opt, const ttd_mesh *mesh, float margin,
                                                  unsigned flags, size_t *count);
/// Whether a mesh comes within margin (>= 0; 0: does it intersect itself?) of itself, by the
/// pairs and rules of ttd_mesh_self_contacts_d: stops at the first such pair, out->tri_a <
/// out->tri_b its triangles (UINT32_MAX when none); the witness depends on the mesh alone.
TTD_API ttd_status ttd_mesh_self_collide_d(const ttd_options *opt, const ttd_mesh *mesh, double margin, unsigned flags,
                                           ttd_collision *out);
/// ttd_mesh_self_collide_d in single precision.
TTD_API ttd_status ttd_mesh_self_collide_f(const ttd_options *opt, const ttd_mesh *mesh, float margin, unsigned flags,
                                           ttd_collision *out);

/** @} */

/** @defgroup points Point queries
 * Points against a mesh: the closest point, the generalized winding number, inside or not, the
 * signed distance, and signed distances on a regular grid (docs/points.md). n points are 3n reals
 * (point i at 3i). A query in double takes a mesh from ttd_mesh_create_d, in float one from
 * ttd_mesh_create_f (TTD_ERR_PRECISION_MISMATCH otherwise); opt may be NULL, its method must be
 * TTD_METHOD_EXACT and its isa and threads apply (points are spread over the threads). Results do
 * not depend on the thread count or the instruction set.
 *
 * pose is NULL (the points are in the mesh's frame) or the mesh's pose in the points' frame: 12
 * reals [R | t] as for the mesh queries (x_points = R x_mesh + t), checked the same way
 * (TTD_ERR_BAD_POSE, TTD_ERR_COORDINATE_RANGE). Each point p is taken into the mesh's frame,
 * x_c = ((r0c (p0 - t0) + r1c (p1 - t1)) + r2c (p2 - t2)) in the query's precision, answered
 * there, and its closest point moved back by ((rc0 y0 + rc1 y1) + rc2 y2) + tc.
 *
 * The closest point is exact: its distance is the minimum over all triangles of
 * ttd_point_triangle_d/f (the exact point-triangle distance), bit for bit, ties to the smallest
 * triangle index, and its point, weights and feature are that function's for that triangle.
 * Points (in the mesh's frame) must lie within the meshes' coordinate range (2^508 in double, 2^60
 * in float; TTD_ERR_COORDINATE_RANGE otherwise, nothing computed). A point with a NaN or infinite
 * coordinate gets NaN outputs and TTD_POINT_NONFINITE while the others are computed; the call then
 * returns TTD_ERR_NONFINITE_INPUT.
 *
 * Inside means a generalized winding number w (Jacobson et al. 2013) with |w| >= 1/2: the one
 * rule of ttd_winding_inside, for every query. For a closed mesh (every directed edge once, and its
 * reverse once) w is counted exactly, by a ray's crossings with exact predicates: an integer, +1
 * inside a mesh wound outwards and -1 inside one wound inwards (the same inside either way), exact
 * for every point off the surface (short of products that underflow, answered as for an open
 * mesh). An open or inconsistently oriented mesh gets w hierarchically (Barill et al. 2018) with
 * a rigorous error bound, tightened until it settles the side of |w| = 1/2 where it can
 * (TTD_POINT_SIGN_UNPROVEN where rounding leaves it open); the winding number every entry reports
 * is that tightened one, so that its |w| >= 1/2 is the side contains and signed distances give.
 * docs/points.md, section 5.
 * @{ */

/// Flags of a point result.
enum {
    TTD_POINT_NONFINITE = 1u << 0,   ///< the point had a NaN or infinite coordinate: outputs NaN
    TTD_POINT_ABOVE_BOUND = 1u << 1, ///< no triangle within upper_bound: distance +inf, no point, triangle UINT32_MAX
    TTD_POINT_INSIDE = 1u << 2,      ///< signed distance: the point is inside (|winding number| >= 1/2)
    TTD_POINT_DEGENERATE = 1u << 3,  ///< the closest triangle has no area (a segment or a point)
    TTD_POINT_SIGN_UNPROVEN = 1u << 4 ///< signed distance: the side is not proven (an open mesh's |winding
                                      ///< number| within rounding of 1/2; never for a closed mesh)
};

/// The closest point of a mesh to one query point (double precision).
typedef struct ttd_point_result_d {
    double distance;     ///< the exact distance (+inf above the bound, NaN for a NaN point)
    double point[3];     ///< the closest point on the mesh, in the points' frame
    double bary[3];      ///< weights of the triangle's vertices that give it (non-negative, sum 1)
    uint32_t triangle;   ///< the triangle it lies on (UINT32_MAX with TTD_POINT_ABOVE_BOUND or NONFINITE)
    uint8_t feature;     ///< bit i when vertex i has a non-zero weight: 1 bit a vertex, 2 an edge, 3 the face
    uint8_t flags;       ///< TTD_POINT_* bits
    uint16_t reserved;
    uint32_t node_tests; ///< nodes of the hierarchy tested (each against up to 8 boxes); with
                         ///< triangle_tests, depends on the batch the point came in (the walk is
                         ///< seeded by its neighbour's answer), never on the threads
    uint32_t triangle_tests; ///< triangles measured exactly
} ttd_point_result_d;

/// ttd_point_result_d in single precision.
typedef struct ttd_point_result_f {
    float distance;
    float point[3];
    float bary[3];
    uint32_t triangle;
    uint8_t feature;
    uint8_t flags;
    uint16_t reserved;
    uint32_t node_tests;
    uint32_t triangle_tests;
} ttd_point_result_f;

/// The exact distance from point p to triangle tri (9 reals: A, B, C), the reference of the
/// point queries, into out (triangle 0; no node or triangle counts). Coordinates within 2^508
/// (float: 2^60): TTD_ERR_COORDINATE_RANGE beyond; NaN or infinite ones: NaN outputs,
/// TTD_POINT_NONFINITE and TTD_ERR_NONFINITE_INPUT.
TTD_API ttd_status ttd_point_triangle_d(const double p[3], const double tri[9], ttd_point_result_d *out);
TTD_API ttd_status ttd_point_triangle_f(const float p[3], const float tri[9], ttd_point_result_f *out);

/// For each of n points, the closest point of mesh (see above) into results[i]. upper_bound >= 0
/// (INFINITY for none): a point farther than it from every triangle gets +inf and
/// TTD_POINT_ABOVE_BOUND; NaN or negative: TTD_ERR_BAD_OPTIONS.
TTD_API ttd_status ttd_points_closest_d(const ttd_options *opt, const ttd_mesh *mesh, size_t n, const double *points,
                                        const double *pose, double upper_bound, ttd_point_result_d *results);
TTD_API ttd_status ttd_points_closest_f(const ttd_options *opt, const ttd_mesh *mesh, size_t n, const float *points,
                                        const float *pose, float upper_bound, ttd_point_result_f *results);

/// The generalized winding number of mesh about each of n points into winding[i]: for a closed
/// mesh the exact integer (1 inside one oriented outwards, -1 inside one oriented inwards, 0
/// outside), fractions for open meshes within the hierarchical walk's bound, tightened until it
/// settles the side of |w| = 1/2 (NaN for a NaN point). The float entry rounds each to float on
/// its side of the inside rule.
TTD_API ttd_status ttd_points_winding_number_d(const ttd_options *opt, const ttd_mesh *mesh, size_t n,
                                               const double *points, const double *pose, double *winding);
TTD_API ttd_status ttd_points_winding_number_f(const ttd_options *opt, const ttd_mesh *mesh, size_t n,
                                               const float *points, const float *pose, float *winding);

/// inside[i] = 1 when point i is inside mesh (ttd_winding_inside: |winding number| >= 1/2), else 0
/// (0 for a NaN point).
TTD_API ttd_status ttd_points_contains_d(const ttd_options *opt, const ttd_mesh *mesh, size_t n, const double *points,
                                         const double *pose, uint8_t *inside);
TTD_API ttd_status ttd_points_contains_f(const ttd_options *opt, const ttd_mesh *mesh, size_t n, const float *points,
                                         const float *pose, uint8_t *inside);

/// Signed distances: the closest point's distance, negative inside (|winding number| >= 1/2), into
/// distance[i]; when results is not NULL, the closest points too, with TTD_POINT_INSIDE set for
/// points inside. Either output may be NULL, not both. Beyond upper_bound: +-inf.
TTD_API ttd_status ttd_points_signed_distance_d(const ttd_options *opt, const ttd_mesh *mesh, size_t n,
                                                const double *points, const double *pose, double upper_bound,
                                                double *distance, ttd_point_result_d *results);
TTD_API ttd_status ttd_points_signed_distance_f(const ttd_options *opt, const ttd_mesh *mesh, size_t n,
                                                const float *points, const float *pose, float upper_bound,
                                                float *distance, ttd_point_result_f *results);

/// Signed distances on a regular grid of dims[0] x dims[1] x dims[2] points, point (i, j, k) at
/// origin + (i step[0], j step[1], k step[2]) (each coordinate computed as origin[c] + i step[c]
/// in the query's precision), into out[(i dims[1] + j) dims[2] + k] (the C order of an (nx, ny,
/// nz) array), in the mesh's frame. Any dimension 0: TTD_ERR_EMPTY; non-finite origin or step, or
/// a step that is not > 0 on some axis (also one whose dimension is 1): TTD_ERR_BAD_OPTIONS.
TTD_API ttd_status ttd_sdf_grid_d(const ttd_options *opt, const ttd_mesh *mesh, const double origin[3],
                                  const double step[3], const size_t dims[3], double *out);
TTD_API ttd_status ttd_sdf_grid_f(const ttd_options *opt, const ttd_mesh *mesh, const float origin[3],
                                  const float step[3], const size_t dims[3], float *out);

/** @} */

/** @defgroup scene Scenes of many bodies
 * A ttd_scene holds bodies, each a ttd_mesh (one mesh may serve any number of bodies) at a world
 * pose [R | t] (x_world = R x_mesh + t, 12 reals row by row as for the mesh queries, with the
 * same checks: R a rotation within 1e-6, the moved mesh within the coordinate range). A scene has
 * one precision, fixed at creation: ttd_scene_create_d takes meshes from ttd_mesh_create_d and
 * double poses, ttd_scene_create_f float ones. Bodies get ids 0, 1, 2, ... in the order they are
 * added; a removed body's id is not given again.
 *
 * A body pair (i, j), i < j, is eligible when both bodies are present, (group_i & mask_j) and
 * (group_j & mask_i) are non-zero (each body starts in group 1 with mask all ones), and the pair
 * is not excluded. Every query is over the eligible pairs, and exact: it equals the exact method
 * over all triangle pairs of all eligible body pairs in the world frame (each triangle's vertices
 * moved by its body's pose, ((r0 x + r1 y) + r2 z) + t per coordinate, in the scene's precision;
 * body i's triangle first), bit for bit. Results are in the world frame, sorted by (i, j) and
 * then by triangles (a manifold's points: in the reduction's order within their body pair), and
 * do not depend on the thread count or the instruction set.
 *
 * A scene keeps the broad phase's state between calls (the bodies' world boxes and their sorted
 * order, updated as poses change): it must not be changed or queried from two threads at once.
 * The meshes must outlive the scene.
 *
 * Deforming bodies: a body's mesh may have its vertices moved (ttd_mesh_set_vertices_d, between
 * scene calls, never during one); the body keeps its id, pose and filters, and the scene's next
 * query sees the new vertices: it recomputes the world box of every body whose mesh changed (a
 * per-mesh update count the scene compares, one comparison per body), after checking the body's
 * pose again against the moved mesh (TTD_ERR_COORDINATE_RANGE when it now leaves the range). A
 * mesh shared by several bodies moves for all of them: give each deforming body its own mesh.
 *
 * opt may be NULL; its method must be TTD_METHOD_EXACT and its isa and threads apply (body pairs
 * are spread over the threads).
 * @{ */

/// A scene of bodies (opaque).
typedef struct ttd_scene ttd_scene;

/// A new, empty scene of double precision.
TTD_API ttd_status ttd_scene_create_d(ttd_scene **out);
/// A new, empty scene of single precision.
TTD_API ttd_status ttd_scene_create_f(ttd_scene **out);
/// Frees a scene (NULL is fine); its meshes are the caller's.
TTD_API void ttd_scene_destroy(ttd_scene *scene);
/// Adds a body of mesh at pose (12 reals); *id is its id. TTD_ERR_PRECISION_MISMATCH for a mesh
/// or call of the other precision, TTD_ERR_BAD_POSE or TTD_ERR_COORDINATE_RANGE for the pose.
TTD_API ttd_status ttd_scene_add_d(ttd_scene *scene, const ttd_mesh *mesh, const double pose[12], uint32_t *id);
TTD_API ttd_status ttd_scene_add_f(ttd_scene *scene, const ttd_mesh *mesh, const float pose[12], uint32_t *id);
/// Removes body id (TTD_ERR_INDEX_OUT_OF_RANGE when there is none).
TTD_API ttd_status ttd_scene_remove(ttd_scene *scene, uint32_t id);
/// Moves body id to pose.
TTD_API ttd_status ttd_scene_set_pose_d(ttd_scene *scene, uint32_t id, const double pose[12]);
TTD_API ttd_status ttd_scene_set_pose_f(ttd_scene *scene, uint32_t id, const float pose[12]);
/// Moves every body at once: poses holds 12 reals for each id below ttd_scene_id_limit (n must be
/// that limit); the entries of removed ids are ignored. Every pose is checked before any is set.
TTD_API ttd_status ttd_scene_set_poses_d(ttd_scene *scene, size_t n, const double *poses);
TTD_API ttd_status ttd_scene_set_poses_f(ttd_scene *scene, size_t n, const float *poses);
/// Sets body id's collision group and mask (see above).
TTD_API ttd_status ttd_scene_set_filter(ttd_scene *scene, uint32_t id, uint32_t group, uint32_t mask);
/// Excludes (excluded != 0) or includes again the pair of bodies i and j (i != j, either order).
TTD_API ttd_status ttd_scene_exclude_pair(ttd_scene *scene, uint32_t i, uint32_t j, int excluded);
/// Marks body id a solid (solid != 0) or a surface again (0; bodies start as surfaces). A solid's
/// mesh must be closed (every edge shared by two triangles running it the two ways:
/// TTD_ERR_MESH_NOT_CLOSED otherwise, the body unchanged: an open or inconsistently oriented mesh,
/// ttd_mesh_orientation tells which); inside is ttd_winding_inside's, as for ttd_options.solid,
/// so a mesh wound inwards is the same solid as wound outwards. A pair of solids is a solid pair: collide finds it when one lies
/// inside the other (its witness: the inner body's triangle 0, UINT32_MAX for the outer), distance
/// is then 0 (the inner body's first vertex as p = q, its triangle 0, UINT32_MAX for the outer),
/// and a manifold carries the points of each body inside the other with negative distances
/// (docs/scenes.md, section 5b). contacts is the same for solids and surfaces.
TTD_API ttd_status ttd_scene_set_solid(ttd_scene *scene, uint32_t id, int solid);
/// Bodies present.
TTD_API size_t ttd_scene_body_count(const ttd_scene *scene);
/// One more than the largest id given so far (0 for an empty or NULL scene).
TTD_API size_t ttd_scene_id_limit(const ttd_scene *scene);

/// A growable array the library manages: start from {0} (or reuse one), free with
/// ttd_scene_array_free. count items at data, of the type the query that filled it names.
typedef struct ttd_scene_array {
    void *data;
    size_t count;
    size_t capacity;  ///< library's business
} ttd_scene_array;
/// Frees an array's memory and zeroes it (NULL is fine).
TTD_API void ttd_scene_array_free(ttd_scene_array *array);

/// A body pair within the margin, with one witness pair of triangles (tri_i of body i).
typedef struct ttd_scene_hit {
    uint32_t i, j, tri_i, tri_j;
} ttd_scene_hit;

/// Every eligible body pair within margin (>= 0, finite; 0: touching or crossing) into out, as
/// ttd_scene_hit items.
TTD_API ttd_status ttd_scene_collide_d(const ttd_options *opt, ttd_scene *scene, double margin, ttd_scene_array *out);
TTD_API ttd_status ttd_scene_collide_f(const ttd_options *opt, ttd_scene *scene, float margin, ttd_scene_array *out);

/// A pair of triangles of bodies i and j, their distance and closest points (p on body i).
typedef struct ttd_scene_contact_d {
    uint32_t i, j, tri_i, tri_j;
    double distance;
    double p[3], q[3];
} ttd_scene_contact_d;
typedef struct ttd_scene_contact_f {
    uint32_t i, j, tri_i, tri_j;
    float distance;
    float p[3], q[3];
} ttd_scene_contact_f;

/// The closest eligible body pair (i < j) into *closest, ties to the smallest (i, j) and then
/// (tri_i, tri_j); and, when nearest is not NULL, each body's nearest eligible other body into
/// nearest[id] for every id below ttd_scene_id_limit (i = id, j the partner, p on body id; ties
/// to the smallest partner and triangles). Within upper_bound (>= 0, +inf for none): beyond it,
/// or with no partner, a record has distance +inf and j, tri_i, tri_j UINT32_MAX (so do removed
/// ids' records). When the bodies touch or cross, distance 0 and p = q.
TTD_API ttd_status ttd_scene_distance_d(const ttd_options *opt, ttd_scene *scene, double upper_bound,
                                        ttd_scene_contact_d *closest, ttd_scene_contact_d *nearest);
TTD_API ttd_status ttd_scene_distance_f(const ttd_options *opt, ttd_scene *scene, float upper_bound,
                                        ttd_scene_contact_f *closest, ttd_scene_contact_f *nearest);

/// Every triangle pair within margin (>= 0, finite) of every eligible body pair into out, as
/// ttd_scene_contact_d (or _f) items.
TTD_API ttd_status ttd_scene_contacts_d(const ttd_options *opt, ttd_scene *scene, double margin, ttd_scene_array *out);
TTD_API ttd_status ttd_scene_contacts_f(const ttd_options *opt, ttd_scene *scene, float margin, ttd_scene_array *out);
/// ttd_scene_contacts_d's number of contacts alone, into *count: each body pair's pairs are
/// counted, not held (memory grows with the body pairs, not the contacts). Same checks and
/// statuses as ttd_scene_contacts_d; the same number on any thread count.
TTD_API ttd_status ttd_scene_contacts_count_d(const ttd_options *opt, ttd_scene *scene, double margin, size_t *count);
/// ttd_scene_contacts_count_d in single precision.
TTD_API ttd_status ttd_scene_contacts_count_f(const ttd_options *opt, ttd_scene *scene, float margin, size_t *count);

/// One contact point of a manifold, what a simulator consumes.
typedef struct ttd_scene_point_d {
    uint32_t i, j;         ///< the bodies, i < j
    uint32_t tri_i, tri_j; ///< the triangle pair it comes from
    double point[3];       ///< world point: the midpoint of a point of each body (the pair's closest points, or a corner of flat contact)
    double normal[3];      ///< unit normal from body i towards body j, from the bodies' shapes (docs/scenes.md, 5a)
    double distance;       ///< the exact distance d between those two points (0 touching or crossing)
    double depth;          ///< margin - d
    double point_i[3];     ///< the point of body i (world): point is the midpoint of point_i and point_j
    double point_j[3];     ///< the point of body j, at distance d from point_i (below 0: inside, docs/scenes.md 5b)
    uint64_t key;          ///< the contact's features on both bodies: the same while the contact persists
                           ///< (bits 32-63 body i's, 0-31 body j's; each: 2 bits vertex 0, edge 1, face 2,
                           ///< then 30 bits the vertex's place, the edge, the flat piece; docs/scenes.md 5c)
} ttd_scene_point_d;
typedef struct ttd_scene_point_f {
    uint32_t i, j;
    uint32_t tri_i, tri_j;
    float point[3];
    float normal[3];
    float distance;
    float depth;
    float point_i[3];
    float point_j[3];
    uint64_t key;
} ttd_scene_point_f;

/// Contact manifolds within margin (>= 0, finite): for every eligible body pair, its contacts
/// and the corners of flat contact they add (where two triangles lie face on face, normals
/// opposite within 0.1 radians: each vertex within the margin of the other triangle, at its
/// closest point; each two edges whose closest points lie inside both within the margin;
/// vertices and edges inside flat faces left out: a box on a box gets the corners of the faces'
/// overlap), merged (in depth order, a point within 1e-3 of the smaller body's mesh radius of a
/// point kept before it goes) and reduced to at most max_points points (0: all of them): the
/// deepest, then spread over the contact region of its level (within a quarter of the margin
/// left below it, none rising above a deeper one by more than 0.1 of their distance: the
/// farthest, the largest triangle, the largest area added). Every point is a
/// real point of contact: a point of each body at their exact distance, within the margin.
/// Normals come from the bodies' shapes, not the triangle pair's: a face's normal where a
/// face of one body lies within the margin of the other, across edges only where both are real
/// edges of their bodies, never outside the normal cones of the contact's features where they
/// meet; the same for any triangulation of a flat face; negated when the bodies swap
/// (docs/scenes.md, section 5a). Each point carries both bodies' points and a key of the
/// features they lie on (section 5c). As ttd_scene_point_d (or _f) items, grouped by body pair
/// in (i, j) order.
TTD_API ttd_status ttd_scene_manifold_d(const ttd_options *opt, ttd_scene *scene, double margin, size_t max_points,
                                        ttd_scene_array *out);
TTD_API ttd_status ttd_scene_manifold_f(const ttd_options *opt, ttd_scene *scene, float margin, size_t max_points,
                                        ttd_scene_array *out);

/// What the scene's last query (collide, contacts, manifold or distance) did, for profiling and
/// for sizing a scene: the work behind an answer, which the answer itself does not show.
typedef struct ttd_scene_stats {
    uint64_t body_pairs;  ///< candidate body pairs the broad phase handed to the narrow phase
    uint64_t node_tests;  ///< box-against-node tests of the narrow phase (each against up to 8 boxes)
    uint64_t pair_tests;  ///< triangle pairs given to the exact method
    uint64_t results;     ///< items the query returned (body pairs, triangle pairs, points; distance: 1)
} ttd_scene_stats;
/// The last query's ttd_scene_stats (all 0 before the first, or after a failed query).
TTD_API ttd_status ttd_scene_get_stats(const ttd_scene *scene, ttd_scene_stats *out);

/** @} */

/** @addtogroup ttd
 * @{ */

/// A short English sentence for a status.
TTD_API const char *ttd_status_string(ttd_status status);
/// "exact", "penalty", "penalty-ref", "barrier", "certified"; NULL when out of range.
TTD_API const char *ttd_method_name(ttd_method method);
/// "auto", "scalar", "sse2", "avx2", "avx512", "neon", "portable"; NULL when out of range.
TTD_API const char *ttd_isa_name(ttd_isa isa);
/// The instruction set called name, ignoring ASCII case ("AVX512" is avx512, "Auto" is auto);
/// TTD_ISA_COUNT when none is (or name is NULL).
TTD_API ttd_isa ttd_isa_from_name(const char *name);
/// NULL when the environment variable TTD_ISA is unset, empty, "auto" or names an instruction set
/// that runs here; otherwise a sentence saying why it is being ignored.
TTD_API const char *ttd_isa_env_note(void);
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

/* ==== Continuous collision detection (issue 33; src/ccd/, docs/ccd.md) ====================
 * Moving primitives under linear motion: each vertex goes from its position at t = 0 to its
 * position at t = 1 along a straight line, all at once. A query asks whether the Euclidean
 * distance between the two primitives comes to min_separation (delta >= 0) or less for some t in
 * [0, 1], and the earliest such time. No contact is ever missed (the separation of every time
 * before toi is certified with rounding error bounds); a hit is reported once a time interval of
 * TTD_CCD_DEFAULT_T_TOL cannot be separated, so toi is never after the true first time and a
 * reported hit comes within a tolerance of contact (docs/ccd.md states it). Coordinates: any
 * finite doubles (floats are widened exactly); a query with a NaN or infinite coordinate is
 * flagged TTD_CCD_NONFINITE with toi NaN and the call returns TTD_ERR_NONFINITE_INPUT after
 * computing the others. opt: NULL or from ttd_default_options() (threads apply; results do not
 * depend on them); n = 0: TTD_ERR_EMPTY; a NULL array: TTD_ERR_NULL_POINTER; min_separation
 * negative, NaN or infinite: TTD_ERR_BAD_OPTIONS. */

/// Time intervals this short that cannot be certified apart are reported as a hit.
#define TTD_CCD_DEFAULT_T_TOL 0x1p-52
/// Intervals one query examines before it answers hit (at the earliest interval left) anyway.
#define TTD_CCD_DEFAULT_MAX_EVALS 1000
/// ttd_ccd_result.flags: the query used up TTD_CCD_DEFAULT_MAX_EVALS; its hit is conservative.
#define TTD_CCD_BUDGET 1u
/// ttd_ccd_result.flags: a coordinate was NaN or infinite; nothing computed, toi NaN.
#define TTD_CCD_NONFINITE 2u

/// One continuous query's answer.
typedef struct ttd_ccd_result {
    /// Conservative time of impact in [0, 1]: the start of the first time interval that could not
    /// be separated; INFINITY when there is no hit, NaN for a non-finite query.
    double toi;
    /// The distance computed (in double, approximate) at the middle of that interval; INFINITY
    /// without a hit. A hit whose gap exceeds min_separation is a near contact within the tolerance.
    double gap;
    uint32_t hit;   ///< 1 when the distance may come to min_separation or less in [0, 1]
    uint32_t flags; ///< TTD_CCD_BUDGET, TTD_CCD_NONFINITE
    /// ttd_ccd_triangles only: the sub-query that gave toi: 0..2 vertex i of a against b, 3..5
    /// vertex i of b against a, 6 + 3 i + j edge i of a against edge j of b (edge i runs from
    /// vertex i to vertex (i + 1) % 3). 0 for the other entries.
    uint32_t sub;
    uint32_t evals; ///< time intervals examined (all sub-queries together for triangles)
} ttd_ccd_result;

/// Vertex-face: n queries; v_t0, v_t1: 3n (the vertex at t = 0 and t = 1); f_t0, f_t1: 9n (the
/// face's three vertices).
TTD_API ttd_status ttd_ccd_vertex_face_d(const ttd_options *opt, size_t n, const double *v_t0,
                                         const double *f_t0, const double *v_t1, const double *f_t1,
                                         double min_separation, ttd_ccd_result *out);
TTD_API ttd_status ttd_ccd_vertex_face_f(const ttd_options *opt, size_t n, const float *v_t0,
                                         const float *f_t0, const float *v_t1, const float *f_t1,
                                         double min_separation, ttd_ccd_result *out);
/// Edge-edge: n queries; ea_t0, eb_t0, ea_t1, eb_t1: 6n each (an edge's two endpoints).
TTD_API ttd_status ttd_ccd_edge_edge_d(const ttd_options *opt, size_t n, const double *ea_t0,
                                       const double *eb_t0, const double *ea_t1, const double *eb_t1,
                                       double min_separation, ttd_ccd_result *out);
TTD_API ttd_status ttd_ccd_edge_edge_f(const ttd_options *opt, size_t n, const float *ea_t0,
                                       const float *eb_t0, const float *ea_t1, const float *eb_t1,
                                       double min_separation, ttd_ccd_result *out);
/// Triangle-triangle: n queries; ta_t0, tb_t0, ta_t1, tb_t1: 9n each. The 6 vertex-face and 9
/// edge-edge sub-queries; toi the earliest, sub the one that gave it (the lowest index on a tie).
TTD_API ttd_status ttd_ccd_triangles_d(const ttd_options *opt, size_t n, const double *ta_t0,
                                       const double *tb_t0, const double *ta_t1, const double *tb_t1,
                                       double min_separation, ttd_ccd_result *out);
TTD_API ttd_status ttd_ccd_triangles_f(const ttd_options *opt, size_t n, const float *ta_t0,
                                       const float *tb_t0, const float *ta_t1, const float *tb_t1,
                                       double min_separation, ttd_ccd_result *out);

/* ---- Continuous collision of deforming meshes (issue 34; src/meshccd/, docs/ccd.md section 10) ----
 * A mesh's vertices move on straight lines from their positions in the mesh (t = 0) to a new
 * array of positions (t = 1), the triangles unchanged. ttd_mesh_ccd_d asks, over every vertex-face
 * and edge-edge pair of two meshes, and ttd_mesh_self_ccd_d over the pairs of one mesh that the
 * self rule keeps, the earliest time any pair comes within min_separation (the primitive queries
 * above, with their guarantee: toi is never after the true first time), and returns every pair
 * whose own conservative time is at most that toi + TTD_CCD_DEFAULT_T_TOL. The set and its order
 * depend on the inputs alone (not on threads). The hierarchy is one over swept boxes (each
 * triangle's box around its vertices at t = 0 and t = 1) built per call. */

/// ttd_mesh_ccd_pair.kind
enum {
    TTD_MESH_CCD_VF = 0, ///< a vertex (a[0]) of mesh a against a triangle (b[0]) of mesh b
    TTD_MESH_CCD_FV = 1, ///< a triangle (a[0]) of mesh a against a vertex (b[0]) of mesh b
    TTD_MESH_CCD_EE = 2  ///< an edge of a (vertices a[0] < a[1]) against an edge of b (b[0] < b[1])
};

/// One primitive pair that comes within min_separation. In a self query a and b name the same
/// mesh: VF is a vertex a[0] against a triangle b[0]; EE two edges, (a[0], a[1]) < (b[0], b[1]).
/// Unused ids (a[1], b[1] of VF and FV) are UINT32_MAX.
typedef struct ttd_mesh_ccd_pair {
    double toi;      ///< the pair's conservative time of impact (ttd_ccd_result.toi)
    double gap;      ///< the distance computed near toi, for information (ttd_ccd_result.gap)
    uint32_t kind;   ///< TTD_MESH_CCD_VF, TTD_MESH_CCD_FV, TTD_MESH_CCD_EE
    uint32_t flags;  ///< TTD_CCD_BUDGET
    uint32_t a[2], b[2];
} ttd_mesh_ccd_pair;

/// What a mesh CCD query answers. pairs is allocated by the library (free it with
/// ttd_mesh_ccd_free); sorted by toi, then kind, a, b.
typedef struct ttd_mesh_ccd_result {
    double toi;              ///< the earliest time of impact in [0, 1]; INFINITY when none
    ttd_mesh_ccd_pair *pairs;
    size_t count;
    uint64_t triangle_pairs; ///< triangle pairs whose swept boxes came within min_separation
    uint64_t queries;        ///< primitive pairs whose swept boxes came within min_separation (each once;
                             ///< in a self query, of the triangle pairs not proved apart whole first)
    uint64_t searches;       ///< of those, the ones not proved apart along a face normal or edge cross
                             ///< product at t = 0 and t = 1, searched by the primitive query
    uint32_t flags;          ///< TTD_CCD_BUDGET when some reported pair used up its budget
} ttd_mesh_ccd_result;

/// Deforming meshes a and b (built in double), a's vertices at t = 1 in a_vertices_t1 (3 nv_a
/// doubles), b's in b_vertices_t1: every vertex of a against every triangle of b, every vertex of
/// b against every triangle of a, every edge of a against every edge of b. min_separation >= 0.
/// Checks: out, a, b or an array NULL: TTD_ERR_NULL_POINTER; options checked as the mesh queries'
/// (TTD_ERR_BAD_OPTIONS; a forced instruction set this machine lacks: TTD_ERR_ISA_UNAVAILABLE);
/// min_separation negative, NaN or infinite: TTD_ERR_BAD_OPTIONS; a mesh of the other precision:
/// TTD_ERR_PRECISION_MISMATCH; a NaN or infinite t = 1 coordinate: TTD_ERR_NONFINITE_MESH (nothing
/// computed). out->count is 0 and out->pairs NULL on any error.
TTD_API ttd_status ttd_mesh_ccd_d(const ttd_options *opt, const ttd_mesh *a, const double *a_vertices_t1,
                                  const ttd_mesh *b, const double *b_vertices_t1, double min_separation,
                                  ttd_mesh_ccd_result *out);
/// ttd_mesh_ccd_d for meshes built in float, float t = 1 arrays (widened to double exactly).
TTD_API ttd_status ttd_mesh_ccd_f(const ttd_options *opt, const ttd_mesh *a, const float *a_vertices_t1,
                                  const ttd_mesh *b, const float *b_vertices_t1, double min_separation,
                                  ttd_mesh_ccd_result *out);
/// Self-CCD of one deforming mesh: the primitive pairs (vertex-face, edge-edge) of triangle pairs
/// that share no vertex (by index), each pair once. With flags TTD_SELF_SHARED_VERTEX, also those
/// of triangle pairs that share exactly one vertex s, less the sub-queries whose two primitives
/// share a vertex (s against the other triangle, and two edges that both end at s): 4 vertex-face
/// and 5 edge-edge sub-queries of the 15. Triangle pairs that share two or three vertices add
/// nothing. Checks as ttd_mesh_ccd_d, and unknown flag bits: TTD_ERR_BAD_OPTIONS.
TTD_API ttd_status ttd_mesh_self_ccd_d(const ttd_options *opt, const ttd_mesh *mesh, const double *vertices_t1,
                                       double min_separation, unsigned flags, ttd_mesh_ccd_result *out);
/// ttd_mesh_self_ccd_d for a mesh built in float.
TTD_API ttd_status ttd_mesh_self_ccd_f(const ttd_options *opt, const ttd_mesh *mesh, const float *vertices_t1,
                                       double min_separation, unsigned flags, ttd_mesh_ccd_result *out);
/// Frees out->pairs and sets count 0 (NULL is fine).
TTD_API void ttd_mesh_ccd_free(ttd_mesh_ccd_result *out);

/* ---- Continuous collision of rigid bodies between two poses (issue 34; src/api/rigid_ccd_api.c,
 * src/meshccd/rigid_motion.c, docs/ccd.md section 13) ----
 * Each body has a world pose at t = 0 and one at t = 1 (12 reals each, [R | t] row by row as
 * for the mesh queries: x_world = R x_mesh + t; a body's 24 reals are the two poses one after
 * the other). Between them the body moves rigidly: its origin (the point x_mesh = 0) on a
 * straight line, T(t) = (1 - t) T0 + t T1, and its rotation about one fixed world axis at a
 * constant rate, R(t) = Rot(u, t theta) R0, where R1 R0^T = Rot(u, theta) with theta in
 * [0, pi] (taken from its unit quaternion with w >= 0; at theta = pi, where both signs of u
 * give R1, the sign that makes u's largest component positive, the first on a tie). R(1) is R1
 * up to R1 R0^T's own distance from a rotation (about 1e-16 for orthonormal matrices). A pose
 * R further than 16 ulps from a rotation (the check allows R^T R - I up to 1e-6) is first
 * replaced by its nearest rotation (the polar factor, within about defect |x| of R x): the query
 * answers about the bodies moved by those rotations, not by the R given. ttd_rigid_pose_at_d
 * gives the pose at any t (the same motion).
 *
 * The query is conservative advancement: the exact mesh distance d at time t, and a bound V on
 * how fast it can fall (each body's |T1 - T0| + theta r, r the largest |x| over its mesh's
 * vertices, rounded upward) prove [t, t + (d - mu - delta) / V] apart; mu bounds rounding. It
 * stops with a hit at t once d comes within the tolerance eta of delta, and with no hit once
 * the proved times reach 1. Guarantees: no contact is missed: every time before toi is proved at
 * a distance above min_separation; toi is never after the true first time of distance <=
 * min_separation, and at toi the distance is at most min_separation + tolerance (the result's
 * tolerance: 2^-30 S in double, 2^-14 S in float, S = both meshes' r + both origins' largest
 * |T| over the two poses); a pair where nothing moves answers no hit inside that band (the
 * first distance query is bounded by min_separation + the rounding margin). A pair that stays within a few tolerances of min_separation without
 * coming nearer (sliding in contact) takes many steps: after TTD_RIGID_CCD_MAX_STEPS the query
 * answers a hit at the last proved time, flagged TTD_CCD_BUDGET (conservative: nothing before
 * it touches). With ttd_options.solid (closed meshes), a body inside the other counts as
 * contact. Checks: out, a mesh or a pose array NULL: TTD_ERR_NULL_POINTER; options as the mesh
 * queries' (TTD_ERR_BAD_OPTIONS, TTD_ERR_ISA_UNAVAILABLE); min_separation negative, NaN or
 * infinite: TTD_ERR_BAD_OPTIONS; a mesh of the other precision: TTD_ERR_PRECISION_MISMATCH; a
 * pose with a NaN or infinite number or whose R is no rotation (R^T R - I beyond 1e-6, det R
 * <= 0): TTD_ERR_BAD_POSE; a mesh moved beyond the coordinate range: TTD_ERR_COORDINATE_RANGE.
 * Nothing is computed on an error (toi INFINITY, hit 0). */

/// Conservative-advancement intervals one rigid pair takes before it answers a conservative hit.
#define TTD_RIGID_CCD_MAX_STEPS 10000

/// What a rigid continuous query answers.
typedef struct ttd_mesh_ccd_rigid_result {
    double toi;       ///< conservative time of impact in [0, 1]; INFINITY when none
    double distance;  ///< the exact mesh distance computed at toi; INFINITY without a hit or with TTD_CCD_BUDGET
    double tolerance; ///< eta: at toi the true distance is at most min_separation + tolerance
    uint32_t hit;     ///< 1 when the bodies come within min_separation (or within the tolerance of it)
    uint32_t flags;   ///< TTD_CCD_BUDGET: TTD_RIGID_CCD_MAX_STEPS used up (or a step below the times' resolution)
    uint32_t steps;   ///< mesh distance queries made
    uint32_t tri_a, tri_b; ///< the closest triangles at toi (UINT32_MAX without a hit or with TTD_CCD_BUDGET)
} ttd_mesh_ccd_rigid_result;

/// Meshes a and b (built in double), each moving rigidly from its first pose to its second
/// (a_poses, b_poses: 24 reals each) over t in [0, 1]: the earliest time their distance comes
/// to min_separation (>= 0) or less. opt's threads do not apply (one pair, one thread).
TTD_API ttd_status ttd_mesh_ccd_rigid_d(const ttd_options *opt, const ttd_mesh *a, const double *a_poses,
                                        const ttd_mesh *b, const double *b_poses, double min_separation,
                                        ttd_mesh_ccd_rigid_result *out);
/// ttd_mesh_ccd_rigid_d for meshes built in float and float poses (the motion computed in double).
TTD_API ttd_status ttd_mesh_ccd_rigid_f(const ttd_options *opt, const ttd_mesh *a, const float *a_poses,
                                        const ttd_mesh *b, const float *b_poses, double min_separation,
                                        ttd_mesh_ccd_rigid_result *out);
/// The pose at time t in [0, 1] of the motion from pose_t0 to pose_t1 (12 reals each) into pose
/// (12 reals). NULL: TTD_ERR_NULL_POINTER; a NaN or infinite number: TTD_ERR_BAD_POSE; t outside
/// [0, 1] or NaN: TTD_ERR_BAD_OPTIONS. The rotations are not checked (the queries do).
TTD_API ttd_status ttd_rigid_pose_at_d(const double *pose_t0, const double *pose_t1, double t, double *pose);

/// A body pair of a scene that comes within min_separation during a step (ttd_scene_ccd_d).
typedef struct ttd_scene_ccd_hit {
    uint32_t i, j;         ///< the bodies, i < j
    uint32_t tri_i, tri_j; ///< the closest triangles at toi (UINT32_MAX with TTD_CCD_BUDGET)
    uint32_t flags;        ///< TTD_CCD_BUDGET (ttd_mesh_ccd_rigid_result.flags)
    uint32_t steps;        ///< the pair's conservative-advancement steps
    double toi;            ///< the pair's conservative time of impact (ttd_mesh_ccd_rigid_d)
    double distance;       ///< the exact distance computed at toi
} ttd_scene_ccd_hit;

/// Continuous collision over a scene's step: every body moves rigidly (the motion above) from its
/// pose in the scene (t = 0) to its pose in poses_t1 (12 reals for each id below
/// ttd_scene_id_limit, n that limit; removed ids' entries ignored). Every eligible body pair (the
/// filters and exclusions, as for contacts; a pair of solids as solids) that comes within
/// min_separation (>= 0, finite) during the step, with ttd_mesh_ccd_rigid_d's answer, into out
/// as ttd_scene_ccd_hit items sorted by (i, j). The broad phase bounds each body's whole sweep by
/// a world box (docs/ccd.md section 13) and keeps the pairs within min_separation plus the pair
/// query's tolerance, so the hits are those of ttd_mesh_ccd_rigid_d over every eligible pair
/// (near contacts within the tolerance included); the pairs run on opt's threads
/// and the answer does not depend on them. The scene is not changed (set the new poses after).
/// Checks: those of the scene queries; n not the id limit: TTD_ERR_INDEX_OUT_OF_RANGE; a t = 1
/// pose refused as by ttd_scene_set_pose_d (TTD_ERR_BAD_POSE, TTD_ERR_COORDINATE_RANGE); out->count
/// is 0 on an error. ttd_scene_get_stats: body_pairs (the broad phase's candidates) and results.
TTD_API ttd_status ttd_scene_ccd_d(const ttd_options *opt, ttd_scene *scene, size_t n, const double *poses_t1,
                                   double min_separation, ttd_scene_array *out);
/// ttd_scene_ccd_d for a scene of single precision (float poses).
TTD_API ttd_status ttd_scene_ccd_f(const ttd_options *opt, ttd_scene *scene, size_t n, const float *poses_t1,
                                   double min_separation, ttd_scene_array *out);
/* ==== end of continuous collision detection ==================================================== */

/** @} */

#ifdef __cplusplus
}
#endif
#endif /* TTD_TTD_H */
