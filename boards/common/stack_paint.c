/*
 * stack_paint.c — how deep the stack went, for every bare-metal board
 * (boards/armv7m/startup.c, boards/rp2040/startup.c): reset paints the
 * stack from its low end up to just below its own frame with a pattern, and
 * board_stack_peak (boards/board.h) finds the highest word the program has
 * overwritten since.
 */
#include <stddef.h>
#include <stdint.h>
#include "board.h"
#include "stack_paint.h"

#define STACK_PAINT 0x5AC0FFEEu
/* Bytes below the current frame left unpainted while painting. */
#define PAINT_MARGIN 64u

static uint32_t *g_paint_low;
static const uint32_t *g_top;

void board_stack_paint(uint32_t *low, const uint32_t *top)
{
    uint32_t here;   /* its address approximates the current stack pointer */
    uint32_t *p = low;
    uint32_t *end = (uint32_t *)((uintptr_t)&here - PAINT_MARGIN);

    g_paint_low = low;
    g_top = top;
    while (p < end)
        *p++ = STACK_PAINT;
}

size_t board_stack_peak(void)
{
    const uint32_t *p = g_paint_low;

    if (p == NULL)
        return 0;
    while (p < g_top && *p == STACK_PAINT)
        p++;
    return (size_t)((uintptr_t)g_top - (uintptr_t)p);
}
