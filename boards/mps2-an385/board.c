/*
 * board.c — the mps2-an385 parts of boards/board.h (the rest is the ARMv7-M
 * family code of boards/armv7m/: startup, faults, semihosting).
 *
 * board_ticks(): the CMSDK APB dual timer (timer 1 at 0x40002000) as a
 * free-running 32-bit down-counter at the 25 MHz system clock. QEMU drives
 * it from its virtual clock; with `-icount shift=0` that clock advances
 * exactly 1 ns per guest instruction, so ticks * 40 is a deterministic
 * instruction count (docs/porting.md).
 *
 * board_scratch(): the whole 16 MiB PSRAM at 0x21000000 (section .psram,
 * NOLOAD in mps2-an385.ld, so it costs nothing to load or clear).
 */
#include <stddef.h>
#include <stdint.h>
#include "board.h"

#define DUALTIMER1_LOAD    (*(volatile uint32_t *)0x40002000u)
#define DUALTIMER1_VALUE   (*(volatile const uint32_t *)0x40002004u)
#define DUALTIMER1_CONTROL (*(volatile uint32_t *)0x40002008u)
#define CTRL_ENABLE 0x80u
#define CTRL_32BIT  0x02u   /* free-running mode: periodic bit 6 left clear */
#define SYSCLK_HZ   25000000u

uint32_t board_ticks(void)
{
    if ((DUALTIMER1_CONTROL & CTRL_ENABLE) == 0) {
        DUALTIMER1_LOAD = 0xFFFFFFFFu;
        DUALTIMER1_CONTROL = CTRL_ENABLE | CTRL_32BIT;
    }
    return 0xFFFFFFFFu - DUALTIMER1_VALUE;
}

uint32_t board_tick_hz(void)
{
    return SYSCLK_HZ;
}

#define PSRAM_BYTES (16u << 20)

__attribute__((section(".psram"), aligned(8)))
static uint8_t g_psram[PSRAM_BYTES];

uint8_t *board_scratch(size_t *bytes)
{
    *bytes = sizeof g_psram;
    return g_psram;
}

/* ---- the link: CMSDK APB UART0, polled (QEMU hw/char/cmsdk-apb-uart.c) ---- */

#define UART0_DATA    (*(volatile uint32_t *)0x40004000u)
#define UART0_STATE   (*(volatile uint32_t *)0x40004004u)
#define UART0_CTRL    (*(volatile uint32_t *)0x40004008u)
#define UART0_BAUDDIV (*(volatile uint32_t *)0x40004010u)
#define STATE_TXFULL  0x1u
#define STATE_RXFULL  0x2u
#define CTRL_TX_RX_EN 0x3u
#define LINK_BAUD     115200u

static void link_enable(void)
{
    if ((UART0_CTRL & CTRL_TX_RX_EN) != CTRL_TX_RX_EN) {
        UART0_BAUDDIV = SYSCLK_HZ / LINK_BAUD;   /* >= 16, or QEMU logs an error */
        UART0_CTRL = CTRL_TX_RX_EN;
    }
}

int board_link_write(const uint8_t *buf, size_t n)
{
    size_t i;

    link_enable();
    for (i = 0; i < n; i++) {
        while (UART0_STATE & STATE_TXFULL)
            ;
        UART0_DATA = buf[i];
    }
    return 0;
}

int32_t board_link_read(uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    uint32_t t0 = board_ticks(), limit = timeout_ms * (SYSCLK_HZ / 1000u);
    size_t n = 0;

    link_enable();
    while (n < cap) {
        if (UART0_STATE & STATE_RXFULL)
            buf[n++] = (uint8_t)UART0_DATA;
        else if (n > 0 || board_ticks() - t0 >= limit)
            break;
    }
    return (int32_t)n;
}
