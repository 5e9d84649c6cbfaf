/* SPDX-License-Identifier: MIT */
/* The benchmark's writers (bench/output.c): the text table, JSON and CSV of a run. They sit
 * above the sections and below bench.c: they write the pair rows (rows.h) and call each
 * section's writers (mesh_bench.h, scene_bench.h); the sections use only what is below them
 * (bench_internal.h, rows.h, json.h), so no file of bench/ includes one that includes it back,
 * and no file calls into one that calls into it. */
#ifndef TTD_BENCH_OUTPUT_H
#define TTD_BENCH_OUTPUT_H

#include <stdio.h>

#include "bench_internal.h"
#include "rows.h"

void bench_write_table(FILE *f, const bench_machine *m, const bench_settings *st, const bench_row *rows, size_t n);
void bench_write_json(FILE *f, const bench_machine *m, const bench_settings *st, const bench_row *rows, size_t n);
void bench_write_csv(FILE *f, const bench_row *rows, size_t n);

#endif /* TTD_BENCH_OUTPUT_H */
