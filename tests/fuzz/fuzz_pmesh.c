/* fuzz_pmesh.c — libFuzzer target for the progressive-mesh batch decoder
 * (lumo/pmesh.h). The input is a whole stream (seeds: real streams from the
 * server in tests/fuzz/seeds/fuzz_pmesh/). CRCs are recomputed before
 * decoding so that mutations reach the header checks, the Draco payloads
 * and the vertex-split decoder instead of stopping at the checksum. After
 * every accepted batch the level must be valid: indices below the vertex
 * count, no degenerate triangle. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "lumo/package.h"
#include "lumo/pmesh.h"
#include "lumo/wire.h"

#define MAX_ARENA ((size_t)64 << 20)

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void put32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v, p[1] = (uint8_t)(v >> 8), p[2] = (uint8_t)(v >> 16), p[3] = (uint8_t)(v >> 24);
}

/* The header's CRC (at its length's end, byte 6) and each record's, with
 * the index it has in the stream, so mutations get past the checksums. */
static void fix_crcs(uint8_t *s, size_t size)
{
    size_t at = s[6], n;
    uint32_t index = 0;
    uint8_t idx[LUMO_WIRE_VARINT32_MAX];
    if (at < LUMO_PMESH_HEADER_MIN || at > LUMO_PMESH_HEADER_MAX || at > size)
        return;
    put32(s + at - 4, lumo_wire_crc32(0, s, at - 4));
    lumo_pmesh_record_head rh;
    while (!lumo_pmesh_read_record_head(s + at, size - at, &rh) &&
           (n = (size_t)rh.head_bytes + rh.side_bytes + rh.draco_bytes) <= size - at) {
        uint32_t crc = lumo_wire_crc32(0, idx, lumo_wire_put_varint(idx, index++));
        crc = lumo_wire_crc32(crc, s + at, rh.head_bytes - 4u);
        put32(s + at + rh.head_bytes - 4u, lumo_wire_crc32(crc, s + at + rh.head_bytes, n - rh.head_bytes));
        at += n;
    }
}

static void check_level(const lumo_pmesh *pm)
{
    lumo_pmesh_view v;
    lumo_pmesh_get_view(pm, &v);
    for (uint32_t i = 0; i < v.face_count; i++) {
        const uint32_t *t = v.triangles + 3 * (size_t)i;
        if (t[0] >= v.vertex_count || t[1] >= v.vertex_count || t[2] >= v.vertex_count ||
            t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
            abort();
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    lumo_pmesh_header h;
    lumo_pmesh pm;
    lumo_arena a;
    if (size < LUMO_PMESH_HEADER_MIN)
        return 0;
    uint8_t *s = malloc(size);
    if (!s)
        return 0;
    memcpy(s, data, size);
    fix_crcs(s, size);
    size_t need;
    if (lumo_pmesh_read_header(s, size, &h) || (need = lumo_pmesh_arena_bytes(&h)) > MAX_ARENA) {
        free(s);
        return 0;
    }
    void *mem = malloc(need);
    lumo_arena_init(&a, mem, need);
    if (mem && !lumo_pmesh_init(&pm, &h, &a)) {
        size_t at = h.header_bytes, n;
        const uint8_t *rec;
        lumo_status st;
        while ((st = lumo_pmesh_next_record(s, size, &at, &rec, &n)) != LUMO_ERR_RANGE) {
            if (st == LUMO_ERR_TRUNCATED)   /* a truncated last record goes in as it is */
                rec = s + at, n = size - at, at = size;
            else if (st)
                break;
            if (!lumo_pmesh_apply(&pm, rec, n))
                check_level(&pm);
        }
    }
    free(mem);
    free(s);
    return 0;
}
