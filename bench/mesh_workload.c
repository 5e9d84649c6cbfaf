/* SPDX-License-Identifier: MIT */
/* The benchmark's mesh pair workloads (see mesh_workload.h): the mesh, the poses at a chosen distance,
 * the candidate pairs of each pose (gen/mesh_pairs.h), and the timing of the exact kernel on
 * them. The kernel is called through the engine's row table (engine/dispatch.h), block by block
 * as the engine calls it, because the public API asks for neither points alone nor a bound.
 *
 * A pose from ttd_gen_pose_gap puts the copies' extents along a direction `distance` apart,
 * but their true distance is usually larger (the two supporting points need not face each
 * other). So the pose's translation is corrected: measure the copies' distance (exact method
 * over the candidates at a margin that is known to hold the closest pair), move the copy along
 * the closest pair's direction by the difference, and repeat until the distance is right. */
#include "mesh_workload.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_internal.h"
#include "core/kernels.h"
#include "engine/dispatch.h"
#include "mesh_pairs.h"
#include <ttd/meshfile.h>
#include "ttd/ttd.h"

int bench_cand_mesh_load(const char *path, int levels, ttd_gen_mesh *fine, ttd_gen_mesh *coarse, char *desc,
                         size_t descsize)
{
    memset(fine, 0, sizeof *fine);
    memset(coarse, 0, sizeof *coarse);
    char why[300] = "no mesh file given";
    const char *base = NULL;
    if (path) {
        ttd_meshfile mf;
        char err[256];
        if (ttd_meshfile_read(path, 0, &mf, err, sizeof err) == 0) {
            const ttd_gen_mesh in = {mf.verts, mf.nv, mf.tris, mf.nt};
            base = strrchr(path, '/');
            base = base ? base + 1 : path;
            if (ttd_gen_mesh_copy(&in, coarse) != 0)
                snprintf(why, sizeof why, "out of memory for %s", base);
            ttd_meshfile_free(&mf);
        } else {
            snprintf(why, sizeof why, "%s", err);
        }
    }
    if (!coarse->nt && ttd_gen_icosphere(3, coarse) != 0)
        return -1;
    /* Flat subdivision keeps the surface and the bounding box (the midpoints lie inside it), so
     * both copies normalise with the same transform and the coarse mesh has the fine one's
     * distances: poses are placed on the coarse one. */
    if (ttd_gen_subdivide(coarse, levels, fine) != 0 || ttd_gen_normalize(coarse) != 0 ||
        ttd_gen_normalize(fine) != 0) {
        ttd_gen_mesh_free(fine);
        ttd_gen_mesh_free(coarse);
        return -1;
    }
    if (base)
        snprintf(desc, descsize, "%s (%zu triangles) subdivided %d times: %zu triangles", base, coarse->nt, levels,
                 fine->nt);
    else
        snprintf(desc, descsize, "icosphere level 3 (%zu triangles) subdivided flat %d times: %zu triangles (%s)",
                 coarse->nt, levels, fine->nt, why);
    return 0;
}

/* The closest pair of candidates (largest margin first needed: doubled until the closest pair
 * found lies within it, which proves no pair outside the candidates is closer). Scalar exact
 * method, so the workload does not depend on the machine. */
static int copies_distance(const ttd_gen_mesh *a, const ttd_gen_mesh *b, double guess, double *d, double p[3],
                           double q[3])
{
    double mg = guess > 0 ? guess : 1e-3;
    for (int tries = 0; tries < 40; ++tries, mg *= 2) {
        uint32_t *pairs = NULL;
        size_t n = 0;
        if (ttd_gen_mesh_pairs(a, b, mg, (size_t)50000000, &pairs, &n) != 0)
            return -1;
        if (n == 0) {
            free(pairs);
            continue;
        }
        double *s = malloc(9 * n * sizeof *s), *t = malloc(9 * n * sizeof *t);
        ttd_result_d *r = malloc(n * sizeof *r);
        int rc = -1;
        if (s && t && r) {
            ttd_gen_mesh_pair_coords(a, b, pairs, n, s, t);
            ttd_options o = ttd_default_options();
            o.isa = TTD_ISA_SCALAR;
            if (ttd_batch_d(&o, n, s, t, NULL, r) == TTD_OK) {
                size_t best = 0;
                for (size_t i = 1; i < n; ++i)
                    if (r[i].distance < r[best].distance)
                        best = i;
                *d = r[best].distance;
                memcpy(p, r[best].p, sizeof r[best].p);
                memcpy(q, r[best].q, sizeof r[best].q);
                rc = *d <= mg ? 0 : 1;
            }
        }
        free(s);
        free(t);
        free(r);
        free(pairs);
        if (rc <= 0)
            return rc;
    }
    return -1;
}

/* Pose i: ttd_gen_pose_gap's rotation, the translation corrected until the copies' distance is
 * `distance` to 0.1%. */
static int place(const ttd_gen_mesh *m, double distance, uint64_t seed, uint64_t i, double pose[12])
{
    if (ttd_gen_pose_gap(m, m, seed, i, NULL, distance, pose) != 0)
        return -1;
    ttd_gen_mesh b = {NULL, 0, NULL, 0};
    double guess = distance;
    for (int it = 0; it < 30; ++it) {
        double d, p[3], q[3];
        if (ttd_gen_mesh_transform(m, pose, &b) != 0 || copies_distance(m, &b, guess, &d, p, q) != 0)
            break;
        ttd_gen_mesh_free(&b);
        if (fabs(d - distance) <= 1e-3 * distance)
            return 0;
        double dir[3];
        if (d > 0) {
            for (int c = 0; c < 3; ++c)
                dir[c] = (p[c] - q[c]) / d * (d - distance);
        } else { /* overlapping: back off along the line between the translations */
            const double len = sqrt(pose[3] * pose[3] + pose[7] * pose[7] + pose[11] * pose[11]);
            for (int c = 0; c < 3; ++c)
                dir[c] = len > 0 ? -pose[4 * c + 3] / len * -distance : (c == 0 ? distance : 0);
        }
        for (int c = 0; c < 3; ++c)
            pose[4 * c + 3] += dir[c];
        guess = fmax(distance, 0.5 * d);
    }
    ttd_gen_mesh_free(&b);
    return -1;
}

int bench_cand_make(const ttd_gen_mesh *m, const ttd_gen_mesh *coarse, const char *desc, double distance,
                    double margin, int poses, uint64_t seed, size_t max_pairs, bench_cand_set *out)
{
    memset(out, 0, sizeof *out);
    snprintf(out->mesh, sizeof out->mesh, "%s", desc ? desc : "mesh");
    out->distance = distance;
    out->margin = margin;
    out->poses = poses;
    for (int i = 0; i < poses; ++i) {
        double pose[12];
        ttd_gen_mesh b = {NULL, 0, NULL, 0};
        uint32_t *pairs = NULL;
        size_t n = 0;
        if (place(coarse, distance, seed, (uint64_t)i, pose) != 0 || ttd_gen_mesh_transform(m, pose, &b) != 0 ||
            ttd_gen_mesh_pairs(m, &b, margin, max_pairs - out->n, &pairs, &n) != 0) {
            ttd_gen_mesh_free(&b);
            bench_cand_free(out);
            return -1;
        }
        double *s = realloc(out->s, 9 * (out->n + n) * sizeof *s + 1);
        if (s)
            out->s = s;
        double *t = realloc(out->t, 9 * (out->n + n) * sizeof *t + 1);
        if (t)
            out->t = t;
        if (!s || !t) {
            free(pairs);
            ttd_gen_mesh_free(&b);
            bench_cand_free(out);
            return -1;
        }
        ttd_gen_mesh_pair_coords(m, &b, pairs, n, out->s + 9 * out->n, out->t + 9 * out->n);
        out->n += n;
        free(pairs);
        ttd_gen_mesh_free(&b);
    }
    double *d = malloc((out->n ? out->n : 1) * sizeof *d);
    ttd_options o = ttd_default_options();
    if (!d || (out->n && ttd_batch_d(&o, out->n, out->s, out->t, d, NULL) != TTD_OK)) {
        free(d);
        bench_cand_free(out);
        return -1;
    }
    for (size_t k = 0; k < out->n; ++k)
        out->within += d[k] <= margin;
    free(d);
    return 0;
}

void bench_cand_free(bench_cand_set *set)
{
    free(set->s);
    free(set->t);
    memset(set, 0, sizeof *set);
}

/* One pass over the pairs, block by block as the engine runs the kernel. */
static void kernel_pass(int bytes, ttd_isa isa, size_t n, const void *s, const void *t, double bound, void *dist,
                        void *pts, void *res)
{
    const ttd_params prm = {0, 0, 1};
    for (size_t i0 = 0; i0 < n; i0 += TTD_BLOCK_PAIRS) {
        const size_t m = n - i0 < TTD_BLOCK_PAIRS ? n - i0 : TTD_BLOCK_PAIRS;
        if (bytes == 8) {
            const ttd_out_d o = {dist ? (double *)dist + i0 : NULL, pts ? (double *)pts + 6 * i0 : NULL,
                                 res ? (ttd_result_d *)res + i0 : NULL};
            ttd_dispatch_kernel_d(isa, TTD_METHOD_EXACT)(m, (const double *)s + 9 * i0, (const double *)t + 9 * i0,
                                                         &prm, bound, &o);
        } else {
            const ttd_out_f o = {dist ? (float *)dist + i0 : NULL, pts ? (float *)pts + 6 * i0 : NULL,
                                 res ? (ttd_result_f *)res + i0 : NULL};
            ttd_dispatch_kernel_f(isa, TTD_METHOD_EXACT)(m, (const float *)s + 9 * i0, (const float *)t + 9 * i0,
                                                         &prm, (float)bound, &o);
        }
    }
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int bench_cand_time(size_t n, const void *s, const void *t, int bytes, ttd_isa isa, int output, double bound,
                    int samples, double min_sample_s, double *dist, double *ns_median, double *ns_min)
{
    const size_t r = bytes == 8 ? sizeof(double) : sizeof(float);
    const size_t rs = bytes == 8 ? sizeof(ttd_result_d) : sizeof(ttd_result_f);
    if (n == 0 || samples < 1 || samples > 64 || !ttd_dispatch_isa_built(isa) || !ttd_dispatch_cpu_supports(isa))
        return -1;
    void *d = output == 2 ? NULL : malloc(n * r), *p = output == 1 ? malloc(6 * n * r) : NULL;
    void *res = output == 2 ? malloc(n * rs) : NULL;
    if ((output != 2 && !d) || (output == 1 && !p) || (output == 2 && !res)) {
        free(d);
        free(p);
        free(res);
        return -1;
    }
    double tt[64];
    long passes = 1;
    kernel_pass(bytes, isa, n, s, t, bound, d, p, res); /* warm-up */
    double t0 = bench_now();
    kernel_pass(bytes, isa, n, s, t, bound, d, p, res);
    const double one = bench_now() - t0;
    if (one < min_sample_s)
        passes = (long)ceil(min_sample_s / fmax(one, 1e-9));
    for (int k = 0; k < samples; ++k) {
        t0 = bench_now();
        for (long j = 0; j < passes; ++j)
            kernel_pass(bytes, isa, n, s, t, bound, d, p, res);
        tt[k] = (bench_now() - t0) * 1e9 / ((double)passes * (double)n);
    }
    qsort(tt, (size_t)samples, sizeof tt[0], cmp_double);
    *ns_median = tt[samples / 2];
    *ns_min = tt[0];
    for (size_t i = 0; i < n; ++i) {
        if (output == 2)
            dist[i] = bytes == 8 ? ((const ttd_result_d *)res)[i].distance : (double)((const ttd_result_f *)res)[i].distance;
        else
            dist[i] = bytes == 8 ? ((const double *)d)[i] : (double)((const float *)d)[i];
    }
    free(d);
    free(p);
    free(res);
    return 0;
}
