/* SPDX-License-Identifier: MIT */
/* Bullet's contact manifolds beside ttd's: the scene workload written and the program run by
 * bench/fcl_scene_link.c's bench_scene_program_run, the program's answers read here
 * (bench/bullet_scene_link.h). When the program was not built (no Bullet), the call says so and
 * the benchmark goes on without Bullet. */
#define _POSIX_C_SOURCE 200809L
#include "bullet_scene_link.h"
#include "bench_internal.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

void bench_bullet_scene_result_free(bench_bullet_scene_result *r)
{
    if (!r)
        return;
    free(r->pairs);
    free(r->pair_points);
    free(r->step_pairs);
    free(r->step_points);
    r->pairs = NULL;
    r->pair_points = NULL;
    r->step_pairs = r->step_points = NULL;
}

static int parse_output(const char *path, size_t nbodies, bench_bullet_scene_result *out)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        snprintf(out->error, sizeof out->error, "%.300s: %s", path, strerror(errno));
        return -1;
    }
    char line[512] = "";
    size_t want = 0, have = 0, got_steps = 0;
    unsigned seen = 0;
    int ok = 1;
    while (ok && fgets(line, sizeof line, f)) {
        char key[16];
        int n = 0, used = 0;
        unsigned long long a = 0, b = 0, c = 0;
        if (line[0] == '#') {
            int v = 0;
            char prec[16];
            if (sscanf(line, "# %*s bullet %d precision %15s", &v, prec) == 2)
                snprintf(out->version, sizeof out->version, "%d.%02d (%s)", v / 100, v % 100, prec);
            continue;
        }
        if (sscanf(line, "%15s%n", key, &n) != 1)
            continue;
        const char *rest = line + n;
        if (strcmp(key, "mpair") == 0) {
            ok = out->pairs && have < want && sscanf(rest, "%llu %llu %llu", &a, &b, &c) == 3 && a < b && b < nbodies;
            if (ok) {
                out->pairs[have].i = (uint32_t)a;
                out->pairs[have].j = (uint32_t)b;
                out->pair_points[have++] = (uint32_t)c;
            }
        } else if (strcmp(key, "step") == 0) {
            ok = out->step_pairs && sscanf(rest, "%llu %llu %llu", &a, &b, &c) == 3 && a < out->steps;
            if (ok) {
                out->step_pairs[a] = b;
                out->step_points[a] = c;
                ++got_steps;
            }
        } else if (have != want) {
            ok = 0;
        } else if (strcmp(key, "build") == 0) {
            ok = sscanf(rest, "%lf %lf", &out->build.ms, &out->build.ms_min) == 2;
            seen |= 1;
        } else if (strcmp(key, "manifold") == 0) {
            ok = sscanf(rest, "%lf %lf%n", &out->manifold.ms, &out->manifold.ms_min, &used) == 2 &&
                 sscanf(rest + used, "%llu %llu", &a, &b) == 2 && b <= nbodies * (nbodies - 1) / 2;
            if (ok) {
                out->manifold.count = a;
                out->manifold.candidates = b;
                want = b;
                out->pairs = calloc(b + 1, sizeof *out->pairs);
                out->pair_points = calloc(b + 1, sizeof *out->pair_points);
                ok = out->pairs && out->pair_points;
            }
            seen |= 2;
        } else if (strcmp(key, "motion") == 0) {
            ok = sscanf(rest, "%lf %lf %llu", &out->motion.ms, &out->motion.ms_min, &a) == 3 && a == out->steps;
            out->step_pairs = calloc(out->steps + 1, sizeof *out->step_pairs);
            out->step_points = calloc(out->steps + 1, sizeof *out->step_points);
            ok = ok && out->step_pairs && out->step_points;
            seen |= 4;
        } else {
            ok = 0;
        }
    }
    fclose(f);
    if (!ok || have != want || (seen & 3) != 3 || (out->steps && (!(seen & 4) || got_steps != out->steps))) {
        snprintf(out->error, sizeof out->error, "%s's output is malformed or incomplete (near: %.80s)",
                 BENCH_BULLET_SCENE_PROGRAM, line);
        return -1;
    }
    return 0;
}

int bench_bullet_scene_run(const char *program, const bench_fcl_scene_job *job, bench_bullet_scene_result *out)
{
    memset(out, 0, sizeof *out);
    out->steps = job && job->motion_runs ? job->steps : 0;
    char out_name[512];
    if (bench_scene_program_run(program, job, out_name, sizeof out_name, out->error, sizeof out->error) != 0)
        return BENCH_FCL_SCENE_ERROR;
    const int rc = parse_output(out_name, job->nbodies, out) == 0 ? BENCH_FCL_SCENE_OK : BENCH_FCL_SCENE_ERROR;
    unlink(out_name);
    if (rc != BENCH_FCL_SCENE_OK)
        bench_bullet_scene_result_free(out);
    return rc;
}
