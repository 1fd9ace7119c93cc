// draco-set-bench-libdraco — libdraco 1.5.5 on many files in one process,
// the peer of bench/draco_set_bench.c: portable integers
// (SetSkipAttributeTransform on every attribute type), the heap counted
// through the global operator new/delete, and under callgrind
// (--collect-atstart=no) the decode call counted and dumped per file.
//
//   draco-set-bench-libdraco FILE.drc...
//   -> per file "<file> heap_peak=<bytes>"
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <new>
#include <vector>

#include <valgrind/callgrind.h>

#include "draco/compression/decode.h"

static size_t g_live, g_peak;
static bool g_count;

void *operator new(size_t n)
{
    size_t *p = static_cast<size_t *>(std::malloc(n + 16));
    if (!p)
        throw std::bad_alloc();
    p[0] = n;
    if (g_count) {
        g_live += n;
        if (g_live > g_peak)
            g_peak = g_live;
    }
    return p + 2;
}
void operator delete(void *q) noexcept
{
    if (!q)
        return;
    size_t *p = static_cast<size_t *>(q) - 2;
    if (g_count && g_live >= p[0])
        g_live -= p[0];
    std::free(p);
}
void *operator new[](size_t n) { return operator new(n); }
void operator delete[](void *q) noexcept { operator delete(q); }
void operator delete(void *q, size_t) noexcept { operator delete(q); }
void operator delete[](void *q, size_t) noexcept { operator delete(q); }

int main(int argc, char **argv)
{
    if (argc < 2)
        return 2;
    for (int i = 1; i < argc; ++i) {
        std::ifstream in(argv[i], std::ios::binary);
        std::vector<char> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        draco::DecoderBuffer buf;
        buf.Init(data.data(), data.size());
        draco::Decoder dec;
        for (int t = draco::GeometryAttribute::POSITION; t <= draco::GeometryAttribute::GENERIC; ++t)
            dec.SetSkipAttributeTransform(static_cast<draco::GeometryAttribute::Type>(t));
        g_live = g_peak = 0;
        g_count = true;
        CALLGRIND_TOGGLE_COLLECT;
        auto res = dec.DecodeMeshFromBuffer(&buf);
        CALLGRIND_TOGGLE_COLLECT;
        CALLGRIND_DUMP_STATS_AT(argv[i]);
        g_count = false;
        if (!res.ok()) {
            std::fprintf(stderr, "libdraco: %s: %s\n", argv[i], res.status().error_msg());
            return 1;
        }
        std::printf("%s heap_peak=%zu\n", argv[i], g_peak);
    }
    return 0;
}
