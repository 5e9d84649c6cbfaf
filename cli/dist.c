/* SPDX-License-Identifier: MIT */
/* `ttd dist [options] [FILE]`: distances of the triangle pairs in FILE (or standard input),
 * one pair per line, computed by the batch engine block by block so that memory stays
 * constant however long the input is.
 *
 * Bad lines: every line that is not blank or a comment yields exactly one output line, so
 * output line k always belongs to the k-th pair line of the input. A line that cannot be
 * read as 18 finite numbers (wrong count, junk or binary bytes, an overlong line, NaN, inf, a
 * number out of range, or out of float range with --precision float) gets a message
 * "ttd: FILE:LINE: ..." on standard error and the output line "nan" (with --points, seven
 * "nan"); reading goes on, and the exit status is 1 at the end. Only the first
 * TTD_DIST_MAX_MESSAGES such messages are printed, then a count. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"
#include "parse.h"

/// Pairs read, computed and written at a time.
#define TTD_DIST_BLOCK 4096
/// Bad-line messages printed before the rest are only counted.
#define TTD_DIST_MAX_MESSAGES 20

static const char ttd_dist_usage[] =
    "usage: ttd dist [options] [FILE]\n"
    "Reads triangle pairs from FILE (or standard input when FILE is absent or '-'), one pair per\n"
    "line: 18 numbers separated by white space, A B C of the first triangle then D E F of the\n"
    "second, x y z each. Blank lines and lines starting with '#' are skipped. Writes one line\n"
    "per pair: the distance, or with --points the distance, p (3 numbers) and q (3 numbers).\n"
    "\n"
    "  --method M        %s (default exact)\n"
    "  --precision P     double (default, printed with %%.17g) or float (input rounded to float,\n"
    "                    printed with %%.9g)\n"
    "  --points          also print the closest points p and q\n"
    "  --rho R           penalty weight of the iterative methods, (0, 1e150] (default %g)\n"
    "  --tol T           step tolerance of the iterative methods, [0, 1] (default %g)\n"
    "  --max-iter N      iteration cap of the iterative methods, 1..65535 (default %d)\n"
    "  --isa I           %s (default auto; TTD_ISA may force one)\n"
    "  --threads N       worker threads, 0 = every core (default)\n"
    "\n"
    "A bad line (not 18 finite numbers) gets a message FILE:LINE on standard error and an output\n"
    "line of nan (seven with --points); reading goes on. Pairs an iterative method did not converge on are printed as\n"
    "computed (points on their triangles) with one warning at the end. Exit status: 0 all pairs\n"
    "computed, 1 some line bad, an I/O error or a library error, 2 bad options.\n";

/* The usage text, with the method and ISA names the library knows. */
static void ttd_dist_print_usage(FILE *f)
{
    char methods[256] = "", isas[256] = "";
    for (int m = 0; m < TTD_METHOD_COUNT; ++m)
        snprintf(methods + strlen(methods), sizeof methods - strlen(methods), "%s%s", m ? "|" : "",
                 ttd_method_name((ttd_method)m));
    for (int i = 0; i < TTD_ISA_COUNT; ++i)
        snprintf(isas + strlen(isas), sizeof isas - strlen(isas), "%s%s", i ? "|" : "",
                 ttd_isa_name((ttd_isa)i));
    const ttd_options o = ttd_default_options();
    fprintf(f, ttd_dist_usage, methods, o.rho, o.tol, o.max_iterations, isas);
}

typedef struct ttd_dist_args {
    ttd_options opt;
    int use_float;
    int points;
    const char *path;
} ttd_dist_args;

/* Options of `ttd dist`; --name value and --name=value both work. */
static int ttd_dist_parse_args(int argc, char **argv, ttd_dist_args *a)
{
    a->opt = ttd_default_options();
    a->use_float = 0;
    a->points = 0;
    a->path = NULL;
    int only_files = 0;
    for (int i = 1; i < argc; ++i) {
        const char *arg = argv[i];
        if (only_files || arg[0] != '-' || strcmp(arg, "-") == 0) {
            if (a->path != NULL) {
                ttd_cli_error("dist: more than one FILE given ('%s' and '%s')", a->path, arg);
                return -1;
            }
            a->path = arg;
            continue;
        }
        if (strcmp(arg, "--") == 0) {
            only_files = 1;
            continue;
        }
        if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
            ttd_dist_print_usage(stdout);
            return 1;
        }
        if (strcmp(arg, "--points") == 0) {
            a->points = 1;
            continue;
        }
        /* The rest take a value. */
        static const char *const valued[] = {"--method", "--precision", "--rho", "--tol",
                                             "--max-iter", "--isa", "--threads"};
        const char *name = NULL, *val = NULL;
        for (size_t k = 0; k < sizeof valued / sizeof valued[0]; ++k) {
            size_t l = strlen(valued[k]);
            if (strncmp(arg, valued[k], l) == 0 && (arg[l] == '\0' || arg[l] == '=')) {
                name = valued[k];
                if (arg[l] == '=')
                    val = arg + l + 1;
                else if (i + 1 < argc)
                    val = argv[++i];
                break;
            }
        }
        if (name == NULL) {
            ttd_cli_error("dist: unknown option '%s' (see ttd dist --help)", arg);
            return -1;
        }
        if (val == NULL) {
            ttd_cli_error("dist: %s needs a value", name);
            return -1;
        }
        long iv;
        int bad = 0;
        if (strcmp(name, "--method") == 0)
            bad = ttd_cli_parse_method(val, &a->opt.method);
        else if (strcmp(name, "--isa") == 0)
            bad = ttd_cli_parse_isa(val, &a->opt.isa);
        else if (strcmp(name, "--precision") == 0) {
            bad = strcmp(val, "double") != 0 && strcmp(val, "float") != 0;
            a->use_float = strcmp(val, "float") == 0;
        } else if (strcmp(name, "--rho") == 0)
            bad = ttd_cli_parse_real(val, &a->opt.rho) || !(a->opt.rho > 0 && a->opt.rho <= TTD_RHO_MAX);
        else if (strcmp(name, "--tol") == 0)
            bad = ttd_cli_parse_real(val, &a->opt.tol) || !(a->opt.tol >= 0 && a->opt.tol <= 1);
        else if (strcmp(name, "--max-iter") == 0) {
            bad = ttd_cli_parse_int(val, 1, 65535, &iv);
            a->opt.max_iterations = (int)iv;
        } else if (strcmp(name, "--threads") == 0) {
            bad = ttd_cli_parse_int(val, 0, 1 << 20, &iv);
            a->opt.threads = (int)iv;
        }
        if (bad) {
            ttd_cli_error("dist: bad value for %s: '%s' (see ttd dist --help)", name, val);
            return -1;
        }
    }
    return 0;
}

/* Prints one number, "nan" for NaN whatever its sign. */
static void ttd_put(FILE *out, double v, int use_float, char sep)
{
    if (isnan(v))
        fputs("nan", out);
    else
        fprintf(out, use_float ? "%.9g" : "%.17g", v);
    fputc(sep, out);
}

/* The buffers of one block, in both precisions (only one is used). */
typedef struct ttd_dist_block {
    double s[9 * TTD_DIST_BLOCK], t[9 * TTD_DIST_BLOCK], dist[TTD_DIST_BLOCK];
    float sf[9 * TTD_DIST_BLOCK], tf[9 * TTD_DIST_BLOCK], distf[TTD_DIST_BLOCK];
    ttd_result_d res[TTD_DIST_BLOCK];
    ttd_result_f resf[TTD_DIST_BLOCK];
} ttd_dist_block;

/* Computes and writes pairs [0, n) of the block. Returns the batch status, and sets
 * *not_converged when a pair was flagged so: from the per-pair flags, because a bad line's
 * TTD_ERR_NONFINITE_INPUT takes precedence over TTD_WARN_NOT_CONVERGED in the status. */
static ttd_status ttd_dist_flush(const ttd_dist_args *a, ttd_dist_block *b, size_t n, FILE *out,
                                 int *not_converged)
{
    ttd_status st;
    const int want_results = a->points || a->opt.method != TTD_METHOD_EXACT;
    if (a->use_float)
        st = ttd_batch_f(&a->opt, n, b->sf, b->tf, b->distf, want_results ? b->resf : NULL);
    else
        st = ttd_batch_d(&a->opt, n, b->s, b->t, b->dist, want_results ? b->res : NULL);
    if (st >= TTD_ERR_FIRST_FATAL)
        return st;
    for (size_t i = 0; i < n && want_results; ++i)
        *not_converged |= ((a->use_float ? b->resf[i].flags : b->res[i].flags) & TTD_PAIR_NOT_CONVERGED) != 0;
    for (size_t i = 0; i < n; ++i) {
        if (!a->points) {
            ttd_put(out, a->use_float ? (double)b->distf[i] : b->dist[i], a->use_float, '\n');
            continue;
        }
        double v[7];
        if (a->use_float) {
            const ttd_result_f *r = &b->resf[i];
            v[0] = (double)r->distance;
            for (int k = 0; k < 3; ++k) {
                v[1 + k] = (double)r->p[k];
                v[4 + k] = (double)r->q[k];
            }
        } else {
            const ttd_result_d *r = &b->res[i];
            v[0] = r->distance;
            for (int k = 0; k < 3; ++k) {
                v[1 + k] = r->p[k];
                v[4 + k] = r->q[k];
            }
        }
        for (int k = 0; k < 7; ++k)
            ttd_put(out, v[k], a->use_float, k == 6 ? '\n' : ' ');
    }
    return st;
}

static double ttd_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int ttd_cli_dist(int argc, char **argv)
{
    ttd_dist_args a;
    int rc = ttd_dist_parse_args(argc, argv, &a);
    if (rc != 0)
        return rc > 0 ? TTD_EXIT_OK : TTD_EXIT_USAGE;
    if (ttd_isa_selected(&a.opt) == TTD_ISA_AUTO) {
        const char *env = getenv("TTD_ISA");
        if (a.opt.isa == TTD_ISA_AUTO && env && env[0])
            ttd_cli_error("dist: TTD_ISA=%s is not available here", env);
        else
            ttd_cli_error("dist: --isa %s is not available here", ttd_isa_name(a.opt.isa));
        ttd_cli_print_isas(stderr);
        return TTD_EXIT_USAGE;
    }

    const int from_stdin = a.path == NULL || strcmp(a.path, "-") == 0;
    const char *name = from_stdin ? "<stdin>" : a.path;
    FILE *in = from_stdin ? stdin : fopen(a.path, "rb");
    if (in == NULL) {
        ttd_cli_error("%s: cannot open: %s", name, strerror(errno));
        return TTD_EXIT_INPUT;
    }
    ttd_line_reader *reader = malloc(sizeof *reader);
    ttd_dist_block *b = malloc(sizeof *b);
    if (reader == NULL || b == NULL) {
        ttd_cli_error("out of memory");
        free(reader);
        free(b);
        if (!from_stdin)
            fclose(in);
        return TTD_EXIT_INPUT;
    }
    ttd_reader_init(reader, in);
    static char outbuf[1 << 16];
    setvbuf(stdout, outbuf, _IOFBF, sizeof outbuf);

    const int progress = isatty(STDERR_FILENO);
    const double t0 = progress ? ttd_now() : 0.0;
    double last_report = t0;
    unsigned long long bad_lines = 0, pairs = 0;
    int not_converged = 0, failed = 0;
    size_t n = 0, len;
    int overlong, more = 1;
    while (more) {
        more = ttd_reader_next(reader, &len, &overlong);
        if (more) {
            double v[18];
            char err[256];
            ttd_line_kind kind;
            /* A comment may be as long as it likes; anything else overlong is an error. */
            const char *p = reader->line;
            while (*p == ' ' || *p == '\t')
                ++p;
            if (overlong && *p != '#') {
                kind = TTD_LINE_ERROR;
                snprintf(err, sizeof err, "line longer than %d bytes", TTD_CLI_MAX_LINE);
            } else {
                kind = ttd_parse_pair_line(reader->line, len, v, err, sizeof err);
            }
            if (kind == TTD_LINE_SKIP)
                continue;
            if (kind == TTD_LINE_PAIR && a.use_float) {
                for (int k = 0; k < 18; ++k)
                    if (fabs(v[k]) > (double)FLT_MAX) {
                        kind = TTD_LINE_ERROR;
                        snprintf(err, sizeof err, "field %d is out of float range: %g", k + 1, v[k]);
                        break;
                    }
            }
            if (kind == TTD_LINE_ERROR) {
                if (bad_lines < TTD_DIST_MAX_MESSAGES)
                    ttd_cli_error("%s:%llu: %s", name, reader->line_no, err);
                else if (bad_lines == TTD_DIST_MAX_MESSAGES)
                    ttd_cli_error("%s: more bad lines; only the first %d are shown", name,
                                  TTD_DIST_MAX_MESSAGES);
                ++bad_lines;
                /* A NaN pair: the engine flags it and its output line reads nan. */
                for (int k = 0; k < 18; ++k)
                    v[k] = (double)NAN;
            }
            for (int k = 0; k < 9; ++k) {
                if (a.use_float) {
                    b->sf[9 * n + k] = (float)v[k];
                    b->tf[9 * n + k] = (float)v[9 + k];
                } else {
                    b->s[9 * n + k] = v[k];
                    b->t[9 * n + k] = v[9 + k];
                }
            }
            ++n;
        }
        if (n == TTD_DIST_BLOCK || (!more && n > 0)) {
            ttd_status st = ttd_dist_flush(&a, b, n, stdout, &not_converged);
            pairs += n;
            n = 0;
            if (st >= TTD_ERR_FIRST_FATAL) {
                ttd_cli_error("%s: %s", name, ttd_status_string(st));
                failed = 1;
                break;
            }
            if (progress) {
                double now = ttd_now();
                if (now - last_report > 0.5) {
                    fprintf(stderr, "\rttd: %s: %llu pairs", name, pairs);
                    last_report = now;
                }
            }
        }
    }
    if (progress && last_report > t0)
        fputs("\r\033[K", stderr);
    if (reader->error) {
        ttd_cli_error("%s: read error: %s", name, strerror(reader->error));
        failed = 1;
    }
    if (fflush(stdout) != 0 || ferror(stdout)) {
        ttd_cli_error("error writing the output");
        failed = 1;
    }
    if (bad_lines > 0)
        ttd_cli_error("%s: %llu bad line%s (output nan)", name, bad_lines, bad_lines == 1 ? "" : "s");
    if (not_converged)
        ttd_cli_error("%s: warning: some pairs did not converge within --max-iter", name);
    free(reader);
    free(b);
    if (!from_stdin)
        fclose(in);
    return failed || bad_lines ? TTD_EXIT_INPUT : TTD_EXIT_OK;
}
