/*
 * test_session.c — the client session (lumo/session.h) on packages built
 * here and on a real progressive stream written by the server
 * (tests/fuzz/seeds/fuzz_pmesh/tiny_predicted.lpm, 20 vertices, base 4,
 * batches of 3): whole packages, one message at a time, levels of detail,
 * arena sizing, message order, and bad messages that change nothing.
 */
#include "test_common.h"
#include <stdio.h>
#include <stdlib.h>
#include "lumo/session.h"
#include "test_pkg_build.h"

#define TINY_STREAM "tests/fuzz/seeds/fuzz_pmesh/tiny_predicted.lpm"

static lumo_session g_s;
static uint8_t g_mem[1u << 20];

static size_t read_tiny(uint8_t *buf, size_t cap)
{
    FILE *f = fopen(TINY_STREAM, "rb");
    size_t n;
    assert_non_null(f);
    n = fread(buf, 1, cap, f);
    fclose(f);
    assert_true(n > LUMO_PMESH_HEADER_SIZE && n < cap);
    return n;
}

/* INFO + MESH + IVGD, or INFO + PMSH (the tiny stream) when pm is set. */
static void build(bytes *pkg, int pm)
{
    static chunk c[3];
    info_chunk(&c[0]);
    if (pm) {
        c[1].type = LUMO_PKG_PMSH;
        c[1].data.n = read_tiny(c[1].data.b, sizeof c[1].data.b);
        assemble(pkg, c, 2);
        return;
    }
    mesh_chunk(&c[1], 1);
    ivgd_chunk(&c[2]);
    assemble(pkg, c, 3);
}

static lumo_status open_session(const bytes *b, lumo_package *pkg, lumo_arena *a, size_t bytes,
                                const lumo_session_config *cfg)
{
    assert_int_equal(lumo_package_open(pkg, b->b, b->n), LUMO_OK);
    lumo_arena_init(a, g_mem, bytes);
    assert_int_equal(lumo_session_init(&g_s, cfg, a), LUMO_OK);
    return lumo_session_feed_package(&g_s, pkg, NULL);
}

/* A raw package: the view is exactly what the package reader gives, the
 * lights and the grid arrive, and the arena holds exactly the need. */
static void test_raw_package(void **state)
{
    static bytes b;
    lumo_package pkg;
    lumo_arena a;
    lumo_pmesh_view v;
    lumo_q16_16 pos[9];
    lumo_q1_14 nrm[9], alb[9];
    uint32_t tris[3], nl;
    size_t need;
    (void)state;
    build(&b, 0);
    assert_int_equal(lumo_package_open(&pkg, b.b, b.n), LUMO_OK);
    assert_int_equal(lumo_session_package_need(&pkg, &need), LUMO_OK);
    assert_int_equal(open_session(&b, &pkg, &a, need, NULL), LUMO_OK);
    assert_int_equal(a.used + LUMO_ARENA_SLACK, need);   /* the need is exact */
    assert_int_equal(lumo_session_mesh(&g_s, 0, &v), LUMO_OK);
    assert_int_equal(lumo_package_mesh_read(&pkg, 0, pos, nrm, alb, tris), LUMO_OK);
    assert_int_equal(v.vertex_count, 3);
    assert_int_equal(v.face_count, 1);
    assert_memory_equal(v.positions, pos, sizeof pos);
    assert_memory_equal(v.normals, nrm, sizeof nrm);
    assert_memory_equal(v.albedo, alb, sizeof alb);
    assert_memory_equal(v.triangles, tris, sizeof tris);
    assert_non_null(lumo_session_lights(&g_s, &nl));
    assert_int_equal(nl, 1);
    assert_int_equal(lumo_session_lights(&g_s, &nl)[0].kind, LUMO_LIGHT_SPOT);
    assert_non_null(lumo_session_ivg(&g_s));
    assert_int_equal(lumo_session_update(&g_s), 0);   /* no bundle: nothing to fill */
    assert_int_equal(lumo_session_mesh(&g_s, 1, &v), LUMO_ERR_RANGE);
}

/* An arena one allocation short fails with NOMEM, never a crash. */
static void test_arena_too_small(void **state)
{
    static bytes b;
    lumo_package pkg;
    lumo_arena a;
    size_t need;
    (void)state;
    build(&b, 0);
    assert_int_equal(lumo_package_open(&pkg, b.b, b.n), LUMO_OK);
    assert_int_equal(lumo_session_package_need(&pkg, &need), LUMO_OK);
    assert_int_equal(open_session(&b, &pkg, &a, need - LUMO_ARENA_SLACK - 8, NULL), LUMO_ERR_NOMEM);
}

/* Messages out of order or malformed change nothing. */
static void test_message_order(void **state)
{
    static bytes b;
    static chunk c[3];
    lumo_arena a;
    lumo_pmesh_view v;
    size_t used;
    (void)state;
    info_chunk(&c[0]);
    mesh_chunk(&c[1], 1);
    ivgd_chunk(&c[2]);
    lumo_arena_init(&a, g_mem, sizeof g_mem);
    assert_int_equal(lumo_session_init(&g_s, NULL, &a), LUMO_OK);
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_MESH, 0, c[1].data.b, c[1].data.n), LUMO_ERR_STATE);
    assert_null(lumo_session_info(&g_s));
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_INFO, 0, c[0].data.b, c[0].data.n - 1),
                     LUMO_ERR_CORRUPT);
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_INFO, 0, c[0].data.b, c[0].data.n), LUMO_OK);
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_INFO, 0, c[0].data.b, c[0].data.n), LUMO_ERR_STATE);
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_MESH, 1, c[1].data.b, c[1].data.n), LUMO_ERR_RANGE);
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PMSB, 0, c[1].data.b, c[1].data.n), LUMO_ERR_STATE);
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_IVGQ, 0, c[1].data.b, c[1].data.n), LUMO_ERR_STATE);
    assert_int_equal(lumo_session_feed(&g_s, 0x21212121u, 0, c[1].data.b, c[1].data.n), LUMO_ERR_UNSUPPORTED);
    used = a.used;
    mesh_chunk(&c[1], 3);   /* a triangle index past the vertices */
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_MESH, 0, c[1].data.b, c[1].data.n), LUMO_ERR_RANGE);
    assert_int_equal(a.used, used);
    assert_int_equal(lumo_session_mesh(&g_s, 0, &v), LUMO_ERR_RANGE);
    mesh_chunk(&c[1], 1);
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_MESH, 0, c[1].data.b, c[1].data.n), LUMO_OK);
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_MESH, 0, c[1].data.b, c[1].data.n), LUMO_ERR_STATE);
    assert_int_equal(lumo_session_mesh(&g_s, 0, &v), LUMO_OK);
    assert_int_equal(v.vertex_count, 3);
    (void)b;
}

static uint32_t level_vertices(const lumo_session_config *cfg)
{
    static bytes b;
    lumo_package pkg;
    lumo_arena a;
    lumo_session_progress p;
    build(&b, 1);
    assert_int_equal(open_session(&b, &pkg, &a, sizeof g_mem, cfg), LUMO_OK);
    assert_int_equal(lumo_session_mesh_progress(&g_s, 0, &p), LUMO_OK);
    assert_int_equal(p.progressive, 1);
    assert_int_equal(p.full_vertices, 20);
    return p.vertices;
}

/* The level-of-detail cursor: a cap, a fraction of the streamed part
 * (rounded up), never below the base mesh (4 vertices), all by default. */
static void test_level_of_detail(void **state)
{
    lumo_session_config cfg = {{0, LUMO_SESSION_LOD_ALL}, LUMO_IVG_SMOOTH};
    (void)state;
    assert_int_equal(level_vertices(NULL), 20);
    cfg.lod.vertices = 10;
    assert_int_equal(level_vertices(&cfg), 10);   /* inside a batch: stepped back */
    cfg.lod.vertices = 2;
    assert_int_equal(level_vertices(&cfg), 4);
    cfg.lod.vertices = 0, cfg.lod.ppm = 500000;
    assert_int_equal(level_vertices(&cfg), 12);
    cfg.lod.ppm = 1;
    assert_int_equal(level_vertices(&cfg), 5);
    cfg.lod.ppm = 0;
    assert_int_equal(level_vertices(&cfg), 4);
    cfg.lod.ppm = LUMO_SESSION_LOD_ALL + 1;
    assert_int_equal(lumo_session_init(&g_s, &cfg, &(lumo_arena){0}), LUMO_ERR_ARG);
}

static uint32_t view_hash(void)
{
    lumo_pmesh_view v;
    uint32_t h = 2166136261u;
    assert_int_equal(lumo_session_mesh(&g_s, 0, &v), LUMO_OK);
    const uint8_t *p = (const uint8_t *)v.positions;
    for (size_t i = 0; i < 12u * v.vertex_count; i++)
        h = (h ^ p[i]) * 16777619u;
    p = (const uint8_t *)v.triangles;
    for (size_t i = 0; i < 12u * v.face_count; i++)
        h = (h ^ p[i]) * 16777619u;
    return h;
}

/* The stream as a network would carry it: the header, then one batch
 * record per message; a damaged record is refused, the level stays, and
 * the good record still applies after it. Same level as the package. */
static void test_one_record_at_a_time(void **state)
{
    static uint8_t s[4096], bad[4096];
    static chunk info;
    lumo_arena a;
    const uint8_t *rec;
    size_t n = read_tiny(s, sizeof s), at = LUMO_PMESH_HEADER_SIZE, rn;
    uint32_t whole, records = 0, before;
    (void)state;
    assert_int_equal(level_vertices(NULL), 20);
    whole = view_hash();
    info_chunk(&info);
    lumo_arena_init(&a, g_mem, sizeof g_mem);
    assert_int_equal(lumo_session_init(&g_s, NULL, &a), LUMO_OK);
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_INFO, 0, info.data.b, info.data.n), LUMO_OK);
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PMSH, 0, s, LUMO_PMESH_HEADER_SIZE), LUMO_OK);
    while (lumo_pmesh_next_record(s, n, &at, &rec, &rn) == LUMO_OK) {
        if (records++ == 2) {
            memcpy(bad, rec, rn);
            bad[rn - 1] ^= 0x40;
            before = view_hash();
            assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PMSB, 0, bad, rn), LUMO_ERR_CHECKSUM);
            assert_int_equal(view_hash(), before);
        }
        assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PMSB, 0, rec, rn), LUMO_OK);
    }
    assert_int_equal(at, n);
    assert_int_equal(records, 7);
    assert_int_equal(view_hash(), whole);
    /* Past the end of the stream a record is ignored, as past the target. */
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PMSB, 0, rec, rn), LUMO_OK);
    assert_int_equal(view_hash(), whole);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_raw_package),
        cmocka_unit_test(test_arena_too_small),
        cmocka_unit_test(test_message_order),
        cmocka_unit_test(test_level_of_detail),
        cmocka_unit_test(test_one_record_at_a_time),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
