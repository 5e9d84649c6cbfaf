/* SPDX-License-Identifier: MIT */
/* Welding (ttd_mesh_weld_d/f, ttd_meshfile_weld): against an O(n^2) reference that joins every
 * pair within the tolerance (the definition in include/ttd/ttd.h, written out here again) on
 * small meshes of clustered points, at tolerances that take the grid's fine and coarse paths;
 * independence of the vertices' order; and by construction: an STL-like soup of a closed
 * icosphere and torus (every facet its own corners, each moved by a few ulps) is refused by the
 * solid mode before welding and accepted after, with the original counts back. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshes.h"
#include <ttd/meshfile.h>
#include <ttd/ttd.h>
#include "test_macros.h"

static uint64_t rng_state = 0x2545F4914F6CDD1Dull;
static uint64_t rnd(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return rng_state;
}
static double unit(void) { return (double)(rnd() >> 11) * 0x1p-53; }

/* ---- the reference: every pair, union-find, by the documented definition --------------- */

static int ref_within(const double *a, const double *b, double t)
{
    double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    if (t == 0)
        return dx == 0 && dy == 0 && dz == 0;
    if (fabs(dx) > t || fabs(dy) > t || fabs(dz) > t || isnan(dx) || isnan(dy) || isnan(dz))
        return 0;
    dx /= t, dy /= t, dz /= t;
    return dx * dx + dy * dy + dz * dz <= 1.0;
}

static size_t ref_root(size_t *p, size_t x)
{
    while (p[x] != x)
        x = p[x];
    return x;
}

/* cls[i]: the smallest old index of i's class */
static void ref_classes(const double *v, size_t nv, double t, size_t *cls)
{
    for (size_t i = 0; i < nv; ++i)
        cls[i] = i;
    for (size_t i = 0; i < nv; ++i)
        for (size_t j = i + 1; j < nv; ++j)
            if (ref_within(v + 3 * i, v + 3 * j, t)) {
                size_t a = ref_root(cls, i), b = ref_root(cls, j);
                if (a < b)
                    cls[b] = a;
                else if (b < a)
                    cls[a] = b;
            }
    for (size_t i = 0; i < nv; ++i)
        cls[i] = ref_root(cls, i);
}

static int lex_less(const double *a, const double *b)
{
    for (int k = 0; k < 3; ++k) {
        if (a[k] < b[k])
            return 1;
        if (a[k] > b[k])
            return 0;
    }
    return 0;
}

/* The weld's whole output against the reference: classes, numbering, representatives,
 * triangles kept and dropped. */
static size_t merged_total, classes_total, dropped_total; /* to see that the cases merge */

static int check_against_reference(const double *v, size_t nv, const uint32_t *tris, size_t nt, double t)
{
    size_t *cls = malloc(nv * sizeof *cls), nvo = 0, nto = 0;
    double *vo = malloc(3 * nv * sizeof *vo);
    uint32_t *to = malloc((3 * nt + 1) * sizeof *to), *map = malloc(nv * sizeof *map);
    size_t *newidx = malloc(nv * sizeof *newidx);
    ENSURE(cls && vo && to && map && newidx);
    ref_classes(v, nv, t, cls);
    ENSURE(ttd_mesh_weld_d(v, nv, tris, nt, t, vo, &nvo, to, &nto, map) == TTD_OK);
    /* numbering: classes in order of their smallest old index */
    size_t n = 0;
    for (size_t i = 0; i < nv; ++i)
        if (cls[i] == i)
            newidx[i] = n++;
    ENSURE_MSG(nvo == n, "tol %g: %zu vertices, the reference %zu", t, nvo, n);
    for (size_t i = 0; i < nv; ++i)
        ENSURE_MSG(map[i] == newidx[cls[i]], "tol %g: vertex %zu -> %u, the reference %zu", t, i, map[i], newidx[cls[i]]);
    /* the representative: the class's lexicographically smallest member, zero as +0 */
    for (size_t i = 0; i < nv; ++i) {
        const double *o = vo + 3 * (size_t)map[i];
        ENSURE(!lex_less(v + 3 * i, o));
        for (int k = 0; k < 3; ++k)
            ENSURE(!(o[k] == 0 && signbit(o[k])));
    }
    for (size_t j = 0; j < nvo; ++j) { /* and it is a member */
        int found = 0;
        for (size_t i = 0; i < nv && !found; ++i)
            found = map[i] == j && v[3 * i] == vo[3 * j] && v[3 * i + 1] == vo[3 * j + 1] && v[3 * i + 2] == vo[3 * j + 2];
        ENSURE(found);
    }
    /* triangles: the collapsed dropped, the rest in order */
    size_t k = 0;
    for (size_t f = 0; f < nt; ++f) {
        size_t a = newidx[cls[tris[3 * f]]], b = newidx[cls[tris[3 * f + 1]]], c = newidx[cls[tris[3 * f + 2]]];
        if (a == b || b == c || a == c)
            continue;
        ENSURE(k < nto);
        ENSURE(to[3 * k] == a && to[3 * k + 1] == b && to[3 * k + 2] == c);
        ++k;
    }
    ENSURE(k == nto);
    merged_total += nv - nvo;
    classes_total += nvo;
    dropped_total += nt - nto;
    free(cls);
    free(vo);
    free(to);
    free(map);
    free(newidx);
    return 0;
}

/* nv points in clusters: centres in [-s, s]^3, members at offsets of a chosen size in random
 * directions (some within the tolerance, some just beyond, some a few ulps), zeros of both
 * signs; triangles of random vertices. */
static void clustered(size_t nv, double s, double spread, double *v, size_t nt, uint32_t *tris)
{
    size_t centres = nv / 4 + 1;
    double *c = malloc(3 * centres * sizeof *c);
    for (size_t i = 0; i < 3 * centres; ++i) {
        c[i] = (2 * unit() - 1) * s;
        if (rnd() % 8 == 0)
            c[i] = 0; /* zeros, signed below */
    }
    for (size_t i = 0; i < nv; ++i) {
        const double *ci = c + 3 * (rnd() % centres);
        uint64_t kind = rnd() % 4;
        for (int d = 0; d < 3; ++d) {
            double x = ci[d];
            if (kind == 1)
                x += (2 * unit() - 1) * spread;
            else if (kind == 2)
                for (int u = (int)(rnd() % 4); u > 0; --u)
                    x = nextafter(x, rnd() & 1 ? INFINITY : -INFINITY);
            if (x == 0 && (rnd() & 1))
                x = -0.0;
            v[3 * i + (size_t)d] = x;
        }
    }
    for (size_t f = 0; f < 3 * nt; ++f)
        tris[f] = (uint32_t)(rnd() % nv);
    free(c);
}

static int test_against_brute_force(void)
{
    enum { NV = 240, NT = 300 };
    static double v[3 * NV];
    static uint32_t tris[3 * NT];
    /* (scale, spread, tolerances): the fine grid, tolerances larger than the mesh, tolerance 0
     * and tolerances of a few ulps of coordinates near 1e10 (the coarse grid) */
    const struct {
        double s, spread, tol[4];
    } cases[] = {
        {1, 1e-3, {1e-3, 5e-4, 2e-3, 0}},
        {1, 0.3, {0.1, 0.25, 3, 1e-9}},
        {1e10, 1e-5, {1e-6, 1e-5, 3e-6, 0}},
        {1e-200, 1e-203, {1e-203, 1e-210, 0, 5e-204}},
        {1e200, 1e190, {1e190, 1e185, 1e195, 0}},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c)
        for (int rep = 0; rep < 6; ++rep) {
            clustered(NV, cases[c].s, cases[c].spread, v, NT, tris);
            for (int k = 0; k < 4; ++k)
                if (check_against_reference(v, NV, tris, NT, cases[c].tol[k]) != 0) {
                    fprintf(stderr, "  case %zu, repetition %d, tolerance %g\n", c, rep, cases[c].tol[k]);
                    return 1;
                }
        }
    printf("  %zu classes, %zu vertices merged away, %zu triangles dropped\n", classes_total, merged_total, dropped_total);
    ENSURE(merged_total > 1000 && classes_total > 1000 && dropped_total > 100);
    return 0;
}

/* A chain: points 0.9 tol apart in a line are one vertex although the ends are far apart. */
static int test_chain_and_signed_zero(void)
{
    double v[3 * 10];
    for (int i = 0; i < 10; ++i) {
        v[3 * i] = 0.9 * i;
        v[3 * i + 1] = v[3 * i + 2] = 0;
    }
    uint32_t t[3] = {0, 5, 9}, to[3], map[10];
    double vo[30];
    size_t nvo, nto;
    ENSURE(ttd_mesh_weld_d(v, 10, t, 1, 1.0, vo, &nvo, to, &nto, map) == TTD_OK);
    ENSURE(nvo == 1 && nto == 0);
    ENSURE(ttd_mesh_weld_d(v, 10, t, 1, 0.89, vo, &nvo, to, &nto, map) == TTD_OK);
    ENSURE(nvo == 10 && nto == 1);
    /* -0 and +0: one vertex at tolerance 0, written +0; its first index decides the number */
    double z[9] = {-0.0, 0.0, -0.0, 0.0, -0.0, 0.0, 1, 0, 0};
    uint32_t tz[3] = {0, 1, 2};
    ENSURE(ttd_mesh_weld_d(z, 3, tz, 1, 0.0, vo, &nvo, to, &nto, map) == TTD_OK);
    ENSURE(nvo == 2 && nto == 0 && map[0] == 0 && map[1] == 0 && map[2] == 1);
    ENSURE(!signbit(vo[0]) && !signbit(vo[1]) && !signbit(vo[2]));
    return 0;
}

/* The output's vertices as points and its triangles as point triples do not depend on the
 * order of the input's vertices. */
static int test_order_independent(void)
{
    enum { NV = 2000, NT = 3000 };
    double *v = malloc(3 * NV * sizeof *v), *w = malloc(3 * NV * sizeof *w);
    double *o1 = malloc(3 * NV * sizeof *o1), *o2 = malloc(3 * NV * sizeof *o2);
    double *t1 = malloc(9 * NT * sizeof *t1), *t2 = malloc(9 * NT * sizeof *t2);
    uint32_t *tris = malloc(3 * NT * sizeof *tris), *tp = malloc(3 * NT * sizeof *tp);
    uint32_t *r1 = malloc(3 * NT * sizeof *r1), *r2 = malloc(3 * NT * sizeof *r2), *perm = malloc(NV * sizeof *perm);
    ENSURE(v && w && o1 && o2 && t1 && t2 && tris && tp && r1 && r2 && perm);
    clustered(NV, 1, 2e-3, v, NT, tris);
    for (size_t i = 0; i < NV; ++i)
        perm[i] = (uint32_t)i;
    for (size_t i = NV - 1; i > 0; --i) {
        size_t j = rnd() % (i + 1);
        uint32_t x = perm[i];
        perm[i] = perm[j];
        perm[j] = x;
    }
    for (size_t i = 0; i < NV; ++i) /* old vertex i is new vertex perm[i] */
        memcpy(w + 3 * (size_t)perm[i], v + 3 * i, 3 * sizeof *v);
    for (size_t f = 0; f < 3 * NT; ++f)
        tp[f] = perm[tris[f]];
    size_t n1, n2, m1, m2;
    ENSURE(ttd_mesh_weld_d(v, NV, tris, NT, 1e-3, o1, &n1, r1, &m1, NULL) == TTD_OK);
    ENSURE(ttd_mesh_weld_d(w, NV, tp, NT, 1e-3, o2, &n2, r2, &m2, NULL) == TTD_OK);
    ENSURE(n1 == n2 && m1 == m2);
    ENSURE(n1 < NV / 2); /* the case does merge */
    for (size_t f = 0; f < m1; ++f)
        for (int c = 0; c < 3; ++c) {
            memcpy(t1 + 9 * f + 3 * c, o1 + 3 * (size_t)r1[3 * f + (size_t)c], 3 * sizeof *t1);
            memcpy(t2 + 9 * f + 3 * c, o2 + 3 * (size_t)r2[3 * f + (size_t)c], 3 * sizeof *t2);
        }
    /* as the triangles keep their order, the point triples match one by one */
    ENSURE(memcmp(t1, t2, 9 * m1 * sizeof *t1) == 0);
    /* and so do the vertices, each class's in its number's place */
    for (size_t j = 0; j < n1; ++j) {
        int found = 0;
        for (size_t i = 0; i < n2 && !found; ++i)
            found = memcmp(o1 + 3 * j, o2 + 3 * i, 3 * sizeof *o1) == 0;
        ENSURE(found);
    }
    free(v), free(w), free(o1), free(o2), free(t1), free(t2), free(tris), free(tp), free(r1), free(r2), free(perm);
    return 0;
}

/* ---- construction: a closed mesh as an STL soup ---------------------------------------- */

static int solid_status(const double *v, size_t nv, const uint32_t *t, size_t nt)
{
    ttd_options opt = ttd_default_options();
    opt.solid = 1;
    ttd_mesh *m = NULL;
    if (ttd_mesh_create_d(&opt, v, nv, t, nt, &m) != TTD_OK)
        return -1;
    double pose[12] = {1, 0, 0, 5, 0, 1, 0, 0, 0, 0, 1, 0};
    ttd_mesh_result_d r;
    ttd_status st = ttd_mesh_distance_d(&opt, m, m, 1, pose, INFINITY, 0, &r);
    ttd_mesh_destroy(m);
    return (int)st;
}

static int soup_welds_closed(const ttd_gen_mesh *g, int ulps, double tol)
{
    size_t nv = 3 * g->nt;
    double *v = malloc(3 * nv * sizeof *v);
    uint32_t *t = malloc(3 * g->nt * sizeof *t), *map = malloc(nv * sizeof *map);
    ENSURE(v && t && map);
    for (size_t f = 0; f < g->nt; ++f)
        for (int c = 0; c < 3; ++c) {
            const double *p = g->verts + 3 * (size_t)g->tris[3 * f + (size_t)c];
            for (int d = 0; d < 3; ++d) {
                double x = p[d];
                for (int u = (int)(rnd() % (unsigned)(2 * ulps + 1)) - ulps; u != 0; u += u > 0 ? -1 : 1)
                    x = nextafter(x, u > 0 ? INFINITY : -INFINITY);
                v[9 * f + 3 * (size_t)c + (size_t)d] = x;
            }
            t[3 * f + (size_t)c] = (uint32_t)(3 * f + (size_t)c);
        }
    ENSURE(solid_status(v, nv, t, g->nt) == TTD_ERR_MESH_NOT_CLOSED);
    size_t nvo, nto;
    ENSURE(ttd_mesh_weld_d(v, nv, t, g->nt, tol, v, &nvo, t, &nto, map) == TTD_OK); /* in place */
    ENSURE_MSG(nvo == g->nv && nto == g->nt, "%zu vertices (%zu before), %zu triangles (%zu)", nvo, g->nv, nto, g->nt);
    /* every corner maps to a vertex within tol of the original corner */
    for (size_t f = 0; f < g->nt; ++f)
        for (int c = 0; c < 3; ++c) {
            const double *p = g->verts + 3 * (size_t)g->tris[3 * f + (size_t)c], *q = v + 3 * (size_t)t[3 * f + (size_t)c];
            ENSURE(fabs(p[0] - q[0]) <= tol && fabs(p[1] - q[1]) <= tol && fabs(p[2] - q[2]) <= tol);
        }
    ENSURE(solid_status(v, nvo, t, nto) == TTD_OK);
    free(v);
    free(t);
    free(map);
    return 0;
}

static int test_soup_becomes_closed(void)
{
    ttd_gen_mesh s = {0}, tor = {0};
    ENSURE(ttd_gen_icosphere(3, &s) == 0);
    ENSURE(ttd_gen_torus(1.0, 0.3, 48, 24, &tor) == 0);
    ENSURE(soup_welds_closed(&s, 2, 1e-12) == 0);
    ENSURE(soup_welds_closed(&tor, 3, 1e-12) == 0);
    ENSURE(soup_welds_closed(&s, 0, 0) == 0); /* exact copies: tolerance 0 is enough */
    ttd_gen_mesh_free(&s);
    ttd_gen_mesh_free(&tor);
    return 0;
}

/* A tolerance larger than the mesh: one vertex, every triangle dropped, in about the sort's time
 * (the grid's cubes are whole classes; a pairwise test would take 10^10 steps). */
static int test_huge_tolerance(void)
{
    ttd_gen_mesh s = {0};
    ENSURE(ttd_gen_icosphere(6, &s) == 0); /* 40,962 vertices */
    size_t nvo, nto;
    double *vo = malloc(3 * s.nv * sizeof *vo);
    uint32_t *to = malloc(3 * s.nt * sizeof *to);
    ENSURE(ttd_mesh_weld_d(s.verts, s.nv, s.tris, s.nt, 10.0, vo, &nvo, to, &nto, NULL) == TTD_OK);
    ENSURE(nvo == 1 && nto == 0);
    ENSURE(vo[0] == -1 || vo[0] < -0.99); /* the lexicographically smallest: smallest x */
    ENSURE(ttd_mesh_weld_d(s.verts, s.nv, s.tris, s.nt, 0.5, vo, &nvo, to, &nto, NULL) == TTD_OK);
    ENSURE(nvo == 1 && nto == 0); /* chained: neighbours 0.5 apart join the whole sphere */
    ttd_gen_mesh_free(&s);
    free(vo);
    free(to);
    return 0;
}

static int test_float(void)
{
    enum { NV = 200, NT = 200 };
    static double v[3 * NV], vr[3 * NV];
    static float vf[3 * NV], of[3 * NV];
    static uint32_t tris[3 * NT], to[3 * NT], map[NV];
    static size_t cls[NV];
    for (int rep = 0; rep < 5; ++rep) {
        clustered(NV, 1, 1e-3, v, NT, tris);
        for (size_t i = 0; i < 3 * NV; ++i) {
            vf[i] = (float)v[i];
            vr[i] = vf[i];
        }
        ref_classes(vr, NV, (double)1e-3f, cls);
        size_t nvo, nto;
        ENSURE(ttd_mesh_weld_f(vf, NV, tris, NT, 1e-3f, of, &nvo, to, &nto, map) == TTD_OK);
        for (size_t i = 0; i < NV; ++i)
            for (size_t j = 0; j < NV; ++j)
                ENSURE((cls[i] == cls[j]) == (map[i] == map[j]));
        for (size_t i = 0; i < NV; ++i) { /* the kept vertex: lexicographically smallest */
            double o[3] = {of[3 * (size_t)map[i]], of[3 * (size_t)map[i] + 1], of[3 * (size_t)map[i] + 2]};
            ENSURE(!lex_less(vr + 3 * i, o));
        }
    }
    return 0;
}

static int test_errors(void)
{
    double v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, vo[9];
    uint32_t t[3] = {0, 1, 2}, to[3];
    size_t nvo = 77, nto = 77;
    ENSURE(ttd_mesh_weld_d(NULL, 3, t, 1, 0, vo, &nvo, to, &nto, NULL) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_mesh_weld_d(v, 3, t, 1, 0, vo, NULL, to, &nto, NULL) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_mesh_weld_d(v, 3, NULL, 1, 0, vo, &nvo, to, &nto, NULL) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_mesh_weld_d(v, 0, t, 1, 0, vo, &nvo, to, &nto, NULL) == TTD_ERR_EMPTY);
    ENSURE(ttd_mesh_weld_d(v, 3, t, 1, -1, vo, &nvo, to, &nto, NULL) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_mesh_weld_d(v, 3, t, 1, NAN, vo, &nvo, to, &nto, NULL) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_mesh_weld_d(v, 3, t, 1, INFINITY, vo, &nvo, to, &nto, NULL) == TTD_ERR_BAD_OPTIONS);
    uint32_t bad[3] = {0, 1, 3};
    ENSURE(ttd_mesh_weld_d(v, 3, bad, 1, 0, vo, &nvo, to, &nto, NULL) == TTD_ERR_INDEX_OUT_OF_RANGE);
    v[4] = NAN;
    ENSURE(ttd_mesh_weld_d(v, 3, t, 1, 0, vo, &nvo, to, &nto, NULL) == TTD_ERR_NONFINITE_MESH);
    ENSURE(nvo == 77 && nto == 77); /* nothing written */
    v[4] = 0;
    ENSURE(ttd_mesh_weld_d(v, 3, NULL, 0, 0, vo, &nvo, NULL, &nto, NULL) == TTD_OK && nvo == 3 && nto == 0);
    float f[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, fo[9];
    ENSURE(ttd_mesh_weld_f(f, 3, t, 1, -1.0f, fo, &nvo, to, &nto, NULL) == TTD_ERR_BAD_OPTIONS);
    f[0] = INFINITY;
    ENSURE(ttd_mesh_weld_f(f, 3, t, 1, 0.0f, fo, &nvo, to, &nto, NULL) == TTD_ERR_NONFINITE_MESH);
    return 0;
}

/* ttd_meshfile_weld: a binary-STL-like soup read from memory, welded with its floats. */
static int test_meshfile_weld(void)
{
    const char *obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1e-9 0 0\nv 1 1 0\nv 0 1.0000000001 0\n"
                      "f 1 2 3\nf 4 5 6\nf 1 4 2\n";
    ttd_meshfile m;
    char err[256];
    ENSURE(ttd_meshfile_parse("w.obj", (const unsigned char *)obj, strlen(obj), TTD_MESHFILE_FLOAT, &m, err, sizeof err) == 0);
    size_t dropped = 9;
    ENSURE(ttd_meshfile_weld(&m, 1e-8, &dropped, err, sizeof err) == 0);
    ENSURE(m.nv == 4 && m.nt == 2 && dropped == 1);
    ENSURE(m.verts[0] == 0 && m.verts_f[0] == 0 && m.verts_f[3] == 1.0f);
    ENSURE(m.tris[3] == 0 && m.tris[4] == 3 && m.tris[5] == 2);
    ENSURE(ttd_meshfile_weld(&m, -1, &dropped, err, sizeof err) == -1 && strstr(err, "tolerance"));
    ENSURE(ttd_meshfile_weld(&m, 5, &dropped, err, sizeof err) == -1 && strstr(err, "collapses"));
    ENSURE(m.nv == 4 && m.nt == 2); /* unchanged */
    ttd_meshfile_free(&m);
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(test_against_brute_force);
    RUN_TEST(test_chain_and_signed_zero);
    RUN_TEST(test_order_independent);
    RUN_TEST(test_soup_becomes_closed);
    RUN_TEST(test_huge_tolerance);
    RUN_TEST(test_float);
    RUN_TEST(test_errors);
    RUN_TEST(test_meshfile_weld);
    TEST_MAIN_END();
}
