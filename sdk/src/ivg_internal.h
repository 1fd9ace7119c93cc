/*
 * ivg_internal.h — the layout of lumo_ivg shared by the sdk/src/ivg_*.c
 * modules (grid, bundle decoder, push-pull, sampling). Not public.
 */
#ifndef LUMO_IVG_INTERNAL_H
#define LUMO_IVG_INTERNAL_H

#include "lumo/ivg.h"

/* Pyramid levels including the grid itself: 256 -> 129 -> 65 -> 33 -> 17 ->
 * 9 -> 5 -> 3 -> 2 -> 1 is the longest chain (10 levels). */
#define IVG_MAX_LEVELS 12

/* Weighted sums of one entry's values and of the weights (push-pull
 * smoothing works one hemisphere at a time on these). */
typedef struct ivg_sum {
    uint64_t c[3];
    int32_t  d[3];
    uint32_t w;
} ivg_sum;

/* Bytes of one stored (packed) entry and of one vertex's six: the
 * quantized wire form itself (docs/ivg-format.md §2.5): d as 3 x int8
 * (q/127), c as a little-endian RGB9E5 word. Received quantized entries are
 * kept as they came; everything else is packed by ivg_entry_pack. */
#define IVG_PACKED        LUMO_IVG_QUANT_ENTRY
#define IVG_PACKED_VERTEX (LUMO_IVG_AXES * IVG_PACKED)

/* One pyramid level. Level 0 is the grid (validity = received bitmap);
 * coarser levels keep one validity bit per vertex. Level 1 is not kept
 * whole but as a ring of `ring` x-y planes (plane z in slot z % ring),
 * made again plane by plane when push-pull needs them
 * (docs/ivg-format.md §6); ring 0: every plane is kept. */
typedef struct ivg_level {
    uint32_t  dims[3];
    uint32_t  count;
    uint32_t  ring;     /* planes kept; 0: all */
    uint8_t  *e;        /* (ring ? ring x plane : count) * IVG_PACKED_VERTEX bytes */
    uint8_t  *valid;    /* as many bits; NULL on level 0 */
} ivg_level;

/* The storage index of the first vertex of plane z: z x plane, or its
 * slot in the ring (vertex (i, j, z) is then at that + i + dims[0] j). */
static inline uint32_t ivg_plane_slot(const ivg_level *lv, uint32_t z)
{
    return (lv->ring ? z % lv->ring : z) * lv->dims[0] * lv->dims[1];
}

struct lumo_ivg {
    lumo_ivg_desc   desc;
    uint32_t        count;            /* vertices */
    uint32_t        received;         /* vertices with received data */
    uint32_t        solid;            /* vertices marked solid */
    uint8_t        *received_bits;    /* count bits */
    uint8_t        *solid_bits;       /* count bits */
    uint8_t        *seen_bits;        /* duplicate check of one bundle; all 0
                                         between calls */
    uint64_t        scale[3];         /* grid cells per Q16.16 unit, Q48:
                                         round((dims-1) * 2^48 / extent) */
    uint32_t        extent[3];        /* bmax - bmin, Q16.16 raw units */
    unsigned        levels;           /* used entries of level[] */
    ivg_level       level[IVG_MAX_LEVELS];
    ivg_sum        *scratch;          /* smoothing: 3 x-y planes of level 1 */
    ivg_level       raw1;             /* level 1 before smoothing: a ring */
};

static inline int ivg_bit(const uint8_t *bits, uint32_t i)
{
    return (bits[i >> 3] >> (i & 7u)) & 1u;
}

static inline void ivg_bit_set(uint8_t *bits, uint32_t i)
{
    bits[i >> 3] = (uint8_t)(bits[i >> 3] | (1u << (i & 7u)));
}

static inline void ivg_bit_clear(uint8_t *bits, uint32_t i)
{
    bits[i >> 3] = (uint8_t)(bits[i >> 3] & ~(1u << (i & 7u)));
}

/* The packed entry (storage index v, hemisphere a) of a level: the vertex
 * index itself on every level kept whole (ivg_plane_slot for a ring). */
static inline uint8_t *ivg_packed_at(const ivg_level *lv, uint32_t v, unsigned a)
{
    return lv->e + (size_t)v * IVG_PACKED_VERTEX + (size_t)a * IVG_PACKED;
}

/* A packed entry opened for arithmetic: c in UQ16.16 (exact, §2.5), d
 * still in the wire's q units (value q/127) — push-pull averages q and
 * sampling interpolates q, converting to Q1.14 once per result. */
typedef struct ivg_raw {
    uint32_t c[3];
    int32_t  q[3];
} ivg_raw;

/* RGB9E5 to UQ16.16 as lumo_rgb9e5_to_uq16: m * 2^(E-8), rounded half up
 * below E = 8, i.e. ((m + add) >> down) << up with, per exponent, add =
 * 2^(7-E), down = 8 - E below 8 and up = E - 8 from 8 on: one table entry
 * per word (ivg_pack.c: add | down << 8 | up << 12), no branch per channel.
 * Inline: sampling and push-pull open every tap. */
extern const uint32_t ivg_e5_steps[32];

static inline void ivg_rgb9e5_open(const uint8_t *p, uint32_t c[3])
{
    uint32_t w = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
    uint32_t t = ivg_e5_steps[w >> 27], add = t & 0xFFu, down = t >> 8 & 15u, up = t >> 12;

    c[0] = ((w & 0x1FFu) + add) >> down << up;
    c[1] = ((w >> 9 & 0x1FFu) + add) >> down << up;
    c[2] = ((w >> 18 & 0x1FFu) + add) >> down << up;
}

static inline void ivg_raw_open(const uint8_t *p, ivg_raw *r)
{
    r->q[0] = (int8_t)p[0];
    r->q[1] = (int8_t)p[1];
    r->q[2] = (int8_t)p[2];
    ivg_rgb9e5_open(p + 3, r->c);
}

/* ivg_pack.c: packing rounds c to the nearest RGB9E5 word (shared
 * exponent: error at most half a mantissa step of the largest channel,
 * 2^-9 of it); q must be in [-127, 127] (an average of such is). Unpacking
 * to lumo_ivg_entry is exact (the decoding of §2.5). */
void ivg_raw_pack(const ivg_raw *r, uint8_t *p);
void ivg_entry_unpack(const uint8_t *p, lumo_ivg_entry *e);
void ivg_entry_pack(const lumo_ivg_entry *e, uint8_t *p);
lumo_q1_14 ivg_snorm8_to_q14(int32_t q);

/* Dims of the next coarser level along one axis (seed 000 §4.1 pyramid for
 * any size): coarse vertex i sits on fine vertex 2i, so F >= 3 vertices need
 * F/2 + 1; an axis of 2 collapses to 1 and 1 stays 1. */
static inline uint32_t ivg_coarse_dim(uint32_t fine)
{
    return fine >= 3u ? fine / 2u + 1u : 1u;
}

#endif /* LUMO_IVG_INTERNAL_H */
