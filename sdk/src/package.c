/*
 * package.c — the .lumo package reader (docs/package-format.md). Validates
 * everything it reads; integer code only; no allocation.
 */
#include <string.h>
#include "lumo/package.h"

#define INFO_FIXED   80u
#define LIGHT_SIZE   72u
#define MESH_HEAD    16u
#define MESH_VERTEX  36u
#define MESH_TRI     12u
#define IVGD_SIZE    48u

static uint32_t rd16(const uint8_t *p) { return (uint32_t)p[0] | ((uint32_t)p[1] << 8); }
static uint32_t rd32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

uint32_t lumo_package_crc32(uint32_t crc, const uint8_t *buf, size_t len)
{
    /* Half-byte table: 64 bytes of constants instead of 1 KiB. */
    static const uint32_t t[16] = {
        0x00000000u, 0x1DB71064u, 0x3B6E20C8u, 0x26D930ACu, 0x76DC4190u, 0x6B6B51F4u,
        0x4DB26158u, 0x5005713Cu, 0xEDB88320u, 0xF00F9344u, 0xD6D6A3E8u, 0xCB61B38Cu,
        0x9B64C2B0u, 0x86D3D2D4u, 0xA00AE278u, 0xBDBDF21Cu};
    size_t i;
    crc = ~crc;
    for (i = 0; i < len; i++) {
        crc ^= buf[i];
        crc = (crc >> 4) ^ t[crc & 15u];
        crc = (crc >> 4) ^ t[crc & 15u];
    }
    return ~crc;
}

static lumo_status check_header(const uint8_t *d, size_t size, uint32_t *count)
{
    if (size < LUMO_PKG_HEADER_SIZE)
        return LUMO_ERR_TRUNCATED;
    if (memcmp(d, "LUMO", 4) != 0)
        return LUMO_ERR_CORRUPT;
    if (lumo_package_crc32(0, d, 20) != rd32(d + 20))
        return LUMO_ERR_CHECKSUM;
    if (rd16(d + 4) != LUMO_PKG_VERSION_MAJOR)
        return LUMO_ERR_VERSION;
    if (rd32(d + 12) != 0)
        return LUMO_ERR_UNSUPPORTED;   /* flags reserved for a later minor */
    *count = rd32(d + 8);
    if (*count > LUMO_PKG_MAX_CHUNKS)
        return LUMO_ERR_LIMIT;
    if ((uint64_t)size < LUMO_PKG_HEADER_SIZE + (uint64_t)*count * LUMO_PKG_ENTRY_SIZE)
        return LUMO_ERR_TRUNCATED;
    return LUMO_OK;
}

/* Chunks must follow the table in order, 4-byte aligned, without overlap,
 * and the last one must end the file. */
static lumo_status check_chunks(const uint8_t *d, size_t size, uint32_t count)
{
    const uint8_t *table = d + LUMO_PKG_HEADER_SIZE;
    uint64_t pos = LUMO_PKG_HEADER_SIZE + (uint64_t)count * LUMO_PKG_ENTRY_SIZE;
    uint32_t i;
    if (lumo_package_crc32(0, table, (size_t)count * LUMO_PKG_ENTRY_SIZE) != rd32(d + 16))
        return LUMO_ERR_CHECKSUM;
    for (i = 0; i < count; i++) {
        const uint8_t *e = table + (size_t)i * LUMO_PKG_ENTRY_SIZE;
        uint64_t off = rd32(e + 4), len = rd32(e + 8);
        if (off < pos || (off & 3u) || off - pos > 3u)
            return LUMO_ERR_CORRUPT;
        if (off > (uint64_t)size)
            return LUMO_ERR_TRUNCATED;
        for (; pos < off; pos++)   /* alignment padding is zero: every byte is checked */
            if (d[pos] != 0)
                return LUMO_ERR_CORRUPT;
        if (off + len > (uint64_t)size)
            return LUMO_ERR_TRUNCATED;
        if (lumo_package_crc32(0, d + off, (size_t)len) != rd32(e + 12))
            return LUMO_ERR_CHECKSUM;
        pos = off + len;
    }
    return pos == (uint64_t)size ? LUMO_OK : LUMO_ERR_CORRUPT;
}

lumo_status lumo_package_open(lumo_package *pkg, const uint8_t *data, size_t size)
{
    uint32_t count = 0;
    lumo_status st;
    if (!pkg || (!data && size))
        return LUMO_ERR_ARG;
    if (!data)
        return LUMO_ERR_TRUNCATED;
    st = check_header(data, size, &count);
    if (st)
        return st;
    st = check_chunks(data, size, count);
    if (st)
        return st;
    pkg->data = data;
    pkg->size = size;
    pkg->version_major = (uint16_t)rd16(data + 4);
    pkg->version_minor = (uint16_t)rd16(data + 6);
    pkg->chunk_count = count;
    return LUMO_OK;
}

lumo_status lumo_package_chunk(const lumo_package *pkg, uint32_t index, lumo_pkg_chunk *out)
{
    const uint8_t *e;
    if (!pkg || !out || !pkg->data)
        return LUMO_ERR_ARG;
    if (index >= pkg->chunk_count)
        return LUMO_ERR_RANGE;
    e = pkg->data + LUMO_PKG_HEADER_SIZE + (size_t)index * LUMO_PKG_ENTRY_SIZE;
    out->type = rd32(e);
    out->offset = rd32(e + 4);
    out->length = rd32(e + 8);
    out->crc = rd32(e + 12);
    return LUMO_OK;
}

lumo_status lumo_package_find(const lumo_package *pkg, uint32_t type, uint32_t nth,
                              const uint8_t **payload, uint32_t *len)
{
    lumo_pkg_chunk c;
    uint32_t i;
    if (!pkg || !payload || !len)
        return LUMO_ERR_ARG;
    for (i = 0; i < pkg->chunk_count; i++) {
        if (lumo_package_chunk(pkg, i, &c))
            return LUMO_ERR_ARG;
        if (c.type == type && nth-- == 0) {
            *payload = pkg->data + c.offset;
            *len = c.length;
            return LUMO_OK;
        }
    }
    return LUMO_ERR_RANGE;
}

/* ---- binary32 fields to fixed point --------------------------------------- */

static lumo_status rd_fixed(const uint8_t *p, unsigned frac, int32_t *out)
{
    return lumo_f32bits_to_fixed(rd32(p), frac, out);
}

static lumo_status rd_q16_3(const uint8_t *p, lumo_q16_16 out[3])
{
    int32_t v[3];
    unsigned i;
    for (i = 0; i < 3; i++) {
        lumo_status st = rd_fixed(p + 4 * i, LUMO_Q16_SHIFT, &v[i]);
        if (st)
            return st;
    }
    for (i = 0; i < 3; i++)
        out[i] = v[i];
    return LUMO_OK;
}

/* A Q1.14 value in [lo, 1] (unit vector components, albedo, cosines). */
static lumo_status rd_q14(const uint8_t *p, int32_t lo, lumo_q1_14 *out)
{
    int32_t v;
    lumo_status st = rd_fixed(p, LUMO_Q14_SHIFT, &v);
    if (st)
        return st;
    if (v < lo || v > LUMO_Q14_ONE)
        return LUMO_ERR_RANGE;
    *out = (lumo_q1_14)v;
    return LUMO_OK;
}

static lumo_status rd_q14_3(const uint8_t *p, int32_t lo, lumo_q1_14 out[3])
{
    lumo_q1_14 v[3];
    unsigned i;
    for (i = 0; i < 3; i++) {
        lumo_status st = rd_q14(p + 4 * i, lo, &v[i]);
        if (st)
            return st;
    }
    for (i = 0; i < 3; i++)
        out[i] = v[i];
    return LUMO_OK;
}

static lumo_status find_info(const lumo_package *pkg, const uint8_t **p, uint32_t *len)
{
    lumo_status st = lumo_package_find(pkg, LUMO_PKG_INFO, 0, p, len);
    if (st == LUMO_ERR_RANGE)
        return LUMO_ERR_CORRUPT;   /* the info chunk is mandatory */
    if (st)
        return st;
    if (*len < INFO_FIXED)
        return LUMO_ERR_TRUNCATED;
    if (rd32(*p + 4) > LUMO_PKG_MAX_LIGHTS)
        return LUMO_ERR_LIMIT;
    if (*len != INFO_FIXED + rd32(*p + 4) * LIGHT_SIZE)
        return LUMO_ERR_CORRUPT;
    return LUMO_OK;
}

lumo_status lumo_package_info(const lumo_package *pkg, lumo_pkg_info *out)
{
    const uint8_t *p;
    uint32_t len;
    lumo_pkg_info r;
    int32_t fovy;
    lumo_status st;
    if (!out)
        return LUMO_ERR_ARG;
    st = find_info(pkg, &p, &len);
    if (st)
        return st;
    r.mesh_count = rd32(p);
    r.light_count = rd32(p + 4);
    r.triangle_count = rd32(p + 8);
    st = rd_q16_3(p + 16, r.bmin);
    if (!st) st = rd_q16_3(p + 28, r.bmax);
    if (!st) st = rd_q16_3(p + 40, r.eye);
    if (!st) st = rd_q16_3(p + 52, r.target);
    if (!st) st = rd_q16_3(p + 64, r.up);
    if (!st) st = rd_fixed(p + 76, LUMO_Q16_SHIFT, &fovy);
    if (st)
        return st;
    if (fovy <= 0 || fovy >= LUMO_Q16_FROM_INT(180))
        return LUMO_ERR_RANGE;
    r.fovy_deg = fovy;
    *out = r;
    return LUMO_OK;
}

lumo_status lumo_package_light(const lumo_package *pkg, uint32_t index, lumo_pkg_light *out)
{
    const uint8_t *p;
    uint32_t len, kind;
    lumo_pkg_light l;
    int32_t w[3];
    lumo_status st;
    unsigned i;
    if (!out)
        return LUMO_ERR_ARG;
    st = find_info(pkg, &p, &len);
    if (st)
        return st;
    if (index >= rd32(p + 4))
        return LUMO_ERR_RANGE;
    p += INFO_FIXED + (size_t)index * LIGHT_SIZE;
    kind = rd32(p);
    if (kind > LUMO_PKG_LIGHT_AREA)
        return LUMO_ERR_UNSUPPORTED;
    l.kind = (lumo_pkg_light_kind)kind;
    st = rd_q16_3(p + 4, l.pos);
    if (!st) st = rd_q14_3(p + 16, -LUMO_Q14_ONE, l.dir);
    if (!st) st = rd_q16_3(p + 28, l.u);
    if (!st) st = rd_q16_3(p + 40, l.v);
    if (!st) st = rd_fixed(p + 52, LUMO_Q16_SHIFT, &l.half_angle_deg);
    if (!st) st = rd_q14(p + 56, -LUMO_Q14_ONE, &l.cos_half);
    for (i = 0; !st && i < 3; i++) {
        st = rd_fixed(p + 60 + 4 * i, LUMO_Q16_SHIFT, &w[i]);
        if (!st && w[i] < 0)
            st = LUMO_ERR_RANGE;
    }
    if (st)
        return st;
    for (i = 0; i < 3; i++)
        l.power[i] = (lumo_uq16_16)w[i];
    *out = l;
    return LUMO_OK;
}

/* ---- meshes ------------------------------------------------------------- */

static lumo_status find_mesh(const lumo_package *pkg, uint32_t index, const uint8_t **p,
                             lumo_pkg_mesh_info *mi)
{
    uint32_t len;
    lumo_status st = lumo_package_find(pkg, LUMO_PKG_MESH, index, p, &len);
    if (st)
        return st;
    if (len < MESH_HEAD)
        return LUMO_ERR_TRUNCATED;
    mi->flags = rd32(*p);
    mi->nverts = rd32(*p + 4);
    mi->ntris = rd32(*p + 8);
    if (mi->flags & ~LUMO_PKG_MESH_EMITTER)
        return LUMO_ERR_UNSUPPORTED;
    if ((uint64_t)len != MESH_HEAD + (uint64_t)mi->nverts * MESH_VERTEX + (uint64_t)mi->ntris * MESH_TRI)
        return LUMO_ERR_CORRUPT;
    return LUMO_OK;
}

lumo_status lumo_package_mesh_info(const lumo_package *pkg, uint32_t index, lumo_pkg_mesh_info *out)
{
    const uint8_t *p;
    lumo_pkg_mesh_info mi;
    lumo_status st;
    if (!out)
        return LUMO_ERR_ARG;
    st = find_mesh(pkg, index, &p, &mi);
    if (st)
        return st;
    *out = mi;
    return LUMO_OK;
}

/* One vertex record: position, normal, albedo; NULL outputs only validate. */
static lumo_status mesh_vertex(const uint8_t *p, lumo_q16_16 *pos, lumo_q1_14 *nrm, lumo_q1_14 *alb)
{
    lumo_q16_16 tp[3];
    lumo_q1_14 tn[3], ta[3];
    lumo_status st = rd_q16_3(p, tp);
    if (!st) st = rd_q14_3(p + 12, -LUMO_Q14_ONE, tn);
    if (!st) st = rd_q14_3(p + 24, 0, ta);
    if (st)
        return st;
    if (pos)
        memcpy(pos, tp, sizeof tp);
    if (nrm)
        memcpy(nrm, tn, sizeof tn);
    if (alb)
        memcpy(alb, ta, sizeof ta);
    return LUMO_OK;
}

lumo_status lumo_package_mesh_read(const lumo_package *pkg, uint32_t index, lumo_q16_16 *pos,
                                   lumo_q1_14 *nrm, lumo_q1_14 *albedo, uint32_t *tris)
{
    const uint8_t *p, *t;
    lumo_pkg_mesh_info mi;
    uint32_t i;
    lumo_status st;
    if (!pos)
        return LUMO_ERR_ARG;
    st = find_mesh(pkg, index, &p, &mi);
    if (st)
        return st;
    p += MESH_HEAD;
    t = p + (size_t)mi.nverts * MESH_VERTEX;
    /* Pass 1 validates everything, pass 2 writes: outputs stay untouched on error. */
    for (i = 0; i < mi.nverts; i++)
        if ((st = mesh_vertex(p + (size_t)i * MESH_VERTEX, NULL, NULL, NULL)) != LUMO_OK)
            return st;
    for (i = 0; i < 3u * mi.ntris; i++)
        if (rd32(t + 4 * (size_t)i) >= mi.nverts)
            return LUMO_ERR_RANGE;
    for (i = 0; i < mi.nverts; i++)
        mesh_vertex(p + (size_t)i * MESH_VERTEX, pos + 3 * (size_t)i, nrm ? nrm + 3 * (size_t)i : NULL,
                    albedo ? albedo + 3 * (size_t)i : NULL);
    for (i = 0; tris && i < 3u * mi.ntris; i++)
        tris[i] = rd32(t + 4 * (size_t)i);
    return LUMO_OK;
}

/* ---- IVG ---------------------------------------------------------------- */

lumo_status lumo_package_ivg_desc(const lumo_package *pkg, lumo_ivg_desc *out)
{
    const uint8_t *p;
    uint32_t len, i;
    lumo_ivg_desc d;
    lumo_status st;
    if (!out)
        return LUMO_ERR_ARG;
    st = lumo_package_find(pkg, LUMO_PKG_IVGD, 0, &p, &len);
    if (st)
        return st;
    if (len != IVGD_SIZE)
        return len < IVGD_SIZE ? LUMO_ERR_TRUNCATED : LUMO_ERR_CORRUPT;
    st = rd_q16_3(p + 8, d.bmin);
    if (!st)
        st = rd_q16_3(p + 20, d.bmax);
    if (st)
        return st;
    for (i = 0; i < 3; i++) {
        d.dims[i] = (uint16_t)rd16(p + 2 * i);
        if (d.dims[i] < LUMO_IVG_MIN_DIM || d.dims[i] > LUMO_IVG_MAX_DIM || d.bmax[i] <= d.bmin[i])
            return LUMO_ERR_RANGE;
    }
    *out = d;
    return LUMO_OK;
}

lumo_status lumo_package_load_ivg(const lumo_package *pkg, lumo_ivg *g, lumo_ivg_form form,
                                  uint32_t *applied)
{
    const uint8_t *p;
    uint32_t len;
    lumo_status st;
    if (!g)
        return LUMO_ERR_ARG;
    st = lumo_package_find(pkg, form == LUMO_IVG_FORM_FLOAT ? LUMO_PKG_IVGF : LUMO_PKG_IVGQ, 0, &p, &len);
    if (st)
        return st;
    return lumo_ivg_apply_bundle(g, p, len, applied);
}
