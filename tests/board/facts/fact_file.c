/* fact_file.c — semihosting file I/O on the host (target=native): write
 * FACT_FILE_PATH (relative to QEMU's working directory), read it back,
 * compare, check the error codes; exit 0 only when all hold. */
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include "board.h"
#include "console.h"

int main(void);

#ifndef FACT_FILE_PATH
#define FACT_FILE_PATH "build/board/mps2-an385/facts/fact_file.bin"
#endif

int main(void)
{
    static uint8_t out[3000], in[4096];
    size_t i, len = 0;

    for (i = 0; i < sizeof out; i++)
        out[i] = (uint8_t)(i * 7u + 3u);
    if (board_write_file(FACT_FILE_PATH, out, sizeof out) != 0) {
        con_str("fact_file: write failed\n");
        return 1;
    }
    if (board_read_file(FACT_FILE_PATH, in, sizeof in, &len) != 0 || len != sizeof out
        || memcmp(in, out, len) != 0) {
        con_str("fact_file: read back differs\n");
        return 1;
    }
    if (board_read_file(FACT_FILE_PATH, in, 100, &len) != -2
        || board_read_file("build/board/mps2-an385/facts/no-such-file", in, sizeof in, &len) != -1) {
        con_str("fact_file: error codes wrong\n");
        return 1;
    }
    con_str("fact_file: 3000 bytes written and read back\n");
    return 0;
}
