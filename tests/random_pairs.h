/* SPDX-License-Identifier: MIT */
/* Random pairs for the iterative methods' tests (test_penalty.c, test_barrier.c): a seeded
 * xorshift stream, so each test sets rng_state and gets the same pairs whatever ran before. */
#ifndef TTD_TEST_RANDOM_PAIRS_H
#define TTD_TEST_RANDOM_PAIRS_H

#include <math.h>
#include <stdint.h>

static uint64_t rng_state;
static inline double urand(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) * (1.0 / 9007199254740992.0);
}

/* Vertices in the unit cube, the second triangle shifted by a uniform offset in [-0.5,0.5]^3. */
static inline void random_pair(double s[9], double t[9])
{
    for (int i = 0; i < 9; ++i) s[i] = urand();
    for (int i = 0; i < 9; ++i) t[i] = urand();
    for (int k = 0; k < 3; ++k) {
        double o = urand() - 0.5;
        t[k] += o;
        t[3 + k] += o;
        t[6 + k] += o;
    }
}

/* Longest edge of the two triangles. */
static inline double pair_size(const double s[9], const double t[9])
{
    double m = 0;
    const double *v[2] = {s, t};
    for (int w = 0; w < 2; ++w)
        for (int i = 0; i < 3; ++i) {
            int j = (i + 1) % 3;
            double dx = v[w][3 * i] - v[w][3 * j], dy = v[w][3 * i + 1] - v[w][3 * j + 1];
            double dz = v[w][3 * i + 2] - v[w][3 * j + 2];
            double l = sqrt(dx * dx + dy * dy + dz * dz);
            if (l > m) m = l;
        }
    return m;
}

#endif /* TTD_TEST_RANDOM_PAIRS_H */
