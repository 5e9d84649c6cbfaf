/* SPDX-License-Identifier: MIT */
/* libFuzzer target: continuous collision of deforming meshes (src/meshccd/) against the brute
 * force over every triangle pair (tests/mesh_ccd_brute.h), bit for bit. The bytes make one or two
 * small meshes (up to 8 vertices and 8 triangles each, indices taken from the bytes, so repeated
 * indices, shared vertices and edges, duplicate triangles and unused vertices come up), their
 * vertices at t = 0 and t = 1 from small dyadic values (multiples of 1/4 in [-2, 2), so that
 * touching, coplanar and still motions are common), optionally scaled by a power of two, a
 * min_separation and the self rule (shared vertex or not). Checked: the status; every pair the
 * library reports is a hit of the brute force with the same toi, bit for bit; every hit of the
 * brute force at or before the library's toi + 2^-52 is reported, unless it is a false positive
 * of the primitive query that the mesh query proved apart (its boxes or its normal test): such a
 * pair must be proved apart here too, independently (distances at 2048 times less the most the
 * distance can change between them); the same result with 1 and 3 threads, and from the float
 * entries on float-exact input. A failure prints the case and aborts, so libFuzzer keeps the
 * input. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../mesh_ccd_brute.h"
#include "ttd/ttd.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

typedef struct reader {
    const uint8_t *d;
    size_t n, i;
} reader;

static unsigned next(reader *r)
{
    return r->i < r->n ? r->d[r->i++] : 0u;
}

typedef struct side {
    size_t nv, nt;
    double x0[24], x1[24];
    uint32_t tris[24];
} side;

static void make_side(reader *r, side *s, double scale)
{
    s->nv = 3 + next(r) % 6;
    s->nt = 1 + next(r) % 8;
    for (size_t i = 0; i < 3 * s->nt; ++i)
        s->tris[i] = next(r) % (unsigned)s->nv;
    for (size_t i = 0; i < 3 * s->nv; ++i) {
        const unsigned b = next(r), c = next(r);
        s->x0[i] = ldexp((double)((int)(b & 15) - 8) / 4, 0) * scale;
        /* still (c & 3 == 0), or moved to another small value */
        s->x1[i] = (c & 3) == 0 ? s->x0[i] : (double)((int)(c >> 2 & 15) - 8) / 4 * scale;
    }
}

/* The pair's points: first set (na of them) then second, at t = 0 and 1. */
static int pair_points(const ttd_mesh_ccd_pair *p, const side *a, const side *b, double x0[12], double x1[12])
{
    uint32_t id[4];
    const side *sd[4];
    int na;
    if (p->kind == TTD_MESH_CCD_VF || p->kind == TTD_MESH_CCD_FV) {
        const int vf = p->kind == TTD_MESH_CCD_VF;
        const side *pv = vf ? a : b, *pf = vf ? b : a;
        const uint32_t v = vf ? p->a[0] : p->b[0], f = vf ? p->b[0] : p->a[0];
        na = 1;
        id[0] = v, sd[0] = pv;
        for (int j = 0; j < 3; ++j)
            id[1 + j] = pf->tris[3 * f + (uint32_t)j], sd[1 + j] = pf;
    } else {
        na = 2;
        id[0] = p->a[0], id[1] = p->a[1], id[2] = p->b[0], id[3] = p->b[1];
        sd[0] = sd[1] = a, sd[2] = sd[3] = b;
    }
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k) {
            x0[3 * i + k] = sd[i]->x0[3 * id[i] + (uint32_t)k];
            x1[3 * i + k] = sd[i]->x1[3 * id[i] + (uint32_t)k];
        }
    return na;
}

/* An independent proof that a pair stays more than delta apart over [0, 1]: the distance (the
 * exact method on the primitives as degenerate triangles) at N + 1 times, less what it can change
 * between two of them (the fastest point of each set: L / N), less a rounding allowance. */
static int proven_apart(const ttd_mesh_ccd_pair *p, const side *a, const side *b, double delta)
{
    enum { N = 2048 };
    double x0[12], x1[12];
    const int na = pair_points(p, a, b, x0, x1);
    double va = 0, vb = 0, S = 0;
    for (int i = 0; i < 4; ++i) {
        double v2 = 0;
        for (int k = 0; k < 3; ++k) {
            const double d = x1[3 * i + k] - x0[3 * i + k];
            v2 += d * d;
            S = fmax(S, fmax(fabs(x0[3 * i + k]), fabs(x1[3 * i + k])));
        }
        if (i < na)
            va = fmax(va, sqrt(v2));
        else
            vb = fmax(vb, sqrt(v2));
    }
    static double s[9 * (N + 1)], t[9 * (N + 1)], d[N + 1];
    for (int q = 0; q <= N; ++q) {
        const double tq = (double)q / N;
        double x[12];
        for (int i = 0; i < 12; ++i)
            x[i] = x0[i] + tq * (x1[i] - x0[i]);
        const int first[3] = {0, na == 1 ? 0 : 1, na == 1 ? 0 : 1};
        const int second[3] = {na, na + 1, na == 1 ? 3 : 3};
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k) {
                s[9 * q + 3 * j + k] = x[3 * first[j] + k];
                t[9 * q + 3 * j + k] = x[3 * second[j] + k];
            }
    }
    if (ttd_batch_d(NULL, N + 1, s, t, d, NULL) != TTD_OK)
        return 0;
    const double slack = (va + vb) / N + 1e-9 * (S + 1);
    for (int q = 0; q <= N; ++q)
        if (!(d[q] - slack > delta))
            return 0;
    return 1;
}

static int pair_eq(const ttd_mesh_ccd_pair *x, const ttd_mesh_ccd_pair *y)
{
    return x->kind == y->kind && x->a[0] == y->a[0] && x->a[1] == y->a[1] && x->b[0] == y->b[0] &&
           x->b[1] == y->b[1];
}

/* r (the library's) against ref (the brute force's), as the top of this file says. */
static int agrees(const ttd_mesh_ccd_result *r, const ttd_mesh_ccd_result *ref, const side *a, const side *b,
                  double delta)
{
    for (size_t i = 0; i < r->count; ++i) {
        size_t j = 0;
        while (j < ref->count && !pair_eq(&r->pairs[i], &ref->pairs[j]))
            ++j;
        /* the brute force keeps only its own window: a reported pair later than its earliest +
         * 2^-52 is fine only when the brute force's earliest is a false positive (checked below) */
        if (j == ref->count) {
            if (!(ref->toi < r->toi))
                return 0;
        } else if (memcmp(&r->pairs[i].toi, &ref->pairs[j].toi, sizeof(double)) != 0 ||
                   r->pairs[i].flags != ref->pairs[j].flags) {
            return 0;
        }
    }
    if (r->count > 0 && r->pairs[0].toi != r->toi)
        return 0;
    for (size_t j = 0; j < ref->count; ++j) {
        if (!(ref->pairs[j].toi <= r->toi + TTD_CCD_DEFAULT_T_TOL))
            continue;
        size_t i = 0;
        while (i < r->count && !pair_eq(&r->pairs[i], &ref->pairs[j]))
            ++i;
        if (i == r->count && !proven_apart(&ref->pairs[j], a, b ? b : a, delta))
            return 0;
    }
    return 1;
}

static int same(const ttd_mesh_ccd_result *p, const ttd_mesh_ccd_result *q)
{
    if (memcmp(&p->toi, &q->toi, sizeof p->toi) != 0 || p->count != q->count || p->flags != q->flags)
        return 0;
    for (size_t i = 0; i < p->count; ++i) {
        const ttd_mesh_ccd_pair *a = &p->pairs[i], *b = &q->pairs[i];
        if (memcmp(&a->toi, &b->toi, sizeof a->toi) != 0 || a->kind != b->kind || a->a[0] != b->a[0] ||
            a->a[1] != b->a[1] || a->b[0] != b->b[0] || a->b[1] != b->b[1] || a->flags != b->flags)
            return 0;
    }
    return 1;
}

static void fail(const char *what, const side *a, const side *b, double delta, unsigned flags,
                 const ttd_mesh_ccd_result *r, const ttd_mesh_ccd_result *ref)
{
    fprintf(stderr, "fuzz_mesh_ccd: %s (delta %a, flags %u): toi %.17g (%zu pairs) against %.17g (%zu pairs)\n", what,
            delta, flags, r->toi, r->count, ref->toi, ref->count);
    for (int k = 0; k < 2; ++k) {
        const ttd_mesh_ccd_result *x = k ? ref : r;
        for (size_t i = 0; i < x->count; ++i)
            fprintf(stderr, "  %s pair: kind %u (%d %d | %d %d) toi %a gap %g\n", k ? "second" : "first",
                    x->pairs[i].kind, (int)x->pairs[i].a[0], (int)x->pairs[i].a[1], (int)x->pairs[i].b[0],
                    (int)x->pairs[i].b[1], x->pairs[i].toi, x->pairs[i].gap);
    }
    for (int s = 0; s < (b ? 2 : 1); ++s) {
        const side *m = s ? b : a;
        fprintf(stderr, "  mesh %d: %zu vertices, %zu triangles\n", s, m->nv, m->nt);
        for (size_t i = 0; i < m->nt; ++i)
            fprintf(stderr, "    f %u %u %u\n", m->tris[3 * i], m->tris[3 * i + 1], m->tris[3 * i + 2]);
        for (size_t i = 0; i < m->nv; ++i)
            fprintf(stderr, "    v %a %a %a -> %a %a %a\n", m->x0[3 * i], m->x0[3 * i + 1], m->x0[3 * i + 2],
                    m->x1[3 * i], m->x1[3 * i + 1], m->x1[3 * i + 2]);
    }
    abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 4)
        return 0;
    reader rd = {data, size, 0};
    const unsigned mode = next(&rd), sc = next(&rd);
    const int self = mode & 1;
    const unsigned flags = self && (mode & 2) ? (unsigned)TTD_SELF_SHARED_VERTEX : 0u;
    const double scale = ldexp(1.0, (int)(sc % 41) - 20); /* 2^-20 .. 2^20: floats hold these exactly */
    const double delta = (mode & 4) ? (double)(mode >> 3 & 7) / 8 * scale : 0.0;
    side a, b;
    make_side(&rd, &a, scale);
    if (!self)
        make_side(&rd, &b, scale);
    ttd_mesh *ma = NULL, *mb = NULL;
    if (ttd_mesh_create_d(NULL, a.x0, a.nv, a.tris, a.nt, &ma) != TTD_OK ||
        (!self && ttd_mesh_create_d(NULL, b.x0, b.nv, b.tris, b.nt, &mb) != TTD_OK))
        abort(); /* small finite meshes always build */
    ttd_options o1 = ttd_default_options(), o3 = ttd_default_options();
    o1.threads = 1;
    o3.threads = 3;
    ttd_mesh_ccd_result r1, r3, ref;
    ttd_status s1, s3;
    if (self) {
        s1 = ttd_mesh_self_ccd_d(&o1, ma, a.x1, delta, flags, &r1);
        s3 = ttd_mesh_self_ccd_d(&o3, ma, a.x1, delta, flags, &r3);
        if (brute_self_ccd(a.x0, a.x1, a.tris, a.nt, delta, flags != 0, &ref) != 0)
            abort();
    } else {
        s1 = ttd_mesh_ccd_d(&o1, ma, a.x1, mb, b.x1, delta, &r1);
        s3 = ttd_mesh_ccd_d(&o3, ma, a.x1, mb, b.x1, delta, &r3);
        if (brute_mesh_ccd(a.x0, a.x1, a.tris, a.nt, b.x0, b.x1, b.tris, b.nt, delta, &ref) != 0)
            abort();
    }
    if (s1 != TTD_OK || s3 != TTD_OK)
        fail("status", &a, self ? NULL : &b, delta, flags, &r1, &ref);
    if (!agrees(&r1, &ref, &a, self ? NULL : &b, delta))
        fail("against the brute force", &a, self ? NULL : &b, delta, flags, &r1, &ref);
    if (!same(&r3, &r1))
        fail("3 threads against 1", &a, self ? NULL : &b, delta, flags, &r3, &r1);
    /* float: every coordinate here is a float exactly */
    float fa0[24], fa1[24], fb0[24], fb1[24];
    for (size_t i = 0; i < 3 * a.nv; ++i)
        fa0[i] = (float)a.x0[i], fa1[i] = (float)a.x1[i];
    if (!self)
        for (size_t i = 0; i < 3 * b.nv; ++i)
            fb0[i] = (float)b.x0[i], fb1[i] = (float)b.x1[i];
    ttd_mesh *fa = NULL, *fb = NULL;
    if (ttd_mesh_create_f(NULL, fa0, a.nv, a.tris, a.nt, &fa) != TTD_OK ||
        (!self && ttd_mesh_create_f(NULL, fb0, b.nv, b.tris, b.nt, &fb) != TTD_OK))
        abort();
    ttd_mesh_ccd_result rf;
    const ttd_status sf = self ? ttd_mesh_self_ccd_f(&o1, fa, fa1, delta, flags, &rf)
                               : ttd_mesh_ccd_f(&o1, fa, fa1, fb, fb1, delta, &rf);
    if (sf != TTD_OK || !same(&rf, &r1))
        fail("float against double", &a, self ? NULL : &b, delta, flags, &rf, &r1);
    ttd_mesh_ccd_free(&r1);
    ttd_mesh_ccd_free(&r3);
    ttd_mesh_ccd_free(&rf);
    free(ref.pairs);
    ttd_mesh_destroy(ma);
    ttd_mesh_destroy(mb);
    ttd_mesh_destroy(fa);
    ttd_mesh_destroy(fb);
    return 0;
}
