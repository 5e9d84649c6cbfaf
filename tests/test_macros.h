/* SPDX-License-Identifier: MIT */
/* A tiny test harness (Box2D's shape). Each tests/test_*.c is one CTest test: its main()
 * runs static test functions that return 0 (pass) or 1 (fail), and exits non-zero if any
 * failed. An optional argument filters tests by substring.
 *
 *     static int exact_pierce(void) { ENSURE(d == 0.0); ENSURE_NEAR(x, 1.0, 1e-12); return 0; }
 *     int main(int argc, char **argv) { TEST_MAIN_BEGIN(argc, argv); RUN_TEST(exact_pierce); TEST_MAIN_END(); }
 */
#ifndef TTD_TEST_MACROS_H
#define TTD_TEST_MACROS_H

#include <math.h>
#include <stdio.h>
#include <string.h>

/// Fails the current test when c is false.
#define ENSURE(c)                                                                   \
    do {                                                                            \
        if (!(c)) {                                                                 \
            fprintf(stderr, "  FAILED %s:%d: %s\n", __FILE__, __LINE__, #c);        \
            return 1;                                                               \
        }                                                                           \
    } while (0)

/// Fails unless |a - b| <= tol; prints both values.
#define ENSURE_NEAR(a, b, tol)                                                      \
    do {                                                                            \
        double ensure_a_ = (double)(a), ensure_b_ = (double)(b);                    \
        if (!(fabs(ensure_a_ - ensure_b_) <= (double)(tol))) {                      \
            fprintf(stderr, "  FAILED %s:%d: %s = %.17g, %s = %.17g, |diff| %.3g > %.3g\n", \
                    __FILE__, __LINE__, #a, ensure_a_, #b, ensure_b_,               \
                    fabs(ensure_a_ - ensure_b_), (double)(tol));                    \
            return 1;                                                               \
        }                                                                           \
    } while (0)

/// Like ENSURE, with a printf-style explanation (for failures inside loops over cases).
#define ENSURE_MSG(c, ...)                                                          \
    do {                                                                            \
        if (!(c)) {                                                                 \
            fprintf(stderr, "  FAILED %s:%d: %s: ", __FILE__, __LINE__, #c);        \
            fprintf(stderr, __VA_ARGS__);                                           \
            fputc('\n', stderr);                                                    \
            return 1;                                                               \
        }                                                                           \
    } while (0)

/// Prints a failing pair (what: a label, e.g. "input") to stderr, all 17 digits, ready to paste.
static inline void print_pair(const char *what, const double *s, const double *t)
{
    fprintf(stderr, "    %s S = (%.17g, %.17g, %.17g) (%.17g, %.17g, %.17g) (%.17g, %.17g, %.17g)\n", what,
            s[0], s[1], s[2], s[3], s[4], s[5], s[6], s[7], s[8]);
    fprintf(stderr, "    %*s T = (%.17g, %.17g, %.17g) (%.17g, %.17g, %.17g) (%.17g, %.17g, %.17g)\n",
            (int)strlen(what), "", t[0], t[1], t[2], t[3], t[4], t[5], t[6], t[7], t[8]);
}

#define TEST_MAIN_BEGIN(argc, argv)                                                 \
    const char *test_filter_ = (argc) > 1 ? (argv)[1] : NULL;                       \
    int test_passed_ = 0, test_failed_ = 0

#define RUN_TEST(fn)                                                                \
    do {                                                                            \
        if (test_filter_ && !strstr(#fn, test_filter_)) break;                      \
        int test_rc_ = fn();                                                        \
        printf("%s %s\n", test_rc_ ? "FAIL" : "ok  ", #fn);                         \
        fflush(stdout);                                                             \
        if (test_rc_) ++test_failed_; else ++test_passed_;                          \
    } while (0)

#define TEST_MAIN_END()                                                             \
    printf("%d passed, %d failed\n", test_passed_, test_failed_);                   \
    return test_failed_ ? 1 : (test_passed_ ? 0 : 1)

#endif /* TTD_TEST_MACROS_H */
