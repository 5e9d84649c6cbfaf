/* SPDX-License-Identifier: MIT */
/* The tests' exact reference for continuous collision at delta = 0 (ccd_ref.c, GMP rationals):
 * independent of src/ccd/ (another method: the coplanarity cubic's roots isolated by Sturm
 * sequences, the inside conditions' signs at those roots). */
#ifndef TTD_TESTS_CCD_REF_H
#define TTD_TESTS_CCD_REF_H

enum { TTD_CCD_REF_MISS = 0, TTD_CCD_REF_HIT = 1, TTD_CCD_REF_UNDECIDED = 2 };

/// kind 1: point 0 against triangle 1, 2, 3; kind 2: segment 0-1 against segment 2-3; x0, x1
/// the 4 points at t = 0 and t = 1. Returns HIT (with the first contact time t* in
/// [*toi_lo, *toi_hi], doubles a few ulps apart), MISS, or UNDECIDED where the method does not
/// apply: the motion is coplanar throughout, or at a coplanar time the triangle has no area or
/// the edges are parallel.
int ttd_ccd_ref(int kind, const double x0[12], const double x1[12], double *toi_lo, double *toi_hi);

#endif
