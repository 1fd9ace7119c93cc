/* fuzz_ivg_bundle.c — hostile bytes into the IVG bundle decoder: it must
 * return an error or apply the bundle, never read or write out of bounds,
 * and push-pull and sampling must stay in bounds afterwards. */
#include <stdint.h>
#include <stddef.h>
#include "lumo/ivg.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static uint8_t g_mem[1u << 20];

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    lumo_arena arena;
    lumo_ivg *g;
    lumo_ivg_desc d = {{5, 4, 3}, {0, 0, 0}, {LUMO_Q16_ONE, LUMO_Q16_ONE, LUMO_Q16_ONE}};
    lumo_q16_16 p[3] = {LUMO_Q16_HALF, LUMO_Q16_HALF, LUMO_Q16_HALF};
    lumo_q1_14 n[3] = {0, LUMO_Q14_ONE, 0};
    lumo_uq16_16 out[3];

    lumo_arena_init(&arena, g_mem, sizeof g_mem);
    if (lumo_ivg_create(&g, &arena, &d) != LUMO_OK)
        return 0;
    if (lumo_ivg_apply_bundle(g, data, size, NULL) == LUMO_OK) {
        lumo_ivg_pushpull(g, size & 1 ? LUMO_IVG_SMOOTH : 0);
        lumo_ivg_irradiance(g, p, n, out);
    }
    return 0;
}
