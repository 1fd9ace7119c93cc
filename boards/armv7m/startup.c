/*
 * startup.c — reset and exceptions of any ARMv7-M board (mps2-an385,
 * lm3s6965evb).
 *
 * QEMU loads the ELF and then boots like the hardware: the initial stack
 * pointer and the reset vector are the first two words at address 0 (the
 * vector table, placed there by the board's linker script, which also
 * defines the symbols used below: __data_load, __data_start, __data_end,
 * __bss_start, __bss_end, __stack_top, __stack_paint_low). Reset copies .data from its
 * load address, zeroes .bss, paints the stack to measure its peak, runs
 * main() and exits QEMU with main's return value through semihosting.
 * Every exception goes to Fault_Handler (fault.c).
 *
 * The stack is bounded: the lowest STACK_GUARD bytes of the stack area
 * (from __stack_paint_low) are made inaccessible with the ARMv7-M MPU, so
 * overflowing it raises MemManage ("FAULT: stack overflow", exit 132)
 * instead of silently overwriting .bss.
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include "board.h"
#include "armv7m.h"
#include "stack_paint.h"

int main(void);
void Reset_Handler(void);

/* Symbols of the linker script (addresses only). */
extern uint32_t __data_load[], __data_start[], __data_end[];
extern uint32_t __bss_start[], __bss_end[];

/* Index 0 is the initial stack pointer; 1 reset; 2..15 system exceptions.
 * The AN385 interrupts (16..47) are never enabled by the board programs. */
typedef void (*vector)(void);
__attribute__((section(".vectors"), used))
static const vector g_vectors[16] = {
    (vector)(uintptr_t)__stack_top,
    Reset_Handler,
    Fault_Handler, /* NMI */
    Fault_Handler, /* HardFault */
    Fault_Handler, /* MemManage */
    Fault_Handler, /* BusFault */
    Fault_Handler, /* UsageFault */
    0, 0, 0, 0,
    Fault_Handler, /* SVCall */
    Fault_Handler, /* DebugMonitor */
    0,
    Fault_Handler, /* PendSV */
    Fault_Handler  /* SysTick */
};

/* ARMv7-M MPU and System Control Block registers (ARMv7-M ARM B3.2, B3.5). */
#define MPU_CTRL   (*(volatile uint32_t *)0xE000ED94u)
#define MPU_RNR    (*(volatile uint32_t *)0xE000ED98u)
#define MPU_RBAR   (*(volatile uint32_t *)0xE000ED9Cu)
#define MPU_RASR   (*(volatile uint32_t *)0xE000EDA0u)
#define SCB_SHCSR  (*(volatile uint32_t *)0xE000ED24u)
#define MPU_CTRL_ENABLE     1u
#define MPU_CTRL_PRIVDEFENA 4u         /* default memory map elsewhere */
#define RASR_XN             (1u << 28)
#define RASR_AP_NONE        (0u << 24)
#define RASR_SIZE(log2)     (((log2) - 1u) << 1)
#define RASR_ENABLE         1u
#define SHCSR_MEMFAULTENA   (1u << 16)

/* Region 0: no access, no execute, over the guard. */
static void guard_stack(void)
{
    MPU_RNR = 0;
    MPU_RBAR = (uint32_t)(uintptr_t)__stack_paint_low;
    MPU_RASR = RASR_XN | RASR_AP_NONE | RASR_SIZE(10u) | RASR_ENABLE;   /* 2^10 */
    MPU_CTRL = MPU_CTRL_ENABLE | MPU_CTRL_PRIVDEFENA;
    SCB_SHCSR |= SHCSR_MEMFAULTENA;
    __asm__ volatile("dsb\n isb" ::: "memory");
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
    size_t data = (size_t)((uintptr_t)__data_end - (uintptr_t)__data_start);
    size_t bss = (size_t)((uintptr_t)__bss_end - (uintptr_t)__bss_start);

    memcpy(__data_start, __data_load, data);
    memset(__bss_start, 0, bss);
    board_stack_paint(__stack_paint_low + STACK_GUARD / 4u, __stack_top);   /* above the guard */
    guard_stack();
    board_exit(main());
}
