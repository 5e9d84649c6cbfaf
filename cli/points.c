/* SPDX-License-Identifier: MIT */
/* `ttd points closest | signed | winding MESH POINTS [options]` and `ttd points grid MESH ...`: the
 * library's point queries (include/ttd/ttd.h, "Point queries"; docs/points.md) on a mesh file
 * (ttd/meshfile.h) and a points file: text, three numbers a line, or a NumPy .npy array of shape
 * (n, 3) (float64 or float32). The usage text below is the reference for the formats.
 *
 * The whole points file is read and checked before anything is computed; points go to the library
 * in chunks, and each chunk's lines are written before the next is computed. A grid is computed
 * slab by slab (one x index at a time: the library's ttd_sdf_grid on that slab gives the bits of
 * the whole grid's call) and written to a .npy or raw file, with a progress line on standard
 * error for large grids. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"
#include <ttd/meshfile.h>
#include "parse.h"

/// Points per library call.
#define TTD_POINTS_CHUNK 65536
/// Grids of at least this many points show a progress line (or --progress).
#define TTD_POINTS_PROGRESS_MIN ((size_t)1 << 20)

typedef enum { CMD_CLOSEST, CMD_SIGNED, CMD_WINDING, CMD_GRID } points_cmd;

static const char ttd_points_usage[] =
    "usage: ttd points closest MESH POINTS [--pose P] [--upper-bound X] [options]\n"
    "       ttd points signed MESH POINTS [--pose P] [--upper-bound X] [options]\n"
    "       ttd points winding MESH POINTS [--pose P] [options]\n"
    "       ttd points grid MESH --origin \"X Y Z\" --step \"S\" --dims \"NX NY NZ\" --out FILE [options]\n"
    "\n"
    "Points against the triangle mesh in the file MESH (OBJ, STL, PLY, OFF, glTF or 3MF, recognised by content:\n"
    "docs/mesh-files.md; '-' for standard input). POINTS is a text file of three numbers a line\n"
    "(x y z; blank lines and '#' comments skipped; '-' for standard input) or a NumPy .npy file of\n"
    "shape (n, 3), float64 or float32, C order. Triangle indices are 0-based in file order.\n"
    "\n"
    "closest: the exact closest point of the mesh, one line per point:\n"
    "    d tri px py pz\n"
    "  d the distance, (px, py, pz) the closest point, on triangle tri. Beyond --upper-bound X:\n"
    "  'inf -1 nan nan nan' (signed: '-inf' inside). A line that is not 3 finite numbers is an error\n"
    "  (the whole file is refused, nothing printed; Python's ttd.closest_points gives such a point\n"
    "  NaN and a warning instead: docs/python.md says why).\n"
    "signed: the same with d negative inside the mesh (|generalized winding number| >= 1/2: a closed\n"
    "  mesh's solid whichever way it is wound)\n"
    "winding: the generalized winding number, one number a line (1 inside a closed mesh oriented\n"
    "  outwards, -1 inside one oriented inwards, 0 outside)\n"
    "grid: signed distances on the grid point (i, j, k) = origin + (i, j, k) * step, i < NX, j < NY,\n"
    "  k < NZ, written to FILE: a .npy file of shape (NX, NY, NZ) when FILE ends in .npy, else raw\n"
    "  little-endian numbers in that (C) order. --step takes one number or three, each > 0. The\n"
    "  sizes are checked first (the point count, one x slab against memory, the file against the\n"
    "  free disk); FILE is written under a temporary name and renamed at the end, so a failed or\n"
    "  interrupted run (Ctrl-C) leaves no partial file. Grids of 2^20 points or more show their\n"
    "  progress on standard error when it is a terminal, at most 4 updates a second (--progress:\n"
    "  also when it is not, one line an update; --quiet: never).\n"
    "\n"
    "options:\n"
    "  --pose P          the mesh's pose in the points' frame, 12 numbers [R | t] row by row (or\n"
    "                    16, the 4x4 matrix), x_points = R x_mesh + t; R a rotation within 1e-6\n"
    "  --upper-bound X   X >= 0: points farther than X from the mesh print inf (default: none)\n"
    "  --precision P     double (default; printed with %.17g) or float (%.9g): the mesh and points\n"
    "                    rounded once to float, the queries run in float\n"
    "  --isa I           an instruction set (ttd info lists them; default auto)\n"
    "  --threads N       worker threads, 0 = every core (default); results do not depend on N\n"
    "  --weld TOL        merge the mesh's vertices within distance TOL of each other (chained),\n"
    "                    dropping collapsed triangles: an STL-like file becomes closed\n"
    "                    (docs/mesh-files.md, Welding)\n"
    "  --help            this text\n"
    "\n"
    "Exit status: 0 done; 1 a file that cannot be read or is malformed (nothing printed), a point\n"
    "beyond the meshes' coordinate range (2^508 double, 2^60 float), a library error or an output\n"
    "error; 2 bad command line.\n";

typedef struct points_args {
    points_cmd cmd;
    const char *mesh_path, *points_path, *out_path;
    ttd_options opt;
    int use_float, has_pose, progress;
    double pose[12], upper_bound, origin[3], step[3];
    size_t dims[3];
    int has_origin, has_step, has_dims;
    int has_weld; /* --weld TOL: the mesh's vertices within TOL merged after reading */
    double weld;
} points_args;

/* n numbers (1..3) separated by blanks from s, all finite; want_one_or_three accepts 1 (repeated). */
static int parse_vec(const char *s, double out[3], int one_ok)
{
    double v[4];
    int k = 0;
    const char *p = s;
    while (*p) {
        char *end;
        errno = 0;
        const double x = strtod(p, &end);
        if (end == p)
            break;
        if (k == 4 || !isfinite(x) || errno == ERANGE)
            return -1;
        v[k++] = x;
        p = end;
        while (*p == ' ' || *p == '\t' || *p == ',')
            ++p;
    }
    if (*p != '\0' || !(k == 3 || (one_ok && k == 1)))
        return -1;
    for (int c = 0; c < 3; ++c)
        out[c] = v[k == 1 ? 0 : c];
    return 0;
}

static int parse_args(int argc, char **argv, points_args *a)
{
    memset(a, 0, sizeof *a);
    a->opt = ttd_default_options();
    a->upper_bound = INFINITY;
    a->progress = -1;
    static const char *const names[] = {"closest", "signed", "winding", "grid"};
    if (argc < 1) {
        ttd_cli_error("points: a command is needed: closest, signed, winding or grid (see ttd points --help)");
        return TTD_EXIT_USAGE;
    }
    int cmd = -1;
    for (int i = 0; i < 4; ++i)
        if (strcmp(argv[0], names[i]) == 0)
            cmd = i;
    if (cmd < 0) {
        ttd_cli_error("points: unknown command '%s' (closest, signed, winding or grid)", argv[0]);
        return TTD_EXIT_USAGE;
    }
    a->cmd = (points_cmd)cmd;
    static const char *const flags[] = {"--progress", "--quiet", NULL};
    static const char *const valued[] = {"--pose", "--upper-bound", "--precision", "--isa", "--threads",
                                         "--origin", "--step", "--dims", "--out", "--weld", NULL};
    int operands = 0;
    ttd_cli_args w = ttd_cli_args_start("points", flags, valued, argc, argv);
    w.no_end_marker = 1;
    for (ttd_cli_arg k; (k = ttd_cli_next_arg(&w)) != TTD_ARG_END;) {
        const char *arg = w.arg, *opt = w.opt, *val = w.val;
        /* --help never comes here: ttd_cli_points answers it wherever it stands */
        if (k == TTD_ARG_BAD || k == TTD_ARG_HELP)
            return TTD_EXIT_USAGE;
        if (k == TTD_ARG_FLAG) {
            a->progress = opt[2] == 'p';
            continue;
        }
        if (k == TTD_ARG_OPERAND) {
            if (operands == 0)
                a->mesh_path = arg;
            else if (operands == 1 && a->cmd != CMD_GRID)
                a->points_path = arg;
            else {
                ttd_cli_error("points: unexpected operand '%s'", arg);
                return TTD_EXIT_USAGE;
            }
            ++operands;
            continue;
        }
        const int r = ttd_cli_run_option(opt, val, &a->opt, &a->use_float);
        int bad = r < 0;
        if (r == 1) {
            if (strcmp(opt, "--pose") == 0) {
                char err[256];
                bad = ttd_parse_pose_line(val, strlen(val), 0, a->pose, err, sizeof err) != TTD_LINE_PAIR ||
                      ttd_cli_pose_problem(a->pose, 0, err, sizeof err) != 0;
                a->has_pose = 1;
            } else if (strcmp(opt, "--upper-bound") == 0) {
                bad = ttd_cli_parse_real(val, &a->upper_bound) || !(a->upper_bound >= 0);
            } else if (strcmp(opt, "--origin") == 0) {
                bad = parse_vec(val, a->origin, 0);
                a->has_origin = 1;
            } else if (strcmp(opt, "--step") == 0) {
                bad = parse_vec(val, a->step, 1) || !(a->step[0] > 0 && a->step[1] > 0 && a->step[2] > 0);
                a->has_step = 1;
            } else if (strcmp(opt, "--dims") == 0) {
                double d[3];
                bad = parse_vec(val, d, 0);
                for (int c = 0; c < 3 && !bad; ++c) {
                    bad = !(d[c] >= 1 && d[c] <= 1e12 && d[c] == floor(d[c]));
                    a->dims[c] = (size_t)d[c];
                }
                a->has_dims = 1;
            } else if (strcmp(opt, "--out") == 0) {
                a->out_path = val;
            } else if (strcmp(opt, "--weld") == 0) {
                bad = ttd_cli_parse_weld(val, &a->weld);
                a->has_weld = 1;
            }
        }
        if (bad) {
            ttd_cli_error("points: bad value for %s: '%s'", opt, val);
            return TTD_EXIT_USAGE;
        }
    }
    if (a->cmd == CMD_GRID ? operands != 1 || !a->has_origin || !a->has_step || !a->has_dims || !a->out_path
                           : operands != 2) {
        ttd_cli_error(a->cmd == CMD_GRID ? "points grid: needs MESH, --origin, --step, --dims and --out"
                                         : "points %s: needs MESH and POINTS",
                      names[cmd]);
        return TTD_EXIT_USAGE;
    }
    if (ttd_isa_selected(&a->opt) == TTD_ISA_AUTO) {
        ttd_cli_error("points: instruction set '%s' is not available here", ttd_isa_name(a->opt.isa));
        return TTD_EXIT_USAGE;
    }
    return 0;
}

/* ---- points files ------------------------------------------------------------------------- */

typedef struct points_in {
    double *d;   /* 3n doubles (double precision) */
    float *f;    /* 3n floats (float) */
    size_t n, cap;
} points_in;

static int points_push(points_in *P, const double x[3], int use_float)
{
    if (P->n == P->cap) {
        const size_t cap = P->cap ? 2 * P->cap : 1024;
        void *p = use_float ? realloc(P->f, 3 * cap * sizeof(float)) : realloc(P->d, 3 * cap * sizeof(double));
        if (p == NULL)
            return -1;
        if (use_float)
            P->f = p;
        else
            P->d = p;
        P->cap = cap;
    }
    for (int c = 0; c < 3; ++c) {
        if (use_float)
            P->f[3 * P->n + (size_t)c] = (float)x[c];
        else
            P->d[3 * P->n + (size_t)c] = x[c];
    }
    ++P->n;
    return 0;
}

/* A .npy file of shape (n, 3), '<f8' or '<f4', C order: 0, or -1 with a message. */
static int read_npy(FILE *f, const char *path, int use_float, points_in *P)
{
    unsigned char head[10];
    if (fread(head, 1, 10, f) != 10 || memcmp(head, "\x93NUMPY", 6) != 0) {
        ttd_cli_error("%s: not a .npy file", path);
        return -1;
    }
    size_t hl = head[8] | (size_t)head[9] << 8;
    if (head[6] >= 2) {
        unsigned char more[2];
        if (fread(more, 1, 2, f) != 2) {
            ttd_cli_error("%s: truncated .npy header", path);
            return -1;
        }
        hl |= (size_t)more[0] << 16 | (size_t)more[1] << 24;
    }
    char *h = malloc(hl + 1);
    if (h == NULL || fread(h, 1, hl, f) != hl) {
        free(h);
        ttd_cli_error("%s: truncated .npy header", path);
        return -1;
    }
    h[hl] = '\0';
    const int f8 = strstr(h, "'<f8'") != NULL, f4 = strstr(h, "'<f4'") != NULL;
    const char *shape = strstr(h, "'shape':");
    unsigned long long n = 0, three = 0;
    const int ok = (f8 || f4) && strstr(h, "'fortran_order': False") && shape &&
                   sscanf(shape, "'shape': (%llu, %llu)", &n, &three) == 2 && three == 3;
    free(h);
    if (!ok) {
        ttd_cli_error("%s: a .npy points file must be float64 or float32 ('<f8', '<f4'), C order, shape (n, 3)", path);
        return -1;
    }
    for (unsigned long long i = 0; i < n; ++i) {
        double x[3];
        for (int c = 0; c < 3; ++c) {
            if (f8) {
                double v;
                if (fread(&v, 8, 1, f) != 1)
                    goto short_read;
                x[c] = v;
            } else {
                float v;
                if (fread(&v, 4, 1, f) != 1)
                    goto short_read;
                x[c] = (double)v;
            }
        }
        if (points_push(P, x, use_float)) {
            ttd_cli_error("%s: out of memory", path);
            return -1;
        }
    }
    return 0;
short_read:
    ttd_cli_error("%s: the .npy data ends before its %llu points", path, n);
    return -1;
}

static int read_points(const points_args *a, points_in *P)
{
    const int std_in = strcmp(a->points_path, "-") == 0;
    FILE *f = std_in ? stdin : fopen(a->points_path, "rb");
    if (f == NULL) {
        ttd_cli_error("%s: %s", a->points_path, strerror(errno));
        return TTD_EXIT_INPUT;
    }
    const size_t l = strlen(a->points_path);
    int rc = 0;
    if (!std_in && l >= 4 && strcmp(a->points_path + l - 4, ".npy") == 0) {
        rc = read_npy(f, a->points_path, a->use_float, P);
    } else {
        static ttd_line_reader r;
        ttd_reader_init(&r, f);
        size_t len;
        int overlong;
        while (rc == 0 && ttd_reader_next(&r, &len, &overlong)) {
            double x[3];
            char err[256];
            const ttd_line_kind k = ttd_parse_numbers_line(r.line, len, a->use_float, 3, x, err, sizeof err);
            if (k == TTD_LINE_SKIP)
                continue;
            if (k == TTD_LINE_ERROR || overlong) {
                ttd_cli_error("%s:%llu: %s", std_in ? "<stdin>" : a->points_path, r.line_no,
                              overlong ? "line too long" : err);
                rc = -1;
            } else if (points_push(P, x, a->use_float)) {
                ttd_cli_error("%s: out of memory", a->points_path);
                rc = -1;
            }
        }
        if (rc == 0 && r.error) {
            ttd_cli_error("%s: %s", a->points_path, strerror(r.error));
            rc = -1;
        }
    }
    if (!std_in)
        fclose(f);
    return rc ? TTD_EXIT_INPUT : 0;
}

/* ---- queries ------------------------------------------------------------------------------ */

static void put_result(FILE *out, int use_float, double d, uint32_t tri, const double p[3])
{
    if (tri == UINT32_MAX)
        fprintf(out, "%s -1 nan nan nan\n", isnan(d) ? "nan" : d < 0 ? "-inf" : "inf");
    else
        fprintf(out, use_float ? "%.9g %u %.9g %.9g %.9g\n" : "%.17g %u %.17g %.17g %.17g\n", d, tri, p[0], p[1], p[2]);
}

static int run_points(const points_args *a, const ttd_mesh *mesh, const points_in *P)
{
    const size_t chunk = TTD_POINTS_CHUNK;
    ttd_point_result_d *rd = NULL;
    ttd_point_result_f *rf = NULL;
    double *sd = malloc(chunk * sizeof *sd);
    float *sf = malloc(chunk * sizeof *sf);
    if (a->use_float)
        rf = malloc(chunk * sizeof *rf);
    else
        rd = malloc(chunk * sizeof *rd);
    if (sd == NULL || sf == NULL || (rd == NULL && rf == NULL)) {
        ttd_cli_error("points: out of memory");
        free(sd), free(sf), free(rd), free(rf);
        return TTD_EXIT_INPUT;
    }
    float posef[12];
    for (int k = 0; k < 12; ++k)
        posef[k] = (float)a->pose[k];
    const double *pd = a->has_pose ? a->pose : NULL;
    const float *pf = a->has_pose ? posef : NULL;
    int rc = 0;
    for (size_t i0 = 0; i0 < P->n && rc == 0; i0 += chunk) {
        const size_t k = P->n - i0 < chunk ? P->n - i0 : chunk;
        ttd_status st;
        if (a->cmd == CMD_WINDING)
            st = a->use_float ? ttd_points_winding_number_f(&a->opt, mesh, k, P->f + 3 * i0, pf, sf)
                              : ttd_points_winding_number_d(&a->opt, mesh, k, P->d + 3 * i0, pd, sd);
        else if (a->cmd == CMD_CLOSEST)
            st = a->use_float ? ttd_points_closest_f(&a->opt, mesh, k, P->f + 3 * i0, pf, (float)a->upper_bound, rf)
                              : ttd_points_closest_d(&a->opt, mesh, k, P->d + 3 * i0, pd, a->upper_bound, rd);
        else
            st = a->use_float ? ttd_points_signed_distance_f(&a->opt, mesh, k, P->f + 3 * i0, pf, (float)a->upper_bound, sf, rf)
                              : ttd_points_signed_distance_d(&a->opt, mesh, k, P->d + 3 * i0, pd, a->upper_bound, sd, rd);
        if (st != TTD_OK && st != TTD_ERR_NONFINITE_INPUT) {
            ttd_cli_error("points: points %zu..%zu: %s", i0, i0 + k - 1, ttd_status_string(st));
            rc = TTD_EXIT_INPUT;
            break;
        }
        for (size_t i = 0; i < k; ++i) {
            if (a->cmd == CMD_WINDING) {
                fprintf(stdout, a->use_float ? "%.9g\n" : "%.17g\n", a->use_float ? (double)sf[i] : sd[i]);
                continue;
            }
            double d, p[3];
            uint32_t tri;
            if (a->use_float) {
                d = a->cmd == CMD_SIGNED ? (double)sf[i] : (double)rf[i].distance;
                tri = rf[i].triangle;
                for (int c = 0; c < 3; ++c)
                    p[c] = (double)rf[i].point[c];
            } else {
                d = a->cmd == CMD_SIGNED ? sd[i] : rd[i].distance;
                tri = rd[i].triangle;
                memcpy(p, rd[i].point, sizeof p);
            }
            put_result(stdout, a->use_float, d, tri, p);
        }
        if (ferror(stdout)) {
            ttd_cli_error("points: cannot write the output");
            rc = TTD_EXIT_INPUT;
        }
    }
    free(sd), free(sf), free(rd), free(rf);
    return rc;
}

/* ---- grids -------------------------------------------------------------------------------- */

static int write_npy_header(FILE *f, const points_args *a)
{
    char dict[256];
    int n = snprintf(dict, sizeof dict, "{'descr': '%s', 'fortran_order': False, 'shape': (%zu, %zu, %zu), }",
                     a->use_float ? "<f4" : "<f8", a->dims[0], a->dims[1], a->dims[2]);
    const int total = 10 + n + 1, pad = (64 - total % 64) % 64; /* header (and newline) to a multiple of 64 */
    const size_t hl = (size_t)(n + pad + 1);
    unsigned char head[10] = {0x93, 'N', 'U', 'M', 'P', 'Y', 1, 0, (unsigned char)(hl & 0xff), (unsigned char)(hl >> 8)};
    if (fwrite(head, 1, 10, f) != 10 || fwrite(dict, 1, (size_t)n, f) != (size_t)n)
        return -1;
    for (int i = 0; i < pad; ++i)
        if (fputc(' ', f) == EOF)
            return -1;
    return fputc('\n', f) == EOF ? -1 : 0;
}

/* Set by SIGINT / SIGTERM while a grid is written: the loop stops after the slab at hand and
 * removes its temporary file, so an interrupted run leaves no partial grid behind. */
static volatile sig_atomic_t grid_stop;

static void grid_on_signal(int sig)
{
    grid_stop = sig;
}

/* mkstemp makes the file 0600; the grid gets the permissions a plain fopen would give it */
static mode_t grid_umask(void)
{
    const mode_t m = umask(0);
    umask(m);
    return m;
}

static double grid_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* The grid's size, checked before anything is written: the point count and the file's bytes must
 * not overflow, one slab's buffer must fit in memory and the file on its disk. Returns 0, or
 * prints why not and returns an exit status. */
static int grid_check_sizes(const points_args *a, const char *dir)
{
    const size_t sz = a->use_float ? sizeof(float) : sizeof(double);
    const size_t d0 = a->dims[0], d1 = a->dims[1], d2 = a->dims[2];
    if (d1 > SIZE_MAX / d2 || d0 > SIZE_MAX / (d1 * d2) || d0 * d1 * d2 > (SIZE_MAX - 128) / sz) {
        ttd_cli_error("points grid: --dims \"%zu %zu %zu\": the point count or the file's size overflows %zu bits", d0, d1,
                      d2, 8 * sizeof(size_t));
        return TTD_EXIT_USAGE;
    }
    const size_t slab_bytes = d1 * d2 * sz, bytes = d0 * d1 * d2 * sz + 128;
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    if (pages > 0 && page > 0 && (double)slab_bytes > 0.5 * (double)pages * (double)page) {
        ttd_cli_error("points grid: one slab of %zu x %zu points needs %.3g GB, more than half this machine's memory "
                      "(%.3g GB): put the longest dimension first (--dims NX NY NZ, computed one x index at a time)",
                      d1, d2, 1e-9 * (double)slab_bytes, 1e-9 * (double)pages * (double)page);
        return TTD_EXIT_USAGE;
    }
    struct statvfs fs;
    if (statvfs(dir, &fs) == 0 && (double)bytes > (double)fs.f_bavail * (double)fs.f_frsize) {
        ttd_cli_error("points grid: %s needs %.4g GB and its disk has %.4g GB free", a->out_path, 1e-9 * (double)bytes,
                      1e-9 * (double)fs.f_bavail * (double)fs.f_frsize);
        return TTD_EXIT_INPUT;
    }
    return 0;
}

static int run_grid(const points_args *a, const ttd_mesh *mesh)
{
    const size_t slab = a->dims[1] * a->dims[2];
    const size_t l = strlen(a->out_path);
    const int npy = l >= 4 && strcmp(a->out_path + l - 4, ".npy") == 0;
    /* the output is written to a temporary file beside it and renamed over it at the end */
    char *tmp = malloc(l + 16), *dir = malloc(l + 2);
    if (tmp == NULL || dir == NULL) {
        free(tmp), free(dir);
        ttd_cli_error("points grid: out of memory");
        return TTD_EXIT_INPUT;
    }
    snprintf(tmp, l + 16, "%s.tmp.XXXXXX", a->out_path);
    const char *slash = strrchr(a->out_path, '/');
    if (slash == NULL)
        snprintf(dir, l + 2, ".");
    else
        snprintf(dir, l + 2, "%.*s", slash == a->out_path ? 1 : (int)(slash - a->out_path), a->out_path);
    int rc = grid_check_sizes(a, dir);
    free(dir);
    if (rc) {
        free(tmp);
        return rc;
    }
    const int fd = mkstemp(tmp);
    FILE *f = fd < 0 ? NULL : fdopen(fd, "wb");
    if (f == NULL) {
        ttd_cli_error("%s: %s", a->out_path, strerror(errno));
        if (fd >= 0)
            close(fd), unlink(tmp);
        free(tmp);
        return TTD_EXIT_INPUT;
    }
    fchmod(fd, 0666 & ~grid_umask());
    void *buf = malloc(slab * (a->use_float ? sizeof(float) : sizeof(double)));
    if (buf == NULL)
        ttd_cli_error("points grid: out of memory for a slab of %zu points", slab);
    rc = buf == NULL || (npy && write_npy_header(f, a)) ? TTD_EXIT_INPUT : 0;
    /* progress: on a terminal for large grids (or --progress), at most 4 updates a second */
    const size_t total = a->dims[0] * slab;
    const int tty = isatty(STDERR_FILENO);
    const int show = a->progress == 1 || (a->progress == -1 && tty && total >= TTD_POINTS_PROGRESS_MIN);
    double next_show = grid_now() + 0.25;
    int shown = 0;
    grid_stop = 0;
    struct sigaction sa, old_int, old_term;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = grid_on_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &old_int);
    sigaction(SIGTERM, &sa, &old_term);
    const size_t dims1[3] = {1, a->dims[1], a->dims[2]};
    for (size_t i = 0; i < a->dims[0] && rc == 0; ++i) {
        if (grid_stop) {
            ttd_cli_error("points grid: interrupted after %zu of %zu slabs; %s not written", i, a->dims[0], a->out_path);
            rc = TTD_EXIT_INPUT;
            break;
        }
        ttd_status st;
        if (a->use_float) {
            /* the slab's origin: origin + i step in float, as the whole grid's call computes x */
            const float o[3] = {(float)a->origin[0] + (float)i * (float)a->step[0], (float)a->origin[1], (float)a->origin[2]};
            const float s[3] = {(float)a->step[0], (float)a->step[1], (float)a->step[2]};
            st = ttd_sdf_grid_f(&a->opt, mesh, o, s, dims1, buf);
        } else {
            const double o[3] = {a->origin[0] + (double)i * a->step[0], a->origin[1], a->origin[2]};
            st = ttd_sdf_grid_d(&a->opt, mesh, o, a->step, dims1, buf);
        }
        if (st != TTD_OK) {
            ttd_cli_error("points grid: slab %zu: %s", i, ttd_status_string(st));
            rc = TTD_EXIT_INPUT;
            break;
        }
        const size_t sz = a->use_float ? sizeof(float) : sizeof(double);
        if (fwrite(buf, sz, slab, f) != slab) {
            ttd_cli_error("%s: cannot write: %s", a->out_path, strerror(errno));
            rc = TTD_EXIT_INPUT;
        }
        if (show && (i + 1 == a->dims[0] || grid_now() >= next_show)) {
            fprintf(stderr, "%sttd points grid: %3d%% (%zu of %zu slabs)%s", tty ? "\r" : "",
                    (int)((double)(i + 1) / (double)a->dims[0] * 100.0), i + 1, a->dims[0], tty ? "" : "\n");
            next_show = grid_now() + 0.25;
            shown = 1;
        }
    }
    sigaction(SIGINT, &old_int, NULL);
    sigaction(SIGTERM, &old_term, NULL);
    if (shown && tty)
        fputc('\n', stderr);
    if (fclose(f) != 0 && rc == 0) {
        ttd_cli_error("%s: cannot write: %s", a->out_path, strerror(errno));
        rc = TTD_EXIT_INPUT;
    }
    if (rc == 0 && rename(tmp, a->out_path) != 0) {
        ttd_cli_error("%s: cannot rename %s to it: %s", a->out_path, tmp, strerror(errno));
        rc = TTD_EXIT_INPUT;
    }
    if (rc != 0)
        unlink(tmp);
    free(tmp);
    free(buf);
    return rc;
}

int ttd_cli_points(int argc, char **argv)
{
    for (int i = 0; i < argc; ++i)
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            fputs(ttd_points_usage, stdout);
            return TTD_EXIT_OK;
        }
    points_args a;
    int rc = parse_args(argc - 1, argv + 1, &a); /* argv[0] is "points" */
    if (rc)
        return rc;
    ttd_cli_warn_isa_env("points");
    points_in P = {0};
    if (a.cmd != CMD_GRID && (rc = read_points(&a, &P)) != 0) {
        free(P.d), free(P.f);
        return rc;
    }
    ttd_meshfile file;
    char err[1024];
    if (ttd_meshfile_read(a.mesh_path, a.use_float ? TTD_MESHFILE_FLOAT : 0, &file, err, sizeof err) != 0) {
        ttd_cli_error("%s", err);
        free(P.d), free(P.f);
        return TTD_EXIT_INPUT;
    }
    if (a.has_weld && ttd_cli_weld(&file, strcmp(a.mesh_path, "-") == 0 ? "<stdin>" : a.mesh_path, a.weld) != 0) {
        ttd_meshfile_free(&file);
        free(P.d), free(P.f);
        return TTD_EXIT_INPUT;
    }
    ttd_mesh *mesh;
    const ttd_status st = a.use_float ? ttd_mesh_create_f(&a.opt, file.verts_f, file.nv, file.tris, file.nt, &mesh)
                                      : ttd_mesh_create_d(&a.opt, file.verts, file.nv, file.tris, file.nt, &mesh);
    ttd_meshfile_free(&file);
    if (st != TTD_OK) {
        ttd_cli_error("%s: cannot build the mesh: %s", a.mesh_path, ttd_status_string(st));
        free(P.d), free(P.f);
        return TTD_EXIT_INPUT;
    }
    if (a.cmd == CMD_GRID)
        rc = run_grid(&a, mesh);
    else if (P.n > 0)
        rc = run_points(&a, mesh, &P);
    ttd_mesh_destroy(mesh);
    free(P.d), free(P.f);
    return rc;
}
