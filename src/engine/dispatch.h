/* SPDX-License-Identifier: MIT */
/* Run-time choice of an instruction set: what the CPU and the operating system support, which
 * rows were built in, and how ttd_options (and the TTD_ISA environment variable) pick one. */
#ifndef TTD_ENGINE_DISPATCH_H
#define TTD_ENGINE_DISPATCH_H

#include "core/kernels.h"

/// Non-zero when the row of isa was compiled into this library (scalar: always).
int ttd_dispatch_isa_built(ttd_isa isa);
/// Non-zero when this CPU and OS can run isa (scalar: always; AUTO: never).
int ttd_dispatch_cpu_supports(ttd_isa isa);
/// The best instruction set that is built and supported (never AUTO).
ttd_isa ttd_dispatch_best(void);
/// The table rows of isa (double, float), or NULL when it was not built.
const ttd_kernels_d *ttd_dispatch_row_d(ttd_isa isa);
const ttd_kernels_f *ttd_dispatch_row_f(ttd_isa isa);
/// The kernel that runs method on isa (built): the row's entry, or the scalar row's where the
/// method has no lane kernel on that ISA.
ttd_kernel_d_fn ttd_dispatch_kernel_d(ttd_isa isa, ttd_method method);
ttd_kernel_f_fn ttd_dispatch_kernel_f(ttd_isa isa, ttd_method method);
/// Resolves requested (AUTO, or a forced one) to a runnable instruction set. With AUTO the
/// environment variable TTD_ISA (a ttd_isa_name in any case, or "auto"/empty) may force one;
/// a name that is unknown or cannot run here is ignored (ttd_dispatch_env_note says so).
/// Returns TTD_OK, or TTD_ERR_ISA_UNAVAILABLE when requested itself cannot run here; *out is
/// set only on TTD_OK.
ttd_status ttd_dispatch_resolve(ttd_isa requested, ttd_isa *out);
/// The instruction set called name, ignoring ASCII case ("AVX2" is avx2); TTD_ISA_COUNT when
/// none is.
ttd_isa ttd_dispatch_isa_from_name(const char *name);
/// NULL, or why TTD_ISA is being ignored (an unknown name, or one that cannot run here).
const char *ttd_dispatch_env_note(void);

#endif /* TTD_ENGINE_DISPATCH_H */
