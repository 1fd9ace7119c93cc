/*
 * golden_pmesh.c — progressive meshes (lumo/pmesh.h) on the board,
 * bit-exact against the host. Reads LUMO_BUILD_DIR/board/pmesh/list.txt
 * (one raw stream per line, written by board.mk: the committed fuzz seeds
 * plus streams `lumo-pm build --raw` made from the test models), applies
 * every batch record and hashes the level after each one (positions,
 * normals, albedo, triangles). Along the way it checks on the board what
 * the host tests check: a corrupted copy of a record is rejected and leaves
 * the level's hash unchanged, after which the good record still applies;
 * and the last batch rewinds to its first level. Host and board must print
 * the same HASH lines.
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include "lumo/pmesh.h"
#include "board.h"
#include "golden.h"

int main(void);

#ifndef LUMO_BUILD_DIR
#define LUMO_BUILD_DIR "build"
#endif
#define LIST_PATH LUMO_BUILD_DIR "/board/pmesh/list.txt"
#define MAX_INPUT (512u << 10)
#define MAX_RECORD (64u << 10)

static uint8_t g_input[MAX_INPUT];
static uint8_t g_bad[MAX_RECORD];

static uint64_t hash_u64(uint64_t h, uint64_t v)
{
    return bt_fnv1a_u32(bt_fnv1a_u32(h, (uint32_t)v), (uint32_t)(v >> 32));
}

static uint64_t hash_words(uint64_t h, const void *p, size_t words)
{
    const uint8_t *b = (const uint8_t *)p;
    size_t i;

    for (i = 0; p != NULL && i < words; i++, b += 4)
        h = bt_fnv1a_u32(h, (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16
                               | (uint32_t)b[3] << 24);
    return h;
}

/* Q1.14 arrays are int16: hash them value by value. */
static uint64_t hash_q14(uint64_t h, const lumo_q1_14 *v, size_t n)
{
    size_t i;

    for (i = 0; v != NULL && i < n; i++)
        h = bt_fnv1a_u32(h, (uint32_t)(uint16_t)v[i]);
    return h;
}

static uint64_t hash_level(const lumo_pmesh *pm)
{
    lumo_pmesh_view v;
    uint64_t h = BT_FNV_OFFSET;

    lumo_pmesh_get_view(pm, &v);
    h = bt_fnv1a_u32(h, v.vertex_count);
    h = bt_fnv1a_u32(h, v.face_count);
    h = hash_words(h, v.positions, (size_t)v.vertex_count * 3u);
    h = hash_q14(h, v.normals, (size_t)v.vertex_count * 3u);
    h = hash_q14(h, v.albedo, (size_t)v.vertex_count * 3u);
    return hash_words(h, v.triangles, (size_t)v.face_count * 3u);
}

static void say(const char *a, const char *b)
{
    con_str(a);
    con_str(b);
    con_nl();
}

/* A corrupted copy of `rec` (one bit of its split block or payload
 * flipped) must be refused and leave the level as it was. */
static int reject_corrupt(lumo_pmesh *pm, const uint8_t *rec, size_t n, const char *path)
{
    uint64_t before = hash_level(pm);

    if (n > sizeof g_bad || n < LUMO_PMESH_BATCH_HEAD_MAX + 1u)
        return 0;
    memcpy(g_bad, rec, n);
    g_bad[n - 1u] ^= 0x10u;
    if (lumo_pmesh_apply(pm, g_bad, n) == LUMO_OK || hash_level(pm) != before) {
        say("golden_pmesh: corrupt record accepted or level changed: ", path);
        return 1;
    }
    return 0;
}

static int apply_stream(lumo_pmesh *pm, const uint8_t *s, size_t len, const char *label,
                        const char *path)
{
    size_t at = pm->h.header_bytes, n = 0;
    uint32_t batch = 0, first = 0, t0 = board_ticks();
    uint64_t h = BT_FNV_OFFSET;
    const uint8_t *rec;
    lumo_pmesh_view v;
    lumo_status st;

    while ((st = lumo_pmesh_next_record(s, len, &at, &rec, &n)) == LUMO_OK) {
        if (batch == 1u && reject_corrupt(pm, rec, n, path))
            return 1;
        lumo_pmesh_get_view(pm, &v);
        first = v.vertex_count;
        if ((st = lumo_pmesh_apply(pm, rec, n)) != LUMO_OK)
            break;
        h = hash_u64(h, hash_level(pm));
        batch++;
    }
    if (st == LUMO_ERR_RANGE)   /* the end of the stream */
        st = LUMO_OK;
    golden_cost(label, t0);
    h = bt_fnv1a_u32(h, (uint32_t)st);
    if (st == LUMO_OK && lumo_pmesh_rewind(pm, first) == LUMO_OK)
        h = hash_u64(h, hash_level(pm));
    golden_hash(label, h);
    con_str(label);
    con_str(": ");
    con_u64(batch);
    con_str(" batches, ");
    con_str(lumo_strerror(st));
    con_nl();
    return 0;
}

static int decode_one(const char *path)
{
    size_t len = 0, bytes = 0;
    uint8_t *mem = board_scratch(&bytes);
    lumo_pmesh_header h;
    lumo_pmesh pm;
    lumo_arena a;
    lumo_status st;
    char label[96];

    golden_label("pmesh.", path, label, sizeof label);
    if (board_read_file(path, g_input, sizeof g_input, &len) != 0) {
        say("golden_pmesh: cannot read ", path);
        return 1;
    }
    lumo_arena_init(&a, mem, bytes);
    st = lumo_pmesh_read_header(g_input, len, &h);
    if (st == LUMO_OK && lumo_pmesh_arena_bytes(&h) > bytes)
        st = LUMO_ERR_NOMEM;
    if (st == LUMO_OK)
        st = lumo_pmesh_init(&pm, &h, &a);
    if (st != LUMO_OK) {
        golden_hash(label, bt_fnv1a_u32(BT_FNV_OFFSET, (uint32_t)st));
        say(label, lumo_strerror(st));
        return 0;
    }
    return apply_stream(&pm, g_input, len, label, path);
}

int main(void)
{
    return golden_done(golden_each_path(LIST_PATH, decode_one));
}
