/*
 * raster_ivg.c — the IVG as the rasterizer's indirect-light source (seed 000,
 * §3.2: trilinear spatial + directional interpolation, done by lumo_ivg).
 * A separate object so that programs without an IVG do not link lumo_ivg.
 */
#include "lumo/ivg.h"
#include "raster_internal.h"

void lumo_raster_ivg_irradiance(const void *ivg, const lumo_q16_16 p[3],
                                const lumo_q1_14 n[3], lumo_uq16_16 out[3])
{
    lumo_ivg_irradiance((const lumo_ivg *)ivg, p, n, out);
}

/* The callback type passes its context as const; the sampler was handed
 * over writable by the caller (lumo/raster.h), so dropping const is sound. */
void lumo_raster_ivg_sampler_irradiance(const void *sampler, const lumo_q16_16 p[3],
                                        const lumo_q1_14 n[3], lumo_uq16_16 out[3])
{
    lumo_ivg_sampler_irradiance((lumo_ivg_sampler *)(uintptr_t)sampler, p, n, out);
}
