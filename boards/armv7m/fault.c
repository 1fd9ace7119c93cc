/*
 * fault.c — the exceptions of any ARMv7-M board: every one of them (the
 * vector table of startup.c) prints its name and the faulting pc on the
 * console and exits with status 128 + exception number (HardFault 131,
 * MemManage 132, BusFault 133, UsageFault 134), so a crash can never hang
 * CI. An overflow into the MPU guard below the stack is reported as
 * "FAULT: stack overflow"; the handler runs on its own small stack for that
 * reason.
 */
#include <stdint.h>
#include "board.h"
#include "console.h"
#include "armv7m.h"

void armv7m_fault_report(const uint32_t *frame, uint32_t exc_return);

/* Fault status (ARMv7-M ARM B3.2): CFSR says which MemManage/Bus/Usage
 * fault, HFSR why HardFault. */
#define SCB_CFSR   (*(volatile const uint32_t *)0xE000ED28u)
#define SCB_HFSR   (*(volatile const uint32_t *)0xE000ED2Cu)

/* The fault handler's own stack (the main one may be what overflowed). */
uint32_t armv7m_fault_stack[128];

/* Naked so that no prologue moves the stack before the exception frame
 * (r0-r3, r12, lr, pc, xpsr) is located: EXC_RETURN bit 2 says whether it
 * was pushed on the main or the process stack. Then the handler switches
 * to its own stack. */
__attribute__((naked)) void Fault_Handler(void)
{
    __asm__ volatile(
        "tst lr, #4\n"
        "ite eq\n"
        "mrseq r0, msp\n"
        "mrsne r0, psp\n"
        "mov r1, lr\n"
        "ldr r2, =armv7m_fault_stack + 512\n"
        "mov sp, r2\n"
        "b armv7m_fault_report\n");
}

static const char *exception_name(uint32_t n)
{
    static const char *const names[16] = {
        "thread", "reset", "NMI", "HardFault", "MemManage", "BusFault", "UsageFault",
        "reserved", "reserved", "reserved", "reserved", "SVCall", "DebugMonitor",
        "reserved", "PendSV", "SysTick"
    };
    return n < 16 ? names[n] : "interrupt";
}

/* CFSR.MSTKERR: the exception frame could not be pushed (stack overflow
 * into the guard), so there is no frame to read. */
#define CFSR_MSTKERR (1u << 4)

/* The exception frame (8 words pushed below the faulting sp) in the guard,
 * or just below it: a function frame that moved sp from above the guard to
 * its lowest 32 bytes faults on its own store into the guard, while the
 * exception's words land below the guard's region, which the MPU lets
 * through (fact_overflow hits either case, depending on where main's stack
 * starts). Up to STACK_GUARD below: larger frames could jump the guard
 * without touching it (docs/porting.md). */
static int in_guard(const uint32_t *frame)
{
    uintptr_t f = (uintptr_t)frame, lo = (uintptr_t)__stack_paint_low;
    return f + STACK_GUARD >= lo && f < lo + STACK_GUARD + 32u;
}

void armv7m_fault_report(const uint32_t *frame, uint32_t exc_return)
{
    uint32_t ipsr;

    __asm__ volatile("mrs %0, ipsr" : "=r"(ipsr));
    ipsr &= 0x1FFu;
    con_str("FAULT: ");
    if ((SCB_CFSR & CFSR_MSTKERR) != 0 || in_guard(frame)) {
        con_str("stack overflow (");
        con_str(exception_name(ipsr));
        con_str(", sp=");
        con_hex((uint32_t)(uintptr_t)frame, 8);
        con_str(")");
        con_nl();
        board_exit((int)(128u + ipsr));
    }
    con_str(exception_name(ipsr));
    con_str(" pc=");
    con_hex(frame[6], 8);
    con_str(" lr=");
    con_hex(frame[5], 8);
    con_str(" cfsr=");
    con_hex(SCB_CFSR, 8);
    con_str(" hfsr=");
    con_hex(SCB_HFSR, 8);
    con_str(" exc_return=");
    con_hex(exc_return, 8);
    con_nl();
    board_exit((int)(128u + ipsr));
}
