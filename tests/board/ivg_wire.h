/*
 * ivg_wire.h — a hand encoder of IVG sample bundles for the board tests,
 * written from the wire format in lumo/ivg.h / docs/ivg-format.md with
 * integer code only (the server's encoder is desktop code and may use float;
 * this one must run on the board too). Little-endian, byte by byte.
 */
#ifndef LUMO_BOARD_IVG_WIRE_H
#define LUMO_BOARD_IVG_WIRE_H

#include <stddef.h>
#include <stdint.h>

#define WIRE_HEADER 16u
#define WIRE_QUANT_RECORD (4u + 6u * 7u)
#define WIRE_FLOAT_RECORD (4u + 6u * 24u)
#define WIRE_SOLID 0x80000000u

void wire_u16(uint8_t *p, uint32_t v);
void wire_u32(uint8_t *p, uint32_t v);

/* Header: magic "IVGB", version 1, form (0 binary32, 1 quantized), dims,
 * record count. Returns WIRE_HEADER. */
size_t wire_header(uint8_t *p, unsigned form, const uint16_t dims[3], uint32_t records);

/* One quantized entry: d as three int8 (value q/127), c as RGB9E5 built from
 * three 9-bit mantissas and a 5-bit exponent (value m * 2^(e - 24)). */
typedef struct wire_qentry {
    int8_t   d[3];
    uint16_t m[3];
    uint8_t  e;
} wire_qentry;

uint32_t wire_rgb9e5(const uint16_t m[3], unsigned e);

/* Record: index word then six entries (+x, -x, +y, -y, +z, -z). Returns the
 * bytes written (WIRE_QUANT_RECORD). */
size_t wire_quant_record(uint8_t *p, uint32_t vertex, const wire_qentry e[6]);

/* The binary32 bit pattern of num / 2^shift, exact when |num| < 2^24 (the
 * float-form tests use only such dyadic values). */
uint32_t wire_f32bits(int32_t num, unsigned shift);

/* A binary32 entry: d = dnum / 64, c = cnum / 256 per channel. */
typedef struct wire_fentry {
    int16_t  dnum[3];
    uint32_t cnum[3];
} wire_fentry;

size_t wire_float_record(uint8_t *p, uint32_t vertex, const wire_fentry e[6]);

#endif
