/*
 * test_package.c — the client's .lumo reader (lumo/package.h) on packages
 * assembled byte by byte here (docs/package-format.md): known values,
 * every single-byte corruption and every truncation refused, outputs
 * untouched on error, CRC-32 check value.
 */
#include "test_common.h"
#include <stdlib.h>
#include "lumo/package.h"
#include "lumo/wire.h"

typedef struct { uint8_t b[8192]; size_t n; } bytes;

static void put32(bytes *o, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        o->b[o->n++] = (uint8_t)(v >> (8 * i));
}
static void put16(bytes *o, uint32_t v)
{
    o->b[o->n++] = (uint8_t)v;
    o->b[o->n++] = (uint8_t)(v >> 8);
}
static void putf(bytes *o, float f) { put32(o, test_f32_bits(f)); }
static void put3(bytes *o, float a, float b, float c) { putf(o, a), putf(o, b), putf(o, c); }
static void wr32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        p[i] = (uint8_t)(v >> (8 * i));
}

typedef struct { uint32_t type; bytes data; } chunk;

/* Header + table + 4-aligned chunks, as the server writes them. */
static void assemble(bytes *out, const chunk *c, uint32_t n)
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

static void info_chunk(chunk *c)
{
    bytes *o = &c->data;
    c->type = LUMO_PKG_INFO;
    o->n = 0;
    put32(o, 1), put32(o, 1), put32(o, 1), put32(o, 0);
    put3(o, -1, 0, -1), put3(o, 1, 2, 1);
    put3(o, 0, 1, 3.5f), put3(o, 0, 1, 0), put3(o, 0, 1, 0), putf(o, 40);
    put32(o, LUMO_PKG_LIGHT_SPOT);
    put3(o, 0, 1.95f, 0), put3(o, 0, -1, 0), put3(o, 0, 0, 0), put3(o, 0, 0, 0);
    putf(o, 60), putf(o, 0.5f), put3(o, 40, 20, 10);
}

static void mesh_chunk(chunk *c, uint32_t bad_index)
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

static void ivgd_chunk(chunk *c)
{
    bytes *o = &c->data;
    c->type = LUMO_PKG_IVGD;
    o->n = 0;
    put16(o, 4), put16(o, 3), put16(o, 2), put16(o, 0);
    put3(o, -1, 0, -1), put3(o, 1, 2, 1);
    put32(o, 64), put32(o, 7), put32(o, 0), put32(o, 24);
}

static void sample_package(bytes *out)
{
    static chunk c[3];
    info_chunk(&c[0]);
    mesh_chunk(&c[1], 1);
    ivgd_chunk(&c[2]);
    assemble(out, c, 3);
}

static void test_open_and_read(void **state)
{
    (void)state;
    static bytes p;
    lumo_package pkg;
    lumo_pkg_info in;
    lumo_pkg_light l;
    lumo_pkg_mesh_info mi;
    lumo_ivg_desc d;
    sample_package(&p);
    assert_int_equal(lumo_package_open(&pkg, p.b, p.n), LUMO_OK);
    assert_int_equal(pkg.chunk_count, 3);
    assert_int_equal(lumo_package_info(&pkg, &in), LUMO_OK);
    assert_int_equal(in.bmin[0], -65536);
    assert_int_equal(in.bmax[1], 2 * 65536);
    assert_int_equal(in.eye[2], 7 * 32768);
    assert_int_equal(in.fovy_deg, 40 * 65536);
    assert_int_equal(lumo_package_light(&pkg, 0, &l), LUMO_OK);
    assert_int_equal(l.kind, LUMO_PKG_LIGHT_SPOT);
    assert_int_equal(l.dir[1], -16384);
    assert_int_equal(l.cos_half, 8192);
    assert_int_equal(l.power[1], 20u * 65536u);
    assert_int_equal(lumo_package_light(&pkg, 1, &l), LUMO_ERR_RANGE);
    assert_int_equal(lumo_package_mesh_info(&pkg, 0, &mi), LUMO_OK);
    assert_int_equal(mi.nverts, 3);
    assert_int_equal(mi.ntris, 1);
    assert_int_equal(lumo_package_mesh_info(&pkg, 1, &mi), LUMO_ERR_RANGE);
    lumo_q16_16 pos[9];
    lumo_q1_14 nrm[9], alb[9];
    uint32_t tris[3];
    assert_int_equal(lumo_package_mesh_read(&pkg, 0, pos, nrm, alb, tris), LUMO_OK);
    assert_int_equal(pos[3], 65536);
    assert_int_equal(pos[8], -3 * 32768);
    assert_int_equal(nrm[4], 16384);
    assert_int_equal(alb[1], 4096);
    assert_int_equal(tris[1], 2);
    assert_int_equal(lumo_package_ivg_desc(&pkg, &d), LUMO_OK);
    assert_int_equal(d.dims[0], 4);
    assert_int_equal(d.dims[2], 2);
    assert_int_equal(d.bmax[1], 2 * 65536);
    const uint8_t *payload;
    uint32_t len;
    assert_int_equal(lumo_package_find(&pkg, LUMO_PKG_IVGQ, 0, &payload, &len), LUMO_ERR_RANGE);
}

/* Every single-byte change is caught (CRCs cover all bytes but the zero
 * padding, which is checked to be zero), and *pkg stays as it was. */
static void test_every_byte_flip_refused(void **state)
{
    (void)state;
    static bytes p;
    lumo_package pkg, before;
    sample_package(&p);
    memset(&pkg, 0xA5, sizeof pkg);
    before = pkg;
    for (size_t i = 0; i < p.n; i++)
        for (int bit = 0; bit < 8; bit++) {
            p.b[i] ^= (uint8_t)(1u << bit);
            assert_int_not_equal(lumo_package_open(&pkg, p.b, p.n), LUMO_OK);
            assert_memory_equal(&pkg, &before, sizeof pkg);
            p.b[i] ^= (uint8_t)(1u << bit);
        }
}

static void test_every_truncation_refused(void **state)
{
    (void)state;
    static bytes p;
    lumo_package pkg;
    sample_package(&p);
    for (size_t n = 0; n < p.n; n++) {
        lumo_status st = lumo_package_open(&pkg, p.b, n);
        assert_true(st == LUMO_ERR_TRUNCATED || st == LUMO_ERR_CORRUPT || st == LUMO_ERR_CHECKSUM);
    }
    p.b[p.n++] = 0;   /* trailing byte */
    assert_int_equal(lumo_package_open(&pkg, p.b, p.n), LUMO_ERR_CORRUPT);
    assert_int_equal(lumo_package_open(&pkg, NULL, 0), LUMO_ERR_TRUNCATED);
    assert_int_equal(lumo_package_open(NULL, p.b, p.n), LUMO_ERR_ARG);
}

static void test_version_and_limits(void **state)
{
    (void)state;
    static bytes p;
    lumo_package pkg;
    sample_package(&p);
    p.b[4] = 2;   /* major 2, header CRC fixed up: a well-formed newer package */
    wr32(p.b + 20, lumo_wire_crc32(0, p.b, 20));
    assert_int_equal(lumo_package_open(&pkg, p.b, p.n), LUMO_ERR_VERSION);
    sample_package(&p);
    p.b[6] = 9;   /* a newer minor version still opens */
    wr32(p.b + 20, lumo_wire_crc32(0, p.b, 20));
    assert_int_equal(lumo_package_open(&pkg, p.b, p.n), LUMO_OK);
    assert_int_equal(pkg.version_minor, 9);
    wr32(p.b + 8, LUMO_PKG_MAX_CHUNKS + 1);
    wr32(p.b + 20, lumo_wire_crc32(0, p.b, 20));
    assert_int_equal(lumo_package_open(&pkg, p.b, p.n), LUMO_ERR_LIMIT);
}

/* Well-formed container, hostile content: bad vertex index, NaN, a normal
 * out of [-1, 1]. Outputs are untouched. */
static void test_mesh_content_errors(void **state)
{
    (void)state;
    static bytes p;
    static chunk c[2];
    lumo_package pkg;
    lumo_q16_16 pos[9];
    uint32_t tris[3];
    info_chunk(&c[0]);
    mesh_chunk(&c[1], 3);
    assemble(&p, c, 2);
    assert_int_equal(lumo_package_open(&pkg, p.b, p.n), LUMO_OK);
    memset(pos, 0x5A, sizeof pos);
    memset(tris, 0x5A, sizeof tris);
    assert_int_equal(lumo_package_mesh_read(&pkg, 0, pos, NULL, NULL, tris), LUMO_ERR_RANGE);
    for (int i = 0; i < 9; i++)
        assert_int_equal(pos[i], 0x5A5A5A5A);
    mesh_chunk(&c[1], 1);
    wr32(c[1].data.b + 16 + 36 + 4, 0x7FC00000u);   /* NaN y of vertex 1 */
    assemble(&p, c, 2);
    assert_int_equal(lumo_package_open(&pkg, p.b, p.n), LUMO_OK);
    assert_int_equal(lumo_package_mesh_read(&pkg, 0, pos, NULL, NULL, tris), LUMO_ERR_NONFINITE);
    mesh_chunk(&c[1], 1);
    wr32(c[1].data.b + 16 + 12, test_f32_bits(1.5f));  /* normal x > 1 */
    assemble(&p, c, 2);
    assert_int_equal(lumo_package_open(&pkg, p.b, p.n), LUMO_OK);
    assert_int_equal(lumo_package_mesh_read(&pkg, 0, pos, (lumo_q1_14[9]){0}, NULL, NULL), LUMO_ERR_RANGE);
    c[1].data.n -= 4;   /* length disagrees with the counts */
    assemble(&p, c, 2);
    assert_int_equal(lumo_package_open(&pkg, p.b, p.n), LUMO_OK);
    assert_int_equal(lumo_package_mesh_read(&pkg, 0, pos, NULL, NULL, NULL), LUMO_ERR_CORRUPT);
    /* No INFO chunk at all: the info getter says corrupt. */
    lumo_pkg_info in;
    assemble(&p, &c[1], 1);
    assert_int_equal(lumo_package_open(&pkg, p.b, p.n), LUMO_OK);
    assert_int_equal(lumo_package_info(&pkg, &in), LUMO_ERR_CORRUPT);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_open_and_read),
        cmocka_unit_test(test_every_byte_flip_refused), cmocka_unit_test(test_every_truncation_refused),
        cmocka_unit_test(test_version_and_limits),      cmocka_unit_test(test_mesh_content_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
