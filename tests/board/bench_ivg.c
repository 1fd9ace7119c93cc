/*
 * bench_ivg.c — Cortex-M3 instruction counts of the IVG client core under
 * QEMU `-icount shift=0` (docs/porting.md "Cost measurement"): bundle
 * decode, push-pull without and with smoothing (seed 000 §4.1; the paper
 * measured smoothing at ~80% of the push-pull time) and sampling, on 16^3
 * and 32^3 grids with 10%, 25% and 50% of the vertices received. 64^3 needs
 * 41 MB of arena and fits no Cortex-M3 board here. Prints markdown rows;
 * `make bench-board` wraps them into a docs/benchmarks.md section.
 */
#include <stddef.h>
#include <stdint.h>
#include "lumo/ivg.h"
#include "board.h"
#include "console.h"
#include "harness.h"
#include "ivg_wire.h"

int main(void);

#define SAMPLES 1000
#define MAX_RECORDS (32u * 32u * 32u / 2u + 64u)

static uint8_t g_bundle[WIRE_HEADER + MAX_RECORDS * WIRE_QUANT_RECORD];

/* Receive each vertex with probability pct/100; d = the hemisphere's axis,
 * random colours. Returns the bundle length, 0 if it would not fit. */
static size_t encode(uint16_t dim, unsigned pct, uint32_t *records)
{
    uint16_t dims[3];
    bt_rng r = {0xBE5C4ull + pct};
    uint32_t v, count = (uint32_t)dim * dim * dim;
    size_t n = WIRE_HEADER;
    int a, k;

    dims[0] = dims[1] = dims[2] = dim;
    *records = 0;
    for (v = 0; v < count; v++) {
        wire_qentry e[6];
        if (bt_rng_next(&r) % 100u >= pct)
            continue;
        if (*records >= MAX_RECORDS)
            return 0;
        for (a = 0; a < 6; a++) {
            for (k = 0; k < 3; k++) {
                e[a].d[k] = (int8_t)(k == a / 2 ? (a % 2 ? -127 : 127) : 0);
                e[a].m[k] = (uint16_t)(bt_rng_next(&r) % 512u);
            }
            e[a].e = (uint8_t)(10u + bt_rng_next(&r) % 10u);
        }
        n += wire_quant_record(g_bundle + n, v, e);
        (*records)++;
    }
    wire_header(g_bundle, LUMO_IVG_FORM_QUANTIZED, dims, *records);
    return n;
}

static uint32_t instructions_since(uint32_t t0)
{
    return (board_ticks() - t0) * (1000000000u / board_tick_hz());
}

/* Build the grid and apply the bundle; *decode gets the instructions the
 * decoder took. Returns 0 on success. */
static int setup(lumo_ivg **g, lumo_arena *a, uint16_t dim, size_t len, uint32_t *decode)
{
    lumo_ivg_desc d = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    size_t bytes = 0;
    uint8_t *mem = board_scratch(&bytes);
    uint32_t t0;
    int k;

    for (k = 0; k < 3; k++) {
        d.dims[k] = dim;
        d.bmax[k] = LUMO_Q16_FROM_INT(10);
    }
    lumo_arena_init(a, mem, bytes);
    if (lumo_ivg_create(g, a, &d) != LUMO_OK)
        return 1;
    t0 = board_ticks();
    if (lumo_ivg_apply_bundle(*g, g_bundle, len, NULL) != LUMO_OK)
        return 1;
    *decode = instructions_since(t0);
    return 0;
}

static uint32_t sample_cost(const lumo_ivg *g)
{
    static lumo_q16_16 p[SAMPLES][3];
    static lumo_q1_14 n[SAMPLES][3];
    lumo_uq16_16 out[3];
    bt_rng r = {0x5A4D1Eull};
    uint32_t t0;
    int i, k;

    for (i = 0; i < SAMPLES; i++) {
        int32_t w[3];
        for (k = 0; k < 3; k++) {
            p[i][k] = (lumo_q16_16)(bt_rng_next(&r) % (10u * 65536u));
            w[k] = (int32_t)(bt_rng_next(&r) % 2001u) - 1000;
        }
        lumo_normalize3_q14(w, n[i]);
    }
    t0 = board_ticks();
    for (i = 0; i < SAMPLES; i++)
        lumo_ivg_irradiance(g, p[i], n[i], out);
    return instructions_since(t0) / SAMPLES;
}

static void cell_u(uint64_t v)
{
    con_str(" | ");
    con_u64(v);
}

/* One row: grid, share received, decode, push-pull, push-pull + smoothing,
 * smoothing share, sampling per point. */
static int row(uint16_t dim, unsigned pct)
{
    lumo_arena a;
    lumo_ivg *g;
    uint32_t records, dec, plain, smooth, t0, per;
    size_t len = encode(dim, pct, &records);

    if (len == 0 || setup(&g, &a, dim, len, &dec) != 0)
        return 1;
    t0 = board_ticks();
    lumo_ivg_pushpull(g, 0);
    plain = instructions_since(t0);
    per = sample_cost(g);
    if (setup(&g, &a, dim, len, &dec) != 0)
        return 1;
    t0 = board_ticks();
    lumo_ivg_pushpull(g, LUMO_IVG_SMOOTH);
    smooth = instructions_since(t0);
    con_str("| ");
    con_u64(dim);
    con_str("^3");
    cell_u(pct);
    con_str("% (");
    con_u64(records);
    con_str(")");
    cell_u(dec);
    cell_u(plain);
    cell_u(smooth);
    cell_u(smooth > plain ? (uint64_t)(smooth - plain) * 100u / smooth : 0u);
    con_str("%");
    cell_u(per);
    cell_u(a.peak);
    con_str(" |\n");
    return 0;
}

int main(void)
{
    static const uint16_t dims[] = {16, 32};
    static const unsigned pcts[] = {10, 25, 50};
    unsigned i, j;

    if (board_tick_hz() == 0) {
        con_str("bench_ivg: this board has no tick counter\n");
        return 1;
    }
    con_str("| grid | received (records) | decode | push-pull | push-pull + smoothing"
            " | smoothing share | irradiance per sample | arena bytes |\n");
    con_str("|---|---|---:|---:|---:|---:|---:|---:|\n");
    for (i = 0; i < sizeof dims / sizeof dims[0]; i++)
        for (j = 0; j < sizeof pcts / sizeof pcts[0]; j++)
            if (row(dims[i], pcts[j]) != 0) {
                con_str("bench_ivg: setup failed\n");
                return 1;
            }
    return 0;
}
