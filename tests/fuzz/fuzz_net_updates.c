/* fuzz_net_updates.c — hostile answers into the updates poller
 * (lumo/net_updates.h, docs/protocol.md §9) and through it into a client
 * session holding a 4 x 3 x 2 grid. The input is a run of frames, each
 * [type u8][length u16][payload], sealed here (header and CRC computed, so
 * mutations reach the payloads): DATA, END and POSES go to the poller, a
 * request is written before each frame when the poller wants one. Checks:
 * no crash or sanitizer report; an error is sticky (every later call
 * returns it); a refused frame changes nothing in the session (the arena
 * and the session struct compared byte for byte); the position held only
 * grows; received vertices never exceed the grid's. */
#include <stdint.h>
#include <stddef.h>
#include <string.h>
#include "lumo/net_updates.h"
#include "lumo/wire.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define CHECK(c) do { if (!(c)) __builtin_trap(); } while (0)
#define MAX_FRAME (1u << 16)

static uint8_t g_mem[1 << 16], g_before[1 << 16], g_frame[MAX_FRAME + 64];
static lumo_session g_s, g_s_before;
static lumo_arena g_a;

static void put32(uint8_t *p, uint32_t v) { lumo_wire_put_le32(p, v); }
static void putf(uint8_t *p, float f) { uint32_t u; memcpy(&u, &f, 4); put32(p, u); }

/* INFO: 1 mesh, 1 spot light; IVGD: 4 x 3 x 2 over the unit box. */
static int setup(void)
{
    static uint8_t info[160], ivgd[64];
    static const float box[6] = {-1, 0, -1, 1, 2, 1}, cam[10] = {0, 1, 3.5f, 0, 1, 0, 0, 1, 0, 40};
    static const float light[17] = {0, 1.95f, 0, 0, -1, 0, 0, 0, 0, 0, 0, 0, 60, 0.5f, 40, 20, 10};
    size_t n = 0, i;
    put32(info, 1), put32(info + 4, 1), put32(info + 8, 1), put32(info + 12, 0);
    for (n = 16, i = 0; i < 6; i++, n += 4)
        putf(info + n, box[i]);
    for (i = 0; i < 10; i++, n += 4)
        putf(info + n, cam[i]);
    put32(info + n, 1), n += 4;   /* LUMO_LIGHT_SPOT */
    for (i = 0; i < 17; i++, n += 4)
        putf(info + n, light[i]);
    ivgd[0] = 4, ivgd[1] = 0, ivgd[2] = 3, ivgd[3] = 0, ivgd[4] = 2, ivgd[5] = 0, ivgd[6] = ivgd[7] = 0;
    for (i = 0; i < 6; i++)
        putf(ivgd + 8 + 4 * i, box[i]);
    put32(ivgd + 32, 64), put32(ivgd + 36, 7), put32(ivgd + 40, 0), put32(ivgd + 44, 24);
    lumo_arena_init(&g_a, g_mem, sizeof g_mem);
    if (lumo_session_init(&g_s, NULL, &g_a) || lumo_session_feed(&g_s, LUMO_MSG_INFO, 0, info, n) ||
        lumo_session_feed(&g_s, LUMO_MSG_IVGD, 0, ivgd, 48))
        return -1;
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    lumo_net_updates u;
    size_t at = 1;
    uint32_t now = 0, last_cursor = 0;
    lumo_status failed = LUMO_OK;

    if (size < 1)
        return 0;
    CHECK(setup() == 0);
    CHECK(lumo_net_updates_init(&u, &g_s, data[0] & 1u, 1u + (data[0] >> 1), 100) == LUMO_OK);
    while (size - at >= 3) {
        uint8_t type = data[at], req[64];
        uint32_t len = (uint32_t)data[at + 1] | (uint32_t)data[at + 2] << 8;
        size_t n = 0, used = 0;
        lumo_net_frame f;
        lumo_status st;
        at += 3;
        if (len > size - at)
            len = (uint32_t)(size - at);
        memcpy(g_frame + LUMO_NET_HEADER, data + at, len);
        at += len;
        lumo_net_frame_seal(g_frame, type, len);
        st = lumo_net_updates_next(&u, now += 60, req, sizeof req, &n);
        CHECK(st == failed);
        if (lumo_net_frame_decode(g_frame, len + LUMO_NET_OVERHEAD, MAX_FRAME, &f, &used) != LUMO_OK ||
            !lumo_net_updates_takes(&f))
            continue;
        memcpy(g_before, g_mem, sizeof g_mem);
        g_s_before = g_s;
        st = lumo_net_updates_on_frame(&u, &f, now);
        if (failed) {
            CHECK(st == failed);
            continue;
        }
        if (st) {
            failed = st;
            CHECK(memcmp(g_before, g_mem, sizeof g_mem) == 0);
            CHECK(memcmp(&g_s_before, &g_s, sizeof g_s) == 0);
            continue;
        }
        CHECK(u.cursor >= last_cursor);
        last_cursor = u.cursor;
        CHECK(lumo_ivg_received_count(lumo_session_ivg(&g_s)) <= 24);
    }
    return 0;
}
