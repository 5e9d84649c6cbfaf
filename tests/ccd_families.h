/* SPDX-License-Identifier: MIT */
/* The continuous-collision tests' generated query families and the benchmark CSV reader, shared by
 * test_ccd.c, test_ccd_lanes.c and test_gpu_ccd.c. Include after test_rand.h (srand1, urand). */
#ifndef TTD_TESTS_CCD_FAMILIES_H
#define TTD_TESTS_CCD_FAMILIES_H

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum {
    F_RANDOM,
    F_NEAR_DEGENERATE,
    F_COPLANAR,
    F_PARALLEL,
    F_TOUCH_T1,
    F_TOUCH_T0,
    F_SCALED,
    F_OFFSET,
    F_DEGENERATE,
    F_STILL,
    F_HUGE,
    F_NONFINITE,
    F_AT_BOUND,
    F_COUNT
};
static const char *const family_name[F_COUNT] = {
    "random", "near-degenerate 1e-12", "coplanar motion", "parallel edges", "touching at t = 1",
    "touching at t = 0", "scaled 1e-8..1e8", "offset 1e6", "zero-length edges, zero-area faces", "no motion",
    "coordinates near 2^400", "non-finite",
    "apart by about the rounding bound"};

/* One query of a family (x0, x1: the four points at t = 0 and t = 1). */
static inline void gen(int fam, int kind, double x0[12], double x1[12])
{
    for (int i = 0; i < 12; ++i) {
        x0[i] = srand1();
        x1[i] = x0[i] + 0.5 * srand1();
    }
    const int b = 3 * kind; /* B's first point */
    switch (fam) {
    case F_NEAR_DEGENERATE: /* B's first point passes within 1e-12 of A's first point's path */
        for (int k = 0; k < 3; ++k) {
            x0[b + k] = x0[k] + 1e-12 * srand1();
            x1[b + k] = x1[k] + 1e-12 * srand1();
        }
        break;
    case F_COPLANAR:
        for (int i = 0; i < 4; ++i)
            x0[3 * i + 2] = x1[3 * i + 2] = 0;
        break;
    case F_PARALLEL: /* edge B = edge A shifted, each translating */
        for (int k = 0; k < 3; ++k) {
            const double s0 = 1e-3 * srand1(), s1 = 0.2 * srand1();
            x0[6 + k] = x0[k] + s0, x0[9 + k] = x0[3 + k] + s0;
            x1[k] = x0[k] + 0.3, x1[3 + k] = x0[3 + k] + 0.3;
            x1[6 + k] = x0[6 + k] + s1, x1[9 + k] = x0[9 + k] + s1;
        }
        break;
    case F_TOUCH_T1:
        for (int k = 0; k < 3; ++k)
            x1[b + k] = x1[k];
        break;
    case F_TOUCH_T0:
        for (int k = 0; k < 3; ++k)
            x0[b + k] = x0[k];
        break;
    case F_SCALED: {
        const double sc = pow(10.0, 8 * srand1());
        for (int i = 0; i < 12; ++i)
            x0[i] *= sc, x1[i] *= sc;
        break;
    }
    case F_OFFSET:
        for (int i = 0; i < 12; ++i)
            x0[i] += 1e6, x1[i] += 1e6;
        break;
    case F_DEGENERATE: /* two points of a primitive equal, or a face's three collinear */
        if (urand() < 0.5) {
            const int i = (int)(urand() * 4), j = (i + 1) % 4;
            memcpy(x0 + 3 * j, x0 + 3 * i, 3 * sizeof(double));
            memcpy(x1 + 3 * j, x1 + 3 * i, 3 * sizeof(double));
        } else {
            for (int k = 0; k < 3; ++k) {
                x0[9 + k] = 0.5 * (x0[3 + k] + x0[6 + k]);
                x1[9 + k] = 0.5 * (x1[3 + k] + x1[6 + k]);
            }
        }
        break;
    case F_STILL:
        memcpy(x1, x0, 12 * sizeof(double));
        break;
    case F_HUGE: { /* on both sides of the screen's limit TTD_CCD_SCREEN_MAX */
        const double sc = ldexp(1.0, 398 + (int)(urand() * 4));
        for (int i = 0; i < 12; ++i)
            x0[i] *= sc, x1[i] *= sc;
        break;
    }
    case F_NONFINITE:
        (urand() < 0.5 ? x0 : x1)[(int)(urand() * 12)] = urand() < 0.5 ? NAN : INFINITY;
        break;
    case F_AT_BOUND: { /* at t = 1 B's first point 2^-50..2^-44 S from A's first: the screen's rounding
                        * bound is 2^-47 S, so its decisions fall on both sides of it */
        const double eps = ldexp(1.0, -50 + (int)(urand() * 7)) * (1 + urand());
        for (int k = 0; k < 3; ++k)
            x1[b + k] = x1[k] + eps * srand1();
        break;
    }
    default:
        break;
    }
}

/* The queries of every family, kind 1 and 2: n each. */
typedef struct qset {
    int kind;
    size_t n;
    double *x0, *x1;
} qset;

static inline qset make_set(int fam, int kind, size_t n)
{
    qset s = {kind, n, malloc(n * 12 * sizeof(double)), malloc(n * 12 * sizeof(double))};
    for (size_t q = 0; q < n; ++q)
        gen(fam, kind, s.x0 + 12 * q, s.x1 + 12 * q);
    return s;
}

/* A benchmark CSV (8 rows a query, numerator,denominator pairs; the benchmark's denominators are
 * powers of two up to 2^110, read through strtod, exact for them): its queries into s (x0, x1, n),
 * and where truth is not NULL each query's truth (the last column of its first row) into a new array
 * *truth. */
static inline int read_csv_truth(const char *path, qset *s, int **truth)
{
    FILE *f = fopen(path, "r");
    if (f == NULL)
        return -1;
    size_t cap = 256, rows = 0;
    double *xyz = malloc(cap * 3 * sizeof(double));
    int *tr = malloc(cap * sizeof(int));
    char line[1024];
    while (fgets(line, sizeof line, f) != NULL) {
        if (line[0] == '\n')
            continue;
        if (rows == cap) {
            cap *= 2;
            xyz = realloc(xyz, cap * 3 * sizeof(double));
            tr = realloc(tr, cap * sizeof(int));
        }
        char *p = line;
        for (int k = 0; k < 3; ++k) {
            const double num = strtod(p, &p);
            ++p;
            const double den = strtod(p, &p);
            ++p;
            xyz[rows * 3 + (size_t)k] = num / den;
        }
        tr[rows] = (int)strtol(p, NULL, 10);
        ++rows;
    }
    fclose(f);
    s->n = rows / 8;
    s->x0 = malloc(s->n * 12 * sizeof(double) + 1);
    s->x1 = malloc(s->n * 12 * sizeof(double) + 1);
    if (truth != NULL)
        *truth = malloc(s->n * sizeof(int) + 1);
    for (size_t q = 0; q < s->n; ++q) {
        memcpy(s->x0 + 12 * q, xyz + 24 * q, 12 * sizeof(double));
        memcpy(s->x1 + 12 * q, xyz + 24 * q + 12, 12 * sizeof(double));
        if (truth != NULL)
            (*truth)[q] = tr[8 * q];
    }
    free(xyz), free(tr);
    return rows % 8 == 0 && s->n > 0 ? 0 : -1;
}

static inline int read_csv(const char *path, qset *s)
{
    return read_csv_truth(path, s, NULL);
}

/* Every CSV file under dir (recursively) whose path names its kind (vertex-face or edge-edge): fn on
 * its queries (the file's path, the set, ctx). Stops at the first nonzero answer of fn, or at a
 * file that cannot be read, and returns nonzero then; *files counts the files fn was given. */
typedef int (*csv_fn)(const char *path, const qset *s, void *ctx);
static inline int walk_csv(const char *dir, csv_fn fn, void *ctx, size_t *files)
{
    DIR *d = opendir(dir);
    if (d == NULL) {
        fprintf(stderr, "  missing %s\n", dir);
        return 1;
    }
    struct dirent *e;
    int bad = 0;
    while (!bad && (e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.')
            continue;
        char path[2048];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        const size_t len = strlen(path);
        if (len < 4 || strcmp(path + len - 4, ".csv") != 0) {
            DIR *sub = opendir(path);
            if (sub != NULL) {
                closedir(sub);
                bad = walk_csv(path, fn, ctx, files);
            }
            continue;
        }
        const int kind = strstr(path, "vertex-face") ? 1 : strstr(path, "edge-edge") ? 2 : 0;
        if (kind == 0)
            continue;
        qset s = {kind, 0, NULL, NULL};
        if (read_csv(path, &s) != 0) {
            fprintf(stderr, "  cannot read %s\n", path);
            bad = 1;
        } else {
            bad = fn(path, &s, ctx);
            ++*files;
        }
        free(s.x0), free(s.x1);
    }
    closedir(d);
    return bad;
}

#endif /* TTD_TESTS_CCD_FAMILIES_H */
