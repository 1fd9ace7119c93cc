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

#include <stddef.h>
#include <stdint.h>
#include "harness.h"

void golden_hash(const char *label, uint64_t h);
/* "COST <label> <instructions>" from board ticks since t0 (under
 * -icount shift=0 one tick of a 25 MHz timer is 40 instructions); prints
 * nothing on a board without ticks (the host). */
void golden_cost(const char *label, uint32_t t0);

/* "<prefix><file name of path>" into out (cap bytes, truncated). */
void golden_label(const char *prefix, const char *path, char *out, size_t cap);

/* Call each(path) for every non-empty line of the file list_path (at most
 * 8 KiB, lines up to 199 characters); returns the OR of the results, or 1
 * when the list cannot be read. The golden programs that work on files
 * read their inputs this way (board.mk writes the lists). */
int golden_each_path(const char *list_path, int (*each)(const char *path));

/* Print the board's stack peak (if it measures one) and return rc: the
 * last statement of a golden main(). */
int golden_done(int rc);

#endif
