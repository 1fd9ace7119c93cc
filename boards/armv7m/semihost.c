/*
 * semihost.c — the console, exit and file calls of boards/board.h for any
 * ARMv7-M board over ARM semihosting: `bkpt 0xab` with the operation in r0
 * and a parameter block in r1 (ARM "Semihosting for AArch32 and AArch64",
 * v2). QEMU serves it when started with
 * `-semihosting-config enable=on,target=native`.
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include "board.h"
#include "semihost.h"

enum {
    SYS_OPEN = 0x01, SYS_CLOSE = 0x02, SYS_WRITE0 = 0x04, SYS_WRITE = 0x05,
    SYS_READ = 0x06, SYS_FLEN = 0x0C, SYS_GET_CMDLINE = 0x15, SYS_EXIT_EXTENDED = 0x20
};
/* Open modes are the indices of fopen's strings "r","rb","r+",... */
enum { MODE_RB = 1, MODE_WB = 5, MODE_A = 8 };
/* ADP_Stopped_ApplicationExit: with SYS_EXIT_EXTENDED its subcode becomes
 * QEMU's exit status. */
#define ADP_STOPPED_APPLICATION_EXIT 0x20026u

int32_t armv7m_semihost_call(uint32_t op, const void *arg)
{
    register uint32_t r0 __asm__("r0") = op;
    register const void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
    return (int32_t)r0;
}

static int32_t sh_open(const char *path, uint32_t mode)
{
    uint32_t blk[3];
    blk[0] = (uint32_t)(uintptr_t)path;
    blk[1] = mode;
    blk[2] = (uint32_t)strlen(path);
    return armv7m_semihost_call(SYS_OPEN, blk);
}

static void sh_close(int32_t fd)
{
    uint32_t blk[1];
    blk[0] = (uint32_t)fd;
    armv7m_semihost_call(SYS_CLOSE, blk);
}

/* SYS_READ and SYS_WRITE return the number of bytes NOT transferred. */
static int32_t sh_transfer(uint32_t op, int32_t fd, const void *buf, size_t n)
{
    uint32_t blk[3];
    blk[0] = (uint32_t)fd;
    blk[1] = (uint32_t)(uintptr_t)buf;
    blk[2] = (uint32_t)n;
    return armv7m_semihost_call(op, blk);
}

/* ":tt" opened for append is the host's stderr (semihosting v2,
 * SH_EXT_STDOUT_STDERR); the handle is opened once and kept. */
static int32_t g_console = -1;

void board_console_write(const char *s, size_t n)
{
    if (g_console < 0)
        g_console = sh_open(":tt", MODE_A);
    if (g_console >= 0)
        sh_transfer(SYS_WRITE, g_console, s, n);
}

void board_exit(int status)
{
    uint32_t blk[2];
    blk[0] = ADP_STOPPED_APPLICATION_EXIT;
    blk[1] = (uint32_t)status;
    for (;;)
        armv7m_semihost_call(SYS_EXIT_EXTENDED, blk);
}

int board_read_file(const char *path, uint8_t *buf, size_t cap, size_t *len)
{
    int32_t fd = sh_open(path, MODE_RB), size;
    uint32_t blk[1];
    int rc = 0;

    if (fd < 0)
        return -1;
    blk[0] = (uint32_t)fd;
    size = armv7m_semihost_call(SYS_FLEN, blk);
    if (size < 0)
        rc = -1;
    else if ((size_t)size > cap)
        rc = -2;
    else if (sh_transfer(SYS_READ, fd, buf, (size_t)size) != 0)
        rc = -1;
    else
        *len = (size_t)size;
    sh_close(fd);
    return rc;
}

int board_write_file(const char *path, const uint8_t *buf, size_t len)
{
    int32_t fd = sh_open(path, MODE_WB);
    int rc;

    if (fd < 0)
        return -1;
    rc = sh_transfer(SYS_WRITE, fd, buf, len) == 0 ? 0 : -1;
    sh_close(fd);
    return rc;
}

/* SYS_GET_CMDLINE writes the NUL-terminated line into the block's buffer;
 * QEMU builds it from -kernel and -append (or -semihosting-config arg=). */
int board_cmdline(char *buf, size_t cap)
{
    uint32_t blk[2];

    if (cap == 0)
        return -1;
    blk[0] = (uint32_t)(uintptr_t)buf;
    blk[1] = (uint32_t)cap;
    if (armv7m_semihost_call(SYS_GET_CMDLINE, blk) != 0)
        return -1;
    buf[cap - 1] = '\0';
    return 0;
}
