/* SPDX-License-Identifier: MIT */
/* The point queries' differential fuzzer core (pointfuzz.h). */
#include "pointfuzz/pointfuzz.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ref_winding.h"
#include "ttd/ttd.h"

size_t pf_sides_checked;

void pf_src_init(pf_src *src, const uint8_t *data, size_t size, uint64_t seed)
{
    src->data = data;
    src->size = data ? size : 0;
    src->pos = 0;
    uint64_t h = seed ^ 0x9E3779B97F4A7C15ull;
    for (size_t i = 0; i < src->size; ++i)
        h = (h ^ data[i]) * 0x100000001B3ull;
    src->state = h;
}

static uint64_t pf_u64(pf_src *s)
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
    uint32_t t0[3 * PF_MAX_TRIS];  /* a box's triangles as drawn (outward) */
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

/* A closed box: the unit cube's corners (corner k at (k >> 2, k >> 1 & 1, k & 1)) jittered by up to
 * 0.1, wound outward (t0); then made c->orient: every face reversed, some (not all, not none)
 * reversed, or one face removed. */
static void pf_box(pf_src *s, pf_case *c)
{
    static const uint32_t faces[36] = {0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5, 0, 4, 5, 0, 5, 1,
                                       2, 3, 7, 2, 7, 6, 0, 2, 6, 0, 6, 4, 1, 5, 7, 1, 7, 3};
    c->nv = 8;
    for (uint32_t k = 0; k < 8; ++k) {
        const double corner[3] = {(double)(k >> 2), (double)(k >> 1 & 1), (double)(k & 1)};
        for (int r = 0; r < 3; ++r)
            c->v[3 * k + (uint32_t)r] = corner[r] + 0.2 * (pf_unit(s) - 0.5);
    }
    c->nt = 12;
    memcpy(c->t0, faces, sizeof faces);
    memcpy(c->t, faces, sizeof faces);
    if (c->orient == TTD_ORIENTATION_INWARD || c->orient == TTD_ORIENTATION_INCONSISTENT) {
        const int some = c->orient == TTD_ORIENTATION_INCONSISTENT;
        const uint32_t keep = some ? 1u + (uint32_t)pf_int(s, 12) : 0; /* this one never reversed */
        const uint32_t flip = some ? (keep + 1u + (uint32_t)pf_int(s, 11)) % 12 : 0; /* this one always */
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

/* Points: on a triangle's face, edge or vertex, 10^-k off it, in the box, far. */
static void pf_points(pf_src *s, pf_case *c)
{
    c->n = 1 + (size_t)pf_int(s, PF_MAX_POINTS);
    for (size_t i = 0; i < c->n; ++i) {
        const size_t t = (size_t)pf_int(s, (int)c->nt);
        const double *a = c->v + 3 * c->t[3 * t], *b = c->v + 3 * c->t[3 * t + 1], *d = c->v + 3 * c->t[3 * t + 2];
        double u = pf_unit(s), w = pf_unit(s);
        if (u + w > 1) {
            u = 1 - u;
            w = 1 - w;
        }
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
}

static void pf_dump(FILE *out, const pf_case *c)
{
    fprintf(out, "  case: %s, %zu triangles, %zu points, bound %.17g%s%s%s\n", c->use_float ? "float" : "double", c->nt,
            c->n, c->ub, c->has_pose ? ", posed" : "", c->orient >= 0 ? ", a box " : "",
            c->orient >= 0 ? ttd_orientation_string((ttd_orientation)c->orient) : "");
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
        for (size_t i = 0; i < c.n; ++i) {                                                             \
            ttd_point_result_##sfx *b = &ref[i];                                                       \
            b->distance = (real)INFINITY;                                                              \
            b->triangle = UINT32_MAX;                                                                  \
            for (size_t t = 0; t < c.nt; ++t) {                                                        \
                real tri[9];                                                                           \
                for (int k = 0; k < 9; ++k)                                                            \
                    tri[k] = v[3 * c.t[3 * t + (size_t)(k / 3)] + (size_t)(k % 3)];                    \
                ttd_point_result_##sfx r;                                                              \
                if (ttd_point_triangle_##sfx(x + 3 * i, tri, &r) != TTD_OK)                            \
                    PF_FAIL("ttd_point_triangle refused point %zu", i);                                \
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
            /* every proven side against the long double sum, for points 1e-9 of the mesh's size or \
             * more off it (1e-5 in float, whose distances round by about 1e-7 of it: a point on a    \
             * box's face read 1.1e-13 off it at size 1.7e-5), where that sum is 1e-9 or more from 1/2 */ \
            double vv[9 * PF_MAX_TRIS], lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}; \
            for (size_t i = 0; i < 3 * c.nv; ++i) {                                                    \
                vv[i] = (double)v[i];                                                                  \
                lo[i % 3] = fmin(lo[i % 3], vv[i]);                                                    \
                hi[i % 3] = fmax(hi[i % 3], vv[i]);                                                    \
            }                                                                                          \
            const double size = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + \
                                     (hi[2] - lo[2]) * (hi[2] - lo[2]));                               \
            for (size_t i = 0; i < c.n; ++i) {                                                         \
                if (ref[i].triangle == UINT32_MAX ||                                                   \
                    !((double)ref[i].distance > (sizeof(real) == 4 ? 1e-5 : 1e-9) * size) ||            \
                    (got[i].flags & (TTD_POINT_SIGN_UNPROVEN | TTD_POINT_NONFINITE)))                  \
                    continue;                                                                          \
                const double xd[3] = {(double)x[3 * i], (double)x[3 * i + 1], (double)x[3 * i + 2]};   \
                const long double wr = ref_winding_ld(vv, c.t, c.nt, xd);                              \
                if (fabsl(fabsl(wr) - 0.5L) > 1e-9L && ((got[i].flags & TTD_POINT_INSIDE) != 0) != (fabsl(wr) >= 0.5L)) \
                    PF_FAIL("point %zu: inside %d, the long double winding number %.17Lg", i,           \
                            (got[i].flags & TTD_POINT_INSIDE) != 0, wr);                               \
                ++*sides;                                                                              \
            }                                                                                          \
        }                                                                                              \
        if (c.orient >= 0) {                                                                           \
            real w[PF_MAX_POINTS], sd0[PF_MAX_POINTS];                                                 \
            uint8_t in0[PF_MAX_POINTS];                                                                \
            ttd_orientation o;                                                                         \
            /* rounding to the query's precision may have flattened the box (float, 1e-8 at 1e6) */    \
            const int drawn = c.orient != TTD_ORIENTATION_OPEN && c.orient != TTD_ORIENTATION_INCONSISTENT && \
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
                    PF_FAIL("point %zu: contains %d, winding %.17g", i, in[i], (double)w[i]);         \
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
                double vd[3 * 8];                                                                      \
                for (size_t i = 0; i < 3 * c.nv; ++i)                                                  \
                    vd[i] = (double)v[i];                                                              \
                for (size_t i = 0; i < c.n; ++i) {                                                     \
                    const double xd[3] = {(double)x[3 * i], (double)x[3 * i + 1], (double)x[3 * i + 2]}; \
                    const long double gap = fabsl(ref_winding_ld(vd, c.t, c.nt, xd)) - 0.5L;          \
                    const double d = (double)ref[i].distance, size = (double)fabs(v[0] - v[3 * 7]);    \
                    if (!(d > 1e-6 * size) || got[i].flags & TTD_POINT_ABOVE_BOUND)                   \
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

int pf_run_case(pf_src *src, FILE *out, int dump, size_t *points)
{
    size_t *sides = &pf_sides_checked;
    pf_case c;
    pf_case_draw(src, &c);
    int fails = 0;
    do {
        if (c.use_float)
            PF_BODY(float, f)
        else
            PF_BODY(double, d)
    } while (0);
    if (fails && dump && out)
        pf_dump(out, &c);
    if (points)
        *points = c.n;
    return fails;
}
