/* SPDX-License-Identifier: MIT */
/* t_stop's promise (ccd/ccd.h): a query whose toi (searched whole) is at most t_stop gets the same
 * answer with t_stop, bit for bit; one whose toi is later, or that has none, gets no hit at or
 * before t_stop. Mesh CCD (src/meshccd/) passes t_stop = its earliest toi so far + the tolerance,
 * which depends on the order it meets the pairs in, so its answer depends on that order unless
 * this holds. Every query of the generated families and of the kept CSV queries (the benchmark's
 * samples, and the step through the layers of `ttd bench ccd --mesh-only`), at delta 0 and 1e-6,
 * with t_stop at the toi itself, just after it, toi + t_tol / 2, + t_tol, + 2 t_tol, further on and
 * 1; and before the toi (just before, halfway, 0) and on a grid where it has none. Then that a
 * search with t_stop stops before the exact work on a coplanarity root that lies well after t_stop
 * (the proved-free prefix, ccd_search_impl.h): one interval, and no contact isolated after t_stop;
 * and the same for motion in one plane (the prefixes before a condition's root and of a quarter)
 * and a contact just after t_stop (the prefix's second step). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ccd/ccd.h"
#include "test_macros.h"

#define TEST_RAND_SEED 0x9e3779b97f4a7c15ull
#include "test_rand.h"
#include "ccd_families.h"

typedef struct counts {
    size_t queries, hits, checks;
} counts;

static int same(const ttd_ccd_result *a, const ttd_ccd_result *b)
{
    return a->hit == b->hit && a->flags == b->flags && memcmp(&a->toi, &b->toi, sizeof a->toi) == 0 &&
           memcmp(&a->gap, &b->gap, sizeof a->gap) == 0;
}

static int check_query(int kind, const double x0[12], const double x1[12], double delta, counts *c)
{
    ttd_ccd_params p = ttd_ccd_default_params();
    p.delta = delta;
    ttd_ccd_result whole, r;
    ttd_ccd_query(kind, x0, x1, &p, &whole);
    ++c->queries;
    const double tol = p.t_tol;
    if (whole.hit && whole.toi <= 1) {
        ++c->hits;
        const double t = whole.toi;
        const double after[] = {t, nextafter(t, 2.0), t + 0.5 * tol, t + tol, t + 2 * tol, t + 0.01, 0.5 * (t + 1), 1};
        for (size_t i = 0; i < sizeof after / sizeof after[0]; ++i) {
            p.t_stop = after[i];
            ttd_ccd_query(kind, x0, x1, &p, &r);
            ++c->checks;
            ENSURE_MSG(same(&r, &whole), "kind %d delta %g: toi %.17g searched whole, with t_stop %.17g: hit %d toi %.17g",
                       kind, delta, t, after[i], r.hit, r.toi);
        }
        const double before[] = {nextafter(t, -1.0), 0.5 * t, t - tol, 0};
        for (size_t i = 0; i < sizeof before / sizeof before[0]; ++i) {
            if (!(before[i] < t) || before[i] < 0)
                continue;
            p.t_stop = before[i];
            ttd_ccd_query(kind, x0, x1, &p, &r);
            ++c->checks;
            ENSURE_MSG(!(r.hit && r.toi <= before[i]), "kind %d delta %g: toi %.17g searched whole, with t_stop %.17g: toi %.17g",
                       kind, delta, t, before[i], r.toi);
        }
    } else {
        const double grid[] = {0, 0.117, 0.25, 0.5, 0.9, 1};
        for (size_t i = 0; i < sizeof grid / sizeof grid[0]; ++i) {
            p.t_stop = grid[i];
            ttd_ccd_query(kind, x0, x1, &p, &r);
            ++c->checks;
            ENSURE_MSG(!(r.hit && r.toi <= grid[i]), "kind %d delta %g: no hit searched whole, with t_stop %.17g: toi %.17g",
                       kind, delta, grid[i], r.toi);
        }
    }
    return 0;
}

static int check_set(const qset *s, counts *c)
{
    static const double deltas[] = {0, 1e-6};
    for (size_t d = 0; d < 2; ++d)
        for (size_t q = 0; q < s->n; ++q)
            if (check_query(s->kind, s->x0 + 12 * q, s->x1 + 12 * q, deltas[d], c))
                return 1;
    return 0;
}

static int check_file(const char *path, const qset *s, void *ctx)
{
    (void)path;
    return check_set(s, ctx);
}

/* Two queries whose first interval the directions cannot prove (they touch at t_c): a vertex
 * through a face's interior (certified contact, its root isolated exactly) and an edge sliding
 * across another as it passes its plane (the conditions change sign on [0, 1]: a cut at f's
 * root, then the piece before it tested). Searched whole: the contact, at most t_c. With t_stop
 * 0.1: no hit and one interval (before the prefix, the first isolated the root, hit at t_c, and
 * the second tested [0, lo] after the cut, two intervals). Each also through check_query. */
static int stops_before_exact_work(counts *c)
{
    /* vertex (0.25, 0.25, 1) -> (0.25, 0.25, -0.6) onto the triangle z = 0: t_c = 1 / 1.6 */
    const double vf0[12] = {0.25, 0.25, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0};
    const double vf1[12] = {0.25, 0.25, -0.6, 0, 0, 0, 1, 0, 0, 0, 1, 0};
    /* edge (-2, 0, 1)-(-1, 0, 1) -> (2, 0, -1)-(3, 0, -1) across (0.5, -1, 0)-(0.5, 1, 0): at
     * t = 0.5 it spans x in [0, 1] at z = 0: t_c = 0.5 */
    const double ee0[12] = {-2, 0, 1, -1, 0, 1, 0.5, -1, 0, 0.5, 1, 0};
    const double ee1[12] = {2, 0, -1, 3, 0, -1, 0.5, -1, 0, 0.5, 1, 0};
    const struct {
        int kind;
        const double *x0, *x1;
        double tc;
    } q[2] = {{TTD_CCD_VF, vf0, vf1, 0.625}, {TTD_CCD_EE, ee0, ee1, 0.5}};
    for (int i = 0; i < 2; ++i) {
        ttd_ccd_params p = ttd_ccd_default_params();
        ttd_ccd_result whole, r;
        ttd_ccd_query(q[i].kind, q[i].x0, q[i].x1, &p, &whole);
        ENSURE_MSG(whole.hit == 1 && whole.toi <= q[i].tc && whole.toi > q[i].tc - 1e-9,
                   "query %d: whole search hit %u toi %.17g, contact at %g", i, whole.hit, whole.toi, q[i].tc);
        p.t_stop = 0.1;
        ttd_ccd_query(q[i].kind, q[i].x0, q[i].x1, &p, &r);
        ENSURE_MSG(r.hit == 0 && r.evals == 1, "query %d, t_stop 0.1: hit %u toi %.17g, %u intervals", i, r.hit, r.toi,
                   r.evals);
        for (int d = 0; d < 2; ++d)
            if (check_query(q[i].kind, q[i].x0, q[i].x1, d ? 1e-6 : 0, c))
                return 1;
    }
    return 0;
}

/* Motion in one plane (f = 0 throughout: no root of f to cut at): edge b sweeping across edge a,
 * which it meets at t_c. (1) b crosses a's line beyond a's end at first (a contact condition < 0
 * at t = 0, its first root at t_c = 2/3): the prefix before the condition's root. (2) b parallel to
 * a at t = 0 (every condition 0 there) and turning as it comes down onto a at t_c = 2/3: the
 * prefix of a quarter. With t_stop 0.1: no hit after one interval (before these prefixes, the
 * search formed the exact polynomials and cut at the condition's root, or halved [0, 1], and took
 * two). (3) The vertex through the face of stops_before_exact_work with t_stop 0.6, past 7/8 of
 * the way to its contact at 0.625: the prefix's second step (to 63/64 of the way) takes it past
 * t_stop, so no hit after one interval (before, the contact isolated exactly: a hit at 0.625). */
static int stops_in_prefix_steps(counts *c)
{
    const double cr0[12] = {0, 0, 0, 1, 0, 0, 2, -1, 0, 2, 1, 0};
    const double cr1[12] = {0, 0, 0, 1, 0, 0, 0.5, -1, 0, 0.5, 1, 0};
    const double pa0[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    const double pa1[12] = {0, 0, 0, 1, 0, 0, 0.2, -0.5, 0, 1.2, 0.7, 0};
    const double vf0[12] = {0.25, 0.25, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0};
    const double vf1[12] = {0.25, 0.25, -0.6, 0, 0, 0, 1, 0, 0, 0, 1, 0};
    const struct {
        int kind;
        const double *x0, *x1;
        double tc, t_stop;
    } q[3] = {{TTD_CCD_EE, cr0, cr1, 2.0 / 3, 0.1}, {TTD_CCD_EE, pa0, pa1, 2.0 / 3, 0.1}, {TTD_CCD_VF, vf0, vf1, 0.625, 0.6}};
    for (int i = 0; i < 3; ++i) {
        ttd_ccd_params p = ttd_ccd_default_params();
        ttd_ccd_result whole, r;
        ttd_ccd_query(q[i].kind, q[i].x0, q[i].x1, &p, &whole);
        ENSURE_MSG(whole.hit == 1 && whole.toi <= q[i].tc && whole.toi > q[i].tc - 1e-9,
                   "query %d: whole search hit %u toi %.17g, contact at %g", i, whole.hit, whole.toi, q[i].tc);
        p.t_stop = q[i].t_stop;
        ttd_ccd_query(q[i].kind, q[i].x0, q[i].x1, &p, &r);
        ENSURE_MSG(r.hit == 0 && r.evals == 1, "query %d, t_stop %g: hit %u toi %.17g, %u intervals", i, q[i].t_stop,
                   r.hit, r.toi, r.evals);
        for (int d = 0; d < 2; ++d)
            if (check_query(q[i].kind, q[i].x0, q[i].x1, d ? 1e-6 : 0, c))
                return 1;
    }
    return 0;
}

int main(void)
{
    counts c = {0, 0, 0};
    if (stops_before_exact_work(&c) || stops_in_prefix_steps(&c))
        return 1;
    for (int fam = 0; fam < F_COUNT; ++fam)
        for (int kind = 1; kind <= 2; ++kind) {
            qset s = make_set(fam, kind, 200);
            const int bad = check_set(&s, &c);
            free(s.x0), free(s.x1);
            if (bad) {
                fprintf(stderr, "  in family %s\n", family_name[fam]);
                return 1;
            }
        }
    size_t files = 0;
    if (walk_csv(TTD_CCD_DATA, check_file, &c, &files) || walk_csv(TTD_LAYER_STEP, check_file, &c, &files))
        return 1;
    ENSURE(files >= 4);
    printf("test_ccd_tstop: %zu queries (%zu hits) in the families and %zu CSV files, %zu searches with t_stop: "
           "same answer where toi <= t_stop, none before t_stop otherwise\n",
           c.queries, c.hits, files, c.checks);
    return 0;
}
