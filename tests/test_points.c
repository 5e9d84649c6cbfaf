/* SPDX-License-Identifier: MIT */
/* The point queries (include/ttd/ttd.h, "Point queries"; docs/points.md) against independent
 * references:
 *  - the exact point-triangle distance against the quad-precision reference and the pair method;
 *  - the closest point of a mesh against the brute force over every triangle with that routine,
 *    bit for bit, on smooth, degenerate and soup meshes at scales 1e-8..1e8 and an offset of 1e6,
 *    for points near, on (vertices, edges, faces), around and far from the surface, both
 *    precisions; every instruction set and thread count alike;
 *  - the winding number against the linear exact sum (within its rigorous bound), inside/outside
 *    against a ray's crossing parity on closed meshes, signed distances and grids against the
 *    closest point and the winding number;
 *  - bad input: statuses, NaN points flagged, poses. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "engine/dispatch.h"
#include "meshes.h"
#include "pairs.h"
#include "points/points.h"
#include "ref_distance.h"
#include "ref_parity.h"
#include "test_macros.h"
#include "ttd/ttd.h"

/* ---- meshes ------------------------------------------------------------------------------- */

/* A soup of trouble: random triangles, needles (widths 1e-3..1e-15), slivers, segments, points and
 * duplicates, in the unit box. */
static int soup(uint64_t seed, size_t nt, ttd_gen_mesh *m)
{
    memset(m, 0, sizeof *m);
    m->verts = malloc(9 * nt * sizeof(double));
    m->tris = malloc(3 * nt * sizeof(uint32_t));
    if (!m->verts || !m->tris)
        return -1;
    ttd_gen_rng r = ttd_gen_rng_make(seed, 7);
    for (size_t t = 0; t < nt; ++t) {
        double *v = m->verts + 9 * t;
        for (int k = 0; k < 9; ++k)
            v[k] = ttd_gen_rng_uniform(&r);
        const int kind = (int)(t % 6);
        const double w = pow(10.0, -3.0 - 12.0 * ttd_gen_rng_uniform(&r));
        for (int c = 0; c < 3; ++c) {
            if (kind == 1) /* needle: C within w of A */
                v[6 + c] = v[c] + w * (v[3 + c] - v[c]) * 0.5 + (c == 2 ? w : 0);
            else if (kind == 2) /* sliver: C within w of the line AB */
                v[6 + c] = v[c] + 0.37 * (v[3 + c] - v[c]) + (c == 1 ? w : 0);
            else if (kind == 3) /* segment */
                v[6 + c] = v[c] + 0.5 * (v[3 + c] - v[c]);
            else if (kind == 4) /* point */
                v[3 + c] = v[6 + c] = v[c];
        }
        if (kind == 5 && t > 0) /* a duplicate of the previous triangle */
            memcpy(v, v - 9, 9 * sizeof(double));
        for (int k = 0; k < 3; ++k)
            m->tris[3 * t + (size_t)k] = (uint32_t)(3 * t + (size_t)k);
    }
    m->nv = 3 * nt;
    m->nt = nt;
    return 0;
}

/* Mesh number i of the test set (normalised to the unit diagonal): 0 icosphere (320), 1 torus
 * (576), 2 the generator's degenerate mesh, 3 a grid (128), 4 a soup (300), 5 one triangle. */
#define NMESHES 6
static int test_mesh(int i, ttd_gen_mesh *m)
{
    int rc;
    switch (i) {
    case 0: rc = ttd_gen_icosphere(2, m); break;
    case 1: rc = ttd_gen_torus(1.0, 0.3, 24, 12, m); break;
    case 2: rc = ttd_gen_mesh_degenerate(m); break;
    case 3: rc = ttd_gen_grid(8, m); break;
    case 4: rc = soup(11, 300, m); break;
    default: rc = ttd_gen_mesh_triangle(m); break;
    }
    return rc != 0 ? rc : ttd_gen_normalize(m);
}

/* Scales and offsets the mesh and makes its points: near (a point of a triangle moved off by up to
 * 1e-3 of the size), on vertices, on edges, on faces, in the box, far. 6 * per points. */
static double *test_points(const ttd_gen_mesh *m, uint64_t seed, size_t per, size_t *n)
{
    *n = 6 * per;
    double *p = malloc(3 * *n * sizeof *p);
    ttd_gen_rng r = ttd_gen_rng_make(seed, 3);
    for (size_t i = 0; i < *n; ++i) {
        const size_t kind = i / per, t = ttd_gen_rng_u64(&r) % m->nt;
        const double *v[3];
        for (int k = 0; k < 3; ++k)
            v[k] = m->verts + 3 * m->tris[3 * t + (size_t)k];
        double a = ttd_gen_rng_uniform(&r), b = ttd_gen_rng_uniform(&r);
        if (a + b > 1) {
            a = 1 - a;
            b = 1 - b;
        }
        const int k = (int)(ttd_gen_rng_u64(&r) % 3);
        for (int c = 0; c < 3; ++c) {
            const double face = v[0][c] + a * (v[1][c] - v[0][c]) + b * (v[2][c] - v[0][c]);
            const double u = ttd_gen_rng_uniform(&r) - 0.5;
            double x;
            switch (kind) {
            case 0: x = face + 1e-3 * u; break;
            case 1: x = v[k][c]; break;
            case 2: x = 0.5 * v[k][c] + 0.5 * v[(k + 1) % 3][c]; break;
            case 3: x = face; break;
            case 4: x = 1.5 * u; break;
            default: x = 1e3 * u; break;
            }
            p[3 * i + (size_t)c] = x;
        }
    }
    return p;
}

/* ---- the brute force ---------------------------------------------------------------------- */

#define BRUTE(real, sfx)                                                                          \
    static void brute_##sfx(const real *verts, const uint32_t *tris, size_t nt, const real p[3],  \
                            ttd_point_result_##sfx *out)                                          \
    {                                                                                             \
        memset(out, 0, sizeof *out); /* every field set, even where no triangle is nearer */      \
        out->distance = (real)INFINITY;                                                           \
        out->triangle = UINT32_MAX;                                                               \
        for (size_t t = 0; t < nt; ++t) {                                                         \
            real tri[9];                                                                          \
            for (int k = 0; k < 9; ++k)                                                           \
                tri[k] = verts[3 * tris[3 * t + (size_t)(k / 3)] + (size_t)(k % 3)];             \
            ttd_point_result_##sfx r;                                                             \
            ttd_point_triangle_##sfx(p, tri, &r);                                                 \
            if (r.distance < out->distance) {                                                     \
                *out = r;                                                                         \
                out->triangle = (uint32_t)t;                                                      \
            }                                                                                     \
        }                                                                                         \
    }
BRUTE(double, d)
BRUTE(float, f)

/* The fields a query promises to equal the brute force's, bit for bit. */
#define SAME_RESULT(a, b)                                                                         \
    (memcmp(&(a).distance, &(b).distance, sizeof (a).distance) == 0 && (a).triangle == (b).triangle && \
     memcmp((a).point, (b).point, sizeof (a).point) == 0 && memcmp((a).bary, (b).bary, sizeof (a).bary) == 0 && \
     (a).feature == (b).feature && ((a).flags & TTD_POINT_DEGENERATE) == ((b).flags & TTD_POINT_DEGENERATE))

/* ---- tests -------------------------------------------------------------------------------- */

/* The reference routine against the quad-precision distance and the pair method. */
static int triangle_reference_accurate(void)
{
    const size_t n = 4000;
    double *s = malloc(9 * n * sizeof *s), *t = malloc(9 * n * sizeof *t);
    ENSURE(s && t);
    double worst = 0, worst_f = 0;
    for (int f = 0; f < TTD_GEN_COUNT; ++f) {
        ttd_gen((ttd_gen_family)f, 77 + (uint64_t)f, n, s, t);
        for (size_t i = 0; i < n; ++i) {
            const double *P = s + 9 * i + 3 * (i % 3), *T = t + 9 * i;
            ttd_point_result_d r;
            ENSURE(ttd_point_triangle_d(P, T, &r) == TTD_OK);
            const double ref = ttd_ref_point_triangle(P, T);
            double ext = 0;
            for (int k = 0; k < 9; ++k)
                ext = fmax(ext, fabs(T[k] - P[k % 3]));
            const double err = fabs(r.distance - ref) / ext;
            worst = fmax(worst, err);
            ENSURE_MSG(err <= 16 * DBL_EPSILON, "family %s pair %zu: %.17g vs %.17g", ttd_gen_name((ttd_gen_family)f), i,
                       r.distance, ref);
            /* the point lies on the triangle (its weights rebuild it) at the distance */
            double q[3], wsum = r.bary[0] + r.bary[1] + r.bary[2];
            for (int c = 0; c < 3; ++c)
                q[c] = r.bary[0] * T[c] + r.bary[1] * T[3 + c] + r.bary[2] * T[6 + c];
            ENSURE(r.bary[0] >= 0 && r.bary[1] >= 0 && r.bary[2] >= 0 && fabs(wsum - 1) <= 8 * DBL_EPSILON);
            const double gap = sqrt((q[0] - r.point[0]) * (q[0] - r.point[0]) + (q[1] - r.point[1]) * (q[1] - r.point[1]) +
                                    (q[2] - r.point[2]) * (q[2] - r.point[2]));
            ENSURE_MSG(gap <= 64 * DBL_EPSILON * (ext + fabs(P[0]) + fabs(P[1]) + fabs(P[2])), "point off its weights by %g", gap);
            const double pd = sqrt((P[0] - r.point[0]) * (P[0] - r.point[0]) + (P[1] - r.point[1]) * (P[1] - r.point[1]) +
                                   (P[2] - r.point[2]) * (P[2] - r.point[2]));
            ENSURE_MSG(fabs(pd - r.distance) <= 64 * DBL_EPSILON * (ext + fabs(P[0]) + fabs(P[1]) + fabs(P[2])),
                       "|p - point| %.17g vs distance %.17g", pd, r.distance);
            /* float: the float inputs' distance in quad, within 16 float eps of the extent */
            float Pf[3], Tf[9];
            double Pd[3], Td[9];
            for (int k = 0; k < 12; ++k) { /* through a volatile: gcc 12 at -O2 drops (double)(float)x */
                volatile float x = (float)(k < 9 ? T[k] : P[k - 9]);
                if (k < 9)
                    Td[k] = Tf[k] = x;
                else
                    Pd[k - 9] = Pf[k - 9] = x;
            }
            ttd_point_result_f rf;
            if (ttd_point_triangle_f(Pf, Tf, &rf) == TTD_OK) {
                double extf = 0;
                for (int k = 0; k < 9; ++k)
                    extf = fmax(extf, fabs(Td[k] - Pd[k % 3]));
                const double errf = fabs((double)rf.distance - ttd_ref_point_triangle(Pd, Td)) / extf;
                worst_f = fmax(worst_f, errf);
                ENSURE_MSG(errf <= 16 * (double)FLT_EPSILON, "float: family %s pair %zu: %.9g (extent %g)", ttd_gen_name((ttd_gen_family)f), i,
                           (double)rf.distance, extf);
            }
        }
    }
    printf("  %d families x %zu: worst error %.2g (double), %.2g (float) of the extent\n", TTD_GEN_COUNT, n, worst, worst_f);
    free(s);
    free(t);
    return 0;
}

/* Scale and offset of case c: 1e-8, 1, 1e8, and 1 at an offset of 1e6. */
static void scale_case(int c, double *scale, double *offset)
{
    static const double sc[4] = {1e-8, 1, 1e8, 1}, off[4] = {0, 0, 0, 1e6};
    *scale = sc[c];
    *offset = off[c];
}

static int closest_equals_brute_force(void)
{
    size_t checked = 0, nodes = 0, tris = 0;
    for (int mi = 0; mi < NMESHES; ++mi)
        for (int sc = 0; sc < 4; ++sc) {
            ttd_gen_mesh m;
            ENSURE(test_mesh(mi, &m) == 0);
            size_t n;
            double *p = test_points(&m, 100 + (uint64_t)mi, 40, &n);
            double scale, offset;
            scale_case(sc, &scale, &offset);
            for (size_t i = 0; i < 3 * m.nv; ++i)
                m.verts[i] = m.verts[i] * scale + offset;
            for (size_t i = 0; i < 3 * n; ++i)
                p[i] = p[i] * scale + offset;
            /* double */
            ttd_mesh *mesh;
            ENSURE(ttd_mesh_create_d(NULL, m.verts, m.nv, m.tris, m.nt, &mesh) == TTD_OK);
            ttd_point_result_d *res = malloc(n * sizeof *res);
            ENSURE(ttd_points_closest_d(NULL, mesh, n, p, NULL, INFINITY, res) == TTD_OK);
            for (size_t i = 0; i < n; ++i) {
                ttd_point_result_d b;
                brute_d(m.verts, m.tris, m.nt, p + 3 * i, &b);
                ENSURE_MSG(SAME_RESULT(res[i], b), "mesh %d scale %g offset %g point %zu: %.17g (tri %u) vs brute %.17g (tri %u)",
                           mi, scale, offset, i, res[i].distance, res[i].triangle, b.distance, b.triangle);
                nodes += res[i].node_tests;
                tris += res[i].triangle_tests;
            }
            ttd_mesh_destroy(mesh);
            /* float */
            float *vf = malloc(3 * m.nv * sizeof *vf), *pf = malloc(3 * n * sizeof *pf);
            for (size_t i = 0; i < 3 * m.nv; ++i)
                vf[i] = (float)m.verts[i];
            for (size_t i = 0; i < 3 * n; ++i)
                pf[i] = (float)p[i];
            ENSURE(ttd_mesh_create_f(NULL, vf, m.nv, m.tris, m.nt, &mesh) == TTD_OK);
            ttd_point_result_f *rf = malloc(n * sizeof *rf);
            ENSURE(ttd_points_closest_f(NULL, mesh, n, pf, NULL, INFINITY, rf) == TTD_OK);
            for (size_t i = 0; i < n; ++i) {
                ttd_point_result_f b;
                brute_f(vf, m.tris, m.nt, pf + 3 * i, &b);
                ENSURE_MSG(SAME_RESULT(rf[i], b), "float mesh %d scale %g offset %g point %zu: %.9g (tri %u) vs brute %.9g (tri %u)",
                           mi, scale, offset, i, (double)rf[i].distance, rf[i].triangle, (double)b.distance, b.triangle);
            }
            ttd_mesh_destroy(mesh);
            checked += 2 * n;
            free(vf);
            free(pf);
            free(rf);
            free(res);
            free(p);
            ttd_gen_mesh_free(&m);
        }
    printf("  %zu points on %d meshes x 4 scales x 2 precisions: the brute force's bits (%.1f node and %.1f triangle tests a point)\n",
           checked, NMESHES, (double)nodes / (double)(checked / 2), (double)tris / (double)(checked / 2));
    return 0;
}

/* Every row and 1, 2 threads give the scalar row's single-thread bits. */
static int rows_threads_identical(void)
{
    ttd_gen_mesh m;
    ENSURE(ttd_gen_torus(1.0, 0.3, 64, 24, &m) == 0);
    size_t n;
    double *p = test_points(&m, 5, 500, &n);
    float *vf = malloc(3 * m.nv * sizeof *vf), *pf = malloc(3 * n * sizeof *pf);
    for (size_t i = 0; i < 3 * m.nv; ++i)
        vf[i] = (float)m.verts[i];
    for (size_t i = 0; i < 3 * n; ++i)
        pf[i] = (float)p[i];
    ttd_mesh *md, *mf;
    ENSURE(ttd_mesh_create_d(NULL, m.verts, m.nv, m.tris, m.nt, &md) == TTD_OK);
    ENSURE(ttd_mesh_create_f(NULL, vf, m.nv, m.tris, m.nt, &mf) == TTD_OK);
    ttd_point_result_d *rd = malloc(n * sizeof *rd), *xd = malloc(n * sizeof *xd);
    ttd_point_result_f *rf = malloc(n * sizeof *rf), *xf = malloc(n * sizeof *xf);
    double *sd = malloc(n * sizeof *sd), *sx = malloc(n * sizeof *sx);
    ttd_options o = ttd_default_options();
    o.isa = TTD_ISA_SCALAR;
    o.threads = 1;
    ENSURE(ttd_points_closest_d(&o, md, n, p, NULL, INFINITY, rd) == TTD_OK);
    ENSURE(ttd_points_closest_f(&o, mf, n, pf, NULL, INFINITY, rf) == TTD_OK);
    ENSURE(ttd_points_signed_distance_d(&o, md, n, p, NULL, INFINITY, sd, NULL) == TTD_OK);
    int rows = 0;
    for (int isa = 1; isa < TTD_ISA_COUNT; ++isa) {
        if (!ttd_isa_available((ttd_isa)isa))
            continue;
        ++rows;
        for (int threads = 1; threads <= 2; ++threads) {
            o.isa = (ttd_isa)isa;
            o.threads = threads;
            ENSURE(ttd_points_closest_d(&o, md, n, p, NULL, INFINITY, xd) == TTD_OK);
            ENSURE(ttd_points_closest_f(&o, mf, n, pf, NULL, INFINITY, xf) == TTD_OK);
            ENSURE(ttd_points_signed_distance_d(&o, md, n, p, NULL, INFINITY, sx, NULL) == TTD_OK);
            for (size_t i = 0; i < n; ++i) {
                ENSURE_MSG(SAME_RESULT(rd[i], xd[i]) && rd[i].node_tests == xd[i].node_tests,
                           "%s, %d threads, point %zu (double)", ttd_isa_name((ttd_isa)isa), threads, i);
                ENSURE_MSG(SAME_RESULT(rf[i], xf[i]) && rf[i].node_tests == xf[i].node_tests,
                           "%s, %d threads, point %zu (float)", ttd_isa_name((ttd_isa)isa), threads, i);
            }
            ENSURE(memcmp(sd, sx, n * sizeof *sd) == 0);
        }
    }
    printf("  %d instruction sets x 1, 2 threads, %zu points: identical\n", rows, n);
    ttd_mesh_destroy(md);
    ttd_mesh_destroy(mf);
    free(rd), free(xd), free(rf), free(xf), free(sd), free(sx), free(vf), free(pf), free(p);
    ttd_gen_mesh_free(&m);
    return 0;
}

/* The upper bound: the points beyond it report +inf, the others what an unbounded query says. */
static int upper_bound_respected(void)
{
    ttd_gen_mesh m;
    ENSURE(test_mesh(1, &m) == 0);
    size_t n;
    double *p = test_points(&m, 9, 100, &n);
    ttd_mesh *mesh;
    ENSURE(ttd_mesh_create_d(NULL, m.verts, m.nv, m.tris, m.nt, &mesh) == TTD_OK);
    ttd_point_result_d *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b);
    ENSURE(ttd_points_closest_d(NULL, mesh, n, p, NULL, INFINITY, a) == TTD_OK);
    const double ub = 0.05;
    ENSURE(ttd_points_closest_d(NULL, mesh, n, p, NULL, ub, b) == TTD_OK);
    size_t above = 0;
    for (size_t i = 0; i < n; ++i) {
        if (a[i].distance > ub) {
            ENSURE(b[i].distance == (double)INFINITY && b[i].flags == TTD_POINT_ABOVE_BOUND && b[i].triangle == UINT32_MAX);
            ++above;
        } else {
            ENSURE(SAME_RESULT(a[i], b[i]));
        }
    }
    ENSURE(above > 0 && above < n);
    /* a bound equal to a distance keeps that point */
    ENSURE(ttd_points_closest_d(NULL, mesh, 1, p + 3 * 400, NULL, a[400].distance, b) == TTD_OK);
    ENSURE(SAME_RESULT(a[400], b[0]));
    ttd_mesh_destroy(mesh);
    free(a), free(b), free(p);
    ttd_gen_mesh_free(&m);
    return 0;
}

static int bad_input_refused(void)
{
    ttd_gen_mesh m;
    ENSURE(test_mesh(0, &m) == 0);
    ttd_mesh *md, *mf;
    ENSURE(ttd_mesh_create_d(NULL, m.verts, m.nv, m.tris, m.nt, &md) == TTD_OK);
    float vf[3 * 642];
    ENSURE(m.nv <= 642);
    for (size_t i = 0; i < 3 * m.nv; ++i)
        vf[i] = (float)m.verts[i];
    ENSURE(ttd_mesh_create_f(NULL, vf, m.nv, m.tris, m.nt, &mf) == TTD_OK);
    double p[12] = {0.05, 0.02, 0.03, NAN, 0, 0, 2, 2, 2, 0, INFINITY, 0};
    ttd_point_result_d r[4];
    double w[4], sd[4];
    uint8_t in[4];
    ENSURE(ttd_points_closest_d(NULL, NULL, 4, p, NULL, INFINITY, r) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_points_closest_d(NULL, md, 4, NULL, NULL, INFINITY, r) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_points_closest_d(NULL, md, 4, p, NULL, INFINITY, NULL) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_points_closest_d(NULL, md, 0, p, NULL, INFINITY, r) == TTD_ERR_EMPTY);
    ENSURE(ttd_points_closest_d(NULL, md, 4, p, NULL, -1, r) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_points_closest_d(NULL, md, 4, p, NULL, NAN, r) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_points_closest_d(NULL, mf, 4, p, NULL, INFINITY, r) == TTD_ERR_PRECISION_MISMATCH);
    ENSURE(ttd_points_winding_number_d(NULL, mf, 4, p, NULL, w) == TTD_ERR_PRECISION_MISMATCH);
    ttd_options o = ttd_default_options();
    o.method = TTD_METHOD_PENALTY;
    ENSURE(ttd_points_closest_d(&o, md, 4, p, NULL, INFINITY, r) == TTD_ERR_BAD_OPTIONS);
    const double bad_pose[12] = {2, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    ENSURE(ttd_points_closest_d(NULL, md, 4, p, bad_pose, INFINITY, r) == TTD_ERR_BAD_POSE);
    const double far_pose[12] = {1, 0, 0, 1e300, 0, 1, 0, 0, 0, 0, 1, 0};
    ENSURE(ttd_points_closest_d(NULL, md, 4, p, far_pose, INFINITY, r) == TTD_ERR_COORDINATE_RANGE);
    const double out_of_range[3] = {1e200, 0, 0};
    ENSURE(ttd_points_closest_d(NULL, md, 1, out_of_range, NULL, INFINITY, r) == TTD_ERR_COORDINATE_RANGE);
    /* NaN and inf points: flagged, NaN outputs, the others computed */
    ENSURE(ttd_points_closest_d(NULL, md, 4, p, NULL, INFINITY, r) == TTD_ERR_NONFINITE_INPUT);
    ENSURE(r[1].flags == TTD_POINT_NONFINITE && isnan(r[1].distance) && isnan(r[1].point[0]) && r[1].triangle == UINT32_MAX);
    ENSURE(r[3].flags == TTD_POINT_NONFINITE && isnan(r[3].distance));
    ttd_point_result_d b;
    brute_d(m.verts, m.tris, m.nt, p, &b);
    ENSURE(SAME_RESULT(r[0], b));
    brute_d(m.verts, m.tris, m.nt, p + 6, &b);
    ENSURE(SAME_RESULT(r[2], b));
    ENSURE(ttd_points_winding_number_d(NULL, md, 4, p, NULL, w) == TTD_ERR_NONFINITE_INPUT);
    ENSURE(isnan(w[1]) && isnan(w[3]) && fabs(w[0] - 1) < 0.1 && fabs(w[2]) < 0.1);
    ENSURE(ttd_points_contains_d(NULL, md, 4, p, NULL, in) == TTD_ERR_NONFINITE_INPUT);
    ENSURE(in[0] == 1 && in[1] == 0 && in[2] == 0 && in[3] == 0);
    ENSURE(ttd_points_signed_distance_d(NULL, md, 4, p, NULL, INFINITY, sd, NULL) == TTD_ERR_NONFINITE_INPUT);
    ENSURE(sd[0] < 0 && isnan(sd[1]) && sd[2] > 0 && isnan(sd[3]));
    ENSURE(ttd_points_signed_distance_d(NULL, md, 4, p, NULL, INFINITY, NULL, NULL) == TTD_ERR_NULL_POINTER);
    /* the reference */
    const double tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    ENSURE(ttd_point_triangle_d(p, tri, NULL) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_point_triangle_d(p + 3, tri, r) == TTD_ERR_NONFINITE_INPUT && isnan(r[0].distance));
    ENSURE(ttd_point_triangle_d(out_of_range, tri, r) == TTD_ERR_COORDINATE_RANGE);
    /* grids */
    const double o3[3] = {0, 0, 0}, s3[3] = {0.1, 0.1, 0.1}, nan3[3] = {NAN, 0, 0};
    const size_t dims[3] = {2, 2, 1}, zero[3] = {2, 0, 2};
    ENSURE(ttd_sdf_grid_d(NULL, md, o3, s3, zero, sd) == TTD_ERR_EMPTY);
    ENSURE(ttd_sdf_grid_d(NULL, md, nan3, s3, dims, sd) == TTD_ERR_BAD_OPTIONS);
    /* a step of 0 or below on any axis (the CLI and Python refuse it too), even where the
     * dimension is 1; and in float */
    for (int c = 0; c < 3; ++c)
        for (int sign = 0; sign < 2; ++sign) {
            double sb[3] = {0.1, 0.1, 0.1};
            sb[c] = sign ? -0.1 : 0;
            ENSURE_MSG(ttd_sdf_grid_d(NULL, md, o3, sb, dims, sd) == TTD_ERR_BAD_OPTIONS, "step %g on axis %d", sb[c], c);
            const float of[3] = {0, 0, 0};
            float sf[3] = {0.1f, 0.1f, 0.1f}, gf[4];
            sf[c] = sign ? -0.1f : -0.0f;
            ENSURE_MSG(ttd_sdf_grid_f(NULL, mf, of, sf, dims, gf) == TTD_ERR_BAD_OPTIONS, "float step %g on axis %d",
                       (double)sf[c], c);
        }
    ENSURE(ttd_sdf_grid_d(NULL, md, o3, s3, NULL, sd) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_sdf_grid_d(NULL, mf, o3, s3, dims, sd) == TTD_ERR_PRECISION_MISMATCH);
    ttd_mesh_destroy(md);
    ttd_mesh_destroy(mf);
    ttd_gen_mesh_free(&m);
    return 0;
}

/* A pose: the points are moved into the mesh's frame by the documented formula, and the closest
 * points back. */
static int pose_applied(void)
{
    ttd_gen_mesh m;
    ENSURE(test_mesh(1, &m) == 0);
    size_t n;
    double *p = test_points(&m, 21, 30, &n);
    double pose[12];
    ttd_gen_pose(3, 1, 2.0, pose);
    ttd_mesh *mesh;
    ENSURE(ttd_mesh_create_d(NULL, m.verts, m.nv, m.tris, m.nt, &mesh) == TTD_OK);
    ttd_point_result_d *r = malloc(n * sizeof *r);
    ENSURE(ttd_points_closest_d(NULL, mesh, n, p, pose, INFINITY, r) == TTD_OK);
    for (size_t i = 0; i < n; ++i) {
        const double *x = p + 3 * i;
        double y[3], back[3];
        for (int c = 0; c < 3; ++c)
            y[c] = (pose[c] * (x[0] - pose[3]) + pose[4 + c] * (x[1] - pose[7])) + pose[8 + c] * (x[2] - pose[11]);
        ttd_point_result_d b;
        brute_d(m.verts, m.tris, m.nt, y, &b);
        for (int c = 0; c < 3; ++c)
            back[c] = ((pose[4 * c] * b.point[0] + pose[4 * c + 1] * b.point[1]) + pose[4 * c + 2] * b.point[2]) + pose[4 * c + 3];
        memcpy(b.point, back, sizeof back);
        ENSURE_MSG(SAME_RESULT(r[i], b), "point %zu", i);
    }
    ttd_mesh_destroy(mesh);
    free(r), free(p);
    ttd_gen_mesh_free(&m);
    return 0;
}

/* ---- winding numbers and signs ------------------------------------------------------------- */

/* On closed meshes: the hierarchical winding number within its bound of the linear exact sum, the
 * certified one within 1/4, and inside agreeing with a ray's parity. */
static int winding_and_signs(void)
{
    size_t checked = 0, certified_by_bound = 0;
    double worst_err = 0;
    for (int mi = 0; mi < 3; ++mi) {
        ttd_gen_mesh m;
        ENSURE((mi == 0   ? ttd_gen_icosphere(3, &m)
                : mi == 1 ? ttd_gen_torus(1.0, 0.3, 48, 16, &m)
                          : ttd_gen_mesh_cube(&m)) == 0);
        ENSURE(ttd_gen_normalize(&m) == 0);
        size_t n;
        double *p = test_points(&m, 31 + (uint64_t)mi, 60, &n);
        ttd_mesh *mesh;
        ENSURE(ttd_mesh_create_d(NULL, m.verts, m.nv, m.tris, m.nt, &mesh) == TTD_OK);
        uint8_t *in = malloc(n);
        double *sd = malloc(n * sizeof *sd);
        ttd_point_result_d *r = malloc(n * sizeof *r);
        ENSURE(ttd_points_contains_d(NULL, mesh, n, p, NULL, in) == TTD_OK);
        ENSURE(ttd_points_signed_distance_d(NULL, mesh, n, p, NULL, INFINITY, sd, r) == TTD_OK);
        const ttd_points_data *pd = ttd_points_data_get(mesh, 1);
        ENSURE(pd != NULL);
        ttd_gen_rng rng = ttd_gen_rng_make(5, (uint64_t)mi);
        for (size_t i = 0; i < n; ++i) {
            const double *x = p + 3 * i;
            double bound;
            const double w = ttd_points_winding(mesh, pd, x, &bound), exact = ttd_mesh_winding(mesh, x);
            ENSURE_MSG(fabs(w - exact) <= bound, "mesh %d point %zu: %.17g vs exact %.17g, bound %.3g", mi, i, w, exact, bound);
            worst_err = fmax(worst_err, fabs(w - exact));
            int proven;
            const double wc = ttd_points_winding_sign(mesh, pd, 1, ttd_dispatch_row_f(TTD_ISA_SCALAR)->ray_node, x, &proven);
            if (r[i].distance < 1e-9)
                continue; /* on the surface (to rounding): either side, and no ray parity */
            /* closed: the exact count, an integer, the linear sum's nearest */
            ENSURE_MSG(wc == nearbyint(exact) && fabs(wc - exact) <= 0.25, "mesh %d point %zu: certified %g, exact sum %.17g",
                       mi, i, wc, exact);
            ENSURE(!(r[i].flags & TTD_POINT_SIGN_UNPROVEN));
            const int inside = parity_inside(&m, x, &rng);
            ENSURE_MSG(in[i] == inside, "mesh %d point %zu (distance %.3g): contains %d, ray parity %d, w %.6f", mi, i,
                       r[i].distance, in[i], inside, w);
            ENSURE(((r[i].flags & TTD_POINT_INSIDE) != 0) == inside);
            ENSURE(sd[i] == (inside ? -r[i].distance : r[i].distance));
            certified_by_bound += bound < fabs(w - 0.5);
            ++checked;
        }
        ttd_mesh_destroy(mesh);
        free(in), free(sd), free(r), free(p);
        ttd_gen_mesh_free(&m);
    }
    printf("  %zu points off 3 closed meshes: inside agrees with ray parity; winding within its bound of the exact sum "
           "(worst error %.2g; %zu of the signs certified by the fast walk's own bound)\n",
           checked, worst_err, certified_by_bound);
    return 0;
}

/* The winding number of closed meshes is the exact count of a ray's crossings (points/ray.c): it
 * equals the linear sum of solid angles, rounded, for points off the surface by 1e-3 down to 1e-12
 * of the size (at faces, edges and vertices), for a grid of points whose rays run along the
 * cube's faces and through its edges and corners (the cases the perturbation decides), at scales
 * 1e-8..1e8 and an offset of 1e6, in both precisions; and every signed distance's side is proven. */
static int exact_count_near_surface(void)
{
    size_t checked = 0, skipped = 0;
    for (int mi = 0; mi < 3; ++mi)
        for (int sc = 0; sc < 4; ++sc)
            for (int prec = 0; prec < 2; ++prec) {
                ttd_gen_mesh m;
                ENSURE((mi == 0   ? ttd_gen_icosphere(2, &m)
                        : mi == 1 ? ttd_gen_torus(1.0, 0.3, 24, 12, &m)
                                  : ttd_gen_mesh_cube(&m)) == 0);
                ENSURE(ttd_gen_normalize(&m) == 0);
                double lo[3], hi[3];
                ENSURE(ttd_gen_mesh_bounds(&m, lo, hi) == 0);
                /* points: off faces, edge midpoints and vertices along a triangle's normal by
                 * +-delta, and a grid over the box whose lines hit the cube's faces, edges, corners */
                const size_t per = 48, ngrid = 7 * 7 * 7, n = 4 * 3 * 2 * per + ngrid;
                double *p = malloc(3 * n * sizeof *p);
                float *pf = malloc(3 * n * sizeof *pf);
                ttd_gen_rng r = ttd_gen_rng_make(77, (uint64_t)(mi * 8 + sc * 2 + prec));
                size_t i = 0;
                static const double deltas[4] = {1e-3, 1e-6, 1e-9, 1e-12};
                for (int di = 0; di < 4; ++di)
                    for (int where = 0; where < 3; ++where)
                        for (int side = -1; side <= 1; side += 2)
                            for (size_t q = 0; q < per; ++q, ++i) {
                                const size_t t = ttd_gen_rng_u64(&r) % m.nt;
                                const double *v[3];
                                for (int k = 0; k < 3; ++k)
                                    v[k] = m.verts + 3 * m.tris[3 * t + (size_t)k];
                                double a = ttd_gen_rng_uniform(&r), b = ttd_gen_rng_uniform(&r);
                                if (a + b > 1) {
                                    a = 1 - a;
                                    b = 1 - b;
                                }
                                if (where == 1)
                                    a = 0.5, b = 0;
                                else if (where == 2)
                                    a = b = 0;
                                double e1[3], e2[3], nn[3];
                                for (int c = 0; c < 3; ++c) {
                                    e1[c] = v[1][c] - v[0][c];
                                    e2[c] = v[2][c] - v[0][c];
                                }
                                nn[0] = e1[1] * e2[2] - e1[2] * e2[1];
                                nn[1] = e1[2] * e2[0] - e1[0] * e2[2];
                                nn[2] = e1[0] * e2[1] - e1[1] * e2[0];
                                const double l = sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
                                for (int c = 0; c < 3; ++c)
                                    p[3 * i + (size_t)c] = v[0][c] + a * e1[c] + b * e2[c] + side * deltas[di] * nn[c] / l;
                            }
                for (int gx = 0; gx < 7; ++gx)
                    for (int gy = 0; gy < 7; ++gy)
                        for (int gz = 0; gz < 7; ++gz, ++i) {
                            const int g[3] = {gx, gy, gz};
                            for (int c = 0; c < 3; ++c) /* -1/4 .. 5/4 of the box in quarters */
                                p[3 * i + (size_t)c] = lo[c] + (hi[c] - lo[c]) * (g[c] - 1) / 4.0;
                        }
                double scale, offset;
                scale_case(sc, &scale, &offset);
                for (size_t k = 0; k < 3 * m.nv; ++k)
                    m.verts[k] = m.verts[k] * scale + offset;
                for (size_t k = 0; k < 3 * n; ++k) {
                    p[k] = p[k] * scale + offset;
                    pf[k] = (float)p[k];
                    if (prec)
                        p[k] = pf[k];
                }
                float *vf = malloc(3 * m.nv * sizeof *vf);
                for (size_t k = 0; k < 3 * m.nv; ++k) {
                    vf[k] = (float)m.verts[k];
                    if (prec)
                        m.verts[k] = vf[k];
                }
                ttd_mesh *mesh;
                ENSURE((prec ? ttd_mesh_create_f(NULL, vf, m.nv, m.tris, m.nt, &mesh)
                             : ttd_mesh_create_d(NULL, m.verts, m.nv, m.tris, m.nt, &mesh)) == TTD_OK);
                double *w = malloc(n * sizeof *w);
                float *wf = malloc(n * sizeof *wf);
                uint8_t *in = malloc(n);
                ttd_point_result_d *rd = malloc(n * sizeof *rd);
                ttd_point_result_f *rf = malloc(n * sizeof *rf);
                if (prec) {
                    ENSURE(ttd_points_winding_number_f(NULL, mesh, n, pf, NULL, wf) == TTD_OK);
                    ENSURE(ttd_points_contains_f(NULL, mesh, n, pf, NULL, in) == TTD_OK);
                    ENSURE(ttd_points_signed_distance_f(NULL, mesh, n, pf, NULL, INFINITY, NULL, rf) == TTD_OK);
                } else {
                    ENSURE(ttd_points_winding_number_d(NULL, mesh, n, p, NULL, w) == TTD_OK);
                    ENSURE(ttd_points_contains_d(NULL, mesh, n, p, NULL, in) == TTD_OK);
                    ENSURE(ttd_points_signed_distance_d(NULL, mesh, n, p, NULL, INFINITY, NULL, rd) == TTD_OK);
                }
                /* the reference's distances in double, on the same (float) coordinates */
                ttd_mesh *md;
                ttd_point_result_d *ref = malloc(n * sizeof *ref);
                ENSURE(ttd_mesh_create_d(NULL, m.verts, m.nv, m.tris, m.nt, &md) == TTD_OK);
                ENSURE(ttd_points_closest_d(NULL, md, n, p, NULL, INFINITY, ref) == TTD_OK);
                const struct ttd_mesh *im = (const struct ttd_mesh *)md;
                for (size_t k = 0; k < n; ++k) {
                    const double wk = prec ? (double)wf[k] : w[k];
                    const double dist = ref[k].distance;
                    const int flags = prec ? rf[k].flags : rd[k].flags;
                    ENSURE(wk == nearbyint(wk));            /* an integer: the count */
                    ENSURE(!(flags & TTD_POINT_SIGN_UNPROVEN)); /* closed: always proven */
                    ENSURE(((flags & TTD_POINT_INSIDE) != 0) == in[k]);
                    ENSURE(in[k] == ttd_winding_inside(wk));
                    const double exact = ttd_mesh_winding(im, p + 3 * k);
                    if (!(dist > 1e-13 * scale) || fabs(exact - nearbyint(exact)) > 0.05) {
                        ++skipped; /* on the surface to rounding: the linear sum is no reference there */
                        continue;
                    }
                    ENSURE_MSG(wk == nearbyint(exact), "mesh %d scale %d prec %d point %zu (%.17g %.17g %.17g): count %g, "
                               "sum %.17g, distance %.3g", mi, sc, prec, k, p[3 * k], p[3 * k + 1], p[3 * k + 2], wk, exact,
                               dist);
                    ++checked;
                }
                ttd_mesh_destroy(mesh);
                ttd_mesh_destroy(md);
                free(p), free(pf), free(vf), free(w), free(wf), free(in), free(rd), free(rf), free(ref);
                ttd_gen_mesh_free(&m);
            }
    printf("  %zu points near and around 3 closed meshes x 4 scales x 2 precisions: the ray's count is the solid "
           "angles' sum, rounded (%zu on the surface or ill-conditioned left out)\n", checked, skipped);
    return 0;
}

/* A grid equals signed distances at its points. */
static int grid_matches_signed(void)
{
    ttd_gen_mesh m;
    ENSURE(test_mesh(1, &m) == 0);
    ttd_mesh *mesh;
    ENSURE(ttd_mesh_create_d(NULL, m.verts, m.nv, m.tris, m.nt, &mesh) == TTD_OK);
    const double origin[3] = {-0.6, -0.55, -0.2}, step[3] = {0.1, 0.11, 0.05};
    const size_t dims[3] = {12, 11, 9}, n = 12 * 11 * 9;
    double *g = malloc(n * sizeof *g), *p = malloc(3 * n * sizeof *p), *s = malloc(n * sizeof *s);
    ENSURE(ttd_sdf_grid_d(NULL, mesh, origin, step, dims, g) == TTD_OK);
    for (size_t i = 0; i < dims[0]; ++i)
        for (size_t j = 0; j < dims[1]; ++j)
            for (size_t k = 0; k < dims[2]; ++k) {
                double *x = p + 3 * ((i * dims[1] + j) * dims[2] + k);
                x[0] = origin[0] + (double)i * step[0];
                x[1] = origin[1] + (double)j * step[1];
                x[2] = origin[2] + (double)k * step[2];
            }
    ENSURE(ttd_points_signed_distance_d(NULL, mesh, n, p, NULL, INFINITY, s, NULL) == TTD_OK);
    ENSURE(memcmp(g, s, n * sizeof *g) == 0);
    size_t neg = 0;
    for (size_t i = 0; i < n; ++i)
        neg += g[i] < 0;
    ENSURE(neg > 0 && neg < n);
    ttd_mesh_destroy(mesh);
    free(g), free(p), free(s);
    ttd_gen_mesh_free(&m);
    return 0;
}

/* Signed distances without the caller's results (made in chunks of 8,192 points) equal those with
 * them (one pass), bit for bit, under a pose, on a closed mesh (the ray count) and an open one (the
 * walk), both precisions; a NaN point in the second chunk is flagged in both. The posed query equals
 * the query of the points moved by the documented formula. */
#define CHUNKS(real, sfx)                                                                          \
    static int chunks_##sfx(const ttd_gen_mesh *m, const double *p64, size_t n, const double pose64[12], size_t *inside) \
    {                                                                                              \
        real *v = malloc(3 * m->nv * sizeof *v), *p = malloc(3 * n * sizeof *p), *y = malloc(3 * n * sizeof *y); \
        real *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b), *c = malloc(n * sizeof *c), pose[12]; \
        ttd_point_result_##sfx *r = malloc(n * sizeof *r);                                         \
        ENSURE(v && p && y && a && b && c && r);                                                  \
        for (size_t i = 0; i < 3 * m->nv; ++i)                                                     \
            v[i] = (real)m->verts[i];                                                              \
        for (int k = 0; k < 12; ++k)                                                               \
            pose[k] = (real)pose64[k];                                                             \
        for (size_t i = 0; i < n; ++i) /* the points near the mesh taken out of its frame */     \
            for (int k = 0; k < 3; ++k) {                                                          \
                const double *x = p64 + 3 * i;                                                     \
                p[3 * i + (size_t)k] = (real)(pose64[4 * k] * x[0] + pose64[4 * k + 1] * x[1] +    \
                                              pose64[4 * k + 2] * x[2] + pose64[4 * k + 3]);       \
            }                                                                                      \
        for (size_t i = 0; i < n; ++i)                                                             \
            for (int k = 0; k < 3; ++k) {                                                          \
                const real *x = p + 3 * i;                                                         \
                y[3 * i + (size_t)k] = (pose[k] * (x[0] - pose[3]) + pose[4 + k] * (x[1] - pose[7])) + \
                                       pose[8 + k] * (x[2] - pose[11]);                            \
            }                                                                                      \
        ttd_mesh *mesh;                                                                            \
        ENSURE(ttd_mesh_create_##sfx(NULL, v, m->nv, m->tris, m->nt, &mesh) == TTD_OK);            \
        ENSURE(ttd_points_signed_distance_##sfx(NULL, mesh, n, p, pose, INFINITY, a, NULL) == TTD_ERR_NONFINITE_INPUT); \
        ENSURE(ttd_points_signed_distance_##sfx(NULL, mesh, n, p, pose, INFINITY, b, r) == TTD_ERR_NONFINITE_INPUT); \
        ENSURE(ttd_points_signed_distance_##sfx(NULL, mesh, n, y, NULL, INFINITY, c, NULL) == TTD_ERR_NONFINITE_INPUT); \
        ENSURE(memcmp(a, b, n * sizeof *a) == 0 && memcmp(a, c, n * sizeof *a) == 0);              \
        *inside = 0;                                                                               \
        for (size_t i = 0; i < n; ++i) {                                                           \
            const int nan = isnan(p[3 * i]);                                                       \
            ENSURE_MSG(nan == ((r[i].flags & TTD_POINT_NONFINITE) != 0) && nan == (isnan(a[i]) != 0), "point %zu", i); \
            if (!nan)                                                                              \
                ENSURE_MSG(a[i] == (r[i].flags & TTD_POINT_INSIDE ? -r[i].distance : r[i].distance), "point %zu", i); \
            *inside += (r[i].flags & TTD_POINT_INSIDE) != 0;                                       \
        }                                                                                          \
        ENSURE(ttd_points_signed_distance_##sfx(NULL, mesh, 0, p, pose, INFINITY, a, NULL) == TTD_ERR_EMPTY); \
        ttd_mesh_destroy(mesh);                                                                    \
        free(v), free(p), free(y), free(a), free(b), free(c), free(r);                             \
        return 0;                                                                                  \
    }
CHUNKS(double, d)
CHUNKS(float, f)

static int chunks_equal_one_pass(void)
{
    double pose[12];
    ttd_gen_pose(7, 1, 2.0, pose);
    for (int mi = 1; mi <= 3; mi += 2) { /* the torus (closed), the grid (open) */
        ttd_gen_mesh m;
        ENSURE(test_mesh(mi, &m) == 0);
        size_t n;
        double *p = test_points(&m, 31, 3000, &n); /* 18,000 points: three chunks */
        ENSURE(n > 2 * 8192);
        p[3 * 9000] = NAN;
        size_t in_d, in_f;
        ENSURE(chunks_d(&m, p, n, pose, &in_d) == 0 && chunks_f(&m, p, n, pose, &in_f) == 0);
        ENSURE(mi == 3 || (in_d > 0 && in_f > 0));
        printf("  %s: %zu posed points, inside %zu (double) %zu (float): chunked = one pass\n",
               mi == 1 ? "torus" : "grid", n, in_d, in_f);
        free(p);
        ttd_gen_mesh_free(&m);
    }
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(triangle_reference_accurate);
    RUN_TEST(closest_equals_brute_force);
    RUN_TEST(rows_threads_identical);
    RUN_TEST(upper_bound_respected);
    RUN_TEST(bad_input_refused);
    RUN_TEST(pose_applied);
    RUN_TEST(winding_and_signs);
    RUN_TEST(exact_count_near_surface);
    RUN_TEST(grid_matches_signed);
    RUN_TEST(chunks_equal_one_pass);
    TEST_MAIN_END();
}
