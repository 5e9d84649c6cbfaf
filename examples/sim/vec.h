/* SPDX-License-Identifier: MIT */
/* 3-vectors, 3x3 matrices (row major) and quaternions (w, x, y, z) for the simulator. */
#ifndef TTD_SIM_VEC_H
#define TTD_SIM_VEC_H

#include <math.h>

static inline double v3_dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void v3_cross(const double a[3], const double b[3], double out[3])
{
    double x = a[1] * b[2] - a[2] * b[1], y = a[2] * b[0] - a[0] * b[2], z = a[0] * b[1] - a[1] * b[0];
    out[0] = x;
    out[1] = y;
    out[2] = z;
}

static inline void v3_sub(const double a[3], const double b[3], double out[3])
{
    out[0] = a[0] - b[0];
    out[1] = a[1] - b[1];
    out[2] = a[2] - b[2];
}

/// out = a + s b
static inline void v3_axpy(const double a[3], double s, const double b[3], double out[3])
{
    out[0] = a[0] + s * b[0];
    out[1] = a[1] + s * b[1];
    out[2] = a[2] + s * b[2];
}

static inline double v3_norm(const double a[3])
{
    return sqrt(v3_dot(a, a));
}

/// a / |a|; 0 when |a| is 0.
static inline double v3_normalize(double a[3])
{
    double n = v3_norm(a);
    if (n > 0) {
        a[0] /= n;
        a[1] /= n;
        a[2] /= n;
    }
    return n;
}

/// out = M a
static inline void m3_mul_v(const double m[9], const double a[3], double out[3])
{
    double x = m[0] * a[0] + m[1] * a[1] + m[2] * a[2];
    double y = m[3] * a[0] + m[4] * a[1] + m[5] * a[2];
    double z = m[6] * a[0] + m[7] * a[1] + m[8] * a[2];
    out[0] = x;
    out[1] = y;
    out[2] = z;
}

/// out = M^T a
static inline void m3_tmul_v(const double m[9], const double a[3], double out[3])
{
    double x = m[0] * a[0] + m[3] * a[1] + m[6] * a[2];
    double y = m[1] * a[0] + m[4] * a[1] + m[7] * a[2];
    double z = m[2] * a[0] + m[5] * a[1] + m[8] * a[2];
    out[0] = x;
    out[1] = y;
    out[2] = z;
}

/// The rotation matrix of a unit quaternion (w, x, y, z).
static inline void quat_to_m3(const double q[4], double m[9])
{
    double w = q[0], x = q[1], y = q[2], z = q[3];
    m[0] = 1 - 2 * (y * y + z * z);
    m[1] = 2 * (x * y - w * z);
    m[2] = 2 * (x * z + w * y);
    m[3] = 2 * (x * y + w * z);
    m[4] = 1 - 2 * (x * x + z * z);
    m[5] = 2 * (y * z - w * x);
    m[6] = 2 * (x * z - w * y);
    m[7] = 2 * (y * z + w * x);
    m[8] = 1 - 2 * (x * x + y * y);
}

/// out = a b (Hamilton product)
static inline void quat_mul(const double a[4], const double b[4], double out[4])
{
    double w = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
    double x = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
    double y = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
    double z = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
    out[0] = w;
    out[1] = x;
    out[2] = y;
    out[3] = z;
}

/// The quaternion of a turn by angle (rad) about a unit axis.
static inline void quat_axis_angle(const double axis[3], double angle, double q[4])
{
    double s = sin(0.5 * angle);
    q[0] = cos(0.5 * angle);
    q[1] = s * axis[0];
    q[2] = s * axis[1];
    q[3] = s * axis[2];
}

/// x_world = R x + t for a pose [R | t] (12 doubles, row by row).
static inline void pose_apply(const double pose[12], const double x[3], double out[3])
{
    double a = pose[0] * x[0] + pose[1] * x[1] + pose[2] * x[2] + pose[3];
    double b = pose[4] * x[0] + pose[5] * x[1] + pose[6] * x[2] + pose[7];
    double c = pose[8] * x[0] + pose[9] * x[1] + pose[10] * x[2] + pose[11];
    out[0] = a;
    out[1] = b;
    out[2] = c;
}

/// R x for a pose's rotation.
static inline void pose_rotate(const double pose[12], const double x[3], double out[3])
{
    double a = pose[0] * x[0] + pose[1] * x[1] + pose[2] * x[2];
    double b = pose[4] * x[0] + pose[5] * x[1] + pose[6] * x[2];
    double c = pose[8] * x[0] + pose[9] * x[1] + pose[10] * x[2];
    out[0] = a;
    out[1] = b;
    out[2] = c;
}

#endif
