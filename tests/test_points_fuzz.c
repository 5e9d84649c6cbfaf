/* SPDX-License-Identifier: MIT */
/* The point queries' differential fuzzer (tests/pointfuzz/) on seeded cases: hostile meshes at
 * scales 1e-8..1e8 and offsets to 1e6, points on and near every feature, bounds and poses; the
 * closest point equals the brute force over every triangle bit for bit, on the scalar row and the
 * automatic choice with 1 and 2 threads; and closed boxes wound outward, inward, inconsistently
 * and open: orientation, the one inside rule, inward = outward, and a long double reference. `test_points_fuzz N SEED` runs N cases from SEED
 * (default 400 from 20261127); `test_points_fuzz --input FILE` reruns a libFuzzer input. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pointfuzz/pointfuzz.h"

int main(int argc, char **argv)
{
    if (argc == 3 && strcmp(argv[1], "--input") == 0) {
        FILE *f = fopen(argv[2], "rb");
        if (f == NULL)
            return 2;
        static uint8_t buf[1 << 16];
        const size_t size = fread(buf, 1, sizeof buf, f);
        fclose(f);
        pf_src src;
        pf_src_init(&src, buf, size, 0);
        const int fails = pf_run_case(&src, stderr, 1, NULL);
        printf("%s\n", fails ? "FAILED" : "passed");
        return fails != 0;
    }
    const unsigned long n = argc > 1 ? strtoul(argv[1], NULL, 10) : 400;
    const unsigned long long seed = argc > 2 ? strtoull(argv[2], NULL, 10) : 20261127ull;
    size_t points = 0, failed = 0;
    for (unsigned long i = 0; i < n; ++i) {
        pf_src src;
        pf_src_init(&src, NULL, 0, seed * 1000003ull + i);
        size_t k;
        if (pf_run_case(&src, stderr, 1, &k) != 0) {
            fprintf(stderr, "  (case %lu of seed %llu)\n", i, seed);
            ++failed;
        }
        points += k;
    }
    printf("%lu cases, %zu points: %zu failed; %zu open meshes' sides against the long double winding number\n", n, points,
           failed, pf_sides_checked);
    return failed != 0;
}
