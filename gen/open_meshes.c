/* SPDX-License-Identifier: MIT */
/* Open meshes for the point queries (open_meshes.h). */
#include "open_meshes.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pairs.h"

int ttd_gen_punch_holes(const ttd_gen_mesh *in, int count, double radius, uint64_t seed, ttd_gen_mesh *out)
{
    memset(out, 0, sizeof *out);
    if (!in || !in->verts || !in->tris || in->nt == 0 || count < 0 || !(radius >= 0))
        return -1;
    double *centre = malloc(3 * (size_t)(count > 0 ? count : 1) * sizeof(double));
    uint32_t *keep = malloc(3 * in->nt * sizeof(uint32_t));
    double *verts = malloc(3 * in->nv * sizeof(double));
    if (!centre || !keep || !verts) {
        free(centre);
        free(keep);
        free(verts);
        return -1;
    }
    ttd_gen_rng r = ttd_gen_rng_make(seed, 31);
    for (int h = 0; h < count; ++h) {
        const size_t t = (size_t)(ttd_gen_rng_u64(&r) % in->nt);
        for (int c = 0; c < 3; ++c) {
            double s = 0;
            for (int k = 0; k < 3; ++k)
                s += in->verts[3 * in->tris[3 * t + (size_t)k] + (size_t)c];
            centre[3 * h + c] = s / 3;
        }
    }
    size_t nt = 0;
    for (size_t t = 0; t < in->nt; ++t) {
        double g[3];
        for (int c = 0; c < 3; ++c) {
            double s = 0;
            for (int k = 0; k < 3; ++k)
                s += in->verts[3 * in->tris[3 * t + (size_t)k] + (size_t)c];
            g[c] = s / 3;
        }
        int cut = 0;
        for (int h = 0; h < count && !cut; ++h) {
            const double dx = g[0] - centre[3 * h], dy = g[1] - centre[3 * h + 1], dz = g[2] - centre[3 * h + 2];
            cut = dx * dx + dy * dy + dz * dz <= radius * radius;
        }
        if (!cut) {
            memcpy(keep + 3 * nt, in->tris + 3 * t, 3 * sizeof(uint32_t));
            ++nt;
        }
    }
    free(centre);
    if (nt == 0) {
        free(keep);
        free(verts);
        return -1;
    }
    memcpy(verts, in->verts, 3 * in->nv * sizeof(double));
    out->verts = verts;
    out->nv = in->nv;
    out->tris = keep;
    out->nt = nt;
    return 0;
}

int ttd_gen_mesh_concat(const ttd_gen_mesh *a, const ttd_gen_mesh *b, ttd_gen_mesh *out)
{
    memset(out, 0, sizeof *out);
    if (!a || !b || out == a || out == b || a->nv + b->nv > UINT32_MAX)
        return -1;
    out->verts = malloc(3 * (a->nv + b->nv) * sizeof(double) + 8);
    out->tris = malloc(3 * (a->nt + b->nt) * sizeof(uint32_t) + 4);
    if (!out->verts || !out->tris) {
        ttd_gen_mesh_free(out);
        return -1;
    }
    memcpy(out->verts, a->verts, 3 * a->nv * sizeof(double));
    memcpy(out->verts + 3 * a->nv, b->verts, 3 * b->nv * sizeof(double));
    memcpy(out->tris, a->tris, 3 * a->nt * sizeof(uint32_t));
    for (size_t k = 0; k < 3 * b->nt; ++k)
        out->tris[3 * a->nt + k] = b->tris[k] + (uint32_t)a->nv;
    out->nv = a->nv + b->nv;
    out->nt = a->nt + b->nt;
    return 0;
}

/* The box [lo, hi] with n[a] segments along axis a, every face its own grid of vertices (the
 * seams' vertices repeated, as CAD exports write them: the same coordinates, computed by one
 * formula), outward normals; faces whose bit (2 a + side, side 1 = hi) is set in `skip` are left
 * out. */
static int gen_box(const double lo[3], const double hi[3], const int n[3], unsigned skip, ttd_gen_mesh *out)
{
    memset(out, 0, sizeof *out);
    size_t nv = 0, nt = 0;
    for (int a = 0; a < 3; ++a)
        for (int side = 0; side < 2; ++side)
            if (!(skip >> (2 * a + side) & 1u)) {
                const int b = (a + 1) % 3, c = (a + 2) % 3;
                nv += (size_t)(n[b] + 1) * (size_t)(n[c] + 1);
                nt += 2 * (size_t)n[b] * (size_t)n[c];
            }
    out->verts = malloc(3 * nv * sizeof(double));
    out->tris = malloc(3 * nt * sizeof(uint32_t));
    if (!out->verts || !out->tris) {
        ttd_gen_mesh_free(out);
        return -1;
    }
    size_t v = 0, t = 0;
    for (int a = 0; a < 3; ++a)
        for (int side = 0; side < 2; ++side) {
            if (skip >> (2 * a + side) & 1u)
                continue;
            const int b = (a + 1) % 3, c = (a + 2) % 3;
            const size_t base = v;
            for (int j = 0; j <= n[c]; ++j)
                for (int i = 0; i <= n[b]; ++i) {
                    double *p = out->verts + 3 * v++;
                    p[a] = side ? hi[a] : lo[a];
                    p[b] = lo[b] + (hi[b] - lo[b]) * (double)i / n[b];
                    p[c] = lo[c] + (hi[c] - lo[c]) * (double)j / n[c];
                }
            for (int j = 0; j < n[c]; ++j)
                for (int i = 0; i < n[b]; ++i) {
                    const uint32_t q00 = (uint32_t)(base + (size_t)j * (size_t)(n[b] + 1) + (size_t)i),
                                   q10 = q00 + 1, q01 = q00 + (uint32_t)(n[b] + 1), q11 = q01 + 1;
                    /* e_b x e_c = e_a: (b, c) counter-clockwise seen from +a */
                    const uint32_t tri[2][3] = {{q00, q10, q11}, {q00, q11, q01}};
                    for (int k = 0; k < 2; ++k) {
                        uint32_t *o = out->tris + 3 * t++;
                        o[0] = tri[k][0];
                        o[1] = side ? tri[k][1] : tri[k][2];
                        o[2] = side ? tri[k][2] : tri[k][1];
                    }
                }
        }
    out->nv = nv;
    out->nt = nt;
    return 0;
}

/* Appends m to *acc (freeing m). */
static int gen_add(ttd_gen_mesh *acc, ttd_gen_mesh *m)
{
    if (acc->nt == 0) {
        *acc = *m;
        memset(m, 0, sizeof *m);
        return 0;
    }
    ttd_gen_mesh s;
    const int rc = ttd_gen_mesh_concat(acc, m, &s);
    ttd_gen_mesh_free(acc);
    ttd_gen_mesh_free(m);
    *acc = s;
    return rc;
}

static int gen_chair(ttd_gen_mesh *out)
{
    memset(out, 0, sizeof *out);
    static const double box[6][6] = {
        {0, 0, 0.45, 1, 1, 0.55},        /* seat */
        {0, 0, 0, 0.1, 0.1, 0.5},        /* legs */
        {0.9, 0, 0, 1, 0.1, 0.5},
        {0, 0.9, 0, 0.1, 1, 0.5},
        {0.9, 0.9, 0, 1, 1, 0.5},
        {0, 0.9, 0.5, 1, 1, 1.4},        /* back */
    };
    static const int seg[6][3] = {{40, 40, 4}, {4, 4, 20}, {4, 4, 20}, {4, 4, 20}, {4, 4, 20}, {40, 4, 36}};
    static const unsigned skip[6] = {0, 1u << 4, 1u << 4, 1u << 4, 1u << 4, 1u << 5}; /* z lo, z hi */
    for (int k = 0; k < 6; ++k) {
        ttd_gen_mesh b;
        if (gen_box(box[k], box[k] + 3, seg[k], skip[k], &b) != 0 || gen_add(out, &b) != 0) {
            ttd_gen_mesh_free(out);
            return -1;
        }
    }
    return 0;
}

/* A cylinder of radius rad along z from 0 to len, open at z = 0, closed by a hemisphere at z = len:
 * nu segments around, rows_cyl rows on the cylinder, rows_cap on the hemisphere to its pole. */
static int gen_capsule(double rad, double len, int nu, int rows_cyl, int rows_cap, ttd_gen_mesh *out)
{
    memset(out, 0, sizeof *out);
    const int rings = rows_cyl + rows_cap; /* rings 0..rings-1, then the pole */
    const size_t nv = (size_t)rings * (size_t)nu + 1, nt = 2 * (size_t)(rings - 1) * (size_t)nu + (size_t)nu;
    out->verts = malloc(3 * nv * sizeof(double));
    out->tris = malloc(3 * nt * sizeof(uint32_t));
    if (!out->verts || !out->tris) {
        ttd_gen_mesh_free(out);
        return -1;
    }
    for (int k = 0; k < rings; ++k) {
        double z, r;
        if (k <= rows_cyl) {
            z = len * k / rows_cyl;
            r = rad;
        } else {
            const double phi = 1.5707963267948966 * (k - rows_cyl) / rows_cap;
            z = len + rad * sin(phi);
            r = rad * cos(phi);
        }
        for (int i = 0; i < nu; ++i) {
            const double a = 6.283185307179586 * i / nu;
            double *p = out->verts + 3 * ((size_t)k * (size_t)nu + (size_t)i);
            p[0] = r * cos(a);
            p[1] = r * sin(a);
            p[2] = z;
        }
    }
    double *pole = out->verts + 3 * (nv - 1);
    pole[0] = pole[1] = 0;
    pole[2] = len + rad;
    size_t t = 0;
    for (int k = 0; k + 1 < rings; ++k)
        for (int i = 0; i < nu; ++i) {
            const uint32_t a = (uint32_t)(k * nu + i), b = (uint32_t)(k * nu + (i + 1) % nu), c = b + (uint32_t)nu,
                           d = a + (uint32_t)nu;
            uint32_t *o = out->tris + 3 * t;
            o[0] = a, o[1] = b, o[2] = c, o[3] = a, o[4] = c, o[5] = d;
            t += 2;
        }
    for (int i = 0; i < nu; ++i) {
        uint32_t *o = out->tris + 3 * t++;
        o[0] = (uint32_t)((rings - 1) * nu + i);
        o[1] = (uint32_t)((rings - 1) * nu + (i + 1) % nu);
        o[2] = (uint32_t)(nv - 1);
    }
    out->nv = nv;
    out->nt = nt;
    return 0;
}

int ttd_gen_open_mesh(const char *name, ttd_gen_mesh *out)
{
    memset(out, 0, sizeof *out);
    ttd_gen_mesh base = {0};
    int rc = -1;
    if (strcmp(name, "cad") == 0) {
        const double lo[3] = {0, 0, 0}, hi[3] = {1, 0.6, 0.12};
        const int n[3] = {400, 20, 4};
        rc = gen_box(lo, hi, n, 0, &base) || ttd_gen_punch_holes(&base, 7, 0.05, 1, out);
    } else if (strcmp(name, "chair") == 0) {
        rc = gen_chair(out);
    } else if (strcmp(name, "capsule") == 0) {
        rc = gen_capsule(0.25, 1, 128, 96, 64, &base) || ttd_gen_punch_holes(&base, 2, 0.1, 2, out);
    } else if (strcmp(name, "scan") == 0) {
        rc = ttd_gen_icosphere(6, &base);
        if (rc == 0) {
            ttd_gen_rng r = ttd_gen_rng_make(3, 7);
            for (size_t v = 0; v < base.nv; ++v) {
                const double f = 1 + 0.02 * (ttd_gen_rng_uniform(&r) - 0.5);
                for (int c = 0; c < 3; ++c)
                    base.verts[3 * v + (size_t)c] *= f;
            }
            rc = ttd_gen_punch_holes(&base, 12, 0.15, 3, out);
        }
    } else if (strcmp(name, "torus-holes") == 0) {
        rc = ttd_gen_torus(1, 0.35, 200, 64, &base) || ttd_gen_punch_holes(&base, 9, 0.2, 4, out);
    }
    ttd_gen_mesh_free(&base);
    if (rc == 0)
        rc = ttd_gen_normalize(out);
    if (rc != 0)
        ttd_gen_mesh_free(out);
    return rc ? -1 : 0;
}
