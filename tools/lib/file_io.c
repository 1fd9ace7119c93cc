/*
 * file_io.c — see lumo_host/file_io.h.
 */
#include <stdio.h>
#include <stdlib.h>
#include "lumo_host/file_io.h"

/* Length of an open file, or -1. ftell after seeking to the end is the
 * portable C way; a directory or pipe fails here or at the read below. */
static long file_length(FILE *f)
{
    long n;

    if (fseek(f, 0, SEEK_END) || (n = ftell(f)) < 0 || fseek(f, 0, SEEK_SET))
        return -1;
    return n;
}

uint8_t *lumo_read_file(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    uint8_t *buf = NULL;
    long n;

    if (!f)
        return NULL;
    n = file_length(f);
    /* +1 for the terminating zero; a bogus huge length fails in malloc. */
    if (n >= 0 && (unsigned long)n < (size_t)-1)
        buf = malloc((size_t)n + 1);
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
