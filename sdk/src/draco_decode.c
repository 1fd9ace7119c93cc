/*
 * draco_decode.c — the Draco container: header, metadata (skipped),
 * sequential mesh connectivity, the attributes-decoder loop, and the public
 * entry points of lumo/draco.h.
 */
#include "draco_internal.h"

#define LD_FLAG_METADATA 0x8000u

typedef struct ld_header {
    uint8_t major, minor, geometry, method;
    uint16_t flags;
} ld_header;

static lumo_status ld_read_header(ld_buf *b, ld_header *h)
{
    lumo_status st;
    if (ld_remaining(b) < 11)
        return LUMO_ERR_TRUNCATED;
    if (memcmp(ld_head(b), "DRACO", 5) != 0)
        return LUMO_ERR_CORRUPT;
    b->pos += 5;
    if ((st = ld_u8(b, &h->major)) || (st = ld_u8(b, &h->minor)) ||
        (st = ld_u8(b, &h->geometry)) || (st = ld_u8(b, &h->method)) ||
        (st = ld_u16(b, &h->flags)))
        return st;
    if (h->geometry > LUMO_DRACO_MESH)
        return LUMO_ERR_UNSUPPORTED;
    /* lumo decodes what libdraco 1.5.5 writes: meshes 2.2, point clouds 2.3. */
    if (h->major != 2 || h->minor != (h->geometry == LUMO_DRACO_MESH ? 2 : 3))
        return LUMO_ERR_VERSION;
    if (h->method > 1)
        return LUMO_ERR_UNSUPPORTED;
    return LUMO_OK;
}

static lumo_status ld_skip_name(ld_buf *b)
{
    uint8_t len;
    lumo_status st = ld_u8(b, &len);
    return st ? st : ld_skip(b, len);
}

/* Metadata blocks form a tree stored depth first; every block after the
 * root starts with its name, so a count of pending blocks suffices. Each
 * block takes at least two bytes, which bounds the loop by the input. */
static lumo_status ld_skip_metadata_blocks(ld_buf *b, uint64_t pending, int first_is_root)
{
    lumo_status st;
    while (pending) {
        uint32_t entries, subs, i;
        --pending;
        if (!first_is_root && (st = ld_skip_name(b)))
            return st;
        first_is_root = 0;
        if ((st = ld_varint32(b, &entries)))
            return st;
        for (i = 0; i < entries; ++i) {
            uint32_t size;
            if ((st = ld_skip_name(b)) || (st = ld_varint32(b, &size)))
                return st;
            if (size == 0)
                return LUMO_ERR_CORRUPT;
            if ((st = ld_skip(b, size)))
                return st;
        }
        if ((st = ld_varint32(b, &subs)))
            return st;
        if (subs > ld_remaining(b))
            return LUMO_ERR_CORRUPT;
        pending += subs;
    }
    return LUMO_OK;
}

static lumo_status ld_skip_metadata(ld_buf *b)
{
    uint32_t n, i;
    lumo_status st = ld_varint32(b, &n);
    if (st)
        return st;
    for (i = 0; i < n; ++i) {
        uint32_t id;
        if ((st = ld_varint32(b, &id)) || (st = ld_skip_metadata_blocks(b, 1, 1)))
            return st;
    }
    return ld_skip_metadata_blocks(b, 1, 1);
}

static lumo_status ld_start(ld_buf *b, const uint8_t *data, size_t size, ld_header *h)
{
    lumo_status st;
    if (!data && size)
        return LUMO_ERR_ARG;
    b->data = data;
    b->size = size;
    b->pos = 0;
    if ((st = ld_read_header(b, h)))
        return st;
    if (h->flags & LD_FLAG_METADATA)
        return ld_skip_metadata(b);
    return LUMO_OK;
}

/* ---- sequential mesh connectivity ------------------------------------------ */

static lumo_status ld_seq_counts(ld_buf *b, uint32_t *faces, uint32_t *points)
{
    lumo_status st;
    if ((st = ld_varint32(b, faces)) || (st = ld_varint32(b, points)))
        return st;
    if (*faces > 0xFFFFFFFFu / 3 || *faces > ld_remaining(b) / 3)
        return LUMO_ERR_CORRUPT;
    if ((uint64_t)*points > (uint64_t)*faces * 3)
        return LUMO_ERR_CORRUPT;
    return LUMO_OK;
}

/* Indices coded as zig-zag deltas from the previous index (method 0). */
static lumo_status ld_seq_compressed_indices(ld_dec *d)
{
    uint32_t n = d->num_faces * 3u, i;
    int32_t last = 0;
    lumo_status st = ld_decode_symbols(&d->buf, &d->mem, n, 1, d->faces, NULL);
    if (st)
        return st;
    for (i = 0; i < n; ++i) {
        uint32_t s = d->faces[i];
        int32_t diff = (int32_t)(s >> 1);
        int64_t v = (int64_t)last + ((s & 1u) ? -(int64_t)diff : diff);
        if (v < 0 || v >= (int64_t)d->num_points)
            return LUMO_ERR_CORRUPT;
        last = (int32_t)v;
        d->faces[i] = (uint32_t)v;
    }
    return LUMO_OK;
}

/* Plain 16-bit indices, checked against the point count as they are
 * copied: one pass, four at a time (the hot loop of -cl 0 meshes). */
static lumo_status ld_seq_u16_indices(uint32_t *f, const uint8_t *p, uint32_t n, uint32_t np)
{
    uint32_t i = 0, max = 0;
    for (; i + 4u <= n; i += 4u, p += 8) {
        const uint32_t a = (uint32_t)p[0] | ((uint32_t)p[1] << 8);
        const uint32_t b = (uint32_t)p[2] | ((uint32_t)p[3] << 8);
        const uint32_t c = (uint32_t)p[4] | ((uint32_t)p[5] << 8);
        const uint32_t e = (uint32_t)p[6] | ((uint32_t)p[7] << 8);
        f[i] = a;
        f[i + 1u] = b;
        f[i + 2u] = c;
        f[i + 3u] = e;
        max = a > max ? a : max;
        max = b > max ? b : max;
        max = c > max ? c : max;
        max = e > max ? e : max;
    }
    for (; i < n; ++i, p += 2) {
        f[i] = (uint32_t)p[0] | ((uint32_t)p[1] << 8);
        max = f[i] > max ? f[i] : max;
    }
    return n && max >= np ? LUMO_ERR_CORRUPT : LUMO_OK;
}

/* Varint indices (fewer than 2^21 points, so one to three bytes each in
 * the encoder's output): a four-byte window decodes them without a loop;
 * longer forms and the last bytes go through ld_varint32. */
static lumo_status ld_seq_varint_indices(uint32_t *f, ld_buf *b, uint32_t n, uint32_t np)
{
    const uint8_t *p = ld_head(b);
    const uint8_t *last = ld_remaining(b) >= 4u ? p + ld_remaining(b) - 4u : p - 1;
    uint32_t i = 0, max = 0;
    for (; i < n && p <= last; ++i) {
        const uint32_t w = (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) |
                           ((uint32_t)p[3] << 24);
        uint32_t v;
        if ((w & 0x808080u) == 0x8080u) {  /* the common length first */
            v = (w & 0x7Fu) | ((w >> 1) & 0x3F80u) | ((w >> 2) & 0x1FC000u);
            p += 3;
        } else if (!(w & 0x80u)) {
            v = w & 0x7Fu;
            p += 1;
        } else if (!(w & 0x8000u)) {
            v = (w & 0x7Fu) | ((w >> 1) & 0x3F80u);
            p += 2;
        } else {
            break;
        }
        f[i] = v;
        max = v > max ? v : max;
    }
    b->pos = (size_t)(p - b->data);
    for (; i < n; ++i) {
        const lumo_status st = ld_varint32(b, &f[i]);
        if (st)
            return st;
        max = f[i] > max ? f[i] : max;
    }
    return n && max >= np ? LUMO_ERR_CORRUPT : LUMO_OK;
}

/* Plain indices (method 1): bytes, 16-bit words or varints by the point
 * count (libdraco MeshSequentialDecoder). libdraco does not check indices
 * against the point count; lumo promises every index is a valid point. */
static lumo_status ld_seq_raw_indices(ld_dec *d)
{
    const uint32_t n = d->num_faces * 3u, np = d->num_points;
    const uint8_t *p = ld_head(&d->buf);
    uint32_t i, bad = 0;
    lumo_status st = LUMO_OK;
    if (np < 256u) {
        if (n > ld_remaining(&d->buf))
            return LUMO_ERR_TRUNCATED;
        for (i = 0; i < n; ++i) {
            d->faces[i] = p[i];
            bad |= p[i] >= np;
        }
        d->buf.pos += n;
        return bad ? LUMO_ERR_CORRUPT : LUMO_OK;
    }
    if (np < 65536u) {
        if ((uint64_t)n * 2u > ld_remaining(&d->buf))
            return LUMO_ERR_TRUNCATED;
        d->buf.pos += (size_t)n * 2u;
        return ld_seq_u16_indices(d->faces, p, n, np);
    }
    if (np < (1u << 21))
        return ld_seq_varint_indices(d->faces, &d->buf, n, np);
    for (i = 0; i < n && !st; ++i) {
        st = ld_u32(&d->buf, &d->faces[i]);
        if (!st && d->faces[i] >= np)
            st = LUMO_ERR_CORRUPT;
    }
    return st;
}

static lumo_status ld_seq_connectivity(ld_dec *d)
{
    uint8_t method;
    lumo_status st = ld_seq_counts(&d->buf, &d->num_faces, &d->num_points);
    if (st)
        return st;
    if (d->num_faces > LD_MAX_FACES || d->num_points > LD_MAX_POINTS)
        return LUMO_ERR_LIMIT;
    if ((st = ld_u8(&d->buf, &method)))
        return st;
    d->connectivity = method ? 1u : 0u;
    d->faces = ld_out(&d->mem, (size_t)d->num_faces * 3u, sizeof(uint32_t));
    if (!d->faces)
        return LUMO_ERR_NOMEM;
    return method == 0 ? ld_seq_compressed_indices(d) : ld_seq_raw_indices(d);
}

/* ---- attributes ---------------------------------------------------------------- */

typedef struct ld_decoder_slot {
    uint32_t first, count;
    ld_seq seq;
    uint8_t traversal, vertex_attr;
} ld_decoder_slot;

/* Decoder headers (EdgeBreaker: data id, element type, traversal), then
 * each decoder's attribute descriptors. */
static lumo_status ld_attribute_headers(ld_dec *d, ld_decoder_slot *slots, uint8_t n, int kd)
{
    uint8_t i;
    uint32_t k;
    lumo_status st;
    for (i = 0; i < n; ++i)
        if (d->eb && (st = ld_eb_create_attributes_decoder(d, i, &slots[i].seq,
                                                           &slots[i].traversal,
                                                           &slots[i].vertex_attr)))
            return st;
    for (i = 0; i < n; ++i) {
        if ((st = ld_read_attribute_descriptors(d, i, &slots[i].first, &slots[i].count, !kd)))
            return st;
        for (k = 0; k < slots[i].count; ++k) {
            d->attrs[slots[i].first + k].modes.traversal = slots[i].traversal;
            d->attrs[slots[i].first + k].modes.vertex_attribute = slots[i].vertex_attr;
        }
    }
    return LUMO_OK;
}

/* One attributes decoder: its point order, then its values. */
static lumo_status ld_attribute_values(ld_dec *d, unsigned i, ld_decoder_slot *slot, int kd)
{
    uint8_t *mark = ld_tmp_mark(&d->mem);
    lumo_status st;
    if (kd)
        return ld_kd_decode_attributes(d, slot->first, slot->count);
    if (d->eb) {
        slot->seq.last = (uint8_t)(i + 1u == d->num_decoders && slot->count == 1u);
        if ((st = ld_eb_sequence(d, i, &slot->seq)))
            return st;
    } else {
        slot->seq.num_entries = d->num_points;  /* linear sequencer */
    }
    st = ld_decode_attributes(d, slot->first, slot->count, &slot->seq);
    ld_tmp_release(&d->mem, slot->seq.work_top ? slot->seq.work_top : mark);
    return st;
}

/* The number of attributes decoders (the decode and the arena-need scan
 * read it alike). */
static lumo_status ld_decoder_count(ld_buf *b, uint8_t *n)
{
    lumo_status st = ld_u8(b, n);
    if (st)
        return st;
    return *n > LD_MAX_DECODERS ? LUMO_ERR_LIMIT : LUMO_OK;
}

static lumo_status ld_all_attributes(ld_dec *d)
{
    ld_decoder_slot slots[LD_MAX_DECODERS];
    const int kd = d->geometry == LUMO_DRACO_POINT_CLOUD && d->method == LUMO_DRACO_METHOD_KD_TREE;
    uint8_t n, i;
    lumo_status st = ld_decoder_count(&d->buf, &n);
    if (st)
        return st;
    d->num_decoders = n;
    memset(slots, 0, sizeof slots);
    if ((st = ld_attribute_headers(d, slots, n, kd)))
        return st;
    for (i = 0; i < n; ++i)
        if ((st = ld_attribute_values(d, i, &slots[i], kd)))
            return st;
    return LUMO_OK;
}

static lumo_status ld_point_cloud_geometry(ld_dec *d)
{
    uint32_t n;
    lumo_status st;
    /* sequential and KD-tree: a 32-bit (signed) point count */
    if ((st = ld_u32(&d->buf, &n)))
        return st;
    if (n > LD_MAX_POINTS)
        return LUMO_ERR_LIMIT;
    d->num_points = n;
    return LUMO_OK;
}

static lumo_status ld_decode_all(ld_dec *d, lumo_draco_mesh *m)
{
    lumo_status st;
    d->attrs = ld_out(&d->mem, LUMO_DRACO_MAX_ATTRIBUTES, sizeof(lumo_draco_attribute));
    if (!d->attrs)
        return LUMO_ERR_NOMEM;
    if (d->geometry == LUMO_DRACO_POINT_CLOUD)
        st = ld_point_cloud_geometry(d);
    else if (d->method == LUMO_DRACO_METHOD_SEQUENTIAL)
        st = ld_seq_connectivity(d);
    else
        st = ld_eb_decode_connectivity(d);
    if (st || (st = ld_all_attributes(d)))
        return st;
    ld_eb_finish(d);
    m->num_points = d->num_points;
    m->num_faces = d->num_faces;
    m->faces = d->faces;
    m->num_attributes = d->num_attrs;
    m->attributes = d->attrs;
    return LUMO_OK;
}

lumo_status lumo_draco_decode(const uint8_t *data, size_t size, lumo_arena *arena,
                              lumo_draco_mesh *out)
{
    return lumo_draco_decode_ex(data, size, 0, arena, out);
}

lumo_status lumo_draco_decode_ex(const uint8_t *data, size_t size, unsigned flags,
                                 lumo_arena *arena, lumo_draco_mesh *out)
{
    ld_dec d;
    ld_header h;
    lumo_draco_mesh m;
    lumo_status st;
    if (!arena || !out)
        return LUMO_ERR_ARG;
    memset(&d, 0, sizeof d);
    memset(&m, 0, sizeof m);
    if ((st = ld_start(&d.buf, data, size, &h)))
        return st;
    d.version = (uint16_t)(h.major << 8 | h.minor);
    d.lean = ld_mode_lean(flags);
    d.geometry = h.geometry;
    d.method = h.method;
    ld_mem_init(&d.mem, arena);
    if ((st = ld_decode_all(&d, &m)))
        return st;  /* nothing committed: the arena is unchanged */
    m.geometry = h.geometry;
    m.method = h.method;
    m.connectivity = d.connectivity;
    m.arena_bytes = (size_t)(d.mem.lo - d.mem.start);
    m.work_bytes = d.mem.peak - m.arena_bytes;
    ld_mem_commit(&d.mem, arena);
    *out = m;
    return LUMO_OK;
}

lumo_status lumo_draco_peek(const uint8_t *data, size_t size, lumo_draco_info *info)
{
    ld_buf b;
    ld_header h;
    lumo_draco_info r;
    lumo_status st;
    if (!info)
        return LUMO_ERR_ARG;
    if ((st = ld_start(&b, data, size, &h)))
        return st;
    memset(&r, 0, sizeof r);
    r.version_major = h.major;
    r.version_minor = h.minor;
    r.geometry = h.geometry;
    r.method = h.method;
    r.flags = h.flags;
    if (h.geometry == LUMO_DRACO_POINT_CLOUD) {
        /* both point-cloud methods start with a 32-bit point count */
        if ((st = ld_u32(&b, &r.num_points_max)))
            return st;
    } else if (h.method == LUMO_DRACO_METHOD_SEQUENTIAL) {
        if ((st = ld_seq_counts(&b, &r.num_faces, &r.num_points_max)) ||
            (st = ld_u8(&b, &r.connectivity)))
            return st;
    } else {
        uint32_t verts, faces, symbols, splits;
        uint8_t type, nad;
        if ((st = ld_u8(&b, &type)) || (st = ld_varint32(&b, &verts)) ||
            (st = ld_varint32(&b, &faces)) || (st = ld_u8(&b, &nad)) ||
            (st = ld_varint32(&b, &symbols)) || (st = ld_varint32(&b, &splits)))
            return st;
        if (faces > LD_MAX_FACES)
            return LUMO_ERR_LIMIT;
        r.connectivity = type;
        r.num_faces = faces;
        /* without attribute seams every point is a decoded vertex;
         * seams can split vertices up to one point per corner */
        if (nad == 0 && (uint64_t)verts + splits < (uint64_t)faces * 3u)
            r.num_points_max = verts + splits;
        else
            r.num_points_max = faces * 3u;
    }
    if (r.num_faces > LD_MAX_FACES || r.num_points_max > LD_MAX_POINTS)
        return LUMO_ERR_LIMIT;
    r.input_bytes = size;
    *info = r;
    return LUMO_OK;
}

/* Work memory of one rANS symbol stream: the table of non-zero symbols
 * (at most one per input byte, at most 2^18) and the lookup table (at most
 * 2^14 buckets, about two per value). */
static size_t ld_rans_work(size_t input, size_t values)
{
    size_t syms = input < ((size_t)1 << 18) ? input : ((size_t)1 << 18), lut = 256;
    while (lut < ((size_t)1 << 16) && lut < 2u * values)  /* draco_rans.c LD_LUT_*_BITS */
        lut <<= 1;
    return lumo_size_add(2u * lumo_arena_round(4u * (syms + 2u)), lumo_arena_round(4u * lut));
}

size_t lumo_draco_arena_bound(const lumo_draco_info *info, unsigned max_components)
{
    size_t f, p, c, out, work, values;
    if (!info)
        return SIZE_MAX;
    f = info->num_faces;
    p = info->num_points_max;
    c = max_components ? max_components : 1u;
    values = lumo_size_mul(p, c);
    if (values < 3u * f)
        values = 3u * f;
    /* outputs: attribute table, faces, values and quantization parameters */
    out = sizeof(lumo_draco_attribute) * LUMO_DRACO_MAX_ATTRIBUTES + 64u * c;
    out = lumo_size_add(out, lumo_size_mul(f, 12u));
    out = lumo_size_add(out, lumo_size_mul(p, 4u * c));
    work = ld_rans_work(info->input_bytes, values);
    if (info->geometry == LUMO_DRACO_MESH && info->method == LUMO_DRACO_METHOD_EDGEBREAKER) {
        /* + a point map per attributes decoder; corner table, symbol
         * phase and traversal ~128 B per face plus 24 for valence
         * contexts, 32 B per face per seam table, 24 B per point */
        out = lumo_size_add(out, lumo_size_mul(p, 4u * c));
        work = lumo_size_add(work, lumo_size_mul(f, 152u + 32u * c));
        work = lumo_size_add(work, lumo_size_mul(p, 24u));
    } else if (info->geometry == LUMO_DRACO_POINT_CLOUD && info->method == LUMO_DRACO_METHOD_KD_TREE) {
        /* KD-tree: base and level stacks, status stack (dimension <= c) */
        work = lumo_size_add(work, lumo_size_mul(32u * c + 2u, 8u * c + 32u));
    }
    return lumo_size_add(lumo_size_add(out, work), 256u + LUMO_ARENA_SLACK);
}

/* ---- the arena need before decoding ---------------------------------------------- *
 * lumo_draco_decode replayed on byte counts (ld_need, draco_internal.h):
 * the same headers are read in the same order and every allocation and
 * release the decode makes is booked; payloads are skipped by their coded
 * sizes (tagged symbol streams: by their tags). */

typedef struct ld_scan {
    ld_buf buf;
    ld_need k;
    ld_header h;
    uint32_t num_points, num_faces, num_attrs;
    ld_need_attr attrs[LUMO_DRACO_MAX_ATTRIBUTES];
    uint32_t first[LD_MAX_DECODERS], count[LD_MAX_DECODERS];
    ld_eb_need eb;
    uint8_t is_eb, lean;
    uint32_t learnt[LD_MAX_DECODERS];  /* value counts known after the scan */
} ld_scan;

/* Raw indices (ld_seq_raw_indices): bytes, 16-bit words, varints or words.
 * n varints end at the n-th byte below 0x80 (where a decode that
 * succeeds ends too). */
static lumo_status ld_scan_raw_indices(ld_buf *b, uint32_t n, uint32_t np)
{
    const uint8_t *p = ld_head(b);
    size_t i, left = ld_remaining(b);
    if (np < 256u)
        return ld_skip(b, n);
    if (np < 65536u)
        return ld_skip(b, (uint64_t)n * 2u);
    if (np >= (1u << 21))
        return ld_skip(b, (uint64_t)n * 4u);
    for (i = 0; left - i >= 8u && n > 8u; i += 8u) {  /* 8 bytes at a time */
        uint64_t w;
        memcpy(&w, p + i, 8);
        w = (~w & 0x8080808080808080ull) >> 7;  /* 1 per terminating byte */
        n -= (uint32_t)((w * 0x0101010101010101ull) >> 56);
    }
    for (; i < left && n; ++i)
        n -= p[i] < 0x80u;
    if (n)
        return LUMO_ERR_TRUNCATED;
    b->pos += i;
    return LUMO_OK;
}

static lumo_status ld_scan_geometry(ld_scan *s)
{
    uint8_t method;
    lumo_status st;
    ld_need_out(&s->k, LUMO_DRACO_MAX_ATTRIBUTES, sizeof(lumo_draco_attribute));
    if (s->h.geometry == LUMO_DRACO_POINT_CLOUD) {
        if ((st = ld_u32(&s->buf, &s->num_points)))
            return st;
        return s->num_points > LD_MAX_POINTS ? LUMO_ERR_LIMIT : LUMO_OK;
    }
    if (s->h.method == LUMO_DRACO_METHOD_EDGEBREAKER) {
        s->is_eb = 1;
        if ((st = ld_eb_need_connectivity(&s->buf, &s->k, &s->eb, s->lean)))
            return st;
        s->num_faces = s->eb.faces;
        return LUMO_OK;
    }
    if ((st = ld_seq_counts(&s->buf, &s->num_faces, &s->num_points)))
        return st;
    if (s->num_faces > LD_MAX_FACES || s->num_points > LD_MAX_POINTS)
        return LUMO_ERR_LIMIT;
    if ((st = ld_u8(&s->buf, &method)))
        return st;
    ld_need_out(&s->k, (size_t)s->num_faces * 3u, sizeof(uint32_t));
    if (method == 0)
        return ld_need_symbols(&s->buf, &s->k, s->num_faces * 3u, 1, NULL);
    return ld_scan_raw_indices(&s->buf, s->num_faces * 3u, s->num_points);
}

/* Decoder headers and attribute descriptors (ld_attribute_headers). */
static lumo_status ld_scan_headers(ld_scan *s, uint8_t n, int kd)
{
    lumo_draco_attribute a;
    uint32_t i, j, count;
    lumo_status st;
    for (i = 0; i < n; ++i)
        if (s->is_eb && (st = ld_eb_need_decoder(&s->buf, &s->eb, i)))
            return st;
    for (i = 0; i < n; ++i) {
        if ((st = ld_varint32(&s->buf, &count)))
            return st;
        if (count == 0 || count > LUMO_DRACO_MAX_ATTRIBUTES - s->num_attrs)
            return count ? LUMO_ERR_LIMIT : LUMO_ERR_CORRUPT;
        s->first[i] = s->num_attrs;
        s->count[i] = count;
        for (j = 0; j < count; ++j) {
            ld_need_attr *q = &s->attrs[s->num_attrs + j];
            if ((st = ld_read_descriptor(&s->buf, i, &a)))
                return st;
            q->components = a.num_components;
            q->data_type = a.data_type;
        }
        for (j = 0; j < count && !kd; ++j) {
            ld_need_attr *q = &s->attrs[s->num_attrs + j];
            a.num_components = q->components;
            a.num_portable = q->components;
            a.data_type = q->data_type;
            if ((st = ld_read_seq_type(&s->buf, &a)))
                return st;
            q->portable = a.num_portable;
            q->seq_type = a.modes.seq_type;
        }
        s->num_attrs += count;
    }
    return LUMO_OK;
}

static lumo_status ld_scan_attributes(ld_scan *s)
{
    const int kd = s->h.geometry == LUMO_DRACO_POINT_CLOUD &&
                   s->h.method == LUMO_DRACO_METHOD_KD_TREE;
    uint8_t n, i;
    lumo_status st = ld_decoder_count(&s->buf, &n);
    if (st)
        return st;
    if ((st = ld_scan_headers(s, n, kd)))
        return st;
    if (s->is_eb) {
        s->eb.num_decoders = n;
        memcpy(s->eb.known, s->learnt, sizeof s->learnt);
        s->num_points = (uint32_t)ld_eb_need_points(&s->k, &s->eb);
    }
    for (i = 0; i < n; ++i) {
        const size_t mark = s->k.work;
        ld_need_seq seq;
        memset(&seq, 0, sizeof seq);
        if (kd) {
            st = ld_kd_need(&s->buf, &s->k, s->attrs + s->first[i], s->count[i], s->num_points);
        } else {
            if (s->is_eb) {
                seq.last = (uint8_t)(i + 1u == n && s->count[i] == 1u);
                seq.attrs = s->attrs + s->first[i];
                seq.count = s->count[i];
                ld_eb_need_sequence(&s->k, &s->eb, i, &seq, &s->buf);
            } else {
                seq.entries = s->num_points;
            }
            st = ld_need_attributes(&s->buf, &s->k, s->attrs + s->first[i], s->count[i], &seq);
            if (!seq.uncertain)
                s->learnt[i] = seq.entries;
        }
        if (st)
            return st;
        ld_need_release(&s->k, seq.work_top ? seq.work_top : mark);
    }
    return LUMO_OK;
}

/* One replay: the peak with every unknown at its lower (hi = 0) or upper
 * (hi = 1) bound, value counts in `learnt` (in: known from an earlier
 * replay; out: known after this one, *fresh: some were learnt now).
 * *comps: portable components per point once known; *unknown: some value
 * count stayed unknown; *bounded: some quantity was only bounded. */
static lumo_status ld_scan_run(const uint8_t *data, size_t size, unsigned flags, int hi,
                               uint32_t *learnt, size_t *peak, int *unknown, int *bounded,
                               int *fresh, unsigned *comps)
{
    ld_scan s;
    uint32_t i;
    lumo_status st;
    memset(&s, 0, sizeof s);
    s.k.hi = hi;
    s.lean = ld_mode_lean(flags);
    memcpy(s.learnt, learnt, sizeof s.learnt);
    if ((st = ld_start(&s.buf, data, size, &s.h)) || (st = ld_scan_geometry(&s)))
        return st;
    st = ld_scan_attributes(&s);
    for (*comps = 0, i = 0; i < s.num_attrs; ++i)
        *comps += s.attrs[i].portable;
    *peak = s.k.peak;
    *bounded = s.k.bounded;
    *fresh = memcmp(learnt, s.learnt, sizeof s.learnt) != 0;
    memcpy(learnt, s.learnt, sizeof s.learnt);
    *unknown = 0;
    for (i = 0; s.is_eb && i < s.eb.num_decoders; ++i)
        *unknown |= s.learnt[i] == LD_NEED_UNKNOWN;
    return st;
}

lumo_status lumo_draco_arena_need(const uint8_t *data, size_t size, lumo_draco_need *need)
{
    return lumo_draco_arena_need_ex(data, size, 0, need);
}

lumo_status lumo_draco_arena_need_ex(const uint8_t *data, size_t size, unsigned flags,
                                     lumo_draco_need *need)
{
    uint32_t learnt[LD_MAX_DECODERS];
    size_t lo, hi;
    int unknown, bounded, fresh;
    unsigned comps = 0;
    lumo_draco_info info;
    lumo_status st;
    if (!need)
        return LUMO_ERR_ARG;
    memset(learnt, 0xFF, sizeof learnt);
    st = ld_scan_run(data, size, flags, 1, learnt, &hi, &unknown, &bounded, &fresh, &comps);
    if (!st && bounded && fresh)  /* again with the value counts learnt */
        st = ld_scan_run(data, size, flags, 1, learnt, &hi, &unknown, &bounded, &fresh, &comps);
    if (st == LUMO_ERR_LIMIT && comps && !lumo_draco_peek(data, size, &info)) {
        /* a stream the scan cannot skip: the header bound */
        hi = lumo_draco_arena_bound(&info, comps) - LUMO_ARENA_SLACK;
        unknown = bounded = 1;
    } else if (st) {
        return st;
    }
    lo = unknown ? 0 : hi;  /* nothing only bounded: one replay was exact */
    if (!unknown && bounded &&
        (st = ld_scan_run(data, size, flags, 0, learnt, &lo, &unknown, &bounded, &fresh, &comps)))
        return st;
    need->bytes = hi;
    need->bytes_min = lo;
    need->exact = (uint8_t)(lo == hi);
    return LUMO_OK;
}
