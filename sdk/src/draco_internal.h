/*
 * draco_internal.h — shared pieces of lumo's Draco decoder (not public).
 *
 * Module map (each file holds one concern):
 *   draco_buffer.c      byte reader, varints, LSB-first bit reader
 *   draco_mem.c         two-ended arena carving: outputs up, work memory down
 *   draco_rans.c        rANS symbol decoder, tagged/raw symbol streams,
 *                       rABS binary decoder
 *   draco_decode.c      header, metadata skip, sequential connectivity, the
 *                       attribute decoder dispatch, public entry points
 *   draco_attribute.c   sequential integer / quantization / normal decoding
 *   draco_predict.c     prediction schemes and their transforms
 *   draco_edgebreaker.c EdgeBreaker connectivity (standard and valence),
 *                       attribute seams, point assignment
 *   draco_traverse.c    attribute traversal orders (depth-first, degree)
 *   draco_cornertable.c the packed opposite table (ld_pot)
 *   draco_kdtree.c      KD-tree point clouds
 *
 * The libdraco 1.5.5 source is the authority for every behaviour here; the
 * comments name the places where it differs from the written spec.
 */
#ifndef LUMO_DRACO_INTERNAL_H
#define LUMO_DRACO_INTERNAL_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include "lumo/draco.h"

/* For a hot loop written once and instantiated with constant flags: the
 * compiler must inline it at each call for the flags to fold away. */
#if defined(__GNUC__)
#define LD_FORCE_INLINE __attribute__((always_inline)) inline
#else
#define LD_FORCE_INLINE inline
#endif
/* A branch the hot loops rarely take: its spills go to its own side. */
#if defined(__GNUC__)
#define LD_UNLIKELY(x) __builtin_expect(!!(x), 0)
#else
#define LD_UNLIKELY(x) (x)
#endif
/* For a rare path kept out of a hot loop, whose registers stay the loop's. */
#if defined(__GNUC__)
#define LD_NOINLINE __attribute__((noinline))
#else
#define LD_NOINLINE
#endif

/* A build with the lean mode only (LUMO_DRACO_MODES, lumo/draco.h): every
 * decode is lean, and each test below that picks a walk's instance by its
 * opposite store is a constant, so the default mode's instances are not
 * compiled in. */
#if LUMO_DRACO_MODES == LUMO_DRACO_MODES_LEAN
#define LD_LEAN_ONLY 1
#elif LUMO_DRACO_MODES == LUMO_DRACO_MODES_ALL
#define LD_LEAN_ONLY 0
#else
#error "LUMO_DRACO_MODES: LUMO_DRACO_MODES_ALL or LUMO_DRACO_MODES_LEAN"
#endif
/* The decode's mode from the caller's flags. */
static inline uint8_t ld_mode_lean(unsigned flags)
{
    return (uint8_t)(LD_LEAN_ONLY || (flags & LUMO_DRACO_LEAN) != 0);
}

/* Work limits: no count read from a stream may exceed these. */
#define LD_MAX_FACES   (1u << 26)
/* The lean mode keeps EdgeBreaker corner ids in 23 bits while it decodes
 * (3F < 2^23 - 1, see ld_o24 below). */
#define LD_MAX_EB_FACES ((LD_O24_NONE - 1u) / 3u)
#define LD_MAX_POINTS  (1u << 27)
#define LD_MAX_DECODERS LUMO_DRACO_MAX_ATTRIBUTES

/* ---- byte reader (draco_buffer.c) --------------------------------------- */
typedef struct ld_buf {
    const uint8_t *data;
    size_t size;
    size_t pos;
} ld_buf;

static inline size_t ld_remaining(const ld_buf *b) { return b->size - b->pos; }
static inline const uint8_t *ld_head(const ld_buf *b) { return b->data + b->pos; }

lumo_status ld_u8(ld_buf *b, uint8_t *v);
lumo_status ld_u16(ld_buf *b, uint16_t *v);
lumo_status ld_u32(ld_buf *b, uint32_t *v);
lumo_status ld_varint32_slow(ld_buf *b, uint32_t *v);
/* LEB128 into 32 bits (at most 5 bytes, high bits dropped as libdraco
 * does); inline fast path when 5 bytes are available. */
static inline lumo_status ld_varint32(ld_buf *b, uint32_t *v)
{
    const uint8_t *p = b->data + b->pos;
    uint32_t r;
    if (b->size - b->pos < 5)
        return ld_varint32_slow(b, v);
    r = p[0] & 0x7Fu;
    if (!(p[0] & 0x80u)) { b->pos += 1; *v = r; return LUMO_OK; }
    r |= (uint32_t)(p[1] & 0x7Fu) << 7;
    if (!(p[1] & 0x80u)) { b->pos += 2; *v = r; return LUMO_OK; }
    r |= (uint32_t)(p[2] & 0x7Fu) << 14;
    if (!(p[2] & 0x80u)) { b->pos += 3; *v = r; return LUMO_OK; }
    r |= (uint32_t)(p[3] & 0x7Fu) << 21;
    if (!(p[3] & 0x80u)) { b->pos += 4; *v = r; return LUMO_OK; }
    if (p[4] & 0x80u)
        return LUMO_ERR_CORRUPT;
    r |= (uint32_t)(p[4] & 0x7Fu) << 28;
    b->pos += 5;
    *v = r;
    return LUMO_OK;
}
lumo_status ld_varint64(ld_buf *b, uint64_t *v);
lumo_status ld_skip(ld_buf *b, uint64_t n);
/* A sub-reader of the next n bytes; the parent skips past them. */
lumo_status ld_take(ld_buf *b, uint64_t n, ld_buf *sub);

/* LSB-first bit reader over the rest of a buffer. Reading past the end
 * yields zero bits without advancing, as libdraco's BitDecoder does. */
typedef struct ld_bits {
    const uint8_t *data;
    size_t size;      /* bytes */
    size_t bit;       /* bits consumed */
} ld_bits;

void ld_bits_start(ld_bits *r, const ld_buf *b);
uint32_t ld_bits_get_slow(ld_bits *r, unsigned nbits);
/* nbits <= 32 bits, least significant first; a 40-bit window when five
 * bytes remain, bit by bit near the end. */
static inline uint32_t ld_bits_get(ld_bits *r, unsigned nbits)
{
    const size_t byte = r->bit >> 3;
    if (nbits && byte + 5u <= r->size) {
        const uint8_t *p = r->data + byte;
        const uint64_t w = (uint64_t)p[0] | ((uint64_t)p[1] << 8) | ((uint64_t)p[2] << 16) |
                           ((uint64_t)p[3] << 24) | ((uint64_t)p[4] << 32);
        const uint64_t mask = ((uint64_t)1 << nbits) - 1u;
        r->bit += nbits;
        return (uint32_t)((w >> (r->bit - nbits - (byte << 3))) & mask);
    }
    return ld_bits_get_slow(r, nbits);
}
/* Advance `b` past the whole bytes the reader touched. */
void ld_bits_end(ld_bits *r, ld_buf *b);
/* Skip n bits as n one-bit reads would (stopping at the end). */
void ld_bits_skip(ld_bits *r, uint64_t n);

/* The packed opposite table (ld_pot) reads a near opposite's offset by an
 * arithmetic right shift of a negative int32, which C99 leaves to the
 * implementation: refuse to build where it is not arithmetic. */
typedef char ld_arithmetic_shift_check[(-2 >> 1) == -1 ? 1 : -1];

/* ---- memory (draco_mem.c) ------------------------------------------------ */
typedef struct ld_mem {
    uint8_t *lo;      /* next output byte (grows up) */
    uint8_t *hi;      /* lowest work byte (grows down) */
    uint8_t *start;   /* first byte of the carved region */
    uint8_t *top;     /* one past the last byte */
    size_t peak;      /* most bytes in use at once, outputs + work */
} ld_mem;

void ld_mem_init(ld_mem *m, lumo_arena *a);
void *ld_out(ld_mem *m, size_t n, size_t size);     /* NULL when full */
void *ld_tmp(ld_mem *m, size_t n, size_t size);     /* NULL when full */
static inline uint8_t *ld_tmp_mark(const ld_mem *m) { return m->hi; }
/* Release work memory down to a mark; a mark below work memory already
 * released further (ld_eb_release_table) is a no-op. */
static inline void ld_tmp_release(ld_mem *m, uint8_t *mark)
{
    if (mark > m->hi)
        m->hi = mark;
}
/* A stack of uint32 in all the free space, for traversals whose depth the
 * stream decides; ld_free_used() books the depth reached into the peak.
 * Nothing else may be allocated while it is in use. */
static inline uint32_t *ld_free_space(const ld_mem *m, size_t *cap)
{
    *cap = (size_t)(m->hi - m->lo) / sizeof(uint32_t);
    return (uint32_t *)(void *)m->lo;
}
void ld_free_used(ld_mem *m, size_t bytes);
/* Commit the outputs to the arena. */
void ld_mem_commit(ld_mem *m, lumo_arena *a);

/* ---- the arena need before decoding (lumo_draco_arena_need) -------------- *
 * A replay of ld_mem's bookkeeping on byte counts only: the scanner reads
 * the headers a decode reads and books every ld_out / ld_tmp / release /
 * free-space use the decode will make, in the same order. Quantities known
 * only after the connectivity is decoded (traversal stack depths, points
 * split along seams) are booked twice: at their smallest value (`lo`) and
 * at the largest the headers allow (`hi`); the need is exact when both
 * replays reach the same peak. */
typedef struct ld_need {
    size_t out;       /* output bytes (ld_out) */
    size_t work;      /* work bytes in use (ld_tmp, top of the arena) */
    size_t peak;
    int hi;           /* 1: book the upper bounds, 0: the lower bounds */
    int bounded;      /* some quantity booked had lower != upper bound */
} ld_need;

static inline size_t ld_need_bytes(size_t n, size_t size)
{
    if (size && n > (SIZE_MAX / 2u) / size)
        return SIZE_MAX / 2u;  /* saturates; no decode fits it */
    return (n * size + 7u) & ~(size_t)7u;
}
static inline void ld_need_track(ld_need *k, size_t extra)
{
    const size_t in_use = k->out + k->work + extra;
    if (in_use > k->peak)
        k->peak = in_use;
}
static inline void ld_need_out(ld_need *k, size_t n, size_t size)
{
    k->out += ld_need_bytes(n, size);
    ld_need_track(k, 0);
}
static inline void ld_need_tmp(ld_need *k, size_t n, size_t size)
{
    k->work += ld_need_bytes(n, size);
    ld_need_track(k, 0);
}
/* ld_tmp_release: a mark is the work in use when it was taken. */
static inline void ld_need_release(ld_need *k, size_t mark)
{
    if (mark < k->work)
        k->work = mark;
}
/* ld_free_used: a stack in the free space, `bytes` deep at most. */
static inline void ld_need_free(ld_need *k, size_t bytes)
{
    ld_need_track(k, ld_need_bytes(bytes, 1));
}
/* Which of two bounds the replay books. */
static inline uint64_t ld_need_pick(ld_need *k, uint64_t lo, uint64_t hi)
{
    k->bounded |= lo != hi;
    return k->hi ? hi : lo;
}

/* ---- entropy coding (draco_rans.c) --------------------------------------- */
/* Symbols of a DecodeSymbols() stream (tagged or raw rANS). */
lumo_status ld_decode_symbols(ld_buf *b, ld_mem *m, uint32_t num_values,
                              unsigned num_components, uint32_t *out,
                              uint8_t *scheme_out);

/* The same stream skipped: its work memory booked into `k`, the values not
 * decoded (tagged streams: the tags only, to find the end of their bits).
 * `found` non-NULL: num_values is only an upper bound of a multiple of
 * num_components; a tagged stream tells the true count / num_components
 * in *found, a raw one leaves it 0xFFFFFFFF (its end is coded).
 * LUMO_ERR_LIMIT: a stream this scan cannot skip (tagged alphabets no
 * encoder writes, or an unknown count under a one-symbol alphabet). */
lumo_status ld_need_symbols(ld_buf *b, ld_need *k, uint32_t num_values, unsigned num_components,
                            uint32_t *found);

/* libdraco's RAnsBitDecoder (rABS with one 8-bit zero probability). */
typedef struct ld_rabs {
    const uint8_t *buf;
    uint32_t offset;
    uint32_t state;
    uint8_t p0;
} ld_rabs;

lumo_status ld_rabs_start(ld_rabs *d, ld_buf *b);
/* One bit (inline: seams, crease flags and KD-tree numbers call it per
 * bit). */
static inline int ld_rabs_bit(ld_rabs *d)
{
    const uint32_t p = (256u - d->p0) & 0xFFu;  /* libdraco keeps p in 8 bits */
    uint32_t quot, rem, xn;
    if (d->state < 4096u && d->offset > 0)
        d->state = d->state * 256u + d->buf[--d->offset];
    quot = d->state >> 8;
    rem = d->state & 0xFFu;
    xn = quot * p;
    if (rem < p) {
        d->state = xn + rem;
        return 1;
    }
    d->state = d->state - xn - p;
    return 0;
}

/* The coder is back where the encoder began (state 4096, every byte read):
 * after the last bit of an encoder's stream, and never before it (while
 * bits remain the state is the encoder's, at least 4096, and without bytes
 * left it only falls). With p0 == 0 the state never moves (zeros only):
 * any count of bits is "done". */
static inline int ld_rabs_done(const ld_rabs *d)
{
    return d->p0 == 0 || (d->state == 4096u && d->offset == 0);
}

/* Draco's zig-zag: even symbols are >= 0, odd ones negative
 * (odd s: -(s >> 1) - 1). */
static inline int32_t ld_zigzag(uint32_t s)
{
    return (int32_t)((s >> 1) ^ (0u - (s & 1u)));
}
/* ld_decode_symbols for zig-zag coded values: each comes out already
 * converted by ld_zigzag (a raw stream's table holds the converted words,
 * so the conversion costs nothing per value). */
lumo_status ld_decode_signed_symbols(ld_buf *b, ld_mem *m, uint32_t num_values,
                                     unsigned num_components, int32_t *out,
                                     uint8_t *scheme_out);

/* ---- decoder state (draco_decode.c) ------------------------------------- */
struct ld_eb;
struct ld_ct;


typedef struct ld_dec {
    ld_buf buf;
    ld_mem mem;
    uint16_t version;         /* major << 8 | minor */
    uint8_t geometry, method, connectivity;
    uint32_t num_points;
    uint32_t num_faces;
    uint32_t *faces;          /* output */
    lumo_draco_attribute *attrs;
    uint32_t num_attrs;
    struct ld_eb *eb;         /* EdgeBreaker state, NULL otherwise */
    uint8_t lean;             /* LUMO_DRACO_LEAN */
    /* per attributes decoder: point sequence (entry order) */
    uint8_t num_decoders;
} ld_dec;

/* One attributes decoder's point sequence and value mapping. */
typedef struct ld_seq {
    uint32_t num_entries;
    const uint32_t *faces;            /* corner -> point (EdgeBreaker), */
    uint32_t faces_mask;              /* ... its bits (& while packed) */
    uint32_t *point_to_value;         /* output map shared by the decoder's
                                         attributes; NULL = identity */
    /* mesh prediction data (EdgeBreaker only, else ct == NULL) */
    const struct ld_ct *ct;
    const int32_t *vertex_to_value;
    const uint32_t *value_to_corner;
    /* value_to_corner holds each entry's opposite corner instead: the
     * corner table's opposites were released (ld_eb_release_table, or
     * after the walk of a table read as decoded, ld_eb_release_o24) */
    uint8_t opposites;
    /* the decoder's only attribute and the stream's last decoder: its
     * prediction may consume the corner table */
    uint8_t last;
    /* NULL, or where the sequence's work memory ends (its tables moved up
     * over dead ones, ld_eb_drop_dead): released to there after the values */
    uint8_t *work_top;
} ld_seq;

/* draco_attribute.c */
lumo_status ld_read_descriptor(ld_buf *b, unsigned decoder, lumo_draco_attribute *a);
lumo_status ld_read_seq_type(ld_buf *b, lumo_draco_attribute *a);

/* What the need scanner keeps of an attribute and of an attributes
 * decoder's sequence. */
typedef struct ld_need_attr {
    uint8_t components, portable, seq_type, data_type;
} ld_need_attr;
typedef struct ld_need_seq {
    uint32_t entries;         /* values of each attribute */
    uint32_t num_corners;
    uint8_t mesh;             /* a corner table exists (EdgeBreaker) */
    uint8_t last;             /* as ld_seq.last */
    uint8_t uncertain;        /* entries is only an upper bound */
    size_t work_top;          /* 0, or ld_seq.work_top as work in use */
    struct ld_eb_need *eb;    /* EdgeBreaker state, NULL otherwise */
    const struct ld_need_attr *attrs; /* the decoder's `count` attributes */
    uint32_t count;                   /* (EdgeBreaker: ld_peek_opposites_only) */
} ld_need_seq;
lumo_status ld_need_attributes(ld_buf *b, ld_need *k, const ld_need_attr *attrs, uint32_t count,
                               ld_need_seq *seq);

lumo_status ld_read_attribute_descriptors(ld_dec *d, unsigned decoder,
                                          uint32_t *first, uint32_t *count, int with_types);
/* Quantization parameters in min_bits/range_bits -> fixed point. */
lumo_status ld_set_quantization(lumo_draco_attribute *a, unsigned bits);
/* draco_kdtree.c: one KD-tree attributes decoder, values and parameters */
lumo_status ld_kd_decode_attributes(ld_dec *d, uint32_t first, uint32_t count);
lumo_status ld_decode_attributes(ld_dec *d, uint32_t first, uint32_t count, ld_seq *seq);
lumo_status ld_kd_need(ld_buf *b, ld_need *k, const ld_need_attr *attrs, uint32_t count,
                       uint32_t num_points);

/* draco_predict.c */
typedef struct ld_pred {
    int8_t method;
    int8_t transform;
    unsigned comps;
    const ld_seq *seq;
    const lumo_draco_attribute *pos;  /* portable positions (parent) */
    /* wrap transform */
    int32_t min_value, max_value;
    /* octahedron transforms */
    int32_t oct_max_q, oct_center;
    unsigned oct_bits;
    /* scheme data */
    ld_rabs crease[4];        /* crease flags per parallelogram count,
                                 decoded as the prediction consumes them */
    uint32_t num_crease[4];
    uint8_t *orient;
    uint32_t num_orient;
    ld_rabs flip;
} ld_pred;

/* m == NULL: only read the data and book its work memory into k. */
lumo_status ld_pred_decode_data(ld_pred *p, ld_buf *b, ld_mem *m, ld_need *k);
lumo_status ld_pred_compute(ld_pred *p, int32_t *values, uint32_t num_entries);
/* 1 when the prediction reads the corner table only as the opposite of
 * each entry's corner (parallelogram). */
int ld_pred_needs_opposites_only(const ld_pred *p);
/* 1 when the prediction reads the corner table at all (not differences). */
int ld_pred_reads_table(const ld_pred *p);
/* draco_attribute.c: whether none of the `count` attributes whose values
 * start at b reads more of the table than the opposites (round six) */
int ld_peek_opposites_only(const ld_buf *b, const ld_need_attr *attrs, uint32_t count,
                           uint32_t entries);

/* ---- corner tables (draco_traverse.c) ------------------------------------ */
#define LD_INV 0xFFFFFFFFu

/* The packed opposite table. EdgeBreaker needs every corner's vertex
 * (the output face array) and its opposite corner at once; 32-bit
 * opposites next to the faces would double the arena. So the opposites
 * live in the spare high bits of the mesh's corner -> vertex words:
 * word = vertex | field << vshift (k = 32 - vshift bits of field). For
 * corner c with opposite o:
 *   bit 31 clear:         a near opposite, o = c + d with d the k - 1
 *                         bits from bit vshift, two's complement (read
 *                         by an arithmetic shift of the word), within
 *                         [-bias, bias): most corners;
 *   bit 31 set, the k - 1 bits below it g:
 *     g bit 0 clear:      a based opposite, o = c + base[2 * (c >>
 *                         LD_POT_BASE) + dir] + (field >> 2), dir = g
 *                         bit 1 (the flag's 2^(k-3) in field >> 2 is
 *                         taken off the stored base);
 *     g all ones:         no opposite (a border edge);
 *     else, an escape:    g bits 1..5 are the corner's rank among the
 *                         escapes of its block of 16 corners, the bits
 *                         above the low part of o, and the escape entry
 *                         (esc_width bytes, little-endian) its high part.
 * The flag is the sign bit and the near offset needs no bias, so the hot
 * loops test and read a near word with no field of the table in a
 * register but the shift.
 * Why based: the opposites beyond the near window are the spiral's
 * previous and next rings, whose distance from the corner changes slowly
 * along the face order. Each block of 2^LD_POT_BASE corners keeps, per
 * direction (dir 1: o > c), the distance of its first far opposite as an
 * int16 base (less half the window, 2^(k-4)); the others of that
 * direction within the window of 2^(k-3) above it are based. Measured on
 * the 871k dragon (k = 13): 71.8% near, 27.2% based, 1.0% escapes, for 4
 * bytes per 128 corners.
 * Escape entries are stored in corner order: the entry of corner c is
 * coarse[c >> 10] + fine[c >> 4] + rank. A window centred on the corner
 * keeps the neighbours on both sides (an earlier XOR form, o ^ c below
 * 2^(k-1), kept only those in the corner's aligned block: 5x the escapes
 * on the 203k dragon). */
typedef struct ld_pot {
    const uint32_t *words;     /* corner -> vertex | field << vshift */
    const uint8_t *esc;        /* escape entries */
    const uint16_t *fine;      /* escapes from a 1024-block to each 16-block */
    const uint32_t *coarse;    /* escapes before each 1024-corner block */
    const int16_t *base;       /* two per 2^LD_POT_BASE corners */
    uint8_t vshift, lshift, esc_width;
} ld_pot;
#define LD_POT_FAR 0x80000000u   /* the flag of a word that is not near */
#define LD_POT_RANK_BITS 5u
#define LD_POT_BLOCK 4u          /* log2 corners per fine block */
#define LD_POT_COARSE 10u        /* log2 corners per coarse block */
#define LD_POT_BASE 7u           /* log2 corners per pair of bases */
#define LD_POT_MAX_VSHIFT 24u    /* 8 bits of field at least */

/* The 24-bit opposite table EdgeBreaker decodes into (3 bytes per corner,
 * little-endian, one byte of padding after the last entry): a corner id
 * below LD_O24_NONE (no opposite yet) in bits 0..22, and bit 23 free for
 * the face flags of the traversal that reads the table as decoded
 * (ld_ct.o24). Packed into an ld_pot afterwards in the other cases. */
#define LD_O24_NONE 0x7FFFFFu
static LD_FORCE_INLINE uint32_t ld_o24(const uint8_t *t, uint32_t c)
{
    const uint8_t *p = t + 3u * (size_t)c;
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    uint32_t x;
    memcpy(&x, p, 4);  /* the padding byte keeps the last read in bounds */
    return x & LD_O24_NONE;
#else
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)(p[2] & 0x7Fu) << 16;
#endif
}
static LD_FORCE_INLINE void ld_o24_set(uint8_t *t, uint32_t c, uint32_t v)
{
    uint8_t *p = t + 3u * (size_t)c;
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    uint32_t x;  /* the fourth byte (the next entry's) is written back as read */
    memcpy(&x, p, 4);
    x = (x & 0xFF000000u) | v;
    memcpy(p, &x, 4);
#else
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
#endif
}
/* Entry c of a new face, its entries written in increasing corner order:
 * a blind 4-byte store, whose fourth byte (the next entry's first) the
 * face's next write, or the next face's first, puts right (the table's
 * padding byte takes the last face's). */
static LD_FORCE_INLINE void ld_o24_put_new(uint8_t *t, uint32_t c, uint32_t v)
{
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    memcpy(t + 3u * (size_t)c, &v, 4);
#else
    ld_o24_set(t, c, v);
#endif
}
/* A face's flag (ld_ct.o24 traversal): bit 23 of each of its entries, so
 * that any corner tests it without a division by 3. */
static LD_FORCE_INLINE int ld_o24_seen(const uint8_t *t, uint32_t c)
{
    return t[3u * (size_t)c + 2u] >> 7;
}
static LD_FORCE_INLINE void ld_o24_mark(uint8_t *t, uint32_t first_corner)
{
    uint8_t *p = t + 3u * (size_t)first_corner + 2u;
    p[0] |= 0x80u;
    p[3] |= 0x80u;
    p[6] |= 0x80u;
}
/* Pack `o24` (num_corners entries) into the spare bits of `words` (vertex
 * ids below 2^vshift, vshift <= LD_POT_MAX_VSHIFT), the escapes written
 * over the start of `o24` in place; `fine`, `coarse` and `base` hold
 * (num_corners + 15) / 16, (num_corners + 1023) / 1024 and
 * 2 * ld_pot_bases(num_corners) entries. Sets *t; *esc_bytes: bytes of
 * escapes at o24. */
void ld_pot_build(ld_pot *t, uint32_t *words, uint32_t num_corners, unsigned vshift, uint8_t *o24,
                  uint16_t *fine, uint32_t *coarse, int16_t *base, size_t *esc_bytes);
/* Blocks of 2^LD_POT_BASE corners (each holds two bases). */
static inline size_t ld_pot_bases(uint64_t num_corners)
{
    return (size_t)((num_corners + (1u << LD_POT_BASE) - 1u) >> LD_POT_BASE);
}
/* Clear the packed bits: words hold the vertex ids alone again. */
void ld_pot_strip(uint32_t *words, uint32_t num_corners, unsigned vshift);
/* Bits of the vertex ids below n (at least 1). */
unsigned ld_pot_vshift(uint32_t n);
/* The low bits of x an escaped word holds (vshift <= 24), and the bytes of
 * an escape entry: shared by the packing and the arena-need replay. */
unsigned ld_pot_lshift(unsigned vshift);
unsigned ld_pot_escape_width(uint32_t num_corners, unsigned vshift);
uint32_t ld_pot_escape(const ld_pot *t, uint32_t c, uint32_t w);
/* A hot loop holds the near case's fields in locals (ld_pot_near) and
 * passes the table itself only to the far words: a loop that passed the
 * address of its own copy would have to reload the copy after every
 * escape. */
typedef struct ld_pot_near {
    const uint32_t *words;
    unsigned s1;               /* vshift + 1 */
    const ld_pot *t;
} ld_pot_near;
static inline ld_pot_near ld_pot_near_of(const ld_pot *t)
{
    ld_pot_near n;
    n.words = t->words;
    n.s1 = t->vshift + 1u;
    n.t = t;
    return n;
}
/* The opposite of a corner whose word is not near: a based one inline
 * (its fields read from the table, not held in the hot loop's registers),
 * escapes and borders in ld_pot_escape. The based case comes first: with
 * the test the other way round GCC 12 lays the loops out 1.3 M
 * instructions longer on the 871k dragon. */
static LD_FORCE_INLINE uint32_t ld_pot_far(const ld_pot *t, uint32_t c, uint32_t w)
{
    const uint32_t field = w >> t->vshift;
    if (!LD_UNLIKELY(field & 1u))
        return c + (uint32_t)(int32_t)t->base[(c >> LD_POT_BASE << 1) | (field >> 1 & 1u)] +
               (field >> 2);
    return ld_pot_escape(t, c, w);
}
static LD_FORCE_INLINE uint32_t ld_pot_near_opp(ld_pot_near n, uint32_t c)
{
    const uint32_t w = n.words[c];
    if (w & LD_POT_FAR)
        return ld_pot_far(n.t, c, w);
    return c + (uint32_t)((int32_t)(w << 1) >> n.s1);
}
static LD_FORCE_INLINE uint32_t ld_pot_opp(const ld_pot *t, uint32_t c)
{
    return ld_pot_near_opp(ld_pot_near_of(t), c);
}

/* An attribute's seam flags: a bit per corner, set when the edge opposite
 * the corner is a seam (3F/8 bytes an attribute with seams, issue 25 round
 * five; a byte per corner before). */
static inline size_t ld_seam_bytes(uint32_t corners) { return ((size_t)corners + 7u) >> 3; }
static LD_FORCE_INLINE int ld_seam(const uint8_t *s, uint32_t c)
{
    return s[c >> 3] >> (c & 7u) & 1;
}
static inline void ld_seam_set(uint8_t *s, uint32_t c)
{
    s[c >> 3] = (uint8_t)(s[c >> 3] | 1u << (c & 7u));
}

/* A view of a corner table: the mesh's own, or an attribute's (whose seam
 * edges have no opposite and whose vertices are split along seams). */
typedef struct ld_ct {
    const uint32_t *c2v;      /* corner -> vertex (& vmask) */
    const uint32_t *opp32;    /* opposite corners of the mesh, or NULL: */
    ld_pot opp;               /* ... packed (LUMO_DRACO_LEAN), or */
    const uint8_t  *o24;      /* ... the lean decode's 24-bit table, read
                                 as decoded by the depth-first traversal
                                 of a mesh without seams (see
                                 ld_eb_sequence): faces seen flagged in
                                 the table (ld_o24_mark), border vertices
                                 -2 in the unvisited vertex map, and each
                                 value keeps its corner's opposite */
    const uint8_t  *seam;     /* corner -> edge opposite is a seam (ld_seam);
                                 NULL: none */
    /* An attribute's table with seams (ld_eb_points_run): c2v holds the
     * points, and rep maps a point to its attribute vertex, named by the
     * vertex's first point, with the vertex's border flag (the depth-first
     * walk's test) in bit 31; the traversal's vertex is rep[point] &
     * LD_REP_MASK. NULL: c2v holds the vertices. The predictions read a
     * corner's value through its point (every point of a vertex holds the
     * vertex's value once the traversal is done), so they ignore it. */
    const uint32_t *rep;
    const uint32_t *lmc;      /* vertex -> left-most corner */
    const uint8_t  *border;   /* vertex -> on a border (left-most corner
                                 has no swing left); NULL: ask lmc */
    uint32_t vmask;           /* the vertex bits of a c2v word */
    uint32_t num_vertices;
    uint32_t num_corners;
} ld_ct;

#define LD_REP_MASK 0x7FFFFFFFu
#define LD_REP_BORDER 0x80000000u
/* The table's opposites are not 32-bit ids (packed, or none): picks the
 * walks' instances. Always so in a lean-only build, where opp32 is NULL. */
static inline int ld_ct_packed(const ld_ct *t)
{
    return LD_LEAN_ONLY || t->opp32 == NULL;
}

/* x is a multiple of 3 exactly when x * 3^-1 (mod 2^32) <= (2^32 - 1) / 3:
 * one multiply and a compare instead of a division (corners < 2^32 - 1). */
static inline int ld_mul3(uint32_t x) { return x * 0xAAAAAAABu <= 0x55555555u; }
/* Corner stepping within a face (corners 3f, 3f+1, 3f+2) for corners
 * known to be valid (no LD_INV check) ... */
static inline uint32_t ld_next_v(uint32_t c) { return ld_mul3(c + 1u) ? c - 2u : c + 1u; }
static inline uint32_t ld_prev_v(uint32_t c) { return ld_mul3(c) ? c + 2u : c - 1u; }
/* ... and for any corner, LD_INV staying LD_INV. */
static inline uint32_t ld_next(uint32_t c) { return c == LD_INV ? c : ld_next_v(c); }
static inline uint32_t ld_prev(uint32_t c) { return c == LD_INV ? c : ld_prev_v(c); }
static inline uint32_t ld_opp(const ld_ct *t, uint32_t c)
{
    if (c == LD_INV || (t->seam && ld_seam(t->seam, c)))
        return LD_INV;
    return t->opp32 ? t->opp32[c] : ld_pot_opp(&t->opp, c);
}
static inline uint32_t ld_vert(const ld_ct *t, uint32_t c)
{
    return c == LD_INV ? LD_INV : t->c2v[c] & t->vmask;
}
/* The vertex a traversal visits at corner c: c2v's, through rep when the
 * table has one (LD_INV for a point out of range). */
static inline uint32_t ld_tvert(const ld_ct *t, uint32_t c)
{
    const uint32_t v = ld_vert(t, c);
    if (!t->rep)
        return v;
    return v < t->num_vertices ? t->rep[v] & LD_REP_MASK : LD_INV;
}

/* Swings take a valid corner and may return LD_INV. */
static inline uint32_t ld_swing_right(const ld_ct *t, uint32_t c)
{
    return ld_prev(ld_opp(t, ld_prev_v(c)));
}
static inline uint32_t ld_swing_left(const ld_ct *t, uint32_t c)
{
    return ld_next(ld_opp(t, ld_next_v(c)));
}

/* Encoded order of one attributes decoder's values (libdraco
 * MeshAttributeIndicesEncodingData + the traversal sequencer). */
typedef struct ld_order {
    const ld_ct *ct;
    int32_t *vertex_to_value;   /* per ct vertex; -1 unvisited */
    uint32_t *value_to_corner;
    uint32_t num_values;
} ld_order;

/* o->vertex_to_value: NULL, or an array of vmap_size entries to fill;
 * with ct->o24, filled by the caller (-1, or -2 for a border vertex).
 * At most max_values vertices get a value (more: LUMO_ERR_CORRUPT). */
lumo_status ld_traverse(ld_mem *m, const ld_ct *ct, uint32_t vmap_size, uint32_t max_values,
                        int prediction_degree, ld_order *o);

/* ---- EdgeBreaker (draco_edgebreaker.c) ----------------------------------- */
/* What the need scanner knows of an EdgeBreaker mesh (lumo_draco_arena_need). */
#define LD_NEED_MAX_ATTR_DATA 16u
typedef struct ld_eb_need {
    uint32_t faces, verts, splits, symbols, nad;
    uint8_t valence, lean;
    size_t w_opp_top;          /* work above the 32-bit opposites (fast) */
    size_t w_lmc_top;          /* work above the left-most corners' block */
    size_t w_table;            /* the packed table's escapes and indices */
    size_t w_region;           /* with seams: work above ld_eb_drop_dead's blocks */
    uint8_t table_live;        /* packed table and border bytes not released */
    uint8_t settled;           /* no seams: the first sequence dropped the
                                  left-most corners and chose how to read
                                  the table (ld_eb_need_sequence) */
    int8_t dec_att_data[LD_MAX_DECODERS];
    uint8_t dec_type[LD_MAX_DECODERS], dec_traversal[LD_MAX_DECODERS];
    uint8_t ad_used[LD_NEED_MAX_ATTR_DATA];
    uint8_t pos_used, num_decoders;
    /* value count of each attributes decoder, when an earlier scan learnt
     * it from a tagged stream (with seams), else LD_NEED_UNKNOWN */
    uint32_t known[LD_MAX_DECODERS];
    /* seams marked in the first 3F/2 bits of each seam stream */
    uint32_t seam_ones[LD_NEED_MAX_ATTR_DATA];
    /* attribute data read through the mesh's table (no interior seam) */
    uint8_t ad_shared[LD_NEED_MAX_ATTR_DATA];
    uint8_t vpoints;           /* no attribute data has an interior seam
                                  (ld_eb_peek_vpoints) */
} ld_eb_need;
#define LD_NEED_UNKNOWN 0xFFFFFFFFu
lumo_status ld_eb_need_connectivity(ld_buf *b, ld_need *k, ld_eb_need *e, int lean);
lumo_status ld_eb_need_decoder(ld_buf *b, ld_eb_need *e, unsigned decoder);
/* One attributes decoder's sequence: sets s->entries and s->mesh. */
/* b: the stream at the decoder's first attribute (its method is peeked) */
void ld_eb_need_sequence(ld_need *k, ld_eb_need *e, unsigned decoder, ld_need_seq *s,
                         const ld_buf *b);
void ld_eb_need_release(ld_eb_need *e, ld_need *k, uint32_t entries, int opposites);
/* Points of the mesh: exact without attribute seams, else a bound. */
uint64_t ld_eb_need_points(ld_need *k, const ld_eb_need *e);

lumo_status ld_eb_decode_connectivity(ld_dec *d);
lumo_status ld_eb_create_attributes_decoder(ld_dec *d, unsigned decoder, ld_seq *seq,
                                            uint8_t *traversal, uint8_t *vertex_attr);
lumo_status ld_eb_sequence(ld_dec *d, unsigned decoder, ld_seq *seq);
void ld_eb_release_table(ld_dec *d, ld_seq *seq, int opposites);
void ld_eb_finish(ld_dec *d);

#endif /* LUMO_DRACO_INTERNAL_H */
