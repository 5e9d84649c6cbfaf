/* SPDX-License-Identifier: MIT */
/* Helpers shared by the ttd commands: messages and option values (cli/cli.h). */
#include "cli.h"

#include "ttd/meshfile.h"

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
    const ttd_isa isa = ttd_isa_from_name(s);
    if (isa == TTD_ISA_COUNT)
        return -1;
    *out = isa;
    return 0;
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
    const char *env = getenv("TTD_ISA"), *note = ttd_isa_env_note();
    fprintf(f, "\nauto:  %s", ttd_isa_name(ttd_isa_selected(NULL)));
    if (env && env[0])
        fprintf(f, " (TTD_ISA=%s%s)", env, note ? ": ignored, not an instruction set this machine runs" : "");
    fputc('\n', f);
}

void ttd_cli_warn_isa_env(const char *command)
{
    const char *note = ttd_isa_env_note();
    if (note != NULL)
        ttd_cli_error("%s: warning: TTD_ISA=%s: %s", command, getenv("TTD_ISA"), note);
}

int ttd_cli_run_option(const char *opt, const char *val, ttd_options *o, int *use_float)
{
    long iv;
    if (strcmp(opt, "--precision") == 0) {
        *use_float = strcmp(val, "float") == 0;
        return strcmp(val, "double") != 0 && !*use_float ? -1 : 0;
    }
    if (strcmp(opt, "--isa") == 0)
        return ttd_cli_parse_isa(val, &o->isa) ? -1 : 0;
    if (strcmp(opt, "--threads") == 0) {
        if (ttd_cli_parse_int(val, 0, 1 << 20, &iv))
            return -1;
        o->threads = (int)iv;
        return 0;
    }
    return 1;
}

ttd_cli_args ttd_cli_args_start(const char *command, const char *const *flags, const char *const *valued, int argc,
                                char **argv)
{
    ttd_cli_args w;
    memset(&w, 0, sizeof w);
    w.command = command;
    w.flags = flags;
    w.valued = valued;
    w.argc = argc;
    w.argv = argv;
    w.i = 1;
    return w;
}

/* The checks in the order every command made them when each had its own loop: operand, "--",
 * --help, a flag (the whole argument), an option with a value (its name, then '=' or the next
 * argument). */
ttd_cli_arg ttd_cli_next_arg(ttd_cli_args *w)
{
    w->opt = w->val = NULL;
    while (w->i < w->argc) {
        const char *arg = w->argv[w->i++];
        w->arg = arg;
        const int option = w->long_only ? strncmp(arg, "--", 2) == 0 || strcmp(arg, "-h") == 0
                                        : !w->only_operands && arg[0] == '-' && arg[1] != '\0';
        if (!option)
            return TTD_ARG_OPERAND;
        if (!w->long_only && !w->no_end_marker && strcmp(arg, "--") == 0) {
            w->only_operands = 1;
            continue;
        }
        if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0)
            return TTD_ARG_HELP;
        for (size_t k = 0; w->flags != NULL && w->flags[k] != NULL; ++k)
            if (strcmp(arg, w->flags[k]) == 0) {
                w->opt = w->flags[k];
                return TTD_ARG_FLAG;
            }
        for (size_t k = 0; w->valued != NULL && w->valued[k] != NULL; ++k) {
            const size_t l = strlen(w->valued[k]);
            if (strncmp(arg, w->valued[k], l) == 0 && (arg[l] == '\0' || arg[l] == '=')) {
                w->opt = w->valued[k];
                if (arg[l] == '=')
                    w->val = arg + l + 1;
                else if (w->i < w->argc)
                    w->val = w->argv[w->i++];
                break;
            }
        }
        if (w->opt == NULL) {
            ttd_cli_error("%s: unknown option '%s' (see ttd %s --help)", w->command, arg, w->command);
            return TTD_ARG_BAD;
        }
        if (w->val == NULL) {
            ttd_cli_error("%s: %s needs a value", w->command, w->opt);
            return TTD_ARG_BAD;
        }
        return TTD_ARG_VALUE;
    }
    return TTD_ARG_END;
}

int ttd_cli_stop_status(ttd_cli_arg k, const char *usage)
{
    if (k == TTD_ARG_HELP) {
        fputs(usage, stdout);
        return TTD_EXIT_OK;
    }
    return k == TTD_ARG_BAD ? TTD_EXIT_USAGE : -1;
}

void ttd_cli_bad_value(const ttd_cli_args *w, const char *why)
{
    if (why != NULL)
        ttd_cli_error("%s: bad value for %s: '%s' (%s)", w->command, w->opt, w->val, why);
    else
        ttd_cli_error("%s: bad value for %s: '%s' (see ttd %s --help)", w->command, w->opt, w->val, w->command);
}

int ttd_cli_parse_weld(const char *s, double *out)
{
    double v;
    if (ttd_cli_parse_real(s, &v) != 0 || !(v >= 0))
        return -1;
    *out = v;
    return 0;
}

int ttd_cli_weld(struct ttd_meshfile *m, const char *name, double tol)
{
    char err[512];
    size_t dropped = 0, nv = m->nv;
    if (ttd_meshfile_weld(m, tol, &dropped, err, sizeof err) != 0) {
        ttd_cli_error("%s: %s", name, err);
        return -1;
    }
    if (dropped > 0)
        ttd_cli_error("%s: --weld %g merged %zu vertices into %zu and dropped %zu collapsed triangle%s", name, tol, nv,
                      m->nv, dropped, dropped == 1 ? "" : "s");
    return 0;
}
