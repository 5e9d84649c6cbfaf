/* SPDX-License-Identifier: MIT */
/* The world's step: ttd's manifold -> contacts (matched to the previous step's for warm
 * starting) -> sequential impulses with friction -> semi-implicit Euler. docs/simulator.md
 * says why each choice. */
#define _POSIX_C_SOURCE 199309L
#include "sim.h"
#include "vec.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

sim_settings sim_default_settings(void)
{
    sim_settings s;
    memset(&s, 0, sizeof s);
    s.dt = 1.0 / 240;
    s.gravity[2] = -9.81;
    s.margin = 0.04;
    s.rest_gap = 0.01;
    s.max_points = 4;
    s.substeps = 16;
    s.iterations = 1;
    s.friction = 0.6;
    s.contact_hertz = 240;
    s.damping_ratio = 10;
    s.max_push = 3;
    s.match_distance = 0.05;
    s.warm_start = 1;
    s.solid = 1;
    s.threads = 1;
    s.jig = 1;
    s.ccd = -1;
    return s;
}

static double cpu_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int sim_world_init(sim_world *w, const sim_settings *set)
{
    memset(w, 0, sizeof *w);
    w->set = set ? *set : sim_default_settings();
    w->opt = ttd_default_options();
    w->opt.threads = w->set.threads;
    w->ccd_last_toi = INFINITY;
    return ttd_scene_create_d(&w->scene) == TTD_OK ? 0 : -1;
}

void sim_world_free(sim_world *w)
{
    sim_ccd_free(w);
    ttd_scene_destroy(w->scene);
    ttd_scene_array_free(&w->manifold);
    free(w->body);
    free(w->contact);
    free(w->previous);
    free(w->poses);
    memset(w, 0, sizeof *w);
}

void sim_body_pose(const sim_body *b, double pose[12])
{
    for (int r = 0; r < 3; ++r) {
        pose[4 * r] = b->R[3 * r];
        pose[4 * r + 1] = b->R[3 * r + 1];
        pose[4 * r + 2] = b->R[3 * r + 2];
        pose[4 * r + 3] = b->x[r];
    }
}

/// R from q, and the world inverse inertia R I^-1 R^T.
void sim_body_update(sim_body *b)
{
    quat_to_m3(b->q, b->R);
    double tmp[9];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            tmp[3 * i + j] = b->R[3 * i] * b->inv_inertia[j] + b->R[3 * i + 1] * b->inv_inertia[3 + j] +
                             b->R[3 * i + 2] * b->inv_inertia[6 + j];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            b->inv_inertia_world[3 * i + j] =
                tmp[3 * i] * b->R[3 * j] + tmp[3 * i + 1] * b->R[3 * j + 1] + tmp[3 * i + 2] * b->R[3 * j + 2];
}

/// The inverse of a symmetric positive definite 3x3 matrix (the adjugate over the determinant).
static void m3_inverse(const double m[9], double out[9])
{
    double c0 = m[4] * m[8] - m[5] * m[7], c1 = m[5] * m[6] - m[3] * m[8], c2 = m[3] * m[7] - m[4] * m[6];
    double det = m[0] * c0 + m[1] * c1 + m[2] * c2;
    out[0] = c0 / det;
    out[1] = (m[2] * m[7] - m[1] * m[8]) / det;
    out[2] = (m[1] * m[5] - m[2] * m[4]) / det;
    out[3] = c1 / det;
    out[4] = (m[0] * m[8] - m[2] * m[6]) / det;
    out[5] = (m[2] * m[3] - m[0] * m[5]) / det;
    out[6] = c2 / det;
    out[7] = (m[1] * m[6] - m[0] * m[7]) / det;
    out[8] = (m[0] * m[4] - m[1] * m[3]) / det;
}

long sim_world_add(sim_world *w, const sim_shape *shape, const double x[3], const double q[4], int is_static)
{
    if (w->n == w->cap) {
        size_t cap = w->cap ? 2 * w->cap : 16;
        sim_body *body = realloc(w->body, cap * sizeof *body);
        double *poses = realloc(w->poses, 12 * cap * sizeof *poses);
        if (body)
            w->body = body;
        if (poses)
            w->poses = poses;
        if (!body || !poses)
            return -1;
        w->cap = cap;
    }
    sim_body *b = w->body + w->n;
    memset(b, 0, sizeof *b);
    b->shape = shape;
    b->is_static = is_static;
    memcpy(b->x, x, sizeof b->x);
    double qn = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (int k = 0; k < 4; ++k)
        b->q[k] = q[k] / qn;
    if (!is_static) {
        b->inv_mass = 1 / shape->volume;
        m3_inverse(shape->inertia, b->inv_inertia);
    }
    sim_body_update(b);
    sim_body_pose(b, w->poses + 12 * w->n);
    uint32_t id;
    if (ttd_scene_add_d(w->scene, shape->mesh, w->poses + 12 * w->n, &id) != TTD_OK || id != w->n)
        return -1;
    /* static bodies: group 2, meeting group 1 only (never each other); moving: group 1, both */
    if (ttd_scene_set_filter(w->scene, id, is_static ? 2 : 1, is_static ? 1 : 3) != TTD_OK)
        return -1;
    /* every shape is closed: as solids, bodies that cross get points of negative distance (their
       depth through the crossing), which the solver's spring pushes out like a deficit */
    if (w->set.solid && ttd_scene_set_solid(w->scene, id, 1) != TTD_OK)
        return -1;
    return (long)w->n++;
}

double sim_world_kinetic(const sim_world *w)
{
    double e = 0;
    for (size_t k = 0; k < w->n; ++k) {
        const sim_body *b = w->body + k;
        if (b->is_static)
            continue;
        double lw[3], iw[3];
        m3_tmul_v(b->R, b->w, lw); /* angular velocity in the body's frame */
        m3_mul_v(b->shape->inertia, lw, iw);
        e += 0.5 * b->shape->volume * v3_dot(b->v, b->v) + 0.5 * v3_dot(lw, iw);
    }
    return e;
}

/// 1 / (the inverse masses and the rotational terms along direction d).
static double effective_mass(const sim_body *a, const sim_body *b, const double ra[3], const double rb[3],
                             const double d[3])
{
    double ca[3], cb[3], ia[3], ib[3];
    v3_cross(ra, d, ca);
    v3_cross(rb, d, cb);
    m3_mul_v(a->inv_inertia_world, ca, ia);
    m3_mul_v(b->inv_inertia_world, cb, ib);
    double k = a->inv_mass + b->inv_mass + v3_dot(ca, ia) + v3_dot(cb, ib);
    return k > 0 ? 1 / k : 0;
}

/// The velocity of b relative to a at the contact.
static void relative_velocity(const sim_body *a, const sim_body *b, const sim_contact *c, double dv[3])
{
    double wa[3], wb[3];
    v3_cross(a->w, c->ra, wa);
    v3_cross(b->w, c->rb, wb);
    for (int i = 0; i < 3; ++i)
        dv[i] = b->v[i] + wb[i] - a->v[i] - wa[i];
}

/// Impulse p on b at rb and -p on a at ra.
static void apply_impulse(sim_body *a, sim_body *b, const sim_contact *c, const double p[3])
{
    double t[3], dw[3];
    v3_axpy(a->v, -a->inv_mass, p, a->v);
    v3_cross(c->ra, p, t);
    m3_mul_v(a->inv_inertia_world, t, dw);
    v3_axpy(a->w, -1, dw, a->w);
    v3_axpy(b->v, b->inv_mass, p, b->v);
    v3_cross(c->rb, p, t);
    m3_mul_v(b->inv_inertia_world, t, dw);
    v3_axpy(b->w, 1, dw, b->w);
}

/// Two unit tangents of n, fixed by n alone.
static void tangents(const double n[3], double t1[3], double t2[3])
{
    const double ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0};
    v3_cross(n, fabs(n[0]) < 0.57 ? ex : ey, t1);
    v3_normalize(t1);
    v3_cross(n, t1, t2);
}

static int grow_contacts(sim_world *w, size_t need)
{
    if (need <= w->contact_cap && need <= w->previous_cap)
        return 0;
    size_t cap = need + need / 2 + 16;
    sim_contact *c = realloc(w->contact, cap * sizeof *c);
    if (c)
        w->contact = c;
    sim_contact *p = realloc(w->previous, cap * sizeof *p);
    if (p)
        w->previous = p;
    if (!c || !p)
        return -1;
    w->contact_cap = w->previous_cap = cap;
    return 0;
}

/// This step's contacts from ttd's manifold, each with the impulses of the previous step's
/// contact of the same body pair nearest to it in a's frame (within match_distance, normals
/// within 25 degrees) not already taken by an earlier one, or none.
static int build_contacts(sim_world *w)
{
    const ttd_scene_point_d *pt = w->manifold.data;
    size_t n = w->manifold.count;
    sim_contact *swap = w->previous;
    w->previous = w->contact;
    w->contact = swap;
    w->nprevious = w->ncontact;
    if (grow_contacts(w, n) != 0)
        return -1;
    size_t prev = 0; /* both lists are sorted by (a, b) */
    for (size_t k = 0; k < n; ++k) {
        sim_contact *c = w->contact + k;
        memset(c, 0, sizeof *c);
        c->a = pt[k].i;
        c->b = pt[k].j;
        memcpy(c->point, pt[k].point, sizeof c->point);
        memcpy(c->normal, pt[k].normal, sizeof c->normal);
        c->distance = pt[k].distance;
        const sim_body *a = w->body + c->a, *b = w->body + c->b;
        if (w->set.vertical_normals) { /* the diagnostic of docs/simulator.md */
            c->normal[0] = c->normal[1] = 0;
            c->normal[2] = 1;
        }
        v3_sub(c->point, a->x, c->ra);
        v3_sub(c->point, b->x, c->rb);
        m3_tmul_v(a->R, c->ra, c->local_a);
        memcpy(c->point_a0, c->point, sizeof c->point);
        memcpy(c->point_b0, c->point, sizeof c->point);
        tangents(c->normal, c->t1, c->t2);
        if (!w->set.warm_start)
            continue;
        while (prev < w->nprevious && (w->previous[prev].a < c->a || (w->previous[prev].a == c->a && w->previous[prev].b < c->b)))
            ++prev;
        sim_contact *best = NULL;
        double best_d = w->set.match_distance;
        for (size_t o = prev; o < w->nprevious && w->previous[o].a == c->a && w->previous[o].b == c->b; ++o) {
            double d[3];
            v3_sub(w->previous[o].local_a, c->local_a, d);
            double dist = v3_norm(d);
            if (dist < best_d && !w->previous[o].claimed && v3_dot(w->previous[o].normal, c->normal) > 0.9) {
                best = w->previous + o;
                best_d = dist;
            }
        }
        if (best) {
            best->claimed = 1; /* one previous contact warms one new one: points that coincide share it */
            double pt_world[3];
            for (int i = 0; i < 3; ++i)
                pt_world[i] = best->impulse_t1 * best->t1[i] + best->impulse_t2 * best->t2[i];
            c->impulse_n = best->impulse_n;
            c->impulse_t1 = v3_dot(pt_world, c->t1);
            c->impulse_t2 = v3_dot(pt_world, c->t2);
        }
    }
    w->ncontact = n;
    return 0;
}

/// A soft constraint's coefficients for a spring of frequency hertz and damping ratio zeta
/// over a substep h (Box2D v3's soft step): the bias rate turns a gap deficit into a speed, and
/// the mass and impulse scales make the constraint a damped spring instead of a rigid one.
typedef struct softness {
    double bias_rate, mass_scale, impulse_scale;
} softness;

static softness make_soft(double hertz, double zeta, double h)
{
    double omega = 2 * 3.141592653589793 * hertz, a1 = 2 * zeta + h * omega, a2 = h * omega * a1, a3 = 1 / (1 + a2);
    softness s = {omega / a1, a2 * a3, a3};
    return s;
}

/// Effective masses, and the anchors in each body's frame for tracking the gap over substeps.
static void prepare_contacts(sim_world *w)
{
    for (size_t k = 0; k < w->ncontact; ++k) {
        sim_contact *c = w->contact + k;
        const sim_body *a = w->body + c->a, *b = w->body + c->b;
        c->mass_n = effective_mass(a, b, c->ra, c->rb, c->normal);
        c->mass_t1 = effective_mass(a, b, c->ra, c->rb, c->t1);
        c->mass_t2 = effective_mass(a, b, c->ra, c->rb, c->t2);
        m3_tmul_v(b->R, c->rb, c->local_b);
        double tilt = acos(fmin(1.0, fabs(c->normal[2])));
        w->max_tilt = fmax(w->max_tilt, tilt);
    }
}

static void warm_start(sim_world *w)
{
    for (size_t k = 0; k < w->ncontact; ++k) {
        sim_contact *c = w->contact + k;
        double p[3];
        for (int i = 0; i < 3; ++i)
            p[i] = c->impulse_n * c->normal[i] + c->impulse_t1 * c->t1[i] + c->impulse_t2 * c->t2[i];
        apply_impulse(w->body + c->a, w->body + c->b, c, p);
    }
}

/// The contact's gap less the rest gap now: its value at the manifold plus how far the two
/// anchors have moved apart along the normal since.
static double current_separation(const sim_world *w, const sim_contact *c)
{
    const sim_body *a = w->body + c->a, *b = w->body + c->b;
    double pa[3], pb[3], d[3];
    m3_mul_v(a->R, c->local_a, pa);
    m3_mul_v(b->R, c->local_b, pb);
    for (int i = 0; i < 3; ++i)
        d[i] = (b->x[i] + pb[i]) - (a->x[i] + pa[i]) - (c->point_b0[i] - c->point_a0[i]);
    return c->distance - w->set.rest_gap + v3_dot(d, c->normal);
}

/// One Gauss-Seidel sweep over the contacts: the normal impulse (>= 0), then friction within
/// the cone of that normal impulse, on impulses accumulated over the substep. With bias, a
/// negative gap is pushed out as a soft spring (soft, or soft_static against a static body);
/// without (the relax sweep), the constraint is rigid and only removes approach speed. A
/// positive gap lets the bodies close by it within the substep h (speculative contact).
static void solve_sweep(sim_world *w, double h, int use_bias, softness soft, softness soft_static)
{
    const double mu = w->set.friction;
    for (size_t k = 0; k < w->ncontact; ++k) {
        sim_contact *c = w->contact + k;
        sim_body *a = w->body + c->a, *b = w->body + c->b;
        double s = current_separation(w, c), bias = 0, mass_scale = 1, impulse_scale = 0;
        if (s > 0) {
            bias = s / h;
        } else if (use_bias) {
            const softness *sf = (a->is_static || b->is_static) ? &soft_static : &soft;
            bias = fmax(sf->bias_rate * s, -w->set.max_push);
            mass_scale = sf->mass_scale;
            impulse_scale = sf->impulse_scale;
        }
        double dv[3], p[3];
        relative_velocity(a, b, c, dv);
        double ln = fmax(c->impulse_n - c->mass_n * mass_scale * (v3_dot(dv, c->normal) + bias) - impulse_scale * c->impulse_n, 0.0);
        double dn = ln - c->impulse_n;
        c->impulse_n = ln;
        for (int i = 0; i < 3; ++i)
            p[i] = dn * c->normal[i];
        apply_impulse(a, b, c, p);

        relative_velocity(a, b, c, dv);
        double l1 = c->impulse_t1 - c->mass_t1 * v3_dot(dv, c->t1);
        double l2 = c->impulse_t2 - c->mass_t2 * v3_dot(dv, c->t2);
        double lmax = mu * c->impulse_n, len = sqrt(l1 * l1 + l2 * l2);
        if (len > lmax) {
            l1 *= lmax / len;
            l2 *= lmax / len;
        }
        double d1 = l1 - c->impulse_t1, d2 = l2 - c->impulse_t2;
        c->impulse_t1 = l1;
        c->impulse_t2 = l2;
        for (int i = 0; i < 3; ++i)
            p[i] = d1 * c->t1[i] + d2 * c->t2[i];
        apply_impulse(a, b, c, p);
    }
}

/// Semi-implicit Euler for the positions: x += h v, q += h/2 (0, w) q, renormalised.
static void integrate_positions(sim_world *w, double h)
{
    for (size_t k = 0; k < w->n; ++k) {
        sim_body *b = w->body + k;
        if (b->is_static)
            continue;
        v3_axpy(b->x, h, b->v, b->x);
        const double wq[4] = {0, b->w[0], b->w[1], b->w[2]};
        double dq[4], norm = 0;
        quat_mul(wq, b->q, dq);
        for (int i = 0; i < 4; ++i) {
            b->q[i] += 0.5 * h * dq[i];
            norm += b->q[i] * b->q[i];
        }
        norm = sqrt(norm);
        for (int i = 0; i < 4; ++i)
            b->q[i] /= norm;
        sim_body_update(b);
    }
}

int sim_world_step(sim_world *w)
{
    const sim_settings *set = &w->set;
    double t0 = cpu_seconds();
    ttd_status st = ttd_scene_manifold_d(&w->opt, w->scene, set->margin, set->max_points, &w->manifold);
    if (st != TTD_OK) {
        fprintf(stderr, "sim: ttd_scene_manifold_d: %s\n", ttd_status_string(st));
        return -1;
    }
    double t1 = cpu_seconds();
    if (build_contacts(w) != 0)
        return -1;
    w->points += w->ncontact;
    prepare_contacts(w);
    if (set->ccd > 0 && sim_ccd_begin(w) != 0)
        return -1;
    double h = set->dt / set->substeps;
    /* Box2D v3's choice: the contact spring at most a quarter of the substep rate */
    double hertz = fmin(set->contact_hertz, 0.25 / h);
    softness soft = make_soft(hertz, set->damping_ratio, h), soft_static = make_soft(2 * hertz, set->damping_ratio, h);
    for (int sub = 0; sub < set->substeps; ++sub) {
        for (size_t k = 0; k < w->n; ++k) {
            sim_body *b = w->body + k;
            if (!b->is_static)
                v3_axpy(b->v, h, set->gravity, b->v);
        }
        warm_start(w);
        for (int it = 0; it < set->iterations; ++it)
            solve_sweep(w, h, 1, soft, soft_static);
        integrate_positions(w, h);
        for (int it = 0; it < set->iterations; ++it)
            solve_sweep(w, h, 0, soft, soft_static);
    }
    if (set->ccd > 0) { /* stops a body short of an impact the manifold did not see (ccd.c) */
        double c0 = cpu_seconds();
        if (sim_ccd_limit(w) != 0)
            return -1;
        w->ccd_seconds += cpu_seconds() - c0;
    }
    for (size_t k = 0; k < w->n; ++k)
        sim_body_pose(w->body + k, w->poses + 12 * k);
    st = ttd_scene_set_poses_d(w->scene, w->n, w->poses);
    if (st != TTD_OK) {
        fprintf(stderr, "sim: ttd_scene_set_poses_d: %s\n", ttd_status_string(st));
        return -1;
    }
    w->time += set->dt;
    ++w->steps;
    w->query_seconds += t1 - t0;
    w->solve_seconds += cpu_seconds() - t1;
    return 0;
}

int sim_world_sync(sim_world *w)
{
    for (size_t k = 0; k < w->n; ++k) {
        sim_body_update(w->body + k);
        sim_body_pose(w->body + k, w->poses + 12 * k);
    }
    return ttd_scene_set_poses_d(w->scene, w->n, w->poses) == TTD_OK ? 0 : -1;
}

int sim_world_write_obj(const sim_world *w, const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return -1;
    size_t base = 1;
    for (size_t k = 0; k < w->n; ++k) {
        const sim_body *b = w->body + k;
        double pose[12];
        sim_body_pose(b, pose);
        fprintf(f, "g %s_%zu %s\n", b->is_static ? "static" : "body", k, b->shape->name);
        for (size_t i = 0; i < b->shape->nv; ++i) {
            double p[3];
            pose_apply(pose, b->shape->v + 3 * i, p);
            fprintf(f, "v %.9g %.9g %.9g\n", p[0], p[1], p[2]);
        }
        for (size_t i = 0; i < b->shape->nt; ++i) {
            const uint32_t *t = b->shape->t + 3 * i;
            fprintf(f, "f %zu %zu %zu\n", base + t[0], base + t[1], base + t[2]);
        }
        base += b->shape->nv;
    }
    return fclose(f) == 0 ? 0 : -1;
}
