/* SPDX-License-Identifier: MIT */
/* The command line's own cost per pair, for `ttd bench`: `ttd dist` run in-process on a
 * prepared input in memory, once as text (18 numbers a line, printed so that they read back
 * to the same values) and once as raw little-endian arrays (--binary-in --binary-out), with
 * distances only as output. In-process rather than by starting the program on a file: the
 * rows then hold the parsing, the engine and the formatting, and not the process start or
 * the file system, which are the same for both forms and do not scale with the pairs. The
 * output of the first pass is kept and read back, so that the benchmark can check that the
 * path computed the right distances; the timed passes write to /dev/null. */
#define _POSIX_C_SOURCE 200809L
#include "bench_internal.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

/* The input in memory: text or raw little-endian records. */
static char *make_input(int bytes, int binary, size_t n, const void *s, const void *t, size_t *len)
{
    const size_t size = (size_t)bytes, per_line = 18 * 26 + 1;
    char *buf = malloc(binary ? 18 * size * n : per_line * n + 1);
    if (!buf)
        return NULL;
    size_t used = 0;
    for (size_t i = 0; i < n; ++i) {
        for (int k = 0; k < 18; ++k) {
            const void *src = k < 9 ? s : t;
            size_t at = 9 * i + (size_t)(k % 9);
            double v = bytes == 8 ? ((const double *)src)[at] : (double)((const float *)src)[at];
            if (binary) {
                unsigned char raw[8];
                memcpy(raw, bytes == 8 ? (const void *)&((const double *)src)[at] : (const void *)&((const float *)src)[at],
                       size);
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
                for (size_t b = 0; b < size / 2; ++b) {
                    unsigned char c = raw[b];
                    raw[b] = raw[size - 1 - b];
                    raw[size - 1 - b] = c;
                }
#endif
                memcpy(buf + used, raw, size);
                used += size;
            } else {
                used += (size_t)snprintf(buf + used, per_line * n + 1 - used, bytes == 8 ? "%.17g%c" : "%.9g%c", v,
                                         k == 17 ? '\n' : ' ');
            }
        }
    }
    *len = used;
    return buf;
}

/* Reads the output of one pass back into n doubles; 0 when it holds exactly n distances. */
static int read_output(int bytes, int binary, const char *out, size_t len, size_t n, double *dist)
{
    if (binary) {
        if (len != n * (size_t)bytes)
            return -1;
        for (size_t i = 0; i < n; ++i) {
            uint64_t u = 0;
            for (int b = bytes - 1; b >= 0; --b)
                u = u << 8 | (unsigned char)out[i * (size_t)bytes + (size_t)b];
            if (bytes == 8) {
                memcpy(&dist[i], &u, 8);
            } else {
                uint32_t w = (uint32_t)u;
                float f;
                memcpy(&f, &w, 4);
                dist[i] = (double)f;
            }
        }
        return 0;
    }
    const char *p = out, *end = out + len;
    for (size_t i = 0; i < n; ++i) {
        char *stop;
        if (p >= end)
            return -1;
        dist[i] = strtod(p, &stop);
        if (stop == p || *stop != '\n')
            return -1;
        p = stop + 1;
    }
    return p == end ? 0 : -1;
}

/* One pass of `ttd dist` over the input; returns its exit status. */
static int one_pass(char **argv, int argc, char *input, size_t len, FILE *out)
{
    FILE *in = fmemopen(input, len, "r");
    if (!in)
        return -1;
    int rc = ttd_cli_dist_run(argc, argv, in, out);
    fclose(in);
    return rc;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int bench_cli_run(int bytes, int binary, const char *isa, size_t n, const void *s, const void *t, int samples,
                  double *dist, double *ns_median, double *ns_min)
{
    char isa_name[16];
    snprintf(isa_name, sizeof isa_name, "%s", isa);
    char *argv[] = {"dist", "--threads", "1", "--isa", isa_name, "--precision",
                    bytes == 8 ? "double" : "float", "--binary-in", "--binary-out", NULL};
    const int argc = binary ? 9 : 7;
    size_t len = 0;
    char *input = make_input(bytes, binary, n, s, t, &len);
    if (!input)
        return -1;
    int rc = -1;
    /* The first pass (also the warm-up) into memory, read back for the accuracy check. */
    char *captured = NULL;
    size_t captured_len = 0;
    FILE *mem = open_memstream(&captured, &captured_len);
    if (mem) {
        int st = one_pass(argv, argc, input, len, mem);
        fclose(mem);
        if (st == 0 && read_output(bytes, binary, captured, captured_len, n, dist) == 0)
            rc = 0;
    }
    free(captured);
    FILE *null = rc == 0 ? fopen("/dev/null", "wb") : NULL;
    static char outbuf[1 << 16]; /* as `ttd dist` buffers standard output */
    if (null)
        setvbuf(null, outbuf, _IOFBF, sizeof outbuf);
    else
        rc = -1;
    double t_ns[64];
    if (samples > 64)
        samples = 64;
    for (int k = 0; k < samples && rc == 0; ++k) {
        double t0 = bench_now();
        if (one_pass(argv, argc, input, len, null) != 0)
            rc = -1;
        t_ns[k] = (bench_now() - t0) * 1e9 / (double)n;
    }
    if (null)
        fclose(null);
    free(input);
    if (rc != 0)
        return -1;
    qsort(t_ns, (size_t)samples, sizeof t_ns[0], cmp_double);
    *ns_min = t_ns[0];
    *ns_median = samples % 2 ? t_ns[samples / 2] : 0.5 * (t_ns[samples / 2 - 1] + t_ns[samples / 2]);
    return 0;
}
