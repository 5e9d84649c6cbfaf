/* SPDX-License-Identifier: MIT */
/* The public entry points of include/ttd/ttd.h: options and their check, argument checks,
 * names, version. Every call checks, in this order: required pointers (TTD_ERR_NULL_POINTER),
 * options (TTD_ERR_BAD_OPTIONS), n == 0 (TTD_ERR_EMPTY), sizes whose arrays could not exist
 * (TTD_ERR_TOO_LARGE), the instruction set (TTD_ERR_ISA_UNAVAILABLE); then the batch engine
 * (engine/batch.h) computes. A single pair is a batch of one, so it gets exactly the bits a
 * batch call would give it. */
#include <float.h>
#include <math.h>
#include <stdint.h>

#include "core/defaults.h"
#include "engine/batch.h"
#include "api/prepare.h"
#include "engine/dispatch.h"
#include "ttd/ttd.h"

/* Set by ttd_default_options(); options built any other way lack it (Box2D's def cookie). */
#define TTD_OPTIONS_COOKIE 0x74746431u /* "ttd1" */

#define TTD_STR2(x) #x
#define TTD_STR(x) TTD_STR2(x)

ttd_options ttd_default_options(void)
{
    ttd_options o = {
        .method = TTD_METHOD_EXACT,
        .isa = TTD_ISA_AUTO,
        .threads = 0,
        .rho = TTD_DEFAULT_RHO,
        .tol = TTD_DEFAULT_TOL,
        .max_iterations = TTD_DEFAULT_MAX_ITERATIONS,
        .internal_cookie = TTD_OPTIONS_COOKIE,
    };
    return o;
}

/* The options, or the defaults when opt is NULL; TTD_ERR_BAD_OPTIONS on a missing cookie or
 * a field out of range. */
static ttd_status ttd_check_options(const ttd_options *opt, ttd_options *out)
{
    if (opt == NULL) {
        *out = ttd_default_options();
        return TTD_OK;
    }
    if (opt->internal_cookie != TTD_OPTIONS_COOKIE)
        return TTD_ERR_BAD_OPTIONS;
    if ((int)opt->method < 0 || (int)opt->method >= TTD_METHOD_COUNT)
        return TTD_ERR_BAD_OPTIONS;
    if ((int)opt->isa < 0 || (int)opt->isa >= TTD_ISA_COUNT)
        return TTD_ERR_BAD_OPTIONS;
    if (opt->threads < 0)
        return TTD_ERR_BAD_OPTIONS;
    /* Written so that NaN fails every test. */
    if (!(opt->rho > 0.0 && opt->rho <= TTD_RHO_MAX))
        return TTD_ERR_BAD_OPTIONS;
    if (!(opt->tol >= 0.0 && opt->tol <= TTD_TOL_MAX))
        return TTD_ERR_BAD_OPTIONS;
    if (opt->max_iterations < 1 || opt->max_iterations > 65535)
        return TTD_ERR_BAD_OPTIONS;
    if (opt->solid != 0 && opt->solid != 1)
        return TTD_ERR_BAD_OPTIONS;
    *out = *opt;
    return TTD_OK;
}

/* Resolves the instruction set and fills the engine's configuration. */
static ttd_status ttd_configure(const ttd_options *o, ttd_engine_config *cfg)
{
    ttd_isa isa;
    ttd_status st = ttd_dispatch_resolve(o->isa, &isa);
    if (st != TTD_OK)
        return st;
    cfg->isa = isa;
    cfg->method = o->method;
    cfg->params.rho = o->rho;
    cfg->params.tol = o->tol;
    cfg->params.max_iterations = o->max_iterations;
    cfg->threads = o->threads;
    return TTD_OK;
}

int ttd_too_large(size_t count, size_t per, size_t size)
{
    return count > (size_t)PTRDIFF_MAX / per / size;
}

ttd_status ttd_prepare(const ttd_options *opt, int pointers_ok, size_t n, int too_large,
                              ttd_engine_config *cfg)
{
    ttd_options o;
    ttd_status st;
    if (!pointers_ok)
        return TTD_ERR_NULL_POINTER;
    if ((st = ttd_check_options(opt, &o)) != TTD_OK)
        return st;
    if (n == 0)
        return TTD_ERR_EMPTY;
    if (too_large)
        return TTD_ERR_TOO_LARGE;
    return ttd_configure(&o, cfg);
}

ttd_status ttd_batch_d(const ttd_options *opt, size_t n, const double *s, const double *t,
                       double *distance, ttd_result_d *results)
{
    ttd_engine_config cfg;
    ttd_status st = ttd_prepare(opt, s && t && (distance || results), n,
                                ttd_too_large(n, 9, sizeof(double)) || ttd_too_large(n, 1, sizeof(ttd_result_d)),
                                &cfg);
    return st != TTD_OK ? st : ttd_engine_batch_d(&cfg, n, s, t, distance, results);
}

ttd_status ttd_batch_f(const ttd_options *opt, size_t n, const float *s, const float *t,
                       float *distance, ttd_result_f *results)
{
    ttd_engine_config cfg;
    ttd_status st = ttd_prepare(opt, s && t && (distance || results), n,
                                ttd_too_large(n, 9, sizeof(float)) || ttd_too_large(n, 1, sizeof(ttd_result_f)),
                                &cfg);
    return st != TTD_OK ? st : ttd_engine_batch_f(&cfg, n, s, t, distance, results);
}

ttd_status ttd_distance_d(const ttd_options *opt, const double s[9], const double t[9],
                          ttd_result_d *out)
{
    if (out == NULL)
        return TTD_ERR_NULL_POINTER;
    return ttd_batch_d(opt, 1, s, t, NULL, out);
}

ttd_status ttd_distance_f(const ttd_options *opt, const float s[9], const float t[9],
                          ttd_result_f *out)
{
    if (out == NULL)
        return TTD_ERR_NULL_POINTER;
    return ttd_batch_f(opt, 1, s, t, NULL, out);
}

/* The mesh entries' pointers, and whether their arrays could exist. */
#define TTD_MESH_POINTERS_OK (verts1 && tris1 && verts2 && tris2 && pairs && (distance || results))
#define TTD_MESH_TOO_LARGE(real, result)                                                       \
    (ttd_too_large(n, 2, sizeof(uint32_t)) || ttd_too_large(n, 1, sizeof(result)) ||          \
     ttd_too_large(nv1, 3, sizeof(real)) || ttd_too_large(nv2, 3, sizeof(real)) ||             \
     ttd_too_large(nt1, 3, sizeof(uint32_t)) || ttd_too_large(nt2, 3, sizeof(uint32_t)))

ttd_status ttd_mesh_batch_d(const ttd_options *opt,
                            const double *verts1, size_t nv1, const uint32_t *tris1, size_t nt1,
                            const double *verts2, size_t nv2, const uint32_t *tris2, size_t nt2,
                            size_t n, const uint32_t *pairs,
                            double *distance, ttd_result_d *results)
{
    ttd_engine_config cfg;
    ttd_status st = ttd_prepare(opt, TTD_MESH_POINTERS_OK, n, TTD_MESH_TOO_LARGE(double, ttd_result_d), &cfg);
    if (st != TTD_OK)
        return st;
    const ttd_mesh_d m1 = {verts1, nv1, tris1, nt1}, m2 = {verts2, nv2, tris2, nt2};
    return ttd_engine_mesh_d(&cfg, &m1, &m2, n, pairs, distance, results);
}

ttd_status ttd_mesh_batch_f(const ttd_options *opt,
                            const float *verts1, size_t nv1, const uint32_t *tris1, size_t nt1,
                            const float *verts2, size_t nv2, const uint32_t *tris2, size_t nt2,
                            size_t n, const uint32_t *pairs,
                            float *distance, ttd_result_f *results)
{
    ttd_engine_config cfg;
    ttd_status st = ttd_prepare(opt, TTD_MESH_POINTERS_OK, n, TTD_MESH_TOO_LARGE(float, ttd_result_f), &cfg);
    if (st != TTD_OK)
        return st;
    const ttd_mesh_f m1 = {verts1, nv1, tris1, nt1}, m2 = {verts2, nv2, tris2, nt2};
    return ttd_engine_mesh_f(&cfg, &m1, &m2, n, pairs, distance, results);
}

int ttd_isa_available(ttd_isa isa)
{
    return ttd_dispatch_isa_built(isa) && ttd_dispatch_cpu_supports(isa);
}

ttd_isa ttd_isa_from_name(const char *name)
{
    return ttd_dispatch_isa_from_name(name);
}

const char *ttd_isa_env_note(void)
{
    return ttd_dispatch_env_note();
}

int ttd_isa_built(ttd_isa isa)
{
    return ttd_dispatch_isa_built(isa);
}

int ttd_isa_supported(ttd_isa isa)
{
    return ttd_dispatch_cpu_supports(isa);
}

int ttd_method_lanes(ttd_method method, ttd_isa isa, int bytes_per_real)
{
    if ((int)method < 0 || (int)method >= TTD_METHOD_COUNT || (bytes_per_real != 4 && bytes_per_real != 8))
        return 0;
    if (!ttd_dispatch_isa_built(isa))
        return 0;
    if (bytes_per_real == 4)
        return ttd_dispatch_row_f(isa)->fn[method] != NULL ? ttd_dispatch_row_f(isa)->lanes : 1;
    return ttd_dispatch_row_d(isa)->fn[method] != NULL ? ttd_dispatch_row_d(isa)->lanes : 1;
}

ttd_isa ttd_isa_selected(const ttd_options *opt)
{
    ttd_options o;
    ttd_isa isa;
    if (ttd_check_options(opt, &o) != TTD_OK || ttd_dispatch_resolve(o.isa, &isa) != TTD_OK)
        return TTD_ISA_AUTO;
    return isa;
}

int ttd_isa_lanes(ttd_isa isa, int bytes_per_real)
{
    if (bytes_per_real != 4 && bytes_per_real != 8)
        return 0;
    if (isa == TTD_ISA_AUTO)
        isa = ttd_isa_selected(NULL);
    if (ttd_dispatch_isa_built(isa))
        return bytes_per_real == 4 ? ttd_dispatch_row_f(isa)->lanes : ttd_dispatch_row_d(isa)->lanes;
    /* Not built here: the register width says what it would be. */
    switch (isa) {
    case TTD_ISA_SSE2:
    case TTD_ISA_NEON: return 16 / bytes_per_real;
    case TTD_ISA_AVX2:
    case TTD_ISA_PORTABLE: return 32 / bytes_per_real;
    case TTD_ISA_AVX512: return 64 / bytes_per_real;
    default: return 0;
    }
}

const char *ttd_version_string(void)
{
    return TTD_STR(TTD_VERSION_MAJOR) "." TTD_STR(TTD_VERSION_MINOR) "." TTD_STR(TTD_VERSION_PATCH);
}
