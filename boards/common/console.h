/*
 * console.h — printf-free text output on the board console
 * (board_console_write of boards/board.h), for every board and board program.
 *
 * newlib's printf pulls in malloc through _sbrk; these few calls format
 * strings and integers by hand instead, so a board program links without any
 * heap. Every call writes immediately (no buffer to flush before a fault).
 */
#ifndef LUMO_BOARD_CONSOLE_H
#define LUMO_BOARD_CONSOLE_H

#include <stdint.h>

void con_str(const char *s);
void con_u64(uint64_t v);                 /* decimal */
void con_i64(int64_t v);                  /* decimal with sign */
void con_hex(uint64_t v, unsigned digits);/* "0x" + exactly `digits` hex digits */
void con_nl(void);

#endif
