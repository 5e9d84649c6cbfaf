/* SPDX-License-Identifier: MIT */
/* The benchmark's mesh pair workloads (docs/benchmark.md): the candidate pairs that a box-based
 * broad phase hands the narrow phase when two copies of a mesh are near each other, timed with
 * ttd's exact kernel for the three outputs a mesh query asks for (distances, distances and
 * points, full results), with and without the query's bound, and with FCL's triangle distance
 * on the same pairs.  */
#ifndef TTD_BENCH_MESH_WORKLOAD_H
#define TTD_BENCH_MESH_WORKLOAD_H

#include <stddef.h>
#include <stdint.h>

#include "meshes.h"
#include "ttd/ttd.h"

/// Candidate pairs of two copies of one mesh: the first as it is, the second placed by
/// `poses` poses, each at the given distance from the first.
typedef struct bench_cand_set {
    char mesh[128];   ///< what the mesh is (file or generator, subdivision, triangles)
    double distance;  ///< the copies' distance at every pose (the mesh's box diagonal is 1)
    double margin;    ///< the broad phase's margin, and the bound a margin query passes
    int poses;
    size_t n;         ///< candidate pairs, all poses together
    double *s, *t;    ///< 9 n coordinates each: the first copy's triangle, the second's
    size_t within;    ///< pairs at distance <= margin
} bench_cand_set;

/// The workloads' mesh: the file at path (OBJ, STL or PLY; NULL: none), or, when there is no
/// file or it cannot be read, an icosphere of level 3 (coarse); normalized (box diagonal 1), and
/// subdivided flat `levels` times (fine: the same surface). desc gets what was used (and why,
/// for the fallback). Returns 0, or -1 when even the generator failed.
int bench_cand_mesh_load(const char *path, int levels, ttd_gen_mesh *fine, ttd_gen_mesh *coarse, char *desc,
                         size_t descsize);

/// The pairs of `poses` poses of a copy of m against m: pose i has the rotation of
/// ttd_gen_pose_gap(coarse, coarse, seed, i, ...) and a translation found so that the copies'
/// distance (ttd's exact method, scalar row, on coarse: the same surface as m with fewer
/// triangles) is `distance` to 0.1%; its candidates are m's triangle pairs whose boxes come
/// within margin (gen/mesh_pairs.h). Stops with -1 past max_pairs in all. Returns 0 or -1
/// (allocation, a pose that does not converge, too many pairs).
int bench_cand_make(const ttd_gen_mesh *m, const ttd_gen_mesh *coarse, const char *desc, double distance,
                    double margin, int poses, uint64_t seed, size_t max_pairs, bench_cand_set *out);

void bench_cand_free(bench_cand_set *set);

/// Times ttd's exact kernel on n pairs (9n reals each in s and t, precision bytes) on
/// instruction set isa, one thread, block by block as the engine calls it: output 0 asks for
/// distances, 1 for distances and points, 2 for full results; bound is the kernel's (INFINITY:
/// every pair exact). A warm-up pass, then `samples` samples (1..64) of enough passes to last
/// min_sample_s. Writes the median and fastest ns per pair, and the distances of the last pass
/// (as double) to dist. Returns 0, or -1 (isa not built or not runnable here, no memory).
int bench_cand_time(size_t n, const void *s, const void *t, int bytes, ttd_isa isa, int output, double bound,
                    int samples, double min_sample_s, double *dist, double *ns_median, double *ns_min);

#endif /* TTD_BENCH_MESH_WORKLOAD_H */
