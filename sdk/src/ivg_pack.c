/*
 * ivg_pack.c — the IVG's stored entry: the quantized wire form (seed 000
 * §3.3: an 8:8:8 direction and an RGB9E5 colour, 7 bytes per hemisphere),
 * kept for received, filled and pyramid vertices alike so the grid costs
 * about what it costs on the wire (docs/ivg-format.md §6). Unpacking gives
 * the fixed-point values of §2.5 exactly; packing rounds to the nearest
 * representable entry. Integer only, no division but by constants.
 */
#include "ivg_internal.h"
#include "lumo/wire.h"

/* RGB9E5 (GL_EXT_texture_shared_exponent): 9-bit mantissas, exponent bias
 * 15; in UQ16.16 units a mantissa step is 2^(E - 8). */
#define MANT_MAX 511u
#define EXP_MAX  31u

/* The steps of opening an RGB9E5 word, per exponent E (ivg_internal.h):
 * below 8, add 2^(7-E) and shift down by 8 - E; from 8 on, shift up by
 * E - 8. */
#define E5_DOWN(e) ((1u << (7u - (e))) | (8u - (e)) << 8)
#define E5_UP(e)   (((e) - 8u) << 12)
const uint32_t ivg_e5_steps[32] = {
    E5_DOWN(0), E5_DOWN(1), E5_DOWN(2), E5_DOWN(3), E5_DOWN(4), E5_DOWN(5), E5_DOWN(6), E5_DOWN(7),
    E5_UP(8), E5_UP(9), E5_UP(10), E5_UP(11), E5_UP(12), E5_UP(13), E5_UP(14), E5_UP(15),
    E5_UP(16), E5_UP(17), E5_UP(18), E5_UP(19), E5_UP(20), E5_UP(21), E5_UP(22), E5_UP(23),
    E5_UP(24), E5_UP(25), E5_UP(26), E5_UP(27), E5_UP(28), E5_UP(29), E5_UP(30), E5_UP(31),
};

lumo_q1_14 ivg_snorm8_to_q14(int32_t q)
{
    int32_t mag = q < 0 ? -q : q;
    int32_t v = (mag * LUMO_Q14_ONE + 63) / 127;   /* q/127 to nearest */

    return (lumo_q1_14)(q < 0 ? -v : v);
}

void ivg_entry_unpack(const uint8_t *p, lumo_ivg_entry *e)
{
    ivg_raw r;
    int k;

    ivg_raw_open(p, &r);
    for (k = 0; k < 3; k++) {
        e->d[k] = ivg_snorm8_to_q14(r.q[k]);
        e->c[k] = r.c[k];
    }
    e->reserved = 0;
}

/* Q1.14 to the nearest q/127, ties away from zero, clamped to +-127 (a
 * direction longer than one, which a binary32 record may hold, keeps its
 * sign and saturates). */
static int32_t q14_to_snorm8(int32_t d)
{
    uint32_t mag = d < 0 ? (uint32_t)-d : (uint32_t)d;
    uint32_t q = (mag * 254u + LUMO_Q14_ONE) / (2u * LUMO_Q14_ONE);   /* round(mag * 127 / 2^14) */

    if (q > 127u)
        q = 127u;
    return d < 0 ? -(int32_t)q : (int32_t)q;
}

/* Bit lengths of 0..255. */
static const uint8_t k_bits8[256] = {
#define B4(n) n, n, n, n
#define B16(n) B4(n), B4(n), B4(n), B4(n)
    0, 1, 2, 2, B4(3), B4(4), B4(4), B16(5), B16(6), B16(6),
    B16(7), B16(7), B16(7), B16(7),
    B16(8), B16(8), B16(8), B16(8), B16(8), B16(8), B16(8), B16(8),
#undef B16
#undef B4
};

/* Bits needed for v (0 for 0), without a count-leading-zeros instruction
 * (the Cortex-M0+ has none): two halvings and a table. */
static unsigned bit_length(uint32_t v)
{
    unsigned b = 0;

    if (v >> 16) {
        v >>= 16;
        b = 16;
    }
    if (v >> 8) {
        v >>= 8;
        b += 8;
    }
    return b + k_bits8[v];
}

/* c in mantissa steps of 2^(e-8) UQ16.16 units, rounded half up:
 * floor((c + 2^(e-9)) / 2^(e-8)) = (floor(c / 2^(e-9)) + 1) / 2, in 32
 * bits; below e = 9 the step divides c exactly (only for c < 2^(e+1): the
 * result is < 512). */
static uint32_t mantissa(uint32_t c, unsigned e)
{
    return e >= 9u ? ((c >> (e - 9u)) + 1u) >> 1 : c << (8u - e);
}

/* The smallest exponent whose rounded mantissa of the largest channel fits
 * 9 bits: e = bit length - 1 puts it in [256, 512) before rounding, one
 * more when it rounds up to 512. */
static uint32_t rgb9e5_pack(const uint32_t c[3])
{
    uint32_t top = c[0] > c[1] ? c[0] : c[1], m[3];
    unsigned b, e, k;

    top = top > c[2] ? top : c[2];
    b = bit_length(top);
    e = b > 0u ? b - 1u : 0u;
    if (e < EXP_MAX && mantissa(top, e) > MANT_MAX)
        e++;
    for (k = 0; k < 3; k++) {
        m[k] = mantissa(c[k], e);
        m[k] = m[k] > MANT_MAX ? MANT_MAX : m[k];   /* only above 65408 W/m^2 */
    }
    return m[0] | m[1] << 9 | m[2] << 18 | (uint32_t)e << 27;
}

void ivg_raw_pack(const ivg_raw *r, uint8_t *p)
{
    int k;

    for (k = 0; k < 3; k++)
        p[k] = (uint8_t)(r->q[k] & 0xFF);
    lumo_wire_put_le32(p + 3, rgb9e5_pack(r->c));
}

void ivg_entry_pack(const lumo_ivg_entry *e, uint8_t *p)
{
    ivg_raw r;
    int k;

    for (k = 0; k < 3; k++) {
        r.q[k] = q14_to_snorm8(e->d[k]);
        r.c[k] = e->c[k];
    }
    ivg_raw_pack(&r, p);
}
