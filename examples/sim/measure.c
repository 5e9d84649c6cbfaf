/* SPDX-License-Identifier: MIT */
/* The rest window's figures: drift of every vertex at every step, interpenetration sampled. */
#include "sim.h"
#include "vec.h"

#include <stdlib.h>
#include <string.h>

/// The largest horizontal displacement of any vertex of b from where start puts it.
static double vertex_drift(const sim_body *b, const double start[12])
{
    double now[12], worst = 0;
    sim_body_pose(b, now);
    for (size_t k = 0; k < b->shape->nv; ++k) {
        double p[3], q[3];
        pose_apply(start, b->shape->v + 3 * k, p);
        pose_apply(now, b->shape->v + 3 * k, q);
        worst = fmax(worst, hypot(q[0] - p[0], q[1] - p[1]));
    }
    return worst;
}

static int sample_overlap(sim_world *w, sim_figures *f)
{
    double depth;
    uint32_t a, b;
    size_t touching;
    if (sim_world_overlap(w, &depth, &a, &b, &touching) != 0)
        return -1;
    if (depth / w->set.margin > f->overlap) {
        f->overlap = depth / w->set.margin;
        f->overlap_a = a;
        f->overlap_b = b;
    }
    f->touching = touching > f->touching ? touching : f->touching;
    return 0;
}

int sim_run_window(sim_world *w, double settle, double seconds, sim_step_fn step, void *ctx, sim_figures *f)
{
    memset(f, 0, sizeof *f);
    f->overlap_a = f->overlap_b = UINT32_MAX;
    const double dt = w->set.dt;
    long settle_steps = lround(settle / dt), rest = lround(seconds / dt), every = lround(0.25 / dt);
    int rc = 0;
    for (long s = 0; s < settle_steps && rc == 0; ++s)
        rc = step(ctx, w);
    double *start = malloc(12 * w->n * sizeof(double));
    if (!start)
        return -1;
    for (size_t k = 0; k < w->n; ++k)
        sim_body_pose(w->body + k, start + 12 * k);
    if (rc == 0)
        rc = sample_overlap(w, f);
    for (long s = 1; s <= rest && rc == 0; ++s) {
        rc = step(ctx, w);
        for (size_t k = 0; rc == 0 && k < w->n; ++k) {
            const sim_body *b = w->body + k;
            if (b->is_static)
                continue;
            double d = vertex_drift(b, start + 12 * k) / b->shape->size;
            double c = hypot(b->x[0] - start[12 * k + 3], b->x[1] - start[12 * k + 7]) / b->shape->size;
            if (d > f->drift) {
                f->drift = d;
                f->drift_body = k;
            }
            f->centre_drift = fmax(f->centre_drift, c);
        }
        if (rc == 0 && (s % every == 0 || s == rest))
            rc = sample_overlap(w, f);
    }
    free(start);
    f->kinetic = sim_world_kinetic(w);
    f->max_tilt_deg = w->max_tilt * 57.29577951308232;
    return rc;
}
