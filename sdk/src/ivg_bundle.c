/*
 * ivg_bundle.c — decoder of IVG sample records (seed 000 §3.3 and §4.1;
 * wire format in lumo/ivg.h and docs/ivg-format.md): whole bundles (a
 * header, then records) and runs of records without the header (a slice of
 * a package's bundle as the server streams it, docs/protocol.md).
 *
 * Every byte is hostile. Both entry points open a `run` (form, count and the
 * record bytes) and hand it to the one loop below: the first walk checks
 * every record (and marks each vertex in seen_bits to catch duplicates), the
 * second stores them. Nothing touches the grid's data until the whole run
 * has passed, so a bad one leaves the grid as it was. Work is linear in the
 * run's length.
 */
#include <string.h>
#include "ivg_internal.h"
#include "lumo/wire.h"

static const uint8_t k_magic[4] = {0x49, 0x56, 0x47, 0x42};   /* "IVGB" */

/* |d|^2 must be zero or within [(15/16)^2, (17/16)^2]: a server normalises
 * d, and 8-bit quantization moves its length by less than 0.007. */
#define D_TOL_LO 15
#define D_TOL_HI 17

/* A run of records: the bytes right after a bundle header, or what
 * lumo_ivg_apply_records was given. */
typedef struct run {
    const uint8_t *p;
    size_t         len;
    unsigned       form;
    uint32_t       records;
    size_t         entry_bytes;
} run;

static int form_known(unsigned form)
{
    return form == LUMO_IVG_FORM_FLOAT || form == LUMO_IVG_FORM_QUANTIZED;
}

/* The checks every run passes before its records are read. */
static lumo_status open_run(const lumo_ivg *g, unsigned form, uint32_t count, const uint8_t *p, size_t len,
                            run *b)
{
    if (!form_known(form))
        return LUMO_ERR_UNSUPPORTED;
    /* Each record is at least its 4-byte index word; with duplicates
     * rejected no valid run has more records than the grid vertices. */
    if (count > g->count)
        return LUMO_ERR_CORRUPT;
    if (count > len / 4u)
        return LUMO_ERR_TRUNCATED;
    b->p = p;
    b->len = len;
    b->form = form;
    b->records = count;
    b->entry_bytes = form == LUMO_IVG_FORM_FLOAT ? LUMO_IVG_FLOAT_ENTRY : LUMO_IVG_QUANT_ENTRY;
    return LUMO_OK;
}

/* The 16-byte bundle header, then the run after it. */
static lumo_status parse_header(const lumo_ivg *g, const uint8_t *buf, size_t len, run *b)
{
    int a;

    if (len < LUMO_IVG_BUNDLE_HEADER)
        return LUMO_ERR_TRUNCATED;
    if (memcmp(buf, k_magic, sizeof k_magic) != 0)
        return LUMO_ERR_CORRUPT;
    if (buf[4] != LUMO_IVG_BUNDLE_VERSION)
        return LUMO_ERR_VERSION;
    if (!form_known(buf[5]))
        return LUMO_ERR_UNSUPPORTED;
    for (a = 0; a < 3; a++)
        if (lumo_wire_le16(buf + 6 + 2 * a) != g->desc.dims[a])
            return LUMO_ERR_RANGE;
    return open_run(g, buf[5], lumo_wire_le32(buf + 12), buf + LUMO_IVG_BUNDLE_HEADER,
                    len - LUMO_IVG_BUNDLE_HEADER, b);
}

/* Length check of a direction given as integers at scale `one` (127 for
 * q/127, 2^14 for Q1.14): zero, or |d| within 1/16 of one. A component
 * beyond 2 * one fails first, which keeps the squares far from overflow
 * whatever a hostile binary32 held. */
static lumo_status check_direction(int64_t x, int64_t y, int64_t z, int64_t one)
{
    int64_t len2, lo = D_TOL_LO * one, hi = D_TOL_HI * one;

    if (x > 2 * one || x < -2 * one || y > 2 * one || y < -2 * one || z > 2 * one || z < -2 * one)
        return LUMO_ERR_RANGE;
    len2 = x * x + y * y + z * z;
    if (len2 == 0)
        return LUMO_OK;
    if (256 * len2 < lo * lo || 256 * len2 > hi * hi)
        return LUMO_ERR_RANGE;
    return LUMO_OK;
}

static lumo_status decode_quantized(const uint8_t *p, lumo_ivg_entry *e)
{
    int32_t q[3];
    lumo_status st;
    int k;

    for (k = 0; k < 3; k++) {
        q[k] = p[k] < 128u ? (int32_t)p[k] : (int32_t)p[k] - 256;
        if (q[k] == -128)
            return LUMO_ERR_CORRUPT;
    }
    st = check_direction(q[0], q[1], q[2], 127);
    if (st)
        return st;
    for (k = 0; k < 3; k++)
        e->d[k] = ivg_snorm8_to_q14(q[k]);
    lumo_rgb9e5_to_uq16(lumo_wire_le32(p + 3), e->c);
    e->reserved = 0;
    return LUMO_OK;
}

/* A binary32 colour channel as UQ16.16. Negative values (but -0) and values
 * above 65535 are out of range. Below 2^15 the value converts with 16
 * fraction bits; from 2^15 on a binary32 has at most 8 fraction bits, so
 * converting with 8 and shifting is exact. */
static lumo_status colour_to_uq16(uint32_t bits, lumo_uq16_16 *out)
{
    int32_t v;
    lumo_status st;

    if ((bits >> 31) != 0)
        return (bits & 0x7FFFFFFFu) == 0 ? (*out = 0, LUMO_OK) : LUMO_ERR_RANGE;
    if (bits > 0x477FFF00u)                         /* 65535.0 */
        return LUMO_ERR_RANGE;
    if (bits < 0x47000000u)                         /* 32768.0 */
        st = lumo_f32bits_to_fixed(bits, 16, &v);
    else
        st = lumo_f32bits_to_fixed(bits, 8, &v);
    if (st)
        return st;
    *out = bits < 0x47000000u ? (uint32_t)v : (uint32_t)v << 8;
    return LUMO_OK;
}

static lumo_status decode_binary32(const uint8_t *p, lumo_ivg_entry *e)
{
    uint32_t bits[6];
    int32_t d[3];
    lumo_status st;
    int k;

    /* Non-finite values first, wherever they are: NaN is never a range error. */
    for (k = 0; k < 6; k++) {
        bits[k] = lumo_wire_le32(p + 4 * k);
        if (!lumo_f32bits_is_finite(bits[k]))
            return LUMO_ERR_NONFINITE;
    }
    for (k = 0; k < 3; k++) {
        st = lumo_f32bits_to_fixed(bits[k], LUMO_Q14_SHIFT, &d[k]);
        if (st)
            return st;
    }
    st = check_direction(d[0], d[1], d[2], LUMO_Q14_ONE);
    for (k = 0; k < 3 && st == LUMO_OK; k++)
        st = colour_to_uq16(bits[3 + k], &e->c[k]);
    if (st)
        return st;
    for (k = 0; k < 3; k++)
        e->d[k] = (lumo_q1_14)d[k];   /* |d| <= 17/16 was checked: fits */
    e->reserved = 0;
    return LUMO_OK;
}

static lumo_status decode_entry(unsigned form, const uint8_t *p, lumo_ivg_entry *e)
{
    return form == LUMO_IVG_FORM_FLOAT ? decode_binary32(p, e) : decode_quantized(p, e);
}

/* Check record by record; on success every record's vertex is marked in
 * seen_bits. *done gets the number of records fully checked (and marked). */
static lumo_status validate(lumo_ivg *g, const run *b, uint32_t *done)
{
    size_t pos = 0;
    lumo_ivg_entry tmp[LUMO_IVG_AXES];
    uint32_t r;
    lumo_status st;
    int a;

    for (r = 0; r < b->records; r++) {
        uint32_t word, v;
        *done = r;
        if (b->len - pos < 4u)
            return LUMO_ERR_TRUNCATED;
        word = lumo_wire_le32(b->p + pos);
        pos += 4u;
        v = word & ~LUMO_IVG_SOLID_BIT;
        if (v >= g->count)
            return LUMO_ERR_RANGE;
        if (ivg_bit(g->seen_bits, v))
            return LUMO_ERR_CORRUPT;
        if (!(word & LUMO_IVG_SOLID_BIT)) {
            if (b->len - pos < LUMO_IVG_AXES * b->entry_bytes)
                return LUMO_ERR_TRUNCATED;
            for (a = 0; a < LUMO_IVG_AXES; a++, pos += b->entry_bytes) {
                st = decode_entry(b->form, b->p + pos, &tmp[a]);
                if (st)
                    return st;
            }
        }
        ivg_bit_set(g->seen_bits, v);
    }
    *done = r;
    return pos == b->len ? LUMO_OK : LUMO_ERR_CORRUPT;
}

/* Vertex v now holds received data, or is solid (data cleared). */
static void mark_vertex(lumo_ivg *g, uint32_t v, int solid)
{
    g->received -= (uint32_t)ivg_bit(g->received_bits, v);
    g->solid -= (uint32_t)ivg_bit(g->solid_bits, v);
    if (solid) {
        ivg_bit_clear(g->received_bits, v);
        ivg_bit_set(g->solid_bits, v);
        memset(ivg_packed_at(&g->level[0], v, 0), 0, IVG_PACKED_VERTEX);
        g->solid++;
    } else {
        ivg_bit_set(g->received_bits, v);
        ivg_bit_clear(g->solid_bits, v);
        g->received++;
    }
}

/* One validated entry into its packed slot: a quantized one is already in
 * the stored form and is kept byte for byte; a binary32 one is rounded to
 * it (docs/ivg-format.md §2.5). */
static void store_entry(unsigned form, const uint8_t *p, uint8_t *slot)
{
    lumo_ivg_entry e;

    if (form == LUMO_IVG_FORM_QUANTIZED) {
        memcpy(slot, p, IVG_PACKED);
        return;
    }
    (void)decode_binary32(p, &e);
    ivg_entry_pack(&e, slot);
}

/* Walk the first `records` records (already validated); store them when
 * `store`, and clear their seen bits either way. */
static void walk(lumo_ivg *g, const run *b, uint32_t records, int store)
{
    size_t pos = 0;
    uint32_t r;
    int a;

    for (r = 0; r < records; r++) {
        uint32_t word = lumo_wire_le32(b->p + pos);
        uint32_t v = word & ~LUMO_IVG_SOLID_BIT;
        uint8_t *e = ivg_packed_at(&g->level[0], v, 0);
        int solid = (word & LUMO_IVG_SOLID_BIT) != 0;

        pos += 4u;
        ivg_bit_clear(g->seen_bits, v);
        if (!solid) {
            for (a = 0; a < LUMO_IVG_AXES && store; a++)
                store_entry(b->form, b->p + pos + a * b->entry_bytes, e + a * IVG_PACKED);
            pos += LUMO_IVG_AXES * b->entry_bytes;
        }
        if (store)
            mark_vertex(g, v, solid);
    }
}

/* The one validate-then-apply loop of both entry points. */
static lumo_status apply_run(lumo_ivg *g, const run *b, uint32_t *applied)
{
    uint32_t done = 0;
    lumo_status st = validate(g, b, &done);

    walk(g, b, done, st == LUMO_OK);
    if (st)
        return st;
    if (applied != NULL)
        *applied = b->records;
    return LUMO_OK;
}

lumo_status lumo_ivg_apply_bundle(lumo_ivg *g, const uint8_t *buf, size_t len, uint32_t *applied)
{
    run b;
    lumo_status st;

    if (g == NULL || (buf == NULL && len != 0))
        return LUMO_ERR_ARG;
    st = parse_header(g, buf, len, &b);
    return st ? st : apply_run(g, &b, applied);
}

lumo_status lumo_ivg_apply_records(lumo_ivg *g, lumo_ivg_form form, uint32_t count, const uint8_t *records,
                                   size_t len, uint32_t *applied)
{
    run b;
    lumo_status st;

    if (g == NULL || (records == NULL && len != 0))
        return LUMO_ERR_ARG;
    st = open_run(g, (unsigned)form, count, records, len, &b);
    return st ? st : apply_run(g, &b, applied);
}
