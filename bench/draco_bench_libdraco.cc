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
#include "heap_count.h"
#include "lumo_host/options.h"

int main(int argc, char **argv)
{
    if (argc != 3 && argc != 4) {
        std::fprintf(stderr, "usage: draco-bench-libdraco FILE.drc REPS [full]\n");
        return 2;
    }
    const bool full = argc == 4;
    std::ifstream in(argv[1], std::ios::binary);
    if (!in) {
        std::fprintf(stderr, "draco-bench-libdraco: error: %s: cannot open\n", argv[1]);
        return 2;
    }
    std::vector<char> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    int reps;
    char why[160];
    if (host_opt_int("REPS", argv[2], 1, 1000000, &reps, why, sizeof why)) {
        std::fprintf(stderr, "draco-bench-libdraco: error: %s\n", why);
        return 2;
    }
    long long best = -1;
    for (int i = 0; i < reps; ++i) {
        draco::DecoderBuffer buf;
        buf.Init(data.data(), data.size());
        draco::Decoder dec;
        for (int t = draco::GeometryAttribute::POSITION; !full && t <= draco::GeometryAttribute::GENERIC; ++t)
            dec.SetSkipAttributeTransform(static_cast<draco::GeometryAttribute::Type>(t));
        heap_count_start();
        auto t0 = std::chrono::steady_clock::now();
        auto res = dec.DecodeMeshFromBuffer(&buf);
        auto t1 = std::chrono::steady_clock::now();
        g_heap.on = false;
        if (!res.ok()) {
            std::fprintf(stderr, "libdraco: %s\n", res.status().error_msg());
            return 1;
        }
        long long ns = std::chrono::duration_cast<std::chrono::nanoseconds>(t1 - t0).count();
        if (best < 0 || ns < best)
            best = ns;
    }
    std::printf("libdraco ns=%lld heap_peak=%zu allocs=%zu\n", best, g_heap.peak, g_heap.allocs);
    return 0;
}
