/*
 * stack_paint.h — the stack's high-water mark on a bare-metal board.
 *
 * A start-up paints the free stack with a known word before main() runs;
 * board_stack_peak() (boards/board.h) later finds the lowest word that is
 * no longer the paint: the deepest the stack has been. Shared by every
 * bare-metal start-up (boards/armv7m/startup.c, boards/rp2040/startup.c);
 * hosted ports measure nothing and answer 0 themselves.
 */
#ifndef LUMO_BOARD_STACK_PAINT_H
#define LUMO_BOARD_STACK_PAINT_H

#include <stdint.h>

/* Paint the words from `low` up to a small margin below the caller's own
 * frame; `top` is the stack's top (its initial pointer). Call once, after
 * .bss is zeroed (the bounds are kept there) and before main(). */
void board_stack_paint(uint32_t *low, const uint32_t *top);

#endif
