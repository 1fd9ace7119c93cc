/*
 * draco_attribute.c — attribute descriptors and the sequential attribute
 * decoders (integer, quantization, octahedral normals): the portable
 * integer values, their prediction, and the transform parameters.
 *
 * Stream order per attributes decoder (libdraco AttributesDecoder):
 *   descriptors of all its attributes, one sequential-decoder type each;
 *   then for each attribute: prediction header, values, prediction data;
 *   then for each attribute: transform parameters (quantization / octahedron).
 */
#include "draco_internal.h"
#include "lumo/fixed.h"

#define LD_PRED_NONE (-2)
#define LD_SEQ_GENERIC 0u
#define LD_SEQ_INTEGER 1u
#define LD_SEQ_QUANTIZATION 2u
#define LD_SEQ_NORMALS 3u

lumo_status ld_read_descriptor(ld_buf *b, unsigned decoder, lumo_draco_attribute *a)
{
    uint8_t f[4];
    unsigned k;
    lumo_status st;
    for (k = 0; k < 4; ++k)
        if ((st = ld_u8(b, &f[k])))
            return st;
    if (f[0] > LUMO_DRACO_GENERIC || f[1] == 0 || f[1] > 11 || f[2] == 0)
        return LUMO_ERR_CORRUPT;
    if (f[2] > LUMO_DRACO_MAX_COMPONENTS)
        return LUMO_ERR_UNSUPPORTED;
    memset(a, 0, sizeof *a);
    a->type = f[0];
    a->data_type = f[1];
    a->num_components = f[2];
    a->num_portable = f[2];
    a->normalized = f[3] ? 1 : 0;
    a->modes.decoder_id = (uint8_t)decoder;
    a->modes.prediction = LD_PRED_NONE;
    a->modes.transform = -1;
    return ld_varint32(b, &a->unique_id);
}

lumo_status ld_read_seq_type(ld_buf *b, lumo_draco_attribute *a)
{
    uint8_t type;
    lumo_status st = ld_u8(b, &type);
    if (st)
        return st;
    if (type == LD_SEQ_GENERIC || type > LD_SEQ_NORMALS)
        return type == LD_SEQ_GENERIC ? LUMO_ERR_UNSUPPORTED : LUMO_ERR_CORRUPT;
    if ((type == LD_SEQ_QUANTIZATION || type == LD_SEQ_NORMALS) &&
        a->data_type != LUMO_DRACO_DT_FLOAT32)
        return LUMO_ERR_CORRUPT;
    if (type == LD_SEQ_NORMALS && a->num_components != 3)
        return LUMO_ERR_CORRUPT;
    if (type == LD_SEQ_INTEGER && (a->data_type > LUMO_DRACO_DT_UINT32))
        return LUMO_ERR_UNSUPPORTED;
    a->modes.seq_type = type;
    if (type == LD_SEQ_NORMALS)
        a->num_portable = 2;  /* octahedral coordinates */
    return LUMO_OK;
}

lumo_status ld_read_attribute_descriptors(ld_dec *d, unsigned decoder,
                                          uint32_t *first, uint32_t *count, int with_types)
{
    uint32_t n, i;
    lumo_status st = ld_varint32(&d->buf, &n);
    if (st)
        return st;
    if (n == 0 || n > LUMO_DRACO_MAX_ATTRIBUTES - d->num_attrs)
        return n ? LUMO_ERR_LIMIT : LUMO_ERR_CORRUPT;
    *first = d->num_attrs;
    *count = n;
    for (i = 0; i < n; ++i)
        if ((st = ld_read_descriptor(&d->buf, decoder, &d->attrs[d->num_attrs + i])))
            return st;
    d->num_attrs += n;
    for (i = 0; i < n && with_types; ++i)
        if ((st = ld_read_seq_type(&d->buf, &d->attrs[*first + i])))
            return st;
    return LUMO_OK;
}

/* The byte width of n values stored without entropy coding (1..4), checked
 * against the bytes left: the decode and the arena-need scan read it alike. */
static lumo_status ld_raw_values_width(ld_buf *b, uint32_t n, uint8_t *nb)
{
    lumo_status st = ld_u8(b, nb);
    if (st)
        return st;
    if (*nb == 0 || *nb > 4)
        return LUMO_ERR_CORRUPT;
    return (uint64_t)*nb * n > ld_remaining(b) ? LUMO_ERR_TRUNCATED : LUMO_OK;
}

/* Values stored without entropy coding: num_bytes little-endian bytes each. */
static lumo_status ld_raw_values(ld_buf *b, uint32_t n, int32_t *out)
{
    uint8_t nb;
    uint32_t i;
    lumo_status st = ld_raw_values_width(b, n, &nb);
    if (st)
        return st;
    for (i = 0; i < n; ++i) {
        const uint8_t *p = ld_head(b);
        uint32_t v = 0;
        unsigned k;
        for (k = 0; k < nb; ++k)
            v |= (uint32_t)p[k] << (8 * k);
        out[i] = (int32_t)v;
        b->pos += nb;
    }
    return LUMO_OK;
}

static void ld_symbols_to_signed(int32_t *v, uint32_t n)
{
    uint32_t i;
    for (i = 0; i < n; ++i)
        v[i] = ld_zigzag((uint32_t)v[i]);
}

static const lumo_draco_attribute *ld_find_position(const ld_dec *d)
{
    uint32_t i;
    for (i = 0; i < d->num_attrs; ++i)
        if (d->attrs[i].type == LUMO_DRACO_POSITION)
            return d->attrs[i].values ? &d->attrs[i] : NULL;
    return NULL;
}

static lumo_status ld_decode_portable(ld_dec *d, lumo_draco_attribute *a, ld_seq *seq)
{
    const uint32_t n = seq->num_entries;
    const unsigned comps = a->num_portable;
    size_t num_values = (size_t)n * comps;
    ld_pred pred;
    int8_t method, transform = -1;
    uint8_t compressed, *mark;
    int zz;
    lumo_status st;

    if (num_values > 0xFFFFFFFFu)
        return LUMO_ERR_LIMIT;
    a->num_values = n;
    a->point_to_value = seq->point_to_value;
    if ((st = ld_u8(&d->buf, (uint8_t *)&method)))
        return st;
    if (method != LD_PRED_NONE) {
        if ((st = ld_u8(&d->buf, (uint8_t *)&transform)))
            return st;
        if (transform < -1 || transform > 3)
            return LUMO_ERR_CORRUPT;
    }
    a->modes.prediction = method;
    a->modes.transform = transform;
    memset(&pred, 0, sizeof pred);
    pred.method = method;
    pred.transform = transform;
    pred.comps = comps;
    pred.seq = seq;
    pred.pos = ld_find_position(d);
    if (method != LD_PRED_NONE) {
        /* libdraco pairs integer attributes only with the wrap transform and
         * normals only with the octahedron transforms. */
        int normals = a->modes.seq_type == LD_SEQ_NORMALS;
        if (normals ? (transform != 2 && transform != 3) : transform != 1)
            return LUMO_ERR_UNSUPPORTED;
    }
    /* What the last attribute's prediction does not need of the corner
     * table goes before the values come. */
    if (seq->last && method != LD_PRED_NONE)
        ld_eb_release_table(d, seq, ld_pred_needs_opposites_only(&pred));
    a->values = ld_out(&d->mem, num_values, sizeof(int32_t));
    if (!a->values)
        return LUMO_ERR_NOMEM;
    if ((st = ld_u8(&d->buf, &compressed)))
        return st;
    a->modes.compressed = compressed ? 1 : 0;
    /* Values are zig-zag coded, except octahedral corrections (stored as
     * non-negative values); entropy-coded ones come out converted. */
    zz = !(method != LD_PRED_NONE && transform >= 2);
    if (compressed && zz)
        st = ld_decode_signed_symbols(&d->buf, &d->mem, (uint32_t)num_values, comps,
                                      a->values, &a->modes.symbol_coding);
    else if (compressed)
        st = ld_decode_symbols(&d->buf, &d->mem, (uint32_t)num_values, comps,
                               (uint32_t *)a->values, &a->modes.symbol_coding);
    else if (!(st = ld_raw_values(&d->buf, (uint32_t)num_values, a->values)) && zz)
        ld_symbols_to_signed(a->values, (uint32_t)num_values);
    if (st)
        return st;
    if (method == LD_PRED_NONE)
        return LUMO_OK;
    mark = ld_tmp_mark(&d->mem);
    st = ld_pred_decode_data(&pred, &d->buf, &d->mem, NULL);
    if (!st && num_values)
        st = ld_pred_compute(&pred, a->values, n);
    ld_tmp_release(&d->mem, mark);
    return st;
}

/* Fractional bits for min/range in fixed point: as many as keep
 * |min| + range below 2^30. */
static unsigned ld_frac_bits(const uint32_t *min_bits, unsigned comps, uint32_t range_bits)
{
    int e = (int)((range_bits >> 23) & 0xFFu) - 127;
    unsigned c;
    int f;
    for (c = 0; c < comps; ++c) {
        int ec = (int)((min_bits[c] >> 23) & 0xFFu) - 127;
        if (ec > e)
            e = ec;
    }
    f = 27 - e;
    return f < 0 ? 0u : (f > 30 ? 30u : (unsigned)f);
}

lumo_status ld_set_quantization(lumo_draco_attribute *a, unsigned bits)
{
    unsigned c;
    lumo_status st;
    a->xform = LUMO_DRACO_XFORM_QUANTIZED;
    a->quant_bits = (uint8_t)bits;
    a->frac_bits = (uint8_t)ld_frac_bits(a->min_bits, a->num_components, a->range_bits);
    for (c = 0; c < a->num_components; ++c)
        if ((st = lumo_f32bits_to_fixed(a->min_bits[c], a->frac_bits, &a->min_fixed[c])))
            return st;
    return lumo_f32bits_to_fixed(a->range_bits, a->frac_bits, &a->range_fixed);
}

/* The quantization transform's bit count, 1..30 as libdraco checks it
 * (AttributeQuantizationTransform::IsQuantizationValid). */
static lumo_status ld_quantization_bits(ld_buf *b, uint8_t *bits)
{
    lumo_status st = ld_u8(b, bits);
    if (st)
        return st;
    return *bits < 1 || *bits > 30 ? LUMO_ERR_CORRUPT : LUMO_OK;
}

static lumo_status ld_decode_quantization(ld_dec *d, lumo_draco_attribute *a)
{
    unsigned c, comps = a->num_components;
    uint8_t bits;
    lumo_status st;
    a->min_bits = ld_out(&d->mem, comps, sizeof(uint32_t));
    a->min_fixed = ld_out(&d->mem, comps, sizeof(int32_t));
    if (!a->min_bits || !a->min_fixed)
        return LUMO_ERR_NOMEM;
    for (c = 0; c < comps; ++c)
        if ((st = ld_u32(&d->buf, &a->min_bits[c])))
            return st;
    if ((st = ld_u32(&d->buf, &a->range_bits)) || (st = ld_quantization_bits(&d->buf, &bits)))
        return st;
    return ld_set_quantization(a, bits);
}

/* The octahedral transform's bit count (AttributeOctahedronTransform):
 * libdraco stores it unchecked and refuses it outside 2..30 only when it
 * converts to floats (OctahedronToolBox::SetQuantizationBits); lumo hands
 * it to the caller (lumo_draco_attribute.quant_bits, a shift count), so
 * it refuses such a stream at once, in the decode and the scan alike. */
static lumo_status ld_octahedral_bits(ld_buf *b, uint8_t *bits)
{
    lumo_status st = ld_u8(b, bits);
    if (st)
        return st;
    return *bits < 2 || *bits > 30 ? LUMO_ERR_CORRUPT : LUMO_OK;
}

static lumo_status ld_decode_transform_params(ld_dec *d, lumo_draco_attribute *a)
{
    uint8_t bits;
    lumo_status st;
    if (a->modes.seq_type == LD_SEQ_QUANTIZATION)
        return ld_decode_quantization(d, a);
    if (a->modes.seq_type != LD_SEQ_NORMALS)
        return LUMO_OK;
    if ((st = ld_octahedral_bits(&d->buf, &bits)))
        return st;
    a->xform = LUMO_DRACO_XFORM_OCTAHEDRAL;
    a->quant_bits = bits;
    return LUMO_OK;
}

lumo_status ld_decode_attributes(ld_dec *d, uint32_t first, uint32_t count, ld_seq *seq)
{
    uint32_t i;
    lumo_status st;
    for (i = 0; i < count; ++i)
        if ((st = ld_decode_portable(d, &d->attrs[first + i], seq)))
            return st;
    for (i = 0; i < count; ++i)
        if ((st = ld_decode_transform_params(d, &d->attrs[first + i])))
            return st;
    return LUMO_OK;
}

int32_t lumo_draco_dequantize(const lumo_draco_attribute *attr, unsigned comp, int32_t q)
{
    int64_t max_q, num, v;
    if (attr->xform != LUMO_DRACO_XFORM_QUANTIZED || comp >= attr->num_components)
        return q;
    max_q = ((int64_t)1 << attr->quant_bits) - 1;
    num = (int64_t)q * attr->range_fixed;
    /* round half away from zero */
    v = num >= 0 ? (num + max_q / 2) / max_q : -((-num + max_q / 2) / max_q);
    return lumo_sat_i32(v + attr->min_fixed[comp]);
}

/* ---- the need of an attributes decoder's values (lumo_draco_arena_need) ---- */

static lumo_status ld_need_raw_values(ld_buf *b, uint32_t n)
{
    uint8_t nb;
    lumo_status st = ld_raw_values_width(b, n, &nb);
    return st ? st : ld_skip(b, (uint64_t)nb * n);
}

/* ld_decode_portable on byte counts: the values output, the symbol
 * stream's tables, the prediction data; `s` says what the decoder's
 * sequence and corner table look like. */
static lumo_status ld_need_portable(ld_buf *b, ld_need *k, const ld_need_attr *a,
                                    ld_need_seq *s)
{
    const unsigned comps = a->portable;
    const uint64_t num_values = (uint64_t)s->entries * comps;
    uint32_t found = 0xFFFFFFFFu;
    size_t mark;
    int8_t method, transform = -1;
    uint8_t compressed;
    ld_pred pred;
    ld_seq seq;
    ld_ct ct;
    lumo_status st;
    if (num_values > 0xFFFFFFFFu)
        return LUMO_ERR_LIMIT;
    if ((st = ld_u8(b, (uint8_t *)&method)))
        return st;
    if (method != LD_PRED_NONE) {
        if ((st = ld_u8(b, (uint8_t *)&transform)))
            return st;
        if (transform < -1 || transform > 3)
            return LUMO_ERR_CORRUPT;
        if (a->seq_type == LD_SEQ_NORMALS ? (transform != 2 && transform != 3) : transform != 1)
            return LUMO_ERR_UNSUPPORTED;
    }
    memset(&pred, 0, sizeof pred);
    memset(&seq, 0, sizeof seq);
    memset(&ct, 0, sizeof ct);
    ct.num_corners = s->num_corners;
    seq.num_entries = s->entries;
    seq.ct = s->mesh ? &ct : NULL;
    pred.method = method;
    pred.transform = transform;
    pred.comps = comps;
    pred.seq = &seq;
    if (s->last && method != LD_PRED_NONE && s->eb)
        ld_eb_need_release(s->eb, k, s->entries, ld_pred_needs_opposites_only(&pred));
    ld_need_out(k, (size_t)num_values, sizeof(int32_t));
    if ((st = ld_u8(b, &compressed)))
        return st;
    if (!compressed && s->uncertain)
        return LUMO_ERR_LIMIT;  /* where they end depends on their count */
    st = compressed ? ld_need_symbols(b, k, (uint32_t)num_values, comps, s->uncertain ? &found : NULL)
                    : ld_need_raw_values(b, (uint32_t)num_values);
    if (st)
        return st;
    if (s->uncertain && found != 0xFFFFFFFFu) {  /* learnt from the tags */
        s->entries = found;
        s->uncertain = 0;
    }
    if (method == LD_PRED_NONE)
        return LUMO_OK;
    mark = k->work;
    st = ld_pred_decode_data(&pred, b, NULL, k);
    ld_need_release(k, mark);
    return st;
}

static lumo_status ld_need_transform_params(ld_buf *b, ld_need *k, const ld_need_attr *a)
{
    uint8_t bits;
    lumo_status st;
    if (a->seq_type == LD_SEQ_NORMALS)
        return ld_octahedral_bits(b, &bits);
    if (a->seq_type != LD_SEQ_QUANTIZATION)
        return LUMO_OK;
    ld_need_out(k, a->components, sizeof(uint32_t));
    ld_need_out(k, a->components, sizeof(int32_t));
    if ((st = ld_skip(b, 4u * (uint64_t)a->components + 4u)))
        return st;
    return ld_quantization_bits(b, &bits);
}

lumo_status ld_need_attributes(ld_buf *b, ld_need *k, const ld_need_attr *attrs, uint32_t count,
                               ld_need_seq *seq)
{
    uint32_t i;
    lumo_status st;
    for (i = 0; i < count; ++i)
        if ((st = ld_need_portable(b, k, &attrs[i], seq)))
            return st;
    for (i = 0; i < count; ++i)
        if ((st = ld_need_transform_params(b, k, &attrs[i])))
            return st;
    return LUMO_OK;
}

/* Whether the mesh attribute whose values start at `b` is predicted by a
 * scheme that reads more of the corner table than each entry's opposite
 * corner: its method byte, peeked (no prediction and differences read
 * none of it, the parallelogram the opposites only). */
static int ld_peek_reads_more(const ld_buf *b)
{
    ld_buf c = *b;
    ld_ct ct;
    ld_seq seq;
    ld_pred pred;
    int8_t method;
    if (ld_u8(&c, (uint8_t *)&method))
        return 1;
    memset(&ct, 0, sizeof ct);
    memset(&seq, 0, sizeof seq);
    memset(&pred, 0, sizeof pred);
    seq.ct = &ct;
    pred.method = method;
    pred.seq = &seq;
    return ld_pred_reads_table(&pred) && !ld_pred_needs_opposites_only(&pred);
}

/* Whether the values of the attribute at `b` are a tagged symbol stream:
 * where it ends is found only by decoding every value's tag
 * (ld_need_tagged), which costs more than the packing a peek past it
 * would spare (round six, scan_20k P+N -cl 4 -qp 14, positions tagged:
 * 0.32 M instructions more with the peek than with the packing). */
static int ld_peek_tagged(const ld_buf *b)
{
    ld_buf c = *b;
    int8_t method;
    uint8_t x;
    if (ld_u8(&c, (uint8_t *)&method) || (method != LD_PRED_NONE && ld_u8(&c, &x)) ||
        ld_u8(&c, &x))
        return 1;
    return x != 0 && (ld_u8(&c, &x) || x == 0);  /* compressed, scheme 0 */
}

/* Whether the `count` mesh attributes whose values start at `b` (`entries`
 * values each) are all predicted by schemes that read of the corner table
 * at most each entry's opposite corner: each one's method byte is peeked,
 * then its values and prediction data are passed over as the arena-need
 * scan passes them (ld_need_portable) to reach the next one's, unless
 * they are tagged (ld_peek_tagged: then the answer is 0). The
 * EdgeBreaker decoder and its arena-need replay ask alike before a
 * traversal (ld_eb_sequence; issue 25 round six). A stream it cannot read
 * answers 0 (the decode then fails where it reads the same bytes). */
int ld_peek_opposites_only(const ld_buf *b, const ld_need_attr *attrs, uint32_t count,
                           uint32_t entries)
{
    ld_buf c = *b;
    ld_need k;
    ld_need_seq s;
    uint32_t i;
    memset(&k, 0, sizeof k);
    memset(&s, 0, sizeof s);
    s.entries = entries;
    s.mesh = 1;
    for (i = 0; i < count; ++i) {
        if (ld_peek_reads_more(&c))
            return 0;
        if (i + 1u < count && (ld_peek_tagged(&c) || ld_need_portable(&c, &k, &attrs[i], &s)))
            return 0;
    }
    return 1;
}
