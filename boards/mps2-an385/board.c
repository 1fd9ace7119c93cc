/*
 * timer.c — board_ticks() on mps2-an385: the CMSDK APB dual timer (timer 1
 * at 0x40002000) as a free-running 32-bit down-counter at the 25 MHz system
 * clock. QEMU drives it from its virtual clock; with `-icount shift=0` that
 * clock advances exactly 1 ns per guest instruction, so ticks * 40 is a
 * deterministic instruction count (docs/porting.md).
 */
#include <stdint.h>
#include "board_io.h"

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
