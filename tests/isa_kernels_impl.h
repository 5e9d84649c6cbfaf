/* SPDX-License-Identifier: MIT */
/* The body of tests/test_isa_kernels.c for one precision (included after core/precision.h).
 * A lane kernel is checked against the scalar function of its method, pair by pair, and
 * against itself: a pair alone, in any lane, among any neighbours (NaN ones included) gives
 * the same bits. */

typedef void (*TTD_SFX(kern_fn))(size_t n, const real *s, const real *t, const ttd_params *prm,
                                 real bound, const TTD_SFX(ttd_out) *out);
typedef void (*TTD_SFX(pair_fn))(const real s[9], const real t[9], const ttd_params *prm, ttd_result *r);

/* The scalar reference of a method (the exact method has no parameters). */
static void TTD_SFX(exact_adapter)(const real s[9], const real t[9], const ttd_params *prm, ttd_result *r)
{
    (void)prm;
    TTD_SFX(ttd_exact_pair)(s, t, r);
}

static TTD_SFX(pair_fn) TTD_SFX(scalar_of)(int method)
{
    switch (method) {
    case TTD_METHOD_EXACT: return TTD_SFX(exact_adapter);
    case TTD_METHOD_PENALTY: return TTD_SFX(ttd_penalty_pair);
    case TTD_METHOD_PENALTY_REFERENCE: return TTD_SFX(ttd_penalty_ref_pair);
    case TTD_METHOD_BARRIER: return TTD_SFX(ttd_barrier_pair);
    case TTD_METHOD_CERTIFIED: return TTD_SFX(ttd_certified_pair);
    default: return NULL;
    }
}

static int TTD_SFX(same_result)(const ttd_result *a, const ttd_result *b)
{
    int same = memcmp(&a->distance, &b->distance, sizeof a->distance) == 0;
    for (int k = 0; k < 3; ++k) {
        same &= memcmp(&a->p[k], &b->p[k], sizeof(real)) == 0;
        same &= memcmp(&a->q[k], &b->q[k], sizeof(real)) == 0;
        same &= memcmp(&a->bary_p[k], &b->bary_p[k], sizeof(real)) == 0;
        same &= memcmp(&a->bary_q[k], &b->bary_q[k], sizeof(real)) == 0;
    }
    return same && a->flags == b->flags && a->feature_p == b->feature_p &&
           a->feature_q == b->feature_q && a->iterations == b->iterations;
}

/* Largest |coordinate| of a pair: the scale that "a few ulps" is relative to. */
static real TTD_SFX(pair_size)(const real *s, const real *t)
{
    real m = 0;
    for (int k = 0; k < 9; ++k) {
        if (TTD_FABS(s[k]) > m) m = TTD_FABS(s[k]);
        if (TTD_FABS(t[k]) > m) m = TTD_FABS(t[k]);
    }
    return m > 0 ? m : 1;
}

/* Fills n pairs of a generated set (see gen_pair in test_isa_kernels.c), rounded to real.
 * The "extreme" family is a random pair scaled by 2^k, k across this precision's whole
 * exponent range: subnormal-sized pairs up to pairs near REAL_MAX. */
static void TTD_SFX(fill)(int family, uint64_t seed, size_t n, real *s, real *t)
{
    double ds[9], dt[9];
    if (family >= GEN_LIBRARY_FIRST) {
        double *gs = malloc(9 * n * sizeof *gs), *gt = malloc(9 * n * sizeof *gt);
        if (!gs || !gt) abort();
        if (family == GEN_MESH) {
            if (mesh_like_pairs(seed, n, gs, gt) != 0) abort();
        } else {
            ttd_gen(gen_library_family[family - GEN_LIBRARY_FIRST], seed, n, gs, gt);
        }
        for (size_t i = 0; i < 9 * n; ++i) {
            s[i] = (real)gs[i];
            t[i] = (real)gt[i];
        }
        free(gs);
        free(gt);
        return;
    }
#ifdef TTD_PRECISION_DOUBLE
    const int kmin = DBL_MIN_EXP - 40, kmax = DBL_MAX_EXP - 3;
#else
    const int kmin = FLT_MIN_EXP - 15, kmax = FLT_MAX_EXP - 3;
#endif
    for (size_t i = 0; i < n; ++i) {
        gen_pair(family == GEN_EXTREME ? 0 : family, seed, i, ds, dt);
        const int k = kmin + (int)((i * 2654435761u) % (size_t)(kmax - kmin + 1));
        for (int c = 0; c < 9; ++c) {
            s[9 * i + c] = (real)ds[c];
            t[9 * i + c] = (real)dt[c];
            if (family == GEN_EXTREME) {
                s[9 * i + c] = TTD_LDEXP(s[9 * i + c], k);
                t[9 * i + c] = TTD_LDEXP(t[9 * i + c], k);
            }
        }
    }
}

/* Every pair of `n` from each family, through the kernel in blocks of TTD_BLOCK_PAIRS, vs
 * the scalar function. Distance, points and weights within `ulps` of the pair's size,
 * iterations and flags equal; also counts bit-identical results. The kernel's three output
 * paths (distances only; distances and points; full results) must give the same bits for
 * what they share. */
static int TTD_SFX(check_vs_scalar)(const char *what, TTD_SFX(kern_fn) kern, int method,
                                    const ttd_params *prm, size_t n, double ulps)
{
    TTD_SFX(pair_fn) ref = TTD_SFX(scalar_of)(method);
    ENSURE(ref != NULL);
    real *s = malloc(9 * n * sizeof *s), *t = malloc(9 * n * sizeof *t);
    real *dist = malloc(n * sizeof *dist), *dist1 = malloc(n * sizeof *dist1), *dist2 = malloc(n * sizeof *dist2);
    real *pts = malloc(6 * n * sizeof *pts);
    ttd_result *res = malloc(n * sizeof *res);
    ENSURE(s && t && dist && dist1 && dist2 && pts && res);
    size_t identical = 0, same_distance = 0, total = 0;
    int rc = 0;
    for (int fam = 0; fam < GEN_FAMILIES && !rc; ++fam) {
        TTD_SFX(fill)(fam, 77u + (uint64_t)fam, n, s, t);
        for (size_t i0 = 0; i0 < n; i0 += TTD_BLOCK_PAIRS) {
            const size_t m = n - i0 < TTD_BLOCK_PAIRS ? n - i0 : TTD_BLOCK_PAIRS;
            TTD_SFX(run_kernel)(kern, m, s + 9 * i0, t + 9 * i0, prm, dist + i0, res + i0);
            TTD_SFX(run_kernel)(kern, m, s + 9 * i0, t + 9 * i0, prm, dist1 + i0, NULL);
            const TTD_SFX(ttd_out) po = {dist2 + i0, pts + 6 * i0, NULL};
            kern(m, s + 9 * i0, t + 9 * i0, prm, (real)INFINITY, &po);
        }
        for (size_t i = 0; i < n && !rc; ++i) {
            ttd_result want;
            ref(s + 9 * i, t + 9 * i, prm, &want);
            const ttd_result *got = &res[i];
            /* a few ulps of the pair's size, and at least a few units of the smallest
             * subnormal (the size itself may be subnormal) */
            double tol = ulps * (double)TTD_REAL_EPS * (double)TTD_SFX(pair_size)(s + 9 * i, t + 9 * i);
#ifdef TTD_PRECISION_DOUBLE
            tol = tol > 4 * 0x1p-1074 ? tol : 4 * 0x1p-1074;
#else
            tol = tol > 4 * 0x1p-149 ? tol : 4 * 0x1p-149;
#endif
            int ok = isfinite((double)got->distance) && fabs((double)got->distance - (double)want.distance) <= tol &&
                     memcmp(&dist[i], &got->distance, sizeof(real)) == 0 &&
                     got->iterations == want.iterations && got->flags == want.flags;
            const int paths = memcmp(&dist1[i], &got->distance, sizeof(real)) == 0 &&
                              memcmp(&dist2[i], &got->distance, sizeof(real)) == 0 &&
                              memcmp(pts + 6 * i, got->p, 3 * sizeof(real)) == 0 &&
                              memcmp(pts + 6 * i + 3, got->q, 3 * sizeof(real)) == 0;
            if (!paths)
                fprintf(stderr, "  %s, %s pair %zu: the distance-only or points path differs from the full results\n",
                        what, gen_family_name(fam), i);
            ok &= paths;
            for (int k = 0; k < 3; ++k) {
                ok &= fabs((double)got->p[k] - (double)want.p[k]) <= tol;
                ok &= fabs((double)got->q[k] - (double)want.q[k]) <= tol;
                ok &= fabs((double)got->bary_p[k] - (double)want.bary_p[k]) <= ulps * (double)TTD_REAL_EPS;
                ok &= fabs((double)got->bary_q[k] - (double)want.bary_q[k]) <= ulps * (double)TTD_REAL_EPS;
            }
            if (!ok) {
                for (int k = 0; k < 3; ++k)
                    fprintf(stderr, "    p %.9g/%.9g q %.9g/%.9g bary_p %.9g/%.9g bary_q %.9g/%.9g\n",
                            (double)got->p[k], (double)want.p[k], (double)got->q[k], (double)want.q[k],
                            (double)got->bary_p[k], (double)want.bary_p[k], (double)got->bary_q[k],
                            (double)want.bary_q[k]);
                fprintf(stderr, "  %s, %s pair %zu: distance %.17g want %.17g (tol %.3g), iterations %u want %u, flags %x want %x\n",
                        what, gen_family_name(fam), i, (double)got->distance, (double)want.distance, tol,
                        (unsigned)got->iterations, (unsigned)want.iterations, got->flags, want.flags);
                rc = 1;
            }
            identical += (size_t)TTD_SFX(same_result)(got, &want);
            same_distance += (size_t)(memcmp(&got->distance, &want.distance, sizeof(real)) == 0);
            ++total;
        }
    }
    printf("  %s: %zu pairs; bit-identical to the scalar code: %zu distances, %zu whole results\n", what,
           total, same_distance, identical);
    free(s);
    free(t);
    free(dist);
    free(dist1);
    free(dist2);
    free(pts);
    free(res);
    return rc;
}

/* A pair alone (n = 1) and the same pair in a random lane of a block among random neighbours
 * (some of them NaN) give the same bits; the NaN neighbours disturb nobody else either. */
static int TTD_SFX(check_lane_independence)(const char *what, TTD_SFX(kern_fn) kern, int lanes,
                                            const ttd_params *prm, ttd_gen_rng *st)
{
    enum { N = 64 };
    real s[9 * N], t[9 * N], ps[9 * N], pt[9 * N];
    ttd_result alone[N], mixed[N];
    TTD_SFX(fill)(0, 991u, N, s, t);
    for (int i = 0; i < N; ++i)
        TTD_SFX(run_kernel)(kern, 1, s + 9 * i, t + 9 * i, prm, NULL, &alone[i]);
    for (int trial = 0; trial < 40; ++trial) {
        /* a random permutation-with-repeats of the pairs, a few replaced by NaN */
        int src[N];
        for (int i = 0; i < N; ++i) {
            src[i] = (int)(ttd_gen_rng_u64(st) % N);
            if (ttd_gen_rng_u64(st) % 8 == 0)
                src[i] = -1;
            for (int k = 0; k < 9; ++k) {
                ps[9 * i + k] = src[i] < 0 ? (real)NAN : s[9 * src[i] + k];
                pt[9 * i + k] = src[i] < 0 ? (real)(k + 1) : t[9 * src[i] + k];
            }
        }
        const size_t n = (size_t)(lanes + 1 + (int)(ttd_gen_rng_u64(st) % (uint64_t)(N - lanes)));
        TTD_SFX(run_kernel)(kern, n, ps, pt, prm, NULL, mixed);
        for (size_t i = 0; i < n; ++i) {
            if (src[i] < 0)
                continue;
            ENSURE_MSG(TTD_SFX(same_result)(&mixed[i], &alone[src[i]]),
                       "%s: pair %d in lane %zu of %zu differs from the pair alone (distance %.17g vs %.17g)",
                       what, src[i], i % (size_t)lanes, n, (double)mixed[i].distance,
                       (double)alone[src[i]].distance);
        }
    }
    return 0;
}

/* n = 0, 1, W-1, W+1, a full block; unaligned real arrays; distance-only, results-only and
 * points calls; nothing written past n. */
static int TTD_SFX(check_sizes)(const char *what, TTD_SFX(kern_fn) kern, int lanes, const ttd_params *prm)
{
    enum { N = TTD_BLOCK_PAIRS };
    real *sbuf = malloc((9 * N + 1) * sizeof(real)), *tbuf = malloc((9 * N + 1) * sizeof(real));
    real *dbuf = malloc((N + 2) * sizeof(real)), *pbuf = malloc((6 * N + 8) * sizeof(real));
    ttd_result *res = malloc((N + 1) * sizeof *res), *ref = malloc(N * sizeof *ref);
    ENSURE(sbuf && tbuf && dbuf && pbuf && res && ref);
    real *s = sbuf + 1, *t = tbuf + 1, *d = dbuf + 1; /* misaligned for every vector width */
    TTD_SFX(fill)(0, 4242u, N, s, t);
    TTD_SFX(run_kernel)(kern, N, s, t, prm, NULL, ref);
    const size_t sizes[] = {0, 1, (size_t)lanes - 1, (size_t)lanes, (size_t)lanes + 1,
                            2 * (size_t)lanes + 3, N - 1, N};
    for (size_t z = 0; z < sizeof sizes / sizeof sizes[0]; ++z) {
        const size_t n = sizes[z];
        for (size_t i = 0; i < N + 2; ++i)
            dbuf[i] = (real)-7;
        memset(res, 0xA5, (N + 1) * sizeof *res);
        const ttd_result sentinel = res[n];
        TTD_SFX(run_kernel)(kern, n, s, t, prm, d, res);
        for (size_t i = 0; i < n; ++i) {
            ENSURE_MSG(TTD_SFX(same_result)(&res[i], &ref[i]), "%s n=%zu: pair %zu differs from the full block", what, n, i);
            ENSURE_MSG(memcmp(&d[i], &ref[i].distance, sizeof(real)) == 0, "%s n=%zu: distance[%zu]", what, n, i);
        }
        ENSURE_MSG(dbuf[0] == (real)-7 && d[n] == (real)-7, "%s n=%zu: distance written out of bounds", what, n);
        ENSURE_MSG(memcmp(&res[n], &sentinel, sizeof sentinel) == 0, "%s n=%zu: results written out of bounds", what, n);
        /* distance only */
        for (size_t i = 0; i < N + 2; ++i)
            dbuf[i] = (real)-7;
        TTD_SFX(run_kernel)(kern, n, s, t, prm, d, NULL);
        for (size_t i = 0; i < n; ++i)
            ENSURE_MSG(memcmp(&d[i], &ref[i].distance, sizeof(real)) == 0, "%s n=%zu: distance-only [%zu]", what, n, i);
        ENSURE(d[n] == (real)-7);
        /* points alone, then with distances: p and q of the full results, bit for bit */
        for (int with_d = 0; with_d < 2; ++with_d) {
            real *pts = pbuf + 1;
            for (size_t i = 0; i < 6 * N + 8; ++i)
                pbuf[i] = (real)-7;
            for (size_t i = 0; i < N + 2; ++i)
                dbuf[i] = (real)-7;
            const TTD_SFX(ttd_out) out = {with_d ? d : NULL, pts, NULL};
            kern(n, s, t, prm, (real)INFINITY, &out);
            for (size_t i = 0; i < n; ++i) {
                ENSURE_MSG(memcmp(pts + 6 * i, ref[i].p, 3 * sizeof(real)) == 0 &&
                               memcmp(pts + 6 * i + 3, ref[i].q, 3 * sizeof(real)) == 0,
                           "%s n=%zu: points of pair %zu differ from the full results", what, n, i);
                if (with_d)
                    ENSURE_MSG(memcmp(&d[i], &ref[i].distance, sizeof(real)) == 0, "%s n=%zu: distance with points [%zu]", what, n, i);
            }
            ENSURE_MSG(pbuf[0] == (real)-7 && pts[6 * n] == (real)-7, "%s n=%zu: points written out of bounds", what, n);
            ENSURE(with_d ? d[n] == (real)-7 : dbuf[1] == (real)-7);
        }
    }
    free(sbuf);
    free(tbuf);
    free(dbuf);
    free(pbuf);
    free(res);
    free(ref);
    return 0;
}

/* One bounded call of kern on n pairs in blocks, into dist (always), pts and res (may be NULL). */
static void TTD_SFX(run_bounded)(TTD_SFX(kern_fn) kern, size_t n, const real *s, const real *t, const ttd_params *prm,
                                 real bound, real *dist, real *pts, ttd_result *res)
{
    for (size_t i0 = 0; i0 < n; i0 += TTD_BLOCK_PAIRS) {
        const size_t m = n - i0 < TTD_BLOCK_PAIRS ? n - i0 : TTD_BLOCK_PAIRS;
        const TTD_SFX(ttd_out) o = {dist + i0, pts ? pts + 6 * i0 : NULL, res ? res + i0 : NULL};
        kern(m, s + 9 * i0, t + 9 * i0, prm, bound, &o);
    }
}

/* The early-out against a bound never changes a result (kernels.h): for bounds at and just
 * below the distances of pairs spread over each family (and 0, -1, REAL_MAX/2), in each output
 * path, every pair whose distance (the unbounded call's) is at most the bound comes out with
 * the same bits as without a bound, and every other pair reports a distance above the bound
 * and not above its distance (within 8 eps of the pair's size): what the kernel writes for a
 * pair it rules out is a lower bound. *ruled_out counts, in the "far" family, the pairs
 * reported with another distance than the unbounded one (pairs the early-out skipped). With
 * ref (the scalar row), every bounded call must also give ref's bits: the rows rule out the
 * same pairs with the same lower bound. */
static int TTD_SFX(check_bound)(const char *what, TTD_SFX(kern_fn) kern, TTD_SFX(kern_fn) ref, const ttd_params *prm,
                                size_t *ruled_out)
{
    enum { N = 600, PROBES = 12 };
    real *s = malloc(9 * N * sizeof *s), *t = malloc(9 * N * sizeof *t);
    real *d0 = malloc(N * sizeof *d0), *p0 = malloc(6 * N * sizeof *p0), *d = malloc(N * sizeof *d);
    real *p = malloc(6 * N * sizeof *p), *dr = malloc(N * sizeof *dr);
    ttd_result *r0 = malloc(N * sizeof *r0), *r = malloc(N * sizeof *r), *rr = malloc(N * sizeof *rr);
    real *dref = malloc(N * sizeof *dref), *pref = malloc(6 * N * sizeof *pref);
    ENSURE(s && t && d0 && p0 && d && p && dr && r0 && r && rr && dref && pref);
    int rc = 0;
    *ruled_out = 0;
    for (int fam = 0; fam < GEN_FAMILIES && !rc; ++fam) {
        TTD_SFX(fill)(fam, 313u + (uint64_t)fam, N, s, t);
        TTD_SFX(run_bounded)(kern, N, s, t, prm, (real)INFINITY, d0, p0, NULL);
        TTD_SFX(run_bounded)(kern, N, s, t, prm, (real)INFINITY, dr, NULL, r0);
        real bounds[2 * PROBES + 3];
        int nb = 0;
        for (int k = 0; k < PROBES; ++k) {
            const real dk = d0[(size_t)k * N / PROBES + (size_t)fam];
            bounds[nb++] = dk;                                 /* the pair itself is within */
            bounds[nb++] = TTD_NEXTAFTER(dk, -(real)INFINITY); /* and just outside */
        }
        bounds[nb++] = 0;
        bounds[nb++] = -1;
        bounds[nb++] = TTD_REAL_MAX / 2;
        for (int b = 0; b < nb && !rc; ++b) {
            const real bound = bounds[b];
            for (int path = 0; path < 3 && !rc; ++path) {
                TTD_SFX(run_bounded)(kern, N, s, t, prm, bound, d, path == 1 ? p : NULL, path == 2 ? r : NULL);
                if (ref) {
                    TTD_SFX(run_bounded)(ref, N, s, t, prm, bound, dref, path == 1 ? pref : NULL, path == 2 ? rr : NULL);
                    int same = memcmp(d, dref, N * sizeof *d) == 0;
                    if (path == 1)
                        same &= memcmp(p, pref, 6 * N * sizeof *p) == 0;
                    for (size_t i = 0; i < N && path == 2; ++i)
                        same &= TTD_SFX(same_result)(&r[i], &rr[i]);
                    if (!same) {
                        fprintf(stderr, "  %s, %s, bound %.17g, path %d: differs from the scalar row\n", what,
                                gen_family_name(fam), (double)bound, path);
                        rc = 1;
                    }
                }
                for (size_t i = 0; i < N && !rc; ++i) {
                    const real dist = path == 2 ? r[i].distance : d[i];
                    const double size = (double)TTD_SFX(pair_size)(s + 9 * i, t + 9 * i);
                    int ok;
                    if (d0[i] <= bound) {
                        ok = memcmp(&dist, &d0[i], sizeof(real)) == 0;
                        if (path == 1)
                            ok &= memcmp(p + 6 * i, p0 + 6 * i, 6 * sizeof(real)) == 0;
                        if (path == 2)
                            ok &= TTD_SFX(same_result)(&r[i], &r0[i]) && memcmp(&d[i], &dist, sizeof(real)) == 0;
                    } else {
                        ok = dist > bound && (double)dist <= (double)d0[i] + 8 * (double)TTD_REAL_EPS * size;
                        if (path == 2)
                            ok &= memcmp(&d[i], &dist, sizeof(real)) == 0;
                        if (fam == 4 && path == 0 && memcmp(&dist, &d0[i], sizeof(real)) != 0)
                            ++*ruled_out;
                    }
                    if (!ok) {
                        fprintf(stderr, "  %s, %s pair %zu, bound %.17g, path %d: distance %.17g, unbounded %.17g\n",
                                what, gen_family_name(fam), i, (double)bound, path, (double)dist, (double)d0[i]);
                        rc = 1;
                    }
                }
            }
        }
    }
    free(s);
    free(t);
    free(d0);
    free(p0);
    free(d);
    free(p);
    free(dr);
    free(r0);
    free(r);
    free(rr);
    free(dref);
    free(pref);
    return rc;
}

/* Every pair of n from each family through kern and through ref (the scalar row's kernel of
 * the same method), in blocks, in the three output paths: *diff counts the pairs whose whole
 * result, distance or points differ in any bit. */
static int TTD_SFX(check_bits)(const char *what, TTD_SFX(kern_fn) kern, TTD_SFX(kern_fn) ref, const ttd_params *prm,
                               size_t n, size_t *diff)
{
    real *s = malloc(9 * n * sizeof *s), *t = malloc(9 * n * sizeof *t);
    real *d = malloc(n * sizeof *d), *dr = malloc(n * sizeof *dr), *p = malloc(6 * n * sizeof *p),
         *pr = malloc(6 * n * sizeof *pr);
    ttd_result *r = malloc(n * sizeof *r), *rr = malloc(n * sizeof *rr);
    ENSURE(s && t && d && dr && p && pr && r && rr);
    *diff = 0;
    for (int fam = 0; fam < GEN_FAMILIES; ++fam) {
        TTD_SFX(fill)(fam, 1009u + (uint64_t)fam, n, s, t);
        size_t fam_diff = 0;
        for (int path = 0; path < 3; ++path) {
            TTD_SFX(run_bounded)(kern, n, s, t, prm, (real)INFINITY, d, path == 1 ? p : NULL, path == 2 ? r : NULL);
            TTD_SFX(run_bounded)(ref, n, s, t, prm, (real)INFINITY, dr, path == 1 ? pr : NULL, path == 2 ? rr : NULL);
            for (size_t i = 0; i < n; ++i) {
                int same = memcmp(&d[i], &dr[i], sizeof(real)) == 0;
                if (path == 1)
                    same &= memcmp(p + 6 * i, pr + 6 * i, 6 * sizeof(real)) == 0;
                if (path == 2)
                    same &= TTD_SFX(same_result)(&r[i], &rr[i]);
                if (!same && fam_diff == 0)
                    fprintf(stderr, "  %s, %s pair %zu (output path %d): distance %.17g, scalar row %.17g\n", what,
                            gen_family_name(fam), i, path, (double)d[i], (double)dr[i]);
                fam_diff += (size_t)!same;
            }
        }
        *diff += fam_diff;
    }
    free(s);
    free(t);
    free(d);
    free(dr);
    free(p);
    free(pr);
    free(r);
    free(rr);
    return 0;
}

/* The node test of a row against the scalar row's on random boxes: x's frame a random rotation
 * (Gram-Schmidt of random vectors) moved by up to 4, the children's axes likewise, centres in
 * [-4, 4]^3, half extents in [0, 2), some children flat (an extent 0) or coinciding with x;
 * *diff counts the children whose lb2 or sep differ in any bit. */
static void TTD_SFX(random_frame)(ttd_gen_rng *st, real m[9])
{
    double a[9];
    for (int k = 0; k < 9; ++k)
        a[k] = ttd_gen_rng_uniform(st) - 0.5;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < i; ++j) {
            const double dp = a[3 * i] * a[3 * j] + a[3 * i + 1] * a[3 * j + 1] + a[3 * i + 2] * a[3 * j + 2];
            for (int c = 0; c < 3; ++c)
                a[3 * i + c] -= dp * a[3 * j + c];
        }
        const double nn = sqrt(a[3 * i] * a[3 * i] + a[3 * i + 1] * a[3 * i + 1] + a[3 * i + 2] * a[3 * i + 2]);
        for (int c = 0; c < 3; ++c)
            m[3 * i + c] = (real)(a[3 * i + c] / nn);
    }
}

typedef void (*TTD_SFX(node_fn))(const TTD_SFX(ttd_box_query) *x, const TTD_SFX(ttd_node) *y, real *lb2, real *sep);

typedef unsigned (*TTD_SFX(within_fn))(const TTD_SFX(ttd_box_query) *x, const TTD_SFX(ttd_node) *y, real lim2, real *lb2,
                                        real *sep);

/* node_test (or, where within is not NULL, node_within with its mask) against ref's bits */
static int TTD_SFX(check_node_bits)(TTD_SFX(node_fn) node_test, TTD_SFX(within_fn) within, TTD_SFX(node_fn) ref,
                                    size_t trials, size_t *diff)
{
    ttd_gen_rng st = ttd_gen_rng_make(20, 26);
    *diff = 0;
    for (size_t trial = 0; trial < trials; ++trial) {
        TTD_SFX(ttd_box_query) x;
        TTD_SFX(ttd_node) y;
        memset(&y, 0, sizeof y);
        TTD_SFX(random_frame)(&st, x.m);
        for (int i = 0; i < 3; ++i) {
            x.v[i] = (real)(8 * ttd_gen_rng_uniform(&st) - 4);
            x.e[i] = (real)(2 * ttd_gen_rng_uniform(&st));
        }
        y.count = TTD_NODE_WIDTH;
        for (int j = 0; j < TTD_NODE_WIDTH; ++j) {
            real u[9];
            TTD_SFX(random_frame)(&st, u);
            for (int k = 0; k < 9; ++k)
                y.u[k][j] = u[k];
            for (int i = 0; i < 3; ++i) {
                y.c[i][j] = (real)(8 * ttd_gen_rng_uniform(&st) - 4);
                y.e[i][j] = (real)(2 * ttd_gen_rng_uniform(&st));
            }
            if (ttd_gen_rng_u64(&st) % 8 == 0)
                y.e[ttd_gen_rng_u64(&st) % 3][j] = 0;
            if (ttd_gen_rng_u64(&st) % 8 == 0)
                for (int i = 0; i < 3; ++i)
                    y.c[i][j] = -x.v[i]; /* near x's centre */
        }
        real lb2[TTD_NODE_WIDTH], sep[TTD_NODE_WIDTH], lb2r[TTD_NODE_WIDTH], sepr[TTD_NODE_WIDTH];
        ref(&x, &y, lb2r, sepr);
        if (within) {
            /* the limit one of the children's own bounds half the time (a tie must count as
             * within), else anywhere in their range; the mask is the reference's comparison */
            const int jt = (int)(ttd_gen_rng_u64(&st) % TTD_NODE_WIDTH);
            const real lim2 = trial % 2 ? lb2r[jt] : (real)(ttd_gen_rng_uniform(&st) * (double)lb2r[jt] * 2);
            const unsigned bits = within(&x, &y, lim2, lb2, sep);
            unsigned want = 0;
            for (int j = 0; j < TTD_NODE_WIDTH; ++j)
                want |= (unsigned)!(lb2r[j] > lim2) << j;
            *diff += (size_t)(bits != want);
        } else
            node_test(&x, &y, lb2, sep);
        for (int j = 0; j < TTD_NODE_WIDTH; ++j)
            *diff += (size_t)(memcmp(&lb2[j], &lb2r[j], sizeof(real)) != 0 || memcmp(&sep[j], &sepr[j], sizeof(real)) != 0);
    }
    return 0;
}
