/*
 * lumo/arena.h — all client memory comes from a caller-given byte buffer.
 *
 * The SDK never calls malloc. The application hands an arena a buffer it
 * owns (static array, linker section, or heap on a desktop); SDK objects are
 * carved from it with bump allocation and released together with mark/reset.
 * The buffer must outlive every object allocated from it.
 *
 * Every allocation is aligned to LUMO_ARENA_ALIGN (8) and its size rounded up
 * to a multiple of it, so "bytes needed" functions can add up
 * lumo_arena_round(n) for each allocation and the caller adds
 * LUMO_ARENA_SLACK once for the alignment of the buffer's start.
 */
#ifndef LUMO_ARENA_H
#define LUMO_ARENA_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/status.h"

#define LUMO_ARENA_ALIGN 8u   /* bytes every allocation is aligned and rounded to */
/* Bytes lost at most to aligning the start of an unaligned buffer. */
#define LUMO_ARENA_SLACK (LUMO_ARENA_ALIGN - 1u)

/* A bump allocator over the caller's buffer; fields are read-only to the
 * caller (peak for memory reports). */
typedef struct lumo_arena {
    uint8_t *base;       /* first aligned byte of the caller's buffer */
    size_t   size;       /* usable bytes from base */
    size_t   used;       /* bytes handed out */
    size_t   peak;       /* high-water mark of used, for memory reports */
} lumo_arena;

/* A mark is the arena's fill level; reset returns to it. */
typedef size_t lumo_arena_mark;

/* Take `bytes` bytes at `buf` (any alignment). Never fails for a non-NULL
 * arena: a too-small buffer gives an arena of size 0. */
lumo_status lumo_arena_init(lumo_arena *a, void *buf, size_t bytes);

/* `bytes` rounded up to LUMO_ARENA_ALIGN, or SIZE_MAX on overflow (which
 * then makes any sum fail the arena's size check). */
size_t lumo_arena_round(size_t bytes);

/* n * size with overflow detection: SIZE_MAX on overflow. */
size_t lumo_size_mul(size_t n, size_t size);
/* a + b saturating at SIZE_MAX. */
size_t lumo_size_add(size_t a, size_t b);

/* Allocate `bytes` (zero allowed) aligned to LUMO_ARENA_ALIGN; the memory is
 * zero-filled. NULL when the arena has too little room (the arena is then
 * unchanged). */
void *lumo_arena_alloc(lumo_arena *a, size_t bytes);

/* lumo_arena_alloc(a, n * size) with overflow detection. */
void *lumo_arena_alloc_array(lumo_arena *a, size_t n, size_t size);

/* The arena's current fill level, for lumo_arena_reset. */
lumo_arena_mark lumo_arena_get_mark(const lumo_arena *a);
/* Release everything allocated after `mark`. */
void lumo_arena_reset(lumo_arena *a, lumo_arena_mark mark);

size_t lumo_arena_remaining(const lumo_arena *a);

#endif /* LUMO_ARENA_H */
