/* SPDX-License-Identifier: MIT */
/* The hierarchy's two promises that the mesh queries' exactness rests on (docs/mesh-queries.md,
 * section 4), checked on every box of meshes made of the triangles that break box builders:
 *   - every box holds its triangles: for each vertex v below a box (as the tree sees it, the
 *     vertex minus the mesh's origin rounded to double), |u_a . (v - c)| <= e_a on each axis a,
 *     evaluated in quad precision (products of doubles exact, sums within 1e-33 relative);
 *   - every box's axes are orthonormal to a few eps of the mesh's precision (the node test's
 *     bound takes them as a frame): |u_a . u_b - [a == b]| <= 8 eps.
 * Both hold for refitted trees too (ttd_mesh_set_vertices_d/f: boxes fitted around boxes).
 * The families: exactly collinear triangles (c = a + t (b - a) rounded), needles with widths
 * 1e-3 .. 1e-15 of their length, segments, points, ordinary triangles, all mixed into soups, in
 * both precisions, at scales 1e-8 .. 1e8 and offsets to 1e6. Before the frames were made
 * orthonormal, the collinear and needle soups failed both checks (axes with |cos| up to 0.99). */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "meshes.h"
#include "mesh/mesh.h"
#include "ref_distance.h" /* ttd_qreal */
#include "test_macros.h"
#include <ttd/ttd.h>

static uint64_t rng_state;

static double urand(void)
{
    rng_state = rng_state * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(rng_state >> 11) * 0x1p-53;
}

/* A soup of n triangles of the kind `kind` (0 collinear, 1 needle of width w, 2 segment, 3
 * point, 4 ordinary; 5 a mix of all), in the unit cube, then scaled and shifted. */
static void make_soup(int kind, double w, size_t n, double scale, double shift, double *v, uint32_t *t)
{
    for (size_t i = 0; i < n; ++i) {
        const int k = kind == 5 ? (int)(i % 5) : kind;
        double a[3], b[3], c[3], off[3];
        for (int d = 0; d < 3; ++d) {
            a[d] = urand();
            b[d] = a[d] + 0.4 * (urand() - 0.5);
            off[d] = urand() - 0.5;
        }
        const double s = urand();
        for (int d = 0; d < 3; ++d) {
            switch (k) {
            case 0: c[d] = a[d] + s * (b[d] - a[d]); break;
            case 1: c[d] = a[d] + s * (b[d] - a[d]) + w * 0.4 * off[d]; break;
            case 2: c[d] = b[d]; break;
            case 3: b[d] = a[d]; c[d] = a[d]; break;
            default: c[d] = urand(); break;
            }
        }
        for (int d = 0; d < 3; ++d) {
            v[9 * i + d] = a[d] * scale + shift;
            v[9 * i + 3 + d] = b[d] * scale + shift;
            v[9 * i + 6 + d] = c[d] * scale + shift;
        }
        for (int j = 0; j < 3; ++j)
            t[3 * i + (size_t)j] = (uint32_t)(3 * i + (size_t)j);
    }
}

typedef struct view {
    const struct ttd_mesh *m;
    double eps;
    double worst_axes;   /* the largest |u_a . u_b - [a == b]| seen */
} view;

static void node_box(const view *V, int32_t n, int j, double c[3], double u[9], double e[3], int32_t *child)
{
    if (V->m->bytes == 8) {
        const ttd_node_d *node = (const ttd_node_d *)V->m->nodes + n;
        for (int i = 0; i < 3; ++i) {
            c[i] = node->c[i][j];
            e[i] = node->e[i][j];
        }
        for (int i = 0; i < 9; ++i)
            u[i] = node->u[i][j];
        *child = node->child[j];
    } else {
        const ttd_node_f *node = (const ttd_node_f *)V->m->nodes + n;
        for (int i = 0; i < 3; ++i) {
            c[i] = node->c[i][j];
            e[i] = node->e[i][j];
        }
        for (int i = 0; i < 9; ++i)
            u[i] = node->u[i][j];
        *child = node->child[j];
    }
}

static int node_count(const view *V, int32_t n)
{
    return V->m->bytes == 8 ? ((const ttd_node_d *)V->m->nodes)[n].count : ((const ttd_node_f *)V->m->nodes)[n].count;
}

/* Checks every triangle below (node n, slot j) against that box, and the boxes below it. */
static int check_below(view *V, int32_t n, int j, const double c[3], const double u[9], const double e[3])
{
    double cc[3], uu[9], ee[3];
    int32_t child;
    node_box(V, n, j, cc, uu, ee, &child);
    if (child < 0) {
        const uint32_t *tri = V->m->tris + 3 * (size_t)(-1 - child);
        for (int k = 0; k < 3; ++k) {
            double v[3];
            for (int d = 0; d < 3; ++d) {
                const double x = V->m->bytes == 8 ? ((const double *)V->m->verts)[3 * (size_t)tri[k] + (size_t)d]
                                                  : (double)((const float *)V->m->verts)[3 * (size_t)tri[k] + (size_t)d];
                v[d] = x - V->m->origin[d]; /* the vertex as the tree sees it */
            }
            for (int a = 0; a < 3; ++a) {
                ttd_qreal s = 0;
                for (int d = 0; d < 3; ++d)
                    s += (ttd_qreal)u[3 * a + d] * ((ttd_qreal)v[d] - (ttd_qreal)c[d]);
                const ttd_qreal out = (s < 0 ? -s : s) - (ttd_qreal)e[a];
                ENSURE_MSG(out <= 0, "vertex outside its box by %.3g on axis %d (extent %.3g; node %d slot %d, child %d)", (double)out, a, e[a], (int)n, j, (int)child);
            }
        }
        return 0;
    }
    for (int jj = 0; jj < node_count(V, child); ++jj)
        if (check_below(V, child, jj, c, u, e))
            return 1;
    return 0;
}

/* Every box of the mesh: its axes, and every vertex below it. */
static int check_mesh(view *V)
{
    for (size_t n = 0; n < V->m->nnodes; ++n)
        for (int j = 0; j < node_count(V, (int32_t)n); ++j) {
            double c[3], u[9], e[3];
            int32_t child;
            node_box(V, (int32_t)n, j, c, u, e, &child);
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b) {
                    const double dot = u[3 * a] * u[3 * b] + u[3 * a + 1] * u[3 * b + 1] + u[3 * a + 2] * u[3 * b + 2];
                    const double defect = fabs(dot - (a == b ? 1.0 : 0.0));
                    V->worst_axes = fmax(V->worst_axes, defect / V->eps);
                    ENSURE_MSG(defect <= 8 * V->eps, "node %zu slot %d: axes %d, %d: |u.u - I| = %.3g eps", n, j, a,
                               b, defect / V->eps);
                }
            ENSURE_MSG(!check_below(V, (int32_t)n, j, c, u, e), "below node %zu slot %d (of %zu nodes)", n, j,
                       V->m->nnodes);
        }
    return 0;
}

static int boxes_hold_their_triangles(void)
{
    static const char *kinds[6] = {"collinear", "needle", "segment", "point", "ordinary", "mix"};
    static const double widths[5] = {1e-3, 1e-8, 1e-12, 1e-15, 0};
    static const double scales[4] = {1, 1e-8, 1e8, 1};
    static const double shifts[4] = {0, 0, 0, 1e6};
    const size_t n = 300;
    double *v = malloc(9 * n * sizeof *v);
    float *vf = malloc(9 * n * sizeof *vf);
    uint32_t *t = malloc(3 * n * sizeof *t);
    ENSURE(v != NULL && vf != NULL && t != NULL);
    ttd_options opt = ttd_default_options();
    opt.threads = 2;
    int meshes = 0;
    double worst_axes = 0;
    for (int kind = 0; kind < 6; ++kind)
        for (int wi = 0; wi < (kind == 1 ? 5 : 1); ++wi)
            for (int si = 0; si < 4; ++si)
                for (int prec = 0; prec < 2; ++prec) {
                    rng_state = (uint64_t)(1000 * kind + 100 * wi + 10 * si + prec + 1);
                    make_soup(kind, widths[wi], n, scales[si], shifts[si], v, t);
                    ttd_mesh *m = NULL;
                    if (prec == 0) {
                        ENSURE(ttd_mesh_create_d(&opt, v, 3 * n, t, n, &m) == TTD_OK);
                    } else {
                        for (size_t i = 0; i < 9 * n; ++i)
                            vf[i] = (float)v[i];
                        ENSURE(ttd_mesh_create_f(&opt, vf, 3 * n, t, n, &m) == TTD_OK);
                    }
                    view V = {(const struct ttd_mesh *)m, prec == 0 ? DBL_EPSILON : (double)FLT_EPSILON, 0};
                    const int bad = check_mesh(&V);
                    worst_axes = fmax(worst_axes, V.worst_axes);
                    ttd_mesh_destroy(m);
                    ENSURE_MSG(!bad, "%s soup, width %g, scale %g, shift %g, %s", kinds[kind], widths[wi], scales[si],
                               shifts[si], prec == 0 ? "double" : "float");
                    ++meshes;
                }
    printf("  %d meshes of %zu triangles: every vertex in every box above it; worst axis defect %.2f eps\n", meshes,
           n, worst_axes);
    free(v);
    free(vf);
    free(t);
    return 0;
}

/* The same after refits (ttd_mesh_set_vertices_d/f, mesh/build.c): each soup's mesh moved to
 * another kind's soup at the same scale (every triangle somewhere else: the refitted boxes around
 * boxes hold them), then to itself jittered by a thousandth; the rebuild a degraded tree would
 * get is turned off, so that every box is a refitted one. */
static int refitted_boxes_hold_their_triangles(void)
{
    static const double scales[4] = {1, 1e-8, 1e8, 1};
    static const double shifts[4] = {0, 0, 0, 1e6};
    const size_t n = 300;
    double *v = malloc(9 * n * sizeof *v), *w = malloc(9 * n * sizeof *w);
    float *vf = malloc(9 * n * sizeof *vf);
    uint32_t *t = malloc(3 * n * sizeof *t);
    ENSURE(v != NULL && w != NULL && vf != NULL && t != NULL);
    ttd_options opt = ttd_default_options();
    opt.threads = 2;
    int refits = 0;
    double worst_axes = 0;
    for (int kind = 0; kind < 6; ++kind)
        for (int si = 0; si < 4; ++si)
            for (int prec = 0; prec < 2; ++prec) {
                rng_state = (uint64_t)(7000 + 10 * kind + si);
                make_soup(kind, 1e-12, n, scales[si], shifts[si], v, t);
                ttd_mesh *m = NULL;
                for (size_t i = 0; i < 9 * n; ++i)
                    vf[i] = (float)v[i];
                ENSURE((prec == 0 ? ttd_mesh_create_d(&opt, v, 3 * n, t, n, &m) : ttd_mesh_create_f(&opt, vf, 3 * n, t, n, &m)) ==
                       TTD_OK);
                m->quality_built = INFINITY; /* refits only */
                for (int step = 0; step < 2; ++step) {
                    if (step == 0) {
                        make_soup((kind + 1) % 6, 1e-9, n, scales[si], shifts[si], w, t);
                    } else {
                        for (size_t i = 0; i < 9 * n; ++i)
                            w[i] = v[i] + 1e-3 * scales[si] * (urand() - 0.5);
                    }
                    for (size_t i = 0; i < 9 * n; ++i)
                        vf[i] = (float)w[i];
                    ENSURE((prec == 0 ? ttd_mesh_set_vertices_d(&opt, m, w) : ttd_mesh_set_vertices_f(&opt, m, vf)) == TTD_OK);
                    ENSURE(m->rebuilds == 0);
                    view V = {(const struct ttd_mesh *)m, prec == 0 ? DBL_EPSILON : (double)FLT_EPSILON, 0};
                    const int bad = check_mesh(&V);
                    worst_axes = fmax(worst_axes, V.worst_axes);
                    ENSURE_MSG(!bad, "kind %d soup refitted (step %d), scale %g, shift %g, %s", kind, step, scales[si],
                               shifts[si], prec == 0 ? "double" : "float");
                    ++refits;
                }
                ttd_mesh_destroy(m);
            }
    /* axis-aligned sheets (a grid, its boxes' faces through its vertices: no slack to spare),
     * moved up and over by steps that are not powers of two, at every scale */
    ttd_gen_mesh grid;
    ENSURE(ttd_gen_grid(40, &grid) == 0);
    double *gv = malloc(3 * grid.nv * sizeof *gv);
    float *gf = malloc(3 * grid.nv * sizeof *gf);
    ENSURE(gv != NULL && gf != NULL);
    for (int si = 0; si < 4; ++si)
        for (int prec = 0; prec < 2; ++prec) {
            ttd_mesh *m = NULL;
            for (int step = 0; step < 4; ++step) {
                for (size_t i = 0; i < 3 * grid.nv; ++i) {
                    gv[i] = (grid.verts[i] + 0.1 * step * (double)(i % 3 + 1)) * scales[si] + shifts[si];
                    gf[i] = (float)gv[i];
                }
                if (step == 0) {
                    ENSURE((prec == 0 ? ttd_mesh_create_d(&opt, gv, grid.nv, grid.tris, grid.nt, &m)
                                      : ttd_mesh_create_f(&opt, gf, grid.nv, grid.tris, grid.nt, &m)) == TTD_OK);
                    m->quality_built = INFINITY;
                    continue;
                }
                ENSURE((prec == 0 ? ttd_mesh_set_vertices_d(&opt, m, gv) : ttd_mesh_set_vertices_f(&opt, m, gf)) == TTD_OK);
                view V = {(const struct ttd_mesh *)m, prec == 0 ? DBL_EPSILON : (double)FLT_EPSILON, 0};
                ENSURE_MSG(!check_mesh(&V), "grid refitted (step %d), scale %g, shift %g, %s", step, scales[si],
                           shifts[si], prec == 0 ? "double" : "float");
                ++refits;
            }
            ttd_mesh_destroy(m);
        }
    free(gv);
    free(gf);
    ttd_gen_mesh_free(&grid);
    printf("  %d refits: every vertex in every box above it; worst axis defect %.2f eps\n", refits, worst_axes);
    free(v);
    free(w);
    free(vf);
    free(t);
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(boxes_hold_their_triangles);
    RUN_TEST(refitted_boxes_hold_their_triangles);
    TEST_MAIN_END();
}
