/* SPDX-License-Identifier: MIT */
/* FCL's scene queries beside ttd's (issue 17, item 5): the file format that `ttd bench` and the
 * C++ program ttd_fcl_scene_bench (bench/fcl/fcl_scene_bench.cpp) share, and the C calls that
 * write a scene, run the program and read its answers back. FCL 0.7's
 * DynamicAABBTreeCollisionManager<double> over CollisionObjects of shared
 * BVHModel<OBBRSS<double>> (one model per mesh), one thread, timed in the same run as ttd on the
 * same bodies and poses. Plain arrays only, as bench/fcl_mesh_link.h.
 *
 * Input file (little-endian; every count checked against the file size by the program):
 *   char     magic[8]     "TTDSCEN1"
 *   uint32   repetitions  timed runs of each query (>= 1); the median and the fastest are reported
 *   uint32   motion_runs  timed runs of the whole motion (0: no motion)
 *   double   margin       of the collide@margin and contacts queries and the motion's query (> 0)
 *   uint32   nmeshes;     then per mesh: uint64 nv, nt; double v[3*nv]; uint32 t[3*nt]
 *   uint64   nbodies;     then per body: uint32 mesh; double pose[12]  ([R | t] row by row, world)
 *   uint32   steps;       then steps * nbodies poses (12 doubles each), step after step
 *
 * Output (text on stdout, numbers %.17g, one record a line, the keyword first):
 *   # ttd_fcl_scene_bench fcl VERSION bodies N meshes K margin M repetitions R steps S
 *   build MED_MS MIN_MS                    models + objects + registerObjects + setup
 *   collide0 MED_MS MIN_MS PAIRS CANDIDATES  body pairs touching or crossing (fcl::collide per candidate)
 *   pair I J                               PAIRS lines, I < J, sorted
 *   collidem MED_MS MIN_MS PAIRS CANDIDATES  body pairs within the margin: boxes inflated by margin/2
 *                                          each, an early-exit OBBRSS margin traversal per candidate
 *   pair I J                               PAIRS lines
 *   distance MED_MS MIN_MS D I J IA IB CALLS  the closest body pair (manager->distance, fcl::distance
 *                                          with nearest points per candidate; stops at a touching pair)
 *   contacts MED_MS MIN_MS COUNT BODYPAIRS CANDIDATES  every triangle pair within the margin
 *                                          (inflated boxes, the mesh benchmark's margin traversal)
 *   motion MED_MS MIN_MS UPDATE_MS STEPS   per step: setTransform + computeAABB (inflated) +
 *                                          manager->update + the collidem query; UPDATE_MS the
 *                                          update's share (median run)
 *   step K PAIRS                           STEPS lines: the collidem answer after step K */
#ifndef TTD_BENCH_FCL_SCENE_LINK_H
#define TTD_BENCH_FCL_SCENE_LINK_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define BENCH_FCL_SCENE_MAGIC "TTDSCEN1"
#define BENCH_FCL_SCENE_PROGRAM "ttd_fcl_scene_bench"
/// Environment variable that names the program (overrides the search next to `ttd`).
#define BENCH_FCL_SCENE_ENV "TTD_FCL_SCENE_BENCH"

#ifndef __cplusplus
/// One mesh: nv vertices (xyz each) and nt triangles (three vertex indices each).
typedef struct bench_fcl_scene_mesh {
    const double *vertices;
    size_t nv;
    const uint32_t *triangles;
    size_t nt;
} bench_fcl_scene_mesh;

/// A scene and what to run on it.
typedef struct bench_fcl_scene_job {
    const bench_fcl_scene_mesh *meshes;
    uint32_t nmeshes;
    size_t nbodies;
    const uint32_t *body_mesh;  ///< nbodies mesh indices
    const double *poses;        ///< 12 nbodies: the bodies' world poses
    double margin;
    uint32_t repetitions;       ///< >= 1
    uint32_t motion_runs;       ///< 0: no motion
    uint32_t steps;             ///< motion steps (poses: steps * nbodies * 12 doubles)
    const double *motion;
} bench_fcl_scene_job;

/// A body pair (i < j).
typedef struct bench_fcl_scene_pair {
    uint32_t i, j;
} bench_fcl_scene_pair;

/// One timed query: median and fastest of the repetitions.
typedef struct bench_fcl_scene_time {
    double ms, ms_min;
    uint64_t count;       ///< collide: body pairs; contacts: triangle pairs
    uint64_t candidates;  ///< broad-phase candidates passed to the callback (distance: its calls)
} bench_fcl_scene_time;

/// Everything one run returns. Free with bench_fcl_scene_result_free().
typedef struct bench_fcl_scene_result {
    bench_fcl_scene_time build, collide0, collidem, distance, contacts, motion;
    bench_fcl_scene_pair *pairs0, *pairsm; ///< collide0.count and collidem.count pairs
    double dist;                           ///< the closest pair's distance
    int64_t di, dj, dia, dib;              ///< its bodies and triangles
    uint64_t contact_body_pairs;
    double motion_update_ms;
    uint64_t *step_pairs;                  ///< motion: the collidem count after each step
    uint32_t steps;
    char error[512];
} bench_fcl_scene_result;

enum {
    BENCH_FCL_SCENE_OK = 0,
    BENCH_FCL_SCENE_MISSING = 1, ///< the program was not found (FCL absent at build time): not an error
    BENCH_FCL_SCENE_ERROR = -1
};

/// Writes the job to a temporary file, runs program (NULL: $TTD_FCL_SCENE_BENCH or next to ttd)
/// and reads the result. Returns BENCH_FCL_SCENE_OK, _MISSING or _ERROR; out->error says why.
int bench_fcl_scene_run(const char *program, const bench_fcl_scene_job *job, bench_fcl_scene_result *out);

/// Frees what a run allocated (the struct itself is the caller's); safe on a zeroed struct.
void bench_fcl_scene_result_free(bench_fcl_scene_result *r);

/// What bench_fcl_scene_run and the other scene programs' runs (bench/bullet_scene_link.c) share:
/// writes the job to a temporary file, runs program on it with its standard output into a new
/// temporary file, whose name goes to out_name (the caller reads it, then unlinks it). 0, or -1
/// with err set (and no file left).
int bench_scene_program_run(const char *program, const bench_fcl_scene_job *job, char *out_name, size_t out_size,
                            char *err, size_t err_size);
#endif

#ifdef __cplusplus
}
#endif
#endif /* TTD_BENCH_FCL_SCENE_LINK_H */
