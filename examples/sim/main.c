/* SPDX-License-Identifier: MIT */
/* ttd_sim: runs issue 23's scenarios and measures them (docs/simulator.md).
 *
 *   ttd_sim                          every scenario, 10 s at rest each, a table of figures
 *   ttd_sim --check                  the same, exit 1 unless every figure is met (the CTest)
 *   ttd_sim --scenario bin --obj out/ --seconds 2
 *
 * Each scenario settles for its own time, then its rest window starts: for --seconds it records
 * every moving body's largest horizontal displacement (of any vertex, relative to the window's
 * start, over every step) and the interpenetration of every pair (overlap.c: every 0.25 s and at
 * the end). The figures, per scenario: drift / size (the body's largest bounding-box extent)
 * under 1e-3, and interpenetration / margin under 0.1. */
#include "sim.h"
#include "vec.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void usage(FILE *f)
{
    fprintf(f, "usage: ttd_sim [--scenario NAME]... [--seconds S] [--settle S] [--check] [--obj DIR] [--threads N]\n"
               "               [--jig S] [--vertical-normals] [--points K] [--hertz F] [--substeps N] [--iterations N] [--dt S] [--no-warm-start] [--surfaces]\n"
               "               [--ccd | --no-ccd]\n"
               "scenarios:");
    for (int k = 0; sim_scenarios[k]; ++k)
        fprintf(f, " %s", sim_scenarios[k]);
    fprintf(f, " (default: all)\n");
}

/// Runs scenario name and prints its row of figures (and, for a scene that judges itself, its
/// note); *met: whether its figures are met (its verdict, or drift < 1e-3 and interpenetration
/// < 0.1 at rest). seconds < 0: the scenario's own window, else 10 s.
static int run_one(const char *name, const sim_settings *set, double seconds, double settle, const char *obj_dir,
                   sim_figures *f, int *met)
{
    sim_run run;
    if (sim_run_build(&run, name, set) != 0) {
        fprintf(stderr, "ttd_sim: could not build scenario %s\n", name);
        return -1;
    }
    sim_world *w = &run.world;
    for (size_t k = 0; k < run.nshape; ++k)
        if (sim_shape_convexity_defect(run.shape + k) > 1e-12) {
            fprintf(stderr, "ttd_sim: %s: shape %s's pieces are not convex (defect %.3g)\n", name, run.shape[k].name,
                    sim_shape_convexity_defect(run.shape + k));
            sim_run_free(&run);
            return -1;
        }
    if (seconds < 0)
        seconds = run.seconds > 0 ? run.seconds : 10;
    int rc = sim_run_window(w, settle >= 0 ? settle : run.settle, seconds, sim_run_step, &run, f);
    if (rc == 0) {
        double steps = (double)w->steps;
        printf("%-12s %6zu %6zu %7.1f %8.3f %8.3f %10.2e %10.2e %10.2e %8.1f %9.2e %7zu  %s %zu\n", name, w->n,
               w->steps, (double)w->points / steps, 1e3 * w->query_seconds / steps, 1e3 * w->solve_seconds / steps,
               f->drift, f->centre_drift, f->overlap, f->max_tilt_deg, f->kinetic, f->touching,
               w->body[f->drift_body].shape->name, f->drift_body);
        *met = f->drift < 1e-3 && f->overlap < 0.1;
        if (run.verdict) {
            char note[512];
            *met = run.verdict(&run, f, note, sizeof note);
            printf("  %s\n", note);
        }
        fflush(stdout);
    }
    if (rc == 0 && obj_dir) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s.obj", obj_dir, name);
        if (sim_world_write_obj(w, path) != 0) {
            fprintf(stderr, "ttd_sim: could not write %s\n", path);
            rc = -1;
        }
    }
    sim_run_free(&run);
    return rc;
}

/// The number in text, or NAN when text is not one whole number.
static double number(const char *text)
{
    char *end;
    double x = strtod(text, &end);
    return (end != text && *end == 0) ? x : (double)NAN;
}

int main(int argc, char **argv)
{
    sim_settings set = sim_default_settings();
    const char *names[32], *obj_dir = NULL;
    int nnames = 0, check = 0;
    double seconds = -1, settle = -1;
    for (int k = 1; k < argc; ++k) {
        const char *a = argv[k];
        if (!strcmp(a, "--check")) {
            check = 1;
            continue;
        } else if (!strcmp(a, "--vertical-normals")) {
            set.vertical_normals = 1;
            continue;
        } else if (!strcmp(a, "--no-warm-start")) {
            set.warm_start = 0;
            continue;
        } else if (!strcmp(a, "--surfaces")) {
            set.solid = 0;
            continue;
        } else if (!strcmp(a, "--ccd")) {
            set.ccd = 1;
            continue;
        } else if (!strcmp(a, "--no-ccd")) {
            set.ccd = 0;
            continue;
        } else if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            return 0;
        }
        if (k + 1 == argc) {
            fprintf(stderr, "ttd_sim: %s needs a value\n", a);
            usage(stderr);
            return 2;
        }
        const char *v = argv[++k];
        double x = number(v);
        int ok = isfinite(x);
        if (!strcmp(a, "--scenario")) {
            ok = nnames < 32;
            int known = 0;
            for (int i = 0; sim_scenarios[i]; ++i)
                known |= !strcmp(sim_scenarios[i], v);
            ok = ok && known;
            if (ok)
                names[nnames++] = v;
        } else if (!strcmp(a, "--obj")) {
            ok = 1;
            obj_dir = v;
        } else if (!strcmp(a, "--seconds")) {
            ok = ok && x >= 0;
            seconds = x;
        } else if (!strcmp(a, "--settle")) {
            ok = ok && x >= 0;
            settle = x;
        } else if (!strcmp(a, "--threads")) {
            ok = ok && x >= 0 && x <= 1024 && x == floor(x);
            set.threads = (int)x;
        } else if (!strcmp(a, "--jig")) {
            set.jig = x;
        } else if (!strcmp(a, "--points")) {
            ok = ok && x >= 0 && x <= 1e6 && x == floor(x);
            set.max_points = (size_t)x;
        } else if (!strcmp(a, "--hertz")) {
            ok = ok && x > 0;
            set.contact_hertz = x;
        } else if (!strcmp(a, "--substeps")) {
            ok = ok && x >= 1 && x <= 1000 && x == floor(x);
            set.substeps = (int)x;
        } else if (!strcmp(a, "--iterations")) {
            ok = ok && x >= 1 && x <= 1000 && x == floor(x);
            set.iterations = (int)x;
        } else if (!strcmp(a, "--dt")) {
            ok = ok && x > 0 && x <= 0.1;
            set.dt = x;
        } else {
            fprintf(stderr, "ttd_sim: unknown option %s\n", a);
            usage(stderr);
            return 2;
        }
        if (!ok) {
            fprintf(stderr, "ttd_sim: bad value for %s: %s\n", a, v);
            usage(stderr);
            return 2;
        }
    }
    if (nnames == 0)
        for (; sim_scenarios[nnames]; ++nnames)
            names[nnames] = sim_scenarios[nnames];
    printf("ttd_sim (ttd %s, %s): dt %.6g s, margin %g, rest gap %g, %zu points per pair, %d substeps of %d sweeps, "
           "friction %g (each scene's own where it sets one), %g s at rest after each scenario settles\n",
           ttd_version_string(), ttd_isa_name(ttd_isa_selected(NULL)), set.dt, set.margin, set.rest_gap,
           set.max_points, set.substeps, set.iterations, set.friction, seconds < 0 ? 10 : seconds);
    printf("%-12s %6s %6s %7s %8s %8s %10s %10s %10s %8s %9s %7s%s\n", "scenario", "bodies", "steps", "points",
           "query ms", "solve ms", "drift", "ctr drift", "overlap", "tilt deg", "kinetic", "touch", "  drifting most");
    int failed = 0;
    for (int k = 0; k < nnames; ++k) {
        sim_figures f;
        int met = 0;
        if (run_one(names[k], &set, seconds, settle, obj_dir, &f, &met) != 0)
            return 1;
        if (check && !met) {
            fprintf(stderr, "ttd_sim: %s FAILED: drift %.3g of body %zu's size (limit 1e-3), interpenetration %.3g "
                            "of the margin between bodies %u and %u (limit 0.1)%s\n",
                    names[k], f.drift, f.drift_body, f.overlap, f.overlap_a, f.overlap_b,
                    " (or the scene's own check above)");
            failed = 1;
        }
    }
    if (check)
        printf("%s\n", failed ? "FAILED: some figures are not met" : "every figure met");
    return failed;
}
