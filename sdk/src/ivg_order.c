/*
 * ivg_order.c — the stratified streaming order of a package's IVG (seed 000
 * §4.1; payload `IVGS` in lumo/ivg.h and docs/package-format.md): decode and
 * check it, say where rounds start, and check a bundle against it.
 *
 * Every byte is hostile: the decoder checks the whole table before it
 * answers anything, so the accessors can read it without checks. Integer
 * code only, no allocation.
 */
#include "lumo/ivg.h"
#include "lumo/wire.h"

uint32_t lumo_ivg_order_axis(const uint16_t dims[3])
{
    if (dims[0] >= dims[1] && dims[0] >= dims[2])
        return 0;
    return dims[1] >= dims[2] ? 1u : 2u;
}

static uint32_t entry(const lumo_ivg_order *o, uint32_t array, uint32_t r)
{
    if (r > o->rounds)
        r = o->rounds;
    return lumo_wire_le32(o->table + 4u * ((size_t)array * (o->rounds + 1u) + r));
}

uint32_t lumo_ivg_order_first(const lumo_ivg_order *o, uint32_t r)
{
    return entry(o, 0, r);
}

uint32_t lumo_ivg_order_offset(const lumo_ivg_order *o, lumo_ivg_form form, uint32_t r)
{
    return entry(o, form == LUMO_IVG_FORM_FLOAT ? 2u : 1u, r);
}

uint32_t lumo_ivg_order_rounds_in(const lumo_ivg_order *o, uint32_t records)
{
    uint32_t lo = 0, hi = o->rounds;

    /* the largest r with first(r) <= records: rounds 0 .. r-1 are whole */
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo + 1u) / 2u;
        if (lumo_ivg_order_first(o, mid) <= records)
            lo = mid;
        else
            hi = mid - 1u;
    }
    return lo;
}

/* Records of round r >= 1 on a grid whose slices hold `per_slice` vertices:
 * every slice that still has unsent ones gives one; the two end slices
 * lost their four corners to round 0. */
static uint32_t grid_round_records(uint32_t slices, uint32_t per_slice, uint32_t r)
{
    uint32_t n = 0;
    if (slices > 2u && r <= per_slice)
        n += slices - 2u;
    if (r + 4u <= per_slice)
        n += 2u;
    return n;
}

/* A round's byte span in one form: 4 bytes per record plus a whole number
 * of data records' entries, at most one per record; *data gets that
 * number. (records <= 256, so everything fits 32 bits.) */
static lumo_status round_data(uint32_t records, uint32_t from, uint32_t to, uint32_t data_record, uint32_t *data)
{
    uint32_t span, extra;
    if (to < from || (span = to - from) < 4u * records)
        return LUMO_ERR_CORRUPT;
    extra = span - 4u * records;
    if (extra % (data_record - 4u) != 0 || extra / (data_record - 4u) > records)
        return LUMO_ERR_CORRUPT;
    *data = extra / (data_record - 4u);
    return LUMO_OK;
}

lumo_status lumo_ivg_order_decode(const uint8_t *p, size_t len, const lumo_ivg_desc *desc, lumo_ivg_order *out)
{
    lumo_ivg_order o;
    uint32_t r, per_slice = 0;
    uint64_t need;
    lumo_status st;

    if (!p || !out)
        return LUMO_ERR_ARG;
    if (len < LUMO_IVG_ORDER_HEADER)
        return LUMO_ERR_TRUNCATED;
    o.seed = lumo_wire_le64(p);
    o.axis = p[8];
    o.slices = lumo_wire_le32(p + 12);
    o.rounds = lumo_wire_le32(p + 16);
    if (o.axis > 2u)
        return LUMO_ERR_CORRUPT;
    if (o.slices < LUMO_IVG_MIN_DIM || o.slices > LUMO_IVG_MAX_DIM || o.rounds < 1u ||
        o.rounds > LUMO_IVG_ORDER_MAX_ROUNDS)
        return LUMO_ERR_RANGE;
    need = LUMO_IVG_ORDER_HEADER + 12u * ((uint64_t)o.rounds + 1u);
    if ((uint64_t)len != need)
        return (uint64_t)len < need ? LUMO_ERR_TRUNCATED : LUMO_ERR_CORRUPT;
    o.table = p + LUMO_IVG_ORDER_HEADER;
    o.records = lumo_ivg_order_first(&o, o.rounds);
    if (desc) {
        uint32_t n = (uint32_t)desc->dims[0] * desc->dims[1] * desc->dims[2];
        if (lumo_ivg_order_axis(desc->dims) != o.axis || desc->dims[o.axis] != o.slices)
            return LUMO_ERR_RANGE;
        per_slice = n / o.slices;
        if (o.rounds != 1u + (o.slices > 2u ? per_slice : per_slice - 4u) || o.records != n)
            return LUMO_ERR_RANGE;
    }
    if (lumo_ivg_order_first(&o, 0) != 0 || lumo_ivg_order_offset(&o, LUMO_IVG_FORM_QUANTIZED, 0) !=
        LUMO_IVG_BUNDLE_HEADER || lumo_ivg_order_offset(&o, LUMO_IVG_FORM_FLOAT, 0) != LUMO_IVG_BUNDLE_HEADER)
        return LUMO_ERR_CORRUPT;
    for (r = 0; r < o.rounds; r++) {
        uint32_t a = lumo_ivg_order_first(&o, r), b = lumo_ivg_order_first(&o, r + 1u), n, dq, df;
        if (b <= a)
            return LUMO_ERR_CORRUPT;
        n = b - a;
        if (r == 0 ? n != 8u : n > o.slices)
            return LUMO_ERR_CORRUPT;
        if (desc && r > 0 && n != grid_round_records(o.slices, per_slice, r))
            return LUMO_ERR_RANGE;
        st = round_data(n, lumo_ivg_order_offset(&o, LUMO_IVG_FORM_QUANTIZED, r),
                        lumo_ivg_order_offset(&o, LUMO_IVG_FORM_QUANTIZED, r + 1u), LUMO_IVG_QUANT_RECORD, &dq);
        if (!st)
            st = round_data(n, lumo_ivg_order_offset(&o, LUMO_IVG_FORM_FLOAT, r),
                            lumo_ivg_order_offset(&o, LUMO_IVG_FORM_FLOAT, r + 1u), LUMO_IVG_FLOAT_RECORD, &df);
        if (st || dq != df)
            return LUMO_ERR_CORRUPT;
    }
    *out = o;
    return LUMO_OK;
}

lumo_status lumo_ivg_order_check_bundle(const lumo_ivg_order *o, lumo_ivg_form form, const uint8_t *bundle,
                                        size_t len)
{
    uint32_t rec_bytes = form == LUMO_IVG_FORM_FLOAT ? LUMO_IVG_FLOAT_RECORD : LUMO_IVG_QUANT_RECORD;
    uint32_t rec, r = 0;
    size_t pos = LUMO_IVG_BUNDLE_HEADER;

    if (!o || !bundle || (form != LUMO_IVG_FORM_FLOAT && form != LUMO_IVG_FORM_QUANTIZED))
        return LUMO_ERR_ARG;
    if (len < LUMO_IVG_BUNDLE_HEADER)
        return LUMO_ERR_TRUNCATED;
    if (bundle[5] != (uint8_t)form || lumo_wire_le32(bundle + 12) != o->records ||
        len != lumo_ivg_order_offset(o, form, o->rounds))
        return LUMO_ERR_CORRUPT;
    for (rec = 0; rec < o->records; rec++) {
        if (lumo_ivg_order_first(o, r) == rec) {
            if (lumo_ivg_order_offset(o, form, r) != pos)
                return LUMO_ERR_CORRUPT;
            r++;
        }
        if (len - pos < 4u)
            return LUMO_ERR_TRUNCATED;
        pos += lumo_wire_le32(bundle + pos) & LUMO_IVG_SOLID_BIT ? 4u : rec_bytes;
        if (pos > len)
            return LUMO_ERR_TRUNCATED;
    }
    return pos == len ? LUMO_OK : LUMO_ERR_CORRUPT;
}
