/*
 * draco_cornertable.c — the packed opposite table (ld_pot, see
 * draco_internal.h): built once the EdgeBreaker connectivity is decoded,
 * read by the seams, the traversals and the predictions.
 *
 * Why packed: the output face array is the corner -> vertex map, and the
 * decoder needs every corner's opposite next to it until the last
 * prediction. As 32-bit ids that is 12 bytes per face on top of the 12 of
 * the faces; the vertex ids leave 32 - log2(V) bits of every face word
 * unused, and EdgeBreaker's opposites are mostly a few corners away
 * (measured on the Stanford dragons, of the corners with an opposite:
 * 72% at 871k triangles, 99.2% at 203k, 99.5% at 48k are within the
 * window those bits hold). The rest are escapes of 2 (3 when 16 bits
 * above the word's low part do not reach 3F: meshes of more than about a
 * million faces with over 2^19 vertices) bytes each.
 */
#include "draco_internal.h"

#define LD_POT_FINE_MASK ((1u << LD_POT_BLOCK) - 1u)
#define LD_POT_COARSE_MASK ((1u << LD_POT_COARSE) - 1u)
#define LD_POT_BASE_MASK ((1u << LD_POT_BASE) - 1u)

unsigned ld_pot_vshift(uint32_t n)
{
    unsigned b = 1;
    if (n <= 1u)
        return 1;
    while (b < 32u && (n - 1u) >> b)
        ++b;
    return b;
}

/* Field bits below an escape's rank: the near flag and the based flag. */
#define LD_POT_MODE_BITS 2u

uint32_t ld_pot_escape(const ld_pot *t, uint32_t c, uint32_t w)
{
    const uint32_t field = w >> t->vshift;
    const uint8_t *p;
    uint32_t e, hi;
    if (field == 0xFFFFFFFFu >> t->vshift)
        return LD_INV;
    e = t->coarse[c >> LD_POT_COARSE] + t->fine[c >> LD_POT_BLOCK] +
        ((field >> LD_POT_MODE_BITS) & ((1u << LD_POT_RANK_BITS) - 1u));
    p = t->esc + (size_t)e * t->esc_width;
    hi = (uint32_t)p[0] | (uint32_t)p[1] << 8;
    if (t->esc_width == 3)
        hi |= (uint32_t)p[2] << 16;
    return hi << t->lshift | field >> (LD_POT_RANK_BITS + LD_POT_MODE_BITS);
}

unsigned ld_pot_lshift(unsigned vshift)
{
    return 32u - vshift - (LD_POT_RANK_BITS + LD_POT_MODE_BITS);
}

/* 2 bytes when they and the word's low part cover any corner below
 * num_corners (ld_pot_vshift bits), else 3. */
unsigned ld_pot_escape_width(uint32_t num_corners, unsigned vshift)
{
    return 16u + ld_pot_lshift(vshift) >= ld_pot_vshift(num_corners) ? 2u : 3u;
}

/* One corner's escape: its rank in the block and the low bits of its
 * opposite x in the word, the high bits as entry e (written at or below
 * entry c of the 24-bit table, which is read: in place). */
static void ld_pot_escape_put(uint8_t *o24, unsigned ew, uint32_t e, uint32_t rank, uint32_t x,
                              unsigned lshift, uint32_t *word, unsigned vshift)
{
    uint8_t *p = o24 + (size_t)e * ew;
    const uint32_t hi = x >> lshift;
    p[0] = (uint8_t)hi;
    p[1] = (uint8_t)(hi >> 8);
    if (ew == 3u)
        p[2] = (uint8_t)(hi >> 16);
    *word |= (3u | rank << LD_POT_MODE_BITS |
              (x & ((1u << lshift) - 1u)) << (LD_POT_RANK_BITS + LD_POT_MODE_BITS))
             << vshift;
}

/* The bases of one block of 2^LD_POT_BASE corners while it is packed:
 * has[dir] once the first far opposite of that direction set base[dir]. */
typedef struct ld_pot_bases_state {
    int16_t *base;
    int has[2];
    int32_t half;  /* 2^(k-4): a based offset is o - c - base in [0, 2 half) */
} ld_pot_bases_state;

/* The based field of corner c with far opposite o, or 0 when o is not
 * within its block's base window (an escape). */
static LD_FORCE_INLINE uint32_t ld_pot_based(ld_pot_bases_state *b, uint32_t c, uint32_t o)
{
    const int32_t d = (int32_t)(o - c);
    const unsigned dir = d > 0;
    uint32_t off;
    if (!b->has[dir]) {
        const int32_t first = d - b->half;
        if (first < INT16_MIN || first > INT16_MAX)
            return 0;
        b->base[dir] = (int16_t)first;
        b->has[dir] = 1;
    }
    off = (uint32_t)d - (uint32_t)(int32_t)b->base[dir];
    if (off >= 2u * (uint32_t)b->half)
        return 0;
    return 1u | dir << 2 | off << 3;
}

void ld_pot_build(ld_pot *t, uint32_t *words, uint32_t num_corners, unsigned vshift, uint8_t *o24,
                  uint16_t *fine, uint32_t *coarse, int16_t *base, size_t *esc_bytes)
{
    const unsigned k = 32u - vshift, lshift = ld_pot_lshift(vshift), s1 = vshift + 1u;
    /* near: o - c in [-bias, bias), stored as o - c + bias. For a border
     * edge o - c = LD_O24_NONE - c >= 2^23 - num_corners: capping the bias
     * there makes every border edge fail the near test, so the hot loop
     * has one test (the cap only turns near opposites into escapes in
     * meshes of over 2^22 corners) */
    const uint32_t cap = (LD_O24_NONE + 1u) - num_corners;
    const uint32_t bias = (1u << (k - 2u)) < cap ? 1u << (k - 2u) : cap;
    const uint32_t none = 0xFFFFFFFFu << vshift;
    const unsigned ew = ld_pot_escape_width(num_corners, vshift);
    const uint32_t blocks = (num_corners + LD_POT_FINE_MASK) >> LD_POT_BLOCK;
    ld_pot_bases_state bs;
    uint32_t b, e = 0;
    memset(base, 0, ld_pot_bases(num_corners) * 2u * sizeof *base);
    bs.half = (int32_t)1 << (k - 4u);
    bs.base = base;
    /* the words hold vertex ids below 2^vshift: the spare bits are zero */
    for (b = 0; b < blocks; ++b) {
        const uint32_t c0 = b << LD_POT_BLOCK, block = e;
        const uint32_t c1 = c0 + LD_POT_FINE_MASK + 1u < num_corners ? c0 + LD_POT_FINE_MASK + 1u
                                                                     : num_corners;
        uint32_t c, f;
        if (!(c0 & LD_POT_COARSE_MASK))
            coarse[c0 >> LD_POT_COARSE] = e;
        if (!(c0 & LD_POT_BASE_MASK)) {
            bs.base = base + 2u * (c0 >> LD_POT_BASE);
            bs.has[0] = bs.has[1] = 0;
        }
        fine[b] = (uint16_t)(e - coarse[c0 >> LD_POT_COARSE]);
#define LD_POT_PUT(c)                                                                   \
    do {                                                                                \
        const uint32_t o_ = ld_o24(o24, c), x_ = o_ - (c) + bias;                       \
        if (x_ < 2u * bias) { /* the common case: a near opposite */                    \
            words[c] |= x_ << s1;                                                       \
        } else if (o_ == LD_O24_NONE) {                                                 \
            words[c] |= none;                                                           \
        } else if ((f = ld_pot_based(&bs, c, o_)) != 0) {                               \
            words[c] |= f << vshift;                                                    \
        } else {                                                                        \
            ld_pot_escape_put(o24, ew, e, e - block, o_, lshift, words + (c), vshift); \
            ++e;                                                                        \
        }                                                                               \
    } while (0)
        if (c1 - c0 == LD_POT_FINE_MASK + 1u) {
            for (c = c0; c < c1; c += 8u) {  /* eight a turn: an eighth of the loop's steps */
                LD_POT_PUT(c);
                LD_POT_PUT(c + 1u);
                LD_POT_PUT(c + 2u);
                LD_POT_PUT(c + 3u);
                LD_POT_PUT(c + 4u);
                LD_POT_PUT(c + 5u);
                LD_POT_PUT(c + 6u);
                LD_POT_PUT(c + 7u);
            }
        } else {
            for (c = c0; c < c1; ++c)
                LD_POT_PUT(c);
        }
#undef LD_POT_PUT
    }
    t->words = words;
    t->esc = o24;
    t->fine = fine;
    t->coarse = coarse;
    t->base = base;
    t->flag = 1u << vshift;
    t->bias = bias;
    t->vshift = (uint8_t)vshift;
    t->lshift = (uint8_t)lshift;
    t->esc_width = (uint8_t)ew;
    *esc_bytes = (size_t)e * ew;
}

/* Four words a step through a pointer: the compiler turns the block into
 * vector code at -O2 (it does not vectorize the plain loop). */
void ld_pot_strip(uint32_t *words, uint32_t num_corners, unsigned vshift)
{
    const uint32_t vmask = 0xFFFFFFFFu >> (32u - vshift);
    uint32_t *p = words, *const end = words + num_corners, *const end4 = end - num_corners % 4u;
    for (; p != end4; p += 4) {
        p[0] &= vmask;
        p[1] &= vmask;
        p[2] &= vmask;
        p[3] &= vmask;
    }
    for (; p != end; ++p)
        *p &= vmask;
}
