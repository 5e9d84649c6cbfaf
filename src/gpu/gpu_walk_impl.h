/* SPDX-License-Identifier: MIT */
/* Mesh against mesh under one pose, the walk one CUDA thread runs (gpu_kernels_impl.cuh's pose
 * kernels, compiled per precision by gpu_d.cu and gpu_f.cu) and the tests' cuda-host row runs on
 * the host (tests/cuda_host/), from this one source, precision-generic. Included after
 * simd/kernel_exact.h and kernel_node.h for one precision with TTDW_USE_CUDA (one lane); every
 * function is TTDW_FN (__host__ __device__ under nvcc), and nothing here allocates: the walk's
 * stack and candidate buffer are fixed arrays.
 *
 * What it computes is the CPU's (src/mesh/query_impl.h, ttd_mesh_distance_d / ttd_mesh_collide_d
 * on surfaces, rel_tol 0): the minimum of the exact kernel's distance over every triangle pair
 * (b's triangle moved by the caller's pose), or whether some pair is within the margin. The
 * same pieces in the same arithmetic: the pose's frames and rounding margin in double
 * (qpose_make), the boxes' views (box_query), the node test (kernel_node.h), the pair screen and
 * the exact kernel (kernel_exact.h, one lane), the winning pair's full result. Only the order
 * differs: the CPU walks overlapping boxes first and then the rest best first, from a heap;
 * here one depth-first walk, children nearest last on a fixed stack, candidate pairs gathered in
 * a small buffer and sent through the kernel one at a time. Items are dropped only when their
 * bound exceeds the limit by the margin that covers all rounding, so no pair within the final
 * minimum (or within the margin) is ever skipped, in any order: the distance is the same
 * minimum of the same kernel values, the same bits, and a collision's verdict the same. Which of
 * several equally near pairs is reported (and so its points and features), the witness pair of a
 * collision, and the counts of node and pair tests depend on the order and may differ.
 *
 * On the device, a warp's threads walk different poses; when one of them must send its
 * candidates through the kernel, every thread that holds some does too (GW_ANY: a warp vote), so
 * that the kernel's 1,500 double operations a pair run converged. The vote changes only the order
 * of work. On the host the vote is a pseudo-random draw (gw_walk.vote), so the tests run the
 * same walk in several orders and require the same answers. */

#include "core/rotation.h"
#include "ttd/ttd_gpu.h"

/* The walk's stack: a walk opens one box of an item into at most TTD_NODE_WIDTH children, each a
 * level deeper, so the stack never holds more than 1 + (TTD_NODE_WIDTH - 1) (h_a + h_b) items,
 * h the trees' heights (gw_tree_height); the entries refuse meshes whose heights do not fit. */
#define GW_STACK 256
/* Candidate pairs waiting for the kernel: a leaf facing a triangle adds up to TTD_NODE_WIDTH at
 * once, so the buffer is drained to at most GW_CAND - TTD_NODE_WIDTH before an item is opened. */
#define GW_CAND (2 * TTD_NODE_WIDTH)

/* The largest coordinate a mesh query works on (mesh/mesh.h, ttd_mesh_range) and the most a
 * pose's R may differ from a rotation (src/api/mesh_api.c, TTD_POSE_TOLERANCE): the tests
 * require these to be the CPU's. */
#ifdef TTD_PRECISION_DOUBLE
#define GW_RANGE 0x1p508
typedef ttd_mesh_result_d gw_mesh_result;
#else
#define GW_RANGE 0x1p60
typedef ttd_mesh_result_f gw_mesh_result;
#endif
#define GW_POSE_TOLERANCE 1e-6

#ifdef __CUDA_ARCH__
#define GW_ANY(w, x) __any_sync(__activemask(), (x))
#else
#define GW_ANY(w, x) ((x) || gw_host_vote(w))
#endif

/* One mesh as the walk reads it: the CPU's arrays as they are (struct ttd_mesh), in device
 * memory on the device. */
typedef struct gw_mesh {
    const ttd_node *nodes;
    const real *verts;
    const uint32_t *tris;
    double origin[3];
    double radius;
    int32_t height; /* node levels below the root's box (gw_tree_height) */
} gw_mesh;

typedef struct gw_item {
    int32_t an, bn, as, bs; /* a's box: slot as of node an; b's likewise */
    real lb2;               /* squared lower bound between the two boxes */
} gw_item;

/* A pose's frames (query_impl.h's qpose, b mapped into a's frame). */
typedef struct gw_pose {
    real r[9], t[3];   /* b's frame about its origin -> a's frame about its origin */
    real ri[9], ti[3]; /* and back */
    real pose[12];     /* the caller's */
    real delta;        /* the rounding margin of the bounds */
} gw_pose;

typedef struct gw_walk {
    int collide;
    real limit, limit2; /* the kernel's bound; items past limit2 are dropped */
    int found;          /* distance: a pair within the bound; collide: a witness */
    uint32_t ta, tb;
    uint32_t node_tests;
    uint64_t pair_tests;
    int overflow;       /* the stack was too small (the entries' height check prevents it) */
    uint64_t vote;      /* host only: 0, or the state of the vote's draw */
} gw_walk;

/* The host's stand-in for a warp vote: with vote != 0, true one time in four (xorshift). */
TTDW_FN int gw_host_vote(gw_walk *w)
{
    if (w->vote == 0)
        return 0;
    w->vote ^= w->vote << 13;
    w->vote ^= w->vote >> 7;
    w->vote ^= w->vote << 17;
    return (w->vote & 3u) == 0;
}

/* Node levels below slot 0 of node 0 (host only: at upload). 0 for a mesh of one triangle. */
TTDW_FN int32_t gw_tree_height(const ttd_node *nodes, int32_t n)
{
    int32_t h = 0;
    for (int j = 0; j < nodes[n].count; ++j)
        if (nodes[n].child[j] >= 0) {
            const int32_t c = 1 + gw_tree_height(nodes, nodes[n].child[j]);
            h = c > h ? c : h;
        }
    return h;
}

/* How far the 3x3 part of pose p is from a rotation, max |R^T R - I|, or -1 when a number is
 * not finite or det R <= 0 (src/api/mesh_api.c's pose_defect: both through core/rotation.h). */
TTDW_FN double gw_pose_defect(const real *pose)
{
    double p[12];
    for (int j = 0; j < 12; ++j) {
        p[j] = (double)pose[j];
        if (!(p[j] - p[j] == 0)) /* NaN or inf */
            return -1;
    }
    const double r[9] = {p[0], p[1], p[2], p[4], p[5], p[6], p[8], p[9], p[10]};
    return ttd_rotation_det(r) > 0 ? ttd_rotation_defect(r) : -1;
}

/* The CPU's pose check (ttd_check_poses): the defect, or -1 when the CPU entry refuses the pose
 * (not a rotation within the tolerance, or b moved past the coordinate range). */
TTDW_FN double gw_pose_check(const gw_mesh *b, const real *pose)
{
    const double defect = gw_pose_defect(pose);
    if (!(defect >= 0 && defect <= GW_POSE_TOLERANCE))
        return -1;
    double c2 = 0;
    for (int r = 0; r < 3; ++r) {
        const double c = (double)pose[4 * r] * b->origin[0] + (double)pose[4 * r + 1] * b->origin[1] +
                         (double)pose[4 * r + 2] * b->origin[2] + (double)pose[4 * r + 3];
        c2 += c * c;
    }
    const double reach = (sqrt(c2) + (1 + 2 * defect) * b->radius) * (1 + 8 * DBL_EPSILON);
    return reach > GW_RANGE ? -1 : defect;
}

/* The pose's frames and rounding margin: query_impl.h's qpose_make without a's pose. */
TTDW_FN void gw_pose_make(const gw_mesh *ma, const gw_mesh *mb, const real pose[12], double defect, gw_pose *P)
{
    double r[9], tb[3];
    for (int i = 0; i < 12; ++i)
        P->pose[i] = pose[i];
    for (int i = 0; i < 3; ++i) {
        tb[i] = (double)pose[4 * i + 3];
        for (int k = 0; k < 3; ++k)
            r[3 * i + k] = (double)pose[4 * i + k];
    }
    double t[3], tn = 0;
    for (int i = 0; i < 3; ++i) {
        t[i] = tb[i] - ma->origin[i];
        for (int k = 0; k < 3; ++k)
            t[i] += r[3 * i + k] * mb->origin[k];
        tn += t[i] * t[i];
    }
    for (int i = 0; i < 3; ++i) {
        P->t[i] = (real)t[i];
        double ti = 0;
        for (int k = 0; k < 3; ++k) {
            P->r[3 * i + k] = (real)r[3 * i + k];
            P->ri[3 * i + k] = (real)r[3 * k + i];
            ti -= r[3 * k + i] * t[k];
        }
        P->ti[i] = (real)ti;
    }
    double oa = 0, ob = 0, tc = 0;
    for (int i = 0; i < 3; ++i) {
        oa += ma->origin[i] * ma->origin[i];
        ob += mb->origin[i] * mb->origin[i];
        tc += (double)pose[4 * i + 3] * (double)pose[4 * i + 3];
    }
    const double S = sqrt(tn) + 2 * (ma->radius + mb->radius) + sqrt(oa) + sqrt(ob) + sqrt(tc);
    P->delta = (real)((64 * (double)TTD_REAL_EPS + 4 * defect) * S);
}

/* The node test's view of box (node, slot j), the other side's frame mapped in by (r, t):
 * query_impl.h's box_query. */
TTDW_FN void gw_box_query(const ttd_node *node, int j, const real r[9], const real t[3], ttd_box_query *q)
{
    real u[9], d[3];
    for (int i = 0; i < 9; ++i)
        u[i] = node->u[i][j];
    for (int i = 0; i < 3; ++i) {
        q->e[i] = node->e[i][j];
        d[i] = t[i] - node->c[i][j];
    }
    for (int i = 0; i < 3; ++i) {
        for (int k = 0; k < 3; ++k)
            q->m[3 * i + k] = (u[3 * i] * r[k] + u[3 * i + 1] * r[3 + k]) + u[3 * i + 2] * r[6 + k];
        q->v[i] = (u[3 * i] * d[0] + u[3 * i + 1] * d[1]) + u[3 * i + 2] * d[2];
    }
}

TTDW_FN real gw_box_size(const ttd_node *node, int j)
{
    return node->e[0][j] + node->e[1][j] + node->e[2][j];
}

/* The items' limit from the kernel's bound (query_impl.h's walk_set_limit, rel_tol 0). */
TTDW_FN void gw_set_limit(gw_walk *w, const gw_pose *P, real limit)
{
    w->limit = limit;
    const real l = (limit + P->delta) / (real)1;
    const real floor2 = 64 * TTD_REAL_MIN;
    w->limit2 = l * l > floor2 ? l * l : floor2;
}

/* x -> pose x, per coordinate ((r0 x + r1 y) + r2 z) + t. */
TTDW_FN void gw_pose_apply(const real p[12], const real *x, real *out)
{
    for (int i = 0; i < 3; ++i)
        out[i] = ((p[4 * i] * x[0] + p[4 * i + 1] * x[1]) + p[4 * i + 2] * x[2]) + p[4 * i + 3];
}

/* Pair (ta, tb) as the kernel takes it: a's triangle as given, b's moved by the pose. */
TTDW_FN void gw_pair_coords(const gw_mesh *a, const gw_mesh *b, const gw_pose *P, uint32_t ta, uint32_t tb, real s[9],
                            real t[9])
{
    for (int k = 0; k < 3; ++k) {
        const real *x = a->verts + 3 * (size_t)a->tris[3 * (size_t)ta + k];
        s[3 * k] = x[0];
        s[3 * k + 1] = x[1];
        s[3 * k + 2] = x[2];
        gw_pose_apply(P->pose, b->verts + 3 * (size_t)b->tris[3 * (size_t)tb + k], t + 3 * k);
    }
}

/* One candidate through the screen and the exact kernel with the walk's limit as its bound (the
 * CPU's kernel_exact on one pair), and what the CPU's flush does with the answer. */
TTDW_FN void gw_pair(const gw_mesh *a, const gw_mesh *b, const gw_pose *P, gw_walk *w, uint32_t ta, uint32_t tb)
{
    real s[9], t[9], d;
    gw_pair_coords(a, b, P, ta, tb, s, t);
    ++w->pair_tests;
    if (w->limit < TTD_REAL_MAX && kx_screen(s, t) > w->limit)
        return; /* farther than the bound: the CPU's kernel answers its lower bound, > limit */
    kx_run_dist(1, s, t, &d);
    if (w->collide) {
        if (d <= w->limit) {
            w->found = 1;
            w->ta = ta;
            w->tb = tb;
        }
    } else if (d < w->limit || (!w->found && d <= w->limit)) {
        w->found = 1;
        w->ta = ta;
        w->tb = tb;
        gw_set_limit(w, P, d);
    }
}

/* Whether the bounding spheres are farther apart than the limit (query_impl.h's spheres_apart). */
TTDW_FN int gw_spheres_apart(const gw_mesh *a, const gw_mesh *b, const gw_pose *P, const gw_walk *w)
{
    double t2 = 0;
    for (int i = 0; i < 3; ++i)
        t2 += (double)P->t[i] * (double)P->t[i];
    const double gap = sqrt(t2) - (a->radius + b->radius) - (double)P->delta;
    return gap > 0 && gap * gap > (double)w->limit2;
}

/* Opens item it (within the limit): query_impl.h's expand for two meshes. The larger box is
 * opened with one node test; a leaf facing a triangle adds its pairs within the limit to the
 * candidates; other children within the limit are pushed nearest last (the deepest overlap last
 * among overlapping ones). Returns the items pushed. */
TTDW_FN int gw_expand(const gw_mesh *a, const gw_mesh *b, const gw_pose *P, gw_walk *w, const gw_item *it,
                      gw_item *dst, uint32_t *ca_out, uint32_t *cb_out, int *nc)
{
    const ttd_node *na = a->nodes + it->an, *nb = b->nodes + it->bn;
    const int32_t ca = na->child[it->as], cb = nb->child[it->bs];
    if (ca < 0 && cb < 0) { /* two triangles (meshes of one triangle) */
        ca_out[*nc] = (uint32_t)(-1 - ca);
        cb_out[(*nc)++] = (uint32_t)(-1 - cb);
        return 0;
    }
    const int open_b = ca < 0 || (cb >= 0 && gw_box_size(nb, it->bs) > gw_box_size(na, it->as));
    ttd_box_query q;
    if (open_b)
        gw_box_query(na, it->as, P->r, P->t, &q);
    else
        gw_box_query(nb, it->bs, P->ri, P->ti, &q);
    const ttd_node *y = open_b ? b->nodes + cb : a->nodes + ca;
    real lb2[TTD_NODE_WIDTH], sep[TTD_NODE_WIDTH];
    node_test(&q, y, lb2, sep);
    ++w->node_tests;
    if (y->child[0] < 0 && (open_b ? ca : cb) < 0) { /* a leaf facing a triangle */
        const int32_t t0 = open_b ? -1 - ca : -1 - cb;
        for (int j = 0; j < y->count; ++j) {
            if (lb2[j] > w->limit2)
                continue;
            const int32_t t = -1 - y->child[j];
            ca_out[*nc] = (uint32_t)(open_b ? t0 : t);
            cb_out[(*nc)++] = (uint32_t)(open_b ? t : t0);
        }
        return 0;
    }
    real key[TTD_NODE_WIDTH];
    int n = 0;
    for (int j = 0; j < y->count; ++j) {
        if (lb2[j] > w->limit2)
            continue;
        gw_item c = *it;
        if (open_b) {
            c.bn = cb;
            c.bs = j;
        } else {
            c.an = ca;
            c.as = j;
        }
        c.lb2 = lb2[j];
        const real kj = lb2[j] > 0 ? lb2[j] : sep[j];
        int at = n++;
        while (at > 0 && key[at - 1] < kj) {
            dst[at] = dst[at - 1];
            key[at] = key[at - 1];
            --at;
        }
        dst[at] = c;
        key[at] = kj;
    }
    return n;
}

/* The walk of one pose from the root's boxes: opens items and sends candidates through the kernel
 * until the stack and the buffer are empty, a collision is found, or the minimum is 0. */
TTDW_FN void gw_walk_run(const gw_mesh *a, const gw_mesh *b, const gw_pose *P, gw_walk *w)
{
    gw_item stack[GW_STACK];
    uint32_t cta[GW_CAND], ctb[GW_CAND];
    int top = 1, nc = 0;
    stack[0].an = stack[0].bn = stack[0].as = stack[0].bs = 0;
    stack[0].lb2 = 0;
    for (;;) {
        if (w->found && (w->collide || w->limit == 0))
            break;
        const int must = nc > GW_CAND - TTD_NODE_WIDTH || (nc > 0 && top == 0);
        if (nc > 0 && GW_ANY(w, must)) {
            --nc;
            gw_pair(a, b, P, w, cta[nc], ctb[nc]);
            continue;
        }
        if (top == 0)
            break;
        const gw_item it = stack[--top];
        if (it.lb2 > w->limit2)
            continue;
        if (top + TTD_NODE_WIDTH > GW_STACK) {
            w->overflow = 1;
            break;
        }
        top += gw_expand(a, b, P, w, &it, stack + top, cta, ctb, &nc);
    }
}

/* Pose `pose` of b against a: the minimum distance into *r, as ttd_mesh_distance_d gives it
 * (surfaces, rel_tol 0, upper_bound >= 0). A pose the CPU entry refuses gets a NaN distance,
 * no triangles, and TTD_GPU_POSE_REFUSED in flags. vote: gw_walk.vote (0 on the device). */
TTDW_FN void gw_distance_pose(const gw_mesh *a, const gw_mesh *b, const real *pose, real upper_bound, uint64_t vote,
                              gw_mesh_result *r)
{
    gw_walk w;
    memset(&w, 0, sizeof w);
    memset(r, 0, sizeof *r);
    const double defect = gw_pose_check(b, pose);
    gw_pose P;
    if (defect >= 0) {
        gw_pose_make(a, b, pose, defect, &P);
        w.ta = w.tb = UINT32_MAX;
        w.vote = vote;
        gw_set_limit(&w, &P, upper_bound);
        if (!gw_spheres_apart(a, b, &P, &w))
            gw_walk_run(a, b, &P, &w);
    }
    r->node_tests = w.node_tests;
    r->pair_tests = w.pair_tests;
    if (defect < 0 || w.overflow) {
        const real nan = (real)NAN;
        r->distance = nan;
        for (int k = 0; k < 3; ++k)
            r->p[k] = r->q[k] = nan;
        r->tri_a = r->tri_b = UINT32_MAX;
        r->flags = TTD_GPU_POSE_REFUSED;
        return;
    }
    if (!w.found) {
        r->distance = (real)INFINITY;
        r->tri_a = r->tri_b = UINT32_MAX;
        r->flags = TTD_MESH_ABOVE_BOUND;
        return;
    }
    /* the pair's full result: query_impl.h's distance_result */
    real s[9], t[9];
    gw_pair_coords(a, b, &P, w.ta, w.tb, s, t);
    ttd_result full;
    const ttd_out out = {NULL, NULL, &full};
    kx_run(1, s, t, &out);
    r->distance = full.distance;
    r->tri_a = w.ta;
    r->tri_b = w.tb;
    r->feature_a = full.feature_p;
    r->feature_b = full.feature_q;
    for (int k = 0; k < 3; ++k) {
        r->p[k] = full.p[k];
        r->q[k] = full.distance == 0 ? full.p[k] : full.q[k];
    }
    r->flags = full.distance == 0 ? TTD_MESH_INTERSECTING : 0;
}

/* Pose `pose` of b against a: whether some pair is within margin (>= 0), into *c, as
 * ttd_mesh_collide_d gives it (surfaces). A refused pose gets hit = TTD_GPU_POSE_REFUSED (non-zero:
 * a caller testing hit treats it as a collision) and no triangles. */
TTDW_FN void gw_collide_pose(const gw_mesh *a, const gw_mesh *b, const real *pose, real margin, uint64_t vote,
                             ttd_collision *c)
{
    gw_walk w;
    memset(&w, 0, sizeof w);
    const double defect = gw_pose_check(b, pose);
    if (defect >= 0) {
        gw_pose P;
        gw_pose_make(a, b, pose, defect, &P);
        w.collide = 1;
        w.ta = w.tb = UINT32_MAX;
        w.vote = vote;
        gw_set_limit(&w, &P, margin);
        if (!gw_spheres_apart(a, b, &P, &w))
            gw_walk_run(a, b, &P, &w);
    }
    const int refused = defect < 0 || w.overflow;
    c->hit = refused ? TTD_GPU_POSE_REFUSED : (uint32_t)w.found;
    c->tri_a = refused ? UINT32_MAX : w.ta;
    c->tri_b = refused ? UINT32_MAX : w.tb;
    c->node_tests = w.node_tests;
    c->pair_tests = w.pair_tests;
}
