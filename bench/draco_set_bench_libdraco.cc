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
#include "heap_count.h"

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
        heap_count_start();
        CALLGRIND_TOGGLE_COLLECT;
        auto res = dec.DecodeMeshFromBuffer(&buf);
        CALLGRIND_TOGGLE_COLLECT;
        CALLGRIND_DUMP_STATS_AT(argv[i]);
        g_heap.on = false;
        if (!res.ok()) {
            std::fprintf(stderr, "libdraco: %s: %s\n", argv[i], res.status().error_msg());
            return 1;
        }
        std::printf("%s heap_peak=%zu\n", argv[i], g_heap.peak);
    }
    return 0;
}
