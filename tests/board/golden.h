/*
 * golden.h — helpers of the golden programs (tests/board/golden_*.c).
 *
 * A golden program computes a fixed workload with the client library and
 * prints one line "HASH <label> 0x<16 hex digits>" per stage (64-bit FNV-1a
 * of every output, bytes in a fixed order). board.mk builds it for the host
 * and for the board; the step fails unless both print identical HASH lines:
 * the proof that integer results are bit-exact across targets. "COST" lines
 * (board ticks) are informational and not compared.
 */
#ifndef LUMO_BOARD_GOLDEN_H
#define LUMO_BOARD_GOLDEN_H

#include <stdint.h>
#include "harness.h"

void golden_hash(const char *label, uint64_t h);
/* "COST <label> <instructions>" from board ticks since t0 (under
 * -icount shift=0 one tick of a 25 MHz timer is 40 instructions); prints
 * nothing on a board without ticks (the host). */
void golden_cost(const char *label, uint32_t t0);

/* Print the board's stack peak (if it measures one) and return rc: the
 * last statement of a golden main(). */
int golden_done(int rc);

#endif
