/* SPDX-License-Identifier: MIT */
/* Continuous collision (src/ccd/, docs/ccd.md): the entries' checks; threads and precision;
 * constructed motions with known answers (degenerate ones included); every generated family
 * against the exact rational reference (tests/ccd_ref/, with GMP); the kept sample queries of
 * the CCD benchmark against their ground truth; triangle-triangle against its sub-queries. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_macros.h"
#include "ttd/ttd.h"
#ifdef TTD_HAVE_GMP
#include "ccd_ref.h"
#endif

/* The time tolerance of a toi against the true first time (docs/ccd.md, section 2). */
#define TOI_TOL 1e-6

#define TEST_RAND_SEED 0x9e3779b97f4a7c15ull
#include "test_rand.h"
#include "ccd_families.h"

/* A benchmark CSV (ccd_families.h's reader) as separate arrays: the queries and their truth. */
static int read_csv_arrays(const char *path, double **x0, double **x1, int **truth, size_t *nq)
{
    qset s = {0, 0, NULL, NULL};
    const int rc = read_csv_truth(path, &s, truth);
    *x0 = s.x0, *x1 = s.x1, *nq = s.n;
    return rc;
}

/* One query through the public entries: kind 1 vertex-face, 2 edge-edge; x0, x1 4 points. */
static ttd_ccd_result run1(int kind, const double x0[12], const double x1[12], double delta)
{
    ttd_ccd_result r;
    memset(&r, 0xff, sizeof r);
    const int na = kind;
    ttd_status st = kind == 1 ? ttd_ccd_vertex_face_d(NULL, 1, x0, x0 + 3 * na, x1, x1 + 3 * na, delta, &r)
                              : ttd_ccd_edge_edge_d(NULL, 1, x0, x0 + 3 * na, x1, x1 + 3 * na, delta, &r);
    if (st != TTD_OK)
        r.hit = 99;
    return r;
}

static int api_checks(void)
{
    double v[3] = {0, 0, 1}, f[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, v1[3] = {0.2, 0.2, -1};
    ttd_ccd_result r[2];
    ENSURE(ttd_ccd_vertex_face_d(NULL, 1, NULL, f, v1, f, 0, r) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_ccd_vertex_face_d(NULL, 1, v, f, v1, f, 0, NULL) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_ccd_vertex_face_d(NULL, 0, v, f, v1, f, 0, r) == TTD_ERR_EMPTY);
    ENSURE(ttd_ccd_vertex_face_d(NULL, 1, v, f, v1, f, -1, r) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_ccd_vertex_face_d(NULL, 1, v, f, v1, f, NAN, r) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_ccd_vertex_face_d(NULL, 1, v, f, v1, f, INFINITY, r) == TTD_ERR_BAD_OPTIONS);
    ttd_options bad;
    memset(&bad, 0, sizeof bad);
    ENSURE(ttd_ccd_edge_edge_d(&bad, 1, f, f, f, f, 0, r) == TTD_ERR_BAD_OPTIONS);
    ttd_options o = ttd_default_options();
    o.threads = -1;
    ENSURE(ttd_ccd_triangles_d(&o, 1, f, f, f, f, 0, r) == TTD_ERR_BAD_OPTIONS);
    /* A NaN in the second query: flagged; the first still computed (it hits at t = 0.5). */
    double v2[6] = {0.2, 0.2, 1, 0.2, 0.2, 1}, f2[18], v21[6] = {0.2, 0.2, -1, NAN, 0.2, -1};
    memcpy(f2, f, sizeof f);
    memcpy(f2 + 9, f, sizeof f);
    ENSURE(ttd_ccd_vertex_face_d(NULL, 2, v2, f2, v21, f2, 0, r) == TTD_ERR_NONFINITE_INPUT);
    ENSURE(r[0].hit == 1 && r[0].toi <= 0.5 && r[0].toi > 0.5 - TOI_TOL && r[0].flags == 0);
    ENSURE(r[1].hit == 0 && isnan(r[1].toi) && r[1].flags == TTD_CCD_NONFINITE);
    float vf[3] = {0.2f, 0.2f, 1}, ff[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, vf1[3] = {0.2f, 0.2f, INFINITY};
    ENSURE(ttd_ccd_vertex_face_f(NULL, 1, vf, ff, vf1, ff, 0, r) == TTD_ERR_NONFINITE_INPUT);
    ENSURE(r[0].flags == TTD_CCD_NONFINITE);
    return 0;
}

/* Random queries where about half hit: a point aimed at a random point of a random moving
 * triangle (or an edge at a point of another edge) at a random time, then perturbed. */
/* ends: 0 a contact time drawn in [0, 1); 1 at t = 1; 2 at t = 0 (touching at the ends, up to the
 * rounding of the aimed point, which the reference decides). */
static int gen_ends = 0;

static void gen_query(int kind, double scale, double offset, double x0[12], double x1[12])
{
    for (int i = 0; i < 12; ++i) {
        x0[i] = srand1();
        x1[i] = x0[i] + 0.5 * srand1();
    }
    if (urand() < 0.6) {
        /* Aim: point 0 (or point 0's edge) passes a point of B at time ts. */
        const double ts = gen_ends == 1 ? 1.0 : gen_ends == 2 ? 0.0 : urand();
        double w[4] = {urand(), urand(), urand(), 0};
        double c[3];
        if (kind == 1) {
            const double sw = w[0] + w[1] + w[2];
            for (int k = 0; k < 3; ++k)
                c[k] = 0;
            for (int j = 0; j < 3; ++j)
                for (int k = 0; k < 3; ++k)
                    c[k] += w[j] / sw * ((1 - ts) * x0[3 + 3 * j + k] + ts * x1[3 + 3 * j + k]);
            /* p(ts) = c: choose p1 from p0 (at ts = 0: p0 = c). */
            if (ts > 0.05)
                for (int k = 0; k < 3; ++k)
                    x1[k] = x0[k] + (c[k] - x0[k]) / ts;
            else if (ts == 0)
                for (int k = 0; k < 3; ++k)
                    x0[k] = c[k];
        } else {
            const double s = w[0], u = w[1];
            for (int k = 0; k < 3; ++k) {
                const double b = (1 - u) * ((1 - ts) * x0[6 + k] + ts * x1[6 + k]) + u * ((1 - ts) * x0[9 + k] + ts * x1[9 + k]);
                /* Edge A's point at s reaches b at ts: move both endpoints of A alike. */
                const double a = (1 - s) * ((1 - ts) * x0[k] + ts * x1[k]) + s * ((1 - ts) * x0[3 + k] + ts * x1[3 + k]);
                if (ts == 0) {
                    x0[k] += b - a;
                    x0[3 + k] += b - a;
                } else {
                    x1[k] += (b - a) / (ts > 0.05 ? ts : 1);
                    x1[3 + k] += (b - a) / (ts > 0.05 ? ts : 1);
                }
            }
        }
    }
    for (int i = 0; i < 12; ++i) {
        x0[i] = x0[i] * scale + offset;
        x1[i] = x1[i] * scale + offset;
    }
}

static int threads_and_precision(void)
{
    enum { N = 3000 };
    double *a0 = malloc(sizeof(double) * 9 * N), *b0 = malloc(sizeof(double) * 9 * N);
    double *a1 = malloc(sizeof(double) * 9 * N), *b1 = malloc(sizeof(double) * 9 * N);
    float *fa0 = malloc(sizeof(float) * 9 * N), *fb0 = malloc(sizeof(float) * 9 * N);
    float *fa1 = malloc(sizeof(float) * 9 * N), *fb1 = malloc(sizeof(float) * 9 * N);
    ttd_ccd_result *r1 = malloc(sizeof *r1 * N), *r2 = malloc(sizeof *r2 * N), *r3 = malloc(sizeof *r3 * N);
    ENSURE(a0 && b0 && a1 && b1 && fa0 && fb0 && fa1 && fb1 && r1 && r2 && r3);
    for (size_t i = 0; i < 9 * (size_t)N; ++i) {
        fa0[i] = (float)srand1(), fb0[i] = (float)srand1();
        fa1[i] = fa0[i] + (float)srand1(), fb1[i] = fb0[i] + (float)srand1();
        a0[i] = fa0[i], b0[i] = fb0[i], a1[i] = fa1[i], b1[i] = fb1[i];
    }
    ttd_options o = ttd_default_options();
    for (int kind = 0; kind < 3; ++kind) {
        ttd_status (*fd)(const ttd_options *, size_t, const double *, const double *, const double *,
                         const double *, double, ttd_ccd_result *) =
            kind == 0 ? ttd_ccd_vertex_face_d : kind == 1 ? ttd_ccd_edge_edge_d : ttd_ccd_triangles_d;
        ttd_status (*ff)(const ttd_options *, size_t, const float *, const float *, const float *,
                         const float *, double, ttd_ccd_result *) =
            kind == 0 ? ttd_ccd_vertex_face_f : kind == 1 ? ttd_ccd_edge_edge_f : ttd_ccd_triangles_f;
        /* vertex-face reads 3 + 9 numbers a query, edge-edge 6 + 6: the same arrays serve. */
        o.threads = 1;
        ENSURE(fd(&o, N, a0, b0, a1, b1, 0.01, r1) == TTD_OK);
        o.threads = 2;
        ENSURE(fd(&o, N, a0, b0, a1, b1, 0.01, r2) == TTD_OK);
        o.threads = 0;
        ENSURE(ff(&o, N, fa0, fb0, fa1, fb1, 0.01, r3) == TTD_OK);
        ENSURE(memcmp(r1, r2, sizeof *r1 * N) == 0);
        ENSURE(memcmp(r1, r3, sizeof *r1 * N) == 0);
        size_t hits = 0;
        for (int i = 0; i < N; ++i)
            hits += r1[i].hit;
        ENSURE_MSG(hits > N / 100 && hits < N, "kind %d: %zu hits of %d", kind, hits, N);
    }
    free(a0), free(b0), free(a1), free(b1), free(fa0), free(fb0), free(fa1), free(fb1);
    free(r1), free(r2), free(r3);
    return 0;
}

/* Motions whose answers are known by construction, degenerate ones included. */
static int constructed(void)
{
    /* Triangle (0,0,0) (1,0,0) (0,1,0) fixed; point straight down through (0.2, 0.2) from z = 1
     * to z = -1: contact at t = 0.5. */
    const double T[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    double x0[12], x1[12];
    memcpy(x0 + 3, T, sizeof T);
    memcpy(x1 + 3, T, sizeof T);
    x0[0] = 0.2, x0[1] = 0.2, x0[2] = 1;
    x1[0] = 0.2, x1[1] = 0.2, x1[2] = -1;
    ttd_ccd_result r = run1(1, x0, x1, 0);
    ENSURE(r.hit == 1 && r.toi <= 0.5 && r.toi >= 0.5 - TOI_TOL);
    /* delta = 0.25: the distance |1 - 2t| reaches 0.25 at t = 0.375. */
    r = run1(1, x0, x1, 0.25);
    ENSURE(r.hit == 1 && r.toi <= 0.375 && r.toi >= 0.375 - TOI_TOL);
    /* Beside the triangle (x = y = 0.6: outside, 0.2/sqrt 2 from the hypotenuse in the plane). */
    x0[0] = x0[1] = x1[0] = x1[1] = 0.6;
    ENSURE(run1(1, x0, x1, 0).hit == 0);
    ENSURE(run1(1, x0, x1, 0.14).hit == 0);
    ENSURE(run1(1, x0, x1, 0.15).hit == 1);
    /* Touching at t = 0 (the point on the face), and at t = 1 exactly. */
    x0[0] = x0[1] = x1[0] = x1[1] = 0.25;
    x0[2] = 0, x1[2] = 1;
    r = run1(1, x0, x1, 0);
    ENSURE(r.hit == 1 && r.toi == 0);
    x0[2] = 1, x1[2] = 0;
    r = run1(1, x0, x1, 0);
    ENSURE(r.hit == 1 && r.toi <= 1 && r.toi >= 1 - TOI_TOL);
    /* No motion: on the face, and 1e-300 above it (apart, tiny). */
    x0[2] = x1[2] = 0;
    r = run1(1, x0, x1, 0);
    ENSURE(r.hit == 1 && r.toi == 0);
    x0[2] = x1[2] = 1e-200;
    ENSURE(run1(1, x0, x1, 0).hit == 0);
    /* Coplanar throughout (the cubic vanishes identically): the point slides in the plane z = 0
     * from (-1, 0.25) to (1, 0.25), entering the triangle at x = 0, t = 0.5; and beside it at
     * y = -0.25, never inside. */
    x0[0] = -1, x0[1] = 0.25, x0[2] = 0, x1[0] = 1, x1[1] = 0.25, x1[2] = 0;
    r = run1(1, x0, x1, 0);
    ENSURE(r.hit == 1 && r.toi <= 0.5 && r.toi >= 0.5 - TOI_TOL);
    x0[1] = x1[1] = -0.25;
    ENSURE(run1(1, x0, x1, 0).hit == 0);
    /* Zero-area face (all three vertices on the x axis, from 0 to 1): the point crosses the
     * segment at x = 0.5 at t = 0.5, or passes it at y = 0.01. */
    const double Z[9] = {0, 0, 0, 1, 0, 0, 0.5, 0, 0};
    memcpy(x0 + 3, Z, sizeof Z);
    memcpy(x1 + 3, Z, sizeof Z);
    x0[0] = x1[0] = 0.5, x0[1] = x1[1] = 0, x0[2] = 1, x1[2] = -1;
    r = run1(1, x0, x1, 0);
    ENSURE(r.hit == 1 && r.toi <= 0.5 && r.toi >= 0.5 - TOI_TOL);
    x0[1] = x1[1] = 0.01;
    ENSURE(run1(1, x0, x1, 0).hit == 0);

    /* Edge-edge: a along x at z = 1 moving to z = -1, b along y at z = 0: cross at t = 0.5. */
    const double E0[12] = {-1, 0, 1, 1, 0, 1, 0, -1, 0, 0, 1, 0};
    const double E1[12] = {-1, 0, -1, 1, 0, -1, 0, -1, 0, 0, 1, 0};
    r = run1(2, E0, E1, 0);
    ENSURE(r.hit == 1 && r.toi <= 0.5 && r.toi >= 0.5 - TOI_TOL);
    /* Parallel edges sliding along each other 1e-3 apart: no contact; 0.001 >= delta hit. */
    const double P0[12] = {0, 0, 0, 1, 0, 0, 2, 0.001, 0, 3, 0.001, 0};
    const double P1[12] = {0, 0, 0, 1, 0, 0, -1, 0.001, 0, 0, 0.001, 0};
    ENSURE(run1(2, P0, P1, 0).hit == 0);
    /* With delta 0.0011: b's start comes within 0.0011 of a's end when it is sqrt(0.0011^2 -
     * 0.001^2) short of x = 1. */
    r = run1(2, P0, P1, 0.0011);
    const double tp = (1 - sqrt(0.0011 * 0.0011 - 1e-6)) / 3;
    ENSURE(r.hit == 1 && r.toi <= tp && r.toi >= tp - TOI_TOL);
    /* Collinear: the same, on one line: contact when b's start reaches x = 1 at t = 1/3. */
    double C0[12], C1[12];
    memcpy(C0, P0, sizeof C0);
    memcpy(C1, P1, sizeof C1);
    C0[7] = C0[10] = C1[7] = C1[10] = 0;
    r = run1(2, C0, C1, 0);
    ENSURE(r.hit == 1 && r.toi <= 1.0 / 3 && r.toi >= 1.0 / 3 - TOI_TOL);
    /* Zero-length edge a (a point) through edge b's middle. */
    const double D0[12] = {0, 0, 1, 0, 0, 1, 0, -1, 0, 0, 1, 0};
    const double D1[12] = {0, 0, -1, 0, 0, -1, 0, -1, 0, 0, 1, 0};
    r = run1(2, D0, D1, 0);
    ENSURE(r.hit == 1 && r.toi <= 0.5 && r.toi >= 0.5 - TOI_TOL);
    /* Both zero length, passing 1e-9 apart: no contact. */
    const double Q0[12] = {0, 0, 1, 0, 0, 1, 1e-9, 0, 0, 1e-9, 0, 0};
    const double Q1[12] = {0, 0, -1, 0, 0, -1, 1e-9, 0, 0, 1e-9, 0, 0};
    ENSURE(run1(2, Q0, Q1, 0).hit == 0);
    /* A near miss below rounding: the point crosses the plane y = 1/2 of the face (0,1/2,0)
     * (0,1/2,1) (1,1/2,1) (the part z >= x of it) at t = 1/2 at x = 1, z = 1 - 2^-54: outside,
     * 2^-54.5 from the edge z = x. No computed distance tells it from a touch; the exact
     * condition for that edge does (the search answered hit before). */
    const double NF[9] = {0, 0.5, 0, 0, 0.5, 1, 1, 0.5, 1};
    memcpy(x0 + 3, NF, sizeof NF);
    memcpy(x1 + 3, NF, sizeof NF);
    x0[0] = 1, x0[1] = 0.75, x0[2] = 1;
    x1[0] = 1, x1[1] = 0.25, x1[2] = 1 - 0x1p-53;
    ENSURE(run1(1, x0, x1, 0).hit == 0);
    /* Moved the other way (x to 1 - 2^-52, z staying 1): at t = 1/2 it is at x = 1 - 2^-53 on the
     * face's edge z = 1, a contact. */
    x1[0] = 1 - 0x1p-52, x1[2] = 1;
    r = run1(1, x0, x1, 0);
    ENSURE(r.hit == 1 && r.toi <= 0.5 && r.toi >= 0.5 - TOI_TOL);
    return 0;
}

/* The 40 queries of the benchmark's handcrafted sets (tests/data/ccd/near-misses, 14 vertex-face,
 * 26 edge-edge) that the search before the exact contact conditions reported as hits though the
 * truth is no contact: near misses by about 1e-17. At most one may stay a hit (a miss closer in
 * time than t_tol to a coplanar instant, where a contact condition changes sign inside the final
 * interval; none does with gcc 12 on x86-64). */
static int near_misses(void)
{
    size_t n_all = 0, fp = 0;
    for (int kind = 1; kind <= 2; ++kind) {
        char path[1024];
        snprintf(path, sizeof path, "%s/near-misses/%s.csv", TTD_CCD_DATA, kind == 1 ? "vertex-face" : "edge-edge");
        double *x0, *x1;
        int *truth;
        size_t n;
        ENSURE_MSG(read_csv_arrays(path, &x0, &x1, &truth, &n) == 0, "cannot read %s", path);
        for (size_t q = 0; q < n; ++q) {
            ENSURE(truth[q] == 0);
            fp += run1(kind, x0 + 12 * q, x1 + 12 * q, 0).hit;
#ifdef TTD_HAVE_GMP
            double lo, hi;
            ENSURE_MSG(ttd_ccd_ref(kind, x0 + 12 * q, x1 + 12 * q, &lo, &hi) == TTD_CCD_REF_MISS,
                       "%s: query %zu: the reference finds a contact", path, q);
#endif
        }
        n_all += n;
        free(x0), free(x1), free(truth);
    }
    printf("  near misses: %zu queries, %zu reported as hits\n", n_all, fp);
    ENSURE(n_all == 40 && fp <= 1);
    return 0;
}

#ifdef TTD_HAVE_GMP
/* One generated family against the exact reference: no false negative ever, toi never after the
 * true first time and within TOI_TOL of it; false positives none where the reference's answer
 * is not within the tolerance (allow_fp: the near-degenerate family, where it may be). */
static int family(const char *name, int kind, double scale, double offset, double eps, int n, int allow_fp)
{
    int hits = 0, misses = 0, undecided = 0, fp = 0;
    for (int q = 0; q < n; ++q) {
        double x0[12], x1[12], lo, hi;
        gen_query(kind, scale, offset, x0, x1);
        if (eps > 0) /* shift B's path by eps along a random direction: a near miss or near hit */
            for (int k = 0; k < 3; ++k) {
                const double d = eps * scale * srand1();
                for (int i = kind; i < 4; ++i)
                    x0[3 * i + k] += d, x1[3 * i + k] += d;
            }
        const int ref = ttd_ccd_ref(kind, x0, x1, &lo, &hi);
        const ttd_ccd_result r = run1(kind, x0, x1, 0);
        ENSURE(r.hit <= 1);
        if (ref == TTD_CCD_REF_HIT) {
            ++hits;
            ENSURE_MSG(r.hit == 1, "%s: query %d: a contact at t in [%.17g, %.17g] missed", name, q, lo, hi);
            ENSURE_MSG(r.toi <= hi, "%s: query %d: toi %.17g after the contact at %.17g", name, q, r.toi, hi);
            if (!allow_fp && !(r.toi >= lo - TOI_TOL))
                for (int i = 0; i < 12; ++i)
                    fprintf(stderr, "%a %a\n", x0[i], x1[i]);
            if (!allow_fp)
                ENSURE_MSG(r.toi >= lo - TOI_TOL, "%s: query %d: toi %.17g, contact %.17g", name, q, r.toi, lo);
        } else if (ref == TTD_CCD_REF_MISS) {
            ++misses;
            fp += r.hit;
            ENSURE_MSG(allow_fp || r.hit == 0, "%s: query %d: a hit at %.17g (gap %.3g) where there is none",
                       name, q, r.toi, r.gap);
            /* An allowed false positive is a near contact: the distance computed there is tiny. */
            ENSURE_MSG(!r.hit || r.gap <= 1e-9 * scale, "%s: query %d: a hit at %.17g with gap %.3g", name, q,
                       r.toi, r.gap);
        } else {
            ++undecided;
        }
    }
    printf("  %-28s %s: %d hits, %d misses, %d undecided, %d false positives\n", name,
           kind == 1 ? "vertex-face" : "edge-edge", hits, misses, undecided, fp);
    ENSURE(hits > 0 && misses > 0);
    return 0;
}

static int families(void)
{
    for (int kind = 1; kind <= 2; ++kind) {
        if (family("random", kind, 1, 0, 0, 1500, 0))
            return 1;
        for (double s = 1e-8; s <= 1e8; s *= 1e4)
            if (family(s < 1 ? "scaled down" : s > 1 ? "scaled up" : "scale 1", kind, s, 0, 0, 300, 0))
                return 1;
        if (family("offset 1e3", kind, 1, 1e3, 0, 300, 0) || family("offset 1e6", kind, 1, 1e6, 0, 300, 0))
            return 1;
        if (family("near-degenerate 1e-6", kind, 1, 0, 1e-6, 600, 0))
            return 1;
        gen_ends = 1;
        /* The aimed point is the face's or edge's point rounded: contact or a miss by a rounding
         * error, which the tolerance may report as a hit. */
        if (family("touching at t = 1", kind, 1, 0, 0, 300, 1))
            return 1;
        gen_ends = 2;
        if (family("touching at t = 0", kind, 1, 0, 0, 300, 1))
            return 1;
        gen_ends = 0;
        /* Within 1e-13 of contact: the tolerance's scale; false positives allowed, not misses. */
        if (family("near-degenerate 1e-13", kind, 1, 0, 1e-13, 600, 1))
            return 1;
    }
    return 0;
}
#endif

#ifdef TTD_HAVE_GMP
/* ccd_families.h's families that the search treats apart, against the exact reference: no contact
 * missed, toi never after the first contact and within TOI_TOL of it, no hit where the reference
 * finds none; at separation 1e-3 a hit wherever there is one at 0, no later.
 * - A point of A on a point of B, exactly, at t = 1 or at t = 0 (the touching families): the
 *   search's certificates (docs/ccd.md, section 3, item 7) answer toi 0 at once, or cut the final
 *   interval [1 - t_tol, 1] off at once and search [0, 1 - t_tol]; a contact is certain, earlier
 *   ones included (a few in a hundred queries at t = 1 touch before), and few intervals: before the
 *   certificates the search halved toward the contact, 46 or 47 intervals toward t = 0 and over 100
 *   toward t = 1.
 * - Parallel edges (up to the rounding of their construction) whose lines stay apart: no cut at a
 *   condition's root is tried (item 5 there; the order of the pieces only, so this checks the
 *   answers; slow_queries checks that edges sliding along one line keep the cut). */
static int families_apart(void)
{
    const int fams[3] = {F_TOUCH_T0, F_TOUCH_T1, F_PARALLEL};
    for (int kind = 1; kind <= 2; ++kind)
        for (int fi = 0; fi < 3; ++fi) {
            const int fam = fams[fi], touch = fam == F_TOUCH_T0 || fam == F_TOUCH_T1;
            if (fam == F_PARALLEL && kind == 1)
                continue;
            const qset s = make_set(fam, kind, 1000);
            int hits = 0, earlier = 0, undecided = 0;
            uint32_t most = 0;
            for (size_t q = 0; q < s.n; ++q) {
                const double *x0 = s.x0 + 12 * q, *x1 = s.x1 + 12 * q;
                double lo, hi;
                const int ref = ttd_ccd_ref(kind, x0, x1, &lo, &hi);
                const ttd_ccd_result r = run1(kind, x0, x1, 0), rd = run1(kind, x0, x1, 1e-3);
                ENSURE(r.hit <= 1 && rd.hit <= 1);
                ENSURE_MSG(!touch || ref != TTD_CCD_REF_MISS, "query %zu: the reference finds no contact", q);
                if (ref == TTD_CCD_REF_HIT) {
                    ++hits;
                    ENSURE_MSG(r.hit == 1 && rd.hit == 1, "%s: query %zu: a contact missed", family_name[fam], q);
                    ENSURE_MSG(r.toi <= hi && r.toi >= lo - TOI_TOL, "%s: query %zu: toi %.17g, contact in [%.17g, %.17g]",
                               family_name[fam], q, r.toi, lo, hi);
                    ENSURE(rd.toi <= hi);
                    earlier += fam == F_TOUCH_T1 && hi < 0.999;
                } else if (ref == TTD_CCD_REF_MISS) {
                    ENSURE_MSG(r.hit == 0, "%s: query %zu: a hit at %.17g where there is none", family_name[fam], q, r.toi);
                } else {
                    ++undecided;
                }
                if (fam == F_TOUCH_T0)
                    ENSURE_MSG(r.hit == 1 && r.toi == 0 && rd.toi == 0 && r.evals == 1, "query %zu: toi %.17g, %u intervals",
                               q, r.toi, r.evals);
                most = r.evals > most ? r.evals : most;
            }
            printf("  %-24s %s: %zu queries, %d hits (%d touching before t = 1), %d undecided, at most %u intervals\n",
                   family_name[fam], kind == 1 ? "vertex-face" : "edge-edge", s.n, hits, earlier, undecided, most);
            if (touch)
                ENSURE(most <= 32 && (fam == F_TOUCH_T0 || earlier >= 10));
            free(s.x0), free(s.x1);
        }
    return 0;
}
#endif

/* The kept sample queries: no false negative against the benchmark's truth; the reference
 * (where it decides) agrees with the truth. */

static int sample_file(const char *path, int kind, size_t *tot, size_t *pos, size_t *fp)
{
    double *x0, *x1;
    int *truth;
    size_t n;
    ENSURE_MSG(read_csv_arrays(path, &x0, &x1, &truth, &n) == 0, "cannot read %s", path);
    for (size_t q = 0; q < n; ++q) {
        const ttd_ccd_result r = run1(kind, x0 + 12 * q, x1 + 12 * q, 0);
        ENSURE(r.hit <= 1);
        ENSURE_MSG(!truth[q] || r.hit, "%s: query %zu: a contact missed", path, q);
        *fp += !truth[q] && r.hit;
        *pos += truth[q] != 0;
#ifdef TTD_HAVE_GMP
        double lo, hi;
        const int ref = ttd_ccd_ref(kind, x0 + 12 * q, x1 + 12 * q, &lo, &hi);
        ENSURE_MSG(ref == TTD_CCD_REF_UNDECIDED || ref == truth[q], "%s: query %zu: reference %d, truth %d",
                   path, q, ref, truth[q]);
        if (ref == TTD_CCD_REF_HIT)
            ENSURE_MSG(r.toi <= hi, "%s: query %zu: toi %.17g after the contact at %.17g", path, q, r.toi, hi);
#endif
    }
    *tot += n;
    free(x0), free(x1), free(truth);
    return 0;
}

static int sample_queries(void)
{
    const char *sets[] = {"unit-tests", "erleben-cube-cliff-edges", "erleben-cube-internal-edges",
                          "erleben-sliding-spike", "erleben-sliding-wedge", "erleben-spike-crack",
                          "erleben-spike-hole", "erleben-spike-wedge", "erleben-spikes",
                          "erleben-wedge-crack", "erleben-wedges", "slow-queries"};
    size_t tot = 0, pos = 0, fp = 0, files = 0;
    for (size_t s = 0; s < sizeof sets / sizeof sets[0]; ++s)
        for (int kind = 1; kind <= 2; ++kind) {
            char dir[1024];
            snprintf(dir, sizeof dir, "%s/%s/%s", TTD_CCD_DATA, sets[s], kind == 1 ? "vertex-face" : "edge-edge");
            DIR *d = opendir(dir);
            ENSURE_MSG(d != NULL, "missing %s", dir);
            struct dirent *e;
            while ((e = readdir(d)) != NULL) {
                if (strstr(e->d_name, ".csv") == NULL)
                    continue;
                char path[2048];
                snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
                if (sample_file(path, kind, &tot, &pos, &fp)) {
                    closedir(d);
                    return 1;
                }
                ++files;
            }
            closedir(d);
        }
    printf("  sample queries: %zu files, %zu queries, %zu positive, 0 missed, %zu false positives\n", files, tot,
           pos, fp);
    ENSURE(files == 26 && tot > 500 && pos > 100);
    return 0;
}

/* The queries the search once bisected to 2^-52 (tests/data/ccd/slow-queries; docs/ccd-speed.md):
 * contacts just after a root of f guessed an ulp or two early, edges sliding in a plane (f about 0),
 * edges touching all along. Each against the truth (sample_queries, with the exact reference), and
 * each in at most 16 intervals (48 to 139 before the cuts at f's root bracketed exactly, at a
 * condition's root, and the probe at the start; the unit tests' edge-edge data_0_1.csv queries 10,
 * 12, 13 are the probe's, 53 intervals before it). */
static int slow_queries(void)
{
    for (int kind = 1; kind <= 2; ++kind) {
        char path[1024];
        snprintf(path, sizeof path, "%s/slow-queries/%s/slow.csv", TTD_CCD_DATA, kind == 1 ? "vertex-face" : "edge-edge");
        double *x0, *x1;
        int *truth;
        size_t n;
        ENSURE_MSG(read_csv_arrays(path, &x0, &x1, &truth, &n) == 0, "cannot read %s", path);
        ENSURE(n == 6);
        for (size_t q = 0; q < n; ++q) {
            const ttd_ccd_result r = run1(kind, x0 + 12 * q, x1 + 12 * q, 0);
            ENSURE_MSG(r.hit == (uint32_t)truth[q], "%s query %zu: hit %u, truth %d", path, q, r.hit, truth[q]);
            ENSURE_MSG(r.evals <= 16, "%s query %zu: %u intervals", path, q, r.evals);
        }
        free(x0), free(x1), free(truth);
    }
    char path[1024];
    snprintf(path, sizeof path, "%s/unit-tests/edge-edge/data_0_1.csv", TTD_CCD_DATA);
    double *x0, *x1;
    int *truth;
    size_t n;
    ENSURE_MSG(read_csv_arrays(path, &x0, &x1, &truth, &n) == 0, "cannot read %s", path);
    ENSURE(n == 20);
    const size_t touching[3] = {10, 12, 13};
    for (int i = 0; i < 3; ++i) {
        const size_t q = touching[i];
        const ttd_ccd_result r = run1(2, x0 + 12 * q, x1 + 12 * q, 0);
        ENSURE_MSG(r.hit == 1 && truth[q] == 1 && r.toi == 0 && r.evals <= 16, "query %zu: hit %u toi %g, %u intervals", q,
                   r.hit, r.toi, r.evals);
    }
    free(x0), free(x1), free(truth);
    return 0;
}

/* Triangle-triangle: the earliest of its 15 sub-queries, each run alone through the public
 * vertex-face and edge-edge entries (a hit where any hits; toi no later than the earliest). */
static int triangles(void)
{
    for (int q = 0; q < 400; ++q) {
        double a0[9], b0[9], a1[9], b1[9];
        for (int i = 0; i < 9; ++i) {
            a0[i] = srand1(), b0[i] = srand1() + 0.5;
            a1[i] = a0[i] + 0.7 * srand1(), b1[i] = b0[i] + 0.7 * srand1() - 0.5;
        }
        ttd_ccd_result r;
        ENSURE(ttd_ccd_triangles_d(NULL, 1, a0, b0, a1, b1, 0, &r) == TTD_OK);
        int any = 0;
        double first = INFINITY;
        for (int sub = 0; sub < 15; ++sub) {
            double x0[12], x1[12];
            int kind;
            if (sub < 6) {
                const double *p0 = sub < 3 ? a0 : b0, *p1 = sub < 3 ? a1 : b1, *f0 = sub < 3 ? b0 : a0,
                             *f1 = sub < 3 ? b1 : a1;
                kind = 1;
                memcpy(x0, p0 + 3 * (sub % 3), 3 * sizeof(double));
                memcpy(x1, p1 + 3 * (sub % 3), 3 * sizeof(double));
                memcpy(x0 + 3, f0, 9 * sizeof(double));
                memcpy(x1 + 3, f1, 9 * sizeof(double));
            } else {
                const int i = (sub - 6) / 3, j = (sub - 6) % 3;
                kind = 2;
                memcpy(x0, a0 + 3 * i, 3 * sizeof(double));
                memcpy(x0 + 3, a0 + 3 * ((i + 1) % 3), 3 * sizeof(double));
                memcpy(x0 + 6, b0 + 3 * j, 3 * sizeof(double));
                memcpy(x0 + 9, b0 + 3 * ((j + 1) % 3), 3 * sizeof(double));
                memcpy(x1, a1 + 3 * i, 3 * sizeof(double));
                memcpy(x1 + 3, a1 + 3 * ((i + 1) % 3), 3 * sizeof(double));
                memcpy(x1 + 6, b1 + 3 * j, 3 * sizeof(double));
                memcpy(x1 + 9, b1 + 3 * ((j + 1) % 3), 3 * sizeof(double));
            }
            const ttd_ccd_result s = run1(kind, x0, x1, 0);
            if (s.hit) {
                any = 1;
                first = fmin(first, s.toi);
            }
            if ((int)r.sub == sub && r.hit)
                ENSURE(s.hit && fabs(s.toi - r.toi) <= TOI_TOL);
#ifdef TTD_HAVE_GMP
            double lo, hi;
            const int ref = ttd_ccd_ref(kind, x0, x1, &lo, &hi);
            if (ref == TTD_CCD_REF_HIT)
                ENSURE(r.hit && r.toi <= hi);
#endif
        }
        ENSURE(r.hit == (uint32_t)any);
        if (any)
            ENSURE(r.toi <= first + TOI_TOL && r.toi >= first - TOI_TOL);
    }
    return 0;
}

/* The distance of p to the segment uv (a point where u = v), in plain double: the test's own. */
static double dist_point_segment(const double p[3], const double u[3], const double v[3])
{
    double e[3], w[3], ee = 0, we = 0;
    for (int k = 0; k < 3; ++k) {
        e[k] = v[k] - u[k];
        w[k] = p[k] - u[k];
        ee += e[k] * e[k];
        we += w[k] * e[k];
    }
    const double s = ee > 0 ? fmin(1, fmax(0, we / ee)) : 0;
    double d = 0;
    for (int k = 0; k < 3; ++k)
        d += (w[k] - s * e[k]) * (w[k] - s * e[k]);
    return sqrt(d);
}

/* Zero-area faces at delta > 0 (issue 33: a face whose first two vertices were equal made the
 * closest-point walk divide 0 by 0 and take a vertex for the closest point, and the query answered
 * hit at t = 0 for a point 2.47 away). The face is then a segment (or a point), the union of its
 * three edges: the reference is the distance to them, sampled at N + 1 times, with the most it can change between samples (the
 * sum of the speeds) giving a lower bound; a delta below it must not hit, one above the sampled
 * minimum must, no later than the first sample within delta. Every order of the face's vertices. */
static int degenerate_face_check(const double p0[3], const double p1[3], const double f0[9], const double f1[9],
                                 double delta)
{
    enum { N = 4096 };
    double speed = 0, dmin = HUGE_VAL, lb = HUGE_VAL, first = HUGE_VAL;
    for (int i = 0; i < 4; ++i) {
        const double *a = i == 0 ? p0 : f0 + 3 * (i - 1), *b = i == 0 ? p1 : f1 + 3 * (i - 1);
        speed += sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) + (b[2] - a[2]) * (b[2] - a[2]));
    }
    for (int q = 0; q <= N; ++q) {
        const double t = (double)q / N;
        double p[3], f[9];
        for (int k = 0; k < 3; ++k)
            p[k] = p0[k] + t * (p1[k] - p0[k]);
        for (int k = 0; k < 9; ++k)
            f[k] = f0[k] + t * (f1[k] - f0[k]);
        const double d = fmin(dist_point_segment(p, f, f + 3),
                              fmin(dist_point_segment(p, f + 3, f + 6), dist_point_segment(p, f + 6, f)));
        dmin = fmin(dmin, d);
        lb = fmin(lb, d - speed / N - 1e-12);
        if (d <= delta && first == HUGE_VAL)
            first = t;
    }
    if (!(delta < lb || delta > dmin))
        return 0; /* too near the minimum for the sampled reference to tell */
    static const int perm[6][3] = {{0, 1, 2}, {1, 0, 2}, {0, 2, 1}, {2, 0, 1}, {1, 2, 0}, {2, 1, 0}};
    for (int o = 0; o < 6; ++o) {
        double x0[12], x1[12];
        memcpy(x0, p0, 3 * sizeof(double));
        memcpy(x1, p1, 3 * sizeof(double));
        for (int i = 0; i < 3; ++i) {
            memcpy(x0 + 3 + 3 * i, f0 + 3 * perm[o][i], 3 * sizeof(double));
            memcpy(x1 + 3 + 3 * i, f1 + 3 * perm[o][i], 3 * sizeof(double));
        }
        const ttd_ccd_result r = run1(1, x0, x1, delta);
        ENSURE_MSG(delta < lb ? r.hit == 0 : (r.hit == 1 && r.toi <= first),
                   "order %d, delta %.17g, reference minimum in [%.17g, %.17g] (first within delta %g): hit %u toi %.17g",
                   o, delta, lb, dmin, first, r.hit, r.toi);
    }
    return 0;
}

static int degenerate_faces(void)
{
    /* The reported case: the face's first two vertices equal, the third moving; the point comes no
     * nearer than 1.114 to the segment they span (the reference below). */
    const double p0[3] = {-0.25, 1.5, 0}, p1[3] = {-0.25, 0, 0};
    const double f0[9] = {-1.5, 0.75, -2, -1.5, 0.75, -2, 0.75, 1, -0.5};
    const double f1[9] = {-1.5, 0.75, -2, -1.5, 0.75, -2, 0.75, -2, -0.5};
    const double deltas[] = {0, 0.375, 1, 1.5, 2, 3};
    for (size_t i = 0; i < sizeof deltas / sizeof deltas[0]; ++i)
        ENSURE(degenerate_face_check(p0, p1, f0, f1, deltas[i]) == 0);
    /* Random ones: two vertices equal (a segment), all three equal (a point), or three on one
     * axis-parallel line (exactly collinear in doubles). */
    for (int it = 0; it < 600; ++it) {
        double q0[3], q1[3], g0[9], g1[9];
        for (int k = 0; k < 3; ++k) {
            q0[k] = 2 * srand1();
            q1[k] = 2 * srand1();
        }
        const int shape = it % 3;
        if (shape < 2) {
            for (int k = 0; k < 9; ++k) {
                g0[k] = 2 * srand1();
                g1[k] = 2 * srand1();
            }
            for (int k = 0; k < 3; ++k) {
                g0[3 + k] = g0[k], g1[3 + k] = g1[k];
                if (shape == 1)
                    g0[6 + k] = g0[k], g1[6 + k] = g1[k];
            }
        } else {
            /* Along x at fixed y, z: the third between the others at both ends (not in between
             * where the outer two pass each other). */
            const double y0 = srand1(), z0 = srand1(), y1 = srand1(), z1 = srand1();
            double xs0[3] = {srand1(), srand1(), 0}, xs1[3] = {srand1(), srand1(), 0};
            xs0[2] = xs0[0] + urand() * (xs0[1] - xs0[0]);
            xs1[2] = xs1[0] + urand() * (xs1[1] - xs1[0]);
            for (int i = 0; i < 3; ++i) {
                g0[3 * i] = xs0[i], g0[3 * i + 1] = y0, g0[3 * i + 2] = z0;
                g1[3 * i] = xs1[i], g1[3 * i + 1] = y1, g1[3 * i + 2] = z1;
            }
        }
        ENSURE_MSG(degenerate_face_check(q0, q1, g0, g1, 1.5 * urand()) == 0, "case %d (shape %d)", it, shape);
    }
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(api_checks);
    RUN_TEST(threads_and_precision);
    RUN_TEST(constructed);
    RUN_TEST(near_misses);
    RUN_TEST(degenerate_faces);
#ifdef TTD_HAVE_GMP
    RUN_TEST(families);
#else
    printf("  families against the exact reference skipped: GMP (libgmp-dev) not found at configure time\n");
#endif
    RUN_TEST(sample_queries);
    RUN_TEST(slow_queries);
    RUN_TEST(triangles);
#ifdef TTD_HAVE_GMP
    RUN_TEST(families_apart);
#endif
    TEST_MAIN_END();
}
