/*
 * startup.c — reset and exceptions of the RP2040 port (Cortex-M0+, ARMv6-M:
 * no MPU guard as on the ARMv7-M boards, no fault status registers, no
 * CLZ, no UDIV). The image is loaded into SRAM by a debugger (rp2040.ld),
 * which also sets sp and pc: reset points VTOR at this image's table,
 * zeroes .bss, paints the stack to measure its peak and runs main().
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include "board.h"
#include "console.h"
#include "stack_paint.h"

int main(void);
void Reset_Handler(void);
void rp2040_fault(void);

extern uint32_t __bss_start[], __bss_end[], __stack_top[], __stack_paint_low[];

#define SCB_VTOR    (*(volatile uint32_t *)0xE000ED08u)
/* 0 initial sp, 1 reset, 2 NMI, 3 HardFault (the only fault ARMv6-M has),
 * 11 SVCall, 14 PendSV, 15 SysTick; the RP2040's IRQs are never enabled. */
typedef void (*vector)(void);
__attribute__((section(".vectors"), used))
static const vector g_vectors[16] = {
    (vector)(uintptr_t)__stack_top, Reset_Handler, rp2040_fault, rp2040_fault,
    0, 0, 0, 0, 0, 0, 0, rp2040_fault, 0, 0, rp2040_fault, rp2040_fault
};

/* Any exception: say so and stop (HardFault is 3: status 131 as on the
 * ARMv7-M boards). */
void rp2040_fault(void)
{
    con_str("FAULT: HardFault");
    con_nl();
    board_exit(131);
}

/* The screen keeps its last picture; the core sleeps between interrupts
 * (none are enabled, so for ever: QEMU until it is quit). */
void board_hold(void)
{
    for (;;)
        __asm__ volatile("wfi");
}

void Reset_Handler(void)
{
    SCB_VTOR = (uint32_t)(uintptr_t)g_vectors;   /* the first thing in SRAM */
    memset(__bss_start, 0, (size_t)((uintptr_t)__bss_end - (uintptr_t)__bss_start));
    board_stack_paint(__stack_paint_low, __stack_top);
    board_exit(main());
}
