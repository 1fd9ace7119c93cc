/* fact_overflow.c — unbounded recursion with a 1 KiB frame: the MPU guard
 * below the stack must stop it with "FAULT: stack overflow" and exit 132
 * (MemManage) before it reaches .bss, whose canary must never change. */
#include <stdint.h>
#include "console.h"

int main(void);

static volatile uint32_t g_canary = 0xC0FFEEu;

static uint32_t deep(uint32_t n)
{
    volatile uint8_t frame[1024];
    frame[n % sizeof frame] = (uint8_t)n;
    if (g_canary != 0xC0FFEEu) {
        con_str("fact_overflow: .bss overwritten\n");
        return 0;
    }
    return deep(n + 1) + frame[(n * 7u) % sizeof frame];
}

int main(void)
{
    con_str("fact_overflow: recursing\n");
    return (int)deep(0) | 1;
}
