/*
 * scratch.c — board_scratch() on mps2-an385: the whole 16 MiB PSRAM at
 * 0x21000000 (section .psram, NOLOAD in mps2-an385.ld, so it costs nothing
 * to load or clear).
 */
#include <stddef.h>
#include <stdint.h>
#include "board_io.h"

#define PSRAM_BYTES (16u << 20)

__attribute__((section(".psram"), aligned(8)))
static uint8_t g_psram[PSRAM_BYTES];

uint8_t *board_scratch(size_t *bytes)
{
    *bytes = sizeof g_psram;
    return g_psram;
}
