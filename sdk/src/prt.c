/* prt.c — the PRTV chunk reader (lumo/prt.h, docs/package-format.md
 * "PRTV"): header, cluster records, pass table, vertex records in the
 * progressive mesh's vertex order, so that a prefix relights the vertices
 * it holds. */
#include "lumo/arena.h"
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

lumo_status lumo_prt_chunk_size(const uint8_t *data, size_t len, size_t *total, size_t *fixed)
{
    lumo_prt p;
    lumo_status st;
    if (!data || !total || !fixed)
        return LUMO_ERR_ARG;
    if ((st = parse_header(&p, data, len)) != LUMO_OK)
        return st;
    size_t f = (size_t)LUMO_PRT_HEADER_SIZE + (size_t)p.clusters * (lumo_prt_cluster_bytes(p.order, p.components) + 2u);
    size_t v = lumo_size_mul(p.vertices, lumo_prt_vertex_bytes(p.components));
    if (v == SIZE_MAX || lumo_size_add(f, v) == SIZE_MAX)
        return LUMO_ERR_OVERFLOW;
    *fixed = f;
    *total = f + v;
    return LUMO_OK;
}

/* The units ending in (from, end] of one table of `n` entries of `size`
 * bytes at `base` whose first two bytes name a cluster: all < k. */
static lumo_status check_table(const uint8_t *data, size_t base, size_t size, size_t n, size_t from, size_t end,
                               uint32_t k)
{
    size_t i = from < base + size ? 0 : (from - base - size) / size + 1;   /* first unit ending after from */
    for (; i < n && base + (i + 1u) * size <= end; i++)
        if (lumo_wire_le16(data + base + i * size) >= k)
            return LUMO_ERR_RANGE;
    return LUMO_OK;
}

lumo_status lumo_prt_check_span(const uint8_t *data, size_t from, size_t end)
{
    lumo_prt p;
    if (!data || end < LUMO_PRT_HEADER_SIZE || from > end || parse_header(&p, data, end) != LUMO_OK)
        return LUMO_ERR_ARG;
    size_t passes = (size_t)LUMO_PRT_HEADER_SIZE + (size_t)p.clusters * lumo_prt_cluster_bytes(p.order, p.components);
    size_t verts = passes + 2u * (size_t)p.clusters;
    lumo_status st = check_table(data, passes, 2u, p.clusters, from, end, p.clusters);
    return st ? st : check_table(data, verts, lumo_prt_vertex_bytes(p.components), p.vertices, from, end, p.clusters);
}

lumo_status lumo_prt_light_decode(const uint8_t *p, size_t len, lumo_prt_light *out)
{
    if (!p || !out)
        return LUMO_ERR_ARG;
    if (len < 4)
        return LUMO_ERR_TRUNCATED;
    if (p[0] < 1 || p[0] > LUMO_PRT_MAX_ORDER)
        return LUMO_ERR_RANGE;
    if (p[1] || p[2] || p[3] || len != 4u + 12u * p[0] * p[0])
        return LUMO_ERR_CORRUPT;
    unsigned n = (unsigned)p[0] * p[0];
    lumo_prt_light_clear(out, p[0]);
    for (unsigned c = 0; c < 3; c++)
        for (unsigned i = 0; i < n; i++)
            out->c[c][i] = (lumo_q16_16)lumo_wire_le32(p + 4u + 4u * (c * n + i));
    return LUMO_OK;
}
