/* SPDX-License-Identifier: MIT */
/* Times the primitive search (ttd_ccd_query, src/ccd/) on CCD-benchmark CSV files, one thread, so
 * that any two versions of the search can be compared on the same queries without building the
 * whole program (docs/ccd-speed.md, "The step through the layers"). Built by hand against one
 * version's src/ccd/ (its ccd.c, and ccd_exact.c where it has one; src/ccd of today compiles
 * ccd.c alone, which includes the rest):
 *
 *   V=<a tree of that version>; cc -O3 -ffp-contract=off -I$V/src -I$V/include bench/ccd_search/ccd_csv_time.c \
 *      $V/src/ccd/ccd.c [$V/src/ccd/ccd_exact.c] -lm -o ccd_csv_time
 *   ./ccd_csv_time [-r REPS] [-s T_STOP] FILE.csv...
 *
 * A file's kind is taken from its path (vertex-face or edge-edge). Prints per file: queries, hits,
 * intervals, the CPU time of the fastest of REPS passes (default 3), mean per query, and a digest
 * of every answer (FNV-1a over hit, flags, the bits of toi and gap, and evals), so that two
 * versions' answers can be compared bit for bit. T_STOP:
 * the params' t_stop (default HUGE_VAL), as the mesh query sets it once it has a hit (its earliest
 * toi + the tolerance: 0.116945 + 2^-20 or so on the step through the layers); versions of the
 * search before t_stop existed ignore it (their params struct lacks it: build with -DNO_T_STOP). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ccd/ccd.h"
#include "ccd_digest.h"

static double cpu(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* 8 rows a query: x, y, z as numerator,denominator, then the truth; read as doubles (num / den). */
static size_t read_csv(const char *path, double **x0, double **x1)
{
    FILE *f = fopen(path, "r");
    if (f == NULL)
        return 0;
    size_t n = 0, cap = 0, row = 0;
    char line[1024];
    double q[24];
    *x0 = *x1 = NULL;
    while (fgets(line, sizeof line, f)) {
        double v[7];
        if (sscanf(line, "%lf,%lf,%lf,%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &v[6]) != 7)
            continue;
        for (int k = 0; k < 3; ++k)
            q[3 * row + k] = v[2 * k] / v[2 * k + 1];
        if (++row < 8)
            continue;
        row = 0;
        if (n == cap) {
            cap = cap ? 2 * cap : 1024;
            double *a = realloc(*x0, cap * 12 * sizeof *a), *b = a ? realloc(*x1, cap * 12 * sizeof *b) : NULL;
            if (a)
                *x0 = a;
            if (b == NULL)
                break;
            *x1 = b;
        }
        memcpy(*x0 + 12 * n, q, 12 * sizeof *q);
        memcpy(*x1 + 12 * n, q + 12, 12 * sizeof *q);
        ++n;
    }
    fclose(f);
    return n;
}

int main(int argc, char **argv)
{
    int reps = 3, i = 1;
    double t_stop = HUGE_VAL;
    while (i + 1 < argc && argv[i][0] == '-') {
        if (strcmp(argv[i], "-r") == 0)
            reps = atoi(argv[i + 1]);
        else if (strcmp(argv[i], "-s") == 0)
            t_stop = atof(argv[i + 1]);
        i += 2;
    }
    for (; i < argc; ++i) {
        const int kind = strstr(argv[i], "vertex-face") ? TTD_CCD_VF : TTD_CCD_EE;
        double *x0, *x1;
        const size_t n = read_csv(argv[i], &x0, &x1);
        if (n == 0) {
            fprintf(stderr, "%s: no queries\n", argv[i]);
            continue;
        }
        ttd_ccd_params p = ttd_ccd_default_params();
#ifndef NO_T_STOP
        p.t_stop = t_stop;
#endif
        double best = HUGE_VAL;
        size_t hits = 0;
        unsigned long long evals = 0;
        uint64_t digest = 0;
        for (int r = 0; r < reps; ++r) {
            hits = 0;
            evals = 0;
            digest = CCD_DIGEST_START;
            const double c0 = cpu();
            for (size_t k = 0; k < n; ++k) {
                ttd_ccd_result o;
                ttd_ccd_query(kind, x0 + 12 * k, x1 + 12 * k, &p, &o);
                hits += o.hit;
                evals += o.evals;
                digest = ccd_digest_answer(digest, &o);
            }
            const double c = cpu() - c0;
            best = c < best ? c : best;
        }
        printf("%s: %zu queries (%s), %zu hits, %llu intervals, %.3f ms CPU, %.3f us a query, digest %016llx\n", argv[i],
               n, kind == TTD_CCD_VF ? "vertex-face" : "edge-edge", hits, evals, best * 1e3, best * 1e6 / (double)n,
               (unsigned long long)digest);
        free(x0);
        free(x1);
    }
    return 0;
}
