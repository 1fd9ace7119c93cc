/*
 * test_package.c — the client's .lumo reader (lumo/package.h) on packages
 * assembled byte by byte here (docs/package-format.md): known values,
 * every single-byte corruption and every truncation refused, outputs
 * untouched on error, CRC-32 check value, version 1 refused, the ORDR
 * decoder.
 */
#include "test_common.h"
#include <stdlib.h>
#include "lumo/package.h"
#include "lumo/wire.h"
#include "test_pkg_build.h"

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
    assert_int_equal(l.kind, LUMO_LIGHT_SPOT);
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
    assert_int_equal(LUMO_PKG_VERSION_MAJOR, 2);
    p.b[4] = 3;   /* major 3, header CRC fixed up: a well-formed newer package */
    wr32(p.b + 20, lumo_wire_crc32(0, p.b, 20));
    assert_int_equal(lumo_package_open(&pkg, p.b, p.n), LUMO_ERR_VERSION);
    p.b[4] = 1;   /* major 1: the IVG in index order, no IVGS; re-bake */
    wr32(p.b + 20, lumo_wire_crc32(0, p.b, 20));
    assert_int_equal(lumo_package_open(&pkg, p.b, p.n), LUMO_ERR_VERSION);
    uint16_t major = 0, minor = 9;
    assert_int_equal(lumo_package_peek_version(p.b, p.n, &major, &minor), LUMO_OK);
    assert_int_equal(major, 1);
    assert_int_equal(minor, 0);
    assert_int_equal(lumo_package_peek_version(p.b, 7, &major, &minor), LUMO_ERR_TRUNCATED);
    p.b[0] = 'X';
    assert_int_equal(lumo_package_peek_version(p.b, p.n, &major, &minor), LUMO_ERR_CORRUPT);
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

/* ORDR: prefix and cycle steps, every field checked. */
static void ordr_chunk(chunk *c, uint32_t prefix, uint32_t cycle, const uint32_t (*steps)[3])
{
    bytes *o = &c->data;
    c->type = LUMO_PKG_ORDR;
    o->n = 0;
    put32(o, prefix), put32(o, cycle);
    for (uint32_t i = 0; i < prefix + cycle; i++)
        put32(o, steps[i][0]), put32(o, steps[i][1]), put32(o, steps[i][2]);
}

static void test_order_chunk(void **state)
{
    (void)state;
    static bytes p;
    static chunk c[3];
    const uint32_t steps[4][3] = {{0, 0, 3}, {1, 0, 1}, {0, 0, 250}, {1, 0, 2}};
    lumo_package pkg;
    lumo_scene_order o;
    lumo_scene_step st;
    lumo_ivg_order io;
    info_chunk(&c[0]);
    ivgd_chunk(&c[1]);
    ordr_chunk(&c[2], 2, 2, steps);
    assemble(&p, c, 3);
    assert_int_equal(lumo_package_open(&pkg, p.b, p.n), LUMO_OK);
    assert_int_equal(lumo_package_order(&pkg, &o), LUMO_OK);
    assert_int_equal(o.prefix, 2);
    assert_int_equal(o.cycle, 2);
    for (uint32_t i = 0; i < 4; i++) {
        assert_int_equal(lumo_scene_order_step(&o, i, &st), LUMO_OK);
        assert_int_equal(st.channel, steps[i][0]);
        assert_int_equal(st.mesh, steps[i][1]);
        assert_int_equal(st.amount, steps[i][2]);
    }
    assert_int_equal(lumo_scene_order_step(&o, 4, &st), LUMO_ERR_RANGE);
    assert_int_equal(lumo_package_ivg_order(&pkg, &io), LUMO_ERR_RANGE);   /* no IVGS */
    /* the decoder on damaged payloads */
    const uint8_t *d = c[2].data.b;
    size_t n = c[2].data.n;
    for (size_t k = 0; k < n; k++)
        assert_int_equal(lumo_scene_order_decode(d, k, 1, &o), LUMO_ERR_TRUNCATED);
    assert_int_equal(lumo_scene_order_decode(d, n, 0, &o), LUMO_ERR_RANGE);   /* mesh 0 of none */
    static uint8_t x[128];
    memcpy(x, d, n);
    x[n] = 0;
    assert_int_equal(lumo_scene_order_decode(x, n + 1, 1, &o), LUMO_ERR_CORRUPT);
    memcpy(x, d, n), x[8 + 12 * 2] = 2;        /* channel 2 */
    assert_int_equal(lumo_scene_order_decode(x, n, 1, &o), LUMO_ERR_UNSUPPORTED);
    memcpy(x, d, n), wr32(x + 8 + 12 * 3 + 8, 0);   /* amount 0 */
    assert_int_equal(lumo_scene_order_decode(x, n, 1, &o), LUMO_ERR_CORRUPT);
    memcpy(x, d, n), wr32(x + 8 + 12 + 4, 1);        /* lighting naming mesh 1 */
    assert_int_equal(lumo_scene_order_decode(x, n, 2, &o), LUMO_ERR_CORRUPT);
    memcpy(x, d, n), wr32(x + 8 + 12 * 2 + 4, 1);    /* geometry mesh 1 of 1 */
    assert_int_equal(lumo_scene_order_decode(x, n, 1, &o), LUMO_ERR_RANGE);
    assert_int_equal(lumo_scene_order_decode(x, n, 2, &o), LUMO_OK);
    memcpy(x, d, n), wr32(x, 0xFFFFFFFFu);           /* counts beyond the length */
    assert_int_equal(lumo_scene_order_decode(x, n, 1, &o), LUMO_ERR_TRUNCATED);
    memcpy(x, d, n), wr32(x, 1);
    assert_int_equal(lumo_scene_order_decode(x, n, 1, &o), LUMO_ERR_CORRUPT);
    /* no ORDR: RANGE; and an empty cycle is a valid order */
    assemble(&p, c, 2);
    assert_int_equal(lumo_package_open(&pkg, p.b, p.n), LUMO_OK);
    assert_int_equal(lumo_package_order(&pkg, &o), LUMO_ERR_RANGE);
    ordr_chunk(&c[2], 1, 0, steps);
    assert_int_equal(lumo_scene_order_decode(c[2].data.b, c[2].data.n, 1, &o), LUMO_OK);
    assert_int_equal(o.cycle, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_open_and_read),
        cmocka_unit_test(test_every_byte_flip_refused), cmocka_unit_test(test_every_truncation_refused),
        cmocka_unit_test(test_version_and_limits),      cmocka_unit_test(test_mesh_content_errors),
        cmocka_unit_test(test_order_chunk),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
