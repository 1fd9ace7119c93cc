/*
 * draco_rans.c — Draco's entropy decoders: the rANS symbol decoder with its
 * probability table, the tagged and raw symbol streams built on it
 * (DecodeSymbols), and the rABS binary decoder (RAnsBitDecoder).
 *
 * Differences from the written spec that the library dictates:
 *  - tagged symbols: one bit reader runs over all values (no per-value
 *    reset), bits least-significant first;
 *  - a 4-byte rANS state prefix (tag 3) exists for precisions above 12 bits.
 */
#include "draco_internal.h"

/* Symbol lookup: a coarse table of 2^LD_LUT_BITS buckets gives the first
 * symbol of each bucket, a short forward scan the exact one. This keeps the
 * table small (libdraco keeps one entry per probability unit, up to 2^20). */
#define LD_LUT_BITS 14u
#define LD_LUT_EXACT_BITS 16u

/* One symbol of non-zero probability: its probability range [lo, lo +
 * freq) and the word it decodes to (the symbol, or its zig-zag decoding
 * for signed streams: folded here once per symbol, not once per value).
 * The table ends with a sentinel whose `lo` is 2^prec_bits, so a coarse
 * bucket's scan needs no bound. */
typedef struct ld_rans_sym {
    uint32_t lo;
    uint32_t freq;
    uint32_t value;
} ld_rans_sym;

typedef struct ld_rans {
    const uint8_t *buf;
    uint32_t offset;
    uint32_t state;
    uint32_t prec_bits;
    uint32_t num_symbols;
    /* Only symbols of non-zero probability are kept (each costs at least
     * one input byte, so the tables are bounded by the input size). */
    uint32_t num_nz;
    ld_rans_sym *tab;  /* num_nz + 1 entries */
    uint32_t *lut;     /* bucket -> first table entry of the bucket, as a
                          byte offset into tab (an address without a
                          multiply per symbol) */
    unsigned lut_shift;
} ld_rans;

/* Precision from the stream's symbol bit length: 3/2 of it, in 12..20. */
static uint32_t ld_rans_precision(unsigned bit_length)
{
    uint32_t p = (3u * bit_length) / 2u;
    return p < 12u ? 12u : (p > 20u ? 20u : p);
}

/* One entry of a probability table: the probability of symbol *i, or a
 * run of zero-probability symbols (*i moves to the run's last, prob 0).
 * Bytes read in place after one bounds check (a table has up to 2^18
 * entries, read twice: no call per byte). */
static LD_FORCE_INLINE lumo_status ld_rans_entry(ld_buf *b, uint32_t n, uint32_t *i,
                                                 uint32_t *prob)
{
    const uint8_t *p = ld_head(b);
    uint32_t byte, extra, j;
    if (ld_remaining(b) < 1)
        return LUMO_ERR_TRUNCATED;
    byte = p[0];
    if ((byte & 3u) == 3u) {  /* run of zero-probability symbols */
        if (*i + (byte >> 2) >= n)
            return LUMO_ERR_CORRUPT;
        b->pos += 1;
        *i += byte >> 2;
        *prob = 0;
        return LUMO_OK;
    }
    extra = byte & 3u;
    if (ld_remaining(b) < 1u + extra)
        return LUMO_ERR_TRUNCATED;
    *prob = byte >> 2;
    for (j = 0; j < extra; ++j)
        *prob |= (uint32_t)p[1 + j] << (8 * (j + 1) - 2);
    b->pos += 1u + extra;
    return LUMO_OK;
}

/* Read the probability table: check it and count its symbols of
 * non-zero probability into r->num_nz (tab NULL), or fill tab with them
 * (num_nz + 1 entries). Inlined at both calls, so the counting pass has
 * no test of tab per entry. `zz`: symbols decode to their zig-zag
 * decoding. */
static LD_FORCE_INLINE lumo_status ld_rans_table(ld_rans *r, ld_buf *b, ld_rans_sym *tab, int zz)
{
    uint32_t n, i, total = 0, nz = 0;
    lumo_status st = ld_varint32(b, &n);
    if (st)
        return st;
    if (n / 64u > ld_remaining(b))
        return LUMO_ERR_CORRUPT;
    if (n > (1u << 18))
        return LUMO_ERR_LIMIT;  /* 18-bit symbols at most (raw coding) */
    r->num_symbols = n;
    if (tab)
        tab[0].lo = 0;
    for (i = 0; i < n; ++i) {
        uint32_t prob;
        if ((st = ld_rans_entry(b, n, &i, &prob)))
            return st;
        if (prob == 0)
            continue;
        if (prob > (1u << r->prec_bits) - total)
            return LUMO_ERR_CORRUPT;
        total += prob;
        if (tab) {
            tab[nz].freq = prob;
            tab[nz].value = zz ? (uint32_t)ld_zigzag(i) : i;
            tab[nz + 1u].lo = total;
        }
        ++nz;
    }
    r->num_nz = nz;
    if (n && total != (1u << r->prec_bits))
        return LUMO_ERR_CORRUPT;
    return LUMO_OK;
}

/* The table into r->tab from `m`, sized by a first, checking pass to its
 * symbols of non-zero probability (an alphabet of 2048 symbols often has
 * a third unused: zero runs cost a byte for many); m == NULL: only check
 * it and book its memory into `k`. */
static lumo_status ld_rans_read_table(ld_rans *r, ld_buf *b, ld_mem *m, ld_need *k, int zz)
{
    ld_buf probe = *b;
    lumo_status st = ld_rans_table(r, m ? &probe : b, NULL, 0);
    r->tab = NULL;
    if (st)
        return st;
    if (!m) {
        ld_need_tmp(k, r->num_nz + 1u, sizeof(ld_rans_sym));
        return LUMO_OK;
    }
    r->tab = ld_tmp(m, r->num_nz + 1u, sizeof(ld_rans_sym));
    if (!r->tab)
        return LUMO_ERR_NOMEM;
    return ld_rans_table(r, b, r->tab, zz);
}

/* The lookup table has at most 2^LD_LUT_BITS buckets and at least 256,
 * about one per four values between: 4 bytes a bucket, a quarter of the
 * values' own output at most (it is live next to them, and at the last
 * attribute's values it decides the arena's peak; two buckets per value
 * before issue 25 round three made it twice the values' bytes on a small
 * mesh's colours). Coarser buckets cost a short scan per symbol. */
static unsigned ld_rans_lut_bits(const ld_rans *r, uint32_t num_values)
{
    unsigned bits = 8;
    while (bits < LD_LUT_BITS && (8u << bits) <= num_values)
        ++bits;
    /* A long stream at up to 16-bit precision gets the exact table (one
     * bucket per probability unit, no scan): at most 256 KB, and only
     * with four values or more per bucket. */
    if (r->prec_bits <= LD_LUT_EXACT_BITS && (4u << r->prec_bits) <= num_values)
        bits = r->prec_bits;
    if (bits > r->prec_bits)
        bits = r->prec_bits;
    return bits;
}

/* q[0..n) = v, four per turn: a symbol's run of buckets is long (an exact
 * table of 2^16 buckets over some 10^3 symbols). */
static void ld_fill_u32(uint32_t *q, uint32_t n, uint32_t v)
{
    uint32_t j = 0;
    for (; j + 4u <= n; j += 4u) {
        q[j] = v;
        q[j + 1u] = v;
        q[j + 2u] = v;
        q[j + 3u] = v;
    }
    for (; j < n; ++j)
        q[j] = v;
}

static lumo_status ld_rans_build_lut(ld_rans *r, ld_mem *m, uint32_t num_values)
{
    const unsigned bits = ld_rans_lut_bits(r, num_values);
    uint32_t buckets, bkt, s, *lut;
    buckets = 1u << bits;
    r->lut_shift = r->prec_bits - bits;
    r->lut = ld_tmp(m, buckets, sizeof(uint32_t));
    if (!r->lut)
        return LUMO_ERR_NOMEM;
    /* Bucket b starts at b << shift; its first symbol is the one whose
     * range [tab[s].lo, tab[s+1].lo) holds that start: fill symbol by
     * symbol the buckets whose start falls in its range (the sentinel
     * tab[num_nz].lo == 2^prec). */
    lut = r->lut;
    for (s = 0, bkt = 0; s < r->num_nz; ++s) {
        const uint32_t end = (r->tab[s + 1].lo + (1u << r->lut_shift) - 1u) >> r->lut_shift;
        if (end > bkt) {
            ld_fill_u32(lut + bkt, end - bkt, s * (uint32_t)sizeof(ld_rans_sym));
            bkt = end;
        }
    }
    return LUMO_OK;
}

static lumo_status ld_rans_start(ld_rans *r, ld_buf *b)
{
    uint64_t bytes;
    const uint8_t *p;
    uint32_t off, x, l_base = 4u << r->prec_bits;
    lumo_status st = ld_varint64(b, &bytes);
    if (st)
        return st;
    if (bytes > ld_remaining(b) || bytes > 0x7FFFFFFFu)
        return LUMO_ERR_CORRUPT;
    p = ld_head(b);
    off = (uint32_t)bytes;
    b->pos += (size_t)bytes;
    if (off < 1)
        return LUMO_ERR_CORRUPT;
    x = p[off - 1] >> 6;
    if (off < x + 1)  /* libdraco does not check the 4-byte case */
        return LUMO_ERR_CORRUPT;
    off -= x + 1;
    r->state = p[off];
    if (x >= 1) r->state |= (uint32_t)p[off + 1] << 8;
    if (x >= 2) r->state |= (uint32_t)p[off + 2] << 16;
    if (x >= 3) r->state |= (uint32_t)p[off + 3] << 24;
    r->state &= (1u << (6 + 8 * x)) - 1u;
    r->state += l_base;
    if (r->state >= l_base * 256u)
        return LUMO_ERR_CORRUPT;
    r->buf = p;
    r->offset = off;
    return LUMO_OK;
}

/* One decoding step on a renormalised state: the symbol e whose range
 * holds rem = x mod 2^prec, then x = quo * freq + rem - lo. `exact`: the
 * lookup table has one bucket per probability unit (lut_shift 0) and
 * gives e itself; else it gives the first symbol of a coarse bucket and a
 * short forward scan the exact one (it stops at the sentinel at the
 * latest: rem < 2^prec). The caller keeps the coder in a local copy:
 * stores to the output may alias an ld_rans reached through a pointer and
 * force a reload of every field. */
static inline uint32_t ld_rans_step(const ld_rans *r, uint32_t *state, int exact)
{
    const uint32_t x = *state, quo = x >> r->prec_bits, rem = x & ((1u << r->prec_bits) - 1u);
    const uint32_t off = r->lut[rem >> (exact ? 0u : r->lut_shift)];
    const ld_rans_sym *e = (const ld_rans_sym *)(const void *)((const uint8_t *)r->tab + off);
    if (!exact)
        while (e[1].lo <= rem)
            ++e;
    *state = quo * e->freq + rem - e->lo;
    return e->value;
}

/* Renormalise and step, checking the start of the buffer: libdraco stops
 * reading there and goes on with a short state. */
static inline uint32_t ld_rans_read(ld_rans *r)
{
    const uint32_t l_base = 4u << r->prec_bits;
    while (r->state < l_base && r->offset > 0)
        r->state = (r->state << 8) | r->buf[--r->offset];
    return ld_rans_step(r, &r->state, 0);
}

/* Renormalise as the next step would; 1 when that reads every byte and
 * gives back the encoder's initial state (no symbol left). */
static int ld_rans_at_start(ld_rans *r)
{
    const uint32_t l_base = 4u << r->prec_bits;
    while (r->state < l_base && r->offset > 0)
        r->state = (r->state << 8) | r->buf[--r->offset];
    return r->offset == 0 && r->state == l_base;
}

/* n symbols into out. A step leaves a state of at least 4 (quo >= 4,
 * frequency >= 1), so three bytes always renormalise it (l_base <= 2^22):
 * offset / 3 steps need no check of the buffer start. */
static LD_FORCE_INLINE void ld_rans_run(ld_rans *r, uint32_t *out, uint32_t n, int exact)
{
    const ld_rans c = *r;
    const uint32_t l_base = 4u << c.prec_bits;
    const uint8_t *p = c.buf + c.offset;
    uint32_t x = c.state, i = 0;
    while (i < n) {
        const uint32_t safe = (uint32_t)(p - c.buf) / 3u;
        uint32_t *end = out + (n - i < safe ? n : i + safe), *o = out + i;
        if (safe == 0) {
            while (x < l_base && p > c.buf)
                x = (x << 8) | *--p;
            out[i++] = ld_rans_step(&c, &x, exact);
            continue;
        }
        /* two symbols per turn: half the loop's tests and increments */
        for (; o + 1 < end; o += 2) {
            while (x < l_base)
                x = (x << 8) | *--p;
            o[0] = ld_rans_step(&c, &x, exact);
            while (x < l_base)
                x = (x << 8) | *--p;
            o[1] = ld_rans_step(&c, &x, exact);
        }
        if (o < end) {
            while (x < l_base)
                x = (x << 8) | *--p;
            *o++ = ld_rans_step(&c, &x, exact);
        }
        i = (uint32_t)(o - out);
    }
    r->state = x;
    r->offset = (uint32_t)(p - c.buf);
}

/* The two instances (the flag must be a constant in the loop). */
static void ld_rans_run_exact(ld_rans *r, uint32_t *out, uint32_t n) { ld_rans_run(r, out, n, 1); }
static void ld_rans_run_coarse(ld_rans *r, uint32_t *out, uint32_t n) { ld_rans_run(r, out, n, 0); }

static lumo_status ld_rans_create(ld_rans *r, ld_buf *b, ld_mem *m, unsigned bit_length,
                                  uint32_t num_values, int zz)
{
    lumo_status st;
    r->prec_bits = ld_rans_precision(bit_length);
    if ((st = ld_rans_read_table(r, b, m, NULL, zz)))
        return st;
    if (r->num_symbols == 0)
        return LUMO_ERR_CORRUPT;  /* values announced but no alphabet */
    return ld_rans_build_lut(r, m, num_values);
}

/* The 8 bytes at p as a little-endian word (compilers make it one load). */
static inline uint64_t ld_le64(const uint8_t *p)
{
    return (uint64_t)p[0] | ((uint64_t)p[1] << 8) | ((uint64_t)p[2] << 16) |
           ((uint64_t)p[3] << 24) | ((uint64_t)p[4] << 32) | ((uint64_t)p[5] << 40) |
           ((uint64_t)p[6] << 48) | ((uint64_t)p[7] << 56);
}

/* Values of up to 32 raw bits after a tag per `comps` values: the bit
 * length, rANS coded. `zz` (a constant in each instance): the values are
 * zig-zag decoded as they are read (the tags never are). The tag coder
 * and the bit position are held in locals (stores to out could alias
 * them). A group whose bits end 8 bytes before the buffer does is read
 * from 64-bit windows (a value starts at most 7 bits into its window and
 * is at most 32 bits long), the same bits ld_bits_get returns; the groups
 * near the end go through ld_bits_get (zero bits past the end). */
static LD_FORCE_INLINE lumo_status ld_tagged_run(ld_rans *tags, ld_bits *bits, uint32_t *out,
                                                 uint32_t num_values, unsigned comps, int zz)
{
    ld_rans c = *tags;
    const uint8_t *const data = bits->data;
    const size_t size = bits->size;
    size_t bit = bits->bit;
    uint32_t *o = out, *const end = out + num_values;
    unsigned j;
    while (o < end) {
        /* a whole group, or the stream's short last one */
        const unsigned group = (size_t)(end - o) < comps ? (unsigned)(end - o) : comps;
        const uint32_t len = ld_rans_read(&c);
        if (len > 32u)
            return LUMO_ERR_CORRUPT;
        if (((bit + (size_t)group * len) >> 3) + 8u <= size) {
            const uint64_t mask = ((uint64_t)1 << len) - 1u;
            for (j = 0; j < group; ++j, bit += len) {
                const uint32_t v = (uint32_t)((ld_le64(data + (bit >> 3)) >> (bit & 7u)) & mask);
                *o++ = zz ? (uint32_t)ld_zigzag(v) : v;
            }
            continue;
        }
        bits->bit = bit;
        for (j = 0; j < group; ++j) {
            const uint32_t v = ld_bits_get(bits, len);
            *o++ = zz ? (uint32_t)ld_zigzag(v) : v;
        }
        bit = bits->bit;
    }
    bits->bit = bit;
    tags->state = c.state;
    tags->offset = c.offset;
    return LUMO_OK;
}

static lumo_status ld_decode_tagged(ld_buf *b, ld_mem *m, uint32_t num_values,
                                    unsigned comps, uint32_t *out, int zz)
{
    ld_rans tags;
    ld_bits bits;
    lumo_status st = ld_rans_create(&tags, b, m, 5, num_values / comps + 1u, 0);
    if (st || (st = ld_rans_start(&tags, b)))
        return st;
    ld_bits_start(&bits, b);
    st = zz ? ld_tagged_run(&tags, &bits, out, num_values, comps, 1)
            : ld_tagged_run(&tags, &bits, out, num_values, comps, 0);
    if (st)
        return st;
    ld_bits_end(&bits, b);
    /* The encoder's stream ends where it began: renormalised, every byte
     * read and the initial state back (libdraco does not check). The arena
     * need's scan finds the end of tags whose count it does not know by
     * this. */
    return ld_rans_at_start(&tags) ? LUMO_OK : LUMO_ERR_CORRUPT;
}

/* A raw rANS stream's symbol width, 1..18 bits (the decode and the
 * arena-need scan read it alike). */
static lumo_status ld_raw_max_bits(ld_buf *b, uint8_t *max_bits)
{
    lumo_status st = ld_u8(b, max_bits);
    if (st)
        return st;
    return *max_bits < 1 || *max_bits > 18 ? LUMO_ERR_CORRUPT : LUMO_OK;
}

static lumo_status ld_decode_raw(ld_buf *b, ld_mem *m, uint32_t num_values, uint32_t *out,
                                 int zz)
{
    ld_rans r;
    uint8_t max_bits;
    lumo_status st = ld_raw_max_bits(b, &max_bits);
    if (st)
        return st;
    if ((st = ld_rans_create(&r, b, m, max_bits, num_values, zz)) || (st = ld_rans_start(&r, b)))
        return st;
    if (r.lut_shift == 0)
        ld_rans_run_exact(&r, out, num_values);
    else
        ld_rans_run_coarse(&r, out, num_values);
    /* as for tagged streams: the encoder's stream ends where it began */
    return ld_rans_at_start(&r) ? LUMO_OK : LUMO_ERR_CORRUPT;
}

static lumo_status ld_decode_stream(ld_buf *b, ld_mem *m, uint32_t num_values,
                                    unsigned num_components, uint32_t *out,
                                    uint8_t *scheme_out, int zz)
{
    uint8_t scheme;
    uint8_t *mark;
    lumo_status st;
    if (num_values == 0)
        return LUMO_OK;  /* nothing at all is stored for an empty stream */
    if (num_components == 0)
        return LUMO_ERR_CORRUPT;
    if ((st = ld_u8(b, &scheme)))
        return st;
    if (scheme_out)
        *scheme_out = scheme;
    mark = ld_tmp_mark(m);
    if (scheme == 0)
        st = ld_decode_tagged(b, m, num_values, num_components, out, zz);
    else if (scheme == 1)
        st = ld_decode_raw(b, m, num_values, out, zz);
    else
        st = LUMO_ERR_CORRUPT;
    ld_tmp_release(m, mark);
    return st;
}

lumo_status ld_decode_symbols(ld_buf *b, ld_mem *m, uint32_t num_values,
                              unsigned num_components, uint32_t *out,
                              uint8_t *scheme_out)
{
    return ld_decode_stream(b, m, num_values, num_components, out, scheme_out, 0);
}

lumo_status ld_decode_signed_symbols(ld_buf *b, ld_mem *m, uint32_t num_values,
                                     unsigned num_components, int32_t *out,
                                     uint8_t *scheme_out)
{
    return ld_decode_stream(b, m, num_values, num_components, (uint32_t *)out, scheme_out, 1);
}

/* ---- rABS binary decoder --------------------------------------------------- */

lumo_status ld_rabs_start(ld_rabs *d, ld_buf *b)
{
    uint32_t size, x;
    const uint8_t *p;
    lumo_status st = ld_u8(b, &d->p0);
    if (st || (st = ld_varint32(b, &size)))
        return st;
    if (size > ld_remaining(b) || size < 1)
        return LUMO_ERR_CORRUPT;
    p = ld_head(b);
    x = p[size - 1] >> 6;
    if (x > 2 || size < x + 1)
        return LUMO_ERR_CORRUPT;
    d->offset = size - (x + 1);
    d->state = p[d->offset];
    if (x >= 1) d->state |= (uint32_t)p[d->offset + 1] << 8;
    if (x >= 2) d->state |= (uint32_t)p[d->offset + 2] << 16;
    d->state &= (1u << (6 + 8 * x)) - 1u;
    d->state += 4096u;
    if (d->state >= 4096u * 256u)
        return LUMO_ERR_CORRUPT;
    d->buf = p;
    b->pos += size;
    return LUMO_OK;
}

/* ---- the need of a symbol stream, without decoding its values ------------- */

static void ld_need_lut(ld_need *k, const ld_rans *r, uint32_t num_values)
{
    ld_need_tmp(k, (size_t)1 << ld_rans_lut_bits(r, num_values), sizeof(uint32_t));
}

/* Tagged values are followed by their raw bits, whose length only the tags
 * tell: the tags are decoded with their table on the stack (a tag is a bit
 * length, so the alphabet of a real stream has at most 33 symbols) and a
 * linear search, and the bits are skipped. */
#define LD_NEED_TAGS 64u

/* The scan reads every tag without having paid for its values in arena
 * memory (the decode allocates them first), so a header claiming millions
 * of values over a few bytes of near-certain tags would keep it busy: it
 * reads at most this many values, 64 per byte left plus 2^20 (a real
 * stream spends well over a bit per value unless its values are all the
 * same length, which one tag codes without a loop), else LUMO_ERR_LIMIT. */
static uint32_t ld_need_tag_budget(const ld_buf *b)
{
    const size_t n = ld_remaining(b);
    return n > 0xFFFFFFu ? 0xFFFFFFFFu : (uint32_t)(n * 64u) + (1u << 20);
}

static lumo_status ld_need_tagged(ld_buf *b, ld_need *k, uint32_t num_values, unsigned comps,
                                  uint32_t *found)
{
    uint64_t space[2u * (LD_NEED_TAGS + 2u)];
    const uint32_t zero = 0;
    ld_buf table = *b;
    ld_rans tags;
    lumo_arena a;
    ld_mem m;
    ld_bits bits;
    const uint32_t budget = ld_need_tag_budget(b);
    uint32_t i = 0;
    unsigned j;
    lumo_status st;
    tags.prec_bits = ld_rans_precision(5);
    if ((st = ld_rans_read_table(&tags, b, NULL, k, 0)))
        return st;
    if (tags.num_symbols == 0)
        return LUMO_ERR_CORRUPT;
    ld_need_lut(k, &tags, num_values / comps + 1u);
    if (tags.num_symbols > LD_NEED_TAGS)
        return LUMO_ERR_LIMIT;  /* not a stream the encoder writes */
    lumo_arena_init(&a, space, sizeof space);
    ld_mem_init(&m, &a);
    if ((st = ld_rans_read_table(&tags, &table, &m, NULL, 0)) || (st = ld_rans_start(&tags, b)))
        return st;
    tags.lut = (uint32_t *)(uintptr_t)&zero;  /* one bucket: search from 0 */
    tags.lut_shift = tags.prec_bits;
    ld_bits_start(&bits, b);
    if (found) {
        /* The count is unknown (values per corner): rANS decoding returns
         * to its initial state with every byte read exactly after the last
         * symbol, and not before unless one tag has all the probability. */
        if (tags.num_nz < 2u)
            return LUMO_ERR_LIMIT;  /* the state never moves */
        for (*found = 0; !ld_rans_at_start(&tags); ++*found) {
            uint32_t len;
            if (*found >= num_values / comps)
                return LUMO_ERR_CORRUPT;  /* the decode fails on it too */
            if (*found >= budget / comps)
                return LUMO_ERR_LIMIT;
            if ((len = ld_rans_read(&tags)) > 32u)
                return LUMO_ERR_CORRUPT;
            for (j = 0; j < comps; ++j)
                (void)ld_bits_get(&bits, len);
        }
        ld_bits_end(&bits, b);
        return LUMO_OK;
    }
    if (tags.num_nz < 2u) {  /* one tag: every value has its length */
        const uint32_t len = ld_rans_read(&tags);
        if (len > 32u)
            return LUMO_ERR_CORRUPT;
        ld_bits_skip(&bits, (uint64_t)len * num_values);
        ld_bits_end(&bits, b);
        return LUMO_OK;
    }
    if (num_values > budget)
        return LUMO_ERR_LIMIT;
    while (i < num_values) {
        const uint32_t len = ld_rans_read(&tags);
        if (len > 32u)
            return LUMO_ERR_CORRUPT;
        for (j = 0; j < comps && i < num_values; ++j, ++i)
            (void)ld_bits_get(&bits, len);
    }
    ld_bits_end(&bits, b);
    return LUMO_OK;
}

/* Symbols of a raw stream whose count is unknown, counted without a
 * table: each step finds its symbol's range by reading the probability
 * table again from the stream. Bounded: LD_NEED_RAW_WORK table entries
 * in all, else the count stays unknown (the stream's end is coded). */
#define LD_NEED_RAW_WORK (1u << 24)

static lumo_status ld_need_raw_count(ld_rans *r, const ld_buf *table, uint32_t max_steps,
                                     uint32_t *steps)
{
    const uint32_t mask = (1u << r->prec_bits) - 1u;
    uint32_t work = 0;
    lumo_status st;
    for (*steps = 0; !ld_rans_at_start(r); ++*steps) {
        const uint32_t rem = r->state & mask, quo = r->state >> r->prec_bits;
        uint32_t i, lo = 0, prob = 0;
        ld_buf t = *table;
        if (*steps >= max_steps)
            return LUMO_ERR_CORRUPT;  /* the decode fails on it too */
        for (i = 0; i < r->num_symbols; ++i) {
            if (++work > LD_NEED_RAW_WORK)
                return LUMO_ERR_LIMIT;
            if ((st = ld_rans_entry(&t, r->num_symbols, &i, &prob)))
                return st;
            if (lo + prob > rem)
                break;
            lo += prob;
        }
        if (i >= r->num_symbols || prob == 0)
            return LUMO_ERR_CORRUPT;
        r->state = quo * prob + rem - lo;
    }
    return LUMO_OK;
}

static lumo_status ld_need_raw(ld_buf *b, ld_need *k, uint32_t num_values, unsigned comps,
                               uint32_t *found)
{
    ld_rans r;
    ld_buf table;
    uint32_t steps, n;
    uint8_t max_bits;
    lumo_status st = ld_raw_max_bits(b, &max_bits);
    if (st)
        return st;
    r.prec_bits = ld_rans_precision(max_bits);
    table = *b;
    if ((st = ld_rans_read_table(&r, b, NULL, k, 0)))
        return st;
    if (r.num_symbols == 0)
        return LUMO_ERR_CORRUPT;
    ld_need_lut(k, &r, num_values);
    if ((st = ld_rans_start(&r, b)) || !found || r.num_nz < 2u)
        return st;  /* the coded bytes skipped; one symbol: the state never moves */
    (void)ld_varint32(&table, &n);  /* read before: cannot fail */
    st = ld_need_raw_count(&r, &table, num_values, &steps);
    if (st == LUMO_ERR_LIMIT)
        return LUMO_OK;  /* count unknown */
    if (st)
        return st;
    if (steps % comps)
        return LUMO_ERR_CORRUPT;
    *found = steps / comps;
    return LUMO_OK;
}

lumo_status ld_need_symbols(ld_buf *b, ld_need *k, uint32_t num_values, unsigned num_components,
                            uint32_t *found)
{
    const size_t mark = k->work;
    uint8_t scheme;
    lumo_status st;
    if (num_values == 0)
        return LUMO_OK;
    if (num_components == 0)
        return LUMO_ERR_CORRUPT;
    if ((st = ld_u8(b, &scheme)))
        return st;
    if (found)
        *found = 0xFFFFFFFFu;
    if (scheme == 0)
        st = ld_need_tagged(b, k, num_values, num_components, found);
    else if (scheme == 1)
        st = ld_need_raw(b, k, num_values, num_components, found);
    else
        st = LUMO_ERR_CORRUPT;
    ld_need_release(k, mark);
    return st;
}
