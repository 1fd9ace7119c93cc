/* fuzz_session_prt.c — hostile PRT messages into the client session
 * (lumo/session.h PRTV, PRTS, PRTL; docs/client-session.md "PRT") after a
 * real scene: INFO and the PMSH streams of
 * tests/fuzz/seeds/fuzz_package/prt.lumo, read at start-up (run from the
 * top of the tree, as `make fuzz-smoke` does).
 *
 * Input: byte 0 bit 0: first feed the real PRTV header of the sphere (mesh
 * 6: 114 vertices, 6 clusters), so that spans reach the unit checks; bit
 * 1: feed the real PRTL. Then messages: u8 kind (% 3: PRTV, PRTS, PRTL),
 * u8 mesh (% 8: one past the meshes), u16 length, the bytes (fewer at the
 * end of the input).
 *
 * Checked after every message: a refused one changed nothing (the bytes
 * held and the chunk sizes of every mesh, the arena's fill); held never
 * passes the chunk's size; every view the session hands out relights all
 * its held vertices in bounds; the lighting decodes. */
#include <stdint.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include "lumo/session.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define PRT_PKG "tests/fuzz/seeds/fuzz_package/prt.lumo"
#define MESHES 7u

static uint8_t g_file[1u << 16];
static size_t g_size;
static lumo_package g_pkg;
static uint8_t g_mem[1u << 20];
static lumo_session g_s;
static lumo_arena g_a;
static lumo_q16_16 g_frame[3u * LUMO_PRT_MAX_CLUSTERS * (LUMO_PRT_MAX_COMPONENTS + 1u)];
static lumo_uq16_16 g_lit[6u * 4096u];

static void load(void)
{
    FILE *f = fopen(PRT_PKG, "rb");
    if (!f)
        __builtin_trap();
    g_size = fread(g_file, 1, sizeof g_file, f);
    fclose(f);
    if (lumo_package_open(&g_pkg, g_file, g_size) != LUMO_OK)
        __builtin_trap();
}

static void feed_chunk(uint32_t type, uint32_t nth, uint32_t len_max)
{
    const uint8_t *p;
    uint32_t len;
    if (lumo_package_find(&g_pkg, type, nth, &p, &len) != LUMO_OK)
        __builtin_trap();
    if (lumo_session_feed(&g_s, type, nth, p, len < len_max ? len : len_max) != LUMO_OK)
        __builtin_trap();
}

static void invariants(void)
{
    lumo_prt_light l;
    for (uint32_t m = 0; m < MESHES + 1; m++) {
        lumo_prt v;
        uint32_t held, size;
        lumo_session_prt_progress(&g_s, m, &held, &size);
        if (held > size)
            __builtin_trap();
        if (lumo_session_prt(&g_s, m, &v) != LUMO_OK)
            continue;
        if (v.vertices_held > 4096u || lumo_prt_frame_entries(&v) > sizeof g_frame / sizeof g_frame[0])
            __builtin_trap();
        lumo_prt_light_clear(&l, v.order);
        l.c[0][0] = l.c[1][0] = l.c[2][0] = 1 << 16;
        if (lumo_prt_frame(&v, &l, g_frame) != LUMO_OK ||
            lumo_prt_shade(&v, g_frame, NULL, 0, v.vertices_held, g_lit) != LUMO_OK)
            __builtin_trap();
    }
    if (lumo_session_prt_light(&g_s, &l) == LUMO_OK && (l.order < 1 || l.order > LUMO_PRT_MAX_ORDER))
        __builtin_trap();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const uint32_t kinds[3] = {LUMO_MSG_PRTV, LUMO_MSG_PRTS, LUMO_MSG_PRTL};
    size_t at = 1;
    if (!g_size)
        load();
    lumo_arena_init(&g_a, g_mem, sizeof g_mem);
    if (lumo_session_init(&g_s, NULL, &g_a) != LUMO_OK)
        __builtin_trap();
    feed_chunk(LUMO_PKG_INFO, 0, UINT32_MAX);
    for (uint32_t m = 0; m < MESHES; m++)
        feed_chunk(LUMO_PKG_PMSH, m, UINT32_MAX);
    if (size && (data[0] & 1))
        feed_chunk(LUMO_MSG_PRTV, 6, LUMO_PRT_HEADER_SIZE);
    if (size && (data[0] & 2))
        feed_chunk(LUMO_MSG_PRTL, 0, UINT32_MAX);
    while (at + 4 <= size) {
        uint32_t kind = kinds[data[at] % 3], mesh = data[at + 1] % (MESHES + 1);
        size_t len = (size_t)(data[at + 2] | data[at + 3] << 8);
        uint32_t held[MESHES + 1], sizes[MESHES + 1];
        size_t used = g_a.used;
        at += 4;
        if (len > size - at)
            len = size - at;
        for (uint32_t m = 0; m < MESHES + 1; m++)
            lumo_session_prt_progress(&g_s, m, &held[m], &sizes[m]);
        lumo_status st = lumo_session_feed(&g_s, kind, mesh, data + at, len);
        at += len;
        for (uint32_t m = 0; st != LUMO_OK && m < MESHES + 1; m++) {
            uint32_t h, z;
            lumo_session_prt_progress(&g_s, m, &h, &z);
            if (h != held[m] || z != sizes[m] || g_a.used != used)
                __builtin_trap();   /* a refused message changed something */
        }
        invariants();
    }
    return 0;
}
