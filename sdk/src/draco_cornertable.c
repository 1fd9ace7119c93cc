/*
 * draco_cornertable.c — the packed opposite table (ld_pot, see
 * draco_internal.h): built once the EdgeBreaker connectivity is decoded,
 * read by the seams, the traversals and the predictions.
 *
 * Why packed: the output face array is the corner -> vertex map, and the
 * decoder needs every corner's opposite next to it until the last
 * prediction. As 32-bit ids that is 12 bytes per face on top of the 12 of
 * the faces; the vertex ids leave 32 - log2(V) bits of every face word
 * unused, and EdgeBreaker's opposites are mostly a few corners away or
 * one ring of the spiral away (measured on the Stanford dragons, of the
 * corners with an opposite: 71.9% near and 27.2% based at 871k triangles,
 * 99.2% near at 203k; about 1% escape, in 2 bytes each, 3 when 16 bits
 * above the word's low part do not reach 3F). The layout is in
 * draco_internal.h (ld_pot) and docs/draco-decoder.md.
 */
#include "draco_internal.h"

unsigned ld_pot_vshift(uint32_t n)
{
    unsigned b = 1;
    if (n <= 1u)
        return 1;
    while (b < 32u && (n - 1u) >> b)
        ++b;
    return b;
}

/* Bits of an escape's field besides its rank and the low part of o: the
 * far flag (bit 31) and the escape bit (g bit 0). */
#define LD_POT_MODE_BITS 2u

uint32_t ld_pot_escape(const ld_pot *t, uint32_t c, uint32_t w)
{
    const uint32_t field = w >> t->vshift;
    const uint8_t *p;
    uint32_t e, hi;
    if (field == 0xFFFFFFFFu >> t->vshift)
        return LD_INV;
    e = t->coarse[c >> LD_POT_COARSE] + t->fine[c >> LD_POT_BLOCK] +
        ((field >> 1) & ((1u << LD_POT_RANK_BITS) - 1u));
    p = t->esc + (size_t)e * t->esc_width;
    hi = (uint32_t)p[0] | (uint32_t)p[1] << 8;
    if (t->esc_width == 3)
        hi |= (uint32_t)p[2] << 16;
    return hi << t->lshift | ((field >> (LD_POT_RANK_BITS + 1u)) & ((1u << t->lshift) - 1u));
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

/* A base not set yet (no far opposite of its direction in its block so
 * far); a base is never this value. */
#define LD_POT_BASE_UNSET INT16_MIN

/* The packing's escapes: their entries, written over the start of the
 * 24-bit table, and the index blocks, which only an escape's read looks
 * at and which are filled when a block's first escape comes. */
typedef struct ld_pot_esc {
    uint32_t *words;
    uint8_t *o24;
    uint16_t *fine;
    uint32_t *coarse;
    uint32_t fine_block, coarse_block;  /* blocks of the last escape, or LD_INV */
    uint32_t e;         /* escapes so far */
    uint32_t rank0;     /* escapes before fine_block */
    unsigned vshift, lshift, ew;
} ld_pot_esc;

/* Corner c's escape: its rank in its 16-corner block and the low bits of o
 * in the word, the high bits as entry e (written at or below entry c of
 * the 24-bit table, which is read: in place). Rare: out of the loop. */
static LD_NOINLINE void ld_pot_escape_put(ld_pot_esc *s, uint32_t c, uint32_t o)
{
    uint8_t *p = s->o24 + (size_t)s->e * s->ew;
    const uint32_t hi = o >> s->lshift;
    if (c >> LD_POT_COARSE != s->coarse_block) {
        s->coarse_block = c >> LD_POT_COARSE;
        s->coarse[s->coarse_block] = s->e;
    }
    if (c >> LD_POT_BLOCK != s->fine_block) {
        s->fine_block = c >> LD_POT_BLOCK;
        s->fine[s->fine_block] = (uint16_t)(s->e - s->coarse[s->coarse_block]);
        s->rank0 = s->e;
    }
    p[0] = (uint8_t)hi;
    p[1] = (uint8_t)(hi >> 8);
    if (s->ew == 3u)
        p[2] = (uint8_t)(hi >> 16);
    s->words[c] |= LD_POT_FAR | (1u | (s->e - s->rank0) << 1 |
                                 (o & ((1u << s->lshift) - 1u)) << (LD_POT_RANK_BITS + 1u))
                                    << s->vshift;
    s->e++;
}

/* The based g (the far field's low bits) of corner c with far opposite o
 * (d = o - c), or LD_INV when o is not within its block's base window.
 * The block's first far opposite of a direction sets the base: its
 * distance less `half`, and less the 2 half that the far flag adds to a
 * read's field >> 2. */
static LD_FORCE_INLINE uint32_t ld_pot_based(int16_t *base, int32_t half, uint32_t c, uint32_t d)
{
    const unsigned dir = (int32_t)d > 0;
    int16_t *b = base + ((c >> LD_POT_BASE << 1) | dir);
    uint32_t off;
    if (*b == LD_POT_BASE_UNSET) {
        const int32_t stored = (int32_t)d - 3 * half;
        if (stored <= LD_POT_BASE_UNSET || stored > INT16_MAX)
            return LD_INV;
        *b = (int16_t)stored;
    }
    off = d - (uint32_t)(int32_t)*b - 2u * (uint32_t)half;
    if (off >= 2u * (uint32_t)half)
        return LD_INV;
    return dir << 1 | off << 2;
}

void ld_pot_build(ld_pot *t, uint32_t *words, uint32_t num_corners, unsigned vshift, uint8_t *o24,
                  uint16_t *fine, uint32_t *coarse, int16_t *base, size_t *esc_bytes)
{
    const unsigned k = 32u - vshift;
    /* near: o - c in [-bias, bias), stored as o - c in the k - 1 bits
     * from bit vshift (x = o - c + bias is the test). For a border
     * edge o - c = LD_O24_NONE - c >= 2^23 - num_corners: capping the bias
     * there makes every border edge fail the near test, so the hot loop
     * has one test (the cap only turns near opposites into escapes in
     * meshes of over 2^22 corners) */
    const uint32_t cap = (LD_O24_NONE + 1u) - num_corners;
    const uint32_t bias = (1u << (k - 2u)) < cap ? 1u << (k - 2u) : cap;
    const uint32_t none = 0xFFFFFFFFu << vshift, n8 = num_corners & ~7u, bsh = bias << vshift;
    const size_t nb = 2u * ld_pot_bases(num_corners);
    const int32_t half = (int32_t)1 << (k - 4u);  /* a based offset is in [0, 2 half) */
    ld_pot_esc s;
    uint32_t c, f;
    size_t i;
    for (i = 0; i < nb; ++i)
        base[i] = LD_POT_BASE_UNSET;
    /* fine and coarse are not cleared: only the blocks holding an escape
     * are read, and ld_pot_escape_put writes them at their first escape */
    s.words = words;
    s.o24 = o24;
    s.fine = fine;
    s.coarse = coarse;
    s.fine_block = s.coarse_block = LD_INV;
    s.e = s.rank0 = 0;
    s.vshift = vshift;
    s.lshift = ld_pot_lshift(vshift);
    s.ew = ld_pot_escape_width(num_corners, vshift);
    /* the words hold vertex ids below 2^vshift: the spare bits are zero */
    /* corner c + j from the turn's pointers and cb = bias - c: constant
     * displacements; x = o - (c + j) + bias is the near test */
#define LD_POT_PUT(j)                                                       \
    do {                                                                    \
        const uint32_t o_ = ld_o24(o24c, j), x_ = o_ + cb - (j);           \
        if (x_ < 2u * bias) /* the common case: a near opposite */          \
            wc[j] |= ((x_ << vshift) - bsh) & ~LD_POT_FAR;                  \
        else if (o_ == LD_O24_NONE)                                         \
            wc[j] |= none;                                                  \
        else if ((f = ld_pot_based(base, half, c + (j), o_ - (c + (j)))) != LD_INV) \
            wc[j] |= LD_POT_FAR | f << vshift;                              \
        else                                                                \
            ld_pot_escape_put(&s, c + (j), o_);                             \
    } while (0)
    for (c = 0; c < n8; c += 8u) {  /* eight a turn: an eighth of the loop's steps */
        const uint8_t *o24c = o24 + 3u * (size_t)c;
        uint32_t *wc = words + c;
        const uint32_t cb = bias - c;
        LD_POT_PUT(0u);
        LD_POT_PUT(1u);
        LD_POT_PUT(2u);
        LD_POT_PUT(3u);
        LD_POT_PUT(4u);
        LD_POT_PUT(5u);
        LD_POT_PUT(6u);
        LD_POT_PUT(7u);
    }
    for (; c < num_corners; ++c) {
        const uint8_t *o24c = o24 + 3u * (size_t)c;
        uint32_t *wc = words + c;
        const uint32_t cb = bias - c;
        LD_POT_PUT(0u);
    }
#undef LD_POT_PUT
    t->words = words;
    t->esc = o24;
    t->fine = fine;
    t->coarse = coarse;
    t->base = base;
    t->vshift = (uint8_t)vshift;
    t->lshift = (uint8_t)s.lshift;
    t->esc_width = (uint8_t)s.ew;
    *esc_bytes = (size_t)s.e * s.ew;
}

/* Eight words a step through a pointer: the compiler turns the block into
 * two vector masks at -O2 (it does not vectorize the plain loop). */
void ld_pot_strip(uint32_t *words, uint32_t num_corners, unsigned vshift)
{
    const uint32_t vmask = 0xFFFFFFFFu >> (32u - vshift);
    uint32_t *p = words, *const end = words + num_corners, *const end8 = end - num_corners % 8u;
    for (; p != end8; p += 8) {
        p[0] &= vmask;
        p[1] &= vmask;
        p[2] &= vmask;
        p[3] &= vmask;
        p[4] &= vmask;
        p[5] &= vmask;
        p[6] &= vmask;
        p[7] &= vmask;
    }
    for (; p != end; ++p)
        *p &= vmask;
}
