/*
 * lm3s_ivg.c — the tiny program of the 64 KiB board: a 6 x 6 x 6 IVG in an
 * arena in SRAM, one hand-encoded quantized bundle (a third of the
 * vertices), push-pull with smoothing, 200 samples; prints the hashes and
 * the arena bytes used. Built for the host too: the hashes must match.
 */
#include <stddef.h>
#include <stdint.h>
#include "lumo/ivg.h"
#include "board.h"
#include "golden.h"
#include "ivg_wire.h"

int main(void);

#define DIM 6
#define VERTS (DIM * DIM * DIM)

static uint8_t g_bundle[WIRE_HEADER + (VERTS / 3 + 1) * WIRE_QUANT_RECORD];

static size_t encode(uint32_t *records)
{
    static const uint16_t dims[3] = {DIM, DIM, DIM};
    static const int8_t axes[6][3] = {
        {127, 0, 0}, {-127, 0, 0}, {0, 127, 0}, {0, -127, 0}, {0, 0, 127}, {0, 0, -127}
    };
    bt_rng r = {0x1A3565ull};
    size_t n = WIRE_HEADER;
    uint32_t v;
    int a, k;

    *records = 0;
    for (v = 0; v < VERTS; v += 3) {
        wire_qentry e[6];
        for (a = 0; a < 6; a++) {
            for (k = 0; k < 3; k++) {
                e[a].d[k] = axes[a][k];
                e[a].m[k] = (uint16_t)(bt_rng_next(&r) % 512u);
            }
            e[a].e = (uint8_t)(12u + bt_rng_next(&r) % 6u);
        }
        n += wire_quant_record(g_bundle + n, v, e);
        (*records)++;
    }
    wire_header(g_bundle, LUMO_IVG_FORM_QUANTIZED, dims, *records);
    return n;
}

int main(void)
{
    static const lumo_ivg_desc desc = {{DIM, DIM, DIM}, {0, 0, 0},
                                       {5 * LUMO_Q16_ONE, 5 * LUMO_Q16_ONE, 5 * LUMO_Q16_ONE}};
    size_t bytes = 0, len;
    uint8_t *mem = board_scratch(&bytes);
    uint32_t records, i;
    uint64_t h = BT_FNV_OFFSET;
    bt_rng r = {0x5EEDull};
    lumo_arena a;
    lumo_ivg *g;

    len = encode(&records);
    lumo_arena_init(&a, mem, bytes);
    if (lumo_ivg_create(&g, &a, &desc) != LUMO_OK || lumo_ivg_apply_bundle(g, g_bundle, len, NULL) != LUMO_OK
        || lumo_ivg_pushpull(g, LUMO_IVG_SMOOTH) != LUMO_OK) {
        con_str("lm3s_ivg: IVG setup failed\n");
        return 1;
    }
    for (i = 0; i < 200; i++) {
        lumo_q16_16 p[3];
        int32_t w[3];
        lumo_q1_14 n[3];
        lumo_uq16_16 out[3];
        int k;
        for (k = 0; k < 3; k++) {
            p[k] = (lumo_q16_16)(bt_rng_next(&r) % (5u * 65536u));
            w[k] = (int32_t)(bt_rng_next(&r) % 2001u) - 1000;
        }
        lumo_normalize3_q14(w, n);
        lumo_ivg_irradiance(g, p, n, out);
        for (k = 0; k < 3; k++)
            h = bt_fnv1a_u32(h, out[k]);
    }
    golden_hash("lm3s.ivg6.samples", h);
    con_str("arena bytes used: ");
    con_u64(a.peak);
    con_str(" of ");
    con_u64(bytes);
    con_nl();
    return 0;
}
