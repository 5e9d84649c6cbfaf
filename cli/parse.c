/* SPDX-License-Identifier: MIT */
/* The line reader and the pair-line parser of cli/parse.h. Everything is bounded: a line
 * is at most TTD_CLI_MAX_LINE bytes in memory however long it is in the file, and bytes that
 * are not part of a number or a comment (binary garbage, NUL) end the parse with a message
 * naming them. */
#define _POSIX_C_SOURCE 200809L

#include "parse.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void ttd_reader_init(ttd_line_reader *r, FILE *f)
{
    r->f = f;
    r->pos = r->len = 0;
    r->eof = r->error = 0;
    r->line_no = 0;
    r->line[0] = '\0';
}

/* Refills buf when empty; 0 when the input is exhausted. */
static int ttd_reader_fill(ttd_line_reader *r)
{
    if (r->pos < r->len)
        return 1;
    if (r->eof)
        return 0;
    r->pos = 0;
    errno = 0;
    r->len = fread(r->buf, 1, sizeof r->buf, r->f);
    if (r->len == 0) {
        r->eof = 1;
        if (ferror(r->f))
            r->error = errno != 0 ? errno : EIO;
        return 0;
    }
    return 1;
}

/* The blanks of every line format read here (space, tab, CR, VT, FF). */
static int ttd_is_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

int ttd_reader_next(ttd_line_reader *r, size_t *len, int *overlong)
{
    size_t n = 0;
    int got = 0;
    /* The first line may carry a 3-byte byte-order mark on top of the limit. */
    const size_t cap = TTD_CLI_MAX_LINE + (r->line_no == 0 ? 3 : 0);
    *overlong = 0;
    while (ttd_reader_fill(r)) {
        got = 1;
        const char *start = r->buf + r->pos;
        size_t avail = r->len - r->pos;
        const char *nl = memchr(start, '\n', avail);
        size_t take = nl ? (size_t)(nl - start) : avail;
        size_t room = cap - n;
        if (take > room) {
            /* What does not fit is dropped; only blanks dropped (padding, a line of blanks
             * alone) leave the line what it was, anything else makes it overlong. */
            memcpy(r->line + n, start, room);
            n += room;
            for (size_t k = room; k < take && !*overlong; ++k)
                *overlong = !ttd_is_blank(start[k]);
        } else {
            memcpy(r->line + n, start, take);
            n += take;
        }
        r->pos += take + (nl != NULL);
        if (nl)
            break;
    }
    if (!got)
        return 0;
    /* A UTF-8 byte-order mark (what some editors put first) is not part of the data. */
    if (r->line_no == 0 && n >= 3 && memcmp(r->line, "\xef\xbb\xbf", 3) == 0) {
        memmove(r->line, r->line + 3, n - 3);
        n -= 3;
    }
    if (n > TTD_CLI_MAX_LINE) {
        for (size_t k = TTD_CLI_MAX_LINE; k < n && !*overlong; ++k)
            *overlong = !ttd_is_blank(r->line[k]);
        n = TTD_CLI_MAX_LINE;
    }
    if (n > 0 && r->line[n - 1] == '\r' && !*overlong)
        --n;
    r->line[n] = '\0';
    *len = n;
    ++r->line_no;
    return 1;
}

/* Quotes up to 24 bytes of a token for a message: printable ASCII as is, others as \xHH. */
static void ttd_quote(const char *p, const char *end, char *out, size_t outsize)
{
    size_t o = 0;
    int k = 0;
    for (; p < end && !ttd_is_blank(*p) && k < 24 && o + 5 < outsize; ++p, ++k) {
        unsigned char c = (unsigned char)*p;
        if (c >= 0x20 && c < 0x7f)
            out[o++] = (char)c;
        else
            o += (size_t)snprintf(out + o, outsize - o, "\\x%02x", c);
    }
    if (p < end && !ttd_is_blank(*p) && o + 4 < outsize) {
        memcpy(out + o, "...", 3);
        o += 3;
    }
    out[o] = '\0';
}

/* Up to max numbers of a line into out, their count in *count; the syntax and messages of
 * ttd_parse_numbers_line, whose "expected ..." words are expect. */
static ttd_line_kind ttd_parse_upto(const char *line, size_t len, int as_float, int max, const char *expect,
                                    double *out, int *count_out, char *err, size_t errsize)
{
    const char *p = line, *end = line + len;
    while (p < end && ttd_is_blank(*p))
        ++p;
    if (p == end || *p == '#')
        return TTD_LINE_SKIP;

    int count = 0;
    while (p < end && *p != '#') {
        char tok[128];
        if (count == max) {
            int extra = 0;
            while (p < end && *p != '#') {
                ++extra;
                while (p < end && !ttd_is_blank(*p) && *p != '#')
                    ++p;
                while (p < end && ttd_is_blank(*p))
                    ++p;
            }
            snprintf(err, errsize, "expected %s numbers, found %d or more", expect, max + extra);
            return TTD_LINE_ERROR;
        }
        char *stop;
        errno = 0;
        /* In float each number is rounded once, decimal to float: through double it would be
         * rounded twice, and a decimal just above a midpoint between floats can land on it. */
        double v = as_float ? (double)strtof(p, &stop) : strtod(p, &stop);
        if (stop == p || (stop < end && !ttd_is_blank(*stop) && *stop != '#')) {
            ttd_quote(p, end, tok, sizeof tok);
            snprintf(err, errsize, "field %d is not a number: '%s'", count + 1, tok);
            return TTD_LINE_ERROR;
        }
        if (!isfinite(v)) {
            ttd_quote(p, end, tok, sizeof tok);
            snprintf(err, errsize, "field %d is %s: '%s'", count + 1,
                     errno != ERANGE ? "not finite" : as_float ? "out of float range" : "out of range", tok);
            return TTD_LINE_ERROR;
        }
        out[count++] = v;
        p = stop;
        while (p < end && ttd_is_blank(*p))
            ++p;
    }
    *count_out = count;
    return TTD_LINE_PAIR;
}

ttd_line_kind ttd_parse_numbers_line(const char *line, size_t len, int as_float, int want, double *out,
                                     char *err, size_t errsize)
{
    char expect[16];
    snprintf(expect, sizeof expect, "%d", want);
    int count = 0;
    ttd_line_kind kind = ttd_parse_upto(line, len, as_float, want, expect, out, &count, err, errsize);
    if (kind == TTD_LINE_PAIR && count != want) {
        snprintf(err, errsize, "expected %d numbers, found %d", want, count);
        return TTD_LINE_ERROR;
    }
    return kind;
}

ttd_line_kind ttd_parse_pose_line(const char *line, size_t len, int as_float, double out[12], char *err,
                                  size_t errsize)
{
    double v[16];
    int count = 0;
    ttd_line_kind kind = ttd_parse_upto(line, len, as_float, 16, "12 or 16", v, &count, err, errsize);
    if (kind != TTD_LINE_PAIR)
        return kind;
    if (count != 12 && count != 16) {
        snprintf(err, errsize, "expected 12 numbers ([R | t], 3x4) or 16 (a 4x4 matrix), found %d", count);
        return TTD_LINE_ERROR;
    }
    if (count == 16 && !(v[12] == 0 && v[13] == 0 && v[14] == 0 && v[15] == 1)) {
        snprintf(err, errsize, "the bottom row of a 4x4 pose must be 0 0 0 1, found %.17g %.17g %.17g %.17g", v[12],
                 v[13], v[14], v[15]);
        return TTD_LINE_ERROR;
    }
    memcpy(out, v, 12 * sizeof *out);
    return TTD_LINE_PAIR;
}

ttd_line_kind ttd_parse_pair_line(const char *line, size_t len, int as_float, double out[18],
                                  char *err, size_t errsize)
{
    return ttd_parse_numbers_line(line, len, as_float, 18, out, err, errsize);
}

ttd_line_kind ttd_read_pose_line(const ttd_line_reader *r, size_t len, int overlong, int as_float, double out[12],
                                 char *err, size_t errsize)
{
    const char *p = r->line;
    while (*p == ' ' || *p == '\t')
        ++p;
    if (overlong && *p != '#') {
        snprintf(err, errsize, "line longer than %d bytes", TTD_CLI_MAX_LINE);
        return TTD_LINE_ERROR;
    }
    return ttd_parse_pose_line(r->line, len, as_float, out, err, errsize);
}
