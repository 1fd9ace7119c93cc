/*
 * test_prt_session.c — PRT carried by the client session (lumo/session.h
 * PRTV, PRTS, PRTL; docs/client-session.md "PRT") on a package baked by
 * lumo-bake --prt (tests/fuzz/seeds/fuzz_package/prt.lumo: 7 progressive
 * meshes, a PRTV each, a PRTL; tests/fuzz/package_seeds/make.sh):
 * the package need is exact; the whole package gives the chunks' own
 * views; a stream of spans split at random points (as DATA frames of the
 * PRT channel) relights, at the end, exactly as the package does (a hash
 * of the relit vertices) and at every step the vertices it holds; a cut
 * and resumed stream (spans lost, repeated, out of order) is refused
 * without change and ends right; hostile spans change nothing.
 */
#include "test_common.h"
#include <stdio.h>
#include <stdlib.h>
#include "lumo/session.h"

#define PRT_PKG "tests/fuzz/seeds/fuzz_package/prt.lumo"
#define SPHERE  6u    /* the mesh with 114 vertices and 6 clusters */

static lumo_session g_s;
static uint8_t g_mem[1u << 20];
static uint8_t g_file[1u << 16];
static size_t g_size;
static lumo_package g_pkg;

static void load(void)
{
    FILE *f = fopen(PRT_PKG, "rb");
    assert_non_null(f);
    g_size = fread(g_file, 1, sizeof g_file, f);
    fclose(f);
    assert_true(g_size > 0 && g_size < sizeof g_file);
    assert_int_equal(lumo_package_open(&g_pkg, g_file, g_size), LUMO_OK);
}

static const uint8_t *chunk(uint32_t type, uint32_t nth, uint32_t *len)
{
    const uint8_t *p;
    assert_int_equal(lumo_package_find(&g_pkg, type, nth, &p, len), LUMO_OK);
    return p;
}

/* FNV-1a of the relit vertices of view p under the package's PRTL. */
static uint64_t relight_hash(const lumo_prt *p, const lumo_prt_light *l)
{
    static lumo_q16_16 frame[3u * 64u * 37u];
    static lumo_uq16_16 lit[6u * 4096u];
    uint64_t h = 1469598103934665603ull;
    assert_true(lumo_prt_frame_entries(p) <= sizeof frame / sizeof frame[0] && p->vertices_held <= 4096u);
    assert_int_equal(lumo_prt_frame(p, l, frame), LUMO_OK);
    assert_int_equal(lumo_prt_shade(p, frame, NULL, 0, p->vertices_held, lit), LUMO_OK);
    for (size_t i = 0; i < 6u * p->vertices_held; i++)
        for (int b = 0; b < 4; b++)
            h = (h ^ ((lit[i] >> (8 * b)) & 0xFFu)) * 1099511628211ull;
    return h;
}

static void session_open(size_t bytes)
{
    static lumo_arena a;
    lumo_arena_init(&a, g_mem, bytes);
    assert_int_equal(lumo_session_init(&g_s, NULL, &a), LUMO_OK);
}

/* Everything but the PRT: INFO and the streams, as a session gets them. */
static void feed_scene(void)
{
    uint32_t len, m;
    const uint8_t *p = chunk(LUMO_PKG_INFO, 0, &len);
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_INFO, 0, p, len), LUMO_OK);
    for (m = 0; m < 7; m++) {
        p = chunk(LUMO_PKG_PMSH, m, &len);
        assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PMSH, m, p, len), LUMO_OK);
    }
}

/* PRTS message: u32 offset then bytes [off, off + n) of the chunk. */
static lumo_status span(uint32_t mesh, const uint8_t *c, uint32_t off, uint32_t n)
{
    static uint8_t msg[8192];
    assert_true(n + 4u <= sizeof msg);
    msg[0] = (uint8_t)off, msg[1] = (uint8_t)(off >> 8), msg[2] = (uint8_t)(off >> 16), msg[3] = (uint8_t)(off >> 24);
    memcpy(msg + 4, c + off, n);
    return lumo_session_feed(&g_s, LUMO_MSG_PRTS, mesh, msg, n + 4u);
}

/* Arena bytes message (type, nth chunk) states it needs; 0 when absent. */
static size_t chunk_need(uint32_t type, uint32_t nth)
{
    const uint8_t *p;
    uint32_t len;
    size_t b;
    if (lumo_package_find(&g_pkg, type, nth, &p, &len) != LUMO_OK)
        return 0;
    assert_int_equal(lumo_session_message_need(type, p, len, &b), LUMO_OK);
    return b;
}

/* The whole package: its need is its messages' (the PRT's included), it
 * fits an arena of exactly that, the PRT messages take exactly what they
 * state; each mesh's view is its chunk's, the lighting is the PRTL's. */
static void test_package(void **state)
{
    size_t need, sum = LUMO_ARENA_SLACK, prt_need = 0, before;
    lumo_arena a;
    lumo_prt got, want;
    lumo_prt_light lg, lw;
    uint32_t len, m, held, size;
    (void)state;
    load();
    assert_int_equal(lumo_session_package_need(&g_pkg, &need), LUMO_OK);
    sum += chunk_need(LUMO_PKG_IVGD, 0) + chunk_need(LUMO_PKG_IVGS, 0) + chunk_need(LUMO_PKG_ORDR, 0);
    for (m = 0; m < 7; m++) {
        sum += chunk_need(LUMO_PKG_PMSH, m);
        prt_need += chunk_need(LUMO_MSG_PRTV, m);
    }
    prt_need += chunk_need(LUMO_MSG_PRTL, 0);
    assert_true(prt_need > 0);
    assert_int_equal(need, sum + prt_need);
    lumo_arena_init(&a, g_mem, need);
    assert_int_equal(lumo_session_init(&g_s, NULL, &a), LUMO_OK);
    assert_int_equal(lumo_session_feed_package(&g_s, &g_pkg, NULL), LUMO_OK);
    /* the PRT again by hand in a fresh session: exactly its stated need */
    session_open(sizeof g_mem);
    feed_scene();
    before = g_s.arena->used;
    for (m = 0; m < 7; m++) {
        const uint8_t *c = chunk(LUMO_MSG_PRTV, m, &len);
        assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PRTV, m, c, len), LUMO_OK);
    }
    const uint8_t *l = chunk(LUMO_MSG_PRTL, 0, &len);
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PRTL, 0, l, len), LUMO_OK);
    assert_int_equal(g_s.arena->used - before, prt_need);
    for (m = 0; m < 7; m++) {
        const uint8_t *c = chunk(LUMO_MSG_PRTV, m, &len);
        assert_int_equal(lumo_prt_parse(&want, c, len), LUMO_OK);
        assert_int_equal(lumo_session_prt(&g_s, m, &got), LUMO_OK);
        assert_int_equal(got.vertices_held, want.vertices);
        assert_int_equal(got.clusters, want.clusters);
        assert_memory_equal(got.cluster_data, want.cluster_data, len - LUMO_PRT_HEADER_SIZE);
        lumo_session_prt_progress(&g_s, m, &held, &size);
        assert_int_equal(held, len);
        assert_int_equal(size, len);
    }
    assert_int_equal(lumo_session_prt(&g_s, 7, &got), LUMO_ERR_RANGE);
    l = chunk(LUMO_MSG_PRTL, 0, &len);
    assert_int_equal(lumo_prt_light_decode(l, len, &lw), LUMO_OK);
    assert_int_equal(lumo_session_prt_light(&g_s, &lg), LUMO_OK);
    assert_memory_equal(&lg, &lw, sizeof lg);
}

/* The sphere's chunk streamed: the header alone, then spans of 1..300
 * bytes split anywhere; after each, the view holds the whole vertex
 * records held (TRUNCATED before the clusters and passes are all there);
 * at the end the relit vertices hash as the package's. */
static void test_streamed_equals_package(void **state)
{
    uint32_t len, llen, off, held, size;
    size_t total, fixed, need;
    lumo_prt want, got;
    lumo_prt_light l;
    test_rng r = {0x9E3779B97F4A7C15ull};
    (void)state;
    load();
    const uint8_t *c = chunk(LUMO_MSG_PRTV, SPHERE, &len);
    assert_int_equal(lumo_prt_parse(&want, c, len), LUMO_OK);
    const uint8_t *pl = chunk(LUMO_MSG_PRTL, 0, &llen);
    assert_int_equal(lumo_prt_light_decode(pl, llen, &l), LUMO_OK);
    assert_int_equal(lumo_prt_chunk_size(c, len, &total, &fixed), LUMO_OK);
    assert_int_equal(total, len);
    assert_int_equal(lumo_session_message_need(LUMO_MSG_PRTV, c, LUMO_PRT_HEADER_SIZE, &need), LUMO_OK);
    assert_int_equal(need, lumo_arena_round(len));   /* the header tells the whole chunk's size */
    for (int trial = 0; trial < 20; trial++) {
        session_open(sizeof g_mem);
        feed_scene();
        assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PRTV, SPHERE, c, LUMO_PRT_HEADER_SIZE), LUMO_OK);
        for (off = LUMO_PRT_HEADER_SIZE; off < len;) {
            uint32_t n = 1u + (uint32_t)(test_rng_next(&r) % 300u);
            if (n > len - off)
                n = len - off;
            assert_int_equal(span(SPHERE, c, off, n), LUMO_OK);
            off += n;
            lumo_session_prt_progress(&g_s, SPHERE, &held, &size);
            assert_int_equal(held, off);
            assert_int_equal(size, len);
            if (off < fixed) {
                assert_int_equal(lumo_session_prt(&g_s, SPHERE, &got), LUMO_ERR_TRUNCATED);
                continue;
            }
            assert_int_equal(lumo_session_prt(&g_s, SPHERE, &got), LUMO_OK);
            assert_int_equal(got.vertices_held, (off - fixed) / lumo_prt_vertex_bytes(want.components));
        }
        assert_int_equal(lumo_session_prt(&g_s, SPHERE, &got), LUMO_OK);
        assert_int_equal(got.vertices_held, want.vertices);
        assert_true(relight_hash(&got, &l) == relight_hash(&want, &l));
    }
}

/* A cut stream: a span lost (the next one starts past what is held), one
 * repeated, one from before the header: STATE, nothing changes; the
 * client resumes from its cursor (the bytes held) and ends right. */
static void test_cut_and_resumed(void **state)
{
    uint32_t len, llen, held, size;
    lumo_prt want, got;
    lumo_prt_light l;
    (void)state;
    load();
    const uint8_t *c = chunk(LUMO_MSG_PRTV, SPHERE, &len);
    assert_int_equal(lumo_prt_parse(&want, c, len), LUMO_OK);
    const uint8_t *pl = chunk(LUMO_MSG_PRTL, 0, &llen);
    assert_int_equal(lumo_prt_light_decode(pl, llen, &l), LUMO_OK);
    session_open(sizeof g_mem);
    feed_scene();
    assert_int_equal(span(SPHERE, c, 0, 16), LUMO_ERR_STATE);     /* a span before its PRTV */
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PRTV, SPHERE, c, 500), LUMO_OK);
    assert_int_equal(span(SPHERE, c, 600, 100), LUMO_ERR_STATE);  /* 500..600 lost */
    assert_int_equal(span(SPHERE, c, 400, 200), LUMO_ERR_STATE);  /* repeated */
    lumo_session_prt_progress(&g_s, SPHERE, &held, &size);
    assert_int_equal(held, 500);
    assert_int_equal(span(SPHERE, c, held, 250), LUMO_OK);        /* resumed from the cursor */
    assert_int_equal(span(SPHERE, c, 750, len - 750), LUMO_OK);
    assert_int_equal(span(SPHERE, c, len, 0), LUMO_OK);           /* nothing more: harmless */
    assert_int_equal(span(SPHERE, c, len - 1, 1), LUMO_ERR_STATE);
    assert_int_equal(lumo_session_prt(&g_s, SPHERE, &got), LUMO_OK);
    assert_true(relight_hash(&got, &l) == relight_hash(&want, &l));
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PRTV, SPHERE, c, len), LUMO_ERR_STATE);   /* once */
}

/* Hostile messages change nothing and say why. */
static void test_hostile(void **state)
{
    static uint8_t bad[4096];
    uint32_t len, llen, held, size;
    lumo_prt got;
    lumo_prt_light l;
    (void)state;
    load();
    const uint8_t *c = chunk(LUMO_MSG_PRTV, SPHERE, &len), *pl = chunk(LUMO_MSG_PRTL, 0, &llen);
    size_t total, fixed;
    assert_int_equal(lumo_prt_chunk_size(c, len, &total, &fixed), LUMO_OK);
    session_open(sizeof g_mem);
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PRTV, SPHERE, c, len), LUMO_ERR_STATE);   /* before INFO */
    feed_scene();
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PRTV, 7, c, len), LUMO_ERR_RANGE);       /* no mesh 7 */
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PRTV, SPHERE, c, 11), LUMO_ERR_TRUNCATED);
    /* the PRTV of another mesh (4 vertices) for the sphere (114) */
    const uint8_t *other = chunk(LUMO_MSG_PRTV, 0, &llen);
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PRTV, SPHERE, other, llen), LUMO_ERR_CORRUPT);
    memcpy(bad, c, len);
    bad[0] = 2;
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PRTV, SPHERE, bad, len), LUMO_ERR_VERSION);
    memcpy(bad, c, len);
    bad[len] = 0;
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PRTV, SPHERE, bad, len + 1), LUMO_ERR_CORRUPT);
    /* a vertex record naming cluster 6 of 6, whole in the PRTV: refused, nothing held */
    memcpy(bad, c, len);
    bad[fixed + 3u * lumo_prt_vertex_bytes(3)] = 6;
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PRTV, SPHERE, bad, len), LUMO_ERR_RANGE);
    assert_int_equal(lumo_session_prt(&g_s, SPHERE, &got), LUMO_ERR_RANGE);
    /* the same record completed by a span: refused, held stays */
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PRTV, SPHERE, c, (uint32_t)fixed + 1), LUMO_OK);
    assert_int_equal(span(SPHERE, bad, (uint32_t)fixed + 1, 4u * 8u - 1u), LUMO_ERR_RANGE);   /* to record 3's end */
    lumo_session_prt_progress(&g_s, SPHERE, &held, &size);
    assert_int_equal(held, fixed + 1);
    /* a pass entry out of range */
    memcpy(bad, c, len);
    bad[fixed - 2] = 0xFF, bad[fixed - 1] = 0xFF;
    assert_int_equal(span(SPHERE, bad, (uint32_t)fixed + 1, 4), LUMO_OK);   /* past the passes: good */
    assert_int_equal(span(SPHERE, c, (uint32_t)fixed + 5, len - (uint32_t)fixed - 5 + 1), LUMO_ERR_CORRUPT);
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PRTS, SPHERE, c, 3), LUMO_ERR_TRUNCATED);
    /* PRTL: order 7, reserved bytes, length; then once */
    memcpy(bad, pl, llen = 112);
    bad[0] = 7;
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PRTL, 0, bad, llen), LUMO_ERR_RANGE);
    bad[0] = 3, bad[2] = 1;
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PRTL, 0, bad, llen), LUMO_ERR_CORRUPT);
    bad[2] = 0;
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PRTL, 0, bad, llen - 4), LUMO_ERR_CORRUPT);
    assert_int_equal(lumo_session_prt_light(&g_s, &l), LUMO_ERR_RANGE);
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PRTL, 0, pl, llen), LUMO_OK);
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PRTL, 0, pl, llen), LUMO_ERR_STATE);
    assert_int_equal(lumo_session_prt_light(&g_s, &l), LUMO_OK);
    /* the pass table checked on its own: a PRTV prefix ending inside it */
    session_open(sizeof g_mem);
    feed_scene();
    memcpy(bad, c, len);
    bad[fixed - 4] = 6;   /* the pass of cluster 4 */
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PRTV, SPHERE, bad, (uint32_t)fixed - 2), LUMO_ERR_RANGE);
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PRTV, SPHERE, bad, (uint32_t)fixed - 4), LUMO_OK);
    assert_int_equal(span(SPHERE, bad, (uint32_t)fixed - 4, 1), LUMO_OK);    /* half an entry: not checked yet */
    assert_int_equal(span(SPHERE, bad, (uint32_t)fixed - 3, 1), LUMO_ERR_RANGE);
    /* an arena one byte short of the chunk */
    session_open(sizeof g_mem);
    feed_scene();
    lumo_arena_mark m = lumo_arena_get_mark(g_s.arena);
    g_s.arena->size = g_s.arena->used + lumo_arena_round(len) - 1;
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_PRTV, SPHERE, c, len), LUMO_ERR_NOMEM);
    assert_int_equal(lumo_arena_get_mark(g_s.arena), m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_package),
        cmocka_unit_test(test_streamed_equals_package),
        cmocka_unit_test(test_cut_and_resumed),
        cmocka_unit_test(test_hostile),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
