/* SPDX-License-Identifier: MIT */
/* One pair of a GPU batch, precision-generic: what each CUDA thread runs (src/gpu/gpu_d.cu,
 * gpu_f.cu) and what the tests' cuda-host row runs on the host (tests/cuda_host/), from this one
 * source. Included after simd/kernels for one precision with TTDW_USE_CUDA (one lane).
 *
 * A pair with a NaN or infinite coordinate gets what the CPU batch gives it (engine/batch_impl.h,
 * sink_finish): NaN distance, points and weights, TTD_PAIR_NONFINITE, no features; any other pair
 * goes through the exact kernel's one-lane group (kx_run), which is the scalar row's bits. */

TTDW_FN int gpu_pair_finite(const real *s, const real *t)
{
    int ok = 1;
    for (int k = 0; k < 9; ++k)
        ok &= (s[k] - s[k] == 0) & (t[k] - t[k] == 0); /* x - x is 0 unless x is NaN or inf */
    return ok;
}

/* Pair i of s, t (9 reals each) into distance[i] and results[i], either of which may be NULL. */
TTDW_FN void gpu_pair(size_t i, const real *s, const real *t, real *distance, ttd_result *results)
{
    const real *si = s + 9 * i, *ti = t + 9 * i;
    if (!gpu_pair_finite(si, ti)) {
        const real nan = (real)NAN;
        if (distance)
            distance[i] = nan;
        if (results) {
            ttd_result *r = &results[i];
            r->distance = nan;
            for (int c = 0; c < 3; ++c)
                r->p[c] = r->q[c] = r->bary_p[c] = r->bary_q[c] = nan;
            r->flags = TTD_PAIR_NONFINITE;
            r->feature_p = r->feature_q = 0;
            r->iterations = 0;
        }
        return;
    }
    const ttd_out o = {distance ? distance + i : NULL, NULL, results ? results + i : NULL};
    kx_run(1, si, ti, &o);
}
