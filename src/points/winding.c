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
#include <stdlib.h>

#include "engine/dispatch.h"
#include "engine/parallel.h"
#include "points/points.h"

#define WN_PI 3.14159265358979323846
/* Barill et al.'s acceptance: a subtree is expanded when q is more than beta radii from its
 * centre. */
#define WN_BETA 2.0
#define WN_STACK 256

/* The signed solid angle of triangle t seen from x (van Oosterom and Strackee, as
 * ttd_mesh_solid_angle), its vectors scaled by a power of two to unit size first, so that no length
 * or product underflows or overflows at any scale of the coordinate range (lengths formed from
 * squares would underflow below about 1e-154). *amb (when not NULL) is set where x lies within
 * rounding of the triangle's plane inside (or on) it, or on a vertex: there the angle jumps by
 * 4 pi and its computed value cannot tell from which side. */
static double wn_solid_angle(const struct ttd_mesh *m, size_t t, const double x[3], int *amb, double *aerr)
{
    double a[3][3], big = 0;
    for (int k = 0; k < 3; ++k) {
        const size_t v = m->tris[3 * t + (size_t)k];
        for (int c = 0; c < 3; ++c) {
            const double p = m->bytes == 8 ? ((const double *)m->verts)[3 * v + (size_t)c]
                                           : (double)((const float *)m->verts)[3 * v + (size_t)c];
            a[k][c] = p - x[c];
            big = ttd_max_nn(big, fabs(a[k][c]));
        }
    }
    if (!(big > 0)) { /* x is the (point) triangle itself */
        if (amb)
            *amb = 1;
        return 0;
    }
    /* a power of two first (exact), then ttd_mesh_solid_angle's steps: the same bits wherever its
     * squares neither underflow nor overflow */
    int e;
    (void)frexp(big, &e);
    const double f = e > -1000 && e < 1000 ? ldexp(1.0, -e) : 0;
    double len[3];
    for (int k = 0; k < 3; ++k) {
        for (int c = 0; c < 3; ++c) /* exact but for parts below 2^-1074 of the largest */
            a[k][c] = f != 0 ? a[k][c] * f : ldexp(a[k][c], -e);
        len[k] = sqrt(a[k][0] * a[k][0] + a[k][1] * a[k][1] + a[k][2] * a[k][2]);
    }
    const double sc = ttd_max_nn(len[0], ttd_max_nn(len[1], len[2]));
    for (int k = 0; k < 3; ++k) {
        len[k] /= sc;
        for (int c = 0; c < 3; ++c)
            a[k][c] /= sc;
    }
    const double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                       a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                       a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    const double ab = a[0][0] * a[1][0] + a[0][1] * a[1][1] + a[0][2] * a[1][2];
    const double ac = a[0][0] * a[2][0] + a[0][1] * a[2][1] + a[0][2] * a[2][2];
    const double bc = a[1][0] * a[2][0] + a[1][1] * a[2][1] + a[1][2] * a[2][2];
    const double den = len[0] * len[1] * len[2] + ab * len[2] + ac * len[1] + bc * len[0];
    /* det's rounding is below 8 eps times its terms' magnitudes, den's below 16 eps times its
     * (the lengths' square roots included): taken twice */
    const double detmag = fabs(a[0][0]) * (fabs(a[1][1] * a[2][2]) + fabs(a[1][2] * a[2][1])) +
                          fabs(a[0][1]) * (fabs(a[1][0] * a[2][2]) + fabs(a[1][2] * a[2][0])) +
                          fabs(a[0][2]) * (fabs(a[1][0] * a[2][1]) + fabs(a[1][1] * a[2][0]));
    const double denmag = 4 * len[0] * len[1] * len[2];
    const double edet = 16 * DBL_EPSILON * detmag, eden = 32 * DBL_EPSILON * denmag;
    if (amb && (len[0] == 0 || len[1] == 0 || len[2] == 0 || (fabs(det) <= edet && !(den > eden))))
        *amb = 1;
    if (aerr) {
        /* the angle's error from det's and den's: |d atan2(y, x)| <= (|x| dy + |y| dx) / (x^2 + y^2)
         * over the box of their rounding (its nearest point to the origin below); where that box
         * holds the origin no bound holds (a needle or an edge seen in its plane: the angle can
         * be anything), counted as ambiguous. The walks add it to their bounds. */
        const double ny = ttd_max_nn(fabs(det) - edet, 0), nx = ttd_max_nn(fabs(den) - eden, 0);
        const double r2 = nx * nx + ny * ny;
        if (r2 > 0)
            *aerr += 2 * ((fabs(den) + eden) * edet + (fabs(det) + edet) * eden) / r2;
        else if (amb)
            *amb = 1;
        else
            *aerr = HUGE_VAL;
    }
    return 2 * atan2(det, den);
}

/* x in the moments' frame (points/points.h): q = (x - origin) scale. Returns 1 (with *err) for a
 * point beyond 2^100 radii of the mesh, whose winding number is 0 within A / (4 pi (R - 1)^2), A
 * the mesh's area (in that frame) and R its distance: far below any rounding of the sums. */
static int wn_frame(const struct ttd_mesh *m, const ttd_points_data *pd, const double x[3], double q[3], double *err)
{
    double far = 0;
    for (int c = 0; c < 3; ++c) {
        q[c] = (x[c] - m->origin[c]) * pd->scale;
        far = fmax(far, fabs(q[c]));
    }
    if (!(far > 0x1p100))
        return 0;
    const double *w = ttd_points_moments(m, pd);
    double area = 0;
    for (int j = 0; w != NULL && j < TTD_NODE_WIDTH; ++j)
        area += w[(size_t)WM_AREA * TTD_NODE_WIDTH + (size_t)j];
    *err = (area / (far - 1)) / (far - 1) / (4 * WN_PI) * 2 + 0x1p-1000;
    return 1;
}

/* The far field of all 8 slots of a node (moments w, point q relative to the mesh's origin) at once,
 * lane by lane with no branch, so that the compiler makes it vector code (the same operations in
 * every lane: the same bits on every instruction set): each slot's distance R, its remainder's
 * bound and its two terms (unused slots: whatever their zero moments give, never read). */
#if defined(__x86_64__) && defined(__GNUC__) && defined(__has_attribute)
#if __has_attribute(target_clones) && !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
/* AVX2 and AVX-512 copies chosen by the loader where the processor has them: 4 or 8 lanes a step
 * instead of SSE2's 2, the same operations in each lane */
__attribute__((target_clones("avx512f", "avx2", "default")))
#endif
#endif
static void wn_lanes(const double *restrict w, const double q[3], double *restrict lr, double *restrict lrem,
                     double *restrict lt1, double *restrict lt2)
{
    const double q0 = q[0], q1 = q[1], q2 = q[2];
#define W(f) w[(size_t)(f) * TTD_NODE_WIDTH + (size_t)j]
        for (int j = 0; j < TTD_NODE_WIDTH; ++j) {
            const double y0 = W(WM_C) - q0, y1 = W(WM_C + 1) - q1, y2 = W(WM_C + 2) - q2;
            const double R2 = y0 * y0 + y1 * y1 + y2 * y2, R = sqrt(R2);
            const double r = W(WM_RADIUS), g = R - r, R3 = R2 * R, g2 = g * g;
            /* one division for the three quotients (a division costs several multiplications in
             * vector code): d = 1 / (R^5 g^2); where that leaves the range (g or R tiny) the
             * remainder's bound is +inf or NaN and the slot is never expanded */
            const double d = 1 / (R3 * R2 * g2);
            lr[j] = R;
            lrem[j] = W(WM_I) * (3 * R - 2 * r) * (R2 * d) * (1 + 16 * DBL_EPSILON);
            lt1[j] = (y0 * W(WM_N) + y1 * W(WM_N + 1) + y2 * W(WM_N + 2)) * (R2 * g2 * d);
            const double yMy = (y0 * ((W(WM_M) * y0 + W(WM_M + 1) * y1) + W(WM_M + 2) * y2) +
                                y1 * ((W(WM_M + 3) * y0 + W(WM_M + 4) * y1) + W(WM_M + 5) * y2)) +
                               y2 * ((W(WM_M + 6) * y0 + W(WM_M + 7) * y1) + W(WM_M + 8) * y2);
            const double tr = W(WM_M) + W(WM_M + 4) + W(WM_M + 8);
            lt2[j] = (R2 * tr - 3 * yMy) * (g2 * d);
        }
#undef W
}

/* The walk: every subtree with R > beta r, and with tau >= 0 also a remainder bound at most tau
 * times A / (R + r)^2 (its share of the unsigned solid angle), is expanded; the rest is opened.
 * Returns the sum of solid angles; *err gets the bound on its error; *amb (when not NULL) is set
 * where a triangle measured exactly has x within rounding of it (wn_solid_angle). */
static double wn_walk(const struct ttd_mesh *m, const ttd_points_data *pd, const double x[3], double beta, double tau,
                      double *err, int *amb)
{
    const double *moments = ttd_points_moments(m, pd);
    if (moments == NULL) { /* out of memory: the linear sum, its rounding alone */
        *err = 64 * DBL_EPSILON * (double)m->nt;
        return ttd_mesh_winding(m, x);
    }
    double q[3];
    if (wn_frame(m, pd, x, q, err))
        return 0;
    double sum = 0, mag = 0, bound = 0, aerr = 0;
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
        double lr[TTD_NODE_WIDTH], lrem[TTD_NODE_WIDTH], lt1[TTD_NODE_WIDTH], lt2[TTD_NODE_WIDTH];
        wn_lanes(w, q, lr, lrem, lt1, lt2);
#define W(f) w[(size_t)(f) * TTD_NODE_WIDTH + (size_t)j]
        for (int j = 0; j < count; ++j) {
            const double R = lr[j], r = W(WM_RADIUS), A = W(WM_AREA), rem = lrem[j];
            int far = R > beta * r && R > r && rem < HUGE_VAL; /* (a tiny slot's is +inf: prepare.c) */
            if (far && tau >= 0 && !(rem <= tau * A / ((R + r) * (R + r))))
                far = 0;
            if (far) {
                sum += lt1[j] + lt2[j];
                mag += fabs(lt1[j]) + fabs(lt2[j]);
                bound += rem;
            } else if (child[j] < 0) {
                const double om = wn_solid_angle(m, (size_t)(-1 - child[j]), x, amb, &aerr);
                sum += om;
                mag += fabs(om);
            } else if (sp < WN_STACK) {
                stack[sp++] = child[j];
            }
        }
#undef W
    }
    if (!(fabs(sum) < HUGE_VAL && bound < HUGE_VAL && mag < HUGE_VAL)) {
        /* a power out of range all the same: every triangle's solid angle, scaled alone */
        sum = mag = bound = aerr = 0;
        for (size_t t = 0; t < m->nt; ++t) {
            const double om = wn_solid_angle(m, t, x, amb, &aerr);
            sum += om;
            mag += fabs(om);
        }
    }
    *err = (bound + 32 * DBL_EPSILON * mag + aerr) / (4 * WN_PI);
    return sum / (4 * WN_PI);
}

double ttd_points_winding(const struct ttd_mesh *mesh, const ttd_points_data *pd, const double x[3], double *bound)
{
    if (!(isfinite(x[0]) && isfinite(x[1]) && isfinite(x[2]))) {
        if (bound)
            *bound = (double)NAN;
        return (double)NAN;
    }
    double err;
    const double w = wn_walk(mesh, pd, x, WN_BETA, -1, &err, NULL);
    if (bound)
        *bound = err;
    return w;
}

/* The walk tightened until its bound is below `want` (every triangle exactly at tau = 0). */
static double wn_tight(const struct ttd_mesh *mesh, const ttd_points_data *pd, const double x[3], double want, double *err,
                       int *amb)
{
    for (double tau = 1.0 / 16;; tau = tau > 1e-6 ? tau / 16 : 0) {
        const double w = wn_walk(mesh, pd, x, WN_BETA, tau, err, amb);
        if (*err < want || tau == 0)
            return w;
    }
}

/* ---- the side of +-1/2 by refinement, largest bound first ------------------------------- */

/* The frontier of the side walk: the slots whose far field is taken, each with its remainder's
 * bound, its term, the term's magnitude and what opening it means (a node, or -1 - t for triangle
 * t), side by side so that the largest bound is found by one pass over an array (a frontier holds
 * tens of slots: cheaper than keeping a heap of them); and the subtrees whose ball holds the
 * point, which must be opened whatever their size, on a stack of their own. */
#define WN_FRONT 1024

typedef struct wn_front {
    double bound[WN_FRONT], term[WN_FRONT], mag[WN_FRONT];
    int32_t child[WN_FRONT], must[WN_FRONT];
    int n, nmust;
} wn_front;

/* The winding number about x as far as its sides of two levels need (for the caps: N - 1/2 and
 * N + 1/2, N the counts, where the mesh's w is +1/2 and -1/2: the inside rule asks about both):
 * every slot of the root far-field expanded where the point is outside its ball, then the slot
 * with the largest bound opened (a node into its slots, a triangle measured exactly) until the
 * bound leaves both levels outside [w - err, w + err], or nothing is left to open. The sum and the
 * bound are formed again from the final frontier, in its order, so that the running sums' own
 * rounding never decides. Returns 0 with *w and *err (the side may still be open: the caller
 * compares), -1 when the frontier outgrows its arrays. *amb as wn_walk's. */
static int wn_side_walk(const struct ttd_mesh *m, const ttd_points_data *pd, const double x[3], double lo, double hi,
                        double *w, double *err, int *amb)
{
    const double *moments = ttd_points_moments(m, pd);
    if (moments == NULL)
        return -1;
    double q[3];
    if (wn_frame(m, pd, x, q, err)) {
        *w = 0;
        return 0;
    }
    const double scale = 1 / (4 * WN_PI), lo4 = lo * 4 * WN_PI, hi4 = hi * 4 * WN_PI;
    wn_front F;
    F.n = F.nmust = 0;
    double exact = 0, emag = 0, eang = 0, S = 0, B = 0, M = 0;
    int32_t open = 0;
    for (;;) {
        if (open >= 0) {
            const int32_t *child;
            int count;
            if (m->bytes == 8) {
                child = ((const ttd_node_d *)m->nodes)[open].child;
                count = ((const ttd_node_d *)m->nodes)[open].count;
            } else {
                child = ((const ttd_node_f *)m->nodes)[open].child;
                count = ((const ttd_node_f *)m->nodes)[open].count;
            }
            if (F.n + F.nmust + count > WN_FRONT)
                return -1;
            const double *wm = moments + (size_t)open * WM_COUNT * TTD_NODE_WIDTH;
            double lr[TTD_NODE_WIDTH], lrem[TTD_NODE_WIDTH], lt1[TTD_NODE_WIDTH], lt2[TTD_NODE_WIDTH];
            wn_lanes(wm, q, lr, lrem, lt1, lt2);
            for (int j = 0; j < count; ++j) {
                const double r = wm[(size_t)WM_RADIUS * TTD_NODE_WIDTH + (size_t)j];
                if (lr[j] > r && lrem[j] < HUGE_VAL) { /* the expansion and its bound hold */
                    const double t = lt1[j] + lt2[j], mg = fabs(lt1[j]) + fabs(lt2[j]);
                    F.bound[F.n] = lrem[j];
                    F.term[F.n] = t;
                    F.mag[F.n] = mg;
                    F.child[F.n++] = child[j];
                    S += t;
                    B += lrem[j];
                    M += mg;
                } else if (child[j] < 0) {
                    const double om = wn_solid_angle(m, (size_t)(-1 - child[j]), x, amb, &eang);
                    exact += om;
                    emag += fabs(om);
                } else {
                    F.must[F.nmust++] = child[j];
                }
            }
        } else {
            const double om = wn_solid_angle(m, (size_t)(-1 - open), x, amb, &eang);
            exact += om;
            emag += fabs(om);
        }
        const double run = B + 32 * DBL_EPSILON * (emag + M) + eang + 1e-300;
        if (F.nmust == 0 && !(fabs(lo4 - (exact + S)) <= run) && !(fabs(hi4 - (exact + S)) <= run)) {
            /* settled by the running sums: form them again from the frontier */
            double s = 0, b = 0, mg = 0;
            for (int i = 0; i < F.n; ++i) {
                s += F.term[i];
                b += F.bound[i];
                mg += F.mag[i];
            }
            *w = (exact + s) * scale;
            *err = (b + 32 * DBL_EPSILON * (emag + mg) + eang) * scale;
            if (fabs(*w - lo) > *err && fabs(*w - hi) > *err)
                return 0;
        }
        if (!(fabs(S) < HUGE_VAL && B < HUGE_VAL))
            return -1; /* a power out of range: the caller's walk measures every triangle */
        if (F.nmust > 0) { /* a subtree whose ball holds the point: opened first */
            open = F.must[--F.nmust];
            continue;
        }
        if (F.n == 0) {
            *w = exact * scale;
            *err = (32 * DBL_EPSILON * emag + eang) * scale;
            return 0;
        }
        int top = 0; /* the largest bound, opened next (its place taken by the last slot) */
        for (int i = 1; i < F.n; ++i)
            top = F.bound[i] > F.bound[top] ? i : top;
        S -= F.term[top];
        B -= F.bound[top];
        M -= F.mag[top];
        open = F.child[top];
        --F.n;
        F.bound[top] = F.bound[F.n];
        F.term[top] = F.term[F.n];
        F.mag[top] = F.mag[F.n];
        F.child[top] = F.child[F.n];
    }
}

/* An open mesh's winding number from its caps (points/caps.c): the exact counts of one ray through
 * the mesh and through its caps, less the caps' winding number (the hierarchical walk on the caps,
 * and for `sign` tightened until its bound settles the side of 1/2 or every cap triangle is
 * measured exactly). 0 with *w and its bound *err; -1 where it cannot answer (out of memory, a
 * count that cannot be made exact, x within rounding of a cap: the caller's walk answers). */
static int wn_caps(const struct ttd_mesh *m, const ttd_points_data *pd, ttd_ray_node_fn ray, const double x[3], int sign,
                   double *w, double *err)
{
    const ttd_points_caps *cp = ttd_points_caps_get(m, pd);
    if (cp == NULL)
        return -1;
    int k, sigma, cm, cc;
    ttd_points_ray_direction(m, pd, x, &k, &sigma);
    if (ttd_points_ray_count(m, pd, ray, x, k, sigma, &cm) != 0)
        return -1;
    if (cp->ntri == 0) { /* no boundary by coordinates: the count is the winding number */
        *w = cm;
        *err = 0;
        return 0;
    }
    if (ttd_points_ray_count(cp->mesh, cp->pd, ray, x, k, sigma, &cc) != 0)
        return -1;
    int amb = 0;
    const double N = (double)cm + (double)cc;
    double wc;
    if (sign && wn_side_walk(cp->mesh, cp->pd, x, N - 0.5, N + 0.5, &wc, err, &amb) == 0) {
        *w = N - wc; /* settled, or every cap triangle measured exactly */
    } else {
        amb = 0;
        wc = wn_walk(cp->mesh, cp->pd, x, WN_BETA, -1, err, &amb);
        *w = N - wc;
        if (sign && !(fabs(fabs(*w) - 0.5) > *err)) {
            amb = 0;
            *w = N - wn_tight(cp->mesh, cp->pd, x, fmax(fabs(fabs(*w) - 0.5) / 2, 1e-3), err, &amb);
        }
    }
    /* the sum's own rounding: cm + cc is exact, the difference rounds by half an ulp of w */
    *err += DBL_EPSILON * fabs(*w);
    return amb ? -1 : 0;
}

double ttd_points_winding_value(const struct ttd_mesh *mesh, const ttd_points_data *pd, int closed, ttd_ray_node_fn ray,
                                const double x[3], int *proven, double *bound)
{
    double err = 0, w;
    if (bound == NULL)
        bound = &err;
    *bound = 0;
    *proven = 0;
    if (!(isfinite(x[0]) && isfinite(x[1]) && isfinite(x[2]))) {
        *bound = (double)NAN;
        return (double)NAN;
    }
    if (mesh->nt == 1) { /* a triangle's solid angle is below 2 pi: |w| < 1/2, outside (w given as 0) */
        *proven = 1;
        *bound = 0.5;
        return 0;
    }
    int c;
    if (closed && ttd_points_ray_winding(mesh, pd, ray, x, &c) == 0) {
        *proven = 1;
        return c;
    }
    /* an open mesh: the caps' exact counts, their walk tightened for the side of 1/2; where that
     * does not settle the side of |w| = 1/2 (a point within rounding, or w near -1/2 on a mesh
     * wound inward), the walk below */
    if (!closed && wn_caps(mesh, pd, ray, x, 1, &w, bound) == 0 && fabs(fabs(w) - 0.5) > *bound) {
        *proven = 1;
        return w;
    }
    /* the fast walk; where its bound does not settle the side of |w| = 1/2 (the inside rule's),
     * the tightened one */
    int amb = 0; /* x within rounding of a measured triangle's plane inside it (wn_solid_angle) */
    w = wn_walk(mesh, pd, x, WN_BETA, -1, bound, &amb);
    if (!(fabs(fabs(w) - 0.5) > *bound)) {
        amb = 0;
        w = wn_tight(mesh, pd, x, fmax(fabs(fabs(w) - 0.5) / 2, 1e-3), bound, &amb);
    }
    if (!(fabs(fabs(w) - 0.5) > *bound)) { /* within 1e-3 of the level: down to every triangle exactly */
        amb = 0;
        w = wn_tight(mesh, pd, x, 0, bound, &amb);
    }
    /* where a measured solid angle cannot tell its side (it jumps by 4 pi there), no bound on w
     * holds: the side is not proven (the point fuzzer found a soup point 1.7e-8 off a triangle
     * pair in their plane, read as inside by w = 0.9967 where the exact sum is -0.0013) */
    *proven = !amb && fabs(fabs(w) - 0.5) > *bound;
    return w;
}

double ttd_points_winding_sign(const struct ttd_mesh *mesh, const ttd_points_data *pd, int closed, ttd_ray_node_fn ray,
                               const double x[3], int *proven)
{
    return ttd_points_winding_value(mesh, pd, closed, ray, x, proven, NULL);
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
/* Batches of at least this many points go in spatial order (as the closest point's). */
#define WN_SORTED 32

typedef struct wn_job {
    const struct ttd_mesh *m;
    const ttd_points_data *pd;
    size_t n;
    const void *points;
    int bytes, closed;
    ttd_ray_node_fn ray;
    double *out;
    uint8_t *proven;
    const size_t *order; /* the points in spatial order (ttd_points_order), or NULL: input order */
} wn_job;

static void wn_block(void *ctx, size_t b, int worker)
{
    (void)worker;
    const wn_job *J = ctx;
    const size_t i1 = (b + 1) * WN_BLOCK < J->n ? (b + 1) * WN_BLOCK : J->n;
    for (size_t k = b * WN_BLOCK; k < i1; ++k) {
        const size_t i = J->order != NULL ? J->order[k] : k;
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
    /* a batch in spatial order: consecutive points' walks (the rays through the mesh, the caps'
     * walk) share nodes in the cache; each point's answer is its own, in any order */
    size_t *order = n >= WN_SORTED ? ttd_points_order(mesh, pd, n, points, mesh->bytes) : NULL;
    wn_job J = {mesh, pd, n, points, mesh->bytes, closed, ttd_dispatch_row_f(cfg->isa)->ray_node, winding, proven, order};
    ttd_parallel_for((n + WN_BLOCK - 1) / WN_BLOCK, cfg->threads, wn_block, &J);
    free(order);
    return TTD_OK;
}
