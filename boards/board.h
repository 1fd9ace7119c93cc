/*
 * board.h — the board contract: what every board gives the programs that run
 * on it (the board tests and golden programs of tests/board/, a device's
 * application).
 *
 * Every board port (boards/mps2-an385 and boards/lm3s6965evb over QEMU
 * semihosting, the Linux board boards/host, a real board over its UART)
 * implements these few calls; a board program uses nothing else, so the same
 * C99 program runs everywhere. No heap, no stdio, no float: the rules of the
 * client code apply (docs/porting.md, which also says what a new board must
 * provide).
 */
#ifndef LUMO_BOARD_H
#define LUMO_BOARD_H

#include <stddef.h>
#include <stdint.h>

/* Write n bytes of text to the board's console (QEMU: semihosting, which
 * QEMU prints on its stderr; host: stdout). */
void board_console_write(const char *s, size_t n);

/* End the program with `status` (0 = success). Never returns. On QEMU this is
 * SYS_EXIT_EXTENDED, so qemu-system-arm exits with `status` (mod 256). */
void board_exit(int status);

/* Read the whole file `path` (host path relative to QEMU's working directory)
 * into buf[0..cap). *len gets its size. Returns 0 on success, -1 when it
 * cannot be opened or read, -2 when it does not fit in cap bytes. */
int board_read_file(const char *path, uint8_t *buf, size_t cap, size_t *len);

/* Create or truncate `path` on the host and write len bytes. 0 or -1. */
int board_write_file(const char *path, const uint8_t *buf, size_t len);

/* A free-running counter for cost measurements, board_tick_hz() per second
 * of (virtual) time; 0 Hz when the board has none. On mps2-an385 it runs at
 * 25 MHz of QEMU's virtual clock, which with `-icount shift=0` advances 1 ns
 * per guest instruction: one tick = 40 instructions, and the count is the
 * same on every run (docs/porting.md). */
uint32_t board_ticks(void);
uint32_t board_tick_hz(void);

/* A large board-owned buffer for arenas (frame buffers, big grids): its
 * address, and its size in *bytes. Contents are undefined at start (the
 * arena zero-fills what it hands out). mps2-an385: the 16 MiB PSRAM at
 * 0x21000000; host: a 16 MiB static array. */
uint8_t *board_scratch(size_t *bytes);

/* Bytes of stack the program has used so far, measured by painting; 0 when
 * the board cannot tell. */
size_t board_stack_peak(void);

/* The program's command line: its name, then its arguments, separated by
 * single spaces, NUL-terminated in buf[0..cap). QEMU: the semihosting
 * command line (SYS_GET_CMDLINE: the -kernel path and the -append text);
 * host: argv. 0, or -1 when the board has none or it does not fit. */
int board_cmdline(char *buf, size_t cap);

/* ---- the link: a byte stream to the server --------------------------------
 * A serial line as the stream protocol sees it (docs/protocol.md §1: bytes
 * may be lost or garbled; the client resynchronises). mps2-an385: CMSDK
 * UART0, which QEMU connects to a chardev (`-serial chardev:ID`); host: a
 * TCP connection to LUMO_LINK=HOST:PORT (lumo-server --serial-listen);
 * lm3s6965evb: none. */

/* Send n bytes; returns once they are handed to the line. 0, or -1 when
 * the board has no link or it failed. */
int board_link_write(const uint8_t *buf, size_t n);

/* Receive up to cap bytes: waits up to timeout_ms for the first one, then
 * takes what follows without waiting. Returns the bytes read (0: none came
 * within the timeout), -1 when the board has no link or it closed, or
 * BOARD_LINK_NEW when the link was cut and is back as a new connection
 * whose peer knows nothing of the conversation (a USB gadget unplugged and
 * plugged again, boards/linux-gadget): bytes of the old one are gone, and
 * the program starts over with HELLO and the cursors it holds. */
#define BOARD_LINK_NEW (-2)
int32_t board_link_read(uint8_t *buf, size_t cap, uint32_t timeout_ms);

/* ---- the display: a board's own screen -------------------------------------
 * lm3s6965evb: the SSD0323 OLED (128 x 64, 16 grey levels, over SSI0);
 * the other boards have none (their pictures are hashed and written). */

/* Show rows y .. y + rows - 1 of the screen, `width` pixels each: 4-bit
 * grey, two pixels a byte, the left one in the high nibble, width / 2 bytes
 * a row (the SSD0323's own order). 0, or -1 when the board has no such
 * screen or the rows do not fit it. */
int board_display_grey4(uint16_t y, uint16_t rows, uint16_t width, const uint8_t *px);

/* Keep the screen as it is and wait for ever, as a device showing its last
 * picture (QEMU: until the test quits it through QMP). Never returns; a
 * board without a screen (host) exits with 0. */
void board_hold(void);

#endif /* LUMO_BOARD_H */
