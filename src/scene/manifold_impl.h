/* SPDX-License-Identifier: MIT */
/* A body pair's contacts reduced to a manifold (docs/scenes.md, section 5), precision-generic:
 * included by scene/query_impl.h. A function of the pair's contacts and the scene alone, so that
 * it may run wherever the pair's contacts are found.
 *
 * 1. Depth order: smaller distance first, ties by triangles.
 * 2. No point twice: in that order, a contact is dropped when its point lies within the merge
 *    tolerance (MERGE_FRACTION of the smaller body's radius) of a point kept before it; a grid
 *    of cells that wide finds the points near it. So no two points kept are that close, and
 *    each kept one is the deepest of those it stands for.
 * 3. The seed: the deepest, and among contacts within FEATURE_TOL of the larger radius of its
 *    depth (faces resting on faces: many at one depth), the one farthest from their centroid.
 * 4. Spread (when more than K remain), first over the contacts of the deepest level (within
 *    LEVEL_FRACTION of the rest of the margin, M - d, of the deepest distance d: where a body
 *    rests, rather than a speculative contact farther inside the margin): the seed; the point
 *    farthest from it; the point making the largest triangle with those two; then, one at a
 *    time, the point that adds the most area to the polygon of those kept (on the plane of the
 *    first three), as PhysX's reduction keeps a box's four corners on a face; where no point
 *    adds area (points on a line, or inside), the point farthest from every point kept. Ties to
 *    the earlier in depth order. When the level holds fewer than K, all of them, then the
 *    farthest from every point kept among the rest.
 * Distances between points are formed on coordinates relative to the deepest point, scaled by a
 * power of two to the larger body's size, so that no square underflows or overflows at any scale
 * of the coordinate range. */

#define MERGE_FRACTION 1e-3
/* The deepest level of step 4: a quarter of the margin left below the deepest contact (a box
 * resting 0.01 inside a margin of 0.04 spreads its points over contacts within 0.0175, not over
 * the torus-side contacts at 0.03 that a simulator found rocking the body). */
#define LEVEL_FRACTION 0.25
#define HULL_MAX 64 /* the polygon of step 4 follows up to this many points; farthest points beyond */

/* Scratch kept across body pairs. */
typedef struct manifold_work {
    double *z;           /* 3 n: points, relative and scaled */
    size_t *kept;        /* kept contacts, in depth order */
    size_t *next;        /* grid: the next kept point in the same cell */
    size_t *cell_head;   /* grid: open addressing, one kept point per cell (or SIZE_MAX) */
    uint64_t *cell_key;
    size_t *sel;         /* the points chosen */
    unsigned char *taken;
    size_t cap, cell_cap;
} manifold_work;

static void manifold_work_free(manifold_work *w)
{
    free(w->z);
    free(w->kept);
    free(w->next);
    free(w->cell_head);
    free(w->cell_key);
    free(w->sel);
    free(w->taken);
    memset(w, 0, sizeof *w);
}

static int manifold_work_reserve(manifold_work *w, size_t n)
{
    if (n > w->cap) {
        size_t cap = w->cap ? w->cap : 64;
        while (cap < n)
            cap *= 2;
        double *z = realloc(w->z, 3 * cap * sizeof *z);
        if (z == NULL)
            return 0;
        w->z = z;
        size_t *k = realloc(w->kept, cap * sizeof *k);
        if (k == NULL)
            return 0;
        w->kept = k;
        size_t *nx = realloc(w->next, cap * sizeof *nx);
        if (nx == NULL)
            return 0;
        w->next = nx;
        size_t *sel = realloc(w->sel, cap * sizeof *sel);
        if (sel == NULL)
            return 0;
        w->sel = sel;
        unsigned char *tk = realloc(w->taken, cap);
        if (tk == NULL)
            return 0;
        w->taken = tk;
        w->cap = cap;
    }
    size_t cells = 64;
    while (cells < 2 * n)
        cells *= 2;
    if (cells > w->cell_cap) {
        size_t *h = realloc(w->cell_head, cells * sizeof *h);
        if (h == NULL)
            return 0;
        w->cell_head = h;
        uint64_t *key = realloc(w->cell_key, cells * sizeof *key);
        if (key == NULL)
            return 0;
        w->cell_key = key;
        w->cell_cap = cells;
    }
    return 1;
}

/* Orders contacts deepest first: smaller distance, then triangles. */
static int depth_cmp(const void *x, const void *y)
{
    const ttd_scene_contact *a = x, *b = y;
    if (a->distance != b->distance)
        return a->distance < b->distance ? -1 : 1;
    return scene_contact_cmp(x, y);
}

static double dist2(const double *a, const double *b)
{
    const double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
}

/* The cell of scaled point z, each coordinate in cells of width `cell` (saturated far out:
 * the cells there only gather more points to compare). */
static void cell_of(const double z[3], double cell, int64_t c[3])
{
    for (int r = 0; r < 3; ++r) {
        const double x = floor(z[r] / cell);
        c[r] = x > 0x1p40 ? (int64_t)0x1p40 : x < -0x1p40 ? -(int64_t)0x1p40 : (int64_t)x;
    }
}

static uint64_t cell_key(const int64_t c[3])
{
    uint64_t h = (uint64_t)c[0] * 0x9e3779b97f4a7c15ULL;
    h ^= (uint64_t)c[1] * 0xc2b2ae3d27d4eb4fULL + (h << 6) + (h >> 2);
    h ^= (uint64_t)c[2] * 0x165667b19e3779f9ULL + (h << 6) + (h >> 2);
    return h | 1; /* never 0: 0 marks an empty slot */
}

/* The slot of cell key k in the open-addressing table (its own, or the empty one where it goes). */
static size_t cell_slot(const manifold_work *w, size_t cells, uint64_t k)
{
    size_t at = (size_t)(k ^ (k >> 29)) & (cells - 1);
    while (w->cell_key[at] != 0 && w->cell_key[at] != k)
        at = (at + 1) & (cells - 1);
    return at;
}

/* Step 2: the contacts to keep (indices into c, depth order) into w->kept; returns how many.
 * z holds the scaled points, tol2 the squared scaled tolerance. */
static size_t merge_points(manifold_work *w, size_t n, double tol, int use_grid)
{
    const double tol2 = tol * tol;
    size_t nk = 0;
    if (!use_grid) {
        for (size_t k = 0; k < n; ++k) {
            int near = 0;
            for (size_t a = 0; a < nk && !near; ++a)
                near = dist2(w->z + 3 * k, w->z + 3 * w->kept[a]) <= tol2;
            if (!near)
                w->kept[nk++] = k;
        }
        return nk;
    }
    size_t cells = 64;
    while (cells < 2 * n)
        cells *= 2;
    memset(w->cell_key, 0, cells * sizeof *w->cell_key);
    /* cells as wide as the tolerance (a tolerance of 0 merges equal points only: any width) */
    const double width = tol > 0 ? tol : 1;
    for (size_t k = 0; k < n; ++k) {
        int64_t c[3];
        cell_of(w->z + 3 * k, width, c);
        int near = 0;
        for (int dx = -1; dx <= 1 && !near; ++dx)
            for (int dy = -1; dy <= 1 && !near; ++dy)
                for (int dz = -1; dz <= 1 && !near; ++dz) {
                    const int64_t cc[3] = {c[0] + dx, c[1] + dy, c[2] + dz};
                    const uint64_t key = cell_key(cc);
                    const size_t at = cell_slot(w, cells, key);
                    if (w->cell_key[at] == 0)
                        continue;
                    for (size_t a = w->cell_head[at]; a != SIZE_MAX && !near; a = w->next[a])
                        near = dist2(w->z + 3 * k, w->z + 3 * a) <= tol2;
                }
        if (near)
            continue;
        w->kept[nk++] = k;
        const uint64_t key = cell_key(c);
        const size_t at = cell_slot(w, cells, key);
        if (w->cell_key[at] == 0) {
            w->cell_key[at] = key;
            w->cell_head[at] = SIZE_MAX;
        }
        w->next[k] = w->cell_head[at];
        w->cell_head[at] = k;
    }
    return nk;
}

/* Twice the area that point x adds to the convex polygon hull[0..nh) of points y (counter-
 * clockwise about m): the sum of the triangles it makes with the edges it lies outside of. */
static double area_gain(const double *y, const size_t *hull, size_t nh, const double m[3], const double *x,
                        unsigned char *sees)
{
    double gain = 0;
    for (size_t e = 0; e < nh; ++e) {
        const double *a = y + 3 * hull[e], *b = y + 3 * hull[(e + 1) % nh];
        const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, ax[3] = {x[0] - a[0], x[1] - a[1], x[2] - a[2]};
        double cr[3];
        cross3d(ab, ax, cr);
        const double o = dot3d(cr, m);
        if (sees != NULL)
            sees[e] = o < 0;
        gain += o < 0 ? -o : 0;
    }
    return gain;
}

/* Inserts point x (outside) into the convex polygon hull (counter-clockwise about m): the
 * vertices strictly inside the run of edges it sees go, x takes their place. */
static size_t hull_insert(const double *y, size_t *hull, size_t nh, const double m[3], size_t x)
{
    unsigned char sees[HULL_MAX];
    area_gain(y, hull, nh, m, y + 3 * x, sees);
    size_t s = 0; /* the first edge of the run: seen, its predecessor not */
    while (s < nh && !(sees[s] && !sees[(s + nh - 1) % nh]))
        ++s;
    if (s == nh)
        return nh;
    size_t t = s; /* the vertex ending the run */
    while (sees[t])
        t = (t + 1) % nh;
    size_t out[HULL_MAX], no = 0;
    out[no++] = hull[s];
    out[no++] = x;
    for (size_t v = t; v != s; v = (v + 1) % nh)
        out[no++] = hull[v];
    memcpy(hull, out, no * sizeof *hull);
    return no;
}

/* The point of y[0..nk) not taken that is farthest from every point of sel[0..ns) (the first
 * of equals), or SIZE_MAX when every point is taken. */
static size_t farthest_point(const double *y, size_t nk, const size_t *sel, size_t ns, const unsigned char *taken)
{
    double best = -1;
    size_t pick = SIZE_MAX;
    for (size_t a = 0; a < nk; ++a) {
        if (taken[a])
            continue;
        double near = HUGE_VAL;
        for (size_t b = 0; b < ns; ++b)
            near = fmin(near, dist2(y + 3 * a, y + 3 * sel[b]));
        if (near > best) {
            best = near;
            pick = a;
        }
    }
    return pick;
}

/* Step 4: up to max of the nk kept points y (3 nk, depth order), the seed first, into sel
 * (indices into y); taken[nk] zeroed. Returns how many. */
static size_t spread_points(const double *y, size_t nk, size_t seed, size_t max, size_t *sel, unsigned char *taken)
{
    size_t ns = 0, hull[HULL_MAX], nh = 0;
    double m[3] = {0, 0, 0};
    sel[ns++] = seed;
    taken[seed] = 1;
    while (ns < max) {
        double best = 0;
        size_t pick = SIZE_MAX;
        if (ns <= 2 || nh >= 3) {
            for (size_t a = 0; a < nk; ++a) {
                if (taken[a])
                    continue;
                const double *x = y + 3 * a, *a0 = y + 3 * sel[0];
                double v;
                if (ns == 1) {
                    v = dist2(x, a0);
                } else if (ns == 2) {
                    const double *a1 = y + 3 * sel[1];
                    const double e1[3] = {a1[0] - a0[0], a1[1] - a0[1], a1[2] - a0[2]};
                    const double e2[3] = {x[0] - a0[0], x[1] - a0[1], x[2] - a0[2]};
                    double cr[3];
                    cross3d(e1, e2, cr);
                    v = dot3d(cr, cr);
                } else {
                    v = area_gain(y, hull, nh, m, x, NULL);
                }
                if (v > best) {
                    best = v;
                    pick = a;
                }
            }
        }
        if (pick == SIZE_MAX) {
            /* nothing adds area (points on a line, or inside what is kept): the point farthest
             * from every point kept */
            pick = farthest_point(y, nk, sel, ns, taken);
            if (pick == SIZE_MAX)
                break;
            nh = 0; /* from here on, farthest points only */
        } else if (ns == 2) {
            /* the plane of the first three, their triangle counter-clockwise about it */
            const double *a0 = y + 3 * sel[0], *a1 = y + 3 * sel[1], *a2 = y + 3 * pick;
            const double e1[3] = {a1[0] - a0[0], a1[1] - a0[1], a1[2] - a0[2]};
            const double e2[3] = {a2[0] - a0[0], a2[1] - a0[1], a2[2] - a0[2]};
            double cr[3];
            cross3d(e1, e2, cr);
            if (unit3(cr, m)) {
                hull[0] = sel[0];
                hull[1] = sel[1];
                hull[2] = pick;
                nh = 3;
            }
        } else if (nh >= 3 && nh + 1 < HULL_MAX) {
            nh = hull_insert(y, hull, nh, m, pick);
        } else {
            nh = 0;
        }
        sel[ns++] = pick;
        taken[pick] = 1;
    }
    return ns;
}

/* Body pair's manifold: its n >= 1 contacts c (reordered here) reduced to at most max points (0:
 * all) into out[0..), in the order chosen; returns how many. w: scratch for n contacts. */
static size_t reduce_pair(const struct ttd_scene *s, ttd_scene_contact *c, size_t n, real margin, size_t max,
                          manifold_work *w, ttd_scene_point *out)
{
    qsort(c, n, sizeof *c, depth_cmp);
    const double ri = s->body[c[0].i].mesh->radius, rj = s->body[c[0].j].mesh->radius;
    const double big = fmax(ri, rj), small = fmin(ri, rj);
    int ex = 0;
    if (big > 0 && isfinite(big))
        frexp(big, &ex);
    /* the points as a point record holds them, relative to the deepest, at the larger body's scale */
    double *z = w->z, origin[3];
    for (size_t k = 0; k < n; ++k)
        for (int r = 0; r < 3; ++r) {
            const double x = (double)(real)(0.5 * (double)c[k].p[r] + 0.5 * (double)c[k].q[r]);
            if (k == 0)
                origin[r] = x;
            z[3 * k + (size_t)r] = ldexp(x - origin[r], -ex);
        }
    const size_t nk = merge_points(w, n, ldexp(MERGE_FRACTION * small, -ex), n > 32);
    for (size_t a = 0; a < nk; ++a) /* compact: kept[a] >= a, increasing */
        memmove(z + 3 * a, z + 3 * w->kept[a], 3 * sizeof *z);
    /* the seed: among the kept within FEATURE_TOL of the larger radius of the smallest distance,
     * the farthest from their centroid */
    const double d0 = (double)c[w->kept[0]].distance, window = FEATURE_TOL * big;
    double g[3] = {0, 0, 0};
    size_t ntie = 0;
    for (size_t a = 0; a < nk && (double)c[w->kept[a]].distance - d0 <= window; ++a, ++ntie)
        for (int r = 0; r < 3; ++r)
            g[r] += z[3 * a + (size_t)r];
    for (int r = 0; r < 3; ++r)
        g[r] /= (double)ntie;
    size_t seed = 0;
    double far = -1;
    for (size_t a = 0; a < ntie; ++a) {
        const double d2 = dist2(z + 3 * a, g);
        if (d2 > far) {
            far = d2;
            seed = a;
        }
    }
    /* the points: all of them (the seed, then depth order), or the spread */
    size_t ns;
    if (max == 0 || nk <= max) {
        w->sel[0] = seed;
        ns = 1;
        for (size_t a = 0; a < nk; ++a)
            if (a != seed)
                w->sel[ns++] = a;
    } else {
        /* the deepest level: the kept within LEVEL_FRACTION of the margin left below d0 (and
         * every contact of the seed's window) */
        const double level = LEVEL_FRACTION * ((double)margin - d0);
        size_t nl = ntie;
        while (nl < nk && (double)c[w->kept[nl]].distance - d0 <= level)
            ++nl;
        memset(w->taken, 0, nk);
        if (nl >= max) {
            ns = spread_points(z, nl, seed, max, w->sel, w->taken);
        } else {
            w->sel[0] = seed;
            w->taken[seed] = 1;
            ns = 1;
            for (size_t a = 0; a < nl; ++a)
                if (a != seed) {
                    w->sel[ns++] = a;
                    w->taken[a] = 1;
                }
            while (ns < max) {
                const size_t pick = farthest_point(z, nk, w->sel, ns, w->taken);
                w->sel[ns++] = pick;
                w->taken[pick] = 1;
            }
        }
    }
    for (size_t k = 0; k < ns; ++k) {
        const ttd_scene_contact *x = &c[w->kept[w->sel[k]]];
        ttd_scene_point *pt = out + k;
        double normal[3];
        contact_normal(s, x, normal);
        pt->i = x->i;
        pt->j = x->j;
        pt->tri_i = x->tri_i;
        pt->tri_j = x->tri_j;
        for (int r = 0; r < 3; ++r) {
            pt->point[r] = (real)(0.5 * (double)x->p[r] + 0.5 * (double)x->q[r]);
            pt->normal[r] = (real)normal[r];
        }
        pt->distance = x->distance;
        pt->depth = margin - x->distance;
    }
    return ns;
}
