/* SPDX-License-Identifier: MIT */
/* Contact regions of solid pairs that are not both convex (docs/scenes.md, section 5b, "contact
 * regions"; issue 32, item 1): every point below 0 of one overlap region carries one direction,
 * out of the other body, and keeps its exact depth. Cases: a plate through a ring's tube (two
 * regions), a square prism through the ring's hole with its four edges sunk into the tube's inner
 * wall (four regions, four directions), a rod through the tube, a box sunk into the ring's top, two
 * L beams crossing; double and float, K = 0 and 4.
 *
 * Reference, written here apart from the library: the overlap of the two solids sampled on a grid
 * of cells h = 0.01 (a cell centre inside both bodies by a ray's crossing parity, tests/ref_parity.h),
 * its components joined through the cells' faces; each manifold point below 0 belongs to the
 * component of the sampled cell nearest it (within 2 h). Checked per component C:
 *  - one direction: every point of C has the same normal, bit for bit, at K = 0, and K = 4's
 *    points of C have that normal too;
 *  - out of the other body: C's deepest point x (depth r; x is the point of the body inside the
 *    other, found by its distance to the other's surface) moved along the direction (j's point: +n,
 *    i's point: -n, the normal pointing from body i to body j) by r - delta is inside the other
 *    body and by r + delta outside it (parity), delta = 2e-3;
 *  - depth: every point's distance is minus its inside point's least distance to the other body's
 *    triangles (Ericson's closest point, tests/boxes.h), to 1e-9 (float 2e-5).
 * And the number of components with points, where the construction fixes it (plate 2, prism 4,
 * rod 1, box 1). Checked to fail: with every point its own normal (the code before: one region of
 * the plate, the rod and the prism carried several directions), with all of a pair's points one
 * region (the prism's regions then take one corner's direction, which leads into the tube at the
 * other three), and with the direction negated. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "boxes.h"
#include "meshes.h"
#include "pairs.h"
#include "ref_parity.h"
#include "solid_cases.h"
#include "test_macros.h"
#include <ttd/ttd.h>

#define HCELL 0.01 /* the reference's cells */
/* Out of the other body at a region's deepest point x (depth r, u the unit direction to its
 * partner on the other's surface): the direction n within 60 degrees of u, x moved along it by
 * IN_RUN r still inside the other body and by OUT_RUN r outside. Not r + a step: n is the normal
 * rule's (section 5a), a face's normal where a face speaks for the contact, while u leads to
 * the closest point on an edge of a faceted tube (up to 15 degrees apart: the ring's facets). */
#define MIN_DOT 0.5
#define IN_RUN 0.5
#define OUT_RUN 1.25
#define DELTA 2e-3 /* the least depth checked: twice this */

/* A square prism 0.6 x 0.6 x 1 standing in the hole of a ring lying flat: its corners at 0.424
 * from the axis, the tube's inner wall at 0.35, so each vertical edge sinks about 0.07 into the
 * tube, in four separate places; turned and moved a little by variant. */
static int make_prism_hole(int bytes, int variant, body *a, body *b)
{
    if (body_torus(0.6, 0.25, a) || body_box(0.6, 0.6, 1.0, b))
        return 1;
    double R[9], I[9];
    rot_axis(2, 0.1 * variant, R);
    rot_axis(2, 0, I);
    const double c[3] = {0.01 * variant, -0.015 * variant, 0.02 * variant}, z[3] = {0, 0, 0};
    body_place(a, I, z, bytes);
    body_place(b, R, c, bytes);
    return 0;
}

typedef struct mpoint {
    double pi[3], pj[3], n[3], d;
    uint32_t nbits[3]; /* the normal's bits in its precision (float: the float's; double: folded) */
} mpoint;

static void bits_of(int bytes, const double n[3], const void *raw, uint32_t out[3])
{
    for (int r = 0; r < 3; ++r) {
        if (bytes == 4) {
            float f;
            memcpy(&f, (const float *)raw + r, sizeof f);
            memcpy(&out[r], &f, sizeof f);
        } else {
            uint64_t u;
            memcpy(&u, &n[r], sizeof u);
            out[r] = (uint32_t)(u ^ (u >> 32) * 0x9e3779b9u);
        }
    }
}

/* The manifold of solids a, b (world vertices, identity poses) at K, margin 0.005: its points. */
static int manifold_points(int bytes, const body *a, const body *b, size_t K, mpoint **out, size_t *n)
{
    uint32_t id[2];
    ttd_scene_array arr = {0};
    int rc = solid_pair_manifold(bytes, a, b, K, &arr, id);
    *out = NULL;
    *n = 0;
    if (!rc && arr.count > 0) {
        *out = calloc(arr.count, sizeof **out);
        rc = *out == NULL;
    }
    for (size_t q = 0; !rc && q < arr.count; ++q) {
        mpoint *m = &(*out)[q];
        if (bytes == 8) {
            const ttd_scene_point_d *p = (const ttd_scene_point_d *)arr.data + q;
            /* body 0 is a: the normal points from a to b */
            rc |= p->i != id[0] || p->j != id[1];
            for (int r = 0; r < 3; ++r) {
                m->pi[r] = p->point_i[r];
                m->pj[r] = p->point_j[r];
                m->n[r] = p->normal[r];
            }
            m->d = p->distance;
            bits_of(8, m->n, p->normal, m->nbits);
        } else {
            const ttd_scene_point_f *p = (const ttd_scene_point_f *)arr.data + q;
            rc |= p->i != id[0] || p->j != id[1];
            for (int r = 0; r < 3; ++r) {
                m->pi[r] = p->point_i[r];
                m->pj[r] = p->point_j[r];
                m->n[r] = p->normal[r];
            }
            m->d = p->distance;
            bits_of(4, m->n, p->normal, m->nbits);
        }
    }
    *n = arr.count;
    ttd_scene_array_free(&arr);
    return rc;
}

/* The sampled overlap: cell centres inside both bodies, labelled by component (1, 2, ...). */
typedef struct overlap {
    double lo[3];
    int dim[3];
    int *label; /* 0: not in the overlap */
    int ncomp;
    double *cx; /* the labelled cells' centres, 3 a cell, and their labels */
    int *cl;
    size_t ncells;
} overlap;

static void overlap_free(overlap *o)
{
    free(o->label);
    free(o->cx);
    free(o->cl);
    memset(o, 0, sizeof *o);
}

static void body_bounds(const body *b, double lo[3], double hi[3])
{
    for (int q = 0; q < 3; ++q) {
        lo[q] = INFINITY;
        hi[q] = -INFINITY;
    }
    for (size_t k = 0; k < b->nv; ++k)
        for (int q = 0; q < 3; ++q) {
            lo[q] = fmin(lo[q], b->v[3 * k + q]);
            hi[q] = fmax(hi[q], b->v[3 * k + q]);
        }
}

static int overlap_make(const body *a, const body *b, ttd_gen_rng *rng, overlap *o)
{
    memset(o, 0, sizeof *o);
    double la[3], ha[3], lb[3], hb[3];
    body_bounds(a, la, ha);
    body_bounds(b, lb, hb);
    size_t total = 1;
    for (int q = 0; q < 3; ++q) {
        o->lo[q] = fmax(la[q], lb[q]);
        const double hi = fmin(ha[q], hb[q]);
        o->dim[q] = hi > o->lo[q] ? (int)ceil((hi - o->lo[q]) / HCELL) : 0;
        total *= (size_t)o->dim[q];
    }
    if (total == 0)
        return 0;
    o->label = calloc(total, sizeof *o->label);
    int *queue = malloc(total * sizeof *queue);
    if (o->label == NULL || queue == NULL) {
        free(queue);
        return 1;
    }
    const ttd_gen_mesh am = {a->v, a->nv, a->t, a->nt}, bm = {b->v, b->nv, b->t, b->nt};
    for (size_t c = 0; c < total; ++c) {
        const int ix = (int)(c % (size_t)o->dim[0]), iy = (int)(c / (size_t)o->dim[0] % (size_t)o->dim[1]),
                  iz = (int)(c / ((size_t)o->dim[0] * (size_t)o->dim[1]));
        const double x[3] = {o->lo[0] + (ix + 0.5) * HCELL, o->lo[1] + (iy + 0.5) * HCELL, o->lo[2] + (iz + 0.5) * HCELL};
        o->label[c] = parity_inside(&bm, x, rng) && parity_inside(&am, x, rng) ? -1 : 0;
        o->ncells += o->label[c] != 0;
    }
    o->cx = malloc(3 * (o->ncells + 1) * sizeof *o->cx);
    o->cl = malloc((o->ncells + 1) * sizeof *o->cl);
    if (o->cx == NULL || o->cl == NULL) {
        free(queue);
        return 1;
    }
    size_t m = 0;
    for (size_t c = 0; c < total; ++c) {
        if (o->label[c] != -1)
            continue;
        const int lab = ++o->ncomp;
        size_t head = 0, tail = 0;
        queue[tail++] = (int)c;
        o->label[c] = lab;
        while (head < tail) {
            const size_t e = (size_t)queue[head++];
            const int ix = (int)(e % (size_t)o->dim[0]), iy = (int)(e / (size_t)o->dim[0] % (size_t)o->dim[1]),
                      iz = (int)(e / ((size_t)o->dim[0] * (size_t)o->dim[1]));
            o->cx[3 * m] = o->lo[0] + (ix + 0.5) * HCELL;
            o->cx[3 * m + 1] = o->lo[1] + (iy + 0.5) * HCELL;
            o->cx[3 * m + 2] = o->lo[2] + (iz + 0.5) * HCELL;
            o->cl[m++] = lab;
            const int nb[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
            for (int k = 0; k < 6; ++k) {
                const int jx = ix + nb[k][0], jy = iy + nb[k][1], jz = iz + nb[k][2];
                if (jx < 0 || jy < 0 || jz < 0 || jx >= o->dim[0] || jy >= o->dim[1] || jz >= o->dim[2])
                    continue;
                const size_t f = (size_t)jx + (size_t)o->dim[0] * ((size_t)jy + (size_t)o->dim[1] * (size_t)jz);
                if (o->label[f] == -1) {
                    o->label[f] = lab;
                    queue[tail++] = (int)f;
                }
            }
        }
    }
    free(queue);
    return 0;
}

/* The component of the sampled cell nearest x, and that cell's distance. */
static int overlap_component(const overlap *o, const double x[3], double *dist)
{
    double best = INFINITY;
    int lab = 0;
    for (size_t c = 0; c < o->ncells; ++c) {
        const double dx = o->cx[3 * c] - x[0], dy = o->cx[3 * c + 1] - x[1], dz = o->cx[3 * c + 2] - x[2];
        const double d2 = dx * dx + dy * dy + dz * dz;
        if (d2 < best) {
            best = d2;
            lab = o->cl[c];
        }
    }
    *dist = sqrt(best);
    return lab;
}

static double surface_distance(const body *y, const double x[3])
{
    double d = INFINITY;
    for (size_t s = 0; s < y->nt; ++s)
        d = fmin(d, test_point_triangle(x, y->v + 3 * y->t[3 * s], y->v + 3 * y->t[3 * s + 1], y->v + 3 * y->t[3 * s + 2]));
    return d;
}

/* One case in one precision: the checks above; returns the number of failures (or -1 on error). */
static int check_regions(const char *what, int (*make)(int, int, body *, body *), int variant, int bytes, int want_comp)
{
    body a = {0}, b = {0};
    if (make(bytes, variant, &a, &b)) {
        body_free(&a);
        body_free(&b);
        return -1;
    }
    ttd_gen_rng rng = ttd_gen_rng_make(33, (uint64_t)variant);
    overlap o;
    mpoint *p0 = NULL, *p4 = NULL;
    size_t n0 = 0, n4 = 0;
    int fails = 0;
    if (overlap_make(&a, &b, &rng, &o) || manifold_points(bytes, &a, &b, 0, &p0, &n0) ||
        manifold_points(bytes, &a, &b, 4, &p4, &n4)) {
        fails = -1;
        goto done;
    }
    const ttd_gen_mesh am = {a.v, a.nv, a.t, a.nt}, bm = {b.v, b.nv, b.t, b.nt};
    const double dtol = bytes == 8 ? 1e-9 : 2e-5;
    /* per component (labels 1..ncomp): its deepest point and its direction's bits */
    int *deep = malloc((size_t)(o.ncomp + 1) * sizeof *deep);
    int *comp = malloc((n0 + 1) * sizeof *comp);
    if (deep == NULL || comp == NULL) {
        free(deep);
        free(comp);
        fails = -1;
        goto done;
    }
    for (int c = 0; c <= o.ncomp; ++c)
        deep[c] = -1;
    size_t below = 0, unassigned = 0, depth_bad = 0, mixed = 0;
    for (size_t q = 0; q < n0; ++q) {
        comp[q] = 0;
        if (!(p0[q].d < 0))
            continue;
        ++below;
        const double r = -p0[q].d;
        const double di = surface_distance(&b, p0[q].pi), dj = surface_distance(&a, p0[q].pj);
        depth_bad += !(fmin(fabs(di - r), fabs(dj - r)) <= dtol * fmax(1, r));
        double e_i, e_j;
        const int ci = overlap_component(&o, p0[q].pi, &e_i), cj = overlap_component(&o, p0[q].pj, &e_j);
        const int c = e_i <= e_j ? ci : cj;
        if (fmin(e_i, e_j) > 2 * HCELL) {
            ++unassigned;
            fails += r > 3 * HCELL; /* a deep point outside every sampled component */
            continue;
        }
        comp[q] = c;
        if (deep[c] < 0)
            deep[c] = (int)q;
        else if (memcmp(p0[q].nbits, p0[deep[c]].nbits, sizeof p0[q].nbits) != 0)
            ++mixed;
        if (p0[q].d < p0[deep[c]].d)
            deep[c] = (int)q;
    }
    /* out of the other body at each component's deepest point: the region's direction is its
     * deepest point's, and points may tie in depth to rounding (the deepest of a face pierced by
     * a tube: the points nearest its inner and outer wall, alike to 1e-6), so any point of the
     * component within the depths' tolerance of its deepest may be the one */
    int with_points = 0, out_bad = 0;
    for (int c = 1; c <= o.ncomp; ++c) {
        if (deep[c] < 0)
            continue;
        ++with_points;
        const double rmax = -p0[deep[c]].d;
        int ok = 0;
        for (size_t q = 0; q < n0 && !ok; ++q) {
            if (comp[q] != c || -p0[q].d < rmax - dtol * fmax(1, rmax))
                continue;
            const mpoint *x = &p0[q];
            const double r = -x->d;
            const double di = surface_distance(&b, x->pi), dj = surface_distance(&a, x->pj);
            const int is_i = fabs(di - r) <= fabs(dj - r); /* body a's point inside b: a leaves along -n */
            const double *y = is_i ? x->pi : x->pj, *yo = is_i ? x->pj : x->pi, sg = is_i ? -1 : 1;
            const ttd_gen_mesh *other = is_i ? &bm : &am;
            /* u: out of the other body at exactly the depth (yo, the partner, lies on the other's
             * surface at distance r: a closest point) */
            double u[3], dot = 0, zin[3], zout[3];
            for (int k = 0; k < 3; ++k) {
                u[k] = (yo[k] - y[k]) / r;
                dot += sg * x->n[k] * u[k];
                zin[k] = y[k] + sg * IN_RUN * r * x->n[k];
                zout[k] = y[k] + sg * OUT_RUN * r * x->n[k];
            }
            const double on = surface_distance(is_i ? &b : &a, yo);
            ok = r > 2 * DELTA && on <= dtol * fmax(1, r) && dot >= MIN_DOT && parity_inside(other, zin, &rng) &&
                 !parity_inside(other, zout, &rng);
            if (getenv("TTD_REGIONS_DEBUG"))
                printf("      r %.9f x (%g %g %g) u (%+.4f %+.4f %+.4f) n (%+.4f %+.4f %+.4f) n.u %.4f ok %d\n", r, y[0],
                       y[1], y[2], u[0], u[1], u[2], x->n[0], x->n[1], x->n[2], dot, ok);
        }
        const mpoint *x = &p0[deep[c]];
        printf("    component %d: deepest %.6f, direction (%+.4f %+.4f %+.4f)%s\n", c, rmax, x->n[0], x->n[1], x->n[2],
               ok ? "" : "  <- NOT OUT OF THE OTHER BODY");
        out_bad += !ok;
    }
    /* K = 4: each point of a component carries the component's direction */
    size_t k4_bad = 0;
    for (size_t q = 0; q < n4; ++q) {
        if (!(p4[q].d < 0))
            continue;
        double e_i, e_j;
        const int ci = overlap_component(&o, p4[q].pi, &e_i), cj = overlap_component(&o, p4[q].pj, &e_j);
        const int c = e_i <= e_j ? ci : cj;
        if (fmin(e_i, e_j) > 2 * HCELL || deep[c] < 0)
            continue;
        k4_bad += memcmp(p4[q].nbits, p0[deep[c]].nbits, sizeof p4[q].nbits) != 0;
    }
    const int comp_bad = want_comp > 0 && with_points != want_comp;
    fails += (int)(depth_bad > 0) + (int)(mixed > 0) + out_bad + (int)(k4_bad > 0) + comp_bad;
    printf("  %-24s %d %s: %zu points below 0 (%zu beyond the sampled overlap), %d components with points%s, "
           "%zu off their component's direction, %zu depths off, K 4: %zu off%s\n",
           what, variant, bytes == 8 ? "double" : "float", below, unassigned, with_points, comp_bad ? " (WRONG)" : "",
           mixed, depth_bad, k4_bad, fails ? "  <- FAILS" : "");
    free(deep);
    free(comp);
done:
    free(p0);
    free(p4);
    overlap_free(&o);
    body_free(&a);
    body_free(&b);
    return fails;
}

static int run_case(const char *what, int (*make)(int, int, body *, body *), int want_comp)
{
    int fails = 0;
    for (int v = 0; v < 3; ++v)
        for (int bytes = 8; bytes >= 4; bytes -= 4) {
            const int f = check_regions(what, make, v, bytes, want_comp);
            ENSURE(f >= 0);
            fails += f;
        }
    ENSURE(fails == 0);
    return 0;
}

static int plate_through_ring(void)
{
    return run_case("plate through ring", make_plate_ring, 2);
}

static int prism_in_ring_hole(void)
{
    return run_case("prism in ring hole", make_prism_hole, 4);
}

static int rod_through_ring(void)
{
    return run_case("rod through ring", make_rod_ring, 1);
}

static int box_into_ring_top(void)
{
    return run_case("box sunk into ring top", make_box_ring_top, 1);
}

static int crossing_beams(void)
{
    return run_case("L beams crossing", make_beams, 0);
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(plate_through_ring);
    RUN_TEST(prism_in_ring_hole);
    RUN_TEST(rod_through_ring);
    RUN_TEST(box_into_ring_top);
    RUN_TEST(crossing_beams);
    TEST_MAIN_END();
}
