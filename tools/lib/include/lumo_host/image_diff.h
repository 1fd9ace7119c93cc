/*
 * image_diff.h — how far apart two 8-bit sRGB images are, as users see
 * it: CIE76 Delta E in CIE L*a*b* (sRGB primaries, D65 white) and PSNR over
 * R, G, B. The one image metric of lumo-compare, the render tests and the
 * benchmarks (issue 3, "mean CIE Lab Delta E"), so their numbers agree.
 */
#ifndef HOST_IMAGE_DIFF_H
#define HOST_IMAGE_DIFF_H

#include <stddef.h>
#include <stdint.h>

typedef struct host_image_diff {
    double mean_de, max_de, p99_de;   /* CIE76 Delta E; p99 in steps of 0.01 */
    double psnr_db;                   /* over R, G, B; 99 when identical */
} host_image_diff;

/* One 8-bit sRGB pixel -> CIE L*a*b* (D65 white, Y of white = 1). */
void host_srgb8_to_lab(const uint8_t rgb[3], double lab[3]);

/* CIE76 Delta E between two 8-bit sRGB pixels. */
double host_delta_e76(const uint8_t a[3], const uint8_t b[3]);

/* Compare npixels of two RGB8 images (3 bytes a pixel, same layout). */
void host_image_diff_rgb8(const uint8_t *a, const uint8_t *b, size_t npixels, host_image_diff *out);

#endif
