/* SPDX-License-Identifier: MIT */
/* The scene section of `ttd bench` (issue 17, item 5): ttd's scene queries (ttd_scene_*) against
 * FCL 0.7's DynamicAABBTreeCollisionManager over CollisionObjects of shared BVHModel<OBBRSS>
 * (bench/fcl/fcl_scene_bench.cpp through bench/fcl_scene_link.c) on the same scenes, one thread,
 * in the same run, with the speed targets printed beside the measured ratios. bench/bench.c
 * only parses the options through bench_scene_option(), runs the section and hands the results to
 * the writers; everything else is in bench/scene_bench.c. docs/benchmark.md describes the scenes. */
#ifndef TTD_BENCH_SCENE_BENCH_H
#define TTD_BENCH_SCENE_BENCH_H

#include <stddef.h>
#include <stdio.h>

#include "bench_internal.h"
#include "rows.h"
#include "mesh_bench.h"

/// What the command line asked of the scene section.
typedef struct bench_scene_config {
    int disabled;          ///< --no-scene
    unsigned named;        ///< workloads named in --scene-workloads (bit i = workload i); 0: none named
    char fcl_scene[1024];  ///< --fcl-scene PATH ("" = $TTD_FCL_SCENE_BENCH or next to ttd)
    char write_dir[1024];  ///< --scene-write DIR: each scene also written there for `ttd scene` ("" = not)
} bench_scene_config;

/// What the rest of the benchmark decided, for the scene section.
typedef struct bench_scene_env {
    const bench_settings *st;      ///< quick, samples, minimum sample time, seed
    int max_threads;               ///< --threads (the motion's second row uses min(2, this))
    unsigned isa_mask;             ///< --isa: the best of these runs every scene row
    int no_fcl;                    ///< --no-fcl
    int want_float;                ///< --precision includes float (the contacts row in float)
    int quiet;
    double t_start;                ///< bench_now() at the start, for the progress lines
    const bench_mesh_config *mesh; ///< where the mesh section looks for the bunny (--bunny)
} bench_scene_env;

/// The measured rows and the checks (opaque).
typedef struct bench_scene_results bench_scene_results;

/// Parses one option of the scene section, as bench_mesh_option().
int bench_scene_option(bench_scene_config *c, const char *a, const char *v);
/// The scene options' lines of `ttd bench --help`.
void bench_scene_usage(FILE *f);
/// Whether the section runs: not with --no-scene; by default yes, unless --workloads or
/// --mesh-workloads named other sections and --scene-workloads named none.
int bench_scene_wanted(const bench_scene_config *c, int other_sections_named);

/// Runs the section. Never fails because of a target or a disagreement (those are reported);
/// returns NULL only when it could not allocate its results.
bench_scene_results *bench_scene_run(const bench_scene_config *c, const bench_scene_env *env);
/// Rows measured (0 for NULL).
size_t bench_scene_row_count(const bench_scene_results *r);

/// The section of the text table (after the mesh rows).
void bench_scene_write_table(FILE *f, const bench_scene_results *r);
/// The value of the "scene" member of bench.json (an object).
void bench_scene_write_json(FILE *f, const bench_scene_results *r);
/// bench-scene.csv: a header and one line per row.
void bench_scene_write_csv(FILE *f, const bench_scene_results *r);

void bench_scene_free(bench_scene_results *r);

#endif /* TTD_BENCH_SCENE_BENCH_H */
