/* SPDX-License-Identifier: MIT */
/* A solid pair's contact regions and their one direction each (docs/scenes.md, section 5b,
 * "contact regions"), precision-generic: included by scene/manifold_impl.h.
 *
 * For a solid pair the separating-axis search did not take (no point of it at the penetration
 * depth: a torus, a bowl, any concave edge), the points below 0 are points x of one body's
 * surface inside the other at depth r = |s|, the exact distance from x to the other's surface, so
 * the open ball of radius r about x lies inside the other body. Two such points belong to one
 * **region** when those balls meet or touch, |x - x'| <= r + r' (in double, on the points'
 * coordinates), and regions are the classes that relation joins (its transitive closure). Each
 * region takes the direction of its deepest point (the smallest distance; ties to the first point
 * made): the direction out of the other body along which that point leaves it at exactly its
 * depth (section 5a: from the point to its closest point on the other's surface, the feature's
 * cone there). Every point of the region carries that direction as its normal and keeps its own
 * distance, where the region's deepest point lies deeper than the margin (s < -M: an overlap, not a
 * resting pair sunk by a solver's rounding, whose points keep their own normals: a ball resting in
 * a ring's hole is held by normals all round it, which one direction would push it off). Points at
 * distance 0 or above keep their own normals. */

typedef struct region_item {
    double x0;   /* the point's first coordinate */
    uint32_t k;  /* its number among the pair's points below 0 */
} region_item;

/* A total order even where a coordinate is NaN (NaN last): qsort needs a consistent comparator. */
static int region_item_cmp(const void *a, const void *b)
{
    const region_item *x = a, *y = b;
    const int nx = x->x0 != x->x0, ny = y->x0 != y->x0;
    if (nx != ny)
        return nx - ny;
    if (!nx && x->x0 != y->x0)
        return x->x0 < y->x0 ? -1 : 1;
    return x->k < y->k ? -1 : x->k > y->k;
}

static uint32_t region_find(uint32_t *par, uint32_t k)
{
    while (par[k] != k) {
        par[k] = par[par[k]];
        k = par[k];
    }
    return k;
}

/* The point of record x that lies inside the other body, in double. */
static void region_point(const manifold_rec *x, double y[3])
{
    const real *v = x->inside == 1 ? x->c.q : x->c.p;
    for (int r = 0; r < 3; ++r)
        y[r] = (double)v[r];
}

/* The 9 keys of a node on triangles ti (body i) and tj (body j): each pair of places, one a vertex
 * of ti and one of tj. Two nodes share a key exactly when their triangles share a place on both
 * bodies. */
typedef struct region_key {
    uint64_t key;
    uint32_t node;
} region_key;

static int region_key_cmp(const void *a, const void *b)
{
    const region_key *x = a, *y = b;
    if (x->key != y->key)
        return x->key < y->key ? -1 : 1;
    return x->node < y->node ? -1 : x->node > y->node;
}

static void region_union(uint32_t *par, uint32_t a, uint32_t b)
{
    a = region_find(par, a);
    b = region_find(par, b);
    /* the smaller number is the root, so the classes do not depend on the order met */
    if (a < b)
        par[b] = a;
    else if (b < a)
        par[a] = b;
}

/* The regions of w->all[before..] (the pair's points of solids, 5b) with the pair's n0 contacts
 * c0: each point below 0 gets the number of its region (rec.region) and w->reg_n that region's
 * direction. Nodes: the points below 0 and the contacts at distance 0 (triangles that cross).
 * Joined: two points below 0 whose balls meet; two nodes whose triangles share a place on body i
 * and a place on body j. A convex pair's points (one at the penetration depth, inside 2) are left
 * as they are. 0 out of memory. */
static int solid_regions(const struct ttd_scene *s, uint32_t bi, uint32_t bj, const ttd_scene_contact *c0, size_t n0,
                         real margin, size_t before, manifold_work *w)
{
    size_t n = 0, nc = 0;
    for (size_t k = before; k < w->all_n; ++k) {
        if (w->all[k].inside == 2)
            return 1;
        n += w->all[k].inside >= 0 && w->all[k].c.distance < 0;
    }
    if (n == 0)
        return 1;
    for (size_t k = 0; k < n0; ++k)
        nc += c0[k].distance == 0;
    const size_t nn = n + nc;
    if (nn > (UINT32_MAX - 1) / 9 || nn > SIZE_MAX / (9 * sizeof(region_key)))
        return 1; /* beyond the numbers a region holds: the points keep their own normals */
    if (nn > w->reg_cap) {
        region_item *a = realloc(w->reg, nn * sizeof *a);
        if (a != NULL)
            w->reg = a;
        uint32_t *b = realloc(w->reg_par, nn * sizeof *b);
        if (b != NULL)
            w->reg_par = b;
        double *c = realloc(w->reg_n, 3 * nn * sizeof *c);
        if (c != NULL)
            w->reg_n = c;
        if (a == NULL || b == NULL || c == NULL)
            return 0;
        w->reg_cap = nn;
    }
    manifold_rec **at = malloc(n * sizeof *at);
    uint32_t *deep = malloc(nn * sizeof *deep);
    region_key *keys = malloc(9 * nn * sizeof *keys);
    if (at == NULL || deep == NULL || keys == NULL) {
        free(at);
        free(deep);
        free(keys);
        return 0;
    }
    /* the points below 0 in their order, numbered 0..n-1 (rec.region holds the number for now);
     * the crossing contacts n..nn-1 */
    double rmax = 0;
    uint32_t m = 0;
    for (size_t k = before; k < w->all_n; ++k) {
        manifold_rec *x = &w->all[k];
        if (!(x->inside >= 0 && x->c.distance < 0))
            continue;
        double y[3];
        region_point(x, y);
        w->reg[m].x0 = y[0];
        w->reg[m].k = m;
        at[m] = x;
        x->region = m++;
        rmax = fmax(rmax, -(double)x->c.distance);
    }
    for (uint32_t k = 0; k < nn; ++k)
        w->reg_par[k] = k;
    /* shared places on both bodies */
    const struct ttd_mesh *mi = s->body[bi].mesh, *mj = s->body[bj].mesh;
    const uint32_t *wi = ttd_mesh_edges_made(mi)->weld, *wj = ttd_mesh_edges_made(mj)->weld;
    size_t nk = 0;
    for (size_t k = 0, q = n; k < nn; ++k) {
        const ttd_scene_contact *c;
        if (k < n)
            c = &at[k]->c;
        else {
            while (c0[q - n].distance != 0)
                ++q;
            c = &c0[q++ - n];
        }
        for (int u = 0; u < 3; ++u)
            for (int v = 0; v < 3; ++v) {
                keys[nk].key = (uint64_t)wi[mi->tris[3 * (size_t)c->tri_i + (size_t)u]] << 32 |
                               wj[mj->tris[3 * (size_t)c->tri_j + (size_t)v]];
                keys[nk++].node = (uint32_t)k;
            }
    }
    qsort(keys, nk, sizeof *keys, region_key_cmp);
    for (size_t k = 1; k < nk; ++k)
        if (keys[k].key == keys[k - 1].key)
            region_union(w->reg_par, keys[k - 1].node, keys[k].node);
    /* balls that meet: by the first coordinate, a point's ball can meet only those within r + rmax */
    qsort(w->reg, n, sizeof *w->reg, region_item_cmp);
    for (size_t a = 0; a < n; ++a) {
        const manifold_rec *xa = at[w->reg[a].k];
        const double ra = -(double)xa->c.distance;
        double ya[3];
        region_point(xa, ya);
        for (size_t b = a + 1; b < n && w->reg[b].x0 - w->reg[a].x0 <= ra + rmax; ++b) {
            const manifold_rec *xb = at[w->reg[b].k];
            const double rb = -(double)xb->c.distance;
            if (w->reg[b].x0 - w->reg[a].x0 > ra + rb)
                continue;
            if (region_find(w->reg_par, w->reg[a].k) == region_find(w->reg_par, w->reg[b].k))
                continue;
            double yb[3], d2 = 0;
            region_point(xb, yb);
            for (int r = 0; r < 3; ++r)
                d2 += (ya[r] - yb[r]) * (ya[r] - yb[r]);
            if (d2 <= (ra + rb) * (ra + rb))
                region_union(w->reg_par, w->reg[a].k, w->reg[b].k);
        }
    }
    /* each region's deepest point, then its direction at the root's number; every point's region
     * is its root */
    for (uint32_t k = 0; k < nn; ++k)
        deep[k] = UINT32_MAX;
    for (uint32_t k = 0; k < n; ++k) {
        const uint32_t r = region_find(w->reg_par, k);
        if (deep[r] == UINT32_MAX || at[k]->c.distance < at[deep[r]]->c.distance)
            deep[r] = k;
    }
    for (uint32_t k = 0; k < nn; ++k)
        if (deep[k] != UINT32_MAX && (double)at[deep[k]]->c.distance < -(double)margin)
            contact_normal(s, &at[deep[k]]->c, at[deep[k]]->inside, w->reg_n + 3 * (size_t)k);
    /* a region whose deepest point lies within the margin (a resting pair sunk by a solver's
     * rounding) keeps its points' own normals */
    for (uint32_t k = 0; k < n; ++k) {
        const uint32_t r = region_find(w->reg_par, k);
        at[k]->region = (double)at[deep[r]]->c.distance < -(double)margin ? r : UINT32_MAX;
    }
    free(keys);
    free(deep);
    free(at);
    return 1;
}
