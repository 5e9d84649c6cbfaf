/* SPDX-License-Identifier: MIT */
/* FCL's mesh queries beside ttd's: the file format that `ttd bench` and the C++ program
 * ttd_fcl_mesh_bench (bench/fcl/fcl_mesh_bench.cpp) share, and the C calls that write a
 * workload, run the program and read its answers back. FCL 0.7 is timed in the same run, on
 * the same meshes and poses as ttd. Plain arrays only, so that the benchmark does not depend
 * on ttd's own mesh API. The program includes this header for the constants below.
 *
 * Input file (little-endian; every count checked against the file size by the program):
 *   char     magic[8]     "TTDMESH1"
 *   uint32   query        0 = minimum distance, 1 = collision, 2 = pairs within margin, 3 = refit
 *   uint32   repetitions  timed runs per pose (>= 1)
 *   double   margin       for queries 1 (0 = plain collision) and 2
 *   uint64   nvA, ntA;  double vA[3*nvA];  uint32 tA[3*ntA]
 *   uint64   nvB, ntB;  double vB[3*nvB];  uint32 tB[3*ntB]
 *   uint64   K;         double pose[12*K]
 * Each pose is the 3x4 matrix [R | t] row by row: x_A = R x_B + t, with A at the identity.
 *
 * Output (text on stdout; numbers %.17g, fields separated by single spaces):
 *   build_ms A B                      ms to build each BVHModel<OBBRSS> from the arrays (a build
 *                                     under 1 s: median of up to 5 after an untimed warm-up)
 *   # ttd_fcl_mesh_bench fcl VERSION query NAME repetitions N margin M poses K
 *   # FIELD FIELD ...                 the names of the row fields, as below
 *   one row per pose, in pose order:
 *   query 0: pose median_ms min_ms distance px py pz qx qy qz ia ib bv_tests leaf_tests
 *   query 1: pose median_ms min_ms collide ia ib bv_tests leaf_tests margin
 *   query 2: pose median_ms min_ms pairs bv_tests leaf_tests
 *   query 3: pose median_ms min_ms    (one row; the pose is not used)
 * p (on triangle ia of A) and q (on triangle ib of B) are in A's frame. collide is 1 or 0, ia
 * and ib the triangles of the contact FCL found (-1 -1 without one); margin is "ok", or
 * "unsupported" when a margin > 0 was asked for: FCL 0.7's collide has none, so the row
 * answers and times plain collision. bv_tests and leaf_tests are bounding-volume pair tests
 * and triangle pair tests of one query. Query 3 (refit, B holding A's triangles and the moved
 * vertices): A's model is built once (build_ms B is 0), then each timed run is FCL's refit,
 * beginUpdateModel(), updateSubModel(vertices), endUpdateModel(true, true) (bottom-up), to B's
 * vertices and A's in turn, so that every run moves the model.
 *
 * Pairs file (query 2, `--pairs FILE`; little-endian):
 *   char magic[8] "TTDPAIR1"; uint64 K; then for each pose: uint64 n, and n records
 *   { uint32 ia, uint32 ib, double d } sorted by (ia, ib), d FCL's triangle distance. */
#ifndef TTD_BENCH_FCL_MESH_LINK_H
#define TTD_BENCH_FCL_MESH_LINK_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define BENCH_FCL_MESH_MAGIC "TTDMESH1"
#define BENCH_FCL_MESH_PAIRS_MAGIC "TTDPAIR1"
#define BENCH_FCL_MESH_PROGRAM "ttd_fcl_mesh_bench"
/// Environment variable that names the program (overrides the search next to `ttd`).
#define BENCH_FCL_MESH_ENV "TTD_FCL_MESH_BENCH"

typedef enum bench_fcl_mesh_query {
    BENCH_FCL_MESH_DISTANCE = 0, ///< minimum distance, closest points and triangle ids
    BENCH_FCL_MESH_COLLIDE = 1,  ///< collision yes/no and one contact's triangle ids
    BENCH_FCL_MESH_PAIRS = 2,    ///< every triangle pair within the margin
    BENCH_FCL_MESH_REFIT = 3,    ///< A's model refitted to B's vertices and back (same triangles)
    BENCH_FCL_MESH_QUERY_COUNT = 4
} bench_fcl_mesh_query;

/// One mesh: nv vertices (xyz each) and nt triangles (three vertex indices each).
typedef struct bench_fcl_mesh {
    const double *vertices;
    size_t nv;
    const uint32_t *triangles;
    size_t nt;
} bench_fcl_mesh;

/// One workload: B under each of nposes poses (12 doubles, [R | t] row by row) against A.
typedef struct bench_fcl_mesh_job {
    bench_fcl_mesh a, b;
    const double *poses;
    size_t nposes;
    bench_fcl_mesh_query query;
    uint32_t repetitions;     ///< timed runs per pose, >= 1
    double margin;            ///< queries 1 and 2
} bench_fcl_mesh_job;

/// FCL's answer for one pose; fields a query does not produce are NaN / -1 / 0.
typedef struct bench_fcl_mesh_pose {
    double median_ms, min_ms;
    double distance;          ///< query 0
    double p[3], q[3];        ///< query 0: closest points, in A's frame
    int64_t ia, ib;           ///< queries 0 and 1: triangles of A and B (-1 when none)
    int collide;              ///< query 1: 1 or 0
    int margin_supported;     ///< query 1: 0 when a margin > 0 was asked for (plain collision timed)
    uint64_t pairs;           ///< query 2: pairs within the margin
    uint64_t bv_tests, leaf_tests;
} bench_fcl_mesh_pose;

/// A triangle pair within the margin (query 2 with want_pairs).
typedef struct bench_fcl_mesh_pair {
    uint32_t ia, ib;
    double d;
} bench_fcl_mesh_pair;

/// Everything one run of the program returns. Free with bench_fcl_mesh_result_free().
typedef struct bench_fcl_mesh_result {
    double build_ms[2];       ///< A, B
    size_t nposes;
    bench_fcl_mesh_pose *poses;
    /// Query 2 with want_pairs: pose k's pairs are pairs[pair_start[k] .. pair_start[k+1]).
    bench_fcl_mesh_pair *pairs;
    size_t *pair_start;
    char error[512];          ///< why a call failed (also set on BENCH_FCL_MESH_MISSING)
} bench_fcl_mesh_result;

enum {
    BENCH_FCL_MESH_OK = 0,
    BENCH_FCL_MESH_MISSING = 1, ///< ttd_fcl_mesh_bench not found: FCL absent at build time; not an error
    BENCH_FCL_MESH_ERROR = -1   ///< bad job, I/O failure or the program failed; see result.error
};

/// Path of ttd_fcl_mesh_bench: explicit_path (may be NULL), $TTD_FCL_MESH_BENCH, or next to
/// this program. Returns BENCH_FCL_MESH_OK or BENCH_FCL_MESH_MISSING.
int bench_fcl_mesh_find(const char *explicit_path, char *path, size_t size);

/// Checks a job (sizes, indices, finite numbers, rigid poses) and writes it to path in the
/// input format. Returns BENCH_FCL_MESH_OK or BENCH_FCL_MESH_ERROR with err (size err_size) set.
int bench_fcl_mesh_write_job(const char *path, const bench_fcl_mesh_job *job, char *err, size_t err_size);

/// Runs the program on an input file already written, parses its output for a job of query
/// and nposes poses; reads the pairs file too when want_pairs (query 2 only).
int bench_fcl_mesh_run_file(const char *program, const char *in_path, bench_fcl_mesh_query query,
                            size_t nposes, int want_pairs, bench_fcl_mesh_result *out);

/// Writes the job to a temporary file, runs program (NULL: bench_fcl_mesh_find(NULL)) and
/// reads the result. Returns BENCH_FCL_MESH_OK, BENCH_FCL_MESH_MISSING (FCL not built: the
/// benchmark goes on without it) or BENCH_FCL_MESH_ERROR; out->error says why.
int bench_fcl_mesh_run(const char *program, const bench_fcl_mesh_job *job, int want_pairs,
                       bench_fcl_mesh_result *out);

/// Frees what a run allocated (the struct itself is the caller's); safe on a zeroed struct.
void bench_fcl_mesh_result_free(bench_fcl_mesh_result *r);

#ifdef __cplusplus
}
#endif
#endif /* TTD_BENCH_FCL_MESH_LINK_H */
