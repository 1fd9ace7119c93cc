/* fuzz_package.c — hostile bytes into the .lumo reader: open, then every
 * getter (info, lights, meshes into fixed buffers, IVG descriptor and both
 * bundles into a grid; the IVG streaming order (IVGS), its rounds applied
 * one run of records at a time, and the interleaving (ORDR)), then the
 * whole package through the client session. Nothing may read or write out of bounds. The CRCs
 * would stop almost every mutation at open(), so each input is also tried
 * with its checksums recomputed: the content checks get fuzzed too. Seeds
 * in tests/fuzz/seeds/fuzz_package/ are real packages from lumo-bake. */
#include <stdint.h>
#include <stddef.h>
#include <string.h>
#include "lumo/package.h"
#include "lumo/session.h"
#include "lumo/wire.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define MAX_V 4096u
#define MAX_T 8192u
static lumo_q16_16 g_pos[3 * MAX_V];
static lumo_q1_14 g_nrm[3 * MAX_V], g_alb[3 * MAX_V];
static uint32_t g_tris[3 * MAX_T];
static uint8_t g_mem[1u << 22];

static void read_meshes(const lumo_package *pkg)
{
    lumo_pkg_mesh_info mi;
    uint32_t i;
    for (i = 0; i < 64 && lumo_package_mesh_info(pkg, i, &mi) == LUMO_OK; i++)
        if (mi.nverts <= MAX_V && mi.ntris <= MAX_T)
            lumo_package_mesh_read(pkg, i, g_pos, g_nrm, g_alb, g_tris);
}

/* IVGS: the decoder alone (no descriptor), then the checked order; each
 * round of each bundle as the server would stream it, through
 * lumo_ivg_apply_records. */
static void read_ivg_order(const lumo_package *pkg, lumo_ivg *g)
{
    static const uint32_t types[2] = {LUMO_PKG_IVGF, LUMO_PKG_IVGQ};
    lumo_ivg_order o;
    const uint8_t *p, *b;
    uint32_t len, blen, r;
    int f;
    if (lumo_package_find(pkg, LUMO_PKG_IVGS, 0, &p, &len) != LUMO_OK)
        return;
    lumo_ivg_order_decode(p, len, NULL, &o);
    if (lumo_package_ivg_order(pkg, &o) != LUMO_OK)
        return;
    for (f = 0; f < 2; f++) {
        if (lumo_package_find(pkg, types[f], 0, &b, &blen) != LUMO_OK)
            continue;
        for (r = 0; r < o.rounds; r++) {
            uint32_t from = lumo_ivg_order_offset(&o, (lumo_ivg_form)f, r);
            uint32_t to = lumo_ivg_order_offset(&o, (lumo_ivg_form)f, r + 1);
            if (from > to || to > blen)
                __builtin_trap();   /* a checked order must stay inside its bundle */
            lumo_ivg_apply_records(g, (lumo_ivg_form)f, lumo_ivg_order_first(&o, r + 1) - lumo_ivg_order_first(&o, r),
                                   b + from, to - from, NULL);
        }
    }
    (void)lumo_ivg_order_rounds_in(&o, o.records / 2);
}

static void read_order(const lumo_package *pkg)
{
    lumo_scene_order o;
    lumo_scene_step st;
    uint32_t i;
    if (lumo_package_order(pkg, &o) != LUMO_OK)
        return;
    for (i = 0; i < o.prefix + o.cycle && i < 4096; i++)
        if (lumo_scene_order_step(&o, i, &st) != LUMO_OK)
            __builtin_trap();
}

static void read_ivg(const lumo_package *pkg)
{
    lumo_ivg_desc d;
    lumo_arena arena;
    lumo_ivg *g;
    if (lumo_package_ivg_desc(pkg, &d) != LUMO_OK)
        return;
    lumo_arena_init(&arena, g_mem, sizeof g_mem);
    if (lumo_ivg_create(&g, &arena, &d) != LUMO_OK)
        return;
    lumo_package_load_ivg(pkg, g, LUMO_IVG_FORM_QUANTIZED, NULL);
    lumo_package_load_ivg(pkg, g, LUMO_IVG_FORM_FLOAT, NULL);
    read_ivg_order(pkg, g);
}

static uint8_t g_copy[1u << 20];

static void wr32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v, p[1] = (uint8_t)(v >> 8), p[2] = (uint8_t)(v >> 16), p[3] = (uint8_t)(v >> 24);
}
static uint32_t rd32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

/* Recompute every CRC field that lies inside the buffer. */
static void fix_crcs(uint8_t *d, size_t size)
{
    uint32_t n, i;
    if (size < LUMO_PKG_HEADER_SIZE)
        return;
    n = rd32(d + 8);
    if (n > LUMO_PKG_MAX_CHUNKS || LUMO_PKG_HEADER_SIZE + (size_t)n * LUMO_PKG_ENTRY_SIZE > size)
        n = 0;
    for (i = 0; i < n; i++) {
        uint8_t *e = d + LUMO_PKG_HEADER_SIZE + (size_t)i * LUMO_PKG_ENTRY_SIZE;
        uint32_t off = rd32(e + 4), len = rd32(e + 8);
        if (off <= size && len <= size - off)
            wr32(e + 12, lumo_wire_crc32(0, d + off, len));
    }
    wr32(d + 16, lumo_wire_crc32(0, d + LUMO_PKG_HEADER_SIZE, (size_t)n * LUMO_PKG_ENTRY_SIZE));
    wr32(d + 20, lumo_wire_crc32(0, d, 20));
}

/* The whole package through the client session, in an arena of exactly its
 * need when that fits (so a need that is too small shows as an ASan error
 * or NOMEM, never silently): every mesh view read back, push-pull run. */
static lumo_session g_session;

static void run_session(const lumo_package *pkg)
{
    lumo_pmesh_view v;
    lumo_arena arena;
    size_t need, i, k;
    volatile uint32_t sink = 0;
    if (lumo_session_package_need(pkg, &need) != LUMO_OK || need > sizeof g_mem)
        return;
    lumo_arena_init(&arena, g_mem, need);
    if (lumo_session_init(&g_session, NULL, &arena) != LUMO_OK)
        return;
    lumo_session_feed_package(&g_session, pkg, NULL);
    lumo_session_update(&g_session);
    for (i = 0; i < LUMO_MAX_MESHES; i++)
        if (lumo_session_mesh(&g_session, (uint32_t)i, &v) == LUMO_OK)
            for (k = 0; k < 3u * v.face_count; k++) {
                if (v.triangles[k] >= v.vertex_count)
                    __builtin_trap();   /* a view must never index past its vertices */
                sink += (uint32_t)v.positions[3 * (size_t)v.triangles[k]];
            }
    (void)sink;
}

static void exercise(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    exercise(data, size);
    if (size <= sizeof g_copy) {
        memcpy(g_copy, data, size);
        fix_crcs(g_copy, size);
        exercise(g_copy, size);
    }
    return 0;
}

static void exercise(const uint8_t *data, size_t size)
{
    lumo_package pkg;
    lumo_pkg_info in;
    lumo_pkg_light l;
    lumo_pkg_chunk c;
    uint32_t i;
    if (lumo_package_open(&pkg, data, size) != LUMO_OK)
        return;
    for (i = 0; i < pkg.chunk_count; i++)
        lumo_package_chunk(&pkg, i, &c);
    if (lumo_package_info(&pkg, &in) == LUMO_OK)
        for (i = 0; i < in.light_count && i < 80; i++)
            lumo_package_light(&pkg, i, &l);
    read_meshes(&pkg);
    read_ivg(&pkg);
    read_order(&pkg);
    run_session(&pkg);
}
