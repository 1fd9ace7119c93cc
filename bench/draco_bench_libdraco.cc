// draco-bench-libdraco — time libdraco 1.5.5 decoding one file, the peer
// of bench/draco_bench.c. Decodes to portable integers like lumo
// (SetSkipAttributeTransform on every attribute type) and counts the heap
// through the global operator new/delete (libdraco allocates with new).
//
//   draco-bench-libdraco FILE.drc REPS [full]
//   -> "libdraco ns=<best ns> heap_peak=<bytes> allocs=<n>"
// With "full" the attribute transforms run too (float output, what
// draco_decoder does).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <new>
#include <vector>

#include "draco/compression/decode.h"

static size_t g_live, g_peak, g_allocs;
static bool g_count;

void *operator new(size_t n)
{
    size_t *p = static_cast<size_t *>(std::malloc(n + 16));
    if (!p)
        throw std::bad_alloc();
    p[0] = n;
    if (g_count) {
        g_live += n;
        g_allocs++;
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
    if (argc != 3 && argc != 4)
        return 2;
    const bool full = argc == 4;
    std::ifstream in(argv[1], std::ios::binary);
    std::vector<char> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    int reps = std::atoi(argv[2]);
    long long best = -1;
    for (int i = 0; i < reps; ++i) {
        draco::DecoderBuffer buf;
        buf.Init(data.data(), data.size());
        draco::Decoder dec;
        for (int t = draco::GeometryAttribute::POSITION; !full && t <= draco::GeometryAttribute::GENERIC; ++t)
            dec.SetSkipAttributeTransform(static_cast<draco::GeometryAttribute::Type>(t));
        g_live = g_peak = g_allocs = 0;
        g_count = true;
        auto t0 = std::chrono::steady_clock::now();
        auto res = dec.DecodeMeshFromBuffer(&buf);
        auto t1 = std::chrono::steady_clock::now();
        g_count = false;
        if (!res.ok()) {
            std::fprintf(stderr, "libdraco: %s\n", res.status().error_msg());
            return 1;
        }
        long long ns = std::chrono::duration_cast<std::chrono::nanoseconds>(t1 - t0).count();
        if (best < 0 || ns < best)
            best = ns;
    }
    std::printf("libdraco ns=%lld heap_peak=%zu allocs=%zu\n", best, g_peak, g_allocs);
    return 0;
}
