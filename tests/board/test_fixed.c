/*
 * test_fixed.c — lumo/fixed.h on the board: known-answer vectors (computed
 * with exact rational arithmetic from the definitions in lumo/fixed.h:
 * round to nearest, ties away from zero, saturate) and integer property
 * checks over a deterministic PRNG. Runs on the host and under QEMU.
 */
#include <stddef.h>
#include <stdint.h>
#include "lumo/fixed.h"
#include "harness.h"

#define COUNT(a) (sizeof (a) / sizeof (a)[0])

typedef struct { int32_t a, b, want; } vec3;

static void test_mul_known(void)
{
    static const vec3 v[] = {
        {229376, -147456, -516096},            /* 3.5 * -2.25 */
        {21845, 196608, 65535},                /* 1/3 * 3 */
        {-809041920, 131072, -1618083840},
        {1966080000, 196608, 2147483647},      /* saturates */
        {1, 32768, 1},                          /* tie rounds away from zero */
        {-1, 32768, -1},
        {3, 32768, 2},
        {65536000, -2621440, -2147483647 - 1},
        {1151561, -2716765, -47737436},
    };
    size_t i;
    for (i = 0; i < COUNT(v); i++)
        BT_EQ(lumo_q16_mul(v[i].a, v[i].b), v[i].want);
}

static void test_div_known(void)
{
    static const vec3 v[] = {
        {65536, 196608, 21845},
        {-65536, 196608, -21845},
        {131072, 196608, 43691},
        {6553600, -458752, -936229},
        {-2147483647 - 1, 65536, -2147483647 - 1},
        {2147418112, 32768, 2147483647},        /* saturates */
        {65536, 0, 2147483647},                 /* b == 0 saturates by sign */
        {-65536, 0, -2147483647 - 1},
    };
    size_t i;
    for (i = 0; i < COUNT(v); i++)
        BT_EQ(lumo_q16_div(v[i].a, v[i].b), v[i].want);
}

static void test_isqrt_known(void)
{
    static const struct { uint64_t v; uint32_t want; } v[] = {
        {0ull, 0u}, {1ull, 1u}, {2ull, 1u}, {3ull, 1u}, {4ull, 2u}, {15ull, 3u},
        {16ull, 4u}, {17ull, 4u}, {1000000000000ull, 1000000u},
        {4611686018427387904ull, 2147483648u},
        {18446744073709551615ull, 4294967295u},
        {18446744065119617025ull, 4294967295u},
        {18446744065119617024ull, 4294967294u},
        {12345678901234567890ull, 3513641828u},
    };
    size_t i;
    for (i = 0; i < COUNT(v); i++)
        BT_EQ(lumo_isqrt64(v[i].v), v[i].want);
}

static void test_sqrt_rsqrt_known(void)
{
    static const int32_t sq[][2] = {
        {1, 256}, {2, 362}, {65536, 65536}, {131072, 92682}, {196608, 113512},
        {655360, 207243}, {12345, 28444}, {2147483647, 11863283}, {0, 0}, {-5, 0},
    };
    static const int32_t rs[][2] = {
        {1, 16777216}, {65536, 65536}, {131072, 46341}, {262144, 32768},
        {196608, 37837}, {100, 1677722}, {2147483647, 362}, {0, 2147483647},
    };
    size_t i;
    for (i = 0; i < COUNT(sq); i++)
        BT_EQ(lumo_q16_sqrt(sq[i][0]), sq[i][1]);
    for (i = 0; i < COUNT(rs); i++)
        BT_EQ(lumo_q16_rsqrt(rs[i][0]), rs[i][1]);
}

static void test_f32bits_known(void)
{
    static const struct { uint32_t bits; unsigned frac; int32_t want; } v[] = {
        {0x3FC00000u, 16, 98304},            /* 1.5 */
        {0xC0300000u, 16, -180224},          /* -2.75 */
        {0x3DCCCCCDu, 16, 6554},             /* 0.1 */
        {0x3DCCCCCDu, 30, 107374184},        /* 0.1 */
        {0xBDCCCCCDu, 20, -104858},          /* -0.1 */
        {0x449A522Bu, 16, 80908632},         /* 1234.5678 */
        {0x37FBA882u, 16, 2},                /* 3e-5 */
        {0xC7000000u, 16, -2147483647 - 1},  /* -32768 */
        {0x3F800000u, 30, 1073741824},       /* 1 */
        {0x3F000000u, 0, 1},                 /* 0.5, tie away from zero */
        {0xBF000000u, 0, -1},                /* -0.5 */
        {0x40200000u, 0, 3},                 /* 2.5 */
        {0x000116C2u, 16, 0},                /* subnormal 1e-40 */
        {0x80000000u, 16, 0},                /* -0 */
    };
    size_t i;
    for (i = 0; i < COUNT(v); i++) {
        int32_t out = 77;
        BT_EQ(lumo_f32bits_to_fixed(v[i].bits, v[i].frac, &out), LUMO_OK);
        BT_EQ(out, v[i].want);
    }
}

static void test_f32bits_errors(void)
{
    int32_t out = 77;
    BT_EQ(lumo_f32bits_to_q16(0x7FC00000u, &out), LUMO_ERR_NONFINITE);   /* NaN */
    BT_EQ(lumo_f32bits_to_q16(0xFF800000u, &out), LUMO_ERR_NONFINITE);   /* -inf */
    BT_EQ(lumo_f32bits_to_q16(0x471C4000u, &out), LUMO_ERR_RANGE);       /* 40000 */
    BT_EQ(lumo_f32bits_to_q16(0x47000000u, &out), LUMO_ERR_RANGE);       /* 32768 */
    BT_EQ(lumo_f32bits_to_fixed(0x40400000u, 31, &out), LUMO_ERR_ARG);
    BT_EQ(out, 77);   /* untouched on every error */
}

static void test_rgb9e5_known(void)
{
    static const struct { uint32_t packed; uint32_t want[3]; } v[] = {
        {0x780601FFu, {65408u, 32768u, 128u}},
        {0x000C0401u, {0u, 0u, 0u}},
        {0xFFFFFFFFu, {4286578688u, 4286578688u, 4286578688u}},
        {0xA4B19064u, {409600u, 819200u, 1228800u}},
        {0x3A01FE03u, {2u, 128u, 64u}},
        {0x40000001u, {1u, 0u, 0u}},
    };
    size_t i, k;
    for (i = 0; i < COUNT(v); i++) {
        lumo_uq16_16 out[3];
        lumo_rgb9e5_to_uq16(v[i].packed, out);
        for (k = 0; k < 3; k++)
            BT_EQ(out[k], v[i].want[k]);
    }
}

static void test_normalize_known(void)
{
    static const struct { int32_t v[3]; int16_t want[3]; } v[] = {
        {{3, 4, 0}, {9830, 13107, 0}},                  /* length 5 */
        {{-2, -2, 1}, {-10923, -10923, 5461}},          /* length 3 */
        {{0, 0, -7}, {0, 0, -16384}},
        {{1000000, 0, 0}, {16384, 0, 0}},
        {{1, 1, 1}, {9459, 9459, 9459}},                /* 1/sqrt(3) */
        {{2147483647, -2147483647 - 1, 0}, {11585, -11585, 0}},
    };
    size_t i, k;
    for (i = 0; i < COUNT(v); i++) {
        lumo_q1_14 out[3];
        BT_EQ(lumo_normalize3_q14(v[i].v, out), LUMO_OK);
        for (k = 0; k < 3; k++)
            BT_NEAR(out[k], v[i].want[k], 1);
    }
}

/* Exact integer references, written differently from fixed.h: rounding by
 * adding half before a truncating division of magnitudes. */
static int64_t ref_round_div(int64_t n, int64_t d)
{
    int neg = (n < 0) != (d < 0);
    uint64_t un = n < 0 ? (uint64_t)0 - (uint64_t)n : (uint64_t)n;
    uint64_t ud = d < 0 ? (uint64_t)0 - (uint64_t)d : (uint64_t)d;
    uint64_t q = (un + ud / 2) / ud;
    return neg ? -(int64_t)q : (int64_t)q;
}

static int32_t ref_sat(int64_t v)
{
    return v > INT32_MAX ? INT32_MAX : v < INT32_MIN ? INT32_MIN : (int32_t)v;
}

/* A random value of `bits` bits (8..32), signed, uniformly spread. */
static int32_t rand_i32(bt_rng *r)
{
    unsigned bits = 8u + (unsigned)(bt_rng_next(r) % 25u);
    uint64_t x = bt_rng_next(r) & (((uint64_t)1 << bits) - 1u);
    return (int32_t)((int64_t)x - ((int64_t)1 << (bits - 1u)));
}

static void test_mul_div_random(void)
{
    bt_rng r = {0x1234567887654321ull};
    int i;
    for (i = 0; i < 3000; i++) {
        int32_t a = rand_i32(&r);
        int32_t b = rand_i32(&r);
        BT_EQ(lumo_q16_mul(a, b), ref_sat(ref_round_div((int64_t)a * b, 65536)));
        if (b != 0 && (b & 1) == 0)  /* even divisor: ties are exact halves */
            BT_EQ(lumo_q16_div(a, b), ref_sat(ref_round_div((int64_t)a * 65536, b)));
    }
}

static void test_sqrt_random(void)
{
    bt_rng r = {0x0DDBA11CAFEull};
    int i;
    for (i = 0; i < 3000; i++) {
        uint64_t v = bt_rng_next(&r) >> (bt_rng_next(&r) % 64);
        uint64_t s = lumo_isqrt64(v);
        int32_t a = (int32_t)((uint32_t)v >> 1);
        int64_t q, x;
        BT_CHECK(s * s <= v);
        if (s < 0xFFFFFFFFu)
            BT_CHECK((s + 1) * (s + 1) > v);
        /* q16_sqrt is the nearest root: (q - 1/2)^2 <= a * 2^16 <= (q + 1/2)^2,
         * scaled by 4 to stay in integers. */
        q = lumo_q16_sqrt(a);
        x = (int64_t)a << 18;
        if (a == 0)
            BT_EQ(q, 0);
        else
            BT_CHECK((2 * q - 1) * (2 * q - 1) <= x && x <= (2 * q + 1) * (2 * q + 1));
    }
}

int main(void)
{
    BT_RUN(test_mul_known);
    BT_RUN(test_div_known);
    BT_RUN(test_isqrt_known);
    BT_RUN(test_sqrt_rsqrt_known);
    BT_RUN(test_f32bits_known);
    BT_RUN(test_f32bits_errors);
    BT_RUN(test_rgb9e5_known);
    BT_RUN(test_normalize_known);
    BT_RUN(test_mul_div_random);
    BT_RUN(test_sqrt_random);
    return bt_finish();
}
