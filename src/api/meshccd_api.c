/* SPDX-License-Identifier: MIT */
/* The public entries of continuous collision for deforming meshes (ttd.h, ttd_mesh_ccd_d and
 * the rest): the checks (pointers, options, min_separation, the meshes' precision, the flags,
 * the t = 1 vertices finite), the t = 0 and t = 1 vertices widened to double, then
 * src/meshccd/. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "api/prepare.h"
#include "mesh/mesh.h"
#include "meshccd/meshccd.h"

/* A side in double: the mesh's vertices (t = 0) and t1 (t = 1), copied when they are float.
 * *owned holds what was allocated (freed by the caller). TTD_ERR_NONFINITE_MESH for a NaN or
 * infinite t = 1 coordinate. */
static ttd_status side_of(const ttd_mesh *m, const void *t1, meshccd_side *s, double **owned)
{
    *owned = NULL;
    const size_t n = 3 * m->nv;
    if (m->bytes == 8) {
        const double *x1 = t1;
        for (size_t i = 0; i < n; ++i)
            if (!isfinite(x1[i]))
                return TTD_ERR_NONFINITE_MESH;
        s->x0 = m->verts;
        s->x1 = x1;
    } else {
        const float *x1 = t1, *x0 = m->verts;
        for (size_t i = 0; i < n; ++i)
            if (!isfinite(x1[i]))
                return TTD_ERR_NONFINITE_MESH;
        double *w = malloc(2 * n * sizeof *w);
        if (w == NULL)
            return TTD_ERR_OUT_OF_MEMORY;
        for (size_t i = 0; i < n; ++i) {
            w[i] = (double)x0[i];
            w[n + i] = (double)x1[i];
        }
        s->x0 = w;
        s->x1 = w + n;
        *owned = w;
    }
    s->tris = m->tris;
    s->nv = m->nv;
    s->nt = m->nt;
    return TTD_OK;
}

static ttd_status mesh_ccd(const ttd_options *opt, int bytes, const ttd_mesh *a, const void *a1, const ttd_mesh *b,
                           const void *b1, double delta, int self, unsigned flags, ttd_mesh_ccd_result *out)
{
    if (out == NULL)
        return TTD_ERR_NULL_POINTER;
    memset(out, 0, sizeof *out);
    out->toi = HUGE_VAL;
    ttd_engine_config cfg;
    ttd_status st = ttd_prepare(opt, a != NULL && a1 != NULL && (self || (b != NULL && b1 != NULL)), 1, 0, &cfg);
    if (st != TTD_OK)
        return st;
    if (!(delta >= 0) || !isfinite(delta) || (flags & ~(unsigned)TTD_SELF_SHARED_VERTEX))
        return TTD_ERR_BAD_OPTIONS;
    if (a->bytes != bytes || (!self && b->bytes != bytes))
        return TTD_ERR_PRECISION_MISMATCH;
    meshccd_side sa, sb;
    double *wa = NULL, *wb = NULL;
    st = side_of(a, a1, &sa, &wa);
    if (st == TTD_OK && !self)
        st = side_of(b, b1, &sb, &wb);
    if (st == TTD_OK)
        st = ttd_meshccd_run(cfg.threads, cfg.isa, &sa, self ? NULL : &sb, delta, flags, out);
    free(wa);
    free(wb);
    return st;
}

ttd_status ttd_mesh_ccd_d(const ttd_options *opt, const ttd_mesh *a, const double *a_vertices_t1, const ttd_mesh *b,
                          const double *b_vertices_t1, double min_separation, ttd_mesh_ccd_result *out)
{
    return mesh_ccd(opt, 8, a, a_vertices_t1, b, b_vertices_t1, min_separation, 0, 0, out);
}

ttd_status ttd_mesh_ccd_f(const ttd_options *opt, const ttd_mesh *a, const float *a_vertices_t1, const ttd_mesh *b,
                          const float *b_vertices_t1, double min_separation, ttd_mesh_ccd_result *out)
{
    return mesh_ccd(opt, 4, a, a_vertices_t1, b, b_vertices_t1, min_separation, 0, 0, out);
}

ttd_status ttd_mesh_self_ccd_d(const ttd_options *opt, const ttd_mesh *mesh, const double *vertices_t1,
                               double min_separation, unsigned flags, ttd_mesh_ccd_result *out)
{
    return mesh_ccd(opt, 8, mesh, vertices_t1, NULL, NULL, min_separation, 1, flags, out);
}

ttd_status ttd_mesh_self_ccd_f(const ttd_options *opt, const ttd_mesh *mesh, const float *vertices_t1,
                               double min_separation, unsigned flags, ttd_mesh_ccd_result *out)
{
    return mesh_ccd(opt, 4, mesh, vertices_t1, NULL, NULL, min_separation, 1, flags, out);
}

void ttd_mesh_ccd_free(ttd_mesh_ccd_result *out)
{
    if (out == NULL)
        return;
    free(out->pairs);
    out->pairs = NULL;
    out->count = 0;
}
