/*
 * file_io.h — whole files into memory, for the desktop tools (server,
 * host board, test helpers). Packages, Draco and PM streams are parsed from
 * one buffer, so every tool used to carry its own fopen/ftell/fread loop.
 */
#ifndef HOST_FILE_IO_H
#define HOST_FILE_IO_H

#include <stddef.h>
#include <stdint.h>

/* Read the file at path into a malloc'ed buffer (caller frees) and store
 * its length in *size. One extra zero byte follows the data, so text
 * formats (PLY headers, scene files) can be scanned as a C string; an
 * empty file gives a valid buffer with *size 0. NULL when the file cannot
 * be opened or read, is not a regular file (directory, pipe), or memory
 * runs out; *size is then untouched. */
uint8_t *host_read_file(const char *path, size_t *size);

#endif
