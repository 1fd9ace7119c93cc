/* prt.c — the PRTV chunk reader (lumo/prt.h, docs/package-format.md
 * "PRTV"): header, cluster records, pass table, vertex records in the
 * progressive mesh's vertex order, so that a prefix relights the vertices
 * it holds. */
#include "lumo/prt.h"
#include "lumo/wire.h"

size_t lumo_prt_cluster_bytes(unsigned order, unsigned components)
{
    return 2u * (size_t)order * order * ((size_t)components + 1u);
}

size_t lumo_prt_vertex_bytes(unsigned components)
{
    return 2u + 2u * (size_t)components;
}

static lumo_status parse_header(lumo_prt *p, const uint8_t *d, size_t len)
{
    if (len < LUMO_PRT_HEADER_SIZE)
        return LUMO_ERR_TRUNCATED;
    if (d[0] != LUMO_PRT_VERSION)
        return LUMO_ERR_VERSION;
    p->order = d[1], p->components = d[2];
    p->clusters = lumo_wire_le32(d + 4), p->vertices = lumo_wire_le32(d + 8);
    if (d[3] != 0)
        return LUMO_ERR_CORRUPT;
    if (p->order < 1 || p->order > LUMO_PRT_MAX_ORDER || p->clusters < 1)
        return LUMO_ERR_RANGE;
    if (p->clusters > LUMO_PRT_MAX_CLUSTERS || p->components > LUMO_PRT_MAX_COMPONENTS || p->clusters > 65535u)
        return LUMO_ERR_LIMIT;
    return LUMO_OK;
}

uint32_t lumo_prt_pass(const lumo_prt *p, uint32_t k)
{
    return p && k < p->clusters ? lumo_wire_le16(p->pass_data + 2u * k) : 0;
}

lumo_status lumo_prt_parse(lumo_prt *out, const uint8_t *data, size_t len)
{
    lumo_prt p;
    lumo_status st;
    if (!out || !data)
        return LUMO_ERR_ARG;
    if ((st = parse_header(&p, data, len)) != LUMO_OK)
        return st;
    /* K <= 65535 and the record sizes are small: no overflow in size_t >= 32 bits */
    size_t cbytes = (size_t)p.clusters * (lumo_prt_cluster_bytes(p.order, p.components) + 2u);
    size_t vbytes = lumo_prt_vertex_bytes(p.components);
    if (len - LUMO_PRT_HEADER_SIZE < cbytes)
        return LUMO_ERR_TRUNCATED;
    size_t rest = len - LUMO_PRT_HEADER_SIZE - cbytes;
    if (rest / vbytes > p.vertices || (rest / vbytes == p.vertices && rest % vbytes != 0))
        return LUMO_ERR_CORRUPT;
    p.cluster_data = data + LUMO_PRT_HEADER_SIZE;
    p.pass_data = p.cluster_data + cbytes - 2u * (size_t)p.clusters;
    p.vertex_data = p.cluster_data + cbytes;
    p.vertices_held = (uint32_t)(rest / vbytes);
    for (uint32_t k = 0; k < p.clusters; k++)
        if (lumo_wire_le16(p.pass_data + 2u * k) >= p.clusters)
            return LUMO_ERR_RANGE;
    for (uint32_t v = 0; v < p.vertices_held; v++)
        if (lumo_wire_le16(p.vertex_data + (size_t)v * vbytes) >= p.clusters)
            return LUMO_ERR_RANGE;
    *out = p;
    return LUMO_OK;
}
