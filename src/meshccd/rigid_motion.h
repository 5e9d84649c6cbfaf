/* SPDX-License-Identifier: MIT */
/* A rigid body's motion between two poses (ttd.h, ttd_rigid_pose_at_d; docs/ccd.md section 13):
 * its origin on a straight line, its rotation about one fixed axis at a constant rate. */
#ifndef TTD_MESHCCD_RIGID_MOTION_H
#define TTD_MESHCCD_RIGID_MOTION_H

#include <stddef.h>

/// One body's motion from pose p0 to pose p1 (12 reals each, [R | t] row by row).
typedef struct rigid_motion {
    double r0[9];     ///< R0 (its nearest rotation if off by more than 16 ulps), row by row
    double t0[3], t1[3];
    double axis[3];   ///< unit axis u of R1 R0^T (world frame); 0 when theta is 0
    double theta;     ///< its angle in [0, pi]
} rigid_motion;

/// The motion from p0 to p1: R1 R0^T as a unit quaternion (w, v) by Shepperd's rule, w >= 0
/// (where w is 0, the sign making v's largest component positive, the first on a tie), theta =
/// 2 atan2(|v|, w), u = v / |v|.
void rigid_motion_make(const double p0[12], const double p1[12], rigid_motion *m);

/// The pose at time t: R(t) = Rot(u, t theta) R0 (Rodrigues' formula), T(t) = (1 - t) T0 + t T1.
/// At t = 0 exactly p0; at t = 1, T1 exactly and R1 up to R1 R0^T's distance from a rotation.
void rigid_motion_at(const rigid_motion *m, double t, double pose[12]);

/// max |x| over n points (3 reals each, double or float by bytes), rounded upward.
double rigid_radius(const void *x, size_t n, int bytes);

/// A bound on the speed of any point of the body, |T1 - T0| + theta (1 + 2 defect) radius,
/// rounded upward; defect is R0's max |R^T R - I| (at most TTD_POSE_TOLERANCE).
double rigid_speed(const rigid_motion *m, double radius);

#endif /* TTD_MESHCCD_RIGID_MOTION_H */
