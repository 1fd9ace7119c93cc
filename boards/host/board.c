/*
 * board.c — the Linux board: boards/board.h on the host, so the same board
 * programs run natively (under ASan/UBSan) and a golden program's host hash
 * can be compared with the board's. Console on stdout, files through stdio,
 * scratch memory a 16 MiB static array, no ticks and no stack measure, the
 * command line from /proc/self/cmdline. The link is a file of its own:
 * link_tcp.c here (a TCP connection to LUMO_LINK=HOST:PORT), or the USB
 * gadget's boards/linux-gadget/link_ffs.c, which reuses this file for the
 * rest. Desktop code: stdio and POSIX allowed.
 */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "board.h"

void board_console_write(const char *s, size_t n)
{
    fwrite(s, 1, n, stdout);
    fflush(stdout);
}

void board_exit(int status)
{
    exit(status);
}

int board_read_file(const char *path, uint8_t *buf, size_t cap, size_t *len)
{
    FILE *f = fopen(path, "rb");
    size_t n;
    int extra;

    if (f == NULL)
        return -1;
    n = fread(buf, 1, cap, f);
    extra = fgetc(f);
    fclose(f);
    if (extra != EOF)
        return -2;
    *len = n;
    return 0;
}

int board_write_file(const char *path, const uint8_t *buf, size_t len)
{
    FILE *f = fopen(path, "wb");
    int rc;

    if (f == NULL)
        return -1;
    rc = fwrite(buf, 1, len, f) == len ? 0 : -1;
    return fclose(f) == 0 ? rc : -1;
}

uint32_t board_ticks(void)
{
    return 0;
}

uint32_t board_tick_hz(void)
{
    return 0;
}

uint8_t *board_scratch(size_t *bytes)
{
    static uint8_t scratch[16u << 20];
    *bytes = sizeof scratch;
    return scratch;
}

size_t board_stack_peak(void)
{
    return 0;
}

/* argv as written by the kernel: NUL-separated words. */
int board_cmdline(char *buf, size_t cap)
{
    FILE *f = fopen("/proc/self/cmdline", "rb");
    size_t n, i;

    if (f == NULL || cap == 0)
        return f ? fclose(f), -1 : -1;
    n = fread(buf, 1, cap, f);
    fclose(f);
    if (n == 0 || n == cap)
        return -1;
    for (i = 0; i + 1 < n; i++)
        if (buf[i] == '\0')
            buf[i] = ' ';
    buf[n - 1] = '\0';
    return 0;
}

/* Nothing to keep on show: done. */
void board_hold(void)
{
    exit(0);
}
