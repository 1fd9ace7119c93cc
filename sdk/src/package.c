/*
 * package.c — the .lumo package container (docs/package-format.md): header,
 * chunk table, checksums; the payloads are decoded by scene_payload.c,
 * pmesh.c and ivg_bundle.c. Validates everything it reads; integer code
 * only; no allocation.
 */
#include <string.h>
#include "lumo/package.h"
#include "lumo/wire.h"


static lumo_status check_header(const uint8_t *d, size_t size, uint32_t *count)
{
    if (size < LUMO_PKG_HEADER_SIZE)
        return LUMO_ERR_TRUNCATED;
    if (memcmp(d, "LUMO", 4) != 0)
        return LUMO_ERR_CORRUPT;
    if (lumo_wire_crc32(0, d, 20) != lumo_wire_le32(d + 20))
        return LUMO_ERR_CHECKSUM;
    if (lumo_wire_le16(d + 4) != LUMO_PKG_VERSION_MAJOR)
        return LUMO_ERR_VERSION;
    if (lumo_wire_le32(d + 12) != 0)
        return LUMO_ERR_UNSUPPORTED;   /* flags reserved for a later minor */
    *count = lumo_wire_le32(d + 8);
    if (*count > LUMO_PKG_MAX_CHUNKS)
        return LUMO_ERR_LIMIT;
    if ((uint64_t)size < LUMO_PKG_HEADER_SIZE + (uint64_t)*count * LUMO_PKG_ENTRY_SIZE)
        return LUMO_ERR_TRUNCATED;
    return LUMO_OK;
}

/* The chunks the format allows once at most (docs/package-format.md):
 * a second INFO or IVG descriptor would leave a reader to guess which one
 * the writer meant. */
static const uint32_t k_singletons[] = {LUMO_PKG_INFO, LUMO_PKG_IVGD, LUMO_PKG_IVGQ,
                                        LUMO_PKG_IVGF, LUMO_PKG_IVGS, LUMO_PKG_ORDR};

lumo_status lumo_package_table_once(const uint8_t *table, uint32_t count, uint32_t *twice)
{
    unsigned k;
    uint32_t i, seen;
    if (!table && count)
        return LUMO_ERR_ARG;
    for (k = 0; k < sizeof k_singletons / sizeof k_singletons[0]; k++) {
        for (i = 0, seen = 0; i < count; i++)
            seen += lumo_wire_le32(table + (size_t)i * LUMO_PKG_ENTRY_SIZE) == k_singletons[k];
        if (seen > 1) {
            if (twice)
                *twice = k_singletons[k];
            return LUMO_ERR_CORRUPT;
        }
    }
    return LUMO_OK;
}

/* Chunks must follow the table in order, 4-byte aligned, without overlap,
 * and the last one must end the file. */
static lumo_status check_chunks(const uint8_t *d, size_t size, uint32_t count)
{
    const uint8_t *table = d + LUMO_PKG_HEADER_SIZE;
    uint64_t pos = LUMO_PKG_HEADER_SIZE + (uint64_t)count * LUMO_PKG_ENTRY_SIZE;
    uint32_t i;
    if (lumo_wire_crc32(0, table, (size_t)count * LUMO_PKG_ENTRY_SIZE) != lumo_wire_le32(d + 16))
        return LUMO_ERR_CHECKSUM;
    for (i = 0; i < count; i++) {
        const uint8_t *e = table + (size_t)i * LUMO_PKG_ENTRY_SIZE;
        uint64_t off = lumo_wire_le32(e + 4), len = lumo_wire_le32(e + 8);
        if (off < pos || (off & 3u) || off - pos > 3u)
            return LUMO_ERR_CORRUPT;
        if (off > (uint64_t)size)
            return LUMO_ERR_TRUNCATED;
        for (; pos < off; pos++)   /* alignment padding is zero: every byte is checked */
            if (d[pos] != 0)
                return LUMO_ERR_CORRUPT;
        if (off + len > (uint64_t)size)
            return LUMO_ERR_TRUNCATED;
        if (lumo_wire_crc32(0, d + off, (size_t)len) != lumo_wire_le32(e + 12))
            return LUMO_ERR_CHECKSUM;
        pos = off + len;
    }
    if (pos != (uint64_t)size)
        return LUMO_ERR_CORRUPT;
    return lumo_package_table_once(table, count, NULL);
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
    pkg->version_major = (uint16_t)lumo_wire_le16(data + 4);
    pkg->version_minor = (uint16_t)lumo_wire_le16(data + 6);
    pkg->chunk_count = count;
    return LUMO_OK;
}

lumo_status lumo_package_peek_version(const uint8_t *data, size_t size, uint16_t *major, uint16_t *minor)
{
    if (!data || !major || !minor)
        return LUMO_ERR_ARG;
    if (size < 8)
        return LUMO_ERR_TRUNCATED;
    if (memcmp(data, "LUMO", 4) != 0)
        return LUMO_ERR_CORRUPT;
    *major = lumo_wire_le16(data + 4);
    *minor = lumo_wire_le16(data + 6);
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
    out->type = lumo_wire_le32(e);
    out->offset = lumo_wire_le32(e + 4);
    out->length = lumo_wire_le32(e + 8);
    out->crc = lumo_wire_le32(e + 12);
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

/* ---- payload getters: the chunk, then its decoder -------------------------- */

lumo_status lumo_package_info(const lumo_package *pkg, lumo_pkg_info *out)
{
    const uint8_t *p = NULL;
    uint32_t len = 0;
    lumo_status st = lumo_package_find(pkg, LUMO_PKG_INFO, 0, &p, &len);
    if (st)
        return st == LUMO_ERR_RANGE ? LUMO_ERR_CORRUPT : st;   /* INFO is mandatory */
    return lumo_scene_info_decode(p, len, out);
}

lumo_status lumo_package_light(const lumo_package *pkg, uint32_t index, lumo_pkg_light *out)
{
    const uint8_t *p = NULL;
    uint32_t len = 0;
    lumo_status st = lumo_package_find(pkg, LUMO_PKG_INFO, 0, &p, &len);
    if (st)
        return st == LUMO_ERR_RANGE ? LUMO_ERR_CORRUPT : st;
    return lumo_scene_light_decode(p, len, index, out);
}

lumo_status lumo_package_mesh_info(const lumo_package *pkg, uint32_t index, lumo_pkg_mesh_info *out)
{
    const uint8_t *p = NULL;
    uint32_t len = 0;
    lumo_status st = lumo_package_find(pkg, LUMO_PKG_MESH, index, &p, &len);
    return st ? st : lumo_scene_mesh_info_decode(p, len, out);
}

lumo_status lumo_package_mesh_read(const lumo_package *pkg, uint32_t index, lumo_q16_16 *pos,
                                   lumo_q1_14 *nrm, lumo_q1_14 *albedo, uint32_t *tris)
{
    const uint8_t *p = NULL;
    uint32_t len = 0;
    lumo_status st = lumo_package_find(pkg, LUMO_PKG_MESH, index, &p, &len);
    return st ? st : lumo_scene_mesh_decode(p, len, pos, nrm, albedo, tris);
}

lumo_status lumo_package_ivg_desc(const lumo_package *pkg, lumo_ivg_desc *out)
{
    const uint8_t *p = NULL;
    uint32_t len = 0;
    lumo_status st = lumo_package_find(pkg, LUMO_PKG_IVGD, 0, &p, &len);
    return st ? st : lumo_scene_ivg_desc_decode(p, len, out);
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

lumo_status lumo_package_ivg_order(const lumo_package *pkg, lumo_ivg_order *out)
{
    static const uint32_t types[2] = {LUMO_PKG_IVGQ, LUMO_PKG_IVGF};
    static const lumo_ivg_form forms[2] = {LUMO_IVG_FORM_QUANTIZED, LUMO_IVG_FORM_FLOAT};
    const uint8_t *p, *b;
    uint32_t len, blen, i;
    lumo_ivg_desc d;
    lumo_ivg_order o;
    lumo_status st;
    if (!out)
        return LUMO_ERR_ARG;
    if ((st = lumo_package_ivg_desc(pkg, &d)) || (st = lumo_package_find(pkg, LUMO_PKG_IVGS, 0, &p, &len)) ||
        (st = lumo_ivg_order_decode(p, len, &d, &o)))
        return st;
    for (i = 0; i < 2; i++)
        if (lumo_package_find(pkg, types[i], 0, &b, &blen) == LUMO_OK &&
            (st = lumo_ivg_order_check_bundle(&o, forms[i], b, blen)))
            return st;
    *out = o;
    return LUMO_OK;
}

lumo_status lumo_package_order(const lumo_package *pkg, lumo_scene_order *out)
{
    const uint8_t *p;
    uint32_t len;
    lumo_pkg_info info;
    lumo_status st;
    if ((st = lumo_package_info(pkg, &info)) || (st = lumo_package_find(pkg, LUMO_PKG_ORDR, 0, &p, &len)))
        return st;
    return lumo_scene_order_decode(p, len, info.mesh_count, out);
}
