/* SPDX-License-Identifier: MIT */
/* A scene query that runs out of memory, then a good one (docs/scenes.md, section 9: the scene
 * keeps its queries' scratch, and a failed query must leave it fit for the next). The scene
 * queries are compiled into this test with TTD_SCENE_ALLOC_HOOK (tests/CMakeLists.txt): each of
 * their malloc, calloc and realloc calls goes through the hooks below, which fail the one the test
 * names. For each query (collide, contacts, manifold K = 4 and K = 0, distance), each precision,
 * 1 and 2 threads, on a fresh scene and on one whose scratch a smaller query made, and for every
 * allocation that query makes in turn: the query with that allocation failed returns
 * TTD_ERR_OUT_OF_MEMORY with no items (or, had it done without that memory, the right answer),
 * and the next query on the same scene gives the bytes a fresh scene gives. The scene: two boxes
 * face on face (flat contact: the pieces' corners), two solid balls crossing (inside points, the
 * separating axis, regions) and a ball beside a box. */
#include <math.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "boxes.h" /* test_mesh_of */
#include "meshes.h"
#include "test_macros.h"
#include <ttd/ttd.h>

/* ---- the hooks (scene/body_impl.h) ------------------------------------------------------------ */

static atomic_long hook_calls, hook_fail_at; /* the allocations so far; the one to fail (0: none) */
static atomic_int hook_fired;

static int hook_fail(void)
{
    const long c = atomic_fetch_add(&hook_calls, 1) + 1;
    if (c != atomic_load(&hook_fail_at))
        return 0;
    atomic_store(&hook_fired, 1);
    return 1;
}

void *ttd_scene_hook_malloc(size_t n)
{
    return hook_fail() ? NULL : malloc(n);
}

void *ttd_scene_hook_calloc(size_t n, size_t size)
{
    return hook_fail() ? NULL : calloc(n, size);
}

void *ttd_scene_hook_realloc(void *p, size_t n)
{
    return hook_fail() ? NULL : realloc(p, n);
}

static void hook_arm(long fail_at)
{
    atomic_store(&hook_calls, 0);
    atomic_store(&hook_fired, 0);
    atomic_store(&hook_fail_at, fail_at);
}

/* ---- the scene ---------------------------------------------------------------------------------- */

#define NBODY 5
#define MARGIN 0.02

static ttd_gen_mesh G[2]; /* a box, a ball */
static double pose[NBODY][12];
static int mesh_of[NBODY], solid[NBODY];

static void place(int id, int mesh, double angle, double x, double y, double z, int is_solid)
{
    const double c = cos(angle), s = sin(angle);
    const double p[12] = {c, -s, 0, x, s, c, 0, y, 0, 0, 1, z};
    memcpy(pose[id], p, sizeof p);
    mesh_of[id] = mesh;
    solid[id] = is_solid;
}

static int make_bodies(void)
{
    ENSURE(ttd_gen_mesh_cube(&G[0]) == 0 && ttd_gen_normalize(&G[0]) == 0);
    ENSURE(ttd_gen_icosphere(2, &G[1]) == 0 && ttd_gen_normalize(&G[1]) == 0);
    double lo[2][3], hi[2][3];
    for (int k = 0; k < 2; ++k)
        ENSURE(ttd_gen_mesh_bounds(&G[k], lo[k], hi[k]) == 0);
    const double box = hi[0][2] - lo[0][2], ball = hi[1][0] - lo[1][0];
    place(0, 0, 0, 0, 0, 0, 0);
    place(1, 0, 0.3, 0.1 * box, 0, box + 0.004, 0);             /* on box 0, turned: flat contact */
    place(2, 1, 0, 3 * box, 0, 0, 1);                            /* two solid balls crossing */
    place(3, 1, 0.2, 3 * box + 0.7 * ball, 0.1 * ball, 0, 1);
    place(4, 1, 0, -0.5 * (box + ball) - 0.005, 0.05, 0.02, 0); /* a ball beside box 0 */
    return 0;
}

typedef struct world {
    ttd_mesh *mesh[2];
    int bytes;
} world;

static int make_meshes(world *W, int bytes)
{
    W->bytes = bytes;
    for (int k = 0; k < 2; ++k) {
        const ttd_gen_mesh *g = &G[k];
        W->mesh[k] = test_mesh_of(bytes, g->verts, g->nv, g->tris, g->nt);
        ENSURE(W->mesh[k] != NULL);
    }
    return 0;
}

static ttd_scene *make_scene(const world *W)
{
    ttd_scene *s;
    if ((W->bytes == 8 ? ttd_scene_create_d(&s) : ttd_scene_create_f(&s)) != TTD_OK)
        return NULL;
    for (int id = 0; id < NBODY; ++id) {
        float pf[12];
        for (int r = 0; r < 12; ++r)
            pf[r] = (float)pose[id][r];
        uint32_t got;
        const ttd_status st = W->bytes == 8 ? ttd_scene_add_d(s, W->mesh[mesh_of[id]], pose[id], &got)
                                            : ttd_scene_add_f(s, W->mesh[mesh_of[id]], pf, &got);
        if (st != TTD_OK || (solid[id] && ttd_scene_set_solid(s, got, 1) != TTD_OK)) {
            ttd_scene_destroy(s);
            return NULL;
        }
    }
    return s;
}

/* ---- the queries ---------------------------------------------------------------------------------- */

enum { COLLIDE, CONTACTS, MANIFOLD_4, MANIFOLD_0, DISTANCE, KINDS };
static const char *const kind_name[KINDS] = {"collide", "contacts", "manifold K = 4", "manifold K = 0", "distance"};

/* A query's answer as bytes (the test's own memory: not hooked). */
typedef struct answer {
    ttd_status st;
    size_t n;               /* items (DISTANCE: 1 + NBODY records) */
    unsigned char *bytes;   /* n items */
    size_t size;            /* an item's bytes */
} answer;

static void answer_free(answer *A)
{
    free(A->bytes);
    memset(A, 0, sizeof *A);
}

static int ask(ttd_scene *s, int bytes, int kind, int threads, double margin, answer *A)
{
    memset(A, 0, sizeof *A);
    ttd_options o = ttd_default_options();
    o.threads = threads;
    const int d = bytes == 8;
    const float mf = (float)margin;
    if (kind == DISTANCE) {
        ttd_scene_contact_d cd[1 + NBODY];
        ttd_scene_contact_f cf[1 + NBODY];
        A->st = d ? ttd_scene_distance_d(&o, s, margin, cd, cd + 1) : ttd_scene_distance_f(&o, s, mf, cf, cf + 1);
        A->n = 1 + NBODY;
        A->size = d ? sizeof cd[0] : sizeof cf[0];
        ENSURE((A->bytes = malloc(A->n * A->size)) != NULL);
        memcpy(A->bytes, d ? (void *)cd : (void *)cf, A->n * A->size);
        return 0;
    }
    ttd_scene_array out = {0};
    switch (kind) {
    case COLLIDE:
        A->st = d ? ttd_scene_collide_d(&o, s, margin, &out) : ttd_scene_collide_f(&o, s, mf, &out);
        A->size = sizeof(ttd_scene_hit);
        break;
    case CONTACTS:
        A->st = d ? ttd_scene_contacts_d(&o, s, margin, &out) : ttd_scene_contacts_f(&o, s, mf, &out);
        A->size = d ? sizeof(ttd_scene_contact_d) : sizeof(ttd_scene_contact_f);
        break;
    default: {
        const size_t K = kind == MANIFOLD_4 ? 4 : 0;
        A->st = d ? ttd_scene_manifold_d(&o, s, margin, K, &out) : ttd_scene_manifold_f(&o, s, mf, K, &out);
        A->size = d ? sizeof(ttd_scene_point_d) : sizeof(ttd_scene_point_f);
    }
    }
    A->n = out.count;
    ENSURE((A->bytes = malloc(A->n ? A->n * A->size : 1)) != NULL);
    if (A->n)
        memcpy(A->bytes, out.data, A->n * A->size);
    ttd_scene_array_free(&out);
    return 0;
}

static int same(const answer *x, const answer *y)
{
    return x->st == y->st && x->n == y->n && x->size == y->size && memcmp(x->bytes, y->bytes, x->n * x->size) == 0;
}

/* Every allocation of the query in turn failed, on a fresh scene (before = 0) or after a query at
 * a margin a tenth as large (before = 1), then the query again on that scene against want. */
static int fail_each(const world *W, int kind, int threads, int before, const answer *want, size_t counts[2])
{
    for (long f = 1;; ++f) {
        ttd_scene *s = make_scene(W);
        ENSURE(s != NULL);
        answer a, b;
        if (before) {
            hook_arm(0);
            ENSURE(ask(s, W->bytes, kind, threads, MARGIN / 10, &a) == 0 && a.st == TTD_OK);
            answer_free(&a);
        }
        hook_arm(f);
        ENSURE(ask(s, W->bytes, kind, threads, MARGIN, &a) == 0);
        const int fired = atomic_load(&hook_fired);
        hook_arm(0);
        if (!fired) { /* f is past the query's allocations: it ran whole */
            ENSURE(same(&a, want));
            answer_free(&a);
            ttd_scene_destroy(s);
            ENSURE_MSG(f > 1, "%s: no allocation to fail", kind_name[kind]);
            return 0;
        }
        /* a query that did without the memory must still be right */
        ENSURE_MSG(a.st == TTD_ERR_OUT_OF_MEMORY ? a.n == 0 || kind == DISTANCE : same(&a, want),
                   "%s, %s, %d threads, %s: allocation %ld failed: status %d, %zu items", W->bytes == 8 ? "double" : "float",
                   kind_name[kind], threads, before ? "after a smaller query" : "a fresh scene", f, (int)a.st, a.n);
        counts[a.st == TTD_ERR_OUT_OF_MEMORY]++;
        ENSURE(ask(s, W->bytes, kind, threads, MARGIN, &b) == 0);
        ENSURE_MSG(same(&b, want),
                   "%s, %s, %d threads, %s: after allocation %ld failed, the next query gave status %d, %zu items; "
                   "a fresh scene %zu",
                   W->bytes == 8 ? "double" : "float", kind_name[kind], threads,
                   before ? "after a smaller query" : "a fresh scene", f, (int)b.st, b.n, want->n);
        answer_free(&a);
        answer_free(&b);
        ttd_scene_destroy(s);
    }
}

static int nomem_then_good(void)
{
    ENSURE(make_bodies() == 0);
    for (int bytes = 8; bytes >= 4; bytes -= 4) {
        world W;
        ENSURE(make_meshes(&W, bytes) == 0);
        for (int kind = 0; kind < KINDS; ++kind) {
            answer want;
            ttd_scene *s = make_scene(&W);
            ENSURE(s != NULL);
            hook_arm(0);
            ENSURE(ask(s, bytes, kind, 1, MARGIN, &want) == 0 && want.st == TTD_OK);
            ttd_scene_destroy(s);
            ENSURE_MSG(kind == DISTANCE || want.n > 0, "%s: no items", kind_name[kind]);
            size_t counts[2] = {0, 0}; /* failures the query did without; out of memory */
            for (int threads = 1; threads <= 2; ++threads)
                for (int before = 0; before < 2; ++before)
                    ENSURE(fail_each(&W, kind, threads, before, &want, counts) == 0);
            printf("    %s, %s: %zu items; %zu allocations failed: %zu out of memory, %zu done without\n",
                   bytes == 8 ? "double" : "float", kind_name[kind], want.n, counts[0] + counts[1], counts[1], counts[0]);
            ENSURE(counts[1] > 0);
            answer_free(&want);
        }
        for (int k = 0; k < 2; ++k)
            ttd_mesh_destroy(W.mesh[k]);
    }
    for (int k = 0; k < 2; ++k)
        ttd_gen_mesh_free(&G[k]);
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(nomem_then_good);
    TEST_MAIN_END();
}
