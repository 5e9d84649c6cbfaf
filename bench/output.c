/* SPDX-License-Identifier: MIT */
/* The three forms of `ttd bench` results: a table for the terminal (with the machine header
 * and a summary against FCL), JSON (a header object and one object per row) and CSV (one
 * line per row, the same fields as the JSON rows). Values that do not apply are "-" in the
 * table, null in the JSON and empty in the CSV. */
#include "bench_internal.h"
#include "rows.h"
#include "json.h"
#include "output.h"
#include "mesh_bench.h"
#include "deform_bench.h"
#include "scene_bench.h"

#include <math.h>
#include <string.h>

#ifndef TTD_C_COMPILER
#define TTD_C_COMPILER "unknown"
#endif
#ifndef TTD_C_FLAGS
#define TTD_C_FLAGS ""
#endif
/* Flags the build adds on top of CMAKE_C_FLAGS for every file, and per instruction set. */
#define BENCH_EXTRA_FLAGS "-ffp-contract=off; src/isa/*.c add their -m flags (-msse2 / -mavx2 -mfma / -mavx512f -mavx512dq -mavx512vl)"

static const char *prec_name(int bytes) { return bytes == 8 ? "double" : "float"; }

/* A number with %.*g, or "-" when not a number. */
static const char *num(char *buf, size_t size, double v, const char *fmt)
{
    if (!isfinite(v))
        snprintf(buf, size, "%s", isinf(v) ? "inf" : "-");
    else
        snprintf(buf, size, fmt, v);
    return buf;
}

static void header_lines(FILE *f, const char *prefix, const bench_machine *m, const bench_settings *st)
{
    char a[32], b[32], c[32], d[32];
    fprintf(f, "%sttd bench, ttd %s%s\n", prefix, ttd_version_string(), st->quick ? " (--quick)" : "");
    fprintf(f, "%scommand: %s\n", prefix, st->command);
    fprintf(f, "%sCPU: %s, %d cores, %.1f GiB; %s\n", prefix, m->cpu, m->cores, m->mem_gib, m->os);
    fprintf(f, "%sCPU SIMD flags: %s\n", prefix, m->cpu_isas);
    fprintf(f, "%sload average (1, 5, 15 min): %s at the start, %s at the end; priority: %s\n", prefix,
            m->load_start, m->load_end, m->priority);
    if (bench_load_exceeds_cores(m))
        fprintf(f, "%sWARNING: the 1-minute load average (%s at the start, %s at the end) exceeds the %d online "
                   "cores: other work competed for the CPU, the timings are not to be trusted\n",
                prefix, num(a, sizeof a, m->load1_start, "%.2f"), num(b, sizeof b, m->load1_end, "%.2f"), m->cores);
    fprintf(f, "%sttd instruction sets built and runnable: %s (auto picks %s)\n", prefix, m->ttd_isas, m->isa_auto);
    fprintf(f, "%scompiler: %s; flags: %s; plus %s\n", prefix, TTD_C_COMPILER, TTD_C_FLAGS, BENCH_EXTRA_FLAGS);
    fprintf(f, "%sprobes: clock ~%s GHz (dependent adds); peak double GFLOP/s on one core: scalar %s, sse2 %s, "
               "avx2 %s",
            prefix, num(a, sizeof a, m->ghz, "%.2f"), num(b, sizeof b, m->peak_gflops_d[TTD_ISA_SCALAR], "%.1f"),
            num(c, sizeof c, m->peak_gflops_d[TTD_ISA_SSE2], "%.1f"),
            num(d, sizeof d, m->peak_gflops_d[TTD_ISA_AVX2], "%.1f"));
    fprintf(f, ", avx512 %s (float: twice)\n", num(a, sizeof a, m->peak_gflops_d[TTD_ISA_AVX512], "%.1f"));
    fprintf(f, "%smemory: copy %s GB/s on 1 thread, %s GB/s on %d; read %s GB/s on 1 thread, %s GB/s on %d "
               "(bytes read + written)\n",
            prefix, num(a, sizeof a, m->copy_gbs[0], "%.1f"), num(b, sizeof b, m->copy_gbs[1], "%.1f"), m->cores,
            num(c, sizeof c, m->read_gbs[0], "%.1f"), num(d, sizeof d, m->read_gbs[1], "%.1f"), m->cores);
    fprintf(f, "%stiming: one warm-up pass, then the median of %d samples of at least %g s each; every ratio "
               "is between rows of this run\n",
            prefix, st->samples, st->min_sample_s);
    fprintf(f, "%sFCL (fcl::detail::TriangleDistance<S>::triDistance): %s\n", prefix, st->fcl);
    fprintf(f, "%smesh pair workloads: %s\n", prefix, st->pair_mesh);
}

void bench_write_table(FILE *f, const bench_machine *m, const bench_settings *st, const bench_row *rows, size_t n)
{
    char b[12][32];
    header_lines(f, "", m, st);
    fprintf(f, "\n%-20s %-11s %-6s %-6s %3s %9s %9s %8s %8s %6s %7s %9s %9s %8s %8s %7s %6s %5s\n", "workload", "method",
            "prec", "isa", "thr", "pairs", "ns/pair", "Mpairs/s", "x_scalar", "lanes%", "x_fcl", "max_rel",
            "p99.9_rel", "disagree", "not_conv", "fallbk", "iters", "occ");
    const char *last = "";
    for (size_t i = 0; i < n; ++i) {
        const bench_row *r = &rows[i];
        if (strcmp(last, r->workload) != 0 && i > 0)
            fputc('\n', f);
        last = r->workload;
        char dis[24] = "-", nc[24] = "-", fb[24] = "-";
        if (r->has_accuracy) {
            snprintf(dis, sizeof dis, "%zu", r->disagree);
            snprintf(nc, sizeof nc, "%zu", r->not_converged);
            if (strcmp(r->method, "certified") == 0)
                snprintf(fb, sizeof fb, "%zu", r->fallback);
        }
        fprintf(f, "%-20s %-11s %-6s %-8s %3d %9zu %9s %8s %8s %6s %7s %9s %9s %8s %8s %7s %6s %5s\n",
                r->workload, r->method, prec_name(r->bytes), r->isa, r->threads, r->pairs,
                num(b[0], 32, r->ns_per_pair, r->ns_per_pair < 100 ? "%.2f" : "%.1f"),
                num(b[1], 32, r->pairs_per_s * 1e-6, "%.2f"), num(b[2], 32, r->speedup_vs_scalar, "%.2f"),
                num(b[3], 32, r->lanes > 1 || r->threads > 1 ? 100.0 * r->lane_fraction : BENCH_NAN, "%.0f%%"),
                num(b[4], 32, strcmp(r->method, "fcl") ? r->speedup_vs_fcl : BENCH_NAN, "%.2f"),
                num(b[5], 32, r->max_rel_err, "%.2g"), num(b[6], 32, r->p999_rel_err, "%.2g"), dis, nc, fb,
                num(b[7], 32, r->mean_iterations, "%.2f"), num(b[8], 32, r->occupancy, "%.2f"));
    }

    /* Summary: ttd's exact method (fastest ISA, one thread) against FCL, per workload. */
    int any = 0;
    for (size_t i = 0; i < n; ++i) {
        const bench_row *fcl = &rows[i], *best = NULL;
        if (strcmp(fcl->method, "fcl") != 0)
            continue;
        for (size_t j = 0; j < n; ++j) {
            const bench_row *r = &rows[j];
            if (strcmp(r->workload, fcl->workload) == 0 && r->bytes == fcl->bytes && r->threads == 1 &&
                strcmp(r->method, "exact") == 0 && (!best || r->ns_per_pair < best->ns_per_pair))
                best = r;
        }
        if (!any)
            fprintf(f, "\nttd's exact method (fastest ISA, 1 thread) against FCL on the same pairs; "
                       "disagree = relative difference > %g (double) / %g (float):\n",
                    bench_disagree_tol(8), bench_disagree_tol(4));
        any = 1;
        fprintf(f, "  %-20s %-6s FCL %8s ns/pair, ttd %8s ns/pair (%s): speedup over FCL %sx; FCL disagrees on %zu of %zu "
                   "pairs, worst relative %s, absolute %s\n",
                fcl->workload, prec_name(fcl->bytes), num(b[0], 32, fcl->ns_per_pair, "%.1f"),
                best ? num(b[1], 32, best->ns_per_pair, "%.2f") : "-", best ? best->isa : "-",
                best ? num(b[2], 32, fcl->ns_per_pair / best->ns_per_pair, "%.1f") : "-",
                fcl->has_accuracy ? fcl->disagree : 0, fcl->pairs, num(b[3], 32, fcl->max_rel_err, "%.3g"),
                num(b[4], 32, fcl->max_abs_err, "%.3g"));
    }
    fprintf(f, "\ncolumns: x_scalar = time of the scalar row (same workload, method, precision, 1 thread) / this "
               "row; lanes%% = x_scalar / (lanes x threads); x_fcl = FCL time / this row; max_rel, p99.9_rel = "
               "error against the exact method in double on the same input, relative to max(distance, longest "
               "edge); not_conv = pairs flagged not converged; fallbk = certified pairs that failed the check and "
               "were computed by the exact method; iters = mean iterations; occ = lane occupancy "
               "(mean iterations / mean of each lane-block's maximum).\n");
    if (st->mesh)
        bench_mesh_write_table(f, st->mesh);
    if (st->scene)
        bench_scene_write_table(f, st->scene);
    if (st->deform)
        bench_deform_write_table(f, st->deform);
}

static void json_num(FILE *f, const char *key, double v)
{
    if (isfinite(v))
        fprintf(f, ", \"%s\": %.6g", key, v);
    else
        fprintf(f, ", \"%s\": null", key);
}

void bench_write_json(FILE *f, const bench_machine *m, const bench_settings *st, const bench_row *rows, size_t n)
{
    fprintf(f, "{\n  \"tool\": \"ttd bench\",\n  \"version\": ");
    bench_json_string(f, ttd_version_string());
    fprintf(f, ",\n  \"command\": ");
    bench_json_string(f, st->command);
    fprintf(f, ",\n  \"machine\": {\"cpu\": ");
    bench_json_string(f, m->cpu);
    fprintf(f, ", \"cores\": %d, \"memory_gib\": %.1f, \"os\": ", m->cores, m->mem_gib);
    bench_json_string(f, m->os);
    fprintf(f, ", \"load_average_start\": ");
    bench_json_string(f, m->load_start);
    fprintf(f, ", \"load_average_end\": ");
    bench_json_string(f, m->load_end);
    fprintf(f, ", \"load_exceeds_cores\": %s", bench_load_exceeds_cores(m) ? "true" : "false");
    fprintf(f, ", \"priority\": ");
    bench_json_string(f, m->priority);
    fprintf(f, ", \"cpu_simd_flags\": ");
    bench_json_string(f, m->cpu_isas);
    fprintf(f, ", \"ttd_isas\": ");
    bench_json_string(f, m->ttd_isas);
    fprintf(f, ", \"isa_auto\": ");
    bench_json_string(f, m->isa_auto);
    fprintf(f, ",\n              \"compiler\": ");
    bench_json_string(f, TTD_C_COMPILER);
    fprintf(f, ", \"flags\": ");
    bench_json_string(f, TTD_C_FLAGS " + " BENCH_EXTRA_FLAGS);
    fprintf(f, ",\n              \"probes\": {\"clock_ghz\": ");
    if (isfinite(m->ghz))
        fprintf(f, "%.6g", m->ghz);
    else
        fprintf(f, "null");
    for (int i = TTD_ISA_SCALAR; i < TTD_ISA_COUNT; ++i) {
        char key[48];
        snprintf(key, sizeof key, "peak_gflops_double_%s", ttd_isa_name((ttd_isa)i));
        json_num(f, key, m->peak_gflops_d[i]);
    }
    json_num(f, "copy_gbs_1_thread", m->copy_gbs[0]);
    json_num(f, "copy_gbs_all_cores", m->copy_gbs[1]);
    json_num(f, "read_gbs_1_thread", m->read_gbs[0]);
    json_num(f, "read_gbs_all_cores", m->read_gbs[1]);
    fprintf(f, "}},\n  \"settings\": {\"quick\": %s, \"samples\": %d, \"min_sample_s\": %g, \"seed\": %llu, "
               "\"disagree_tol_double\": %g, \"disagree_tol_float\": %g, \"fcl\": ",
            st->quick ? "true" : "false", st->samples, st->min_sample_s, st->seed, bench_disagree_tol(8),
            bench_disagree_tol(4));
    bench_json_string(f, st->fcl);
    fprintf(f, ", \"pair_mesh\": ");
    bench_json_string(f, st->pair_mesh);
    fprintf(f, "},\n  \"rows\": [\n");
    for (size_t i = 0; i < n; ++i) {
        const bench_row *r = &rows[i];
        fprintf(f, "    {\"workload\": ");
        bench_json_string(f, r->workload);
        fprintf(f, ", \"method\": ");
        bench_json_string(f, r->method);
        fprintf(f, ", \"precision\": \"%s\", \"isa\": ", prec_name(r->bytes));
        bench_json_string(f, r->isa);
        fprintf(f, ", \"lanes\": %d, \"threads\": %d, \"pairs\": %zu, \"samples\": %d, \"passes\": %ld", r->lanes,
                r->threads, r->pairs, r->samples, r->passes);
        json_num(f, "ns_per_pair", r->ns_per_pair);
        json_num(f, "ns_per_pair_min", r->ns_min);
        json_num(f, "pairs_per_s", r->pairs_per_s);
        json_num(f, "speedup_vs_scalar", r->speedup_vs_scalar);
        json_num(f, "lane_fraction", r->lane_fraction);
        json_num(f, "thread_speedup", r->thread_speedup);
        json_num(f, "speedup_vs_fcl", r->speedup_vs_fcl);
        json_num(f, "max_rel_err", r->has_accuracy ? r->max_rel_err : BENCH_NAN);
        json_num(f, "p999_rel_err", r->has_accuracy ? r->p999_rel_err : BENCH_NAN);
        json_num(f, "max_abs_err", r->has_accuracy ? r->max_abs_err : BENCH_NAN);
        if (r->has_accuracy)
            fprintf(f, ", \"disagree\": %zu, \"not_converged\": %zu, \"fallback\": %zu", r->disagree,
                    r->not_converged, r->fallback);
        else
            fprintf(f, ", \"disagree\": null, \"not_converged\": null, \"fallback\": null");
        json_num(f, "mean_iterations", r->mean_iterations);
        json_num(f, "occupancy", r->occupancy);
        fprintf(f, "}%s\n", i + 1 < n ? "," : "");
    }
    fprintf(f, "  ]");
    if (st->mesh) {
        fprintf(f, ",\n  \"mesh\": ");
        bench_mesh_write_json(f, st->mesh);
    }
    if (st->deform) {
        fprintf(f, ",\n  \"deform\": ");
        bench_deform_write_json(f, st->deform);
    }
    if (st->scene) {
        fprintf(f, ",\n  \"scene\": ");
        bench_scene_write_json(f, st->scene);
    }
    fprintf(f, "\n}\n");
}

static void csv_num(FILE *f, double v)
{
    if (isfinite(v))
        fprintf(f, ",%.6g", v);
    else
        fputc(',', f);
}

void bench_write_csv(FILE *f, const bench_row *rows, size_t n)
{
    fprintf(f, "workload,method,precision,isa,lanes,threads,pairs,samples,ns_per_pair,ns_per_pair_min,pairs_per_s,"
               "speedup_vs_scalar,lane_fraction,thread_speedup,speedup_vs_fcl,max_rel_err,p999_rel_err,"
               "max_abs_err,disagree,not_converged,fallback,mean_iterations,occupancy\n");
    for (size_t i = 0; i < n; ++i) {
        const bench_row *r = &rows[i];
        fprintf(f, "%s,%s,%s,%s,%d,%d,%zu,%d", r->workload, r->method, prec_name(r->bytes), r->isa, r->lanes,
                r->threads, r->pairs, r->samples);
        csv_num(f, r->ns_per_pair);
        csv_num(f, r->ns_min);
        csv_num(f, r->pairs_per_s);
        csv_num(f, r->speedup_vs_scalar);
        csv_num(f, r->lane_fraction);
        csv_num(f, r->thread_speedup);
        csv_num(f, r->speedup_vs_fcl);
        csv_num(f, r->has_accuracy ? r->max_rel_err : BENCH_NAN);
        csv_num(f, r->has_accuracy ? r->p999_rel_err : BENCH_NAN);
        csv_num(f, r->has_accuracy ? r->max_abs_err : BENCH_NAN);
        if (r->has_accuracy)
            fprintf(f, ",%zu,%zu,%zu", r->disagree, r->not_converged, r->fallback);
        else
            fputs(",,,", f);
        csv_num(f, r->mean_iterations);
        csv_num(f, r->occupancy);
        fputc('\n', f);
    }
}
