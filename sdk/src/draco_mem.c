/*
 * draco_mem.c — the decoder's view of the caller's arena.
 *
 * A decode knows its output sizes only as it goes (points appear after the
 * connectivity, values per attribute), and needs work memory in between.
 * So it takes the arena's whole free space and fills it from both ends:
 * outputs upwards, work memory downwards (released in stack order). At the
 * end only the outputs are committed, so the arena holds no dead work bytes.
 */
#include "draco_internal.h"

static size_t ld_round8(size_t n) { return (n + 7u) & ~(size_t)7u; }

void ld_mem_init(ld_mem *m, lumo_arena *a)
{
    m->start = a->base + a->used;
    m->lo = m->start;
    m->top = a->base + (a->size & ~(size_t)7u);  /* keep work memory aligned */
    m->hi = m->top;
    m->peak = 0;
}

static void ld_track(ld_mem *m)
{
    size_t in_use = (size_t)(m->lo - m->start) + (size_t)(m->top - m->hi);
    if (in_use > m->peak)
        m->peak = in_use;
}

static int ld_bytes(size_t n, size_t size, size_t *out)
{
    if (size && n > (SIZE_MAX - 8u) / size)
        return 0;
    *out = ld_round8(n * size);
    return 1;
}

void *ld_out(ld_mem *m, size_t n, size_t size)
{
    size_t bytes;
    void *p;
    if (!ld_bytes(n, size, &bytes) || bytes > (size_t)(m->hi - m->lo))
        return NULL;
    p = m->lo;
    m->lo += bytes;
    ld_track(m);
    return p;
}

void *ld_tmp(ld_mem *m, size_t n, size_t size)
{
    size_t bytes;
    if (!ld_bytes(n, size, &bytes) || bytes > (size_t)(m->hi - m->lo))
        return NULL;
    m->hi -= bytes;
    ld_track(m);
    return m->hi;
}

void ld_mem_commit(ld_mem *m, lumo_arena *a)
{
    a->used = (size_t)(m->lo - a->base);
    if (a->used > a->peak)
        a->peak = a->used;
    if ((size_t)(m->start - a->base) + m->peak > a->peak)
        a->peak = (size_t)(m->start - a->base) + m->peak;
}

void ld_free_used(ld_mem *m, size_t bytes)
{
    size_t in_use;
    bytes = ld_round8(bytes);  /* an arena of the reported need holds it */
    in_use = (size_t)(m->lo - m->start) + (size_t)(m->top - m->hi) + bytes;
    if (in_use > m->peak)
        m->peak = in_use;
}
