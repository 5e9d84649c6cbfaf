/* SPDX-License-Identifier: MIT */
/* The machine `ttd bench` runs on: a description for the header (CPU model and SIMD flags
 * from /proc/cpuinfo, cores, memory, the instruction sets ttd built and can run) and three
 * small probes whose numbers the analysis compares the kernels against:
 *   - the core clock, from a chain of dependent integer adds (one per cycle on every x86 core
 *     of the last decade);
 *   - peak arithmetic of one core per instruction set: independent chains of multiply-adds
 *     (FMA on AVX2/AVX-512, mul and add on SSE2 and scalar, as the baseline build issues them);
 *   - memory bandwidth: a plain copy loop and a read loop over buffers far larger than the
 *     caches, on one thread and on every core.
 * The probe loops on x86 use intrinsics in functions given their own target attribute, so
 * the rest of the program stays at the baseline instruction set. */
#define _POSIX_C_SOURCE 200809L
#include "bench_internal.h"

#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/utsname.h>
#include <time.h>
#include <unistd.h>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define BENCH_X86 1
#endif

double bench_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_seconds(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int bench_time_call(int (*fn)(void *arg), void *arg, double min_s, double max_row_s, int samples, int single_long,
                    bench_timing *out)
{
    double t[64];
    int have = 0;
    double t0 = bench_now();
    if (fn(arg))
        return -1;
    double one = bench_now() - t0;
    /* a call of a second or more is its own warm-up and the first sample (the builds and contacts
     * of the 1M-triangle torus: a fourth call would add seconds and change nothing) */
    if (one >= 1.0) {
        t[have++] = one;
    } else {
        t0 = bench_now();
        if (fn(arg))
            return -1;
        one = bench_now() - t0;
    }
    long passes = 1;
    if (have == 0 && one >= min_s)
        t[have++] = one;
    else if (have == 0)
        passes = (long)fmin(ceil(min_s / fmax(one, 1e-9)), 1e7);
    while (samples > 3 && one * (double)passes * samples > max_row_s)
        --samples;
    if (single_long && one >= 1.0 && samples > 1 && one * samples > max_row_s)
        samples = 1;
    if (samples > 64)
        samples = 64;
    while (have < samples) {
        t0 = bench_now();
        for (long k = 0; k < passes; ++k)
            if (fn(arg))
                return -1;
        t[have++] = (bench_now() - t0) / (double)passes;
    }
    qsort(t, (size_t)samples, sizeof t[0], cmp_seconds);
    out->med_s = samples % 2 ? t[samples / 2] : 0.5 * (t[samples / 2 - 1] + t[samples / 2]);
    out->min_s = t[0];
    out->samples = samples;
    out->passes = passes;
    return 0;
}

static double thread_cpu_now(void)
{
    struct timespec t;
    if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t) != 0)
        return BENCH_NAN;
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double median_sorted(double *t, int n)
{
    qsort(t, (size_t)n, sizeof t[0], cmp_seconds);
    return n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
}

int bench_time_alternating(int (*fa)(void *), void *a, int (*fb)(void *), void *b, int thread_cpu, double min_s,
                           int min_rounds, int max_rounds, double max_s, bench_alternation *out)
{
    double (*now)(void) = thread_cpu ? thread_cpu_now : bench_now;
    int (*fn[2])(void *) = {fa, fb};
    void *arg[2] = {a, b};
    double t[2][64], ratio[64], spent = 0.0;
    long passes[2];
    if (max_rounds > 64)
        max_rounds = 64;
    if (min_rounds < 1)
        min_rounds = 1;
    if (max_rounds < min_rounds)
        max_rounds = min_rounds > 64 ? 64 : min_rounds;
    for (int s = 0; s < 2; ++s) {
        const double t0 = now();
        if (fn[s](arg[s]))
            return -1;
        passes[s] = (long)fmin(fmax(ceil(min_s / fmax(now() - t0, 1e-9)), 1.0), 1e7);
    }
    int rounds = 0;
    while (rounds < max_rounds && (rounds < min_rounds || spent < max_s)) {
        for (int s = 0; s < 2; ++s) {
            const double t0 = now();
            for (long k = 0; k < passes[s]; ++k)
                if (fn[s](arg[s]))
                    return -1;
            const double dt = now() - t0;
            spent += dt;
            t[s][rounds] = dt / (double)passes[s];
        }
        if (!(t[0][rounds] > 0.0 && t[1][rounds] > 0.0))
            return -1; /* a clock too coarse for the sample: no ratio to sort */
        ratio[rounds] = t[0][rounds] / t[1][rounds];
        ++rounds;
    }
    out->rounds = rounds;
    out->passes[0] = passes[0];
    out->passes[1] = passes[1];
    out->ratio_med = median_sorted(ratio, rounds);
    out->ratio_lo = ratio[0];
    out->ratio_hi = ratio[rounds - 1];
    out->a_med_s = median_sorted(t[0], rounds);
    out->a_min_s = t[0][0];
    out->b_med_s = median_sorted(t[1], rounds);
    out->b_min_s = t[1][0];
    return 0;
}

static void trim(char *s)
{
    size_t n = strlen(s);
    while (n > 0 && (s[n - 1] == '\n' || s[n - 1] == ' ' || s[n - 1] == '\t'))
        s[--n] = '\0';
}

/* The value of the first "key : value" line of /proc/cpuinfo whose key starts with key. */
static int cpuinfo_field(const char *key, char *out, size_t size)
{
    FILE *f = fopen("/proc/cpuinfo", "r");
    char line[8192];
    int found = 0;
    if (!f)
        return 0;
    while (!found && fgets(line, sizeof line, f)) {
        char *colon = strchr(line, ':');
        if (strncmp(line, key, strlen(key)) == 0 && colon) {
            const char *v = colon + 1;
            while (*v == ' ')
                ++v;
            snprintf(out, size, "%s", v);
            trim(out);
            found = 1;
        }
    }
    fclose(f);
    return found;
}

/* Keeps the SIMD-related words of the cpuinfo flags line, in a fixed order. */
static void simd_flags(const char *flags, char *out, size_t size)
{
    static const char *const wanted[] = {"sse2", "sse4_1", "sse4_2", "avx", "avx2", "fma",
                                         "avx512f", "avx512dq", "avx512vl", "avx512bw",
                                         "avx512_vnni", "avx512_bf16", "asimd", "sve"};
    size_t used = 0;
    out[0] = '\0';
    for (size_t i = 0; i < sizeof wanted / sizeof wanted[0]; ++i) {
        size_t len = strlen(wanted[i]);
        const char *p = flags;
        while ((p = strstr(p, wanted[i])) != NULL) {
            int starts = p == flags || p[-1] == ' ';
            int ends = p[len] == ' ' || p[len] == '\0';
            if (starts && ends) {
                int k = snprintf(out + used, size - used, "%s%s", used ? " " : "", wanted[i]);
                if (k > 0 && (size_t)k < size - used)
                    used += (size_t)k;
                break;
            }
            p += len;
        }
    }
}

double bench_load_average(char *out, size_t size)
{
    /* TTD_BENCH_LOADAVG names a file read in place of /proc/loadavg (tests use it to check
     * the warning without loading the machine). */
    const char *path = getenv("TTD_BENCH_LOADAVG");
    FILE *f = fopen(path && path[0] ? path : "/proc/loadavg", "r");
    double a = 0.0, b = 0.0, c = 0.0, one = BENCH_NAN;
    if (f && fscanf(f, "%lf %lf %lf", &a, &b, &c) == 3) {
        snprintf(out, size, "%.2f %.2f %.2f", a, b, c);
        one = a;
    } else {
        snprintf(out, size, "?");
    }
    if (f)
        fclose(f);
    return one;
}

int bench_load_exceeds_cores(const bench_machine *m)
{
    return m->load1_start > (double)m->cores || m->load1_end > (double)m->cores;
}

void bench_machine_describe(bench_machine *m)
{
    char flags[8192];
    struct utsname u;
    memset(m, 0, sizeof *m);
    if (!cpuinfo_field("model name", m->cpu, sizeof m->cpu) &&
        !cpuinfo_field("Model", m->cpu, sizeof m->cpu))
        snprintf(m->cpu, sizeof m->cpu, "unknown");
    if (cpuinfo_field("flags", flags, sizeof flags) || cpuinfo_field("Features", flags, sizeof flags))
        simd_flags(flags, m->cpu_isas, sizeof m->cpu_isas);
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    m->cores = cores > 0 ? (int)cores : 1;
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    m->mem_gib = pages > 0 && page > 0 ? (double)pages * (double)page / (1024.0 * 1024.0 * 1024.0) : BENCH_NAN;
    if (uname(&u) == 0)
        snprintf(m->os, sizeof m->os, "%s %s %s", u.sysname, u.release, u.machine);
    size_t used = 0;
    for (int i = TTD_ISA_SCALAR; i < TTD_ISA_COUNT; ++i) {
        if (!ttd_isa_available((ttd_isa)i))
            continue;
        int k = snprintf(m->ttd_isas + used, sizeof m->ttd_isas - used, "%s%s", used ? " " : "",
                         ttd_isa_name((ttd_isa)i));
        if (k > 0 && (size_t)k < sizeof m->ttd_isas - used)
            used += (size_t)k;
    }
    m->load1_start = bench_load_average(m->load_start, sizeof m->load_start);
    m->load1_end = BENCH_NAN;
    {
        char group[64] = "";
        FILE *f = fopen("/proc/self/autogroup", "r");
        if (f) {
            if (fgets(group, sizeof group, f))
                trim(group);
            fclose(f);
        }
        errno = 0;
        int nice_value = getpriority(PRIO_PROCESS, 0);
        snprintf(m->priority, sizeof m->priority, "nice %d%s%s", errno ? 0 : nice_value, group[0] ? ", " : "",
                 group);
    }
    const char *a = ttd_isa_name(ttd_isa_selected(NULL));
    snprintf(m->isa_auto, sizeof m->isa_auto, "%s", a ? a : "?");
    m->ghz = BENCH_NAN;
    for (int i = 0; i < TTD_ISA_COUNT; ++i)
        m->peak_gflops_d[i] = BENCH_NAN;
    m->copy_gbs[0] = m->copy_gbs[1] = m->read_gbs[0] = m->read_gbs[1] = BENCH_NAN;
}

/* ---- clock ---------------------------------------------------------------------------- */

#ifdef BENCH_X86
/* 64 dependent adds per round: the chain runs at one add per cycle. */
static double adds_per_second(double seconds)
{
    uint64_t x = 0, rounds = 0;
    double t0 = bench_now(), t;
    do {
        for (int k = 0; k < 1024; ++k) {
            __asm__ volatile(".rept 64\n\taddq $1, %0\n\t.endr" : "+r"(x));
        }
        rounds += 1024;
        t = bench_now() - t0;
    } while (t < seconds);
    return (double)rounds * 64.0 / t;
}
#endif

/* ---- peak arithmetic ------------------------------------------------------------------ */

/* Each probe runs `reps` rounds of 12 independent multiply-add chains (enough to cover a
 * 4-cycle latency on 2 ports) and returns a value so that the work cannot be dropped. The
 * chains converge to a fixed point, so no value overflows or goes subnormal. The factor is
 * read from a volatile: otherwise the compiler may find the probe free of side effects and
 * move the call past the clock that times it. */
static volatile double probe_factor = 0.999;
#ifdef BENCH_X86
__attribute__((target("avx512f"))) static double chains_avx512(long reps)
{
    __m512d a[12], x = _mm512_set1_pd(probe_factor), y = _mm512_set1_pd(1e-3);
    for (int k = 0; k < 12; ++k)
        a[k] = _mm512_set1_pd(1.0 + k);
    for (long r = 0; r < reps; ++r) {
        for (int k = 0; k < 12; ++k)
            a[k] = _mm512_fmadd_pd(a[k], x, y);
    }
    __m512d s = a[0];
    for (int k = 1; k < 12; ++k)
        s = _mm512_add_pd(s, a[k]);
    double out[8];
    _mm512_storeu_pd(out, s);
    return out[0] + out[7];
}

__attribute__((target("avx2,fma"))) static double chains_avx2(long reps)
{
    __m256d a[12], x = _mm256_set1_pd(probe_factor), y = _mm256_set1_pd(1e-3);
    for (int k = 0; k < 12; ++k)
        a[k] = _mm256_set1_pd(1.0 + k);
    for (long r = 0; r < reps; ++r) {
        for (int k = 0; k < 12; ++k)
            a[k] = _mm256_fmadd_pd(a[k], x, y);
    }
    __m256d s = a[0];
    for (int k = 1; k < 12; ++k)
        s = _mm256_add_pd(s, a[k]);
    double out[4];
    _mm256_storeu_pd(out, s);
    return out[0] + out[3];
}

static double chains_sse2(long reps)
{
    __m128d a[12], x = _mm_set1_pd(probe_factor), y = _mm_set1_pd(1e-3);
    for (int k = 0; k < 12; ++k)
        a[k] = _mm_set1_pd(1.0 + k);
    for (long r = 0; r < reps; ++r) {
        for (int k = 0; k < 12; ++k)
            a[k] = _mm_add_pd(_mm_mul_pd(a[k], x), y);
    }
    __m128d s = a[0];
    for (int k = 1; k < 12; ++k)
        s = _mm_add_pd(s, a[k]);
    double out[2];
    _mm_storeu_pd(out, s);
    return out[0] + out[1];
}


/* Scalar chains: mulsd then addsd, as the baseline build issues them (intrinsics, so that
 * the compiler cannot pack the twelve chains into vectors). */
static double chains_scalar(long reps)
{
    __m128d a[12], x = _mm_set_sd(probe_factor), y = _mm_set_sd(1e-3);
    for (int k = 0; k < 12; ++k)
        a[k] = _mm_set_sd(1.0 + k);
    for (long r = 0; r < reps; ++r) {
        for (int k = 0; k < 12; ++k)
            a[k] = _mm_add_sd(_mm_mul_sd(a[k], x), y);
    }
    __m128d s = a[0];
    for (int k = 1; k < 12; ++k)
        s = _mm_add_sd(s, a[k]);
    return _mm_cvtsd_f64(s);
}
#else
/* Portable scalar chains (mul then add). */
static double chains_scalar(long reps)
{
    double a[12], x = probe_factor, y = 1e-3, s = 0.0;
    for (int k = 0; k < 12; ++k)
        a[k] = 1.0 + k;
    for (long r = 0; r < reps; ++r) {
        for (int k = 0; k < 12; ++k)
            a[k] = a[k] * x + y;
    }
    for (int k = 0; k < 12; ++k)
        s += a[k];
    return s;
}
#endif

typedef double (*chains_fn)(long reps);

/* GFLOP/s (2 per multiply-add per lane) of one probe, best of three timed runs. */
static double peak_of(chains_fn fn, int lanes, double seconds)
{
    volatile double sink = 0.0;
    long reps = 1 << 12;
    double took = 0.0;
    for (;;) { /* grow until one run lasts about a third of the budget */
        double t0 = bench_now();
        sink = sink + fn(reps);
        took = bench_now() - t0;
        if (took > seconds / 3.0 || reps > (1L << 40))
            break;
        reps *= 2;
    }
    double best = took;
    for (int i = 0; i < 3; ++i) {
        double t0 = bench_now();
        sink = sink + fn(reps);
        double t = bench_now() - t0;
        if (t < best)
            best = t;
    }
    (void)sink;
    return (double)reps * 12.0 * 2.0 * lanes / best * 1e-9;
}

/* ---- memory bandwidth ----------------------------------------------------------------- */

typedef struct stream_job {
    const uint64_t *src;
    uint64_t *dst;       /* NULL: read only */
    size_t count;
    uint64_t sum;
} stream_job;

static void *stream_worker(void *arg)
{
    stream_job *j = arg;
    if (j->dst) {
        for (size_t i = 0; i < j->count; ++i)
            j->dst[i] = j->src[i];
    } else {
        uint64_t s0 = 0, s1 = 0, s2 = 0, s3 = 0;
        size_t i = 0;
        for (; i + 4 <= j->count; i += 4) {
            s0 += j->src[i];
            s1 += j->src[i + 1];
            s2 += j->src[i + 2];
            s3 += j->src[i + 3];
        }
        for (; i < j->count; ++i)
            s0 += j->src[i];
        j->sum = s0 + s1 + s2 + s3;
    }
    return NULL;
}

/* Best of several runs of `threads` workers over count words, in GB/s (1e9 bytes), counting
 * bytes read plus bytes written (not the write-allocate reads a copy also causes). */
static double stream_gbs(const uint64_t *src, uint64_t *dst, size_t count, int threads, int runs)
{
    pthread_t tid[64];
    stream_job jobs[64];
    double best = BENCH_INF;
    if (threads > 64)
        threads = 64;
    for (int r = 0; r < runs; ++r) {
        double t0 = bench_now();
        int started = 0;
        for (int k = 0; k < threads; ++k) {
            size_t lo = count * (size_t)k / (size_t)threads, hi = count * (size_t)(k + 1) / (size_t)threads;
            jobs[k] = (stream_job){src + lo, dst ? dst + lo : NULL, hi - lo, 0};
            if (k == 0 || pthread_create(&tid[k], NULL, stream_worker, &jobs[k]) == 0)
                started = k + 1;
            else
                break;
        }
        stream_worker(&jobs[0]);
        for (int k = 1; k < started; ++k)
            pthread_join(tid[k], NULL);
        double t = bench_now() - t0;
        if (started == threads && t < best)
            best = t;
    }
    double bytes = (double)count * 8.0 * (dst ? 2.0 : 1.0);
    return isfinite(best) ? bytes / best * 1e-9 : BENCH_NAN;
}

void bench_machine_probe(bench_machine *m, double seconds, size_t stream_bytes)
{
#ifdef BENCH_X86
    m->ghz = adds_per_second(seconds) * 1e-9;
    m->peak_gflops_d[TTD_ISA_SCALAR] = peak_of(chains_scalar, 1, seconds);
    m->peak_gflops_d[TTD_ISA_SSE2] = peak_of(chains_sse2, 2, seconds);
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
        m->peak_gflops_d[TTD_ISA_AVX2] = peak_of(chains_avx2, 4, seconds);
    if (__builtin_cpu_supports("avx512f"))
        m->peak_gflops_d[TTD_ISA_AVX512] = peak_of(chains_avx512, 8, seconds);
#else
    m->peak_gflops_d[TTD_ISA_SCALAR] = peak_of(chains_scalar, 1, seconds);
#endif
    size_t count = stream_bytes / 8;
    uint64_t *src = malloc(count * sizeof *src), *dst = malloc(count * sizeof *dst);
    if (src && dst) {
        for (size_t i = 0; i < count; ++i) { /* touch every page before timing */
            src[i] = i;
            dst[i] = 0;
        }
        m->copy_gbs[0] = stream_gbs(src, dst, count, 1, 5);
        m->copy_gbs[1] = stream_gbs(src, dst, count, m->cores, 5);
        m->read_gbs[0] = stream_gbs(src, NULL, count, 1, 5);
        m->read_gbs[1] = stream_gbs(src, NULL, count, m->cores, 5);
    }
    free(src);
    free(dst);
}

/* Instruction sets from the fastest down: the portable row is plain C over lane arrays, slower
 * than any native SIMD row, so it ranks just above scalar (its enum value is the highest). */
static const ttd_isa isa_preference[] = {TTD_ISA_AVX512, TTD_ISA_NEON, TTD_ISA_AVX2, TTD_ISA_SSE2, TTD_ISA_PORTABLE,
                                         TTD_ISA_SCALAR};

ttd_isa bench_best_isa(unsigned mask)
{
    for (size_t i = 0; i < sizeof isa_preference / sizeof isa_preference[0]; ++i)
        if ((mask & (1u << isa_preference[i])) && ttd_isa_available(isa_preference[i]))
            return isa_preference[i];
    return TTD_ISA_AUTO;
}
