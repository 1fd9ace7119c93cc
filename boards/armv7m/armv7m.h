/*
 * armv7m.h — what the ARMv7-M family files share (startup.c, fault.c): the
 * stack symbols of the board's linker script and the MPU guard below the
 * stack.
 */
#ifndef LUMO_ARMV7M_H
#define LUMO_ARMV7M_H

#include <stdint.h>

/* Symbols of the linker script (addresses only): the top of the stack and
 * the bottom of the area painted to measure its peak, which starts with
 * the guard. */
extern uint32_t __stack_top[], __stack_paint_low[];

/* MPU guard at the bottom of the stack area: 1 KiB, the linker scripts
 * keep __stack_paint_low 1 KiB aligned (an MPU region is size aligned). */
#define STACK_GUARD 1024u

/* Every exception of the vector table (fault.c). */
void Fault_Handler(void);

#endif
