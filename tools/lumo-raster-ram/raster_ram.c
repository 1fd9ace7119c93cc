/*
 * raster_ram.c — lumo-raster-ram: the memory the soft rasterizer needs per
 * resolution, pixel format and band height, as a markdown table, from the
 * library's own size functions (docs/rasterizer.md, benchmarks).
 */
#include <stdio.h>
#include "lumo/raster.h"

int main(void)
{
    static const uint16_t sizes[][2] = {{160, 128}, {320, 240}, {640, 480}};
    static const uint16_t bands[] = {0, 64, 32, 16, 8, 4, 1};
    size_t s, b;

    printf("| frame | band rows K | RGB565 + 16-bit depth | XRGB8888 + 32-bit depth |\n");
    printf("|---|---|---|---|\n");
    for (s = 0; s < sizeof sizes / sizeof sizes[0]; s++)
        for (b = 0; b < sizeof bands / sizeof bands[0]; b++) {
            uint16_t w = sizes[s][0], h = sizes[s][1], k = bands[b] ? bands[b] : h;
            if (k > h)
                continue;
            printf("| %ux%u | %u%s | %zu B | %zu B |\n", w, h, k, bands[b] ? "" : " (full frame)",
                   lumo_raster_band_bytes(w, k, LUMO_PIXEL_RGB565, 16),
                   lumo_raster_band_bytes(w, k, LUMO_PIXEL_XRGB8888, 32));
        }
    printf("\nOptional transformed-vertex cache: %zu bytes per vertex "
           "(dragon 48k: %zu B for 22998 vertices); without it each triangle transforms "
           "and lights its three vertices (same bytes, more work).\n",
           lumo_raster_cache_bytes(1), lumo_raster_cache_bytes(22998));
    return 0;
}
