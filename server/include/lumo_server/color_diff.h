/* color_diff.h — image error in CIE Lab (D65), for benchmarks and tests. */
#ifndef LUMO_SERVER_COLOR_DIFF_H
#define LUMO_SERVER_COLOR_DIFF_H

#include <stddef.h>
#include <stdint.h>

/* 8-bit sRGB -> CIE L*a*b* (D65 white). */
void lumo_srgb8_to_lab(const uint8_t rgb[3], double lab[3]);

/* Mean CIE76 Delta E over n pixels of two 8-bit sRGB images. */
double lumo_mean_delta_e(const uint8_t *a, const uint8_t *b, size_t npixels);

#endif
