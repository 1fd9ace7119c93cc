/*
 * grey4.h — an RGB565 band reduced to a 16-level grey screen (the
 * lm3s6965evb's SSD0323 OLED, boards/board.h board_display_grey4), the same
 * on every board so the host can predict the board's screen bit for bit.
 *
 * Luma Y = (77 R + 150 G + 29 B + 128) >> 8 of the 8-bit channels (RGB565
 * widened by bit replication, BT.601 weights summing to 256), then
 * level = (15 Y + t) / 255 with t the 4x4 Bayer threshold of the pixel's
 * screen position, (2 b + 1) * 255 / 32 for Bayer index b: an ordered
 * dither whose mean over a 4x4 tile is 15 Y / 255 (docs/porting.md §8).
 */
#ifndef LUMO_BOARD_GREY4_H
#define LUMO_BOARD_GREY4_H

#include <stdint.h>

/* Rows y0 .. y0 + rows - 1 of a w-pixel-wide picture (w even), `band` the
 * RGB565 pixels row by row, into w / 2 bytes a row at out: two pixels a
 * byte, the left one in the high nibble. */
void grey4_band(const uint16_t *band, uint16_t w, uint16_t rows, uint16_t y0, uint8_t *out);

#endif
