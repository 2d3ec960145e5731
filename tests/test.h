/* test.h - the whole unit-test framework (jsmn/nanopb style), host and Cortex-M4F.
 * SPDX-License-Identifier: MIT
 *
 * A test is `int test_xxx(void)` returning 0 on success or the failing __LINE__.
 * Register it in tests/tests.def with TEST(xxx). The same sources run natively
 * (runner word "unit" / "unit-double") and on QEMU mps2-an386 ("m4f"); output goes
 * through printf (newlib's _write is routed to semihosting on the target).
 */
#ifndef TEST_H
#define TEST_H

#include <math.h>
#include <stdio.h>

#define CHECK(cond)                                                         \
    do {                                                                    \
        if (!(cond)) {                                                      \
            printf("  %s:%d: CHECK(%s)\n", __FILE__, __LINE__, #cond);      \
            return __LINE__;                                                \
        }                                                                   \
    } while (0)

#define CHECK_EQ_INT(a, b)                                                  \
    do {                                                                    \
        long a_ = (long)(a), b_ = (long)(b);                                \
        if (a_ != b_) {                                                     \
            printf("  %s:%d: %s = %ld, want %ld\n", __FILE__, __LINE__, #a, \
                   a_, b_);                                                 \
            return __LINE__;                                                \
        }                                                                   \
    } while (0)

/* |val - ref| <= abs_tol + rel_tol * |ref|  (CMSIS-DSP assert_close_error) */
#define CHECK_NEAR(val, ref, abs_tol, rel_tol)                                   \
    do {                                                                         \
        double v_ = (double)(val), r_ = (double)(ref);                           \
        if (!(fabs(v_ - r_) <= (double)(abs_tol) + (double)(rel_tol) * fabs(r_))) { \
            printf("  %s:%d: %s = %.17g, want %.17g (diff %.3g)\n", __FILE__,    \
                   __LINE__, #val, v_, r_, v_ - r_);                             \
            return __LINE__;                                                     \
        }                                                                        \
    } while (0)

/* Deterministic PRNG (xorshift32) for random inputs; seed it per test. */
static inline unsigned test_prng(unsigned *state)
{
    unsigned x = *state ? *state : 2463534242u;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    *state = x;
    return x;
}

/* Report a measured figure (appears in the log; never decides pass/fail). */
#define TEST_NOTE(...) printf("  note: " __VA_ARGS__)

#define TEST(name) int test_##name(void);
#include "tests.def"
#undef TEST

#endif /* TEST_H */
