/* SPDX-License-Identifier: MIT */
/* A rigid body's motion between two poses: the origin on a straight line, the rotation about a
 * fixed axis at a constant rate (rigid_motion.h). The continuous queries certify with a bound on
 * any point's speed, so the motion only has to be this one, evaluated the same way everywhere. */
#include "meshccd/rigid_motion.h"

#include "core/rotation.h"

#include <float.h>
#include <math.h>
#include <string.h>


/* The pose checks accept R^T R - I up to 1e-6, but the queries use R^T as R's inverse within a
 * margin of about 2^-40 of the scene's size: a rotation further off than a few ulps is replaced
 * by the nearest rotation (its polar factor), by Newton-Schulz steps R <- R (3 I - R^T R) / 2,
 * each squaring the defect (1e-6 -> 1e-12 -> rounding). Rotations already within 16 ulps are
 * kept bit for bit. */
static void orthonormalise(double r[9])
{
    for (int it = 0; it < 4 && ttd_rotation_defect(r) > 16 * DBL_EPSILON; ++it) {
        double g[9], n[9];
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b)
                g[3 * a + b] = 0.5 * ((a == b) * 3.0 - (r[a] * r[b] + r[3 + a] * r[3 + b] + r[6 + a] * r[6 + b]));
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                n[3 * i + j] = r[3 * i] * g[j] + r[3 * i + 1] * g[3 + j] + r[3 * i + 2] * g[6 + j];
        memcpy(r, n, sizeof n);
    }
}

void rigid_motion_make(const double p0[12], const double p1[12], rigid_motion *m)
{
    double a[9] = {p0[0], p0[1], p0[2], p0[4], p0[5], p0[6], p0[8], p0[9], p0[10]};
    double b[9] = {p1[0], p1[1], p1[2], p1[4], p1[5], p1[6], p1[8], p1[9], p1[10]};
    orthonormalise(a);
    orthonormalise(b);
    for (int i = 0; i < 9; ++i)
        m->r0[i] = a[i];
    for (int i = 0; i < 3; ++i) {
        m->t0[i] = p0[4 * i + 3];
        m->t1[i] = p1[4 * i + 3];
    }
    /* M = R1 R0^T: the turn from the first pose to the second, in the world frame. */
    double M[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            M[i][j] = b[3 * i] * a[3 * j] + b[3 * i + 1] * a[3 * j + 1] + b[3 * i + 2] * a[3 * j + 2];
    /* Shepperd: the quaternion's largest component first, from the largest of the trace and
     * the diagonal, so no division by a small number. */
    const double tr = M[0][0] + M[1][1] + M[2][2];
    double w, x, y, z;
    if (tr >= M[0][0] && tr >= M[1][1] && tr >= M[2][2]) {
        w = 0.5 * sqrt(fmax(1 + tr, 0));
        const double f = 0.25 / w;
        x = (M[2][1] - M[1][2]) * f;
        y = (M[0][2] - M[2][0]) * f;
        z = (M[1][0] - M[0][1]) * f;
    } else if (M[0][0] >= M[1][1] && M[0][0] >= M[2][2]) {
        x = 0.5 * sqrt(fmax(1 + M[0][0] - M[1][1] - M[2][2], 0));
        const double f = 0.25 / x;
        w = (M[2][1] - M[1][2]) * f;
        y = (M[0][1] + M[1][0]) * f;
        z = (M[0][2] + M[2][0]) * f;
    } else if (M[1][1] >= M[2][2]) {
        y = 0.5 * sqrt(fmax(1 - M[0][0] + M[1][1] - M[2][2], 0));
        const double f = 0.25 / y;
        w = (M[0][2] - M[2][0]) * f;
        x = (M[0][1] + M[1][0]) * f;
        z = (M[1][2] + M[2][1]) * f;
    } else {
        z = 0.5 * sqrt(fmax(1 - M[0][0] - M[1][1] + M[2][2], 0));
        const double f = 0.25 / z;
        w = (M[1][0] - M[0][1]) * f;
        x = (M[0][2] + M[2][0]) * f;
        y = (M[1][2] + M[2][1]) * f;
    }
    /* The angle in [0, pi]: w >= 0. At w = 0 (a half turn) both signs of the axis give R1; the
     * one whose largest component (the first on a tie) is positive is taken. */
    int flip = w < 0;
    if (w == 0) {
        const double v[3] = {x, y, z};
        int k = 0;
        for (int i = 1; i < 3; ++i)
            if (fabs(v[i]) > fabs(v[k]))
                k = i;
        flip = v[k] < 0;
    }
    if (flip) {
        w = -w;
        x = -x;
        y = -y;
        z = -z;
    }
    const double s = sqrt(x * x + y * y + z * z);
    if (!(s > 0)) {
        m->theta = 0;
        m->axis[0] = m->axis[1] = m->axis[2] = 0;
        return;
    }
    m->theta = 2 * atan2(s, w);
    m->axis[0] = x / s;
    m->axis[1] = y / s;
    m->axis[2] = z / s;
}

void rigid_motion_at(const rigid_motion *m, double t, double pose[12])
{
    const double ang = t * m->theta;
    const double c = cos(ang), s = sin(ang), k = 1 - c;
    const double ux = m->axis[0], uy = m->axis[1], uz = m->axis[2];
    /* Rodrigues: c I + s [u]x + (1 - c) u u^T; exactly I at angle 0. */
    const double q[9] = {c + k * ux * ux,      k * ux * uy - s * uz, k * ux * uz + s * uy,
                         k * uy * ux + s * uz, c + k * uy * uy,      k * uy * uz - s * ux,
                         k * uz * ux - s * uy, k * uz * uy + s * ux, c + k * uz * uz};
    const double *r = m->r0;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j)
            pose[4 * i + j] = q[3 * i] * r[j] + q[3 * i + 1] * r[3 + j] + q[3 * i + 2] * r[6 + j];
        pose[4 * i + 3] = (1 - t) * m->t0[i] + t * m->t1[i];
    }
}

double rigid_radius(const void *x, size_t n, int bytes)
{
    double r2 = 0;
    for (size_t i = 0; i < n; ++i) {
        double v[3];
        for (int c = 0; c < 3; ++c)
            v[c] = bytes == 8 ? ((const double *)x)[3 * i + (size_t)c] : (double)((const float *)x)[3 * i + (size_t)c];
        const double d = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
        r2 = d > r2 ? d : r2;
    }
    /* x^2 + y^2 + z^2 is within 3 ulps, its square root within 2 more: 8 covers both. */
    return sqrt(r2) * (1 + 8 * DBL_EPSILON);
}

double rigid_speed(const rigid_motion *m, double radius)
{
    const double defect = ttd_rotation_defect(m->r0);
    double d2 = 0;
    for (int i = 0; i < 3; ++i) {
        const double d = m->t1[i] - m->t0[i];
        d2 += d * d;
    }
    /* d/dt (R(t) x + T(t)) = w x (R(t) x) + T1 - T0 with |w| = theta, and |R(t) x| = |R0 x| <=
     * sqrt(1 + 3 defect) |x| <= (1 + 2 defect) |x|. Each term rounded up by a few ulps. */
    const double lin = sqrt(d2) * (1 + 8 * DBL_EPSILON);
    const double rot = m->theta * (1 + 2 * defect) * radius * (1 + 8 * DBL_EPSILON);
    return (lin + rot) * (1 + 4 * DBL_EPSILON);
}
