/*
 * test_vsl_updates.c — the updates channel end to end without sockets: the
 * server's compacted log (vsl_updates.h) answers the client's poller
 * (lumo/net_updates.h), whose records land in a real client session.
 *  - every published vertex arrives once, at its latest value, oldest
 *    change first; a vertex changed again is sent again, once;
 *  - answers split into frames under the client's max payload and cut at
 *    the amount asked; the poller catches up over several answers;
 *  - coarse-to-fine within one publication; LIMIT for a payload too small.
 */
#include "test_common.h"
#include <stdlib.h>
#include "test_pkg_build.h"
#include "lumo/net_updates.h"
#include "vsl/vsl_updates.h"

enum { NX = 4, NY = 3, NZ = 2, NV = NX * NY * NZ };
static uint8_t g_mem[1 << 16];
static lumo_session g_s;
static lumo_arena g_a;
static double g_I[NV * SRV_VSL_IVG_VALUES];

static void session_with_grid(void)
{
    chunk c[2];
    info_chunk(&c[0]);
    ivgd_chunk(&c[1]);   /* 4 x 3 x 2 */
    lumo_arena_init(&g_a, g_mem, sizeof g_mem);
    assert_int_equal(lumo_session_init(&g_s, NULL, &g_a), LUMO_OK);
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_INFO, 0, c[0].data.b, c[0].data.n), LUMO_OK);
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_IVGD, 0, c[1].data.b, c[1].data.n), LUMO_OK);
}

/* Vertex v lit from +x with value k (W/m^2) in every channel. */
static void set_value(uint32_t v, double k)
{
    for (int h = 0; h < 6; h++)
        for (int ch = 0; ch < 3; ch++)
            for (int c = 0; c < 3; c++)
                g_I[(size_t)v * SRV_VSL_IVG_VALUES + (size_t)((h * 3 + ch) * 3 + c)] = h == 0 && c == 0 ? k : 0.0;
}

/* One request / answer round: the poller's REQUEST decoded by the server
 * side, its answer's frames fed back. Returns the records that came. */
static uint32_t round_trip(srv_vsl_updates *u, lumo_net_updates *p, uint32_t max_payload, uint32_t *frames)
{
    uint8_t req[64], *buf = NULL;
    size_t n = 0, len = 0, at = 0, used;
    lumo_net_frame f;
    lumo_net_request r;
    uint32_t before = p->records;
    assert_int_equal(lumo_net_updates_next(p, 0, req, sizeof req, &n), LUMO_OK);
    assert_true(n > 0);
    assert_int_equal(lumo_net_frame_decode(req, n, LUMO_NET_MAX_PAYLOAD, &f, &used), LUMO_OK);
    assert_int_equal(lumo_net_request_decode(&f, &r), LUMO_OK);
    assert_int_equal(srv_vsl_updates_answer(u, r.cursor, r.amount, LUMO_IVG_FORM_QUANTIZED, max_payload, &buf, &len),
                     LUMO_OK);
    *frames = 0;
    while (at < len) {
        assert_int_equal(lumo_net_frame_decode(buf + at, len - at, max_payload, &f, &used), LUMO_OK);
        assert_true(lumo_net_updates_takes(&f));
        assert_int_equal(lumo_net_updates_on_frame(p, &f, 0), LUMO_OK);
        at += used;
        (*frames)++;
    }
    free(buf);
    assert_int_equal(p->in_flight, 0);   /* END came last */
    return p->records - before;
}

static uint32_t red_px(uint32_t v)
{
    lumo_ivg_entry e;
    assert_int_equal(lumo_ivg_entry_get(lumo_session_ivg(&g_s), v, LUMO_IVG_PX, &e), LUMO_OK);
    return e.c[0];
}

static void test_log_to_session(void **state)
{
    (void)state;
    srv_vsl_updates u;
    lumo_net_updates p;
    const int dims[3] = {NX, NY, NZ};
    uint32_t frames;
    session_with_grid();
    assert_int_equal(srv_vsl_updates_init(&u, dims), LUMO_OK);
    assert_int_equal(lumo_net_updates_init(&p, &g_s, LUMO_IVG_FORM_QUANTIZED, 1000, 0), LUMO_OK);
    assert_int_equal(round_trip(&u, &p, 4096, &frames), 0);   /* nothing yet: END alone */
    assert_int_equal(frames, 1);
    uint32_t all[NV];
    for (uint32_t v = 0; v < NV; v++)
        all[v] = v, set_value(v, 1.0 + v);
    srv_vsl_updates_publish(&u, g_I, all, NV);
    /* 5 records a frame: 24 records in 5 DATA frames, then END */
    assert_int_equal(round_trip(&u, &p, LUMO_NET_DATA_HEAD + 5 * 46, &frames), NV);
    assert_int_equal(frames, 6);
    assert_int_equal(lumo_ivg_received_count(lumo_session_ivg(&g_s)), NV);
    assert_int_equal(p.cursor, NV);
    assert_int_equal(red_px(7), 8 * 65536);
    /* vertices 7 and 2 change twice: sent once each, at the last value */
    uint32_t some[] = {7, 2};
    set_value(7, 100.0), set_value(2, 50.0);
    srv_vsl_updates_publish(&u, g_I, some, 2);
    set_value(7, 200.0);
    srv_vsl_updates_publish(&u, g_I, some, 1);
    assert_int_equal(round_trip(&u, &p, 4096, &frames), 2);
    assert_int_equal(red_px(7), 200 * 65536);
    assert_int_equal(red_px(2), 50 * 65536);
    assert_int_equal(p.cursor, NV + 3);
    assert_int_equal(srv_vsl_updates_position(&u), NV + 3);
    assert_int_equal(round_trip(&u, &p, 4096, &frames), 0);
    srv_vsl_updates_free(&u);
}

static void test_amount_and_catch_up(void **state)
{
    (void)state;
    srv_vsl_updates u;
    lumo_net_updates p;
    const int dims[3] = {NX, NY, NZ};
    uint32_t frames, all[NV];
    session_with_grid();
    assert_int_equal(srv_vsl_updates_init(&u, dims), LUMO_OK);
    assert_int_equal(lumo_net_updates_init(&p, &g_s, LUMO_IVG_FORM_QUANTIZED, 10, 0), LUMO_OK);
    for (uint32_t v = 0; v < NV; v++)
        all[v] = v, set_value(v, 3.0);
    srv_vsl_updates_publish(&u, g_I, all, NV);
    assert_int_equal(round_trip(&u, &p, 4096, &frames), 10);
    /* one publication goes coarse to fine: (0,0,0) on every lattice first,
     * the lattice levels never rising along the log */
    assert_int_equal(u.order[0], 0);
    for (uint32_t i = 1; i < NV; i++)
        assert_true(u.coarse[u.order[i]] <= u.coarse[u.order[i - 1]]);
    srv_vsl_updates_publish(&u, g_I, all + 20, 2);   /* 20, 21 change meanwhile */
    assert_int_equal(round_trip(&u, &p, 4096, &frames), 10);
    assert_int_equal(round_trip(&u, &p, 4096, &frames), 4);   /* 24 distinct vertices in all */
    assert_int_equal(lumo_ivg_received_count(lumo_session_ivg(&g_s)), NV);
    uint8_t *buf;
    size_t len;
    assert_int_equal(srv_vsl_updates_answer(&u, 0, 10, LUMO_IVG_FORM_FLOAT, LUMO_NET_DATA_HEAD + 100, &buf, &len),
                     LUMO_ERR_LIMIT);
    srv_vsl_updates_free(&u);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_log_to_session),
        cmocka_unit_test(test_amount_and_catch_up),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
