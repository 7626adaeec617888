/* Common includes for cmocka tests, in the order cmocka requires, and
 * double-precision comparisons (cmocka 1.1 compares floats only). */
#ifndef GR_TEST_H
#define GR_TEST_H

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include <cmocka.h>

/* |a - b| <= tol, printing both values on failure. */
#define assert_close(a, b, tol)                                                   \
    do {                                                                          \
        double a_ = (a), b_ = (b), t_ = (tol);                                    \
        if (!(fabs(a_ - b_) <= t_)) {                                             \
            print_error("%s = %.17g, %s = %.17g, |diff| %.3g > tol %.3g\n", #a, a_, \
                        #b, b_, fabs(a_ - b_), t_);                               \
            fail();                                                               \
        }                                                                         \
    } while (0)

/* |a - b| <= rel * |b|. */
#define assert_rel(a, b, rel) assert_close((a), (b), (rel) * fabs((double)(b)))

#endif
