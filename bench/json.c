/* SPDX-License-Identifier: MIT */
/* Output pieces every writer of `ttd bench` shares (bench/json.h). */
#include <math.h>

#include "json.h"

void bench_json_string(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; ++s) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(f, "\\%c", c);
        else if (c < 0x20)
            fprintf(f, "\\u%04x", c);
        else
            fputc(c, f);
    }
    fputc('"', f);
}

const char *bench_slower_note(char *buf, size_t size, double x, const char *other)
{
    if (isfinite(x) && x > 0.0 && x < 1.0)
        snprintf(buf, size, "%s faster: ttd took %.2fx its time", other, 1.0 / x);
    else if (size)
        buf[0] = '\0';
    return buf;
}

const char *bench_num(char *buf, size_t size, double v, const char *fmt)
{
    if (!isfinite(v))
        snprintf(buf, size, "-");
    else
        snprintf(buf, size, fmt, v);
    return buf;
}
