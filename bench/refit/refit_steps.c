/* SPDX-License-Identifier: MIT */
/* N refits of `ttd bench`'s twisted torus (deform_bench.c's twist: 0.3 radian along x and 2%
 * stretch, then back, in turn) with nothing else between them: for perf, callgrind and A/B
 * timings of two library builds (refit_ab.sh). One thread; the ISA from TTD_ISA.
 *   gcc -O2 -Iinclude -I. bench/refit/refit_steps.c build/gen/libttd_gen.a build/src/libttd.a \
 *       -lm -lpthread -o refit_steps
 *   ./refit_steps NU REFITS   (2 NU (NU / 2) triangles: 100 -> 10k, 316 -> 100k, 1000 -> 1M)
 *   ./refit_steps NU REFITS build   (a build of the moved torus before each refit, as `ttd bench`
 *       alternates them: the refit then starts with caches full of the build's data; prints the
 *       median CPU time of a refit and of a build, the calling thread's)
 * callgrind: TTD_ISA=avx2 valgrind --tool=callgrind --toggle-collect=ttd_mesh_refit ./refit_steps 316 4 */
#include "gen/meshes.h"
#include "ttd/ttd.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double cpu_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return 1e3 * (double)ts.tv_sec + 1e-6 * (double)ts.tv_nsec;
}

static int cmp(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

int main(int argc, char **argv)
{
    if (argc != 3 && !(argc == 4 && strcmp(argv[3], "build") == 0))
        return fprintf(stderr, "usage: refit_steps NU REFITS [build]\n"), 2;
    const int builds = argc == 4;
    const size_t nu = (size_t)atoi(argv[1]);
    const int reps = atoi(argv[2]);
    ttd_gen_mesh g;
    if (nu < 4 || ttd_gen_torus(1.0, 0.3, nu, nu / 2, &g) != 0)
        return 1;
    double *mv = malloc(3 * g.nv * sizeof *mv), lo[3], hi[3];
    if (mv == NULL)
        return 1;
    ttd_gen_mesh_bounds(&g, lo, hi);
    for (size_t i = 0; i < g.nv; ++i) {
        const double *x = g.verts + 3 * i, a = 0.3 * (x[0] - lo[0]) / (hi[0] - lo[0]);
        mv[3 * i] = 1.02 * x[0];
        mv[3 * i + 1] = x[1] * cos(a) - x[2] * sin(a);
        mv[3 * i + 2] = x[1] * sin(a) + x[2] * cos(a);
    }
    ttd_options o = ttd_default_options();
    o.threads = 1;
    ttd_mesh *m;
    if (ttd_mesh_create_d(&o, g.verts, g.nv, g.tris, g.nt, &m) != TTD_OK)
        return 1;
    double *tr = malloc((reps > 0 ? (size_t)reps : 1) * 2 * sizeof *tr), *tb = tr + (reps > 0 ? reps : 1);
    if (tr == NULL)
        return 1;
    for (int k = 0; k < reps; ++k) {
        const double *to = k % 2 ? g.verts : mv;
        if (builds) {
            ttd_mesh *fresh;
            const double t0 = cpu_ms();
            if (ttd_mesh_create_d(&o, to, g.nv, g.tris, g.nt, &fresh) != TTD_OK)
                return 1;
            tb[k] = cpu_ms() - t0;
            ttd_mesh_destroy(fresh);
        }
        const double t0 = cpu_ms();
        if (ttd_mesh_set_vertices_d(&o, m, to) != TTD_OK)
            return 1;
        tr[k] = cpu_ms() - t0;
    }
    if (builds && reps > 0) {
        qsort(tr, (size_t)reps, sizeof *tr, cmp);
        qsort(tb, (size_t)reps, sizeof *tb, cmp);
        printf("%zu triangles: refit %.3f ms, build %.3f ms (CPU, medians of %d), %.2fx\n", g.nt, tr[reps / 2],
               tb[reps / 2], reps, tb[reps / 2] / tr[reps / 2]);
    } else {
        printf("%zu\n", g.nt);
    }
    free(tr);
    ttd_mesh_destroy(m);
    free(mv);
    ttd_gen_mesh_free(&g);
    return 0;
}
