/* SPDX-License-Identifier: MIT */
/* The mesh-query section of `ttd bench` (issue 9, item 4; bench/mesh_bench.h): ttd's mesh queries
 * against FCL 0.7 (bench/fcl/fcl_mesh_bench.cpp through bench/fcl_mesh_link.c) on the same meshes
 * and poses, in one run.
 *
 * Meshes, each normalised to a bounding-box diagonal of 1 and queried against a copy of itself:
 * an icosphere, the Stanford bunny (scripts/fetch-bunny.sh), the bunny subdivided 3 times and a
 * 1M-triangle torus; --quick uses the icosphere and a small torus only (no file, no network).
 * Poses: b turned by a seeded random rotation and moved along a seeded random direction
 * (ttd_gen_pose_gap), the slab gap along that direction bisected until ttd's own minimum distance
 * is within 1% of the target (far 1, near 0.01, contact 0.002), and an overlapping placement that
 * ttd finds intersecting; plus 1,000 random poses of the bunny (ttd_gen_pose).
 *
 * Every ttd row is a warm-up call, then the median of several samples, each enough calls to last
 * the benchmark's minimum sample time (fewer samples for long calls), as the pair rows are
 * timed. FCL's program times each pose `repetitions` times and reports the median; the count is
 * chosen from ttd's time so that FCL's share stays bounded. Correctness is checked on every row
 * that has an FCL counterpart: distances within 1e-12 of the size, the same collision answer, the
 * same set of pairs within the margin (pairs whose distance lies within rounding of the margin
 * are reported apart, as boundary pairs). A disagreement is printed on standard error and in the
 * table; the benchmark never fails because of one, nor because of a missed target. */
#define _POSIX_C_SOURCE 200809L
#include "mesh_bench.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fcl_mesh_link.h"
#include "json.h"
#include "meshes.h"
#include <ttd/meshfile.h>

/* ---- workloads ------------------------------------------------------------------------ */

enum { MW_ICOSPHERE, MW_BUNNY, MW_BUNNY_SUB3, MW_TORUS_1M, MW_TORUS_SMALL, MW_POSES, MW_COUNT };

typedef struct mesh_workload {
    const char *name;
    int in_full, in_quick;   /* in that mode's default list */
    double contact_margin;   /* the contacts rows' margin (the near placement) */
    const char *what;
} mesh_workload;

/* Contact margins give thousands to millions of pairs at the near placement (distance 1%): 2% of
 * the size as in docs/anchors.md ("Mesh queries") for the big meshes, 5% for the coarse ones, whose
 * triangles are a few percent of the size across. */
static const mesh_workload mws[MW_COUNT] = {
    {"icosphere", 1, 1, 0.05, "ttd_gen_icosphere(3), the icosahedron split 4:1 three times: 1,280 triangles"},
    {"bunny", 1, 0, 0.05, "the Stanford bunny (npm package bunny 1.0.1): 3,674 triangles"},
    {"bunny-sub3", 1, 0, 0.02, "the bunny subdivided 3 times (flat, 4:1): 235,136 triangles"},
    {"torus-1m", 1, 0, 0.02, "ttd_gen_torus(1, 0.35, 1000, 500): 1,000,000 triangles"},
    {"torus-small", 0, 1, 0.05, "ttd_gen_torus(1, 0.35, 40, 20): 1,600 triangles"},
    {"poses", 1, 1, 0.0, "1,000 poses ttd_gen_pose(seed, 1000 + i, 0.5) of the bunny in one call (--quick: 20, "
                         "and with --quick or without the bunny: of the icosphere)"},
};

/* The placements: target distances (fractions of the size; overlap: intersecting). */
enum { PL_FAR, PL_NEAR, PL_CONTACT, PL_OVERLAP, PL_COUNT };
static const char *const pl_name[PL_COUNT] = {"far", "near", "contact", "overlap"};
static const double pl_target[PL_COUNT] = {1.0, 0.01, 0.002, 0.0};

/* collide+m rows: between the contact (0.2%) and near (1%) placements, so that both answers occur */
#define COLLIDE_MARGIN 0.005
/* random poses: translation uniform in [-scale, scale)^3, a mix of overlapping and separated */
#define POSES_SCALE 0.5
#define POSES_FULL 1000
#define POSES_QUICK 20
/* agreement tolerances, as fractions of the size (1): double, and float against FCL's double */
#define TOL_D 1e-12
#define TOL_F 1e-5

/* ---- results -------------------------------------------------------------------------- */

enum { FCL_NONE = 0, FCL_OK, FCL_NO_MARGIN, FCL_FAILED };

/* One line of the section. NaN where a field does not apply. */
typedef struct mrow {
    char workload[16];
    size_t tris;            /* triangles of each mesh */
    char pose[16];          /* far near contact overlap, random, or - (build) */
    double pose_dist;       /* ttd's distance at the placement */
    char query[16];         /* build distance collide collide+m contacts closest */
    int bytes, threads;
    size_t poses;           /* poses per call (times are per pose) */
    double margin;
    char result[32];        /* what the query answered, printable */
    double value;           /* the same as a number (distance, pairs, hit, nodes) */
    double ms, ms_min;      /* per query (per pose) */
    int samples;
    long passes;
    double pair_tests, node_tests; /* per query, mean over poses */
    int fcl;                /* FCL_* */
    double fcl_ms, fcl_ms_min, fcl_bv, fcl_leaf, fcl_value;
    double x_fcl;           /* FCL's time / ttd's */
    double diff;            /* worst |d - d_fcl| */
    double x_threads;       /* 2 threads: one thread's sample / two threads' beside it, median over rounds */
    double x_threads_lo, x_threads_hi; /* and the rounds' range (bench_time_alternating) */
    int thread_rounds;
    int disagree;
    char note[200];
} mrow;

typedef struct target {
    const char *what;
    const char *need;       /* the words */
    double required;        /* the ratio that meets it */
    double measured;        /* NaN: not measured */
    char where[96];         /* which row gave it, or why n/a */
} target;

enum { T_DIST_EVERY, T_DIST_MEDIAN, T_POSES, T_POSES_2T, T_CONTACTS_D, T_CONTACTS_F, T_BUILD, T_COLLIDE, T_COUNT };

struct bench_mesh_results {
    mrow *rows;
    size_t n, cap;
    target targets[T_COUNT];
    int quick;
    unsigned ran;           /* workloads asked for (bit i = mws[i]) */
    char isa[16];
    char bunny[1600];       /* where the bunny came from, or why it is missing */
    char fcl[1200];         /* the FCL program, or why it is absent */
    size_t compared;        /* distances compared with FCL */
    double worst_diff;      /* over them */
    size_t disagreements;
    char alarms[8][240];    /* the first disagreements, for the table */
    size_t nalarms;
};

/* What a run shares. */
typedef struct mctx {
    const bench_mesh_env *env;
    bench_mesh_results *R;
    ttd_isa isa;
    int fcl_ok;
    char fcl_path[1024];
    double min_s, max_row_s, fcl_budget_s;
    const ttd_gen_mesh *bunny; /* normalised, or NULL */
} mctx;

__attribute__((format(printf, 2, 3))) static void progress(const mctx *M, const char *fmt, ...)
{
    va_list ap;
    if (M->env->quiet)
        return;
    fprintf(stderr, "ttd bench [%6.1f s] mesh: ", bench_now() - M->env->t_start);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
}

/* A disagreement between ttd and FCL: on standard error at once (even with --quiet), in the row's
 * note and in the table's alarm list. */
__attribute__((format(printf, 3, 4))) static void alarm_(mctx *M, mrow *r, const char *fmt, ...)
{
    char msg[240];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    fprintf(stderr, "ttd bench: MESH DISAGREEMENT: %s %s %s %s: %s\n", r->workload, r->pose, r->query,
            r->bytes == 8 ? "double" : "float", msg);
    r->disagree = 1;
    snprintf(r->note, sizeof r->note, "DISAGREES: %.180s", msg);
    if (M->R->nalarms < sizeof M->R->alarms / sizeof M->R->alarms[0])
        snprintf(M->R->alarms[M->R->nalarms++], sizeof M->R->alarms[0], "%s %s %s %s: %.180s", r->workload, r->pose,
                 r->query, r->bytes == 8 ? "double" : "float", msg);
    M->R->disagreements++;
}

/* Rows live in one array allocated at the start and never moved: the code keeps pointers to rows
 * while it adds others. */
#define MAX_MESH_ROWS 512

static mrow *new_row(mctx *M, const char *workload, size_t tris, const char *pose, const char *query, int bytes,
                     int threads, size_t poses)
{
    bench_mesh_results *R = M->R;
    if (R->n == R->cap) {
        fprintf(stderr, "ttd bench: mesh: more than %d rows; the rest are left out\n", MAX_MESH_ROWS);
        return NULL;
    }
    mrow *r = &R->rows[R->n++];
    memset(r, 0, sizeof *r);
    snprintf(r->workload, sizeof r->workload, "%s", workload);
    snprintf(r->pose, sizeof r->pose, "%s", pose);
    snprintf(r->query, sizeof r->query, "%s", query);
    snprintf(r->result, sizeof r->result, "-");
    r->tris = tris;
    r->bytes = bytes;
    r->threads = threads;
    r->poses = poses;
    r->pose_dist = r->margin = r->value = r->ms = r->ms_min = BENCH_NAN;
    r->pair_tests = r->node_tests = BENCH_NAN;
    r->fcl_ms = r->fcl_ms_min = r->fcl_bv = r->fcl_leaf = r->fcl_value = r->x_fcl = r->diff = BENCH_NAN;
    r->x_threads = r->x_threads_lo = r->x_threads_hi = BENCH_NAN;
    return r;
}

/* ---- options -------------------------------------------------------------------------- */

int bench_mesh_option(bench_mesh_config *c, const char *a, const char *v)
{
    if (strcmp(a, "--no-mesh") == 0) {
        c->disabled = 1;
        return 1;
    }
    int which = strcmp(a, "--mesh-workloads") == 0 ? 0 : strcmp(a, "--bunny") == 0 ? 1
                                                      : strcmp(a, "--fcl-mesh") == 0 ? 2 : -1;
    if (which < 0)
        return 0;
    if (!v || !*v) {
        fprintf(stderr, "ttd bench: %s needs a value (see ttd bench --help)\n", a);
        return -1;
    }
    if (which == 1 || which == 2) {
        char *dst = which == 1 ? c->bunny : c->fcl_mesh;
        if (strlen(v) >= sizeof c->bunny) {
            fprintf(stderr, "ttd bench: %s: path too long\n", a);
            return -1;
        }
        snprintf(dst, sizeof c->bunny, "%s", v);
        return 2;
    }
    char buf[256];
    if (strlen(v) >= sizeof buf) {
        fprintf(stderr, "ttd bench: --mesh-workloads: list too long\n");
        return -1;
    }
    snprintf(buf, sizeof buf, "%s", v);
    c->named = 0;
    for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        int found = -1;
        for (int i = 0; i < MW_COUNT; ++i)
            if (strcmp(tok, mws[i].name) == 0)
                found = i;
        if (found < 0) {
            fprintf(stderr, "ttd bench: unknown mesh workload '%s' (icosphere bunny bunny-sub3 torus-1m torus-small "
                            "poses)\n",
                    tok);
            return -1;
        }
        c->named |= 1u << found;
    }
    if (!c->named) {
        fprintf(stderr, "ttd bench: --mesh-workloads names no workload\n");
        return -1;
    }
    return 2;
}

void bench_mesh_usage(FILE *f)
{
    fputs("\nMesh queries (issue 9; docs/benchmark.md): ttd's mesh queries against FCL 0.7's BVHModel<OBBRSS>\n"
          "(ttd_fcl_mesh_bench) on the same meshes and poses, with the issue's speed targets. Run by default,\n"
          "after the pair workloads; --workloads alone runs only pair workloads, --mesh-workloads alone only\n"
          "mesh workloads, both: the named ones of each.\n"
          "  --mesh-workloads LIST comma-separated, from: icosphere (1,280 triangles), bunny (3,674),\n"
          "                       bunny-sub3 (235,136), torus-1m (1,000,000), torus-small (1,600), poses\n"
          "                       (1,000 random bunny poses in one call). Default: icosphere bunny bunny-sub3\n"
          "                       torus-1m poses; --quick: icosphere torus-small poses (20 icosphere poses)\n"
          "  --no-mesh            leave the mesh section out\n"
          "  --bunny PATH         the Stanford bunny as OBJ/STL/PLY (default: $TTD_BUNNY, else\n"
          "                       build/data/bunny.obj, else data/bunny.obj next to ttd's folder; fetch it with\n"
          "                       scripts/fetch-bunny.sh). Without it the bunny workloads are left out (said so)\n"
          "                       and the random poses use the icosphere\n"
          "  --fcl-mesh PATH      the ttd_fcl_mesh_bench program (default: $TTD_FCL_MESH_BENCH, or next to ttd)\n"
          "The section adds rows to the table, a \"mesh\" object to the JSON and, with --out DIR,\n"
          "DIR/bench-mesh.csv (scripts/bench.sh draws figure-mesh.svg/.png from it).\n",
          f);
}

int bench_mesh_wanted(const bench_mesh_config *c, int pair_workloads_named)
{
    if (c->disabled)
        return 0;
    return c->named || !pair_workloads_named;
}

/* ---- meshes --------------------------------------------------------------------------- */

static int file_readable(const char *path) { return path && *path && access(path, R_OK) == 0; }

/* The bunny's path: --bunny, $TTD_BUNNY, build/data/bunny.obj, or ../data/bunny.obj beside ttd.
 * Returns 0 with the path, or -1 with where it looked in why. */
static int find_bunny(const bench_mesh_config *c, char *path, size_t size, char *why, size_t why_size)
{
    const char *env = getenv("TTD_BUNNY");
    if (c->bunny[0] || (env && *env)) {
        const char *p = c->bunny[0] ? c->bunny : env;
        snprintf(path, size, "%s", p);
        if (file_readable(p))
            return 0;
        snprintf(why, why_size, "%s (%s) is not readable: %s", p, c->bunny[0] ? "--bunny" : "$TTD_BUNNY",
                 strerror(errno));
        return -1;
    }
    if (file_readable("build/data/bunny.obj")) {
        snprintf(path, size, "build/data/bunny.obj");
        return 0;
    }
    char self[4096];
    ssize_t len = readlink("/proc/self/exe", self, sizeof self - 1);
    if (len > 0) {
        self[len] = '\0';
        char *slash = strrchr(self, '/');
        if (slash) {
            *slash = '\0';
            if ((size_t)snprintf(path, size, "%s/../data/bunny.obj", self) < size && file_readable(path))
                return 0;
        }
    }
    snprintf(why, why_size, "not found (looked at --bunny, $TTD_BUNNY, build/data/bunny.obj and data/bunny.obj beside "
                            "ttd's folder; scripts/fetch-bunny.sh fetches it)");
    return -1;
}

int bench_mesh_load_bunny(const bench_mesh_config *c, ttd_gen_mesh *out, char *what, size_t size)
{
    char path[1100], why[1400];
    memset(out, 0, sizeof *out);
    if (find_bunny(c, path, sizeof path, why, sizeof why) != 0) {
        snprintf(what, size, "missing: %s", why);
        return -1;
    }
    ttd_meshfile mf;
    char err[512];
    if (ttd_meshfile_read(path, 0, &mf, err, sizeof err) != 0) {
        snprintf(what, size, "missing: %s", err);
        return -1;
    }
    ttd_gen_mesh view = {mf.verts, mf.nv, mf.tris, mf.nt};
    int rc = ttd_gen_mesh_copy(&view, out) || ttd_gen_normalize(out) ? -1 : 0;
    if (rc == 0)
        snprintf(what, size, "%s (%zu vertices, %zu triangles)", path, mf.nv, mf.nt);
    else
        snprintf(what, size, "missing: %s could not be normalised (empty or degenerate?)", path);
    ttd_meshfile_free(&mf);
    if (rc)
        ttd_gen_mesh_free(out);
    return rc;
}

/* Mesh w, normalised (diagonal 1). -1 when it cannot be made (the bunny missing). */
static int make_mesh(const mctx *M, int w, ttd_gen_mesh *out)
{
    memset(out, 0, sizeof *out);
    int rc = -1;
    switch (w) {
    case MW_ICOSPHERE:
        rc = ttd_gen_icosphere(3, out);
        break;
    case MW_BUNNY:
        if (M->bunny)
            rc = ttd_gen_mesh_copy(M->bunny, out);
        break;
    case MW_BUNNY_SUB3:
        if (M->bunny)
            rc = ttd_gen_subdivide(M->bunny, 3, out);
        break;
    case MW_TORUS_1M:
        rc = ttd_gen_torus(1.0, 0.35, 1000, 500, out);
        break;
    case MW_TORUS_SMALL:
        rc = ttd_gen_torus(1.0, 0.35, 40, 20, out);
        break;
    default:
        break;
    }
    if (rc == 0)
        rc = ttd_gen_normalize(out);
    if (rc)
        ttd_gen_mesh_free(out);
    return rc;
}

static float *to_float(const double *x, size_t n)
{
    float *f = malloc(n * sizeof *f + 1);
    if (f)
        for (size_t i = 0; i < n; ++i)
            f[i] = (float)x[i];
    return f;
}

/* ---- timing --------------------------------------------------------------------------- */

typedef int (*call_fn)(void *arg);

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Times fn as the pair rows are timed: a warm-up call, then samples of enough calls to last the
 * minimum sample time (at least 3 samples; fewer than asked when one call is long). per_call
 * divides the time (poses per call). Fills ms, ms_min, samples and passes of r; -1 when fn failed. */
static int time_call(const mctx *M, call_fn fn, void *arg, double per_call, mrow *r)
{
    bench_timing t;
    if (bench_time_call(fn, arg, M->min_s, M->max_row_s, M->env->st->samples, 0, &t) != 0)
        return -1;
    r->ms = t.med_s * 1e3 / per_call;
    r->ms_min = t.min_s * 1e3 / per_call;
    r->samples = t.samples;
    r->passes = t.passes;
    return 0;
}

/* The calls that are timed. */
enum { Q_BUILD_D, Q_DISTANCE, Q_COLLIDE, Q_CONTACTS_D, Q_CONTACTS_F, Q_CLOSEST };

typedef struct qarg {
    int kind;
    ttd_options o;
    const ttd_gen_mesh *g;     /* Q_BUILD_D */
    const ttd_mesh *a, *b;
    size_t k;
    const double *poses;
    const float *poses_f;
    double margin;
    ttd_mesh_result_d *dist;   /* k results */
    ttd_collision *col;        /* k results */
    ttd_contacts_d *cd;
    ttd_contacts_f *cf;
    ttd_closest_d *for_a, *for_b;
    ttd_status st;
} qarg;

static int call_query(void *p)
{
    qarg *q = p;
    switch (q->kind) {
    case Q_BUILD_D: {
        ttd_mesh *m = NULL;
        q->st = ttd_mesh_create_d(&q->o, q->g->verts, q->g->nv, q->g->tris, q->g->nt, &m);
        ttd_mesh_destroy(m);
        break;
    }
    case Q_DISTANCE:
        q->st = ttd_mesh_distance_d(&q->o, q->a, q->b, q->k, q->poses, BENCH_INF, 0.0, q->dist);
        break;
    case Q_COLLIDE:
        q->st = ttd_mesh_collide_d(&q->o, q->a, q->b, q->k, q->poses, q->margin, q->col);
        break;
    case Q_CONTACTS_D:
        q->st = ttd_mesh_contacts_d(&q->o, q->a, q->b, q->k, q->poses, q->margin, q->cd);
        break;
    case Q_CONTACTS_F:
        q->st = ttd_mesh_contacts_f(&q->o, q->a, q->b, q->k, q->poses_f, (float)q->margin, q->cf);
        break;
    default:
        q->st = ttd_mesh_closest_d(&q->o, q->a, q->b, q->k, q->poses, q->margin, q->for_a, q->for_b);
        break;
    }
    return q->st == TTD_OK ? 0 : -1;
}

static ttd_options options(const mctx *M, int threads)
{
    ttd_options o = ttd_default_options();
    o.isa = M->isa;
    o.threads = threads;
    return o;
}

/* Times one query call and fills the row; a failure is said and leaves the row's times NaN. */
static int time_query(mctx *M, qarg *q, mrow *r)
{
    if (time_call(M, call_query, q, (double)q->k, r) != 0) {
        fprintf(stderr, "ttd bench: mesh: %s %s %s failed: %s\n", r->workload, r->pose, r->query,
                ttd_status_string(q->st));
        snprintf(r->note, sizeof r->note, "failed: %s", ttd_status_string(q->st));
        return -1;
    }
    return 0;
}

/* ---- placements ----------------------------------------------------------------------- */

static double ttd_distance(const mctx *M, const ttd_mesh *a, const ttd_mesh *b, const double pose[12])
{
    ttd_options o = options(M, 0);
    ttd_mesh_result_d r;
    if (ttd_mesh_distance_d(&o, a, b, 1, pose, BENCH_INF, 0.0, &r) != TTD_OK)
        return BENCH_NAN;
    return r.distance;
}

/* Placement pl of b against a: ttd_gen_pose_gap(seed, stream) turns b and moves it along a
 * direction, both drawn from (seed, stream), the same for every placement of one workload, to a
 * slab gap g. For a target distance D the gap is bisected until ttd's minimum distance is within
 * 1% of D: g = D gives a distance >= D; lower gaps are tried (D minus 1, 2, 4, ... times the
 * excess) until one gives less, then the bracket is halved, at most 60 times. Overlap: gaps
 * -0.05, -0.1, -0.2, ... until ttd finds the meshes intersecting. Returns the distance, NaN when
 * no such pose was found (the pose is then the last one tried). */
static double place(const mctx *M, const ttd_gen_mesh *ga, const ttd_gen_mesh *gb, const ttd_mesh *a,
                    const ttd_mesh *b, uint64_t stream, int pl, double pose[12], int *evals)
{
    const uint64_t seed = M->env->st->seed;
    *evals = 0;
    if (pl == PL_OVERLAP) {
        for (double g = -0.05; g >= -1.0; g *= 2.0) {
            if (ttd_gen_pose_gap(ga, gb, seed, stream, NULL, g, pose))
                return BENCH_NAN;
            double d = ttd_distance(M, a, b, pose);
            ++*evals;
            if (d == 0.0)
                return d;
        }
        return BENCH_NAN;
    }
    const double D = pl_target[pl], tol = 0.01 * D;
    double hi = D, lo, d_lo;
    if (ttd_gen_pose_gap(ga, gb, seed, stream, NULL, hi, pose))
        return BENCH_NAN;
    double d_hi = ttd_distance(M, a, b, pose);
    ++*evals;
    if (!(d_hi >= D - tol))
        return BENCH_NAN; /* the slab gap bounds the distance from below: cannot happen */
    if (d_hi <= D + tol)
        return d_hi;
    double step = fmax(d_hi - D, 1e-3);
    for (;;) {
        lo = D - step;
        if (ttd_gen_pose_gap(ga, gb, seed, stream, NULL, lo, pose))
            return BENCH_NAN;
        d_lo = ttd_distance(M, a, b, pose);
        ++*evals;
        if (fabs(d_lo - D) <= tol)
            return d_lo;
        if (d_lo < D)
            break;
        hi = lo;
        if ((step *= 2.0) > 4.0)
            return BENCH_NAN;
    }
    for (int it = 0; it < 60; ++it) {
        double g = 0.5 * lo + 0.5 * hi;
        if (ttd_gen_pose_gap(ga, gb, seed, stream, NULL, g, pose))
            return BENCH_NAN;
        double d = ttd_distance(M, a, b, pose);
        ++*evals;
        if (fabs(d - D) <= tol)
            return d;
        if (d > D)
            hi = g;
        else
            lo = g;
    }
    return BENCH_NAN;
}

/* ---- FCL ------------------------------------------------------------------------------ */

/* Timed runs per pose for FCL: about budget seconds per pose if FCL were 10x slower than ttd's
 * ttd_ms, within [3, 1000]. */
static uint32_t fcl_reps(const mctx *M, double ttd_ms)
{
    double est = 10.0 * (isfinite(ttd_ms) && ttd_ms > 0.0 ? ttd_ms : 1.0) * 1e-3;
    double reps = ceil(M->fcl_budget_s / est);
    return (uint32_t)fmin(fmax(reps, 3.0), 1000.0);
}

/* Runs one FCL job; 0 on success. A failure is said on standard error (FCL's rows are then
 * left without FCL), not counted as a disagreement. */
static int fcl_run(mctx *M, const ttd_gen_mesh *g, const double *poses, size_t k, bench_fcl_mesh_query q,
                   uint32_t reps, double margin, int want_pairs, bench_fcl_mesh_result *out, const char *label)
{
    memset(out, 0, sizeof *out);
    if (!M->fcl_ok)
        return -1;
    bench_fcl_mesh_job job;
    memset(&job, 0, sizeof job);
    job.a.vertices = job.b.vertices = g->verts;
    job.a.nv = job.b.nv = g->nv;
    job.a.triangles = job.b.triangles = g->tris;
    job.a.nt = job.b.nt = g->nt;
    job.poses = poses;
    job.nposes = k;
    job.query = q;
    job.repetitions = reps;
    job.margin = margin;
    const char *qn = q == BENCH_FCL_MESH_DISTANCE ? "distance" : q == BENCH_FCL_MESH_COLLIDE ? "collide" : "pairs";
    if (g->nt >= 100000)
        progress(M, "%s: FCL %s: building two %zu-triangle OBBRSS trees, then %zu pose(s) x %u runs", label, qn, g->nt,
                 k, reps);
    int rc = bench_fcl_mesh_run(M->fcl_path, &job, want_pairs, out);
    if (rc != BENCH_FCL_MESH_OK) {
        fprintf(stderr, "ttd bench: mesh: FCL's %s on %s failed (%s); its columns are left empty\n", qn, label,
                out->error);
        bench_fcl_mesh_result_free(out);
        return -1;
    }
    progress(M, "%s: FCL %s done (build %.1f + %.1f ms)", label, qn, out->build_ms[0], out->build_ms[1]);
    return 0;
}

/* ---- pair sets ------------------------------------------------------------------------ */

typedef struct tpair {
    uint32_t a, b;
    double d;
} tpair;

static int cmp_tpair(const void *x, const void *y)
{
    const tpair *p = x, *q = y;
    if (p->a != q->a)
        return p->a < q->a ? -1 : 1;
    return (p->b > q->b) - (p->b < q->b);
}

typedef struct setcmp {
    size_t only_ttd, only_fcl, boundary; /* mismatches; boundary: within tol of the margin */
    double worst;                        /* max |d - d_fcl| over common pairs */
} setcmp;

/* Compares ttd's pairs (sorted here) with FCL's (sorted by the program). */
static setcmp compare_sets(tpair *t, size_t nt, const bench_fcl_mesh_pair *f, size_t nf, double margin, double tol)
{
    setcmp c = {0, 0, 0, 0.0};
    qsort(t, nt, sizeof *t, cmp_tpair);
    size_t i = 0, j = 0;
    while (i < nt || j < nf) {
        int order = i == nt ? 1 : j == nf ? -1
                                         : (t[i].a != f[j].ia ? (t[i].a < f[j].ia ? -1 : 1)
                                                              : (t[i].b > f[j].ib) - (t[i].b < f[j].ib));
        if (order == 0) {
            c.worst = fmax(c.worst, fabs(t[i].d - f[j].d));
            ++i;
            ++j;
        } else if (order < 0) {
            if (fabs(t[i].d - margin) <= tol)
                c.boundary++;
            else
                c.only_ttd++;
            ++i;
        } else {
            if (fabs(f[j].d - margin) <= tol)
                c.boundary++;
            else
                c.only_fcl++;
            ++j;
        }
    }
    return c;
}

/* ---- one mesh workload ---------------------------------------------------------------- */

static void set_ratio(mrow *r)
{
    if (r->fcl == FCL_OK && r->ms > 0.0 && r->fcl_ms > 0.0)
        r->x_fcl = r->fcl_ms / r->ms;
}

static double median_d(double *v, size_t n)
{
    qsort(v, n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* Build rows: ttd_mesh_create_d on one thread and on all threads; FCL's OBBRSS build (the median
 * of the builds its runs made) is filled in by the caller once the FCL runs are done. */
static void build_rows(mctx *M, const char *name, const ttd_gen_mesh *g, size_t nodes, mrow **rows, int *nrows)
{
    int counts[2] = {1, M->env->max_threads};
    *nrows = 0;
    for (int i = 0; i < 2; ++i) {
        if (i == 1 && counts[1] <= 1)
            break;
        if (g->nt >= 100000)
            progress(M, "%s: timing ttd's build of %zu triangles on %d thread(s)", name, g->nt, counts[i]);
        qarg q;
        memset(&q, 0, sizeof q);
        q.kind = Q_BUILD_D;
        q.o = options(M, counts[i]);
        q.g = g;
        q.k = 1;
        mrow *r = new_row(M, name, g->nt, "-", "build", 8, counts[i], 1);
        if (!r)
            return;
        if (time_call(M, call_query, &q, 1.0, r) != 0) {
            snprintf(r->note, sizeof r->note, "failed: %s", ttd_status_string(q.st));
            continue;
        }
        r->value = (double)nodes;
        snprintf(r->result, sizeof r->result, "%zu nodes", nodes);
        rows[(*nrows)++] = r;
        progress(M, "%s: build %d thread(s): %.2f ms", name, counts[i], r->ms);
    }
}

/* One mesh workload: the mesh, its two ttd trees (a and a copy b), the placements and what the FCL
 * runs report about their builds. */
typedef struct mjob {
    const char *name;
    int w;
    ttd_gen_mesh g;
    ttd_mesh *a, *b;
    double poses[PL_COUNT][12], pdist[PL_COUNT];
    mrow *dist[PL_COUNT];     /* the distance rows (the collide+m rows are checked against them) */
    double fcl_builds[8];     /* every build FCL's runs made of this mesh, ms */
    size_t nfb;
} mjob;

static qarg query_arg(const mctx *M, int kind, const ttd_mesh *a, const ttd_mesh *b, size_t k, const double *poses)
{
    qarg q;
    memset(&q, 0, sizeof q);
    q.kind = kind;
    q.o = options(M, 1);
    q.a = a;
    q.b = b;
    q.k = k;
    q.poses = poses;
    return q;
}

/* FCL's time and traversal counts for one pose into a row, and the ratio. */
static void fill_fcl(mrow *r, const bench_fcl_mesh_pose *p)
{
    r->fcl = FCL_OK;
    r->fcl_ms = p->median_ms;
    r->fcl_ms_min = p->min_ms;
    r->fcl_bv = (double)p->bv_tests;
    r->fcl_leaf = (double)p->leaf_tests;
    set_ratio(r);
}

static void keep_fcl_builds(mjob *J, const bench_fcl_mesh_result *fr)
{
    for (int i = 0; i < 2 && J->nfb < sizeof J->fcl_builds / sizeof J->fcl_builds[0]; ++i)
        J->fcl_builds[J->nfb++] = fr->build_ms[i];
}

static void placements(mctx *M, mjob *J)
{
    for (int pl = 0; pl < PL_COUNT; ++pl) {
        int evals;
        double d = place(M, &J->g, &J->g, J->a, J->b, (uint64_t)J->w, pl, J->poses[pl], &evals);
        if (!isfinite(d)) {
            d = ttd_distance(M, J->a, J->b, J->poses[pl]);
            fprintf(stderr, "ttd bench: mesh: %s: no %s placement found after %d distance queries; its rows use the "
                            "last pose tried (distance %.6g)\n",
                    J->name, pl_name[pl], evals, d);
        }
        J->pdist[pl] = d;
        progress(M, "%s: %s placement: distance %.6g after %d queries", J->name, pl_name[pl], d, evals);
    }
}

static void distance_rows(mctx *M, mjob *J)
{
    double dms[PL_COUNT];
    size_t ndms = 0;
    for (int pl = 0; pl < PL_COUNT; ++pl) {
        ttd_mesh_result_d res;
        qarg q = query_arg(M, Q_DISTANCE, J->a, J->b, 1, J->poses[pl]);
        q.dist = &res;
        mrow *r = J->dist[pl] = new_row(M, J->name, J->g.nt, pl_name[pl], "distance", 8, 1, 1);
        if (!r)
            return;
        r->pose_dist = J->pdist[pl];
        if (time_query(M, &q, r) == 0) {
            r->value = res.distance;
            snprintf(r->result, sizeof r->result, "%.9g", res.distance);
            r->pair_tests = (double)res.pair_tests;
            r->node_tests = (double)res.node_tests;
            dms[ndms++] = r->ms;
        }
    }
    bench_fcl_mesh_result fr;
    if (fcl_run(M, &J->g, &J->poses[0][0], PL_COUNT, BENCH_FCL_MESH_DISTANCE,
                fcl_reps(M, ndms ? median_d(dms, ndms) : 1.0), 0.0, 0, &fr, J->name) == 0) {
        keep_fcl_builds(J, &fr);
        for (int pl = 0; pl < PL_COUNT; ++pl) {
            mrow *r = J->dist[pl];
            const bench_fcl_mesh_pose *p = &fr.poses[pl];
            fill_fcl(r, p);
            r->fcl_value = p->distance;
            if (isfinite(r->value)) {
                r->diff = fabs(r->value - p->distance);
                M->R->compared++;
                M->R->worst_diff = fmax(M->R->worst_diff, r->diff);
                if (!(r->diff <= TOL_D))
                    alarm_(M, r, "ttd %.17g, FCL %.17g (difference %.3g > %g)", r->value, p->distance, r->diff, TOL_D);
            }
        }
        bench_fcl_mesh_result_free(&fr);
    }
    for (int pl = 0; pl < PL_COUNT; ++pl)
        progress(M, "%s %s distance: ttd %.4f ms, FCL %.4f ms", J->name, pl_name[pl], J->dist[pl]->ms,
                 J->dist[pl]->fcl_ms);
}

/* Collision with margin 0 (FCL's collide beside) and with COLLIDE_MARGIN (ttd only; its answer is
 * checked against the minimum distance, FCL's where measured). */
static void collide_rows(mctx *M, mjob *J)
{
    mrow *cr[PL_COUNT] = {NULL};
    double cms[PL_COUNT];
    size_t ncms = 0;
    for (int withm = 0; withm < 2; ++withm) {
        for (int pl = 0; pl < PL_COUNT; ++pl) {
            ttd_collision col;
            qarg q = query_arg(M, Q_COLLIDE, J->a, J->b, 1, J->poses[pl]);
            q.margin = withm ? COLLIDE_MARGIN : 0.0;
            q.col = &col;
            mrow *r = new_row(M, J->name, J->g.nt, pl_name[pl], withm ? "collide+m" : "collide", 8, 1, 1);
            if (!r)
                return;
            r->pose_dist = J->pdist[pl];
            r->margin = q.margin;
            if (!withm)
                cr[pl] = r;
            else
                r->fcl = FCL_NO_MARGIN;
            if (time_query(M, &q, r) != 0)
                continue;
            r->value = col.hit;
            snprintf(r->result, sizeof r->result, "%s", col.hit ? "hit" : "no");
            r->pair_tests = (double)col.pair_tests;
            r->node_tests = (double)col.node_tests;
            if (!withm) {
                cms[ncms++] = r->ms;
                continue;
            }
            snprintf(r->note, sizeof r->note, "FCL 0.7's collide has no margin");
            const mrow *d = J->dist[pl];
            double ref = d && d->fcl == FCL_OK ? d->fcl_value : d ? d->value : BENCH_NAN;
            if (isfinite(ref) && fabs(ref - COLLIDE_MARGIN) > TOL_D && (ref <= COLLIDE_MARGIN) != (col.hit != 0))
                alarm_(M, r, "collide with margin %g says %s, the minimum distance is %.17g", COLLIDE_MARGIN,
                       col.hit ? "hit" : "no", ref);
        }
    }
    bench_fcl_mesh_result fr;
    if (fcl_run(M, &J->g, &J->poses[0][0], PL_COUNT, BENCH_FCL_MESH_COLLIDE,
                fcl_reps(M, ncms ? median_d(cms, ncms) : 1.0), 0.0, 0, &fr, J->name) == 0) {
        keep_fcl_builds(J, &fr);
        for (int pl = 0; pl < PL_COUNT; ++pl) {
            mrow *r = cr[pl];
            const bench_fcl_mesh_pose *p = &fr.poses[pl];
            fill_fcl(r, p);
            r->fcl_value = p->collide;
            if (isfinite(r->value) && (r->value != 0.0) != (p->collide != 0))
                alarm_(M, r, "ttd says %s, FCL's collide %s", r->value != 0.0 ? "hit" : "no", p->collide ? "hit" : "no");
        }
        bench_fcl_mesh_result_free(&fr);
    }
}

/* Contacts within the workload's margin at the near placement in one precision: the timed row,
 * and the pairs (sorted later) for the comparison with FCL. The float trees are built here and
 * freed at once, and the contact set is freed as soon as its pairs are copied, so that the
 * 1M-triangle workload keeps its memory low while FCL runs. */
static mrow *contact_row(mctx *M, mjob *J, int bytes, tpair **pairs)
{
    const double margin = mws[J->w].contact_margin;
    ttd_mesh *af = NULL, *bf = NULL;
    float *vf = NULL, pose_f[12];
    ttd_contacts_d cd = {0};
    ttd_contacts_f cf = {0};
    *pairs = NULL;
    mrow *r = new_row(M, J->name, J->g.nt, "near", "contacts", bytes, 1, 1);
    if (!r)
        return NULL;
    r->pose_dist = J->pdist[PL_NEAR];
    r->margin = margin;
    qarg q = query_arg(M, bytes == 8 ? Q_CONTACTS_D : Q_CONTACTS_F, J->a, J->b, 1, J->poses[PL_NEAR]);
    q.margin = margin;
    q.cd = &cd;
    q.cf = &cf;
    if (bytes == 4) {
        ttd_options o = options(M, 0);
        for (int i = 0; i < 12; ++i)
            pose_f[i] = (float)J->poses[PL_NEAR][i];
        q.poses_f = pose_f;
        if (!(vf = to_float(J->g.verts, 3 * J->g.nv)) ||
            ttd_mesh_create_f(&o, vf, J->g.nv, J->g.tris, J->g.nt, &af) != TTD_OK ||
            ttd_mesh_create_f(&o, vf, J->g.nv, J->g.tris, J->g.nt, &bf) != TTD_OK) {
            snprintf(r->note, sizeof r->note, "failed: cannot build the float trees");
            goto done;
        }
        q.a = af;
        q.b = bf;
    }
    if (time_query(M, &q, r) != 0)
        goto done;
    size_t n = bytes == 8 ? cd.count : cf.count;
    r->value = (double)n;
    snprintf(r->result, sizeof r->result, "%zu pairs", n);
    tpair *t = *pairs = malloc((n ? n : 1) * sizeof *t);
    for (size_t i = 0; t && i < n; ++i) {
        t[i].a = bytes == 8 ? cd.pairs[i].tri_a : cf.pairs[i].tri_a;
        t[i].b = bytes == 8 ? cd.pairs[i].tri_b : cf.pairs[i].tri_b;
        t[i].d = bytes == 8 ? cd.pairs[i].distance : (double)cf.pairs[i].distance;
    }
    progress(M, "%s contacts %s: %zu pairs in %.3f ms", J->name, bytes == 8 ? "double" : "float", n, r->ms);
done:
    ttd_contacts_free_d(&cd);
    ttd_contacts_free_f(&cf);
    ttd_mesh_destroy(af);
    ttd_mesh_destroy(bf);
    free(vf);
    return r;
}

/* The per-triangle reduction at the same pose and margin, checked against the contact set td of
 * rd's n pairs: each triangle's closest distance is the least of its pairs'. */
static mrow *closest_row(mctx *M, mjob *J, const tpair *td, size_t n)
{
    const size_t nt = J->g.nt;
    ttd_closest_d *for_a = malloc(nt * sizeof *for_a), *for_b = malloc(nt * sizeof *for_b);
    double *near_a = NULL, *near_b = NULL;
    mrow *r = new_row(M, J->name, nt, "near", "closest", 8, 1, 1);
    if (!r || !for_a || !for_b)
        goto done;
    r->pose_dist = J->pdist[PL_NEAR];
    r->margin = mws[J->w].contact_margin;
    qarg q = query_arg(M, Q_CLOSEST, J->a, J->b, 1, J->poses[PL_NEAR]);
    q.margin = r->margin;
    q.for_a = for_a;
    q.for_b = for_b;
    if (time_query(M, &q, r) != 0)
        goto done;
    size_t with = 0;
    for (size_t i = 0; i < nt; ++i)
        with += (for_a[i].partner != UINT32_MAX) + (for_b[i].partner != UINT32_MAX);
    r->value = (double)with;
    snprintf(r->result, sizeof r->result, "%zu tris", with);
    snprintf(r->note, sizeof r->note, "triangles of a and b with a partner within the margin");
    if (td && (near_a = malloc(nt * sizeof *near_a)) && (near_b = malloc(nt * sizeof *near_b))) {
        for (size_t i = 0; i < nt; ++i)
            near_a[i] = near_b[i] = BENCH_INF;
        for (size_t i = 0; i < n; ++i) {
            near_a[td[i].a] = fmin(near_a[td[i].a], td[i].d);
            near_b[td[i].b] = fmin(near_b[td[i].b], td[i].d);
        }
        size_t bad = 0;
        for (size_t i = 0; i < nt; ++i)
            bad += (near_a[i] != for_a[i].distance) + (near_b[i] != for_b[i].distance);
        if (bad)
            alarm_(M, r, "%zu triangles' closest distance differs from the contact set's", bad);
    }
done:
    free(near_a);
    free(near_b);
    free(for_a);
    free(for_b);
    return r;
}

/* Contacts in double and float, the reduction, and FCL's traversal of its own trees collecting
 * the same pairs, compared set against set. */
static void contact_rows(mctx *M, mjob *J)
{
    const double margin = mws[J->w].contact_margin;
    tpair *sets[2] = {NULL, NULL};
    mrow *rows[2] = {NULL, NULL}, *rc = NULL;
    if (M->env->want_double)
        rows[0] = contact_row(M, J, 8, &sets[0]);
    if (M->env->want_float)
        rows[1] = contact_row(M, J, 4, &sets[1]);
    if (M->env->want_double)
        rc = closest_row(M, J, sets[0], rows[0] && isfinite(rows[0]->value) ? (size_t)rows[0]->value : 0);
    const mrow *timed = rows[0] && isfinite(rows[0]->ms) ? rows[0] : rows[1];
    bench_fcl_mesh_result fr;
    if ((rows[0] || rows[1]) && fcl_run(M, &J->g, J->poses[PL_NEAR], 1, BENCH_FCL_MESH_PAIRS,
                                        fcl_reps(M, timed ? timed->ms : 1.0), margin, 1, &fr, J->name) == 0) {
        keep_fcl_builds(J, &fr);
        const bench_fcl_mesh_pose *p = &fr.poses[0];
        for (int prec = 0; prec < 2; ++prec) {
            mrow *r = rows[prec];
            if (!r || !sets[prec])
                continue;
            fill_fcl(r, p);
            r->fcl_value = (double)p->pairs;
            double tol = prec ? TOL_F : TOL_D;
            setcmp c = compare_sets(sets[prec], (size_t)r->value, fr.pairs, fr.pair_start[1], margin, tol);
            r->diff = c.worst;
            if (c.only_ttd || c.only_fcl || !(c.worst <= tol))
                alarm_(M, r, "%zu pairs only in ttd's set, %zu only in FCL's (%" PRIu64 "), worst distance "
                             "difference %.3g",
                       c.only_ttd, c.only_fcl, p->pairs, c.worst);
            else if (c.boundary)
                snprintf(r->note, sizeof r->note, "FCL %" PRIu64 " pairs (double); %zu differ, all within %g of the margin",
                         p->pairs, c.boundary, tol);
            else
                snprintf(r->note, sizeof r->note, "the same pairs as FCL's %straversal", prec ? "(double) " : "");
            /* per pair found, the cost an output-bound query is judged by */
            size_t used = strlen(r->note);
            if (!r->disagree && r->value > 0.0 && p->pairs > 0)
                snprintf(r->note + used, sizeof r->note - used, "; per pair: ttd %.0f ns, FCL %.0f ns",
                         r->ms * 1e6 / r->value, r->fcl_ms * 1e6 / (double)p->pairs);
        }
        if (rc && isfinite(rc->ms)) {
            fill_fcl(rc, p);
            snprintf(rc->note, sizeof rc->note,
                     "triangles with a partner within the margin; FCL: its pair traversal (no reduction)");
        }
        bench_fcl_mesh_result_free(&fr);
    }
    free(sets[0]);
    free(sets[1]);
}

static void run_mesh(mctx *M, int w)
{
    mjob *J = calloc(1, sizeof *J);
    if (!J)
        return;
    J->name = mws[w].name;
    J->w = w;
    double t0 = bench_now();
    if (w == MW_TORUS_1M)
        progress(M, "%s: generating the torus (1,000,000 triangles)", J->name);
    if (make_mesh(M, w, &J->g) != 0) {
        if (w == MW_BUNNY || w == MW_BUNNY_SUB3)
            fprintf(stderr, "ttd bench: mesh: %s left out: the Stanford bunny is %s\n", J->name, M->R->bunny);
        else
            fprintf(stderr, "ttd bench: mesh: cannot make the %s mesh (out of memory?); left out\n", J->name);
        free(J);
        return;
    }
    progress(M, "%s: %zu triangles, %zu vertices, made in %.2f s; building ttd's two trees", J->name, J->g.nt,
             J->g.nv, bench_now() - t0);
    ttd_options ob = options(M, 0);
    if (ttd_mesh_create_d(&ob, J->g.verts, J->g.nv, J->g.tris, J->g.nt, &J->a) != TTD_OK ||
        ttd_mesh_create_d(&ob, J->g.verts, J->g.nv, J->g.tris, J->g.nt, &J->b) != TTD_OK) {
        fprintf(stderr, "ttd bench: mesh: cannot build the %s trees; left out\n", J->name);
        goto done;
    }
    mrow *build[2];
    int nbuild = 0;
    build_rows(M, J->name, &J->g, ttd_mesh_node_count(J->a), build, &nbuild);
    placements(M, J);
    distance_rows(M, J);
    collide_rows(M, J);
    contact_rows(M, J);
    /* FCL's build time: the median of every build its runs made of this mesh */
    for (int i = 0; i < nbuild && J->nfb > 0; ++i) {
        double v[8];
        memcpy(v, J->fcl_builds, J->nfb * sizeof *v);
        build[i]->fcl = FCL_OK;
        build[i]->fcl_ms = median_d(v, J->nfb);
        build[i]->fcl_ms_min = v[0];
        set_ratio(build[i]);
        snprintf(build[i]->note, sizeof build[i]->note, "FCL: BVHModel<OBBRSS>, median of %zu builds", J->nfb);
    }
done:
    ttd_mesh_destroy(J->a);
    ttd_mesh_destroy(J->b);
    ttd_gen_mesh_free(&J->g);
    free(J);
}

/* ---- many poses ----------------------------------------------------------------------- */

static void run_poses(mctx *M)
{
    const int quick = M->env->st->quick;
    const size_t k = quick ? POSES_QUICK : POSES_FULL;
    ttd_gen_mesh g;
    char name[16];
    int on_bunny = !quick && M->bunny;
    if (on_bunny ? ttd_gen_mesh_copy(M->bunny, &g) : make_mesh(M, MW_ICOSPHERE, &g)) {
        fprintf(stderr, "ttd bench: mesh: cannot make the mesh of the random poses; left out\n");
        return;
    }
    snprintf(name, sizeof name, "poses-%s", on_bunny ? "bunny" : "ico");
    if (!quick && !M->bunny)
        fprintf(stderr, "ttd bench: mesh: the bunny is missing: the random poses use the icosphere\n");
    double *poses = malloc(12 * k * sizeof *poses);
    ttd_mesh_result_d *res[3] = {malloc(k * sizeof(ttd_mesh_result_d)), malloc(k * sizeof(ttd_mesh_result_d)),
                                 malloc(k * sizeof(ttd_mesh_result_d))};
    ttd_mesh *a = NULL, *b = NULL;
    ttd_options ob = options(M, 0);
    if (!poses || !res[0] || !res[1] || !res[2] ||
        ttd_mesh_create_d(&ob, g.verts, g.nv, g.tris, g.nt, &a) != TTD_OK ||
        ttd_mesh_create_d(&ob, g.verts, g.nv, g.tris, g.nt, &b) != TTD_OK) {
        fprintf(stderr, "ttd bench: mesh: out of memory for the random poses; left out\n");
        goto done;
    }
    for (size_t i = 0; i < k; ++i)
        ttd_gen_pose(M->env->st->seed, 1000 + i, POSES_SCALE, poses + 12 * i);

    int counts[3] = {1, 2, M->env->max_threads};
    mrow *rows[3] = {NULL};
    for (int c = 0; c < 3; ++c) {
        if ((c == 1 && counts[1] > M->env->max_threads) || (c == 2 && counts[2] <= 2))
            continue;
        qarg q;
        memset(&q, 0, sizeof q);
        q.kind = Q_DISTANCE;
        q.o = options(M, counts[c]);
        q.a = a;
        q.b = b;
        q.k = k;
        q.poses = poses;
        q.dist = res[c];
        mrow *r = rows[c] = new_row(M, name, g.nt, "random", "distance", 8, counts[c], k);
        if (!r)
            continue;
        if (c == 1 && rows[0] && isfinite(rows[0]->ms)) {
            /* two threads over one timed alternately, as the scene's thread rows (scene_bench.c's
             * thread_ratio): the row's time from the two-thread samples */
            qarg one = q;
            one.o = options(M, 1);
            one.dist = res[0];
            bench_alternation alt;
            if (bench_time_alternating(call_query, &one, call_query, &q, 0, M->min_s, quick ? 3 : 5, 15,
                                       M->max_row_s, &alt) != 0) {
                snprintf(r->note, sizeof r->note, "failed: %s", ttd_status_string(one.st != TTD_OK ? one.st : q.st));
                continue;
            }
            r->ms = alt.b_med_s * 1e3 / (double)k;
            r->ms_min = alt.b_min_s * 1e3 / (double)k;
            r->samples = alt.rounds;
            r->passes = alt.passes[1];
            r->x_threads = alt.ratio_med;
            r->x_threads_lo = alt.ratio_lo;
            r->x_threads_hi = alt.ratio_hi;
            r->thread_rounds = alt.rounds;
        } else if (time_query(M, &q, r) != 0) {
            continue;
        }
        double pt = 0.0, nt = 0.0, dsum = 0.0;
        size_t hit = 0;
        for (size_t i = 0; i < k; ++i) {
            pt += (double)res[c][i].pair_tests;
            nt += (double)res[c][i].node_tests;
            dsum += res[c][i].distance;
            hit += res[c][i].distance == 0.0;
        }
        r->pair_tests = pt / (double)k;
        r->node_tests = nt / (double)k;
        r->value = dsum / (double)k;
        snprintf(r->result, sizeof r->result, "mean %.4g", r->value);
        snprintf(r->note, sizeof r->note, "%zu poses in one call, %zu intersecting; times per pose", k, hit);
        if (isfinite(r->x_threads)) {
            const size_t at = strlen(r->note);
            snprintf(r->note + at, sizeof r->note - at, "; 2 threads over 1 alternating: %.2fx (%d rounds, %.2f-%.2fx)"
                     "; rows timed apart %.2fx", r->x_threads, r->thread_rounds, r->x_threads_lo, r->x_threads_hi,
                     rows[0]->ms / r->ms);
        }
        if (c > 0 && rows[0] && isfinite(rows[0]->value)) {
            size_t differ = 0;
            for (size_t i = 0; i < k; ++i)
                differ += res[c][i].distance != res[0][i].distance || res[c][i].tri_a != res[0][i].tri_a ||
                          res[c][i].tri_b != res[0][i].tri_b;
            if (differ)
                alarm_(M, r, "%zu of %zu poses differ from the 1-thread call", differ, k);
        }
        progress(M, "%s: %zu poses on %d thread(s): %.4f ms per pose", name, k, counts[c], r->ms);
    }
    bench_fcl_mesh_result fr;
    if (rows[0] && fcl_run(M, &g, poses, k, BENCH_FCL_MESH_DISTANCE, 3, 0.0, 0, &fr, name) == 0) {
        double ms = 0.0, ms_min = 0.0, bv = 0.0, leaf = 0.0, worst = 0.0;
        size_t bad = 0, first_bad = 0;
        for (size_t i = 0; i < k; ++i) {
            const bench_fcl_mesh_pose *p = &fr.poses[i];
            ms += p->median_ms;
            ms_min += p->min_ms;
            bv += (double)p->bv_tests;
            leaf += (double)p->leaf_tests;
            double diff = fabs(res[0][i].distance - p->distance);
            if (!(diff <= TOL_D) && bad++ == 0)
                first_bad = i;
            worst = fmax(worst, diff);
            M->R->compared++;
        }
        M->R->worst_diff = fmax(M->R->worst_diff, worst);
        for (int c = 0; c < 3; ++c) {
            mrow *r = rows[c];
            if (!r || !isfinite(r->ms))
                continue;
            r->fcl = FCL_OK;
            r->fcl_ms = ms / (double)k;
            r->fcl_ms_min = ms_min / (double)k;
            r->fcl_bv = bv / (double)k;
            r->fcl_leaf = leaf / (double)k;
            r->diff = worst;
            set_ratio(r);
        }
        if (bad)
            alarm_(M, rows[0], "%zu of %zu poses differ by more than %g (first: pose %zu, ttd %.17g, FCL %.17g)", bad, k,
                   TOL_D, first_bad, res[0][first_bad].distance, fr.poses[first_bad].distance);
        bench_fcl_mesh_result_free(&fr);
    }
done:
    free(poses);
    for (int c = 0; c < 3; ++c)
        free(res[c]);
    ttd_mesh_destroy(a);
    ttd_mesh_destroy(b);
    ttd_gen_mesh_free(&g);
}

/* ---- targets -------------------------------------------------------------------------- */

static void set_target(target *t, const char *what, const char *need, double required)
{
    t->what = what;
    t->need = need;
    t->required = required;
    t->measured = BENCH_NAN;
    snprintf(t->where, sizeof t->where, "not measured in this run");
}

static int is_row(const mrow *r, const char *query, int bytes, int threads)
{
    return strcmp(r->query, query) == 0 && r->bytes == bytes && r->threads == threads;
}

static void evaluate_targets(bench_mesh_results *R, int fcl_ok)
{
    target *T = R->targets;
    /* issue 19's targets where it raised issue 9's; the build and collision ones are issue 9's */
    set_target(&T[T_DIST_EVERY], "minimum distance, every mesh workload", ">= 8x FCL", 8.0);
    set_target(&T[T_DIST_MEDIAN], "minimum distance, median over workloads", ">= 10x FCL", 10.0);
    set_target(&T[T_POSES], "1,000 random bunny poses, 1 thread", ">= 7x FCL", 7.0);
    set_target(&T[T_POSES_2T], "1,000 random bunny poses, 2 threads over 1", ">= 1.85x", 1.85);
    set_target(&T[T_CONTACTS_D], "contacts within a margin, double (worst mesh)", ">= 5x FCL's traversal", 5.0);
    set_target(&T[T_CONTACTS_F], "contacts within a margin, float (worst mesh)", ">= 8x FCL's traversal", 8.0);
    set_target(&T[T_BUILD], "tree build, 1M triangles, 1 thread", ">= 10x FCL's OBBRSS", 10.0);
    set_target(&T[T_COLLIDE], "collision, margin 0 (worst row)", "within 1.5x of FCL (x_fcl >= 0.67)", 1.0 / 1.5);
    if (!fcl_ok)
        for (int i = 0; i < T_COUNT; ++i)
            if (i != T_POSES_2T)
                snprintf(T[i].where, sizeof T[i].where, "n/a: FCL absent");

    double x[64];
    size_t nx = 0;
    const mrow *one = NULL, *two = NULL;
    for (size_t i = 0; i < R->n; ++i) {
        const mrow *r = &R->rows[i];
        const int placed = strcmp(r->pose, "random") != 0 && strcmp(r->pose, "-") != 0;
        if (is_row(r, "distance", 8, 1) && placed && isfinite(r->x_fcl)) {
            if (nx < 64)
                x[nx++] = r->x_fcl;
            if (!(r->x_fcl >= T[T_DIST_EVERY].measured)) {
                T[T_DIST_EVERY].measured = r->x_fcl;
                snprintf(T[T_DIST_EVERY].where, sizeof T[T_DIST_EVERY].where, "worst: %s %s", r->workload, r->pose);
            }
        }
        if (is_row(r, "distance", 8, 1) && strcmp(r->pose, "random") == 0) {
            one = r;
            if (isfinite(r->x_fcl)) {
                T[T_POSES].measured = r->x_fcl;
                snprintf(T[T_POSES].where, sizeof T[T_POSES].where, "%s, %zu poses%s", r->workload, r->poses,
                         strcmp(r->workload, "poses-bunny") ? " (not the bunny)" : "");
            }
        }
        if (is_row(r, "distance", 8, 2) && strcmp(r->pose, "random") == 0)
            two = r;
        for (int prec = 0; prec < 2; ++prec) {
            int t = prec ? T_CONTACTS_F : T_CONTACTS_D;
            if (is_row(r, "contacts", prec ? 4 : 8, 1) && isfinite(r->x_fcl) && !(r->x_fcl >= T[t].measured)) {
                T[t].measured = r->x_fcl;
                snprintf(T[t].where, sizeof T[t].where, "worst: %s, margin %g", r->workload, r->margin);
            }
        }
        if (is_row(r, "build", 8, 1) && strcmp(r->workload, "torus-1m") == 0 && isfinite(r->x_fcl)) {
            T[T_BUILD].measured = r->x_fcl;
            snprintf(T[T_BUILD].where, sizeof T[T_BUILD].where, "torus-1m");
        }
        if (is_row(r, "collide", 8, 1) && isfinite(r->x_fcl) && !(r->x_fcl >= T[T_COLLIDE].measured)) {
            T[T_COLLIDE].measured = r->x_fcl;
            snprintf(T[T_COLLIDE].where, sizeof T[T_COLLIDE].where, "worst: %s %s", r->workload, r->pose);
        }
    }
    if (nx) {
        T[T_DIST_MEDIAN].measured = median_d(x, nx);
        snprintf(T[T_DIST_MEDIAN].where, sizeof T[T_DIST_MEDIAN].where, "median of %zu rows", nx);
    }
    if (two && isfinite(two->x_threads)) {
        T[T_POSES_2T].measured = two->x_threads;
        snprintf(T[T_POSES_2T].where, sizeof T[T_POSES_2T].where, "%s: alternating, %d rounds %.2f-%.2fx",
                 two->workload, two->thread_rounds, two->x_threads_lo, two->x_threads_hi);
    } else if (one && two && one->ms > 0.0 && two->ms > 0.0) {
        T[T_POSES_2T].measured = one->ms / two->ms;
        snprintf(T[T_POSES_2T].where, sizeof T[T_POSES_2T].where, "%s: 1 thread / 2 threads", one->workload);
    }
    /* the build row with all threads, beside the 1-thread target */
    for (size_t i = 0; i < R->n; ++i) {
        const mrow *r = &R->rows[i];
        if (strcmp(r->query, "build") == 0 && r->threads > 1 && strcmp(r->workload, "torus-1m") == 0 &&
            isfinite(r->x_fcl) && isfinite(T[T_BUILD].measured)) {
            size_t used = strlen(T[T_BUILD].where);
            snprintf(T[T_BUILD].where + used, sizeof T[T_BUILD].where - used, " (%.1fx on %d threads)", r->x_fcl,
                     r->threads);
        }
    }
}

/* ---- the run -------------------------------------------------------------------------- */

bench_mesh_results *bench_mesh_run(const bench_mesh_config *c, const bench_mesh_env *env)
{
    bench_mesh_results *R = calloc(1, sizeof *R);
    if (R && !(R->rows = calloc(MAX_MESH_ROWS, sizeof *R->rows))) {
        free(R);
        R = NULL;
    }
    if (!R)
        return NULL;
    R->cap = MAX_MESH_ROWS;
    mctx M;
    memset(&M, 0, sizeof M);
    M.env = env;
    M.R = R;
    R->quick = env->st->quick;
    /* what the library picks by itself, unless --isa ruled it out: then the best one allowed */
    M.isa = ttd_isa_selected(NULL);
    if (!(env->isa_mask & (1u << M.isa)))
        M.isa = bench_best_isa(env->isa_mask) == TTD_ISA_AUTO ? TTD_ISA_SCALAR : bench_best_isa(env->isa_mask);
    snprintf(R->isa, sizeof R->isa, "%s", ttd_isa_name(M.isa));
    M.min_s = env->st->min_sample_s;
    M.max_row_s = env->st->quick ? 0.2 : 3.0;
    M.fcl_budget_s = env->st->quick ? 0.01 : 0.25;

    unsigned want = c->named;
    if (!want)
        for (int i = 0; i < MW_COUNT; ++i)
            if (env->st->quick ? mws[i].in_quick : mws[i].in_full)
                want |= 1u << i;
    R->ran = want;

    if (env->no_fcl) {
        snprintf(R->fcl, sizeof R->fcl, "left out (--no-fcl)");
    } else if (bench_fcl_mesh_find(c->fcl_mesh[0] ? c->fcl_mesh : NULL, M.fcl_path, sizeof M.fcl_path) ==
               BENCH_FCL_MESH_OK) {
        M.fcl_ok = 1;
        snprintf(R->fcl, sizeof R->fcl, "%s", M.fcl_path);
    } else {
        snprintf(R->fcl, sizeof R->fcl,
                 "%s not found (%s; FCL found when ttd was built gives it: apt-get install libfcl-dev and rebuild)",
                 c->fcl_mesh[0] ? c->fcl_mesh : BENCH_FCL_MESH_PROGRAM,
                 c->fcl_mesh[0] ? "--fcl-mesh" : "$" BENCH_FCL_MESH_ENV " or next to ttd");
        fprintf(stderr, "ttd bench: mesh: FCL's program %s: the mesh rows go without FCL\n", R->fcl);
    }

    ttd_gen_mesh bunny;
    memset(&bunny, 0, sizeof bunny);
    int bunny_needed = (want & ((1u << MW_BUNNY) | (1u << MW_BUNNY_SUB3))) || ((want & (1u << MW_POSES)) && !R->quick);
    if (bunny_needed) {
        if (bench_mesh_load_bunny(c, &bunny, R->bunny, sizeof R->bunny) == 0) {
            M.bunny = &bunny;
        } else {
            fprintf(stderr, "ttd bench: mesh: the Stanford bunny is %s: the bunny workloads are left out\n", R->bunny);
        }
    } else {
        snprintf(R->bunny, sizeof R->bunny, "not used in this run");
    }

    progress(&M, "%s, FCL %s", R->isa, M.fcl_ok ? "beside" : "absent");
    for (int w = 0; w < MW_COUNT; ++w) {
        if (!(want & (1u << w)))
            continue;
        if (w == MW_POSES)
            run_poses(&M);
        else
            run_mesh(&M, w);
    }
    evaluate_targets(R, M.fcl_ok);
    ttd_gen_mesh_free(&bunny);
    return R;
}

size_t bench_mesh_row_count(const bench_mesh_results *r) { return r ? r->n : 0; }

void bench_mesh_free(bench_mesh_results *r)
{
    if (!r)
        return;
    free(r->rows);
    free(r);
}

/* ---- writers -------------------------------------------------------------------------- */

static const char *num(char *buf, size_t size, double v, const char *fmt)
{
    if (!isfinite(v))
        snprintf(buf, size, "%s", isinf(v) ? "inf" : "-");
    else
        snprintf(buf, size, fmt, v);
    return buf;
}

/* ms with three significant digits, or "-" */
static const char *ms_str(char *buf, size_t size, double v)
{
    return num(buf, size, v, v >= 100.0 ? "%.0f" : "%.3g");
}

static const char *fcl_state(const mrow *r)
{
    return r->fcl == FCL_NO_MARGIN ? "no margin" : r->fcl == FCL_OK ? NULL : "-";
}

static const char *verdict(const target *t)
{
    if (!isfinite(t->measured))
        return "n/a";
    return t->measured >= t->required ? "met" : "MISSED";
}

void bench_mesh_write_table(FILE *f, const bench_mesh_results *R)
{
    if (!R)
        return;
    char b[12][40];
    fprintf(f, "\nMesh queries (issue 9): ttd (%s, exact kernel) against FCL 0.7 BVHModel<OBBRSS> on the same meshes "
               "and poses%s\n",
            R->isa, R->quick ? " (--quick: small generated meshes, few poses)" : "");
    fprintf(f, "meshes normalised to a bounding-box diagonal of 1, each against a copy of itself; times are per query "
               "(per pose), the median of samples as above; FCL: median of its timed runs per pose\n");
    for (int i = 0; i < MW_COUNT; ++i)
        if (R->ran & (1u << i))
            fprintf(f, "  %-12s %s\n", mws[i].name, mws[i].what);
    fprintf(f, "bunny: %s\nFCL mesh program: %s\n", R->bunny, R->fcl);
    fprintf(f, "\n%-12s %7s %-7s %8s %-9s %-6s %3s %6s %-14s %9s %9s %8s %9s %9s %9s %7s %8s  %s\n", "workload", "tris",
            "pose", "d_pose", "query", "prec", "thr", "margin", "result", "ms", "pairs_t", "nodes_t", "fcl_ms", "fcl_bv",
            "fcl_leaf", "x_fcl", "diff", "note");
    const char *last = "";
    for (size_t i = 0; i < R->n; ++i) {
        const mrow *r = &R->rows[i];
        if (strcmp(last, r->workload) != 0 && i > 0)
            fputc('\n', f);
        last = r->workload;
        const char *fs = fcl_state(r);
        fprintf(f, "%-12s %7zu %-7s %8s %-9s %-6s %3d %6s %-14s %9s %9s %8s %9s %9s %9s %7s %8s  %s\n", r->workload,
                r->tris, r->pose, num(b[0], 40, r->pose_dist, "%.4g"), r->query, r->bytes == 8 ? "double" : "float",
                r->threads, num(b[1], 40, r->margin, "%g"), r->result, ms_str(b[2], 40, r->ms),
                num(b[3], 40, r->pair_tests, "%.0f"), num(b[4], 40, r->node_tests, "%.0f"),
                fs ? fs : ms_str(b[5], 40, r->fcl_ms), fs ? "-" : num(b[6], 40, r->fcl_bv, "%.0f"),
                fs ? "-" : num(b[7], 40, r->fcl_leaf, "%.0f"), num(b[8], 40, r->x_fcl, "%.2f"),
                num(b[9], 40, r->diff, "%.2g"), r->note);
    }
    fprintf(f, "\nmesh columns: d_pose = ttd's minimum distance at the placement (far 1, near 0.01, contact 0.002 of the "
               "size, each within 1%%; overlap 0); result = distance, collision (hit/no), pairs within the margin, "
               "triangles with a partner (closest), or tree nodes (build); pairs_t = triangle pairs ttd gave the exact "
               "kernel; nodes_t = ttd's node tests (one box against up to 8); fcl_bv, fcl_leaf = FCL's bounding-volume "
               "pair tests and triangle pair tests; x_fcl = FCL's time / ttd's; diff = worst |d - d_fcl| (distance), "
               "or of the distances of common pairs (contacts). Contacts and closest report no traversal counts.\n");
    fprintf(f, "ttd against FCL: %zu distances compared, worst difference %s (tolerance %g of the size); %zu "
               "disagreement(s)\n",
            R->compared, num(b[0], 40, R->compared ? R->worst_diff : BENCH_NAN, "%.3g"), TOL_D, R->disagreements);
    for (size_t i = 0; i < R->nalarms; ++i)
        fprintf(f, "  DISAGREEMENT: %s\n", R->alarms[i]);
    fprintf(f, "\nmesh targets, issues 9 and 19 (ratios of this run%s; the benchmark measures, it does not fail on them):\n",
            R->quick ? ", --quick: small meshes, not the issue's workloads" : "");
    for (int i = 0; i < T_COUNT; ++i) {
        const target *t = &R->targets[i];
        char slower[64] = "";
        if (i != T_POSES_2T) /* every other target is a ratio over FCL */
            bench_slower_note(slower, sizeof slower, t->measured, "FCL");
        fprintf(f, "  %-48s %-36s measured %7s  %-6s  %s%s%s\n", t->what, t->need, num(b[0], 40, t->measured, "%.2fx"),
                verdict(t), t->where, slower[0] ? "; " : "", slower);
    }
}

static void json_num(FILE *f, const char *key, double v, const char *fmt)
{
    fprintf(f, ", \"%s\": ", key);
    if (isfinite(v))
        fprintf(f, fmt, v);
    else
        fputs("null", f);
}

void bench_mesh_write_json(FILE *f, const bench_mesh_results *R)
{
    if (!R) {
        fputs("null", f);
        return;
    }
    fprintf(f, "{\"quick\": %s, \"isa\": ", R->quick ? "true" : "false");
    bench_json_string(f, R->isa);
    fputs(", \"bunny\": ", f);
    bench_json_string(f, R->bunny);
    fputs(", \"fcl\": ", f);
    bench_json_string(f, R->fcl);
    fprintf(f, ", \"distances_compared\": %zu", R->compared);
    json_num(f, "worst_distance_difference", R->compared ? R->worst_diff : BENCH_NAN, "%.6g");
    fprintf(f, ", \"distance_tolerance\": %g, \"disagreements\": %zu,\n    \"rows\": [\n", TOL_D, R->disagreements);
    for (size_t i = 0; i < R->n; ++i) {
        const mrow *r = &R->rows[i];
        fputs("      {\"workload\": ", f);
        bench_json_string(f, r->workload);
        fprintf(f, ", \"triangles\": %zu, \"pose\": ", r->tris);
        bench_json_string(f, r->pose);
        fputs(", \"query\": ", f);
        bench_json_string(f, r->query);
        fprintf(f, ", \"precision\": \"%s\", \"threads\": %d, \"poses\": %zu", r->bytes == 8 ? "double" : "float",
                r->threads, r->poses);
        json_num(f, "pose_distance", r->pose_dist, "%.17g");
        json_num(f, "margin", r->margin, "%.17g");
        fputs(", \"result\": ", f);
        bench_json_string(f, r->result);
        json_num(f, "value", r->value, "%.17g");
        json_num(f, "ms", r->ms, "%.6g");
        json_num(f, "ms_min", r->ms_min, "%.6g");
        fprintf(f, ", \"samples\": %d, \"passes\": %ld", r->samples, r->passes);
        json_num(f, "pair_tests", r->pair_tests, "%.6g");
        json_num(f, "node_tests", r->node_tests, "%.6g");
        fprintf(f, ", \"fcl\": \"%s\"",
                r->fcl == FCL_OK ? "measured" : r->fcl == FCL_NO_MARGIN ? "no margin in FCL 0.7" : "none");
        json_num(f, "fcl_ms", r->fcl_ms, "%.6g");
        json_num(f, "fcl_ms_min", r->fcl_ms_min, "%.6g");
        json_num(f, "fcl_bv_tests", r->fcl_bv, "%.6g");
        json_num(f, "fcl_leaf_tests", r->fcl_leaf, "%.6g");
        json_num(f, "fcl_value", r->fcl_value, "%.17g");
        json_num(f, "speedup_vs_fcl", r->x_fcl, "%.6g");
        json_num(f, "diff", r->diff, "%.6g");
        json_num(f, "x_threads", r->x_threads, "%.6g");
        json_num(f, "x_threads_lo", r->x_threads_lo, "%.6g");
        json_num(f, "x_threads_hi", r->x_threads_hi, "%.6g");
        fprintf(f, ", \"thread_rounds\": %d", r->thread_rounds);
        fprintf(f, ", \"disagree\": %s, \"note\": ", r->disagree ? "true" : "false");
        bench_json_string(f, r->note);
        fprintf(f, "}%s\n", i + 1 < R->n ? "," : "");
    }
    fputs("    ],\n    \"targets\": [\n", f);
    for (int i = 0; i < T_COUNT; ++i) {
        const target *t = &R->targets[i];
        fputs("      {\"target\": ", f);
        bench_json_string(f, t->what);
        fputs(", \"need\": ", f);
        bench_json_string(f, t->need);
        json_num(f, "required", t->required, "%.6g");
        json_num(f, "measured", t->measured, "%.6g");
        fprintf(f, ", \"verdict\": \"%s\", \"where\": ", verdict(t));
        bench_json_string(f, t->where);
        fprintf(f, "}%s\n", i + 1 < T_COUNT ? "," : "");
    }
    fputs("    ]}", f);
}

static void csv_num(FILE *f, double v, const char *fmt)
{
    fputc(',', f);
    if (isfinite(v))
        fprintf(f, fmt, v);
}

void bench_mesh_write_csv(FILE *f, const bench_mesh_results *R)
{
    fputs("workload,triangles,pose,pose_distance,query,precision,threads,poses,margin,value,ms,ms_min,pair_tests,"
          "node_tests,fcl_ms,fcl_ms_min,fcl_bv_tests,fcl_leaf_tests,speedup_vs_fcl,diff,disagree,x_threads,"
          "x_threads_lo,x_threads_hi,thread_rounds\n",
          f);
    for (size_t i = 0; R && i < R->n; ++i) {
        const mrow *r = &R->rows[i];
        fprintf(f, "%s,%zu,%s", r->workload, r->tris, r->pose);
        csv_num(f, r->pose_dist, "%.9g");
        fprintf(f, ",%s,%s,%d,%zu", r->query, r->bytes == 8 ? "double" : "float", r->threads, r->poses);
        csv_num(f, r->margin, "%g");
        csv_num(f, r->value, "%.9g");
        csv_num(f, r->ms, "%.6g");
        csv_num(f, r->ms_min, "%.6g");
        csv_num(f, r->pair_tests, "%.6g");
        csv_num(f, r->node_tests, "%.6g");
        csv_num(f, r->fcl_ms, "%.6g");
        csv_num(f, r->fcl_ms_min, "%.6g");
        csv_num(f, r->fcl_bv, "%.6g");
        csv_num(f, r->fcl_leaf, "%.6g");
        csv_num(f, r->x_fcl, "%.6g");
        csv_num(f, r->diff, "%.3g");
        fprintf(f, ",%d", r->disagree);
        csv_num(f, r->x_threads, "%.6g");
        csv_num(f, r->x_threads_lo, "%.6g");
        csv_num(f, r->x_threads_hi, "%.6g");
        fprintf(f, ",%d\n", r->thread_rounds);
    }
}
