/* SPDX-License-Identifier: MIT */
/* FCL's scene queries beside ttd's: writes a scene (meshes, bodies, poses, a motion) to a
 * temporary file, runs the C++ program ttd_fcl_scene_bench (bench/fcl/fcl_scene_bench.cpp) on it
 * and reads back its times and answers. The formats are in bench/fcl_scene_link.h. When the
 * program was not built (no FCL), the call says so and the benchmark goes on without FCL. */
#define _POSIX_C_SOURCE 200809L
#include "fcl_scene_link.h"
#include "bench_internal.h"

#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <math.h>
#include <spawn.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

static void set_error(char *err, size_t size, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void set_error(char *err, size_t size, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, size, fmt, ap);
    va_end(ap);
}

void bench_fcl_scene_result_free(bench_fcl_scene_result *r)
{
    if (!r)
        return;
    free(r->pairs0);
    free(r->pairsm);
    free(r->step_pairs);
    r->pairs0 = r->pairsm = NULL;
    r->step_pairs = NULL;
}

static int temp_name(char *name, size_t size, const char *tag)
{
    const char *dir = getenv("TMPDIR");
    if (!dir || !*dir)
        dir = "/tmp";
    if ((size_t)snprintf(name, size, "%s/ttd-bench-scene-%s-XXXXXX", dir, tag) >= size)
        return -1;
    int fd = mkstemp(name);
    if (fd < 0)
        return -1;
    close(fd);
    return 0;
}

static void put_uint(FILE *f, uint64_t x, int bytes)
{
    unsigned char b[8];
    for (int i = 0; i < bytes; ++i)
        b[i] = (unsigned char)(x >> (8 * i));
    fwrite(b, 1, (size_t)bytes, f);
}

static void put_f64(FILE *f, double x)
{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    put_uint(f, bits, 8);
}

static int write_job(const char *path, const bench_fcl_scene_job *job, char *err, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        set_error(err, size, "%s: %s", path, strerror(errno));
        return -1;
    }
    fwrite(BENCH_FCL_SCENE_MAGIC, 1, 8, f);
    put_uint(f, job->repetitions, 4);
    put_uint(f, job->motion_runs, 4);
    put_f64(f, job->margin);
    put_uint(f, job->nmeshes, 4);
    for (uint32_t m = 0; m < job->nmeshes; ++m) {
        const bench_fcl_scene_mesh *g = &job->meshes[m];
        put_uint(f, g->nv, 8);
        put_uint(f, g->nt, 8);
        for (size_t i = 0; i < 3 * g->nv; ++i)
            put_f64(f, g->vertices[i]);
        for (size_t i = 0; i < 3 * g->nt; ++i)
            put_uint(f, g->triangles[i], 4);
    }
    put_uint(f, job->nbodies, 8);
    for (size_t b = 0; b < job->nbodies; ++b) {
        put_uint(f, job->body_mesh[b], 4);
        for (int i = 0; i < 12; ++i)
            put_f64(f, job->poses[12 * b + (size_t)i]);
    }
    put_uint(f, job->steps, 4);
    for (size_t i = 0; i < 12 * job->nbodies * job->steps; ++i)
        put_f64(f, job->motion[i]);
    int bad = ferror(f);
    if (fclose(f) != 0 || bad) {
        set_error(err, size, "cannot write %s", path);
        return -1;
    }
    return 0;
}

static void first_line(const char *path, char *out, size_t size)
{
    out[0] = '\0';
    FILE *f = fopen(path, "r");
    if (!f)
        return;
    if (fgets(out, (int)size, f))
        out[strcspn(out, "\n")] = '\0';
    fclose(f);
}

/* Reads a timed record's "MED MIN" and the rest into t; returns the fields after the times. */
static int parse_time(const char *rest, bench_fcl_scene_time *t, int *used)
{
    return sscanf(rest, "%lf %lf%n", &t->ms, &t->ms_min, used) == 2 ? 0 : -1;
}

static int parse_output(const char *path, size_t nbodies, bench_fcl_scene_result *out)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        set_error(out->error, sizeof out->error, "%s: %s", path, strerror(errno));
        return -1;
    }
    char line[512];
    size_t max_pairs = nbodies * (nbodies - 1) / 2;
    bench_fcl_scene_pair *into = NULL;
    size_t want = 0, have = 0, got_steps = 0;
    unsigned seen = 0;
    int ok = 1;
    while (ok && fgets(line, sizeof line, f)) {
        char key[16];
        int n = 0, used = 0;
        if (line[0] == '#' || sscanf(line, "%15s%n", key, &n) != 1)
            continue;
        const char *rest = line + n;
        unsigned long long a = 0, b = 0, c = 0;
        if (strcmp(key, "pair") == 0) {
            ok = into && have < want && sscanf(rest, "%llu %llu", &a, &b) == 2 && a < b && b < nbodies;
            if (ok) {
                into[have].i = (uint32_t)a;
                into[have++].j = (uint32_t)b;
            }
        } else if (strcmp(key, "step") == 0) {
            ok = out->step_pairs && sscanf(rest, "%llu %llu", &a, &b) == 2 && a < out->steps;
            if (ok) {
                out->step_pairs[a] = b;
                ++got_steps;
            }
        } else if (have != want) {
            ok = 0;
        } else if (strcmp(key, "build") == 0) {
            ok = parse_time(rest, &out->build, &used) == 0;
            seen |= 1;
        } else if (strcmp(key, "collide0") == 0 || strcmp(key, "collidem") == 0) {
            int zero = key[7] == '0';
            bench_fcl_scene_time *t = zero ? &out->collide0 : &out->collidem;
            ok = parse_time(rest, t, &used) == 0 && sscanf(rest + used, "%llu %llu", &a, &b) == 2 && a <= max_pairs;
            if (ok) {
                t->count = a;
                t->candidates = b;
                into = calloc(a + 1, sizeof *into);
                ok = into != NULL;
                if (zero)
                    out->pairs0 = into;
                else
                    out->pairsm = into;
                want = a;
                have = 0;
            }
            seen |= zero ? 2u : 4u;
        } else if (strcmp(key, "distance") == 0) {
            long long i, j, ia, ib;
            ok = parse_time(rest, &out->distance, &used) == 0 &&
                 sscanf(rest + used, "%lf %lld %lld %lld %lld %llu", &out->dist, &i, &j, &ia, &ib, &a) == 6;
            out->di = i, out->dj = j, out->dia = ia, out->dib = ib;
            out->distance.candidates = a;
            seen |= 8;
        } else if (strcmp(key, "contacts") == 0) {
            ok = parse_time(rest, &out->contacts, &used) == 0 &&
                 sscanf(rest + used, "%llu %llu %llu", &a, &b, &c) == 3;
            out->contacts.count = a;
            out->contact_body_pairs = b;
            out->contacts.candidates = c;
            seen |= 16;
        } else if (strcmp(key, "motion") == 0) {
            ok = parse_time(rest, &out->motion, &used) == 0 &&
                 sscanf(rest + used, "%lf %llu", &out->motion_update_ms, &a) == 2 && a == out->steps;
            out->step_pairs = calloc(out->steps + 1, sizeof *out->step_pairs);
            ok = ok && out->step_pairs;
            seen |= 32;
        } else {
            ok = 0;
        }
    }
    fclose(f);
    if (!ok || have != want || (seen & 31) != 31 || (out->steps && (!(seen & 32) || got_steps != out->steps))) {
        set_error(out->error, sizeof out->error, "%s's output is malformed or incomplete (near: %.80s)",
                  BENCH_FCL_SCENE_PROGRAM, line);
        return -1;
    }
    return 0;
}

int bench_scene_program_run(const char *program, const bench_fcl_scene_job *job, char *out_name, size_t out_size,
                            char *err, size_t err_size)
{
    out_name[0] = '\0';
    if (!job || job->nbodies < 2 || !job->nmeshes || job->repetitions < 1 || !(job->margin > 0.0) ||
        (job->steps && !job->motion)) {
        set_error(err, err_size, "bad scene job");
        return -1;
    }
    char in_name[512], err_name[512];
    in_name[0] = err_name[0] = '\0';
    int rc = -1;
    if (temp_name(in_name, sizeof in_name, "in") || temp_name(out_name, out_size, "out") ||
        temp_name(err_name, sizeof err_name, "err")) {
        set_error(err, err_size, "cannot create a temporary file: %s", strerror(errno));
        goto done;
    }
    bench_fcl_scene_job j = *job;
    if (!j.motion_runs)
        j.steps = 0;
    if (write_job(in_name, &j, err, err_size))
        goto done;
    char prog[1024];
    snprintf(prog, sizeof prog, "%s", program);
    char *argv[] = {prog, in_name, NULL};
    posix_spawn_file_actions_t actions;
    if (posix_spawn_file_actions_init(&actions) != 0) {
        set_error(err, err_size, "cannot spawn %s", program);
        goto done;
    }
    pid_t pid;
    int spawned = posix_spawn_file_actions_addopen(&actions, 1, out_name, O_WRONLY | O_TRUNC, 0) == 0 &&
                  posix_spawn_file_actions_addopen(&actions, 2, err_name, O_WRONLY | O_TRUNC, 0) == 0 &&
                  posix_spawn(&pid, program, &actions, NULL, argv, environ) == 0;
    posix_spawn_file_actions_destroy(&actions);
    if (!spawned) {
        set_error(err, err_size, "cannot run %s", program);
        goto done;
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) {
            set_error(err, err_size, "waiting for %s: %s", program, strerror(errno));
            goto done;
        }
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        char why[400];
        first_line(err_name, why, sizeof why);
        if (WIFEXITED(status))
            set_error(err, err_size, "%s exited with %d: %s", program, WEXITSTATUS(status), why);
        else
            set_error(err, err_size, "%s was killed by signal %d", program, WIFSIGNALED(status) ? WTERMSIG(status) : 0);
        goto done;
    }
    rc = 0;
done:
    if (in_name[0])
        unlink(in_name);
    if (err_name[0])
        unlink(err_name);
    if (rc != 0 && out_name[0]) {
        unlink(out_name);
        out_name[0] = '\0';
    }
    return rc;
}

int bench_fcl_scene_run(const char *program, const bench_fcl_scene_job *job, bench_fcl_scene_result *out)
{
    memset(out, 0, sizeof *out);
    char found[1024];
    if (!program) {
        if (bench_fcl_find_program(BENCH_FCL_SCENE_PROGRAM, BENCH_FCL_SCENE_ENV, NULL, found, sizeof found) != 0) {
            set_error(out->error, sizeof out->error,
                      "%s not found (FCL was not found when ttd was built; apt-get install libfcl-dev and rebuild, "
                      "or set %s): FCL is left out",
                      BENCH_FCL_SCENE_PROGRAM, BENCH_FCL_SCENE_ENV);
            return BENCH_FCL_SCENE_MISSING;
        }
        program = found;
    }
    out->steps = job && job->motion_runs ? job->steps : 0;
    char out_name[512];
    if (bench_scene_program_run(program, job, out_name, sizeof out_name, out->error, sizeof out->error) != 0)
        return BENCH_FCL_SCENE_ERROR;
    const int rc = parse_output(out_name, job->nbodies, out) == 0 ? BENCH_FCL_SCENE_OK : BENCH_FCL_SCENE_ERROR;
    unlink(out_name);
    if (rc != BENCH_FCL_SCENE_OK)
        bench_fcl_scene_result_free(out);
    return rc;
}
