/* SPDX-License-Identifier: MIT */
/* Solid mesh queries (ttd_options.solid): distance and collision treat closed meshes as solids.
 *   - against an independent inside test: a small icosphere placed at random in and around a large
 *     one (both convex polyhedra, so "inside" is every face plane's inequality, no winding
 *     number), and the large one around the small: where the surfaces do not meet, the solid
 *     query says contained exactly when the plane test does, and otherwise returns the surface
 *     query's answer bit for bit; where they meet, the surface answer;
 *   - a tetrahedron inside a cube (the case a surface query reports at 0.4), the cube inside a
 *     larger tetrahedron (a inside b), nested and touching, an inside-out cube, both precisions;
 *   - open meshes (a grid, a cube without a face, a mesh with an edge used three times) refused
 *     with TTD_ERR_MESH_NOT_CLOSED, while the surface queries still answer. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshes.h"
#include "pairs.h"
#include "test_macros.h"
#include <ttd/ttd.h>

static ttd_options solid_options(int solid)
{
    ttd_options o = ttd_default_options();
    o.solid = solid;
    return o;
}

/* Whether x is strictly inside the convex closed mesh m (outward-oriented faces): below every
 * face's plane by more than tol. */
static int convex_inside(const ttd_gen_mesh *m, const double x[3], double tol)
{
    for (size_t t = 0; t < m->nt; ++t) {
        const double *a = m->verts + 3 * m->tris[3 * t], *b = m->verts + 3 * m->tris[3 * t + 1],
                     *c = m->verts + 3 * m->tris[3 * t + 2];
        const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        const double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if ((n[0] * (x[0] - a[0]) + n[1] * (x[1] - a[1]) + n[2] * (x[2] - a[2])) / len > -tol)
            return 0;
    }
    return 1;
}

static void apply(const double P[12], const double x[3], double out[3])
{
    for (int r = 0; r < 3; ++r)
        out[r] = ((P[4 * r] * x[0] + P[4 * r + 1] * x[1]) + P[4 * r + 2] * x[2]) + P[4 * r + 3];
}

static void scale_mesh(ttd_gen_mesh *m, double s)
{
    for (size_t i = 0; i < 3 * m->nv; ++i)
        m->verts[i] *= s;
}

/* Random placements of small (b) in and around big (a), and of big around small: the solid
 * answers against the convex-plane test and the surface answers. */
static int spheres_against_plane_test(void)
{
    ttd_gen_mesh big, small;
    ENSURE(ttd_gen_icosphere(2, &big) == 0);
    ENSURE(ttd_gen_icosphere(1, &small) == 0);
    scale_mesh(&small, 0.15);
    ttd_mesh *mb, *ms;
    ENSURE(ttd_mesh_create_d(NULL, big.verts, big.nv, big.tris, big.nt, &mb) == TTD_OK);
    ENSURE(ttd_mesh_create_d(NULL, small.verts, small.nv, small.tris, small.nt, &ms) == TTD_OK);
    const ttd_options surf = solid_options(0), sol = solid_options(1);
    int contained = 0, apart = 0, meeting = 0;
    for (uint64_t i = 0; i < 400; ++i) {
        double P[12];
        ttd_gen_pose(2026, i, 1.1, P);
        for (int swap = 0; swap < 2; ++swap) {
            /* swap: the big one is b, placed around the small one (a at identity): the pose's
             * inverse keeps the geometry, so the same answer in the plane test */
            const ttd_mesh *a = swap ? ms : mb, *b = swap ? mb : ms;
            double Q[12];
            if (!swap) {
                memcpy(Q, P, sizeof Q);
            } else { /* Q = P^-1: [R^T | -R^T t] */
                for (int r = 0; r < 3; ++r) {
                    Q[4 * r + 3] = 0;
                    for (int c = 0; c < 3; ++c) {
                        Q[4 * r + c] = P[4 * c + r];
                        Q[4 * r + 3] -= P[4 * c + r] * P[4 * c + 3];
                    }
                }
            }
            ttd_mesh_result_d rs, rv;
            ttd_collision cs, cv;
            ENSURE(ttd_mesh_distance_d(&surf, a, b, 1, Q, INFINITY, 0, &rs) == TTD_OK);
            ENSURE(ttd_mesh_distance_d(&sol, a, b, 1, Q, INFINITY, 0, &rv) == TTD_OK);
            ENSURE(ttd_mesh_collide_d(&surf, a, b, 1, Q, 0, &cs) == TTD_OK);
            ENSURE(ttd_mesh_collide_d(&sol, a, b, 1, Q, 0, &cv) == TTD_OK);
            if (rs.distance == 0) { /* surfaces meet: the surface answer */
                ++meeting;
                ENSURE(memcmp(&rs, &rv, sizeof rs) == 0 && cv.hit && cs.hit && cv.tri_a == cs.tri_a);
                continue;
            }
            /* the small sphere's first vertex (triangle 0, vertex 0) in the big one's frame */
            double x[3];
            const double *v0 = small.verts + 3 * small.tris[0];
            apply(P, v0, x);
            const int in = convex_inside(&big, x, 1e-12);
            ENSURE_MSG(in || !convex_inside(&big, x, -1e-12), "pose %llu: too near the surface to tell",
                       (unsigned long long)i);
            if (in) {
                ++contained;
                ENSURE_MSG(rv.distance == 0 && rv.flags == (TTD_MESH_INTERSECTING | TTD_MESH_CONTAINED),
                           "pose %llu swap %d: the small sphere inside, solid distance %.17g flags %u",
                           (unsigned long long)i, swap, rv.distance, rv.flags);
                ENSURE(cv.hit == 1 && !cs.hit);
                /* the inner mesh's triangle 0 named, the outer's not; p = q on the inner vertex */
                ENSURE(swap ? (rv.tri_a == 0 && rv.tri_b == UINT32_MAX) : (rv.tri_b == 0 && rv.tri_a == UINT32_MAX));
                ENSURE(swap ? (cv.tri_a == 0 && cv.tri_b == UINT32_MAX) : (cv.tri_b == 0 && cv.tri_a == UINT32_MAX));
                for (int c = 0; c < 3; ++c)
                    ENSURE(rv.p[c] == rv.q[c]);
                double want[3];
                if (swap)
                    memcpy(want, v0, sizeof want);
                else
                    apply(Q, v0, want);
                for (int c = 0; c < 3; ++c)
                    ENSURE(rv.p[c] == want[c]);
            } else {
                ++apart;
                ENSURE_MSG(memcmp(&rs, &rv, sizeof rs) == 0, "pose %llu swap %d: outside, the solid answer differs",
                           (unsigned long long)i, swap);
                ENSURE(!cv.hit && cv.tri_a == UINT32_MAX);
            }
        }
    }
    printf("  800 placements: %d contained, %d apart, %d with the surfaces meeting\n", contained, apart, meeting);
    ENSURE(contained > 50 && apart > 50 && meeting > 10);
    ttd_mesh_destroy(mb);
    ttd_mesh_destroy(ms);
    ttd_gen_mesh_free(&big);
    ttd_gen_mesh_free(&small);
    return 0;
}

/* The case and its relatives, in both precisions. */
static int tetrahedron_in_cube(void)
{
    ttd_gen_mesh cube, tet, flipped;
    ENSURE(ttd_gen_mesh_cube(&cube) == 0);
    ENSURE(ttd_gen_mesh_tetrahedron(&tet) == 0);
    ENSURE(ttd_gen_mesh_copy(&cube, &flipped) == 0);
    for (size_t t = 0; t < flipped.nt; ++t) { /* inside out: every triangle reversed */
        const uint32_t x = flipped.tris[3 * t + 1];
        flipped.tris[3 * t + 1] = flipped.tris[3 * t + 2];
        flipped.tris[3 * t + 2] = x;
    }
    double lo[3], hi[3], tlo[3], thi[3];
    ENSURE(ttd_gen_mesh_bounds(&cube, lo, hi) == 0);
    ENSURE(ttd_gen_mesh_bounds(&tet, tlo, thi) == 0);
    const double s = 0.25 * (hi[0] - lo[0]) / (thi[0] - tlo[0]);
    double P[12] = {s, 0, 0, 0, 0, s, 0, 0, 0, 0, s, 0}; /* the tetrahedron scaled into the cube's middle */
    ttd_gen_mesh small;
    ENSURE(ttd_gen_mesh_transform(&tet, P, &small) == 0);
    double c[3] = {0, 0, 0}, tc[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k) {
        c[k] = 0.5 * (lo[k] + hi[k]);
        for (size_t v = 0; v < small.nv; ++v)
            tc[k] += small.verts[3 * v + (size_t)k] / (double)small.nv;
    }
    const double id[12] = {1, 0, 0, c[0] - tc[0], 0, 1, 0, c[1] - tc[1], 0, 0, 1, c[2] - tc[2]};
    const double away[12] = {1, 0, 0, c[0] - tc[0] + 3 * (hi[0] - lo[0]), 0, 1, 0, c[1] - tc[1], 0, 0, 1, c[2] - tc[2]};
    const ttd_options surf = solid_options(0), sol = solid_options(1);
    for (int prec = 0; prec < 2; ++prec) {
        const ttd_gen_mesh *outer_list[2] = {&cube, &flipped};
        for (int o = 0; o < 2; ++o) {
            const ttd_gen_mesh *outer = outer_list[o];
            if (prec == 0) {
                ttd_mesh *a, *b;
                ENSURE(ttd_mesh_create_d(NULL, outer->verts, outer->nv, outer->tris, outer->nt, &a) == TTD_OK);
                ENSURE(ttd_mesh_create_d(NULL, small.verts, small.nv, small.tris, small.nt, &b) == TTD_OK);
                ttd_mesh_result_d r;
                ttd_collision x;
                ENSURE(ttd_mesh_distance_d(&surf, a, b, 1, id, INFINITY, 0, &r) == TTD_OK && r.distance > 0.1);
                ENSURE(ttd_mesh_collide_d(&surf, a, b, 1, id, 0, &x) == TTD_OK && !x.hit);
                ENSURE(ttd_mesh_distance_d(&sol, a, b, 1, id, INFINITY, 0, &r) == TTD_OK);
                ENSURE(r.distance == 0 && (r.flags & TTD_MESH_CONTAINED) && r.tri_b == 0);
                ENSURE(ttd_mesh_distance_d(&sol, a, b, 1, id, 0.01, 0, &r) == TTD_OK && r.distance == 0); /* within any bound */
                ENSURE(ttd_mesh_collide_d(&sol, a, b, 1, id, 0, &x) == TTD_OK && x.hit);
                /* a inside b: the small one as a */
                ENSURE(ttd_mesh_distance_d(&sol, b, a, 1, away, INFINITY, 0, &r) == TTD_OK && r.distance > 0);
                double inv[12] = {1, 0, 0, -id[3], 0, 1, 0, -id[7], 0, 0, 1, -id[11]};
                ENSURE(ttd_mesh_distance_d(&sol, b, a, 1, inv, INFINITY, 0, &r) == TTD_OK);
                ENSURE(r.distance == 0 && (r.flags & TTD_MESH_CONTAINED) && r.tri_a == 0 && r.tri_b == UINT32_MAX);
                ttd_mesh_destroy(a);
                ttd_mesh_destroy(b);
            } else {
                float *va = malloc(3 * outer->nv * sizeof *va), *vb = malloc(3 * small.nv * sizeof *vb);
                ENSURE(va && vb);
                for (size_t i = 0; i < 3 * outer->nv; ++i)
                    va[i] = (float)outer->verts[i];
                for (size_t i = 0; i < 3 * small.nv; ++i)
                    vb[i] = (float)small.verts[i];
                float idf[12];
                for (int k = 0; k < 12; ++k)
                    idf[k] = (float)id[k];
                ttd_mesh *a, *b;
                ENSURE(ttd_mesh_create_f(NULL, va, outer->nv, outer->tris, outer->nt, &a) == TTD_OK);
                ENSURE(ttd_mesh_create_f(NULL, vb, small.nv, small.tris, small.nt, &b) == TTD_OK);
                ttd_mesh_result_f r;
                ttd_collision x;
                ENSURE(ttd_mesh_distance_f(&surf, a, b, 1, idf, INFINITY, 0, &r) == TTD_OK && r.distance > 0.1f);
                ENSURE(ttd_mesh_distance_f(&sol, a, b, 1, idf, INFINITY, 0, &r) == TTD_OK);
                ENSURE(r.distance == 0 && (r.flags & TTD_MESH_CONTAINED));
                ENSURE(ttd_mesh_collide_f(&sol, a, b, 1, idf, 0, &x) == TTD_OK && x.hit);
                ttd_mesh_destroy(a);
                ttd_mesh_destroy(b);
                free(va);
                free(vb);
            }
        }
    }
    ttd_gen_mesh_free(&cube);
    ttd_gen_mesh_free(&tet);
    ttd_gen_mesh_free(&flipped);
    ttd_gen_mesh_free(&small);
    return 0;
}

/* Nesting at tiny and huge scales and far from the origin (the winding number works at unit
 * scale per triangle), and a closed sliver (a tetrahedron 1e-9 of its size thick) that holds
 * nothing: a small sphere inside the large one is contained, one beside it is not, and the sliver
 * answers as its surface does. */
static int nesting_at_scales(void)
{
    static const double scales[][2] = {{1e-8, 0}, {1e8, 0}, {1, 1e6}, {1e-6, 3e-4}};
    ttd_gen_mesh big, small, sliver;
    ENSURE(ttd_gen_icosphere(2, &big) == 0);
    ENSURE(ttd_gen_icosphere(1, &small) == 0);
    ENSURE(ttd_gen_mesh_tetrahedron(&sliver) == 0);
    for (size_t v = 0; v < sliver.nv; ++v)
        sliver.verts[3 * v + 2] *= 1e-9; /* the apex nearly in the base's plane */
    const ttd_options sol = solid_options(1), surf = solid_options(0);
    for (size_t c = 0; c < sizeof scales / sizeof scales[0]; ++c) {
        const double k = scales[c][0], o = scales[c][1];
        ttd_gen_mesh B, S, L;
        const double scale_big[12] = {k, 0, 0, o, 0, k, 0, o, 0, 0, k, o};
        const double scale_small[12] = {0.15 * k, 0, 0, 0, 0, 0.15 * k, 0, 0, 0, 0, 0.15 * k, 0};
        const double scale_sliver[12] = {k, 0, 0, 0, 0, k, 0, 0, 0, 0, k, 0};
        ENSURE(ttd_gen_mesh_transform(&big, scale_big, &B) == 0);
        ENSURE(ttd_gen_mesh_transform(&small, scale_small, &S) == 0);
        ENSURE(ttd_gen_mesh_transform(&sliver, scale_sliver, &L) == 0);
        ttd_mesh *mb, *ms, *ml;
        ENSURE(ttd_mesh_create_d(NULL, B.verts, B.nv, B.tris, B.nt, &mb) == TTD_OK);
        ENSURE(ttd_mesh_create_d(NULL, S.verts, S.nv, S.tris, S.nt, &ms) == TTD_OK);
        ENSURE(ttd_mesh_create_d(NULL, L.verts, L.nv, L.tris, L.nt, &ml) == TTD_OK);
        const double inside[12] = {1, 0, 0, o + 0.3 * k, 0, 1, 0, o - 0.2 * k, 0, 0, 1, o + 0.1 * k};
        const double beside[12] = {1, 0, 0, o + 1.4 * k, 0, 1, 0, o, 0, 0, 1, o};
        ttd_mesh_result_d r, rs;
        ttd_collision x;
        ENSURE(ttd_mesh_distance_d(&sol, mb, ms, 1, inside, INFINITY, 0, &r) == TTD_OK);
        ENSURE_MSG(r.distance == 0 && (r.flags & TTD_MESH_CONTAINED), "scale %g offset %g: not contained", k, o);
        ENSURE(ttd_mesh_collide_d(&sol, ms, mb, 1, (const double[12]){1, 0, 0, -inside[3], 0, 1, 0, -inside[7], 0, 0, 1,
                                                                      -inside[11]},
                                  0, &x) == TTD_OK &&
               x.hit && x.tri_a == 0 && x.tri_b == UINT32_MAX);
        ENSURE(ttd_mesh_distance_d(&sol, mb, ms, 1, beside, INFINITY, 0, &r) == TTD_OK);
        ENSURE(ttd_mesh_distance_d(&surf, mb, ms, 1, beside, INFINITY, 0, &rs) == TTD_OK);
        ENSURE_MSG(r.distance > 0 && memcmp(&r, &rs, sizeof r) == 0, "scale %g offset %g: beside", k, o);
        /* the sliver, 0.2 of its size above the small sphere's centre: surfaces apart, nothing inside */
        const double above[12] = {1, 0, 0, -0.3 * k, 0, 1, 0, -0.3 * k, 0, 0, 1, 0.2 * k};
        ENSURE(ttd_mesh_distance_d(&sol, ms, ml, 1, above, INFINITY, 0, &r) == TTD_OK);
        ENSURE(ttd_mesh_distance_d(&surf, ms, ml, 1, above, INFINITY, 0, &rs) == TTD_OK);
        ENSURE_MSG(rs.distance > 0 && memcmp(&r, &rs, sizeof r) == 0, "scale %g: the sliver", k);
        ttd_mesh_destroy(mb);
        ttd_mesh_destroy(ms);
        ttd_mesh_destroy(ml);
        ttd_gen_mesh_free(&B);
        ttd_gen_mesh_free(&S);
        ttd_gen_mesh_free(&L);
    }
    ttd_gen_mesh_free(&big);
    ttd_gen_mesh_free(&small);
    ttd_gen_mesh_free(&sliver);
    return 0;
}

/* Open meshes are refused in solid mode and answered in surface mode. */
static int open_meshes_refused(void)
{
    ttd_gen_mesh cube, grid, open, tri3;
    ENSURE(ttd_gen_mesh_cube(&cube) == 0);
    ENSURE(ttd_gen_grid(3, &grid) == 0);
    ENSURE(ttd_gen_mesh_copy(&cube, &open) == 0);
    open.nt -= 1; /* one face short */
    ENSURE(ttd_gen_mesh_copy(&cube, &tri3) == 0);
    /* the cube with its first triangle twice: that triangle's edges are used three times */
    uint32_t *t = realloc(tri3.tris, 3 * (tri3.nt + 1) * sizeof *t);
    ENSURE(t != NULL);
    tri3.tris = t;
    memcpy(t + 3 * tri3.nt, t, 3 * sizeof *t);
    tri3.nt += 1;
    ttd_mesh *mc, *mg, *mo, *m3;
    ENSURE(ttd_mesh_create_d(NULL, cube.verts, cube.nv, cube.tris, cube.nt, &mc) == TTD_OK);
    ENSURE(ttd_mesh_create_d(NULL, grid.verts, grid.nv, grid.tris, grid.nt, &mg) == TTD_OK);
    ENSURE(ttd_mesh_create_d(NULL, open.verts, open.nv, open.tris, open.nt, &mo) == TTD_OK);
    ENSURE(ttd_mesh_create_d(NULL, tri3.verts, tri3.nv, tri3.tris, tri3.nt, &m3) == TTD_OK);
    const ttd_options surf = solid_options(0), sol = solid_options(1);
    ttd_options bad = solid_options(1);
    bad.solid = 2;
    const double id[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 5};
    ttd_mesh_result_d r;
    ttd_collision x;
    const ttd_mesh *opens[3] = {mg, mo, m3};
    for (int k = 0; k < 3; ++k) {
        ENSURE(ttd_mesh_distance_d(&sol, mc, opens[k], 1, id, INFINITY, 0, &r) == TTD_ERR_MESH_NOT_CLOSED);
        ENSURE(ttd_mesh_distance_d(&sol, opens[k], mc, 1, id, INFINITY, 0, &r) == TTD_ERR_MESH_NOT_CLOSED);
        ENSURE(ttd_mesh_collide_d(&sol, opens[k], mc, 1, id, 0, &x) == TTD_ERR_MESH_NOT_CLOSED);
        ENSURE(ttd_mesh_distance_d(&surf, mc, opens[k], 1, id, INFINITY, 0, &r) == TTD_OK);
    }
    ENSURE(ttd_mesh_distance_d(&sol, mc, mc, 1, id, INFINITY, 0, &r) == TTD_OK); /* closed: fine */
    ENSURE(ttd_mesh_distance_d(&bad, mc, mc, 1, id, INFINITY, 0, &r) == TTD_ERR_BAD_OPTIONS);
    ENSURE(strstr(ttd_status_string(TTD_ERR_MESH_NOT_CLOSED), "closed") != NULL);
    ttd_mesh_destroy(mc);
    ttd_mesh_destroy(mg);
    ttd_mesh_destroy(mo);
    ttd_mesh_destroy(m3);
    ttd_gen_mesh_free(&cube);
    ttd_gen_mesh_free(&grid);
    ttd_gen_mesh_free(&open);
    ttd_gen_mesh_free(&tri3);
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(spheres_against_plane_test);
    RUN_TEST(tetrahedron_in_cube);
    RUN_TEST(nesting_at_scales);
    RUN_TEST(open_meshes_refused);
    TEST_MAIN_END();
}
