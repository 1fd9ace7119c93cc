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

lumo_q1_14 ivg_snorm8_to_q14(int32_t q)
{
    int32_t mag = q < 0 ? -q : q;
    int32_t v = (mag * LUMO_Q14_ONE + 63) / 127;   /* q/127 to nearest */

    return (lumo_q1_14)(q < 0 ? -v : v);
}

void ivg_entry_unpack(const uint8_t *p, lumo_ivg_entry *e)
{
    int k;

    for (k = 0; k < 3; k++)
        e->d[k] = ivg_snorm8_to_q14((int8_t)p[k]);
    lumo_rgb9e5_to_uq16(lumo_wire_le32(p + 3), e->c);
    e->reserved = 0;
}

/* Q1.14 to the nearest q/127, ties away from zero, clamped to +-127 (a
 * direction longer than one, which a binary32 record may hold, keeps its
 * sign and saturates). */
static uint8_t q14_to_snorm8(int32_t d)
{
    uint32_t mag = d < 0 ? (uint32_t)-d : (uint32_t)d;
    uint32_t q = (mag * 254u + LUMO_Q14_ONE) / (2u * LUMO_Q14_ONE);   /* round(mag * 127 / 2^14) */

    if (q > 127u)
        q = 127u;
    return (uint8_t)(d < 0 ? (256u - q) & 0xFFu : q);
}

/* c >> s rounded half up (s may be 0). */
static uint32_t shift_round(uint32_t c, unsigned s)
{
    return s == 0 ? c : (uint32_t)(((uint64_t)c + (1u << (s - 1u))) >> s);
}

/* The smallest exponent whose rounded mantissa of the largest channel fits
 * 9 bits: E < 8 shifts left (exact for the tiny values that take it). */
static uint32_t rgb9e5_pack(const uint32_t c[3])
{
    uint32_t top = c[0] > c[1] ? c[0] : c[1], m[3], word;
    unsigned e = 0, k;

    top = top > c[2] ? top : c[2];
    while (e < EXP_MAX && (e < 8u ? (uint64_t)top << (8u - e) : shift_round(top, e - 8u)) > MANT_MAX)
        e++;
    for (k = 0; k < 3; k++) {
        uint64_t v = e < 8u ? (uint64_t)c[k] << (8u - e) : shift_round(c[k], e - 8u);
        m[k] = v > MANT_MAX ? MANT_MAX : (uint32_t)v;
    }
    word = m[0] | m[1] << 9 | m[2] << 18 | (uint32_t)e << 27;
    return word;
}

void ivg_entry_pack(const lumo_ivg_entry *e, uint8_t *p)
{
    int k;

    for (k = 0; k < 3; k++)
        p[k] = q14_to_snorm8(e->d[k]);
    lumo_wire_put_le32(p + 3, rgb9e5_pack(e->c));
}
