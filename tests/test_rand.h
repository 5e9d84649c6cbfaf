/* SPDX-License-Identifier: MIT */
/* A test file's random numbers: Marsaglia's xorshift64, one stream per file, seeded by the file
 * (define TEST_RAND_SEED before including), so that a file's cases stay the same whatever
 * another file draws. */
#ifndef TTD_TEST_RAND_H
#define TTD_TEST_RAND_H

#include <stdint.h>

#ifndef TEST_RAND_SEED
#error "define TEST_RAND_SEED (a nonzero 64-bit seed) before including test_rand.h"
#endif

static uint64_t rng_state = TEST_RAND_SEED;

/* Uniform in [0, 1), 53 random bits. */
static inline double urand(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) * 0x1p-53;
}

/* Uniform in [-1, 1). */
static inline double srand1(void)
{
    return 2 * urand() - 1;
}

#endif
