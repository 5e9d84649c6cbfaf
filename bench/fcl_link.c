/* SPDX-License-Identifier: MIT */
/* FCL beside ttd: `ttd bench` writes a workload to a temporary file, runs the separate C++
 * program ttd_fcl_bench (bench/fcl/) on it, and reads back FCL's median time per pair and
 * its distances, so that FCL is timed on exactly the pairs ttd was and the two can be
 * compared pair by pair. The file formats are described in bench/fcl/fcl_bench.cpp. */
#define _POSIX_C_SOURCE 200809L
#include "bench_internal.h"

#include <errno.h>
#include <spawn.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

#define FCL_PROGRAM "ttd_fcl_bench"

static int executable(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode) && access(path, X_OK) == 0;
}

int bench_fcl_find_program(const char *name, const char *env_var, const char *explicit_path, char *path,
                           size_t size)
{
    const char *env = getenv(env_var);
    if (explicit_path && *explicit_path) {
        snprintf(path, size, "%s", explicit_path);
        return executable(path) ? 0 : -1;
    }
    if (env && *env) {
        snprintf(path, size, "%s", env);
        return executable(path) ? 0 : -1;
    }
    char self[4096];
    ssize_t len = readlink("/proc/self/exe", self, sizeof self - 1);
    if (len <= 0)
        return -1;
    self[len] = '\0';
    char *slash = strrchr(self, '/');
    if (!slash)
        return -1;
    slash[1] = '\0';
    if ((size_t)snprintf(path, size, "%s%s", self, name) >= size)
        return -1;
    return executable(path) ? 0 : -1;
}

int bench_fcl_find(const char *explicit_path, char *path, size_t size)
{
    return bench_fcl_find_program(FCL_PROGRAM, "TTD_FCL_BENCH", explicit_path, path, size);
}

static int temp_file(char *name, size_t size, const char *tag)
{
    const char *dir = getenv("TMPDIR");
    if (!dir || !*dir)
        dir = "/tmp";
    snprintf(name, size, "%s/ttd-bench-%s-XXXXXX", dir, tag);
    return mkstemp(name);
}

static int write_all(int fd, const void *buf, size_t bytes)
{
    const char *p = buf;
    while (bytes > 0) {
        ssize_t k = write(fd, p, bytes);
        if (k < 0 && errno == EINTR)
            continue;
        if (k <= 0)
            return -1;
        p += k;
        bytes -= (size_t)k;
    }
    return 0;
}

static int read_exact(FILE *f, void *buf, size_t bytes)
{
    return fread(buf, 1, bytes, f) == bytes ? 0 : -1;
}

int bench_fcl_run(const char *program, int bytes, size_t n, const void *s, const void *t,
                  double min_sample_s, int samples, double *dist, double *ns_median, double *ns_min)
{
    char in_name[512], out_name[512], arg_time[32], arg_samples[16];
    int rc = -1;
    int in_fd = temp_file(in_name, sizeof in_name, "in");
    if (in_fd < 0)
        return -1;
    int out_fd = temp_file(out_name, sizeof out_name, "out");
    if (out_fd < 0) {
        close(in_fd);
        unlink(in_name);
        return -1;
    }
    close(out_fd);

    struct {
        char magic[4];
        uint32_t version, bytes, pad;
        uint64_t n;
    } head = {{'T', 'T', 'D', 'W'}, 1, (uint32_t)bytes, 0, (uint64_t)n};
    size_t payload = 9 * n * (size_t)bytes;
    int ok = write_all(in_fd, &head, sizeof head) == 0 && write_all(in_fd, s, payload) == 0 &&
             write_all(in_fd, t, payload) == 0;
    ok = close(in_fd) == 0 && ok;
    if (!ok)
        goto done;

    snprintf(arg_time, sizeof arg_time, "%g", min_sample_s);
    snprintf(arg_samples, sizeof arg_samples, "%d", samples);
    char prog[1024];
    snprintf(prog, sizeof prog, "%s", program);
    char *argv[] = {prog, in_name, out_name, arg_time, arg_samples, NULL};
    pid_t pid;
    if (posix_spawn(&pid, program, NULL, NULL, argv, environ) != 0)
        goto done;
    int status = 0;
    while (waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR)
            goto done;
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        goto done;

    FILE *f = fopen(out_name, "rb");
    if (!f)
        goto done;
    struct {
        char magic[4];
        uint32_t version, bytes, samples;
        uint64_t n;
    } rh;
    double times[2];
    if (read_exact(f, &rh, sizeof rh) == 0 && memcmp(rh.magic, "TTDR", 4) == 0 && rh.version == 1 &&
        rh.bytes == (uint32_t)bytes && rh.n == (uint64_t)n && read_exact(f, times, sizeof times) == 0 &&
        read_exact(f, dist, n * sizeof *dist) == 0) {
        *ns_median = times[0];
        *ns_min = times[1];
        rc = 0;
    }
    fclose(f);
done:
    unlink(in_name);
    unlink(out_name);
    return rc;
}
