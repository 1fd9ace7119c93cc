/*
 * draco_kdtree.c — KD-tree point clouds (libdraco KdTreeAttributesDecoder
 * with DynamicIntegerPointsKdTreeDecoder; not in the written spec, the
 * 1.5.5 library is the reference). All attributes of the decoder form one
 * integer point of `dim` coordinates; the tree splits the point set in
 * halves along one axis per level, coding only how the count splits.
 */
#include "draco_internal.h"

/* Bit sources: "direct" (32-bit words read most significant bit first) or
 * rABS, or 32 rABS coders, one per bit position ("folded"). */
typedef struct ld_direct {
    const uint8_t *words;
    uint32_t num_words, pos, used;
} ld_direct;

typedef struct ld_kd {
    unsigned level;           /* compression level 0..6 */
    uint32_t dim, bit_length, num_points, decoded;
    ld_direct remaining, axis, half, numbers_direct;
    ld_rabs numbers_rabs;
    ld_rabs folded[32];
    ld_rabs folded_bit;
    int32_t *out[LUMO_DRACO_MAX_ATTRIBUTES];
    uint32_t out_comps[LUMO_DRACO_MAX_ATTRIBUTES];
    uint32_t out_mask[LUMO_DRACO_MAX_ATTRIBUTES];
    uint32_t num_out;
} ld_kd;

static lumo_status ld_direct_start(ld_direct *d, ld_buf *b)
{
    uint32_t size;
    lumo_status st = ld_u32(b, &size);
    if (st)
        return st;
    if (size == 0 || (size & 3u) || size > ld_remaining(b))
        return LUMO_ERR_CORRUPT;
    d->words = ld_head(b);
    d->num_words = size / 4u;
    d->pos = 0;
    d->used = 0;
    b->pos += size;
    return LUMO_OK;
}

static uint32_t ld_direct_word(const ld_direct *d, uint32_t i)
{
    const uint8_t *p = d->words + 4u * i;
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

/* DirectBitDecoder::DecodeLeastSignificantBits32 (1 <= nbits <= 32);
 * 0 when the words run out (libdraco then leaves the value unchanged). */
static int ld_direct_bits(ld_direct *d, unsigned nbits, uint32_t *value)
{
    const unsigned remaining = 32u - d->used;
    if (nbits <= remaining) {
        if (d->pos >= d->num_words)
            return 0;
        *value = (uint32_t)(ld_direct_word(d, d->pos) << d->used) >> (32u - nbits);
        d->used += nbits;
        if (d->used == 32u) {
            d->pos++;
            d->used = 0;
        }
    } else {
        uint32_t l, r;
        if (d->pos + 1u >= d->num_words)
            return 0;
        l = ld_direct_word(d, d->pos) << d->used;
        d->used = nbits - remaining;
        d->pos++;
        r = ld_direct_word(d, d->pos) >> (32u - d->used);
        *value = (l >> (32u - d->used - remaining)) | r;
    }
    return 1;
}

static int ld_direct_bit(ld_direct *d)
{
    uint32_t v = 0;
    return ld_direct_bits(d, 1, &v) ? (int)v : 0;
}

static uint32_t ld_kd_number(ld_kd *k, unsigned nbits)
{
    uint32_t v = 0;
    unsigned i;
    if (k->level < 2) {
        (void)ld_direct_bits(&k->numbers_direct, nbits, &v);
    } else if (k->level < 4) {
        for (i = 0; i < nbits; ++i)
            v = (v << 1) + (uint32_t)ld_rabs_bit(&k->numbers_rabs);
    } else {
        for (i = 0; i < nbits; ++i)
            v = (v << 1) + (uint32_t)ld_rabs_bit(&k->folded[i]);
    }
    return v;
}

static lumo_status ld_kd_start(ld_kd *k, ld_buf *b)
{
    lumo_status st = LUMO_OK;
    unsigned i;
    if (k->level < 2)
        st = ld_direct_start(&k->numbers_direct, b);
    else if (k->level < 4)
        st = ld_rabs_start(&k->numbers_rabs, b);
    else {
        for (i = 0; i < 32 && !st; ++i)
            st = ld_rabs_start(&k->folded[i], b);
        if (!st)
            st = ld_rabs_start(&k->folded_bit, b);
    }
    if (st || (st = ld_direct_start(&k->remaining, b)) || (st = ld_direct_start(&k->axis, b)))
        return st;
    return ld_direct_start(&k->half, b);
}

static lumo_status ld_kd_emit(ld_kd *k, const uint32_t *p)
{
    uint32_t a, c, off = 0;
    if (k->decoded >= k->num_points)
        return LUMO_ERR_CORRUPT;  /* libdraco fails on the count later */
    for (a = 0; a < k->num_out; ++a) {
        int32_t *dst = k->out[a] + (size_t)k->decoded * k->out_comps[a];
        for (c = 0; c < k->out_comps[a]; ++c)
            dst[c] = (int32_t)(p[off + c] & k->out_mask[a]);
        off += k->out_comps[a];
    }
    k->decoded++;
    return LUMO_OK;
}

typedef struct ld_kd_status {
    uint32_t remaining, last_axis, stack_pos;
} ld_kd_status;

static uint32_t ld_kd_axis(ld_kd *k, uint32_t remaining, const uint32_t *levels, uint32_t last)
{
    uint32_t best = 0, a;
    if (k->level < 6)
        return last + 1u == k->dim ? 0u : last + 1u;
    if (remaining < 64) {
        for (a = 1; a < k->dim; ++a)
            if (levels[best] > levels[a])
                best = a;
        return best;
    }
    (void)ld_direct_bits(&k->axis, 4, &best);
    return best;
}

/* DynamicIntegerPointsKdTreeDecoder::DecodeInternal */
static lumo_status ld_kd_tree(ld_kd *k, ld_mem *m)
{
    const uint32_t dim = k->dim, depth = 32u * dim + 1u, max_status = 2u * depth + 2u;
    uint32_t *base = ld_tmp(m, (size_t)depth * dim, sizeof(uint32_t));
    uint32_t *levels = ld_tmp(m, (size_t)depth * dim, sizeof(uint32_t));
    uint32_t *p = ld_tmp(m, dim, sizeof(uint32_t)), *axes = ld_tmp(m, dim, sizeof(uint32_t));
    ld_kd_status *stack = ld_tmp(m, max_status, sizeof(ld_kd_status));
    uint32_t top = 0;
    lumo_status st;
    if (!base || !levels || !p || !axes || !stack)
        return LUMO_ERR_NOMEM;
    memset(base, 0, (size_t)depth * dim * sizeof(uint32_t));
    memset(levels, 0, (size_t)depth * dim * sizeof(uint32_t));
    stack[top].remaining = k->num_points;
    stack[top].last_axis = 0;
    stack[top++].stack_pos = 0;
    while (top) {
        const ld_kd_status s = stack[--top];
        uint32_t *ob = base + (size_t)s.stack_pos * dim, *lv = levels + (size_t)s.stack_pos * dim;
        uint32_t axis, level, i, j, number, first, second, modifier;
        if (s.remaining > k->num_points)
            return LUMO_ERR_CORRUPT;
        axis = ld_kd_axis(k, s.remaining, lv, s.last_axis);
        if (axis >= dim)
            return LUMO_ERR_CORRUPT;
        level = lv[axis];
        if (k->bit_length == level) {
            for (i = 0; i < s.remaining; ++i)
                if ((st = ld_kd_emit(k, ob)))
                    return st;
            continue;
        }
        if (s.remaining <= 2) {
            axes[0] = axis;
            for (i = 1; i < dim; ++i)
                axes[i] = axes[i - 1] + 1u == dim ? 0u : axes[i - 1] + 1u;
            for (i = 0; i < s.remaining; ++i) {
                for (j = 0; j < dim; ++j) {
                    const uint32_t ax = axes[j], bits = k->bit_length - lv[ax];
                    p[ax] = 0;
                    if (bits && !ld_direct_bits(&k->remaining, bits, &p[ax]))
                        return LUMO_ERR_CORRUPT;
                    p[ax] |= ob[ax];
                }
                if ((st = ld_kd_emit(k, p)))
                    return st;
            }
            continue;
        }
        if (s.stack_pos + 1u >= depth || level > k->bit_length || top + 2u > max_status)
            return LUMO_ERR_CORRUPT;
        modifier = 1u << (k->bit_length - level - 1u);
        memcpy(ob + dim, ob, dim * sizeof(uint32_t));
        ob[dim + axis] += modifier;
        i = 31u;
        while (!(s.remaining >> i))
            --i;  /* most significant bit; remaining > 2 */
        number = ld_kd_number(k, i);
        first = s.remaining / 2u;
        if (first < number)
            return LUMO_ERR_CORRUPT;
        first -= number;
        second = s.remaining - first;
        if (first != second && !ld_direct_bit(&k->half)) {
            uint32_t t = first;
            first = second;
            second = t;
        }
        lv[axis] += 1u;
        memcpy(lv + dim, lv, dim * sizeof(uint32_t));
        if (first) {
            stack[top].remaining = first;
            stack[top].last_axis = axis;
            stack[top++].stack_pos = s.stack_pos;
        }
        if (second) {
            stack[top].remaining = second;
            stack[top].last_axis = axis;
            stack[top++].stack_pos = s.stack_pos + 1u;
        }
    }
    return LUMO_OK;
}

static lumo_status ld_kd_params(ld_dec *d, uint32_t first, uint32_t count)
{
    uint32_t i;
    lumo_status st;
    for (i = 0; i < count; ++i) {
        lumo_draco_attribute *a = &d->attrs[first + i];
        unsigned c;
        uint8_t bits;
        if (a->data_type != LUMO_DRACO_DT_FLOAT32)
            continue;
        a->min_bits = ld_out(&d->mem, a->num_components, sizeof(uint32_t));
        a->min_fixed = ld_out(&d->mem, a->num_components, sizeof(int32_t));
        if (!a->min_bits || !a->min_fixed)
            return LUMO_ERR_NOMEM;
        for (c = 0; c < a->num_components; ++c)
            if ((st = ld_u32(&d->buf, &a->min_bits[c])))
                return st;
        if ((st = ld_u32(&d->buf, &a->range_bits)) || (st = ld_u8(&d->buf, &bits)))
            return st;
        if (bits > 31 || bits < 1 || bits > 30)
            return bits > 31 ? LUMO_ERR_CORRUPT : LUMO_ERR_UNSUPPORTED;
        if ((st = ld_set_quantization(a, bits)))
            return st;
    }
    return LUMO_OK;
}

lumo_status ld_kd_decode_attributes(ld_dec *d, uint32_t first, uint32_t count)
{
    ld_kd k;
    uint8_t level;
    uint32_t i;
    lumo_status st;
    uint8_t *mark = ld_tmp_mark(&d->mem);
    memset(&k, 0, sizeof k);
    if ((st = ld_u8(&d->buf, &level)))
        return st;
    if (level > 6)
        return LUMO_ERR_CORRUPT;
    k.level = level;
    for (i = 0; i < count; ++i) {
        lumo_draco_attribute *a = &d->attrs[first + i];
        unsigned dt = a->data_type;
        if (dt == LUMO_DRACO_DT_UINT8 || dt == LUMO_DRACO_DT_UINT16 || dt == LUMO_DRACO_DT_UINT32)
            k.out_mask[i] = dt == LUMO_DRACO_DT_UINT8 ? 0xFFu : dt == LUMO_DRACO_DT_UINT16 ? 0xFFFFu
                                                                                    : 0xFFFFFFFFu;
        else if (dt == LUMO_DRACO_DT_FLOAT32)
            k.out_mask[i] = 0xFFFFFFFFu;
        else
            return LUMO_ERR_UNSUPPORTED;  /* signed integer attributes */
        a->num_values = d->num_points;
        a->values = ld_out(&d->mem, (size_t)d->num_points * a->num_components, sizeof(int32_t));
        if (!a->values)
            return LUMO_ERR_NOMEM;
        a->modes.seq_type = 2;
        k.out[i] = a->values;
        k.out_comps[i] = a->num_components;
        k.dim += a->num_components;
    }
    k.num_out = count;
    if ((st = ld_u32(&d->buf, &k.bit_length)) || (st = ld_u32(&d->buf, &k.num_points)))
        return st;
    if (k.bit_length > 32 || k.num_points != d->num_points)
        return LUMO_ERR_CORRUPT;
    if (k.num_points) {
        if ((st = ld_kd_start(&k, &d->buf)) || (st = ld_kd_tree(&k, &d->mem)))
            return st;
        if (k.decoded != k.num_points)
            return LUMO_ERR_CORRUPT;
    }
    ld_tmp_release(&d->mem, mark);
    return ld_kd_params(d, first, count);
}

/* ---- the need before decoding (lumo_draco_arena_need) ----------------------- *
 * ld_kd_decode_attributes on byte counts: everything it takes follows from
 * the header (the tree's stacks from the dimension), so this is exact. */
lumo_status ld_kd_need(ld_buf *b, ld_need *k, const ld_need_attr *attrs, uint32_t count,
                       uint32_t num_points)
{
    const size_t mark = k->work;
    ld_kd kd;
    uint32_t i, dim = 0, bit_length, n;
    uint8_t level, bits;
    lumo_status st;
    memset(&kd, 0, sizeof kd);
    if ((st = ld_u8(b, &level)))
        return st;
    if (level > 6)
        return LUMO_ERR_CORRUPT;
    kd.level = level;
    for (i = 0; i < count; ++i) {
        const unsigned dt = attrs[i].data_type;
        if (dt != LUMO_DRACO_DT_UINT8 && dt != LUMO_DRACO_DT_UINT16 &&
            dt != LUMO_DRACO_DT_UINT32 && dt != LUMO_DRACO_DT_FLOAT32)
            return LUMO_ERR_UNSUPPORTED;
        ld_need_out(k, (size_t)num_points * attrs[i].components, sizeof(int32_t));
        dim += attrs[i].components;
    }
    if ((st = ld_u32(b, &bit_length)) || (st = ld_u32(b, &n)))
        return st;
    if (bit_length > 32 || n != num_points)
        return LUMO_ERR_CORRUPT;
    if (n) {  /* ld_kd_tree's stacks */
        const uint32_t depth = 32u * dim + 1u;
        if ((st = ld_kd_start(&kd, b)))
            return st;
        ld_need_tmp(k, (size_t)depth * dim, sizeof(uint32_t));
        ld_need_tmp(k, (size_t)depth * dim, sizeof(uint32_t));
        ld_need_tmp(k, dim, sizeof(uint32_t));
        ld_need_tmp(k, dim, sizeof(uint32_t));
        ld_need_tmp(k, 2u * (size_t)depth + 2u, sizeof(ld_kd_status));
    }
    ld_need_release(k, mark);
    for (i = 0; i < count; ++i) {  /* ld_kd_params */
        if (attrs[i].data_type != LUMO_DRACO_DT_FLOAT32)
            continue;
        ld_need_out(k, attrs[i].components, sizeof(uint32_t));
        ld_need_out(k, attrs[i].components, sizeof(int32_t));
        if ((st = ld_skip(b, 4u * (uint64_t)attrs[i].components + 4u)) || (st = ld_u8(b, &bits)))
            return st;
        if (bits > 31 || bits < 1 || bits > 30)
            return bits > 31 ? LUMO_ERR_CORRUPT : LUMO_ERR_UNSUPPORTED;
    }
    return LUMO_OK;
}
