/*
 * test_pkg_build.h — .lumo packages assembled byte by byte for the tests
 * (docs/package-format.md), with the CRCs the server writes: a header, a
 * table, 4-aligned chunks, and small INFO / MESH / IVGD payloads.
 */
#ifndef LUMO_TEST_PKG_BUILD_H
#define LUMO_TEST_PKG_BUILD_H

#include <stdint.h>
#include <string.h>
#include "test_common.h"
#include "lumo/package.h"
#include "lumo/wire.h"

typedef struct { uint8_t b[8192]; size_t n; } bytes;

static inline void put32(bytes *o, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        o->b[o->n++] = (uint8_t)(v >> (8 * i));
}
static inline void put16(bytes *o, uint32_t v)
{
    o->b[o->n++] = (uint8_t)v;
    o->b[o->n++] = (uint8_t)(v >> 8);
}
static inline void putf(bytes *o, float f) { put32(o, test_f32_bits(f)); }
static inline void put3(bytes *o, float a, float b, float c) { putf(o, a), putf(o, b), putf(o, c); }
static inline void wr32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        p[i] = (uint8_t)(v >> (8 * i));
}

typedef struct { uint32_t type; bytes data; } chunk;

/* Header + table + 4-aligned chunks, as the server writes them. */
static inline void assemble(bytes *out, const chunk *c, uint32_t n)
{
    size_t pos = LUMO_PKG_HEADER_SIZE + n * LUMO_PKG_ENTRY_SIZE;
    memset(out, 0, sizeof *out);
    memcpy(out->b, "LUMO", 4);
    out->n = 4;
    put16(out, LUMO_PKG_VERSION_MAJOR);
    put16(out, LUMO_PKG_VERSION_MINOR);
    put32(out, n);
    put32(out, 0);
    put32(out, 0);   /* table crc, patched */
    put32(out, 0);   /* header crc, patched */
    for (uint32_t i = 0; i < n; i++) {
        pos = (pos + 3) & ~(size_t)3;
        put32(out, c[i].type);
        put32(out, (uint32_t)pos);
        put32(out, (uint32_t)c[i].data.n);
        put32(out, lumo_wire_crc32(0, c[i].data.b, c[i].data.n));
        pos += c[i].data.n;
    }
    wr32(out->b + 16, lumo_wire_crc32(0, out->b + LUMO_PKG_HEADER_SIZE, n * LUMO_PKG_ENTRY_SIZE));
    wr32(out->b + 20, lumo_wire_crc32(0, out->b, 20));
    for (uint32_t i = 0; i < n; i++) {
        while (out->n & 3)
            out->b[out->n++] = 0;
        memcpy(out->b + out->n, c[i].data.b, c[i].data.n);
        out->n += c[i].data.n;
    }
}

static inline void info_chunk(chunk *c)
{
    bytes *o = &c->data;
    c->type = LUMO_PKG_INFO;
    o->n = 0;
    put32(o, 1), put32(o, 1), put32(o, 1), put32(o, 0);
    put3(o, -1, 0, -1), put3(o, 1, 2, 1);
    put3(o, 0, 1, 3.5f), put3(o, 0, 1, 0), put3(o, 0, 1, 0), putf(o, 40);
    put32(o, LUMO_LIGHT_SPOT);
    put3(o, 0, 1.95f, 0), put3(o, 0, -1, 0), put3(o, 0, 0, 0), put3(o, 0, 0, 0);
    putf(o, 60), putf(o, 0.5f), put3(o, 40, 20, 10);
}

static inline void mesh_chunk(chunk *c, uint32_t bad_index)
{
    bytes *o = &c->data;
    c->type = LUMO_PKG_MESH;
    o->n = 0;
    put32(o, 0), put32(o, 3), put32(o, 1), put32(o, 0);
    put3(o, 0, 0, 0), put3(o, 0, 1, 0), put3(o, 0.5f, 0.25f, 1);
    put3(o, 1, 0, 0), put3(o, 0, 1, 0), put3(o, 0.5f, 0.25f, 1);
    put3(o, 0, 0, -1.5f), put3(o, 0, 1, 0), put3(o, 0.5f, 0.25f, 1);
    put32(o, 0), put32(o, 2), put32(o, bad_index);
}

static inline void ivgd_chunk(chunk *c)
{
    bytes *o = &c->data;
    c->type = LUMO_PKG_IVGD;
    o->n = 0;
    put16(o, 4), put16(o, 3), put16(o, 2), put16(o, 0);
    put3(o, -1, 0, -1), put3(o, 1, 2, 1);
    put32(o, 64), put32(o, 7), put32(o, 0), put32(o, 24);
}

#endif
