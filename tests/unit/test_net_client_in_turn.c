/* test_net_client_in_turn.c — the protocol driver's judgement of frames out of turn
 * (lumo_net_client_in_turn, lumo/net_client.h): on a serial line the client
 * asks again after a refused frame (docs/protocol.md §1) and drops the rest
 * of the earlier answers. The driver's state is set by hand here (its
 * fields are in the header); the whole conversation is exercised end to end
 * by tests/serve (lumo-client) and boards/client/client-test.sh (the board client). */
#include <string.h>
#include "test_common.h"
#include "lumo/net.h"
#include "lumo/net_client.h"

static uint8_t g_buf[8][256];
static int g_next;

/* A frame as the receiver decodes it from encoded bytes. */
static lumo_net_frame framed(const uint8_t *b, size_t n)
{
    lumo_net_frame f;
    size_t used;

    assert_int_equal(lumo_net_frame_decode(b, n, 1u << 16, &f, &used), LUMO_OK);
    assert_int_equal(used, n);
    return f;
}

static lumo_net_frame data(uint8_t channel, uint32_t mesh, uint32_t first)
{
    static const uint8_t bytes[4] = {1, 2, 3, 4};
    uint8_t *b = g_buf[g_next++ % 8];
    lumo_net_data d;
    size_t n;

    memset(&d, 0, sizeof d);
    d.channel = channel;
    d.mesh = mesh;
    d.first = first;
    d.count = d.records = 1;
    d.form = channel == LUMO_NET_LIGHTING ? 1 : 0;
    d.bytes = bytes;
    d.len = sizeof bytes;
    assert_int_equal(lumo_net_data_encode(&d, b, 256, &n), LUMO_OK);
    return framed(b, n);
}

static lumo_net_frame end(uint8_t channel, uint32_t mesh)
{
    uint8_t *b = g_buf[g_next++ % 8];
    lumo_net_end e = {channel, mesh};
    size_t n;

    assert_int_equal(lumo_net_end_encode(&e, b, 256, &n), LUMO_OK);
    return framed(b, n);
}

/* Two meshes (3 batches held of mesh 0, none of mesh 1), 5 rounds held;
 * the oldest request in flight is `channel` (mesh 0). */
static void ready(lumo_net_client *c, uint8_t channel)
{
    memset(c, 0, sizeof *c);
    c->state = LUMO_NET_READY;
    c->mesh_count = 2;
    c->held[0] = 3;
    c->rounds_held = 5;
    c->has_ivg = 1;
    c->npending = 2;
    c->pending[0].channel = channel;
    c->pending[0].cursor = channel == LUMO_NET_GEOMETRY ? 3 : 5;
    c->pending[1].channel = LUMO_NET_GEOMETRY;
    c->pending[1].mesh = 1;
}

static void test_data_at_the_cursor_of_the_oldest_request(void **state)
{
    lumo_net_client c;
    lumo_net_frame f;
    (void)state;

    ready(&c, LUMO_NET_GEOMETRY);
    f = data(LUMO_NET_GEOMETRY, 0, 3);
    assert_true(lumo_net_client_in_turn(&c, &f));
    f = data(LUMO_NET_GEOMETRY, 0, 2);   /* held already: an earlier answer */
    assert_false(lumo_net_client_in_turn(&c, &f));
    f = data(LUMO_NET_GEOMETRY, 0, 4);   /* past a lost frame */
    assert_false(lumo_net_client_in_turn(&c, &f));
    f = data(LUMO_NET_GEOMETRY, 1, 0);   /* the second request's answer, early */
    assert_false(lumo_net_client_in_turn(&c, &f));
    f = data(LUMO_NET_LIGHTING, 0, 5);
    assert_false(lumo_net_client_in_turn(&c, &f));
    ready(&c, LUMO_NET_LIGHTING);
    assert_true(lumo_net_client_in_turn(&c, &f));
    f = data(LUMO_NET_LIGHTING, 0, 4);
    assert_false(lumo_net_client_in_turn(&c, &f));
    c.npending = 0;                      /* nothing asked (after reset_link) */
    f = data(LUMO_NET_LIGHTING, 0, 5);
    assert_false(lumo_net_client_in_turn(&c, &f));
}

static void test_end_welcome_error(void **state)
{
    lumo_net_client c;
    lumo_net_frame f, w;
    uint8_t wb[64];
    size_t n;
    (void)state;

    ready(&c, LUMO_NET_GEOMETRY);
    f = end(LUMO_NET_GEOMETRY, 0);
    assert_true(lumo_net_client_in_turn(&c, &f));
    f = end(LUMO_NET_GEOMETRY, 1);
    assert_false(lumo_net_client_in_turn(&c, &f));
    f = end(LUMO_NET_LIGHTING, 0);
    assert_false(lumo_net_client_in_turn(&c, &f));
    assert_int_equal(lumo_net_welcome_encode(7, 100, NULL, 0, wb, sizeof wb, &n), LUMO_OK);
    w = framed(wb, n);
    assert_false(lumo_net_client_in_turn(&c, &w));   /* a WELCOME sent again */
    c.state = LUMO_NET_HELLO_SENT;
    assert_true(lumo_net_client_in_turn(&c, &w));
    f = data(LUMO_NET_GEOMETRY, 0, 3);
    assert_false(lumo_net_client_in_turn(&c, &f));   /* no DATA before WELCOME */
    assert_int_equal(lumo_net_error_encode(LUMO_ERR_RANGE, "no", wb, sizeof wb, &n), LUMO_OK);
    f = framed(wb, n);
    assert_true(lumo_net_client_in_turn(&c, &f));
    assert_false(lumo_net_client_in_turn(NULL, &f));
}

/* Replay: no requests are in flight; the cursors alone decide. A payload
 * that does not decode is left to on_frame, which says why. */
static void test_replay_and_malformed(void **state)
{
    lumo_net_client c;
    lumo_net_frame f;
    uint8_t b[64];
    (void)state;

    ready(&c, LUMO_NET_GEOMETRY);
    c.npending = 0;
    c.cfg.replay = 1;
    f = data(LUMO_NET_GEOMETRY, 1, 0);
    assert_true(lumo_net_client_in_turn(&c, &f));
    f = data(LUMO_NET_GEOMETRY, 2, 0);                /* no such mesh */
    assert_false(lumo_net_client_in_turn(&c, &f));
    f = data(LUMO_NET_LIGHTING, 0, 4);
    assert_false(lumo_net_client_in_turn(&c, &f));
    f = end(LUMO_NET_LIGHTING, 0);
    assert_true(lumo_net_client_in_turn(&c, &f));
    memset(b, 0, sizeof b);                           /* a DATA of 4 bytes */
    lumo_net_frame_seal(b, LUMO_NET_DATA, 4);
    f = framed(b, 4 + LUMO_NET_OVERHEAD);
    assert_true(lumo_net_client_in_turn(&c, &f));
    assert_int_equal(lumo_net_client_on_frame(&c, &f), LUMO_ERR_TRUNCATED);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_data_at_the_cursor_of_the_oldest_request),
        cmocka_unit_test(test_end_welcome_error),
        cmocka_unit_test(test_replay_and_malformed),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
