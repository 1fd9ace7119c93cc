/*
 * test_net_updates.c — the updates channel (docs/protocol.md §9,
 * lumo/net_updates.h): the codec's checks for channel 2, and the poller
 * against hand-made answers: requests at the position held, records
 * applied as IVGU (not counted as streamed lighting), the position
 * advancing, END ending an answer and push-pull, polling after an empty
 * answer; hostile answers refused with the session unchanged.
 */
#include "test_common.h"
#include "test_pkg_build.h"
#include "lumo/net_updates.h"

static uint8_t g_mem[1 << 16], g_frame[4096];
static lumo_session g_s;
static lumo_arena g_a;

static void session_with_grid(void)
{
    chunk c[2];
    info_chunk(&c[0]);
    ivgd_chunk(&c[1]);   /* 4 x 3 x 2 = 24 vertices */
    lumo_arena_init(&g_a, g_mem, sizeof g_mem);
    assert_int_equal(lumo_session_init(&g_s, NULL, &g_a), LUMO_OK);
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_INFO, 0, c[0].data.b, c[0].data.n), LUMO_OK);
    assert_int_equal(lumo_session_feed(&g_s, LUMO_MSG_IVGD, 0, c[1].data.b, c[1].data.n), LUMO_OK);
}

/* A quantized record of vertex v: zero d, colour word w in every entry. */
static size_t put_record(uint8_t *p, uint32_t v, uint32_t w)
{
    wr32(p, v);
    for (int h = 0; h < 6; h++) {
        p[4 + 7 * h] = p[5 + 7 * h] = p[6 + 7 * h] = 0;
        wr32(p + 7 + 7 * h, w);
    }
    return 46;
}

/* A DATA of channel 2 carrying vertices vs[0..n) into g_frame. */
static lumo_net_frame data_frame(uint32_t first, uint32_t count, uint8_t form, const uint32_t *vs, uint32_t n,
                                 uint32_t w)
{
    static uint8_t recs[2048];
    size_t len = 0, written = 0, used = 0;
    for (uint32_t i = 0; i < n; i++)
        len += put_record(recs + len, vs[i], w);
    lumo_net_data d = {LUMO_NET_UPDATES, form, 0, first, count, n, recs, (uint32_t)len};
    assert_int_equal(lumo_net_data_encode(&d, g_frame, sizeof g_frame, &written), LUMO_OK);
    lumo_net_frame f;
    assert_int_equal(lumo_net_frame_decode(g_frame, written, LUMO_NET_MAX_PAYLOAD, &f, &used), LUMO_OK);
    return f;
}

static lumo_net_frame end_frame(uint8_t channel)
{
    size_t written = 0, used = 0;
    lumo_net_end e = {channel, 0};
    lumo_net_frame f;
    assert_int_equal(lumo_net_end_encode(&e, g_frame, sizeof g_frame, &written), LUMO_OK);
    assert_int_equal(lumo_net_frame_decode(g_frame, written, LUMO_NET_MAX_PAYLOAD, &f, &used), LUMO_OK);
    return f;
}

static lumo_net_request sent_request(lumo_net_updates *u, uint32_t now)
{
    uint8_t out[64];
    size_t n = 0, used = 0;
    lumo_net_frame f;
    lumo_net_request r;
    assert_int_equal(lumo_net_updates_next(u, now, out, sizeof out, &n), LUMO_OK);
    assert_true(n > 0);
    assert_int_equal(lumo_net_frame_decode(out, n, LUMO_NET_MAX_PAYLOAD, &f, &used), LUMO_OK);
    assert_int_equal(lumo_net_request_decode(&f, &r), LUMO_OK);
    return r;
}

static void nothing_to_send(lumo_net_updates *u, uint32_t now)
{
    uint8_t out[64];
    size_t n = 99;
    assert_int_equal(lumo_net_updates_next(u, now, out, sizeof out, &n), LUMO_OK);
    assert_int_equal(n, 0);
}

static void test_codec_channel_2(void **state)
{
    (void)state;
    uint8_t out[128];
    size_t n;
    lumo_net_request r = {LUMO_NET_UPDATES, 0, 7, 100};
    assert_int_equal(lumo_net_request_encode(&r, out, sizeof out, &n), LUMO_OK);
    r.mesh = 1;
    assert_int_equal(lumo_net_request_encode(&r, out, sizeof out, &n), LUMO_ERR_ARG);
    r.mesh = 0, r.channel = 4;   /* past the PRT channel (§10) */
    assert_int_equal(lumo_net_request_encode(&r, out, sizeof out, &n), LUMO_ERR_ARG);
    uint8_t rec[46];
    put_record(rec, 0, 1);
    lumo_net_data d = {LUMO_NET_UPDATES, LUMO_IVG_FORM_QUANTIZED, 0, 5, 5, 1, rec, 46};
    assert_int_equal(lumo_net_data_encode(&d, g_frame, sizeof g_frame, &n), LUMO_ERR_ARG);   /* count <= first */
    d.count = 6, d.records = 0;
    assert_int_equal(lumo_net_data_encode(&d, g_frame, sizeof g_frame, &n), LUMO_ERR_ARG);   /* no record */
    d.records = 1, d.form = 2;
    assert_int_equal(lumo_net_data_encode(&d, g_frame, sizeof g_frame, &n), LUMO_ERR_ARG);
    /* count <= first on the wire: CORRUPT from the decoder */
    uint32_t v = 1;
    lumo_net_frame f = data_frame(5, 6, LUMO_IVG_FORM_QUANTIZED, &v, 1, 1);
    lumo_net_data back;
    assert_int_equal(lumo_net_data_decode(&f, &back), LUMO_OK);
    wr32(g_frame + LUMO_NET_HEADER + 12, 5);
    assert_int_equal(lumo_net_data_decode(&f, &back), LUMO_ERR_CORRUPT);
    f = end_frame(LUMO_NET_UPDATES);
    lumo_net_end e;
    assert_int_equal(lumo_net_end_decode(&f, &e), LUMO_OK);
    assert_int_equal(e.channel, LUMO_NET_UPDATES);
}

static void test_poll_and_apply(void **state)
{
    (void)state;
    lumo_net_updates u;
    lumo_session_lighting lp;
    session_with_grid();
    assert_int_equal(lumo_net_updates_init(&u, &g_s, LUMO_IVG_FORM_QUANTIZED, 4, 100), LUMO_OK);
    lumo_net_request r = sent_request(&u, 1000);
    assert_int_equal(r.channel, LUMO_NET_UPDATES);
    assert_int_equal(r.cursor, 0);
    assert_int_equal(r.amount, 4);
    nothing_to_send(&u, 1000);   /* one in flight */
    uint32_t a[] = {3, 17}, b[] = {5, 3};
    lumo_net_frame f = data_frame(0, 9, LUMO_IVG_FORM_QUANTIZED, a, 2, (20u << 27) | 100u);
    assert_int_equal(lumo_net_updates_on_frame(&u, &f, 1001), LUMO_OK);
    f = data_frame(9, 12, LUMO_IVG_FORM_QUANTIZED, b, 2, (20u << 27) | 200u);
    assert_int_equal(lumo_net_updates_on_frame(&u, &f, 1002), LUMO_OK);
    f = end_frame(LUMO_NET_UPDATES);
    assert_int_equal(lumo_net_updates_on_frame(&u, &f, 1003), LUMO_OK);
    assert_int_equal(u.cursor, 12);
    assert_int_equal(u.records, 4);
    assert_int_equal(lumo_ivg_received_count(lumo_session_ivg(&g_s)), 3);
    lumo_ivg_entry e3;
    assert_int_equal(lumo_ivg_entry_get(lumo_session_ivg(&g_s), 3, LUMO_IVG_PX, &e3), LUMO_OK);
    assert_int_equal(e3.c[0], 819200);   /* the later record: 200 * 2^(20 - 24) = 12.5 W/m^2 */
    lumo_session_lighting_progress(&g_s, &lp);
    assert_int_equal(lp.records, 0);   /* updates are not the package's rounds */
    /* a full answer: ask again at once, from the new position */
    r = sent_request(&u, 1003);
    assert_int_equal(r.cursor, 12);
    f = end_frame(LUMO_NET_UPDATES);   /* nothing new */
    assert_int_equal(lumo_net_updates_on_frame(&u, &f, 2000), LUMO_OK);
    nothing_to_send(&u, 2099);
    r = sent_request(&u, 2100);
    assert_int_equal(r.cursor, 12);
    assert_int_equal(u.answers, 2);
}

/* Every hostile answer fails the poller and leaves the grid as it was. */
static void hostile(uint32_t first, uint8_t form, uint32_t nrec, uint32_t vertex, int send_request,
                    lumo_status want)
{
    lumo_net_updates u;
    static uint8_t before[sizeof g_mem];
    uint32_t vs[5] = {vertex, 1, 2, 4, 6};
    session_with_grid();
    assert_int_equal(lumo_net_updates_init(&u, &g_s, LUMO_IVG_FORM_QUANTIZED, 4, 100), LUMO_OK);
    if (send_request)
        sent_request(&u, 0);
    memcpy(before, g_mem, sizeof g_mem);
    lumo_net_frame f = data_frame(first, first + 10, form, vs, nrec, 0x08000001u);
    assert_int_equal(lumo_net_updates_on_frame(&u, &f, 1), want);
    assert_memory_equal(before, g_mem, sizeof g_mem);
    uint8_t out[64];
    size_t n;
    assert_int_equal(lumo_net_updates_next(&u, 5000, out, sizeof out, &n), want);   /* sticky */
}

static void test_hostile_answers(void **state)
{
    (void)state;
    hostile(0, LUMO_IVG_FORM_QUANTIZED, 1, 0, 0, LUMO_ERR_STATE);      /* nothing asked */
    hostile(3, LUMO_IVG_FORM_QUANTIZED, 1, 0, 1, LUMO_ERR_STATE);      /* not at the position held */
    hostile(0, LUMO_IVG_FORM_FLOAT, 1, 0, 1, LUMO_ERR_RANGE);          /* another form */
    hostile(0, LUMO_IVG_FORM_QUANTIZED, 5, 0, 1, LUMO_ERR_CORRUPT);    /* more than asked */
    hostile(0, LUMO_IVG_FORM_QUANTIZED, 1, 24, 1, LUMO_ERR_RANGE);     /* vertex past the grid */
    hostile(0, LUMO_IVG_FORM_QUANTIZED, 2, 1, 1, LUMO_ERR_CORRUPT);    /* the same vertex twice */
    /* ERROR from the server: its status */
    lumo_net_updates u;
    size_t n, used;
    lumo_net_frame f;
    session_with_grid();
    assert_int_equal(lumo_net_updates_init(&u, &g_s, LUMO_IVG_FORM_QUANTIZED, 4, 100), LUMO_OK);
    assert_int_equal(lumo_net_error_encode(LUMO_ERR_RANGE, "no", g_frame, sizeof g_frame, &n), LUMO_OK);
    assert_int_equal(lumo_net_frame_decode(g_frame, n, LUMO_NET_MAX_PAYLOAD, &f, &used), LUMO_OK);
    assert_int_equal(lumo_net_updates_on_frame(&u, &f, 0), LUMO_ERR_RANGE);
    /* the wrong channel's END, and init's checks */
    session_with_grid();
    assert_int_equal(lumo_net_updates_init(&u, &g_s, LUMO_IVG_FORM_QUANTIZED, 4, 100), LUMO_OK);
    sent_request(&u, 0);
    f = end_frame(LUMO_NET_LIGHTING);
    assert_false(lumo_net_updates_takes(&f));
    assert_int_equal(lumo_net_updates_on_frame(&u, &f, 0), LUMO_ERR_STATE);
    assert_int_equal(lumo_net_updates_init(&u, &g_s, 2, 4, 100), LUMO_ERR_ARG);
    assert_int_equal(lumo_net_updates_init(&u, &g_s, 1, 0, 100), LUMO_ERR_ARG);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_codec_channel_2),
        cmocka_unit_test(test_poll_and_apply),
        cmocka_unit_test(test_hostile_answers),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
