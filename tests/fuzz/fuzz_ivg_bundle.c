/* fuzz_ivg_bundle.c — hostile bytes into the IVG bundle decoder: it must
 * return an error or apply the bundle, never read or write out of bounds,
 * and leave every byte of the grid unchanged when it fails; push-pull and
 * sampling must stay in bounds afterwards.
 *
 * The grid's dims come from the bundle's own header (bytes 6-11; values
 * outside 2..12 are folded into that range) so the fuzzer also explores odd
 * pyramid shapes; inputs whose first byte is a multiple of 4 get a fixed
 * 5x4x3 grid instead, so the dims check is fuzzed too.
 *
 * Each input is also read as a run of records without the header
 * (lumo_ivg_apply_records, the session's IVGR): form from byte 5, count
 * from bytes 12-15, the records from byte 16 on, on a fresh grid.
 */
#include <stdint.h>
#include <stddef.h>
#include <string.h>
#include "lumo/ivg.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static uint8_t g_mem[1u << 20];
static uint8_t g_copy[1u << 20];

static void pick_desc(const uint8_t *data, size_t size, lumo_ivg_desc *d)
{
    int a;

    memset(d, 0, sizeof *d);
    for (a = 0; a < 3; a++) {
        d->dims[a] = (uint16_t)(a == 0 ? 5 : a == 1 ? 4 : 3);
        d->bmin[a] = -LUMO_Q16_ONE * a;
        d->bmax[a] = LUMO_Q16_ONE * (a + 1);
    }
    if (size < 12 || data[0] % 4 == 0)
        return;
    for (a = 0; a < 3; a++) {
        unsigned v = data[6 + 2 * a] | (unsigned)data[7 + 2 * a] << 8;
        d->dims[a] = (uint16_t)(v >= 2 && v <= 12 ? v : 2 + v % 11);
    }
}

static void run_one(const uint8_t *data, size_t size, int as_run)
{
    lumo_arena arena;
    lumo_ivg *g;
    lumo_ivg_desc d;
    size_t need;
    lumo_uq16_16 out[3];
    lumo_ivg_sampler smp;
    lumo_status st;
    int s;

    pick_desc(data, size, &d);
    need = lumo_ivg_memory_size(&d);
    if (need == 0 || need > sizeof g_mem)
        return;
    lumo_arena_init(&arena, g_mem, need);
    if (lumo_ivg_create(&g, &arena, &d) != LUMO_OK)
        __builtin_trap();
    memcpy(g_copy, g_mem, need);
    if (as_run)
        st = lumo_ivg_apply_records(g, (lumo_ivg_form)data[5],
                                    (uint32_t)data[12] | (uint32_t)data[13] << 8 | (uint32_t)data[14] << 16 |
                                        (uint32_t)data[15] << 24,
                                    data + 16, size - 16, NULL);
    else
        st = lumo_ivg_apply_bundle(g, data, size, NULL);
    if (st != LUMO_OK) {
        if (memcmp(g_copy, g_mem, need) != 0)
            __builtin_trap();   /* a rejected bundle changed the grid */
        return;
    }
    if (lumo_ivg_pushpull(g, size & 1 ? LUMO_IVG_SMOOTH : 0) != LUMO_OK)
        __builtin_trap();
    lumo_ivg_sampler_init(&smp, g);
    for (s = 0; s < 4 && size > 0; s++) {
        /* points and normals from the input itself, in and out of the box */
        size_t o = (size / 4) * (size_t)s;
        lumo_q16_16 p[3];
        lumo_q1_14 n[3], albedo[3] = {LUMO_Q14_ONE, LUMO_Q14_ONE / 2, 0};
        lumo_uq16_16 memo[3];
        int a;
        for (a = 0; a < 3; a++) {
            p[a] = (lumo_q16_16)((uint32_t)data[(o + a) % size] << 17) - LUMO_Q16_FROM_INT(4);
            n[a] = (lumo_q1_14)((int)data[(o + 3 + a) % size] * 128 - 16384);
        }
        lumo_ivg_irradiance(g, p, n, out);
        lumo_ivg_sampler_irradiance(&smp, p, n, memo);   /* the sampler: the same bits */
        if (memcmp(memo, out, sizeof memo) != 0)
            __builtin_trap();
        lumo_ivg_radiance(g, p, n, albedo, out);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    run_one(data, size, 0);
    if (size >= 16)
        run_one(data, size, 1);
    return 0;
}
