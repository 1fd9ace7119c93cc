/* fuzz_net_client.c — any byte stream as the server's frames into the
 * client's protocol driver (lumo/net_client.h) after a valid WELCOME: the
 * WELCOME of tests/fuzz/seeds/fuzz_package/stream.lumo, built at start-up
 * by tests/include/test_net_fake.h (run from the top of the tree, as
 * `make test` and `make fuzz` do).
 *
 * Input: three bytes of configuration, then the frames.
 *   byte 0  bits 0-1 order (3: interleaved), bits 2-4 pipeline - 1,
 *           bit 5 binary32 IVG (else quantized), bit 6 fixed request sizes
 *           (else adaptive on a fake clock), bit 7 recompute the CRC of
 *           every frame the headers chain to (so mutations reach the driver
 *           and the session instead of the CRC check)
 *   byte 1  fixed geometry size: {1, 7, 40, 250, 100000}[byte 1 % 5]
 *   byte 2  bits 0-6: fixed lighting size {1, 2, 5, 1000}[(byte 2 & 127) % 4];
 *           bit 7: a lossy line (lumo-client --serial): frames the driver
 *           does not expect are dropped (lumo_net_client_expects) and a
 *           refused frame is asked again (lumo_net_client_resync, once
 *           until a frame is taken)
 * The frames are decoded as a byte stream (a refused frame: resynchronise
 * on the next magic, docs/protocol.md §1) and each is given to the driver,
 * which is asked for its requests after every one. Seeds
 * (tests/fuzz/seeds/fuzz_net_client/) are whole conversations written by
 * tests/unit/test_net_client.c with LUMO_NET_CLIENT_SEEDS=DIR.
 *
 * Checked after every frame: an error fails the driver for good (the same
 * status again, nothing to send); the driver's cursors never pass the
 * streams' ends nor disagree with the session's; every mesh the session
 * holds still draws (triangle indices below the vertex count).
 */
#include <stdint.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include "lumo/net_client.h"
#include "test_net_fake.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define STREAM_PKG "tests/fuzz/seeds/fuzz_package/stream.lumo"
#define ARENA ((size_t)4 << 20)
#define CHECK(c) do { if (!(c)) __builtin_trap(); } while (0)

static fake_pkg g_k;
static int g_ready;
static uint8_t g_mem[ARENA];
static lumo_session g_s;
static lumo_net_client g_c;
static uint32_t g_now;

static uint32_t fake_clock(void *ctx)
{
    (void)ctx;
    return g_now += 3;
}

static void setup(void)
{
    if (g_ready)
        return;
    if (fake_pkg_load(&g_k, STREAM_PKG) != LUMO_OK) {
        fprintf(stderr, "fuzz_net_client: cannot load %s (run from the top of the tree)\n", STREAM_PKG);
        abort();
    }
    g_ready = 1;
}

/* The driver's requests until it has nothing to send. */
static void pump(void)
{
    uint8_t out[256];
    size_t n;
    int i;

    for (i = 0; i < 32; i++) {
        lumo_status st = lumo_net_client_next(&g_c, out, sizeof out, &n);
        if (g_c.state == LUMO_NET_FAILED) {
            CHECK(st == g_c.error && n == 0);
            return;
        }
        CHECK(st == LUMO_OK);
        if (n == 0)
            return;
        CHECK(g_c.npending <= 8);
    }
}

static void invariants(void)
{
    lumo_net_progress p;
    uint32_t m, i;

    CHECK(g_c.rounds_held <= g_c.rounds_total && g_c.rounds_asked <= g_c.rounds_total);
    for (m = 0; m < g_c.mesh_count; m++) {
        lumo_session_progress sp;
        lumo_pmesh_view v;
        CHECK(g_c.held[m] <= g_c.batches[m]);
        CHECK(lumo_session_mesh_progress(&g_s, m, &sp) == LUMO_OK && sp.batches == g_c.held[m]);
        CHECK(lumo_session_mesh(&g_s, m, &v) == LUMO_OK);
        for (i = 0; i < 3 * v.face_count; i++)
            CHECK(v.triangles[i] < v.vertex_count);
    }
    lumo_net_client_progress(&g_c, &p);
    CHECK(p.vertices <= p.full_vertices && p.rounds <= p.full_rounds);
}

/* Recompute the CRC of every frame whose header chains from the start. */
static void fix_crcs(uint8_t *b, size_t n)
{
    size_t at = 0;

    while (n - at >= LUMO_NET_OVERHEAD) {
        uint32_t len = lumo_wire_le32(b + at + 4);
        if (len > n - at - LUMO_NET_OVERHEAD)
            return;
        lumo_wire_put_le32(b + at + LUMO_NET_HEADER + len, lumo_wire_crc32(0, b + at, LUMO_NET_HEADER + len));
        at += LUMO_NET_OVERHEAD + len;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const uint32_t vertices[] = {1, 7, 40, 250, 100000};
    static const uint32_t rounds[] = {1, 2, 5, 1000};
    lumo_net_client_config cfg;
    lumo_arena a;
    lumo_net_frame f;
    uint8_t out[256], *buf;
    size_t n, at = 0, used;
    int lossy, resyncing = 0;

    setup();
    if (size < 3)
        return 0;
    lossy = data[2] >> 7;
    memset(&cfg, 0, sizeof cfg);
    cfg.arena_bytes = (uint32_t)ARENA;
    cfg.max_payload = LUMO_NET_MIN_PAYLOAD;
    cfg.width = 64, cfg.height = 48;
    cfg.ivg_form = data[0] & 0x20 ? LUMO_IVG_FORM_FLOAT : LUMO_IVG_FORM_QUANTIZED;
    cfg.smoothing = 1;
    cfg.policy.order = (lumo_net_order)((data[0] & 3) % 3);
    cfg.policy.pipeline = 1u + ((data[0] >> 2) & 7);
    if (data[0] & 0x40) {
        cfg.policy.vertices = vertices[data[1] % 5];
        cfg.policy.rounds = rounds[(data[2] & 127) % 4];
    } else {
        cfg.clock = fake_clock;
    }
    g_now = 0;
    lumo_arena_init(&a, g_mem, sizeof g_mem);
    CHECK(lumo_session_init(&g_s, NULL, &a) == LUMO_OK);
    CHECK(lumo_net_client_init(&g_c, &g_s, &cfg) == LUMO_OK);
    CHECK(lumo_net_client_hello(&g_c, out, sizeof out, &n) == LUMO_OK);
    CHECK(lumo_net_frame_decode(g_k.welcome, g_k.welcome_len, cfg.max_payload, &f, &used) == LUMO_OK);
    CHECK(lumo_net_client_on_frame(&g_c, &f) == LUMO_OK && g_c.state == LUMO_NET_READY);
    pump();

    size -= 3;
    if (!(buf = (uint8_t *)malloc(size ? size : 1)))
        return 0;
    memcpy(buf, data + 3, size);
    if (data[0] & 0x80)
        fix_crcs(buf, size);
    while (at < size) {
        lumo_status st = lumo_net_frame_decode(buf + at, size - at, cfg.max_payload, &f, &used);
        if (st == LUMO_ERR_TRUNCATED)
            break;
        if (st) {
            at = lumo_net_resync(buf, size, at + 1);
            if (lossy && !resyncing) {
                st = lumo_net_client_resync(&g_c, out, sizeof out, &n);
                CHECK(st == LUMO_OK || (g_c.state == LUMO_NET_FAILED && st == g_c.error));
                resyncing = 1;
                pump();
            }
            continue;
        }
        at += used;
        if (lossy && !lumo_net_client_expects(&g_c, &f))
            continue;
        st = lumo_net_client_on_frame(&g_c, &f);
        resyncing = 0;
        if (st) {
            CHECK(g_c.state == LUMO_NET_FAILED && g_c.error == st);
            CHECK(lumo_net_client_on_frame(&g_c, &f) == st);
        }
        pump();
        invariants();
    }
    invariants();
    if (lossy) {   /* silence at the end: asked again */
        lumo_status st = lumo_net_client_resync(&g_c, out, sizeof out, &n);
        CHECK(st == LUMO_OK || (g_c.state == LUMO_NET_FAILED && st == g_c.error));
        CHECK(g_c.state == LUMO_NET_FAILED || g_c.npending <= 1);
        pump();
        invariants();
    }
    free(buf);
    return 0;
}
