/* SPDX-License-Identifier: MIT */
/* The deforming-mesh section of `ttd bench` (issue 25, item 5), one thread:
 *   - refit against rebuild and against FCL's refit: tori of 10k, 100k and 1M triangles twisted
 *     back and forth; ttd_mesh_set_vertices_d (a refit) against ttd_mesh_create_d on the moved
 *     vertices (a rebuild), and FCL 0.7's BVHModel<OBBRSS> refit (beginUpdateModel /
 *     updateSubModel / endUpdateModel, bottom-up; bench/fcl/fcl_mesh_bench.cpp, query 3);
 *   - self-contacts per step on a folding sheet of 100k triangles (gen: ttd_gen_folded_sheet)
 *     against a uniform-grid brute force, the broad phase a user writes by hand (triangles'
 *     boxes hashed into cells, candidate pairs that share no vertex through the exact kernel);
 *     both answers compared pair for pair.
 * The targets are printed beside the measured figures. bench/bench.c parses the options
 * through bench_deform_option(), runs the section and hands the results to the writers;
 * docs/benchmark.md describes it. */
#ifndef TTD_BENCH_DEFORM_BENCH_H
#define TTD_BENCH_DEFORM_BENCH_H

#include <stdio.h>

#include "bench_internal.h"
#include "rows.h"

/// What the command line asked of the deforming-mesh section.
typedef struct bench_deform_config {
    int disabled; ///< --no-deform
    int only;     ///< --deform-only: the other sections are not run
    int refit_only; ///< --refit-only: --deform-only without the self-contact rows
    int self_only;  ///< --self-only: --deform-only without the refit rows
    int sheet7_only; ///< --sheet7-only: the self rows of issue 36's 7-layer sheet alone
    int no_self_grid; ///< --no-self-grid: the self rows without the grid brute force
} bench_deform_config;

/// What the rest of the benchmark decided, for this section.
typedef struct bench_deform_env {
    const bench_settings *st; ///< quick, samples
    int no_fcl;               ///< --no-fcl
    int quiet;
    double t_start;           ///< bench_now() at the start, for the progress lines
} bench_deform_env;

/// The measured rows (opaque).
typedef struct bench_deform_results bench_deform_results;

/// Parses one option of the section: 1 when a (flag) option was taken, 0 when a is not ours.
int bench_deform_option(bench_deform_config *c, const char *a);
/// The section's lines of `ttd bench --help`.
void bench_deform_usage(FILE *f);

/// Runs the section; NULL only when its results could not be allocated.
bench_deform_results *bench_deform_run(const bench_deform_config *c, const bench_deform_env *env);
/// Rows measured (0 for NULL).
size_t bench_deform_row_count(const bench_deform_results *r);

/// The section of the text table.
void bench_deform_write_table(FILE *f, const bench_deform_results *r);
/// The value of the "deform" member of bench.json (an object).
void bench_deform_write_json(FILE *f, const bench_deform_results *r);

void bench_deform_free(bench_deform_results *r);

#endif /* TTD_BENCH_DEFORM_BENCH_H */
