/* SPDX-License-Identifier: MIT */
/* The caps of an open mesh (points/points.h; docs/points.md, section 5.4): the surface that
 * closes it, so that its winding number is an exact ray count less the caps' winding number.
 *
 * The triangles' boundaries add up to a 1-cycle: the directed edges whose reverse does not cancel
 * them (vertices identified by their coordinates, so that a mesh written with its vertices
 * repeated per face has the boundary of its geometry, not of its indices). That cycle splits into
 * closed loops (every vertex has as many boundary edges in as out); a loop's polygon cut into
 * triangles (halved recursively) and taken backwards is a surface whose boundary is the loop
 * reversed. The mesh and these caps together are a chain without boundary, whose winding number
 * is an integer counted exactly by a ray (points/ray.c). So
 *
 *     w_mesh(x) = count_mesh(x) + count_caps(x) - w_caps(x),
 *
 * the two counts exact (the same ray for both), w_caps the hierarchical walk on the caps, a mesh
 * of as many triangles as the boundary has edges: small where the holes are few and far from
 * the point, and exact where the mesh has no boundary by coordinates at all. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "points/points.h"

static double cap_coord(const struct ttd_mesh *m, size_t v, int c)
{
    return m->bytes == 8 ? ((const double *)m->verts)[3 * v + (size_t)c] : (double)((const float *)m->verts)[3 * v + (size_t)c];
}

static uint64_t cap_mix(uint64_t h)
{
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdULL;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ULL;
    return h ^ (h >> 33);
}

/* canon[v]: the first vertex with v's coordinates (+0 and -0 alike). */
static int cap_canon(const struct ttd_mesh *m, uint32_t *canon)
{
    size_t cap = 16;
    while (cap < 2 * m->nv)
        cap *= 2;
    uint32_t *slot = malloc(cap * sizeof *slot);
    if (slot == NULL)
        return -1;
    memset(slot, 0xff, cap * sizeof *slot);
    for (size_t v = 0; v < m->nv; ++v) {
        double p[3];
        uint64_t h = 0;
        for (int c = 0; c < 3; ++c) {
            p[c] = cap_coord(m, v, c) + 0.0; /* -0 + 0 = +0 */
            uint64_t b;
            memcpy(&b, &p[c], sizeof b);
            h = cap_mix(h ^ b);
        }
        size_t i = (size_t)h & (cap - 1);
        for (;; i = (i + 1) & (cap - 1)) {
            const uint32_t u = slot[i];
            if (u == UINT32_MAX) {
                slot[i] = (uint32_t)v;
                canon[v] = (uint32_t)v;
                break;
            }
            if (cap_coord(m, u, 0) == p[0] && cap_coord(m, u, 1) == p[1] && cap_coord(m, u, 2) == p[2]) {
                canon[v] = u;
                break;
            }
        }
    }
    free(slot);
    return 0;
}

typedef struct cap_edge {
    uint64_t key; /* lower << 32 | higher, UINT64_MAX empty */
    int64_t net;  /* directed (lower, higher) minus (higher, lower) */
} cap_edge;

/* The caps' triangles and vertices (the boundary's); returns the number of cap triangles, or -1 when out of memory. *vout: the vertices (3 doubles each), *nvout. */
static long cap_build(const struct ttd_mesh *m, double **vout, size_t *nvout, uint32_t **tout)
{
    long result = -1;
    uint32_t *canon = malloc(m->nv * sizeof *canon);
    size_t cap = 16;
    while (cap < 6 * m->nt)
        cap *= 2;
    cap_edge *e = malloc(cap * sizeof *e);
    uint32_t *from = NULL, *to = NULL, *start = NULL, *next = NULL, *loop = NULL, *tris = NULL, *map = NULL;
    unsigned char *used = NULL;
    double *verts = NULL;
    if (canon == NULL || e == NULL || cap_canon(m, canon) != 0)
        goto out;
    for (size_t i = 0; i < cap; ++i)
        e[i].key = UINT64_MAX, e[i].net = 0;
    for (size_t t = 0; t < m->nt; ++t)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = canon[m->tris[3 * t + (size_t)k]], b = canon[m->tris[3 * t + (size_t)(k + 1) % 3]];
            if (a == b)
                continue;
            const uint64_t key = a < b ? (uint64_t)a << 32 | b : (uint64_t)b << 32 | a;
            size_t i = (size_t)cap_mix(key) & (cap - 1);
            while (e[i].key != UINT64_MAX && e[i].key != key)
                i = (i + 1) & (cap - 1);
            e[i].key = key;
            e[i].net += a < b ? 1 : -1;
        }
    /* the boundary's directed edges, |net| copies each */
    size_t nb = 0;
    for (size_t i = 0; i < cap; ++i)
        if (e[i].key != UINT64_MAX)
            nb += (size_t)(e[i].net < 0 ? -e[i].net : e[i].net);
    *vout = NULL;
    *nvout = 0;
    *tout = NULL;
    if (nb == 0) {
        result = 0;
        goto out;
    }
    from = malloc(nb * sizeof *from);
    to = malloc(nb * sizeof *to);
    start = calloc(m->nv + 1, sizeof *start);
    next = malloc(m->nv * sizeof *next);
    loop = malloc(nb * sizeof *loop);
    used = calloc(nb, 1);
    tris = malloc(3 * nb * sizeof *tris);
    map = malloc(m->nv * sizeof *map);
    verts = malloc(3 * nb * sizeof *verts); /* at most nb loop vertices */
    if (!from || !to || !start || !next || !loop || !used || !tris || !map || !verts)
        goto out;
    size_t j = 0;
    for (size_t i = 0; i < cap; ++i) {
        if (e[i].key == UINT64_MAX)
            continue;
        const uint32_t lo = (uint32_t)(e[i].key >> 32), hi = (uint32_t)e[i].key;
        for (int64_t c = 0; c < (e[i].net < 0 ? -e[i].net : e[i].net); ++c, ++j) {
            from[j] = e[i].net > 0 ? lo : hi;
            to[j] = e[i].net > 0 ? hi : lo;
        }
    }
    /* edges sorted by their source (counting sort): out-edges of v at order[start[v] ..] */
    uint32_t *order = loop; /* reused below after a copy */
    for (size_t k = 0; k < nb; ++k)
        ++start[from[k] + 1];
    for (size_t v = 0; v < m->nv; ++v)
        start[v + 1] += start[v];
    memcpy(next, start, m->nv * sizeof *next);
    for (size_t k = 0; k < nb; ++k)
        order[next[from[k]]++] = (uint32_t)k;
    uint32_t *sorted_to = malloc(nb * sizeof *sorted_to);
    if (sorted_to == NULL)
        goto out;
    for (size_t k = 0; k < nb; ++k)
        sorted_to[k] = to[order[k]];
    memcpy(next, start, m->nv * sizeof *next); /* next[v]: v's first unused out-edge */
    for (size_t v = 0; v < m->nv; ++v)
        map[v] = UINT32_MAX;
    size_t nv = 0, nt = 0;
    for (size_t v0 = 0; v0 < m->nv; ++v0) {
        while (next[v0] < start[v0 + 1]) {
            /* a closed walk from v0: every vertex has as many boundary edges in as out, so it can
             * only end back at v0 */
            size_t len = 0;
            uint32_t v = (uint32_t)v0;
            do {
                const uint32_t w = sorted_to[next[v]++];
                loop[len++] = v; /* the edge v -> w */
                v = w;
            } while (v != v0 && next[v] < start[v + 1]);
            if (v != v0) { /* cannot happen for a cycle; refused rather than trusted */
                free(sorted_to);
                goto out;
            }
            for (size_t k = 0; k < len; ++k) {
                const uint32_t u = loop[k];
                if (map[u] == UINT32_MAX) {
                    map[u] = (uint32_t)nv++;
                    for (int a = 0; a < 3; ++a)
                        verts[3 * map[u] + (size_t)a] = cap_coord(m, u, a);
                }
            }
            /* the polygon loop[0 .. len-1] cut in halves recursively: the chain i..j and its chord
             * (j, i) get the triangle (i, mid, j) and the two halves (so small triangles line the
             * rim and large ones fill the middle, which the hierarchy groups well), each taken
             * backwards (i, j, mid): the triangles in index order have the loop as their boundary */
            size_t st[2 * 64], sp = 0;
            st[sp++] = 0;
            st[sp++] = len - 1;
            while (sp > 0) {
                const size_t hi = st[--sp], lo = st[--sp];
                if (hi - lo < 2)
                    continue;
                const size_t mid = lo + (hi - lo) / 2;
                tris[3 * nt] = map[loop[lo]];
                tris[3 * nt + 1] = map[loop[hi]];
                tris[3 * nt + 2] = map[loop[mid]];
                ++nt;
                st[sp++] = lo;
                st[sp++] = mid;
                st[sp++] = mid;
                st[sp++] = hi;
            }
        }
    }
    free(sorted_to);
    *vout = verts;
    *nvout = nv;
    *tout = tris;
    verts = NULL;
    tris = NULL;
    result = (long)nt;
out:
    free(canon), free(e), free(from), free(to), free(start), free(next), free(loop), free(used), free(tris), free(map);
    free(verts);
    return result;
}

static void caps_free(void *p)
{
    ttd_points_caps *c = p;
    if (c == NULL)
        return;
    if (c->mesh != NULL)
        ttd_mesh_free(c->mesh);
    free(c);
}

void ttd_points_caps_free(ttd_points_caps *caps)
{
    caps_free(caps);
}

const ttd_points_caps *ttd_points_caps_get(const struct ttd_mesh *mesh, const ttd_points_data *pd)
{
    ttd_points_data *p = (ttd_points_data *)(uintptr_t)pd; /* a cache of what the mesh determines */
    ttd_points_caps *c = __atomic_load_n(&p->caps, __ATOMIC_ACQUIRE);
    if (c != NULL)
        return c;
    c = calloc(1, sizeof *c);
    if (c == NULL)
        return NULL;
    double *v = NULL;
    size_t nv = 0;
    uint32_t *t = NULL;
    const long nt = cap_build(mesh, &v, &nv, &t);
    if (nt < 0) {
        free(c);
        return NULL;
    }
    c->ntri = (size_t)nt;
    if (nt > 0) {
        ttd_engine_config cfg;
        memset(&cfg, 0, sizeof cfg);
        cfg.threads = 1;
        int ok;
        if (mesh->bytes == 8) {
            ok = ttd_mesh_build(&cfg, 8, v, nv, t, (size_t)nt, &c->mesh) == TTD_OK;
        } else {
            float *vf = malloc(3 * nv * sizeof *vf);
            for (size_t i = 0; vf != NULL && i < 3 * nv; ++i)
                vf[i] = (float)v[i]; /* exact: the mesh's own floats */
            ok = vf != NULL && ttd_mesh_build(&cfg, 4, vf, nv, t, (size_t)nt, &c->mesh) == TTD_OK;
            free(vf);
        }
        free(v);
        free(t);
        if (!ok || (c->pd = ttd_points_data_get(c->mesh, 1)) == NULL || ttd_points_moments(c->mesh, c->pd) == NULL) {
            caps_free(c);
            return NULL;
        }
    }
    ttd_points_caps *expected = NULL;
    if (!__atomic_compare_exchange_n(&p->caps, &expected, c, 0, __ATOMIC_ACQ_REL, __ATOMIC_ACQUIRE)) {
        caps_free(c); /* another thread made them first: the same caps */
        return expected;
    }
    return c;
}
