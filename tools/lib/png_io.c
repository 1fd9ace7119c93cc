/*
 * png_io.c — see lumo_host/png_io.h. libpng's simplified API writes the
 * sRGB chunk for 8-bit non-linear data itself, and reads any PNG format
 * converted to RGB, so no setjmp error handling is needed here.
 */
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo_host/png_io.h"
#include "lumo_host/tonemap.h"

static void set_error(char *err, size_t errlen, const char *path, const char *what)
{
    if (err)
        snprintf(err, errlen, "%s: %s", path, what);
}

int host_png_write_rgb8(const char *path, const uint8_t *rgb, int w, int h, char *err, size_t errlen)
{
    png_image pi;
    char msg[128];

    memset(&pi, 0, sizeof pi);
    pi.version = PNG_IMAGE_VERSION;
    pi.width = (png_uint_32)w;
    pi.height = (png_uint_32)h;
    pi.format = PNG_FORMAT_RGB;
    if (png_image_write_to_file(&pi, path, 0, rgb, 0, NULL))
        return 0;
    snprintf(msg, sizeof msg, "cannot write PNG: %s", pi.message);
    set_error(err, errlen, path, msg);
    return -1;
}

int host_png_write_radiance(const char *path, const float *rgb, int w, int h, float exposure, char *err,
                            size_t errlen)
{
    uint8_t *px = host_tonemap_rgb8(rgb, (size_t)w * (size_t)h * 3, exposure);
    int rc;

    if (!px) {
        set_error(err, errlen, path, "out of memory");
        return -1;
    }
    rc = host_png_write_rgb8(path, px, w, h, err, errlen);
    free(px);
    return rc;
}

int host_png_read_rgb8(const char *path, uint8_t **rgb, int *w, int *h)
{
    png_image pi;
    uint8_t *buf;

    memset(&pi, 0, sizeof pi);
    pi.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&pi, path))
        return -1;
    pi.format = PNG_FORMAT_RGB;
    if ((uint64_t)pi.width * pi.height > HOST_PNG_MAX_PIXELS) {
        png_image_free(&pi);
        return -1;
    }
    buf = malloc(PNG_IMAGE_SIZE(pi));
    if (!buf || !png_image_finish_read(&pi, NULL, buf, 0, NULL)) {
        free(buf);
        png_image_free(&pi);
        return -1;
    }
    *rgb = buf;
    *w = (int)pi.width;
    *h = (int)pi.height;
    return 0;
}
