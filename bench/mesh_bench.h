/* SPDX-License-Identifier: MIT */
/* The mesh-query section of `ttd bench` (issue 9): ttd's mesh queries (minimum distance,
 * collision with and without a margin, contacts within a margin, the per-triangle reduction,
 * many poses in one call, tree builds) timed beside FCL 0.7's on the same meshes and poses, with
 * the speed targets printed next to the measured ratios. bench/bench.c only parses the
 * options through bench_mesh_option(), runs the section and hands the results to the writers;
 * everything else is in bench/mesh_bench.c. docs/benchmark.md describes the workloads. */
#ifndef TTD_BENCH_MESH_BENCH_H
#define TTD_BENCH_MESH_BENCH_H

#include <stddef.h>
#include <stdio.h>

#include "bench_internal.h"
#include "rows.h"
#include "meshes.h"

/// What the command line asked of the mesh section.
typedef struct bench_mesh_config {
    int disabled;          ///< --no-mesh
    unsigned named;        ///< workloads named in --mesh-workloads (bit i = workload i); 0: none named
    char bunny[1024];      ///< --bunny PATH ("" = $TTD_BUNNY or the default places)
    char fcl_mesh[1024];   ///< --fcl-mesh PATH ("" = $TTD_FCL_MESH_BENCH or next to ttd)
} bench_mesh_config;

/// What the rest of the benchmark decided, for the mesh section.
typedef struct bench_mesh_env {
    const bench_settings *st; ///< quick, samples, minimum sample time, seed
    int max_threads;          ///< --threads (the many-poses rows use 1, 2 and this many)
    unsigned isa_mask;        ///< --isa (bit i = ttd_isa i): the best of these runs every mesh row
    int no_fcl;               ///< --no-fcl
    int want_double, want_float; ///< --precision
    int quiet;
    double t_start;           ///< bench_now() at the start, for the progress lines
} bench_mesh_env;

/// The measured rows, the targets and the checks (opaque).
typedef struct bench_mesh_results bench_mesh_results;

/// Parses one option of the mesh section: a is the option, v the next argument (NULL at the
/// end). Returns 0 when a is not a mesh option, 1 when it was a flag, 2 when it consumed v, and
/// -1 (after a message on standard error) when its value is bad.
int bench_mesh_option(bench_mesh_config *c, const char *a, const char *v);
/// The mesh options' lines of `ttd bench --help`.
void bench_mesh_usage(FILE *f);
/// Whether the section runs: not with --no-mesh; by default yes, unless --workloads named the
/// pair workloads and --mesh-workloads named none.
int bench_mesh_wanted(const bench_mesh_config *c, int pair_workloads_named);

/// Runs the section. Never fails because of a target or a disagreement (those are reported);
/// returns NULL only when it could not allocate its results.
bench_mesh_results *bench_mesh_run(const bench_mesh_config *c, const bench_mesh_env *env);
/// Rows measured (0 for NULL).
size_t bench_mesh_row_count(const bench_mesh_results *r);

/// The section of the text table (after the pair rows).
void bench_mesh_write_table(FILE *f, const bench_mesh_results *r);
/// The value of the "mesh" member of bench.json (an object).
void bench_mesh_write_json(FILE *f, const bench_mesh_results *r);
/// bench-mesh.csv: a header and one line per row (the figure bench/plot-mesh.gp reads it).
void bench_mesh_write_csv(FILE *f, const bench_mesh_results *r);

void bench_mesh_free(bench_mesh_results *r);

/// The Stanford bunny where the section finds it (--bunny, $TTD_BUNNY, build/data/bunny.obj,
/// data/bunny.obj beside ttd's folder), normalised to a bounding-box diagonal of 1. Returns 0 with
/// what (the file and its size), or -1 with what saying why it is missing (the scene section
/// uses it too).
int bench_mesh_load_bunny(const bench_mesh_config *c, ttd_gen_mesh *out, char *what, size_t size);

#endif /* TTD_BENCH_MESH_BENCH_H */
