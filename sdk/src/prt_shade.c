/* prt_shade.c — relighting with clustered-PCA transfer (lumo/prt.h; seed
 * 003 §3.2, Eq. 7): the per-cluster dot products once per frame, then the
 * per-vertex weighted sums. */
#include "lumo/prt.h"
#include "lumo/wire.h"

static int32_t le_s16(const uint8_t *p)
{
    uint32_t u = lumo_wire_le16(p);
    return (int32_t)u - (int32_t)((u & 0x8000u) << 1);
}

size_t lumo_prt_frame_entries(const lumo_prt *p)
{
    return p ? 3u * (size_t)p->clusters * ((size_t)p->components + 1u) : 0;
}

/* sum_i v_i (Q1.14, little-endian int16) * l_i (Q16.16), as Q16.16. */
static lumo_q16_16 dot(const uint8_t *v, const lumo_q16_16 *l, unsigned n)
{
    int64_t s = 0;
    for (unsigned i = 0; i < n; i++)
        s += (int64_t)le_s16(v + 2u * i) * l[i];
    return lumo_sat_i32(lumo_round_shift(s, LUMO_Q14_SHIFT));
}

lumo_status lumo_prt_frame(const lumo_prt *p, const lumo_prt_light *l, lumo_q16_16 *frame)
{
    if (!p || !l || !frame || !p->cluster_data)
        return LUMO_ERR_ARG;
    if (l->order != p->order)
        return LUMO_ERR_RANGE;
    unsigned nc = (unsigned)p->order * p->order, np = p->components + 1u;
    size_t rec = lumo_prt_cluster_bytes(p->order, p->components);
    for (uint32_t k = 0; k < p->clusters; k++) {
        const uint8_t *r = p->cluster_data + (size_t)k * rec;
        for (unsigned c = 0; c < 3; c++)
            for (unsigned j = 0; j < np; j++)   /* j = 0: the mean, then B_1..B_P */
                frame[((size_t)k * 3u + c) * np + j] = dot(r + 2u * nc * j, l->c[c], nc);
    }
    return LUMO_OK;
}

/* One channel of one vertex: M.L + sum_j w_j (B_j.L), Q16.16 in int64. */
static int64_t vertex_channel(const uint8_t *w, unsigned npc, const lumo_q16_16 *f)
{
    int64_t acc = (int64_t)f[0] * LUMO_Q14_ONE;
    for (unsigned j = 0; j < npc; j++)
        acc += (int64_t)le_s16(w + 2u * j) * f[1 + j];
    return lumo_round_shift(acc, LUMO_Q14_SHIFT);
}

lumo_status lumo_prt_shade(const lumo_prt *p, const lumo_q16_16 *frame, const lumo_q1_14 *albedo,
                           uint32_t first, uint32_t count, lumo_uq16_16 *lit)
{
    if (!p || !frame || !lit || !p->vertex_data)
        return LUMO_ERR_ARG;
    if (first > p->vertices_held || count > p->vertices_held - first)
        return LUMO_ERR_RANGE;
    unsigned npc = p->components, np = npc + 1u;
    size_t vb = lumo_prt_vertex_bytes(npc);
    for (uint32_t i = 0; i < count; i++) {
        uint32_t v = first + i;
        const uint8_t *r = p->vertex_data + (size_t)v * vb;
        uint32_t k = lumo_wire_le16(r);   /* checked < K by lumo_prt_parse */
        for (unsigned c = 0; c < 3; c++) {
            int64_t t = vertex_channel(r + 2, npc, &frame[((size_t)k * 3u + c) * np]);
            int64_t a = albedo ? albedo[3u * (size_t)v + c] : LUMO_Q14_ONE;
            lit[6u * (size_t)v + c] = lumo_sat_u32(lumo_round_shift(t * a, LUMO_Q14_SHIFT));
            lit[6u * (size_t)v + 3u + c] = 0;
        }
    }
    return LUMO_OK;
}
