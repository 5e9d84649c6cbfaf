/* SPDX-License-Identifier: MIT */
/* `ttd bench ccd --rigid`: continuous collision of rigid meshes between two poses (ttd_mesh_ccd_rigid_d)
 * on generated motions of tori, a sphere and the bunny (when found), beside FCL 0.7's
 * continuous collision (conservative advancement, CCDM_LINEAR: the same motion; on RSS trees, the
 * ones it answers on, and on OBBRSS trees, on which FCL 0.7 finds no contact; through
 * bench/fcl/fcl_ccd_bench.cpp), and a scene's step (ttd_scene_ccd_d) on 1 and 2 threads.
 * Times are process CPU time, the fastest of --reps runs over all the motions of a row. */
#define _POSIX_C_SOURCE 200809L
#include "ccd_rigid_bench.h"

#include <math.h>
#include <spawn.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "bench_internal.h"
#include "mesh_bench.h"
#include "meshes.h"
#include "ttd/ttd.h"

extern char **environ;

static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static uint64_t rng = 0x853c49e6748fea9bull;
static double urand(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (double)(rng >> 11) * 0x1p-53;
}
static void unit(double u[3])
{
    double n;
    do {
        for (int i = 0; i < 3; ++i)
            u[i] = 2 * urand() - 1;
        n = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    } while (n < 0.1 || n > 1);
    for (int i = 0; i < 3; ++i)
        u[i] /= n;
}
/* Rot(u, a) R as a pose with translation t. */
static void pose_of(const double u[3], double a, const double R[9], const double t[3], double P[12])
{
    const double c = cos(a), s = sin(a), k = 1 - c;
    const double q[9] = {c + k * u[0] * u[0],        k * u[0] * u[1] - s * u[2], k * u[0] * u[2] + s * u[1],
                         k * u[1] * u[0] + s * u[2], c + k * u[1] * u[1],        k * u[1] * u[2] - s * u[0],
                         k * u[2] * u[0] - s * u[1], k * u[2] * u[1] + s * u[0], c + k * u[2] * u[2]};
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j)
            P[4 * i + j] = q[3 * i] * R[j] + q[3 * i + 1] * R[3 + j] + q[3 * i + 2] * R[6 + j];
        P[4 * i + 3] = t[i];
    }
}

/* k motions of two bodies of size about `size` (a bounding radius): a turns in place by up to
 * 0.9 pi about a random axis; b, turning likewise, passes from 3 sizes away on one side to 1 on
 * the other, offset sideways by up to 3.2 sizes: about half meet. 48 reals a motion. */
static void make_motions(size_t k, double size, double *m)
{
    const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    for (size_t i = 0; i < k; ++i) {
        double *p = m + 48 * i, u[3], v[3], d[3], s[3], R[9], P[12];
        unit(u);
        pose_of(u, 3.0 * urand(), I, (double[3]){0, 0, 0}, P); /* a random start */
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
                R[3 * r + c] = P[4 * r + c];
        const double z[3] = {0, 0, 0};
        pose_of(u, 0, R, z, p);
        unit(v);
        pose_of(v, 0.9 * 3.14159265358979 * urand(), R, z, p + 12);
        unit(d);
        unit(s);
        const double off = 3.2 * size * urand();
        double b0[3], b1[3];
        for (int c = 0; c < 3; ++c) {
            b0[c] = 3 * size * d[c] + off * s[c];
            b1[c] = -1 * size * d[c] + off * s[c];
        }
        unit(u);
        pose_of(u, 3.0 * urand(), I, z, P);
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
                R[3 * r + c] = P[4 * r + c];
        pose_of(u, 0, R, b0, p + 24);
        unit(v);
        pose_of(v, 0.9 * 3.14159265358979 * urand(), R, b1, p + 36);
    }
}

/* FCL's program on the same meshes and motions: for OBBRSS trees (w = 0) and RSS trees (w = 1),
 * hit and time of contact per motion (hit[w k + i]) and the CPU time. 0, or -1 where it could
 * not run. */
static int fcl_run(const char *program, const ttd_gen_mesh *a, const ttd_gen_mesh *b, size_t k, const double *m,
                   int reps, int *hit, double *toc, double cpu[2], double build[2])
{
    char job[] = "/tmp/ttd-ccd-rigid-jobXXXXXX", ans[] = "/tmp/ttd-ccd-rigid-ansXXXXXX";
    const int fj = mkstemp(job), fa = mkstemp(ans);
    if (fj < 0 || fa < 0)
        return -1;
    close(fa);
    FILE *f = fdopen(fj, "wb");
    int rc = f == NULL ? -1 : 0;
    if (rc == 0) {
        const int32_t r = reps;
        fwrite(&r, 4, 1, f);
        const ttd_gen_mesh *g[2] = {a, b};
        for (int w = 0; w < 2; ++w) {
            const uint64_t nv = g[w]->nv, nt = g[w]->nt;
            fwrite(&nv, 8, 1, f);
            fwrite(&nt, 8, 1, f);
            fwrite(g[w]->verts, 8, 3 * nv, f);
            fwrite(g[w]->tris, 4, 3 * nt, f);
        }
        const uint64_t kk = k;
        fwrite(&kk, 8, 1, f);
        fwrite(m, 8, 48 * k, f);
        rc = fclose(f) == 0 ? 0 : -1;
    }
    pid_t pid;
    char prog[1024];
    snprintf(prog, sizeof prog, "%s", program);
    char *argv[] = {prog, job, ans, NULL};
    int status = 0;
    if (rc == 0 && (posix_spawn(&pid, program, NULL, NULL, argv, environ) != 0 || waitpid(pid, &status, 0) < 0 ||
                    !WIFEXITED(status) || WEXITSTATUS(status) != 0))
        rc = -1;
    f = rc == 0 ? fopen(ans, "rb") : NULL;
    if (f != NULL) {
        for (size_t w = 0; w < 2 && rc == 0; ++w) {
            for (size_t i = 0; i < k && rc == 0; ++i) {
                int32_t h;
                if (fread(&h, 4, 1, f) != 1 || fread(&toc[w * k + i], 8, 1, f) != 1)
                    rc = -1;
                hit[w * k + i] = h;
            }
            if (rc == 0 && (fread(&cpu[w], 8, 1, f) != 1 || fread(&build[w], 8, 1, f) != 1))
                rc = -1;
        }
        fclose(f);
    } else {
        rc = -1;
    }
    unlink(job);
    unlink(ans);
    return rc;
}

/* The truth on one motion, independently of both answers: the exact distance at 4,097 times of
 * the motion (ttd_rigid_pose_at_d, ttd_mesh_distance_d) and how fast it can change (each body's
 * |T1 - T0| + theta r, theta from R1 R0^T's trace). 1: a sample touches (contact); 0: every
 * interval between samples is proved apart; -1: neither. */
static int sampled_truth(const ttd_mesh *m, double size, const double *mo)
{
    enum { N = 4096 };
    double V = 0;
    for (int w = 0; w < 2; ++w) {
        const double *p0 = mo + 24 * w, *p1 = p0 + 12;
        double tr = 0, d2 = 0;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                tr += i == j ? p1[4 * i] * p0[4 * j] + p1[4 * i + 1] * p0[4 * j + 1] + p1[4 * i + 2] * p0[4 * j + 2] : 0;
        for (int i = 0; i < 3; ++i)
            d2 += (p1[4 * i + 3] - p0[4 * i + 3]) * (p1[4 * i + 3] - p0[4 * i + 3]);
        const double c = fmax(-1, fmin(1, (tr - 1) / 2));
        V += sqrt(d2) + (acos(c) + 1e-6) * size;
    }
    V *= 1.001;
    double prev = 0;
    int apart = 1;
    for (int s = 0; s <= N; ++s) {
        const double t = (double)s / N;
        double pa[12], pb[12], rel[12];
        ttd_rigid_pose_at_d(mo, mo + 12, t, pa);
        ttd_rigid_pose_at_d(mo + 24, mo + 36, t, pb);
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j)
                rel[4 * i + j] = pa[i] * pb[j] + pa[4 + i] * pb[4 + j] + pa[8 + i] * pb[8 + j];
            rel[4 * i + 3] = pa[i] * (pb[3] - pa[3]) + pa[4 + i] * (pb[7] - pa[7]) + pa[8 + i] * (pb[11] - pa[11]);
        }
        ttd_mesh_result_d r;
        if (ttd_mesh_distance_d(NULL, m, m, 1, rel, INFINITY, 0, &r) != TTD_OK)
            return -1;
        if (r.distance <= 1e-12 * size)
            return 1;
        if (s > 0 && (prev + r.distance - V / N) / 2 <= 0)
            apart = 0;
        prev = r.distance;
    }
    return apart ? 0 : -1;
}

/* One row: k motions of the pair (a, b), ttd and FCL. */
static int rigid_row(const char *name, const ttd_gen_mesh *g, size_t k, int reps, const char *fcl)
{
    ttd_options o = ttd_default_options();
    o.threads = 1;
    ttd_mesh *m = NULL;
    if (ttd_mesh_create_d(&o, g->verts, g->nv, g->tris, g->nt, &m) != TTD_OK)
        return -1;
    double size = 0;
    for (size_t i = 0; i < g->nv; ++i) {
        const double *x = g->verts + 3 * i;
        size = fmax(size, sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]));
    }
    double *mo = malloc(48 * k * sizeof *mo), *toi = malloc(k * sizeof *toi), *toc = malloc(2 * k * sizeof *toc);
    int *hit = malloc(k * sizeof *hit), *fhit = malloc(2 * k * sizeof *fhit);
    if (!mo || !toi || !toc || !hit || !fhit)
        return -1;
    make_motions(k, size, mo);
    double best = INFINITY;
    uint64_t steps = 0;
    uint32_t most = 0;
    int rc = 0;
    for (int r = 0; r < reps && rc == 0; ++r) {
        steps = 0;
        most = 0;
        const double c0 = cpu_now();
        for (size_t i = 0; i < k; ++i) {
            ttd_mesh_ccd_rigid_result res;
            if (ttd_mesh_ccd_rigid_d(&o, m, mo + 48 * i, m, mo + 48 * i + 24, 0, &res) != TTD_OK) {
                rc = -1;
                break;
            }
            hit[i] = (int)res.hit;
            toi[i] = res.toi;
            steps += res.steps;
            most = res.steps > most ? res.steps : most;
        }
        best = fmin(best, cpu_now() - c0);
    }
    int hits = 0;
    for (size_t i = 0; i < k; ++i)
        hits += hit[i];
    printf("%-26s %7zu %6zu %5d %9.1f %6u %10.3f", name, g->nt, k, hits, (double)steps / (double)k, most,
           best * 1e3 / (double)k);
    double fcpu[2] = {0, 0}, fbuild[2] = {0, 0};
    if (rc == 0 && fcl != NULL && fcl_run(fcl, g, g, k, mo, reps, fhit, toc, fcpu, fbuild) == 0) {
        int fh[2] = {0, 0}, only_ttd = 0, only_fcl = 0;
        double worst = 0;
        for (size_t i = 0; i < k; ++i) {
            fh[0] += fhit[i];
            fh[1] += fhit[k + i];
            only_ttd += hit[i] && !fhit[k + i];
            only_fcl += !hit[i] && fhit[k + i];
            if (hit[i] && fhit[k + i])
                worst = fmax(worst, fabs(toi[i] - toc[k + i]));
        }
        /* Each motion where ttd and FCL (RSS) disagree, settled by sampling: who was right. */
        int ttd_right = 0, fcl_right = 0, open = 0;
        for (size_t i = 0; i < k; ++i)
            if (hit[i] != fhit[k + i]) {
                const int truth = sampled_truth(m, size, mo + 48 * i);
                ttd_right += truth >= 0 && truth == hit[i];
                fcl_right += truth >= 0 && truth == fhit[k + i];
                open += truth < 0;
            }
        printf(" | %5d %10.3f %7.2fx | %4d %4d %9.2g | %3d %3d %3d | %5d\n", fh[1], fcpu[1] * 1e3 / (double)k,
               fcpu[1] / best, only_ttd, only_fcl, worst, ttd_right, fcl_right, open, fh[0]);
    } else {
        printf(" | %s\n", fcl == NULL ? "FCL: not run" : "FCL: failed");
    }
    free(mo);
    free(toi);
    free(toc);
    free(hit);
    free(fhit);
    ttd_mesh_destroy(m);
    return rc;
}

/* One scene step on the threads of o, for bench_time_alternating. */
typedef struct step_arg {
    ttd_options o;
    ttd_scene *s;
    size_t n;
    const double *p1;
    ttd_scene_array out;
} step_arg;

static int step_call(void *p)
{
    step_arg *a = p;
    return ttd_scene_ccd_d(&a->o, a->s, a->n, a->p1, 0, &a->out) == TTD_OK ? 0 : -1;
}

/* A scene's step: n small spheres and tori in a box 10 wide, each moving up to 1 and turning up
 * to 0.9 pi; ttd_scene_ccd_d on 1 and 2 threads (CPU time on 1, wall time on 2), then two
 * threads over one timed alternately (as `ttd bench`'s scene rows, docs/benchmark.md). */
static int scene_row(size_t n, int reps)
{
    ttd_gen_mesh g[2];
    if (ttd_gen_icosphere(2, &g[0]) != 0 || ttd_gen_torus(0.35, 0.12, 24, 12, &g[1]) != 0)
        return -1;
    for (size_t i = 0; i < 3 * g[0].nv; ++i)
        g[0].verts[i] *= 0.4;
    ttd_mesh *m[2] = {NULL, NULL};
    ttd_scene *s = NULL;
    if (ttd_mesh_create_d(NULL, g[0].verts, g[0].nv, g[0].tris, g[0].nt, &m[0]) != TTD_OK ||
        ttd_mesh_create_d(NULL, g[1].verts, g[1].nv, g[1].tris, g[1].nt, &m[1]) != TTD_OK ||
        ttd_scene_create_d(&s) != TTD_OK)
        return -1;
    double *p1 = malloc(12 * n * sizeof *p1);
    if (p1 == NULL)
        return -1;
    const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    for (size_t i = 0; i < n; ++i) {
        double u[3], v[3], t0[3], t1[3], P[12], R[9];
        unit(u);
        for (int c = 0; c < 3; ++c)
            t0[c] = 10 * urand();
        pose_of(u, 3.0 * urand(), I, t0, P);
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
                R[3 * r + c] = P[4 * r + c];
        uint32_t id;
        if (ttd_scene_add_d(s, m[i % 2], P, &id) != TTD_OK)
            return -1;
        unit(v);
        for (int c = 0; c < 3; ++c)
            t1[c] = t0[c] + (2 * urand() - 1);
        pose_of(v, 0.9 * 3.14159265358979 * urand(), R, t1, p1 + 12 * i);
    }
    for (int threads = 1; threads <= 2; ++threads) {
        ttd_options o = ttd_default_options();
        o.threads = threads;
        double best_c = INFINITY, best_w = INFINITY;
        ttd_scene_array out = {0};
        for (int r = 0; r < reps; ++r) {
            const double c0 = cpu_now(), w0 = bench_now();
            if (ttd_scene_ccd_d(&o, s, n, p1, 0, &out) != TTD_OK)
                return -1;
            best_c = fmin(best_c, cpu_now() - c0);
            best_w = fmin(best_w, bench_now() - w0);
        }
        ttd_scene_stats st;
        ttd_scene_get_stats(s, &st);
        printf("scene step, %zu bodies (320 and 576 triangles), %d thread%s: %llu candidate pairs, %zu hit; "
               "%.2f ms CPU, %.2f ms wall\n",
               n, threads, threads > 1 ? "s" : "", (unsigned long long)st.body_pairs, out.count, best_c * 1e3,
               best_w * 1e3);
        ttd_scene_array_free(&out);
    }
    step_arg a1 = {ttd_default_options(), s, n, p1, {0}}, a2 = a1;
    a1.o.threads = 1;
    a2.o.threads = 2;
    bench_alternation alt;
    const int bad = bench_time_alternating(step_call, &a1, step_call, &a2, 0, 0.0, 3, 15, 2.0, &alt);
    ttd_scene_array_free(&a1.out);
    ttd_scene_array_free(&a2.out);
    if (bad)
        return -1;
    printf("scene step, %zu bodies: two threads over one, alternating: %.2fx (%d rounds, %.2f-%.2fx)\n", n,
           alt.ratio_med, alt.rounds, alt.ratio_lo, alt.ratio_hi);
    free(p1);
    ttd_scene_destroy(s);
    ttd_mesh_destroy(m[0]);
    ttd_mesh_destroy(m[1]);
    ttd_gen_mesh_free(&g[0]);
    ttd_gen_mesh_free(&g[1]);
    return 0;
}

int bench_ccd_rigid_main(int argc, char **argv)
{
    int reps = 3, use_fcl = 1;
    size_t k = 100, bodies = 400;
    const char *fcl_path = NULL;
    bench_mesh_config mc;
    memset(&mc, 0, sizeof mc);
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--rigid") == 0)
            continue;
        if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc)
            reps = atoi(argv[++i]) > 0 ? atoi(argv[i]) : 1;
        else if (strcmp(argv[i], "--motions") == 0 && i + 1 < argc)
            k = (size_t)(atol(argv[++i]) > 0 ? atol(argv[i]) : 1);
        else if (strcmp(argv[i], "--bodies") == 0 && i + 1 < argc)
            bodies = (size_t)(atol(argv[++i]) > 1 ? atol(argv[i]) : 2);
        else if (strcmp(argv[i], "--bunny") == 0 && i + 1 < argc)
            snprintf(mc.bunny, sizeof mc.bunny, "%s", argv[++i]);
        else if (strcmp(argv[i], "--fcl-ccd") == 0 && i + 1 < argc)
            fcl_path = argv[++i];
        else if (strcmp(argv[i], "--no-fcl") == 0)
            use_fcl = 0;
        else {
            printf("usage: ttd bench ccd --rigid [--reps N] [--motions K] [--bodies N] [--bunny PATH]\n"
                   "                             [--fcl-ccd PROGRAM | --no-fcl]\n"
                   "  rigid bodies between two poses: K motions of each pair (default 100), ttd_mesh_ccd_rigid_d\n"
                   "  beside FCL 0.7's continuous collision (ttd_fcl_ccd_bench beside ttd, $TTD_FCL_CCD_BENCH, or\n"
                   "  --fcl-ccd), CPU time, the fastest of N runs (default 3); then a scene's step of N bodies\n"
                   "  (default 400) through ttd_scene_ccd_d on 1 and 2 threads.\n");
            return strcmp(argv[i], "--help") == 0 ? 0 : 2;
        }
    }
    bench_machine mach;
    bench_machine_describe(&mach);
    char fcl[1024] = "";
    const int have_fcl =
        use_fcl && bench_fcl_find_program("ttd_fcl_ccd_bench", "TTD_FCL_CCD_BENCH", fcl_path, fcl, sizeof fcl) == 0;
    printf("ttd bench ccd --rigid: %s, %d cores, load %s, one thread, CPU time, fastest of %d runs\n", mach.cpu,
           mach.cores, mach.load_start, reps);
    printf("FCL: %s\n", have_fcl ? fcl
                                 : use_fcl ? "skipped: ttd_fcl_ccd_bench not found beside ttd (built when CMake finds "
                                             "FCL: apt-get install libfcl-dev)"
                                           : "skipped (--no-fcl)");
    printf("each motion: body a turns in place by up to 0.9 pi, body b (the same mesh) turns likewise and passes "
           "from 3 radii away to 1 on the other side, offset up to 3.2 radii; min_separation 0\n");
    printf("\n%-26s %7s %6s %5s %9s %6s %10s | %5s %10s %8s | %4s %4s %9s | %3s %3s %3s | %5s\n",
           "pair (same mesh twice)", "tris", "motions", "hits", "steps", "most", "ms/motion", "hits", "ms/motion",
           "fcl/ttd", "ttd", "fcl", "max|dtoi|", "ttd", "fcl", "?", "hits");
    printf("%-26s %7s %6s %5s %9s %6s %10s | %-26s | %-24s | %-11s | %s\n", "", "", "", "ttd", "mean", "", "ttd",
           "FCL (CA, RSS)", "hit only in (ttd, RSS)", "right (4097", "FCL OBBRSS");
    printf("%-26s %7s %6s %5s %9s %6s %10s | %-26s | %-24s | %-11s |\n", "", "", "", "", "", "", "", "", "",
           " samples)");
    ttd_gen_mesh g;
    int rc = 0;
    struct {
        const char *name;
        int kind;
    } rows[] = {{"icosphere level 3", 0}, {"torus 48 x 24", 1}, {"torus 128 x 64", 2}, {"bunny", 3}};
    for (size_t r = 0; r < sizeof rows / sizeof rows[0] && rc == 0; ++r) {
        char what[1600] = "";
        int made = rows[r].kind == 0   ? ttd_gen_icosphere(3, &g)
                   : rows[r].kind == 1 ? ttd_gen_torus(1.0, 0.3, 48, 24, &g)
                   : rows[r].kind == 2 ? ttd_gen_torus(1.0, 0.3, 128, 64, &g)
                                       : bench_mesh_load_bunny(&mc, &g, what, sizeof what);
        if (made != 0) {
            printf("%-26s skipped: %s\n", rows[r].name, what);
            continue;
        }
        rc = rigid_row(rows[r].name, &g, k, reps, have_fcl ? fcl : NULL);
        ttd_gen_mesh_free(&g);
    }
    printf("\n");
    if (rc == 0)
        rc = scene_row(bodies, reps);
    char load_end[64];
    bench_load_average(load_end, sizeof load_end);
    printf("\nload at the end %s\n", load_end);
    return rc != 0;
}
