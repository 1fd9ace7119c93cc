/* fuzz_draco.c — hostile bytes into lumo's Draco decoder: it must return an
 * error (arena unchanged) or a decode whose every index is in range, never
 * read or write out of bounds, and finish in bounded time. The arena need
 * computed before decoding (lumo_draco_arena_need) must cover every decode
 * that succeeds, and equal its use when it says it is exact; the lean mode
 * must give the same result. Seeds:
 * tests/fuzz/seeds/fuzz_draco/ (draco_encoder output over all levels). */
#include <stdint.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include "lumo/draco.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static uint8_t g_mem[2u << 20];

static void check(const lumo_draco_mesh *m)
{
    uint32_t i, p;
    for (i = 0; i < 3 * m->num_faces; ++i)
        if (m->faces[i] >= m->num_points)
            abort();
    for (i = 0; i < m->num_attributes; ++i) {
        const lumo_draco_attribute *a = &m->attributes[i];
        for (p = 0; p < m->num_points; ++p) {
            uint32_t e = a->point_to_value ? a->point_to_value[p] : p;
            if (e >= a->num_values)
                abort();
            (void)lumo_draco_dequantize(a, 0, lumo_draco_value(a, p, 0));
        }
    }
}

/* One mode: the need covers the decode; returns the decode's status. */
static lumo_status decode(const uint8_t *data, size_t size, unsigned flags, lumo_draco_mesh *m)
{
    lumo_arena arena;
    lumo_draco_need need;
    const lumo_status need_st = lumo_draco_arena_need_ex(data, size, flags, &need);
    lumo_status st;
    lumo_arena_init(&arena, g_mem, sizeof g_mem);
    st = lumo_draco_decode_ex(data, size, flags, &arena, m);
    if (st == LUMO_OK) {
        const size_t used = m->arena_bytes + m->work_bytes;
        check(m);
        if (need_st != LUMO_OK || used > need.bytes || used < need.bytes_min ||
            (need.exact && used != need.bytes))
            abort();
    } else if (arena.used != 0) {
        abort();
    }
    return st;
}

/* Both modes (LUMO_DRACO_LEAN: a 24-bit corner table) must agree: the
 * same status, and on success the same faces. */
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static uint32_t faces[3u << 16];
    lumo_draco_mesh m;
    lumo_draco_info info;
    lumo_status st, lean;
    size_t n = 0;
    (void)lumo_draco_peek(data, size, &info);
    st = decode(data, size, 0, &m);
    if (st == LUMO_OK) {
        n = 3u * (size_t)m.num_faces;
        if (n > sizeof faces / sizeof faces[0])
            n = sizeof faces / sizeof faces[0];
        if (n)  /* point clouds: no face array */
            memcpy(faces, m.faces, n * sizeof faces[0]);
    }
    lean = decode(data, size, LUMO_DRACO_LEAN, &m);
    /* allowed differences: the arena (either side may not fit) and the
     * lean mode's lower face limit (23-bit corner ids) */
    if (lean != st && st != LUMO_ERR_NOMEM && lean != LUMO_ERR_NOMEM && lean != LUMO_ERR_LIMIT)
        abort();
    if (lean == LUMO_OK && st == LUMO_OK && n && memcmp(faces, m.faces, n * sizeof faces[0]))
        abort();
    return 0;
}
