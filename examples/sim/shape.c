/* SPDX-License-Identifier: MIT */
/* Shapes: boxes in three triangulations, icospheres and tori as closed meshes, their mass
 * properties (the signed tetrahedra from the origin to each triangle) and their convex pieces. */
#include "sim.h"
#include "vec.h"

#include "meshes.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/// python/README.md's cube, vertex index 4x + 2y + z (x, y, z in {0, 1}): two triangles per
/// face, each pair (a, b, c), (a, c, d) of the quad a b c d.
static const uint32_t box_diag_a[36] = {0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5, 0, 4, 5, 0, 5, 1,
                                        2, 3, 7, 2, 7, 6, 0, 2, 6, 0, 6, 4, 1, 5, 7, 1, 7, 3};
/// docs/examples/cube.obj's quads, its vertex index x + 2y + 4z.
static const uint32_t box_obj_quads[24] = {0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4, 2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5};

/// Fills a shape's arrays from its vertices and triangles, moves the centroid to the origin and
/// computes the mass properties, radius and size. Takes ownership of v and t.
static int shape_finish(sim_shape *s, const char *name, double *v, size_t nv, uint32_t *t, size_t nt)
{
    snprintf(s->name, sizeof s->name, "%s", name);
    s->v = v;
    s->t = t;
    s->nv = nv;
    s->nt = nt;
    /* volume and centroid: sum over the tetrahedra (0, a, b, c) */
    double vol6 = 0, c[3] = {0, 0, 0};
    for (size_t k = 0; k < nt; ++k) {
        const double *a = v + 3 * t[3 * k], *b = v + 3 * t[3 * k + 1], *d = v + 3 * t[3 * k + 2];
        double bd[3];
        v3_cross(b, d, bd);
        double det = v3_dot(a, bd);
        vol6 += det;
        for (int i = 0; i < 3; ++i)
            c[i] += det * (a[i] + b[i] + d[i]);
    }
    if (!(vol6 > 0))
        return -1;
    for (int i = 0; i < 3; ++i)
        c[i] /= 4 * vol6;
    for (size_t k = 0; k < nv; ++k)
        v3_sub(v + 3 * k, c, v + 3 * k);
    /* second moments about the centroid: a tetrahedron (0, a, b, c) of det D has
     * integral of x x^T = D / 120 (a a^T + b b^T + c c^T + s s^T), s = a + b + c */
    double cov[9] = {0};
    for (size_t k = 0; k < nt; ++k) {
        const double *p[3] = {v + 3 * t[3 * k], v + 3 * t[3 * k + 1], v + 3 * t[3 * k + 2]};
        double bd[3], sum[3];
        v3_cross(p[1], p[2], bd);
        double det = v3_dot(p[0], bd);
        for (int i = 0; i < 3; ++i)
            sum[i] = p[0][i] + p[1][i] + p[2][i];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                cov[3 * i + j] += det / 120 * (p[0][i] * p[0][j] + p[1][i] * p[1][j] + p[2][i] * p[2][j] + sum[i] * sum[j]);
    }
    double tr = cov[0] + cov[4] + cov[8];
    for (int i = 0; i < 9; ++i)
        s->inertia[i] = (i % 4 == 0 ? tr : 0) - cov[i];
    s->volume = vol6 / 6;
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    s->radius = 0;
    for (size_t k = 0; k < nv; ++k) {
        s->radius = fmax(s->radius, v3_norm(v + 3 * k));
        for (int i = 0; i < 3; ++i) {
            lo[i] = fmin(lo[i], v[3 * k + i]);
            hi[i] = fmax(hi[i], v[3 * k + i]);
        }
    }
    s->size = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
    return ttd_mesh_create_d(NULL, v, nv, t, nt, &s->mesh) == TTD_OK ? 0 : -1;
}

/// A convex piece of the triangles [t0, t1) of s and the vertices they use, plus extra face
/// normals (4 each: unit normal, offset); edges are the triangles' edges, each once.
static int piece_make(sim_piece *p, const sim_shape *s, size_t t0, size_t t1, const double *extra, size_t nextra)
{
    memset(p, 0, sizeof *p);
    size_t nt = t1 - t0;
    unsigned char *used = calloc(s->nv, 1);
    p->v = malloc(3 * 3 * nt * sizeof(double));
    p->normal = malloc(4 * (nt + nextra) * sizeof(double));
    p->edge = malloc(3 * 3 * nt * sizeof(double));
    if (!used || !p->v || !p->normal || !p->edge) {
        free(used);
        return -1;
    }
    for (size_t k = t0; k < t1; ++k) {
        const uint32_t *tri = s->t + 3 * k;
        for (int e = 0; e < 3; ++e) {
            uint32_t u = tri[e], w = tri[(e + 1) % 3];
            if (!used[u]) {
                used[u] = 1;
                memcpy(p->v + 3 * p->nv++, s->v + 3 * u, 3 * sizeof(double));
            }
            /* a closed mesh holds each edge once as (u, w) with u < w, once the other way; an
             * edge of the piece's boundary may come only the other way, so keep both when the
             * piece is not the whole shape (the test only needs a superset of directions) */
            if (u < w || t1 - t0 < s->nt)
                v3_sub(s->v + 3 * w, s->v + 3 * u, p->edge + 3 * p->ne++);
        }
        double *n = p->normal + 4 * p->nn, ab[3], ac[3];
        v3_sub(s->v + 3 * tri[1], s->v + 3 * tri[0], ab);
        v3_sub(s->v + 3 * tri[2], s->v + 3 * tri[0], ac);
        v3_cross(ab, ac, n);
        if (v3_normalize(n) > 0) {
            n[3] = v3_dot(n, s->v + 3 * tri[0]);
            ++p->nn;
        }
    }
    free(used);
    if (nextra) {
        memcpy(p->normal + 4 * p->nn, extra, 4 * nextra * sizeof(double));
        p->nn += nextra;
    }
    /* the sphere around the vertices' mean */
    for (size_t k = 0; k < p->nv; ++k)
        v3_axpy(p->centre, 1.0 / (double)p->nv, p->v + 3 * k, p->centre);
    for (size_t k = 0; k < p->nv; ++k) {
        double d[3];
        v3_sub(p->v + 3 * k, p->centre, d);
        p->radius = fmax(p->radius, v3_norm(d));
    }
    return 0;
}

/// A convex shape is its own piece.
static int shape_one_piece(sim_shape *s)
{
    s->pieces = calloc(1, sizeof(sim_piece));
    if (!s->pieces)
        return -1;
    s->npieces = 1;
    return piece_make(s->pieces, s, 0, s->nt, NULL, 0);
}

/// The index of point p among the n vertices at v, appended when new (exact comparison: the
/// faces' shared rims are computed the same way on both faces).
static uint32_t vertex_at(double *v, size_t *n, const double p[3])
{
    for (size_t k = 0; k < *n; ++k)
        if (v[3 * k] == p[0] && v[3 * k + 1] == p[1] && v[3 * k + 2] == p[2])
            return (uint32_t)k;
    memcpy(v + 3 * *n, p, 3 * sizeof(double));
    return (uint32_t)(*n)++;
}

/// splitmix64 as a uniform in [0, 1): the cut faces' jitter.
static double shape_uniform(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return (double)((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
}

/// A box's faces with a centre vertex each (SIM_BOX_CENTRE) or cut 4 x 4 with the inner
/// vertices jittered in the face's plane by up to 0.3 of a cell (SIM_BOX_CUT, as
/// scripts/tower_scene.py's "cut"). Each face: a corner o and edges along axes U, V with
/// U x V outward; the rim's vertices are shared by the faces that meet there.
static size_t box_grid(const double h[3], sim_box_tri tri, double *v, size_t *nv, uint32_t *t)
{
    const int n = tri == SIM_BOX_CUT ? 4 : 1;
    uint64_t rng = 3;
    size_t nt = 0;
    for (int axis = 0; axis < 3; ++axis)
        for (int sgn = -1; sgn <= 1; sgn += 2) {
            const int u = (axis + 1) % 3, w = (axis + 2) % 3, U = sgn > 0 ? u : w, V = sgn > 0 ? w : u;
            uint32_t g[5][5];
            for (int a = 0; a <= n; ++a)
                for (int b = 0; b <= n; ++b) {
                    const int rim = a == 0 || a == n || b == 0 || b == n;
                    double ja = 0, jb = 0;
                    if (!rim) {
                        ja = (shape_uniform(&rng) - 0.5) * 0.6 / n;
                        jb = (shape_uniform(&rng) - 0.5) * 0.6 / n;
                    }
                    double p[3];
                    p[axis] = sgn * h[axis];
                    p[U] = -h[U] + 2 * h[U] * ((double)a / n + ja);
                    p[V] = -h[V] + 2 * h[V] * ((double)b / n + jb);
                    g[a][b] = vertex_at(v, nv, p);
                }
            if (tri == SIM_BOX_CENTRE) {
                double c[3];
                c[axis] = sgn * h[axis];
                c[U] = c[V] = 0;
                const uint32_t mid = vertex_at(v, nv, c), ring[4] = {g[0][0], g[1][0], g[1][1], g[0][1]};
                for (int k = 0; k < 4; ++k, ++nt) {
                    t[3 * nt] = ring[k];
                    t[3 * nt + 1] = ring[(k + 1) % 4];
                    t[3 * nt + 2] = mid;
                }
                continue;
            }
            for (int a = 0; a < n; ++a)
                for (int b = 0; b < n; ++b) {
                    const uint32_t q[6] = {g[a][b], g[a + 1][b], g[a + 1][b + 1], g[a][b], g[a + 1][b + 1], g[a][b + 1]};
                    memcpy(t + 3 * nt, q, sizeof q);
                    nt += 2;
                }
        }
    return nt;
}

/// A box's one piece: every vertex of the shape, its six faces and three edge directions
/// (the cut and centred faces' triangles would give the same planes many times over).
static int box_piece(sim_shape *s)
{
    if (!(s->pieces = calloc(1, sizeof(sim_piece))))
        return -1;
    s->npieces = 1;
    sim_piece *p = s->pieces;
    p->v = malloc(3 * s->nv * sizeof(double));
    p->normal = calloc(4 * 6, sizeof(double));
    p->edge = calloc(9, sizeof(double));
    if (!p->v || !p->normal || !p->edge)
        return -1;
    memcpy(p->v, s->v, 3 * s->nv * sizeof(double));
    p->nv = s->nv;
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (size_t k = 0; k < s->nv; ++k)
        for (int i = 0; i < 3; ++i) {
            lo[i] = fmin(lo[i], s->v[3 * k + i]);
            hi[i] = fmax(hi[i], s->v[3 * k + i]);
        }
    for (int i = 0; i < 3; ++i) {
        p->normal[8 * i + i] = 1;
        p->normal[8 * i + 3] = hi[i];
        p->normal[8 * i + 4 + i] = -1;
        p->normal[8 * i + 7] = -lo[i];
        p->edge[4 * i] = 1;
        p->centre[i] = 0.5 * (lo[i] + hi[i]);
    }
    p->nn = 6;
    p->ne = 3;
    for (size_t k = 0; k < p->nv; ++k) {
        double d[3];
        v3_sub(p->v + 3 * k, p->centre, d);
        p->radius = fmax(p->radius, v3_norm(d));
    }
    return 0;
}

int sim_shape_box(sim_shape *s, const double h[3], sim_box_tri tri)
{
    memset(s, 0, sizeof *s);
    const int grid = tri == SIM_BOX_CENTRE || tri == SIM_BOX_CUT;
    double *v = malloc(3 * 6 * 25 * sizeof(double));
    uint32_t *t = malloc(3 * 6 * 32 * sizeof(uint32_t));
    if (!v || !t || (int)tri < 0 || (int)tri > 4) {
        free(v);
        free(t);
        return -1;
    }
    static const char *names[5] = {"box-a", "box-b", "box-fan", "box-centre", "box-cut"};
    size_t nv = 8, nt = 12;
    if (grid) {
        nv = 0;
        nt = box_grid(h, tri, v, &nv, t);
        if (shape_finish(s, names[tri], v, nv, t, nt) != 0 || box_piece(s) != 0) {
            sim_shape_free(s);
            return -1;
        }
        return 0;
    }
    for (int k = 0; k < 8; ++k) {
        v[3 * k] = (k & 4) ? h[0] : -h[0];
        v[3 * k + 1] = (k & 2) ? h[1] : -h[1];
        v[3 * k + 2] = (k & 1) ? h[2] : -h[2];
    }
    for (int f = 0; f < 6; ++f) {
        uint32_t *o = t + 6 * f;
        if (tri == SIM_BOX_FAN) {
            /* cube.obj's index x + 2y + 4z is this one's 4x + 2y + z: swap the x and z bits */
            uint32_t q[4];
            for (int c = 0; c < 4; ++c) {
                uint32_t k = box_obj_quads[4 * f + c];
                q[c] = ((k & 1) << 2) | (k & 2) | ((k & 4) >> 2);
            }
            const uint32_t fan[6] = {q[0], q[1], q[2], q[0], q[2], q[3]};
            memcpy(o, fan, sizeof fan);
        } else {
            const uint32_t *a = box_diag_a + 6 * f; /* (a, b, c), (a, c, d) */
            uint32_t qa = a[0], qb = a[1], qc = a[2], qd = a[5];
            const uint32_t diag_a[6] = {qa, qb, qc, qa, qc, qd}, diag_b[6] = {qa, qb, qd, qb, qc, qd};
            memcpy(o, tri == SIM_BOX_DIAG_A ? diag_a : diag_b, sizeof diag_a);
        }
    }
    if (shape_finish(s, names[tri], v, nv, t, nt) != 0 || shape_one_piece(s) != 0) {
        sim_shape_free(s);
        return -1;
    }
    return 0;
}

int sim_shape_icosphere(sim_shape *s, double radius, int level)
{
    memset(s, 0, sizeof *s);
    ttd_gen_mesh m;
    if (ttd_gen_icosphere(level, &m) != 0)
        return -1;
    /* turn the first face's normal n onto -z: about n x (-z), by the angle between them */
    double ab[3], ac[3], n[3], axis[3], q[4], R[9];
    const uint32_t *f = m.tris;
    v3_sub(m.verts + 3 * f[1], m.verts + 3 * f[0], ab);
    v3_sub(m.verts + 3 * f[2], m.verts + 3 * f[0], ac);
    v3_cross(ab, ac, n);
    v3_normalize(n);
    const double down[3] = {0, 0, -1};
    v3_cross(n, down, axis);
    double sin_angle = v3_normalize(axis);
    quat_axis_angle(axis, atan2(sin_angle, v3_dot(n, down)), q);
    quat_to_m3(q, R);
    for (size_t k = 0; k < m.nv; ++k) {
        double *p = m.verts + 3 * k;
        m3_mul_v(R, p, p);
        for (int i = 0; i < 3; ++i)
            p[i] *= radius;
    }
    char name[32];
    snprintf(name, sizeof name, "icosphere-%d", level);
    if (shape_finish(s, name, m.verts, m.nv, m.tris, m.nt) != 0 || shape_one_piece(s) != 0) {
        sim_shape_free(s);
        return -1;
    }
    return 0;
}

int sim_shape_torus(sim_shape *s, double R, double r, size_t nu, size_t nv)
{
    memset(s, 0, sizeof *s);
    ttd_gen_mesh m;
    if (ttd_gen_torus(R, r, nu, nv, &m) != 0)
        return -1;
    if (shape_finish(s, "torus", m.verts, m.nv, m.tris, m.nt) != 0 || !(s->pieces = calloc(nu, sizeof(sim_piece)))) {
        sim_shape_free(s);
        return -1;
    }
    s->npieces = nu;
    /* segment i: the 2 nv triangles between rings i and i + 1, closed by the two rings' planes
     * (ring k's plane holds the z axis and vertex (k, 0)) */
    for (size_t i = 0; i < nu; ++i) {
        double caps[8];
        for (int c = 0; c < 2; ++c) {
            size_t ring = (i + (size_t)c) % nu, other = (i + 1 - (size_t)c) % nu;
            const double z[3] = {0, 0, 1};
            double *n = caps + 4 * c;
            v3_cross(z, s->v + 3 * (ring * nv), n);
            v3_normalize(n);
            n[3] = v3_dot(n, s->v + 3 * (ring * nv));
            if (v3_dot(n, s->v + 3 * (other * nv)) > n[3]) { /* outward: away from the other ring */
                for (int k = 0; k < 4; ++k)
                    n[k] = -n[k];
            }
        }
        if (piece_make(s->pieces + i, s, 2 * nv * i, 2 * nv * (i + 1), caps, 2) != 0) {
            sim_shape_free(s);
            return -1;
        }
    }
    return 0;
}

/// A convex piece of eight corners (a cell of the bowl: 0-3 on the inner surface, 4-7 the
/// outer ones behind them; 0 and 1 its lower and upper arc steps at its first angle, 2 and 3
/// at the next angle).
/// Faces from Newell's normal of each quad, turned away from the cell's centre; a quad that
/// collapses (at the poles) is left out, and so are zero edges.
static int cell_piece(sim_piece *p, double c[8][3])
{
    static const int quad[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1}, {2, 3, 7, 6}};
    static const int edge[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3}, {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    memset(p, 0, sizeof *p);
    p->v = malloc(3 * 8 * sizeof(double));
    p->normal = malloc(4 * 6 * sizeof(double));
    p->edge = malloc(3 * 12 * sizeof(double));
    if (!p->v || !p->normal || !p->edge)
        return -1;
    for (int k = 0; k < 8; ++k) {
        int seen = 0;
        for (size_t i = 0; i < p->nv; ++i)
            seen |= p->v[3 * i] == c[k][0] && p->v[3 * i + 1] == c[k][1] && p->v[3 * i + 2] == c[k][2];
        if (!seen)
            memcpy(p->v + 3 * p->nv++, c[k], 3 * sizeof(double));
    }
    for (size_t k = 0; k < p->nv; ++k)
        v3_axpy(p->centre, 1.0 / (double)p->nv, p->v + 3 * k, p->centre);
    for (size_t k = 0; k < p->nv; ++k) {
        double d[3];
        v3_sub(p->v + 3 * k, p->centre, d);
        p->radius = fmax(p->radius, v3_norm(d));
    }
    for (int f = 0; f < 6; ++f) {
        double *n = p->normal + 4 * p->nn, m[3] = {0, 0, 0}, d[3];
        n[0] = n[1] = n[2] = 0;
        for (int k = 0; k < 4; ++k) {
            const double *a = c[quad[f][k]], *b = c[quad[f][(k + 1) % 4]];
            n[0] += (a[1] - b[1]) * (a[2] + b[2]);
            n[1] += (a[2] - b[2]) * (a[0] + b[0]);
            n[2] += (a[0] - b[0]) * (a[1] + b[1]);
            v3_axpy(m, 0.25, a, m);
        }
        if (!(v3_normalize(n) > 1e-12 * p->radius * p->radius))
            continue;
        v3_sub(m, p->centre, d);
        if (v3_dot(n, d) < 0)
            for (int i = 0; i < 3; ++i)
                n[i] = -n[i];
        /* the plane through the face's mean corner: a face not flat, or a cell not convex, leaves
           corners outside it by what sim_shape_convexity_defect measures */
        n[3] = v3_dot(n, m);
        ++p->nn;
    }
    for (int e = 0; e < 12; ++e) {
        double *d = p->edge + 3 * p->ne;
        v3_sub(c[edge[e][1]], c[edge[e][0]], d);
        if (v3_norm(d) > 0)
            ++p->ne;
    }
    return 0;
}

int sim_shape_bowl(sim_shape *s, double r, double thickness, double rim, size_t nu, size_t nseg, double *bottom)
{
    memset(s, 0, sizeof *s);
    if (nu < 3 || nseg < 1 || !(r > 0 && thickness > 0 && rim > 0 && rim < 3.0))
        return -1;
    /* the profile: inner pole, inner rings 1..nseg, outer rings nseg..1, outer pole; the sphere's
       centre at height r, so the inner bottom is at 0 before the centroid moves */
    const size_t nring = 2 * nseg, nv = 2 + nring * nu, nt = 2 * nu * (2 * nseg - 1) + 2 * nu;
    double *v = malloc(3 * nv * sizeof(double));
    uint32_t *t = malloc(3 * nt * sizeof(uint32_t));
    if (!v || !t) {
        free(v);
        free(t);
        return -1;
    }
    const double ro = r + thickness;
    v[0] = v[1] = 0;
    v[2] = 0;
    v[3 * (nv - 1)] = v[3 * (nv - 1) + 1] = 0;
    v[3 * (nv - 1) + 2] = r - ro;
    for (size_t k = 0; k < nring; ++k) {
        const int outer = k >= nseg;
        const size_t j = outer ? 2 * nseg - k : k + 1; /* arc step, 1..nseg */
        const double th = rim * (double)j / (double)nseg, rad = outer ? ro : r;
        for (size_t i = 0; i < nu; ++i) {
            const double phi = 6.283185307179586 * (double)i / (double)nu;
            double *p = v + 3 * (1 + k * nu + i);
            p[0] = rad * sin(th) * cos(phi);
            p[1] = rad * sin(th) * sin(phi);
            p[2] = r - rad * cos(th);
        }
    }
    /* profile vertex k (0 the inner pole, 1..nring the rings, nring + 1 the outer pole) at angle i */
#define BOWL_VID(k, i) ((k) == 0 ? 0u : (k) == nring + 1 ? (uint32_t)(nv - 1) : (uint32_t)(1 + ((k) - 1) * nu + (i) % nu))
    size_t m = 0;
    for (size_t k = 0; k <= nring; ++k)
        for (size_t i = 0; i < nu; ++i) {
            const uint32_t a = BOWL_VID(k, i), b = BOWL_VID(k, i + 1), c = BOWL_VID(k + 1, i + 1), d = BOWL_VID(k + 1, i);
            if (k != 0) { /* (a, b, c) unless a and b are the same pole */
                t[3 * m] = a, t[3 * m + 1] = b, t[3 * m + 2] = c;
                ++m;
            }
            if (k != nring) {
                t[3 * m] = a, t[3 * m + 1] = c, t[3 * m + 2] = d;
                ++m;
            }
        }
    /* which way round: the profile runs up the inside, so make the volume positive */
    double vol6 = 0;
    for (size_t q = 0; q < m; ++q) {
        double bd[3];
        v3_cross(v + 3 * t[3 * q + 1], v + 3 * t[3 * q + 2], bd);
        vol6 += v3_dot(v + 3 * t[3 * q], bd);
    }
    if (vol6 < 0)
        for (size_t q = 0; q < m; ++q) {
            uint32_t x = t[3 * q + 1];
            t[3 * q + 1] = t[3 * q + 2];
            t[3 * q + 2] = x;
        }
    if (m != nt || shape_finish(s, "bowl", v, nv, t, nt) != 0 || !(s->pieces = calloc(nu * nseg, sizeof(sim_piece)))) {
        if (!s->v) {
            free(v);
            free(t);
        }
        sim_shape_free(s);
        return -1;
    }
    *bottom = s->v[2];
    s->npieces = nu * nseg;
    for (size_t j = 0; j < nseg; ++j)
        for (size_t i = 0; i < nu; ++i) {
            /* the cell between arc steps j, j + 1 and angles i, i + 1: inner profile vertices j
               and j + 1, the outer ones behind them (profile 2 nseg + 1 - j, 2 nseg - j) */
            const size_t kin[2] = {j, j + 1}, kout[2] = {nring + 1 - j, nring - j};
            double c[8][3];
            for (int side = 0; side < 2; ++side)
                for (int step = 0; step < 2; ++step)
                    for (int turn = 0; turn < 2; ++turn) {
                        const size_t k = side ? kout[step] : kin[step];
                        memcpy(c[4 * side + 2 * turn + step], s->v + 3 * BOWL_VID(k, i + (size_t)turn), 3 * sizeof(double));
                    }
            if (cell_piece(s->pieces + j * nu + i, c) != 0) {
                sim_shape_free(s);
                return -1;
            }
        }
#undef BOWL_VID
    return 0;
}

void sim_shape_free(sim_shape *s)
{
    if (!s)
        return;
    for (size_t k = 0; k < s->npieces; ++k) {
        free(s->pieces[k].v);
        free(s->pieces[k].normal);
        free(s->pieces[k].edge);
    }
    free(s->pieces);
    free(s->v);
    free(s->t);
    ttd_mesh_destroy(s->mesh);
    memset(s, 0, sizeof *s);
}

double sim_shape_convexity_defect(const sim_shape *s)
{
    double worst = 0;
    for (size_t k = 0; k < s->npieces; ++k) {
        const sim_piece *p = s->pieces + k;
        for (size_t f = 0; f < p->nn; ++f)
            for (size_t i = 0; i < p->nv; ++i)
                worst = fmax(worst, v3_dot(p->normal + 4 * f, p->v + 3 * i) - p->normal[4 * f + 3]);
    }
    return worst / s->radius;
}
