/*
 * file_io.c — see lumo_host/file_io.h.
 */
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>
#include "lumo_host/file_io.h"

/* Length of an open regular file, or -1. fstat rather than ftell at the
 * end: on a directory ftell "succeeds" with LONG_MAX, and pipes have no
 * length to allocate for. */
static long file_length(FILE *f)
{
    struct stat st;

    if (fstat(fileno(f), &st) || !S_ISREG(st.st_mode) || st.st_size < 0)
        return -1;
    return (long)st.st_size;
}

uint8_t *host_read_file(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    uint8_t *buf = NULL;
    long n;

    if (!f)
        return NULL;
    n = file_length(f);
    if (n >= 0)
        buf = malloc((size_t)n + 1);   /* +1 for the terminating zero */
    if (buf && fread(buf, 1, (size_t)n, f) != (size_t)n) {
        free(buf);
        buf = NULL;
    }
    fclose(f);
    if (!buf)
        return NULL;
    buf[n] = 0;
    *size = (size_t)n;
    return buf;
}
