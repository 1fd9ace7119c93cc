// heap_count.h — the C++ heap a peer library uses, counted through the
// global operator new/delete (bench/heap_count.cc): libdraco allocates with
// new, so its decoders' peak heap is what these see while counting is on.
#ifndef LUMO_BENCH_HEAP_COUNT_H
#define LUMO_BENCH_HEAP_COUNT_H

#include <cstddef>

struct heap_count {
    size_t live, peak, allocs;   // bytes now, the most bytes, allocations
    bool on;                     // count only while set
};
extern heap_count g_heap;

// Zero the counts and start counting.
void heap_count_start();

#endif
