/*
 * lumo/fixed.h — the fixed-point formats of the lumo client, in one place.
 *
 * The client side (sdk/, rasterizer/soft/, the net codec) uses no float or
 * double: every real number is an integer with an implied binary point, named
 * by its type. Results are bit-exact on every target (host, Cortex-M3, ...)
 * because only C99 integer arithmetic with defined behaviour is used: 64-bit
 * intermediates for products, explicit rounding, explicit saturation.
 * docs/fixed-point.md states ranges and error bounds for each operation.
 *
 * Formats
 *   lumo_q16_16  int32   Q16.16 signed scalar: positions, lengths, weights.
 *                         range [-32768, 32768), step 2^-16.
 *   lumo_q1_14   int16   Q1.14 signed: unit-vector components, cosines.
 *                         LUMO_Q14_ONE = 1.0, range [-2, 2), step 2^-14.
 *   lumo_uq16_16 uint32  UQ16.16 unsigned HDR value: irradiance (W/m^2),
 *                         radiance, colour. range [0, 65536), step 2^-16;
 *                         holds every RGB9E5 value with exponent >= 8
 *                         exactly; smaller ones round (error <= 1/2 ulp).
 *
 * Rounding: every narrowing operation rounds to nearest, ties away from zero
 * (LUMO_ROUND_SHIFT), and saturates to the destination range.
 */
#ifndef LUMO_FIXED_H
#define LUMO_FIXED_H

#include <stdint.h>
#include "lumo/status.h"

typedef int32_t  lumo_q16_16;    /* signed Q16.16: value = v / 65536 */
typedef int16_t  lumo_q1_14;     /* signed Q1.14: value = v / 16384, in [-2, 2) */
typedef uint32_t lumo_uq16_16;   /* unsigned Q16.16: value = v / 65536, in [0, 65536) */

#define LUMO_Q16_SHIFT 16   /* fraction bits of Q16.16 */
#define LUMO_Q16_ONE   ((lumo_q16_16)1 << LUMO_Q16_SHIFT)          /* 1.0 in Q16.16 */
#define LUMO_Q16_HALF  ((lumo_q16_16)1 << (LUMO_Q16_SHIFT - 1))    /* 0.5 in Q16.16 */
#define LUMO_Q16_MAX   INT32_MAX   /* the largest Q16.16, saturation bound */
#define LUMO_Q16_MIN   INT32_MIN   /* the smallest Q16.16, saturation bound */

#define LUMO_Q14_SHIFT 14   /* fraction bits of Q1.14 */
#define LUMO_Q14_ONE   ((lumo_q1_14)(1 << LUMO_Q14_SHIFT))         /* 1.0 in Q1.14 */

/* 1/pi in Q16.16: round(65536 / pi) = 20861. */
#define LUMO_Q16_INV_PI ((lumo_q16_16)20861)

/* Integer constant n as Q16.16 (n must fit in [-32768, 32767]). */
#define LUMO_Q16_FROM_INT(n) ((lumo_q16_16)((int32_t)(n) * LUMO_Q16_ONE))
/* The rational num/den as Q16.16, rounded to nearest (ties away from zero);
 * compile-time friendly, so constants never need a float literal. den > 0. */
#define LUMO_Q16_FRAC(num, den)                                                \
    ((lumo_q16_16)(((int64_t)(num) * 65536                                     \
                    + ((num) < 0 ? -((int64_t)(den) / 2) : (int64_t)(den) / 2)) \
                   / (int64_t)(den)))
/* The rational num/den as Q1.14, rounded to nearest (den > 0, num >= 0). */
#define LUMO_Q14_FRAC(num, den) \
    ((lumo_q1_14)((((int32_t)(num) * 16384) + ((int32_t)(den) / 2)) / (int32_t)(den)))

/* ---- saturation and rounding -------------------------------------------- */

/* v clamped to [INT32_MIN, INT32_MAX]. */
static inline int32_t lumo_sat_i32(int64_t v)
{
    if (v > INT32_MAX) return INT32_MAX;
    if (v < INT32_MIN) return INT32_MIN;
    return (int32_t)v;
}

/* v clamped to [0, UINT32_MAX]. */
static inline uint32_t lumo_sat_u32(int64_t v)
{
    if (v < 0) return 0;
    if (v > (int64_t)UINT32_MAX) return UINT32_MAX;
    return (uint32_t)v;
}

/* v clamped to [INT16_MIN, INT16_MAX]. */
static inline int16_t lumo_sat_i16(int32_t v)
{
    if (v > INT16_MAX) return INT16_MAX;
    if (v < INT16_MIN) return INT16_MIN;
    return (int16_t)v;
}

/* v / 2^shift rounded to nearest, ties away from zero. shift in [1, 62].
 * Written without shifting negative values, whose behaviour C leaves to the
 * implementation: the magnitude is shifted and the sign restored. */
static inline int64_t lumo_round_shift(int64_t v, unsigned shift)
{
    uint64_t mag = v < 0 ? (uint64_t)0 - (uint64_t)v : (uint64_t)v;
    mag = (mag + ((uint64_t)1 << (shift - 1))) >> shift;
    return v < 0 ? -(int64_t)mag : (int64_t)mag;
}

/* Unsigned variant: (v + 2^(shift-1)) >> shift without overflow. */
static inline uint64_t lumo_round_shift_u(uint64_t v, unsigned shift)
{
    return (v >> shift) + ((v >> (shift - 1)) & 1u);
}

/* ---- Q16.16 arithmetic --------------------------------------------------- */

/* a * b, rounded to nearest, saturated. */
static inline lumo_q16_16 lumo_q16_mul(lumo_q16_16 a, lumo_q16_16 b)
{
    return lumo_sat_i32(lumo_round_shift((int64_t)a * b, LUMO_Q16_SHIFT));
}

/* a / b, rounded to nearest, saturated; b == 0 saturates by the sign of a. */
lumo_q16_16 lumo_q16_div(lumo_q16_16 a, lumo_q16_16 b);

/* Saturating add and subtract. */
static inline lumo_q16_16 lumo_q16_add(lumo_q16_16 a, lumo_q16_16 b)
{
    return lumo_sat_i32((int64_t)a + b);
}

/* a - b, saturated. */
static inline lumo_q16_16 lumo_q16_sub(lumo_q16_16 a, lumo_q16_16 b)
{
    return lumo_sat_i32((int64_t)a - b);
}

/* UQ16.16 times Q1.14 (e.g. irradiance times a cosine), result UQ16.16,
 * negative products clamp to zero. */
static inline lumo_uq16_16 lumo_uq16_mul_q14(lumo_uq16_16 a, lumo_q1_14 b)
{
    return lumo_sat_u32(lumo_round_shift((int64_t)a * b, LUMO_Q14_SHIFT));
}

/* UQ16.16 product, rounded, saturated. */
static inline lumo_uq16_16 lumo_uq16_mul(lumo_uq16_16 a, lumo_uq16_16 b)
{
    uint64_t p = lumo_round_shift_u((uint64_t)a * b, LUMO_Q16_SHIFT);
    return p > UINT32_MAX ? UINT32_MAX : (uint32_t)p;
}

/* Q1.14 product, rounded, saturated to Q1.14. */
static inline lumo_q1_14 lumo_q14_mul(lumo_q1_14 a, lumo_q1_14 b)
{
    return lumo_sat_i16((int32_t)lumo_round_shift((int64_t)a * b, LUMO_Q14_SHIFT));
}

/* Q1.14 <-> Q16.16 */
static inline lumo_q16_16 lumo_q14_to_q16(lumo_q1_14 v)
{
    return (lumo_q16_16)v * 4;
}

/* Q16.16 to Q1.14, rounded, saturated to Q1.14's range. */
static inline lumo_q1_14 lumo_q16_to_q14(lumo_q16_16 v)
{
    return lumo_sat_i16((int32_t)lumo_round_shift(v, 2));
}

/* ---- roots --------------------------------------------------------------- */

/* floor(sqrt(v)), exact for every input. */
uint32_t lumo_isqrt64(uint64_t v);

/* sqrt of a non-negative Q16.16; negative input gives 0. Error <= 1 ulp. */
lumo_q16_16 lumo_q16_sqrt(lumo_q16_16 a);

/* 1/sqrt(a) for a > 0 in Q16.16, saturated; a <= 0 gives LUMO_Q16_MAX.
 * Relative error <= 2^-15 + 1 ulp over the whole range. */
lumo_q16_16 lumo_q16_rsqrt(lumo_q16_16 a);

/* Normalise an integer 3-vector (any common scale) to Q1.14 unit length.
 * The zero vector gives (0,0,0) and LUMO_ERR_RANGE. Error <= 2 ulp. */
lumo_status lumo_normalize3_q14(const int32_t v[3], lumo_q1_14 out[3]);

/* ---- IEEE-754 single bit patterns, read with integer operations ---------- */

/* Convert the binary32 value with bit pattern `bits` to a signed fixed-point
 * integer with `frac_bits` fractional bits (0..30), rounded to nearest (ties
 * away from zero). NaN/Inf give LUMO_ERR_NONFINITE; a value outside int32
 * gives LUMO_ERR_RANGE; *out is written only on success. */
lumo_status lumo_f32bits_to_fixed(uint32_t bits, unsigned frac_bits, int32_t *out);

/* lumo_f32bits_to_fixed with 16 fraction bits: a binary32 to Q16.16. */
static inline lumo_status lumo_f32bits_to_q16(uint32_t bits, lumo_q16_16 *out)
{
    return lumo_f32bits_to_fixed(bits, LUMO_Q16_SHIFT, out);
}

/* 1 when the bit pattern is a finite number (not NaN, not infinity). */
static inline int lumo_f32bits_is_finite(uint32_t bits)
{
    return ((bits >> 23) & 0xFFu) != 0xFFu;
}

/* ---- shared-exponent HDR colour (RGB9E5, GL_EXT_texture_shared_exponent) -- */

/* Unpack a packed RGB9E5 word (R bits 0-8, G 9-17, B 18-26, E 27-31) into
 * three UQ16.16 values, rounded to nearest. value = m * 2^(E - 15 - 9). */
void lumo_rgb9e5_to_uq16(uint32_t packed, lumo_uq16_16 out[3]);

#endif /* LUMO_FIXED_H */
