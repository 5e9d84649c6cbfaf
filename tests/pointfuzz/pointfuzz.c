/* SPDX-License-Identifier: MIT */
/* The point queries' differential fuzzer core (pointfuzz.h). */
#include "pointfuzz/pointfuzz.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ref_winding.h"
#include "ttd/ttd.h"

size_t pf_sides_checked;
pf_counts pf_count;

void pf_src_init(pf_src *src, const uint8_t *data, size_t size, uint64_t seed)
{
    src->data = data;
    src->size = data ? size : 0;
    src->pos = 0;
    uint64_t h = seed ^ 0x9E3779B97F4A7C15ull;
    for (size_t i = 0; i < src->size; ++i)
        h = (h ^ data[i]) * 0x100000001B3ull;
    src->state = h;
    src->log = NULL;
    src->nlog = src->caplog = src->nlog_first = 0;
}

static uint64_t pf_u64_raw(pf_src *s)
{
    if (s->pos + 8 <= s->size) {
        uint64_t x = 0;
        memcpy(&x, s->data + s->pos, 8);
        s->pos += 8;
        return x;
    }
    s->pos = s->size;
    uint64_t z = (s->state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static uint64_t pf_u64(pf_src *s)
{
    const uint64_t x = pf_u64_raw(s);
    if (s->log != NULL && s->nlog < s->caplog)
        s->log[s->nlog] = x;
    s->nlog++;
    return x;
}

static double pf_unit(pf_src *s)
{
    return (double)(pf_u64(s) >> 11) * 0x1p-53;
}

static int pf_int(pf_src *s, int n)
{
    return (int)(pf_u64(s) % (uint64_t)n);
}

#define PF_MAX_TRIS 24
#define PF_MAX_POINTS 48

typedef struct pf_case {
    int use_float, has_pose;
    int orient;                    /* -1: the hostile soup; else a closed jittered box made
                                    * ttd_orientation orient: outward as drawn, inward (every face
                                    * reversed), inconsistent (some reversed), open (one removed) */
    uint32_t t0[3 * PF_MAX_TRIS];  /* a box's triangles as drawn (outward); unwelded: by the drawn
                                    * vertices' numbers (first[] gives each one's first copy) */
    int unwelded;                  /* each triangle its own corners, moved by up to 2 ulps (STL) */
    int scale_exp;                 /* the case was scaled by 2^scale_exp at last (0: not) */
    size_t nt_big;                 /* the triangles before the tiny box's (all where none) */
    double size;                   /* the box's (the soup's) size: its scale */
    double tiny;                   /* the tiny box's size (0: none) */
    uint32_t first[3 * PF_MAX_TRIS], orig[3 * PF_MAX_TRIS]; /* unwelded: copies and originals */
    size_t nv, nt, n;
    double v[9 * PF_MAX_TRIS];
    uint32_t t[3 * PF_MAX_TRIS];
    double p[3 * PF_MAX_POINTS];
    double pose[12];
    double ub;
} pf_case;

/* A mesh of hostile triangles in [0, 1]^3, some sharing vertices with the one before. */
static void pf_mesh(pf_src *s, pf_case *c)
{
    c->nt = 1 + (size_t)pf_int(s, PF_MAX_TRIS);
    c->nv = 0;
    for (size_t t = 0; t < c->nt; ++t) {
        double *v = c->v + 3 * c->nv;
        const int kind = pf_int(s, 8);
        const int share = t > 0 && pf_int(s, 3) == 0; /* reuse the previous triangle's last two vertices */
        size_t base = c->nv;
        for (int k = 0; k < 9; ++k)
            v[k] = pf_unit(s);
        const double w = pow(10.0, -(double)pf_int(s, 16));
        for (int k = 0; k < 3; ++k) {
            switch (kind) {
            case 1: v[6 + k] = v[k] + w * (v[3 + k] - v[k]) + (k == 2 ? w : 0); break;         /* needle */
            case 2: v[6 + k] = v[k] + 0.4 * (v[3 + k] - v[k]) + (k == 1 ? w : 0); break;       /* sliver */
            case 3: v[6 + k] = v[k] + 0.5 * (v[3 + k] - v[k]); break;                          /* segment */
            case 4: v[3 + k] = v[6 + k] = v[k]; break;                                          /* point */
            case 5: v[3 + k] = v[k]; break;                                                     /* repeated vertex */
            default: break;
            }
        }
        c->nv += 3;
        for (int k = 0; k < 3; ++k)
            c->t[3 * t + (size_t)k] = (uint32_t)(base + (size_t)k);
        if (share) {
            c->t[3 * t] = c->t[3 * (t - 1) + 1];
            c->t[3 * t + 1] = c->t[3 * (t - 1) + 2];
        }
        if (kind == 6 && t > 0) /* a duplicate */
            memcpy(&c->t[3 * t], &c->t[3 * (t - 1)], 3 * sizeof(uint32_t));
    }
}

static const uint32_t pf_box_faces[36] = {0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5, 0, 4, 5, 0, 5, 1,
                                          2, 3, 7, 2, 7, 6, 0, 2, 6, 0, 6, 4, 1, 5, 7, 1, 7, 3};

/* A closed box: the unit cube's corners (corner k at (k >> 2, k >> 1 & 1, k & 1)) jittered by up to
 * 0.1, wound outward (t0); then made c->orient: every face reversed, some (not all, not none)
 * reversed, or one face removed. */
static void pf_box(pf_src *s, pf_case *c)
{
    const uint32_t *faces = pf_box_faces;
    c->nv = 8;
    for (uint32_t k = 0; k < 8; ++k) {
        const double corner[3] = {(double)(k >> 2), (double)(k >> 1 & 1), (double)(k & 1)};
        for (int r = 0; r < 3; ++r)
            c->v[3 * k + (uint32_t)r] = corner[r] + 0.2 * (pf_unit(s) - 0.5);
    }
    c->nt = 12;
    memcpy(c->t0, faces, sizeof pf_box_faces);
    memcpy(c->t, faces, sizeof pf_box_faces);
    if (c->orient == TTD_ORIENTATION_INWARD || c->orient == TTD_ORIENTATION_INCONSISTENT) {
        const int some = c->orient == TTD_ORIENTATION_INCONSISTENT;
        const uint32_t keep = some ? 1u + (uint32_t)pf_int(s, 12) : 0; /* face keep - 1 never reversed */
        /* face flip always: one of the 11 others. The draw j = 0..9 gives keep + 1 .. keep + 10 (as
         * before, so the corpus's inputs draw the same boxes) and j = 10 the one left, keep; it gave
         * (keep + 11) % 12 = keep - 1 once, which reversed the kept face too, and every face where
         * the coin said so for the other 11 (a consistent, inward box called inconsistent:
         * tests/fuzz/corpus/points/box-inconsistent-all-reversed). */
        const uint32_t j = some ? (uint32_t)pf_int(s, 11) : 0;
        const uint32_t flip = some ? (j == 10 ? keep : keep + 1u + j) % 12 : 0;
        for (uint32_t t = 0; t < 12; ++t)
            if (!some || t == flip || (t != keep - 1 && pf_int(s, 2))) {
                const uint32_t x = c->t[3 * t + 1];
                c->t[3 * t + 1] = c->t[3 * t + 2];
                c->t[3 * t + 2] = x;
            }
    } else if (c->orient == TTD_ORIENTATION_OPEN) {
        const size_t gone = (size_t)pf_int(s, 12);
        memmove(c->t + 3 * gone, c->t + 3 * (gone + 1), 3 * (11 - gone) * sizeof *c->t);
        c->nt = 11;
    }
}

/* Whether the box's vertices v (of the query's precision, `bytes`) enclose no volume: the sum of
 * the drawn (outward) triangles' determinants about vertex 0, in long double, within 1e-12 of
 * the box's size cubed (rounding has collapsed it). */
static int pf_flat(const pf_case *c, const void *v, size_t bytes)
{
    long double sum = 0, size = 0, x[8][3];
    for (int k = 0; k < 8; ++k)
        for (int r = 0; r < 3; ++r)
            x[k][r] = bytes == 8 ? (long double)((const double *)v)[3 * k + r] : (long double)((const float *)v)[3 * k + r];
    for (int k = 7; k >= 0; --k) /* about vertex 0 (exact in long double) */
        for (int r = 0; r < 3; ++r) {
            x[k][r] -= x[0][r];
            size = fmaxl(size, fabsl(x[k][r]));
        }
    for (int t = 0; t < 12; ++t) {
        const long double *a = x[c->t0[3 * t]], *b = x[c->t0[3 * t + 1]], *d = x[c->t0[3 * t + 2]];
        sum += a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) + a[2] * (b[0] * d[1] - b[1] * d[0]);
    }
    return !(fabsl(sum) > 1e-12L * size * size * size);
}

/* Weights (u, w) of a point uniform on a triangle: u, w >= 0, u + w <= 1. */
static void pf_barycentric(pf_src *s, double *u, double *w)
{
    *u = pf_unit(s);
    *w = pf_unit(s);
    if (*u + *w > 1) {
        *u = 1 - *u;
        *w = 1 - *w;
    }
}

/* Points: on a triangle's face, edge or vertex, 10^-k off it, in the box, far. */
static void pf_points(pf_src *s, pf_case *c)
{
    c->n = 1 + (size_t)pf_int(s, PF_MAX_POINTS);
    for (size_t i = 0; i < c->n; ++i) {
        const size_t t = (size_t)pf_int(s, (int)c->nt);
        const double *a = c->v + 3 * c->t[3 * t], *b = c->v + 3 * c->t[3 * t + 1], *d = c->v + 3 * c->t[3 * t + 2];
        double u, w;
        pf_barycentric(s, &u, &w);
        const int kind = pf_int(s, 7);
        const double off = pow(10.0, -(double)pf_int(s, 17));
        for (int k = 0; k < 3; ++k) {
            const double face = a[k] + u * (b[k] - a[k]) + w * (d[k] - a[k]);
            double x;
            switch (kind) {
            case 0: x = face; break;
            case 1: x = a[k] + u * (b[k] - a[k]); break;
            case 2: x = b[k]; break;
            case 3: x = face + off * (pf_unit(s) - 0.5); break;
            case 4: x = 1.5 * pf_unit(s) - 0.25; break;
            case 5: x = 1e4 * (pf_unit(s) - 0.5); break;
            default: x = i > 0 ? c->p[3 * (i - 1) + (size_t)k] : face; break; /* a repeated point */
            }
            c->p[3 * i + (size_t)k] = x;
        }
    }
}

/* x moved by m units in the last place of the query's precision. */
static double pf_ulps(double x, int m, int use_float)
{
    if (use_float) {
        float f = (float)x;
        for (; m > 0; --m)
            f = nextafterf(f, INFINITY);
        for (; m < 0; ++m)
            f = nextafterf(f, -INFINITY);
        return (double)f;
    }
    for (; m > 0; --m)
        x = nextafter(x, (double)INFINITY);
    for (; m < 0; ++m)
        x = nextafter(x, -(double)INFINITY);
    return x;
}

/* A tiny box beside or inside the big one: a jittered box 2^-j the big one's size (j = 4..563 in
 * double, 4..43 in float) at the origin, where its coordinates can be that small; the case is
 * moved first so that the origin is the big box's centre (the tiny box nested: w = 2 or 0 in it)
 * or 0.3 of its size beyond its corner 0 (w = +-1), the pose's translation dropped (a point's move
 * into the mesh frame would round away a tiny feature), and half the points put on, near and
 * around the tiny box. Wound as the big box is made (reversed with it; either way where the big
 * box is inconsistent or open); t0 has it as drawn. */
static void pf_tiny(pf_src *s, pf_case *c)
{
    const int j = 4 + pf_int(s, c->use_float ? 40 : 560);
    const double st = ldexp(c->size, -j);
    double u[3];
    const int nested = pf_int(s, 2);
    for (int r = 0; r < 3; ++r)
        u[r] = nested ? 0.5 * (c->v[r] + c->v[21 + r]) : c->v[r] - 0.3 * c->size;
    for (size_t i = 0; i < c->nv; ++i)
        for (int r = 0; r < 3; ++r)
            c->v[3 * i + (size_t)r] -= u[r];
    const double *P = c->pose;
    for (size_t i = 0; i < c->n; ++i) { /* the point in the mesh's frame, moved with the mesh, back by R alone */
        double *p = c->p + 3 * i, x[3];
        for (int k = 0; k < 3; ++k)
            x[k] = c->has_pose ? P[k] * (p[0] - P[3]) + P[4 + k] * (p[1] - P[7]) + P[8 + k] * (p[2] - P[11]) - u[k]
                               : p[k] - u[k];
        for (int r = 0; r < 3; ++r)
            p[r] = c->has_pose ? P[4 * r] * x[0] + P[4 * r + 1] * x[1] + P[4 * r + 2] * x[2] : x[r];
    }
    c->pose[3] = c->pose[7] = c->pose[11] = 0;
    const uint32_t base = (uint32_t)c->nv;
    for (uint32_t k = 0; k < 8; ++k) {
        const double corner[3] = {(double)(k >> 2), (double)(k >> 1 & 1), (double)(k & 1)};
        for (int r = 0; r < 3; ++r)
            c->v[3 * (base + k) + (uint32_t)r] = st * (corner[r] - 0.5 + 0.2 * (pf_unit(s) - 0.5));
    }
    c->nv += 8;
    const int drawn = pf_int(s, 2) ? 1 : -1; /* as t0 has it: outward or reversed */
    for (uint32_t t = 0; t < 12; ++t) {
        int wind = drawn;
        if (c->orient == TTD_ORIENTATION_INWARD)
            wind = -drawn;
        else if (c->orient != TTD_ORIENTATION_OUTWARD && pf_int(s, 2))
            wind = -drawn;
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = base + pf_box_faces[3 * t + (uint32_t)k];
            const uint32_t b = base + pf_box_faces[3 * t + (uint32_t)(k == 0 ? 0 : 3 - k)];
            c->t0[36 + 3 * t + (uint32_t)k] = drawn > 0 ? a : b;
            c->t[3 * c->nt + 3 * t + (uint32_t)k] = wind > 0 ? a : b;
        }
    }
    c->nt += 12;
    for (size_t i = 1; i < c->n; i += 2) {
        const size_t t = c->nt - 12 + (size_t)pf_int(s, 12);
        const double *a = c->v + 3 * c->t[3 * t], *b = c->v + 3 * c->t[3 * t + 1], *d = c->v + 3 * c->t[3 * t + 2];
        double w0, w1;
        pf_barycentric(s, &w0, &w1);
        const int kind = pf_int(s, 4);
        const double off = st * pow(10.0, -(double)pf_int(s, 17));
        double x[3];
        for (int k = 0; k < 3; ++k) {
            const double face = a[k] + w0 * (b[k] - a[k]) + w1 * (d[k] - a[k]);
            x[k] = kind == 0 ? face : kind == 1 ? face + off * (pf_unit(s) - 0.5) : kind == 2 ? 3 * st * (pf_unit(s) - 0.5) : b[k];
        }
        for (int r = 0; r < 3; ++r)
            c->p[3 * i + (size_t)r] = c->has_pose ? P[4 * r] * x[0] + P[4 * r + 1] * x[1] + P[4 * r + 2] * x[2] : x[r];
    }
    c->tiny = st;
    ++pf_count.tiny;
}

/* Unwelded, as STL files and many CAD exports write a mesh: every triangle its own three corners,
 * each coordinate moved by -2..2 units in the last place of the query's precision. */
static void pf_unweld(pf_src *s, pf_case *c)
{
    double v[9 * PF_MAX_TRIS];
    for (size_t i = 0; i < c->nv; ++i)
        c->first[i] = UINT32_MAX;
    for (size_t t = 0; t < c->nt; ++t)
        for (int k = 0; k < 3; ++k) {
            const uint32_t o = c->t[3 * t + (size_t)k], n = (uint32_t)(3 * t + (size_t)k);
            for (int r = 0; r < 3; ++r)
                v[3 * n + (uint32_t)r] = pf_ulps(c->v[3 * o + (uint32_t)r], pf_int(s, 5) - 2, c->use_float);
            if (c->first[o] == UINT32_MAX)
                c->first[o] = n;
            c->orig[n] = o;
            c->t[3 * t + (size_t)k] = n;
        }
    c->nv = 3 * c->nt;
    memcpy(c->v, v, 3 * c->nv * sizeof *v);
    c->unwelded = 1;
    ++pf_count.unwelded;
}

/* The whole case scaled by 2^k, k across the coordinate range: up to where a point's move into the
 * mesh's frame stays below 2^508 (double) or 2^60 (float), down to where the box (the tiny box) is
 * 2^-950 (2^-100) in size; a quarter of the time within 10 of either end. */
static void pf_scale(pf_src *s, pf_case *c)
{
    double m = fmax(fabs(c->pose[3]), fmax(fabs(c->pose[7]), fabs(c->pose[11])));
    for (size_t i = 0; i < 3 * c->nv; ++i)
        m = fmax(m, fabs(c->v[i]));
    for (size_t i = 0; i < 3 * c->n; ++i)
        m = fmax(m, fabs(c->p[i]));
    const double small = c->tiny > 0 ? c->tiny : c->size;
    /* ilogb of 0, inf or NaN is INT_MIN or INT_MAX: no scale to pick then (and no overflow) */
    if (!(m > 0) || !isfinite(m) || !(small > 0) || !isfinite(small))
        return;
    const int hi = (c->use_float ? 58 : 506) - (ilogb(m) + 2);
    const int lo = (c->use_float ? -100 : -950) - ilogb(small);
    const int pick = pf_int(s, 8);
    if (lo >= hi)
        return;
    const int k = pick == 0 ? lo + pf_int(s, 10) : pick == 1 ? hi - pf_int(s, 10) : lo + pf_int(s, hi - lo + 1);
    for (size_t i = 0; i < 3 * c->nv; ++i)
        c->v[i] = ldexp(c->v[i], k);
    for (size_t i = 0; i < 3 * c->n; ++i)
        c->p[i] = ldexp(c->p[i], k);
    c->pose[3] = ldexp(c->pose[3], k);
    c->pose[7] = ldexp(c->pose[7], k);
    c->pose[11] = ldexp(c->pose[11], k);
    c->ub = ldexp(c->ub, k);
    c->size = ldexp(c->size, k);
    c->tiny = ldexp(c->tiny, k);
    c->scale_exp = k;
    pf_count.exp_lo = pf_count.scaled == 0 || k < pf_count.exp_lo ? k : pf_count.exp_lo;
    pf_count.exp_hi = pf_count.scaled == 0 || k > pf_count.exp_hi ? k : pf_count.exp_hi;
    ++pf_count.scaled;
}

/* The families added after the first ones, drawn after everything above so that an input found
 * before them draws the same case where these draws say none (tests/fuzz/corpus/points/): of the
 * boxes, a third get a tiny box and a third are unwelded; a quarter of all cases are scaled by a
 * power of two across the coordinate range. */
static void pf_extras(pf_src *s, pf_case *c)
{
    c->nt_big = c->nt;
    if (c->orient >= 0 && pf_int(s, 3) == 0)
        pf_tiny(s, c);
    if (c->orient >= 0 && pf_int(s, 3) == 0)
        pf_unweld(s, c);
    if (pf_int(s, 4) == 0)
        pf_scale(s, c);
}

static void pf_case_draw(pf_src *s, pf_case *c)
{
    memset(c, 0, sizeof *c);
    c->use_float = pf_int(s, 2);
    /* a third of the cases: a closed box, outward, inward, inconsistent or open */
    c->orient = pf_int(s, 3) == 0 ? (int)pf_int(s, 4) : -1;
    if (c->orient >= 0)
        pf_box(s, c);
    else
        pf_mesh(s, c);
    pf_points(s, c);
    /* scale and offset */
    const double scale = pow(10.0, (double)(pf_int(s, 17) - 8));
    const double offset = pf_int(s, 3) == 0 ? 1e6 * (pf_unit(s) - 0.5) : 0;
    for (size_t i = 0; i < 3 * c->nv; ++i)
        c->v[i] = c->v[i] * scale + offset;
    for (size_t i = 0; i < 3 * c->n; ++i)
        c->p[i] = c->p[i] * scale + offset;
    c->ub = pf_int(s, 3) == 0 ? scale * pf_unit(s) * 0.5 : (double)INFINITY;
    c->has_pose = pf_int(s, 4) == 0;
    if (c->has_pose) { /* a rotation about z by a quarter turn and a translation */
        const double tr = scale * (pf_unit(s) - 0.5);
        const double P[12] = {0, -1, 0, tr, 1, 0, 0, 0, 0, 0, 1, -tr};
        memcpy(c->pose, P, sizeof P);
    }
    c->size = scale;
    s->nlog_first = s->nlog;
    pf_extras(s, c);
}

static void pf_dump(FILE *out, const pf_case *c)
{
    fprintf(out, "  case: %s, %zu triangles, %zu points, bound %.17g%s%s%s%s, scaled by 2^%d", c->use_float ? "float" : "double",
            c->nt, c->n, c->ub, c->has_pose ? ", posed" : "", c->orient >= 0 ? ", a box " : "",
            c->orient >= 0 ? ttd_orientation_string((ttd_orientation)c->orient) : "", c->unwelded ? ", unwelded" : "",
            c->scale_exp);
    if (c->tiny > 0)
        fprintf(out, ", a tiny box %.3g (its triangles from %zu)", c->tiny, c->nt_big);
    fputc('\n', out);
    for (size_t t = 0; t < c->nt; ++t) {
        fprintf(out, "    tri %zu:", t);
        for (int k = 0; k < 3; ++k) {
            const double *v = c->v + 3 * c->t[3 * t + (size_t)k];
            fprintf(out, " (%.17g %.17g %.17g)", v[0], v[1], v[2]);
        }
        fputc('\n', out);
    }
    for (size_t i = 0; i < c->n; ++i)
        fprintf(out, "    point %zu: %.17g %.17g %.17g\n", i, c->p[3 * i], c->p[3 * i + 1], c->p[3 * i + 2]);
}

#define PF_FAIL(...)                                                                                   \
    do {                                                                                               \
        if (out) {                                                                                     \
            fprintf(out, "pointfuzz: ");                                                               \
            fprintf(out, __VA_ARGS__);                                                                 \
            fputc('\n', out);                                                                          \
        }                                                                                              \
        ++fails;                                                                                       \
    } while (0)

/* The case in one precision: real, the result type and the entries' suffix. */
#define PF_BODY(real, sfx)                                                                             \
    {                                                                                                  \
        real v[9 * PF_MAX_TRIS], p[3 * PF_MAX_POINTS], pose[12], x[3 * PF_MAX_POINTS];                 \
        for (size_t i = 0; i < 3 * c.nv; ++i)                                                          \
            v[i] = (real)c.v[i];                                                                       \
        for (size_t i = 0; i < 3 * c.n; ++i)                                                           \
            p[i] = (real)c.p[i];                                                                       \
        for (int k = 0; k < 12; ++k)                                                                   \
            pose[k] = (real)c.pose[k];                                                                 \
        const real ub = (real)c.ub;                                                                    \
        ttd_mesh *mesh;                                                                                \
        if (ttd_mesh_create_##sfx(NULL, v, c.nv, c.t, c.nt, &mesh) != TTD_OK) {                        \
            PF_FAIL("mesh not built");                                                                 \
            break;                                                                                     \
        }                                                                                              \
        /* the points in the mesh's frame, by the documented formula */                               \
        for (size_t i = 0; i < c.n; ++i)                                                               \
            for (int k = 0; k < 3; ++k)                                                                \
                x[3 * i + (size_t)k] = c.has_pose ? (pose[k] * (p[3 * i] - pose[3]) + pose[4 + k] * (p[3 * i + 1] - pose[7])) + \
                                                        pose[8 + k] * (p[3 * i + 2] - pose[11])        \
                                                  : p[3 * i + (size_t)k];                              \
        ttd_point_result_##sfx ref[PF_MAX_POINTS], got[PF_MAX_POINTS];                                 \
        double dpart[2][PF_MAX_POINTS]; /* the distance to the triangles before the tiny box's, to its */ \
        for (size_t i = 0; i < c.n; ++i) {                                                             \
            ttd_point_result_##sfx *b = &ref[i];                                                       \
            b->distance = (real)INFINITY;                                                              \
            b->triangle = UINT32_MAX;                                                                  \
            dpart[0][i] = dpart[1][i] = HUGE_VAL;                                                      \
            for (size_t t = 0; t < c.nt; ++t) {                                                        \
                real tri[9];                                                                           \
                for (int k = 0; k < 9; ++k)                                                            \
                    tri[k] = v[3 * c.t[3 * t + (size_t)(k / 3)] + (size_t)(k % 3)];                    \
                ttd_point_result_##sfx r;                                                              \
                if (ttd_point_triangle_##sfx(x + 3 * i, tri, &r) != TTD_OK)                            \
                    PF_FAIL("ttd_point_triangle refused point %zu", i);                                \
                dpart[t >= c.nt_big][i] = fmin(dpart[t >= c.nt_big][i], (double)r.distance);           \
                if (r.distance < b->distance && r.distance <= ub) {                                    \
                    *b = r;                                                                            \
                    b->triangle = (uint32_t)t;                                                         \
                }                                                                                      \
            }                                                                                          \
            if (c.has_pose && b->triangle != UINT32_MAX) {                                             \
                const real y[3] = {b->point[0], b->point[1], b->point[2]};                             \
                for (int k = 0; k < 3; ++k)                                                            \
                    b->point[k] = ((pose[4 * k] * y[0] + pose[4 * k + 1] * y[1]) + pose[4 * k + 2] * y[2]) + pose[4 * k + 3]; \
            }                                                                                          \
        }                                                                                              \
        for (int run = 0; run < 3; ++run) {                                                            \
            ttd_options o = ttd_default_options();                                                     \
            o.isa = run == 0 ? TTD_ISA_SCALAR : TTD_ISA_AUTO;                                          \
            o.threads = run == 2 ? 2 : 1;                                                              \
            const ttd_status st = ttd_points_closest_##sfx(&o, mesh, c.n, p, c.has_pose ? pose : NULL, ub, got); \
            if (st != TTD_OK) {                                                                        \
                PF_FAIL("run %d: status %s", run, ttd_status_string(st));                              \
                continue;                                                                              \
            }                                                                                          \
            for (size_t i = 0; i < c.n; ++i) {                                                         \
                const ttd_point_result_##sfx *a = &got[i], *b = &ref[i];                               \
                const int same = b->triangle == UINT32_MAX                                            \
                                     ? a->triangle == UINT32_MAX && a->flags == TTD_POINT_ABOVE_BOUND && isinf(a->distance) \
                                     : memcmp(&a->distance, &b->distance, sizeof a->distance) == 0 &&  \
                                           a->triangle == b->triangle &&                               \
                                           memcmp(a->point, b->point, sizeof a->point) == 0 &&         \
                                           memcmp(a->bary, b->bary, sizeof a->bary) == 0 && a->feature == b->feature; \
                if (!same)                                                                             \
                    PF_FAIL("run %d point %zu: %.17g (tri %u) vs brute force %.17g (tri %u)", run, i,   \
                            (double)a->distance, a->triangle, (double)b->distance, b->triangle);       \
            }                                                                                          \
        }                                                                                              \
        double vv[9 * PF_MAX_TRIS], lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}; \
        for (size_t i = 0; i < 3 * c.nv; ++i) {                                                        \
            vv[i] = (double)v[i];                                                                      \
            lo[i % 3] = fmin(lo[i % 3], vv[i]);                                                        \
            hi[i % 3] = fmax(hi[i % 3], vv[i]);                                                        \
        }                                                                                              \
        const double size = hypot(hypot(hi[0] - lo[0], hi[1] - lo[1]), hi[2] - lo[2]); /* no underflow */   \
        const double near = sizeof(real) == 4 ? 1e-5 : 1e-9;                                           \
        int far[PF_MAX_POINTS]; /* off the surface enough for the long double sum to be a reference */ \
        for (size_t i = 0; i < c.n; ++i)                                                               \
            far[i] = dpart[0][i] > near * size && dpart[1][i] > near * c.tiny;                         \
        real sd[PF_MAX_POINTS];                                                                        \
        uint8_t in[PF_MAX_POINTS];                                                                     \
        if (ttd_points_signed_distance_##sfx(NULL, mesh, c.n, p, c.has_pose ? pose : NULL, ub, sd, got) != TTD_OK || \
            ttd_points_contains_##sfx(NULL, mesh, c.n, p, c.has_pose ? pose : NULL, in) != TTD_OK) {   \
            PF_FAIL("signed distance or contains refused the case");                                   \
        } else {                                                                                       \
            for (size_t i = 0; i < c.n; ++i) {                                                         \
                const real d = ref[i].triangle == UINT32_MAX ? (real)INFINITY : ref[i].distance;       \
                if (!(sd[i] == (in[i] ? -d : d)) || ((got[i].flags & TTD_POINT_INSIDE) != 0) != (in[i] != 0)) \
                    PF_FAIL("point %zu: signed %.17g, distance %.17g, inside %d", i, (double)sd[i], (double)d, in[i]); \
            }                                                                                          \
            /* every proven side against the long double sum, for points 1e-9 of the mesh's size or    \
             * more off it (1e-5 in float, whose distances round by about 1e-7 of it: a point on a     \
             * box's face read 1.1e-13 off it at size 1.7e-5), and as far off a tiny box relative to   \
             * its size, where that sum is 1e-9 or more from 1/2 */                                    \
            for (size_t i = 0; i < c.n; ++i) {                                                         \
                if (ref[i].triangle == UINT32_MAX || !far[i] ||                                        \
                    (got[i].flags & (TTD_POINT_SIGN_UNPROVEN | TTD_POINT_NONFINITE)))                  \
                    continue;                                                                          \
                const double xd[3] = {(double)x[3 * i], (double)x[3 * i + 1], (double)x[3 * i + 2]};   \
                const long double wr = ref_winding_ld(vv, c.t, c.nt, xd);                              \
                if (fabsl(fabsl(wr) - 0.5L) > 1e-9L && ((got[i].flags & TTD_POINT_INSIDE) != 0) != (fabsl(wr) >= 0.5L)) \
                    PF_FAIL("point %zu: inside %d, the long double winding number %.17Lg (%.3g off, size %.3g)", i, \
                            (got[i].flags & TTD_POINT_INSIDE) != 0, wr, (double)ref[i].distance, size); \
                ++*sides;                                                                              \
            }                                                                                          \
        }                                                                                              \
        if (c.orient >= 0) {                                                                           \
            real w[PF_MAX_POINTS], sd0[PF_MAX_POINTS];                                                 \
            uint8_t in0[PF_MAX_POINTS];                                                                \
            ttd_orientation o;                                                                         \
            /* rounding to the query's precision may have flattened the box (float, 1e-8 at 1e6) */    \
            const int drawn = c.unwelded ? TTD_ORIENTATION_OPEN /* by index */                         \
                              : c.orient != TTD_ORIENTATION_OPEN && c.orient != TTD_ORIENTATION_INCONSISTENT && \
                                      pf_flat(&c, v, sizeof(real))                                     \
                                  ? TTD_ORIENTATION_FLAT                                               \
                                  : c.orient;                                                          \
            if (ttd_mesh_orientation(mesh, &o) != TTD_OK || (int)o != drawn)                           \
                PF_FAIL("orientation %s, drawn %s", ttd_orientation_string(o),                        \
                        ttd_orientation_string((ttd_orientation)drawn));                               \
            if (ttd_points_winding_number_##sfx(NULL, mesh, c.n, p, c.has_pose ? pose : NULL, w) != TTD_OK) \
                PF_FAIL("winding number refused the case");                                            \
            for (size_t i = 0; i < c.n; ++i) /* one rule: contains is the reported winding's side */  \
                if (in[i] != ttd_winding_inside((double)w[i]))                                         \
                    PF_FAIL("point %zu: contains %d, winding %.17g", i, in[i], (double)w[i]);          \
            if (drawn == TTD_ORIENTATION_OUTWARD || drawn == TTD_ORIENTATION_INWARD) /* closed: exact */ \
                for (size_t i = 0; i < c.n; ++i) {                                                     \
                    const double xd[3] = {(double)x[3 * i], (double)x[3 * i + 1], (double)x[3 * i + 2]}; \
                    const long double wr = far[i] ? ref_winding_ld(vv, c.t, c.nt, xd) : 0;             \
                    if (far[i] && !(got[i].flags & TTD_POINT_ABOVE_BOUND) && (got[i].flags & TTD_POINT_SIGN_UNPROVEN)) \
                        PF_FAIL("point %zu: a closed mesh's side unproven", i);                        \
                    pf_count.exact += far[i] != 0;                                                     \
                    if (far[i] && (long double)w[i] != roundl(wr))                                     \
                        PF_FAIL("point %zu: a closed mesh's winding number %.17g, the long double sum %.17Lg", i, \
                                (double)w[i], wr);                                                     \
                }                                                                                      \
            ttd_mesh *m0;                                                                              \
            if (drawn == TTD_ORIENTATION_INWARD) { /* the outward box's inside, exactly */             \
                if (ttd_mesh_create_##sfx(NULL, v, c.nv, c.t0, c.nt, &m0) != TTD_OK ||                \
                    ttd_points_contains_##sfx(NULL, m0, c.n, p, c.has_pose ? pose : NULL, in0) != TTD_OK || \
                    ttd_points_signed_distance_##sfx(NULL, m0, c.n, p, c.has_pose ? pose : NULL, ub, sd0, NULL) != TTD_OK) { \
                    PF_FAIL("the outward box refused the case");                                      \
                } else {                                                                               \
                    for (size_t i = 0; i < c.n; ++i)                                                   \
                        if (in[i] != in0[i] || signbit(sd[i]) != signbit(sd0[i]))                      \
                            PF_FAIL("point %zu: inward contains %d signed %.17g, outward %d %.17g", i, in[i], \
                                    (double)sd[i], in0[i], (double)sd0[i]);                            \
                }                                                                                      \
                ttd_mesh_destroy(m0);                                                                  \
            } else if (c.orient != TTD_ORIENTATION_OUTWARD) { /* against the long double sum */        \
                for (size_t i = 0; i < c.n; ++i) {                                                     \
                    const double xd[3] = {(double)x[3 * i], (double)x[3 * i + 1], (double)x[3 * i + 2]}; \
                    const long double gap = fabsl(ref_winding_ld(vv, c.t, c.nt, xd)) - 0.5L;           \
                    if (!(dpart[0][i] > 1e-6 * c.size) || !(dpart[1][i] > 1e-6 * c.tiny) ||            \
                        got[i].flags & TTD_POINT_ABOVE_BOUND)                                          \
                        continue; /* on the surface to rounding: no reference; or no side asked */    \
                    if (got[i].flags & TTD_POINT_SIGN_UNPROVEN) {                                      \
                        if (!(fabsl(gap) < 1e-6L))                                                     \
                            PF_FAIL("point %zu: unproven %.3Lg from |w| = 1/2", i, gap);              \
                    } else if (fabsl(gap) > 1e-9L && in[i] != (gap >= 0)) {                            \
                        PF_FAIL("point %zu: contains %d, reference |w| - 1/2 = %.3Lg", i, in[i], gap); \
                    }                                                                                  \
                }                                                                                      \
            }                                                                                          \
        }                                                                                              \
        ttd_mesh_destroy(mesh);                                                                        \
    }

/* The checks of one case (its copy: the macro names it c). */
static int pf_check(pf_case c, FILE *out)
{
    size_t *sides = &pf_sides_checked;
    int fails = 0;
    do {
        if (c.use_float)
            PF_BODY(float, f)
        else
            PF_BODY(double, d)
    } while (0);
    return fails;
}

/* An unwelded box welded back (ttd_mesh_weld_*, tolerance 16 units in the last place of the largest
 * coordinate, where that is below 1/100 of the box): every drawn vertex's copies one vertex, no two
 * drawn vertices one, no triangle dropped; *w the welded case (the box as drawn, its own corners
 * moved by up to 2 ulps). Returns the failed checks; *w->nv 0 where no weld was tried. */
static int pf_weld(const pf_case *c, pf_case *w, FILE *out)
{
    int fails = 0;
    *w = *c;
    w->nv = 0;
    double m = 0;
    for (size_t i = 0; i < 3 * c->nv; ++i)
        m = fmax(m, fabs(c->v[i]));
    const double tol = ldexp(m, c->use_float ? -19 : -48);
    if (c->tiny > 0 || !(tol < 0.01 * c->size))
        return 0;
    uint32_t map[3 * PF_MAX_TRIS];
    size_t nv = 0, nt = 0;
    ttd_status st;
    if (c->use_float) {
        float vf[9 * PF_MAX_TRIS], of[9 * PF_MAX_TRIS];
        for (size_t i = 0; i < 3 * c->nv; ++i)
            vf[i] = (float)c->v[i];
        st = ttd_mesh_weld_f(vf, c->nv, c->t, c->nt, (float)tol, of, &nv, w->t, &nt, map);
        for (size_t i = 0; st == TTD_OK && i < 3 * nv; ++i)
            w->v[i] = (double)of[i];
    } else {
        st = ttd_mesh_weld_d(c->v, c->nv, c->t, c->nt, tol, w->v, &nv, w->t, &nt, map);
    }
    if (st != TTD_OK || nt != c->nt || nv != 8) {
        PF_FAIL("weld: status %s, %zu vertices and %zu triangles, drawn 8 and %zu", ttd_status_string(st), nv, nt, c->nt);
        return fails;
    }
    for (size_t i = 0; i < c->nv; ++i)
        if (map[i] != map[c->first[c->orig[i]]])
            PF_FAIL("weld: vertex %zu (a copy of %u) went to %u, its first copy to %u", i, c->orig[i], map[i],
                    map[c->first[c->orig[i]]]);
    for (uint32_t a = 0; a < 8; ++a)
        for (uint32_t b = 0; b < a; ++b)
            if (map[c->first[a]] == map[c->first[b]])
                PF_FAIL("weld: drawn vertices %u and %u made one", a, b);
    w->nv = nv;
    w->unwelded = 0;
    for (size_t i = 0; i < 36; ++i)
        w->t0[i] = map[c->first[c->t0[i]]];
    return fails;
}

int pf_run_case(pf_src *src, FILE *out, int dump, size_t *points)
{
    pf_case c;
    pf_case_draw(src, &c);
    int fails = pf_check(c, out);
    if (fails && dump && out)
        pf_dump(out, &c);
    if (c.unwelded) {
        pf_case w;
        int wf = pf_weld(&c, &w, out);
        if (wf == 0 && w.nv > 0) {
            ++pf_count.welded;
            wf = pf_check(w, out);
        }
        if (wf && dump && out) {
            fprintf(out, "  (the case welded)\n");
            pf_dump(out, wf && w.nv > 0 ? &w : &c);
        }
        fails += wf;
    }
    if (points)
        *points = c.n;
    return fails;
}

size_t pf_case_words(const uint8_t *data, size_t size, uint64_t seed, uint64_t *words, size_t cap, size_t *first)
{
    pf_src src;
    pf_src_init(&src, data, size, seed);
    src.log = words;
    src.caplog = cap;
    pf_case c;
    pf_case_draw(&src, &c);
    *first = src.nlog_first;
    return src.nlog;
}
