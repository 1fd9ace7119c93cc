/*
 * tonemap.h — linear radiance to 8-bit sRGB, the one tone mapping of the
 * desktop side (docs/scene-format.md): multiply by the exposure, clamp to
 * [0, 1] (NaN becomes 0), apply the IEC 61966-2-1 sRGB curve, round to 8
 * bits. The reference renderer's PNGs and the benchmarks' Delta E images
 * both go through it, so they stay comparable with each other.
 */
#ifndef HOST_TONEMAP_H
#define HOST_TONEMAP_H

#include <stddef.h>
#include <stdint.h>

/* One linear value (any channel). */
uint8_t host_tonemap(float v, float exposure);

/* n values (w*h*3 for an RGB image) into a malloc'ed 8-bit buffer (caller
 * frees); NULL when out of memory. */
uint8_t *host_tonemap_rgb8(const float *rgb, size_t n, float exposure);

#endif
