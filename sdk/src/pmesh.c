/* pmesh.c — progressive-mesh stream header, arena sizing and the view
 * (docs/progressive-mesh.md; seed 000 §4.2). Batches: pmesh_batch.c. */
#include <string.h>
#include "lumo/draco.h"
#include "lumo/pmesh.h"
#include "lumo_shared/pmesh_shared.h"
#include "lumo/wire.h"

/* Counts above this are refused (LIMIT) so 3 * count and byte sizes fit. */
#define MAX_COUNT (1u << 28)

static uint32_t max_u32(uint32_t a, uint32_t b) { return a > b ? a : b; }

/* Batches: the base mesh, then ceil((n - base) / batch_vertices) splits. */
static uint32_t expected_batches(const lumo_pmesh_header *h)
{
    uint32_t rest = h->vertices - h->base_vertices;
    return 1u + rest / h->batch_vertices + (rest % h->batch_vertices != 0);
}

static lumo_status check_counts(const lumo_pmesh_header *h)
{
    if (h->vertices > MAX_COUNT || h->faces > MAX_COUNT || h->batch_vertices > MAX_COUNT)
        return LUMO_ERR_LIMIT;
    if (h->base_vertices < 1 || h->base_vertices > h->vertices || h->base_faces > h->faces ||
        h->batch_vertices < 1 || h->max_batch_faces > h->faces ||
        h->max_batch_faces < h->base_faces || h->max_batch_moves > 3u * h->faces ||
        h->max_batch_bytes < LUMO_PMESH_BATCH_HEAD_MIN)
        return LUMO_ERR_CORRUPT;
    if (h->quant_bits < 1 || h->quant_bits > LUMO_PMESH_MAX_QBITS ||
        h->position_coding > LUMO_PMESH_POS_CODED ||
        (h->flags & ~(LUMO_PMESH_HAS_ALBEDO | LUMO_PMESH_LATTICE)))
        return LUMO_ERR_UNSUPPORTED;
    if (h->position_coding != LUMO_PMESH_POS_CODED && (h->flags & LUMO_PMESH_LATTICE))
        return LUMO_ERR_UNSUPPORTED;  /* lattice copies live in the range code */
    return LUMO_OK;
}

/* A header the caller filled: its counts, and the batch count they imply
 * (lumo_pmesh_read_header derives it). */
static lumo_status check_header(const lumo_pmesh_header *h)
{
    lumo_status st = check_counts(h);
    if (st)
        return st;
    return h->batch_count == expected_batches(h) ? LUMO_OK : LUMO_ERR_CORRUPT;
}

/* The header's fixed tail after the counts: quant_bits, position_coding,
 * flags, the grid's origin and range, the CRC. */
#define HEADER_TAIL 23u
#define HEADER_COUNTS 8

/* The eight counts, LEB128 (lumo_wire_varint), filling the bytes between
 * the 7-byte front and the tail exactly. */
static lumo_status read_counts(const uint8_t *d, size_t end, lumo_pmesh_header *h)
{
    uint32_t *dst[HEADER_COUNTS] = {&h->vertices, &h->faces, &h->base_vertices, &h->base_faces,
                                    &h->batch_vertices, &h->max_batch_faces, &h->max_batch_moves,
                                    &h->max_batch_bytes};
    size_t at = 7;
    for (int i = 0; i < HEADER_COUNTS; i++) {
        lumo_status st = lumo_wire_varint(d, end, &at, UINT32_MAX, dst[i]);
        if (st)
            return st == LUMO_ERR_TRUNCATED ? LUMO_ERR_CORRUPT : st;
    }
    return at == end ? LUMO_OK : LUMO_ERR_CORRUPT;
}

lumo_status lumo_pmesh_read_header(const uint8_t *d, size_t size, lumo_pmesh_header *out)
{
    lumo_pmesh_header h;
    int32_t probe;
    if (!d || !out)
        return LUMO_ERR_ARG;
    if (size < 7)
        return LUMO_ERR_TRUNCATED;
    if (lumo_wire_le32(d) != LUMO_PMESH_MAGIC)
        return LUMO_ERR_CORRUPT;
    if ((d[4] | d[5] << 8) != LUMO_PMESH_VERSION)
        return LUMO_ERR_VERSION;
    h.header_bytes = d[6];
    if (h.header_bytes < LUMO_PMESH_HEADER_MIN || h.header_bytes > LUMO_PMESH_HEADER_MAX)
        return LUMO_ERR_CORRUPT;
    if (size < h.header_bytes)
        return LUMO_ERR_TRUNCATED;
    const uint8_t *tail = d + h.header_bytes - HEADER_TAIL;
    if (lumo_wire_crc32(0, d, h.header_bytes - 4u) != lumo_wire_le32(tail + 19))
        return LUMO_ERR_CHECKSUM;
    lumo_status st = read_counts(d, h.header_bytes - HEADER_TAIL, &h);
    if (st)
        return st;
    h.quant_bits = tail[0], h.position_coding = tail[1], h.flags = tail[2];
    for (int i = 0; i < 3; i++)
        h.origin_bits[i] = lumo_wire_le32(tail + 3 + 4 * i);
    h.range_bits = lumo_wire_le32(tail + 15);
    if ((st = check_counts(&h)))
        return st;
    h.batch_count = expected_batches(&h);
    for (int i = 0; i < 3; i++)
        if ((st = lumo_f32bits_to_fixed(h.origin_bits[i], LUMO_Q16_SHIFT, &probe)))
            return st;
    if ((st = lumo_f32bits_to_fixed(h.range_bits, LUMO_Q16_SHIFT, &probe)))
        return st;
    if (probe <= 0)
        return LUMO_ERR_RANGE;
    /* The whole grid must be representable in Q16.16. */
    for (int i = 0; i < 3; i++) {
        int32_t o;
        (void)lumo_f32bits_to_fixed(h.origin_bits[i], LUMO_Q16_SHIFT, &o);
        if ((int64_t)o + probe > INT32_MAX)
            return LUMO_ERR_RANGE;
    }
    *out = h;
    return LUMO_OK;
}

/* Draco work memory for the largest point payload of the stream; none for
 * a CODED stream, which has no payloads. */
static size_t scratch_bytes(const lumo_pmesh_header *h)
{
    lumo_draco_info info;
    if (h->position_coding == LUMO_PMESH_POS_CODED)
        return 0;
    memset(&info, 0, sizeof info);
    info.geometry = LUMO_DRACO_POINT_CLOUD;
    info.method = LUMO_DRACO_METHOD_SEQUENTIAL;
    info.num_points_max = max_u32(h->base_vertices, h->batch_vertices);
    info.input_bytes = h->max_batch_bytes;  /* no payload is longer than its record */
    /* position (3 components) and, with albedo, the colour (3 more) */
    return lumo_draco_arena_bound(&info, h->flags & LUMO_PMESH_HAS_ALBEDO ? 6u : 3u);
}

/* Undo-log words: three per corner move or face. Dirty vertices: up to
 * four per move (its face and the old vertex), three per face. */
static size_t log_words(const lumo_pmesh_header *h, size_t per)
{
    return lumo_size_mul(per, lumo_size_add(h->max_batch_moves, h->max_batch_faces));
}

#define NARRAYS 18
/* Fan-rank candidates of one split (pmesh_batch.c read_arc): n^2 at most. */
#define ARC_KEYS (LUMO_PMESH_ARC_MAX_CORNERS * LUMO_PMESH_ARC_MAX_CORNERS)

/* The arrays init carves, in order: {count, element size}. */
static void layout(const lumo_pmesh_header *h, size_t n[NARRAYS], size_t sz[NARRAYS])
{
    size_t v = h->vertices, c = lumo_size_mul(3u, h->faces), vv = lumo_size_mul(3u, v);
    size_t splits = lumo_size_add(max_u32(h->base_vertices, h->batch_vertices), 1u);
    size_t rgb = h->flags & LUMO_PMESH_HAS_ALBEDO ? vv : 0;
    size_t cnt[NARRAYS] = {vv, vv, vv, c, c, v, v, log_words(h, 3u), log_words(h, 4u), splits, splits,
                           scratch_bytes(h), rgb, ARC_KEYS, v, splits, LUMO_PMESH_CONTEXTS,
                           LUMO_PMESH_CONTEXTS};
    size_t el[NARRAYS] = {sizeof(lumo_q16_16), sizeof(int32_t), sizeof(lumo_q1_14), 4, 4, 4, 4, 4, 4, 4, 4, 1,
                          sizeof(lumo_q1_14), sizeof(int64_t), 4, 4, 4, 4};
    memcpy(n, cnt, sizeof cnt);
    memcpy(sz, el, sizeof el);
}

size_t lumo_pmesh_arena_bytes(const lumo_pmesh_header *h)
{
    size_t n[NARRAYS], sz[NARRAYS], total = LUMO_ARENA_SLACK;
    if (!h || check_header(h))
        return SIZE_MAX;
    layout(h, n, sz);
    for (int i = 0; i < NARRAYS; i++)
        total = lumo_size_add(total, lumo_arena_round(lumo_size_mul(n[i], sz[i])));
    return total;
}

lumo_status lumo_pmesh_init(lumo_pmesh *pm, const lumo_pmesh_header *h, lumo_arena *arena)
{
    size_t n[NARRAYS], sz[NARRAYS];
    void *p[NARRAYS];
    lumo_status st;
    if (!pm || !h || !arena)
        return LUMO_ERR_ARG;
    if ((st = check_header(h)))
        return st;
    lumo_arena_mark mark = lumo_arena_get_mark(arena);
    layout(h, n, sz);
    for (int i = 0; i < NARRAYS; i++)
        if (!(p[i] = lumo_arena_alloc_array(arena, n[i], sz[i]))) {
            lumo_arena_reset(arena, mark);
            return LUMO_ERR_NOMEM;
        }
    memset(pm, 0, sizeof *pm);
    pm->h = *h;
    pm->pos = p[0], pm->qpos = p[1], pm->nrm = p[2], pm->tris = p[3], pm->next = p[4];
    pm->head = p[5], pm->mark = p[6], pm->journal = p[7], pm->dirty = p[8];
    pm->split_log = p[9], pm->batch_parent = p[10], pm->scratch = p[11], pm->scratch_bytes = n[11];
    pm->albedo = n[12] ? p[12] : NULL;
    pm->arc_key = p[13];
    pm->round_parent = p[14], pm->stamp_log = p[15], pm->ctx = p[16], pm->ctx_undo = p[17];
    memset(pm->round_parent, 0, n[14] * sizeof(uint32_t));
    for (size_t i = 0; i < 3; i++)
        (void)lumo_f32bits_to_fixed(h->origin_bits[i], LUMO_Q16_SHIFT, &pm->origin[i]);
    (void)lumo_f32bits_to_fixed(h->range_bits, LUMO_Q16_SHIFT, &pm->range);
    memset(pm->head, 0xff, n[5] * sizeof(uint32_t));
    pm->last_parent = 0xffffffffu;
    lumo_pmesh_init_contexts(pm->ctx);
    return LUMO_OK;
}

lumo_status lumo_pmesh_read_record_head(const uint8_t *d, size_t size, lumo_pmesh_record_head *out)
{
    lumo_pmesh_record_head h;
    size_t at = 0;
    uint32_t sizes;
    lumo_status st;
    if (!d || !out)
        return LUMO_ERR_ARG;
    /* Minimally coded varints below 2^28 (docs/progressive-mesh.md §2.2):
     * the block's size doubled, plus 1 when a payload's size follows. */
    if ((st = lumo_wire_varint(d, size, &at, 2u * MAX_COUNT + 1u, &sizes)))
        return st;
    h.side_bytes = sizes >> 1, h.draco_bytes = 0;
    if ((sizes & 1u) && (st = lumo_wire_varint(d, size, &at, MAX_COUNT, &h.draco_bytes)))
        return st;
    if ((sizes & 1u) && !h.draco_bytes)
        return LUMO_ERR_CORRUPT;  /* the flag says a payload follows */
    if (size - at < 4)
        return LUMO_ERR_TRUNCATED;
    h.crc = lumo_wire_le32(d + at);
    h.head_bytes = (uint32_t)at + 4u;
    *out = h;
    return LUMO_OK;
}

lumo_status lumo_pmesh_record_size(const uint8_t *d, size_t size, size_t *record_bytes)
{
    lumo_pmesh_record_head h;
    if (!record_bytes)
        return LUMO_ERR_ARG;
    lumo_status st = lumo_pmesh_read_record_head(d, size, &h);
    if (st)
        return st;
    *record_bytes = (size_t)h.head_bytes + h.side_bytes + h.draco_bytes;
    return LUMO_OK;
}

lumo_status lumo_pmesh_record_check(const uint8_t *d, size_t size, uint32_t index)
{
    lumo_pmesh_record_head h;
    uint8_t idx[LUMO_WIRE_VARINT32_MAX];
    lumo_status st = lumo_pmesh_read_record_head(d, size, &h);
    if (st)
        return st;
    size_t need = (size_t)h.head_bytes + h.side_bytes + h.draco_bytes;
    if (size != need)
        return size < need ? LUMO_ERR_TRUNCATED : LUMO_ERR_CORRUPT;
    /* The index, which the record does not carry, then the record without
     * its CRC: a record put in another's place fails like a damaged one. */
    uint32_t crc = lumo_wire_crc32(0, idx, lumo_wire_put_varint(idx, index));
    crc = lumo_wire_crc32(crc, d, h.head_bytes - 4u);
    crc = lumo_wire_crc32(crc, d + h.head_bytes, need - h.head_bytes);
    return crc == h.crc ? LUMO_OK : LUMO_ERR_CHECKSUM;
}

lumo_status lumo_pmesh_next_record(const uint8_t *d, size_t size, size_t *at, const uint8_t **record,
                                   size_t *record_bytes)
{
    size_t n;
    lumo_status st;
    if (!d || !at || !record || !record_bytes || *at > size)
        return LUMO_ERR_ARG;
    if (*at == size)
        return LUMO_ERR_RANGE;
    if ((st = lumo_pmesh_record_size(d + *at, size - *at, &n)))
        return st;
    if (n > size - *at)
        return LUMO_ERR_TRUNCATED;
    *record = d + *at;
    *record_bytes = n;
    *at += n;
    return LUMO_OK;
}

void lumo_pmesh_get_view(const lumo_pmesh *pm, lumo_pmesh_view *out)
{
    out->vertex_count = pm->vertex_count;
    out->face_count = pm->face_count;
    out->positions = pm->pos;
    out->normals = pm->nrm;
    out->triangles = pm->tris;
    out->albedo = pm->albedo;
}

int lumo_pmesh_complete(const lumo_pmesh *pm)
{
    return pm->vertex_count == pm->h.vertices;
}

uint32_t lumo_pmesh_batches(const lumo_pmesh *pm)
{
    return pm->batches_applied;
}
