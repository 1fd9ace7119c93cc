/*
 * ivg_memory.c — bytes per grid vertex of the client's IVG
 * (lumo_ivg_memory_size: entries, bitmaps, push-pull pyramid and smoothing
 * sums) for the grids of docs/benchmarks.md "IVG memory". Built against the
 * current SDK and against the peer (the SDK before the packed grid) by
 * bench/ivg_compact.sh, so both columns come from the same run.
 *
 *   lumo-bench-ivg-memory       prints "N^3 bytes bytes-per-vertex" lines
 */
#include <stdio.h>
#include "lumo/ivg.h"

int main(void)
{
    static const unsigned sizes[] = {6, 8, 10, 12, 16, 17, 32, 33, 64, 65};
    size_t i;

    for (i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        unsigned n = sizes[i];
        lumo_ivg_desc d = {{(uint16_t)n, (uint16_t)n, (uint16_t)n}, {0, 0, 0}, {65536, 65536, 65536}};
        size_t bytes = lumo_ivg_memory_size(&d);
        printf("%u %zu %.2f\n", n, bytes, (double)bytes / ((double)n * n * n));
    }
    return 0;
}
