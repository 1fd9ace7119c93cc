/* test_pmesh.c — the client's progressive-mesh decoder (lumo/pmesh.h) on a
 * real stream written by the server (tests/pm/pm_check --gen tiny --batch 3
 * --max-error 0 --write-stream, positions CODED; also tests/fuzz/seeds/fuzz_pmesh/tiny_coded.lpm): invariants at
 * every level, every truncation, every byte flip, CRC-fixed tampering that
 * fails deep inside a batch (rollback), order, arena sizing. The
 * server-side comparisons (level by level against the server's own
 * decimation) are in tests/pm/pm_check.c. */
#include "test_common.h"
#include <stdlib.h>
#include "lumo/package.h"
#include "lumo/pmesh.h"
#include "lumo_shared/pmesh_shared.h"
#include "lumo/wire.h"

static const uint8_t k_stream[] = {
    0x4c, 0x50, 0x4d, 0x31, 0x08, 0x00, 0x26, 0x14, 0x24, 0x04, 0x04, 0x03, 0x06, 0x0a, 0x16, 0x08,
    0x02, 0x02, 0xaa, 0xd2, 0x7e, 0xbf, 0xb2, 0xa0, 0x5c, 0xbf, 0x08, 0x00, 0x80, 0xbf, 0xd8, 0x10,
    0x01, 0x40, 0xa7, 0xa7, 0x26, 0xdd, 0x22, 0x1f, 0x33, 0x57, 0x2f, 0x84, 0xe5, 0x18, 0xcd, 0x46,
    0x7d, 0x60, 0xff, 0xb7, 0xf9, 0xfd, 0x68, 0xfb, 0x45, 0x7d, 0x90, 0x00, 0x1c, 0x12, 0xcb, 0x97,
    0xe7, 0x11, 0x83, 0x92, 0xfc, 0xdf, 0xb8, 0x92, 0xe0, 0x2e, 0x17, 0x53, 0xe7, 0xc0, 0xf7, 0x18,
    0x94, 0xe6, 0xe6, 0x79, 0x02, 0xf4, 0x32, 0xc1, 0x98, 0x09, 0xde, 0xa6, 0x9b, 0x14, 0x6f, 0xc4,
    0x14, 0x64, 0x18, 0x4d, 0xbc, 0xfa, 0xda, 0xe7, 0x9a, 0x1f, 0x60, 0x09, 0x67, 0x84, 0x02, 0x1a,
    0x78, 0xe4, 0x1a, 0xe7, 0x43, 0x29, 0xfe, 0x7b, 0xbb, 0xf9, 0xd6, 0xa4, 0xfa, 0x02, 0x43, 0x71,
    0x26, 0x16, 0x5a, 0xfb, 0xdc, 0x28, 0x31, 0x56, 0xcc, 0x17, 0xd4, 0xb1, 0x12, 0xdf, 0x26, 0xda,
    0x41, 0x06, 0x9e, 0x57, 0xac, 0xd4, 0xd7, 0xa0, 0x07,
};

/* tests/pm/pm_check --gen tiny --batch 3 --max-error 0.15 --write-stream
 * (tests/fuzz/seeds/fuzz_pmesh/tiny_seeded.lpm): a base mesh of 8 vertices
 * whose record builds it from a seed of 4 by 4 splits in a range code
 * (docs/progressive-mesh.md §2.3 "Base record"), then 4 split records. */
static const uint8_t k_seeded[] = {
    0x4c, 0x50, 0x4d, 0x31, 0x08, 0x00, 0x26, 0x14, 0x24, 0x08, 0x0c, 0x03, 0x0c, 0x09, 0x29, 0x08,
    0x02, 0x02, 0xaa, 0xd2, 0x7e, 0xbf, 0xb2, 0xa0, 0x5c, 0xbf, 0x08, 0x00, 0x80, 0xbf, 0xd8, 0x10,
    0x01, 0x40, 0x39, 0xa4, 0x35, 0xb2, 0x48, 0x33, 0x1a, 0xb3, 0xa2, 0x84, 0xe5, 0x18, 0xcd, 0x46,
    0x7d, 0x60, 0xff, 0xb7, 0xf9, 0xfd, 0x68, 0xfb, 0x45, 0x7d, 0x90, 0x00, 0x11, 0x83, 0x92, 0xfc,
    0xdf, 0xb8, 0x92, 0xe0, 0x2e, 0x17, 0x53, 0xe7, 0xc0, 0xf6, 0xe6, 0x46, 0xf3, 0xdf, 0x73, 0x16,
    0xbd, 0xf4, 0x93, 0xe1, 0x06, 0xb2, 0x24, 0xb8, 0x98, 0x2a, 0x27, 0xcb, 0x64, 0x84, 0xe5, 0x18,
    0x1f, 0xcb, 0xf1, 0x7c, 0x1b, 0xac, 0xf2, 0xd0, 0x74, 0x78, 0x44, 0xbc, 0x11, 0xe9, 0x70, 0x12,
    0x1a, 0xf1, 0x9d, 0x8f, 0x02, 0x20, 0x30, 0x3c, 0x2f, 0xe3, 0xb8, 0x81, 0x7e, 0x51, 0x93, 0xc2,
    0x79, 0x89, 0x12, 0xe8, 0x5c, 0x25, 0x8e, 0xe6, 0x58, 0xf5, 0xe9, 0xbb, 0x25, 0xf0, 0x79, 0xc7,
};

/* FNV-1a of the final triangles and positions, pinned from the server's
 * stream: any change in decoding shows. */
#define FINAL_HASH 0x7342dc14u

typedef struct {
    lumo_pmesh_header h;
    lumo_pmesh pm;
    lumo_arena arena;
    uint8_t *mem;
    size_t at;
    const uint8_t *data;  /* the stream: k_stream unless open_on says */
    size_t size;
} fixture;

static void open_on(fixture *f, const uint8_t *data, size_t size)
{
    f->data = data, f->size = size;
    assert_int_equal(lumo_pmesh_read_header(data, size, &f->h), LUMO_OK);
    size_t n = lumo_pmesh_arena_bytes(&f->h);
    f->mem = malloc(n);
    assert_non_null(f->mem);
    lumo_arena_init(&f->arena, f->mem, n);
    assert_int_equal(lumo_pmesh_init(&f->pm, &f->h, &f->arena), LUMO_OK);
    f->at = f->h.header_bytes;
}

static void open_fixture(fixture *f)
{
    open_on(f, k_stream, sizeof k_stream);
}

static size_t next_record(const fixture *f, const uint8_t **rec)
{
    size_t n;
    assert_int_equal(lumo_pmesh_record_size(f->data + f->at, f->size - f->at, &n), LUMO_OK);
    assert_true(n <= f->size - f->at);
    *rec = f->data + f->at;
    return n;
}

static void step(fixture *f)
{
    const uint8_t *rec;
    size_t n = next_record(f, &rec);
    assert_int_equal(lumo_pmesh_apply(&f->pm, rec, n), LUMO_OK);
    f->at += n;
}

/* Valid level: indices in range, no degenerate triangle, unit normals
 * (or, when `faceless_ok`, zero for a vertex that lost all its faces in a
 * tampered but well-formed batch). */
static void check_level_ex(const lumo_pmesh *pm, int faceless_ok)
{
    lumo_pmesh_view v;
    lumo_pmesh_get_view(pm, &v);
    for (uint32_t i = 0; i < v.face_count; i++) {
        const uint32_t *t = v.triangles + 3 * i;
        assert_true(t[0] < v.vertex_count && t[1] < v.vertex_count && t[2] < v.vertex_count);
        assert_true(t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
    }
    for (uint32_t i = 0; i < v.vertex_count; i++) {
        const lumo_q1_14 *n = v.normals + 3 * i;
        double len = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
        if (!(faceless_ok && len == 0))
            assert_close(len, 16384.0, 80.0);  /* every vertex of this mesh has faces */
    }
}

static void check_level(const lumo_pmesh *pm)
{
    check_level_ex(pm, 0);
}

static uint32_t fnv(uint32_t h, const void *p, size_t n)
{
    const uint8_t *b = p;
    for (size_t i = 0; i < n; i++)
        h = (h ^ b[i]) * 16777619u;
    return h;
}

static uint32_t mesh_hash(const lumo_pmesh *pm)
{
    lumo_pmesh_view v;
    lumo_pmesh_get_view(pm, &v);
    uint32_t h = fnv(2166136261u, v.triangles, 12u * v.face_count);
    return fnv(h, v.positions, 12u * v.vertex_count);
}

/* What must not change when a batch is rejected. */
typedef struct {
    uint32_t vc, fc, ba;
    uint8_t *bytes;
    size_t n;
} snapshot;

static size_t snap_bytes(const lumo_pmesh *pm)
{
    return 12u * pm->face_count * 2 + 4u * pm->vertex_count + 12u * pm->vertex_count + 6u * pm->vertex_count;
}

static void snap_fill(const lumo_pmesh *pm, uint8_t *o)
{
    size_t fc = 12u * pm->face_count, vc = pm->vertex_count;
    memcpy(o, pm->tris, fc), o += fc;
    memcpy(o, pm->next, fc), o += fc;
    memcpy(o, pm->head, 4 * vc), o += 4 * vc;
    memcpy(o, pm->pos, 12 * vc), o += 12 * vc;
    memcpy(o, pm->nrm, 6 * vc);
}

static void snap(const lumo_pmesh *pm, snapshot *s)
{
    s->vc = pm->vertex_count, s->fc = pm->face_count, s->ba = pm->batches_applied;
    s->n = snap_bytes(pm);
    s->bytes = malloc(s->n + 1);
    snap_fill(pm, s->bytes);
}

static void assert_unchanged(const lumo_pmesh *pm, const snapshot *s)
{
    assert_int_equal(pm->vertex_count, s->vc);
    assert_int_equal(pm->face_count, s->fc);
    assert_int_equal(pm->batches_applied, s->ba);
    uint8_t *now = malloc(s->n + 1);
    snap_fill(pm, now);
    assert_memory_equal(now, s->bytes, s->n);
    free(now);
}

static void put32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        p[i] = (uint8_t)(v >> (8 * i));
}

/* LEB128 (docs/progressive-mesh.md §2.2); `overlong` adds a zero group. */
static size_t put_leb(uint8_t *d, uint32_t v, int overlong)
{
    size_t n = 0;
    for (; v > 0x7fu; v >>= 7)
        d[n++] = (uint8_t)(v | 0x80u);
    d[n++] = (uint8_t)v;
    if (overlong)
        d[n - 1] |= 0x80u, d[n++] = 0;
    return n;
}

/* A header written field by field (docs/progressive-mesh.md §2.1), as a
 * second writer would; `pad` adds a zero byte after the counts and
 * `overlong` writes the first count with one byte too many (both refused).
 * Returns the length; h->header_bytes is set to it. */
static uint32_t put_header(uint8_t *d, lumo_pmesh_header *h, int pad, int overlong)
{
    const uint32_t counts[8] = {h->vertices, h->faces, h->base_vertices, h->base_faces,
                                h->batch_vertices, h->max_batch_faces, h->max_batch_moves,
                                h->max_batch_bytes};
    size_t n = 7;
    put32(d, LUMO_PMESH_MAGIC);
    d[4] = LUMO_PMESH_VERSION, d[5] = 0;
    for (int i = 0; i < 8; i++)
        n += put_leb(d + n, counts[i], overlong && i == 0);
    if (pad)
        d[n++] = 0;
    d[n++] = (uint8_t)h->quant_bits, d[n++] = (uint8_t)h->position_coding, d[n++] = (uint8_t)h->flags;
    for (int i = 0; i < 3; i++, n += 4)
        put32(d + n, h->origin_bits[i]);
    put32(d + n, h->range_bits), n += 4;
    d[6] = (uint8_t)(n + 4);
    put32(d + n, lumo_wire_crc32(0, d, n));
    h->header_bytes = (uint32_t)(n + 4);
    return h->header_bytes;
}

/* ---- tests --------------------------------------------------------------- */
static void test_header(void **state)
{
    (void)state;
    lumo_pmesh_header h;
    assert_int_equal(lumo_pmesh_read_header(k_stream, sizeof k_stream, &h), LUMO_OK);
    assert_int_equal(h.vertices, 20);
    assert_int_equal(h.faces, 36);
    assert_int_equal(h.base_vertices, 4);
    assert_int_equal(h.batch_vertices, 3);
    assert_int_equal(h.batch_count, 7);
    assert_int_equal(h.quant_bits, 8);  /* per mesh: the tiny mesh's long edges */
    for (size_t n = 0; n < h.header_bytes; n++)
        assert_int_equal(lumo_pmesh_read_header(k_stream, n, &h), LUMO_ERR_TRUNCATED);
    uint8_t b[LUMO_PMESH_HEADER_MAX + 8];
    for (size_t i = 0; i < h.header_bytes; i++) {  /* any flipped byte is caught */
        memcpy(b, k_stream, h.header_bytes);
        b[i] ^= 0x10;
        assert_int_not_equal(lumo_pmesh_read_header(b, h.header_bytes, &h), LUMO_OK);
    }
    assert_int_equal(lumo_pmesh_read_header(k_stream, sizeof k_stream, &h), LUMO_OK);
    /* our own writer's bytes give the stream's header back */
    assert_int_equal(put_header(b, &h, 0, 0), h.header_bytes);
    assert_memory_equal(b, k_stream, h.header_bytes);
    /* fields with the CRC fixed: each check has its own error */
    enum { VTX, FACES, BASE, BASEF, BATCH, MAXF, MAXM, MAXB, QBITS, CODING, FLAGS, RANGE, VERSION };
    struct { int field; uint32_t v; lumo_status want; } cases[] = {
        {VERSION, 7, LUMO_ERR_VERSION}, {QBITS, 0, LUMO_ERR_UNSUPPORTED},
        {QBITS, 21, LUMO_ERR_UNSUPPORTED}, {BASE, 0, LUMO_ERR_CORRUPT},
        {BASE, 21, LUMO_ERR_CORRUPT}, {VTX, 1u << 29, LUMO_ERR_LIMIT}, {RANGE, 0x7f800000u, LUMO_ERR_NONFINITE},
        {RANGE, 0xbf800000u, LUMO_ERR_RANGE}, {MAXF, 37, LUMO_ERR_CORRUPT}, {MAXB, 4, LUMO_ERR_CORRUPT},
        {FLAGS, 4, LUMO_ERR_UNSUPPORTED},                        /* unknown flag */
        {FLAGS, 2, LUMO_OK},                                     /* LATTICE with CODED */
        {CODING, 1, LUMO_ERR_UNSUPPORTED},                       /* ... and without */
        {CODING, 3, LUMO_ERR_UNSUPPORTED},                       /* unknown coding */
        {FLAGS, 3, LUMO_OK},                                     /* CODED, albedo and LATTICE */
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        lumo_pmesh_header m = h;
        uint32_t *field[] = {&m.vertices, &m.faces, &m.base_vertices, &m.base_faces, &m.batch_vertices,
                             &m.max_batch_faces, &m.max_batch_moves, &m.max_batch_bytes, &m.quant_bits,
                             &m.position_coding, &m.flags, &m.range_bits};
        if (cases[c].field == CODING)
            m.flags = LUMO_PMESH_LATTICE;
        if (cases[c].field == VERSION) {
            put_header(b, &m, 0, 0);
            b[4] = (uint8_t)cases[c].v;
            put32(b + m.header_bytes - 4, lumo_wire_crc32(0, b, m.header_bytes - 4));
        } else {
            *field[cases[c].field] = cases[c].v;
            put_header(b, &m, 0, 0);
        }
        assert_int_equal(lumo_pmesh_read_header(b, sizeof b, &m), cases[c].want);
    }
    /* the counts must fill their bytes exactly, minimally coded */
    lumo_pmesh_header m = h;
    put_header(b, &m, 1, 0);  /* a zero byte after the counts */
    assert_int_equal(lumo_pmesh_read_header(b, sizeof b, &m), LUMO_ERR_CORRUPT);
    m = h;
    put_header(b, &m, 0, 1);  /* the first count overlong */
    assert_int_equal(lumo_pmesh_read_header(b, sizeof b, &m), LUMO_ERR_CORRUPT);
    memcpy(b, k_stream, h.header_bytes);
    for (uint32_t len = 0; len < 256; len++) {  /* a length byte not the header's */
        if (len == h.header_bytes)
            continue;
        b[6] = (uint8_t)len;
        lumo_status st = lumo_pmesh_read_header(b, sizeof b, &m);
        assert_true(st == LUMO_ERR_CORRUPT || st == LUMO_ERR_CHECKSUM);
    }
}

static void test_arena_sizing(void **state)
{
    (void)state;
    lumo_pmesh_header h;
    lumo_pmesh pm;
    lumo_arena a;
    assert_int_equal(lumo_pmesh_read_header(k_stream, sizeof k_stream, &h), LUMO_OK);
    size_t need = lumo_pmesh_arena_bytes(&h);
    uint8_t *mem = malloc(need);
    /* one byte short fails cleanly, leaving the arena as it was */
    lumo_arena_init(&a, mem, need - LUMO_ARENA_SLACK - 1);
    if (a.size == need - LUMO_ARENA_SLACK - 1) {
        assert_int_equal(lumo_pmesh_init(&pm, &h, &a), LUMO_ERR_NOMEM);
        assert_int_equal(a.used, 0);
    }
    lumo_arena_init(&a, mem, need);
    assert_int_equal(lumo_pmesh_init(&pm, &h, &a), LUMO_OK);
    lumo_pmesh_view v;
    lumo_pmesh_get_view(&pm, &v);
    assert_int_equal(v.vertex_count, 0);
    assert_int_equal(v.face_count, 0);
    free(mem);
}

static void test_full_stream(void **state)
{
    (void)state;
    fixture f;
    open_fixture(&f);
    uint32_t last = 0;
    while (!lumo_pmesh_complete(&f.pm)) {
        step(&f);
        assert_true(f.pm.vertex_count > last);
        last = f.pm.vertex_count;
        check_level(&f.pm);
    }
    assert_int_equal(f.at, sizeof k_stream);
    assert_int_equal(f.pm.face_count, 36);
    assert_int_equal(f.pm.batches_applied, 7);
    print_message("final hash 0x%08x\n", mesh_hash(&f.pm));
    assert_int_equal(mesh_hash(&f.pm), FINAL_HASH);
    free(f.mem);
}

/* Every truncation and every byte flip of every record is rejected and the
 * mesh stays as it was; then the good record applies. */
static void truncation_and_flips(const uint8_t *data, size_t size, uint32_t final_hash)
{
    fixture f;
    open_on(&f, data, size);
    while (!lumo_pmesh_complete(&f.pm)) {
        const uint8_t *rec;
        size_t n = next_record(&f, &rec);
        snapshot s;
        snap(&f.pm, &s);
        for (size_t cut = 0; cut < n; cut++) {
            assert_int_not_equal(lumo_pmesh_apply(&f.pm, rec, cut), LUMO_OK);
            assert_unchanged(&f.pm, &s);
        }
        uint8_t *b = malloc(n);
        for (size_t i = 0; i < n; i++) {
            memcpy(b, rec, n);
            b[i] ^= 0x81;
            assert_int_not_equal(lumo_pmesh_apply(&f.pm, b, n), LUMO_OK);
            assert_unchanged(&f.pm, &s);
        }
        free(b);
        free(s.bytes);
        step(&f);
    }
    if (final_hash)
        assert_int_equal(mesh_hash(&f.pm), final_hash);
    free(f.mem);
}

static void test_truncation_and_flips(void **state)
{
    (void)state;
    truncation_and_flips(k_stream, sizeof k_stream, FINAL_HASH);
    truncation_and_flips(k_seeded, sizeof k_seeded, 0);
}

/* The record's head (varints and CRC): its length. */
static uint32_t head_bytes(const uint8_t *r, size_t n)
{
    lumo_pmesh_record_head rh;
    assert_int_equal(lumo_pmesh_read_record_head(r, n, &rh), LUMO_OK);
    return rh.head_bytes;
}

static uint32_t side_bytes(const uint8_t *r, size_t n)
{
    lumo_pmesh_record_head rh;
    assert_int_equal(lumo_pmesh_read_record_head(r, n, &rh), LUMO_OK);
    return rh.side_bytes;
}

/* The CRC of record number `index` (which it does not carry). */
static void fix_crc(uint8_t *r, size_t n, uint32_t index)
{
    uint8_t idx[LUMO_WIRE_VARINT32_MAX];
    uint32_t hb = head_bytes(r, n);
    uint32_t crc = lumo_wire_crc32(0, idx, put_leb(idx, index, 0));
    crc = lumo_wire_crc32(crc, r, hb - 4u);
    put32(r + hb - 4u, lumo_wire_crc32(crc, r + hb, n - hb));
}

/* Bit flips behind a valid CRC reach the split decoder: each is either
 * rejected with the mesh untouched (the undo log) or yields a valid level. */
static void tampered_batches(const uint8_t *data, size_t size, uint32_t final_hash)
{
    fixture f;
    open_on(&f, data, size);
    unsigned rejected = 0, accepted = 0;
    while (!lumo_pmesh_complete(&f.pm)) {
        const uint8_t *rec;
        size_t n = next_record(&f, &rec);
        uint32_t hb = head_bytes(rec, n), side = side_bytes(rec, n);
        uint8_t *b = malloc(n);
        for (size_t bit = 0; bit < 8u * (hb + side); bit++) {
            if (bit >= 8u * (hb - 4u) && bit < 8u * hb)
                continue;  /* the CRC itself */
            memcpy(b, rec, n);
            b[bit / 8] ^= (uint8_t)(1u << (bit % 8));
            lumo_pmesh_record_head rh;
            if (lumo_pmesh_read_record_head(b, n, &rh) || rh.head_bytes != hb ||
                rh.side_bytes != side || (size_t)hb + side + rh.draco_bytes != n)
                continue;  /* a changed head: the size checks (test_truncation_and_flips) */
            fix_crc(b, n, f.pm.batches_applied);
            snapshot s;
            snap(&f.pm, &s);
            lumo_status st = lumo_pmesh_apply(&f.pm, b, n);
            if (st) {
                assert_unchanged(&f.pm, &s);
                rejected++;
            } else {
                check_level_ex(&f.pm, 1);
                accepted++;
                /* rebuild the good state: replay from scratch up to here */
                size_t at = f.at;
                free(f.mem);
                open_on(&f, data, size);
                while (f.at < at)
                    step(&f);
            }
            free(s.bytes);
        }
        free(b);
        step(&f);
    }
    assert_true(rejected > 0);
    print_message("tampered: %u rejected, %u accepted as another valid level\n", rejected, accepted);
    if (final_hash)
        assert_int_equal(mesh_hash(&f.pm), final_hash);
    free(f.mem);
}

static void test_tampered_batches(void **state)
{
    (void)state;
    tampered_batches(k_stream, sizeof k_stream, FINAL_HASH);
    tampered_batches(k_seeded, sizeof k_seeded, 0);
}

static void test_order(void **state)
{
    (void)state;
    fixture f;
    open_fixture(&f);
    const uint8_t *rec0, *rec1;
    size_t n0 = next_record(&f, &rec0);
    f.at += n0;
    size_t n1 = next_record(&f, &rec1);
    f.at -= n0;
    /* the CRC covers the index a record should have (§2.2) */
    assert_int_equal(lumo_pmesh_record_check(rec0, n0, 0), LUMO_OK);
    assert_int_equal(lumo_pmesh_record_check(rec1, n1, 1), LUMO_OK);
    assert_int_equal(lumo_pmesh_record_check(rec1, n1, 0), LUMO_ERR_CHECKSUM);
    assert_int_equal(lumo_pmesh_record_check(rec1, n1, 2), LUMO_ERR_CHECKSUM);
    assert_int_equal(lumo_pmesh_record_check(rec1, n1 - 1, 1), LUMO_ERR_TRUNCATED);
    assert_int_equal(lumo_pmesh_record_check(rec1, n1 + 1, 1), LUMO_ERR_CORRUPT);
    assert_int_equal(lumo_pmesh_apply(&f.pm, rec1, n1), LUMO_ERR_CHECKSUM);  /* split before base */
    assert_int_equal(lumo_pmesh_apply(&f.pm, rec0, n0), LUMO_OK);
    assert_int_equal(lumo_pmesh_apply(&f.pm, rec0, n0), LUMO_ERR_CHECKSUM);  /* repeated */
    assert_int_equal(lumo_pmesh_apply(&f.pm, rec1, n1), LUMO_OK);
    assert_int_equal(lumo_pmesh_apply(&f.pm, rec1, n1), LUMO_ERR_CHECKSUM);
    assert_int_equal(lumo_pmesh_apply(&f.pm, rec0, n0 + 1), LUMO_ERR_CORRUPT);  /* trailing byte */
    check_level(&f.pm);
    free(f.mem);
}

/* Record rec (n bytes) with its split block replaced by `side` (sn
 * bytes): new head varints, the same payload, a valid CRC for record
 * number `index`. Returns the
 * new length; out holds n + 16 bytes. */
static size_t with_side(const uint8_t *rec, size_t n, const uint8_t *side, size_t sn, uint32_t index,
                        uint8_t *out)
{
    lumo_pmesh_record_head rh;
    assert_int_equal(lumo_pmesh_read_record_head(rec, n, &rh), LUMO_OK);
    size_t at = lumo_wire_put_varint(out, (uint32_t)sn * 2u + (rh.draco_bytes != 0));
    if (rh.draco_bytes)
        at += lumo_wire_put_varint(out + at, rh.draco_bytes);
    at += 4;
    memmove(out + at, side, sn);
    memcpy(out + at + sn, rec + rh.head_bytes + rh.side_bytes, rh.draco_bytes);
    at += sn + rh.draco_bytes;
    fix_crc(out, at, index);
    return at;
}

/* A bad record is refused with the mesh as it was, or reads as a valid
 * level; then the fixture goes back to the level before (replayed). */
static void refused_or_valid(fixture *f, const uint8_t *b, size_t n, const snapshot *s)
{
    if (lumo_pmesh_apply(&f->pm, b, n)) {
        assert_unchanged(&f->pm, s);
        return;
    }
    check_level(&f->pm);
    size_t at = f->at;
    free(f->mem);
    open_fixture(f);
    while (f->at < at)
        step(f);
}

/* The split block is one range code that ends exactly where the writer's
 * flush ends it (docs/progressive-mesh.md §2.3, §2.5): a byte more, a
 * byte less, its last byte changed, or bytes of noise behind a valid CRC
 * are rejected and leave the mesh as it was; the good copy then applies. */
static void test_range_code_end(void **state)
{
    (void)state;
    fixture f;
    open_fixture(&f);
    step(&f);  /* the base mesh */
    const uint8_t *rec;
    size_t n = next_record(&f, &rec);
    while (n >= f.h.max_batch_bytes) {  /* a byte more must not hit the record limit (LIMIT) first */
        step(&f);
        n = next_record(&f, &rec);
    }
    uint32_t hb = head_bytes(rec, n), sb = side_bytes(rec, n);
    uint8_t *side = malloc(sb + 1), *b = malloc(n + 16);
    snapshot s;
    snap(&f.pm, &s);
    memcpy(side, rec + hb, sb);
    side[sb] = 0;
    assert_int_equal(lumo_pmesh_apply(&f.pm, b, with_side(rec, n, side, sb + 1, f.pm.batches_applied, b)), LUMO_ERR_CORRUPT);
    assert_unchanged(&f.pm, &s);
    /* A byte less, the last byte changed, noise: the end rules (code below
     * 2^24, the implied zeros) refuse most, but such a block may also read
     * as other splits that end right: then it is another valid level (the
     * CRC, not the code, is the check against damage). */
    refused_or_valid(&f, b, with_side(rec, n, side, sb - 1, f.pm.batches_applied, b), &s);
    side[sb - 1] ^= 1u;
    refused_or_valid(&f, b, with_side(rec, n, side, sb, f.pm.batches_applied, b), &s);
    static const uint8_t noise[] = {0x00, 0xff, 0x5a};
    for (size_t i = 0; i < sizeof noise; i++) {
        memset(side, noise[i], sb);
        refused_or_valid(&f, b, with_side(rec, n, side, sb, f.pm.batches_applied, b), &s);
    }
    assert_int_equal(lumo_pmesh_apply(&f.pm, rec, n), LUMO_OK);  /* the good copy still applies */
    free(s.bytes);
    free(side);
    free(b);
    free(f.mem);
}

/* ---- the base record's seed (docs/progressive-mesh.md §2.3 "Base record") ---- */
/* Elias gamma code of v >= 1 at bit *pos of buf (LSB first). */
static void put_gamma(uint8_t *buf, size_t *pos, uint32_t v)
{
    unsigned z = 0;
    while (z < 31 && v >> (z + 1))
        z++;
    lumo_wire_put_bits(buf, *pos, 0, z), *pos += z;
    lumo_wire_put_bits(buf, *pos, 1, 1), *pos += 1;
    lumo_wire_put_bits(buf, *pos, v & ((1u << z) - 1u), z), *pos += z;
}

static uint32_t get_gamma(const uint8_t *buf, size_t n, size_t *pos)
{
    lumo_wire_bits b;
    uint32_t z = 0, bit = 0, low = 0;
    lumo_wire_bits_init(&b, buf, n);
    b.pos = *pos;
    while (!bit) {
        assert_int_equal(lumo_wire_bits_read(&b, 1, &bit), LUMO_OK);
        z += !bit;
    }
    assert_int_equal(lumo_wire_bits_read(&b, z, &low), LUMO_OK);
    *pos = b.pos;
    return 1u << z | low;
}

/* A copy of a stream whose header allows records 16 bytes longer (CRC
 * fixed), so a byte appended to a record reaches the block's end rules
 * rather than the LIMIT check. */
static uint8_t *roomy_copy(const uint8_t *data, size_t size, size_t *out_size)
{
    lumo_pmesh_header h;
    assert_int_equal(lumo_pmesh_read_header(data, size, &h), LUMO_OK);
    size_t old = h.header_bytes;
    uint8_t *c = malloc(size + 8);
    h.max_batch_bytes += 16u;
    size_t hn = put_header(c, &h, 0, 0);
    memcpy(c + hn, data + old, size - old);
    *out_size = size - old + hn;
    return c;
}

/* A fixture on a roomy copy of stream s (the caller frees the copy) and
 * its contexts as they start, for "as before" checks. */
static uint8_t *open_roomy(fixture *f, const uint8_t *s, size_t n, uint32_t *ctx0)
{
    size_t data_n;
    uint8_t *data = roomy_copy(s, n, &data_n);
    open_on(f, data, data_n);
    memcpy(ctx0, f->pm.ctx, LUMO_PMESH_CONTEXTS * sizeof *ctx0);
    return data;
}

/* Sorted position triples of the current level (numbering-free). */
static int cmp_tri9(const void *a, const void *b)
{
    return memcmp(a, b, 36);
}

static int32_t *level_tris(const lumo_pmesh *pm)
{
    lumo_pmesh_view v;
    lumo_pmesh_get_view(pm, &v);
    int32_t *t = malloc(36u * v.face_count + 4);
    for (uint32_t f = 0; f < v.face_count; f++) {
        uint32_t r = 0;  /* rotate the smallest corner first, winding kept */
        for (uint32_t c = 1; c < 3; c++)
            if (memcmp(v.positions + 3 * v.triangles[3 * f + c], v.positions + 3 * v.triangles[3 * f + r], 12) < 0)
                r = c;
        for (uint32_t c = 0; c < 3; c++)
            memcpy(t + 9 * f + 3 * c, v.positions + 3 * v.triangles[3 * f + (r + c) % 3], 12);
    }
    qsort(t, v.face_count, 36, cmp_tri9);
    return t;
}

/* The seeded stream: its base record holds a seed of 4 vertices and 4
 * faces and the 4 splits to the 8-vertex base mesh, which is the first
 * level shown (no rewind below it); the split records continue its range
 * code's state; the full mesh is the same as k_stream's (same mesh, same
 * grid). */
static void test_seeded_stream(void **state)
{
    (void)state;
    fixture f, g;
    const uint8_t *rec;
    open_on(&f, k_seeded, sizeof k_seeded);
    assert_int_equal(f.h.base_vertices, 8);
    assert_int_equal(f.h.position_coding, LUMO_PMESH_POS_CODED);
    size_t n = next_record(&f, &rec), pos = 0;
    const uint8_t *block = rec + head_bytes(rec, n);
    assert_int_equal(get_gamma(block, side_bytes(rec, n), &pos), 4);      /* seed vertices */
    assert_int_equal(get_gamma(block, side_bytes(rec, n), &pos) - 1, 4);  /* seed faces */
    step(&f);
    assert_int_equal(f.pm.vertex_count, 8);
    assert_int_equal(f.pm.face_count, f.h.base_faces);
    assert_true(f.pm.last_parent < 8);  /* the base's last split, continued by record 1 */
    check_level(&f.pm);
    assert_int_equal(lumo_pmesh_rewind(&f.pm, 7), LUMO_ERR_RANGE);  /* seed levels are never shown */
    while (!lumo_pmesh_complete(&f.pm)) {
        step(&f);
        check_level(&f.pm);
    }
    assert_int_equal(f.at, sizeof k_seeded);
    open_fixture(&g);
    while (!lumo_pmesh_complete(&g.pm))
        step(&g);
    assert_int_equal(f.pm.face_count, g.pm.face_count);
    int32_t *a = level_tris(&f.pm), *b = level_tris(&g.pm);
    assert_memory_equal(a, b, 36u * f.pm.face_count);
    free(a), free(b);
    free(f.mem), free(g.mem);
}

/* Nothing of a rejected base record stays: no face, no vertex, the range
 * code's contexts and round state as at the start. */
static void assert_fresh(const fixture *f, const uint32_t *ctx0)
{
    assert_int_equal(f->pm.vertex_count, 0);
    assert_int_equal(f->pm.face_count, 0);
    assert_int_equal(f->pm.batches_applied, 0);
    assert_int_equal(f->pm.last_parent, 0xffffffffu);
    assert_int_equal(f->pm.round_first, 0);
    assert_int_equal(f->pm.last_fan, 0);
    assert_memory_equal(f->pm.ctx, ctx0, LUMO_PMESH_CONTEXTS * sizeof *ctx0);
    for (uint32_t v = 0; v < f->h.vertices; v++)
        assert_int_equal(f->pm.round_parent[v], 0);
    for (uint32_t v = 0; v < f->h.vertices; v++)
        assert_int_equal(f->pm.head[v], LUMO_PMESH_NIL);
}

/* Hostile seed fields behind a valid CRC, each with its own error, the
 * client left as before; then the good base record and the rest apply. */
static void test_seed_fields(void **state)
{
    (void)state;
    fixture f;
    const uint8_t *rec;
    uint32_t ctx0[LUMO_PMESH_CONTEXTS];
    uint8_t *data = open_roomy(&f, k_seeded, sizeof k_seeded, ctx0);
    size_t n = next_record(&f, &rec);
    uint32_t hb = head_bytes(rec, n), sb = side_bytes(rec, n), b = f.h.base_vertices;
    const uint8_t *block = rec + hb;
    uint8_t side[512], *out = malloc(n + 512);
    assert_true(sb + 8 <= sizeof side);
    /* the plain part: two gamma codes, 3 * 4 face indices in tb(4) (2
     * bits each), 3 * 4 grid integers; then zero padding */
    size_t plain = 5 + 5 + 12 * 2 + 12 * f.h.quant_bits, plain_bytes = (plain + 7) / 8;
    struct { uint32_t s, sf; lumo_status want; } sizes[] = {
        {b + 1, 4, LUMO_ERR_RANGE},                   /* a seed larger than the base mesh */
        {0xffffffffu, 4, LUMO_ERR_RANGE},
        {4, f.h.base_faces + 1, LUMO_ERR_CORRUPT},    /* more faces than the base mesh */
        {4, 0xfffffffeu, LUMO_ERR_CORRUPT},
        {b, 4, LUMO_ERR_CORRUPT},                     /* no splits left to add the faces */
    };
    for (size_t c = 0; c < sizeof sizes / sizeof sizes[0]; c++) {
        size_t pos = 0;
        memset(side, 0, sizeof side);
        put_gamma(side, &pos, sizes[c].s);
        put_gamma(side, &pos, sizes[c].sf + 1);
        assert_int_equal(lumo_pmesh_apply(&f.pm, out, with_side(rec, n, side, sb, 0, out)), sizes[c].want);
        assert_fresh(&f, ctx0);
    }
    memset(side, 0, sizeof side);  /* a gamma code of 32 zeros: CORRUPT; cut short: TRUNCATED */
    side[4] = 1;
    assert_int_equal(lumo_pmesh_apply(&f.pm, out, with_side(rec, n, side, 5, 0, out)), LUMO_ERR_CORRUPT);
    assert_int_equal(lumo_pmesh_apply(&f.pm, out, with_side(rec, n, side, 3, 0, out)), LUMO_ERR_TRUNCATED);
    assert_fresh(&f, ctx0);
    /* the seed without its splits' range code: cut, or zero bytes of it */
    assert_true(plain_bytes < sb);
    assert_int_not_equal(lumo_pmesh_apply(&f.pm, out, with_side(rec, n, block, plain_bytes, 0, out)), LUMO_OK);
    assert_fresh(&f, ctx0);
    memcpy(side, block, sb);
    memset(side + plain_bytes, 0, sb - plain_bytes);
    assert_int_not_equal(lumo_pmesh_apply(&f.pm, out, with_side(rec, n, side, sb, 0, out)), LUMO_OK);
    assert_fresh(&f, ctx0);
    /* a padding bit set, or a byte more after the range code */
    if (plain % 8) {
        memcpy(side, block, sb);
        side[plain / 8] |= (uint8_t)(0x80u);
        assert_int_equal(lumo_pmesh_apply(&f.pm, out, with_side(rec, n, side, sb, 0, out)), LUMO_ERR_CORRUPT);
        assert_fresh(&f, ctx0);
    }
    memcpy(side, block, sb);
    side[sb] = 0;
    assert_int_equal(lumo_pmesh_apply(&f.pm, out, with_side(rec, n, side, sb + 1, 0, out)), LUMO_ERR_CORRUPT);
    assert_fresh(&f, ctx0);
    /* the splits' last byte changed: refused late, after splits to undo,
     * or read as other splits that end right (a valid level; the CRC is
     * the check against damage): then back to nothing received */
    memcpy(side, block, sb);
    side[sb - 1] ^= 0x40u;
    if (lumo_pmesh_apply(&f.pm, out, with_side(rec, n, side, sb, 0, out)) == LUMO_OK) {
        check_level(&f.pm);
        free(f.mem);
        open_on(&f, data, f.size);
    }
    assert_fresh(&f, ctx0);
    step(&f);  /* the good copy, then the rest */
    while (!lumo_pmesh_complete(&f.pm)) {
        step(&f);
        check_level(&f.pm);
    }
    free(out);
    free(f.mem);
    free(data);
}

/* Without splits (k_stream's seed is its base mesh) the block ends at its
 * zero padding: a byte more is CORRUPT. */
static void test_seed_is_base(void **state)
{
    (void)state;
    fixture f;
    const uint8_t *rec;
    uint32_t ctx0[LUMO_PMESH_CONTEXTS];
    uint8_t *data = open_roomy(&f, k_stream, sizeof k_stream, ctx0);
    size_t n = next_record(&f, &rec), pos = 0;
    uint32_t hb = head_bytes(rec, n), sb = side_bytes(rec, n);
    assert_int_equal(get_gamma(rec + hb, sb, &pos), f.h.base_vertices);
    assert_int_equal(get_gamma(rec + hb, sb, &pos) - 1, f.h.base_faces);
    uint8_t side[256], *out = malloc(n + 16);
    assert_true(sb + 1 <= sizeof side);
    memcpy(side, rec + hb, sb);
    side[sb] = 0;
    assert_int_equal(lumo_pmesh_apply(&f.pm, out, with_side(rec, n, side, sb + 1, 0, out)), LUMO_ERR_CORRUPT);
    assert_fresh(&f, ctx0);
    step(&f);
    assert_int_equal(f.pm.vertex_count, f.h.base_vertices);
    assert_int_equal(f.pm.last_parent, 0xffffffffu);  /* no split yet */
    free(out);
    free(f.mem);
    free(data);
}

/* The record head's varints (docs/progressive-mesh.md §2.2): minimal
 * LEB128 of at most 5 bytes, the block's size below 2^28 doubled plus the
 * payload flag, a payload size only after the flag and not 0; else
 * CORRUPT; a cut head is TRUNCATED. */
static void test_record_head(void **state)
{
    (void)state;
    lumo_pmesh_record_head rh;
    const uint8_t good[] = {0x83, 0x02, 0x2c, 1, 2, 3, 4};  /* 2 * 129 + 1, then 44 */
    assert_int_equal(lumo_pmesh_read_record_head(good, sizeof good, &rh), LUMO_OK);
    assert_int_equal(rh.side_bytes, 129);
    assert_int_equal(rh.draco_bytes, 44);
    assert_int_equal(rh.crc, 0x04030201u);
    assert_int_equal(rh.head_bytes, 7);
    for (size_t n = 0; n < sizeof good; n++)
        assert_int_equal(lumo_pmesh_read_record_head(good, n, &rh), LUMO_ERR_TRUNCATED);
    const uint8_t coded[] = {0x82, 0x02, 1, 2, 3, 4};  /* no payload */
    assert_int_equal(lumo_pmesh_read_record_head(coded, sizeof coded, &rh), LUMO_OK);
    assert_int_equal(rh.side_bytes, 129);
    assert_int_equal(rh.draco_bytes, 0);
    assert_int_equal(rh.head_bytes, 6);
    const uint8_t empty_payload[] = {0x83, 0x02, 0x00, 1, 2, 3, 4};
    const uint8_t overlong[] = {0x85, 0x00, 0x01, 1, 2, 3, 4};   /* 5 in two bytes */
    const uint8_t six[] = {0x80, 0x80, 0x80, 0x80, 0x80, 0x01, 1, 2, 3, 4};
    const uint8_t big[] = {0x82, 0x80, 0x80, 0x80, 0x02, 1, 2, 3, 4};  /* 2 * (2^28 + 1) */
    assert_int_equal(lumo_pmesh_read_record_head(empty_payload, sizeof empty_payload, &rh), LUMO_ERR_CORRUPT);
    assert_int_equal(lumo_pmesh_read_record_head(overlong, sizeof overlong, &rh), LUMO_ERR_CORRUPT);
    assert_int_equal(lumo_pmesh_read_record_head(six, sizeof six, &rh), LUMO_ERR_CORRUPT);
    assert_int_equal(lumo_pmesh_read_record_head(big, sizeof big, &rh), LUMO_ERR_CORRUPT);
}

/* Rewinding inside the last batch gives every level; the mesh is final. */
static void test_rewind(void **state)
{
    (void)state;
    for (uint32_t k = 4; k <= 20; k++) {
        fixture f;
        open_fixture(&f);
        while (f.pm.vertex_count < k)
            step(&f);
        uint32_t first = f.pm.last_first;
        assert_int_equal(lumo_pmesh_rewind(&f.pm, f.pm.vertex_count + 1), LUMO_ERR_RANGE);
        if (first > 0)
            assert_int_equal(lumo_pmesh_rewind(&f.pm, first - 1), LUMO_ERR_RANGE);
        assert_int_equal(lumo_pmesh_rewind(&f.pm, k), LUMO_OK);
        assert_int_equal(f.pm.vertex_count, k);
        check_level(&f.pm);
        if (f.at < sizeof k_stream) {
            const uint8_t *rec;
            size_t n = next_record(&f, &rec);
            assert_int_equal(lumo_pmesh_apply(&f.pm, rec, n), LUMO_ERR_STATE);
        }
        free(f.mem);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_header),
        cmocka_unit_test(test_arena_sizing),
        cmocka_unit_test(test_full_stream),
        cmocka_unit_test(test_truncation_and_flips),
        cmocka_unit_test(test_tampered_batches),
        cmocka_unit_test(test_order),
        cmocka_unit_test(test_range_code_end),
        cmocka_unit_test(test_rewind),
        cmocka_unit_test(test_record_head),
        cmocka_unit_test(test_seeded_stream),
        cmocka_unit_test(test_seed_fields),
        cmocka_unit_test(test_seed_is_base),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
