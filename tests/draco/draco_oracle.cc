// tests/draco/draco_oracle.cc — the conformance oracle: decodes a .drc with
// libdraco, skipping the attribute transforms, and dumps the portable
// integers per point and the faces in libdraco's order. lumo-draco-decode
// --dump writes the same format; the two files must be identical.
//
//   draco-oracle IN.drc OUT.txt
#include <cstdio>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <vector>

#include "draco/compression/decode.h"
#include "draco/mesh/mesh.h"


static void dump(FILE *f, const draco::PointCloud &pc, const draco::Mesh *mesh)
{
    std::fprintf(f, "points %u\n", (unsigned)pc.num_points());
    if (mesh) {
        std::fprintf(f, "faces %u\n", (unsigned)mesh->num_faces());
        for (draco::FaceIndex i(0); i < mesh->num_faces(); ++i) {
            const auto &face = mesh->face(i);
            std::fprintf(f, "%u %u %u\n", face[0].value(), face[1].value(), face[2].value());
        }
    }
    std::fprintf(f, "attributes %d\n", pc.num_attributes());
    for (int a = 0; a < pc.num_attributes(); ++a) {
        const draco::PointAttribute *att = pc.attribute(a);
        const int n = att->num_components();
        std::fprintf(f, "attribute %d type %d components %d\n", a,
                     (int)att->attribute_type(), n);
        std::vector<int32_t> v(n);
        for (draco::PointIndex p(0); p < pc.num_points(); ++p) {
            att->ConvertValue<int32_t>(att->mapped_index(p), (int8_t)n, v.data());
            for (int c = 0; c < n; ++c)
                std::fprintf(f, c ? " %d" : "%d", v[c]);
            std::fputc('\n', f);
        }
    }
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        std::fprintf(stderr, "usage: draco-oracle IN.drc OUT.txt\n");
        return 2;
    }
    std::ifstream in(argv[1], std::ios::binary);
    std::vector<char> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    draco::DecoderBuffer buf;
    buf.Init(data.data(), data.size());
    draco::Decoder dec;
    for (int t = draco::GeometryAttribute::POSITION; t <= draco::GeometryAttribute::GENERIC; ++t)
        dec.SetSkipAttributeTransform(static_cast<draco::GeometryAttribute::Type>(t));
    auto type = draco::Decoder::GetEncodedGeometryType(&buf);
    if (!type.ok()) {
        std::fprintf(stderr, "oracle: %s\n", type.status().error_msg());
        return 1;
    }
    FILE *f = std::fopen(argv[2], "w");
    if (!f)
        return 1;
    if (type.value() == draco::TRIANGULAR_MESH) {
        auto res = dec.DecodeMeshFromBuffer(&buf);
        if (!res.ok()) {
            std::fprintf(stderr, "oracle: %s\n", res.status().error_msg());
            return 1;
        }
        dump(f, *res.value(), res.value().get());
    } else {
        auto res = dec.DecodePointCloudFromBuffer(&buf);
        if (!res.ok()) {
            std::fprintf(stderr, "oracle: %s\n", res.status().error_msg());
            return 1;
        }
        dump(f, *res.value(), nullptr);
    }
    return std::fclose(f) ? 1 : 0;
}
