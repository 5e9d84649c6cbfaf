/* SPDX-License-Identifier: MIT */
/* The brute force that the mesh CCD tests and fuzzer compare ttd_mesh_ccd_d and
 * ttd_mesh_self_ccd_d against: every triangle pair (no boxes, no hierarchy, no owner rule), its
 * sub-queries by the rules of ttd.h written out directly, each primitive pair kept once (by a
 * sort of their ids), each run through the public primitive entries (ttd_ccd_vertex_face_d,
 * ttd_ccd_edge_edge_d), then the earliest toi and the pairs within TTD_CCD_DEFAULT_T_TOL of it. */
#ifndef TTD_TESTS_MESH_CCD_BRUTE_H
#define TTD_TESTS_MESH_CCD_BRUTE_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ttd/ttd.h"

typedef struct brute_key {
    uint32_t kind, a0, a1, b0, b1;
} brute_key;

static int brute_key_cmp(const void *x, const void *y)
{
    const brute_key *p = x, *q = y;
    const uint32_t kp[5] = {p->kind, p->a0, p->a1, p->b0, p->b1}, kq[5] = {q->kind, q->a0, q->a1, q->b0, q->b1};
    for (int i = 0; i < 5; ++i)
        if (kp[i] != kq[i])
            return kp[i] < kq[i] ? -1 : 1;
    return 0;
}

static int brute_pair_cmp(const void *x, const void *y)
{
    const ttd_mesh_ccd_pair *p = x, *q = y;
    if (p->toi != q->toi)
        return p->toi < q->toi ? -1 : 1;
    const brute_key kp = {p->kind, p->a[0], p->a[1], p->b[0], p->b[1]};
    const brute_key kq = {q->kind, q->a[0], q->a[1], q->b[0], q->b[1]};
    return brute_key_cmp(&kp, &kq);
}

typedef struct brute_list {
    brute_key *k;
    size_t n, cap;
} brute_list;

static int brute_push(brute_list *l, uint32_t kind, uint32_t a0, uint32_t a1, uint32_t b0, uint32_t b1)
{
    if (l->n == l->cap) {
        const size_t cap = l->cap ? 2 * l->cap : 1024;
        brute_key *k = realloc(l->k, cap * sizeof *k);
        if (k == NULL)
            return -1;
        l->k = k;
        l->cap = cap;
    }
    l->k[l->n++] = (brute_key){kind, a0, a1, b0, b1};
    return 0;
}

static int brute_has(const uint32_t *t, uint32_t v)
{
    return t[0] == v || t[1] == v || t[2] == v;
}

/* Edge k of triangle t, smaller index first. */
static void brute_edge(const uint32_t *t, int k, uint32_t e[2])
{
    const uint32_t p = t[k], q = t[(k + 1) % 3];
    e[0] = p < q ? p : q;
    e[1] = p < q ? q : p;
}

/* Distinct vertices two triangles share. */
static int brute_shared(const uint32_t *t, const uint32_t *u)
{
    int c = 0;
    for (int k = 0; k < 3; ++k)
        c += (k == 0 || (t[k] != t[0] && (k == 1 || t[k] != t[1]))) && brute_has(u, t[k]);
    return c;
}

/* Runs the kept keys and fills out like the library (pairs malloc'd). Sides: a (x0a, x1a, ta),
 * b (the same as a for self). Returns 0, or -1 on a failure. */
static int brute_run(brute_list *l, const double *x0a, const double *x1a, const uint32_t *ta, const double *x0b,
                     const double *x1b, const uint32_t *tb, double delta, ttd_mesh_ccd_result *out)
{
    memset(out, 0, sizeof *out);
    out->toi = (double)INFINITY;
    if (l->n > 0)
        qsort(l->k, l->n, sizeof *l->k, brute_key_cmp);
    size_t m = 0;
    for (size_t i = 0; i < l->n; ++i)
        if (m == 0 || brute_key_cmp(&l->k[m - 1], &l->k[i]) != 0)
            l->k[m++] = l->k[i];
    l->n = m;
    out->queries = m;
    if (m == 0)
        return 0;
    double *x0 = malloc(m * 12 * sizeof *x0), *x1 = malloc(m * 12 * sizeof *x1);
    ttd_ccd_result *r = malloc(m * sizeof *r);
    out->pairs = malloc(m * sizeof *out->pairs);
    if (!x0 || !x1 || !r || !out->pairs) {
        free(x0);
        free(x1);
        free(r);
        return -1;
    }
    /* vertex-face queries first (points 0, then 3 face points), then edge-edge */
    size_t nvf = 0;
    for (int pass = 0; pass < 2; ++pass) {
        size_t q = 0;
        for (size_t i = 0; i < m; ++i) {
            const brute_key *k = &l->k[i];
            const int vf = k->kind != TTD_MESH_CCD_EE;
            if (vf != (pass == 0))
                continue;
            uint32_t pid[4];
            const double *P0[4], *P1[4];
            if (k->kind == TTD_MESH_CCD_VF) {
                pid[0] = k->a0;
                P0[0] = x0a, P1[0] = x1a;
                for (int j = 0; j < 3; ++j)
                    pid[1 + j] = tb[3 * (size_t)k->b0 + (size_t)j], P0[1 + j] = x0b, P1[1 + j] = x1b;
            } else if (k->kind == TTD_MESH_CCD_FV) {
                pid[0] = k->b0;
                P0[0] = x0b, P1[0] = x1b;
                for (int j = 0; j < 3; ++j)
                    pid[1 + j] = ta[3 * (size_t)k->a0 + (size_t)j], P0[1 + j] = x0a, P1[1 + j] = x1a;
            } else {
                pid[0] = k->a0, pid[1] = k->a1, pid[2] = k->b0, pid[3] = k->b1;
                P0[0] = P0[1] = x0a, P1[0] = P1[1] = x1a;
                P0[2] = P0[3] = x0b, P1[2] = P1[3] = x1b;
            }
            /* layout: VF v (3n) then f (9n); EE ea (6n) then eb (6n): here one array of 12 a query,
             * rearranged below */
            const size_t o = pass == 0 ? q : nvf + q;
            for (int j = 0; j < 4; ++j)
                for (int c = 0; c < 3; ++c) {
                    x0[12 * o + 3 * (size_t)j + (size_t)c] = P0[j][3 * (size_t)pid[j] + (size_t)c];
                    x1[12 * o + 3 * (size_t)j + (size_t)c] = P1[j][3 * (size_t)pid[j] + (size_t)c];
                }
            ++q;
        }
        if (pass == 0)
            nvf = q;
    }
    /* split into the entries' arrays */
    const size_t nee = m - nvf;
    double *buf = malloc(m * 24 * sizeof *buf);
    if (buf == NULL) {
        free(x0);
        free(x1);
        free(r);
        return -1;
    }
    int bad = 0;
    if (nvf > 0) {
        double *v0 = buf, *f0 = v0 + 3 * nvf, *v1 = f0 + 9 * nvf, *f1 = v1 + 3 * nvf;
        for (size_t i = 0; i < nvf; ++i) {
            memcpy(v0 + 3 * i, x0 + 12 * i, 3 * sizeof(double));
            memcpy(f0 + 9 * i, x0 + 12 * i + 3, 9 * sizeof(double));
            memcpy(v1 + 3 * i, x1 + 12 * i, 3 * sizeof(double));
            memcpy(f1 + 9 * i, x1 + 12 * i + 3, 9 * sizeof(double));
        }
        bad |= ttd_ccd_vertex_face_d(NULL, nvf, v0, f0, v1, f1, delta, r) != TTD_OK;
    }
    if (nee > 0) {
        double *a0 = buf, *b0 = a0 + 6 * nee, *a1 = b0 + 6 * nee, *b1 = a1 + 6 * nee;
        for (size_t i = 0; i < nee; ++i) {
            memcpy(a0 + 6 * i, x0 + 12 * (nvf + i), 6 * sizeof(double));
            memcpy(b0 + 6 * i, x0 + 12 * (nvf + i) + 6, 6 * sizeof(double));
            memcpy(a1 + 6 * i, x1 + 12 * (nvf + i), 6 * sizeof(double));
            memcpy(b1 + 6 * i, x1 + 12 * (nvf + i) + 6, 6 * sizeof(double));
        }
        bad |= ttd_ccd_edge_edge_d(NULL, nee, a0, b0, a1, b1, delta, r + nvf) != TTD_OK;
    }
    free(buf);
    free(x0);
    free(x1);
    if (bad) {
        free(r);
        return -1;
    }
    /* keys in the order the results were written: the VF/FV keys, then the EE keys */
    size_t q[2] = {0, nvf};
    double best = (double)INFINITY;
    for (size_t i = 0; i < m; ++i) {
        const int vf = l->k[i].kind != TTD_MESH_CCD_EE;
        const ttd_ccd_result *ri = &r[q[!vf]++];
        if (ri->hit && ri->toi < best)
            best = ri->toi;
    }
    q[0] = 0, q[1] = nvf;
    for (size_t i = 0; i < m; ++i) {
        const brute_key *k = &l->k[i];
        const int vf = k->kind != TTD_MESH_CCD_EE;
        const ttd_ccd_result *ri = &r[q[!vf]++];
        if (!ri->hit || !(ri->toi <= best + TTD_CCD_DEFAULT_T_TOL))
            continue;
        ttd_mesh_ccd_pair *p = &out->pairs[out->count++];
        p->toi = ri->toi;
        p->gap = ri->gap;
        p->kind = k->kind;
        p->flags = ri->flags & TTD_CCD_BUDGET;
        p->a[0] = k->a0, p->a[1] = k->a1, p->b[0] = k->b0, p->b[1] = k->b1;
        out->flags |= p->flags;
    }
    free(r);
    out->toi = best;
    qsort(out->pairs, out->count, sizeof *out->pairs, brute_pair_cmp);
    return 0;
}

/* Two meshes: every vertex of a against every triangle of b and back, every edge against every edge. */
static int brute_mesh_ccd(const double *x0a, const double *x1a, const uint32_t *ta, size_t nta, const double *x0b,
                          const double *x1b, const uint32_t *tb, size_t ntb, double delta, ttd_mesh_ccd_result *out)
{
    brute_list l = {0};
    const uint32_t none = UINT32_MAX;
    for (size_t i = 0; i < nta; ++i)
        for (size_t j = 0; j < ntb; ++j)
            for (int k = 0; k < 3; ++k) {
                int fail = brute_push(&l, TTD_MESH_CCD_VF, ta[3 * i + (size_t)k], none, (uint32_t)j, none);
                fail |= brute_push(&l, TTD_MESH_CCD_FV, (uint32_t)i, none, tb[3 * j + (size_t)k], none);
                for (int h = 0; h < 3; ++h) {
                    uint32_t e[2], g[2];
                    brute_edge(ta + 3 * i, k, e);
                    brute_edge(tb + 3 * j, h, g);
                    fail |= brute_push(&l, TTD_MESH_CCD_EE, e[0], e[1], g[0], g[1]);
                }
                if (fail) {
                    free(l.k);
                    return -1;
                }
            }
    const int rc = brute_run(&l, x0a, x1a, ta, x0b, x1b, tb, delta, out);
    free(l.k);
    return rc;
}

/* One mesh: triangle pairs i < j sharing no vertex, or (shared) exactly one, each with its
 * sub-queries whose two primitives share no vertex. */
static int brute_self_ccd(const double *x0, const double *x1, const uint32_t *t, size_t nt, double delta, int shared,
                          ttd_mesh_ccd_result *out)
{
    brute_list l = {0};
    const uint32_t none = UINT32_MAX;
    for (size_t i = 0; i < nt; ++i)
        for (size_t j = i + 1; j < nt; ++j) {
            const uint32_t *ti = t + 3 * i, *tj = t + 3 * j;
            const int c = brute_shared(ti, tj);
            if (!(c == 0 || (c == 1 && shared)))
                continue;
            int fail = 0;
            for (int k = 0; k < 3; ++k) {
                if (!brute_has(tj, ti[k]))
                    fail |= brute_push(&l, TTD_MESH_CCD_VF, ti[k], none, (uint32_t)j, none);
                if (!brute_has(ti, tj[k]))
                    fail |= brute_push(&l, TTD_MESH_CCD_VF, tj[k], none, (uint32_t)i, none);
                for (int h = 0; h < 3; ++h) {
                    uint32_t e[2], g[2];
                    brute_edge(ti, k, e);
                    brute_edge(tj, h, g);
                    if (e[0] == g[0] || e[0] == g[1] || e[1] == g[0] || e[1] == g[1])
                        continue;
                    if (g[0] < e[0] || (g[0] == e[0] && g[1] < e[1]))
                        fail |= brute_push(&l, TTD_MESH_CCD_EE, g[0], g[1], e[0], e[1]);
                    else
                        fail |= brute_push(&l, TTD_MESH_CCD_EE, e[0], e[1], g[0], g[1]);
                }
            }
            if (fail) {
                free(l.k);
                return -1;
            }
        }
    const int rc = brute_run(&l, x0, x1, t, x0, x1, t, delta, out);
    free(l.k);
    return rc;
}

#endif /* TTD_TESTS_MESH_CCD_BRUTE_H */
