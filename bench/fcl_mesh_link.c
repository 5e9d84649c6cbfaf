/* SPDX-License-Identifier: MIT */
/* FCL's mesh queries beside ttd's: writes a mesh workload (two meshes, poses, a query) to a
 * temporary file, runs the C++ program ttd_fcl_mesh_bench (bench/fcl/fcl_mesh_bench.cpp) on
 * it and reads back its build times and one answer per pose (time, distance, points, triangle
 * ids, traversal counts, pairs). The formats are in bench/fcl_mesh_link.h. When the program
 * was not built (no FCL), the calls say so and the benchmark goes on without FCL. */
#define _POSIX_C_SOURCE 200809L
#include "fcl_mesh_link.h"
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

/* The program keeps counts in FCL's int; the same bound here gives the error before a spawn. */
#define MAX_COUNT ((size_t)1 << 30)

static void set_error(char *err, size_t size, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void set_error(char *err, size_t size, const char *fmt, ...)
{
    if (!err || size == 0)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, size, fmt, ap);
    va_end(ap);
}

int bench_fcl_mesh_find(const char *explicit_path, char *path, size_t size)
{
    return bench_fcl_find_program(BENCH_FCL_MESH_PROGRAM, BENCH_FCL_MESH_ENV, explicit_path, path, size) == 0
               ? BENCH_FCL_MESH_OK
               : BENCH_FCL_MESH_MISSING;
}

static int check_mesh(const bench_fcl_mesh *m, char name, char *err, size_t size)
{
    if (!m->vertices || !m->triangles) {
        set_error(err, size, "mesh %c: NULL vertex or triangle array", name);
        return -1;
    }
    if (m->nv < 3 || m->nt < 1 || m->nv > MAX_COUNT || m->nt > MAX_COUNT) {
        set_error(err, size, "mesh %c: %zu vertices and %zu triangles (needs 3..2^30 and 1..2^30)", name, m->nv,
                  m->nt);
        return -1;
    }
    for (size_t i = 0; i < 3 * m->nv; ++i)
        if (!isfinite(m->vertices[i])) {
            set_error(err, size, "mesh %c: vertex %zu has a non-finite coordinate", name, i / 3);
            return -1;
        }
    for (size_t i = 0; i < 3 * m->nt; ++i)
        if (m->triangles[i] >= m->nv) {
            set_error(err, size, "mesh %c: triangle %zu uses vertex %" PRIu32 ", out of range (%zu vertices)", name,
                      i / 3, m->triangles[i], m->nv);
            return -1;
        }
    return 0;
}

/* The program's rule for a rigid pose, so that a bad pose is named before the spawn. */
static int check_pose(const double *m, size_t k, char *err, size_t size)
{
    for (int i = 0; i < 12; ++i)
        if (!isfinite(m[i])) {
            set_error(err, size, "pose %zu has a non-finite entry", k);
            return -1;
        }
    double worst = 0.0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            double dot = m[4 * i] * m[4 * j] + m[4 * i + 1] * m[4 * j + 1] + m[4 * i + 2] * m[4 * j + 2];
            double e = fabs(dot - (i == j ? 1.0 : 0.0));
            worst = e > worst ? e : worst;
        }
    double det = m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
                 m[2] * (m[4] * m[9] - m[5] * m[8]);
    if (worst > 1e-9 || !(det > 0.0)) {
        set_error(err, size, "pose %zu: R is not a rotation (|R R^T - I| = %.3g, det %.17g)", k, worst, det);
        return -1;
    }
    return 0;
}

static int check_job(const bench_fcl_mesh_job *job, char *err, size_t size)
{
    if (!job) {
        set_error(err, size, "NULL job");
        return -1;
    }
    if ((unsigned)job->query >= BENCH_FCL_MESH_QUERY_COUNT) {
        set_error(err, size, "query %d unknown", (int)job->query);
        return -1;
    }
    if (job->repetitions < 1 || job->repetitions > 1000000) {
        set_error(err, size, "repetitions %" PRIu32 " out of range [1, 1000000]", job->repetitions);
        return -1;
    }
    if (!isfinite(job->margin) || job->margin < 0.0) {
        set_error(err, size, "margin %g is not a finite number >= 0", job->margin);
        return -1;
    }
    if (check_mesh(&job->a, 'A', err, size) || check_mesh(&job->b, 'B', err, size))
        return -1;
    if (!job->poses || job->nposes < 1 || job->nposes > SIZE_MAX / (12 * sizeof(double))) {
        set_error(err, size, "no poses (or a NULL pose array)");
        return -1;
    }
    for (size_t k = 0; k < job->nposes; ++k)
        if (check_pose(job->poses + 12 * k, k, err, size))
            return -1;
    return 0;
}

/* Little-endian output through a buffer, whatever the host's byte order. */
typedef struct writer {
    FILE *f;
    unsigned char buf[1 << 16];
    size_t used;
    int failed;
} writer;

static void put_bytes(writer *w, const void *p, size_t n)
{
    if (w->used + n > sizeof w->buf) {
        if (fwrite(w->buf, 1, w->used, w->f) != w->used)
            w->failed = 1;
        w->used = 0;
    }
    memcpy(w->buf + w->used, p, n);
    w->used += n;
}

static void put_uint(writer *w, uint64_t x, int bytes)
{
    unsigned char b[8];
    for (int i = 0; i < bytes; ++i)
        b[i] = (unsigned char)(x >> (8 * i));
    put_bytes(w, b, (size_t)bytes);
}

static void put_f64(writer *w, double x)
{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    put_uint(w, bits, 8);
}

static void put_mesh(writer *w, const bench_fcl_mesh *m)
{
    put_uint(w, m->nv, 8);
    put_uint(w, m->nt, 8);
    for (size_t i = 0; i < 3 * m->nv; ++i)
        put_f64(w, m->vertices[i]);
    for (size_t i = 0; i < 3 * m->nt; ++i)
        put_uint(w, m->triangles[i], 4);
}

int bench_fcl_mesh_write_job(const char *path, const bench_fcl_mesh_job *job, char *err, size_t err_size)
{
    if (!path) {
        set_error(err, err_size, "NULL path");
        return BENCH_FCL_MESH_ERROR;
    }
    if (check_job(job, err, err_size))
        return BENCH_FCL_MESH_ERROR;
    writer *w = malloc(sizeof *w);
    if (!w) {
        set_error(err, err_size, "out of memory");
        return BENCH_FCL_MESH_ERROR;
    }
    w->f = fopen(path, "wb");
    w->used = 0;
    w->failed = 0;
    if (!w->f) {
        set_error(err, err_size, "%s: %s", path, strerror(errno));
        free(w);
        return BENCH_FCL_MESH_ERROR;
    }
    put_bytes(w, BENCH_FCL_MESH_MAGIC, 8);
    put_uint(w, (uint64_t)job->query, 4);
    put_uint(w, job->repetitions, 4);
    put_f64(w, job->margin);
    put_mesh(w, &job->a);
    put_mesh(w, &job->b);
    put_uint(w, job->nposes, 8);
    for (size_t i = 0; i < 12 * job->nposes; ++i)
        put_f64(w, job->poses[i]);
    if (w->used && fwrite(w->buf, 1, w->used, w->f) != w->used)
        w->failed = 1;
    int ok = !w->failed && !ferror(w->f);
    ok = fclose(w->f) == 0 && ok;
    free(w);
    if (!ok) {
        set_error(err, err_size, "%s: cannot write the workload", path);
        return BENCH_FCL_MESH_ERROR;
    }
    return BENCH_FCL_MESH_OK;
}

void bench_fcl_mesh_result_free(bench_fcl_mesh_result *r)
{
    if (!r)
        return;
    free(r->poses);
    free(r->pairs);
    free(r->pair_start);
    r->poses = NULL;
    r->pairs = NULL;
    r->pair_start = NULL;
    r->nposes = 0;
}

static int temp_name(char *name, size_t size, const char *tag)
{
    const char *dir = getenv("TMPDIR");
    if (!dir || !*dir)
        dir = "/tmp";
    if ((size_t)snprintf(name, size, "%s/ttd-bench-mesh-%s-XXXXXX", dir, tag) >= size)
        return -1;
    int fd = mkstemp(name);
    if (fd < 0)
        return -1;
    close(fd);
    return 0;
}

/* The first line of a file, for an error message: the program's own explanation. */
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

static const char *const row_header[BENCH_FCL_MESH_QUERY_COUNT] = {
    "# pose median_ms min_ms distance px py pz qx qy qz ia ib bv_tests leaf_tests",
    "# pose median_ms min_ms collide ia ib bv_tests leaf_tests margin",
    "# pose median_ms min_ms pairs bv_tests leaf_tests",
    "# pose median_ms min_ms",
};

/* Splits a row into at most max fields at single spaces; returns the count. */
static int split(char *line, char **field, int max)
{
    int n = 0;
    for (char *tok = strtok(line, " \n"); tok; tok = strtok(NULL, " \n")) {
        if (n == max)
            return max + 1;
        field[n++] = tok;
    }
    return n;
}

static int parse_double(const char *s, double *x)
{
    char *end;
    errno = 0;
    *x = strtod(s, &end);
    return *s && !*end && errno == 0 ? 0 : -1;
}

static int parse_int(const char *s, long long lo, int64_t *x)
{
    char *end;
    errno = 0;
    long long v = strtoll(s, &end, 10);
    if (!*s || *end || errno || v < lo)
        return -1;
    *x = v;
    return 0;
}

static int parse_row(char *line, bench_fcl_mesh_query query, size_t k, bench_fcl_mesh_pose *r)
{
    static const int nfields[BENCH_FCL_MESH_QUERY_COUNT] = {14, 9, 6, 3};
    char *f[16];
    if (split(line, f, 16) != nfields[query])
        return -1;
    int64_t pose, a, b;
    if (parse_int(f[0], 0, &pose) || (uint64_t)pose != k || parse_double(f[1], &r->median_ms) ||
        parse_double(f[2], &r->min_ms))
        return -1;
    r->distance = BENCH_NAN;
    for (int i = 0; i < 3; ++i)
        r->p[i] = r->q[i] = BENCH_NAN;
    r->ia = r->ib = -1;
    r->margin_supported = 1;
    if (query == BENCH_FCL_MESH_DISTANCE) {
        if (parse_double(f[3], &r->distance))
            return -1;
        for (int i = 0; i < 3; ++i)
            if (parse_double(f[4 + i], &r->p[i]) || parse_double(f[7 + i], &r->q[i]))
                return -1;
        if (parse_int(f[10], 0, &r->ia) || parse_int(f[11], 0, &r->ib) || parse_int(f[12], 0, &a) ||
            parse_int(f[13], 0, &b))
            return -1;
    } else if (query == BENCH_FCL_MESH_COLLIDE) {
        int64_t c;
        if (parse_int(f[3], 0, &c) || c > 1 || parse_int(f[4], -1, &r->ia) || parse_int(f[5], -1, &r->ib) ||
            parse_int(f[6], 0, &a) || parse_int(f[7], 0, &b))
            return -1;
        r->collide = (int)c;
        if (strcmp(f[8], "ok") == 0)
            r->margin_supported = 1;
        else if (strcmp(f[8], "unsupported") == 0)
            r->margin_supported = 0;
        else
            return -1;
    } else if (query == BENCH_FCL_MESH_PAIRS) {
        int64_t n;
        if (parse_int(f[3], 0, &n) || parse_int(f[4], 0, &a) || parse_int(f[5], 0, &b))
            return -1;
        r->pairs = (uint64_t)n;
    } else { /* refit: the times only */
        a = b = 0;
    }
    r->bv_tests = (uint64_t)a;
    r->leaf_tests = (uint64_t)b;
    return 0;
}

static int parse_output(const char *path, bench_fcl_mesh_query query, size_t nposes, bench_fcl_mesh_result *out)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        set_error(out->error, sizeof out->error, "%s: %s", path, strerror(errno));
        return -1;
    }
    char line[1024];
    int rc = -1;
    size_t k = 0;
    int header = 0;
    if (!fgets(line, sizeof line, f) || sscanf(line, "build_ms %lf %lf", &out->build_ms[0], &out->build_ms[1]) != 2) {
        set_error(out->error, sizeof out->error, "the program's output does not start with build_ms");
        goto done;
    }
    while (fgets(line, sizeof line, f)) {
        if (line[0] == '#') {
            line[strcspn(line, "\n")] = '\0';
            if (strncmp(line, "# pose ", 7) == 0) {
                if (strcmp(line, row_header[query]) != 0) {
                    set_error(out->error, sizeof out->error, "unexpected row fields \"%s\"", line);
                    goto done;
                }
                header = 1;
            }
            continue;
        }
        if (!header || k == nposes || parse_row(line, query, k, &out->poses[k]) != 0) {
            set_error(out->error, sizeof out->error, "cannot read the program's row for pose %zu", k);
            goto done;
        }
        ++k;
    }
    if (k != nposes) {
        set_error(out->error, sizeof out->error, "the program answered %zu of %zu poses", k, nposes);
        goto done;
    }
    rc = 0;
done:
    fclose(f);
    return rc;
}

static int get_uint(FILE *f, int bytes, uint64_t *x)
{
    unsigned char b[8];
    if (fread(b, 1, (size_t)bytes, f) != (size_t)bytes)
        return -1;
    *x = 0;
    for (int i = 0; i < bytes; ++i)
        *x |= (uint64_t)b[i] << (8 * i);
    return 0;
}

static int parse_pairs(const char *path, size_t nposes, bench_fcl_mesh_result *out)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        set_error(out->error, sizeof out->error, "%s: %s", path, strerror(errno));
        return -1;
    }
    int rc = -1;
    char magic[8];
    uint64_t k, n, ia, ib, bits;
    size_t total = 0, cap = 0;
    out->pair_start = calloc(nposes + 1, sizeof *out->pair_start);
    if (!out->pair_start || fread(magic, 1, 8, f) != 8 || memcmp(magic, BENCH_FCL_MESH_PAIRS_MAGIC, 8) != 0 ||
        get_uint(f, 8, &k) || k != nposes)
        goto done;
    for (size_t pose = 0; pose < nposes; ++pose) {
        if (get_uint(f, 8, &n) || n != out->poses[pose].pairs)
            goto done;
        for (uint64_t i = 0; i < n; ++i) {
            if (get_uint(f, 4, &ia) || get_uint(f, 4, &ib) || get_uint(f, 8, &bits))
                goto done;
            if (total == cap) {
                size_t grown = cap ? 2 * cap : 1024;
                bench_fcl_mesh_pair *p = realloc(out->pairs, grown * sizeof *p);
                if (!p)
                    goto done;
                out->pairs = p;
                cap = grown;
            }
            out->pairs[total].ia = (uint32_t)ia;
            out->pairs[total].ib = (uint32_t)ib;
            memcpy(&out->pairs[total].d, &bits, sizeof bits);
            ++total;
        }
        out->pair_start[pose + 1] = total;
    }
    rc = fgetc(f) == EOF ? 0 : -1;
done:
    if (rc)
        set_error(out->error, sizeof out->error, "%s: not a complete pairs file for %zu poses", path, nposes);
    fclose(f);
    return rc;
}

int bench_fcl_mesh_run_file(const char *program, const char *in_path, bench_fcl_mesh_query query, size_t nposes,
                            int want_pairs, bench_fcl_mesh_result *out)
{
    if (!out)
        return BENCH_FCL_MESH_ERROR;
    memset(out, 0, sizeof *out);
    if (!program || !in_path || (unsigned)query >= BENCH_FCL_MESH_QUERY_COUNT || nposes < 1 ||
        (want_pairs && query != BENCH_FCL_MESH_PAIRS)) {
        set_error(out->error, sizeof out->error,
                  "bad arguments (NULL path, unknown query, no poses, or pairs asked for a query other than 2)");
        return BENCH_FCL_MESH_ERROR;
    }
    char out_name[512], err_name[512], pairs_name[512];
    pairs_name[0] = '\0';
    if (temp_name(out_name, sizeof out_name, "out")) {
        set_error(out->error, sizeof out->error, "cannot create a temporary file: %s", strerror(errno));
        return BENCH_FCL_MESH_ERROR;
    }
    int rc = BENCH_FCL_MESH_ERROR;
    if (temp_name(err_name, sizeof err_name, "err")) {
        set_error(out->error, sizeof out->error, "cannot create a temporary file: %s", strerror(errno));
        unlink(out_name);
        return BENCH_FCL_MESH_ERROR;
    }
    if (want_pairs && temp_name(pairs_name, sizeof pairs_name, "pairs")) {
        set_error(out->error, sizeof out->error, "cannot create a temporary file: %s", strerror(errno));
        pairs_name[0] = '\0';
        goto done;
    }
    out->poses = calloc(nposes, sizeof *out->poses);
    if (!out->poses) {
        set_error(out->error, sizeof out->error, "out of memory");
        goto done;
    }
    out->nposes = nposes;

    char prog[1024], in[1024], flag[] = "--pairs";
    snprintf(prog, sizeof prog, "%s", program);
    snprintf(in, sizeof in, "%s", in_path);
    char *argv[] = {prog, in, want_pairs ? flag : NULL, want_pairs ? pairs_name : NULL, NULL};
    posix_spawn_file_actions_t actions;
    if (posix_spawn_file_actions_init(&actions) != 0) {
        set_error(out->error, sizeof out->error, "cannot spawn %s", program);
        goto done;
    }
    pid_t pid;
    int spawned = posix_spawn_file_actions_addopen(&actions, 1, out_name, O_WRONLY | O_TRUNC, 0) == 0 &&
                  posix_spawn_file_actions_addopen(&actions, 2, err_name, O_WRONLY | O_TRUNC, 0) == 0 &&
                  posix_spawn(&pid, program, &actions, NULL, argv, environ) == 0;
    posix_spawn_file_actions_destroy(&actions);
    if (!spawned) {
        set_error(out->error, sizeof out->error, "cannot run %s", program);
        goto done;
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) {
            set_error(out->error, sizeof out->error, "waiting for %s: %s", program, strerror(errno));
            goto done;
        }
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        char why[400];
        first_line(err_name, why, sizeof why);
        if (WIFEXITED(status))
            set_error(out->error, sizeof out->error, "%s exited with %d: %s", program, WEXITSTATUS(status), why);
        else
            set_error(out->error, sizeof out->error, "%s was killed by signal %d", program,
                      WIFSIGNALED(status) ? WTERMSIG(status) : 0);
        goto done;
    }
    if (parse_output(out_name, query, nposes, out) == 0 && (!want_pairs || parse_pairs(pairs_name, nposes, out) == 0))
        rc = BENCH_FCL_MESH_OK;
done:
    if (rc != BENCH_FCL_MESH_OK)
        bench_fcl_mesh_result_free(out);
    unlink(out_name);
    unlink(err_name);
    if (pairs_name[0])
        unlink(pairs_name);
    return rc;
}

int bench_fcl_mesh_run(const char *program, const bench_fcl_mesh_job *job, int want_pairs,
                       bench_fcl_mesh_result *out)
{
    if (!out)
        return BENCH_FCL_MESH_ERROR;
    memset(out, 0, sizeof *out);
    char found[1024];
    if (!program) {
        if (bench_fcl_mesh_find(NULL, found, sizeof found) != BENCH_FCL_MESH_OK) {
            set_error(out->error, sizeof out->error,
                      "%s not found (FCL was not found when ttd was built; apt-get install libfcl-dev and rebuild, "
                      "or set %s): FCL is left out",
                      BENCH_FCL_MESH_PROGRAM, BENCH_FCL_MESH_ENV);
            return BENCH_FCL_MESH_MISSING;
        }
        program = found;
    }
    if (check_job(job, out->error, sizeof out->error))
        return BENCH_FCL_MESH_ERROR;
    char in_name[512];
    if (temp_name(in_name, sizeof in_name, "in")) {
        set_error(out->error, sizeof out->error, "cannot create a temporary file: %s", strerror(errno));
        return BENCH_FCL_MESH_ERROR;
    }
    int rc = bench_fcl_mesh_write_job(in_name, job, out->error, sizeof out->error);
    if (rc == BENCH_FCL_MESH_OK)
        rc = bench_fcl_mesh_run_file(program, in_name, job->query, job->nposes, want_pairs, out);
    unlink(in_name);
    return rc;
}
