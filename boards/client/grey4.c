/*
 * grey4.c — RGB565 to 4-bit grey with a 4x4 ordered dither (grey4.h).
 * Integer only, one division by a constant per pixel.
 */
#include "grey4.h"

/* The 4x4 Bayer matrix, row by row. */
static const uint8_t k_bayer[4][4] = {{0, 8, 2, 10}, {12, 4, 14, 6}, {3, 11, 1, 9}, {15, 7, 13, 5}};

static unsigned luma(uint16_t v)
{
    unsigned r = (v >> 11 << 3) | (v >> 13);
    unsigned g = ((v >> 5 & 63u) << 2) | (v >> 9 & 3u);
    unsigned b = ((v & 31u) << 3) | (v >> 2 & 7u);

    return (77u * r + 150u * g + 29u * b + 128u) >> 8;
}

static unsigned level(uint16_t v, unsigned x, unsigned y)
{
    unsigned t = (2u * k_bayer[y & 3u][x & 3u] + 1u) * 255u / 32u;

    return (15u * luma(v) + t) / 255u;
}

void grey4_band(const uint16_t *band, uint16_t w, uint16_t rows, uint16_t y0, uint8_t *out)
{
    unsigned x, y;

    for (y = 0; y < rows; y++)
        for (x = 0; x + 1u < w; x += 2u) {
            const uint16_t *p = band + (unsigned long)y * w + x;
            *out++ = (uint8_t)(level(p[0], x, y0 + y) << 4 | level(p[1], x + 1u, y0 + y));
        }
}
