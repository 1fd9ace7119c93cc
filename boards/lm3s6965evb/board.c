/*
 * board.c — the lm3s6965evb parts of boards/board.h (the rest is the
 * ARMv7-M family code of boards/armv7m/: startup, faults, semihosting):
 * no cost timer, and scratch memory is a static array inside the 64 KiB
 * SRAM, sized so .bss + stack still fit (lm3s6965evb.ld checks it); no
 * link.
 */
#include <stddef.h>
#include <stdint.h>
#include "board.h"

#ifndef LM3S_SCRATCH_BYTES
#define LM3S_SCRATCH_BYTES (48u << 10)
#endif

uint32_t board_ticks(void)
{
    return 0;
}

uint32_t board_tick_hz(void)
{
    return 0;
}

uint8_t *board_scratch(size_t *bytes)
{
    static uint8_t scratch[LM3S_SCRATCH_BYTES] __attribute__((aligned(8)));
    *bytes = sizeof scratch;
    return scratch;
}

/* No link: the 64 KiB board runs the IVG programs, not the streaming
 * client (its UART0 would be a PL011 at 0x4000C000). */
int board_link_write(const uint8_t *buf, size_t n)
{
    (void)buf;
    (void)n;
    return -1;
}

int32_t board_link_read(uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    (void)buf;
    (void)cap;
    (void)timeout_ms;
    return -1;
}
