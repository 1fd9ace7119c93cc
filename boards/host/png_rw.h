/*
 * png_rw.h — 8-bit RGB PNG files through libpng (desktop tools).
 */
#ifndef LUMO_HOST_PNG_RW_H
#define LUMO_HOST_PNG_RW_H

#include <stdint.h>

/* Write w x h RGB8 pixels (top row first), with an sRGB chunk. 0 on success. */
int png_write_rgb(const char *path, const uint8_t *rgb, int w, int h);

/* Read any 8-bit PNG as RGB8 (malloc'ed, caller frees). 0 on success. */
int png_read_rgb(const char *path, uint8_t **rgb, int *w, int *h);

#endif
