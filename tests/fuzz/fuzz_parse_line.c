/* SPDX-License-Identifier: MIT */
/* libFuzzer target: the CLI's input path (cli/parse.h) on arbitrary bytes. The bytes are read
 * as a file through the line reader (any length, NUL bytes, CR, missing final newline), and
 * every line is parsed, in double and in float; the whole input is also parsed as one line.
 * Checked: no crash or out-of-bounds access (AddressSanitizer, buffers sized exactly), lines
 * never longer than TTD_CLI_MAX_LINE (a leading byte-order mark dropped), line numbers counting
 * up by one, a pair line holding 18 finite numbers (floats, exactly, in float), an error line
 * carrying a non-empty message, both precisions agreeing on what is blank or a comment and a
 * line that is bad in double being bad in float too. Build and run: scripts/fuzz.sh. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "parse.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static ttd_line_kind check_line_as(const char *line, size_t len, int as_float)
{
    double v[18];
    char err[256];
    err[0] = '\0';
    ttd_line_kind k = ttd_parse_pair_line(line, len, as_float, v, err, sizeof err);
    if (k == TTD_LINE_PAIR) {
        for (int i = 0; i < 18; ++i)
            if (!isfinite(v[i]) || (as_float && (double)(float)v[i] != v[i]))
                abort();
    } else if (k == TTD_LINE_ERROR) {
        size_t n = strnlen(err, sizeof err);
        if (n == 0 || n == sizeof err)
            abort();
    } else if (k != TTD_LINE_SKIP) {
        abort();
    }
    /* The pose parser of `ttd mesh` (12 or 16 numbers) on the same line: the same kinds of
     * answer, a blank or comment line skipped by both. */
    double pose[12];
    char perr[256];
    perr[0] = '\0';
    ttd_line_kind pk = ttd_parse_pose_line(line, len, as_float, pose, perr, sizeof perr);
    if (pk == TTD_LINE_PAIR) {
        for (int i = 0; i < 12; ++i)
            if (!isfinite(pose[i]))
                abort();
    } else if (pk == TTD_LINE_ERROR) {
        size_t n = strnlen(perr, sizeof perr);
        if (n == 0 || n == sizeof perr)
            abort();
    } else if (pk != TTD_LINE_SKIP) {
        abort();
    }
    if ((pk == TTD_LINE_SKIP) != (k == TTD_LINE_SKIP))
        abort();
    return k;
}

/* Both precisions see the same lines as blank, comment, pair or error, except that a number
 * beyond float range is an error in float only. */
static void check_line(const char *line, size_t len)
{
    ttd_line_kind kd = check_line_as(line, len, 0), kf = check_line_as(line, len, 1);
    if ((kd == TTD_LINE_SKIP) != (kf == TTD_LINE_SKIP) || (kd == TTD_LINE_ERROR && kf == TTD_LINE_PAIR))
        abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* The whole input as one line, in a buffer of exactly size + 1 bytes. */
    char *line = malloc(size + 1);
    if (!line)
        return 0;
    if (size)
        memcpy(line, data, size);
    line[size] = '\0';
    check_line(line, size);
    free(line);

    /* The input as a file, through the reader. */
    if (size == 0)
        return 0;
    FILE *f = fmemopen((void *)(uintptr_t)data, size, "r");
    if (!f)
        return 0;
    static ttd_line_reader r; /* 70 KB: not on the stack */
    ttd_reader_init(&r, f);
    size_t len = 0, newlines = 0;
    int overlong = 0;
    unsigned long long expect = 0;
    for (size_t i = 0; i < size; ++i)
        newlines += data[i] == '\n';
    while (ttd_reader_next(&r, &len, &overlong)) {
        if (len > TTD_CLI_MAX_LINE || r.line[len] != '\0' || r.line_no != ++expect || expect > newlines + 1)
            abort();
        check_line(r.line, len);
    }
    fclose(f);
    return 0;
}
