/*
 * test_session.c — the client session (lumo/session.h) on packages built
 * here and on a real progressive stream written by the server
 * (tests/fuzz/seeds/fuzz_pmesh/tiny_predicted.lpm, 20 vertices, base 4,
 * batches of 3): whole packages, one message at a time, levels of detail,
 * arena sizing, message order, and bad messages that change nothing. The
 * lighting channel on a package baked by lumo-bake
 * (tests/fuzz/seeds/fuzz_package/stream.lumo: PMSH streams, a 4x3x4 IVG,
 * IVGS, ORDR): IVGS and ORDR stored, the IVG streamed round by round as
 * IVGR messages (also wrapped in place in a protocol DATA payload), equal to
 * the whole bundle; version 1 refused.
 */
#include "test_common.h"
#include <stdio.h>
#include <stdlib.h>
#include "lumo/session.h"
#include "test_pkg_build.h"
#include "test_ivg_entry.h"

#define TINY_STREAM "tests/fuzz/seeds/fuzz_pmesh/tiny_predicted.lpm"
#define STREAM_PKG  "tests/fuzz/seeds/fuzz_package/stream.lumo"
#define V1_PKG      "tests/server/data/v1_tiny.lumo"

static lumo_session g_s;
static uint8_t g_mem[1u << 20];

static size_t read_tiny(uint8_t *buf, size_t cap)
{
    FILE *f = fopen(TINY_STREAM, "rb");
    size_t n;
    assert_non_null(f);
    n = fread(buf, 1, cap, f);
    fclose(f);
    assert_true(n > LUMO_PMESH_HEADER_MIN && n < cap);
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
    size_t n = read_tiny(s, sizeof s), at, rn;
    lumo_pmesh_header h;
    uint32_t whole, records = 0, before;
    (void)state;
    assert_int_equal(level_vertices(NULL), 20);
    whole = view_hash();
    info_chunk(&info);
    lumo_arena_init(&a, g_mem, sizeof g_mem);
    assert_int_equal(lumo_session_init(&g_s, NULL, &a), LUMO_OK);
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_INFO, 0, info.data.b, info.data.n), LUMO_OK);
    assert_int_equal(lumo_pmesh_read_header(s, n, &h), LUMO_OK);
    at = h.header_bytes;
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PMSH, 0, s, at), LUMO_OK);
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

/* ---- the lighting channel ------------------------------------------------- */

static lumo_session g_s2;
static uint8_t g_mem2[1u << 20];

static size_t read_file(const char *path, uint8_t *buf, size_t cap)
{
    FILE *f = fopen(path, "rb");
    size_t n;
    assert_non_null(f);
    n = fread(buf, 1, cap, f);
    fclose(f);
    assert_true(n > 0 && n < cap);
    return n;
}

static const uint8_t *find(const lumo_package *pkg, uint32_t type, uint32_t nth, uint32_t *len)
{
    const uint8_t *p;
    assert_int_equal(lumo_package_find(pkg, type, nth, &p, len), LUMO_OK);
    return p;
}

/* Same received/solid state and entries in both sessions' grids. */
static void assert_same_ivg(const lumo_session *a, const lumo_session *b)
{
    const lumo_ivg *ga = lumo_session_ivg(a), *gb = lumo_session_ivg(b);
    uint32_t v;
    assert_int_equal(lumo_ivg_received_count(ga), lumo_ivg_received_count(gb));
    assert_int_equal(lumo_ivg_solid_count(ga), lumo_ivg_solid_count(gb));
    for (v = 0; v < lumo_ivg_vertex_count(ga); v++) {
        assert_int_equal(lumo_ivg_is_received(ga, v), lumo_ivg_is_received(gb, v));
        assert_true(test_ivg_vertex_equal(ga, v, gb, v));
    }
}

/* The whole package: IVGS and ORDR stored in exactly the need, every round held. */
static void test_package_v2(void **state)
{
    static uint8_t file[1u << 16];
    size_t n = read_file(STREAM_PKG, file, sizeof file), need;
    lumo_package pkg;
    lumo_arena a;
    lumo_session_lighting l;
    lumo_ivg_order io;
    lumo_scene_order so;
    (void)state;
    assert_int_equal(lumo_package_open(&pkg, file, n), LUMO_OK);
    assert_int_equal(lumo_package_ivg_order(&pkg, &io), LUMO_OK);
    assert_int_equal(lumo_package_order(&pkg, &so), LUMO_OK);
    assert_int_equal(lumo_session_package_need(&pkg, &need), LUMO_OK);
    lumo_arena_init(&a, g_mem, need);
    assert_int_equal(lumo_session_init(&g_s, NULL, &a), LUMO_OK);
    assert_int_equal(lumo_session_feed_package(&g_s, &pkg, NULL), LUMO_OK);
    /* the need counts the IVGS and ORDR copies (the progressive decoders'
     * shares are upper bounds, so the whole need is not exact here) */
    const uint8_t *p;
    uint32_t len;
    size_t part;
    p = find(&pkg, LUMO_PKG_IVGS, 0, &len);
    assert_int_equal(lumo_session_message_need(LUMO_MSG_IVGS, p, len, &part), LUMO_OK);
    assert_int_equal(part, lumo_arena_round(len));
    p = find(&pkg, LUMO_PKG_ORDR, 0, &len);
    assert_int_equal(lumo_session_message_need(LUMO_MSG_ORDR, p, len, &part), LUMO_OK);
    assert_int_equal(part, lumo_arena_round(len));
    assert_true(a.used + LUMO_ARENA_SLACK <= need);
    assert_non_null(lumo_session_ivg_order(&g_s));
    assert_int_equal(lumo_session_ivg_order(&g_s)->rounds, io.rounds);
    assert_int_equal(lumo_ivg_order_offset(lumo_session_ivg_order(&g_s), LUMO_IVG_FORM_FLOAT, 3),
                     lumo_ivg_order_offset(&io, LUMO_IVG_FORM_FLOAT, 3));
    assert_true(lumo_ivg_order_first(lumo_session_ivg_order(&g_s), 1) == 8);
    assert_non_null(lumo_session_order(&g_s));
    assert_int_equal(lumo_session_order(&g_s)->prefix, so.prefix);
    assert_int_equal(lumo_session_order(&g_s)->cycle, so.cycle);
    assert_true(lumo_session_order(&g_s)->steps != so.steps);   /* a copy, not the caller's bytes */
    lumo_session_lighting_progress(&g_s, &l);
    assert_int_equal(l.records, io.records);
    assert_int_equal(l.rounds, io.rounds);
    assert_int_equal(l.rounds_held, io.rounds);
    assert_int_equal(lumo_session_update(&g_s), 1);
}

/* The IVG as a server streams it: descriptors (as in WELCOME), then each
 * round of the quantized bundle as one IVGR message; a damaged run is
 * refused and changes nothing, the good one applies after it. The end
 * state equals the whole package's. */
static void test_ivgr_round_by_round(void **state)
{
    static uint8_t file[1u << 16], msg[1u << 16];
    size_t n = read_file(STREAM_PKG, file, sizeof file);
    lumo_package pkg;
    lumo_arena a, a2;
    lumo_session_lighting l;
    const lumo_ivg_order *io;
    const uint8_t *p, *b;
    uint32_t len, blen, r, i;
    lumo_pkg_info info;
    (void)state;
    assert_int_equal(lumo_package_open(&pkg, file, n), LUMO_OK);
    lumo_arena_init(&a, g_mem, sizeof g_mem);
    assert_int_equal(lumo_session_init(&g_s, NULL, &a), LUMO_OK);
    assert_int_equal(lumo_session_feed_package(&g_s, &pkg, NULL), LUMO_OK);
    lumo_arena_init(&a2, g_mem2, sizeof g_mem2);
    assert_int_equal(lumo_session_init(&g_s2, NULL, &a2), LUMO_OK);
    assert_int_equal(lumo_package_info(&pkg, &info), LUMO_OK);
    p = find(&pkg, LUMO_PKG_INFO, 0, &len);
    assert_int_equal(lumo_session_feed(&g_s2, LUMO_MSG_INFO, 0, p, len), LUMO_OK);
    /* before IVGD: no grid for records or an order */
    msg[0] = LUMO_IVG_FORM_QUANTIZED;
    memset(msg + 1, 0, 7);
    assert_int_equal(lumo_session_feed(&g_s2, LUMO_MSG_IVGR, 0, msg, 8), LUMO_ERR_STATE);
    p = find(&pkg, LUMO_PKG_IVGS, 0, &len);
    assert_int_equal(lumo_session_feed(&g_s2, LUMO_MSG_IVGS, 0, p, len), LUMO_ERR_STATE);
    for (i = 0; i < info.mesh_count; i++) {
        p = find(&pkg, LUMO_PKG_PMSH, i, &len);
        lumo_pmesh_header h;
        assert_int_equal(lumo_pmesh_read_header(p, len, &h), LUMO_OK);
        assert_int_equal(lumo_session_feed(&g_s2, LUMO_MSG_PMSH, i, p, h.header_bytes), LUMO_OK);
    }
    p = find(&pkg, LUMO_PKG_IVGD, 0, &len);
    assert_int_equal(lumo_session_feed(&g_s2, LUMO_MSG_IVGD, 0, p, len), LUMO_OK);
    p = find(&pkg, LUMO_PKG_IVGS, 0, &len);
    memcpy(msg, p, len);
    msg[20 + 4]++;   /* round 0 of 9 records */
    assert_int_equal(lumo_session_feed(&g_s2, LUMO_MSG_IVGS, 0, msg, len), LUMO_ERR_CORRUPT);
    assert_null(lumo_session_ivg_order(&g_s2));
    memcpy(msg, p, len);
    assert_int_equal(lumo_session_feed(&g_s2, LUMO_MSG_IVGS, 0, msg, len), LUMO_OK);
    memset(msg, 0xEE, len);   /* the session kept its own copy */
    assert_int_equal(lumo_session_feed(&g_s2, LUMO_MSG_IVGS, 0, p, len), LUMO_ERR_STATE);
    io = lumo_session_ivg_order(&g_s2);
    assert_non_null(io);
    p = find(&pkg, LUMO_PKG_ORDR, 0, &len);
    assert_int_equal(lumo_session_feed(&g_s2, LUMO_MSG_ORDR, 0, p, len), LUMO_OK);
    assert_int_equal(lumo_session_feed(&g_s2, LUMO_MSG_ORDR, 0, p, len), LUMO_ERR_STATE);
    b = find(&pkg, LUMO_PKG_IVGQ, 0, &blen);
    for (r = 0; r < io->rounds; r++) {
        uint32_t from = lumo_ivg_order_offset(io, LUMO_IVG_FORM_QUANTIZED, r);
        uint32_t to = lumo_ivg_order_offset(io, LUMO_IVG_FORM_QUANTIZED, r + 1);
        uint32_t count = lumo_ivg_order_first(io, r + 1) - lumo_ivg_order_first(io, r);
        uint32_t received = lumo_ivg_received_count(lumo_session_ivg(&g_s2));
        msg[0] = LUMO_IVG_FORM_QUANTIZED, msg[1] = msg[2] = msg[3] = 0;
        wr32(msg + 4, count);
        memcpy(msg + 8, b + from, to - from);
        if (r == 2) {   /* damaged: one record too many announced, then a bad form */
            wr32(msg + 4, count + 1);
            assert_int_equal(lumo_session_feed(&g_s2, LUMO_MSG_IVGR, 0, msg, 8 + to - from), LUMO_ERR_TRUNCATED);
            wr32(msg + 4, count);
            msg[0] = 7;
            assert_int_equal(lumo_session_feed(&g_s2, LUMO_MSG_IVGR, 0, msg, 8 + to - from), LUMO_ERR_UNSUPPORTED);
            msg[0] = LUMO_IVG_FORM_QUANTIZED;
            assert_int_equal(lumo_session_feed(&g_s2, LUMO_MSG_IVGR, 0, msg, 7), LUMO_ERR_TRUNCATED);
            assert_int_equal(lumo_ivg_received_count(lumo_session_ivg(&g_s2)), received);
            lumo_session_lighting_progress(&g_s2, &l);
            assert_int_equal(l.rounds_held, 2);
        }
        assert_int_equal(lumo_session_feed(&g_s2, LUMO_MSG_IVGR, 0, msg, 8 + to - from), LUMO_OK);
        lumo_session_lighting_progress(&g_s2, &l);
        assert_int_equal(l.records, lumo_ivg_order_first(io, r + 1));
        assert_int_equal(l.rounds_held, r + 1);
        assert_int_equal(l.rounds, io->rounds);
        assert_int_equal(lumo_session_update(&g_s2), 1);   /* push-pull after every round */
    }
    assert_same_ivg(&g_s, &g_s2);
}

/* docs/protocol.md: a DATA payload of the lighting channel becomes an IVGR
 * message in place — form into byte 12, zeros into 13..15; bytes 16..19
 * already hold the record count. */
static void test_ivgr_from_data(void **state)
{
    static uint8_t file[1u << 16], data[1u << 16];
    size_t n = read_file(STREAM_PKG, file, sizeof file);
    lumo_package pkg;
    lumo_arena a;
    lumo_ivg_order io;
    const uint8_t *p, *b;
    uint32_t len, blen, k = 4, bytes, records;
    (void)state;
    assert_int_equal(lumo_package_open(&pkg, file, n), LUMO_OK);
    assert_int_equal(lumo_package_ivg_order(&pkg, &io), LUMO_OK);
    lumo_arena_init(&a, g_mem2, sizeof g_mem2);
    assert_int_equal(lumo_session_init(&g_s2, NULL, &a), LUMO_OK);
    p = find(&pkg, LUMO_PKG_INFO, 0, &len);
    assert_int_equal(lumo_session_feed(&g_s2, LUMO_MSG_INFO, 0, p, len), LUMO_OK);
    p = find(&pkg, LUMO_PKG_IVGD, 0, &len);
    assert_int_equal(lumo_session_feed(&g_s2, LUMO_MSG_IVGD, 0, p, len), LUMO_OK);
    /* DATA: channel 1, form 0 (binary32), mesh 0, first round 0, k rounds, the records */
    b = find(&pkg, LUMO_PKG_IVGF, 0, &blen);
    bytes = lumo_ivg_order_offset(&io, LUMO_IVG_FORM_FLOAT, k) - 16;
    records = lumo_ivg_order_first(&io, k);
    memset(data, 0, 20);
    data[0] = 1, data[1] = LUMO_IVG_FORM_FLOAT;
    wr32(data + 8, 0), wr32(data + 12, k), wr32(data + 16, records);
    memcpy(data + 20, b + 16, bytes);
    data[12] = data[1], data[13] = data[14] = data[15] = 0;   /* the wrap */
    assert_int_equal(lumo_session_feed(&g_s2, LUMO_MSG_IVGR, 0, data + 12, 8 + bytes), LUMO_OK);
    assert_int_equal(lumo_ivg_received_count(lumo_session_ivg(&g_s2)) + lumo_ivg_solid_count(lumo_session_ivg(&g_s2)),
                     records);
}

/* A version-1 package (IVG in index order, no IVGS) is refused as a whole. */
static void test_version_1_refused(void **state)
{
    static uint8_t file[1u << 16];
    size_t n = read_file(V1_PKG, file, sizeof file);
    lumo_package pkg;
    uint16_t major, minor;
    (void)state;
    assert_int_equal(lumo_package_open(&pkg, file, n), LUMO_ERR_VERSION);
    assert_int_equal(lumo_package_peek_version(file, n, &major, &minor), LUMO_OK);
    assert_int_equal(major, 1);
}

/* An INFO claiming 2^32 - 1 meshes: the need is refused at once (it used
 * to walk four billion chunk lookups; found by fuzz_package), and so is
 * the package. */
static void test_mesh_count_limit(void **state)
{
    static chunk c[2];
    static bytes pkgb;
    lumo_package pkg;
    lumo_arena a;
    size_t need;
    (void)state;
    info_chunk(&c[0]);
    c[0].data.b[0] = c[0].data.b[1] = c[0].data.b[2] = c[0].data.b[3] = 0xff;
    mesh_chunk(&c[1], 1);
    assemble(&pkgb, c, 2);
    assert_int_equal(lumo_package_open(&pkg, pkgb.b, pkgb.n), LUMO_OK);
    assert_int_equal(lumo_session_package_need(&pkg, &need), LUMO_ERR_LIMIT);
    assert_int_equal(open_session(&pkgb, &pkg, &a, sizeof g_mem, NULL), LUMO_ERR_LIMIT);
}

/* IVGS of another grid, ORDR naming a mesh the scene lacks: refused. */
static void test_order_messages_checked(void **state)
{
    static bytes b;
    static chunk c[3];
    static uint8_t file[1u << 16], msg[4096];
    size_t n = read_file(STREAM_PKG, file, sizeof file);
    lumo_package pkg;
    lumo_arena a;
    const uint8_t *p;
    uint32_t len;
    (void)state;
    assert_int_equal(lumo_package_open(&pkg, file, n), LUMO_OK);
    info_chunk(&c[0]);   /* 1 mesh, IVGD 4x3x2 */
    ivgd_chunk(&c[1]);
    assemble(&b, c, 2);
    lumo_arena_init(&a, g_mem2, sizeof g_mem2);
    assert_int_equal(lumo_session_init(&g_s2, NULL, &a), LUMO_OK);
    assert_int_equal(lumo_session_feed(&g_s2, LUMO_MSG_INFO, 0, c[0].data.b, c[0].data.n), LUMO_OK);
    assert_int_equal(lumo_session_feed(&g_s2, LUMO_MSG_IVGD, 0, c[1].data.b, c[1].data.n), LUMO_OK);
    p = find(&pkg, LUMO_PKG_IVGS, 0, &len);   /* 4x3x4: slices along x as here, but 13 rounds */
    assert_int_equal(lumo_session_feed(&g_s2, LUMO_MSG_IVGS, 0, p, len), LUMO_ERR_RANGE);
    p = find(&pkg, LUMO_PKG_ORDR, 0, &len);   /* names meshes 0..6 of a 1-mesh scene */
    assert_int_equal(lumo_session_feed(&g_s2, LUMO_MSG_ORDR, 0, p, len), LUMO_ERR_RANGE);
    assert_null(lumo_session_order(&g_s2));
    memcpy(msg, p, len);
    msg[8] = 2;   /* channel 2 */
    assert_int_equal(lumo_session_feed(&g_s2, LUMO_MSG_ORDR, 0, msg, len), LUMO_ERR_UNSUPPORTED);
    size_t need = 1;
    assert_int_equal(lumo_session_message_need(LUMO_MSG_ORDR, p, len, &need), LUMO_OK);
    assert_int_equal(need, lumo_arena_round(len));
    assert_int_equal(lumo_session_message_need(LUMO_MSG_ORDR, msg, len, &need), LUMO_ERR_UNSUPPORTED);
    (void)b;
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_raw_package),
        cmocka_unit_test(test_arena_too_small),
        cmocka_unit_test(test_message_order),
        cmocka_unit_test(test_level_of_detail),
        cmocka_unit_test(test_one_record_at_a_time),
        cmocka_unit_test(test_package_v2),
        cmocka_unit_test(test_ivgr_round_by_round),
        cmocka_unit_test(test_ivgr_from_data),
        cmocka_unit_test(test_version_1_refused),
        cmocka_unit_test(test_mesh_count_limit),
        cmocka_unit_test(test_order_messages_checked),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
