/* SPDX-License-Identifier: MIT */
/* Output pieces shared by the benchmark's writers: the top-level ones (bench/output.c) and each
 * section's (mesh_bench.c, scene_bench.c, deform_bench.c). It sits below all of them and
 * includes none. */
#ifndef TTD_BENCH_JSON_H
#define TTD_BENCH_JSON_H

#include <stddef.h>
#include <stdio.h>

/// Writes s as a JSON string literal (quotes, backslashes and control characters escaped).
void bench_json_string(FILE *f, const char *s);

/// v printed with fmt into buf (size bytes), or "-" when v is not finite (a table's cell);
/// returns buf.
const char *bench_num(char *buf, size_t size, double v, const char *fmt);

/// For a ratio x = the other's time / ttd's: when x < 1 (the other library was faster), writes
/// "OTHER faster: ttd took N.NNx its time" into buf, else "" (finite x only); returns buf. A row or
/// target line where ttd lost says so in words, not only by a ratio below 1.
const char *bench_slower_note(char *buf, size_t size, double x, const char *other);

#endif /* TTD_BENCH_JSON_H */
