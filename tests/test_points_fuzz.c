/* SPDX-License-Identifier: MIT */
/* The point queries' differential fuzzer (tests/pointfuzz/) on seeded cases: hostile meshes at
 * scales 1e-8..1e8 and offsets to 1e6, points on and near every feature, bounds and poses; the
 * closest point equals the brute force over every triangle bit for bit, on the scalar row and the
 * automatic choice with 1 and 2 threads; closed boxes wound outward, inward, inconsistently and
 * open, some with a tiny box, some unwelded (and welded back), and cases scaled by 2^k across the
 * coordinate range: orientation, the one inside rule, inward = outward, exact counts, and a long
 * double reference (docs/testing.md).
 *   test_points_fuzz [N [SEED [FIRST]]]   N cases (400) of SEED (20261127) from case FIRST (0)
 *   test_points_fuzz --input FILE...      reruns libFuzzer inputs (CTest: the corpus)
 *   test_points_fuzz --write SEED CASE OUT   writes case CASE of SEED as an input that draws it
 *   test_points_fuzz --extend IN OUT      writes an input found before the later families (tiny
 *                                         and unwelded boxes, scales by 2^k) as one that draws the
 *                                         same case with none of them */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pointfuzz/pointfuzz.h"

#define WORDS 4096

static size_t read_file(const char *path, uint8_t *buf, size_t cap)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return (size_t)-1;
    const size_t size = fread(buf, 1, cap, f);
    fclose(f);
    return size;
}

static int write_words(const char *path, const uint64_t *w, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (f == NULL || fwrite(w, 8, n, f) != n) {
        if (f)
            fclose(f);
        return 2;
    }
    return fclose(f) != 0 ? 2 : 0;
}

int main(int argc, char **argv)
{
    static uint8_t buf[1 << 16];
    static uint64_t words[WORDS];
    if (argc >= 3 && strcmp(argv[1], "--input") == 0) {
        int failed = 0;
        for (int a = 2; a < argc; ++a) {
            const size_t size = read_file(argv[a], buf, sizeof buf);
            if (size == (size_t)-1)
                return 2;
            pf_src src;
            pf_src_init(&src, buf, size, 0);
            const int fails = pf_run_case(&src, stderr, 1, NULL);
            printf("%s: %s\n", argv[a], fails ? "FAILED" : "passed");
            failed += fails != 0;
        }
        return failed != 0;
    }
    if (argc == 5 && strcmp(argv[1], "--write") == 0) {
        const unsigned long long seed = strtoull(argv[2], NULL, 10);
        const unsigned long i = strtoul(argv[3], NULL, 10);
        size_t first;
        const size_t n = pf_case_words(NULL, 0, seed * 1000003ull + i, words, WORDS, &first);
        return n > WORDS ? 2 : write_words(argv[4], words, n);
    }
    if (argc == 4 && strcmp(argv[1], "--extend") == 0) {
        const size_t size = read_file(argv[2], buf, sizeof buf);
        size_t first;
        if (size == (size_t)-1 || pf_case_words(buf, size, 0, words, WORDS, &first) > WORDS || first + 4 > WORDS)
            return 2;
        for (size_t k = first; k < first + 4; ++k) /* 1: "none" for every later family's draw */
            words[k] = 1;
        return write_words(argv[3], words, first + 4);
    }
    const unsigned long n = argc > 1 ? strtoul(argv[1], NULL, 10) : 400;
    const unsigned long long seed = argc > 2 ? strtoull(argv[2], NULL, 10) : 20261127ull;
    const unsigned long first = argc > 3 ? strtoul(argv[3], NULL, 10) : 0; /* rerun case `first` on */
    size_t points = 0, failed = 0;
    for (unsigned long i = first; i < first + n; ++i) {
        pf_src src;
        pf_src_init(&src, NULL, 0, seed * 1000003ull + i);
        size_t k;
        if (pf_run_case(&src, stderr, 1, &k) != 0) {
            fprintf(stderr, "  (case %lu of seed %llu)\n", i, seed);
            ++failed;
        }
        points += k;
    }
    printf("%lu cases, %zu points: %zu failed; %zu proven sides against the long double winding number\n", n, points,
           failed, pf_sides_checked);
    printf("  boxes with a tiny box %zu, unwelded %zu (welded back and checked %zu), scaled by 2^k %zu (k from %d to %d); "
           "%zu closed meshes' winding numbers equal to the rounded long double sum\n",
           pf_count.tiny, pf_count.unwelded, pf_count.welded, pf_count.scaled, pf_count.exp_lo, pf_count.exp_hi,
           pf_count.exact);
    return failed != 0;
}
