/* SPDX-License-Identifier: MIT */
/* Small helpers of the point queries that the device compiles too (points/points.h includes
 * them; so does points/ray_impl.h, the ray count shared with src/gpu/): doubles rounded to float
 * downwards and upwards for the walks' float boxes, and the larger of two numbers. Host and device
 * functions under nvcc, plain static inline in C. */
#ifndef TTD_POINTS_POINT_MATH_H
#define TTD_POINTS_POINT_MATH_H

#include <stdint.h>
#include <string.h>

#ifdef __CUDACC__
#define TTD_PMATH_FN static inline __host__ __device__
#else
#define TTD_PMATH_FN static inline
#endif

/* x rounded to float downwards, upwards (|x| <= 2^100). The round trip goes through a volatile: the
 * rounding must really happen (docs/mesh-queries.md, 4.1, saw gcc drop it). */
TTD_PMATH_FN float ttd_float_down(double x)
{
    volatile float f = (float)x;
    float r = f;
    if ((double)r > x) { /* one float step down: r is finite and nonzero here unless x rounds to 0 */
        uint32_t b;
        memcpy(&b, &r, sizeof b);
        if (r > 0)
            --b;
        else if (r < 0)
            ++b;
        else
            b = 0x80000001u; /* -0 -> the smallest negative subnormal */
        memcpy(&r, &b, sizeof r);
    }
    return r;
}

TTD_PMATH_FN float ttd_float_up(double x)
{
    return -ttd_float_down(-x);
}

/* The larger of two numbers neither of which is NaN: fmax is a call into libm wherever the compiler
 * must keep its NaN rule, and the ray's and the solid angle's scalings take several per triangle. */
TTD_PMATH_FN double ttd_max_nn(double a, double b)
{
    return a > b ? a : b;
}

#endif /* TTD_POINTS_POINT_MATH_H */
