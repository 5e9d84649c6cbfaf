/* SPDX-License-Identifier: MIT */
/* Steps 1 to 4 of the reduction: depth order, no point twice (a grid of cells),
 * the seed, and the spread over the deepest level (farthest, largest triangle, largest area). Part of a body pair's manifold
 * (scene/manifold_impl.h, which includes it once per precision; docs/scenes.md, section 5). */

/* ---- step 1: depth order ---------------------------------------------------------------------- */

/* Orders contacts deepest first: smaller distance, then triangles, then the midpoint of their
 * points (a triangle pair's corners, step 0; the midpoint is the same when the bodies swap). */
static int depth_cmp(const void *x, const void *y)
{
    const ttd_scene_contact *a = &((const manifold_rec *)x)->c, *b = &((const manifold_rec *)y)->c;
    if (a->distance != b->distance)
        return a->distance < b->distance ? -1 : 1;
    const int t = scene_contact_cmp(a, b);
    if (t != 0)
        return t;
    for (int r = 0; r < 3; ++r) {
        const double ma = 0.5 * (double)a->p[r] + 0.5 * (double)a->q[r], mb = 0.5 * (double)b->p[r] + 0.5 * (double)b->q[r];
        if (ma != mb)
            return ma < mb ? -1 : 1;
    }
    return 0;
}

/* Step 1's order as keys, sorted in place of the points: the distance's bits made to order as the
 * numbers do, the triangles, the point's index (the midpoint only where those tie). */
typedef struct depth_key {
    uint64_t d, t;
    size_t at;
} depth_key;

static uint64_t order_bits(double x)
{
    x += 0.0; /* -0 is +0 */
    uint64_t u;
    memcpy(&u, &x, sizeof u);
    return u >> 63 ? ~u : u | 0x8000000000000000ULL;
}

static int key_before(const depth_key *a, const depth_key *b, const manifold_rec *rc)
{
    if (a->d != b->d)
        return a->d < b->d;
    if (a->t != b->t)
        return a->t < b->t;
    return depth_cmp(&rc[a->at], &rc[b->at]) < 0;
}

/* Step 1's sort by radix, where the points are many (a resting face's level holds hundreds a
 * pair, whose merge sort's jumps on the comparison mispredict): the keys (d, t) a byte at a time
 * from the lowest, stably, the bytes on which all keys agree (found first) skipped; then each run of keys with
 * equal (d, t) (a triangle pair's corners at one distance: a few) put in depth_cmp's order by a
 * stable insertion. A stable sort by key_before's order, as the merge sort is, so the same
 * order to the point. 0 where a run is longer than RADIX_RUN (the insertion would grow with its
 * square): the merge sort then runs on the keys as left, which hold equal points in their first
 * order, so its stable result is the same. *a holds the keys, *b as many
 * for scratch; the sorted keys end in *a (the two may trade places). */
#define RADIX_MIN 512
#define RADIX_RUN 32
static int depth_radix(uint32_t *count, const manifold_rec *rc, size_t n, depth_key **a, depth_key **b)
{
    /* the bytes on which the keys differ (digit g: byte g of t, g < 8; byte g - 8 of d), counted */
    const depth_key *x = *a;
    uint64_t dt = 0, dd = 0;
    for (size_t k = 1; k < n; ++k) {
        dt |= x[k].t ^ x[0].t;
        dd |= x[k].d ^ x[0].d;
    }
    int digit[16], nd = 0;
    for (int g = 0; g < 16; ++g)
        if (((g < 8 ? dt : dd) >> (8 * (g & 7))) & 255)
            digit[nd++] = g;
    memset(count, 0, (size_t)nd * 256 * sizeof *count);
    for (size_t k = 0; k < n; ++k)
        for (int e = 0; e < nd; ++e) {
            const int g = digit[e];
            count[256 * e + (((g < 8 ? x[k].t : x[k].d) >> (8 * (g & 7))) & 255)]++;
        }
    depth_key *src = *a, *dst = *b;
    for (int e = 0; e < nd; ++e) {
        uint32_t *c = count + 256 * e;
        const int g = digit[e], shift = 8 * (g & 7);
        uint32_t sum = 0;
        for (int v = 0; v < 256; ++v) {
            const uint32_t m = c[v];
            c[v] = sum;
            sum += m;
        }
        for (size_t k = 0; k < n; ++k) {
            const uint64_t key = g < 8 ? src[k].t : src[k].d;
            dst[c[(key >> shift) & 255]++] = src[k];
        }
        depth_key *t = src;
        src = dst;
        dst = t;
    }
    *a = src;
    *b = dst;
    for (size_t lo = 0, hi; lo < n; lo = hi) {
        for (hi = lo + 1; hi < n && src[hi].d == src[lo].d && src[hi].t == src[lo].t; ++hi)
            ;
        if (hi - lo > RADIX_RUN)
            return 0;
        for (size_t k = lo + 1; k < hi; ++k) { /* stable: moved only past points strictly after it */
            const depth_key v = src[k];
            size_t m = k;
            for (; m > lo && depth_cmp(&rc[v.at], &rc[src[m - 1].at]) < 0; --m)
                src[m] = src[m - 1];
            src[m] = v;
        }
    }
    return 1;
}

/* A compare-exchange of keys *x and *y (x first) without a jump where their (d, t) differ (the
 * merge sort's first levels mispredict one comparison in two): y goes first where key_before puts
 * it first, or where it ties x and came later in the points (so equals stay in the input's
 * order, as the stable merge leaves them). */
static void key_cswap(depth_key *x, depth_key *y, const manifold_rec *rc)
{
    const depth_key p = *x, q = *y;
    uint64_t sw = (uint64_t)((q.d < p.d) | ((q.d == p.d) & (q.t < p.t)));
    if (q.d == p.d && q.t == p.t) {
        const int c = depth_cmp(&rc[q.at], &rc[p.at]);
        sw = c < 0 || (c == 0 && q.at < p.at);
    }
    const uint64_t m = 0 - sw, dd = (p.d ^ q.d) & m, dt = (p.t ^ q.t) & m;
    const size_t da = (p.at ^ q.at) & (size_t)m;
    x->d = p.d ^ dd;
    y->d = q.d ^ dd;
    x->t = p.t ^ dt;
    y->t = q.t ^ dt;
    x->at = p.at ^ da;
    y->at = q.at ^ da;
}

/* Sorts the n points rc into depth order (depth_cmp's; a merge sort of 24-byte keys, stable, in
 * place of qsort on the records): returns the keys in that order (in w->keys; key k's `at` the
 * point's index in rc), the points left where they are (a copy of each record in order was a
 * tenth of the sort and merge). NULL out of memory. */
static const depth_key *depth_sort(manifold_work *w, const manifold_rec *rc, size_t n)
{
    if (2 * n > w->keys_cap) {
        depth_key *k = realloc(w->keys, 2 * n * sizeof *k);
        if (k == NULL)
            return NULL;
        w->keys = k;
        w->keys_cap = 2 * n;
    }
    depth_key *a = w->keys, *b = w->keys + n;
    for (size_t k = 0; k < n; ++k) {
        a[k].d = order_bits((double)rc[k].c.distance);
        a[k].t = (uint64_t)rc[k].c.tri_i << 32 | rc[k].c.tri_j;
        a[k].at = k;
    }
    int sorted = 0;
    if (n >= RADIX_MIN && n <= UINT32_MAX) {
        if (w->radix_count == NULL && (w->radix_count = malloc(16 * 256 * sizeof *w->radix_count)) == NULL)
            return NULL;
        sorted = depth_radix(w->radix_count, rc, n, &a, &b);
    }
    /* the merge sort's runs of 8 first, each by a sorting network (19 compare-exchanges: the
     * keys in depth_cmp's order, equals by their place, as the merges would leave them), the last
     * (under 8) by insertion */
    size_t run0 = 1;
    if (!sorted) {
        static const unsigned char net[19][2] = {{0, 2}, {1, 3}, {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6},
                                                 {3, 7}, {0, 1}, {2, 3}, {4, 5}, {6, 7}, {2, 4}, {3, 5},
                                                 {1, 4}, {3, 6}, {1, 2}, {3, 4}, {5, 6}};
        size_t lo = 0;
        for (; lo + 8 <= n; lo += 8)
            for (int e = 0; e < 19; ++e)
                key_cswap(&a[lo + net[e][0]], &a[lo + net[e][1]], rc);
        for (size_t k = lo + 1; k < n; ++k) {
            const depth_key v = a[k];
            size_t m = k;
            for (; m > lo && key_before(&v, &a[m - 1], rc); --m)
                a[m] = a[m - 1];
            a[m] = v;
        }
        run0 = 8;
    }
    for (size_t run = run0; !sorted && run < n; run *= 2) {
        for (size_t lo = 0; lo < n; lo += 2 * run) {
            const size_t mid = lo + run < n ? lo + run : n, hi = lo + 2 * run < n ? lo + 2 * run : n;
            size_t x = lo, y = mid, o = lo;
            while (x < mid && y < hi)
                b[o++] = key_before(&a[y], &a[x], rc) ? a[y++] : a[x++];
            while (x < mid)
                b[o++] = a[x++];
            while (y < hi)
                b[o++] = a[y++];
        }
        depth_key *t = a;
        a = b;
        b = t;
    }
    return a;
}

/* ---- steps 2 to 4: merge, seed, spread ------------------------------------------------------- */

static double dist2(const double *a, const double *b)
{
    const double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
}

/* The grid's cells are CELL_TOLS tolerances wide: the points within the tolerance of a point
 * lie in its own cell and, per axis where it lies within the tolerance of its cell's side, the
 * neighbour across that side; NEAR_SIDE (of a cell) allows for the rounding of the cell
 * coordinates with room to spare. Wide cells leave most points one cell to look in (8 at
 * most), at the price of comparing the few points that share a cell. */
#define CELL_TOLS 8.0
#define NEAR_SIDE (1.0 / CELL_TOLS + 0.05)

/* The cell of scaled point z, each coordinate in cells of width 1 / inv (saturated far out:
 * the cells there only gather more points to compare), and per axis the neighbour to look in
 * too: -1 or +1 where z lies within NEAR_SIDE of that side, else 0. (The product by the
 * reciprocal rounds once more than a quotient: a few ulps of a cell coordinate, well inside
 * the slack.) */
static void cell_of(const double z[3], double inv, int64_t c[3], int side[3])
{
    for (int r = 0; r < 3; ++r) {
        /* floor(q) by a conversion (libm's floor is a call on the baseline ISA), on q held
         * within 2^41, where every double is the floor's own or has an integer part in int64 */
        const double q = z[r] * inv, h = q > 0x1p41 ? 0x1p41 : q < -0x1p41 ? -0x1p41 : q;
        int64_t t = (int64_t)h;
        t -= (double)t > h;
        const double x = (double)t;
        c[r] = x > 0x1p40 ? (int64_t)0x1p40 : x < -0x1p40 ? -(int64_t)0x1p40 : t;
        /* the two tests exclusive: their difference, without the jump that mispredicted (a
         * side is near for a third of the points, at random) */
        side[r] = (q - x > 1 - NEAR_SIDE) - (q - x < NEAR_SIDE);
    }
}

/* A cell's key from its coordinates' products with the axes' odd constants (cell_axes), XORed:
 * mixed once more, never 0 (0 marks an empty slot). Two cells with one key share a list: their
 * points are only compared more, so any mixing gives the same points kept. */
static uint64_t cell_key(uint64_t h)
{
    h = (h ^ (h >> 29)) * 0xbf58476d1ce4e5b9ULL;
    return (h ^ (h >> 32)) | 1;
}

/* Per axis r, the products of cell coordinate c[r] (x[r][0]) and of its neighbour's (x[r][1])
 * with the axis's constant: a cell of the 8 probed is one XOR of three. */
static void cell_axes(const int64_t c[3], const int side[3], uint64_t x[3][2])
{
    static const uint64_t mul[3] = {0x9e3779b97f4a7c15ULL, 0xc2b2ae3d27d4eb4fULL, 0x165667b19e3779f9ULL};
    for (int r = 0; r < 3; ++r) {
        x[r][0] = (uint64_t)c[r] * mul[r];
        x[r][1] = (uint64_t)(c[r] + side[r]) * mul[r];
    }
}

/* The slot of cell key k in the open-addressing table of 2^bits slots (its own, or the empty one
 * where it goes): from the key's top bits, then the next ones. */
static size_t cell_slot(const manifold_work *w, int bits, uint64_t k)
{
    const size_t mask = ((size_t)1 << bits) - 1;
    size_t at = (size_t)(k >> (64 - bits));
    while (w->cell_key[at] != 0 && w->cell_key[at] != k)
        at = (at + 1) & mask;
    return at;
}

/* Step 2: the contacts to keep (indices into c, depth order) into w->kept; returns how many.
 * z holds the scaled points, tol the scaled tolerance. The grid's cells are CELL_TOLS
 * tolerances wide, so that the points within the tolerance of a point lie in its own cell and
 * the neighbours cell_of names (8 cells at most). */
static size_t merge_points(manifold_work *w, size_t n, double tol, int use_grid)
{
    const double tol2 = tol * tol;
    size_t nk = 0;
    /* a point at the place of the one before it (a vertex's contact with each triangle around it:
     * a seventh of the pile's) is dropped as the search would drop it: that one kept lies at 0,
     * and dropped, the same search found a kept point within tol of the same place */
    const int same_drops = tol2 >= 0;
#define SAME_AS_BEFORE(k) \
    ((k) > 0 && same_drops && w->z[3 * (k)] == w->z[3 * (k) - 3] && w->z[3 * (k) + 1] == w->z[3 * (k) - 2] && \
     w->z[3 * (k) + 2] == w->z[3 * (k) - 1])
    if (!use_grid) {
        for (size_t k = 0; k < n; ++k) {
            if (SAME_AS_BEFORE(k))
                continue;
            int near = 0;
            for (size_t a = 0; a < nk && !near; ++a)
                near = dist2(w->z + 3 * k, w->z + 3 * w->kept[a]) <= tol2;
            if (!near)
                w->kept[nk++] = k;
        }
        return nk;
    }
    int bits = 6;
    while (((size_t)1 << bits) < 2 * n)
        ++bits;
    memset(w->cell_key, 0, ((size_t)1 << bits) * sizeof *w->cell_key);
    /* (a tolerance of 0 merges equal points only: any width) */
    const double inv = 1 / (tol > 0 ? CELL_TOLS * tol : 1);
    for (size_t k = 0; k < n; ++k) {
        if (SAME_AS_BEFORE(k))
            continue;
        int64_t c[3];
        int side[3];
        uint64_t x[3][2];
        cell_of(w->z + 3 * k, inv, c, side);
        cell_axes(c, side, x);
        int near = 0;
        const int look = (side[0] != 0) | (side[1] != 0) << 1 | (side[2] != 0) << 2;
        /* the cells of look's submasks m (0 first, then upward: m - look & look steps to the
         * next), not all 8 values of m each tested against look: most points look in one cell */
        for (int m = 0, first = 1; (first || m != 0) && !near; m = (m - look) & look, first = 0) {
            const size_t at = cell_slot(w, bits, cell_key(x[0][m & 1] ^ x[1][(m >> 1) & 1] ^ x[2][(m >> 2) & 1]));
            if (w->cell_key[at] == 0)
                continue;
            for (size_t a = w->cell_head[at]; a != SIZE_MAX && !near; a = w->next[a])
                near = dist2(w->z + 3 * k, w->z + 3 * a) <= tol2;
        }
        if (near)
            continue;
        w->kept[nk++] = k;
        const uint64_t key = cell_key(x[0][0] ^ x[1][0] ^ x[2][0]);
        const size_t at = cell_slot(w, bits, key);
        if (w->cell_key[at] == 0) {
            w->cell_key[at] = key;
            w->cell_head[at] = SIZE_MAX;
        }
        w->next[k] = w->cell_head[at];
        w->cell_head[at] = k;
    }
#undef SAME_AS_BEFORE
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

/* Room for n points in w->near and n0 contacts' indices in w->pick. 0 out of memory. */
static int near_reserve(manifold_work *w, size_t n, size_t n0)
{
    if (n > w->near_cap) {
        manifold_rec *f = realloc(w->near, n * sizeof *f);
        if (f == NULL)
            return 0;
        w->near = f;
        w->near_cap = n;
    }
    if (n0 > w->pick_cap) {
        size_t *p = realloc(w->pick, n0 * sizeof *p);
        if (p == NULL)
            return 0;
        w->pick = p;
        w->pick_cap = n0;
    }
    return 1;
}

/* Steps 1 and 2 on the n points rc (n > 0): their points in depth order, relative to the first
 * and scaled by f1 f2, into w->z, the kept (merge tolerance tol, scaled) into w->kept (indices
 * into rc, in depth order) with z compacted to them. Returns how many are kept; 0 out of memory. */
static size_t order_merge(manifold_work *w, const manifold_rec *rc, size_t n, double f1, double f2, double tol)
{
    const depth_key *o;
    if (!manifold_work_reserve(w, n) || (o = depth_sort(w, rc, n)) == NULL)
        return 0;
    double *z = w->z, origin[3] = {0, 0, 0};
    for (size_t k = 0; k < n; ++k)
        for (int r = 0; r < 3; ++r) {
            const manifold_rec *x = &rc[o[k].at];
            const double v = (double)(real)(0.5 * (double)x->c.p[r] + 0.5 * (double)x->c.q[r]);
            if (k == 0)
                origin[r] = v;
            z[3 * k + (size_t)r] = (v - origin[r]) * f1 * f2;
        }
    const size_t nk = merge_points(w, n, tol, n > 32);
    for (size_t a = 0; a < nk; ++a) { /* compact: kept[a] >= a, increasing; then into rc */
        for (int r = 0; r < 3; ++r)
            z[3 * a + (size_t)r] = z[3 * w->kept[a] + (size_t)r];
        w->kept[a] = o[w->kept[a]].at;
    }
    return nk;
}

/* Steps 3 and 4 on the nk points kept (w->kept into rc, w->z): the points chosen into w->sel
 * (indices into w->kept); returns how many. part: rc holds the deepest level's points alone,
 * and the answer is 0 where the choice would look beyond them (max or fewer kept, or fewer
 * than max on the level). */
static size_t choose_points(manifold_work *w, const manifold_rec *rc, size_t nk, real margin, size_t max, double big,
                            double f1, double f2, int part)
{
    const double *z = w->z;
    /* the seed: among the kept within FEATURE_TOL of the larger radius of the smallest distance,
     * the farthest from their centroid */
    const double d0 = (double)rc[w->kept[0]].c.distance, window = FEATURE_TOL * big;
    double g[3] = {0, 0, 0};
    size_t ntie = 0;
    for (size_t a = 0; a < nk && (double)rc[w->kept[a]].c.distance - d0 <= window; ++a, ++ntie)
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
    if (part && nk <= max)
        return 0;
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
        size_t nd = ntie;
        while (nd < nk && (double)rc[w->kept[nd]].c.distance - d0 <= level)
            ++nd;
        /* of those, the level: the points on the resting plane, each rising above every deeper
         * point of the level by at most LEVEL_SLOPE of the distance between them (a plane
         * tilted by less than the flat angle); a point rising steeply from a deeper one beside it
         * is across an edge (an overhanging edge's closest point, farther than the faces' gap
         * beside it) and would hold the body up only after it sank. taken[a] = 2: not of it. */
        memset(w->taken, 0, nk);
        const double slope2 = LEVEL_SLOPE * LEVEL_SLOPE;
        size_t nl = 0;
        /* A point a breaks b's slope only within rb / LEVEL_SLOPE of it, rb b's rise above the
         * deepest (a's rise is no more, with every rounding): so only the level's points so far
         * within that of b along the first axis are looked at, from w->ord (those points by
         * their first coordinate; its differences are dist2's, monotone). Rises too small to
         * square look at every point. */
        size_t no = 0;
        for (size_t b = 0; b < nd; ++b) {
            const double db = (double)rc[w->kept[b]].c.distance;
            int on = 1; /* the seed's window is of the level whole */
            const double rb = (db - d0) * f1 * f2, xb = z[3 * b];
            if (b >= ntie && rb > 0x1p-300) {
                const double reach = rb / LEVEL_SLOPE * 1.001;
                size_t lo = 0, hi = no; /* the first with a difference above -reach */
                while (lo < hi) {
                    const size_t mid = lo + (hi - lo) / 2;
                    if (z[3 * w->ord[mid]] - xb > -reach)
                        hi = mid;
                    else
                        lo = mid + 1;
                }
                for (size_t k = lo; k < no && on && z[3 * w->ord[k]] - xb < reach; ++k) {
                    const size_t a = w->ord[k];
                    const double rise = (db - (double)rc[w->kept[a]].c.distance) * f1 * f2;
                    on = rise * rise <= slope2 * dist2(z + 3 * a, z + 3 * b);
                }
            } else {
                for (size_t a = 0; a < b && on && b >= ntie; ++a) {
                    const double rise = (db - (double)rc[w->kept[a]].c.distance) * f1 * f2;
                    on = w->taken[a] == 2 || rise * rise <= slope2 * dist2(z + 3 * a, z + 3 * b);
                }
            }
            w->taken[b] = on ? 0 : 2;
            nl += (size_t)on;
            if (on) { /* into the order, after its equals: the first place whose point lies above xb
                       * (by bisection; a scan back from the end was a tenth of a sliver tower's
                       * reduction) */
                size_t at = 0, hi = no;
                while (at < hi) {
                    const size_t mid = at + (hi - at) / 2;
                    if (z[3 * w->ord[mid]] > xb)
                        hi = mid;
                    else
                        at = mid + 1;
                }
                memmove(w->ord + at + 1, w->ord + at, (no - at) * sizeof *w->ord);
                w->ord[at] = b;
                ++no;
            }
        }
        for (size_t b = nd; b < nk; ++b)
            w->taken[b] = 2;
        /* of the level, the touching points: within TOUCH_FRACTION of the margin left below d0,
         * where a resting body's supports lie (two parts of a torus, a ball in a groove); a
         * point of the level farther above the deepest holds nothing until the body sinks, so
         * the spread is over these when they are K or more. taken[a] = 3: of the level, not
         * touching (made 0 again when they are fewer). */
        const double touch = TOUCH_FRACTION * ((double)margin - d0);
        size_t nt = 0;
        for (size_t b = 0; b < nd; ++b)
            if (w->taken[b] == 0) {
                if ((double)rc[w->kept[b]].c.distance - d0 <= touch)
                    ++nt;
                else
                    w->taken[b] = 3;
            }
        if (nt >= max) {
            ns = spread_points(z, nk, seed, max, w->sel, w->taken);
        } else if (part) {
            return 0;
        } else {
            /* fewer than K touch: every touching point (the seed first, then by depth), then
             * the level's point farthest from every point kept; when the level holds fewer
             * than K, all of it, then the farthest among the rest */
            const int whole = nl < max;
            w->sel[0] = seed;
            w->taken[seed] = 1;
            ns = 1;
            for (size_t a = 0; a < nk; ++a)
                if (a != seed && (w->taken[a] == 0 || (whole && w->taken[a] == 3))) {
                    w->sel[ns++] = a;
                    w->taken[a] = 1;
                }
            for (size_t a = 0; a < nk; ++a) /* 0: may be picked next */
                w->taken[a] = whole ? w->taken[a] == 1 : w->taken[a] == 3 ? 0 : w->taken[a];
            while (ns < max) {
                const size_t pick = farthest_point(z, nk, w->sel, ns, w->taken);
                if (pick == SIZE_MAX)
                    break;
                w->sel[ns++] = pick;
                w->taken[pick] = 1;
            }
        }
    }
    return ns;
}
