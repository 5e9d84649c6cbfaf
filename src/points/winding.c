/* SPDX-License-Identifier: MIT */
/* The hierarchical generalized winding number (points/points.h), after Barill, Dickson, Schmidt,
 * Levin and Jacobson, "Fast Winding Numbers for Soups and Clouds" (2018), with a rigorous bound on
 * what its approximation costs (docs/points.md, section 5).
 *
 * The winding number about q is (1 / 4 pi) times the integral over the surface of
 * f(x) . n(x) dA, f(x) = (x - q) / |x - q|^3. A subtree whose surface lies in the ball of radius r
 * about its centre c, seen from q at R = |c - q| > r, is replaced by the first two terms of the
 * Taylor series of f about c: f(c) . N + J(c) : M, J = (I R^2 - 3 y y^T) / R^5, y = c - q, with the
 * area vector N and the second moment M of its triangles (points/prepare.c). The remainder is at most
 * I (3R - 2r) / (R^3 (R - r)^2), I the subtree's polar moment about c (docs/points.md, section 5:
 * the integral form of Taylor's remainder with the third derivatives of 1 / |x| bounded by
 * 3! / |x|^4), which the walk adds up. Triangles too near for that are measured exactly (their
 * solid angles, mesh/solid.c). The walk's own rounding is small next to those bounds and is added
 * too: 32 eps times the sum of the terms' magnitudes.
 *
 * A closed mesh's winding number is an integer, counted exactly by a ray (points/ray.c): the
 * queries use that, and the walk for open meshes (and where the count cannot be made exact). */
#include <float.h>
#include <math.h>
#include <stdint.h>

#include "engine/dispatch.h"
#include "engine/parallel.h"
#include "points/points.h"

#define WN_PI 3.14159265358979323846
/* Barill et al.'s acceptance: a subtree is expanded when q is more than beta radii from its
 * centre. */
#define WN_BETA 2.0
#define WN_STACK 256

/* The walk: every subtree with R > beta r, and with tau >= 0 also a remainder bound at most tau
 * times A / (R + r)^2 (its share of the unsigned solid angle), is expanded; the rest is opened.
 * Returns the sum of solid angles; *err gets the bound on its error. */
static double wn_walk(const struct ttd_mesh *m, const ttd_points_data *pd, const double x[3], double beta, double tau,
                      double *err)
{
    const double *moments = ttd_points_moments(m, pd);
    if (moments == NULL) { /* out of memory: the linear sum, its rounding alone */
        *err = 64 * DBL_EPSILON * (double)m->nt;
        return ttd_mesh_winding(m, x);
    }
    const double q[3] = {x[0] - m->origin[0], x[1] - m->origin[1], x[2] - m->origin[2]};
    double sum = 0, mag = 0, bound = 0;
    int32_t stack[WN_STACK];
    int sp = 0;
    stack[sp++] = 0;
    while (sp > 0) {
        const int32_t n = stack[--sp];
        const int32_t *child;
        int count;
        if (m->bytes == 8) {
            child = ((const ttd_node_d *)m->nodes)[n].child;
            count = ((const ttd_node_d *)m->nodes)[n].count;
        } else {
            child = ((const ttd_node_f *)m->nodes)[n].child;
            count = ((const ttd_node_f *)m->nodes)[n].count;
        }
        const double *w = moments + (size_t)n * WM_COUNT * TTD_NODE_WIDTH;
        for (int j = 0; j < count; ++j) {
#define W(f) w[(size_t)(f) * TTD_NODE_WIDTH + (size_t)j]
            const double y[3] = {W(WM_C) - q[0], W(WM_C + 1) - q[1], W(WM_C + 2) - q[2]};
            const double R2 = y[0] * y[0] + y[1] * y[1] + y[2] * y[2], R = sqrt(R2);
            const double r = W(WM_RADIUS), A = W(WM_AREA);
            int far = R > beta * r && R > r;
            double rem = 0;
            if (far) {
                const double g = R - r;
                rem = W(WM_I) * (3 * R - 2 * r) / (R2 * R * g * g) * (1 + 16 * DBL_EPSILON);
                if (tau >= 0 && !(rem <= tau * A / ((R + r) * (R + r))))
                    far = 0;
            }
            if (far) {
                const double R3 = R2 * R;
                const double t1 = (y[0] * W(WM_N) + y[1] * W(WM_N + 1) + y[2] * W(WM_N + 2)) / R3;
                double yMy = 0;
                for (int a = 0; a < 3; ++a)
                    yMy += y[a] * ((W(WM_M + 3 * a) * y[0] + W(WM_M + 3 * a + 1) * y[1]) + W(WM_M + 3 * a + 2) * y[2]);
                const double tr = W(WM_M) + W(WM_M + 4) + W(WM_M + 8);
                const double t2 = (R2 * tr - 3 * yMy) / (R3 * R2);
                sum += t1 + t2;
                mag += fabs(t1) + fabs(t2);
                bound += rem;
            } else if (child[j] < 0) {
                const double om = ttd_mesh_solid_angle(m, (size_t)(-1 - child[j]), x);
                sum += om;
                mag += fabs(om);
            } else if (sp < WN_STACK) {
                stack[sp++] = child[j];
            }
#undef W
        }
    }
    *err = (bound + 32 * DBL_EPSILON * mag) / (4 * WN_PI);
    return sum / (4 * WN_PI);
}

double ttd_points_winding(const struct ttd_mesh *mesh, const ttd_points_data *pd, const double x[3], double *bound)
{
    if (!(isfinite(x[0]) && isfinite(x[1]) && isfinite(x[2]))) {
        if (bound)
            *bound = NAN;
        return NAN;
    }
    double err;
    const double w = wn_walk(mesh, pd, x, WN_BETA, -1, &err);
    if (bound)
        *bound = err;
    return w;
}

/* The walk tightened until its bound is below `want` (every triangle exactly at tau = 0). */
static double wn_tight(const struct ttd_mesh *mesh, const ttd_points_data *pd, const double x[3], double want, double *err)
{
    for (double tau = 1.0 / 16;; tau = tau > 1e-6 ? tau / 16 : 0) {
        const double w = wn_walk(mesh, pd, x, WN_BETA, tau, err);
        if (*err < want || tau == 0)
            return w;
    }
}

double ttd_points_winding_sign(const struct ttd_mesh *mesh, const ttd_points_data *pd, int closed, ttd_ray_node_fn ray,
                               const double x[3], int *proven)
{
    *proven = 0;
    if (!(isfinite(x[0]) && isfinite(x[1]) && isfinite(x[2])))
        return NAN;
    if (mesh->nt == 1) { /* a triangle's solid angle is below 2 pi: |w| < 1/2, outside (w given as 0) */
        *proven = 1;
        return 0;
    }
    int c;
    if (closed && ttd_points_ray_winding(mesh, pd, ray, x, &c) == 0) {
        *proven = 1;
        return c;
    }
    /* the fast walk; where its bound does not settle the side of |w| = 1/2 (the inside rule's),
     * the tightened one */
    double err;
    double w = wn_walk(mesh, pd, x, WN_BETA, -1, &err);
    if (!(fabs(fabs(w) - 0.5) > err))
        w = wn_tight(mesh, pd, x, fmax(fabs(fabs(w) - 0.5) / 2, 1e-3), &err);
    if (!(fabs(fabs(w) - 0.5) > err)) /* within 1e-3 of the level: down to every triangle exactly */
        w = wn_tight(mesh, pd, x, 0, &err);
    *proven = fabs(fabs(w) - 0.5) > err;
    return w;
}

/* The one inside rule (include/ttd/ttd.h; docs/points.md, section 5): inside where the magnitude
 * of the winding number is at least 1/2. The magnitude makes the inside of a closed mesh the same
 * whichever way it is wound as a whole (an inward mesh counts -1 inside); a count of 2 (a
 * self-overlapping mesh, two overlapping shells) is inside too, and 0 (shells of opposite
 * windings cancelling, a cavity) outside. Every query that decides a side asks this function,
 * about ttd_points_winding_sign's value, whose side of |w| = 1/2 that function settles. */
int ttd_winding_inside(double w)
{
    return fabs(w) >= 0.5;
}

int ttd_points_inside(const struct ttd_mesh *m, const double x[3])
{
    double d2 = 0;
    for (int c = 0; c < 3; ++c)
        d2 += (x[c] - m->origin[c]) * (x[c] - m->origin[c]);
    if (!(d2 <= m->radius * m->radius * (1 + 1e-9)))
        return 0;
    const ttd_points_data *pd = ttd_points_data_get(m, 0);
    if (pd == NULL) /* out of memory: the pass over the triangles (a closed mesh: within rounding of an integer) */
        return ttd_winding_inside(ttd_mesh_winding(m, x));
    int proven;
    return ttd_winding_inside(ttd_points_winding_sign(m, pd, ttd_mesh_closed(m) == 1, ttd_kernels_scalar_f.ray_node, x, &proven));
}

/* ---- many points over the threads ------------------------------------------------------- */

#define WN_BLOCK 64

typedef struct wn_job {
    const struct ttd_mesh *m;
    const ttd_points_data *pd;
    size_t n;
    const void *points;
    int bytes, closed;
    ttd_ray_node_fn ray;
    double *out;
    uint8_t *proven;
} wn_job;

static void wn_block(void *ctx, size_t b, int worker)
{
    (void)worker;
    const wn_job *J = ctx;
    const size_t i1 = (b + 1) * WN_BLOCK < J->n ? (b + 1) * WN_BLOCK : J->n;
    for (size_t i = b * WN_BLOCK; i < i1; ++i) {
        double x[3];
        for (int c = 0; c < 3; ++c)
            x[c] = J->bytes == 8 ? ((const double *)J->points)[3 * i + (size_t)c]
                                 : (double)((const float *)J->points)[3 * i + (size_t)c];
        int proven = 0;
        J->out[i] = ttd_points_winding_sign(J->m, J->pd, J->closed, J->ray, x, &proven);
        if (J->proven)
            J->proven[i] = (uint8_t)proven;
    }
}

ttd_status ttd_points_query_winding(const ttd_engine_config *cfg, const struct ttd_mesh *mesh, size_t n,
                                    const void *points, double *winding, uint8_t *proven)
{
    const ttd_points_data *pd = ttd_points_data_get(mesh, cfg->threads);
    const int closed = ttd_mesh_closed(mesh);
    if (pd == NULL || closed < 0)
        return TTD_ERR_OUT_OF_MEMORY;
    wn_job J = {mesh, pd, n, points, mesh->bytes, closed, ttd_dispatch_row_f(cfg->isa)->ray_node, winding, proven};
    ttd_parallel_for((n + WN_BLOCK - 1) / WN_BLOCK, cfg->threads, wn_block, &J);
    return TTD_OK;
}
