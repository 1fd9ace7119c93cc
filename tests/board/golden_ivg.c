/*
 * golden_ivg.c — the IVG pipeline over fixed test grids, hashed stage by
 * stage; host and board must print the same hashes (ARCHITECTURE.md rule 3,
 * bit-exact). For each grid: a deterministic integer PRNG picks ~30% of the
 * vertices and their six entries, a bundle is hand-encoded in the quantized
 * wire form (and the first grid also in binary32 form), applied, filled by
 * push-pull without and with smoothing, and sampled at 1000 fixed points and
 * normals (irradiance and radiance). Non-power-of-two dims on purpose.
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include "lumo/ivg.h"
#include "board.h"
#include "golden.h"
#include "ivg_wire.h"

int main(void);

#define SAMPLES 1000

typedef struct case_ {
    const char *name;
    lumo_ivg_desc desc;
    unsigned form;
} case_;

static uint8_t g_bundle[WIRE_HEADER + 1400u * WIRE_FLOAT_RECORD];

/* A random unit-ish direction as int8 (|q| within 1/16 of 127), or zero. */
static void rand_qdir(bt_rng *r, int8_t d[3])
{
    for (;;) {
        int32_t x = (int32_t)(bt_rng_next(r) % 255u) - 127;
        int32_t y = (int32_t)(bt_rng_next(r) % 255u) - 127;
        int32_t z = (int32_t)(bt_rng_next(r) % 255u) - 127;
        int32_t len2 = x * x + y * y + z * z;
        /* scale to length ~127 by an integer square root search */
        int32_t len = 1, k;
        if (len2 == 0)
            continue;
        while ((len + 1) * (len + 1) <= len2)
            len++;
        x = x * 127 / len;
        y = y * 127 / len;
        z = z * 127 / len;
        len2 = x * x + y * y + z * z;
        if (256 * len2 < 15 * 15 * 127 * 127 || 256 * len2 > 17 * 17 * 127 * 127)
            continue;
        for (k = 0; k < 3; k++)
            d[k] = (int8_t)(k == 0 ? x : k == 1 ? y : z);
        return;
    }
}

/* Same in sixty-fourths for the binary32 form. */
static void rand_fdir(bt_rng *r, int16_t d[3])
{
    int8_t q[3];
    int k;

    rand_qdir(r, q);
    for (k = 0; k < 3; k++)
        d[k] = (int16_t)(q[k] / 2);   /* q/127 ~ (q/2)/64, still within tolerance */
}

static int fdir_ok(const int16_t d[3])
{
    int32_t len2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    return 256 * len2 >= 15 * 15 * 64 * 64 && 256 * len2 <= 17 * 17 * 64 * 64;
}

static size_t encode(const case_ *c, uint32_t seed, uint32_t *records)
{
    bt_rng r;
    uint32_t count = (uint32_t)c->desc.dims[0] * c->desc.dims[1] * c->desc.dims[2], v;
    size_t n = WIRE_HEADER;
    int a, k;

    r.s = 0x9E3779B97F4A7C15ull ^ seed;
    *records = 0;
    for (v = 0; v < count; v++) {
        if (bt_rng_next(&r) % 10u >= 3u)
            continue;
        if (c->form == LUMO_IVG_FORM_QUANTIZED) {
            wire_qentry e[6];
            for (a = 0; a < 6; a++) {
                rand_qdir(&r, e[a].d);
                for (k = 0; k < 3; k++)
                    e[a].m[k] = (uint16_t)(bt_rng_next(&r) % 512u);
                e[a].e = (uint8_t)(10u + bt_rng_next(&r) % 12u);
            }
            n += wire_quant_record(g_bundle + n, v, e);
        } else {
            wire_fentry e[6];
            for (a = 0; a < 6; a++) {
                do
                    rand_fdir(&r, e[a].dnum);
                while (!fdir_ok(e[a].dnum));
                for (k = 0; k < 3; k++)
                    e[a].cnum[k] = (uint32_t)(bt_rng_next(&r) % (200u * 256u));
            }
            n += wire_float_record(g_bundle + n, v, e);
        }
        (*records)++;
    }
    wire_header(g_bundle, c->form, c->desc.dims, *records);
    return n;
}

static uint64_t hash_entries(const lumo_ivg *g)
{
    uint64_t h = BT_FNV_OFFSET;
    uint32_t v, count = lumo_ivg_vertex_count(g);
    int a, k;

    for (v = 0; v < count; v++) {
        h = bt_fnv1a_u32(h, (uint32_t)lumo_ivg_is_received(g, v));
        for (a = 0; a < LUMO_IVG_AXES; a++) {
            lumo_ivg_entry e;
            (void)lumo_ivg_entry_get(g, v, (lumo_ivg_axis)a, &e);
            for (k = 0; k < 3; k++) {
                h = bt_fnv1a_u32(h, e.c[k]);
                h = bt_fnv1a_u32(h, (uint32_t)(int32_t)e.d[k]);
            }
        }
    }
    return h;
}

/* 1000 points inside and slightly outside the box, random unit normals and
 * albedos, generated first so the timed loop holds only the SDK calls. */
typedef struct sample_in {
    lumo_q16_16 p[3];
    lumo_q1_14  n[3], albedo[3];
} sample_in;

static sample_in g_in[SAMPLES];
static lumo_uq16_16 g_irr[SAMPLES][3], g_rad[SAMPLES][3];

static void make_samples(const lumo_ivg_desc *d)
{
    bt_rng r = {0x5A3B1E5ull};
    int i, k;

    for (i = 0; i < SAMPLES; i++) {
        int8_t q[3];
        int32_t w[3];
        for (k = 0; k < 3; k++) {
            int64_t ext = (int64_t)d->bmax[k] - d->bmin[k];
            g_in[i].p[k] = (lumo_q16_16)(d->bmin[k] - ext / 16
                                         + (int64_t)(bt_rng_next(&r) % (uint64_t)(ext + ext / 8)));
            g_in[i].albedo[k] = (lumo_q1_14)(bt_rng_next(&r) % (LUMO_Q14_ONE + 1u));
        }
        rand_qdir(&r, q);
        for (k = 0; k < 3; k++)
            w[k] = q[k];
        lumo_normalize3_q14(w, g_in[i].n);
    }
}

/* Irradiance (timed: COST <name>, per 1000 samples) and radiance at every
 * sample, hashed together. */
static uint64_t hash_samples(const lumo_ivg *g, const lumo_ivg_desc *d, const char *name)
{
    uint64_t h = BT_FNV_OFFSET;
    uint32_t t0;
    int i, k;

    make_samples(d);
    t0 = board_ticks();
    for (i = 0; i < SAMPLES; i++)
        lumo_ivg_irradiance(g, g_in[i].p, g_in[i].n, g_irr[i]);
    golden_cost(name, t0);
    for (i = 0; i < SAMPLES; i++)
        lumo_ivg_radiance(g, g_in[i].p, g_in[i].n, g_in[i].albedo, g_rad[i]);
    for (i = 0; i < SAMPLES; i++)
        for (k = 0; k < 3; k++) {
            h = bt_fnv1a_u32(h, g_irr[i][k]);
            h = bt_fnv1a_u32(h, g_rad[i][k]);
        }
    return h;
}

static void label(char *out, const char *name, const char *stage)
{
    size_t a = strlen(name);
    memcpy(out, name, a);
    out[a] = '.';
    memcpy(out + a + 1, stage, strlen(stage) + 1);
}

/* One grid through the whole pipeline; returns 0 on success. */
static int run_case(const case_ *c, uint32_t seed)
{
    size_t scratch_bytes = 0, len;
    uint8_t *mem = board_scratch(&scratch_bytes);
    char name[64];
    uint32_t records = 0, applied = 0, t0;
    unsigned flags;
    lumo_arena a;
    lumo_ivg *g;

    len = encode(c, seed, &records);
    for (flags = 0; flags <= LUMO_IVG_SMOOTH; flags++) {
        lumo_arena_init(&a, mem, scratch_bytes);
        if (lumo_ivg_create(&g, &a, &c->desc) != LUMO_OK
            || lumo_ivg_apply_bundle(g, g_bundle, len, &applied) != LUMO_OK || applied != records) {
            con_str("golden_ivg: cannot build ");
            con_str(c->name);
            con_nl();
            return 1;
        }
        if (flags == 0) {
            label(name, c->name, "decoded");
            golden_hash(name, hash_entries(g));
        }
        t0 = board_ticks();
        if (lumo_ivg_pushpull(g, flags) != LUMO_OK)
            return 1;
        label(name, c->name, flags ? "pushpull_smooth" : "pushpull");
        golden_cost(name, t0);
        golden_hash(name, hash_entries(g));
        label(name, c->name, flags ? "samples_smooth" : "samples");
        golden_hash(name, hash_samples(g, &c->desc, name));
    }
    return 0;
}

int main(void)
{
    static const case_ cases[] = {
        {"ivg9x7x5", {{9, 7, 5}, {-LUMO_Q16_ONE, 0, LUMO_Q16_HALF},
                      {3 * LUMO_Q16_ONE, 2 * LUMO_Q16_ONE, 4 * LUMO_Q16_ONE}}, LUMO_IVG_FORM_QUANTIZED},
        {"ivg9x7x5f", {{9, 7, 5}, {-LUMO_Q16_ONE, 0, LUMO_Q16_HALF},
                       {3 * LUMO_Q16_ONE, 2 * LUMO_Q16_ONE, 4 * LUMO_Q16_ONE}}, LUMO_IVG_FORM_FLOAT},
        {"ivg16", {{16, 16, 16}, {0, 0, 0},
                   {10 * LUMO_Q16_ONE, 10 * LUMO_Q16_ONE, 10 * LUMO_Q16_ONE}}, LUMO_IVG_FORM_QUANTIZED},
        {"ivg2x33x3", {{2, 33, 3}, {0, -8 * LUMO_Q16_ONE, 0},
                       {LUMO_Q16_ONE, 8 * LUMO_Q16_ONE, LUMO_Q16_ONE / 4}}, LUMO_IVG_FORM_QUANTIZED},
    };
    size_t i;

    for (i = 0; i < sizeof cases / sizeof cases[0]; i++)
        if (run_case(&cases[i], (uint32_t)i + 1u) != 0)
            return golden_done(1);
    return golden_done(0);
}
