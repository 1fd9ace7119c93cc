/*
 * png_io.h — 8-bit RGB PNG files through libpng's simplified API, for the
 * desktop tools (reference renderer, lumo-render, lumo-compare). Files are
 * written with an sRGB chunk; the bytes do not depend on which tool wrote
 * them.
 */
#ifndef HOST_PNG_IO_H
#define HOST_PNG_IO_H

#include <stddef.h>
#include <stdint.h>

/* Write w x h RGB8 pixels (rows from the top). 0 on success; else -1 and,
 * when err is not NULL, a message naming path in err. */
int host_png_write_rgb8(const char *path, const uint8_t *rgb, int w, int h, char *err, size_t errlen);

/* Tone map w x h x 3 linear radiance values (host_tonemap, tonemap.h) and
 * write them as above. 0, or -1 with a message in err (may be NULL). */
int host_png_write_radiance(const char *path, const float *rgb, int w, int h, float exposure, char *err,
                            size_t errlen);

/* Most pixels of a PNG read: 2^26 (an 8192 x 8192 picture, 192 MiB as
 * RGB8). A PNG header may declare up to 2^31 - 1 per side over a few
 * hundred bytes of deflated zeros; the buffer is sized from the header. */
#define HOST_PNG_MAX_PIXELS ((uint64_t)1 << 26)

/* Read any 8-bit PNG (grey, RGB, alpha dropped) as RGB8 into *rgb
 * (malloc'ed, w*h*3, caller frees). 0 on success, -1 otherwise (not a
 * PNG, damaged, or more than HOST_PNG_MAX_PIXELS pixels). */
int host_png_read_rgb8(const char *path, uint8_t **rgb, int *w, int *h);

#endif
