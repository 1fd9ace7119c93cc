/*
 * board.c — the lm3s6965evb parts of boards/board.h (the rest is the
 * ARMv7-M family code of boards/armv7m/: startup, faults, semihosting), for
 * TI's Stellaris LM3S6965 (Cortex-M3, 12.5 MHz out of reset as QEMU's
 * `lm3s6965evb` models it, 64 KiB SRAM, 256 KiB flash), docs/porting.md §8:
 *
 *   scratch  a static array inside the 64 KiB SRAM, LM3S_SCRATCH_BYTES,
 *            sized so .bss + stack still fit (lm3s6965evb.ld checks it);
 *   link     UART0 (PL011 at 0x4000C000, FIFOs on), polled; QEMU connects it
 *            to lumo-server's serial listener with -serial chardev:ID;
 *   clock    none for costs (0 Hz): SysTick counts the milliseconds of a
 *            link read's timeout only;
 *   display  the SSD0323 OLED (128 x 64, 4-bit grey) on SSI0 (PL022 at
 *            0x40008000), data/command on GPIO C7, chip select SSI0Fss.
 *
 * Polled, no interrupts: what QEMU needs; a real board wants an RX
 * interrupt into a ring buffer (docs/porting.md §7, "The link").
 */
#include <stddef.h>
#include <stdint.h>
#include "board.h"

#ifndef LM3S_SCRATCH_BYTES
#define LM3S_SCRATCH_BYTES (48u << 10)
#endif

#define REG(a) (*(volatile uint32_t *)(a))
#define SYSCLK_HZ 12500000u   /* RCC's reset value: 200 MHz PLL / 16 */

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

/* ---- clocks and pins (LM3S6965 data sheet §6 System Control, §8 GPIO) ---- */

#define RCGC1          REG(0x400FE104u)   /* bit 0 UART0, bit 4 SSI0 */
#define RCGC2          REG(0x400FE108u)   /* bit 0 GPIO A, bit 2 GPIO C */
#define GPIOA_AFSEL    REG(0x40004420u)
#define GPIOA_DEN      REG(0x4000451Cu)
#define GPIOC_DIR      REG(0x40006400u)
#define GPIOC_DEN      REG(0x4000651Cu)
#define GPIOC_DATA(m)  REG(0x40006000u + ((uint32_t)(m) << 2))   /* masked access */
#define PA_UART0       0x03u   /* PA0 U0Rx, PA1 U0Tx */
#define PA_SSI0        0x2Cu   /* PA2 SSI0Clk, PA3 SSI0Fss (OLED select), PA5 SSI0Tx */
#define PC_OLED_DC     0x80u   /* PC7: 1 data, 0 command */
#define PC_OLED_POWER  0x40u   /* PC6: the panel's +15 V enable on the EVB */

static void pins_on(void)
{
    static int done;

    if (done)
        return;
    RCGC1 |= 0x11u;
    RCGC2 |= 0x05u;
    GPIOA_AFSEL |= PA_UART0 | PA_SSI0;
    GPIOA_DEN |= PA_UART0 | PA_SSI0;
    GPIOC_DIR |= PC_OLED_DC | PC_OLED_POWER;
    GPIOC_DEN |= PC_OLED_DC | PC_OLED_POWER;
    GPIOC_DATA(PC_OLED_POWER) = PC_OLED_POWER;
    done = 1;
}

/* ---- the link: UART0, a PL011 (QEMU hw/char/pl011.c, luminary variant) ---- */

#define UART0_DR    REG(0x4000C000u)
#define UART0_FR    REG(0x4000C018u)
#define UART0_IBRD  REG(0x4000C024u)
#define UART0_FBRD  REG(0x4000C028u)
#define UART0_LCRH  REG(0x4000C02Cu)
#define UART0_CR    REG(0x4000C030u)
#define FR_RXFE     0x10u
#define FR_TXFF     0x20u
#define LCRH_8N1    0x60u
#define LCRH_FEN    0x10u
#define CR_ON       0x301u   /* UARTEN, TXE, RXE */
#define LINK_BAUD   115200u

static void link_enable(void)
{
    uint32_t div64;

    if ((UART0_CR & CR_ON) == CR_ON)
        return;
    pins_on();
    /* 12.5 MHz / (16 x 115200) = 6.78: integer 6, fraction 50/64 */
    div64 = (SYSCLK_HZ * 4u + LINK_BAUD / 2u) / LINK_BAUD;
    UART0_IBRD = div64 >> 6;
    UART0_FBRD = div64 & 63u;
    UART0_LCRH = LCRH_8N1 | LCRH_FEN;
    UART0_CR = CR_ON;
}

int board_link_write(const uint8_t *buf, size_t n)
{
    size_t i;

    link_enable();
    for (i = 0; i < n; i++) {
        while (UART0_FR & FR_TXFF)
            ;
        UART0_DR = buf[i];
    }
    return 0;
}

/* SysTick on the core clock, wrapping every millisecond: COUNTFLAG (read
 * to clear) tells that one more has passed. */
#define SYST_CSR    REG(0xE000E010u)
#define SYST_RVR    REG(0xE000E014u)
#define SYST_CVR    REG(0xE000E018u)
#define CSR_ON      0x5u          /* ENABLE, CLKSOURCE = core */
#define CSR_COUNTED 0x10000u

static void ms_start(void)
{
    SYST_CSR = 0;
    SYST_RVR = SYSCLK_HZ / 1000u - 1u;
    SYST_CVR = 0;
    SYST_CSR = CSR_ON;
}

int32_t board_link_read(uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    uint32_t ms = 0;
    size_t n = 0;

    link_enable();
    ms_start();
    while (n < cap) {
        if ((UART0_FR & FR_RXFE) == 0u)
            buf[n++] = (uint8_t)UART0_DR;
        else if (n > 0 || ms >= timeout_ms)
            break;
        else if (SYST_CSR & CSR_COUNTED)
            ms++;
    }
    return (int32_t)n;
}

/* ---- the display: SSD0323 on SSI0, a PL022 (QEMU hw/ssi/pl022.c) ---- */

#define SSI0_CR0    REG(0x40008000u)
#define SSI0_CR1    REG(0x40008004u)
#define SSI0_DR     REG(0x40008008u)
#define SSI0_SR     REG(0x4000800Cu)
#define SSI0_CPSR   REG(0x40008010u)
#define SR_TNF      0x02u
#define SR_RNE      0x04u
#define CR0_8BIT    0x07u         /* Freescale SPI, mode 0, 8-bit frames */
#define CR1_SSE     0x02u
#define OLED_W      128u
#define OLED_H      64u

/* One byte out; its echo taken back so the receive FIFO never stalls the
 * transmitter (QEMU moves a frame only while the receive FIFO has room)
 * and the byte is on the wire before the D/C line may change. */
static void ssi_put(uint8_t b)
{
    while ((SSI0_SR & SR_TNF) == 0u)
        ;
    SSI0_DR = b;
    while ((SSI0_SR & SR_RNE) == 0u)
        ;
    (void)SSI0_DR;
}

static void oled_cmd(const uint8_t *p, size_t n)
{
    GPIOC_DATA(PC_OLED_DC) = 0;
    while (n--)
        ssi_put(*p++);
}

/* The panel's set-up (SSD0323 data sheet §8; QEMU keeps only the address
 * window and ignores the rest): columns are byte pairs of pixels. */
static void oled_on(void)
{
    static const uint8_t init[] = {
        0xAE,               /* display off while it is set up */
        0xA0, 0x52,         /* remap: left pixel in the high nibble, COM split */
        0xA1, 0x00,         /* start line */
        0xA2, 0x4C,         /* display offset of the 128 x 64 panel */
        0xA8, 0x3F,         /* 64 rows */
        0x81, 0x33,         /* contrast */
        0x84,               /* current range */
        0xA4,               /* normal display */
        0xAF,               /* display on */
    };
    static int done;

    if (done)
        return;
    pins_on();
    SSI0_CR1 = 0;
    SSI0_CPSR = 2u;
    SSI0_CR0 = CR0_8BIT;
    SSI0_CR1 = CR1_SSE;
    oled_cmd(init, sizeof init);
    done = 1;
}

int board_display_grey4(uint16_t y, uint16_t rows, uint16_t width, const uint8_t *px)
{
    uint8_t window[6] = {0x15, 0x00, OLED_W / 2u - 1u, 0x75, 0, 0};
    size_t i, n = (size_t)rows * (OLED_W / 2u);

    if (width != OLED_W || rows == 0 || (uint32_t)y + rows > OLED_H)
        return -1;
    oled_on();
    window[4] = (uint8_t)y;
    window[5] = (uint8_t)(y + rows - 1u);
    oled_cmd(window, sizeof window);
    GPIOC_DATA(PC_OLED_DC) = PC_OLED_DC;
    for (i = 0; i < n; i++)
        ssi_put(px[i]);
    return 0;
}
