/*
 * lumo/wire.h — the byte layer every lumo format shares, on both sides:
 * little-endian integers, LEB128 varints, LSB-first bit fields and CRC-32.
 *
 * The package container, the progressive-mesh stream, IVG bundles, the
 * Draco decoder and the network frames read their bytes through these
 * functions, and the server writes them through the same ones, so a format
 * cannot drift between its writer and its reader (docs/architecture.md).
 *
 * Nothing here allocates; readers bounds-check against the size they are
 * given and return a lumo_status (TRUNCATED when the bytes run out, CORRUPT
 * for an ill-formed varint) with their outputs untouched on error. The
 * fixed-width helpers (lumo_wire_le*) read or write exactly their width at p:
 * the caller has checked the room.
 */
#ifndef LUMO_WIRE_H
#define LUMO_WIRE_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/status.h"

/* ---- fixed-width little-endian integers ---------------------------------- */

/* The little-endian uint16 at p (2 bytes readable). */
static inline uint16_t lumo_wire_le16(const uint8_t *p)
{
    return (uint16_t)(p[0] | p[1] << 8);
}

/* The little-endian uint32 at p (4 bytes readable). */
static inline uint32_t lumo_wire_le32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* The little-endian uint64 at p (8 bytes readable). */
static inline uint64_t lumo_wire_le64(const uint8_t *p)
{
    return (uint64_t)lumo_wire_le32(p) | (uint64_t)lumo_wire_le32(p + 4) << 32;
}

/* v little-endian at p (2 bytes writable). */
static inline void lumo_wire_put_le16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)v, p[1] = (uint8_t)(v >> 8);
}

/* v little-endian at p (4 bytes writable). */
static inline void lumo_wire_put_le32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v, p[1] = (uint8_t)(v >> 8), p[2] = (uint8_t)(v >> 16), p[3] = (uint8_t)(v >> 24);
}

/* v little-endian at p (8 bytes writable). */
static inline void lumo_wire_put_le64(uint8_t *p, uint64_t v)
{
    lumo_wire_put_le32(p, (uint32_t)v);
    lumo_wire_put_le32(p + 4, (uint32_t)(v >> 32));
}

/* ---- LEB128 varints -------------------------------------------------------
 * 7 bits per byte, low group first, the high bit set on every byte but the
 * last. */

/* Bytes of a 32-bit varint, at most. */
#define LUMO_WIRE_VARINT32_MAX 5u

/* The permissive reader Draco needs (libdraco's DecodeVarint): at most
 * max_bytes bytes from d[*at], groups beyond 64 bits dropped, any coding of
 * a value accepted. Advances *at past the varint. TRUNCATED when the data
 * ends inside it, CORRUPT when max_bytes bytes all carry the "more" bit. */
lumo_status lumo_wire_leb128(const uint8_t *d, size_t size, size_t *at, unsigned max_bytes,
                             uint64_t *v);

/* The strict reader lumo's own formats use: at most 5 bytes, the value at
 * most `max`, and minimally coded (no trailing zero group), so every value
 * has exactly one encoding. CORRUPT otherwise. */
lumo_status lumo_wire_varint(const uint8_t *d, size_t size, size_t *at, uint32_t max, uint32_t *v);

/* Write v minimally coded at out (room for LUMO_WIRE_VARINT32_MAX bytes);
 * returns the bytes written (1..5). */
size_t lumo_wire_put_varint(uint8_t *out, uint32_t v);

/* ---- LSB-first bit fields -------------------------------------------------
 * Bit i of a stream is bit (i & 7) of byte i >> 3; a field of n bits holds
 * its lowest bit first. */

/* A bit reader over the caller's bytes. */
typedef struct lumo_wire_bits {
    const uint8_t *data;   /* not owned */
    size_t nbits;          /* bits available */
    size_t pos;            /* next bit to read */
} lumo_wire_bits;

/* Read from `bytes` bytes at data. */
void lumo_wire_bits_init(lumo_wire_bits *b, const uint8_t *data, size_t bytes);

/* Read n (0..32) bits into *out. TRUNCATED (and nothing consumed) when
 * fewer than n bits are left. */
lumo_status lumo_wire_bits_read(lumo_wire_bits *b, unsigned n, uint32_t *out);

/* Bits left to read. */
static inline size_t lumo_wire_bits_left(const lumo_wire_bits *b)
{
    return b->nbits - b->pos;
}

/* OR the low n (0..32) bits of v into buf at bit position pos: the writer's
 * side of lumo_wire_bits_read. The caller owns buf, has zeroed the bits
 * written and checked the room (pos + n bits). */
void lumo_wire_put_bits(uint8_t *buf, size_t pos, uint32_t v, unsigned n);

/* ---- CRC-32 -----------------------------------------------------------------
 * IEEE 802.3, reflected (zlib's crc32): continue `crc` (0 to start) over
 * len bytes. */
uint32_t lumo_wire_crc32(uint32_t crc, const uint8_t *buf, size_t len);

#endif /* LUMO_WIRE_H */
