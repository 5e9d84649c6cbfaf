/* SPDX-License-Identifier: MIT */
/* The brute force the mesh tests compare against: the exact method over every triangle pair
 * (ttd_batch_d/f), b's vertices moved into a's frame exactly as include/ttd/ttd.h documents
 * ((r0 x + r1 y) + r2 z) + t, so that each pair's distance is the very number a query's kernel
 * computes. Shared by tests/test_mesh.c and tests/test_mesh_deform.c. */
#ifndef TTD_TESTS_MESH_BRUTE_H
#define TTD_TESTS_MESH_BRUTE_H

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "meshes.h"
#include "ttd/ttd.h"

static inline void pose_apply_d(const double p[12], const double x[3], double out[3])
{
    for (int i = 0; i < 3; ++i)
        out[i] = ((p[4 * i] * x[0] + p[4 * i + 1] * x[1]) + p[4 * i + 2] * x[2]) + p[4 * i + 3];
}

static inline void pose_apply_f(const float p[12], const float x[3], float out[3])
{
    for (int i = 0; i < 3; ++i)
        out[i] = ((p[4 * i] * x[0] + p[4 * i + 1] * x[1]) + p[4 * i + 2] * x[2]) + p[4 * i + 3];
}

/* Every pair's full result, pair (i, j) at i * nt_b + j. */
static inline ttd_result_d *brute_d(const ttd_gen_mesh *a, const ttd_gen_mesh *b, const double pose[12])
{
    const size_t n = a->nt * b->nt;
    double *s = malloc(9 * n * sizeof *s), *t = malloc(9 * n * sizeof *t);
    ttd_result_d *r = malloc(n * sizeof *r);
    if (!s || !t || !r)
        abort();
    for (size_t i = 0; i < a->nt; ++i)
        for (size_t j = 0; j < b->nt; ++j)
            for (int v = 0; v < 3; ++v) {
                memcpy(s + 9 * (i * b->nt + j) + 3 * v, a->verts + 3 * (size_t)a->tris[3 * i + v], 3 * sizeof(double));
                pose_apply_d(pose, b->verts + 3 * (size_t)b->tris[3 * j + v], t + 9 * (i * b->nt + j) + 3 * v);
            }
    if (ttd_batch_d(NULL, n, s, t, NULL, r) != TTD_OK)
        abort();
    free(s);
    free(t);
    return r;
}

typedef struct mesh_f {
    float *verts;
    size_t nv;
    const uint32_t *tris;
    size_t nt;
} mesh_f;

static inline mesh_f to_float(const ttd_gen_mesh *m)
{
    mesh_f f = {malloc(3 * m->nv * sizeof(float)), m->nv, m->tris, m->nt};
    if (!f.verts)
        abort();
    for (size_t i = 0; i < 3 * m->nv; ++i)
        f.verts[i] = (float)m->verts[i];
    return f;
}

static inline ttd_result_f *brute_f(const mesh_f *a, const mesh_f *b, const float pose[12])
{
    const size_t n = a->nt * b->nt;
    float *s = malloc(9 * n * sizeof *s), *t = malloc(9 * n * sizeof *t);
    ttd_result_f *r = malloc(n * sizeof *r);
    if (!s || !t || !r)
        abort();
    for (size_t i = 0; i < a->nt; ++i)
        for (size_t j = 0; j < b->nt; ++j)
            for (int v = 0; v < 3; ++v) {
                memcpy(s + 9 * (i * b->nt + j) + 3 * v, a->verts + 3 * (size_t)a->tris[3 * i + v], 3 * sizeof(float));
                pose_apply_f(pose, b->verts + 3 * (size_t)b->tris[3 * j + v], t + 9 * (i * b->nt + j) + 3 * v);
            }
    if (ttd_batch_f(NULL, n, s, t, NULL, r) != TTD_OK)
        abort();
    free(s);
    free(t);
    return r;
}

#endif /* TTD_TESTS_MESH_BRUTE_H */
