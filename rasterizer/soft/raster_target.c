/*
 * raster_target.c — frame and band buffers: sizes, checks, clearing.
 * A band is rows [band_y, band_y + band_rows) of the frame; a full frame is
 * the band with band_y = 0 and band_rows = height.
 */
#include <string.h>
#include "raster_internal.h"

static size_t pixel_bytes(lumo_pixel_format f)
{
    return f == LUMO_PIXEL_RGB565 ? 2u : 4u;
}

size_t lumo_raster_band_bytes(uint16_t width, uint16_t rows, lumo_pixel_format format,
                              uint8_t depth_bits)
{
    if (width == 0 || rows == 0 || width > LUMO_MAX_FRAME_DIM || rows > LUMO_MAX_FRAME_DIM)
        return 0;
    if ((format != LUMO_PIXEL_XRGB8888 && format != LUMO_PIXEL_RGB565)
        || (depth_bits != 16 && depth_bits != 32))
        return 0;
    return (size_t)width * rows * (pixel_bytes(format) + depth_bits / 8u);
}

lumo_status lumo_raster_target_init(lumo_raster_target *t, uint16_t width, uint16_t height,
                                    uint16_t band_y, uint16_t band_rows,
                                    lumo_pixel_format format, void *color, void *depth,
                                    uint8_t depth_bits)
{
    if (!t)
        return LUMO_ERR_ARG;
    memset(t, 0, sizeof *t);
    t->width = width;
    t->height = height;
    t->band_y = band_y;
    t->band_rows = band_rows;
    t->format = format;
    t->color = color;
    t->color_stride = (uint32_t)width * (uint32_t)pixel_bytes(format);
    t->depth = depth;
    t->depth_bits = depth_bits;
    return lumo_raster_target_check(t);
}

lumo_status lumo_raster_target_check(const lumo_raster_target *t)
{
    if (!t || !t->color || !t->depth)
        return LUMO_ERR_ARG;
    if (lumo_raster_band_bytes(t->width, t->band_rows, t->format, t->depth_bits) == 0)
        return LUMO_ERR_RANGE;
    if (t->height == 0 || t->height > LUMO_MAX_FRAME_DIM
        || (uint32_t)t->band_y + t->band_rows > t->height)
        return LUMO_ERR_RANGE;
    if (t->color_stride < t->width * pixel_bytes(t->format) || t->color_stride % pixel_bytes(t->format))
        return LUMO_ERR_RANGE;
    return LUMO_OK;
}

/* One row of the clear colour; the others are copies of it (memcpy moves
 * whole words, where a store per pixel cost 7 instructions per pixel of a
 * 640x480 frame). */
static void clear_row(const lumo_raster_target *t, uint8_t *row, uint32_t rgb)
{
    uint32_t x;

    if (t->format == LUMO_PIXEL_RGB565) {
        uint16_t c = (uint16_t)(((rgb >> 8) & 0xF800u) | ((rgb >> 5) & 0x07E0u) | ((rgb >> 3) & 0x001Fu));
        for (x = 0; x < t->width; x++)
            ((uint16_t *)(void *)row)[x] = c;
    } else {
        for (x = 0; x < t->width; x++)
            ((uint32_t *)(void *)row)[x] = rgb & 0xFFFFFFu;
    }
}

lumo_status lumo_raster_clear(lumo_raster_target *t, uint32_t rgb)
{
    lumo_status st = lumo_raster_target_check(t);
    size_t bytes;
    uint32_t y;

    if (st)
        return st;
    bytes = (size_t)t->width * pixel_bytes(t->format);
    clear_row(t, (uint8_t *)t->color, rgb);
    for (y = 1; y < t->band_rows; y++)
        memcpy((uint8_t *)t->color + (size_t)y * t->color_stride, t->color, bytes);
    memset(t->depth, 0, (size_t)t->width * t->band_rows * (t->depth_bits / 8u));
    return LUMO_OK;
}
