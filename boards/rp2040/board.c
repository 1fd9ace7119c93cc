/*
 * board.c — the RP2040 parts of boards/board.h (console, exit, files and
 * command line come over semihosting, boards/armv7m/semihost.c: the same
 * `bkpt 0xab` on ARMv6-M, answered by the debugger):
 *   clock  the 12 MHz crystal (XOSC) drives clk_ref, clk_sys and clk_peri;
 *          the watchdog tick divides clk_ref to 1 MHz for the 64-bit
 *          TIMER, whose low word is board_ticks (microseconds);
 *   link   UART0 (PL011) on GPIO0 (TX) / GPIO1 (RX), 115200 8N1, polled;
 *   memory scratch is a static array in SRAM (RP2040_SCRATCH_BYTES).
 * Register addresses and fields: RP2040 datasheet §2.14 (subsystem
 * resets), §2.15-2.16 (clocks, XOSC), §4.6-4.7 (timer, watchdog tick),
 * §4.2 (UART), §2.19 (IO bank 0).
 */
#include <stddef.h>
#include <stdint.h>
#include "board.h"

#ifndef RP2040_SCRATCH_BYTES
#define RP2040_SCRATCH_BYTES (128u << 10)
#endif

#define REG(addr) (*(volatile uint32_t *)(addr))
#define CLR(addr) REG((addr) + 0x3000u)    /* atomic bit-clear alias */

#define RESETS          0x4000C000u
#define RESETS_RESET    (RESETS + 0x0u)
#define RESETS_DONE     (RESETS + 0x8u)
#define RESET_IO_BANK0  (1u << 5)
#define RESET_PADS0     (1u << 8)
#define RESET_TIMER     (1u << 21)
#define RESET_UART0     (1u << 22)

#define XOSC_CTRL       0x40024000u
#define XOSC_STATUS     0x40024004u
#define XOSC_STARTUP    0x4002400Cu
#define XOSC_1_15MHZ    0xAA0u
#define XOSC_ENABLE     (0xFABu << 12)
#define XOSC_STABLE     (1u << 31)
#define XOSC_HZ         12000000u

#define CLK_REF_CTRL    0x40008030u
#define CLK_REF_SELECT  0x40008038u
#define CLK_SYS_CTRL    0x4000803Cu
#define CLK_SYS_SELECT  0x40008044u
#define CLK_PERI_CTRL   0x40008048u
#define CLK_REF_XOSC    2u                  /* CLK_REF_CTRL.SRC */
#define CLK_PERI_ENABLE (1u << 11)          /* AUXSRC 0: clk_sys */

#define WATCHDOG_TICK   0x4005802Cu
#define TICK_ENABLE     (1u << 9)
#define TIMER_RAWL      0x40054028u

#define IO_GPIO_CTRL(n) (0x40014004u + 8u * (n))
#define FUNC_UART       2u

#define UART0           0x40034000u
#define UART_DR         (UART0 + 0x00u)
#define UART_FR         (UART0 + 0x18u)
#define UART_IBRD       (UART0 + 0x24u)
#define UART_FBRD       (UART0 + 0x28u)
#define UART_LCR_H      (UART0 + 0x2Cu)
#define UART_CR         (UART0 + 0x30u)
#define FR_RXFE         (1u << 4)
#define FR_TXFF         (1u << 5)
#define LCR_8N1_FIFO    0x70u               /* WLEN 8 bits, FEN */
#define CR_ENABLE       0x301u              /* UARTEN, TXE, RXE */
#define BAUD            115200u

static int g_ready;

/* XOSC on, clk_ref and clk_sys from it (clk_sys via clk_ref), clk_peri on. */
static void start_clocks(void)
{
    REG(XOSC_CTRL) = XOSC_1_15MHZ;
    REG(XOSC_STARTUP) = (XOSC_HZ / 1000u + 128u) / 256u;   /* ~1 ms */
    REG(XOSC_CTRL) = XOSC_1_15MHZ | XOSC_ENABLE;
    while (!(REG(XOSC_STATUS) & XOSC_STABLE))
        ;
    REG(CLK_REF_CTRL) = CLK_REF_XOSC;
    while (!(REG(CLK_REF_SELECT) & (1u << CLK_REF_XOSC)))
        ;
    REG(CLK_SYS_CTRL) = 0;                  /* SRC clk_ref */
    while (!(REG(CLK_SYS_SELECT) & 1u))
        ;
    REG(CLK_PERI_CTRL) = CLK_PERI_ENABLE;
    REG(WATCHDOG_TICK) = TICK_ENABLE | (XOSC_HZ / 1000000u);
}

/* IBRD.FBRD = clk_peri / (16 baud), the fraction in 64ths, rounded. */
static void start_uart(void)
{
    uint32_t div64 = (8u * XOSC_HZ / BAUD + 1u) / 2u;   /* 64 * clk / (16 baud) */

    REG(IO_GPIO_CTRL(0)) = FUNC_UART;
    REG(IO_GPIO_CTRL(1)) = FUNC_UART;
    REG(UART_IBRD) = div64 >> 6;
    REG(UART_FBRD) = div64 & 63u;
    REG(UART_LCR_H) = LCR_8N1_FIFO;         /* written after the divisors */
    REG(UART_CR) = CR_ENABLE;
}

static void start(void)
{
    uint32_t bits = RESET_IO_BANK0 | RESET_PADS0 | RESET_TIMER | RESET_UART0;

    if (g_ready)
        return;
    start_clocks();
    CLR(RESETS_RESET) = bits;
    while ((REG(RESETS_DONE) & bits) != bits)
        ;
    start_uart();
    g_ready = 1;
}

uint32_t board_ticks(void)
{
    start();
    return REG(TIMER_RAWL);
}

uint32_t board_tick_hz(void)
{
    return 1000000u;
}

uint8_t *board_scratch(size_t *bytes)
{
    static uint8_t scratch[RP2040_SCRATCH_BYTES] __attribute__((aligned(8)));
    *bytes = sizeof scratch;
    return scratch;
}

int board_link_write(const uint8_t *buf, size_t n)
{
    size_t i;

    start();
    for (i = 0; i < n; i++) {
        while (REG(UART_FR) & FR_TXFF)
            ;
        REG(UART_DR) = buf[i];
    }
    return 0;
}

/* What is in the FIFO, waiting up to timeout_ms for the first byte. */
int32_t board_link_read(uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    uint32_t t0;
    size_t n = 0;

    start();
    t0 = REG(TIMER_RAWL);
    while (REG(UART_FR) & FR_RXFE)
        if (REG(TIMER_RAWL) - t0 >= timeout_ms * 1000u)
            return 0;
    while (n < cap && !(REG(UART_FR) & FR_RXFE))
        buf[n++] = (uint8_t)REG(UART_DR);
    return (int32_t)n;
}

