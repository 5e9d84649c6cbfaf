/* SPDX-License-Identifier: MIT */
/* The thresholds of the certified mode's optimality check, shared by the scalar code
 * (scalar/certified_impl.h) and the lane kernel (simd/kernel_certified.h) so that both take
 * the same decisions. All are in the frame's units: the pair translated to A and scaled by a
 * power of two so that its largest coordinate lies in [0.5, 1), which is at most 3x
 * max(distance, size) of the pair (docs/certified-mode.md). Why each value:
 *
 *   GAP    accept only when |p - q| exceeds the lower bound proved by the separating planes
 *          normal to p - q by at most this (the KKT multipliers' deficit, over |p - q|). The
 *          error of an accepted pair is then at most GAP plus the rounding of the check
 *          (~18 eps of double: the check runs in double for both precisions), in frame
 *          units. A frame unit is at most twice the extent, and the extent at most
 *          3 max(distance, size), so the error is below 7.2e-13 (double) and 5.8e-6 (float,
 *          with the rounding of the returned distance) of max(distance, size): inside the
 *          targets, 1e-12 and 1e-5. Smaller values send more pairs to the exact method
 *          (docs/certified-mode.md).
 *   TOUCH  the proved lower bound must exceed this, or the pair goes to the exact method:
 *          whether a pair touches is the exact method's decision (a distance within 4 eps of
 *          the extent is snapped to 0 and flagged), and a certificate this close to 0 cannot
 *          tell a contact from a near miss.
 *   CROSS  a contact is certified without the exact method only as a clear crossing: an edge
 *          whose ends lie at least CROSS of the extent on opposite sides of the other
 *          triangle's plane, crossing it at least CROSS inside each of that triangle's edge
 *          lines. The heights' rounding (~14 eps) then moves the crossing point by at most
 *          ~30 eps / CROSS of the extent (7e-9 double, 2.3e-4 float), far inside CROSS, so
 *          the triangles certainly intersect (distance 0, flagged). Every other contact
 *          (touching, coplanar, grazing) goes to the exact method.
 *   FEAS   the weights solved on the active set may be below 0 by this much (rounding at a
 *          vertex or edge end); they are then clamped onto the triangle, and the gap check
 *          above judges the clamped points, so this decides nothing about correctness. */
#ifndef TTD_CORE_CERTIFIED_TOL_H
#define TTD_CORE_CERTIFIED_TOL_H

#define TTD_CERT_GAP_D 0x1p-43
#define TTD_CERT_TOUCH_D 0x1p-42
#define TTD_CERT_FEAS_D 0x1p-43
#define TTD_CERT_GAP_F 0x1p-20f
#define TTD_CERT_TOUCH_F 0x1p-16f
#define TTD_CERT_FEAS_F 0x1p-20f
#define TTD_CERT_CROSS_D 0x1p-20
#define TTD_CERT_CROSS_F 0x1p-6f

#endif /* TTD_CORE_CERTIFIED_TOL_H */
