/* png_io.c — tone mapping (docs/scene-format.md) and PNG files via libpng's
 * simplified API. */
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo_server/reference.h"

/* IEC 61966-2-1 sRGB transfer function. */
static float srgb_encode(float v)
{
    return v <= 0.0031308f ? 12.92f * v : 1.055f * powf(v, 1.0f / 2.4f) - 0.055f;
}

uint8_t lumo_tonemap(float v, float exposure)
{
    v *= exposure;
    v = isnan(v) ? 0.0f : fminf(fmaxf(v, 0.0f), 1.0f);
    return (uint8_t)lrintf(255.0f * srgb_encode(v));
}

int lumo_png_write(const char *path, const lumo_image *img, float exposure, char *err, size_t errlen)
{
    size_t n = (size_t)img->w * (size_t)img->h * 3;
    uint8_t *px = malloc(n ? n : 1);
    png_image pi;
    if (!px) {
        snprintf(err, errlen, "%s: out of memory", path);
        return -1;
    }
    for (size_t i = 0; i < n; i++)
        px[i] = lumo_tonemap(img->rgb[i], exposure);
    memset(&pi, 0, sizeof pi);
    pi.version = PNG_IMAGE_VERSION;
    pi.width = (png_uint_32)img->w;
    pi.height = (png_uint_32)img->h;
    pi.format = PNG_FORMAT_RGB;
    int ok = png_image_write_to_file(&pi, path, 0, px, 0, NULL);
    free(px);
    if (!ok) {
        snprintf(err, errlen, "%s: cannot write PNG: %s", path, pi.message);
        return -1;
    }
    return 0;
}

int lumo_png_read(const char *path, uint8_t **rgb8, int *w, int *h)
{
    png_image pi;
    memset(&pi, 0, sizeof pi);
    pi.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&pi, path))
        return -1;
    pi.format = PNG_FORMAT_RGB;
    *rgb8 = malloc(PNG_IMAGE_SIZE(pi));
    if (!*rgb8 || !png_image_finish_read(&pi, NULL, *rgb8, 0, NULL)) {
        free(*rgb8);
        png_image_free(&pi);
        return -1;
    }
    *w = (int)pi.width;
    *h = (int)pi.height;
    return 0;
}
