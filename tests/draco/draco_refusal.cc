// tests/draco/draco_refusal.cc — refusal conformance: every stream libdraco
// refuses, lumo refuses too (issue 24: "every header field range-checked as
// libdraco does, or tighter").
//
//   draco-refusal IN.drc...
//
// For each stream, every byte (of a long stream: every byte of its first
// and last 160 and a sample between) is overwritten in turn with each of a set of
// values that reach the ends of the fields' ranges (0, 1, 31, 128, 155,
// 255, and the byte with its lowest and highest bit flipped). Each mutated stream is decoded by libdraco as draco_decoder
// decodes it (attribute transforms to floats included: libdraco checks the
// octahedral bit count only there) and by lumo (sanitizer build) in both
// modes, each in exactly its lumo_draco_arena_need_ex() arena. A stream
// libdraco refuses that lumo decodes is a failure; one lumo refuses that
// libdraco decodes is allowed (lumo is tighter: docs/draco-decoder.md,
// "Differences" 7, 9, 15, 16) and counted. Where both decode, lumo's
// portable values are compared with libdraco's (transforms skipped):
// differences are counted, not failed (a mutated connectivity may hold
// opposites that disagree with its vertices, where lumo's prediction may
// differ: docs/draco-decoder.md, Performance, "Corner stepping").
//
// A stream that holds normals must also show the class issue 24 found: at
// least one mutation that only libdraco's attribute transform refuses (the
// octahedral bit count), which lumo must refuse as well.
//
// Prints one line per stream and "RESULT: N passed, M failed".
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iterator>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include "draco/compression/decode.h"
#include "draco/mesh/mesh.h"

extern "C" {
#include "lumo/draco.h"
}

// libdraco sizes some vectors from crafted counts before it checks them
// against the input: on the streams here no decode needs 64 MB, so a
// larger request fails as bad_alloc (a refusal) instead of exhausting the
// machine; below that, the sanitizer runtime's malloc.
void *operator new(std::size_t n)
{
    void *p = n <= ((std::size_t)64 << 20) ? std::malloc(n ? n : 1) : nullptr;
    if (!p)
        throw std::bad_alloc();
    return p;
}
void *operator new[](std::size_t n) { return operator new(n); }
void operator delete(void *p) noexcept { std::free(p); }
void operator delete[](void *p) noexcept { std::free(p); }
void operator delete(void *p, std::size_t) noexcept { std::free(p); }
void operator delete[](void *p, std::size_t) noexcept { std::free(p); }

namespace {

struct Decoded {
    bool ok = false;
    std::vector<int32_t> values;  // faces, then portable values per point
};

void collect(const draco::PointCloud &pc, const draco::Mesh *mesh, Decoded *out)
{
    out->values.push_back((int32_t)pc.num_points());
    if (mesh)
        for (draco::FaceIndex i(0); i < mesh->num_faces(); ++i)
            for (int k = 0; k < 3; ++k)
                out->values.push_back((int32_t)mesh->face(i)[k].value());
    for (int a = 0; a < pc.num_attributes(); ++a) {
        const draco::PointAttribute *att = pc.attribute(a);
        const int n = att->num_components();
        std::vector<int32_t> v(n);
        for (draco::PointIndex p(0); p < pc.num_points(); ++p) {
            att->ConvertValue<int32_t>(att->mapped_index(p), (int8_t)n, v.data());
            out->values.insert(out->values.end(), v.begin(), v.end());
        }
    }
}

// libdraco's decode; `skip`: portable integers (the conformance oracle's
// view), else the full decode draco_decoder runs.
Decoded libdraco(const std::vector<uint8_t> &data, bool skip)
{
    Decoded r;
    draco::DecoderBuffer buf;
    buf.Init(reinterpret_cast<const char *>(data.data()), data.size());
    draco::Decoder dec;
    if (skip)
        for (int t = draco::GeometryAttribute::POSITION; t <= draco::GeometryAttribute::GENERIC; ++t)
            dec.SetSkipAttributeTransform(static_cast<draco::GeometryAttribute::Type>(t));
    try {
        auto type = draco::Decoder::GetEncodedGeometryType(&buf);
        if (!type.ok())
            return r;
        if (type.value() == draco::TRIANGULAR_MESH) {
            auto res = dec.DecodeMeshFromBuffer(&buf);
            if (!res.ok() || !res.value())
                return r;
            if (skip)
                collect(*res.value(), res.value().get(), &r);
        } else if (type.value() == draco::POINT_CLOUD) {
            auto res = dec.DecodePointCloudFromBuffer(&buf);
            if (!res.ok() || !res.value())
                return r;
            if (skip)
                collect(*res.value(), nullptr, &r);
        } else {
            return r;
        }
    } catch (const std::exception &) {  // bad_alloc on a crafted count
        return r;
    }
    r.ok = true;
    return r;
}

// lumo's decode in exactly its need; `keep`: collect the values.
Decoded lumo(const std::vector<uint8_t> &data, unsigned flags, bool keep, lumo_status *status)
{
    Decoded r;
    lumo_draco_need need;
    lumo_draco_mesh m;
    lumo_arena a;
    *status = lumo_draco_arena_need_ex(data.data(), data.size(), flags, &need);
    if (*status)
        return r;
    // a crafted header can ask for more than the machine has: such a
    // stream gets 64 MB (no stream here needs 1 MB) and must then fail cleanly (LUMO_ERR_NOMEM)
    const size_t bytes = need.bytes < ((size_t)64 << 20) ? need.bytes : (size_t)64 << 20;
    std::unique_ptr<void, void (*)(void *)> mem(std::malloc(bytes ? bytes : 1), std::free);
    if (!mem) {
        *status = LUMO_ERR_NOMEM;
        return r;
    }
    lumo_arena_init(&a, mem.get(), bytes);
    *status = lumo_draco_decode_ex(data.data(), data.size(), flags, &a, &m);
    if (*status)
        return r;
    r.ok = true;
    if (!keep)
        return r;
    r.values.push_back((int32_t)m.num_points);
    if (m.geometry == LUMO_DRACO_MESH)
        for (uint32_t i = 0; i < 3 * m.num_faces; ++i)
            r.values.push_back((int32_t)m.faces[i]);
    for (uint32_t i = 0; i < m.num_attributes; ++i)
        for (uint32_t p = 0; p < m.num_points; ++p)
            for (unsigned c = 0; c < m.attributes[i].num_portable; ++c)
                r.values.push_back(lumo_draco_value(&m.attributes[i], p, c));
    return r;
}

bool has_normals(const std::vector<uint8_t> &data)
{
    draco::DecoderBuffer buf;
    buf.Init(reinterpret_cast<const char *>(data.data()), data.size());
    draco::Decoder dec;
    auto res = dec.DecodePointCloudFromBuffer(&buf);
    return res.ok() && res.value()->GetNamedAttribute(draco::GeometryAttribute::NORMAL);
}

struct Counts {
    unsigned mutations = 0, both_refuse = 0, lumo_tighter = 0, both_decode = 0, differ = 0;
    unsigned transform_only = 0, failures = 0;
};

bool run_stream(const char *path)
{
    std::ifstream in(path, std::ios::binary);
    std::vector<uint8_t> orig((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (orig.empty() || !libdraco(orig, false).ok) {
        std::printf("FAIL %s: not a stream libdraco decodes\n", path);
        return false;
    }
    static const int kValues[] = {0, 1, 31, 128, 155, 255, -1, -2};
    Counts n;
    const std::clock_t t0 = std::clock();
    std::vector<uint8_t> d = orig;
    // every byte of a short stream; of a longer one the headers (the first
    // 160 bytes), the transform parameters (the last 160) and a sample
    // between them: about 512 positions a stream
    const size_t size = orig.size(), step = size <= 512 ? 1 : (size - 320) / 192 + 1;
    for (size_t pos = 0; pos < size; pos += pos < 160 || pos + 160 >= size ? 1 : step) {
        for (int v : kValues) {
            const uint8_t b = v == -1 ? (uint8_t)(orig[pos] ^ 0x01u)
                            : v == -2 ? (uint8_t)(orig[pos] ^ 0x80u) : (uint8_t)v;
            if (b == orig[pos])
                continue;
            d[pos] = b;
            ++n.mutations;
            const bool ref = libdraco(d, false).ok;
            lumo_status s0, s1;
            const Decoded l0 = lumo(d, 0, ref, &s0);
            const Decoded l1 = lumo(d, LUMO_DRACO_LEAN, false, &s1);
            if (!ref && (l0.ok || l1.ok)) {
                if (++n.failures <= 5)
                    std::printf("FAIL %s: byte %zu = %u: libdraco refuses, lumo decodes (%s)\n",
                                path, pos, b, l0.ok ? "default" : "lean");
            } else if (!ref) {
                ++n.both_refuse;
                if (libdraco(d, true).ok)
                    ++n.transform_only;  // refused only by the attribute transform
            } else if (!l0.ok) {
                ++n.lumo_tighter;
            } else {
                ++n.both_decode;
                if (libdraco(d, true).values != l0.values)
                    ++n.differ;
            }
            if (l0.ok != l1.ok && ++n.failures <= 5)
                std::printf("FAIL %s: byte %zu = %u: the modes disagree (%s / %s)\n", path, pos,
                            b, lumo_strerror(s0), lumo_strerror(s1));
        }
        d[pos] = orig[pos];
    }
    if (has_normals(orig) && n.transform_only == 0 && ++n.failures)
        std::printf("FAIL %s: no mutation refused only by libdraco's octahedral transform\n", path);
    std::printf("%s %s: %zu bytes, %.1f s, %u mutations: both refuse %u (by the transform alone %u), "
                "lumo alone refuses %u, both decode %u (values differ %u)\n",
                n.failures ? "FAIL" : "PASS", path, orig.size(),
                (double)(std::clock() - t0) / CLOCKS_PER_SEC, n.mutations, n.both_refuse,
                n.transform_only, n.lumo_tighter, n.both_decode, n.differ);
    return n.failures == 0;
}

}  // namespace

int main(int argc, char **argv)
{
    int pass = 0, fail = 0;
    if (argc < 2) {
        std::fprintf(stderr, "usage: draco-refusal IN.drc...\n");
        return 2;
    }
    for (int i = 1; i < argc; ++i)
        (run_stream(argv[i]) ? pass : fail)++;
    std::printf("RESULT: %d passed, %d failed\n", pass, fail);
    return fail ? 1 : 0;
}
