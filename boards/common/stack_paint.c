/*
 * stack_paint.c — the stack's high-water mark of the bare-metal boards
 * (stack_paint.h).
 */
#include <stddef.h>
#include <stdint.h>
#include "board.h"
#include "stack_paint.h"

#define STACK_PAINT 0x5AC0FFEEu
/* Bytes below the painting frame left unpainted: the painter's own frame
 * and the call that got here must not be overwritten while it runs. */
#define PAINT_MARGIN 64u

static uint32_t *g_paint_low;
static const uint32_t *g_paint_top;

void board_stack_paint(uint32_t *low, const uint32_t *top)
{
    uint32_t here;   /* its address approximates the current stack pointer */
    uint32_t *p = low;
    uint32_t *end = (uint32_t *)((uintptr_t)&here - PAINT_MARGIN);

    g_paint_low = low;
    g_paint_top = top;
    while (p < end)
        *p++ = STACK_PAINT;
}

size_t board_stack_peak(void)
{
    const uint32_t *p = g_paint_low;

    if (p == NULL)
        return 0;
    while (p < g_paint_top && *p == STACK_PAINT)
        p++;
    return (size_t)((uintptr_t)g_paint_top - (uintptr_t)p);
}
