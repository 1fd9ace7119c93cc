/*
 * image_metrics.h — image differences as users see them: mean CIE Lab
 * Delta E (CIE76, sRGB D65) and PSNR over 8-bit RGB.
 */
#ifndef LUMO_HOST_IMAGE_METRICS_H
#define LUMO_HOST_IMAGE_METRICS_H

#include <stddef.h>
#include <stdint.h>

typedef struct image_diff {
    double mean_de, max_de, p99_de;   /* CIE76 Delta E */
    double psnr_db;                   /* over R, G, B; 99 when identical */
} image_diff;

/* Compare n pixels of two RGB8 images. */
void image_compare(const uint8_t *a, const uint8_t *b, size_t n, image_diff *out);

#endif
