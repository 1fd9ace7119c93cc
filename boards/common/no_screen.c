/*
 * no_screen.c — board_display_grey4 (boards/board.h) for a port without a
 * screen: the AN385 image as QEMU models it, the RP2040 port (an SPI panel
 * could take a band at a time) and the host. Their pictures are hashed and
 * written to files instead (boards/client/client.c --out); the client
 * ignores the refusal.
 */
#include <stdint.h>
#include "board.h"

int board_display_grey4(uint16_t y, uint16_t rows, uint16_t width, const uint8_t *px)
{
    (void)y;
    (void)rows;
    (void)width;
    (void)px;
    return -1;
}
