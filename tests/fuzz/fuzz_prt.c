/* fuzz_prt.c — hostile bytes into the PRTV reader (lumo/prt.h): it must
 * return an error or a view whose every use stays in bounds — the frame
 * table from a lighting vector (its coefficients from the input's last
 * bytes), every held vertex shaded, the lighting rotated by angles read
 * from the input; every cluster's pass in range. */
#include <stdint.h>
#include <stddef.h>
#include <string.h>
#include "lumo/prt.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static lumo_q16_16 g_frame[3u * LUMO_PRT_MAX_CLUSTERS * (LUMO_PRT_MAX_COMPONENTS + 1u)];
#define MAXV 65536u
static lumo_uq16_16 g_lit[6u * MAXV];
static lumo_q1_14 g_albedo[3u * MAXV];

static void light_from(const uint8_t *data, size_t size, unsigned order, lumo_prt_light *l)
{
    lumo_prt_light_clear(l, order);
    for (unsigned c = 0; c < 3; c++)
        for (unsigned i = 0; i < order * order; i++) {
            size_t at = (c * 37u + i * 4u) % (size ? size : 1);
            uint32_t v = 0;
            for (unsigned b = 0; b < 4 && size; b++)
                v |= (uint32_t)data[(at + b) % size] << (8 * b);
            l->c[c][i] = (lumo_q16_16)v;
        }
}

static void rotate(const uint8_t *data, size_t size, const lumo_prt_light *l)
{
    lumo_prt_light out;
    lumo_q1_14 a[2] = {16384, 0}, b[2] = {0, 16384}, g[2] = {11585, 11585};
    if (size >= 2)
        a[0] = (lumo_q1_14)(int16_t)(data[0] | data[1] << 8);
    if (lumo_prt_light_rotate(l, a, b, g, &out) == LUMO_OK && out.order != l->order)
        __builtin_trap();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    lumo_prt p;
    lumo_prt_light l;
    if (lumo_prt_parse(&p, data, size) != LUMO_OK)
        return 0;
    if (p.vertices_held > p.vertices || lumo_prt_frame_entries(&p) > sizeof g_frame / sizeof g_frame[0])
        __builtin_trap();
    if (p.vertices_held > MAXV)
        return 0;
    for (uint32_t k = 0; k < p.clusters; k++)
        if (lumo_prt_pass(&p, k) >= p.clusters)
            __builtin_trap();
    light_from(data, size, p.order, &l);
    rotate(data, size, &l);
    if (lumo_prt_frame(&p, &l, g_frame) != LUMO_OK)
        __builtin_trap();
    memset(g_albedo, 0x20, sizeof g_albedo);
    for (uint32_t v = 0; v < p.vertices_held; v += 256) {
        uint32_t n = p.vertices_held - v < 256 ? p.vertices_held - v : 256;
        if (lumo_prt_shade(&p, g_frame, v % 512 ? g_albedo : NULL, v, n, g_lit) != LUMO_OK)
            __builtin_trap();
    }
    if (lumo_prt_shade(&p, g_frame, NULL, p.vertices_held, 1, g_lit) != LUMO_ERR_RANGE)
        __builtin_trap();
    return 0;
}
