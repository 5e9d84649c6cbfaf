/* SPDX-License-Identifier: MIT */
/* The exact continuous-collision reference of the tests (ccd_ref.h), in GMP's rationals.
 *
 * Everything is a polynomial in t with rational coefficients. A contact at time t is the
 * vanishing of one polynomial (the coplanarity of the four points, or for a motion coplanar
 * throughout a sign change of an in-plane condition) together with inequalities. The candidate
 * times are t = 0, t = 1 and the real roots in [0, 1] of the deciding polynomials, isolated by
 * Sturm sequences and bisection; the sign of each inequality at an algebraic root is read on an
 * isolating interval made small enough that the inequality keeps one sign over it, or found zero
 * when the root is also one of the inequality's (a common factor: the gcd). Slow and simple. */
#include "ccd_ref.h"

#include <gmp.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { MAXD = 9 };

/* A polynomial: c[0] + c[1] t + ..., degree deg (-1 for zero). */
typedef struct poly {
    mpq_t c[MAXD + 1];
    int deg;
} poly;

static void p_init(poly *p)
{
    for (int i = 0; i <= MAXD; ++i)
        mpq_init(p->c[i]);
    p->deg = -1;
}
static void p_clear(poly *p)
{
    for (int i = 0; i <= MAXD; ++i)
        mpq_clear(p->c[i]);
}
static void p_norm(poly *p)
{
    while (p->deg >= 0 && mpq_sgn(p->c[p->deg]) == 0)
        --p->deg;
}
static void p_copy(poly *r, const poly *a)
{
    for (int i = 0; i <= MAXD; ++i)
        mpq_set(r->c[i], a->c[i]);
    r->deg = a->deg;
}
static void p_zero(poly *p)
{
    for (int i = 0; i <= MAXD; ++i)
        mpq_set_ui(p->c[i], 0, 1);
    p->deg = -1;
}
/* r = a + s b (s = +-1); r may be a. */
static void p_addsub(poly *r, const poly *a, const poly *b, int s)
{
    poly t;
    p_init(&t);
    const int d = a->deg > b->deg ? a->deg : b->deg;
    for (int i = 0; i <= d; ++i) {
        if (s > 0)
            mpq_add(t.c[i], a->c[i], b->c[i]);
        else
            mpq_sub(t.c[i], a->c[i], b->c[i]);
    }
    t.deg = d;
    p_norm(&t);
    p_copy(r, &t);
    p_clear(&t);
}
static void p_mul(poly *r, const poly *a, const poly *b)
{
    poly t;
    p_init(&t);
    mpq_t x;
    mpq_init(x);
    if (a->deg >= 0 && b->deg >= 0) {
        for (int i = 0; i <= a->deg; ++i)
            for (int j = 0; j <= b->deg; ++j) {
                mpq_mul(x, a->c[i], b->c[j]);
                mpq_add(t.c[i + j], t.c[i + j], x);
            }
        t.deg = a->deg + b->deg;
        p_norm(&t);
    }
    p_copy(r, &t);
    mpq_clear(x);
    p_clear(&t);
}
/* The sign of p at t = a/b (b > 0) in integers: the sign of p(a/b) b^deg D, where D > 0 is the
 * product of the coefficients' denominators, is that of sum N_i a^i b^(deg-i) with the integers
 * N_i = n_i prod_{j != i} d_j. No rational is formed, so no gcd is taken: evaluating at the deep
 * bisection points of close roots in mpq spent most of its time canonicalising (gcd). */
static int p_sign_at(const poly *p, const mpq_t t)
{
    if (p->deg < 0)
        return 0;
    const int d = p->deg;
    mpz_t pre[MAXD + 2], v, term, bpow;
    mpz_init_set_ui(pre[0], 1);
    for (int i = 0; i <= d; ++i) {
        mpz_init(pre[i + 1]);
        mpz_mul(pre[i + 1], pre[i], mpq_denref(p->c[i]));
    }
    mpz_init(v);
    mpz_init(term);
    mpz_init_set_ui(bpow, 1);
    mpz_t suf;
    mpz_init_set_ui(suf, 1); /* prod_{j > i} d_j */
    /* Horner from the top: v = N_d; v = v a + N_i b^(d-i). */
    for (int i = d; i >= 0; --i) {
        mpz_mul(term, mpq_numref(p->c[i]), pre[i]);
        mpz_mul(term, term, suf);
        if (i == d) {
            mpz_set(v, term);
        } else {
            mpz_mul(bpow, bpow, mpq_denref(t));
            mpz_mul(v, v, mpq_numref(t));
            mpz_addmul(v, term, bpow);
        }
        mpz_mul(suf, suf, mpq_denref(p->c[i]));
    }
    const int s = mpz_sgn(v);
    for (int i = 0; i <= d + 1; ++i)
        mpz_clear(pre[i]);
    mpz_clear(v);
    mpz_clear(term);
    mpz_clear(bpow);
    mpz_clear(suf);
    return s;
}
static void p_deriv(poly *r, const poly *a)
{
    poly t;
    p_init(&t);
    mpq_t k;
    mpq_init(k);
    for (int i = 1; i <= a->deg; ++i) {
        mpq_set_ui(k, (unsigned long)i, 1);
        mpq_mul(t.c[i - 1], a->c[i], k);
    }
    t.deg = a->deg - 1;
    p_norm(&t);
    p_copy(r, &t);
    mpq_clear(k);
    p_clear(&t);
}
/* Remainder of a by b (b nonzero) into r; quotient into q when q is not NULL. */
static void p_divmod(poly *q, poly *r, const poly *a, const poly *b)
{
    poly rem, quo;
    p_init(&rem);
    p_init(&quo);
    p_copy(&rem, a);
    mpq_t f, x;
    mpq_init(f);
    mpq_init(x);
    while (rem.deg >= b->deg && rem.deg >= 0) {
        const int sh = rem.deg - b->deg;
        mpq_div(f, rem.c[rem.deg], b->c[b->deg]);
        mpq_set(quo.c[sh], f);
        if (quo.deg < sh)
            quo.deg = sh;
        for (int i = 0; i <= b->deg; ++i) {
            mpq_mul(x, f, b->c[i]);
            mpq_sub(rem.c[i + sh], rem.c[i + sh], x);
        }
        p_norm(&rem);
    }
    if (q)
        p_copy(q, &quo);
    p_copy(r, &rem);
    mpq_clear(f);
    mpq_clear(x);
    p_clear(&rem);
    p_clear(&quo);
}
static void p_gcd(poly *g, const poly *a, const poly *b)
{
    poly x, y, r;
    p_init(&x);
    p_init(&y);
    p_init(&r);
    p_copy(&x, a);
    p_copy(&y, b);
    while (y.deg >= 0) {
        p_divmod(NULL, &r, &x, &y);
        p_copy(&x, &y);
        p_copy(&y, &r);
    }
    p_copy(g, &x);
    p_clear(&x);
    p_clear(&y);
    p_clear(&r);
}

/* Sturm sequence of p (p squarefree, deg >= 1). */
typedef struct sturm {
    poly s[MAXD + 2];
    int n;
} sturm;
static void sturm_make(sturm *st, const poly *p)
{
    st->n = 0;
    p_init(&st->s[0]);
    p_copy(&st->s[0], p);
    p_init(&st->s[1]);
    p_deriv(&st->s[1], p);
    st->n = 2;
    while (st->s[st->n - 1].deg > 0) {
        poly *r = &st->s[st->n];
        p_init(r);
        p_divmod(NULL, r, &st->s[st->n - 2], &st->s[st->n - 1]);
        for (int i = 0; i <= r->deg; ++i)
            mpq_neg(r->c[i], r->c[i]);
        if (r->deg < 0) {
            p_clear(r);
            break;
        }
        st->n++;
    }
}
static void sturm_clear(sturm *st)
{
    for (int i = 0; i < st->n; ++i)
        p_clear(&st->s[i]);
}
static int sturm_changes(const sturm *st, const mpq_t t)
{
    int last = 0, ch = 0;
    for (int i = 0; i < st->n; ++i) {
        const int s = p_sign_at(&st->s[i], t);
        if (s == 0)
            continue;
        if (last != 0 && s != last)
            ++ch;
        last = s;
    }
    return ch;
}
/* Roots of squarefree p in (lo, hi]. */
static int sturm_count(const sturm *st, const mpq_t lo, const mpq_t hi)
{
    return sturm_changes(st, lo) - sturm_changes(st, hi);
}

/* The squarefree part of p (deg >= 1). */
static void p_squarefree(poly *r, const poly *p)
{
    poly d, g;
    p_init(&d);
    p_init(&g);
    p_deriv(&d, p);
    p_gcd(&g, p, &d);
    if (g.deg <= 0)
        p_copy(r, p);
    else
        p_divmod(r, &d, p, &g);
    p_clear(&d);
    p_clear(&g);
}

/* An isolated root: exactly 'lo' when exact, else the only root of sq in (lo, hi). */
typedef struct root {
    mpq_t lo, hi;
    int exact;
} root;

/* The roots of p (not identically zero) in [0, 1], increasing; returns how many (at most MAXD). */
static int isolate(const poly *p, root *out, poly *sq_out)
{
    int n = 0;
    if (p->deg <= 0)
        return 0;
    poly sq;
    p_init(&sq);
    p_squarefree(&sq, p);
    sturm st;
    sturm_make(&st, &sq);
    /* A stack of intervals (lo, hi]. Close roots need deep bisection (two roots 2^-k apart
     * need k levels, and each level leaves one interval waiting), so the stack grows. */
    int cap = 64, top = 0;
    mpq_t *los = malloc((size_t)cap * sizeof(mpq_t)), *his = malloc((size_t)cap * sizeof(mpq_t));
    if (!los || !his)
        abort();
    for (int i = 0; i < cap; ++i) {
        mpq_init(los[i]);
        mpq_init(his[i]);
    }
    mpq_t zero, one, mid;
    mpq_init(zero);
    mpq_init(one);
    mpq_init(mid);
    mpq_set_ui(one, 1, 1);
    if (p_sign_at(&sq, zero) == 0) {
        mpq_init(out[n].lo);
        mpq_init(out[n].hi);
        out[n].exact = 1;
        ++n;
    }
    mpq_set(los[0], zero);
    mpq_set(his[0], one);
    top = 1;
    /* Depth first, earliest first: push later halves first. */
    while (top > 0) {
        --top;
        mpq_t lo, hi;
        mpq_init(lo);
        mpq_init(hi);
        mpq_set(lo, los[top]);
        mpq_set(hi, his[top]);
        const int c = sturm_count(&st, lo, hi);
        if (c == 1) {
            mpq_init(out[n].lo);
            mpq_init(out[n].hi);
            /* lo may be the previous interval's root (it belongs to (.., lo]): move lo off it,
             * keeping the one root in (lo, hi], so that sq's sign at lo tells the side. */
            while (p_sign_at(&sq, hi) != 0 && p_sign_at(&sq, lo) == 0) {
                mpq_add(mid, lo, hi);
                mpq_div_2exp(mid, mid, 1);
                if (sturm_count(&st, mid, hi) == 1)
                    mpq_set(lo, mid);
                else
                    mpq_set(hi, mid);
            }
            if (p_sign_at(&sq, hi) == 0) {
                mpq_set(out[n].lo, hi);
                out[n].exact = 1;
            } else {
                mpq_set(out[n].lo, lo);
                mpq_set(out[n].hi, hi);
                out[n].exact = 0;
            }
            ++n;
        } else if (c > 1) {
            if (top + 2 > cap) {
                const int ncap = 2 * cap;
                /* GMP values move bitwise: their limbs stay where they are. */
                los = realloc(los, (size_t)ncap * sizeof(mpq_t));
                his = realloc(his, (size_t)ncap * sizeof(mpq_t));
                if (!los || !his)
                    abort();
                for (int i = cap; i < ncap; ++i) {
                    mpq_init(los[i]);
                    mpq_init(his[i]);
                }
                cap = ncap;
            }
            mpq_add(mid, lo, hi);
            mpq_div_2exp(mid, mid, 1);
            mpq_set(los[top], mid);
            mpq_set(his[top], hi);
            ++top;
            mpq_set(los[top], lo);
            mpq_set(his[top], mid);
            ++top;
        }
        mpq_clear(lo);
        mpq_clear(hi);
    }
    for (int i = 0; i < cap; ++i) {
        mpq_clear(los[i]);
        mpq_clear(his[i]);
    }
    free(los);
    free(his);
    mpq_clear(zero);
    mpq_clear(one);
    mpq_clear(mid);
    sturm_clear(&st);
    p_copy(sq_out, &sq);
    p_clear(&sq);
    return n;
}

/* The sign of c at the root r of squarefree sq (r isolated in (lo, hi), refined in place). */
static int sign_at_root(const poly *c, const poly *sq, root *r)
{
    if (r->exact)
        return p_sign_at(c, r->lo);
    if (c->deg < 0)
        return 0;
    /* Zero at r exactly when r is a root of gcd(sq, c). */
    poly g;
    p_init(&g);
    p_gcd(&g, sq, c);
    int result = 2;
    if (g.deg >= 1) {
        sturm sg;
        sturm_make(&sg, &g);
        /* g divides sq, which has one root in (lo, hi): g has it or none there. */
        if (p_sign_at(&g, r->hi) == 0 || sturm_count(&sg, r->lo, r->hi) > 0)
            result = 0;
        sturm_clear(&sg);
    }
    p_clear(&g);
    if (result == 0)
        return 0;
    /* Else c(r) != 0: refine until c has no root in [lo, hi]. */
    poly csq;
    p_init(&csq);
    if (c->deg >= 1)
        p_squarefree(&csq, c);
    sturm sc;
    if (c->deg >= 1)
        sturm_make(&sc, &csq);
    mpq_t mid;
    mpq_init(mid);
    const int slo = p_sign_at(sq, r->lo);
    for (;;) {
        if (c->deg < 1) {
            result = mpq_sgn(c->c[0]);
            break;
        }
        if (p_sign_at(c, r->lo) != 0 && p_sign_at(c, r->hi) != 0 && sturm_count(&sc, r->lo, r->hi) == 0) {
            result = p_sign_at(c, r->lo);
            break;
        }
        /* Four halvings (one sign of sq each) between the checks of c (a Sturm sequence of up to
         * ten polynomials): roots of sq and c close together take hundreds of halvings. */
        int exact = 0;
        for (int h = 0; h < 4 && !exact; ++h) {
            mpq_add(mid, r->lo, r->hi);
            mpq_div_2exp(mid, mid, 1);
            const int sm = p_sign_at(sq, mid);
            if (sm == 0) {
                mpq_set(r->lo, mid);
                r->exact = 1;
                result = p_sign_at(c, mid);
                exact = 1;
            } else if (sm == slo) {
                mpq_set(r->lo, mid);
            } else {
                mpq_set(r->hi, mid);
            }
        }
        if (exact)
            break;
    }
    mpq_clear(mid);
    if (c->deg >= 1)
        sturm_clear(&sc);
    p_clear(&csq);
    return result;
}

/* Linear motion of coordinate k of point i: x0 + t (x1 - x0). */
static void p_motion(poly *p, const double *x0, const double *x1, int i, int k)
{
    p_zero(p);
    mpq_set_d(p->c[0], x0[3 * i + k]);
    mpq_t a;
    mpq_init(a);
    mpq_set_d(a, x1[3 * i + k]);
    mpq_sub(p->c[1], a, p->c[0]);
    mpq_clear(a);
    p->deg = 1;
    p_norm(p);
}

typedef struct pvec {
    poly v[3];
} pvec;
static void v_init(pvec *v)
{
    for (int k = 0; k < 3; ++k)
        p_init(&v->v[k]);
}
static void v_clear(pvec *v)
{
    for (int k = 0; k < 3; ++k)
        p_clear(&v->v[k]);
}
static void v_point(pvec *v, const double *x0, const double *x1, int i)
{
    for (int k = 0; k < 3; ++k)
        p_motion(&v->v[k], x0, x1, i, k);
}
static void v_sub(pvec *r, const pvec *a, const pvec *b)
{
    for (int k = 0; k < 3; ++k)
        p_addsub(&r->v[k], &a->v[k], &b->v[k], -1);
}
static void v_cross(pvec *r, const pvec *a, const pvec *b)
{
    poly x, y;
    p_init(&x);
    p_init(&y);
    pvec t;
    v_init(&t);
    for (int k = 0; k < 3; ++k) {
        const int i = (k + 1) % 3, j = (k + 2) % 3;
        p_mul(&x, &a->v[i], &b->v[j]);
        p_mul(&y, &a->v[j], &b->v[i]);
        p_addsub(&t.v[k], &x, &y, -1);
    }
    for (int k = 0; k < 3; ++k)
        p_copy(&r->v[k], &t.v[k]);
    v_clear(&t);
    p_clear(&x);
    p_clear(&y);
}
static void v_dot(poly *r, const pvec *a, const pvec *b)
{
    poly x;
    p_init(&x);
    p_zero(r);
    for (int k = 0; k < 3; ++k) {
        p_mul(&x, &a->v[k], &b->v[k]);
        p_addsub(r, r, &x, 1);
    }
    p_clear(&x);
}

/* The conditions of a contact at time t, for motions not coplanar throughout: the coplanarity
 * polynomial f and inequalities cond[i] >= 0; nondeg > 0 is required (else undecided). */
typedef struct system {
    poly f, nondeg, cond[4];
    int ncond;
} csystem;

static void system_make(csystem *s, int kind, const double *x0, const double *x1)
{
    pvec P[4];
    for (int i = 0; i < 4; ++i) {
        v_init(&P[i]);
        v_point(&P[i], x0, x1, i);
    }
    p_init(&s->f);
    p_init(&s->nondeg);
    for (int i = 0; i < 4; ++i)
        p_init(&s->cond[i]);
    pvec e1, e2, w, n, c;
    v_init(&e1), v_init(&e2), v_init(&w), v_init(&n), v_init(&c);
    if (kind == 1) {
        /* p = P0 in triangle P1 P2 P3: n = (b - a) x (c - a), f = n.(p - a); edge conditions
         * ((v - u) x (p - u)).n >= 0 for the edges ab, bc, ca. */
        v_sub(&e1, &P[2], &P[1]);
        v_sub(&e2, &P[3], &P[1]);
        v_cross(&n, &e1, &e2);
        v_sub(&w, &P[0], &P[1]);
        v_dot(&s->f, &n, &w);
        v_dot(&s->nondeg, &n, &n);
        const int ed[3][2] = {{1, 2}, {2, 3}, {3, 1}};
        for (int i = 0; i < 3; ++i) {
            v_sub(&e1, &P[ed[i][1]], &P[ed[i][0]]);
            v_sub(&w, &P[0], &P[ed[i][0]]);
            v_cross(&c, &e1, &w);
            v_dot(&s->cond[i], &c, &n);
        }
        s->ncond = 3;
    } else {
        /* Segments P0P1, P2P3: m = ea x eb, f = m.(b0 - a0); a0 + s ea = b0 + u eb with
         * s = ((b0 - a0) x eb).m / |m|^2, u = ((b0 - a0) x ea).m / |m|^2, both in [0, 1]. */
        v_sub(&e1, &P[1], &P[0]);
        v_sub(&e2, &P[3], &P[2]);
        v_cross(&n, &e1, &e2);
        v_sub(&w, &P[2], &P[0]);
        v_dot(&s->f, &n, &w);
        v_dot(&s->nondeg, &n, &n);
        v_cross(&c, &w, &e2);
        v_dot(&s->cond[0], &c, &n);
        p_addsub(&s->cond[1], &s->nondeg, &s->cond[0], -1);
        v_cross(&c, &w, &e1);
        v_dot(&s->cond[2], &c, &n);
        p_addsub(&s->cond[3], &s->nondeg, &s->cond[2], -1);
        s->ncond = 4;
    }
    v_clear(&e1), v_clear(&e2), v_clear(&w), v_clear(&n), v_clear(&c);
    for (int i = 0; i < 4; ++i)
        v_clear(&P[i]);
}

static void system_clear(csystem *s)
{
    p_clear(&s->f);
    p_clear(&s->nondeg);
    for (int i = 0; i < 4; ++i)
        p_clear(&s->cond[i]);
}

int ttd_ccd_ref(int kind, const double x0[12], const double x1[12], double *toi_lo, double *toi_hi)
{
    csystem s;
    system_make(&s, kind, x0, x1);
    int result;
    if (s.f.deg < 0) {
        result = TTD_CCD_REF_UNDECIDED; /* coplanar throughout */
    } else {
        root r[MAXD + 2];
        poly sq;
        p_init(&sq);
        const int n = isolate(&s.f, r, &sq);
        result = TTD_CCD_REF_MISS;
        for (int i = 0; i < n && result == TTD_CCD_REF_MISS; ++i) {
            const int nd = sign_at_root(&s.nondeg, &sq, &r[i]);
            int inside = 1;
            for (int j = 0; j < s.ncond && inside; ++j)
                inside = sign_at_root(&s.cond[j], &sq, &r[i]) >= 0;
            if (nd == 0) {
                result = TTD_CCD_REF_UNDECIDED; /* a degenerate triangle or parallel edges at a root */
            } else if (inside) {
                result = TTD_CCD_REF_HIT;
                /* Shrink the isolating interval to a few ulps for the caller. */
                if (!r[i].exact) {
                    mpq_t mid;
                    mpq_init(mid);
                    const int slo = p_sign_at(&sq, r[i].lo);
                    for (int it = 0; it < 200; ++it) {
                        mpq_add(mid, r[i].lo, r[i].hi);
                        mpq_div_2exp(mid, mid, 1);
                        const int sm = p_sign_at(&sq, mid);
                        if (sm == 0) {
                            mpq_set(r[i].lo, mid);
                            r[i].exact = 1;
                            break;
                        }
                        if (sm == slo)
                            mpq_set(r[i].lo, mid);
                        else
                            mpq_set(r[i].hi, mid);
                    }
                    mpq_clear(mid);
                }
                /* Outward to doubles: lo rounded down, hi up. */
                const double lo = mpq_get_d(r[i].lo);
                *toi_lo = lo;
                {
                    mpq_t q;
                    mpq_init(q);
                    mpq_set_d(q, lo);
                    if (mpq_cmp(q, r[i].lo) > 0)
                        *toi_lo = nextafter(lo, -1.0);
                    const double hi = r[i].exact ? mpq_get_d(r[i].lo) : mpq_get_d(r[i].hi);
                    mpq_set_d(q, hi);
                    *toi_hi = hi;
                    if (mpq_cmp(q, r[i].exact ? r[i].lo : r[i].hi) < 0)
                        *toi_hi = nextafter(hi, 2.0);
                    mpq_clear(q);
                }
            }
        }
        for (int i = 0; i < n; ++i) {
            mpq_clear(r[i].lo);
            mpq_clear(r[i].hi);
        }
        p_clear(&sq);
    }
    system_clear(&s);
    return result;
}
