/*
 * bench_prt.c — Cortex-M3 instruction counts of the PRT client (lumo/prt.h,
 * docs/prt.md) under QEMU `-icount shift=0`: a PRTV chunk built here (order
 * 6 or 4, 64 clusters, 8 components, 2 000 vertices, random values of the
 * right shape), then the lighting vector from two lights, a rotation of it,
 * the per-cluster table (once per frame) and the per-vertex relight. Prints
 * markdown rows; `make bench-prt-board` wraps them for docs/benchmarks.md.
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include "lumo/prt.h"
#include "lumo/raster.h"
#include "lumo/wire.h"
#include "board.h"
#include "console.h"
#include "harness.h"

int main(void);

#define CLUSTERS 64u
#define COMPONENTS 8u
#define VERTICES 2000u

static uint8_t g_chunk[LUMO_PRT_HEADER_SIZE + CLUSTERS * (2u * 36u * (COMPONENTS + 1u) + 2u) +
                       VERTICES * (2u + 2u * COMPONENTS)];
static lumo_q16_16 g_frame[3u * CLUSTERS * (COMPONENTS + 1u)];
static lumo_uq16_16 g_lit[6u * VERTICES];
static lumo_q1_14 g_albedo[3u * VERTICES];

static uint32_t instructions_since(uint32_t t0);

static lumo_q16_16 g_pos[3u * VERTICES];
static lumo_q1_14 g_normal[3u * VERTICES];

/* Per-vertex Lambert with two directional lights, per vertex. */
static uint32_t lambert_cost(void)
{
    lumo_raster_light rl[2];
    lumo_raster_scene rs;
    lumo_raster_mesh m;
    bt_rng r = {0x1A3Bull};
    uint32_t v, t0;
    int k;
    for (v = 0; v < VERTICES; v++) {
        int32_t w[3];
        for (k = 0; k < 3; k++) {
            g_pos[3 * v + (uint32_t)k] = (lumo_q16_16)(bt_rng_next(&r) % 65536u);
            w[k] = (int32_t)(bt_rng_next(&r) % 2001u) - 1000;
        }
        lumo_normalize3_q14(w, &g_normal[3 * v]);
    }
    memset(rl, 0, sizeof rl);
    memset(&rs, 0, sizeof rs);
    memset(&m, 0, sizeof m);
    rl[0].kind = rl[1].kind = LUMO_LIGHT_DIRECTIONAL;
    rl[0].dir[1] = -16384, rl[1].dir[0] = -11585, rl[1].dir[2] = -11585;
    for (k = 0; k < 3; k++)
        rl[0].value[k] = rl[1].value[k] = 3u << 16;
    rs.lights = rl, rs.light_count = 2, rs.exposure = LUMO_Q16_ONE;
    m.pos = g_pos, m.normal = g_normal, m.albedo = g_albedo, m.vertex_count = VERTICES;
    t0 = board_ticks();
    if (lumo_raster_light_vertices(&rs, &m, g_lit) != LUMO_OK)
        return 0;
    return instructions_since(t0) / VERTICES;
}

static size_t build(unsigned order)
{
    bt_rng r = {0x9E7ull + order};
    unsigned nc = order * order, k, v, i;
    uint8_t *p = g_chunk + LUMO_PRT_HEADER_SIZE;
    memset(g_chunk, 0, LUMO_PRT_HEADER_SIZE);
    g_chunk[0] = LUMO_PRT_VERSION, g_chunk[1] = (uint8_t)order, g_chunk[2] = COMPONENTS;
    lumo_wire_put_le32(g_chunk + 4, CLUSTERS);
    lumo_wire_put_le32(g_chunk + 8, VERTICES);
    for (k = 0; k < CLUSTERS * nc * (COMPONENTS + 1u); k++, p += 2)
        lumo_wire_put_le16(p, (uint16_t)(bt_rng_next(&r) % 8192u));
    for (k = 0; k < CLUSTERS; k++, p += 2)
        lumo_wire_put_le16(p, (uint16_t)(k / 3u));
    for (v = 0; v < VERTICES; v++) {
        lumo_wire_put_le16(p, (uint16_t)(bt_rng_next(&r) % CLUSTERS));
        p += 2;
        for (i = 0; i < COMPONENTS; i++, p += 2)
            lumo_wire_put_le16(p, (uint16_t)(bt_rng_next(&r) % 4096u));
        for (i = 0; i < 3; i++)
            g_albedo[3 * v + i] = (lumo_q1_14)(8192 + i * 1000);
    }
    return (size_t)(p - g_chunk);
}

static uint32_t instructions_since(uint32_t t0)
{
    return (board_ticks() - t0) * (1000000000u / board_tick_hz());
}

static void cell_u(uint64_t v)
{
    con_str(" | ");
    con_u64(v);
}

static int row(unsigned order)
{
    lumo_prt p;
    lumo_prt_light l, turned;
    lumo_q1_14 d1[3] = {0, 16384, 0}, d2[3] = {11585, 0, 11585};
    lumo_uq16_16 e[3] = {3u << 16, 3u << 16, 3u << 16};
    lumo_q1_14 one[2] = {16384, 0}, b[2] = {15137, 6270};
    lumo_pkg_light point;
    lumo_q16_16 centre[3] = {0, 0, 0};
    uint32_t t0, parse, light, pkg, rot, frame, shade;
    size_t len = build(order);

    memset(&point, 0, sizeof point);
    point.kind = LUMO_LIGHT_POINT, point.pos[1] = 3 << 16, point.power[0] = point.power[1] = point.power[2] = 50u << 16;
    t0 = board_ticks();
    if (lumo_prt_parse(&p, g_chunk, len) != LUMO_OK)
        return 1;
    parse = instructions_since(t0);
    lumo_prt_light_clear(&l, order);
    t0 = board_ticks();
    lumo_prt_light_add_directional(&l, d1, e);
    lumo_prt_light_add_directional(&l, d2, e);
    light = instructions_since(t0) / 2u;
    t0 = board_ticks();
    lumo_prt_light_add_pkg(&l, &point, centre);
    pkg = instructions_since(t0);
    t0 = board_ticks();
    if (lumo_prt_light_rotate(&l, one, b, one, &turned) != LUMO_OK)
        return 1;
    rot = instructions_since(t0);
    t0 = board_ticks();
    if (lumo_prt_frame(&p, &turned, g_frame) != LUMO_OK)
        return 1;
    frame = instructions_since(t0);
    t0 = board_ticks();
    if (lumo_prt_shade(&p, g_frame, g_albedo, 0, VERTICES, g_lit) != LUMO_OK)
        return 1;
    shade = instructions_since(t0);
    con_str("| ");
    con_u64(order);
    cell_u(parse);
    cell_u(light);
    cell_u(pkg);
    cell_u(rot);
    cell_u(frame);
    cell_u(shade / VERTICES);
    cell_u(frame + shade);
    cell_u(lambert_cost());
    con_str(" |\n");
    return 0;
}

int main(void)
{
    if (board_tick_hz() == 0) {
        con_str("bench_prt: this board has no tick counter\n");
        return 1;
    }
    con_str("| SH order | parse (2 000 vertices) | directional light | scene light (point) | rotation |"
            " per-cluster table (64 clusters) | relight per vertex | frame total (2 000 vertices) |"
            " peer: Lambert, 2 lights, per vertex |\n");
    con_str("|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    if (row(6) || row(4)) {
        con_str("bench_prt: failed\n");
        return 1;
    }
    return 0;
}
