// server/pm/draco_shim.cc — the only C++ in lumo: libdraco's encoder behind the
// extern "C" API of pm/draco_shim.h. Exceptions never cross the
// boundary (libdraco reports through draco::Status; allocation failure ends
// the process as any C tool would).
#include "pm/draco_shim.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>
#include <draco/point_cloud/point_cloud.h>

namespace {

// Fill `pc` with one float32 xyz POSITION attribute, one value per point.
// libdraco fails to add an attribute only when it cannot allocate it.
lumo_status add_positions(draco::PointCloud *pc, const float *xyz, size_t n)
{
    pc->set_num_points(static_cast<draco::PointIndex::ValueType>(n));
    draco::GeometryAttribute ga;
    ga.Init(draco::GeometryAttribute::POSITION, nullptr, 3, draco::DT_FLOAT32, false,
            sizeof(float) * 3, 0);
    const int id = pc->AddAttribute(ga, true, static_cast<uint32_t>(n));
    if (id < 0)
        return LUMO_ERR_NOMEM;
    draco::PointAttribute *att = pc->attribute(id);
    for (size_t i = 0; i < n; ++i)
        att->SetAttributeValue(draco::AttributeValueIndex(static_cast<uint32_t>(i)), xyz + 3 * i);
    return LUMO_OK;
}

// Optional COLOR uint8 x3 attribute (albedo), one value per point.
lumo_status add_color(draco::PointCloud *pc, const uint8_t *rgb, size_t n)
{
    if (!rgb)
        return LUMO_OK;
    draco::GeometryAttribute ga;
    ga.Init(draco::GeometryAttribute::COLOR, nullptr, 3, draco::DT_UINT8, true, 3, 0);
    const int id = pc->AddAttribute(ga, true, static_cast<uint32_t>(n));
    if (id < 0)
        return LUMO_ERR_NOMEM;
    for (size_t i = 0; i < n; ++i)
        pc->attribute(id)->SetAttributeValue(draco::AttributeValueIndex(static_cast<uint32_t>(i)),
                                             rgb + 3 * i);
    return LUMO_OK;
}

lumo_status copy_out(const draco::EncoderBuffer &buf, uint8_t **out, size_t *out_len)
{
    *out_len = buf.size();
    *out = static_cast<uint8_t *>(std::malloc(buf.size() ? buf.size() : 1));
    if (!*out)
        return LUMO_ERR_NOMEM;
    std::memcpy(*out, buf.data(), buf.size());
    return LUMO_OK;
}

// LUMO_OK, or `code` with libdraco's message on stderr.
lumo_status report(const draco::Status &st, const char *what, lumo_status code)
{
    if (st.ok())
        return LUMO_OK;
    std::fprintf(stderr, "draco: %s: %s\n", what, st.error_msg());
    return code;
}

void set_quant(draco::Encoder *enc, const srv_draco_quant *q)
{
    enc->SetAttributeExplicitQuantization(draco::GeometryAttribute::POSITION, q->bits, 3,
                                          q->origin, q->range);
}

}  // namespace

// The float libdraco will hold after its std::to_string round trip.
static float draco_text_float(double v)
{
    char text[64];
    std::snprintf(text, sizeof text, "%f", static_cast<float>(v));
    return std::strtof(text, nullptr);
}

// The next text float from v in direction dir (+1 or -1): a step of 1e-6,
// doubled until the text round trip moves (past ~8 m a float's spacing is
// above 1e-6, and a fixed step would round back to v for ever).
static float draco_text_step(float v, int dir)
{
    for (double step = 1e-6;; step *= 2) {
        float next = draco_text_float(static_cast<double>(v) + dir * step);
        if (dir > 0 ? next > v : next < v)
            return next;
    }
}

extern "C" void srv_draco_grid(const float lo[3], const float hi[3], int bits, srv_draco_quant *q)
{
    double extent = 0;
    q->bits = bits;
    for (int c = 0; c < 3; ++c) {
        q->origin[c] = draco_text_float(std::floor(static_cast<double>(lo[c]) * 1e6) / 1e6 - 1e-6);
        while (q->origin[c] > lo[c])  // text rounding went up: step down
            q->origin[c] = draco_text_step(q->origin[c], -1);
        double e = static_cast<double>(hi[c]) - q->origin[c];
        extent = e > extent ? e : extent;
    }
    q->range = draco_text_float(std::ceil(extent * 1e6) / 1e6 + 1e-6);
    for (int c = 0; c < 3; ++c)
        while (static_cast<double>(q->origin[c]) + q->range < hi[c])
            q->range = draco_text_step(q->range, +1);
    if (q->range <= 0)
        q->range = 1;
}

extern "C" srv_draco_settings srv_draco_default_settings(void)
{
    // Sequential point clouds keep point order, which the vertex numbering of
    // the stream relies on. Speed 5 lets libdraco use rANS-coded differences.
    srv_draco_settings s;
    s.speed = 5;
    s.method = draco::POINT_CLOUD_SEQUENTIAL_ENCODING;
    return s;
}

extern "C" lumo_status srv_draco_encode_points(const float *xyz, const uint8_t *rgb, size_t n,
                                               const srv_draco_quant *q, srv_draco_settings s,
                                               uint8_t **out, size_t *out_len)
{
    draco::PointCloud pc;
    lumo_status st = add_positions(&pc, xyz, n);
    if (!st)
        st = add_color(&pc, rgb, n);
    if (st)
        return st;
    draco::Encoder enc;
    set_quant(&enc, q);
    enc.SetSpeedOptions(s.speed, s.speed);
    enc.SetEncodingMethod(s.method);
    draco::EncoderBuffer buf;
    if ((st = report(enc.EncodePointCloudToBuffer(pc, &buf), "encode points", LUMO_ERR_ARG)))
        return st;
    return copy_out(buf, out, out_len);
}

extern "C" lumo_status srv_draco_encode_ints(const int32_t *values, const uint8_t *rgb, size_t n,
                                             int comps, srv_draco_settings s, uint8_t **out,
                                             size_t *out_len)
{
    draco::PointCloud pc;
    pc.set_num_points(static_cast<draco::PointIndex::ValueType>(n));
    draco::GeometryAttribute ga;
    ga.Init(draco::GeometryAttribute::GENERIC, nullptr, static_cast<uint8_t>(comps), draco::DT_INT32,
            false, sizeof(int32_t) * comps, 0);
    const int id = pc.AddAttribute(ga, true, static_cast<uint32_t>(n));
    if (id < 0)
        return LUMO_ERR_NOMEM;
    for (size_t i = 0; i < n; ++i)
        pc.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(static_cast<uint32_t>(i)),
                                            values + comps * i);
    lumo_status st = add_color(&pc, rgb, n);
    if (st)
        return st;
    draco::Encoder enc;
    enc.SetSpeedOptions(s.speed, s.speed);
    enc.SetEncodingMethod(s.method);
    if ((st = report(enc.SetAttributePredictionScheme(draco::GeometryAttribute::GENERIC,
                                                      draco::PREDICTION_NONE), "prediction",
                     LUMO_ERR_ARG)))
        return st;
    draco::EncoderBuffer buf;
    if ((st = report(enc.EncodePointCloudToBuffer(pc, &buf), "encode ints", LUMO_ERR_ARG)))
        return st;
    return copy_out(buf, out, out_len);
}

extern "C" lumo_status srv_draco_encode_mesh(const float *xyz, size_t nv, const uint32_t *tris,
                                             size_t nt, const srv_draco_quant *q, int cl,
                                             uint8_t **out, size_t *out_len)
{
    draco::Mesh mesh;
    lumo_status st = add_positions(&mesh, xyz, nv);
    if (st)
        return st;
    mesh.SetNumFaces(nt);
    for (size_t f = 0; f < nt; ++f) {
        draco::Mesh::Face face;
        for (int c = 0; c < 3; ++c)
            face[c] = draco::PointIndex(tris[3 * f + c]);
        mesh.SetFace(draco::FaceIndex(static_cast<uint32_t>(f)), face);
    }
    draco::Encoder enc;
    set_quant(&enc, q);
    enc.SetSpeedOptions(10 - cl, 10 - cl);
    enc.SetEncodingMethod(cl == 0 ? draco::MESH_SEQUENTIAL_ENCODING
                                  : draco::MESH_EDGEBREAKER_ENCODING);
    draco::EncoderBuffer buf;
    if ((st = report(enc.EncodeMeshToBuffer(mesh, &buf), "encode mesh", LUMO_ERR_ARG)))
        return st;
    return copy_out(buf, out, out_len);
}

extern "C" lumo_status srv_draco_decode_points(const uint8_t *data, size_t len, float **xyz,
                                               size_t *n)
{
    draco::DecoderBuffer in;
    in.Init(reinterpret_cast<const char *>(data), len);
    draco::Decoder dec;
    auto res = dec.DecodePointCloudFromBuffer(&in);
    lumo_status st = report(res.status(), "decode", LUMO_ERR_CORRUPT);
    if (st)
        return st;
    std::unique_ptr<draco::PointCloud> pc = std::move(res).value();
    const draco::PointAttribute *att = pc->GetNamedAttribute(draco::GeometryAttribute::POSITION);
    if (!att)
        return LUMO_ERR_CORRUPT;
    *n = pc->num_points();
    *xyz = static_cast<float *>(std::malloc(sizeof(float) * 3 * (*n ? *n : 1)));
    if (!*xyz)
        return LUMO_ERR_NOMEM;
    for (uint32_t i = 0; i < *n; ++i)
        att->GetMappedValue(draco::PointIndex(i), *xyz + 3 * i);
    return LUMO_OK;
}
