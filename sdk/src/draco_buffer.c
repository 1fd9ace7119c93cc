/*
 * draco_buffer.c — the Draco decoder's bounds-checked cursor over the wire
 * layer (lumo/wire.h), and libdraco's own bit reader (DecoderBuffer::
 * BitDecoder), kept apart from lumo_wire_bits because a read past its end
 * yields zero bits instead of an error, as libdraco's does.
 */
#include "draco_internal.h"
#include "lumo/wire.h"

lumo_status ld_u8(ld_buf *b, uint8_t *v)
{
    if (ld_remaining(b) < 1)
        return LUMO_ERR_TRUNCATED;
    *v = b->data[b->pos++];
    return LUMO_OK;
}

lumo_status ld_u16(ld_buf *b, uint16_t *v)
{
    const uint8_t *p;
    if (ld_remaining(b) < 2)
        return LUMO_ERR_TRUNCATED;
    p = ld_head(b);
    *v = lumo_wire_le16(p);
    b->pos += 2;
    return LUMO_OK;
}

lumo_status ld_u32(ld_buf *b, uint32_t *v)
{
    const uint8_t *p;
    if (ld_remaining(b) < 4)
        return LUMO_ERR_TRUNCATED;
    p = ld_head(b);
    *v = lumo_wire_le32(p);
    b->pos += 4;
    return LUMO_OK;
}

/* LEB128 as libdraco reads it: sizeof(T) + 1 + sizeof(T) / 8 bytes at most,
 * bits that overflow the type silently dropped (lumo_wire_leb128). */
static lumo_status ld_varint(ld_buf *b, unsigned max_bytes, uint64_t *v)
{
    return lumo_wire_leb128(b->data, b->size, &b->pos, max_bytes, v);
}

lumo_status ld_varint32_slow(ld_buf *b, uint32_t *v)
{
    uint64_t r;
    lumo_status st = ld_varint(b, 5, &r);
    if (st)
        return st;
    *v = (uint32_t)r;
    return LUMO_OK;
}

lumo_status ld_varint64(ld_buf *b, uint64_t *v)
{
    return ld_varint(b, 10, v);
}

lumo_status ld_skip(ld_buf *b, uint64_t n)
{
    if (n > ld_remaining(b))
        return LUMO_ERR_TRUNCATED;
    b->pos += (size_t)n;
    return LUMO_OK;
}

lumo_status ld_take(ld_buf *b, uint64_t n, ld_buf *sub)
{
    if (n > ld_remaining(b))
        return LUMO_ERR_TRUNCATED;
    sub->data = ld_head(b);
    sub->size = (size_t)n;
    sub->pos = 0;
    b->pos += (size_t)n;
    return LUMO_OK;
}

void ld_bits_start(ld_bits *r, const ld_buf *b)
{
    r->data = ld_head(b);
    r->size = ld_remaining(b);
    r->bit = 0;
}

uint32_t ld_bits_get_slow(ld_bits *r, unsigned nbits)
{
    uint32_t v = 0;
    unsigned i;
    for (i = 0; i < nbits; ++i) {
        size_t byte = r->bit >> 3;
        if (byte >= r->size)
            break;  /* libdraco: zero bits, position unchanged */
        v |= (uint32_t)((r->data[byte] >> (r->bit & 7u)) & 1u) << i;
        r->bit++;
    }
    return v;
}

void ld_bits_skip(ld_bits *r, uint64_t n)
{
    const uint64_t left = (uint64_t)r->size * 8u - r->bit;
    r->bit += (size_t)(n < left ? n : left);
}

void ld_bits_end(ld_bits *r, ld_buf *b)
{
    size_t bytes = (r->bit + 7u) >> 3;
    b->pos += bytes;  /* bytes <= remaining by construction */
}
