/* console.c — printf-free console output (see console.h). */
#include <stddef.h>
#include <string.h>
#include "board.h"
#include "console.h"

void con_str(const char *s)
{
    board_console_write(s, strlen(s));
}

void con_nl(void)
{
    board_console_write("\n", 1);
}

void con_u64(uint64_t v)
{
    char buf[20];
    size_t i = sizeof buf;

    do {
        buf[--i] = (char)('0' + v % 10u);
        v /= 10u;
    } while (v != 0);
    board_console_write(buf + i, sizeof buf - i);
}

void con_i64(int64_t v)
{
    if (v < 0) {
        board_console_write("-", 1);
        /* negate in unsigned so INT64_MIN is defined */
        con_u64((uint64_t)0 - (uint64_t)v);
        return;
    }
    con_u64((uint64_t)v);
}

void con_hex(uint64_t v, unsigned digits)
{
    static const char hex[] = "0123456789abcdef";
    char buf[18];
    unsigned i;

    if (digits > 16)
        digits = 16;
    buf[0] = '0';
    buf[1] = 'x';
    for (i = 0; i < digits; i++)
        buf[2 + i] = hex[(v >> (4u * (digits - 1u - i))) & 15u];
    board_console_write(buf, 2 + digits);
}
