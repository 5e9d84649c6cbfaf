/* SPDX-License-Identifier: MIT */
/* `ttd bench`'s mesh distance rows outside the bench, for callgrind and A/B timings of two library
 * builds (docs/kernel-speed.md section 7): the icosphere and the bunny against a copy of
 * themselves at the bench's far, near, contact and overlap placements (bench/mesh_bench.c's
 * `place`, seed 1, stream = the workload's index), and the bench's 1,000 random bunny poses.
 *   gcc -O2 -Iinclude -I. bench/meshdist/mesh_dist_poses.c build/gen/libttd_gen.a \
 *       build/src/libttd.a -lm -lpthread -o mesh_dist_poses
 *   ./mesh_dist_poses BUNNY.obj place FILE        the 8 placements' poses (%a) into FILE
 *   ./mesh_dist_poses BUNNY.obj digest FILE       every result's bits, a line each: the 8 rows, each
 *                                                 placement's direction at 65 gaps from -0.1 to 0.1,
 *                                                 the 1,000 random poses of both meshes (also in
 *                                                 float, the mesh against itself), and 2,592
 *                                                 poses with many pairs at one distance
 *   ./mesh_dist_poses BUNNY.obj time FILE ROWS N  N queries of each row in ROWS (0-7, e.g. 0123),
 *                                                 CPU seconds of each row
 * One thread; the ISA from TTD_ISA. */
#define _POSIX_C_SOURCE 200809L
#include "gen/meshes.h"
#include "ttd/meshfile.h"
#include "ttd/ttd.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static ttd_options opts(void)
{
    ttd_options o = ttd_default_options();
    o.threads = 1;
    return o;
}

static double dist(const ttd_mesh *a, const ttd_mesh *b, const double pose[12])
{
    ttd_options o = opts();
    ttd_mesh_result_d r;
    if (ttd_mesh_distance_d(&o, a, b, 1, pose, INFINITY, 0.0, &r) != TTD_OK)
        return NAN;
    return r.distance;
}

/* bench/mesh_bench.c's place(), seed 1 */
static double place(const ttd_gen_mesh *g, const ttd_mesh *a, const ttd_mesh *b, uint64_t stream, int pl,
                    double pose[12])
{
    static const double target[4] = {1.0, 0.01, 0.002, 0.0};
    const uint64_t seed = 1;
    if (pl == 3) {
        for (double gg = -0.05; gg >= -1.0; gg *= 2.0) {
            if (ttd_gen_pose_gap(g, g, seed, stream, NULL, gg, pose))
                return NAN;
            if (dist(a, b, pose) == 0.0)
                return 0.0;
        }
        return NAN;
    }
    const double D = target[pl], tol = 0.01 * D;
    double hi = D, lo;
    if (ttd_gen_pose_gap(g, g, seed, stream, NULL, hi, pose))
        return NAN;
    double d_hi = dist(a, b, pose);
    if (d_hi <= D + tol)
        return d_hi;
    double step = fmax(d_hi - D, 1e-3);
    for (;;) {
        lo = D - step;
        ttd_gen_pose_gap(g, g, seed, stream, NULL, lo, pose);
        double d_lo = dist(a, b, pose);
        if (fabs(d_lo - D) <= tol)
            return d_lo;
        if (d_lo < D)
            break;
        hi = lo;
        if ((step *= 2.0) > 4.0)
            return NAN;
    }
    for (int it = 0; it < 60; ++it) {
        double gg = 0.5 * lo + 0.5 * hi;
        ttd_gen_pose_gap(g, g, seed, stream, NULL, gg, pose);
        double d = dist(a, b, pose);
        if (fabs(d - D) <= tol)
            return d;
        if (d > D)
            hi = gg;
        else
            lo = gg;
    }
    return NAN;
}

static void print_result(const char *tag, const ttd_mesh_result_d *r)
{
    printf("%s %a %u %u %d %d %a %a %a %a %a %a %u %llu %llu\n", tag, r->distance, r->tri_a, r->tri_b,
           (int)r->feature_a, (int)r->feature_b, r->p[0], r->p[1], r->p[2], r->q[0], r->q[1], r->q[2],
           (unsigned)r->flags, (unsigned long long)r->node_tests, (unsigned long long)r->pair_tests);
}

/* The query, or the program stops: a failed query must not print a stale result. */
static void query(const ttd_options *o, const ttd_mesh *a, const ttd_mesh *b, const double pose[12],
                  ttd_mesh_result_d *r)
{
    const ttd_status st = ttd_mesh_distance_d(o, a, b, 1, pose, INFINITY, 0.0, r);
    if (st != TTD_OK) {
        fprintf(stderr, "mesh_dist_poses: ttd_mesh_distance_d failed (status %d)\n", (int)st);
        exit(1);
    }
}

static double cpu(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int main(int argc, char **argv)
{
    if (argc < 4)
        return 2;
    ttd_gen_mesh g[2];
    memset(g, 0, sizeof g);
    ttd_meshfile mf;
    char err[256];
    if (ttd_gen_icosphere(3, &g[0]) || ttd_gen_normalize(&g[0]))
        return 1;
    if (ttd_meshfile_read(argv[1], 0, &mf, err, sizeof err) != 0) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    ttd_gen_mesh view = {mf.verts, mf.nv, mf.tris, mf.nt};
    if (ttd_gen_mesh_copy(&view, &g[1]) || ttd_gen_normalize(&g[1]))
        return 1;
    ttd_mesh *a[2], *b[2];
    ttd_options o = opts();
    for (int w = 0; w < 2; ++w)
        if (ttd_mesh_create_d(&o, g[w].verts, g[w].nv, g[w].tris, g[w].nt, &a[w]) != TTD_OK ||
            ttd_mesh_create_d(&o, g[w].verts, g[w].nv, g[w].tris, g[w].nt, &b[w]) != TTD_OK)
            return 1;
    double poses[8][12];
    if (strcmp(argv[2], "place") == 0) {
        FILE *f = fopen(argv[3], "w");
        if (!f) {
            fprintf(stderr, "mesh_dist_poses: cannot write %s\n", argv[3]);
            return 1;
        }
        for (int w = 0; w < 2; ++w)
            for (int pl = 0; pl < 4; ++pl) {
                double d = place(&g[w], a[w], b[w], (uint64_t)w, pl, poses[4 * w + pl]);
                fprintf(stderr, "row %d: distance %.9g\n", 4 * w + pl, d);
                for (int k = 0; k < 12; ++k)
                    fprintf(f, "%a%c", poses[4 * w + pl][k], k == 11 ? '\n' : ' ');
            }
        fclose(f);
        return 0;
    }
    FILE *f = fopen(argv[3], "r");
    if (!f)
        return 1;
    for (int i = 0; i < 8; ++i)
        for (int k = 0; k < 12; ++k)
            if (fscanf(f, "%la", &poses[i][k]) != 1)
                return 1;
    fclose(f);
    ttd_mesh_result_d r;
    if (strcmp(argv[2], "digest") == 0) {
        char tag[64];
        for (int i = 0; i < 8; ++i) {
            query(&o, a[i / 4], b[i / 4], poses[i], &r);
            snprintf(tag, sizeof tag, "row%d", i);
            print_result(tag, &r);
            /* the same direction and rotation, other gaps: more ties and near misses */
            for (int s = 0; s <= 64; ++s) {
                double p[12];
                ttd_gen_pose_gap(&g[i / 4], &g[i / 4], 1, (uint64_t)(i / 4), NULL, -0.1 + 0.02 * s * s / 64.0, p);
                query(&o, a[i / 4], b[i / 4], p, &r);
                snprintf(tag, sizeof tag, "row%d.gap%d", i, s);
                print_result(tag, &r);
            }
        }
        ttd_mesh *af[2];
        for (int w = 0; w < 2; ++w) {
            float *v = malloc(3 * g[w].nv * sizeof *v);
            for (size_t i = 0; v && i < 3 * g[w].nv; ++i)
                v[i] = (float)g[w].verts[i];
            if (!v || ttd_mesh_create_f(&o, v, g[w].nv, g[w].tris, g[w].nt, &af[w]) != TTD_OK)
                return 1;
            free(v);
        }
        for (int i = 0; i < 1000; ++i) {
            double p[12];
            float pf[12];
            ttd_gen_pose(1, 1000 + (uint64_t)i, 0.5, p);
            for (int k = 0; k < 12; ++k)
                pf[k] = (float)p[k];
            for (int w = 0; w < 2; ++w) {
                query(&o, a[w], b[w], p, &r);
                snprintf(tag, sizeof tag, "random%d.%d", w, i);
                print_result(tag, &r);
                /* float: the same walk compiled in single precision */
                ttd_mesh_result_f rf;
                ttd_mesh_distance_f(&o, af[w], af[w], 1, pf, INFINITY, 0.0f, &rf);
                printf("float%d.%d %a %u %u %d %d %a %a %a %a %a %a %u %u %llu\n", w, i, (double)rf.distance, rf.tri_a,
                       rf.tri_b, (int)rf.feature_a, (int)rf.feature_b, (double)rf.p[0], (double)rf.p[1], (double)rf.p[2],
                       (double)rf.q[0], (double)rf.q[1], (double)rf.q[2], (unsigned)rf.flags, (unsigned)rf.node_tests,
                       (unsigned long long)rf.pair_tests);
            }
        }
        /* ties: a grid over a copy of itself, an icosphere and a cube beside copies, moved without
         * a turn or by quarter turns about z, so that many pairs lie at one distance */
        ttd_gen_mesh tg[3];
        memset(tg, 0, sizeof tg);
        if (ttd_gen_grid(12, &tg[0]) || ttd_gen_icosphere(2, &tg[1]) || ttd_gen_mesh_cube(&tg[2]))
            return 1;
        for (int w = 0; w < 3; ++w) {
            ttd_mesh *m;
            if (ttd_mesh_create_d(&o, tg[w].verts, tg[w].nv, tg[w].tris, tg[w].nt, &m) != TTD_OK)
                return 1;
            static const double dz[6] = {0.0, 0x1p-20, 0.001, 0.25, 1.0, 3.0};
            for (int q = 0; q < 4; ++q)
                for (int i = 0; i < 6; ++i)
                    for (int j = 0; j < 6; ++j)
                        for (int z = 0; z < 6; ++z) {
                            const double c = q == 0 ? 1 : q == 2 ? -1 : 0, sn = q == 1 ? 1 : q == 3 ? -1 : 0;
                            const double p[12] = {c, -sn, 0, i / 12.0 + (w ? 1.0 : 0.0), sn, c, 0, j / 24.0, 0, 0, 1,
                                                  dz[z]};
                            query(&o, m, m, p, &r);
                            snprintf(tag, sizeof tag, "tie%d.%d.%d.%d.%d", w, q, i, j, z);
                            print_result(tag, &r);
                        }
            ttd_mesh_destroy(m);
        }
        return 0;
    }
    if (strcmp(argv[2], "time") == 0 && argc >= 6) {
        const long n = atol(argv[5]);
        for (const char *c = argv[4]; *c; ++c) {
            const int i = *c - '0';
            const double t0 = cpu();
            for (long k = 0; k < n; ++k)
                query(&o, a[i / 4], b[i / 4], poses[i], &r);
            printf("row%d %.6f us %llu nodes %llu pairs\n", i, (cpu() - t0) / (double)n * 1e6,
                   (unsigned long long)r.node_tests, (unsigned long long)r.pair_tests);
        }
        return 0;
    }
    return 2;
}
