/* SPDX-License-Identifier: MIT */
/* Continuous collision for the world's step (docs/simulator.md, section 1b): after the solver has
 * moved the bodies, ttd's deforming-mesh CCD (ttd_mesh_ccd_d) on each body pair's world vertices
 * at the step's start and end stops a body short of an impact the manifold could not see, because
 * the pair was farther apart than the margin when the step began.
 *
 * The motion CCD is asked about: each vertex on the straight line between its world positions at
 * the step's start and end. A body's motion taken as rigid (its centroid on a straight line, its
 * orientation turning about one axis at a constant rate, the slerp between the two orientations)
 * moves a vertex at distance r from the centroid on an arc, which leaves that line by at most
 * r ((1 - cos a) + (a - sin a)), a = half the angle turned (chord_error below); that much is added
 * to the pair's separation, so that the rigid motion stays at least the separation apart wherever
 * the straight lines do. Where the two bodies' chord errors reach the separation itself, the step
 * is cut into k pieces, each asked from its own rigid poses (the chord error falls as 1/k^2), up to
 * 64 pieces; a pair that needs more is not asked (counted in ccd_skipped). A body thrown without
 * spin turns by nothing: the lines are its motion. */
#include "sim.h"
#include "vec.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/// Half the angle of the turn from q0 to q1.
static double half_angle(const double q0[4], const double q1[4])
{
    double d = fabs(q0[0] * q1[0] + q0[1] * q1[1] + q0[2] * q1[2] + q0[3] * q1[3]);
    return acos(fmin(1.0, d));
}

/// The most a vertex within radius of the centroid leaves its straight line while the body turns
/// by twice the half angle a at a constant rate about one axis (see above).
static double chord_error(double a, double radius)
{
    return radius * ((1 - cos(a)) + (a - sin(a)));
}

/// q at fraction f of the constant-rate turn from q0 to q1 (slerp, the shorter way).
static void slerp(const double q0[4], const double q1[4], double f, double out[4])
{
    double d = q0[0] * q1[0] + q0[1] * q1[1] + q0[2] * q1[2] + q0[3] * q1[3], s = 1;
    if (d < 0) {
        d = -d;
        s = -1;
    }
    double a = acos(fmin(1.0, d)), w0 = 1 - f, w1 = f;
    if (a > 1e-9) {
        w0 = sin((1 - f) * a) / sin(a);
        w1 = sin(f * a) / sin(a);
    }
    double n = 0;
    for (int i = 0; i < 4; ++i) {
        out[i] = w0 * q0[i] + s * w1 * q1[i];
        n += out[i] * out[i];
    }
    n = sqrt(n);
    for (int i = 0; i < 4; ++i)
        out[i] /= n;
}

/// Body k's world vertices at centroid x and orientation q into out (3 nv), and their box.
static void world_vertices(const sim_body *b, const double x[3], const double q[4], double *out, double lo[3],
                           double hi[3])
{
    double R[9], pose[12];
    quat_to_m3(q, R);
    for (int r = 0; r < 3; ++r) {
        pose[4 * r] = R[3 * r];
        pose[4 * r + 1] = R[3 * r + 1];
        pose[4 * r + 2] = R[3 * r + 2];
        pose[4 * r + 3] = x[r];
    }
    for (size_t i = 0; i < b->shape->nv; ++i) {
        pose_apply(pose, b->shape->v + 3 * i, out + 3 * i);
        for (int c = 0; c < 3; ++c) {
            lo[c] = fmin(lo[c], out[3 * i + c]);
            hi[c] = fmax(hi[c], out[3 * i + c]);
        }
    }
}

/// The least distance of body pair (a, b)'s points (a < b) in the step's manifold (its list is
/// sorted by pair), or INFINITY when it held none: the pair was farther apart than the margin.
static double manifold_distance(const sim_world *w, uint32_t a, uint32_t b)
{
    const ttd_scene_point_d *pt = w->manifold.data;
    size_t lo = 0, hi = w->manifold.count;
    while (lo < hi) { /* the first point with (i, j) >= (a, b) */
        size_t mid = lo + (hi - lo) / 2;
        if (pt[mid].i < a || (pt[mid].i == a && pt[mid].j < b))
            lo = mid + 1;
        else
            hi = mid;
    }
    double d = INFINITY;
    for (; lo < w->manifold.count && pt[lo].i == a && pt[lo].j == b; ++lo)
        d = fmin(d, pt[lo].distance);
    return d;
}

enum { CCD_MAX_PIECES = 64 };

/// Body b's world vertices at fraction f of its motion from (x0, q0) to its pose now.
static void vertices_at(const sim_body *b, const double x0[3], const double q0[4], double f, double *out)
{
    double x[3], q[4], lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int c = 0; c < 3; ++c)
        x[c] = x0[c] + f * (b->x[c] - x0[c]);
    slerp(q0, b->q, f, q);
    world_vertices(b, x, q, out, lo, hi);
}

/// The earliest toi in [0, 1] of bodies a and b over the step cut into k pieces, each piece from
/// its own rigid poses, its separation base + chord (the pieces' chord error), or INFINITY. 0, or
/// -1 when ttd refuses a call.
static int pieces_toi(sim_world *w, size_t a, size_t b, int k, double base, double chord, double *toi)
{
    const sim_body *body[2] = {w->body + a, w->body + b};
    const double *x0[2] = {w->ccd_x0 + 7 * a, w->ccd_x0 + 7 * b};
    double *v[2][2] = {{NULL, NULL}, {NULL, NULL}};
    int rc = 0;
    *toi = INFINITY;
    for (int s = 0; s < 2; ++s)
        for (int e = 0; e < 2; ++e)
            if (!(v[s][e] = malloc(3 * body[s]->shape->nv * sizeof(double))))
                rc = -1;
    for (int j = 0; j < k && rc == 0 && isinf(*toi); ++j) {
        ttd_mesh *m[2] = {NULL, NULL};
        for (int s = 0; s < 2 && rc == 0; ++s) {
            vertices_at(body[s], x0[s], x0[s] + 3, (double)j / k, v[s][0]);
            vertices_at(body[s], x0[s], x0[s] + 3, (double)(j + 1) / k, v[s][1]);
            if (ttd_mesh_create_d(&w->opt, v[s][0], body[s]->shape->nv, body[s]->shape->t, body[s]->shape->nt, m + s) != TTD_OK)
                rc = -1;
        }
        ttd_mesh_ccd_result out;
        if (rc == 0 && ttd_mesh_ccd_d(&w->opt, m[0], v[0][1], m[1], v[1][1], base + chord, &out) == TTD_OK) {
            ++w->ccd_queries;
            if (out.toi <= 1)
                *toi = (j + out.toi) / k;
            ttd_mesh_ccd_free(&out);
        } else {
            rc = -1;
        }
        ttd_mesh_destroy(m[0]);
        ttd_mesh_destroy(m[1]);
    }
    for (int s = 0; s < 2; ++s)
        for (int e = 0; e < 2; ++e)
            free(v[s][e]);
    if (rc != 0)
        fprintf(stderr, "sim: the CCD of a pair in pieces failed\n");
    return rc;
}

static int grow_ccd(sim_world *w)
{
    if (w->ccd_cap >= w->n)
        return 0;
    size_t cap = w->n, nv = 0;
    for (size_t k = 0; k < w->n; ++k)
        nv += w->body[k].shape->nv;
    ttd_mesh **mesh = realloc(w->ccd_mesh, cap * sizeof *mesh);
    if (!mesh)
        return -1;
    w->ccd_mesh = mesh;
    for (size_t k = w->ccd_cap; k < cap; ++k)
        mesh[k] = NULL;
    double *x0 = realloc(w->ccd_x0, 7 * cap * sizeof *x0);
    double *v = realloc(w->ccd_v, 6 * nv * sizeof *v);
    double *box = realloc(w->ccd_box, 6 * cap * sizeof *box);
    if (x0)
        w->ccd_x0 = x0;
    if (v)
        w->ccd_v = v;
    if (box)
        w->ccd_box = box;
    if (!x0 || !v || !box)
        return -1;
    w->ccd_cap = cap;
    return 0;
}

int sim_ccd_begin(sim_world *w)
{
    if (grow_ccd(w) != 0)
        return -1;
    for (size_t k = 0; k < w->n; ++k) {
        memcpy(w->ccd_x0 + 7 * k, w->body[k].x, 3 * sizeof(double));
        memcpy(w->ccd_x0 + 7 * k + 3, w->body[k].q, 4 * sizeof(double));
    }
    return 0;
}

void sim_ccd_free(sim_world *w)
{
    for (size_t k = 0; k < w->ccd_cap; ++k)
        ttd_mesh_destroy(w->ccd_mesh[k]);
    free(w->ccd_mesh);
    free(w->ccd_x0);
    free(w->ccd_v);
    free(w->ccd_box);
}

enum { CCD_ROUNDS = 4 };

int sim_ccd_limit(sim_world *w)
{
    const double delta = 0.5 * w->set.margin; /* the gap an impact is stopped at: inside the margin */
    double *t0v = w->ccd_v;
    /* each body's vertices at the step's start (t0v) and end (t1v, after all of t0v), boxes */
    size_t nv = 0;
    for (size_t k = 0; k < w->n; ++k)
        nv += w->body[k].shape->nv;
    double *t1v = w->ccd_v + 3 * nv, *box = w->ccd_box;
    double *frac = malloc(w->n * sizeof *frac);
    if (!frac)
        return -1;
    double earliest = INFINITY;
    int limited = 0, rc = 0;
    for (int round = 0; round <= CCD_ROUNDS && rc == 0; ++round) {
        size_t off = 0;
        for (size_t k = 0; k < w->n; ++k) {
            sim_body *b = w->body + k;
            double *lo = box + 6 * k, *hi = lo + 3;
            lo[0] = lo[1] = lo[2] = INFINITY;
            hi[0] = hi[1] = hi[2] = -INFINITY;
            world_vertices(b, w->ccd_x0 + 7 * k, w->ccd_x0 + 7 * k + 3, t0v + off, lo, hi);
            world_vertices(b, b->x, b->q, t1v + off, lo, hi);
            if (round == 0 && (!w->ccd_mesh[k] || !b->is_static)) {
                ttd_status st = w->ccd_mesh[k] ? ttd_mesh_set_vertices_d(&w->opt, w->ccd_mesh[k], t0v + off)
                                               : ttd_mesh_create_d(&w->opt, t0v + off, b->shape->nv, b->shape->t,
                                                                   b->shape->nt, w->ccd_mesh + k);
                if (st != TTD_OK) {
                    fprintf(stderr, "sim: the CCD's world mesh: %s\n", ttd_status_string(st));
                    rc = -1;
                    break;
                }
            }
            frac[k] = 1;
            off += 3 * b->shape->nv;
        }
        if (rc != 0)
            break;
        int hit = 0;
        size_t off_a = 0;
        for (size_t a = 0; a < w->n && rc == 0; off_a += 3 * w->body[a].shape->nv, ++a) {
            const sim_body *ba = w->body + a;
            size_t off_b = off_a + 3 * ba->shape->nv;
            for (size_t b = a + 1; b < w->n; off_b += 3 * w->body[b].shape->nv, ++b) {
                const sim_body *bb = w->body + b;
                if (ba->is_static && bb->is_static)
                    continue;
                /* a pair out of the margin at the start is kept half the margin apart; a pair in the
                   manifold, which its points hold, is kept half its distance apart elsewhere too (a
                   turning body's corner); one touching or crossing is left to the solver */
                const double d0 = manifold_distance(w, (uint32_t)a, (uint32_t)b);
                if (!(d0 > 0))
                    continue;
                const double base = isinf(d0) ? delta : 0.5 * d0;
                const double ha = half_angle(w->ccd_x0 + 7 * a + 3, ba->q), hb = half_angle(w->ccd_x0 + 7 * b + 3, bb->q);
                int pieces = 1;
                double chord = chord_error(ha, ba->shape->radius) + chord_error(hb, bb->shape->radius);
                const double whole = chord; /* how far the rigid motion leaves the boxes of its two ends */
                while (chord >= base && pieces < CCD_MAX_PIECES) { /* cut the turn until its chords fit */
                    pieces *= 2;
                    chord = chord_error(ha / pieces, ba->shape->radius) + chord_error(hb / pieces, bb->shape->radius);
                }
                if (chord >= base) {
                    ++w->ccd_skipped;
                    continue;
                }
                const double sep = base + chord;
                w->ccd_max_chord = fmax(w->ccd_max_chord, chord);
                w->ccd_max_pieces = w->ccd_max_pieces > (size_t)pieces ? w->ccd_max_pieces : (size_t)pieces;
                const double *la = box + 6 * a, *lb = box + 6 * b;
                int apart = 0;
                for (int c = 0; c < 3; ++c)
                    apart |= la[c] > lb[3 + c] + base + whole || lb[c] > la[3 + c] + base + whole;
                if (apart)
                    continue;
                ttd_mesh_ccd_result out = {0};
                if (pieces > 1) {
                    if (pieces_toi(w, a, b, pieces, base, chord, &out.toi) != 0) {
                        rc = -1;
                        break;
                    }
                } else {
                    ttd_status st = ttd_mesh_ccd_d(&w->opt, w->ccd_mesh[a], t1v + off_a, w->ccd_mesh[b], t1v + off_b,
                                                   sep, &out);
                    ++w->ccd_queries;
                    if (st != TTD_OK) {
                        fprintf(stderr, "sim: ttd_mesh_ccd_d: %s\n", ttd_status_string(st));
                        rc = -1;
                        break;
                    }
                    ttd_mesh_ccd_free(&out);
                }
                if (out.toi <= 1) {
                    hit = 1;
                    if (round == 0)
                        earliest = fmin(earliest, out.toi);
                    if (!ba->is_static)
                        frac[a] = fmin(frac[a], out.toi);
                    if (!bb->is_static)
                        frac[b] = fmin(frac[b], out.toi);
                }
            }
        }
        if (rc != 0 || !hit)
            break;
        limited = 1;
        ++w->ccd_rounds;
        /* each body hit goes back along its motion to the earliest toi of its pairs; the
           bodies' new ends make new motions, asked again; when the last round still finds an
           impact every moving body goes back to where the step began (a body alone sent back
           would make pairs with the others' ends that no round asked about) */
        for (size_t k = 0; k < w->n; ++k) {
            sim_body *b = w->body + k;
            const double f = round == CCD_ROUNDS ? 0.0 : frac[k];
            if (f >= 1 || b->is_static)
                continue;
            const double *x0 = w->ccd_x0 + 7 * k, *q0 = x0 + 3;
            double q[4];
            for (int c = 0; c < 3; ++c)
                b->x[c] = x0[c] + f * (b->x[c] - x0[c]);
            slerp(q0, b->q, f, q);
            memcpy(b->q, q, sizeof q);
            sim_body_update(b);
        }
    }
    free(frac);
    if (limited)
        ++w->ccd_steps;
    w->ccd_last_toi = earliest;
    return rc;
}
