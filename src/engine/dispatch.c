/* SPDX-License-Identifier: MIT */
/* CPU and OS feature detection and the table of ISA rows (xxHash's x86 dispatcher shape).
 *
 * This file is compiled with the baseline flags only: if it were built with -mavx the
 * compiler could emit AVX instructions anywhere in it, including on the path that decides
 * whether AVX may be used. The detection asks CPUID what the CPU implements and XGETBV what
 * the OS saves on a context switch (a CPU may have AVX-512 while the OS does not preserve the
 * ZMM registers). The answer is kept in one atomic word, written once with a value that
 * every thread computes alike (CPUID traps to the hypervisor in a virtual machine, costing
 * microseconds per call, which a single-pair call should not pay). That cache is the only
 * static state in the library, and it holds a fact of the hardware, not of any call. */
#if defined(__AVX__)
#error "engine/dispatch.c must be compiled with baseline flags (no -mavx...): see the comment above"
#endif

#include "engine/dispatch.h"

#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#if defined(__x86_64__) || defined(__i386__) || defined(_M_X64)
#define TTD_DISPATCH_X86 1
#include <cpuid.h>
#endif

/* The tables, indexed by ttd_isa; NULL where a row was not built. */
static const ttd_kernels_d *const ttd_rows_d[TTD_ISA_COUNT] = {
    [TTD_ISA_AUTO] = NULL,
    [TTD_ISA_SCALAR] = &ttd_kernels_scalar_d,
#ifdef TTD_HAVE_SSE2
    [TTD_ISA_SSE2] = &ttd_kernels_sse2_d,
#endif
#ifdef TTD_HAVE_AVX2
    [TTD_ISA_AVX2] = &ttd_kernels_avx2_d,
#endif
#ifdef TTD_HAVE_AVX512
    [TTD_ISA_AVX512] = &ttd_kernels_avx512_d,
#endif
#ifdef TTD_HAVE_NEON
    [TTD_ISA_NEON] = &ttd_kernels_neon_d,
#endif
#ifdef TTD_HAVE_PORTABLE
    [TTD_ISA_PORTABLE] = &ttd_kernels_portable_d,
#endif
};

static const ttd_kernels_f *const ttd_rows_f[TTD_ISA_COUNT] = {
    [TTD_ISA_AUTO] = NULL,
    [TTD_ISA_SCALAR] = &ttd_kernels_scalar_f,
#ifdef TTD_HAVE_SSE2
    [TTD_ISA_SSE2] = &ttd_kernels_sse2_f,
#endif
#ifdef TTD_HAVE_AVX2
    [TTD_ISA_AVX2] = &ttd_kernels_avx2_f,
#endif
#ifdef TTD_HAVE_AVX512
    [TTD_ISA_AVX512] = &ttd_kernels_avx512_f,
#endif
#ifdef TTD_HAVE_NEON
    [TTD_ISA_NEON] = &ttd_kernels_neon_f,
#endif
#ifdef TTD_HAVE_PORTABLE
    [TTD_ISA_PORTABLE] = &ttd_kernels_portable_f,
#endif
};

_Static_assert(TTD_ISA_PORTABLE == TTD_ISA_COUNT - 1, "update ttd_rows_d, ttd_rows_f and ttd_preference with ttd_isa");

/* Auto picks the first of these that is built and supported. */
static const ttd_isa ttd_preference[] = {TTD_ISA_AVX512, TTD_ISA_AVX2,     TTD_ISA_SSE2,
                                         TTD_ISA_NEON,   TTD_ISA_PORTABLE, TTD_ISA_SCALAR};

#ifdef TTD_DISPATCH_X86
/* XCR0: which register states the OS saves. Inline asm, so that no -mxsave is needed. */
static unsigned long long ttd_xgetbv0(void)
{
    unsigned int eax, edx;
    __asm__ volatile("xgetbv" : "=a"(eax), "=d"(edx) : "c"(0));
    return ((unsigned long long)edx << 32) | eax;
}

static int ttd_x86_supports(ttd_isa isa)
{
    unsigned int a, b, c, d;
    if (!__get_cpuid(1, &a, &b, &c, &d))
        return 0;
    const int sse2 = (d >> 26) & 1;
    if (isa == TTD_ISA_SSE2)
        return sse2;
    const int osxsave = (c >> 27) & 1, avx = (c >> 28) & 1, fma = (c >> 12) & 1;
    if (!sse2 || !osxsave || !avx)
        return 0;
    const unsigned long long xcr0 = ttd_xgetbv0();
    const int os_ymm = (xcr0 & 0x6) == 0x6;     /* XMM and YMM state */
    const int os_zmm = (xcr0 & 0xe6) == 0xe6;   /* plus opmask, ZMM_Hi256, Hi16_ZMM */
    if (!os_ymm || __get_cpuid_max(0, NULL) < 7)
        return 0;
    __cpuid_count(7, 0, a, b, c, d);
    const int avx2 = (b >> 5) & 1;
    const int avx512f = (b >> 16) & 1, avx512dq = (b >> 17) & 1, avx512vl = (b >> 31) & 1;
    if (isa == TTD_ISA_AVX2)
        return avx2 && fma;
    if (isa == TTD_ISA_AVX512)
        return os_zmm && avx2 && fma && avx512f && avx512dq && avx512vl;
    return 0;
}
#endif

int ttd_dispatch_isa_built(ttd_isa isa)
{
    return (int)isa > 0 && (int)isa < TTD_ISA_COUNT && ttd_rows_d[isa] != NULL;
}

static int ttd_detect(ttd_isa isa)
{
    switch (isa) {
    case TTD_ISA_SCALAR:
    case TTD_ISA_PORTABLE: /* baseline code of whatever target it was built for */
        return 1;
#ifdef TTD_DISPATCH_X86
    case TTD_ISA_SSE2:
    case TTD_ISA_AVX2:
    case TTD_ISA_AVX512:
        return ttd_x86_supports(isa);
#endif
#if defined(__aarch64__) || defined(_M_ARM64)
    case TTD_ISA_NEON: /* Advanced SIMD is part of every AArch64 CPU */
        return 1;
#endif
    default:
        return 0;
    }
}

/* Bit i: ISA i runs here; bit 31: detection done. */
static atomic_uint ttd_cpu_bits;

int ttd_dispatch_cpu_supports(ttd_isa isa)
{
    if ((int)isa <= 0 || (int)isa >= TTD_ISA_COUNT)
        return 0;
    unsigned bits = atomic_load_explicit(&ttd_cpu_bits, memory_order_relaxed);
    if (bits == 0) {
        bits = 1u << 31;
        for (int i = 1; i < TTD_ISA_COUNT; ++i)
            if (ttd_detect((ttd_isa)i))
                bits |= 1u << i;
        atomic_store_explicit(&ttd_cpu_bits, bits, memory_order_relaxed);
    }
    return (int)((bits >> isa) & 1u);
}

ttd_isa ttd_dispatch_best(void)
{
    for (size_t i = 0; i < sizeof ttd_preference / sizeof ttd_preference[0]; ++i)
        if (ttd_dispatch_isa_built(ttd_preference[i]) && ttd_dispatch_cpu_supports(ttd_preference[i]))
            return ttd_preference[i];
    return TTD_ISA_SCALAR;
}

const ttd_kernels_d *ttd_dispatch_row_d(ttd_isa isa)
{
    return ttd_dispatch_isa_built(isa) ? ttd_rows_d[isa] : NULL;
}

const ttd_kernels_f *ttd_dispatch_row_f(ttd_isa isa)
{
    return ttd_dispatch_isa_built(isa) ? ttd_rows_f[isa] : NULL;
}

ttd_kernel_d_fn ttd_dispatch_kernel_d(ttd_isa isa, ttd_method method)
{
    ttd_kernel_d_fn fn = ttd_rows_d[isa]->fn[method];
    return fn != NULL ? fn : ttd_kernels_scalar_d.fn[method];
}

ttd_kernel_f_fn ttd_dispatch_kernel_f(ttd_isa isa, ttd_method method)
{
    ttd_kernel_f_fn fn = ttd_rows_f[isa]->fn[method];
    return fn != NULL ? fn : ttd_kernels_scalar_f.fn[method];
}

/* Equal ignoring ASCII case. */
static int ttd_same_name(const char *a, const char *b)
{
    for (; *a && *b; ++a, ++b) {
        const int ca = *a >= 'A' && *a <= 'Z' ? *a - 'A' + 'a' : *a, cb = *b >= 'A' && *b <= 'Z' ? *b - 'A' + 'a' : *b;
        if (ca != cb)
            return 0;
    }
    return *a == *b;
}

ttd_isa ttd_dispatch_isa_from_name(const char *name)
{
    for (int i = 0; name != NULL && i < TTD_ISA_COUNT; ++i)
        if (ttd_same_name(name, ttd_isa_name((ttd_isa)i)))
            return (ttd_isa)i;
    return TTD_ISA_COUNT;
}

/* What TTD_ISA asks for: AUTO when unset, empty, "auto", or a name this machine cannot use
 * (ignored: see ttd_dispatch_env_note); otherwise that ISA. */
static ttd_isa ttd_isa_from_env(void)
{
    const char *v = getenv("TTD_ISA");
    if (v == NULL || v[0] == '\0')
        return TTD_ISA_AUTO;
    const ttd_isa isa = ttd_dispatch_isa_from_name(v);
    if (isa == TTD_ISA_COUNT || !ttd_dispatch_isa_built(isa) || !ttd_dispatch_cpu_supports(isa))
        return TTD_ISA_AUTO;
    return isa;
}

const char *ttd_dispatch_env_note(void)
{
    const char *v = getenv("TTD_ISA");
    if (v == NULL || v[0] == '\0')
        return NULL;
    const ttd_isa isa = ttd_dispatch_isa_from_name(v);
    if (isa == TTD_ISA_COUNT)
        return "TTD_ISA is not the name of an instruction set: ignored, the best available one is used";
    if (isa != TTD_ISA_AUTO && !(ttd_dispatch_isa_built(isa) && ttd_dispatch_cpu_supports(isa)))
        return "TTD_ISA names an instruction set this library or machine cannot run: ignored, the best available one is used";
    return NULL;
}

ttd_status ttd_dispatch_resolve(ttd_isa requested, ttd_isa *out)
{
    if ((int)requested < 0 || (int)requested >= TTD_ISA_COUNT)
        return TTD_ERR_BAD_OPTIONS;
    if (requested == TTD_ISA_AUTO)
        requested = ttd_isa_from_env();
    if (requested == TTD_ISA_AUTO) {
        *out = ttd_dispatch_best();
        return TTD_OK;
    }
    if (!ttd_dispatch_isa_built(requested) || !ttd_dispatch_cpu_supports(requested))
        return TTD_ERR_ISA_UNAVAILABLE;
    *out = requested;
    return TTD_OK;
}
