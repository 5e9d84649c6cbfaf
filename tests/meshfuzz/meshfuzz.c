/* SPDX-License-Identifier: MIT */
/* The mesh-query fuzzer's core (meshfuzz.h): case generation, the brute-force oracle and the
 * checks. Everything a query returns is compared bit for bit with what the exact method on the
 * scalar row gives for the same triangle pairs: that is the promise of include/ttd/ttd.h
 * ("returns what the exact method over all triangle pairs would", "results do not depend on the
 * thread count or the instruction set"). Float cases run the float API; their results are
 * widened to double (exact), so one set of checks serves both precisions. */
#include "meshfuzz.h"
#include "self_brute.h"

#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "ref_distance.h"
#include "ttd/ttd.h"

enum { MAXK = 4, ND = 5, NC = 4, NCL = 3, NX = 4, MAX_CONFIGS = 2 * TTD_ISA_COUNT };

/* ---- the byte source ---------------------------------------------------------------------- */

static uint64_t splitmix(uint64_t *state)
{
    uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

void mf_src_seeded(mf_src *src, uint64_t seed, uint64_t index)
{
    uint64_t s = seed ^ (index * 0xD1B54A32D192ED03ull);
    src->data = NULL;
    src->size = src->pos = 0;
    src->state = splitmix(&s);
}

void mf_src_bytes(mf_src *src, const uint8_t *data, size_t size)
{
    uint64_t h = 0xCBF29CE484222325ull; /* FNV-1a: the stream after the input depends on all of it */
    for (size_t i = 0; i < size; ++i)
        h = (h ^ data[i]) * 0x100000001B3ull;
    src->data = data;
    src->size = size;
    src->pos = 0;
    src->state = h;
}

/* n bytes (1..8) of the input while it lasts, then of the stream. */
static uint64_t src_bytes(mf_src *src, int n)
{
    uint64_t v = 0;
    if (src->pos + (size_t)n <= src->size) {
        for (int i = 0; i < n; ++i)
            v = (v << 8) | src->data[src->pos + (size_t)i];
        src->pos += (size_t)n;
        return v;
    }
    src->pos = src->size;
    v = splitmix(&src->state);
    return n == 8 ? v : v >> (64 - 8 * n);
}

/* 0..n-1; one byte when that covers n (libFuzzer then picks it directly). */
static int rint_n(mf_src *src, int n)
{
    return (int)(src_bytes(src, n <= 256 ? 1 : 4) % (uint64_t)n);
}

/* Uniform in [0, 1) with 53 bits. */
static double unif(mf_src *src)
{
    return (double)(src_bytes(src, 7) >> 3) * 0x1p-53;
}

static double urange(mf_src *src, double lo, double hi)
{
    return lo + (hi - lo) * unif(src);
}

/* 10^u, u uniform in [lo, hi]. */
static double pow10u(mf_src *src, double lo, double hi)
{
    return pow(10.0, urange(src, lo, hi));
}

/* ---- names -------------------------------------------------------------------------------- */

static const char *const family_names[MF_COUNT] = {
    "collinear", "point", "segment", "repeated", "sliver", "needle", "duplicate",
    "coplanar",  "touch", "gap",     "scaled",   "tolerance", "grid", "mixed"};
static const char *const query_names[MFQ_COUNT] = {"pose",    "reference", "distance", "bound", "reltol",
                                                   "contacts", "closest",  "collide",  "k-poses", "threads",
                                                   "isa",      "refit",    "self"};

const char *mf_family_name(int family)
{
    return family >= 0 && family < MF_COUNT ? family_names[family] : "?";
}

int mf_family_from_name(const char *name)
{
    for (int i = 0; i < MF_COUNT; ++i)
        if (strcmp(name, family_names[i]) == 0)
            return i;
    return -1;
}

const char *mf_query_name(int query)
{
    return query >= 0 && query < MFQ_COUNT ? query_names[query] : "?";
}

/* ---- meshes ------------------------------------------------------------------------------- */

typedef struct mmesh {
    double *v; /* 3 per vertex; in a float case every value is a float */
    uint32_t *t;
    size_t nv, nt, cap_v, cap_t;
} mmesh;

static void *grow(void *p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap)
        return p;
    size_t c = *cap ? *cap : 16;
    while (c < need)
        c *= 2;
    void *q = realloc(p, c * elem);
    if (!q)
        abort();
    *cap = c;
    return q;
}

static uint32_t add_vertex(mmesh *m, const double x[3])
{
    m->v = grow(m->v, &m->cap_v, 3 * (m->nv + 1), sizeof *m->v);
    memcpy(m->v + 3 * m->nv, x, 3 * sizeof *x);
    return (uint32_t)m->nv++;
}

static void add_tri_idx(mmesh *m, uint32_t i, uint32_t j, uint32_t k)
{
    m->t = grow(m->t, &m->cap_t, 3 * (m->nt + 1), sizeof *m->t);
    m->t[3 * m->nt] = i, m->t[3 * m->nt + 1] = j, m->t[3 * m->nt + 2] = k;
    ++m->nt;
}

/* A triangle with fresh vertex records, in one of the 6 vertex orders. */
static void add_tri(mf_src *src, mmesh *m, const double p0[3], const double p1[3], const double p2[3])
{
    static const int perm[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
    const double *p[3] = {p0, p1, p2};
    const int *o = perm[rint_n(src, 6)];
    const uint32_t i = add_vertex(m, p[o[0]]), j = add_vertex(m, p[o[1]]), k = add_vertex(m, p[o[2]]);
    add_tri_idx(m, i, j, k);
}

/* ---- triangle kinds ----------------------------------------------------------------------- */

enum { K_ORDINARY, K_COLLINEAR, K_POINT, K_SEGMENT, K_REPEATED, K_SLIVER, K_NEEDLE, K_DUPLICATE, K_KINDS };

/* A point of the half-space of side (-1: z <= 0, mesh a; +1: z >= 0, mesh b) in the unit box;
 * a quarter on the plane z = 0, where a and b meet when a pose puts b on a. */
static void rand_point(mf_src *src, int side, double x[3])
{
    x[0] = urange(src, -1, 1);
    x[1] = urange(src, -1, 1);
    x[2] = rint_n(src, 4) == 0 ? 0.0 : side * urange(src, 0, 0.8);
}

static void rand_unit(mf_src *src, double u[3])
{
    for (;;) {
        for (int c = 0; c < 3; ++c)
            u[c] = urange(src, -1, 1);
        const double n = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        if (n > 0.1 && n <= 1) {
            for (int c = 0; c < 3; ++c)
                u[c] /= n;
            return;
        }
    }
}

/* A unit vector perpendicular to d (d non-zero). */
static void perpendicular(mf_src *src, const double d[3], double n[3])
{
    double r[3], c[3];
    for (;;) {
        rand_unit(src, r);
        c[0] = d[1] * r[2] - d[2] * r[1];
        c[1] = d[2] * r[0] - d[0] * r[2];
        c[2] = d[0] * r[1] - d[1] * r[0];
        const double l = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        if (l > 1e-3 * sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])) {
            for (int k = 0; k < 3; ++k)
                n[k] = c[k] / l;
            return;
        }
    }
}

/* Two distinct points of the half-space. */
static void two_points(mf_src *src, int side, double p0[3], double p1[3])
{
    rand_point(src, side, p0);
    do
        rand_point(src, side, p1);
    while (p0[0] == p1[0] && p0[1] == p1[1] && p0[2] == p1[2]);
}

/* Appends one triangle of the kind to m, in the half-space of side. */
static void add_kind(mf_src *src, mmesh *m, int kind, int side)
{
    double p0[3], p1[3], p2[3], d[3], n[3];
    switch (kind) {
    case K_COLLINEAR: { /* c = a + t (b - a), each coordinate rounded: exactly or nearly collinear */
        two_points(src, side, p0, p1);
        static const double ts[] = {0.3, 0.5, 1.0 / 3, 0.1, 0.7};
        const int w = rint_n(src, 7);
        const double t = w < 5 ? ts[w] : (w == 5 ? unif(src) : urange(src, -1, 2));
        for (int c = 0; c < 3; ++c)
            p2[c] = p0[c] + t * (p1[c] - p0[c]);
        add_tri(src, m, p0, p1, p2);
        return;
    }
    case K_POINT: /* a = b = c: three records of one point, or one record three times */
        rand_point(src, side, p0);
        if (rint_n(src, 2)) {
            const uint32_t i = add_vertex(m, p0);
            add_tri_idx(m, i, i, i);
        } else
            add_tri(src, m, p0, p0, p0);
        return;
    case K_SEGMENT: /* a repeated vertex by coordinates */
        two_points(src, side, p0, p1);
        add_tri(src, m, p0, p0, p1);
        return;
    case K_REPEATED: { /* a repeated index, or a vertex record repeated and used by two triangles */
        two_points(src, side, p0, p1);
        const uint32_t i = add_vertex(m, p0), j = add_vertex(m, p1);
        if (rint_n(src, 2)) {
            const int o = rint_n(src, 3);
            add_tri_idx(m, o == 0 ? i : j, o == 1 ? i : j, o == 2 ? i : i);
        } else {
            rand_point(src, side, p2);
            const uint32_t k = add_vertex(m, p2), k2 = add_vertex(m, p2);
            add_tri_idx(m, i, j, k);
            add_tri_idx(m, k2, j, i);
        }
        return;
    }
    case K_SLIVER: case K_NEEDLE: {
        /* sliver: the third vertex w L off the long edge (inside its span or past an end);
         * needle: one edge of length w L */
        two_points(src, side, p0, p1);
        for (int c = 0; c < 3; ++c)
            d[c] = p1[c] - p0[c];
        const double L = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        const double w = pow10u(src, -15, -3) * L;
        if (kind == K_SLIVER) {
            perpendicular(src, d, n);
            const double s = rint_n(src, 4) == 0 ? urange(src, -0.5, 1.5) : unif(src);
            for (int c = 0; c < 3; ++c)
                p2[c] = p0[c] + s * d[c] + w * n[c];
        } else {
            rand_unit(src, n);
            for (int c = 0; c < 3; ++c)
                p2[c] = p0[c] + w * n[c];
        }
        add_tri(src, m, p0, p1, p2);
        return;
    }
    case K_DUPLICATE:
        if (m->nt > 0) { /* a triangle again: same indices, rotated or mirrored, or copied records */
            const size_t t = (size_t)rint_n(src, (int)(m->nt < 256 ? m->nt : 256));
            const uint32_t *x = m->t + 3 * t;
            const uint32_t i = x[0], j = x[1], k = x[2];
            switch (rint_n(src, 4)) {
            case 0: add_tri_idx(m, i, j, k); break;
            case 1: add_tri_idx(m, j, k, i); break;
            case 2: add_tri_idx(m, k, j, i); break;
            default: {
                double q0[3], q1[3], q2[3];
                memcpy(q0, m->v + 3 * i, sizeof q0);
                memcpy(q1, m->v + 3 * j, sizeof q1);
                memcpy(q2, m->v + 3 * k, sizeof q2);
                add_tri(src, m, q0, q1, q2);
            }
            }
            return;
        }
        rand_point(src, side, p0); /* nothing to duplicate yet: an ordinary triangle */
        rand_point(src, side, p1);
        rand_point(src, side, p2);
        add_tri(src, m, p0, p1, p2);
        return;
    default:
        rand_point(src, side, p0);
        rand_point(src, side, p1);
        rand_point(src, side, p2);
        add_tri(src, m, p0, p1, p2);
        return;
    }
}

/* The kind a soup of family draws next: the family's own kind most of the time, ordinary
 * triangles mixed in, and now and then any kind. */
static int soup_kind(mf_src *src, int family)
{
    static const int own[MF_COUNT] = {K_COLLINEAR, K_POINT, K_SEGMENT, K_REPEATED, K_SLIVER,
                                      K_NEEDLE,    K_DUPLICATE, -1, -1, -1, -1, -1, -1, -1};
    const int r = rint_n(src, 20);
    if (own[family] >= 0 && r < 11)
        return own[family];
    if (r < 16 && own[family] >= 0)
        return K_ORDINARY;
    return rint_n(src, K_KINDS);
}

static int small_meshes; /* mf_run.small of the case being drawn */

static size_t draw_count(mf_src *src)
{
    if (small_meshes)
        return (size_t)(1 + rint_n(src, 24));
    /* mostly small meshes; one in 8 up to 120 triangles */
    return rint_n(src, 8) == 0 ? (size_t)(1 + rint_n(src, 120)) : (size_t)(1 + rint_n(src, 24));
}

static void soup(mf_src *src, mmesh *m, int family, int side)
{
    const size_t n = draw_count(src);
    while (m->nt < n)
        add_kind(src, m, soup_kind(src, family), side);
}

/* ---- poses -------------------------------------------------------------------------------- */

enum { P_NEAR, P_GAP, P_TOUCH, P_TILT, P_OVERLAP, P_FAR, P_RANDOM, P_KINDS };

static void rot_z(double theta, double R[9])
{
    const double c = cos(theta), s = sin(theta);
    const double r[9] = {c, -s, 0, s, c, 0, 0, 0, 1};
    memcpy(R, r, sizeof r);
}

static void mat_mul(const double A[9], const double B[9], double C[9])
{
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            C[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
}

static void rot_random(mf_src *src, double R[9])
{
    double q[4], n2;
    do {
        for (int i = 0; i < 4; ++i)
            q[i] = urange(src, -1, 1);
        n2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
    } while (n2 < 0.01 || n2 > 1);
    const double s = 1 / sqrt(n2), w = q[0] * s, x = q[1] * s, y = q[2] * s, z = q[3] * s;
    const double r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - z * w),     2 * (x * z + y * w),
                         2 * (x * y + z * w),     1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
                         2 * (x * z - y * w),     2 * (y * z + x * w),     1 - 2 * (x * x + y * y)};
    memcpy(R, r, sizeof r);
}

/* Largest |entry| of R^T R - I, in double (exact enough for a 1e-6 test). */
static double defect(const double R[9])
{
    double m = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const double s = R[i] * R[j] + R[3 + i] * R[3 + j] + R[6 + i] * R[6 + j];
            m = fmax(m, fabs(s - (i == j)));
        }
    return m;
}

static void set_pose(double pose[12], const double R[9], const double t[3])
{
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j)
            pose[4 * i + j] = R[3 * i + j];
        pose[4 * i + 3] = t[i];
    }
}

/* R times (I + S), S symmetric with entries up to lim: R^T R - I is then about 2S, near the
 * 1e-6 the queries accept. */
static void perturb_to_tolerance(mf_src *src, double R[9], double lim)
{
    double S[9], IS[9], out[9];
    for (int i = 0; i < 3; ++i)
        for (int j = i; j < 3; ++j)
            S[3 * i + j] = S[3 * j + i] = (i == j) + lim * urange(src, -1, 1);
    /* push one entry to the limit, so the set reaches it */
    const int e = rint_n(src, 3);
    S[4 * e] = 1 + (rint_n(src, 2) ? lim : -lim);
    memcpy(IS, S, sizeof IS);
    mat_mul(R, IS, out);
    memcpy(R, out, sizeof out);
}

/* ---- a case ------------------------------------------------------------------------------- */

typedef struct mcase {
    int family, is_float;
    mmesh a, b;
    size_t k;
    double poses[12 * MAXK]; /* float values in a float case */
    int pose_kind[MAXK];
    double size;             /* extent of the scene, for the reports */
    int refit;               /* 0: meshes built from their vertices; else 1 + how they were moved to
                              * them (REFIT_*) */
} mcase;

static void round_to_float(mcase *c)
{
    for (size_t i = 0; i < 3 * c->a.nv; ++i)
        c->a.v[i] = (double)(float)c->a.v[i];
    for (size_t i = 0; i < 3 * c->b.nv; ++i)
        c->b.v[i] = (double)(float)c->b.v[i];
    for (size_t i = 0; i < 12 * c->k; ++i)
        c->poses[i] = (double)(float)c->poses[i];
}

/* The pose kinds a family draws from (weights out of 20). */
static int draw_pose_kind(mf_src *src, int family)
{
    const int r = rint_n(src, 20);
    if (family == MF_TOUCH)
        return r < 16 ? P_TOUCH : (r < 18 ? P_NEAR : P_TILT);
    if (family == MF_GAP)
        return r < 16 ? P_GAP : P_NEAR;
    if (family == MF_COPLANAR)
        return r < 9 ? P_TOUCH : (r < 13 ? P_GAP : (r < 16 ? P_OVERLAP : P_NEAR));
    static const int w[P_KINDS] = {6, 2, 3, 2, 2, 2, 3}; /* near, gap, touch, tilt, overlap, far, random */
    int acc = 0;
    for (int i = 0; i < P_KINDS; ++i)
        if (r < (acc += w[i]))
            return i;
    return P_NEAR;
}

/* A pose of b over a. b lies in z >= 0 and a in z <= 0 (mostly), so a rotation about z and a
 * translation (x, y, g) put b's lowest features at height g over a's highest: g = 0 touches
 * exactly (z = 0 maps to z = 0 exactly under such a pose), g of 1e-6..2e-3 of the size is near
 * contact. at, when given, is where b's origin goes (touch family). */
static void make_pose(mf_src *src, int kind, double size, const double *at, double pose[12])
{
    double R[9], T[9], t[3];
    const double theta = rint_n(src, 4) == 0 ? 1.5707963267948966 * rint_n(src, 4) : urange(src, -3.2, 3.2);
    rot_z(theta, R);
    t[0] = at ? at[0] : urange(src, -0.6, 0.6);
    t[1] = at ? at[1] : urange(src, -0.6, 0.6);
    t[2] = 0;
    switch (kind) {
    case P_NEAR: t[2] = size * pow10u(src, -6, log10(2e-3)); break;
    case P_GAP: t[2] = size * pow10u(src, -15, -3); break;
    case P_TOUCH: break;
    case P_TILT: { /* a small tilt about x: the planes meet at a tiny angle */
        const double phi = pow10u(src, -12, -2) * (rint_n(src, 2) ? 1 : -1);
        const double X[9] = {1, 0, 0, 0, cos(phi), -sin(phi), 0, sin(phi), cos(phi)};
        mat_mul(R, X, T);
        memcpy(R, T, sizeof T);
        t[2] = rint_n(src, 2) ? 0 : size * pow10u(src, -9, -3);
        break;
    }
    case P_OVERLAP: t[2] = -size * urange(src, 0.01, 0.4); break;
    case P_FAR: {
        double u[3];
        rot_random(src, R);
        rand_unit(src, u);
        const double r = size * pow10u(src, 0.3, 3);
        for (int c = 0; c < 3; ++c)
            t[c] = r * u[c];
        break;
    }
    default: /* P_RANDOM: any rotation, overlapping boxes */
        rot_random(src, R);
        for (int c = 0; c < 3; ++c)
            t[c] = urange(src, -1, 1);
        break;
    }
    set_pose(pose, R, t);
}

/* Touch and gap families: a below z = 0 with a top feature (a vertex, an edge or a face) on
 * z = 0; b above with a bottom feature through its origin; the pose puts b's origin on a's
 * top feature, which a rotation about z keeps exact in z. */
static void contact_scene(mf_src *src, mcase *c, double at[3])
{
    double p0[3], p1[3], p2[3], o[3] = {0, 0, 0};
    const size_t na = draw_count(src), nb = draw_count(src);
    for (size_t i = 1; i < na; ++i) { /* a's body, below */
        const int kind = rint_n(src, K_KINDS);
        const size_t before = c->a.nv;
        add_kind(src, &c->a, kind, -1);
        for (size_t v = before; v < c->a.nv; ++v)
            c->a.v[3 * v + 2] = -0.05 - fabs(c->a.v[3 * v + 2]);
    }
    for (size_t i = 1; i < nb; ++i) {
        const size_t before = c->b.nv;
        add_kind(src, &c->b, rint_n(src, K_KINDS), 1);
        for (size_t v = before; v < c->b.nv; ++v)
            c->b.v[3 * v + 2] = 0.05 + fabs(c->b.v[3 * v + 2]);
    }
    /* a's top feature: 1, 2 or 3 vertices on z = 0, possibly a thin one */
    const int fa = 1 + rint_n(src, 3), fb = 1 + rint_n(src, 3);
    two_points(src, -1, p0, p1);
    rand_point(src, -1, p2);
    p0[2] = 0;
    p1[2] = fa >= 2 ? 0 : -urange(src, 0.05, 0.8);
    p2[2] = fa >= 3 ? 0 : -urange(src, 0.05, 0.8);
    if (rint_n(src, 3) == 0) { /* make the top triangle a sliver or a segment */
        const double w = rint_n(src, 4) == 0 ? 0.0 : pow10u(src, -15, -3);
        for (int k = 0; k < 3; ++k)
            p2[k] = p0[k] + 0.3 * (p1[k] - p0[k]) + (k < 2 ? w : 0);
    }
    add_tri(src, &c->a, p0, p1, p2);
    /* where b's origin goes: on that feature (rounded: on it or a hair off it) */
    const double s = fa >= 2 ? unif(src) : 0, r = fa >= 3 ? unif(src) * (1 - s) : 0;
    for (int k = 0; k < 2; ++k)
        at[k] = p0[k] + s * (p1[k] - p0[k]) + r * (p2[k] - p0[k]);
    at[2] = 0;
    /* b's bottom feature through its origin */
    rand_point(src, 1, p1);
    rand_point(src, 1, p2);
    p1[2] = fb >= 2 ? 0 : urange(src, 0.05, 0.8);
    p2[2] = fb >= 3 ? 0 : urange(src, 0.05, 0.8);
    add_tri(src, &c->b, o, p1, p2);
}

/* The grid family: n x n cells of two triangles in z = 0 (vertices jittered in x and y, which
 * makes slivers), against one triangle of any kind; either mesh may be the grid. */
static void grid_scene(mf_src *src, mcase *c, int allow_big)
{
    const int big = allow_big && rint_n(src, 32) == 0;
    const int n = big ? 224 : 2 + rint_n(src, small_meshes ? 3 : 30); /* 224: 100,352 triangles */
    const int grid_is_b = rint_n(src, 2);
    mmesh *g = grid_is_b ? &c->b : &c->a, *o = grid_is_b ? &c->a : &c->b;
    const double jitter = rint_n(src, 2) ? 0.0 : pow10u(src, -15, -0.5);
    const double h = 2.0 / n;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
            double x[3] = {-1 + h * i, -1 + h * j, 0};
            if (jitter > 0 && i > 0 && j > 0 && i < n && j < n) {
                x[0] += jitter * h * urange(src, -0.5, 0.5);
                x[1] += jitter * h * urange(src, -0.5, 0.5);
            }
            add_vertex(g, x);
        }
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const uint32_t v = (uint32_t)(i * (n + 1) + j);
            add_tri_idx(g, v, v + (uint32_t)(n + 1), v + 1);
            add_tri_idx(g, v + 1, v + (uint32_t)(n + 1), v + (uint32_t)(n + 2));
        }
    add_kind(src, o, rint_n(src, K_KINDS - 1), grid_is_b ? -1 : 1);
}

static double scene_size(const mcase *c)
{
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (size_t i = 0; i < 3 * c->a.nv; ++i)
        lo = fmin(lo, c->a.v[i]), hi = fmax(hi, c->a.v[i]);
    for (size_t i = 0; i < 3 * c->b.nv; ++i)
        lo = fmin(lo, c->b.v[i]), hi = fmax(hi, c->b.v[i]);
    return hi > lo ? hi - lo : 1;
}

/* The scaled family: everything times s (1e-8..1e8), a moved by an offset of 1e6 and b's frame
 * by its own offset, the poses' translations following (rounded: near contact stays near). */
static void scale_scene(mf_src *src, mcase *c)
{
    const double s = pow10u(src, -8, 8);
    double oa[3] = {0, 0, 0}, ob[3] = {0, 0, 0};
    if (rint_n(src, 3)) {
        for (int k = 0; k < 3; ++k)
            oa[k] = 1e6 * (rint_n(src, 2) ? 1 : -1);
        if (rint_n(src, 2))
            for (int k = 0; k < 3; ++k)
                ob[k] = rint_n(src, 2) ? oa[k] : -1e6;
    }
    for (size_t i = 0; i < c->a.nv; ++i)
        for (int k = 0; k < 3; ++k)
            c->a.v[3 * i + k] = c->a.v[3 * i + k] * s + oa[k];
    for (size_t i = 0; i < c->b.nv; ++i)
        for (int k = 0; k < 3; ++k)
            c->b.v[3 * i + k] = c->b.v[3 * i + k] * s + ob[k];
    for (size_t p = 0; p < c->k; ++p) {
        double *P = c->poses + 12 * p;
        for (int i = 0; i < 3; ++i)
            P[4 * i + 3] = P[4 * i + 3] * s + oa[i] - (P[4 * i] * ob[0] + P[4 * i + 1] * ob[1] + P[4 * i + 2] * ob[2]);
    }
}

static void generate(mf_src *src, int family, int allow_big, mcase *c)
{
    memset(c, 0, sizeof *c);
    c->family = family;
    c->is_float = rint_n(src, 4) == 0;
    double at[3];
    const int touch = family == MF_TOUCH || family == MF_GAP;
    if (touch)
        contact_scene(src, c, at);
    else if (family == MF_GRID)
        grid_scene(src, c, allow_big);
    else {
        const int f = family == MF_SCALED || family == MF_TOLERANCE ? MF_MIXED : family;
        soup(src, &c->a, f == MF_COPLANAR ? MF_MIXED : f, -1);
        soup(src, &c->b, f == MF_COPLANAR ? MF_MIXED : f, 1);
        if (family == MF_COPLANAR) { /* flatten both onto z = 0: sheets in one plane */
            for (size_t i = 0; i < c->a.nv; ++i)
                c->a.v[3 * i + 2] = 0;
            for (size_t i = 0; i < c->b.nv; ++i)
                c->b.v[3 * i + 2] = 0;
        }
    }
    const double size = scene_size(c);
    c->k = 1 + (size_t)rint_n(src, MAXK);
    if (c->a.nt * c->b.nt > 20000)
        c->k = 1; /* the big grid: one pose keeps the run short */
    for (size_t p = 0; p < c->k; ++p) {
        c->pose_kind[p] = draw_pose_kind(src, family);
        make_pose(src, c->pose_kind[p], size, touch && c->pose_kind[p] != P_NEAR ? at : NULL, c->poses + 12 * p);
    }
    if (family == MF_SCALED)
        scale_scene(src, c);
    if (family == MF_TOLERANCE || rint_n(src, 16) == 0)
        for (size_t p = 0; p < c->k; ++p) {
            double R[9], t[3], *P = c->poses + 12 * p;
            for (int i = 0; i < 3; ++i) {
                for (int j = 0; j < 3; ++j)
                    R[3 * i + j] = P[4 * i + j];
                t[i] = P[4 * i + 3];
            }
            /* entries of R^T R - I up to about 0.9e-6 (double), 0.5e-6 (float, which rounds
             * R by up to 6e-8 more) */
            perturb_to_tolerance(src, R, (c->is_float ? 0.25e-6 : 0.45e-6) * urange(src, 0.5, 1));
            set_pose(P, R, t);
        }
    if (c->is_float)
        round_to_float(c);
    c->size = scene_size(c);
}

static void free_case(mcase *c)
{
    free(c->a.v);
    free(c->a.t);
    free(c->b.v);
    free(c->b.t);
}

/* ---- the brute force ---------------------------------------------------------------------- */

/* One pair's exact result, widened to double. */
typedef struct bpair {
    double d, p[3], q[3];
    uint32_t flags;
    uint8_t fp, fq;
} bpair;

static void pose_apply_d(const double P[12], const double x[3], double out[3])
{
    for (int i = 0; i < 3; ++i)
        out[i] = ((P[4 * i] * x[0] + P[4 * i + 1] * x[1]) + P[4 * i + 2] * x[2]) + P[4 * i + 3];
}

static void pose_apply_f(const float P[12], const float x[3], float out[3])
{
    for (int i = 0; i < 3; ++i)
        out[i] = ((P[4 * i] * x[0] + P[4 * i + 1] * x[1]) + P[4 * i + 2] * x[2]) + P[4 * i + 3];
}

/* The coordinates of pair (i, j) under pose P, as the brute force gives them to the kernel
 * (widened to double in a float case). */
static void pair_coords(const mcase *c, const double *P, size_t i, size_t j, double s[9], double t[9])
{
    float Pf[12];
    for (int k = 0; k < 12; ++k)
        Pf[k] = (float)P[k];
    for (int v = 0; v < 3; ++v) {
        memcpy(s + 3 * v, c->a.v + 3 * (size_t)c->a.t[3 * i + v], 3 * sizeof(double));
        const double *x = c->b.v + 3 * (size_t)c->b.t[3 * j + v];
        if (c->is_float) {
            const float xf[3] = {(float)x[0], (float)x[1], (float)x[2]};
            float o[3];
            pose_apply_f(Pf, xf, o);
            for (int k = 0; k < 3; ++k)
                t[3 * v + k] = (double)o[k];
        } else
            pose_apply_d(P, x, t + 3 * v);
    }
}

/* Every pair under pose P: pair (i, j) at i * nt_b + j. */
static bpair *brute(const mcase *c, const double *P)
{
    const size_t n = c->a.nt * c->b.nt;
    bpair *out = malloc(n * sizeof *out);
    ttd_options o = ttd_default_options();
    o.isa = TTD_ISA_SCALAR;
    o.threads = 2;
    if (!out)
        abort();
    if (!c->is_float) {
        double *s = malloc(9 * n * sizeof *s), *t = malloc(9 * n * sizeof *t);
        ttd_result_d *r = malloc(n * sizeof *r);
        if (!s || !t || !r)
            abort();
        for (size_t i = 0; i < c->a.nt; ++i)
            for (size_t j = 0; j < c->b.nt; ++j)
                pair_coords(c, P, i, j, s + 9 * (i * c->b.nt + j), t + 9 * (i * c->b.nt + j));
        if (ttd_batch_d(&o, n, s, t, NULL, r) != TTD_OK)
            abort();
        for (size_t i = 0; i < n; ++i) {
            out[i].d = r[i].distance;
            memcpy(out[i].p, r[i].p, sizeof out[i].p);
            memcpy(out[i].q, r[i].q, sizeof out[i].q);
            out[i].flags = r[i].flags, out[i].fp = r[i].feature_p, out[i].fq = r[i].feature_q;
        }
        free(s), free(t), free(r);
    } else {
        float *s = malloc(9 * n * sizeof *s), *t = malloc(9 * n * sizeof *t);
        ttd_result_f *r = malloc(n * sizeof *r);
        if (!s || !t || !r)
            abort();
        for (size_t i = 0; i < c->a.nt; ++i)
            for (size_t j = 0; j < c->b.nt; ++j) {
                double sd[9], td[9];
                pair_coords(c, P, i, j, sd, td);
                for (int k = 0; k < 9; ++k)
                    s[9 * (i * c->b.nt + j) + k] = (float)sd[k], t[9 * (i * c->b.nt + j) + k] = (float)td[k];
            }
        if (ttd_batch_f(&o, n, s, t, NULL, r) != TTD_OK)
            abort();
        for (size_t i = 0; i < n; ++i) {
            out[i].d = (double)r[i].distance;
            for (int k = 0; k < 3; ++k)
                out[i].p[k] = (double)r[i].p[k], out[i].q[k] = (double)r[i].q[k];
            out[i].flags = r[i].flags, out[i].fp = r[i].feature_p, out[i].fq = r[i].feature_q;
        }
        free(s), free(t), free(r);
    }
    return out;
}

static int cmp_double(const void *x, const void *y)
{
    const double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

/* ---- running the queries ------------------------------------------------------------------ */

/* The parameters of one pose's queries, all from its brute force (values of the precision). */
typedef struct pparams {
    double min, median, max, below; /* below: the next value under min (min > 0 only) */
    size_t argmin;
} pparams;

/* What one configuration (ISA, threads) returned for one pose. Distance variants: 0 plain,
 * 1 upper bound = min, 2 upper bound just below min, 3 rel_tol 0.1, 4 rel_tol 1. Contacts at
 * 0, min, median, L (every pair); closest at min, median, L; collide at 0, min, below min, L. */
typedef struct pout {
    ttd_status dst[ND], cst[NC], clst[NCL], xst[NX];
    int has[ND];
    ttd_mesh_result_d d[ND];
    ttd_contact_d *c[NC];
    size_t nc[NC];
    ttd_closest_d *cla[NCL], *clb[NCL];
    ttd_collision x[NX];
} pout;

static const double rel_tols[2] = {0.1, 1.0};

typedef struct qctx {
    const mcase *c;
    const ttd_mesh *a, *b;
    float posef[12 * MAXK];
    const pparams *pp;
    double L; /* a margin above every pair's distance under every pose */
} qctx;

static double prec(const mcase *c, double x)
{
    return c->is_float ? (double)(float)x : x;
}

static ttd_status q_distance(const qctx *q, const ttd_options *o, size_t first, size_t k, double ub, double rel,
                             ttd_mesh_result_d *out)
{
    if (!q->c->is_float)
        return ttd_mesh_distance_d(o, q->a, q->b, k, q->c->poses + 12 * first, ub, rel, out);
    ttd_mesh_result_f r[MAXK];
    memset(r, 0, sizeof r);
    const ttd_status st = ttd_mesh_distance_f(o, q->a, q->b, k, q->posef + 12 * first, (float)ub, (float)rel, r);
    for (size_t i = 0; i < k; ++i) {
        ttd_mesh_result_d *d = &out[i];
        memset(d, 0, sizeof *d);
        d->distance = (double)r[i].distance;
        for (int j = 0; j < 3; ++j)
            d->p[j] = (double)r[i].p[j], d->q[j] = (double)r[i].q[j];
        d->tri_a = r[i].tri_a, d->tri_b = r[i].tri_b, d->feature_a = r[i].feature_a, d->feature_b = r[i].feature_b;
        d->flags = r[i].flags, d->node_tests = r[i].node_tests, d->pair_tests = r[i].pair_tests;
    }
    return st;
}

/* Contacts of poses first..first+k-1 into per-pose copies (sets[i], counts[i]). */
static ttd_status q_contacts(const qctx *q, const ttd_options *o, size_t first, size_t k, double margin,
                             ttd_contact_d **sets, size_t *counts)
{
    ttd_status st;
    size_t start[MAXK + 1];
    ttd_contact_d *all = NULL;
    if (!q->c->is_float) {
        ttd_contacts_d s = {0};
        st = ttd_mesh_contacts_d(o, q->a, q->b, k, q->c->poses + 12 * first, margin, &s);
        if (st == TTD_OK) {
            all = malloc((s.count + 1) * sizeof *all);
            if (!all)
                abort();
            if (s.count)
                memcpy(all, s.pairs, s.count * sizeof *all);
            memcpy(start, s.pose_start, (k + 1) * sizeof *start);
        }
        ttd_contacts_free_d(&s);
    } else {
        ttd_contacts_f s = {0};
        st = ttd_mesh_contacts_f(o, q->a, q->b, k, q->posef + 12 * first, (float)margin, &s);
        if (st == TTD_OK) {
            all = malloc((s.count + 1) * sizeof *all);
            if (!all)
                abort();
            for (size_t i = 0; i < s.count; ++i) {
                all[i].tri_a = s.pairs[i].tri_a, all[i].tri_b = s.pairs[i].tri_b;
                all[i].distance = (double)s.pairs[i].distance;
                for (int j = 0; j < 3; ++j)
                    all[i].p[j] = (double)s.pairs[i].p[j], all[i].q[j] = (double)s.pairs[i].q[j];
            }
            memcpy(start, s.pose_start, (k + 1) * sizeof *start);
        }
        ttd_contacts_free_f(&s);
    }
    for (size_t i = 0; i < k; ++i) {
        counts[i] = 0;
        sets[i] = NULL;
        if (st != TTD_OK)
            continue;
        counts[i] = start[i + 1] - start[i];
        sets[i] = malloc((counts[i] + 1) * sizeof **sets);
        if (!sets[i])
            abort();
        if (counts[i])
            memcpy(sets[i], all + start[i], counts[i] * sizeof **sets);
    }
    free(all);
    return st;
}

static ttd_status q_closest(const qctx *q, const ttd_options *o, size_t first, size_t k, double margin,
                            ttd_closest_d **fa, ttd_closest_d **fb)
{
    const size_t na = q->c->a.nt, nb = q->c->b.nt;
    ttd_closest_d *ra = calloc(k * na, sizeof *ra), *rb = calloc(k * nb, sizeof *rb);
    ttd_status st;
    if (!ra || !rb)
        abort();
    if (!q->c->is_float)
        st = ttd_mesh_closest_d(o, q->a, q->b, k, q->c->poses + 12 * first, margin, ra, rb);
    else {
        ttd_closest_f *xa = calloc(k * na, sizeof *xa), *xb = calloc(k * nb, sizeof *xb);
        if (!xa || !xb)
            abort();
        st = ttd_mesh_closest_f(o, q->a, q->b, k, q->posef + 12 * first, (float)margin, xa, xb);
        for (size_t side = 0; side < 2; ++side) {
            const ttd_closest_f *x = side ? xb : xa;
            ttd_closest_d *r = side ? rb : ra;
            for (size_t i = 0; i < k * (side ? nb : na); ++i) {
                r[i].partner = x[i].partner;
                r[i].distance = (double)x[i].distance;
                for (int j = 0; j < 3; ++j)
                    r[i].p[j] = (double)x[i].p[j], r[i].q[j] = (double)x[i].q[j];
            }
        }
        free(xa), free(xb);
    }
    for (size_t i = 0; i < k; ++i) {
        fa[i] = malloc(na * sizeof **fa);
        fb[i] = malloc(nb * sizeof **fb);
        if (!fa[i] || !fb[i])
            abort();
        memcpy(fa[i], ra + i * na, na * sizeof **fa);
        memcpy(fb[i], rb + i * nb, nb * sizeof **fb);
    }
    free(ra), free(rb);
    return st;
}

static ttd_status q_collide(const qctx *q, const ttd_options *o, size_t first, size_t k, double margin,
                            ttd_collision *out)
{
    return q->c->is_float ? ttd_mesh_collide_f(o, q->a, q->b, k, q->posef + 12 * first, (float)margin, out)
                          : ttd_mesh_collide_d(o, q->a, q->b, k, q->c->poses + 12 * first, margin, out);
}

/* Every query of every pose under options o: those whose parameters hold for all poses as one
 * call of k poses, the others (bounds and margins from one pose's brute force) per pose. */
static void run_all(const qctx *q, const ttd_options *o, pout *out)
{
    const size_t k = q->c->k;
    ttd_mesh_result_d dr[MAXK];
    ttd_collision xr[MAXK];
    ttd_contact_d *sets[MAXK];
    size_t counts[MAXK];
    ttd_closest_d *fa[MAXK], *fb[MAXK];
    ttd_status st;
    memset(out, 0, k * sizeof *out);
    /* k poses per call */
    const double drel[3] = {0, rel_tols[0], rel_tols[1]};
    const int dvar[3] = {0, 3, 4};
    for (int v = 0; v < 3; ++v) {
        memset(dr, 0, sizeof dr);
        st = q_distance(q, o, 0, k, HUGE_VAL, prec(q->c, drel[v]), dr);
        for (size_t i = 0; i < k; ++i)
            out[i].dst[dvar[v]] = st, out[i].d[dvar[v]] = dr[i], out[i].has[dvar[v]] = 1;
    }
    const double cm[2] = {0, q->L};
    const int cvar[2] = {0, 3}, xvar[2] = {0, 3};
    for (int v = 0; v < 2; ++v) {
        st = q_contacts(q, o, 0, k, cm[v], sets, counts);
        for (size_t i = 0; i < k; ++i)
            out[i].cst[cvar[v]] = st, out[i].c[cvar[v]] = sets[i], out[i].nc[cvar[v]] = counts[i];
        memset(xr, 0, sizeof xr);
        st = q_collide(q, o, 0, k, cm[v], xr);
        for (size_t i = 0; i < k; ++i)
            out[i].xst[xvar[v]] = st, out[i].x[xvar[v]] = xr[i];
    }
    st = q_closest(q, o, 0, k, q->L, fa, fb);
    for (size_t i = 0; i < k; ++i)
        out[i].clst[2] = st, out[i].cla[2] = fa[i], out[i].clb[2] = fb[i];
    /* per pose */
    for (size_t i = 0; i < k; ++i) {
        const pparams *pp = &q->pp[i];
        pout *po = &out[i];
        po->dst[1] = q_distance(q, o, i, 1, pp->min, 0, &po->d[1]);
        po->has[1] = 1;
        if (pp->min > 0) {
            po->dst[2] = q_distance(q, o, i, 1, pp->below, 0, &po->d[2]);
            po->has[2] = 1;
        }
        po->cst[1] = q_contacts(q, o, i, 1, pp->min, &po->c[1], &po->nc[1]);
        po->cst[2] = q_contacts(q, o, i, 1, pp->median, &po->c[2], &po->nc[2]);
        po->clst[0] = q_closest(q, o, i, 1, pp->min, &po->cla[0], &po->clb[0]);
        po->clst[1] = q_closest(q, o, i, 1, pp->median, &po->cla[1], &po->clb[1]);
        po->xst[1] = q_collide(q, o, i, 1, pp->min, &po->x[1]);
        if (pp->min > 0)
            po->xst[2] = q_collide(q, o, i, 1, pp->below, &po->x[2]);
    }
}

static void free_outs(pout *out, size_t k)
{
    for (size_t i = 0; i < k; ++i) {
        for (int v = 0; v < NC; ++v)
            free(out[i].c[v]);
        for (int v = 0; v < NCL; ++v)
            free(out[i].cla[v]), free(out[i].clb[v]);
    }
}

/* ---- reporting ---------------------------------------------------------------------------- */

typedef struct where {
    mf_run *run;
    const mcase *c;
    uint64_t seed, index;
    int has_seed;
    size_t pose;
    const char *config; /* "avx2/1" */
    int dumped;
} where;

static FILE *out_of(const mf_run *run)
{
    return run->out ? run->out : stdout;
}

static void dump_case(FILE *f, const mcase *c)
{
    static const char *const refits[] = {"built", "refitted from permuted vertices", "refitted from jittered vertices",
                                         "refitted from rotated vertices", "refitted from one point"};
    fprintf(f, "    case: %s, %s, a %zu triangles / %zu vertices, b %zu / %zu, %zu poses, size %.3g, %s\n",
            mf_family_name(c->family), c->is_float ? "float" : "double", c->a.nt, c->a.nv, c->b.nt, c->b.nv, c->k,
            c->size, refits[c->refit]);
    for (size_t p = 0; p < c->k; ++p) {
        fprintf(f, "    pose %zu:", p);
        for (int i = 0; i < 12; ++i)
            fprintf(f, " %a", c->poses[12 * p + (size_t)i]);
        fputc('\n', f);
    }
    if (c->a.nt * c->b.nt > 4096)
        return;
    for (int side = 0; side < 2; ++side) {
        const mmesh *m = side ? &c->b : &c->a;
        for (size_t t = 0; t < m->nt; ++t) {
            fprintf(f, "    %c[%zu]:", side ? 'b' : 'a', t);
            for (int v = 0; v < 3; ++v) {
                const double *x = m->v + 3 * (size_t)m->t[3 * t + (size_t)v];
                fprintf(f, " (%a, %a, %a)#%u", x[0], x[1], x[2], m->t[3 * t + (size_t)v]);
            }
            fputc('\n', f);
        }
    }
}

/* One counted check; on failure the message (with where it happened and how to rerun it). */
static int check(where *w, int query, int ok, const char *fmt, ...)
{
    mf_run *run = w->run;
    ++run->checks;
    ++run->family_checks[w->c->family];
    if (ok)
        return 1;
    ++run->failures;
    ++run->family_failures[w->c->family];
    ++run->query_failures[w->c->family][query];
    const int limit = run->max_printed > 0 ? run->max_printed : 20;
    if (run->failures > (uint64_t)limit)
        return 0;
    FILE *f = out_of(run);
    fprintf(f, "FAIL %s family=%s case=%llu", mf_query_name(query), mf_family_name(w->c->family),
            (unsigned long long)w->index);
    if (w->has_seed)
        fprintf(f, " seed=%llu", (unsigned long long)w->seed);
    fprintf(f, " %s pose=%zu (%s) config=%s: ", w->c->is_float ? "float" : "double", w->pose,
            w->pose < w->c->k ? (const char *[]){"near", "gap", "touch", "tilt", "overlap", "far", "random"}
                                    [w->c->pose_kind[w->pose]]
                              : "-",
            w->config ? w->config : "-");
    va_list ap;
    va_start(ap, fmt);
    vfprintf(f, fmt, ap);
    va_end(ap);
    fputc('\n', f);
    if (w->has_seed)
        fprintf(f, "    rerun: test_mesh_fuzz --seed %llu --family %s --first %llu --cases 1 --verbose\n",
                (unsigned long long)w->seed, mf_family_name(w->c->family), (unsigned long long)w->index);
    if ((run->verbose || run->dump_failures) && !w->dumped) {
        dump_case(f, w->c);
        w->dumped = 1;
    }
    return 0;
}

/* "%.17g (%a)" of a value, for the messages. */
#define V(x) (x), (x)
#define VF "%.17g (%a)"

static void print_pair(where *w, size_t i, size_t j)
{
    const int limit = w->run->max_printed > 0 ? w->run->max_printed : 20;
    if (w->run->failures > (uint64_t)limit)
        return;
    double s[9], t[9];
    pair_coords(w->c, w->c->poses + 12 * w->pose, i, j, s, t);
    fprintf(out_of(w->run), "    pair (%zu, %zu) as brute-forced: S =", i, j);
    for (int k = 0; k < 9; ++k)
        fprintf(out_of(w->run), " %.17g", s[k]);
    fprintf(out_of(w->run), "; T =");
    for (int k = 0; k < 9; ++k)
        fprintf(out_of(w->run), " %.17g", t[k]);
    fputc('\n', out_of(w->run));
}

/* ---- the checks against the brute force --------------------------------------------------- */

static int same3(const double *x, const double *y)
{
    return x[0] == y[0] && x[1] == y[1] && x[2] == y[2];
}

/* The q a query reports for a pair: the kernel's q, or p where the distance is 0 (ttd.h). */
static const double *q_of(const bpair *b)
{
    return b->d == 0 ? b->p : b->q;
}

static void check_distance(where *w, const bpair *all, const pparams *pp, const pout *po)
{
    const mcase *c = w->c;
    const size_t nb = c->b.nt;
    const ttd_mesh_result_d *r = &po->d[0];
    /* plain: the minimum, a pair at it, that pair's points and features, the flag */
    if (check(w, MFQ_DISTANCE, po->dst[0] == TTD_OK, "status %d", po->dst[0])) {
        int ok = r->distance == pp->min && r->tri_a < c->a.nt && r->tri_b < nb;
        const bpair *b = ok ? &all[(size_t)r->tri_a * nb + r->tri_b] : NULL;
        ok = ok && b->d == pp->min && same3(r->p, b->p) && same3(r->q, q_of(b)) && r->feature_a == b->fp &&
             r->feature_b == b->fq && r->flags == (pp->min == 0 ? TTD_MESH_INTERSECTING : 0);
        if (!check(w, MFQ_DISTANCE, ok,
                   "distance " VF " pair (%u, %u) flags %u features %u/%u; brute force min " VF
                   " at (%zu, %zu)%s",
                   V(r->distance), r->tri_a, r->tri_b, r->flags, r->feature_a, r->feature_b, V(pp->min),
                   pp->argmin / nb, pp->argmin % nb,
                   b && b->d == pp->min ? " (the pair is at the min: points, features or flags differ)" : "")) {
            print_pair(w, pp->argmin / nb, pp->argmin % nb);
        }
    }
    /* upper bound at the minimum: found; just below: above the bound */
    r = &po->d[1];
    if (check(w, MFQ_BOUND, po->dst[1] == TTD_OK, "upper bound = min: status %d", po->dst[1])) {
        const int ok = r->distance == pp->min && !(r->flags & TTD_MESH_ABOVE_BOUND) && r->tri_a < c->a.nt &&
                       r->tri_b < nb && all[(size_t)r->tri_a * nb + r->tri_b].d == pp->min;
        if (!check(w, MFQ_BOUND, ok, "upper bound = min " VF ": distance " VF " flags %u pair (%u, %u)", V(pp->min),
                   V(r->distance), r->flags, r->tri_a, r->tri_b))
            print_pair(w, pp->argmin / nb, pp->argmin % nb);
    }
    if (po->has[2] && check(w, MFQ_BOUND, po->dst[2] == TTD_OK, "upper bound below min: status %d", po->dst[2])) {
        r = &po->d[2];
        const int ok = isinf(r->distance) && r->distance > 0 && r->flags == TTD_MESH_ABOVE_BOUND &&
                       r->tri_a == UINT32_MAX && r->tri_b == UINT32_MAX;
        check(w, MFQ_BOUND, ok, "upper bound " VF " just below min " VF ": distance " VF " flags %u pair (%u, %u)",
              V(pp->below), V(pp->min), V(r->distance), r->flags, r->tri_a, r->tri_b);
    }
    /* rel_tol: a real pair, its distance as brute-forced, within the factor */
    for (int v = 0; v < 2; ++v) {
        r = &po->d[3 + v];
        const double rel = prec(c, rel_tols[v]);
        if (!check(w, MFQ_RELTOL, po->dst[3 + v] == TTD_OK, "rel_tol %g: status %d", rel, po->dst[3 + v]))
            continue;
        const int real = r->tri_a < c->a.nt && r->tri_b < nb;
        const double bd = real ? all[(size_t)r->tri_a * nb + r->tri_b].d : (double)NAN;
        const double eps = c->is_float ? (double)FLT_EPSILON : DBL_EPSILON;
        const int ok = real && bd == r->distance && r->distance >= pp->min &&
                       r->distance <= pp->min * (1 + rel) * (1 + 4 * eps);
        check(w, MFQ_RELTOL, ok, "rel_tol %g: distance " VF " pair (%u, %u) brute " VF ", min " VF, rel,
              V(r->distance), r->tri_a, r->tri_b, V(bd), V(pp->min));
    }
}

static int contact_cmp(const void *x, const void *y)
{
    const ttd_contact_d *a = x, *b = y;
    if (a->tri_a != b->tri_a)
        return a->tri_a < b->tri_a ? -1 : 1;
    return (a->tri_b > b->tri_b) - (a->tri_b < b->tri_b);
}

static void check_contacts(where *w, const bpair *all, double margin, const char *label, ttd_status st,
                           ttd_contact_d *set, size_t count)
{
    const mcase *c = w->c;
    const size_t nb = c->b.nt, n = c->a.nt * nb;
    if (!check(w, MFQ_CONTACTS, st == TTD_OK, "contacts at %s: status %d", label, st))
        return;
    ttd_contact_d *s = malloc((count + 1) * sizeof *s); /* sorted copy: the set's order is the library's */
    if (!s)
        abort();
    if (count)
        memcpy(s, set, count * sizeof *s);
    qsort(s, count, sizeof *s, contact_cmp);
    size_t k = 0, want = 0, missing = 0, extra = 0, wrong = 0, first_missing = SIZE_MAX, first_wrong = SIZE_MAX;
    for (size_t i = 0; i < n; ++i) {
        const int in = all[i].d <= margin;
        want += (size_t)in;
        const size_t ia = i / nb, ib = i % nb;
        while (k < count && (s[k].tri_a < ia || (s[k].tri_a == ia && s[k].tri_b < ib)))
            ++extra, ++k; /* out of range indices or duplicates */
        const int there = k < count && s[k].tri_a == ia && s[k].tri_b == ib;
        if (in && !there) {
            ++missing;
            if (first_missing == SIZE_MAX)
                first_missing = i;
        } else if (!in && there)
            ++extra;
        if (there) {
            if (in && !(s[k].distance == all[i].d && same3(s[k].p, all[i].p) && same3(s[k].q, q_of(&all[i])))) {
                ++wrong;
                if (first_wrong == SIZE_MAX)
                    first_wrong = i;
            }
            ++k;
            while (k < count && s[k].tri_a == ia && s[k].tri_b == ib)
                ++extra, ++k; /* a pair twice */
        }
    }
    extra += count - k;
    if (!check(w, MFQ_CONTACTS, missing == 0 && extra == 0 && wrong == 0,
               "contacts at %s " VF ": %zu pairs, brute force %zu: %zu missing, %zu extra, %zu with other "
               "distance or points",
               label, V(margin), count, want, missing, extra, wrong)) {
        if (first_missing != SIZE_MAX) {
            const int limit = w->run->max_printed > 0 ? w->run->max_printed : 20;
            if (w->run->failures <= (uint64_t)limit)
                fprintf(out_of(w->run), "    first missing: (%zu, %zu) at " VF "\n", first_missing / nb,
                        first_missing % nb, V(all[first_missing].d));
            print_pair(w, first_missing / nb, first_missing % nb);
        }
        if (first_wrong != SIZE_MAX)
            print_pair(w, first_wrong / nb, first_wrong % nb);
    }
    free(s);
}

/* The per-triangle reduction of the brute force: nearest partner within the margin, ties to the
 * smaller index; none: UINT32_MAX and +inf. */
static void check_closest(where *w, const bpair *all, double margin, const char *label, ttd_status st,
                          const ttd_closest_d *fa, const ttd_closest_d *fb)
{
    const mcase *c = w->c;
    const size_t na = c->a.nt, nb = c->b.nt;
    if (!check(w, MFQ_CLOSEST, st == TTD_OK, "closest at %s: status %d", label, st))
        return;
    size_t bad = 0, first = SIZE_MAX;
    int first_side = 0;
    for (int side = 0; side < 2; ++side) {
        const size_t n = side ? nb : na, m = side ? na : nb;
        const ttd_closest_d *got = side ? fb : fa;
        for (size_t i = 0; i < n; ++i) {
            size_t best = SIZE_MAX;
            for (size_t j = 0; j < m; ++j) {
                const bpair *x = side ? &all[j * nb + i] : &all[i * nb + j];
                if (x->d <= margin && (best == SIZE_MAX || x->d < (side ? all[best * nb + i] : all[i * nb + best]).d))
                    best = j;
            }
            int ok;
            if (best == SIZE_MAX)
                ok = got[i].partner == UINT32_MAX && isinf(got[i].distance);
            else {
                const bpair *x = side ? &all[best * nb + i] : &all[i * nb + best];
                const double *p = side ? q_of(x) : x->p, *q = side ? x->p : q_of(x);
                ok = got[i].partner == best && got[i].distance == x->d && same3(got[i].p, p) && same3(got[i].q, q);
            }
            if (!ok && bad++ == 0)
                first = i, first_side = side;
        }
    }
    check(w, MFQ_CLOSEST, bad == 0, "closest at %s " VF ": %zu records differ, first %s[%zu]: partner %u at " VF,
          label, V(margin), bad, first_side ? "b" : "a", first, bad ? (first_side ? fb : fa)[first].partner : 0,
          V(bad ? (first_side ? fb : fa)[first].distance : 0.0));
}

static void check_collide(where *w, const bpair *all, const pparams *pp, double margin, const char *label,
                          ttd_status st, const ttd_collision *x)
{
    const mcase *c = w->c;
    if (!check(w, MFQ_COLLIDE, st == TTD_OK, "collide at %s: status %d", label, st))
        return;
    const int want = pp->min <= margin;
    int ok = x->hit == (uint32_t)want;
    if (ok && want)
        ok = x->tri_a < c->a.nt && x->tri_b < c->b.nt && all[(size_t)x->tri_a * c->b.nt + x->tri_b].d <= margin;
    else if (ok)
        ok = x->tri_a == UINT32_MAX && x->tri_b == UINT32_MAX;
    if (!check(w, MFQ_COLLIDE, ok, "collide at %s " VF ": hit %u witness (%u, %u); brute force min " VF " at (%zu, %zu)",
               label, V(margin), x->hit, x->tri_a, x->tri_b, V(pp->min), pp->argmin / c->b.nt, pp->argmin % c->b.nt))
        print_pair(w, pp->argmin / c->b.nt, pp->argmin % c->b.nt);
}

static void check_against_brute(where *w, const bpair *all, const pparams *pp, const pout *po, double L)
{
    check_distance(w, all, pp, po);
    const double cm[NC] = {0, pp->min, pp->median, L};
    static const char *const cl[NC] = {"0", "min", "median", "L"};
    for (int v = 0; v < NC; ++v)
        check_contacts(w, all, cm[v], cl[v], po->cst[v], po->c[v], po->nc[v]);
    const double clm[NCL] = {pp->min, pp->median, L};
    for (int v = 0; v < NCL; ++v)
        check_closest(w, all, clm[v], cl[v + 1], po->clst[v], po->cla[v], po->clb[v]);
    const double xm[NX] = {0, pp->min, pp->below, L};
    static const char *const xl[NX] = {"0", "min", "below-min", "L"};
    for (int v = 0; v < NX; ++v)
        if (v != 2 || pp->min > 0)
            check_collide(w, all, pp, xm[v], xl[v], po->xst[v], &po->x[v]);
}

/* ---- bit-identity between runs ------------------------------------------------------------ */

static int bits_equal(const void *x, const void *y, size_t n)
{
    return n == 0 || memcmp(x, y, n) == 0;
}

static int dist_equal(const ttd_mesh_result_d *x, const ttd_mesh_result_d *y)
{
    return bits_equal(&x->distance, &y->distance, sizeof x->distance) && bits_equal(x->p, y->p, sizeof x->p) &&
           bits_equal(x->q, y->q, sizeof x->q) && x->tri_a == y->tri_a && x->tri_b == y->tri_b &&
           x->feature_a == y->feature_a && x->feature_b == y->feature_b && x->flags == y->flags &&
           x->node_tests == y->node_tests && x->pair_tests == y->pair_tests;
}

static int contacts_equal(const ttd_contact_d *x, size_t nx, const ttd_contact_d *y, size_t ny)
{
    if (nx != ny)
        return 0;
    for (size_t i = 0; i < nx; ++i)
        if (x[i].tri_a != y[i].tri_a || x[i].tri_b != y[i].tri_b ||
            !bits_equal(&x[i].distance, &y[i].distance, sizeof x[i].distance) || !bits_equal(x[i].p, y[i].p, sizeof x[i].p) ||
            !bits_equal(x[i].q, y[i].q, sizeof x[i].q))
            return 0;
    return 1;
}

static int closest_equal(const ttd_closest_d *x, const ttd_closest_d *y, size_t n)
{
    for (size_t i = 0; i < n; ++i)
        if (x[i].partner != y[i].partner || !bits_equal(&x[i].distance, &y[i].distance, sizeof x[i].distance) ||
            !bits_equal(x[i].p, y[i].p, sizeof x[i].p) || !bits_equal(x[i].q, y[i].q, sizeof x[i].q))
            return 0;
    return 1;
}

static int collision_equal(const ttd_collision *x, const ttd_collision *y)
{
    return x->hit == y->hit && x->tri_a == y->tri_a && x->tri_b == y->tri_b && x->node_tests == y->node_tests &&
           x->pair_tests == y->pair_tests;
}

/* One counted check per query variant: got equals ref bit for bit. only: the variants to
 * compare (the k-pose calls, for the poses check), -1 all. */
static void check_same(where *w, int query, const pout *ref, const pout *got, const char *what, int kpose_only)
{
    const mcase *c = w->c;
    static const char *const dn[ND] = {"distance", "distance ub=min", "distance ub<min", "distance rel 0.1",
                                       "distance rel 1"};
    for (int v = 0; v < ND; ++v) {
        if (!ref->has[v] || (kpose_only && v != 0 && v != 3 && v != 4))
            continue;
        const ttd_mesh_result_d *x = &ref->d[v], *y = &got->d[v];
        check(w, query, ref->dst[v] == got->dst[v] && dist_equal(x, y),
              "%s differs from %s: " VF " (%u, %u) vs " VF " (%u, %u), tests %u/%llu vs %u/%llu", dn[v], what,
              V(y->distance), y->tri_a, y->tri_b, V(x->distance), x->tri_a, x->tri_b, y->node_tests,
              (unsigned long long)y->pair_tests, x->node_tests, (unsigned long long)x->pair_tests);
    }
    static const char *const cn[NC] = {"contacts at 0", "contacts at min", "contacts at median", "contacts at L"};
    for (int v = 0; v < NC; ++v) {
        if (kpose_only && v != 0 && v != 3)
            continue;
        check(w, query, ref->cst[v] == got->cst[v] && contacts_equal(ref->c[v], ref->nc[v], got->c[v], got->nc[v]),
              "%s differ from %s: %zu pairs vs %zu", cn[v], what, got->nc[v], ref->nc[v]);
    }
    static const char *const ln[NCL] = {"closest at min", "closest at median", "closest at L"};
    for (int v = 0; v < NCL; ++v) {
        if (kpose_only && v != 2)
            continue;
        check(w, query,
              ref->clst[v] == got->clst[v] && closest_equal(ref->cla[v], got->cla[v], c->a.nt) &&
                  closest_equal(ref->clb[v], got->clb[v], c->b.nt),
              "%s differs from %s", ln[v], what);
    }
    static const char *const xn[NX] = {"collide at 0", "collide at min", "collide below min", "collide at L"};
    for (int v = 0; v < NX; ++v) {
        if ((kpose_only && v != 0 && v != 3) || (v == 2 && !ref->has[2]))
            continue;
        const ttd_collision *x = &ref->x[v], *y = &got->x[v];
        check(w, query, ref->xst[v] == got->xst[v] && collision_equal(x, y),
              "%s differs from %s: hit %u (%u, %u) vs hit %u (%u, %u)", xn[v], what, y->hit, y->tri_a, y->tri_b,
              x->hit, x->tri_a, x->tri_b);
    }
}

/* ---- the reference check of the brute force ----------------------------------------------- */

static void check_reference(where *w, mf_src *src, const bpair *all, const pparams *pp)
{
    const mcase *c = w->c;
    const size_t nb = c->b.nt, n = c->a.nt * nb;
    /* the minimum's pair and two drawn ones: the brute force is right where it matters most */
    for (int s = 0; s < 3; ++s) {
        const size_t i = s == 0 ? pp->argmin : (size_t)(unif(src) * (double)n) % n;
        double S[9], T[9];
        pair_coords(c, c->poses + 12 * w->pose, i / nb, i % nb, S, T);
        ttd_ref_result ref;
        ttd_ref_distance(S, T, &ref);
        const double scale = fmax(ttd_ref_size(S, T), ref.distance);
        const double tol = (c->is_float ? 1e-5 : 1e-12) + (scale > 0 ? fmax(0.0, ref.distance - ref.lower_bound) / scale : 0);
        const int ok = fabs(all[i].d - ref.distance) <= tol * scale;
        if (!check(w, MFQ_REFERENCE, ok, "brute force pair (%zu, %zu): " VF ", quad reference " VF " (tolerance %.3g)",
                   i / nb, i % nb, V(all[i].d), V(ref.distance), tol * scale))
            print_pair(w, i / nb, i % nb);
    }
}

/* ---- a case, start to end ----------------------------------------------------------------- */

/* How a refitted case's meshes were built before they took the case's vertices. */
enum { REFIT_PERMUTED = 1, REFIT_JITTERED, REFIT_ROTATED, REFIT_POINT, REFIT_KINDS };

/* Builds (when set) or moves the mesh to vertices v (3 nv doubles, floats in a float case). */
static ttd_status build_or_move(const mcase *c, const mmesh *m, const double *v, ttd_mesh **out, int move)
{
    if (!c->is_float)
        return move ? ttd_mesh_set_vertices_d(NULL, *out, v) : ttd_mesh_create_d(NULL, v, m->nv, m->t, m->nt, out);
    float *f = malloc(3 * m->nv * sizeof *f);
    if (!f)
        abort();
    for (size_t i = 0; i < 3 * m->nv; ++i)
        f[i] = (float)v[i];
    const ttd_status st = move ? ttd_mesh_set_vertices_f(NULL, *out, f) : ttd_mesh_create_f(NULL, f, m->nv, m->t, m->nt, out);
    free(f);
    return st;
}

/* The mesh of m: built from its vertices, or (c->refit) from other vertices drawn from src and
 * then moved to them, so that the queries run on a refitted tree (or a rebuilt one, where the
 * refit degraded it: permuted vertices, one point). */
static ttd_status build(mf_src *src, const mcase *c, const mmesh *m, ttd_mesh **out)
{
    if (c->refit == 0)
        return build_or_move(c, m, m->v, out, 0);
    double *pre = malloc((3 * m->nv + 1) * sizeof *pre);
    if (!pre)
        abort();
    const double amp = c->size * pow10u(src, -9, -1);
    for (size_t i = 0; i < m->nv; ++i) {
        const double *x = m->v + 3 * i;
        double *y = pre + 3 * i;
        switch (c->refit) {
        case REFIT_PERMUTED: { /* another vertex's place */
            const size_t j = (size_t)rint_n(src, (int)(m->nv < 1000000 ? m->nv : 1000000));
            memcpy(y, m->v + 3 * j, 3 * sizeof *y);
            break;
        }
        case REFIT_JITTERED:
            for (int k = 0; k < 3; ++k)
                y[k] = x[k] + amp * (unif(src) - 0.5);
            break;
        case REFIT_ROTATED: /* a quarter turn about z, twice the size */
            y[0] = -2 * x[1], y[1] = 2 * x[0], y[2] = 2 * x[2];
            break;
        default: /* REFIT_POINT */
            memcpy(y, m->v, 3 * sizeof *y);
            break;
        }
        if (c->is_float)
            for (int k = 0; k < 3; ++k)
                y[k] = (double)(float)y[k];
    }
    ttd_status st = build_or_move(c, m, pre, out, 0);
    if (st == TTD_OK)
        st = build_or_move(c, m, m->v, out, 1);
    free(pre);
    return st;
}

/* ---- self queries ---------------------------------------------------------------------------- */

/* Self-contacts of mesh mm (the case's mesh m) at margin with flags under options o, sorted by
 * (tri_a, tri_b), widened to double; and its self-collision. */
static ttd_status self_run(const mcase *c, const ttd_mesh *mm, const ttd_options *o, double margin, unsigned flags,
                           ttd_contact_d **set, size_t *n, ttd_collision *col)
{
    ttd_status st;
    *set = NULL;
    *n = 0;
    if (!c->is_float) {
        ttd_contacts_d s = {0};
        st = ttd_mesh_self_contacts_d(o, mm, margin, flags, &s);
        *n = s.count;
        *set = malloc((s.count + 1) * sizeof **set);
        if (!*set)
            abort();
        if (s.count)
            memcpy(*set, s.pairs, s.count * sizeof **set);
        ttd_contacts_free_d(&s);
        if (st == TTD_OK)
            st = ttd_mesh_self_collide_d(o, mm, margin, flags, col);
    } else {
        ttd_contacts_f s = {0};
        st = ttd_mesh_self_contacts_f(o, mm, (float)margin, flags, &s);
        *n = s.count;
        *set = malloc((s.count + 1) * sizeof **set);
        if (!*set)
            abort();
        for (size_t i = 0; i < s.count; ++i) {
            ttd_contact_d *d = &(*set)[i];
            d->tri_a = s.pairs[i].tri_a, d->tri_b = s.pairs[i].tri_b, d->distance = (double)s.pairs[i].distance;
            for (int k = 0; k < 3; ++k)
                d->p[k] = (double)s.pairs[i].p[k], d->q[k] = (double)s.pairs[i].q[k];
        }
        ttd_contacts_free_f(&s);
        if (st == TTD_OK)
            st = ttd_mesh_self_collide_f(o, mm, (float)margin, flags, col);
    }
    return st;
}

static int contact_pair_cmp(const void *x, const void *y)
{
    const ttd_contact_d *a = x, *b = y;
    return a->tri_a != b->tri_a ? (a->tri_a < b->tri_a ? -1 : 1) : (a->tri_b > b->tri_b) - (a->tri_b < b->tri_b);
}

/* Self-contacts and self-collision of mesh mm (the case's m) against the brute force, with and
 * without shared-vertex pairs, at margins 0, the nearest counting pair's distance and the
 * median's; every row with 1 and 2 threads, each equal to the scalar row's bits (set order and
 * witness included). Meshes of more than 200 triangles are skipped (the brute force is
 * quadratic). */
static void check_self(where *w, const mcase *c, const mmesh *m, const ttd_mesh *mm, const ttd_isa *isas, int nisa)
{
    if (m->nt > 200)
        return;
    for (unsigned flags = 0; flags < 2; ++flags) {
        size_t np;
        spair *all = brute_self(m->v, m->t, m->nt, c->is_float, (int)flags, &np);
        double *d = malloc((np + 1) * sizeof *d);
        if (!d)
            abort();
        for (size_t k = 0; k < np; ++k)
            d[k] = all[k].d;
        qsort(d, np, sizeof *d, cmp_double);
        const double margins[3] = {0, np ? d[0] : 0, np ? d[np / 2] : 0};
        free(d);
        for (int mi = 0; mi < 3; ++mi) {
            const double margin = prec(c, margins[mi]);
            ttd_contact_d *ref = NULL, *got;
            size_t nref = 0, ngot;
            ttd_collision cref = {0}, cgot;
            for (int ii = 0; ii < nisa; ++ii)
                for (int threads = 1; threads <= 2; ++threads) {
                    ttd_options o = ttd_default_options();
                    o.isa = isas[ii];
                    o.threads = threads;
                    const ttd_status st = self_run(c, mm, &o, margin, flags, &got, &ngot, &cgot);
                    if (!check(w, MFQ_SELF, st == TTD_OK, "self query failed (status %d)", st)) {
                        free(got);
                        continue;
                    }
                    if (ref == NULL) { /* the scalar row, 1 thread: against the brute force */
                        ref = got, nref = ngot, cref = cgot;
                        ttd_contact_d *sorted = malloc((ngot + 1) * sizeof *sorted);
                        if (!sorted)
                            abort();
                        memcpy(sorted, got, ngot * sizeof *sorted);
                        qsort(sorted, ngot, sizeof *sorted, contact_pair_cmp);
                        size_t k = 0, want = 0, bad = 0;
                        for (size_t e = 0; e < np; ++e) {
                            if (!(all[e].d <= margin))
                                continue;
                            ++want;
                            bad += !(k < ngot && sorted[k].tri_a == all[e].i && sorted[k].tri_b == all[e].j &&
                                     sorted[k].distance == all[e].d && memcmp(sorted[k].p, all[e].p, sizeof all[e].p) == 0 &&
                                     memcmp(sorted[k].q, all[e].q, sizeof all[e].q) == 0);
                            if (k < ngot && sorted[k].tri_a == all[e].i && sorted[k].tri_b == all[e].j)
                                ++k;
                        }
                        check(w, MFQ_SELF, bad == 0 && want == ngot,
                              "self-contacts (flags %u) at margin %.17g: %zu pairs, brute force %zu, %zu differ", flags,
                              margin, ngot, want, bad);
                        int within = 0;
                        for (size_t e = 0; e < np && cgot.hit; ++e)
                            within |= all[e].i == cgot.tri_a && all[e].j == cgot.tri_b && all[e].d <= margin;
                        check(w, MFQ_SELF, cgot.hit == (want > 0) && (!cgot.hit || within),
                              "self-collide (flags %u) at margin %.17g: hit %u (%u, %u), brute force %zu pairs", flags,
                              margin, cgot.hit, cgot.tri_a, cgot.tri_b, want);
                        free(sorted);
                        continue;
                    }
                    check(w, MFQ_SELF,
                          ngot == nref && (ngot == 0 || memcmp(got, ref, ngot * sizeof *got) == 0) &&
                              cgot.hit == cref.hit && cgot.tri_a == cref.tri_a && cgot.tri_b == cref.tri_b,
                          "self queries (flags %u, margin %.17g) on %s with %d threads differ from the scalar row", flags,
                          margin, ttd_isa_name(isas[ii]), threads);
                    free(got);
                }
            free(ref);
        }
        free(all);
    }
}

uint64_t mf_run_case(mf_run *run, mf_src *src, int family, uint64_t seed, uint64_t index)
{
    const uint64_t failures_before = run->failures;
    if (family < 0 || family >= MF_COUNT)
        family = rint_n(src, MF_COUNT);
    small_meshes = run->small;
    mcase c;
    generate(src, family, run->allow_big, &c);
    where w = {run, &c, seed, index, src->data == NULL, 0, NULL, 0};
    ++run->cases;
    run->poses += c.k;
    if (c.is_float)
        ++run->float_cases;
    else
        ++run->double_cases;
    if (run->verbose) {
        fprintf(out_of(run), "case %llu: ", (unsigned long long)index);
        dump_case(out_of(run), &c);
    }

    ttd_mesh *a = NULL, *b = NULL;
    c.refit = rint_n(src, 2) ? 1 + rint_n(src, REFIT_KINDS - 1) : 0;
    if (!check(&w, c.refit ? MFQ_REFIT : MFQ_POSE, build(src, &c, &c.a, &a) == TTD_OK && build(src, &c, &c.b, &b) == TTD_OK,
               "mesh build failed")) {
        ttd_mesh_destroy(a), ttd_mesh_destroy(b), free_case(&c);
        return run->failures - failures_before;
    }
    /* every pose is a rotation within the tolerance: the queries must take it */
    qctx q = {&c, a, b, {0}, NULL, 0};
    for (size_t i = 0; i < 12 * c.k; ++i)
        q.posef[i] = (float)c.poses[i];
    size_t bad = 0;
    const ttd_status pst = c.is_float ? ttd_mesh_check_poses_f(a, b, c.k, q.posef, &bad)
                                      : ttd_mesh_check_poses_d(a, b, c.k, c.poses, &bad);
    double worst = 0;
    for (size_t p = 0; p < c.k; ++p) {
        double R[9];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                R[3 * i + j] = c.poses[12 * p + 4 * (size_t)i + (size_t)j];
        worst = fmax(worst, defect(R));
    }
    if (worst > (c.is_float ? 0.7e-6 : 0.95e-6) ||
        !check(&w, MFQ_POSE, pst == TTD_OK, "pose %zu refused (status %d); largest |R^T R - I| %.3g", bad, pst, worst)) {
        ttd_mesh_destroy(a), ttd_mesh_destroy(b), free_case(&c);
        return run->failures - failures_before; /* a pose we did not mean to make: nothing to check */
    }

    /* the brute force of every pose and the parameters drawn from it */
    const size_t n = c.a.nt * c.b.nt;
    bpair *all[MAXK];
    pparams pp[MAXK];
    double *dist = malloc(n * sizeof *dist);
    if (!dist)
        abort();
    for (size_t p = 0; p < c.k; ++p) {
        all[p] = brute(&c, c.poses + 12 * p);
        pp[p].argmin = 0;
        for (size_t i = 0; i < n; ++i) {
            dist[i] = all[p][i].d;
            if (all[p][i].d < all[p][pp[p].argmin].d)
                pp[p].argmin = i;
        }
        qsort(dist, n, sizeof *dist, cmp_double);
        pp[p].min = dist[0];
        pp[p].median = dist[n / 2];
        pp[p].max = dist[n - 1];
        pp[p].below = c.is_float ? (double)nextafterf((float)pp[p].min, 0.0f) : nextafter(pp[p].min, 0);
        q.L = fmax(q.L, pp[p].max);
    }
    free(dist);
    q.L = prec(&c, q.L * 1.5 + c.size * 1e-3); /* above every pair; finite */
    q.pp = pp;
    for (size_t p = 0; p < c.k; ++p) {
        w.pose = p;
        check_reference(&w, src, all[p], &pp[p]);
    }

    /* every instruction set with 1 and 2 threads; the scalar row with 1 thread is the reference
     * for the identity checks, every one-thread run is checked against the brute force */
    ttd_isa isas[TTD_ISA_COUNT];
    int nisa = 0;
    for (int i = TTD_ISA_SCALAR; i < TTD_ISA_COUNT; ++i)
        if (ttd_isa_available((ttd_isa)i) && (!run->one_isa || i == TTD_ISA_SCALAR || i == (int)ttd_isa_selected(NULL))) {
            isas[nisa++] = (ttd_isa)i;
            run->isas_run[i] = 1;
        }
    pout *ref = calloc(c.k, sizeof *ref), *one = calloc(c.k, sizeof *one), *two = calloc(c.k, sizeof *two);
    if (!ref || !one || !two)
        abort();
    char label[32];
    for (int ii = 0; ii < nisa; ++ii)
        for (int threads = 1; threads <= 2; ++threads) {
            ttd_options o = ttd_default_options();
            o.isa = isas[ii];
            o.threads = threads;
            pout *po = threads == 2 ? two : ii == 0 ? ref : one;
            run_all(&q, &o, po);
            snprintf(label, sizeof label, "%s/%d", ttd_isa_name(isas[ii]), threads);
            w.config = label;
            for (size_t p = 0; p < c.k; ++p) {
                w.pose = p;
                if (threads == 1)
                    check_against_brute(&w, all[p], &pp[p], &po[p], q.L);
                if (threads == 1 && ii > 0)
                    check_same(&w, MFQ_ISA, &ref[p], &po[p], "scalar/1", 0);
                if (threads == 2) /* against the same row with 1 thread */
                    check_same(&w, MFQ_THREADS, ii == 0 ? &ref[p] : &one[p], &po[p], "1 thread", 0);
            }
            if (threads == 2) {
                free_outs(two, c.k);
                if (ii > 0)
                    free_outs(one, c.k);
            }
        }
    /* each mesh against itself */
    w.config = "self";
    check_self(&w, &c, &c.a, a, isas, nisa);
    check_self(&w, &c, &c.b, b, isas, nisa);
    /* k poses in one call equal k single calls (the automatic choice, 1 thread) */
    if (c.k > 1) {
        ttd_options o = ttd_default_options();
        o.threads = 1;
        pout *multi = calloc(c.k, sizeof *multi), single;
        if (!multi)
            abort();
        run_all(&q, &o, multi);
        w.config = "auto/1";
        mcase c1 = c; /* the same case with its pose p alone */
        for (size_t p = 0; p < c.k; ++p) {
            c1.k = 1;
            memcpy(c1.poses, c.poses + 12 * p, sizeof(double) * 12);
            qctx q1 = q;
            q1.c = &c1;
            memcpy(q1.posef, q.posef + 12 * p, sizeof(float) * 12);
            q1.pp = &pp[p];
            run_all(&q1, &o, &single);
            w.pose = p;
            check_same(&w, MFQ_POSES, &single, &multi[p], "the single-pose call", 1);
            free_outs(&single, 1);
        }
        free_outs(multi, c.k);
        free(multi);
    }
    free_outs(ref, c.k);
    free(ref), free(one), free(two);
    for (size_t p = 0; p < c.k; ++p)
        free(all[p]);
    ttd_mesh_destroy(a);
    ttd_mesh_destroy(b);
    free_case(&c);
    return run->failures - failures_before;
}

int mf_summary(const mf_run *run, FILE *f)
{
    if (run->failures) {
        fprintf(f, "failures by family and query:\n");
        for (int fam = 0; fam < MF_COUNT; ++fam) {
            if (!run->family_failures[fam])
                continue;
            fprintf(f, "  %-10s %llu of %llu checks:", mf_family_name(fam), (unsigned long long)run->family_failures[fam],
                    (unsigned long long)run->family_checks[fam]);
            for (int qn = 0; qn < MFQ_COUNT; ++qn)
                if (run->query_failures[fam][qn])
                    fprintf(f, " %s %llu", mf_query_name(qn), (unsigned long long)run->query_failures[fam][qn]);
            fputc('\n', f);
        }
    }
    fprintf(f, "mesh fuzz: %llu checks, %llu failures (%llu cases, %llu poses, %d double / %d float; families",
            (unsigned long long)run->checks, (unsigned long long)run->failures, (unsigned long long)run->cases,
            (unsigned long long)run->poses, run->double_cases, run->float_cases);
    for (int fam = 0; fam < MF_COUNT; ++fam)
        if (run->family_checks[fam])
            fprintf(f, " %s", mf_family_name(fam));
    fprintf(f, "; ISAs");
    for (int i = TTD_ISA_SCALAR; i < TTD_ISA_COUNT; ++i)
        if (run->isas_run[i])
            fprintf(f, " %s", ttd_isa_name((ttd_isa)i));
    fprintf(f, "; not available here:");
    int none = 1;
    for (int i = TTD_ISA_SCALAR; i < TTD_ISA_COUNT; ++i)
        if (!ttd_isa_available((ttd_isa)i))
            fprintf(f, " %s", ttd_isa_name((ttd_isa)i)), none = 0;
    fprintf(f, "%s)\n", none ? " none" : "");
    return run->failures != 0;
}
