/*
 * stack_paint.h — the stack painting of the bare-metal boards' start-up
 * code (stack_paint.c); board_stack_peak (boards/board.h) reads it back.
 */
#ifndef BOARD_STACK_PAINT_H
#define BOARD_STACK_PAINT_H

#include <stdint.h>

/* Paint the stack from `low` (its lowest painted word) up to just below the
 * caller's frame; `top` is the stack's top (exclusive). Call once, from
 * reset, before main. */
void board_stack_paint(uint32_t *low, const uint32_t *top);

#endif
