/*
 * golden_fixed.c — every lumo/fixed.h operation over 20000 PRNG inputs,
 * hashed per operation; host and board must print the same hashes.
 */
#include <stdint.h>
#include "lumo/fixed.h"
#include "board.h"
#include "golden.h"

#define N 20000

int main(void);

static int32_t rand_i32(bt_rng *r)
{
    unsigned bits = 4u + (unsigned)(bt_rng_next(r) % 29u);
    uint64_t x = bt_rng_next(r) & (((uint64_t)1 << bits) - 1u);
    return (int32_t)((int64_t)x - ((int64_t)1 << (bits - 1u)));
}

static void hash_arith(void)
{
    bt_rng r = {0xF1ED0001ull};
    uint64_t hm = BT_FNV_OFFSET, hd = BT_FNV_OFFSET, hs = BT_FNV_OFFSET;
    uint32_t t0 = board_ticks();
    int i;

    for (i = 0; i < N; i++) {
        int32_t a = rand_i32(&r), b = rand_i32(&r);
        hm = bt_fnv1a_u32(hm, (uint32_t)lumo_q16_mul(a, b));
        hm = bt_fnv1a_u32(hm, lumo_uq16_mul((uint32_t)a, (uint32_t)b));
        hm = bt_fnv1a_u32(hm, lumo_uq16_mul_q14((uint32_t)a, (lumo_q1_14)b));
        hd = bt_fnv1a_u32(hd, (uint32_t)lumo_q16_div(a, b));
        hs = bt_fnv1a_u32(hs, (uint32_t)lumo_q16_sqrt(a));
        hs = bt_fnv1a_u32(hs, (uint32_t)lumo_q16_rsqrt(a));
        hs = bt_fnv1a_u32(hs, lumo_isqrt64(bt_rng_next(&r) >> (i % 64)));
    }
    golden_cost("fixed.arith", t0);
    golden_hash("fixed.mul", hm);
    golden_hash("fixed.div", hd);
    golden_hash("fixed.sqrt", hs);
}

static void hash_conversions(void)
{
    bt_rng r = {0xF1ED0002ull};
    uint64_t hf = BT_FNV_OFFSET, hc = BT_FNV_OFFSET, hn = BT_FNV_OFFSET;
    int i, k;

    for (i = 0; i < N; i++) {
        uint32_t bits = (uint32_t)bt_rng_next(&r);
        int32_t v = 0, w[3];
        lumo_uq16_16 c[3];
        lumo_q1_14 n[3];
        lumo_status st = lumo_f32bits_to_fixed(bits, (unsigned)(i % 31), &v);

        hf = bt_fnv1a_u32(hf, (uint32_t)st);
        hf = bt_fnv1a_u32(hf, (uint32_t)v);
        lumo_rgb9e5_to_uq16(bits, c);
        for (k = 0; k < 3; k++) {
            hc = bt_fnv1a_u32(hc, c[k]);
            w[k] = rand_i32(&r);
        }
        st = lumo_normalize3_q14(w, n);
        hn = bt_fnv1a_u32(hn, (uint32_t)st);
        for (k = 0; k < 3; k++)
            hn = bt_fnv1a_u32(hn, (uint32_t)(int32_t)n[k]);
    }
    golden_hash("fixed.f32bits", hf);
    golden_hash("fixed.rgb9e5", hc);
    golden_hash("fixed.normalize3", hn);
}

int main(void)
{
    hash_arith();
    hash_conversions();
    return golden_done(0);
}
