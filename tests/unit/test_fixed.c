/* test_fixed.c — fixed-point operations against double-precision references. */
#include "test_common.h"
#include "lumo/fixed.h"

#define Q16 65536.0
#define Q14 16384.0

static void test_mul_div_random(void **state)
{
    test_rng r = {0x1234567u};
    int i;
    (void)state;
    for (i = 0; i < 200000; i++) {
        double a = test_rng_uniform(&r, -180.0, 180.0);
        double b = test_rng_uniform(&r, -180.0, 180.0);
        lumo_q16_16 qa = (lumo_q16_16)lround(a * Q16), qb = (lumo_q16_16)lround(b * Q16);
        double ea = qa / Q16, eb = qb / Q16;
        /* products are exact-then-rounded: error <= 1/2 ulp */
        assert_close(lumo_q16_mul(qa, qb) / Q16, ea * eb, 0.5 / Q16 + 1e-12);
        if (fabs(eb) > 0.01 && fabs(ea / eb) < 30000.0)
            assert_close(lumo_q16_div(qa, qb) / Q16, ea / eb, 0.5 / Q16 + 1e-12);
    }
}

static void test_saturation(void **state)
{
    (void)state;
    assert_int_equal(lumo_q16_mul(LUMO_Q16_FROM_INT(30000), LUMO_Q16_FROM_INT(30000)), LUMO_Q16_MAX);
    assert_int_equal(lumo_q16_mul(LUMO_Q16_FROM_INT(-30000), LUMO_Q16_FROM_INT(30000)), LUMO_Q16_MIN);
    assert_int_equal(lumo_q16_div(LUMO_Q16_ONE, 0), LUMO_Q16_MAX);
    assert_int_equal(lumo_q16_div(-LUMO_Q16_ONE, 0), LUMO_Q16_MIN);
    assert_int_equal(lumo_q16_div(LUMO_Q16_FROM_INT(20000), 1), LUMO_Q16_MAX);
    assert_int_equal(lumo_q16_add(LUMO_Q16_MAX, 1), LUMO_Q16_MAX);
    assert_int_equal(lumo_q16_sub(LUMO_Q16_MIN, 1), LUMO_Q16_MIN);
    assert_int_equal(lumo_sat_i16(40000), INT16_MAX);
    assert_int_equal(lumo_uq16_mul_q14(1000, -LUMO_Q14_ONE), 0);
    assert_int_equal(lumo_uq16_mul(UINT32_MAX, UINT32_MAX), UINT32_MAX);
}

static void test_rounding(void **state)
{
    (void)state;
    /* ties away from zero, symmetric in sign */
    assert_int_equal(lumo_round_shift(3, 1), 2);
    assert_int_equal(lumo_round_shift(-3, 1), -2);
    assert_int_equal(lumo_round_shift(5, 2), 1);
    assert_int_equal(lumo_round_shift(-5, 2), -1);
    assert_int_equal(lumo_round_shift(6, 2), 2);
    assert_int_equal(lumo_round_shift(-6, 2), -2);
    assert_int_equal(lumo_round_shift_u(UINT64_MAX, 1), (uint64_t)1 << 63);
    assert_int_equal(LUMO_Q16_FRAC(1, 3), 21845);
    assert_int_equal(LUMO_Q16_FRAC(-1, 2), -32768);
    assert_int_equal(LUMO_Q14_FRAC(1, 2), 8192);
    assert_int_equal(LUMO_Q16_INV_PI, (lumo_q16_16)lround(Q16 / M_PI));
}

static void test_isqrt_exact(void **state)
{
    test_rng r = {99};
    int i;
    (void)state;
    assert_int_equal(lumo_isqrt64(0), 0);
    assert_int_equal(lumo_isqrt64(1), 1);
    assert_int_equal(lumo_isqrt64(UINT64_MAX), 0xFFFFFFFFu);
    for (i = 0; i < 100000; i++) {
        uint64_t v = test_rng_next(&r) >> (test_rng_next(&r) % 64);
        uint64_t s = lumo_isqrt64(v);
        assert_true(s * s <= v);
        assert_true((s + 1) * (s + 1) > v || s == 0xFFFFFFFFu);
    }
}

static void test_sqrt_rsqrt(void **state)
{
    test_rng r = {7};
    int i;
    (void)state;
    assert_int_equal(lumo_q16_sqrt(LUMO_Q16_FROM_INT(4)), LUMO_Q16_FROM_INT(2));
    assert_int_equal(lumo_q16_sqrt(-5), 0);
    assert_int_equal(lumo_q16_rsqrt(LUMO_Q16_FROM_INT(4)), LUMO_Q16_HALF);
    assert_int_equal(lumo_q16_rsqrt(0), LUMO_Q16_MAX);
    for (i = 0; i < 100000; i++) {
        lumo_q16_16 a = (lumo_q16_16)(test_rng_next(&r) >> 33) + 1;   /* (0, 32768) */
        double x = a / Q16;
        assert_close(lumo_q16_sqrt(a) / Q16, sqrt(x), 0.5 / Q16 + 1e-12);
        if (x >= 1.0 / 256.0) {   /* result below 16: fits with margin */
            double want = 1.0 / sqrt(x);
            assert_close(lumo_q16_rsqrt(a) / Q16, want, want * 0x1p-15 + 1.0 / Q16);
        }
    }
}

static void test_normalize(void **state)
{
    test_rng r = {42};
    int i, k;
    lumo_q1_14 n[3];
    int32_t zero[3] = {0, 0, 0}, x[3] = {5, 0, 0};
    (void)state;
    assert_int_equal(lumo_normalize3_q14(zero, n), LUMO_ERR_RANGE);
    assert_int_equal(lumo_normalize3_q14(x, n), LUMO_OK);
    assert_int_equal(n[0], LUMO_Q14_ONE);
    assert_int_equal(n[1], 0);
    for (i = 0; i < 100000; i++) {
        int32_t v[3];
        double len = 0;
        int scale = (int)(test_rng_next(&r) % 31);
        for (k = 0; k < 3; k++) {
            v[k] = (int32_t)((int64_t)(test_rng_next(&r) >> 32) - 2147483648ll) >> scale;
            len += (double)v[k] * v[k];
        }
        len = sqrt(len);
        if (len == 0) continue;
        assert_int_equal(lumo_normalize3_q14(v, n), LUMO_OK);
        for (k = 0; k < 3; k++)
            assert_close(n[k] / Q14, v[k] / len, 2.0 / Q14);
    }
}

static void test_f32_conversion(void **state)
{
    test_rng r = {5};
    int32_t out = 12345;
    int i;
    (void)state;
    assert_int_equal(lumo_f32bits_to_q16(test_f32_bits(1.5f), &out), LUMO_OK);
    assert_int_equal(out, 98304);
    assert_int_equal(lumo_f32bits_to_q16(test_f32_bits(-0.0f), &out), LUMO_OK);
    assert_int_equal(out, 0);
    assert_int_equal(lumo_f32bits_to_q16(test_f32_bits(1e-30f), &out), LUMO_OK);
    assert_int_equal(out, 0);
    assert_int_equal(lumo_f32bits_to_q16(test_f32_bits(1e-45f), &out), LUMO_OK); /* subnormal */
    assert_int_equal(out, 0);
    out = 77;
    assert_int_equal(lumo_f32bits_to_q16(0x7FC00000u, &out), LUMO_ERR_NONFINITE);
    assert_int_equal(lumo_f32bits_to_q16(0xFF800000u, &out), LUMO_ERR_NONFINITE);
    assert_int_equal(lumo_f32bits_to_q16(test_f32_bits(40000.0f), &out), LUMO_ERR_RANGE);
    assert_int_equal(out, 77);   /* untouched on error */
    assert_int_equal(lumo_f32bits_to_q16(test_f32_bits(-32768.0f), &out), LUMO_OK);
    assert_int_equal(out, INT32_MIN);
    assert_int_equal(lumo_f32bits_to_q16(test_f32_bits(32768.0f), &out), LUMO_ERR_RANGE);
    assert_int_equal(lumo_f32bits_to_fixed(test_f32_bits(3.0f), 31, &out), LUMO_ERR_ARG);
    for (i = 0; i < 200000; i++) {
        float f = (float)test_rng_uniform(&r, -32000.0, 32000.0);
        unsigned frac = (unsigned)(test_rng_next(&r) % 17);
        double want = f * ldexp(1.0, (int)frac);
        assert_int_equal(lumo_f32bits_to_fixed(test_f32_bits(f), frac, &out), LUMO_OK);
        /* round half away from zero, as lround */
        assert_int_equal(out, (int32_t)lround(want));
    }
}

static void test_rgb9e5(void **state)
{
    lumo_uq16_16 c[3];
    uint32_t e, m;
    (void)state;
    /* every exponent and mantissa against value = m * 2^(e-24) */
    for (e = 0; e < 32; e++) {
        for (m = 0; m < 512; m += 7) {
            uint32_t packed = m | ((511u - m) << 9) | ((m / 2u) << 18) | (e << 27);
            double want[3] = {m, 511.0 - m, m / 2};
            int k;
            lumo_rgb9e5_to_uq16(packed, c);
            for (k = 0; k < 3; k++)
                assert_close(c[k] / Q16, want[k] * ldexp(1.0, (int)e - 24), 0.5 / Q16 + 1e-12);
        }
    }
    lumo_rgb9e5_to_uq16(0xFFFFFFFFu, c);   /* largest value: 65408 */
    assert_int_equal(c[0], 511u << 23);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mul_div_random),
        cmocka_unit_test(test_saturation),
        cmocka_unit_test(test_rounding),
        cmocka_unit_test(test_isqrt_exact),
        cmocka_unit_test(test_sqrt_rsqrt),
        cmocka_unit_test(test_normalize),
        cmocka_unit_test(test_f32_conversion),
        cmocka_unit_test(test_rgb9e5),
    };
    return cmocka_run_group_tests_name("fixed", tests, NULL, NULL);
}
