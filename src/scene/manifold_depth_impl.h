/* SPDX-License-Identifier: MIT */
/* Section 5b: where the depth of a solid pair that is not searched by separating axes (a torus,
 * a bowl, any concave edge; or over that search's budget) peaks inside a face. Part of a body
 * pair's manifold (scene/manifold_impl.h, which includes it once per precision; docs/scenes.md,
 * section 5b, "the faces' deepest points").
 *
 * For a triangle F of one body A and the other solid B, the depth of a point x is its signed
 * distance to B's surface, phi(x) = +dist(x, dB) inside B and -dist outside. Its largest value
 * over F is sought by branch and bound over F cut into triangles (each cut in 4 at its edges'
 * midpoints), with two upper bounds on phi over a cell T, both exact statements:
 *   - phi is 1-Lipschitz: phi <= phi(c) + rho, c the cell's centroid and rho its distance to the
 *     farthest corner;
 *   - phi(x) <= dist(x, g) for every triangle g of B (inside, phi is the least of those; outside
 *     it is negative), and dist(x, g) is convex in x, so over T it is at most its largest value
 *     at T's corners. g: the triangles nearest the cell's corners and centroid, and its parent's
 *     (FACE_NEAR); two of them mixed (face_mix: a slab's two faces), and two coplanar neighbours
 *     forming a convex quadrilateral as one (face_quad: a box's face cut along its diagonal).
 * The second makes a face lying flat over B's face (a plateau, where the first never settles) a
 * single cell. Cells whose bound is at most L + eps are dropped (L: the face's best depth so far,
 * at least the floor below), the rest cut, best bound first over all the pair's faces; so when
 * the search ends each face's largest depth is at most max(L, floor) + eps, and the point
 * reported is a real point of F at exactly its distance to B (the point queries' exact distance
 * of the point as rounded). */

/* eps: this fraction of the smaller body's radius */
#define DEPTH_FACE_TOL 0x1p-16
/* The search's budget: at most this many cells per body pair, over both bodies' faces (each a
 * winding number and four closest-point queries: its centroid's phi, its corners' nearest
 * triangles); beyond it the search stops where it is, the faces' points so far kept (real
 * points, without the bound eps). */
#define DEPTH_FACE_BUDGET 4096

#define FACE_NEAR 6 /* triangles of B a cell keeps for its bound */

typedef struct face_cell {
    double x[9];          /* corners, world */
    double ub;            /* bound on phi over the cell */
    uint32_t face;        /* which face (an index into the pair's list) */
    uint32_t g[FACE_NEAR]; /* triangles of B near the cell: its centroid's, then its parent's
                           * (UINT32_MAX: none) */
} face_cell;

typedef struct face_heap {
    face_cell *c;
    size_t n, cap;
} face_heap;

static int face_heap_push(face_heap *h, const face_cell *x)
{
    if (h->n == h->cap) {
        face_cell *v = array_grow(h->c, &h->cap, h->n + 1, sizeof *v, 64);
        if (v == NULL)
            return 0;
        h->c = v;
    }
    size_t k = h->n++;
    while (k > 0 && h->c[(k - 1) / 2].ub < x->ub) {
        h->c[k] = h->c[(k - 1) / 2];
        k = (k - 1) / 2;
    }
    h->c[k] = *x;
    return 1;
}

static face_cell face_heap_pop(face_heap *h)
{
    const face_cell top = h->c[0], last = h->c[--h->n];
    size_t k = 0;
    for (;;) {
        size_t m = 2 * k + 1;
        if (m >= h->n)
            break;
        if (m + 1 < h->n && h->c[m + 1].ub > h->c[m].ub)
            ++m;
        if (!(h->c[m].ub > last.ub))
            break;
        h->c[k] = h->c[m];
        k = m;
    }
    if (h->n > 0)
        h->c[k] = last;
    return top;
}

/* One evaluation of phi at world point x (double, rounded to the scene's precision into xr):
 * *phi, the closest point's result into *r. 0 out of memory. */
static int face_phi(const struct ttd_scene *s, const ttd_engine_config *cfg, uint32_t a, const double x[3], real xr[3],
                    double *phi, ttd_point_result *r)
{
    for (int k = 0; k < 3; ++k)
        xr[k] = (real)x[k];
    if (!edge_depth(s, cfg, a, xr, r))
        return 0;
    *phi = (double)r->distance > 0 && body_inside(s, a, xr) ? (double)r->distance : -(double)r->distance;
    return 1;
}

/* The distances of the cell's corners x to triangle g of body a (the exact point-triangle
 * distance of each corner moved into a's frame) into d[3]. */
static void face_tri_dist(const struct ttd_scene *s, uint32_t a, uint32_t g, const double x[9], double d[3])
{
    const struct ttd_mesh *m = s->body[a].mesh;
    const real *V = (const real *)m->verts;
    double tri[9];
    for (int k = 0; k < 3; ++k)
        for (int r = 0; r < 3; ++r)
            tri[3 * k + r] = (double)V[3 * (size_t)m->tris[3 * (size_t)g + (size_t)k] + (size_t)r];
    for (int k = 0; k < 3; ++k) {
        real xr[3], y[3];
        for (int r = 0; r < 3; ++r)
            xr[r] = (real)x[3 * k + r];
        TTD_POINT_INTO(body_pose(s, a), xr, y)
        const double yd[3] = {(double)y[0], (double)y[1], (double)y[2]};
        ttd_point_result_d pr;
        d[k] = ttd_point_triangle_d(yd, tri, &pr) == TTD_OK ? pr.distance : HUGE_VAL;
    }
}

/* min over lambda in [0, 1] of the largest over the corners of lambda p_k + (1 - lambda) q_k: a
 * bound on min(dist(., g), dist(., h)) over the cell, since that is at most the convex function
 * lambda dist(., g) + (1 - lambda) dist(., h) for every lambda, whose largest value is at a
 * corner. Its minimum is at 0, 1 or where two corners' lines cross; every lambda tried gives a
 * bound, so rounding only makes it a little looser. Two planes bounding a slab (a thin plate's
 * faces) make it exact between them, where each distance alone is not. */
static double face_mix(const double p[3], const double q[3])
{
    double best = HUGE_VAL;
    for (int k = 0; k < 3; ++k)
        if (!(p[k] < HUGE_VAL && q[k] < HUGE_VAL))
            return HUGE_VAL; /* a distance that failed: 0 * inf would be NaN, which fmax drops */
    double lam[5] = {0, 1, -1, -1, -1};
    for (int k = 0; k < 3; ++k) {
        const int l = (k + 1) % 3;
        const double den = (p[k] - q[k]) - (p[l] - q[l]);
        if (den != 0)
            lam[2 + k] = (q[l] - q[k]) / den;
    }
    for (int c = 0; c < 5; ++c) {
        const double t = lam[c];
        if (!(t >= 0 && t <= 1))
            continue;
        double hi = 0;
        for (int k = 0; k < 3; ++k)
            hi = fmax(hi, t * p[k] + (1 - t) * q[k]);
        best = fmin(best, hi);
    }
    return best;
}

/* Where triangles g and h of body a (its frame) share an edge and lie nearly in one plane,
 * forming a convex quadrilateral there: delta, the height of h's far vertex over g's plane (>= 0);
 * else -1. Then min(dist(., g), dist(., h)), the distance to g and h together, is within delta
 * of the distance to the flat quadrilateral Q (g with h's far vertex moved onto g's plane: the two
 * sets lie within delta of each other), which is convex: over a cell it is at most its largest
 * value at the corners plus 2 delta. A face cut along a diagonal (a box's) is then one piece for
 * the bound, where each triangle alone leaves a seam that never settles. */
static double face_quad(const struct ttd_scene *s, uint32_t a, uint32_t g, uint32_t h)
{
    const struct ttd_mesh *m = s->body[a].mesh;
    const ttd_mesh_edges *E = ttd_mesh_edges_made(m);
    int k = 0;
    while (k < 3 && E->across[3 * (size_t)g + (size_t)k] != h)
        ++k;
    if (k == 3)
        return -1;
    const real *V = (const real *)m->verts;
    const uint32_t *T = m->tris;
    double P[4][3]; /* g's far vertex, the shared edge's ends, h's far vertex */
    const uint32_t gv[3] = {T[3 * (size_t)g + (size_t)((k + 2) % 3)], T[3 * (size_t)g + (size_t)k],
                            T[3 * (size_t)g + (size_t)((k + 1) % 3)]};
    uint32_t hv = T[3 * (size_t)h];
    for (int l = 0; l < 3; ++l) {
        const uint32_t v = T[3 * (size_t)h + (size_t)l];
        if (E->weld[v] != E->weld[gv[1]] && E->weld[v] != E->weld[gv[2]])
            hv = v;
    }
    for (int r = 0; r < 3; ++r) {
        for (int l = 0; l < 3; ++l)
            P[l][r] = (double)V[3 * (size_t)gv[l] + (size_t)r];
        P[3][r] = (double)V[3 * (size_t)hv + (size_t)r];
    }
    double e1[3], e2[3], nrm[3];
    for (int r = 0; r < 3; ++r) {
        e1[r] = P[1][r] - P[0][r];
        e2[r] = P[2][r] - P[0][r];
    }
    cross3d(e1, e2, nrm);
    const double len = sqrt(dot3d(nrm, nrm));
    if (!(len > 0))
        return -1;
    for (int r = 0; r < 3; ++r)
        nrm[r] /= len;
    double d[3], Q[3];
    for (int r = 0; r < 3; ++r)
        d[r] = P[3][r] - P[0][r];
    const double hgt = dot3d(d, nrm);
    for (int r = 0; r < 3; ++r)
        Q[r] = P[3][r] - hgt * nrm[r];
    /* convex: g's far vertex and Q on opposite sides of the shared edge, the edge's ends on
     * opposite sides of the line from g's far vertex to Q (strictly, with room for rounding) */
    double u[3], v[3], x[3], y[3], c1[3], c2[3];
    for (int r = 0; r < 3; ++r) {
        u[r] = P[2][r] - P[1][r];
        v[r] = P[0][r] - P[1][r];
        x[r] = Q[r] - P[1][r];
    }
    cross3d(u, v, c1);
    cross3d(u, x, c2);
    const double tiny = 0x1p-20 * dot3d(u, u);
    if (!(dot3d(c1, nrm) > tiny && dot3d(c2, nrm) < -tiny) && !(dot3d(c1, nrm) < -tiny && dot3d(c2, nrm) > tiny))
        return -1;
    for (int r = 0; r < 3; ++r) {
        u[r] = Q[r] - P[0][r];
        v[r] = P[1][r] - P[0][r];
        y[r] = P[2][r] - P[0][r];
    }
    cross3d(u, v, c1);
    cross3d(u, y, c2);
    if (!(dot3d(c1, nrm) > tiny && dot3d(c2, nrm) < -tiny) && !(dot3d(c1, nrm) < -tiny && dot3d(c2, nrm) > tiny))
        return -1;
    /* nearly in one plane: the bend far below the bound's use (a flat edge is within 1e-3 rad) */
    const double h2 = fabs(hgt);
    return h2 <= 1e-3 * sqrt(dot3d(d, d)) ? h2 * (1 + 0x1p-40) : -1;
}

/* The cell's bound from its centroid's phi and the triangles g[]; fills ub. Convex functions
 * at least phi, by their values at the corners: each g's distance, each flat pair's (face_quad);
 * the bound is the least over pairs of them mixed (face_mix, a function with itself: its own). */
static void face_cell_bound(const struct ttd_scene *s, uint32_t a, face_cell *c, const double cen[3], double phi)
{
    double rho = 0;
    for (int k = 0; k < 3; ++k) {
        double d2 = 0;
        for (int r = 0; r < 3; ++r)
            d2 += (c->x[3 * k + r] - cen[r]) * (c->x[3 * k + r] - cen[r]);
        rho = fmax(rho, sqrt(d2));
    }
    double ub = phi + rho, d[FACE_NEAR + FACE_NEAR * (FACE_NEAR - 1) / 2][3];
    int ng = 0;
    for (int k = 0; k < FACE_NEAR && c->g[k] != UINT32_MAX; ++k, ++ng)
        face_tri_dist(s, a, c->g[k], c->x, d[k]);
    int nf = ng;
    for (int k = 0; k < ng; ++k)
        for (int l = k + 1; l < ng; ++l) {
            const double delta = face_quad(s, a, c->g[k], c->g[l]);
            if (delta >= 0) {
                for (int q = 0; q < 3; ++q)
                    d[nf][q] = fmin(d[k][q], d[l][q]) + 2 * delta;
                ++nf;
            }
        }
    for (int k = 0; k < nf; ++k)
        for (int l = k; l < nf; ++l)
            ub = fmin(ub, face_mix(d[k], d[l]));
    c->ub = ub;
}

/* The cell's triangles of body a: those nearest its corners (closest-point queries; the
 * centroid's, t, first), then its parent's others, each once, up to FACE_NEAR. 0 out of memory. */
static int face_near(const struct ttd_scene *s, const ttd_engine_config *cfg, uint32_t a, face_cell *ch, uint32_t t,
                     const uint32_t parent[FACE_NEAR])
{
    uint32_t cand[4 + FACE_NEAR];
    int nc = 0, n = 0;
    cand[nc++] = t;
    for (int k = 0; k < 3; ++k) {
        real xr[3];
        ttd_point_result r;
        for (int q = 0; q < 3; ++q)
            xr[q] = (real)ch->x[3 * k + q];
        if (!edge_depth(s, cfg, a, xr, &r))
            return 0;
        cand[nc++] = r.triangle;
    }
    for (int k = 0; k < FACE_NEAR && parent != NULL; ++k)
        cand[nc++] = parent[k];
    for (int k = 0; k < nc && n < FACE_NEAR; ++k) {
        int seen = cand[k] == UINT32_MAX;
        for (int l = 0; l < n && !seen; ++l)
            seen = ch->g[l] == cand[k];
        if (!seen)
            ch->g[n++] = cand[k];
    }
    while (n < FACE_NEAR)
        ch->g[n++] = UINT32_MAX;
    return 1;
}

/* Whether the pair is one solid_sat searches (both convex, within its budget). */
static int depth_pair_convex(const struct ttd_scene *s, uint32_t i, uint32_t j)
{
    size_t nei, nej;
    if (!sat_convex(s, i, &nei) || !sat_convex(s, j, &nej))
        return 0;
    const struct ttd_mesh *mi = s->body[i].mesh, *mj = s->body[j].mesh;
    const ttd_mesh_edges *Ei = ttd_mesh_edges_made(mi), *Ej = ttd_mesh_edges_made(mj);
    return !((double)mi->nt * (double)Ej->nw + (double)mj->nt * (double)Ei->nw + (double)nei * (double)nej > SAT_BUDGET);
}

static int u32_cmp(const void *x, const void *y)
{
    const uint32_t a = *(const uint32_t *)x, b = *(const uint32_t *)y;
    return (a > b) - (a < b);
}

/* Solid pair (i, j) that solid_sat does not search, whose surfaces cross (a contact at d = 0) or
 * nest: for each triangle of each body that crosses the other's surface (a contact's at d = 0)
 * or has a vertex inside it (w->inner, from solid_side), its deepest point inside the other (the
 * search above), pushed into w->all where deeper than every point of the pair so far (from
 * w->all[before]) by more than the seed's window, so that where vertices or edges measure the
 * depth nothing changes. nested: n == 0 and one body inside the other. 0 out of memory. */
/* One cell c of a face (its corners and face set; parent: its parent's triangles, NULL for a
 * whole face): phi at its centroid, which raises the face's best (*best, its point's query *br
 * and rounded place bx) where deeper, then its triangles and bound; the cell goes on the heap
 * while the bound exceeds the best by more than eps. 0 out of memory or a failed query. */
static int face_visit(const struct ttd_scene *s, const ttd_engine_config *cfg, uint32_t a, face_cell *c,
                      const uint32_t *parent, double eps, double *best, ttd_point_result *br, real bx[3], face_heap *h)
{
    double cen[3], phi;
    real xr[3];
    ttd_point_result r;
    for (int q = 0; q < 3; ++q)
        cen[q] = (c->x[q] + c->x[3 + q] + c->x[6 + q]) / 3;
    if (!face_phi(s, cfg, a, cen, xr, &phi, &r))
        return 0;
    if (phi > *best) {
        *best = phi;
        *br = r;
        memcpy(bx, xr, sizeof xr);
    }
    if (!face_near(s, cfg, a, c, r.triangle, parent))
        return 0;
    face_cell_bound(s, a, c, cen, phi);
    return c->ub > *best + eps ? face_heap_push(h, c) : 1;
}

static int solid_faces(const struct ttd_scene *s, const ttd_engine_config *cfg, uint32_t i, uint32_t j, size_t before,
                       const ttd_scene_contact *c, size_t n, manifold_work *w)
{
    int crossing = n == 0; /* nested */
    for (size_t k = 0; k < n && !crossing; ++k)
        crossing = c[k].distance == 0;
    if (!crossing && w->all_n == before)
        return 1;
    if (depth_pair_convex(s, i, j))
        return 1;
    if (s->body[i].mesh->nt >= (size_t)1 << 31 || s->body[j].mesh->nt >= (size_t)1 << 31)
        return 1; /* a face is named by 31 bits below its side's */
    double floor = 0;
    for (size_t k = before; k < w->all_n; ++k)
        floor = fmax(floor, -(double)w->all[k].c.distance);
    const double ri = s->body[i].mesh->radius, rj = s->body[j].mesh->radius;
    floor += FEATURE_TOL * fmax(ri, rj);
    const double eps = DEPTH_FACE_TOL * fmin(ri, rj);
    size_t budget = DEPTH_FACE_BUDGET;
    face_heap h = {0};
    uint32_t *tl = NULL;  /* the faces: side << 31 | triangle */
    double *best = NULL;  /* each face's deepest phi so far (the floor: none yet) */
    real *bx = NULL;      /* its point */
    ttd_point_result *br = NULL; /* its closest point on the other body */
    size_t ntl = 0;
    int ok = 1;
    const ttd_mesh_edges *Es[2] = {ttd_mesh_edges_made(s->body[i].mesh), ttd_mesh_edges_made(s->body[j].mesh)};
    const size_t want = 2 * n + 3 * (s->body[i].mesh->nt + s->body[j].mesh->nt); /* the rings: 3 nt in all */
    tl = malloc(want * sizeof *tl);
    if (tl == NULL)
        return 0;
    for (int side = 0; side < 2; ++side) {
        const ttd_mesh_edges *E = Es[side];
        const size_t from = ntl;
        for (size_t k = 0; k < n; ++k)
            if (c[k].distance == 0)
                tl[ntl++] = (uint32_t)side << 31 | (side ? c[k].tri_j : c[k].tri_i);
        if (w->inner_cap[side] >= E->nw + 1)
            for (uint32_t pl = 0; pl < E->nw; ++pl)
                if (w->inner[side][pl] == 2)
                    for (uint32_t r = E->ring_start[pl]; r < E->ring_start[pl + 1] && ntl < want; ++r)
                        tl[ntl++] = (uint32_t)side << 31 | E->ring[r];
        if (ntl - from > 1)
            qsort(tl + from, ntl - from, sizeof *tl, u32_cmp);
    }
    size_t u = 0;
    for (size_t k = 0; k < ntl; ++k)
        if (k == 0 || tl[k] != tl[k - 1])
            tl[u++] = tl[k];
    ntl = u;
    best = malloc((ntl + 1) * sizeof *best);
    bx = malloc(3 * (ntl + 1) * sizeof *bx);
    br = malloc((ntl + 1) * sizeof *br);
    ok = best != NULL && bx != NULL && br != NULL;
    /* Every face starts at the floor, also those the budget stops before reaching: the last
     * loop reads every face's best (a fine torus nested in a box has more faces than the budget). */
    for (size_t f = 0; f < ntl && ok; ++f)
        best[f] = floor;
    /* every face's whole triangle first, then the cells of all faces, best bound first */
    for (size_t f = 0; f < ntl && ok && budget > 0; ++f) {
        const int side = (int)(tl[f] >> 31);
        const uint32_t t = tl[f] & 0x7fffffffu, b = side ? j : i, a = side ? i : j;
        face_cell root;
        real xt[9];
        world_triangle(s, b, t, xt);
        for (int k = 0; k < 9; ++k)
            root.x[k] = (double)xt[k];
        root.face = (uint32_t)f;
        ok = face_visit(s, cfg, a, &root, NULL, eps, best + f, br + f, bx + 3 * f, &h);
        --budget;
    }
    while (ok && h.n > 0 && budget > 0) {
        const face_cell cell = face_heap_pop(&h);
        const size_t f = cell.face;
        if (!(cell.ub > best[f] + eps))
            continue; /* its face found a point within eps of the bound */
        const int side = (int)(tl[f] >> 31);
        const uint32_t a = side ? i : j;
        double m[9]; /* the edges' midpoints: 01, 12, 20 */
        for (int k = 0; k < 3; ++k)
            for (int q = 0; q < 3; ++q)
                m[3 * k + q] = 0.5 * (cell.x[3 * k + q] + cell.x[3 * ((k + 1) % 3) + q]);
        const double *kids[4][3] = {{cell.x, m, m + 6}, {m, cell.x + 3, m + 3}, {m + 6, m + 3, cell.x + 6}, {m + 3, m + 6, m}};
        for (int kk = 0; kk < 4 && ok && budget > 0; ++kk) {
            face_cell ch;
            for (int k = 0; k < 3; ++k)
                memcpy(ch.x + 3 * k, kids[kk][k], 3 * sizeof(double));
            ch.face = (uint32_t)f;
            ok = face_visit(s, cfg, a, &ch, cell.g, eps, best + f, br + f, bx + 3 * f, &h);
            --budget;
        }
    }
    /* each face's point deeper than the floor, in the faces' order */
    for (size_t f = 0; f < ntl && ok; ++f) {
        if (!(best[f] > floor))
            continue;
        const int side = (int)(tl[f] >> 31);
        const uint32_t t = tl[f] & 0x7fffffffu, a = side ? i : j;
        real y[3] = {br[f].point[0], br[f].point[1], br[f].point[2]};
        TTD_POINT_BACK(real, body_pose(s, a), y);
        ttd_scene_contact rec = {i, j, side ? br[f].triangle : t, side ? t : br[f].triangle, -br[f].distance, {0, 0, 0}, {0, 0, 0}};
        memcpy(rec.p, side ? y : bx + 3 * f, sizeof rec.p);
        memcpy(rec.q, side ? bx + 3 * f : y, sizeof rec.q);
        ok = all_push(w, &rec, side, side ? br[f].feature : 7u, side ? 7u : br[f].feature);
    }
    free(h.c);
    free(tl);
    free(best);
    free(bx);
    free(br);
    return ok;
}
