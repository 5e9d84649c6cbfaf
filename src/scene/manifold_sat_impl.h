/* SPDX-License-Identifier: MIT */
/* Section 5b: the penetration depth of a pair of convex solids by separating axes, one point of
 * the manifold at that depth along the separating direction. Part of a body pair's manifold
 * (scene/manifold_impl.h, which includes it once per precision; docs/scenes.md, section 5b).
 *
 * The points of one body inside the other measure how far each lies from the other's surface,
 * which is less than the shortest translation that separates the bodies wherever the deepest
 * point of the overlap is not a vertex or on an edge (rods crossing deeper than half their
 * thickness, a body nested in another). For two convex bodies that translation is exact and
 * cheap: the smallest, over unit directions n, of h_i(n) + h_j(-n) (h: the support function,
 * the largest n.x over the body's vertices), reached on a face normal of the Minkowski
 * difference: a face normal of either body, or the cross product of a real edge of each whose
 * arcs of normals cross on the unit sphere (the Gauss map test). For such an edge pair the
 * edges themselves are the supporting features, so its depth is n.(a0 - b0) without a search. */

/* A pair's depth is sought only where this many operations suffice: faces of each against the
 * other's vertices, plus edge pairs (an icosphere of 80 triangles against another: about 2e4). */
#define SAT_BUDGET ((double)(1u << 22))

/* One convex body's data for the search, in world coordinates (double). */
typedef struct sat_body {
    double *x;       /* 3 nw: one vertex per place */
    uint32_t *vtri;  /* nw: a triangle with that vertex */
    uint8_t *vbit;   /* nw: the vertex's corner of it, as a feature bit */
    size_t nw;
    double *fn;      /* 4 nt: each triangle's unit outward normal and offset (0 0 0 0: none) */
    size_t nt;
    uint32_t *edge;  /* 2 ne: (triangle << 2 | k) of each real edge, and the triangle across */
    size_t ne;
    double c[3];     /* the mean of the vertices: inside a convex body */
} sat_body;

static void sat_body_free(sat_body *b)
{
    free(b->x);
    free(b->vtri);
    free(b->vbit);
    free(b->fn);
    free(b->edge);
}

/* Whether body id's mesh, as the solid sees it (inward meshes turned out), has only convex and
 * flat edges and is one piece: then the closed surface bounds one convex body (to the flat
 * angle). Each piece of a closed surface whose edges are all convex is a sphere (Euler
 * characteristic V - E + F = 2, with E = 3F/2), so one piece is exactly 2 V - F = 4 over the
 * places in use; two convex pieces in one mesh (4, or 3 where they share a place) would
 * otherwise be searched as their hull, whose depth is not theirs. */
static int sat_convex(const struct ttd_scene *s, uint32_t id, size_t *ne)
{
    const struct ttd_mesh *m = s->body[id].mesh;
    ttd_mesh_edges view;
    const ttd_mesh_edges *E = ttd_mesh_edges_seen(ttd_mesh_edges_made(m), 1, &view);
    size_t n = 0;
    for (size_t t = 0; t < m->nt; ++t)
        for (int k = 0; k < 3; ++k) {
            const int cl = ttd_edge_class(E, (uint32_t)t, k);
            if (cl == TTD_EDGE_CONVEX)
                ++n;
            else if (cl != TTD_EDGE_FLAT)
                return 0;
        }
    size_t places = 0;
    for (size_t pl = 0; pl < E->nw; ++pl)
        places += E->ring_start[pl] < E->ring_start[pl + 1];
    if (2 * places != m->nt + 4)
        return 0;
    *ne = n / 2;
    return 1;
}

/* Body id's vertices (one per place), face planes and real edges into *b. 0 out of memory. */
static int sat_body_make(const struct ttd_scene *s, uint32_t id, size_t ne, sat_body *b)
{
    const struct ttd_mesh *m = s->body[id].mesh;
    ttd_mesh_edges view;
    const ttd_mesh_edges *E0 = ttd_mesh_edges_made(m), *E = ttd_mesh_edges_seen(E0, 1, &view);
    memset(b, 0, sizeof *b);
    b->x = malloc(3 * (E->nw + 1) * sizeof *b->x);
    b->vtri = malloc((E->nw + 1) * sizeof *b->vtri);
    b->vbit = malloc(E->nw + 1);
    b->fn = malloc(4 * m->nt * sizeof *b->fn);
    b->edge = malloc(2 * (ne + 1) * sizeof *b->edge);
    if (!b->x || !b->vtri || !b->vbit || !b->fn || !b->edge) {
        sat_body_free(b);
        return 0;
    }
    double c[3] = {0, 0, 0};
    for (uint32_t pl = 0; pl < E->nw; ++pl) {
        if (!(E->ring_start[pl] < E->ring_start[pl + 1]))
            continue;
        uint32_t tri;
        const uint32_t v = place_vertex(E, m->tris, pl, &tri);
        real x[3];
        body_vertex(s, id, v, x);
        unsigned bit = 1;
        for (int k = 0; k < 3; ++k)
            if (m->tris[3 * (size_t)tri + (size_t)k] == v) {
                bit = 1u << k;
                break;
            }
        for (int r = 0; r < 3; ++r) {
            b->x[3 * b->nw + (size_t)r] = (double)x[r];
            c[r] += (double)x[r];
        }
        b->vtri[b->nw] = tri;
        b->vbit[b->nw++] = (uint8_t)bit;
    }
    for (int r = 0; r < 3; ++r)
        b->c[r] = b->nw ? c[r] / (double)b->nw : 0;
    const double sign = E0->inward ? -1 : 1; /* the solid's outward side */
    b->nt = m->nt;
    for (size_t t = 0; t < m->nt; ++t) {
        real w[9];
        world_triangle(s, id, (uint32_t)t, w);
        double e1[3], e2[3], n[3], u[3];
        for (int r = 0; r < 3; ++r) {
            e1[r] = (double)w[3 + r] - (double)w[r];
            e2[r] = (double)w[6 + r] - (double)w[r];
        }
        cross3d(e1, e2, n);
        double *f = b->fn + 4 * t;
        if (!unit3(n, u)) {
            f[0] = f[1] = f[2] = f[3] = 0;
            continue;
        }
        for (int r = 0; r < 3; ++r)
            f[r] = sign * u[r];
        f[3] = f[0] * (double)w[0] + f[1] * (double)w[1] + f[2] * (double)w[2];
    }
    for (size_t t = 0; t < m->nt && b->ne < ne; ++t)
        for (int k = 0; k < 3; ++k) {
            const uint32_t u = E->across[3 * t + (size_t)k];
            if (ttd_edge_class(E, (uint32_t)t, k) == TTD_EDGE_CONVEX && u != TTD_NO_TRIANGLE && u > t &&
                b->ne < ne) {
                b->edge[2 * b->ne] = (uint32_t)t << 2 | (uint32_t)k;
                b->edge[2 * b->ne++ + 1] = u;
            }
        }
    return 1;
}

/* The smallest n.x over b's vertices, and which. */
static double sat_low(const sat_body *b, const double n[3], size_t *at)
{
    double lo = HUGE_VAL;
    *at = 0;
    for (size_t v = 0; v < b->nw; ++v) {
        const double d = dot3d(n, b->x + 3 * v);
        if (d < lo) {
            lo = d;
            *at = v;
        }
    }
    return lo;
}

/* The ends of real edge e of body id (world, double), its triangle and index. */
static void sat_edge(const struct ttd_scene *s, uint32_t id, const sat_body *b, size_t e, double p[3], double q[3],
                     uint32_t *t, int *k)
{
    *t = b->edge[2 * e] >> 2;
    *k = (int)(b->edge[2 * e] & 3);
    real w[9];
    world_triangle(s, id, *t, w);
    const int k1 = (*k + 1) % 3;
    for (int r = 0; r < 3; ++r) {
        p[r] = (double)w[3 * *k + r];
        q[r] = (double)w[3 * k1 + r];
    }
}

/* The closest points of lines p + s e and q + t f, s and t kept in [0, 1], into x and y. */
static void sat_lines(const double p[3], const double e[3], const double q[3], const double f[3], double x[3],
                      double y[3])
{
    double r[3];
    for (int k = 0; k < 3; ++k)
        r[k] = p[k] - q[k];
    const double a = dot3d(e, e), b = dot3d(e, f), c = dot3d(f, f), d = dot3d(e, r), g = dot3d(f, r);
    const double den = a * c - b * b;
    double s = den > 0 ? (b * g - c * d) / den : 0;
    s = s < 0 ? 0 : s > 1 ? 1 : s;
    double t = c > 0 ? (b * s + g) / c : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    for (int k = 0; k < 3; ++k) {
        x[k] = p[k] + s * e[k];
        y[k] = q[k] + t * f[k];
    }
}

/* The triangle of body id and the feature of it nearest world point x (the image of the other
 * body's vertex on a face plane of id: on that face wherever the face is the support, whichever
 * triangle of a flat face holds it). 0 out of memory. */
static int sat_image(const struct ttd_scene *s, const ttd_engine_config *cfg, uint32_t id, const double x[3],
                     uint32_t *tri, unsigned *feat)
{
    const real xr[3] = {(real)x[0], (real)x[1], (real)x[2]};
    ttd_point_result r;
    if (!edge_depth(s, cfg, id, xr, &r))
        return 0;
    *tri = r.triangle;
    *feat = r.feature;
    return 1;
}

/* Solid pair (i, j), both convex and small enough (SAT_BUDGET): its penetration depth D and
 * separating direction n, the direction in which j leaves i by D (into w->sat_n). Where D
 * exceeds the depth of the pair's deepest point so far (its points from w->all[before]) by more
 * than FEATURE_TOL of the larger radius (the seed's window), one point: body i's point p and
 * body j's q with p - q = D n, distance -D, pushed into w->all with inside = 2 (normal n). Else a
 * vertex or an edge's point already measures the depth (a box sunk face first): those points
 * within the window of D stay, their normal n (inside = 2). *added: whether a point was pushed.
 * 0 out of memory. */
static int solid_sat(const struct ttd_scene *s, const ttd_engine_config *cfg, uint32_t i, uint32_t j, size_t before,
                     manifold_work *w, int *added)
{
    *added = 0;
    size_t nei, nej;
    if (!sat_convex(s, i, &nei) || !sat_convex(s, j, &nej))
        return 1;
    const struct ttd_mesh *mi = s->body[i].mesh, *mj = s->body[j].mesh;
    const ttd_mesh_edges *Ei = ttd_mesh_edges_made(mi), *Ej = ttd_mesh_edges_made(mj);
    if ((double)mi->nt * (double)Ej->nw + (double)mj->nt * (double)Ei->nw + (double)nei * (double)nej > SAT_BUDGET)
        return 1;
    sat_body A, B;
    if (!sat_body_make(s, i, nei, &A))
        return 0;
    if (!sat_body_make(s, j, nej, &B)) {
        sat_body_free(&A);
        return 0;
    }
    /* the best axis: kind 0 a face of i (t), 1 a face of j (t), 2 edge ea of i and eb of j */
    double best = HUGE_VAL, bn[3] = {0, 0, 1};
    int kind = -1;
    size_t bt = 0, bv = 0, bea = 0, beb = 0;
    for (int side = 0; side < 2; ++side) {
        const sat_body *F = side ? &B : &A, *V = side ? &A : &B;
        size_t hint = 0;
        for (size_t t = 0; t < F->nt; ++t) {
            const double *f = F->fn + 4 * t;
            if (f[0] == 0 && f[1] == 0 && f[2] == 0)
                continue;
            size_t at, top;
            /* a face of i: j leaves along f by max over i - min over j; a face of j: along -f by
               max over j - min over i (the face's own plane where the body is convex; from the
               vertices, so that a flat edge bent within the flat angle makes no axis too short).
               Both bounded below by the face's plane against any vertex of the other body, so
               faces turned away from it are passed over without a search (the last face's
               lowest vertex as that vertex), and by the face's plane against the other's
               support before the face's own body is searched. */
            if (!(f[3] - dot3d(f, V->x + 3 * hint) < best))
                continue;
            const double mf[3] = {-f[0], -f[1], -f[2]}, low = sat_low(V, f, &at);
            hint = at;
            if (!(f[3] - low < best))
                continue;
            const double D = -sat_low(F, mf, &top) - low;
            if (D < best) {
                best = D;
                kind = side;
                bt = t;
                bv = at;
                for (int r = 0; r < 3; ++r)
                    bn[r] = side ? -f[r] : f[r];
            }
        }
    }
    /* each real edge of j: its two normals turned over (the Minkowski difference i - j), c and
       d, and d x c, formed once */
    double *arc = malloc(9 * (B.ne + 1) * sizeof *arc);
    if (arc == NULL) {
        sat_body_free(&A);
        sat_body_free(&B);
        return 0;
    }
    for (size_t eb = 0; eb < B.ne; ++eb) {
        const uint32_t tb = B.edge[2 * eb] >> 2, ub = B.edge[2 * eb + 1];
        double *g = arc + 9 * eb;
        for (int r = 0; r < 3; ++r) {
            g[r] = -B.fn[4 * (size_t)tb + (size_t)r];
            g[3 + r] = -B.fn[4 * (size_t)ub + (size_t)r];
        }
        cross3d(g + 3, g, g + 6);
    }
    for (size_t ea = 0; ea < A.ne; ++ea) {
        const uint32_t ta = A.edge[2 * ea] >> 2, ua = A.edge[2 * ea + 1];
        const double *a = A.fn + 4 * (size_t)ta, *b = A.fn + 4 * (size_t)ua;
        double bxa[3];
        cross3d(b, a, bxa);
        for (size_t eb = 0; eb < B.ne; ++eb) {
            const double *c = arc + 9 * eb, *d = c + 3, *dxc = c + 6;
            const double cba = dot3d(c, bxa), dba = dot3d(d, bxa);
            if (!(cba * dba < 0))
                continue; /* the arcs do not cross: no face of the difference */
            const double adc = dot3d(a, dxc), bdc = dot3d(b, dxc);
            if (!(adc * bdc < 0 && cba * bdc > 0))
                continue;
            double p0[3], p1[3], q0[3], q1[3], e[3], f[3], n[3], u[3];
            uint32_t t0;
            int k0;
            sat_edge(s, i, &A, ea, p0, p1, &t0, &k0);
            sat_edge(s, j, &B, eb, q0, q1, &t0, &k0);
            for (int r = 0; r < 3; ++r) {
                e[r] = p1[r] - p0[r];
                f[r] = q1[r] - q0[r];
            }
            cross3d(e, f, n);
            if (!unit3(n, u))
                continue; /* parallel edges: their planes are faces' */
            if (dot3d(u, a) + dot3d(u, b) < 0) /* out of i, within its edge's arc */
                for (int r = 0; r < 3; ++r)
                    u[r] = -u[r];
            /* the overlap along u from the supports, not from the edges: where the arcs only
               touch (bodies turned alike: arcs meeting at their ends) rounding can pass the test
               for edges that do not support the bodies along u, and their n.(a0 - b0) would be
               too small. From the supports it is never below the depth. */
            /* the edges' ends are vertices of the bodies, so the supports' overlap is at least
               the edges' own: no better where that is not */
            if (!(dot3d(u, p0) - dot3d(u, q0) < best))
                continue;
            const double mu[3] = {-u[0], -u[1], -u[2]};
            size_t at_a, at_b;
            const double D = -sat_low(&A, mu, &at_a) - sat_low(&B, u, &at_b);
            if (D < best) {
                best = D;
                /* the edges' closest points where they support the bodies along u, else j's
                   vertex deepest along -u (as for a face of i) */
                const double De = dot3d(u, p0) - dot3d(u, q0);
                kind = fabs(De - D) <= 0x1p-40 * (fabs(D) + fabs(dot3d(u, p0)) + fabs(dot3d(u, q0))) ? 2 : 0;
                bt = SIZE_MAX;
                bea = ea;
                beb = eb;
                bv = at_b;
                memcpy(bn, u, sizeof bn);
            }
        }
    }
    free(arc);
    int ok = 1;
    const double window = FEATURE_TOL * fmax(mi->radius, mj->radius);
    double have = 0; /* the depth of the pair's deepest point so far */
    for (size_t k = before; k < w->all_n; ++k)
        have = fmax(have, -(double)w->all[k].c.distance);
    if (kind >= 0 && best > 0 && !(best > have + window) && isfinite(best)) {
        /* a vertex or an edge's point already at the depth: those points stay, with the pair's
           direction as their normal (a point of an edge equally near two faces of the other has
           either face's normal out of that body, not always one that separates them) */
        memcpy(w->sat_n, bn, sizeof bn);
        for (size_t k = before; k < w->all_n; ++k)
            if (-(double)w->all[k].c.distance >= best - window)
                w->all[k].inside = 2;
    }
    if (kind >= 0 && best > have + window && isfinite(best)) {
        double p[3], q[3];
        uint32_t ti, tj;
        unsigned fi, fj;
        if (kind == 0) { /* j's vertex bv below i's face bt, or below i's support plane along bn */
            for (int r = 0; r < 3; ++r) {
                q[r] = B.x[3 * bv + (size_t)r];
                p[r] = q[r] + best * bn[r];
            }
            ti = bt == SIZE_MAX ? 0 : (uint32_t)bt;
            fi = 7;
            ok = sat_image(s, cfg, i, p, &ti, &fi);
            tj = B.vtri[bv];
            fj = B.vbit[bv];
        } else if (kind == 1) { /* i's vertex bv below j's face bt */
            for (int r = 0; r < 3; ++r) {
                p[r] = A.x[3 * bv + (size_t)r];
                q[r] = p[r] - best * bn[r];
            }
            ti = A.vtri[bv];
            fi = A.vbit[bv];
            tj = (uint32_t)bt;
            fj = 7;
            ok = sat_image(s, cfg, j, q, &tj, &fj);
        } else {
            double p0[3], p1[3], q0[3], q1[3], e[3], f[3];
            int ki, kj;
            sat_edge(s, i, &A, bea, p0, p1, &ti, &ki);
            sat_edge(s, j, &B, beb, q0, q1, &tj, &kj);
            for (int r = 0; r < 3; ++r) {
                e[r] = p1[r] - p0[r];
                f[r] = q1[r] - q0[r];
            }
            sat_lines(p0, e, q0, f, p, q);
            fi = 1u << ki | 1u << ((ki + 1) % 3);
            fj = 1u << kj | 1u << ((kj + 1) % 3);
        }
        if (!ok) {
            sat_body_free(&A);
            sat_body_free(&B);
            return 0;
        }
        ttd_scene_contact rec = {i, j, ti, tj, (real)-best, {0, 0, 0}, {0, 0, 0}};
        for (int r = 0; r < 3; ++r) {
            rec.p[r] = (real)p[r];
            rec.q[r] = (real)q[r];
        }
        memcpy(w->sat_n, bn, sizeof bn);
        ok = all_push(w, &rec, 2, fi, fj);
        *added = ok;
    }
    sat_body_free(&A);
    sat_body_free(&B);
    return ok;
}
