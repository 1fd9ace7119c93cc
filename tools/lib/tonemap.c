/*
 * tonemap.c — see lumo_host/tonemap.h.
 */
#include <math.h>
#include <stdlib.h>
#include "lumo_host/tonemap.h"

/* IEC 61966-2-1 sRGB transfer function (linear segment near black). */
static float srgb_encode(float v)
{
    return v <= 0.0031308f ? 12.92f * v : 1.055f * powf(v, 1.0f / 2.4f) - 0.055f;
}

uint8_t host_tonemap(float v, float exposure)
{
    v *= exposure;
    v = isnan(v) ? 0.0f : fminf(fmaxf(v, 0.0f), 1.0f);
    return (uint8_t)lrintf(255.0f * srgb_encode(v));
}

uint8_t *host_tonemap_rgb8(const float *rgb, size_t n, float exposure)
{
    uint8_t *px = malloc(n ? n : 1);   /* malloc(0) may return NULL */

    if (!px)
        return NULL;
    for (size_t i = 0; i < n; i++)
        px[i] = host_tonemap(rgb[i], exposure);
    return px;
}
