/*
 * wire.c — varints, bit fields and CRC-32 of the byte layer (lumo/wire.h).
 */
#include "lumo/wire.h"

lumo_status lumo_wire_leb128(const uint8_t *d, size_t size, size_t *at, unsigned max_bytes,
                             uint64_t *v)
{
    uint64_t r = 0;
    size_t i = *at;
    unsigned k;

    for (k = 0; k < max_bytes; k++, i++) {
        if (i >= size)
            return LUMO_ERR_TRUNCATED;
        if (7 * k < 64)
            r |= (uint64_t)(d[i] & 0x7fu) << (7 * k);
        if (!(d[i] & 0x80u)) {
            *at = i + 1;
            *v = r;
            return LUMO_OK;
        }
    }
    return LUMO_ERR_CORRUPT;
}

lumo_status lumo_wire_varint(const uint8_t *d, size_t size, size_t *at, uint32_t max, uint32_t *v)
{
    size_t next = *at;
    uint64_t x;
    lumo_status st = lumo_wire_leb128(d, size, &next, LUMO_WIRE_VARINT32_MAX, &x);

    if (st)
        return st;
    /* A last byte of zero after the first is a trailing zero group. */
    if ((next - *at > 1 && d[next - 1] == 0) || x > max)
        return LUMO_ERR_CORRUPT;
    *at = next;
    *v = (uint32_t)x;
    return LUMO_OK;
}

size_t lumo_wire_put_varint(uint8_t *out, uint32_t v)
{
    size_t n = 0;

    while (v >= 0x80u) {
        out[n++] = (uint8_t)(v | 0x80u);
        v >>= 7;
    }
    out[n++] = (uint8_t)v;
    return n;
}

void lumo_wire_bits_init(lumo_wire_bits *b, const uint8_t *data, size_t bytes)
{
    b->data = data;
    b->nbits = bytes * 8u;
    b->pos = 0;
}

lumo_status lumo_wire_bits_read(lumo_wire_bits *b, unsigned n, uint32_t *out)
{
    uint32_t v = 0;
    unsigned i;

    if (n > b->nbits - b->pos)
        return LUMO_ERR_TRUNCATED;
    for (i = 0; i < n; i++, b->pos++)
        v |= (uint32_t)(b->data[b->pos >> 3] >> (b->pos & 7u) & 1u) << i;
    *out = v;
    return LUMO_OK;
}

void lumo_wire_put_bits(uint8_t *buf, size_t pos, uint32_t v, unsigned n)
{
    unsigned i;

    for (i = 0; i < n; i++, pos++)
        buf[pos >> 3] |= (uint8_t)((v >> i & 1u) << (pos & 7u));
}

uint32_t lumo_wire_crc32(uint32_t crc, const uint8_t *buf, size_t len)
{
    /* Half-byte table: 64 bytes of constants instead of 1 KiB. */
    static const uint32_t t[16] = {
        0x00000000u, 0x1DB71064u, 0x3B6E20C8u, 0x26D930ACu, 0x76DC4190u, 0x6B6B51F4u,
        0x4DB26158u, 0x5005713Cu, 0xEDB88320u, 0xF00F9344u, 0xD6D6A3E8u, 0xCB61B38Cu,
        0x9B64C2B0u, 0x86D3D2D4u, 0xA00AE278u, 0xBDBDF21Cu};
    size_t i;

    crc = ~crc;
    for (i = 0; i < len; i++) {
        crc ^= buf[i];
        crc = (crc >> 4) ^ t[crc & 15u];
        crc = (crc >> 4) ^ t[crc & 15u];
    }
    return ~crc;
}
