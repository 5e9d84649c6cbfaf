/* SPDX-License-Identifier: MIT */
/* Issue 32's scenes that judge themselves (docs/simulator.md, section 1): a row of dominoes,
 * two square rods crossing sunk into each other, spheres dropped into a bowl, a box on a slope
 * that slides (mu 0.2) or holds (mu 0.5); issue 34's sphere thrown at 40 m/s against a thin
 * plate, which continuous collision (ccd.c) stops. Each has an observer, called after every step, that
 * records what its verdict asks, and a verdict in place of (or beside) the rest figures. */
#include "sim.h"
#include "vec.h"

#include <stdio.h>
#include <string.h>

static const double identity[4] = {1, 0, 0, 0};
static const double pi = 3.141592653589793;

/* ---- dominoes ---------------------------------------------------------------------------- */

enum { DOMINOES = 10 };
/* value[]: 0..9 the time each domino first leans past 30 degrees (-1 before), 10 the deepest
   interpenetration over the whole run, 11 when */
#define DOMINO_LEAN (30 * 3.141592653589793 / 180)

/// The angle of body b's up axis from vertical.
static double tilt(const sim_body *b)
{
    return acos(fmax(-1.0, fmin(1.0, b->R[8])));
}

static int observe_overlap(sim_run *run, int slot)
{
    double depth;
    uint32_t a, b;
    size_t touching;
    if (sim_world_overlap(&run->world, &depth, &a, &b, &touching) != 0)
        return -1;
    if (depth > run->value[slot]) {
        run->value[slot] = depth;
        run->value[slot + 1] = run->world.time;
    }
    return 0;
}

static int observe_dominoes(sim_run *run)
{
    for (int k = 0; k < DOMINOES; ++k)
        if (run->value[k] < 0 && tilt(run->world.body + 1 + k) > DOMINO_LEAN)
            run->value[k] = run->world.time;
    return observe_overlap(run, 10);
}

/// The row fell in sequence: each domino leans past 30 degrees after the one before it, each
/// ends tilted more than 60 degrees, no two interpenetrate deeper than a tenth of the margin at
/// any step, and the fallen row then rests (the rest figures).
static int verdict_dominoes(const sim_run *run, const sim_figures *f, char *note, size_t size)
{
    int ordered = 1;
    double least = HUGE_VAL;
    for (int k = 0; k < DOMINOES; ++k) {
        ordered &= run->value[k] >= 0 && (k == 0 || run->value[k] > run->value[k - 1]);
        least = fmin(least, tilt(run->world.body + 1 + k));
    }
    const double deepest = run->value[10] / run->world.set.margin;
    snprintf(note, size,
             "dominoes: lean past 30 deg at %.3f s (first) .. %.3f s (last), %s; least final tilt %.1f deg (limit 60); "
             "deepest interpenetration over the run %.3g of the margin at %.3f s (limit 0.1)",
             run->value[0], run->value[DOMINOES - 1], ordered ? "in order" : "NOT in order", least * 180 / pi, deepest,
             run->value[11]);
    return ordered && least > 60 * pi / 180 && deepest < 0.1 && f->drift < 1e-3 && f->overlap < 0.1;
}

/// Ten dominoes 0.16 x 0.5 x 1 standing in a row along x, 0.55 apart, at the rest gap on the
/// floor; the first is set turning about its +x bottom edge at 2 rad/s.
static int build_dominoes(sim_run *run)
{
    const double h[3] = {0.08, 0.25, 0.5}, gap = run->world.set.rest_gap;
    if (sim_run_add_floor(run) != 0 || sim_shape_box(run->shape + run->nshape, h, SIM_BOX_DIAG_A) != 0)
        return -1;
    const sim_shape *domino = run->shape + run->nshape++;
    for (int k = 0; k < DOMINOES; ++k) {
        const double x[3] = {-2.5 + 0.55 * k, 0, h[2] + gap};
        if (sim_world_add(&run->world, domino, x, identity, 0) < 0)
            return -1;
    }
    sim_body *first = run->world.body + 1;
    const double spin = 2.0, r[3] = {-h[0], 0, h[2] + gap}; /* from the edge it turns about to the centroid */
    first->w[1] = spin;
    v3_cross(first->w, r, first->v);
    for (int k = 0; k < DOMINOES; ++k)
        run->value[k] = -1;
    run->observe = observe_dominoes;
    run->verdict = verdict_dominoes;
    run->settle = 4.0;
    return 0;
}

/* ---- crossing rods ------------------------------------------------------------------------ */

/* value[]: 0 the first time the rods' interpenetration is below a tenth of the margin (-1
   before), 1 the first time it is 0, 2 the deepest after that, 3 when */
static int observe_rods(sim_run *run)
{
    double depth;
    uint32_t a, b;
    size_t touching;
    if (sim_world_overlap(&run->world, &depth, &a, &b, &touching) != 0)
        return -1;
    const double t = run->world.time;
    if (run->value[0] < 0 && depth < 0.1 * run->world.set.margin)
        run->value[0] = t;
    if (run->value[1] < 0 && depth <= 0)
        run->value[1] = t;
    if (run->value[1] >= 0 && depth > run->value[2]) {
        run->value[2] = depth;
        run->value[3] = t;
    }
    return 0;
}

/// The rods come apart (interpenetration under a tenth of the margin) within 0.1 s, once apart
/// never cross deeper than a tenth of the margin again, then rest.
static int verdict_rods(const sim_run *run, const sim_figures *f, char *note, size_t size)
{
    const double M = run->world.set.margin;
    snprintf(note, size,
             "rods: interpenetration below 0.1 of the margin at %.4f s (limit 0.1 s), 0 at %.4f s; deepest after "
             "that %.3g of the margin (limit 0.1)",
             run->value[0], run->value[1], run->value[2] / M);
    return run->value[0] >= 0 && run->value[0] <= 0.1 && run->value[1] >= 0 && run->value[2] < 0.1 * M && f->drift < 1e-3 && f->overlap < 0.1;
}

/// Two solid square rods 2 x 0.1 x 0.1, one lying along x on the floor at the rest gap, the
/// other along y across it, sunk 0.05 into it: no vertex of either is inside the other, so only
/// the edges' deepest points (docs/scenes.md 5b) push them apart.
static int build_rods(sim_run *run)
{
    const double h[3] = {1.0, 0.05, 0.05}, gap = run->world.set.rest_gap, sunk = 0.05;
    if (sim_run_add_floor(run) != 0 || sim_shape_box(run->shape + run->nshape, h, SIM_BOX_DIAG_A) != 0)
        return -1;
    const sim_shape *rod = run->shape + run->nshape++;
    const double z[3] = {0, 0, 1}, xa[3] = {0, 0, h[2] + gap}, xb[3] = {0.1, -0.2, 3 * h[2] + gap - sunk};
    double turned[4];
    quat_axis_angle(z, 0.5 * pi, turned);
    if (sim_world_add(&run->world, rod, xa, identity, 0) < 0 || sim_world_add(&run->world, rod, xb, turned, 0) < 0)
        return -1;
    run->value[0] = run->value[1] = -1;
    run->observe = observe_rods;
    run->verdict = verdict_rods;
    run->settle = 1.0;
    return 0;
}

/* ---- the bowl ----------------------------------------------------------------------------- */

/* value[]: 0 the inner sphere's radius, 1 its centre's height, 2 the rim's height, 3 the
   spheres' radius (set when built) */
static int verdict_bowl(const sim_run *run, const sim_figures *f, char *note, size_t size)
{
    double worst = -HUGE_VAL; /* the largest centre distance from the inner sphere's centre, less what fits */
    int below_rim = 1;
    for (size_t k = 1; k < run->world.n; ++k) {
        const double *x = run->world.body[k].x, d[3] = {x[0], x[1], x[2] - run->value[1]};
        worst = fmax(worst, v3_norm(d) - (run->value[0] - run->value[3]));
        below_rim &= x[2] < run->value[2];
    }
    snprintf(note, size,
             "bowl: every ball's centre within %.4f of the inner surface's sphere less its radius (<= 0.02), %s the rim",
             worst, below_rim ? "below" : "NOT below");
    return worst <= 0.02 && below_rim && f->drift < 1e-3 && f->overlap < 0.1;
}

/// A bowl (the shell between spheres of radius 2.5 and 2.7, up to 57 degrees from the bottom,
/// 32 x 10 cells) static, its inner bottom at z = 0; seven icospheres (radius 0.4, 80 triangles)
/// dropped into it, one over the centre and six around it 1 out, 0.3 above the surface.
static int build_bowl(sim_run *run)
{
    const double r = 2.5, rim = 1.0, ball = 0.4;
    double bottom;
    if (sim_shape_bowl(run->shape, r, 0.2, rim, 32, 10, &bottom) != 0)
        return -1;
    if (sim_shape_icosphere(run->shape + 1, ball, 1) != 0) {
        sim_shape_free(run->shape);
        return -1;
    }
    run->nshape = 2;
    const double xb[3] = {0, 0, -bottom};
    if (sim_world_add(&run->world, run->shape, xb, identity, 1) < 0)
        return -1;
    for (int k = 0; k < 7; ++k) {
        const double rho = k ? 1.0 : 0, phi = (k - 1) * pi / 3, surface = r - sqrt(r * r - rho * rho);
        const double x[3] = {rho * cos(phi), rho * sin(phi), surface + ball + 0.3};
        if (sim_world_add(&run->world, run->shape + 1, x, identity, 0) < 0)
            return -1;
    }
    run->value[0] = r;
    run->value[1] = r;
    run->value[2] = r - r * cos(rim);
    run->value[3] = ball;
    run->verdict = verdict_bowl;
    run->settle = 6.0;
    return 0;
}

/* ---- the slope ---------------------------------------------------------------------------- */

/* value[]: 0 the slope's angle, 1 mu, 2-4 the downhill direction, 5-7 the box's start; the
   trace: (time, distance slid downhill) for the first 2 s */
static int observe_slope(sim_run *run)
{
    const double t = run->world.time, *x = run->world.body[1].x;
    if (t > 2.0 + 1e-9)
        return 0;
    const double d[3] = {x[0] - run->value[5], x[1] - run->value[6], x[2] - run->value[7]};
    return sim_run_trace(run, t, v3_dot(d, run->value + 2));
}

/// The least-squares parabola s = s0 + v0 t + a t^2 / 2 through the trace's samples with
/// t >= from: its a (times centred and scaled to [-1, 1] for the normal equations' sake).
static double fitted_acceleration(const sim_run *run, double from)
{
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (size_t k = 0; k < run->ntrace; k += 2)
        if (run->trace[k] >= from) {
            lo = fmin(lo, run->trace[k]);
            hi = fmax(hi, run->trace[k]);
        }
    const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
    double A[3][4] = {{0}};
    for (size_t k = 0; k < run->ntrace; k += 2) {
        if (run->trace[k] < from)
            continue;
        const double u = (run->trace[k] - mid) / half, p[3] = {1, u, u * u}, s = run->trace[k + 1];
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j)
                A[i][j] += p[i] * p[j];
            A[i][3] += p[i] * s;
        }
    }
    for (int i = 0; i < 3; ++i) /* Gauss-Jordan; the matrix is positive definite */
        for (int r = 0; r < 3; ++r) {
            if (r == i)
                continue;
            const double m = A[r][i] / A[i][i];
            for (int c = i; c < 4; ++c)
                A[r][c] -= m * A[i][c];
        }
    const double c2 = A[2][3] / A[2][2]; /* s = c0 + c1 u + c2 u^2, u = (t - mid) / half */
    return 2 * c2 / (half * half);
}

/// Sliding: the fitted acceleration over 0.25-2 s within 1% of g (sin a - mu cos a).
static int verdict_slide(const sim_run *run, const sim_figures *f, char *note, size_t size)
{
    (void)f;
    const double g = -run->world.set.gravity[2], a = run->value[0], mu = run->value[1];
    const double want = g * (sin(a) - mu * cos(a)), got = fitted_acceleration(run, 0.25);
    snprintf(note, size, "slope: slides at %.5f m/s^2 over 0.25-2 s, g (sin a - mu cos a) = %.5f: %+.3f%% (limit 1%%)",
             got, want, 100 * (got / want - 1));
    return fabs(got / want - 1) < 0.01;
}

/// A static slope (the floor's box turned 20 degrees about y, so +x runs downhill) and a box
/// 1 x 1 x 0.5 at rest on it at the rest gap, 2.5 uphill of the slope's middle; friction mu.
static int build_slope(sim_run *run, double mu)
{
    const double hf[3] = {4.2, 4.2, 0.5}, hb[3] = {0.5, 0.5, 0.25}, gap = run->world.set.rest_gap, a = 20 * pi / 180;
    if (sim_shape_box(run->shape, hf, SIM_BOX_DIAG_A) != 0)
        return -1;
    if (sim_shape_box(run->shape + 1, hb, SIM_BOX_DIAG_A) != 0) {
        sim_shape_free(run->shape);
        return -1;
    }
    run->nshape = 2;
    const double y[3] = {0, 1, 0}, origin[3] = {0, 0, 0};
    double q[4], R[9], down[3], n[3], x[3];
    quat_axis_angle(y, a, q);
    quat_to_m3(q, R);
    const double ex[3] = {1, 0, 0}, ez[3] = {0, 0, 1};
    m3_mul_v(R, ex, down);
    m3_mul_v(R, ez, n);
    for (int i = 0; i < 3; ++i)
        x[i] = n[i] * (hf[2] + hb[2] + gap) - 2.5 * down[i];
    if (sim_world_add(&run->world, run->shape, origin, q, 1) < 0 || sim_world_add(&run->world, run->shape + 1, x, q, 0) < 0)
        return -1;
    run->world.set.friction = mu;
    run->value[0] = a;
    run->value[1] = mu;
    memcpy(run->value + 2, down, sizeof down);
    memcpy(run->value + 5, x, sizeof x);
    if (mu < tan(a)) { /* it slides: 2 s watched from the start */
        run->observe = observe_slope;
        run->verdict = verdict_slide;
        run->settle = 0;
        run->seconds = 2.0;
    } else {
        run->settle = 0.5; /* it holds: the rest figures */
    }
    return 0;
}

/* ---- a fast sphere against a thin plate ---------------------------------------------------- */

/* value[]: 0 the plate's top, 1 its bottom, 2 the lowest a vertex of the sphere came relative to
   the top over the run, 3 the lowest its centroid came, 4 the first step whose end had the
   centroid under the plate's top (-1: none), 5 the step the sphere stopped (-1: not yet), 6 the
   first step CCD limited (-1), 7 that step's earliest toi, 8 the steps CCD limited, 9 the
   deepest interpenetration over the run, 10 when */
/// The height of body b's lowest vertex.
static double lowest_vertex(const sim_body *b)
{
    double z = HUGE_VAL;
    for (size_t k = 0; k < b->shape->nv; ++k) {
        const double *v = b->shape->v + 3 * k;
        z = fmin(z, b->x[2] + b->R[6] * v[0] + b->R[7] * v[1] + b->R[8] * v[2]);
    }
    return z;
}

static int observe_fast_sphere(sim_run *run)
{
    const sim_world *w = &run->world;
    const sim_body *s = w->body + 1;
    const double step = (double)w->steps, low = lowest_vertex(s) - run->value[0];
    run->value[2] = fmin(run->value[2], low);
    run->value[3] = fmin(run->value[3], s->x[2] - run->value[0]);
    if (run->value[4] < 0 && s->x[2] < run->value[0])
        run->value[4] = step;
    if (run->value[5] < 0 && s->v[2] > -1.0 && s->x[2] > run->value[0])
        run->value[5] = step;
    if (run->value[6] < 0 && w->ccd_last_toi <= 1) {
        run->value[6] = step;
        run->value[7] = w->ccd_last_toi;
    }
    run->value[8] = (double)w->ccd_steps;
    return observe_overlap(run, 9);
}

/// The sphere stopped at the plate: its centroid never went under the plate's top, no vertex
/// of it ever sank under the top by more than a tenth of the margin, it came to rest on the
/// plate (its lowest vertex within the margin above the top), and then rested (the rest figures).
static int verdict_fast_sphere(const sim_run *run, const sim_figures *f, char *note, size_t size)
{
    const sim_world *w = &run->world;
    const double M = w->set.margin, low_end = lowest_vertex(w->body + 1) - run->value[0];
    const int through = run->value[4] >= 0;
    snprintf(note, size,
             "fast-sphere: %s; %s; lowest vertex over the run %.4f from the plate's top (limit -%.3g), at the end %.4f "
             "(0 .. %g); deepest interpenetration %.3g of the margin; CCD %s: %zu of %zu steps limited, first at step %.0f "
             "(toi %.4f), %zu mesh CCD calls, CCD pass %.3f ms a step (CPU), largest chord error %.3g",
             through ? "went THROUGH the plate" : "never under the plate's top",
             run->value[5] >= 0 ? "stopped above it" : "never stopped above it", run->value[2], 0.1 * M, low_end, M, run->value[9] / M,
             w->set.ccd > 0 ? "on" : "OFF", w->ccd_steps, w->steps, run->value[6], run->value[7], w->ccd_queries,
             1e3 * w->ccd_seconds / (double)w->steps, w->ccd_max_chord);
    if (through) {
        size_t len = strlen(note);
        snprintf(note + len, size - len, "; its centroid first under the plate's top after step %.0f", run->value[4]);
    }
    return !through && run->value[5] >= 0 && run->value[2] > -0.1 * M && low_end >= 0 && low_end <= M &&
           run->value[9] < 0.1 * M && f->drift < 1e-3 && f->overlap < 0.1;
}

/// A static plate 2 x 2 x 0.1 (its top at z = 0) and an icosphere of radius 0.2 (320 triangles)
/// thrown straight down at it at 40 m/s, without spin, at 60 Hz (dt 1/60 s): a step moves it
/// about 0.67, more than the sphere and the plate together (about 0.49), and its third step
/// begins with it 0.09 above the plate, out of the margin. Without CCD that step carries it
/// through; with CCD (on unless the command says --no-ccd) it stops at the plate.
static int build_fast_sphere(sim_run *run)
{
    const double hp[3] = {1.0, 1.0, 0.05}, r = 0.2, speed = 40.0;
    run->world.set.dt = 1.0 / 60;
    if (run->world.set.ccd < 0)
        run->world.set.ccd = 1;
    if (sim_shape_box(run->shape, hp, SIM_BOX_DIAG_A) != 0)
        return -1;
    if (sim_shape_icosphere(run->shape + 1, r, 2) != 0) {
        sim_shape_free(run->shape);
        return -1;
    }
    run->nshape = 2;
    /* a vertex straight down: the first contact point is under the centroid, so the impact's
       impulse turns nothing (face down, the manifold's corners of the face, off the axis, take
       it one after another and set the sphere spinning at up to 20 rad/s) */
    const double *v = run->shape[1].v, down[3] = {0, 0, -1}, len = v3_norm(v);
    double axis[3], q[4];
    v3_cross(v, down, axis);
    const double sine = v3_normalize(axis);
    quat_axis_angle(axis, atan2(sine, -v[2]), q);
    const double lowest = -len;
    /* two steps of semi-implicit Euler in substeps h from -speed: speed 2 dt + g h^2 (1 + .. + 2S) */
    const int S = run->world.set.substeps;
    const double h = run->world.set.dt / S, g = -run->world.set.gravity[2];
    const double fall = speed * 2 * run->world.set.dt + g * h * h * (2.0 * S) * (2.0 * S + 1) / 2;
    const double xp[3] = {0, 0, -hp[2]}, xs[3] = {0.5, 0.0, -lowest + 0.09 + fall};
    if (sim_world_add(&run->world, run->shape, xp, identity, 1) < 0 ||
        sim_world_add(&run->world, run->shape + 1, xs, q, 0) < 0)
        return -1;
    run->world.body[1].v[2] = -speed;
    run->value[0] = 0;
    run->value[1] = -2 * hp[2];
    run->value[2] = run->value[3] = HUGE_VAL;
    run->value[4] = run->value[5] = run->value[6] = -1;
    run->value[7] = INFINITY;
    run->observe = observe_fast_sphere;
    run->verdict = verdict_fast_sphere;
    run->settle = 0.5;
    run->seconds = 2.0;
    return 0;
}

int sim_run_build_judged(sim_run *run, const char *name)
{
    if (!strcmp(name, "fast-sphere"))
        return build_fast_sphere(run);
    if (!strcmp(name, "dominoes"))
        return build_dominoes(run);
    if (!strcmp(name, "rods"))
        return build_rods(run);
    if (!strcmp(name, "bowl"))
        return build_bowl(run);
    if (!strcmp(name, "slope-slide"))
        return build_slope(run, 0.2);
    if (!strcmp(name, "slope-hold"))
        return build_slope(run, 0.5);
    return 1;
}
