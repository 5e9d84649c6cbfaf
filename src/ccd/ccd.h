/* SPDX-License-Identifier: MIT */
/* Continuous collision of moving primitives under linear motion over t in [0, 1] (docs/ccd.md).
 * One query is two convex sets of moving points: a vertex against a triangle (vertex-face, 1 + 3
 * points) or a segment against a segment (edge-edge, 2 + 2). The scalar reference here decides
 * whether their Euclidean distance comes to delta or less for some t in [0, t_max], and the
 * earliest such time, conservatively (never later than the true one). */
#ifndef TTD_CCD_CCD_H
#define TTD_CCD_CCD_H

#include <stdint.h>

#include "core/kernels.h"
#include "ttd/ttd.h"

/// Query kinds: how many of the 4 points belong to the first set.
enum { TTD_CCD_VF = 1, TTD_CCD_EE = 2 };

/// The search's limits (docs/ccd.md, section 2).
typedef struct ttd_ccd_params {
    double delta;     ///< minimum separation, >= 0 (Euclidean)
    double t_max;     ///< search [0, t_max], t_max in [0, 1]
    double t_tol;     ///< a time interval this short that cannot be separated is a hit
    int max_evals;    ///< intervals examined before the query answers hit conservatively
    /// Stop, answering no hit, at the first open interval that starts after t_stop, or once a
    /// proved-free prefix reaches past it (mesh CCD, src/meshccd/: a pair whose contact comes
    /// after the earliest found cannot be reported; docs/ccd.md, section 3, item 9). The answer
    /// of a query whose toi is at most t_stop is the same as without (the same intervals in the
    /// same order); one whose toi is later gets no hit at or before t_stop. Default HUGE_VAL.
    double t_stop;
} ttd_ccd_params;

/// The defaults: delta 0, t_max 1, t_tol TTD_CCD_DEFAULT_T_TOL, max_evals TTD_CCD_DEFAULT_MAX_EVALS,
/// t_stop HUGE_VAL.
ttd_ccd_params ttd_ccd_default_params(void);

/// One query: x0[3i..3i+2], x1[3i..3i+2] are point i at t = 0 and t = 1; points [0, kind) are
/// the first set, [kind, 4) the second. Coordinates must be finite. Writes hit, toi (INFINITY when no hit),
/// gap, flags and evals into *out (sub untouched).
void ttd_ccd_query(int kind, const double x0[12], const double x1[12], const ttd_ccd_params *p,
                   ttd_ccd_result *out);

/// The screen: the certified tests of a query's first interval [0, t_max] that a batch runs in
/// SIMD lanes (simd/kernel_ccd.h computes the same bits): at delta = 0 the coplanarity cubic of
/// one strict sign, then the separation along the closest points' difference and along the
/// closest features' direction at t_max / 2. Returns 1 when one of them proves the query free of
/// contact; ttd_ccd_query's answer is then no hit after 1 evaluation (its first interval runs
/// these tests). 0 otherwise, for non-finite input, and where the largest coordinate magnitude
/// is TTD_CCD_SCREEN_MAX (core/kernels.h) or more (the lanes' arithmetic then stays clear of
/// overflow).
int ttd_ccd_screen(int kind, const double x0[12], const double x1[12], double delta, double t_max);

#endif /* TTD_CCD_CCD_H */
