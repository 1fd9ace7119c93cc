/*
 * ivg_grid.c — creation, memory accounting and accessors of the Irradiance
 * Vector Grid (seed 000 §3; lumo/ivg.h). Decoding lives in ivg_bundle.c,
 * hole filling in ivg_pushpull.c, shading in ivg_sample.c.
 */
#include <string.h>
#include "ivg_internal.h"

/* Every arena allocation create() makes, in order; memory_size() adds them
 * up from the same plan so the two can never disagree. */
typedef struct ivg_plan {
    unsigned levels;
    uint32_t dims[IVG_MAX_LEVELS][3];
    uint32_t count[IVG_MAX_LEVELS];
    size_t   bitmap_bytes;            /* one bit per grid vertex */
} ivg_plan;

static int desc_valid(const lumo_ivg_desc *d)
{
    int a;

    if (d == NULL)
        return 0;
    for (a = 0; a < 3; a++) {
        if (d->dims[a] < LUMO_IVG_MIN_DIM || d->dims[a] > LUMO_IVG_MAX_DIM)
            return 0;
        if (d->bmax[a] <= d->bmin[a])
            return 0;
    }
    return 1;
}

static size_t bits_bytes(uint32_t count)
{
    return ((size_t)count + 7u) / 8u;
}

/* The pyramid: halve every axis (ivg_coarse_dim) until one vertex is left. */
static void plan_levels(const lumo_ivg_desc *d, ivg_plan *p)
{
    unsigned l = 0;
    int a;

    for (a = 0; a < 3; a++)
        p->dims[0][a] = d->dims[a];
    for (;;) {
        p->count[l] = p->dims[l][0] * p->dims[l][1] * p->dims[l][2];
        if (p->count[l] == 1u)
            break;
        for (a = 0; a < 3; a++)
            p->dims[l + 1][a] = ivg_coarse_dim(p->dims[l][a]);
        l++;
    }
    p->levels = l + 1;
    p->bitmap_bytes = bits_bytes(p->count[0]);
}

/* Every level's vertices are packed (ivg_pack.c): 42 bytes each. */
static size_t entries_bytes(uint32_t count)
{
    return lumo_arena_round(lumo_size_mul(count, IVG_PACKED_VERTEX));
}

/* Smoothing keeps three x-y planes of sums of the largest coarse level. */
static size_t smooth_sums(const ivg_plan *p)
{
    return (size_t)3u * p->dims[1][0] * p->dims[1][1];
}

/* Planes of level 1 kept in each of its two rings (before and after
 * smoothing, ivg_pushpull.c): the three a smoothing or a push reads; 0 (the
 * level kept whole) when two rings would hold as many planes as the level
 * (level 1 of 6 planes or fewer: grid axes of 10 or fewer along z). */
#define IVG_RING_PLANES 3u

static uint32_t ring_planes(const ivg_plan *p)
{
    return p->levels > 1 && p->dims[1][2] > 2u * IVG_RING_PLANES ? IVG_RING_PLANES : 0u;
}

/* Vertices a level stores: level 1 its ring's planes, the others all. */
static uint32_t stored(const ivg_plan *p, unsigned l)
{
    return l == 1u && ring_planes(p) ? ring_planes(p) * p->dims[1][0] * p->dims[1][1] : p->count[l];
}

static size_t plan_bytes(const ivg_plan *p)
{
    size_t total = lumo_arena_round(sizeof(lumo_ivg));
    unsigned l;

    total = lumo_size_add(total, entries_bytes(p->count[0]));
    total = lumo_size_add(total, lumo_size_mul(3, lumo_arena_round(p->bitmap_bytes)));
    for (l = 1; l < p->levels; l++) {
        total = lumo_size_add(total, entries_bytes(stored(p, l)));
        total = lumo_size_add(total, lumo_arena_round(bits_bytes(stored(p, l))));
    }
    if (p->levels > 1)
        total = lumo_size_add(total, lumo_arena_round(lumo_size_mul(smooth_sums(p), sizeof(ivg_sum))));
    if (ring_planes(p)) {   /* level 1 before smoothing */
        total = lumo_size_add(total, entries_bytes(stored(p, 1)));
        total = lumo_size_add(total, lumo_arena_round(bits_bytes(stored(p, 1))));
    }
    return total;
}

size_t lumo_ivg_memory_size(const lumo_ivg_desc *desc)
{
    ivg_plan p;

    if (!desc_valid(desc))
        return 0;
    plan_levels(desc, &p);
    return plan_bytes(&p);
}

static uint8_t *alloc_entries(lumo_arena *a, uint32_t count)
{
    return lumo_arena_alloc(a, lumo_size_mul(count, IVG_PACKED_VERTEX));
}

/* Sampling maps p to grid units with one multiply per axis (§3.2):
 * u = (p - bmin) * scale >> 32 in Q16.16, scale = (dims-1) * 2^48 / extent.
 * The only 64-bit division of the grid is here, once per axis. */
static void init_scale(lumo_ivg *g)
{
    int a;

    for (a = 0; a < 3; a++) {
        uint64_t extent = (uint64_t)((int64_t)g->desc.bmax[a] - g->desc.bmin[a]);
        uint64_t num = (uint64_t)(g->desc.dims[a] - 1u) << 48;
        g->extent[a] = (uint32_t)extent;
        g->scale[a] = (num + extent / 2u) / extent;
    }
}

lumo_status lumo_ivg_create(lumo_ivg **out, lumo_arena *arena, const lumo_ivg_desc *desc)
{
    lumo_arena_mark mark;
    ivg_plan p;
    lumo_ivg *g;
    unsigned l;

    if (out == NULL || arena == NULL || !desc_valid(desc))
        return LUMO_ERR_ARG;
    plan_levels(desc, &p);
    if (plan_bytes(&p) > lumo_arena_remaining(arena))
        return LUMO_ERR_NOMEM;
    mark = lumo_arena_get_mark(arena);
    g = lumo_arena_alloc(arena, sizeof *g);
    if (g == NULL)
        return LUMO_ERR_NOMEM;
    g->desc = *desc;
    g->count = p.count[0];
    g->levels = p.levels;
    g->received_bits = lumo_arena_alloc(arena, p.bitmap_bytes);
    g->solid_bits = lumo_arena_alloc(arena, p.bitmap_bytes);
    g->seen_bits = lumo_arena_alloc(arena, p.bitmap_bytes);
    for (l = 0; l < p.levels; l++) {
        memcpy(g->level[l].dims, p.dims[l], sizeof p.dims[l]);
        g->level[l].count = p.count[l];
        g->level[l].ring = l == 1u ? ring_planes(&p) : 0u;
        g->level[l].e = alloc_entries(arena, stored(&p, l));
        g->level[l].valid = l == 0 ? NULL : lumo_arena_alloc(arena, bits_bytes(stored(&p, l)));
    }
    g->scratch = p.levels > 1 ? lumo_arena_alloc_array(arena, smooth_sums(&p), sizeof(ivg_sum)) : NULL;
    if (ring_planes(&p)) {
        g->raw1 = g->level[1];
        g->raw1.e = alloc_entries(arena, stored(&p, 1));
        g->raw1.valid = lumo_arena_alloc(arena, bits_bytes(stored(&p, 1)));
    }
    /* plan_bytes() was checked against the room left, so these cannot fail;
     * the check stays in case the two ever drift apart. */
    if (g->received_bits == NULL || g->solid_bits == NULL || g->seen_bits == NULL
        || g->level[p.levels - 1].e == NULL || (p.levels > 1 && g->scratch == NULL) || (ring_planes(&p) && g->raw1.valid == NULL)) {
        lumo_arena_reset(arena, mark);
        return LUMO_ERR_NOMEM;
    }
    init_scale(g);
    *out = g;
    return LUMO_OK;
}

const lumo_ivg_desc *lumo_ivg_get_desc(const lumo_ivg *g)
{
    return g == NULL ? NULL : &g->desc;
}

uint32_t lumo_ivg_vertex_count(const lumo_ivg *g)
{
    return g == NULL ? 0 : g->count;
}

uint32_t lumo_ivg_received_count(const lumo_ivg *g)
{
    return g == NULL ? 0 : g->received;
}

uint32_t lumo_ivg_solid_count(const lumo_ivg *g)
{
    return g == NULL ? 0 : g->solid;
}

int lumo_ivg_is_received(const lumo_ivg *g, uint32_t vertex)
{
    return g != NULL && vertex < g->count && ivg_bit(g->received_bits, vertex);
}

int lumo_ivg_is_solid(const lumo_ivg *g, uint32_t vertex)
{
    return g != NULL && vertex < g->count && ivg_bit(g->solid_bits, vertex);
}

lumo_status lumo_ivg_entry_get(const lumo_ivg *g, uint32_t vertex, lumo_ivg_axis axis, lumo_ivg_entry *out)
{
    if (g == NULL || out == NULL || vertex >= g->count || (unsigned)axis >= (unsigned)LUMO_IVG_AXES)
        return LUMO_ERR_ARG;
    ivg_entry_unpack(ivg_packed_at(&g->level[0], vertex, (unsigned)axis), out);
    return LUMO_OK;
}
