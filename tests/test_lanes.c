/* SPDX-License-Identifier: MIT */
/* The lane layer (src/simd/lanes_*.h) against scalar C, for every instruction set that is
 * built into the library and that this CPU runs; the others are skipped with a printed
 * reason. Each ISA's translation unit exports a probe (src/simd/probe.h) that applies one
 * lane operation to plain arrays, so the code checked here is the code the kernels inline,
 * compiled with that ISA's flags. Expected values come from plain scalar C (and libm's fma
 * where the ISA has FMA), bit for bit. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "simd/probe.h"
#include "isa_rows.h"
#include "test_macros.h"

static uint64_t lanes_rng(uint64_t *st)
{
    /* splitmix64 */
    uint64_t z = (*st += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static double lanes_uniform(uint64_t *st, double lo, double hi)
{
    return lo + (hi - lo) * ((double)(lanes_rng(st) >> 11) * 0x1p-53);
}

#define TTD_PRECISION_DOUBLE
#include "precision_open.h"
#include "lanes_check_impl.h"
#include "precision_close.h"
#define TTD_PRECISION_FLOAT
#include "precision_open.h"
#include "lanes_check_impl.h"
#include "precision_close.h"

/* The rows built into the library (src/CMakeLists.txt defines TTD_HAVE_<ISA> for internal
 * users), with what the CPU must support to run them; and the tests' cuda-host row
 * (tests/cuda_host/, src/simd/lanes_cuda.h compiled for the host). */
typedef struct isa_probe {
    const char *name;
    int has_fma;
    ttd_lanes_probe_d_fn d;
    ttd_lanes_probe_f_fn f;
} isa_probe;

static const isa_probe probes[] = {
#ifdef TTD_HAVE_SSE2
    {"sse2", 0, ttd_lanes_probe_sse2_d, ttd_lanes_probe_sse2_f},
#endif
#ifdef TTD_HAVE_AVX2
    {"avx2", 1, ttd_lanes_probe_avx2_d, ttd_lanes_probe_avx2_f},
#endif
#ifdef TTD_HAVE_AVX512
    {"avx512", 1, ttd_lanes_probe_avx512_d, ttd_lanes_probe_avx512_f},
#endif
#ifdef TTD_HAVE_NEON
    {"neon", 1, ttd_lanes_probe_neon_d, ttd_lanes_probe_neon_f},
#endif
#ifdef TTD_HAVE_PORTABLE
    {"portable", 0, ttd_lanes_probe_portable_d, ttd_lanes_probe_portable_f},
#endif
#ifdef TTD_HAVE_CUDA_HOST
    {"cuda-host", 1, ttd_lanes_probe_cuda_host_d, ttd_lanes_probe_cuda_host_f},
#endif
    {NULL, 0, NULL, NULL},
};


static int lanes_every_isa(void)
{
    int ran = 0;
    for (const isa_probe *p = probes; p->name; ++p) {
        const char *why = "";
        if (!cpu_runs(p->name, &why)) {
            printf("  skip %s: %s\n", p->name, why);
            continue;
        }
        uint64_t st = 0x1234u + (uint64_t)ran;
        double z[16] = {0}, zo[16];
        char name[32];
        snprintf(name, sizeof name, "%s double", p->name);
        ENSURE(check_lane_ops_d(name, p->d, p->has_fma, &st, 400) == 0);
        ENSURE(check_reductions_d(name, p->d, &st, 200) == 0);
        ENSURE(check_transpose_d(name, p->d, &st) == 0);
        snprintf(name, sizeof name, "%s float", p->name);
        ENSURE(check_lane_ops_f(name, p->f, p->has_fma, &st, 400) == 0);
        ENSURE(check_reductions_f(name, p->f, &st, 200) == 0);
        ENSURE(check_transpose_f(name, p->f, &st) == 0);
        ENSURE(check_widen_f(name, p->f, &st) == 0);
        ENSURE(p->d(TTDW_OP_WIDEN, z, z, z, zo) == -1);
        printf("  %s: every lane op, both precisions\n", p->name);
        ++ran;
    }
    if (!ran)
        printf("  no SIMD row runs here: nothing checked\n");
    return 0;
}

/* The probes reject an unknown op instead of guessing. */
static int lanes_unknown_op(void)
{
    for (const isa_probe *p = probes; p->name; ++p) {
        const char *why = "";
        if (!cpu_runs(p->name, &why))
            continue;
        double a[16] = {0}, out[16];
        float af[16] = {0}, outf[16];
        ENSURE(p->d(TTDW_OP_COUNT, a, a, a, out) == -1);
        ENSURE(p->f(TTDW_OP_COUNT, af, af, af, outf) == -1);
    }
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(lanes_every_isa);
    RUN_TEST(lanes_unknown_op);
    TEST_MAIN_END();
}
