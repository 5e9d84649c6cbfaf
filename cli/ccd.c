/* SPDX-License-Identifier: MIT */
/* `ttd ccd FILE`: continuous collision of the queries in a CCD-benchmark CSV file (docs/ccd.md,
 * section 5), and the reader that `ttd bench ccd` shares. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli.h"

static const char ccd_usage[] =
    "usage: ttd ccd [options] FILE\n"
    "Continuous collision of the queries in FILE, a CSV file of the CCD benchmark's format: 8\n"
    "rows a query, each row x, y, z as numerator,denominator pairs and a last column, the truth\n"
    "(0 or 1). Vertex-face rows: v, f0, f1, f2 at t = 0, then at t = 1; edge-edge rows: ea0,\n"
    "ea1, eb0, eb1 at t = 0, then at t = 1. The kind comes from the path (vertex-face or\n"
    "edge-edge in it) or --kind. Rationals are rounded to the nearest double (the benchmark's\n"
    "are all doubles exactly; others are counted as inexact).\n"
    "options:\n"
    "  --kind vf|ee             the query kind (default: from the path)\n"
    "  --min-separation D       report distances of D or less (default 0)\n"
    "  --threads N              worker threads (default 0: all cores)\n"
    "  --summary                only the totals, not a line per query\n"
    "output: a line per query 'i hit toi truth gap evals' (toi inf without a hit), then the totals: queries,\n"
    "hits, false negatives and positives against the file's truth, time.\n";

/* A decimal integer as the nearest double; *exact when that double is the integer itself (glibc
 * prints doubles' integer values exactly). */
static int parse_integer(const char *s, double *out, int *exact)
{
    char *end;
    const char *p = s + (*s == '-' || *s == '+');
    if (*p < '0' || *p > '9')
        return -1;
    *out = strtod(s, &end);
    if (end == s || !isfinite(*out))
        return -1;
    char buf[400];
    snprintf(buf, sizeof buf, "%.0f", fabs(*out));
    while (*p == '0' && p[1] != '\0')
        ++p;
    *exact = strcmp(buf, p) == 0;
    return 0;
}

/* One numerator/denominator pair as the nearest double (the benchmark's denominators run past
 * 2^64, so both are read as doubles); *inexact set when the value is not exact. */
static int parse_rational(const char *num, const char *den, double *out, int *inexact)
{
    double dn, dd;
    int en, ed;
    if (parse_integer(num, &dn, &en) != 0 || parse_integer(den, &dd, &ed) != 0 || dd == 0)
        return -1;
    *out = dn / dd;
    if (!en || !ed || *out * dd != dn)
        *inexact = 1;
    return 0;
}

int ttd_cli_ccd_read(const char *path, int kind_hint, int *kind, size_t *nq, double **x0, double **x1,
                     int **truth, size_t *inexact)
{
    if (kind_hint != 0)
        *kind = kind_hint;
    else if (strstr(path, "vertex-face") != NULL)
        *kind = 1;
    else if (strstr(path, "edge-edge") != NULL)
        *kind = 2;
    else {
        ttd_cli_error("ccd: cannot tell the kind of '%s' from its path: give --kind vf|ee", path);
        return -1;
    }
    FILE *f = fopen(path, "r");
    if (f == NULL) {
        ttd_cli_error("ccd: cannot open '%s'", path);
        return -1;
    }
    size_t cap = 1024, rows = 0;
    double *xyz = malloc(cap * 3 * sizeof(double));
    int *tr = malloc(cap * sizeof(int));
    char line[1024];
    int bad = xyz == NULL || tr == NULL;
    *inexact = 0;
    while (!bad && fgets(line, sizeof line, f) != NULL) {
        if (line[0] == '\n' || line[0] == '\r' || line[0] == '\0')
            continue;
        char *fields[7];
        int nf = 0;
        for (char *tok = strtok(line, ",\r\n"); tok != NULL && nf < 8; tok = strtok(NULL, ",\r\n"))
            fields[nf < 7 ? nf : 6] = tok, ++nf;
        if (nf != 7) {
            ttd_cli_error("ccd: %s: row %zu has %d fields, not 7", path, rows + 1, nf);
            bad = 1;
            break;
        }
        if (rows == cap) {
            cap *= 2;
            double *nx = realloc(xyz, cap * 3 * sizeof(double));
            int *nt = realloc(tr, cap * sizeof(int));
            if (nx != NULL)
                xyz = nx;
            if (nt != NULL)
                tr = nt;
            if (nx == NULL || nt == NULL) {
                bad = 1;
                break;
            }
        }
        int ix = 0;
        for (int k = 0; k < 3; ++k)
            if (parse_rational(fields[2 * k], fields[2 * k + 1], &xyz[rows * 3 + (size_t)k], &ix) != 0) {
                ttd_cli_error("ccd: %s: row %zu: bad rational", path, rows + 1);
                bad = 1;
            }
        if (ix)
            ++*inexact;
        tr[rows] = atoi(fields[6]);
        ++rows;
    }
    fclose(f);
    if (!bad && rows % 8 != 0) {
        ttd_cli_error("ccd: %s: %zu rows, not a multiple of 8", path, rows);
        bad = 1;
    }
    if (!bad && rows == 0) {
        ttd_cli_error("ccd: %s: no queries", path);
        bad = 1;
    }
    if (bad) {
        free(xyz);
        free(tr);
        return -1;
    }
    const size_t n = rows / 8;
    *x0 = malloc(n * 12 * sizeof(double));
    *x1 = malloc(n * 12 * sizeof(double));
    *truth = malloc(n * sizeof(int));
    if (*x0 == NULL || *x1 == NULL || *truth == NULL) {
        free(*x0), free(*x1), free(*truth), free(xyz), free(tr);
        ttd_cli_error("ccd: out of memory");
        return -1;
    }
    for (size_t q = 0; q < n; ++q) {
        memcpy(*x0 + q * 12, xyz + q * 24, 12 * sizeof(double));
        memcpy(*x1 + q * 12, xyz + q * 24 + 12, 12 * sizeof(double));
        (*truth)[q] = tr[q * 8] != 0;
    }
    *nq = n;
    free(xyz);
    free(tr);
    return 0;
}

int ttd_cli_ccd_run(const ttd_options *o, int kind, size_t n, const double *x0, const double *x1,
                    double delta, ttd_ccd_result *out)
{
    /* The query arrays hold 4 points a query; split into the API's two primitives. */
    const int na = kind, nb = 4 - kind;
    double *a0 = malloc(n * 3 * (size_t)na * sizeof(double)), *b0 = malloc(n * 3 * (size_t)nb * sizeof(double));
    double *a1 = malloc(n * 3 * (size_t)na * sizeof(double)), *b1 = malloc(n * 3 * (size_t)nb * sizeof(double));
    ttd_status st = TTD_ERR_OUT_OF_MEMORY;
    if (a0 != NULL && b0 != NULL && a1 != NULL && b1 != NULL) {
        for (size_t q = 0; q < n; ++q) {
            memcpy(a0 + q * 3 * (size_t)na, x0 + q * 12, 3 * (size_t)na * sizeof(double));
            memcpy(b0 + q * 3 * (size_t)nb, x0 + q * 12 + 3 * na, 3 * (size_t)nb * sizeof(double));
            memcpy(a1 + q * 3 * (size_t)na, x1 + q * 12, 3 * (size_t)na * sizeof(double));
            memcpy(b1 + q * 3 * (size_t)nb, x1 + q * 12 + 3 * na, 3 * (size_t)nb * sizeof(double));
        }
        st = kind == 1 ? ttd_ccd_vertex_face_d(o, n, a0, b0, a1, b1, delta, out)
                       : ttd_ccd_edge_edge_d(o, n, a0, b0, a1, b1, delta, out);
    }
    free(a0), free(b0), free(a1), free(b1);
    return (int)st;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int ttd_cli_ccd(int argc, char **argv)
{
    static const char *const flags[] = {"--summary", NULL};
    static const char *const valued[] = {"--kind", "--min-separation", "--threads", NULL};
    ttd_options o = ttd_default_options();
    const char *path = NULL;
    int kind = 0, summary = 0;
    double delta = 0;
    ttd_cli_args w = ttd_cli_args_start("ccd", flags, valued, argc, argv);
    w.long_only = 1;
    for (ttd_cli_arg k; (k = ttd_cli_next_arg(&w)) != TTD_ARG_END;) {
        if (k == TTD_ARG_BAD || k == TTD_ARG_HELP)
            return ttd_cli_stop_status(k, ccd_usage);
        const char *opt = w.opt, *val = w.val;
        if (k == TTD_ARG_FLAG) {
            summary = 1;
        } else if (k == TTD_ARG_VALUE) {
            long v;
            if (strcmp(opt, "--kind") == 0 && (strcmp(val, "vf") == 0 || strcmp(val, "ee") == 0))
                kind = val[0] == 'v' ? 1 : 2;
            else if (strcmp(opt, "--min-separation") == 0 && ttd_cli_parse_real(val, &delta) == 0 && delta >= 0)
                ;
            else if (strcmp(opt, "--threads") == 0 && ttd_cli_parse_int(val, 0, 1 << 20, &v) == 0)
                o.threads = (int)v;
            else {
                ttd_cli_error("ccd: bad value '%s' for %s", val, opt);
                return TTD_EXIT_USAGE;
            }
        } else if (path != NULL) {
            ttd_cli_error("ccd: one FILE only (see ttd ccd --help)");
            return TTD_EXIT_USAGE;
        } else {
            path = w.arg;
        }
    }
    if (path == NULL) {
        fputs(ccd_usage, stderr);
        return TTD_EXIT_USAGE;
    }
    size_t n, inexact;
    double *x0, *x1;
    int *truth;
    if (ttd_cli_ccd_read(path, kind, &kind, &n, &x0, &x1, &truth, &inexact) != 0)
        return TTD_EXIT_INPUT;
    ttd_ccd_result *r = malloc(n * sizeof *r);
    int rc = TTD_EXIT_OK;
    if (r == NULL) {
        ttd_cli_error("ccd: out of memory");
        rc = TTD_EXIT_INPUT;
    } else {
        const double t0 = now_s();
        const int st = ttd_cli_ccd_run(&o, kind, n, x0, x1, delta, r);
        const double secs = now_s() - t0;
        if (st != TTD_OK && st != TTD_ERR_NONFINITE_INPUT) {
            ttd_cli_error("ccd: %s", ttd_status_string((ttd_status)st));
            rc = TTD_EXIT_INPUT;
        } else {
            size_t hits = 0, fn = 0, fp = 0, budget = 0, positives = 0;
            for (size_t q = 0; q < n; ++q) {
                hits += r[q].hit;
                positives += truth[q] != 0;
                fn += truth[q] && !r[q].hit;
                fp += !truth[q] && r[q].hit;
                budget += (r[q].flags & TTD_CCD_BUDGET) != 0;
                if (!summary)
                    printf("%zu %u %.17g %d %.3g %u\n", q, r[q].hit, r[q].toi, truth[q], r[q].gap, r[q].evals);
            }
            printf("queries %zu (%s), hits %zu, truth %zu, false negatives %zu, false positives %zu, "
                   "budget %zu, inexact rows %zu, time %.6f s (%.3f us a query)\n",
                   n, kind == 1 ? "vertex-face" : "edge-edge", hits, positives, fn, fp, budget, inexact,
                   secs, 1e6 * secs / (double)n);
            if (st == TTD_ERR_NONFINITE_INPUT)
                rc = TTD_EXIT_INPUT;
        }
    }
    free(r), free(x0), free(x1), free(truth);
    return rc;
}
