/* ivg_wire.c — IVG bundle hand encoder for the board tests (see ivg_wire.h). */
#include "ivg_wire.h"

void wire_u16(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
}

void wire_u32(uint8_t *p, uint32_t v)
{
    wire_u16(p, v);
    wire_u16(p + 2, v >> 16);
}

size_t wire_header(uint8_t *p, unsigned form, const uint16_t dims[3], uint32_t records)
{
    p[0] = 'I';
    p[1] = 'V';
    p[2] = 'G';
    p[3] = 'B';
    p[4] = 1;
    p[5] = (uint8_t)form;
    wire_u16(p + 6, dims[0]);
    wire_u16(p + 8, dims[1]);
    wire_u16(p + 10, dims[2]);
    wire_u32(p + 12, records);
    return WIRE_HEADER;
}

uint32_t wire_rgb9e5(const uint16_t m[3], unsigned e)
{
    return (uint32_t)(m[0] & 0x1FFu) | (uint32_t)(m[1] & 0x1FFu) << 9
         | (uint32_t)(m[2] & 0x1FFu) << 18 | (uint32_t)(e & 31u) << 27;
}

size_t wire_quant_record(uint8_t *p, uint32_t vertex, const wire_qentry e[6])
{
    size_t pos = 4;
    int a, k;

    wire_u32(p, vertex);
    for (a = 0; a < 6; a++) {
        for (k = 0; k < 3; k++)
            p[pos + (size_t)k] = (uint8_t)e[a].d[k];
        wire_u32(p + pos + 3, wire_rgb9e5(e[a].m, e[a].e));
        pos += 7;
    }
    return pos;
}

uint32_t wire_f32bits(int32_t num, unsigned shift)
{
    uint32_t sign = num < 0 ? 0x80000000u : 0u;
    uint32_t mag = num < 0 ? (uint32_t)0 - (uint32_t)num : (uint32_t)num;
    unsigned msb = 0;

    if (mag == 0)
        return sign;
    while ((mag >> msb) > 1u)
        msb++;
    /* value = 1.f * 2^(msb - shift); the mantissa keeps 23 bits below msb */
    return sign | (uint32_t)(127u + msb - shift) << 23 | ((mag << (23u - msb)) & 0x7FFFFFu);
}

size_t wire_float_record(uint8_t *p, uint32_t vertex, const wire_fentry e[6])
{
    size_t pos = 4;
    int a, k;

    wire_u32(p, vertex);
    for (a = 0; a < 6; a++) {
        for (k = 0; k < 3; k++)
            wire_u32(p + pos + 4u * (size_t)k, wire_f32bits(e[a].dnum[k], 6));
        for (k = 0; k < 3; k++)
            wire_u32(p + pos + 12u + 4u * (size_t)k, wire_f32bits((int32_t)e[a].cnum[k], 8));
        pos += 24;
    }
    return pos;
}
