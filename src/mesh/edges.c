/* SPDX-License-Identifier: MIT */
/* The edge information of a mesh (mesh/edges.h): places, rings, neighbours across edges, and the
 * classes of edges and vertices.
 *
 * Places: vertices at the same point are one place (a hash of the coordinates' bits, in vertex
 * order, so each place is named by its first vertex's turn). Rings: the triangles around each
 * place, by a counting pass (in triangle order). Across: for edge (a, b) of t, the triangles of
 * a's ring that also have a corner at b; exactly one, which runs the edge the other way (b to a),
 * makes a manifold edge; anything else is open. Classes: from the two unit normals (computed at
 * unit scale, so that tiny and huge meshes get the same classes as at size 1) and the side of t's
 * plane on which the neighbour's far vertex lies. Every step is O(n) but for the rings' scans,
 * O(triangles x ring size). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mesh/edges.h"

static void vertex_at(int bytes, const void *verts, size_t v, double x[3])
{
    for (int c = 0; c < 3; ++c)
        x[c] = bytes == 8 ? ((const double *)verts)[3 * v + (size_t)c] : (double)((const float *)verts)[3 * v + (size_t)c];
}

/* The unit normal of triangle (a, b, c) into n, computed on its edges scaled by a power of two
 * to unit size (exact, and no square underflows or overflows); 0 when it has no area to speak of
 * (|e1 x e2| within 64 eps of |e1| |e2|: collinear to rounding). */
static int unit_normal(const double a[3], const double b[3], const double c[3], double n[3])
{
    double e1[3], e2[3], m = 0;
    for (int r = 0; r < 3; ++r) {
        e1[r] = b[r] - a[r];
        e2[r] = c[r] - a[r];
        m = fmax(m, fmax(fabs(e1[r]), fabs(e2[r])));
    }
    if (!(m > 0) || !isfinite(m))
        return 0;
    int ex;
    frexp(m, &ex);
    const double s = ldexp(1.0, -ex);
    for (int r = 0; r < 3; ++r) {
        e1[r] *= s;
        e2[r] *= s;
    }
    const double x[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    const double len = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    const double l1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    const double l2 = sqrt(e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]);
    if (!(len > 64 * 2.220446049250313e-16 * l1 * l2))
        return 0;
    for (int r = 0; r < 3; ++r)
        n[r] = x[r] / len;
    return 1;
}

/* The sign of the volume the triangles enclose (the sum of det(A - O, B - O, C - O), O the first
 * vertex, at unit scale so that no product overflows or underflows): for a closed surface, +
 * wound outward, - inward. */
static int volume_sign(int bytes, const void *verts, const uint32_t *tris, size_t nt)
{
    double o[3], x[3], m = 0, sum = 0;
    vertex_at(bytes, verts, tris[0], o);
    for (size_t i = 0; i < 3 * nt; ++i) {
        vertex_at(bytes, verts, tris[i], x);
        for (int r = 0; r < 3; ++r)
            m = fmax(m, fabs(x[r] - o[r]));
    }
    if (!(m > 0) || !isfinite(m))
        return 0;
    int ex;
    frexp(m, &ex);
    for (size_t t = 0; t < nt; ++t) {
        double a[3][3];
        for (int k = 0; k < 3; ++k) {
            vertex_at(bytes, verts, tris[3 * t + (size_t)k], a[k]);
            for (int r = 0; r < 3; ++r)
                a[k][r] = ldexp(a[k][r] - o[r], -ex);
        }
        sum += a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
               a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    }
    return (sum > 0) - (sum < 0);
}

/* The root of t's set, halving the path on the way. */
static uint32_t find_root(uint32_t *up, uint32_t t)
{
    while (up[t] != t) {
        up[t] = up[up[t]];
        t = up[t];
    }
    return t;
}

static uint64_t mix64(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

static uint64_t coord_bits(double x)
{
    x += 0.0; /* -0 is +0 */
    uint64_t b;
    memcpy(&b, &x, sizeof b);
    return b;
}

/* weld[v] for every vertex; returns the number of places, or SIZE_MAX out of memory. */
static size_t weld_vertices(int bytes, const void *verts, size_t nv, uint32_t *weld)
{
    size_t cap = 16;
    while (cap < 2 * nv)
        cap *= 2;
    uint32_t *slot = calloc(cap, sizeof *slot); /* first vertex of a place + 1; 0 empty */
    if (slot == NULL)
        return SIZE_MAX;
    size_t nw = 0;
    for (size_t v = 0; v < nv; ++v) {
        double x[3];
        vertex_at(bytes, verts, v, x);
        const uint64_t h = mix64(coord_bits(x[0]) ^ mix64(coord_bits(x[1]) ^ mix64(coord_bits(x[2]))));
        size_t at = (size_t)h & (cap - 1);
        for (;; at = (at + 1) & (cap - 1)) {
            if (slot[at] == 0) {
                slot[at] = (uint32_t)v + 1;
                weld[v] = (uint32_t)nw++;
                break;
            }
            double y[3];
            const uint32_t u = slot[at] - 1;
            vertex_at(bytes, verts, u, y);
            if (coord_bits(x[0]) == coord_bits(y[0]) && coord_bits(x[1]) == coord_bits(y[1]) &&
                coord_bits(x[2]) == coord_bits(y[2])) {
                weld[v] = weld[u];
                break;
            }
        }
    }
    free(slot);
    return nw;
}

void ttd_mesh_edges_free(ttd_mesh_edges *e)
{
    free(e->across);
    free(e->shape);
    free(e->weld);
    free(e->ring_start);
    free(e->ring);
    free(e->piece);
    free(e->piece_area);
    free(e->piece_planar);
    free(e->normal);
    free(e->shape_solid);
    memset(e, 0, sizeof *e);
}

int ttd_mesh_edges_build(int bytes, const void *verts, size_t nv, const uint32_t *tris, size_t nt,
                         ttd_mesh_edges *out)
{
    memset(out, 0, sizeof *out);
    ttd_mesh_edges E = {0};
    double *normal = NULL;   /* 3 nt unit normals */
    unsigned char *has_normal = NULL; /* nt: 1 when the triangle has a normal */
    E.across = malloc((3 * nt + 1) * sizeof *E.across);
    E.normal = malloc((3 * nt + 1) * sizeof *E.normal);
    E.shape = calloc(nt + 1, sizeof *E.shape);
    E.weld = malloc((nv + 1) * sizeof *E.weld);
    normal = malloc((3 * nt + 1) * sizeof *normal);
    has_normal = malloc(nt + 1);
    if (!E.across || !E.shape || !E.weld || !normal || !has_normal || !E.normal)
        goto nomem;
    E.nw = weld_vertices(bytes, verts, nv, E.weld);
    if (E.nw == SIZE_MAX)
        goto nomem;
    /* rings, by counting */
    E.ring_start = calloc(E.nw + 1, sizeof *E.ring_start);
    E.ring = malloc((3 * nt + 1) * sizeof *E.ring);
    if (!E.ring_start || !E.ring)
        goto nomem;
    for (size_t i = 0; i < 3 * nt; ++i)
        E.ring_start[E.weld[tris[i]] + 1]++;
    for (size_t w = 0; w < E.nw; ++w)
        E.ring_start[w + 1] += E.ring_start[w];
    {
        uint32_t *fill = malloc((E.nw + 1) * sizeof *fill);
        if (fill == NULL)
            goto nomem;
        memcpy(fill, E.ring_start, E.nw * sizeof *fill);
        for (size_t i = 0; i < 3 * nt; ++i)
            E.ring[fill[E.weld[tris[i]]]++] = (uint32_t)(i / 3);
        free(fill);
    }
    /* normals; a triangle with two corners at one place has none */
    for (size_t t = 0; t < nt; ++t) {
        double x[3][3];
        for (int k = 0; k < 3; ++k)
            vertex_at(bytes, verts, tris[3 * t + (size_t)k], x[k]);
        const uint32_t *w = E.weld;
        const uint32_t a = w[tris[3 * t]], b = w[tris[3 * t + 1]], c = w[tris[3 * t + 2]];
        has_normal[t] = (unsigned char)(a != b && b != c && a != c && unit_normal(x[0], x[1], x[2], normal + 3 * t));
        for (int r = 0; r < 3; ++r)
            E.normal[3 * t + (size_t)r] = has_normal[t] ? (float)normal[3 * t + (size_t)r] : 0.0f;
    }
    const double cos_flat = cos(TTD_FLAT_ANGLE);
    int closed = 1; /* every edge of a triangle with a normal has one neighbour, running it back */
    /* edges: the one triangle across, and the class */
    for (size_t t = 0; t < nt; ++t) {
        for (int k = 0; k < 3; ++k) {
            const uint32_t va = tris[3 * t + (size_t)k], vb = tris[3 * t + (size_t)((k + 1) % 3)];
            const uint32_t a = E.weld[va], b = E.weld[vb];
            uint32_t found = TTD_NO_TRIANGLE;
            int count = 0, reversed = 0;
            for (uint32_t r = E.ring_start[a]; has_normal[t] && r < E.ring_start[a + 1]; ++r) {
                const uint32_t u = E.ring[r];
                if (u == t || (r > E.ring_start[a] && E.ring[r - 1] == u))
                    continue; /* t itself; a triangle listed twice (two corners at a) */
                int ia = -1, ib = -1;
                for (int m = 0; m < 3; ++m) {
                    const uint32_t wm = E.weld[tris[3 * (size_t)u + (size_t)m]];
                    ia = wm == a ? m : ia;
                    ib = wm == b ? m : ib;
                }
                if (ia < 0 || ib < 0)
                    continue;
                ++count;
                found = u;
                reversed = (ib + 1) % 3 == ia; /* u runs b -> a */
            }
            closed &= !has_normal[t] || (count == 1 && reversed);
            int cls = TTD_EDGE_OPEN;
            if (count == 1 && reversed && has_normal[found]) {
                const double *nt_ = normal + 3 * t, *nu = normal + 3 * (size_t)found;
                const double c = nt_[0] * nu[0] + nt_[1] * nu[1] + nt_[2] * nu[2];
                /* the neighbour's far vertex: in front of t's plane (concave) or behind (convex) */
                uint32_t far = tris[3 * (size_t)found];
                for (int m = 0; m < 3; ++m) {
                    const uint32_t wm = E.weld[tris[3 * (size_t)found + (size_t)m]];
                    if (wm != a && wm != b)
                        far = tris[3 * (size_t)found + (size_t)m];
                }
                double xa[3], xf[3];
                vertex_at(bytes, verts, va, xa);
                vertex_at(bytes, verts, far, xf);
                const double side = (xf[0] - xa[0]) * nt_[0] + (xf[1] - xa[1]) * nt_[1] + (xf[2] - xa[2]) * nt_[2];
                if (c >= cos_flat)
                    cls = TTD_EDGE_FLAT;
                else if (side < 0)
                    cls = TTD_EDGE_CONVEX;
                else if (side > 0)
                    cls = TTD_EDGE_CONCAVE;
                /* else folded back onto itself: open */
            }
            E.across[3 * t + (size_t)k] = cls == TTD_EDGE_OPEN ? TTD_NO_TRIANGLE : found;
            E.shape[t] |= (uint16_t)(cls << (2 * k));
        }
    }
    /* a closed surface wound inward (negative volume): as a solid it is the solid wound outward
     * (the one inside rule, points/winding.c), seen from which its convex and concave edges swap
     * (shape_solid; its vertices' classes below) */
    E.inward = closed && nt > 0 && volume_sign(bytes, verts, tris, nt) < 0;
    if (E.inward && (E.shape_solid = malloc((nt + 1) * sizeof *E.shape_solid)) == NULL)
        goto nomem;
    for (size_t t = 0; E.inward && t < nt; ++t) {
        E.shape_solid[t] = E.shape[t];
        for (int k = 0; k < 3; ++k) {
            const int cls = ttd_edge_class(&E, (uint32_t)t, k);
            const int swapped = cls == TTD_EDGE_CONVEX ? TTD_EDGE_CONCAVE : cls == TTD_EDGE_CONCAVE ? TTD_EDGE_CONVEX : cls;
            E.shape_solid[t] = (uint16_t)((E.shape_solid[t] & ~(3u << (2 * k))) | (unsigned)swapped << (2 * k));
        }
    }
    /* flat pieces: triangles joined by flat edges (union by the smaller root, so that a piece's
     * root is its first triangle), their areas summed at the mesh's scale, kept as log2 */
    E.piece = malloc((nt + 1) * sizeof *E.piece);
    if (E.piece == NULL)
        goto nomem;
    for (size_t t = 0; t < nt; ++t)
        E.piece[t] = (uint32_t)t;
    for (size_t t = 0; t < nt; ++t)
        for (int k = 0; k < 3; ++k)
            if (ttd_edge_class(&E, (uint32_t)t, k) == TTD_EDGE_FLAT) {
                const uint32_t a = find_root(E.piece, (uint32_t)t), b = find_root(E.piece, E.across[3 * t + (size_t)k]);
                if (a != b)
                    E.piece[a > b ? a : b] = a < b ? a : b;
            }
    {
        double lo = HUGE_VAL, hi = -HUGE_VAL;
        for (size_t v = 0; v < nv; ++v) {
            double x[3];
            vertex_at(bytes, verts, v, x);
            for (int c = 0; c < 3; ++c) {
                lo = fmin(lo, x[c]);
                hi = fmax(hi, x[c]);
            }
        }
        int es = 0;
        const double ext = fmax(fabs(lo), fabs(hi));
        if (ext > 0 && isfinite(ext))
            frexp(ext, &es);
        /* number the pieces in order of their first triangle, and sum their areas */
        uint32_t *num = malloc((nt + 1) * sizeof *num);
        double *area = calloc(nt + 1, sizeof *area);
        if (num == NULL || area == NULL) {
            free(num);
            free(area);
            goto nomem;
        }
        E.npieces = 0;
        for (size_t t = 0; t < nt; ++t) {
            const uint32_t r = find_root(E.piece, (uint32_t)t);
            num[t] = r == t ? (uint32_t)E.npieces++ : num[r];
            double x[3][3];
            for (int k = 0; k < 3; ++k) {
                vertex_at(bytes, verts, tris[3 * t + (size_t)k], x[k]);
                for (int c = 0; c < 3; ++c)
                    x[k][c] = ldexp(x[k][c], -es);
            }
            const double e1[3] = {x[1][0] - x[0][0], x[1][1] - x[0][1], x[1][2] - x[0][2]};
            const double e2[3] = {x[2][0] - x[0][0], x[2][1] - x[0][1], x[2][2] - x[0][2]};
            const double cr[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
            area[num[t]] += 0.5 * sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
        }
        for (size_t t = 0; t < nt; ++t)
            E.piece[t] = num[t];
        E.piece_area = malloc((E.npieces + 1) * sizeof *E.piece_area);
        E.piece_planar = malloc(E.npieces + 1);
        if (E.piece_area == NULL || E.piece_planar == NULL) {
            free(num);
            free(area);
            goto nomem;
        }
        for (size_t p = 0; p < E.npieces; ++p)
            E.piece_area[p] = area[p] > 0 ? log2(area[p]) + 2 * es : -HUGE_VAL;
        /* planar pieces: each piece's largest triangle (the first of equals) gives the plane,
         * every vertex of the piece within TTD_PLANAR_TOL of it (at the mesh's scale); num and
         * area are reused as each piece's largest triangle and its doubled area */
        for (size_t p = 0; p < E.npieces; ++p) {
            area[p] = -1;
            E.piece_planar[p] = 1;
        }
        double *plane = malloc((4 * E.npieces + 1) * sizeof *plane);
        if (plane == NULL) {
            free(num);
            free(area);
            goto nomem;
        }
        for (int pass = 0; pass < 2; ++pass)
            for (size_t t = 0; t < nt; ++t) {
                const size_t p = E.piece[t];
                double x[3][3];
                for (int k = 0; k < 3; ++k) {
                    vertex_at(bytes, verts, tris[3 * t + (size_t)k], x[k]);
                    for (int c = 0; c < 3; ++c)
                        x[k][c] = ldexp(x[k][c], -es);
                }
                if (pass == 0) { /* the largest triangle */
                    const double e1[3] = {x[1][0] - x[0][0], x[1][1] - x[0][1], x[1][2] - x[0][2]};
                    const double e2[3] = {x[2][0] - x[0][0], x[2][1] - x[0][1], x[2][2] - x[0][2]};
                    const double cr[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                                          e1[0] * e2[1] - e1[1] * e2[0]};
                    const double l = sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
                    if (l > area[p]) {
                        area[p] = l;
                        num[p] = (uint32_t)t;
                        for (int c = 0; c < 3; ++c)
                            plane[4 * p + (size_t)c] = l > 0 ? cr[c] / l : 0;
                        plane[4 * p + 3] = 0;
                        for (int c = 0; c < 3; ++c)
                            plane[4 * p + 3] += plane[4 * p + (size_t)c] * x[0][c];
                    }
                } else { /* every vertex near that plane */
                    if (!(area[p] > 0) || !has_normal[t]) {
                        E.piece_planar[p] = 0;
                        continue;
                    }
                    for (int k = 0; k < 3; ++k) {
                        const double h = plane[4 * p] * x[k][0] + plane[4 * p + 1] * x[k][1] +
                                         plane[4 * p + 2] * x[k][2] - plane[4 * p + 3];
                        if (!(fabs(h) <= TTD_PLANAR_TOL))
                            E.piece_planar[p] = 0;
                    }
                }
            }
        free(plane);
        free(num);
        free(area);
    }
    /* vertices: the class of each place, from the triangles and edges around it */
    for (size_t w = 0; w < E.nw; ++w) {
        const uint32_t r0 = E.ring_start[w], r1 = E.ring_start[w + 1];
        if (r0 == r1)
            continue;
        int all_flat = 1, convex = r1 - r0 <= TTD_CORNER_MAX, concave = convex; /* concave: a corner of the
                                                                                  * solid an inward mesh bounds */
        const double *n0 = normal + 3 * (size_t)E.ring[r0];
        for (uint32_t r = r0; r < r1; ++r) {
            const uint32_t u = E.ring[r];
            if (!has_normal[u]) {
                all_flat = convex = 0;
                break;
            }
            const double *nu = normal + 3 * (size_t)u;
            all_flat &= n0[0] * nu[0] + n0[1] * nu[1] + n0[2] * nu[2] >= cos_flat;
            for (int m = 0; m < 3; ++m) {
                if (E.weld[tris[3 * (size_t)u + (size_t)m]] != w)
                    continue;
                const int before = ttd_edge_class(&E, u, (m + 2) % 3), after = ttd_edge_class(&E, u, m);
                all_flat &= before == TTD_EDGE_FLAT && after == TTD_EDGE_FLAT;
                convex &= (before == TTD_EDGE_FLAT || before == TTD_EDGE_CONVEX) &&
                          (after == TTD_EDGE_FLAT || after == TTD_EDGE_CONVEX);
                concave &= (before == TTD_EDGE_FLAT || before == TTD_EDGE_CONCAVE) &&
                           (after == TTD_EDGE_FLAT || after == TTD_EDGE_CONCAVE);
            }
        }
        const int cls = all_flat ? TTD_VERTEX_FLAT : convex ? TTD_VERTEX_CORNER : TTD_VERTEX_OTHER;
        const int cls_solid = all_flat ? TTD_VERTEX_FLAT : concave ? TTD_VERTEX_CORNER : TTD_VERTEX_OTHER;
        for (uint32_t r = r0; r < r1; ++r) {
            const uint32_t u = E.ring[r];
            for (int m = 0; m < 3; ++m)
                if (E.weld[tris[3 * (size_t)u + (size_t)m]] == w) {
                    E.shape[u] &= (uint16_t)~(3u << (6 + 2 * m));
                    E.shape[u] |= (uint16_t)(cls << (6 + 2 * m));
                    if (E.inward) {
                        E.shape_solid[u] &= (uint16_t)~(3u << (6 + 2 * m));
                        E.shape_solid[u] |= (uint16_t)(cls_solid << (6 + 2 * m));
                    }
                }
        }
    }
    free(normal);
    free(has_normal);
    *out = E;
    return 1;
nomem:
    free(normal);
    free(has_normal);
    ttd_mesh_edges_free(&E);
    return 0;
}
