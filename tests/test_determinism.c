/* SPDX-License-Identifier: MIT */
/* Determinism of the exact method through the public batch API:
 *   - for each instruction set and precision, thread counts 1, 2, 3 and 8 give bit-identical
 *     results (every field), on a batch large enough that 8 workers really run (the engine
 *     gives a worker at least 8 blocks of 256 pairs), with pairs from every generator family
 *     and a non-finite pair in the middle; a second call gives the same bits again;
 *   - across instruction sets the distances agree within the method's accuracy target
 *     (1e-12 of max(d, size) in double, 1e-5 in float; size from the quad reference's helper),
 *     so do the closest points (plus the rounding at the coordinates' magnitude, which an FMA
 *     in a row's rebuild of p would change), and the
 *     intersecting flag agrees wherever the distance is not within that tolerance of 0.
 *   - six callers at once (each with 2 worker threads, each on its own ISA and precision) get
 *     the same bits as one caller alone: the library keeps no mutable state between calls.
 * (tests/test_api.c checks thread counts for every method on the default instruction set; this
 * file pins the exact method on every one.) The number of pairs that are bit-identical across
 * instruction sets is printed, not asserted. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "pairs.h"
#include "ref_distance.h"
#include "test_macros.h"
#include "ttd/ttd.h"

enum { N = 8 * 8 * 256 + 77 }; /* 65 blocks: 8 workers get 8 blocks each, plus a tail */

static double S[9 * N], T[9 * N];
static float Sf[9 * N], Tf[9 * N];
static double SIZE[N];
static ttd_result_d R1[N], RK[N], RISA[TTD_ISA_COUNT][N];
static ttd_result_f RF1[N], RFK[N], RFISA[TTD_ISA_COUNT][N];

/* Pairs from every family, interleaved by blocks of 97 so that every block mixes families. */
static void make_pairs(void)
{
    static double s[9 * N], t[9 * N];
    size_t per = N / TTD_GEN_COUNT + 1;
    for (int f = 0; f < TTD_GEN_COUNT; ++f) {
        size_t m = per;
        if ((size_t)f * per + m > N)
            m = N - (size_t)f * per;
        ttd_gen((ttd_gen_family)f, 42, m, s + 9 * f * per, t + 9 * f * per);
    }
    /* shuffle deterministically: pair i goes to (i * 97) mod N (97 is prime to N) */
    for (size_t i = 0; i < N; ++i) {
        size_t j = (i * 97) % N;
        memcpy(S + 9 * j, s + 9 * i, 9 * sizeof(double));
        memcpy(T + 9 * j, t + 9 * i, 9 * sizeof(double));
    }
    S[9 * (N / 2) + 4] = (double)NAN;
    for (size_t k = 0; k < 9 * N; ++k)
        Sf[k] = (float)S[k], Tf[k] = (float)T[k];
    for (size_t i = 0; i < N; ++i)
        SIZE[i] = ttd_ref_size(S + 9 * i, T + 9 * i);
}

static ttd_options opts(ttd_isa isa, int threads)
{
    ttd_options o = ttd_default_options();
    o.method = TTD_METHOD_EXACT;
    o.isa = isa;
    o.threads = threads;
    return o;
}

/* One thread, every ISA: the results both tests compare against. */
static int run_isas(void)
{
    for (int isa = TTD_ISA_SCALAR; isa < TTD_ISA_COUNT; ++isa) {
        if (!ttd_isa_available((ttd_isa)isa))
            continue;
        ttd_options o = opts((ttd_isa)isa, 1);
        ENSURE(ttd_batch_d(&o, N, S, T, NULL, RISA[isa]) == TTD_ERR_NONFINITE_INPUT);
        ENSURE(ttd_batch_f(&o, N, Sf, Tf, NULL, RFISA[isa]) == TTD_ERR_NONFINITE_INPUT);
    }
    return 0;
}

static int threads_bit_identical(void)
{
    static const int counts[] = {2, 3, 8, 1};
    for (int isa = TTD_ISA_SCALAR; isa < TTD_ISA_COUNT; ++isa) {
        if (!ttd_isa_available((ttd_isa)isa))
            continue;
        ttd_options o = opts((ttd_isa)isa, 1);
        memcpy(R1, RISA[isa], sizeof R1);
        memcpy(RF1, RFISA[isa], sizeof RF1);
        for (size_t c = 0; c < sizeof counts / sizeof counts[0]; ++c) {
            o.threads = counts[c];
            memset(RK, 0x5a, sizeof RK);
            memset(RFK, 0x5a, sizeof RFK);
            ENSURE(ttd_batch_d(&o, N, S, T, NULL, RK) == TTD_ERR_NONFINITE_INPUT);
            ENSURE(ttd_batch_f(&o, N, Sf, Tf, NULL, RFK) == TTD_ERR_NONFINITE_INPUT);
            for (size_t i = 0; i < N; ++i) {
                ENSURE_MSG(memcmp(&R1[i], &RK[i], sizeof R1[i]) == 0, "%s double, %d threads: pair %zu differs",
                           ttd_isa_name((ttd_isa)isa), counts[c], i);
                ENSURE_MSG(memcmp(&RF1[i], &RFK[i], sizeof RF1[i]) == 0, "%s float, %d threads: pair %zu differs",
                           ttd_isa_name((ttd_isa)isa), counts[c], i);
            }
        }
    }
    return 0;
}

static int isas_agree(void)
{
    int any_simd = 0;
    for (int isa = TTD_ISA_SCALAR + 1; isa < TTD_ISA_COUNT; ++isa) {
        if (!ttd_isa_available((ttd_isa)isa))
            continue;
        any_simd = 1;
        size_t same_d = 0, same_f = 0;
        double worst_d = 0, worst_f = 0;
        for (size_t i = 0; i < N; ++i) {
            const ttd_result_d *a = &RISA[TTD_ISA_SCALAR][i], *b = &RISA[isa][i];
            const ttd_result_f *af = &RFISA[TTD_ISA_SCALAR][i], *bf = &RFISA[isa][i];
            same_d += memcmp(a, b, sizeof *a) == 0;
            same_f += memcmp(af, bf, sizeof *af) == 0;
            if (a->flags & TTD_PAIR_NONFINITE) {
                ENSURE(b->flags == a->flags && isnan(b->distance) && bf->flags == af->flags && isnan(bf->distance));
                continue;
            }
            double scale = fmax(a->distance, SIZE[i]);
            double ed = scale > 0 ? fabs(a->distance - b->distance) / scale : fabs(a->distance - b->distance);
            double sf = fmax((double)af->distance, SIZE[i]);
            double ef = sf > 0 ? fabs((double)af->distance - (double)bf->distance) / sf
                               : fabs((double)af->distance - (double)bf->distance);
            worst_d = fmax(worst_d, ed), worst_f = fmax(worst_f, ef);
            ENSURE_MSG(ed <= 1e-12, "%s vs scalar, double, pair %zu: %.17g vs %.17g", ttd_isa_name((ttd_isa)isa), i,
                       b->distance, a->distance);
            ENSURE_MSG(ef <= 1e-5, "%s vs scalar, float, pair %zu: %.9g vs %.9g", ttd_isa_name((ttd_isa)isa), i,
                       (double)bf->distance, (double)af->distance);
            /* closest points: within the same tolerance plus the rounding at the coordinates'
             * magnitude (an FMA in the weighted sum would move them by an ulp) */
            double mag = 0;
            for (int k = 0; k < 9; ++k)
                mag = fmax(mag, fmax(fabs(S[9 * i + k]), fabs(T[9 * i + k])));
            for (int k = 0; k < 3; ++k) {
                ENSURE_MSG(fabs(a->p[k] - b->p[k]) <= 1e-12 * scale + 4e-16 * mag &&
                               fabs(a->q[k] - b->q[k]) <= 1e-12 * scale + 4e-16 * mag,
                           "%s vs scalar, double, pair %zu: p or q differ", ttd_isa_name((ttd_isa)isa), i);
                ENSURE_MSG(fabs((double)af->p[k] - (double)bf->p[k]) <= 1e-5 * sf + 2.4e-7 * mag &&
                               fabs((double)af->q[k] - (double)bf->q[k]) <= 1e-5 * sf + 2.4e-7 * mag,
                           "%s vs scalar, float, pair %zu: p or q differ", ttd_isa_name((ttd_isa)isa), i);
            }
            if (a->distance > 1e-12 * scale || b->distance > 1e-12 * scale)
                ENSURE_MSG((a->flags & TTD_PAIR_INTERSECTING) == (b->flags & TTD_PAIR_INTERSECTING),
                           "%s vs scalar, pair %zu: intersecting flag differs", ttd_isa_name((ttd_isa)isa), i);
        }
        printf("  %s vs scalar: %zu/%d double and %zu/%d float results bit-identical; worst distance difference "
               "%.2e (double), %.2e (float) of max(d, size)\n",
               ttd_isa_name((ttd_isa)isa), same_d, N, same_f, N, worst_d, worst_f);
    }
    if (!any_simd)
        printf("  only the scalar instruction set is available here\n");
    return 0;
}

/* One concurrent caller: its ISA and precision, its own output, and whether it matched. */
typedef struct caller {
    ttd_isa isa;
    int is_float, rounds, ok;
    ttd_result_d *rd;
    ttd_result_f *rf;
} caller;

static void *caller_run(void *arg)
{
    caller *c = arg;
    ttd_options o = opts(c->isa, 2);
    c->ok = 1;
    for (int k = 0; k < c->rounds && c->ok; ++k) {
        if (c->is_float) {
            c->ok = ttd_batch_f(&o, N, Sf, Tf, NULL, c->rf) == TTD_ERR_NONFINITE_INPUT &&
                    memcmp(c->rf, RFISA[c->isa], sizeof RF1) == 0;
        } else {
            c->ok = ttd_batch_d(&o, N, S, T, NULL, c->rd) == TTD_ERR_NONFINITE_INPUT &&
                    memcmp(c->rd, RISA[c->isa], sizeof R1) == 0;
        }
    }
    return NULL;
}

static int concurrent_callers(void)
{
    enum { NC = 6 };
    static ttd_result_d rd[NC][N];
    static ttd_result_f rf[NC][N];
    ttd_isa isas[TTD_ISA_COUNT];
    int nisa = 0;
    for (int isa = TTD_ISA_SCALAR; isa < TTD_ISA_COUNT; ++isa)
        if (ttd_isa_available((ttd_isa)isa))
            isas[nisa++] = (ttd_isa)isa;
    caller c[NC];
    pthread_t tid[NC];
    for (int k = 0; k < NC; ++k) {
        c[k] = (caller){isas[k % nisa], k & 1, 3, 0, rd[k], rf[k]};
        ENSURE(pthread_create(&tid[k], NULL, caller_run, &c[k]) == 0);
    }
    for (int k = 0; k < NC; ++k)
        ENSURE(pthread_join(tid[k], NULL) == 0);
    for (int k = 0; k < NC; ++k)
        ENSURE_MSG(c[k].ok, "caller %d (%s, %s) got different results", k, ttd_isa_name(c[k].isa),
                   c[k].is_float ? "float" : "double");
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    make_pairs();
    if (run_isas()) {
        printf("FAIL: the one-thread runs\n");
        return 1;
    }
    RUN_TEST(threads_bit_identical);
    RUN_TEST(isas_agree);
    RUN_TEST(concurrent_callers);
    TEST_MAIN_END();
}
