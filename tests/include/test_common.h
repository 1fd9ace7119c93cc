/*
 * test_common.h — shared by the unit tests: cmocka, a deterministic PRNG and
 * float helpers for double-precision references (tests may use floats).
 */
#ifndef LUMO_TEST_COMMON_H
#define LUMO_TEST_COMMON_H

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

/* xorshift64*: the same sequence on every machine, so random tests repeat. */
typedef struct { uint64_t s; } test_rng;

static inline uint64_t test_rng_next(test_rng *r)
{
    r->s ^= r->s >> 12;
    r->s ^= r->s << 25;
    r->s ^= r->s >> 27;
    return r->s * 2685821657736338717ull;
}

/* Uniform double in [lo, hi). */
static inline double test_rng_uniform(test_rng *r, double lo, double hi)
{
    return lo + (hi - lo) * (double)(test_rng_next(r) >> 11) * (1.0 / 9007199254740992.0);
}

static inline uint32_t test_f32_bits(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

/* Assert |got - want| <= tol, printing the values on failure. */
#define assert_close(got, want, tol)                                           \
    do {                                                                       \
        double g_ = (double)(got), w_ = (double)(want), t_ = (double)(tol);    \
        if (!(fabs(g_ - w_) <= t_))                                            \
            fail_msg("%s = %.9g, want %.9g (tol %.3g)", #got, g_, w_, t_);     \
    } while (0)

#endif
