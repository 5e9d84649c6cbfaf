/* SPDX-License-Identifier: MIT */
/* Helpers shared by the ttd commands: messages and option values (cli/cli.h). */
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>


void ttd_cli_error(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("ttd: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
}

int ttd_cli_parse_method(const char *s, ttd_method *out)
{
    for (int m = 0; m < TTD_METHOD_COUNT; ++m) {
        const char *name = ttd_method_name((ttd_method)m);
        if (name && strcmp(s, name) == 0) {
            *out = (ttd_method)m;
            return 0;
        }
    }
    return -1;
}

int ttd_cli_parse_isa(const char *s, ttd_isa *out)
{
    for (int i = 0; i < TTD_ISA_COUNT; ++i) {
        const char *name = ttd_isa_name((ttd_isa)i);
        if (name && strcmp(s, name) == 0) {
            *out = (ttd_isa)i;
            return 0;
        }
    }
    return -1;
}

int ttd_cli_parse_int(const char *s, long lo, long hi, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s || *end != '\0' || errno != 0 || v < lo || v > hi)
        return -1;
    *out = v;
    return 0;
}

int ttd_cli_parse_real(const char *s, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end != '\0' || !isfinite(v))
        return -1;
    *out = v;
    return 0;
}

void ttd_cli_print_isas(FILE *f)
{
    fputs("built:", f);
    for (int i = 1; i < TTD_ISA_COUNT; ++i)
        if (ttd_isa_built((ttd_isa)i))
            fprintf(f, " %s", ttd_isa_name((ttd_isa)i));
    fputs("\ncpu:  ", f);
    for (int i = 1; i < TTD_ISA_COUNT; ++i)
        if (ttd_isa_supported((ttd_isa)i))
            fprintf(f, " %s", ttd_isa_name((ttd_isa)i));
    const char *env = getenv("TTD_ISA");
    ttd_isa sel = ttd_isa_selected(NULL);
    fprintf(f, "\nauto:  %s", sel == TTD_ISA_AUTO ? "(none: TTD_ISA names an unavailable one)" : ttd_isa_name(sel));
    if (env && env[0])
        fprintf(f, " (TTD_ISA=%s)", env);
    fputc('\n', f);
}
