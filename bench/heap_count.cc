// heap_count.cc — the global operator new/delete of the libdraco peers
// (bench/draco_bench_libdraco.cc, bench/draco_set_bench_libdraco.cc): each
// block carries its size in a 16-byte header so delete can count it out.
#include <cstdlib>
#include <new>

#include "heap_count.h"

heap_count g_heap;

void heap_count_start()
{
    g_heap.live = g_heap.peak = g_heap.allocs = 0;
    g_heap.on = true;
}

void *operator new(size_t n)
{
    size_t *p = static_cast<size_t *>(std::malloc(n + 16));
    if (!p)
        throw std::bad_alloc();
    p[0] = n;
    if (g_heap.on) {
        g_heap.live += n;
        g_heap.allocs++;
        if (g_heap.live > g_heap.peak)
            g_heap.peak = g_heap.live;
    }
    return p + 2;
}
void operator delete(void *q) noexcept
{
    if (!q)
        return;
    size_t *p = static_cast<size_t *>(q) - 2;
    if (g_heap.on && g_heap.live >= p[0])
        g_heap.live -= p[0];
    std::free(p);
}
void *operator new[](size_t n) { return operator new(n); }
void operator delete[](void *q) noexcept { operator delete(q); }
void operator delete(void *q, size_t) noexcept { operator delete(q); }
void operator delete[](void *q, size_t) noexcept { operator delete(q); }
