/* SPDX-License-Identifier: MIT */
/* tests/test_gpu_walk.c's comparison for one precision: included with GW_REAL (double or float)
 * and GW_SUF (d or f) defined, it writes check_poses_<suf>. */
#define GW_CAT2(a, b) a##b
#define GW_CAT(a, b) GW_CAT2(a, b)
#define GW_FN(name) GW_CAT(name, GW_SUF)

/* pair (ta, tb) as the CPU's query hands it to the kernel (b moved by the pose) through the
 * public batch: the result a reported pair must have */
static ttd_status GW_FN(pair_result_)(const gw_case *c, const GW_REAL *pose, uint32_t ta, uint32_t tb,
                                      GW_CAT(ttd_result_, GW_SUF) *r)
{
    GW_REAL s[9], t[9];
    const ttd_gen_mesh *a = c->a, *b = c->b;
    for (int k = 0; k < 3; ++k) {
        const double *x = a->verts + 3 * (size_t)a->tris[3 * (size_t)ta + k];
        const double *y = b->verts + 3 * (size_t)b->tris[3 * (size_t)tb + k];
        GW_REAL yr[3] = {(GW_REAL)y[0], (GW_REAL)y[1], (GW_REAL)y[2]};
        for (int i = 0; i < 3; ++i) {
            s[3 * k + i] = (GW_REAL)x[i];
            t[3 * k + i] = ((pose[4 * i] * yr[0] + pose[4 * i + 1] * yr[1]) + pose[4 * i + 2] * yr[2]) + pose[4 * i + 3];
        }
    }
    ttd_options opt = ttd_default_options();
    opt.threads = 1;
    return GW_CAT(ttd_batch_, GW_SUF)(&opt, 1, s, t, NULL, r);
}

static int GW_FN(same_bits_)(GW_REAL x, GW_REAL y)
{
    return memcmp(&x, &y, sizeof x) == 0;
}

/* The device walk (on the host) against the CPU's query for every pose of case c: each pose
 * alone (k = 1, so that a refused pose refuses only itself), distance with upper_bound ub and
 * collision with margin mg; the walk in its own order and in a voted one. Adds to st. */
static int GW_FN(check_poses_)(const gw_case *c, const ttd_mesh *ma, const ttd_mesh *mb, size_t k, const double *posesd,
                               GW_REAL ub, GW_REAL mg, gw_stats *st)
{
    ttd_options opt = ttd_default_options();
    opt.threads = 1;
    for (size_t i = 0; i < k; ++i) {
        GW_REAL pose[12];
        for (int j = 0; j < 12; ++j)
            pose[j] = (GW_REAL)posesd[12 * i + (size_t)j];
        GW_CAT(ttd_mesh_result_, GW_SUF) want, got, got_v;
        ttd_collision cw, cg, cg_v;
        const ttd_status sd = GW_CAT(ttd_mesh_distance_, GW_SUF)(&opt, ma, mb, 1, pose, ub, 0, &want);
        const ttd_status sc = GW_CAT(ttd_mesh_collide_, GW_SUF)(&opt, ma, mb, 1, pose, mg, &cw);
        GW_CAT(ttd_cuda_host_mesh_distance_, GW_SUF)(ma, mb, 1, pose, ub, 0, &got);
        GW_CAT(ttd_cuda_host_mesh_distance_, GW_SUF)(ma, mb, 1, pose, ub, 0x9e3779b97f4a7c15ull + i, &got_v);
        GW_CAT(ttd_cuda_host_mesh_collide_, GW_SUF)(ma, mb, 1, pose, mg, 0, &cg);
        GW_CAT(ttd_cuda_host_mesh_collide_, GW_SUF)(ma, mb, 1, pose, mg, 0x2545f4914f6cdd1dull + i, &cg_v);
        ++st->poses;
        if (sd != TTD_OK) { /* the CPU refuses the pose: so must the walk, in both queries */
            ENSURE_MSG(sd == TTD_ERR_BAD_POSE || sd == TTD_ERR_COORDINATE_RANGE, "%s pose %zu: status %d", c->name, i, sd);
            ENSURE_MSG(sc == sd, "%s pose %zu", c->name, i);
            ENSURE_MSG(got.flags == TTD_GPU_POSE_REFUSED && isnan(got.distance) && got.tri_a == UINT32_MAX,
                       "%s pose %zu: refused by the CPU, walk flags %u", c->name, i, (unsigned)got.flags);
            ENSURE_MSG(cg.hit == TTD_GPU_POSE_REFUSED && cg.tri_a == UINT32_MAX, "%s pose %zu", c->name, i);
            ++st->refused;
            continue;
        }
        ENSURE_MSG(sc == TTD_OK, "%s pose %zu", c->name, i);
        st->pairs_cpu += want.pair_tests;
        st->pairs_walk += got.pair_tests;
        st->nodes_cpu += want.node_tests;
        st->nodes_walk += got.node_tests;
        /* the distance and flags: the CPU's bits, in either order of the walk */
        ENSURE_MSG(GW_FN(same_bits_)(got.distance, want.distance) && got.flags == want.flags,
                   "%s pose %zu: walk %.17g flags %u, CPU %.17g flags %u", c->name, i, (double)got.distance,
                   (unsigned)got.flags, (double)want.distance, (unsigned)want.flags);
        ENSURE_MSG(GW_FN(same_bits_)(got_v.distance, want.distance) && got_v.flags == want.flags,
                   "%s pose %zu (voted order): walk %.17g, CPU %.17g", c->name, i, (double)got_v.distance,
                   (double)want.distance);
        if (want.flags & TTD_MESH_ABOVE_BOUND) {
            ENSURE(got.tri_a == UINT32_MAX && got.tri_b == UINT32_MAX && isinf(got.distance));
            ++st->above;
        } else if (got.tri_a == want.tri_a && got.tri_b == want.tri_b) {
            /* the same pair: the whole record but the counts */
            ENSURE_MSG(memcmp(got.p, want.p, sizeof got.p) == 0 && memcmp(got.q, want.q, sizeof got.q) == 0 &&
                           got.feature_a == want.feature_a && got.feature_b == want.feature_b,
                       "%s pose %zu: same pair, other points", c->name, i);
            ++st->same_pair;
        } else {
            /* a tie: the walk's pair is at the same distance, and its points are that pair's */
            GW_CAT(ttd_result_, GW_SUF) r;
            ENSURE(GW_FN(pair_result_)(c, pose, got.tri_a, got.tri_b, &r) == TTD_OK);
            ENSURE_MSG(GW_FN(same_bits_)(r.distance, want.distance) && memcmp(got.p, r.p, sizeof r.p) == 0 &&
                           (got.distance == 0 || memcmp(got.q, r.q, sizeof r.q) == 0) &&
                           got.feature_a == r.feature_p && got.feature_b == r.feature_q,
                       "%s pose %zu: the walk's pair (%u, %u) at %.17g, the CPU's (%u, %u) at %.17g", c->name, i,
                       got.tri_a, got.tri_b, (double)r.distance, want.tri_a, want.tri_b, (double)want.distance);
            ++st->tie_pair;
        }
        /* collision: the CPU's verdict; a witness within the margin */
        ENSURE_MSG(cg.hit == cw.hit && cg_v.hit == cw.hit, "%s pose %zu: walk hit %u (voted %u), CPU %u", c->name, i,
                   cg.hit, cg_v.hit, cw.hit);
        if (cg.hit) {
            GW_CAT(ttd_result_, GW_SUF) r;
            ENSURE(GW_FN(pair_result_)(c, pose, cg.tri_a, cg.tri_b, &r) == TTD_OK);
            ENSURE_MSG(r.distance <= mg, "%s pose %zu: witness at %.17g, margin %.17g", c->name, i, (double)r.distance,
                       (double)mg);
            st->hits += 1;
            st->same_witness += cg.tri_a == cw.tri_a && cg.tri_b == cw.tri_b;
        } else {
            ENSURE(cg.tri_a == UINT32_MAX && cg.tri_b == UINT32_MAX);
        }
        st->zero += want.distance == 0;
    }
    return 0;
}

#undef GW_FN
#undef GW_CAT
#undef GW_CAT2
