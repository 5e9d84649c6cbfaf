/* SPDX-License-Identifier: MIT */
/* Default parameters of the iterative methods (ttd_default_options). The penalty and
 * barrier methods run on the pair translated and scaled (by a power of two) to unit size,
 * so these values do not depend on the triangles' scale. How they were chosen:
 * docs/penalty-method.md. */
#ifndef TTD_COMMON_DEFAULTS_H
#define TTD_COMMON_DEFAULTS_H

#define TTD_DEFAULT_RHO 1.0e4
#define TTD_DEFAULT_TOL 1.0e-10
#define TTD_DEFAULT_MAX_ITERATIONS 99

#endif /* TTD_COMMON_DEFAULTS_H */
