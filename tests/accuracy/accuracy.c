/* SPDX-License-Identifier: MIT */
/* ttd_accuracy: every method, precision and instruction set against the independent quad
 * reference (tests/reference/ref_distance.h) on every generator family (gen/pairs.h).
 *
 * Each configuration (method, precision, ISA) runs through the public batch API with
 * options.isa forced, so what is measured is what a user gets. Per family it reports:
 *   err     |d - d_ref| / max(d_ref, size): worst and 99.9th percentile
 *   off     how far p and q lie off their triangles (quad point-triangle distance), / max(d_ref, size)
 *   pq      | |p - q| - d | / max(d_ref, size)
 *   nonfin  pairs with a non-finite output (distance, p, q or weights) for finite input
 *   nconv   pairs flagged TTD_PAIR_NOT_CONVERGED
 * size is the longest edge of the pair. Float runs round the input to float first and are
 * compared with the reference distance of the float-rounded input, which is the float target.
 *
 * With --check the targets are asserted and the exit status says whether they hold:
 *   exact     double err <= 1e-12, float err <= 1e-5, on every family and ISA;
 *   certified the same (it falls back to the exact method where it cannot certify);
 *   penalty   double err <= 1e-10, float err <= 2e-4 on `random` (docs/penalty-method.md);
 *   barrier   double err <= 1e-8 on `random` pairs with d >= 0.05 (docs/penalty-method.md);
 *   every method on every family and ISA: no non-finite output; p, q on their triangles and
 *   |p - q| = d within the method's distance tolerance (16 eps where it has none: every method
 *   clamps or projects its points), plus 8 eps |coordinate|, the rounding of forming p and q
 *   at the coordinates' magnitude (which dominates off and pq on `offset` and `far`). The paper's reference
 *   form (penalty-ref) has no accuracy target: it is reported, not judged.
 * The reference's own certificate gap is added to every tolerance (zero in quad).
 *
 * Usage: ttd_accuracy [--pairs N] [--seed S] [--json] [--check] [--threads K]
 *                     [--family NAME]... [--method NAME]... [--isa NAME]... [--precision double|float]
 */
#include <errno.h>
#include <float.h>
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pairs.h"
#include "ref_distance.h"
#include "ttd/ttd.h"

/* ---- one family's input and reference, shared by every configuration --------------------- */

typedef struct family_data {
    ttd_gen_family family;
    size_t n;
    double *s, *t;        /* the generated pairs (9n each) */
    float *sf, *tf;       /* rounded to float */
    double *sw, *tw;      /* the float input widened back to double, for the reference */
    double *ref[2];       /* reference distance: [0] double input, [1] float input */
    double *scale[2];     /* max(d_ref, size) */
    double *gap[2];       /* certificate gap d_ref - lower_bound, >= 0 */
    double *mag[2];       /* largest |coordinate| of the pair */
} family_data;

static void *xcalloc(size_t count, size_t size)
{
    void *p = calloc(count ? count : 1, size);
    if (!p) {
        fprintf(stderr, "ttd_accuracy: out of memory\n");
        exit(2);
    }
    return p;
}

static double max_abs18(const double *s, const double *t)
{
    double m = 0;
    for (int k = 0; k < 9; ++k)
        m = fmax(m, fmax(fabs(s[k]), fabs(t[k])));
    return m;
}

static void family_init(family_data *fd, ttd_gen_family f, uint64_t seed, size_t n)
{
    memset(fd, 0, sizeof *fd);
    fd->family = f;
    fd->n = n;
    fd->s = xcalloc(9 * n, sizeof(double));
    fd->t = xcalloc(9 * n, sizeof(double));
    fd->sf = xcalloc(9 * n, sizeof(float));
    fd->tf = xcalloc(9 * n, sizeof(float));
    fd->sw = xcalloc(9 * n, sizeof(double));
    fd->tw = xcalloc(9 * n, sizeof(double));
    ttd_gen(f, seed, n, fd->s, fd->t);
    for (size_t k = 0; k < 9 * n; ++k) {
        fd->sf[k] = (float)fd->s[k];
        fd->tf[k] = (float)fd->t[k];
        fd->sw[k] = (double)fd->sf[k];
        fd->tw[k] = (double)fd->tf[k];
    }
    for (int pr = 0; pr < 2; ++pr) {
        fd->ref[pr] = xcalloc(n, sizeof(double));
        fd->scale[pr] = xcalloc(n, sizeof(double));
        fd->gap[pr] = xcalloc(n, sizeof(double));
        fd->mag[pr] = xcalloc(n, sizeof(double));
        const double *s = pr ? fd->sw : fd->s, *t = pr ? fd->tw : fd->t;
        for (size_t i = 0; i < n; ++i) {
            ttd_ref_result r;
            ttd_ref_distance(s + 9 * i, t + 9 * i, &r);
            fd->ref[pr][i] = r.distance;
            fd->scale[pr][i] = fmax(r.distance, ttd_ref_size(s + 9 * i, t + 9 * i));
            fd->gap[pr][i] = fmax(0.0, r.distance - r.lower_bound);
            fd->mag[pr][i] = max_abs18(s + 9 * i, t + 9 * i);
        }
    }
}

static void family_free(family_data *fd)
{
    free(fd->s), free(fd->t), free(fd->sf), free(fd->tf), free(fd->sw), free(fd->tw);
    for (int pr = 0; pr < 2; ++pr)
        free(fd->ref[pr]), free(fd->scale[pr]), free(fd->gap[pr]), free(fd->mag[pr]);
}

/* ---- targets ------------------------------------------------------------------------------ */

/// The distance tolerance a configuration is held to on a family; 0 = not judged (reported only).
static double distance_target(ttd_method m, int is_float, ttd_gen_family f)
{
    switch (m) {
    case TTD_METHOD_EXACT:
    case TTD_METHOD_CERTIFIED: return is_float ? 1e-5 : 1e-12; /* certified promises exact's targets */
    case TTD_METHOD_PENALTY:
        return f == TTD_GEN_RANDOM ? (is_float ? 2e-4 : 1e-10) : 0;
    case TTD_METHOD_BARRIER:
        return f == TTD_GEN_RANDOM && !is_float ? 1e-8 : 0;
    default: return 0;
    }
}

/// Pairs the barrier's documented bound covers: separated by at least 0.05 (random family, size ~1).
static int target_applies(ttd_method m, double d_ref)
{
    return m != TTD_METHOD_BARRIER || d_ref >= 0.05;
}

/* ---- one configuration on one family ------------------------------------------------------ */

typedef struct row {
    const char *family;
    size_t n;
    double max_err, p999, max_off, max_pq;
    size_t worst; /* pair index of max_err */
    size_t nonfinite, not_converged, failures;
    double target;
    ttd_status status;
} row;

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

typedef struct config {
    ttd_method method;
    int is_float;
    ttd_isa isa;
} config;

static int verbose_failures = 5;

static void print_pair(FILE *out, const double *s, const double *t)
{
    fprintf(out, "    S =");
    for (int k = 0; k < 9; ++k)
        fprintf(out, " %.17g", s[k]);
    fprintf(out, "\n    T =");
    for (int k = 0; k < 9; ++k)
        fprintf(out, " %.17g", t[k]);
    fputc('\n', out);
}

/// Runs one configuration on one family and measures it. Returns the row.
static row run_one(const family_data *fd, config c, int threads, int check, double *errs, ttd_result_d *rd,
                   ttd_result_f *rf)
{
    row w;
    memset(&w, 0, sizeof w);
    w.family = ttd_gen_name(fd->family);
    w.n = fd->n;
    w.target = distance_target(c.method, c.is_float, fd->family);
    ttd_options o = ttd_default_options();
    o.method = c.method;
    o.isa = c.isa;
    o.threads = threads;
    const int pr = c.is_float;
    w.status = pr ? ttd_batch_f(&o, fd->n, fd->sf, fd->tf, NULL, rf) : ttd_batch_d(&o, fd->n, fd->s, fd->t, NULL, rd);
    if (w.status >= TTD_ERR_FIRST_FATAL) { /* nothing computed: no numbers to show */
        w.failures = fd->n;
        w.max_err = w.p999 = w.max_off = w.max_pq = (double)NAN;
        return w;
    }
    const double eps = pr ? (double)FLT_EPSILON / 2 : DBL_EPSILON / 2;
    const double *s = pr ? fd->sw : fd->s, *t = pr ? fd->tw : fd->t;
    for (size_t i = 0; i < fd->n; ++i) {
        double d, p[3], q[3], bp[3], bq[3];
        uint32_t flags;
        if (pr) {
            d = (double)rf[i].distance;
            for (int k = 0; k < 3; ++k) {
                p[k] = (double)rf[i].p[k], q[k] = (double)rf[i].q[k];
                bp[k] = (double)rf[i].bary_p[k], bq[k] = (double)rf[i].bary_q[k];
            }
            flags = rf[i].flags;
        } else {
            d = rd[i].distance;
            for (int k = 0; k < 3; ++k)
                p[k] = rd[i].p[k], q[k] = rd[i].q[k], bp[k] = rd[i].bary_p[k], bq[k] = rd[i].bary_q[k];
            flags = rd[i].flags;
        }
        if (flags & TTD_PAIR_NOT_CONVERGED)
            w.not_converged++;
        int finite = isfinite(d);
        for (int k = 0; k < 3; ++k)
            finite = finite && isfinite(p[k]) && isfinite(q[k]) && isfinite(bp[k]) && isfinite(bq[k]);
        double scale = fd->scale[pr][i], ref = fd->ref[pr][i];
        double err, off, pq;
        if (!finite) {
            w.nonfinite++;
            err = off = pq = (double)INFINITY;
        } else if (scale == 0) { /* both triangles one and the same point */
            err = d == 0 ? 0 : (double)INFINITY;
            off = pq = err;
        } else {
            err = fabs(d - ref) / scale;
            off = fmax(ttd_ref_point_triangle(p, s + 9 * i), ttd_ref_point_triangle(q, t + 9 * i)) / scale;
            double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
            pq = fabs(sqrt(dx * dx + dy * dy + dz * dz) - d) / scale;
        }
        errs[i] = err;
        if (!(err <= w.max_err)) /* NaN-safe: a NaN error becomes the worst */
            w.max_err = err, w.worst = i;
        w.max_off = fmax(w.max_off, off);
        w.max_pq = fmax(w.max_pq, pq);
        if (!check)
            continue;
        /* The tolerances: the target (or, when not judged, only the points' consistency) plus
         * the reference's certificate gap and the rounding of p and q at the coordinates'
         * magnitude. */
        double gap = scale > 0 ? fd->gap[pr][i] / scale : 0;
        double tol = w.target + gap;
        /* Forming p and q in the working precision moves them by a few eps * |coordinate|
         * (up to 1e-9 of size at offset 1e6 in double, 0.5 in float): allowed on top. */
        double rounding = 8 * eps * fd->mag[pr][i] / (scale > 0 ? scale : 1);
        double point_tol = (w.target > 0 ? w.target : 16 * eps) + gap + 8 * eps + rounding;
        int bad = !finite || !(off <= point_tol) || !(pq <= point_tol);
        if (w.target > 0 && target_applies(c.method, ref))
            bad = bad || !(err <= tol);
        if (bad) {
            if (w.failures < (size_t)verbose_failures) {
                fprintf(stderr, "FAIL %s %s %s %s pair %zu: d %.17g ref %.17g err %.3g (target %.3g) off %.3g "
                                "pq %.3g flags 0x%x\n",
                        ttd_method_name(c.method), pr ? "float" : "double", ttd_isa_name(c.isa), w.family, i, d,
                        ref, err, w.target, off, pq, (unsigned)flags);
                print_pair(stderr, fd->s + 9 * i, fd->t + 9 * i);
            }
            w.failures++;
        }
    }
    /* 99.9th percentile (nearest rank) */
    qsort(errs, fd->n, sizeof *errs, cmp_double);
    size_t rank = (size_t)ceil(0.999 * (double)fd->n);
    w.p999 = fd->n ? errs[rank ? rank - 1 : 0] : 0;
    return w;
}

/* ---- output ------------------------------------------------------------------------------- */

static void print_json_number(FILE *out, double v)
{
    if (isfinite(v))
        fprintf(out, "%.3e", v);
    else
        fprintf(out, "null"); /* JSON has no inf/NaN */
}

static void print_row_json(FILE *out, config c, const row *w, int first)
{
    fprintf(out, "%s\n    {\"method\": \"%s\", \"precision\": \"%s\", \"isa\": \"%s\", \"family\": \"%s\", \"pairs\": %zu, ",
            first ? "" : ",", ttd_method_name(c.method), c.is_float ? "float" : "double", ttd_isa_name(c.isa),
            w->family, w->n);
    fprintf(out, "\"max_rel_err\": ");
    print_json_number(out, w->max_err);
    fprintf(out, ", \"p999_rel_err\": ");
    print_json_number(out, w->p999);
    fprintf(out, ", \"max_off_triangle\": ");
    print_json_number(out, w->max_off);
    fprintf(out, ", \"max_pq_minus_d\": ");
    print_json_number(out, w->max_pq);
    fprintf(out, ", \"nonfinite\": %zu, \"not_converged\": %zu, \"status\": \"%s\", \"target\": ", w->nonfinite,
            w->not_converged, ttd_status_string(w->status));
    if (w->target > 0)
        print_json_number(out, w->target);
    else
        fprintf(out, "null");
    fprintf(out, ", \"failures\": %zu}", w->failures);
}

static void print_header(config c, int check)
{
    printf("\n%s, %s, %s%s\n", ttd_method_name(c.method), c.is_float ? "float" : "double", ttd_isa_name(c.isa),
           check ? " (failures: pairs outside the target)" : "");
    printf("| family | pairs | max err | p99.9 err | max off-triangle | max ||p-q|-d| | non-finite | not conv. | target |%s\n",
           check ? " failures |" : "");
    printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|%s\n", check ? "---:|" : "");
}

static void print_row_text(const row *w, int check)
{
    char target[32] = "-";
    if (w->target > 0)
        snprintf(target, sizeof target, "%.0e", w->target);
    printf("| %s | %zu | %.2e | %.2e | %.2e | %.2e | %zu | %zu | %s |", w->family, w->n, w->max_err, w->p999,
           w->max_off, w->max_pq, w->nonfinite, w->not_converged, target);
    if (check)
        printf(" %zu |", w->failures);
    if (w->status >= TTD_ERR_FIRST_FATAL)
        printf(" status: %s", ttd_status_string(w->status));
    putchar('\n');
}

/* ---- command line ------------------------------------------------------------------------- */

static void usage(FILE *out)
{
    fprintf(out,
            "usage: ttd_accuracy [--pairs N] [--seed S] [--json] [--check] [--threads K]\n"
            "                    [--family NAME]... [--method NAME]... [--isa NAME]... [--precision double|float]\n"
            "Compares every method, precision and available instruction set with the quad reference\n"
            "on every generator family (default 2000 pairs per family, seed 1). --check asserts the\n"
            "targets (exit status 1 when one is missed). Families:");
    for (int f = 0; f < TTD_GEN_COUNT; ++f)
        fprintf(out, " %s", ttd_gen_name((ttd_gen_family)f));
    fprintf(out, "\n");
}

static int parse_size(const char *arg, size_t *out)
{
    char *end;
    errno = 0;
    unsigned long long v = strtoull(arg, &end, 0);
    if (errno || end == arg || *end || arg[0] == '-' || v > (1ull << 32))
        return 0;
    *out = (size_t)v;
    return 1;
}

int main(int argc, char **argv)
{
    size_t pairs = 2000, seed = 1, threads = 1;
    int json = 0, check = 0;
    unsigned fam_mask = 0, method_mask = 0, isa_mask = 0, prec_mask = 0;
    for (int a = 1; a < argc; ++a) {
        const char *arg = argv[a];
        const char *val = a + 1 < argc ? argv[a + 1] : NULL;
        if (!strcmp(arg, "--json")) {
            json = 1;
        } else if (!strcmp(arg, "--check")) {
            check = 1;
        } else if (!strcmp(arg, "--help") || !strcmp(arg, "-h")) {
            usage(stdout);
            return 0;
        } else if (val && !strcmp(arg, "--pairs")) {
            if (!parse_size(val, &pairs) || pairs == 0)
                goto bad;
            ++a;
        } else if (val && !strcmp(arg, "--seed")) {
            if (!parse_size(val, &seed))
                goto bad;
            ++a;
        } else if (val && !strcmp(arg, "--threads")) {
            if (!parse_size(val, &threads) || threads > 1024)
                goto bad;
            ++a;
        } else if (val && !strcmp(arg, "--family")) {
            int f = ttd_gen_family_from_name(val);
            if (f < 0)
                goto bad;
            fam_mask |= 1u << f;
            ++a;
        } else if (val && !strcmp(arg, "--method")) {
            int m = 0;
            while (m < TTD_METHOD_COUNT && strcmp(ttd_method_name((ttd_method)m), val))
                ++m;
            if (m == TTD_METHOD_COUNT)
                goto bad;
            method_mask |= 1u << m;
            ++a;
        } else if (val && !strcmp(arg, "--isa")) {
            int i = TTD_ISA_SCALAR;
            while (i < TTD_ISA_COUNT && strcmp(ttd_isa_name((ttd_isa)i), val))
                ++i;
            if (i == TTD_ISA_COUNT)
                goto bad;
            if (!ttd_isa_available((ttd_isa)i)) {
                fprintf(stderr, "ttd_accuracy: --isa %s: not built in or not supported by this CPU\n", val);
                return 2;
            }
            isa_mask |= 1u << i;
            ++a;
        } else if (val && !strcmp(arg, "--precision")) {
            if (!strcmp(val, "double"))
                prec_mask |= 1;
            else if (!strcmp(val, "float"))
                prec_mask |= 2;
            else
                goto bad;
            ++a;
        } else {
        bad:
            fprintf(stderr, "ttd_accuracy: bad argument '%s'%s%s\n", arg, val ? " " : "", val ? val : "");
            usage(stderr);
            return 2;
        }
    }
    if (!fam_mask)
        fam_mask = (1u << TTD_GEN_COUNT) - 1;
    if (!method_mask)
        method_mask = (1u << TTD_METHOD_COUNT) - 1;
    if (!prec_mask)
        prec_mask = 3;
    config configs[TTD_METHOD_COUNT * 2 * TTD_ISA_COUNT];
    int nconf = 0;
    for (int m = 0; m < TTD_METHOD_COUNT; ++m)
        for (int pr = 0; pr < 2; ++pr)
            for (int i = TTD_ISA_SCALAR; i < TTD_ISA_COUNT; ++i) {
                if (!(method_mask >> m & 1) || !(prec_mask >> pr & 1))
                    continue;
                if (isa_mask ? !(isa_mask >> i & 1) : !ttd_isa_available((ttd_isa)i))
                    continue;
                configs[nconf++] = (config){(ttd_method)m, pr, (ttd_isa)i};
            }
    int nfam = 0;
    ttd_gen_family fams[TTD_GEN_COUNT];
    for (int f = 0; f < TTD_GEN_COUNT; ++f)
        if (fam_mask >> f & 1)
            fams[nfam++] = (ttd_gen_family)f;

    /* Reference once per family, then every configuration. */
    family_data *fd = xcalloc((size_t)nfam, sizeof *fd);
    for (int f = 0; f < nfam; ++f)
        family_init(&fd[f], fams[f], (uint64_t)seed, pairs);
    row *rows = xcalloc((size_t)nconf * (size_t)nfam, sizeof *rows);
    double *errs = xcalloc(pairs, sizeof *errs);
    ttd_result_d *rd = xcalloc(pairs, sizeof *rd);
    ttd_result_f *rf = xcalloc(pairs, sizeof *rf);
    size_t total_failures = 0;
    for (int c = 0; c < nconf; ++c)
        for (int f = 0; f < nfam; ++f) {
            rows[c * nfam + f] = run_one(&fd[f], configs[c], (int)threads, check, errs, rd, rf);
            total_failures += rows[c * nfam + f].failures;
        }

    if (json) {
        printf("{\"tool\": \"ttd_accuracy\", \"version\": \"%s\", \"reference\": \"%s\", \"seed\": %zu, "
               "\"pairs_per_family\": %zu, \"check\": %s, \"results\": [",
               ttd_version_string(), ttd_ref_precision(), seed, pairs, check ? "true" : "false");
        for (int c = 0; c < nconf; ++c)
            for (int f = 0; f < nfam; ++f)
                print_row_json(stdout, configs[c], &rows[c * nfam + f], c == 0 && f == 0);
        printf("\n  ], \"failures\": %zu}\n", total_failures);
    } else {
        printf("ttd_accuracy: ttd %s, reference %s, seed %zu, %zu pairs per family\n", ttd_version_string(),
               ttd_ref_precision(), seed, pairs);
        printf("err = |d - d_ref| / max(d_ref, size); off = distance of p, q from their triangles and\n"
               "pq = ||p-q| - d|, both / max(d_ref, size) (at offset L they include the rounding of p, q:\n"
               "~eps L / size); float: against the reference of the float-rounded input.\n");
        for (int c = 0; c < nconf; ++c) {
            print_header(configs[c], check);
            for (int f = 0; f < nfam; ++f)
                print_row_text(&rows[c * nfam + f], check);
        }
        printf("\nSummary (worst over the families):\n");
        printf("| method | precision | isa | max err | max off | max pq | non-finite | not conv. |%s\n",
               check ? " failures |" : "");
        printf("|---|---|---|---:|---:|---:|---:|---:|%s\n", check ? "---:|" : "");
        for (int c = 0; c < nconf; ++c) {
            double e = 0, o = 0, q = 0;
            size_t nf = 0, nc = 0, fl = 0;
            for (int f = 0; f < nfam; ++f) {
                const row *w = &rows[c * nfam + f];
                e = fmax(e, w->max_err), o = fmax(o, w->max_off), q = fmax(q, w->max_pq);
                nf += w->nonfinite, nc += w->not_converged, fl += w->failures;
            }
            printf("| %s | %s | %s | %.2e | %.2e | %.2e | %zu | %zu |", ttd_method_name(configs[c].method),
                   configs[c].is_float ? "float" : "double", ttd_isa_name(configs[c].isa), e, o, q, nf, nc);
            if (check)
                printf(" %zu |", fl);
            putchar('\n');
        }
        if (check)
            printf("\n%s: %zu pairs outside their targets\n", total_failures ? "FAILED" : "PASSED", total_failures);
    }
    for (int f = 0; f < nfam; ++f)
        family_free(&fd[f]);
    free(fd), free(rows), free(errs), free(rd), free(rf);
    return check && total_failures ? 1 : 0;
}
