/* SPDX-License-Identifier: MIT */
/* JSON pieces shared by the benchmark's writers: the top-level ones (bench/output.c) and each
 * section's (mesh_bench.c, scene_bench.c). It sits below all of them and includes none. */
#ifndef TTD_BENCH_JSON_H
#define TTD_BENCH_JSON_H

#include <stdio.h>

/// Writes s as a JSON string literal (quotes, backslashes and control characters escaped).
void bench_json_string(FILE *f, const char *s);

#endif /* TTD_BENCH_JSON_H */
