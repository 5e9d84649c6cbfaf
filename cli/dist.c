/* SPDX-License-Identifier: MIT */
/* `ttd dist [options] [FILE]`: distances of the triangle pairs in FILE (or standard input),
 * computed by the batch engine block by block so that memory stays constant however long the
 * input is. Input and output are text (one pair per line) or raw little-endian arrays of the
 * precision's type (--binary-in, --binary-out) for pipelines, where text parsing would cost
 * far more than the distance.
 *
 * Bad input: in text, every line that is not blank or only a comment yields exactly one
 * output line, so output line k always belongs to the k-th pair line of the input. A line that
 * cannot be read as 18 finite numbers (wrong count, junk or binary bytes, an overlong line,
 * NaN, inf, a number out of range, or out of float range with --precision float) gets a
 * message "ttd: FILE:LINE: ..." on standard error and the output line "nan" (seven with
 * --points); reading goes on, and the exit status is 1 at the end. In binary, a record with a
 * non-finite number is named by its index and byte offset and gives NaN; a truncated last
 * record is an error naming its byte offset. Only the first TTD_DIST_MAX_MESSAGES such messages
 * are printed, then a count. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
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
    "second, x y z each. A '#' starts a comment to the end of the line, after the 18 numbers or\n"
    "alone; blank and comment-only lines are skipped (they get no output line). A line may hold\n"
    "at most 4096 bytes before its newline; a UTF-8 byte-order mark at the start of the input is\n"
    "skipped. Writes one line per pair: the distance, or with --points the distance, p (3 numbers)\n"
    "and q (3 numbers).\n"
    "\n"
    "  --method M        %s (default exact).\n"
    "                    penalty-ref (the paper's MATLAB ttd1 step for step) and barrier (the\n"
    "                    paper's first attempt) are there for comparison, not for use: on the\n"
    "                    100,000 random pairs of `ttd bench --workloads random --pairs 100000`\n"
    "                    (size ~1) penalty-ref is off by more than 1e-9 on 2,765 (2.8%%; worst\n"
    "                    1.04, each flagged not_converged), barrier by up to 9.5e-7. Use exact,\n"
    "                    penalty or certified.\n"
    "  --precision P     double (default, printed with %%.17g) or float (each number rounded once,\n"
    "                    decimal to float; printed with %%.9g)\n"
    "  --points          also print the closest points p and q\n"
    "  --detail          print per pair 17 columns: distance, p (3), q (3), the weights of A B C\n"
    "                    that give p (3), the weights of D E F that give q (3), feature_p,\n"
    "                    feature_q, iterations, flags. A feature is the vertices with a non-zero\n"
    "                    weight: 'A' a vertex, 'AB' an edge, 'ABC' the face ('D'..'DEF' for q;\n"
    "                    '-' none). flags is '-' or a comma-separated list of: nonfinite (input\n"
    "                    NaN/inf, outputs NaN), degenerate_s, degenerate_t (zero-area triangle),\n"
    "                    intersecting (distance 0), not_converged (iterative method hit\n"
    "                    --max-iter), fallback (certified: computed by the exact method)\n"
    "  --binary-in       read raw little-endian numbers of the precision's type (float64, or\n"
    "                    float32 with --precision float), 18 per pair, no separators; a partial\n"
    "                    last record is an error naming its byte offset\n"
    "  --binary-out      write raw little-endian numbers of the precision's type: 1 per pair (the\n"
    "                    distance), 7 with --points (distance, p, q); not with --detail, nor to a\n"
    "                    terminal\n"
    "  --rho R           penalty weight of the iterative methods, (0, 1e150] (default %g)\n"
    "  --tol T           step tolerance of the iterative methods, [0, 1] (default %g)\n"
    "  --max-iter N      iteration cap of the iterative methods, 1..65535 (default %d)\n"
    "  --isa I           %s (default auto; TTD_ISA may force one)\n"
    "  --threads N       worker threads, 0 = every core (default)\n"
    "\n"
    "A bad line (not 18 finite numbers) gets a message FILE:LINE on standard error and an output\n"
    "line of nan (seven with --points; with --detail 13, then '- - 0 nonfinite'); a binary record with NaN or inf gets a message naming its\n"
    "index and byte offset and NaN output; reading goes on. Pairs an iterative method did not\n"
    "converge on are printed as computed (points on their triangles), with a warning at the end\n"
    "that counts them. Exit status: 0 all pairs computed, 1 some line or record bad, an I/O error\n"
    "or a library error, 2 bad options.\n";

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
    int detail;
    int binary_in, binary_out;
    const char *path;
} ttd_dist_args;

/* Options of `ttd dist`; --name value and --name=value both work. Returns 0, 1 after --help,
 * -1 on a bad option (message printed). */
static int ttd_dist_parse_args(int argc, char **argv, ttd_dist_args *a)
{
    memset(a, 0, sizeof *a);
    a->opt = ttd_default_options();
    static const char *const flags[] = {"--points", "--detail", "--binary-in", "--binary-out", NULL};
    static const char *const valued[] = {"--method", "--precision", "--rho", "--tol",
                                         "--max-iter", "--isa", "--threads", NULL};
    ttd_cli_args w = ttd_cli_args_start("dist", flags, valued, argc, argv);
    for (ttd_cli_arg k; (k = ttd_cli_next_arg(&w)) != TTD_ARG_END;) {
        const char *name = w.opt, *val = w.val;
        if (k == TTD_ARG_BAD)
            return -1;
        if (k == TTD_ARG_HELP) {
            ttd_dist_print_usage(stdout);
            return 1;
        }
        if (k == TTD_ARG_OPERAND) {
            if (a->path != NULL) {
                ttd_cli_error("dist: more than one FILE given ('%s' and '%s')", a->path, w.arg);
                return -1;
            }
            a->path = w.arg;
            continue;
        }
        if (k == TTD_ARG_FLAG) {
            *(strcmp(name, "--points") == 0      ? &a->points
              : strcmp(name, "--detail") == 0    ? &a->detail
              : strcmp(name, "--binary-in") == 0 ? &a->binary_in
                                                 : &a->binary_out) = 1;
            continue;
        }
        long iv;
        int bad = 0;
        if (strcmp(name, "--method") == 0)
            bad = ttd_cli_parse_method(val, &a->opt.method);
        else if (strcmp(name, "--rho") == 0)
            bad = ttd_cli_parse_real(val, &a->opt.rho) || !(a->opt.rho > 0 && a->opt.rho <= TTD_RHO_MAX);
        else if (strcmp(name, "--tol") == 0)
            bad = ttd_cli_parse_real(val, &a->opt.tol) || !(a->opt.tol >= 0 && a->opt.tol <= 1);
        else if (strcmp(name, "--max-iter") == 0) {
            bad = ttd_cli_parse_int(val, 1, 65535, &iv);
            a->opt.max_iterations = (int)iv;
        } else {
            bad = ttd_cli_run_option(name, val, &a->opt, &a->use_float) < 0;
        }
        if (bad && strcmp(name, "--isa") == 0) {
            ttd_cli_error("dist: --isa %s: unknown instruction set (auto, scalar, sse2, avx2, avx512, neon, portable; "
                          "any letter case)", val);
            return -1;
        }
        if (bad) {
            ttd_cli_bad_value(&w, NULL);
            return -1;
        }
    }
    if (a->binary_out && a->detail) {
        ttd_cli_error("dist: --detail is text only; it does not go with --binary-out");
        return -1;
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

/* A feature as the letters of its vertices ("A", "AB", "ABC"; "D".. for q), "-" for none. */
static void ttd_put_feature(FILE *out, unsigned bits, char first)
{
    if ((bits & 7u) == 0)
        fputc('-', out);
    for (int k = 0; k < 3; ++k)
        if (bits & (1u << k))
            fputc(first + k, out);
    fputc(' ', out);
}

/* The flags as a comma-separated list of names, "-" for none. */
static void ttd_put_flags(FILE *out, uint32_t flags)
{
    static const struct {
        uint32_t bit;
        const char *name;
    } names[] = {{TTD_PAIR_NONFINITE, "nonfinite"},         {TTD_PAIR_DEGENERATE_S, "degenerate_s"},
                 {TTD_PAIR_DEGENERATE_T, "degenerate_t"},   {TTD_PAIR_INTERSECTING, "intersecting"},
                 {TTD_PAIR_NOT_CONVERGED, "not_converged"}, {TTD_PAIR_FALLBACK, "fallback"}};
    int any = 0;
    for (size_t k = 0; k < sizeof names / sizeof names[0]; ++k) {
        if (flags & names[k].bit) {
            fprintf(out, "%s%s", any ? "," : "", names[k].name);
            any = 1;
        }
    }
    fputs(any ? "\n" : "-\n", out);
}

/* The buffers of one block, in both precisions (only one is used), and the raw bytes of a
 * binary block (input, then reused for the output). */
typedef struct ttd_dist_block {
    double s[9 * TTD_DIST_BLOCK], t[9 * TTD_DIST_BLOCK], dist[TTD_DIST_BLOCK];
    float sf[9 * TTD_DIST_BLOCK], tf[9 * TTD_DIST_BLOCK], distf[TTD_DIST_BLOCK];
    ttd_result_d res[TTD_DIST_BLOCK];
    ttd_result_f resf[TTD_DIST_BLOCK];
    unsigned char raw[18 * sizeof(double) * TTD_DIST_BLOCK];
} ttd_dist_block;

/* Raw numbers are little-endian in the stream whatever the host; swap on a big-endian one. */
static void ttd_le_bytes(unsigned char *b, size_t size)
{
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
    for (size_t k = 0; k < size / 2; ++k) {
        unsigned char c = b[k];
        b[k] = b[size - 1 - k];
        b[size - 1 - k] = c;
    }
#else
    (void)b;
    (void)size;
#endif
}

/* One pair's outputs widened to double: distance, p, q, weights of p, weights of q. */
static void ttd_dist_values(const ttd_dist_args *a, const ttd_dist_block *b, size_t i, double v[13])
{
    if (a->use_float) {
        const ttd_result_f *r = &b->resf[i];
        v[0] = (double)r->distance;
        for (int k = 0; k < 3; ++k) {
            v[1 + k] = (double)r->p[k];
            v[4 + k] = (double)r->q[k];
            v[7 + k] = (double)r->bary_p[k];
            v[10 + k] = (double)r->bary_q[k];
        }
    } else {
        const ttd_result_d *r = &b->res[i];
        v[0] = r->distance;
        for (int k = 0; k < 3; ++k) {
            v[1 + k] = r->p[k];
            v[4 + k] = r->q[k];
            v[7 + k] = r->bary_p[k];
            v[10 + k] = r->bary_q[k];
        }
    }
}

/* Writes pairs [0, n) of the block in binary: 1 or 7 numbers of the precision's type each. */
static void ttd_dist_write_binary(const ttd_dist_args *a, ttd_dist_block *b, size_t n, FILE *out)
{
    const size_t size = a->use_float ? sizeof(float) : sizeof(double);
    const int per = a->points ? 7 : 1;
    unsigned char *o = b->raw;
    for (size_t i = 0; i < n; ++i) {
        double v[13];
        if (a->points)
            ttd_dist_values(a, b, i, v);
        else
            v[0] = a->use_float ? (double)b->distf[i] : b->dist[i];
        for (int k = 0; k < per; ++k, o += size) {
            if (a->use_float) {
                float f = (float)v[k];
                memcpy(o, &f, size);
            } else {
                memcpy(o, &v[k], size);
            }
            ttd_le_bytes(o, size);
        }
    }
    fwrite(b->raw, size, (size_t)per * n, out);
}

/* Writes pairs [0, n) of the block as text. */
static void ttd_dist_write_text(const ttd_dist_args *a, const ttd_dist_block *b, size_t n, FILE *out)
{
    for (size_t i = 0; i < n; ++i) {
        if (!a->points && !a->detail) {
            ttd_put(out, a->use_float ? (double)b->distf[i] : b->dist[i], a->use_float, '\n');
            continue;
        }
        double v[13];
        ttd_dist_values(a, b, i, v);
        if (!a->detail) {
            for (int k = 0; k < 7; ++k)
                ttd_put(out, v[k], a->use_float, k == 6 ? '\n' : ' ');
            continue;
        }
        for (int k = 0; k < 13; ++k)
            ttd_put(out, v[k], a->use_float, ' ');
        const unsigned fp = a->use_float ? b->resf[i].feature_p : b->res[i].feature_p;
        const unsigned fq = a->use_float ? b->resf[i].feature_q : b->res[i].feature_q;
        const unsigned it = a->use_float ? b->resf[i].iterations : b->res[i].iterations;
        ttd_put_feature(out, fp, 'A');
        ttd_put_feature(out, fq, 'D');
        fprintf(out, "%u ", it);
        ttd_put_flags(out, a->use_float ? b->resf[i].flags : b->res[i].flags);
    }
}

/* Computes and writes pairs [0, n) of the block. Returns the batch status, and adds to
 * *not_converged the pairs flagged so: from the per-pair flags, because a bad line's
 * TTD_ERR_NONFINITE_INPUT takes precedence over TTD_WARN_NOT_CONVERGED in the status. */
static ttd_status ttd_dist_flush(const ttd_dist_args *a, ttd_dist_block *b, size_t n, FILE *out,
                                 unsigned long long *not_converged)
{
    ttd_status st;
    const int want_results = a->points || a->detail || a->opt.method != TTD_METHOD_EXACT;
    if (a->use_float)
        st = ttd_batch_f(&a->opt, n, b->sf, b->tf, b->distf, want_results ? b->resf : NULL);
    else
        st = ttd_batch_d(&a->opt, n, b->s, b->t, b->dist, want_results ? b->res : NULL);
    if (st >= TTD_ERR_FIRST_FATAL)
        return st;
    for (size_t i = 0; i < n && want_results; ++i)
        *not_converged += ((a->use_float ? b->resf[i].flags : b->res[i].flags) & TTD_PAIR_NOT_CONVERGED) != 0;
    if (a->binary_out)
        ttd_dist_write_binary(a, b, n, out);
    else
        ttd_dist_write_text(a, b, n, out);
    return st;
}

static double ttd_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* What a run of `ttd dist` keeps between blocks. */
typedef struct ttd_dist_run {
    const ttd_dist_args *a;
    const char *name;
    FILE *in, *out;
    ttd_dist_block *b;
    int progress;
    double t0, last_report;
    unsigned long long bad, pairs, not_converged;
    int failed;
} ttd_dist_run;

/* A bad line or record: its message (the first TTD_DIST_MAX_MESSAGES), counted. */
static void ttd_dist_bad(ttd_dist_run *r, const char *where, const char *what)
{
    if (r->bad < TTD_DIST_MAX_MESSAGES)
        ttd_cli_error("%s:%s %s", r->name, where, what);
    else if (r->bad == TTD_DIST_MAX_MESSAGES)
        ttd_cli_error("%s: more bad %s; only the first %d are shown", r->name,
                      r->a->binary_in ? "records" : "lines", TTD_DIST_MAX_MESSAGES);
    ++r->bad;
}

/* Stores pair slot i of the block from 18 numbers (NaN for a bad one: the engine flags it). */
static void ttd_dist_store(const ttd_dist_args *a, ttd_dist_block *b, size_t i, const double v[18])
{
    for (int k = 0; k < 9; ++k) {
        if (a->use_float) {
            b->sf[9 * i + k] = (float)v[k];
            b->tf[9 * i + k] = (float)v[9 + k];
        } else {
            b->s[9 * i + k] = v[k];
            b->t[9 * i + k] = v[9 + k];
        }
    }
}

/* Computes and writes a full or final block; 0, or -1 on a library error (reported). */
static int ttd_dist_block_done(ttd_dist_run *r, size_t n)
{
    ttd_status st = ttd_dist_flush(r->a, r->b, n, r->out, &r->not_converged);
    r->pairs += n;
    if (st >= TTD_ERR_FIRST_FATAL) {
        ttd_cli_error("%s: %s", r->name, ttd_status_string(st));
        r->failed = 1;
        return -1;
    }
    if (r->progress) {
        double now = ttd_now();
        if (now - r->last_report > 0.5) {
            fprintf(stderr, "\rttd: %s: %llu pairs", r->name, r->pairs);
            r->last_report = now;
        }
    }
    return 0;
}

/* Text input: one pair per line. */
static void ttd_dist_text(ttd_dist_run *r, ttd_line_reader *reader)
{
    const ttd_dist_args *a = r->a;
    size_t n = 0, len;
    int overlong, more = 1;
    ttd_reader_init(reader, r->in);
    while (more) {
        more = ttd_reader_next(reader, &len, &overlong);
        if (more) {
            double v[18];
            char err[256], where[32];
            ttd_line_kind kind;
            /* A comment may be as long as it likes; anything else overlong is an error. */
            const char *p = reader->line;
            while (*p == ' ' || *p == '\t')
                ++p;
            if (overlong && *p != '#') {
                kind = TTD_LINE_ERROR;
                snprintf(err, sizeof err, "line longer than %d bytes", TTD_CLI_MAX_LINE);
            } else {
                kind = ttd_parse_pair_line(reader->line, len, a->use_float, v, err, sizeof err);
            }
            if (kind == TTD_LINE_SKIP)
                continue;
            if (kind == TTD_LINE_ERROR) {
                snprintf(where, sizeof where, "%llu:", reader->line_no);
                ttd_dist_bad(r, where, err);
                for (int k = 0; k < 18; ++k)
                    v[k] = (double)NAN;
            }
            ttd_dist_store(a, r->b, n++, v);
        }
        if ((n == TTD_DIST_BLOCK || (!more && n > 0)) && ttd_dist_block_done(r, n) != 0)
            return;
        if (n == TTD_DIST_BLOCK)
            n = 0;
    }
    if (reader->error) {
        ttd_cli_error("%s: read error: %s", r->name, strerror(reader->error));
        r->failed = 1;
    }
}

/* Reads up to size bytes, retrying short reads (pipes); returns the bytes read. */
static size_t ttd_read_full(FILE *in, unsigned char *buf, size_t size, int *error)
{
    size_t got = 0;
    while (got < size) {
        errno = 0;
        size_t k = fread(buf + got, 1, size - got, in);
        got += k;
        if (k == 0) {
            if (ferror(in))
                *error = errno != 0 ? errno : EIO;
            break;
        }
    }
    return got;
}

/* Binary input: records of 18 little-endian numbers of the precision's type. */
static void ttd_dist_binary(ttd_dist_run *r)
{
    const ttd_dist_args *a = r->a;
    const size_t size = a->use_float ? sizeof(float) : sizeof(double), record = 18 * size;
    unsigned long long offset = 0, index = 0;
    int error = 0;
    for (;;) {
        size_t got = ttd_read_full(r->in, r->b->raw, record * TTD_DIST_BLOCK, &error);
        size_t n = got / record;
        for (size_t i = 0; i < n; ++i, ++index) {
            double v[18];
            int finite = 1;
            for (int k = 0; k < 18; ++k) {
                unsigned char *p = r->b->raw + i * record + (size_t)k * size;
                ttd_le_bytes(p, size);
                if (a->use_float) {
                    float f;
                    memcpy(&f, p, size);
                    v[k] = (double)f;
                } else {
                    memcpy(&v[k], p, size);
                }
                finite &= isfinite(v[k]) != 0;
            }
            if (!finite) {
                char where[80];
                snprintf(where, sizeof where, " record %llu (byte offset %llu):", index + 1,
                         offset + (unsigned long long)(i * record));
                ttd_dist_bad(r, where, "a number is NaN or infinite");
            }
            ttd_dist_store(a, r->b, i, v);
        }
        offset += (unsigned long long)(n * record);
        if (n > 0 && ttd_dist_block_done(r, n) != 0)
            return;
        if (got % record != 0) {
            ttd_cli_error("%s: truncated record at byte offset %llu: %zu bytes, a record is %zu (18 %s)", r->name,
                          offset, got % record, record, a->use_float ? "float32" : "float64");
            r->failed = 1;
        }
        if (got < record * TTD_DIST_BLOCK)
            break;
    }
    if (error) {
        ttd_cli_error("%s: read error: %s", r->name, strerror(error));
        r->failed = 1;
    }
}

/* What is checked before any input is opened: the instruction set, and binary output not
 * going to a terminal. Returns 0 or the exit status. */
static int ttd_dist_check(const ttd_dist_args *a, FILE *out)
{
    if (ttd_isa_selected(&a->opt) == TTD_ISA_AUTO) {
        ttd_cli_error("dist: --isa %s is not available here; this machine has:", ttd_isa_name(a->opt.isa));
        ttd_cli_print_isas(stderr);
        return TTD_EXIT_USAGE;
    }
    ttd_cli_warn_isa_env("dist");
    if (a->binary_out && isatty(fileno(out))) {
        ttd_cli_error("dist: --binary-out: standard output is a terminal; redirect it to a file or a pipe");
        return TTD_EXIT_USAGE;
    }
    return 0;
}

/* Runs `ttd dist` with checked options from in (named name in messages) to out. */
static int ttd_dist_streams(const ttd_dist_args *a, FILE *in, const char *name, FILE *out, int progress)
{
    ttd_dist_run r = {.a = a, .name = name, .in = in, .out = out, .progress = progress};
    ttd_line_reader *reader = a->binary_in ? NULL : malloc(sizeof *reader);
    r.b = malloc(sizeof *r.b);
    if ((reader == NULL && !a->binary_in) || r.b == NULL) {
        ttd_cli_error("out of memory");
        free(reader);
        free(r.b);
        return TTD_EXIT_INPUT;
    }
    r.t0 = r.last_report = progress ? ttd_now() : 0.0;
    if (a->binary_in)
        ttd_dist_binary(&r);
    else
        ttd_dist_text(&r, reader);
    if (progress && r.last_report > r.t0)
        fputs("\r\033[K", stderr);
    if (fflush(out) != 0 || ferror(out)) {
        ttd_cli_error("error writing the output");
        r.failed = 1;
    }
    if (r.bad > 0)
        ttd_cli_error("%s: %llu bad %s%s (output nan)", name, r.bad, a->binary_in ? "record" : "line",
                      r.bad == 1 ? "" : "s");
    if (r.not_converged > 0)
        ttd_cli_error("%s: warning: %llu of %llu pairs did not converge (within --max-iter %d, or the barrier "
                      "method stalled): printed as computed, flagged not_converged by --detail",
                      name, r.not_converged, r.pairs, a->opt.max_iterations);
    free(reader);
    free(r.b);
    return r.failed || r.bad ? TTD_EXIT_INPUT : TTD_EXIT_OK;
}

int ttd_cli_dist_run(int argc, char **argv, FILE *in, FILE *out)
{
    ttd_dist_args a;
    int rc = ttd_dist_parse_args(argc, argv, &a);
    if (rc != 0)
        return rc > 0 ? TTD_EXIT_OK : TTD_EXIT_USAGE;
    if ((rc = ttd_dist_check(&a, out)) != 0)
        return rc;
    return ttd_dist_streams(&a, in, "<memory>", out, 0);
}

int ttd_cli_dist(int argc, char **argv)
{
    ttd_dist_args a;
    int rc = ttd_dist_parse_args(argc, argv, &a);
    if (rc != 0)
        return rc > 0 ? TTD_EXIT_OK : TTD_EXIT_USAGE;
    if ((rc = ttd_dist_check(&a, stdout)) != 0)
        return rc;

    const int from_stdin = a.path == NULL || strcmp(a.path, "-") == 0;
    const char *name = from_stdin ? "<stdin>" : a.path;
    FILE *in = from_stdin ? stdin : fopen(a.path, "rb");
    if (in == NULL) {
        ttd_cli_error("%s: cannot open: %s", name, strerror(errno));
        return TTD_EXIT_INPUT;
    }
    static char outbuf[1 << 16];
    setvbuf(stdout, outbuf, _IOFBF, sizeof outbuf);
    rc = ttd_dist_streams(&a, in, name, stdout, isatty(STDERR_FILENO));
    if (!from_stdin)
        fclose(in);
    return rc;
}
