/* arena.c — bump allocation from a caller-given buffer (see lumo/arena.h). */
#include <string.h>
#include "lumo/arena.h"

lumo_status lumo_arena_init(lumo_arena *a, void *buf, size_t bytes)
{
    uintptr_t addr, pad;

    if (a == NULL || (buf == NULL && bytes != 0))
        return LUMO_ERR_ARG;
    addr = (uintptr_t)buf;
    pad = (LUMO_ARENA_ALIGN - (addr % LUMO_ARENA_ALIGN)) % LUMO_ARENA_ALIGN;
    a->base = (uint8_t *)buf + (pad < bytes ? pad : 0);
    a->size = bytes > pad ? bytes - pad : 0;
    a->used = 0;
    a->peak = 0;
    return LUMO_OK;
}

size_t lumo_arena_round(size_t bytes)
{
    if (bytes > SIZE_MAX - (LUMO_ARENA_ALIGN - 1u))
        return SIZE_MAX;
    return (bytes + (LUMO_ARENA_ALIGN - 1u)) & ~(size_t)(LUMO_ARENA_ALIGN - 1u);
}

size_t lumo_size_mul(size_t n, size_t size)
{
    if (size != 0 && n > SIZE_MAX / size)
        return SIZE_MAX;
    return n * size;
}

size_t lumo_size_add(size_t a, size_t b)
{
    return a > SIZE_MAX - b ? SIZE_MAX : a + b;
}

void *lumo_arena_alloc(lumo_arena *a, size_t bytes)
{
    size_t need = lumo_arena_round(bytes);
    void *p;

    if (a == NULL || need == SIZE_MAX || need > a->size - a->used)
        return NULL;
    p = a->base + a->used;
    a->used += need;
    if (a->used > a->peak)
        a->peak = a->used;
    memset(p, 0, need);
    return p;
}

void *lumo_arena_alloc_array(lumo_arena *a, size_t n, size_t size)
{
    size_t bytes = lumo_size_mul(n, size);
    return bytes == SIZE_MAX ? NULL : lumo_arena_alloc(a, bytes);
}

lumo_arena_mark lumo_arena_get_mark(const lumo_arena *a)
{
    return a->used;
}

void lumo_arena_reset(lumo_arena *a, lumo_arena_mark mark)
{
    if (mark <= a->used)
        a->used = mark;
}

size_t lumo_arena_remaining(const lumo_arena *a)
{
    return a->size - a->used;
}
