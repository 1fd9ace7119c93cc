/*
 * fixed.c — the fixed-point operations too large to inline (see lumo/fixed.h
 * and docs/fixed-point.md for formats and error bounds).
 */
#include "lumo/fixed.h"

/* Rounded division of magnitudes: round(n / d), ties away from zero. */
static uint64_t udiv_round(uint64_t n, uint64_t d)
{
    uint64_t q = n / d;
    uint64_t r = n - q * d;
    return (r >= d - r) ? q + 1 : q;
}

lumo_q16_16 lumo_q16_div(lumo_q16_16 a, lumo_q16_16 b)
{
    int negative = (a < 0) != (b < 0);
    uint64_t n, d, q;

    if (b == 0)
        return a < 0 ? LUMO_Q16_MIN : LUMO_Q16_MAX;
    n = (a < 0 ? (uint64_t)0 - (uint64_t)(int64_t)a : (uint64_t)a) << LUMO_Q16_SHIFT;
    d = b < 0 ? (uint64_t)0 - (uint64_t)(int64_t)b : (uint64_t)b;
    q = udiv_round(n, d);
    if (q > (uint64_t)INT32_MAX + (negative ? 1u : 0u))
        return negative ? LUMO_Q16_MIN : LUMO_Q16_MAX;
    return negative ? (lumo_q16_16)(0 - (int64_t)q) : (lumo_q16_16)q;
}

/* Digit-by-digit (base 4) square root: exact floor, no division, constant
 * 32 iterations, so its cost is the same on every input and board. */
uint32_t lumo_isqrt64(uint64_t v)
{
    uint64_t rem = v, root = 0;
    uint64_t bit = (uint64_t)1 << 62;

    while (bit > rem)
        bit >>= 2;
    while (bit != 0) {
        if (rem >= root + bit) {
            rem -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    return (uint32_t)root;
}

/* Round-to-nearest integer square root: floor root r, bumped when v lies
 * above (r + 1/2)^2 = r^2 + r + 1/4, i.e. when v - r^2 > r. */
static uint32_t isqrt64_round(uint64_t v)
{
    uint32_t r = lumo_isqrt64(v);
    return (v - (uint64_t)r * r > r) ? r + 1 : r;
}

lumo_q16_16 lumo_q16_sqrt(lumo_q16_16 a)
{
    if (a <= 0)
        return 0;
    /* sqrt(a / 2^16) * 2^16 = sqrt(a * 2^16) */
    return (lumo_q16_16)isqrt64_round((uint64_t)a << LUMO_Q16_SHIFT);
}

lumo_q16_16 lumo_q16_rsqrt(lumo_q16_16 a)
{
    uint64_t s, q;

    if (a <= 0)
        return LUMO_Q16_MAX;
    /* 2^16 / sqrt(a / 2^16) = 2^24 / sqrt(a) = 2^40 / sqrt(a * 2^32);
     * the scaled root keeps 16 more significant bits than sqrt(a). */
    s = lumo_isqrt64((uint64_t)a << 32);
    q = udiv_round((uint64_t)1 << 40, s);
    return q > (uint64_t)INT32_MAX ? LUMO_Q16_MAX : (lumo_q16_16)q;
}

static uint64_t abs_u64(int64_t v)
{
    return v < 0 ? (uint64_t)0 - (uint64_t)v : (uint64_t)v;
}

lumo_status lumo_normalize3_q14(const int32_t v[3], lumo_q1_14 out[3])
{
    int64_t s[3];
    uint64_t m = 0, len2 = 0, len;
    int i;

    for (i = 0; i < 3; i++) {
        uint64_t a = abs_u64(v[i]);
        if (a > m) m = a;
    }
    if (m == 0) {
        out[0] = out[1] = out[2] = 0;
        return LUMO_ERR_RANGE;
    }
    /* Bring the largest magnitude into [2^29, 2^30] so the length carries
     * ~29 significant bits whatever the input scale; multiplying by a power
     * of two keeps the direction exact. */
    for (i = 0; i < 3; i++)
        s[i] = v[i];
    while (m < ((uint64_t)1 << 29)) {
        m <<= 1;
        for (i = 0; i < 3; i++) s[i] *= 2;
    }
    for (i = 0; i < 3; i++)
        len2 += (uint64_t)(s[i] * s[i]);
    len = isqrt64_round(len2);
    for (i = 0; i < 3; i++) {
        uint64_t q = udiv_round(abs_u64(s[i]) << LUMO_Q14_SHIFT, len);
        out[i] = (lumo_q1_14)(s[i] < 0 ? -(int32_t)q : (int32_t)q);
    }
    return LUMO_OK;
}

lumo_status lumo_f32bits_to_fixed(uint32_t bits, unsigned frac_bits, int32_t *out)
{
    uint32_t exp = (bits >> 23) & 0xFFu;
    uint64_t mant = bits & 0x7FFFFFu;
    int negative = (bits >> 31) != 0;
    int shift;
    uint64_t mag;

    if (exp == 0xFFu)
        return LUMO_ERR_NONFINITE;
    if (frac_bits > 30)
        return LUMO_ERR_ARG;
    if (exp == 0)
        exp = 1;                 /* subnormal: 0.mant * 2^-126 */
    else
        mant |= 0x800000u;       /* normal: 1.mant * 2^(exp-127) */
    /* value = mant * 2^(exp - 150); fixed = value * 2^frac_bits */
    shift = (int)exp - 150 + (int)frac_bits;
    if (shift >= 0) {
        if (shift > 8 && mant != 0)
            return LUMO_ERR_RANGE;   /* mant >= 2^23 would pass 2^31 */
        mag = mant << shift;
    } else if (shift < -25) {
        mag = 0;                     /* below half a unit: rounds to 0 */
    } else {
        mag = lumo_round_shift_u(mant, (unsigned)-shift);
    }
    if (mag > (uint64_t)INT32_MAX + (negative ? 1u : 0u))
        return LUMO_ERR_RANGE;
    *out = negative ? (int32_t)(0 - (int64_t)mag) : (int32_t)mag;
    return LUMO_OK;
}

void lumo_rgb9e5_to_uq16(uint32_t packed, lumo_uq16_16 out[3])
{
    /* value = m * 2^(E - 24); in UQ16.16 that is m * 2^(E - 8). The largest,
     * 511 * 2^23, still fits in 32 bits. */
    unsigned e = packed >> 27;
    int i;

    for (i = 0; i < 3; i++) {
        uint32_t m = (packed >> (9 * i)) & 0x1FFu;
        out[i] = e >= 8 ? m << (e - 8) : (uint32_t)lumo_round_shift_u(m, 8 - e);
    }
}
