/* SPDX-License-Identifier: MIT */
/* The scene queries, precision-generic: scene/query_d.c and query_f.c compile this once each.
 *
 * A query sweeps the bodies' world boxes for the eligible pairs that may come within its margin
 * (scene/scene.c), then hands each such body pair to the mesh traversal (mesh/mesh.h) with both
 * bodies' world poses: the tree works in body i's frame, the exact kernel on both triangles moved
 * into the world, as a brute force over all triangle pairs in the world frame would. Body pairs
 * are spread over the threads, each walked by one thread (one pair's answer does not depend on
 * which), and their answers are joined in (i, j) order: results do not depend on the threads.
 * docs/scenes.md has the design. */

/* The pose of body id in the scene's precision. */
static const real *body_pose(const struct ttd_scene *s, uint32_t id)
{
#ifdef TTD_PRECISION_DOUBLE
    return s->body[id].pose;
#else
    return s->body[id].pose_f;
#endif
}

/* How far from a rotation body j's pose in body i's frame, R_i^T R_j, may be: with R_i^T R_i =
 * I + E_i (entries within d_i), |R_i R_i^T - I| <= 3 d_i in norm, so the relative pose's entries
 * are within d_j + 3 d_i (1 + 3 d_j). */
static double pair_defect(const struct ttd_scene *s, uint32_t i, uint32_t j)
{
    const double di = s->body[i].defect, dj = s->body[j].defect;
    return dj + 3 * di * (1 + 3 * dj);
}

/* One thread per body pair: the mesh queries inside run on one thread each. */
static ttd_engine_config one_thread(const ttd_engine_config *cfg)
{
    ttd_engine_config c = *cfg;
    c.threads = 1;
    return c;
}

/* ---- collide and distance: one mesh query per body pair ------------------------------------ */

typedef struct pair_job {
    const ttd_engine_config *cfg; /* one thread */
    struct ttd_scene *s;
    const scene_pair *pairs;
    int mode;                     /* MODE_COLLIDE or MODE_DISTANCE */
    real limit;                   /* the margin, or the distance's bound */
    ttd_collision *hit;           /* collide: one per pair */
    ttd_mesh_result *dist;        /* distance: one per pair */
    /* the closest pair alone: the bound falls to the best distance so far (its bits: distances
     * are >= 0, so their bit patterns order as they do), and no pair after the first at
     * distance 0 is needed (pairs come in (i, j) order: that one is the answer) */
    int closest_only;
    _Atomic uint64_t best_bits;
    atomic_size_t first_zero;
    atomic_int nomem;
} pair_job;

/* *x = min(*x, v), atomically. */
static void atomic_min_size(atomic_size_t *x, size_t v)
{
    size_t old = atomic_load(x);
    while (v < old && !atomic_compare_exchange_weak(x, &old, v))
        ;
}

static uint64_t real_bits(real x)
{
    double d = (double)x;
    uint64_t b;
    memcpy(&b, &d, sizeof b);
    return b;
}

static real bits_real(uint64_t b)
{
    double d;
    memcpy(&d, &b, sizeof d);
    return (real)d;
}

enum { MODE_COLLIDE, MODE_DISTANCE };

static void pair_task(void *ctx, size_t k, int worker)
{
    (void)worker;
    pair_job *J = ctx;
    const scene_pair *p = &J->pairs[k];
    const struct ttd_mesh *a = J->s->body[p->i].mesh, *b = J->s->body[p->j].mesh;
    const double defect = pair_defect(J->s, p->i, p->j);
    ttd_status st;
    if (J->mode == MODE_COLLIDE && J->closest_only && k > atomic_load_explicit(&J->first_zero, memory_order_relaxed)) {
        J->hit[k] = (ttd_collision){0, UINT32_MAX, UINT32_MAX, 0, 0}; /* after a touching pair: not needed */
        st = TTD_OK;
    } else if (J->mode == MODE_COLLIDE) {
        st = TTD_QUERY(collide)(J->cfg, a, b, 1, body_pose(J->s, p->j), body_pose(J->s, p->i), &defect, J->limit,
                                &J->hit[k]);
        if (st == TTD_OK && J->closest_only && J->hit[k].hit) {
            atomic_min_size(&J->first_zero, k);
        }
    } else if (J->closest_only && k > atomic_load_explicit(&J->first_zero, memory_order_relaxed)) {
        J->dist[k].distance = (real)INFINITY; /* after a pair at 0: not needed */
        J->dist[k].node_tests = 0;
        J->dist[k].pair_tests = 0;
        st = TTD_OK;
    } else {
        const real bound = J->closest_only ? bits_real(atomic_load(&J->best_bits)) : J->limit;
        st = TTD_QUERY(distance)(J->cfg, a, b, 1, body_pose(J->s, p->j), body_pose(J->s, p->i), &defect, bound, 0,
                                 &J->dist[k]);
        const real d = J->dist[k].distance;
        if (st == TTD_OK && J->closest_only && d <= bound) {
            uint64_t old = atomic_load(&J->best_bits);
            const uint64_t mine = real_bits(d);
            while (mine < old && !atomic_compare_exchange_weak(&J->best_bits, &old, mine))
                ;
            if (d == 0) {
                atomic_min_size(&J->first_zero, k);
            }
        }
    }
    if (st != TTD_OK)
        atomic_store(&J->nomem, 1);
}

static ttd_status run_pairs(const ttd_engine_config *cfg, pair_job *J, size_t n)
{
    const ttd_engine_config one = one_thread(cfg);
    J->cfg = &one;
    atomic_init(&J->best_bits, real_bits(J->limit));
    atomic_init(&J->first_zero, SIZE_MAX);
    atomic_init(&J->nomem, 0);
    ttd_pool_tasks(J->s->pool, n, cfg->threads, pair_task, J);
    if (atomic_load(&J->nomem))
        return TTD_ERR_OUT_OF_MEMORY;
    ttd_scene_stats *t = &J->s->stats;
    t->body_pairs += n;
    for (size_t k = 0; k < n; ++k) {
        t->node_tests += J->mode == MODE_COLLIDE ? J->hit[k].node_tests : J->dist[k].node_tests;
        t->pair_tests += J->mode == MODE_COLLIDE ? J->hit[k].pair_tests : J->dist[k].pair_tests;
    }
    return TTD_OK;
}

/* Room for n items of `size` bytes in a caller's array. */
static int array_reserve(ttd_scene_array *a, size_t n, size_t size)
{
    if (n <= a->capacity)
        return 1;
    size_t cap = a->capacity ? a->capacity : 64;
    while (cap < n)
        cap *= 2;
    void *v = realloc(a->data, cap * size);
    if (v == NULL)
        return 0;
    a->data = v;
    a->capacity = cap;
    return 1;
}

static ttd_status query_collide(const ttd_engine_config *cfg, struct ttd_scene *s, real margin, ttd_scene_array *out)
{
    out->count = 0;
    s->stats = (ttd_scene_stats){0};
    scene_pair *pairs;
    size_t n;
    if (!ttd_scene_sweep(s, (double)margin, NULL, &pairs, &n))
        return TTD_ERR_OUT_OF_MEMORY;
    pair_job J = {.s = s, .pairs = pairs, .mode = MODE_COLLIDE, .limit = margin};
    J.hit = malloc((n ? n : 1) * sizeof *J.hit);
    ttd_status st = J.hit == NULL ? TTD_ERR_OUT_OF_MEMORY : run_pairs(cfg, &J, n);
    size_t hits = 0;
    for (size_t k = 0; st == TTD_OK && k < n; ++k)
        hits += J.hit[k].hit != 0;
    if (st == TTD_OK && !array_reserve(out, hits, sizeof(ttd_scene_hit)))
        st = TTD_ERR_OUT_OF_MEMORY;
    for (size_t k = 0; st == TTD_OK && k < n; ++k)
        if (J.hit[k].hit)
            ((ttd_scene_hit *)out->data)[out->count++] =
                (ttd_scene_hit){pairs[k].i, pairs[k].j, J.hit[k].tri_a, J.hit[k].tri_b};
    free(J.hit);
    free(pairs);
    s->stats.results = out->count;
    if (st != TTD_OK)
        s->stats = (ttd_scene_stats){0};
    return st;
}

/* ---- contacts: every pair within the margin, per body pair ---------------------------------- */

typedef struct contact_job {
    const ttd_engine_config *cfg;
    struct ttd_scene *s;
    const scene_pair *pairs;
    real margin;
    ttd_mesh_contacts *sets;      /* one per worker, reused */
    ttd_scene_contact **found;    /* per pair: its contacts, sorted by triangles */
    size_t *nfound;
    uint64_t *tests;              /* per pair: node tests and pair tests */
    atomic_int nomem;
} contact_job;

static int scene_contact_cmp(const void *x, const void *y)
{
    const ttd_scene_contact *a = x, *b = y;
    if (a->tri_i != b->tri_i)
        return a->tri_i < b->tri_i ? -1 : 1;
    return (a->tri_j > b->tri_j) - (a->tri_j < b->tri_j);
}

/* The contacts of body pair p within margin, sorted by (tri_i, tri_j), into a new array. */
static int pair_contacts(const ttd_engine_config *cfg, struct ttd_scene *s, const scene_pair *p, real margin,
                         ttd_mesh_contacts *set, ttd_scene_contact **out, size_t *n, uint64_t tests[2])
{
    *out = NULL;
    *n = 0;
    const double defect = pair_defect(s, p->i, p->j);
    if (TTD_QUERY(contacts)(cfg, s->body[p->i].mesh, s->body[p->j].mesh, 1, body_pose(s, p->j), body_pose(s, p->i),
                            &defect, margin, set) != TTD_OK)
        return 0;
    tests[0] = set->node_tests;
    tests[1] = set->pair_tests;
    if (set->count == 0)
        return 1;
    ttd_scene_contact *v = malloc(set->count * sizeof *v);
    if (v == NULL)
        return 0;
    for (size_t k = 0; k < set->count; ++k) {
        const ttd_mesh_contact *c = &set->pairs[k];
        v[k].i = p->i;
        v[k].j = p->j;
        v[k].tri_i = c->tri_a;
        v[k].tri_j = c->tri_b;
        v[k].distance = c->distance;
        memcpy(v[k].p, c->p, sizeof v[k].p);
        memcpy(v[k].q, c->q, sizeof v[k].q);
    }
    qsort(v, set->count, sizeof *v, scene_contact_cmp);
    *out = v;
    *n = set->count;
    return 1;
}

static void contact_task(void *ctx, size_t k, int worker)
{
    contact_job *J = ctx;
    if (!pair_contacts(J->cfg, J->s, &J->pairs[k], J->margin, &J->sets[worker], &J->found[k], &J->nfound[k],
                       J->tests + 2 * k))
        atomic_store(&J->nomem, 1);
}

/* Every eligible body pair within a margin and its contacts: pairs[0..n), with found[k] and
 * nfound[k] for pair k (sorted by triangles). */
typedef struct pair_contacts_set {
    scene_pair *pairs;
    size_t n;
    ttd_scene_contact **found;
    size_t *nfound;
} pair_contacts_set;

static void pair_contacts_free(pair_contacts_set *c)
{
    for (size_t k = 0; c->found != NULL && k < c->n; ++k)
        free(c->found[k]);
    free(c->found);
    free(c->nfound);
    free(c->pairs);
}

/* The set of every eligible body pair's contacts within margin (the caller frees it with
 * pair_contacts_free, whatever the status). */
static ttd_status all_contacts(const ttd_engine_config *cfg, struct ttd_scene *s, real margin, pair_contacts_set *c)
{
    *c = (pair_contacts_set){NULL, 0, NULL, NULL};
    if (!ttd_scene_sweep(s, (double)margin, NULL, &c->pairs, &c->n))
        return TTD_ERR_OUT_OF_MEMORY;
    const ttd_engine_config one = one_thread(cfg);
    const int workers = ttd_parallel_task_workers(c->n, cfg->threads);
    contact_job J = {&one, s, c->pairs, margin, calloc((size_t)workers, sizeof(ttd_mesh_contacts)),
                     calloc(c->n ? c->n : 1, sizeof(ttd_scene_contact *)), calloc(c->n ? c->n : 1, sizeof(size_t)),
                     calloc(2 * (c->n ? c->n : 1), sizeof(uint64_t)), 0};
    atomic_init(&J.nomem, J.sets == NULL || J.found == NULL || J.nfound == NULL || J.tests == NULL);
    if (!atomic_load(&J.nomem))
        ttd_pool_tasks(s->pool, c->n, cfg->threads, contact_task, &J);
    s->stats = (ttd_scene_stats){0};
    s->stats.body_pairs = c->n;
    for (size_t k = 0; J.tests != NULL && k < c->n; ++k) {
        s->stats.node_tests += J.tests[2 * k];
        s->stats.pair_tests += J.tests[2 * k + 1];
    }
    free(J.tests);
    for (int w = 0; J.sets != NULL && w < workers; ++w)
        TTD_CONTACTS_FREE(&J.sets[w]);
    free(J.sets);
    c->found = J.found;
    c->nfound = J.nfound;
    return atomic_load(&J.nomem) ? TTD_ERR_OUT_OF_MEMORY : TTD_OK;
}

static ttd_status query_contacts(const ttd_engine_config *cfg, struct ttd_scene *s, real margin,
                                 ttd_scene_array *out)
{
    out->count = 0;
    pair_contacts_set c;
    ttd_status st = all_contacts(cfg, s, margin, &c);
    size_t total = 0;
    for (size_t k = 0; st == TTD_OK && k < c.n; ++k)
        total += c.nfound[k];
    if (st == TTD_OK && !array_reserve(out, total, sizeof(ttd_scene_contact)))
        st = TTD_ERR_OUT_OF_MEMORY;
    for (size_t k = 0; st == TTD_OK && k < c.n; ++k) {
        if (c.nfound[k])
            memcpy((ttd_scene_contact *)out->data + out->count, c.found[k], c.nfound[k] * sizeof(ttd_scene_contact));
        out->count += c.nfound[k];
    }
    pair_contacts_free(&c);
    s->stats.results = out->count;
    if (st != TTD_OK)
        s->stats = (ttd_scene_stats){0};
    return st;
}

/* ---- manifolds: each body pair's contacts reduced to a few points --------------------------- */

/* Triangle tri of body id in the world, as the kernel sees it (9 reals). */
static void world_triangle(const struct ttd_scene *s, uint32_t id, uint32_t tri, real x[9])
{
    const struct ttd_mesh *m = s->body[id].mesh;
    const real *v = (const real *)m->verts, *pose = body_pose(s, id);
    for (int k = 0; k < 3; ++k) {
        const real *src = v + 3 * (size_t)m->tris[3 * (size_t)tri + (size_t)k];
        for (int r = 0; r < 3; ++r)
            x[3 * k + r] = ((pose[4 * r] * src[0] + pose[4 * r + 1] * src[1]) + pose[4 * r + 2] * src[2]) + pose[4 * r + 3];
    }
}

/* The unit normal of triangle x (0 when it has no area), and its centroid. */
static void triangle_normal(const real x[9], double n[3], double g[3])
{
    const double e1[3] = {(double)x[3] - (double)x[0], (double)x[4] - (double)x[1], (double)x[5] - (double)x[2]};
    const double e2[3] = {(double)x[6] - (double)x[0], (double)x[7] - (double)x[1], (double)x[8] - (double)x[2]};
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    const double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int r = 0; r < 3; ++r) {
        n[r] = len > 0 && isfinite(len) ? n[r] / len : 0;
        g[r] = ((double)x[r] + (double)x[3 + r] + (double)x[6 + r]) / 3;
    }
}

/* The direction of the edge of triangle x whose two vertices are the bits of f. */
static void edge_of(const real x[9], unsigned f, double e[3])
{
    const int a = (f & 1) ? 0 : 1, b = (f & 4) ? 2 : 1;
    for (int r = 0; r < 3; ++r)
        e[r] = (double)x[3 * b + r] - (double)x[3 * a + r];
}

static int bits3(unsigned f)
{
    return (int)(f & 1) + (int)((f >> 1) & 1) + (int)((f >> 2) & 1);
}

/* The normal of contact c, from body i towards body j: the direction from p to q when they
 * differ. Where they meet (d = 0) there is none; then, by where the contact lies on each
 * triangle (the exact method's features): across both edges where an edge of each crosses the
 * other; j's face normal where the contact lies inside j's face and not inside i's (a vertex or
 * an edge of i on a face of j: a box resting on an edge of another gets the face it rests on,
 * not the side face of the edge); i's face normal otherwise, or the other's when one has no
 * area; turned to point from i's triangle's centroid towards j's where that direction is
 * within 60 degrees of the normal, from i's body's box centre towards j's otherwise (coplanar
 * faces, crossing triangles side by side); where both triangles have no area, the direction between the centroids, else
 * between the boxes' centres, else +z. */
static void contact_normal(const struct ttd_scene *s, const ttd_scene_contact *c, double n[3])
{
    double d[3], len2 = 0;
    for (int r = 0; r < 3; ++r) {
        d[r] = (double)c->q[r] - (double)c->p[r];
        len2 += d[r] * d[r];
    }
    if (c->distance > 0 && len2 > 0) {
        const double len = sqrt(len2);
        for (int r = 0; r < 3; ++r)
            n[r] = d[r] / len;
        return;
    }
    real ti[9], tj[9];
    world_triangle(s, c->i, c->tri_i, ti);
    world_triangle(s, c->j, c->tri_j, tj);
    double ni[3], nj[3], gi[3], gj[3];
    triangle_normal(ti, ni, gi);
    triangle_normal(tj, nj, gj);
    ttd_result full;
    TTD_EXACT_PAIR(ti, tj, &full); /* where on each triangle the contact lies */
    const int has_i = ni[0] != 0 || ni[1] != 0 || ni[2] != 0, has_j = nj[0] != 0 || nj[1] != 0 || nj[2] != 0;
    const int use_j = has_j && (!has_i || (bits3(full.feature_q) == 3 && bits3(full.feature_p) < 3));
    double ne[3] = {0, 0, 0};
    if (bits3(full.feature_p) == 2 && bits3(full.feature_q) == 2) { /* two edges cross: across both */
        double ei[3], ej[3];
        edge_of(ti, full.feature_p, ei);
        edge_of(tj, full.feature_q, ej);
        ne[0] = ei[1] * ej[2] - ei[2] * ej[1];
        ne[1] = ei[2] * ej[0] - ei[0] * ej[2];
        ne[2] = ei[0] * ej[1] - ei[1] * ej[0];
        const double l = sqrt(ne[0] * ne[0] + ne[1] * ne[1] + ne[2] * ne[2]);
        for (int r = 0; r < 3; ++r)
            ne[r] = l > 0 && isfinite(l) ? ne[r] / l : 0;
    }
    const int use_edges = ne[0] != 0 || ne[1] != 0 || ne[2] != 0;
    const double *bi = s->box + 6 * (size_t)c->i, *bj = s->box + 6 * (size_t)c->j; /* their world boxes */
    double towards[3], t2 = 0, boxes[3], b2 = 0;
    for (int r = 0; r < 3; ++r) {
        towards[r] = gj[r] - gi[r];
        t2 += towards[r] * towards[r];
        boxes[r] = 0.5 * (bj[r] + bj[3 + r]) - 0.5 * (bi[r] + bi[3 + r]);
        b2 += boxes[r] * boxes[r];
    }
    if (!has_i && !has_j) {
        const double *dir = t2 > 0 ? towards : boxes;
        const double len = sqrt(t2 > 0 ? t2 : b2);
        for (int r = 0; r < 3; ++r)
            n[r] = len > 0 ? dir[r] / len : (r == 2 ? 1.0 : 0.0);
        return;
    }
    memcpy(n, use_edges ? ne : use_j ? nj : ni, 3 * sizeof *n);
    /* the sign: from i's triangle towards j's where that direction is within 60 degrees of the
     * normal either way; otherwise (coplanar faces, crossing triangles whose centroids sit side
     * by side) from i's body towards j's */
    double dot = n[0] * towards[0] + n[1] * towards[1] + n[2] * towards[2];
    if (!(fabs(dot) >= 0.5 * sqrt(t2)))
        dot = n[0] * boxes[0] + n[1] * boxes[1] + n[2] * boxes[2];
    if (dot < 0)
        for (int r = 0; r < 3; ++r)
            n[r] = -n[r];
}

/* Orders contacts deepest first: smaller distance, then triangles. */
static int depth_cmp(const void *x, const void *y)
{
    const ttd_scene_contact *a = x, *b = y;
    if (a->distance != b->distance)
        return a->distance < b->distance ? -1 : 1;
    return scene_contact_cmp(x, y);
}

/* Appends body pair's manifold: its n contacts (reordered here) reduced to at most max points:
 * the deepest, then repeatedly the contact whose point is farthest from every point kept (ties
 * to the earlier in depth order), until max points or none left at a new point: the deepest
 * contact and the spread of the region, as Hauser's clustering keeps, without repeated points,
 * in O(max n) and the same on every run. */
static int append_manifold(const struct ttd_scene *s, ttd_scene_contact *c, size_t n, real margin, size_t max,
                           ttd_scene_array *out)
{
    qsort(c, n, sizeof *c, depth_cmp);
    const size_t keep = max == 0 || max > n ? n : max;
    if (!array_reserve(out, out->count + keep, sizeof(ttd_scene_point)))
        return 0;
    double *far = malloc(n * sizeof *far); /* squared distance to the nearest kept point */
    unsigned char *taken = calloc(n, 1);
    if (far == NULL || taken == NULL) {
        free(far);
        free(taken);
        return 0;
    }
    for (size_t k = 0; k < n; ++k)
        far[k] = HUGE_VAL;
    size_t next = 0;
    for (size_t kept = 0; kept < keep; ++kept) {
        const ttd_scene_contact *x = &c[next];
        taken[next] = 1;
        ttd_scene_point *pt = (ttd_scene_point *)out->data + out->count++;
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
        /* the next: farthest from every point kept so far; none when every contact left is at a
         * point already kept (faces in contact give many pairs at the same points) */
        double best = 0;
        for (size_t k = 0; k < n; ++k) {
            if (taken[k])
                continue;
            double d2 = 0;
            for (int r = 0; r < 3; ++r) {
                /* the midpoint as a point would hold it: equal points are equal reals */
                const double a = (double)(real)(0.5 * (double)c[k].p[r] + 0.5 * (double)c[k].q[r]) - (double)pt->point[r];
                d2 += a * a;
            }
            far[k] = d2 < far[k] ? d2 : far[k];
            if (far[k] > best) {
                best = far[k];
                next = k;
            }
        }
        if (!(best > 0))
            break;
    }
    free(far);
    free(taken);
    return 1;
}

static ttd_status query_manifold(const ttd_engine_config *cfg, struct ttd_scene *s, real margin, size_t max_points,
                                 ttd_scene_array *out)
{
    out->count = 0;
    pair_contacts_set c;
    ttd_status st = all_contacts(cfg, s, margin, &c);
    for (size_t k = 0; st == TTD_OK && k < c.n; ++k)
        if (c.nfound[k] && !append_manifold(s, c.found[k], c.nfound[k], margin, max_points, out))
            st = TTD_ERR_OUT_OF_MEMORY;
    pair_contacts_free(&c);
    s->stats.results = out->count;
    if (st != TTD_OK) {
        out->count = 0;
        s->stats = (ttd_scene_stats){0};
    }
    return st;
}

/* ---- distance: the closest body pair, and each body's nearest ------------------------------ */

static ttd_scene_contact no_contact(uint32_t i)
{
    ttd_scene_contact c = {i, UINT32_MAX, UINT32_MAX, UINT32_MAX, (real)INFINITY, {0, 0, 0}, {0, 0, 0}};
    return c;
}

/* The record of body pair p at its minimum d, with its smallest pair of triangles at d (as body
 * `first` sees it: its own triangle first), from the contacts within d. */
static int pair_record(const ttd_engine_config *cfg, struct ttd_scene *s, const scene_pair *p, real d, uint32_t first,
                       ttd_scene_contact *rec)
{
    ttd_mesh_contacts set = {0};
    ttd_scene_contact *v;
    size_t n;
    const ttd_engine_config one = one_thread(cfg);
    uint64_t tests[2];
    const int ok = pair_contacts(&one, s, p, d, &set, &v, &n, tests);
    TTD_CONTACTS_FREE(&set);
    if (!ok)
        return 0;
    const int swap = first != p->i;
    size_t best = n;
    for (size_t k = 0; k < n; ++k) {
        if (v[k].distance != d)
            continue;
        if (best == n)
            best = k;
        else if (swap && (v[k].tri_j < v[best].tri_j || (v[k].tri_j == v[best].tri_j && v[k].tri_i < v[best].tri_i)))
            best = k;
        /* not swapped: v is sorted by (tri_i, tri_j), the first at d is the smallest */
    }
    if (best == n) { /* cannot happen: the distance query found a pair at d */
        free(v);
        return 0;
    }
    *rec = v[best];
    if (swap) {
        *rec = (ttd_scene_contact){p->j, p->i, v[best].tri_j, v[best].tri_i, d, {0, 0, 0}, {0, 0, 0}};
        memcpy(rec->p, v[best].q, sizeof rec->p);
        memcpy(rec->q, v[best].p, sizeof rec->q);
    }
    free(v);
    return 1;
}

static ttd_status query_distance(const ttd_engine_config *cfg, struct ttd_scene *s, real upper_bound,
                                 ttd_scene_contact *closest, ttd_scene_contact *nearest)
{
    *closest = no_contact(UINT32_MAX);
    s->stats = (ttd_scene_stats){0};
    const size_t nb = s->nbody;
    for (size_t id = 0; nearest != NULL && id < nb; ++id)
        nearest[id] = no_contact((uint32_t)id);
    /* nearest[] of the present bodies still open (beyond every margin tried) */
    unsigned char *open = nearest != NULL ? calloc(nb ? nb : 1, 1) : NULL;
    real *best = nearest != NULL ? malloc((nb ? nb : 1) * sizeof *best) : NULL;
    uint32_t *partner = nearest != NULL ? malloc((nb ? nb : 1) * sizeof *partner) : NULL;
    if (nearest != NULL && (open == NULL || best == NULL || partner == NULL)) {
        free(open);
        free(best);
        free(partner);
        return TTD_ERR_OUT_OF_MEMORY;
    }
    size_t nopen = 0;
    for (size_t id = 0; nearest != NULL && id < nb; ++id) {
        open[id] = s->body[id].mesh != NULL;
        nopen += open[id];
        best[id] = (real)INFINITY;
        partner[id] = UINT32_MAX;
    }
    /* margins: the bound, or growing ones until the answers are inside (every body pair within a
     * margin is examined, so a minimum at or below it is the minimum over all pairs) */
    const double extent = ttd_scene_extent(s);
    double margin = isfinite((double)upper_bound) ? (double)upper_bound : 1e-3 * extent;
    ttd_status st = TTD_OK;
    int closest_done = s->present < 2;
    real cbest = (real)INFINITY;
    size_t cpair_i = SIZE_MAX;
    scene_pair cpair = {0, 0};
    /* the closest pair alone: touching bodies are found sooner by collision at 0, which stops at
     * its first pair within 0, than by distance; the first touching pair in (i, j) order is the
     * answer, and no pair after it is needed */
    if (nearest == NULL && !closest_done) {
        scene_pair *pairs;
        size_t n;
        if (!ttd_scene_sweep(s, 0, NULL, &pairs, &n))
            return TTD_ERR_OUT_OF_MEMORY;
        pair_job J = {.s = s, .pairs = pairs, .mode = MODE_COLLIDE, .limit = 0, .closest_only = 1};
        J.hit = malloc((n ? n : 1) * sizeof *J.hit);
        st = J.hit == NULL ? TTD_ERR_OUT_OF_MEMORY : run_pairs(cfg, &J, n);
        const size_t z = atomic_load(&J.first_zero);
        if (st == TTD_OK && z < n) {
            cbest = 0;
            cpair = pairs[z];
            cpair_i = z;
            closest_done = 1;
        }
        free(J.hit);
        free(pairs);
    }
    while (st == TTD_OK && !(closest_done && nopen == 0)) {
        const int last = isfinite((double)upper_bound) || !(margin < extent) || !(margin > 0);
        const double m = last && !isfinite((double)upper_bound) ? HUGE_VAL : margin;
        scene_pair *pairs;
        size_t n;
        if (!ttd_scene_sweep(s, m, closest_done ? open : NULL, &pairs, &n)) {
            st = TTD_ERR_OUT_OF_MEMORY;
            break;
        }
        pair_job J = {.s = s, .pairs = pairs, .mode = MODE_DISTANCE,
                      .limit = isfinite(m) ? (real)m : (real)INFINITY, .closest_only = nearest == NULL};
        J.dist = malloc((n ? n : 1) * sizeof *J.dist);
        st = J.dist == NULL ? TTD_ERR_OUT_OF_MEMORY : run_pairs(cfg, &J, n);
        for (size_t k = 0; st == TTD_OK && k < n; ++k) {
            const real d = J.dist[k].distance;
            if (!(d <= J.limit))
                continue;
            if (!closest_done && d < cbest) { /* pairs come in (i, j) order: ties keep the first */
                cbest = d;
                cpair = pairs[k];
                cpair_i = k;
            }
            for (int side = 0; nearest != NULL && side < 2; ++side) {
                const uint32_t me = side ? pairs[k].j : pairs[k].i, other = side ? pairs[k].i : pairs[k].j;
                if (open[me] && (d < best[me] || (d == best[me] && other < partner[me]))) {
                    best[me] = d;
                    partner[me] = other;
                }
            }
        }
        free(J.dist);
        free(pairs);
        if (st != TTD_OK)
            break;
        if (cpair_i != SIZE_MAX)
            closest_done = 1;
        for (size_t id = 0; nearest != NULL && id < nb; ++id)
            if (open[id] && best[id] <= (real)m) {
                open[id] = 0;
                --nopen;
            }
        if (last || (closest_done && nopen == 0))
            break;
        margin *= 4;
    }
    if (st == TTD_OK && cpair_i != SIZE_MAX && !pair_record(cfg, s, &cpair, cbest, cpair.i, closest))
        st = TTD_ERR_OUT_OF_MEMORY;
    for (size_t id = 0; st == TTD_OK && nearest != NULL && id < nb; ++id) {
        if (partner[id] == UINT32_MAX)
            continue;
        const uint32_t o = partner[id];
        const scene_pair p = {id < o ? (uint32_t)id : o, id < o ? o : (uint32_t)id};
        if (!pair_record(cfg, s, &p, best[id], (uint32_t)id, &nearest[id]))
            st = TTD_ERR_OUT_OF_MEMORY;
    }
    free(open);
    free(best);
    free(partner);
    s->stats.results = st == TTD_OK && cpair_i != SIZE_MAX;
    if (st != TTD_OK)
        s->stats = (ttd_scene_stats){0};
    return st;
}
