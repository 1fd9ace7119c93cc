/*
 * golden_draco.c — the Draco decoder (lumo/draco.h) on the board, bit-exact
 * against the host. Reads the list LUMO_BUILD_DIR/board/draco/list.txt (one
 * .drc path per line, written by board.mk: the committed fuzz seeds plus
 * real meshes encoded with draco_encoder from the test models), decodes
 * each file with its arena in scratch memory and hashes everything decoded:
 * counts, faces, every attribute's portable values, point map and
 * dequantization parameters, in both decoding modes (the default and
 * LUMO_DRACO_LEAN must agree). Host and board must print the same HASH
 * lines.
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include "lumo/draco.h"
#include "board.h"
#include "golden.h"

int main(void);

#ifndef LUMO_BUILD_DIR
#define LUMO_BUILD_DIR "build"
#endif
#define LIST_PATH LUMO_BUILD_DIR "/board/draco/list.txt"
#define MAX_INPUT (2u << 20)

static uint8_t g_input[MAX_INPUT];

static uint64_t hash_u32s(uint64_t h, const uint32_t *v, size_t n)
{
    size_t i;

    for (i = 0; v != NULL && i < n; i++)
        h = bt_fnv1a_u32(h, v[i]);
    return h;
}

static uint64_t hash_attribute(uint64_t h, const lumo_draco_attribute *a, uint32_t num_points)
{
    size_t i, n = (size_t)a->num_values * a->num_portable;

    h = bt_fnv1a(h, &a->type, 8);   /* the eight uint8_t descriptors */
    h = bt_fnv1a_u32(h, a->unique_id);
    h = bt_fnv1a_u32(h, a->num_values);
    for (i = 0; i < n; i++)
        h = bt_fnv1a_u32(h, (uint32_t)a->values[i]);
    h = hash_u32s(h, a->point_to_value, num_points);
    if (a->xform == LUMO_DRACO_XFORM_QUANTIZED) {
        h = hash_u32s(h, a->min_bits, a->num_components);
        h = hash_u32s(h, (const uint32_t *)a->min_fixed, a->num_components);
        h = bt_fnv1a_u32(h, a->range_bits);
        h = bt_fnv1a_u32(h, (uint32_t)a->range_fixed);
        for (i = 0; i < a->num_values && i < 64u; i++)
            h = bt_fnv1a_u32(h, (uint32_t)lumo_draco_dequantize(a, 0, a->values[i * a->num_portable]));
    }
    return h;
}

/* Decode in one mode (lumo_draco_decode_ex flags) and hash the result;
 * on success check the arena need computed before decoding, on this
 * target's struct sizes: it covers the decode, and is its use when it
 * says it is exact. Returns 1 on a wrong need. */
static int decode_mode(const char *label, size_t len, unsigned flags, lumo_draco_mesh *mesh,
                       lumo_status *st, uint64_t *hash)
{
    size_t bytes = 0;
    uint8_t *mem = board_scratch(&bytes);
    lumo_draco_info info;
    lumo_draco_need need;
    lumo_arena a;
    uint64_t h = BT_FNV_OFFSET;
    uint32_t i, t0;
    lumo_arena_init(&a, mem, bytes);
    t0 = board_ticks();
    *st = lumo_draco_peek(g_input, len, &info);
    if (*st == LUMO_OK)
        *st = lumo_draco_decode_ex(g_input, len, flags, &a, mesh);
    golden_cost(label, t0);
    /* a clean rejection (unsupported feature) is an outcome to hash too */
    h = bt_fnv1a_u32(h, (uint32_t)*st);
    if (*st == LUMO_OK) {
        h = bt_fnv1a_u32(h, mesh->num_points);
        h = bt_fnv1a_u32(h, mesh->num_faces);
        h = hash_u32s(h, mesh->faces, (size_t)mesh->num_faces * 3u);
        h = bt_fnv1a_u32(h, mesh->num_attributes);
        for (i = 0; i < mesh->num_attributes; i++)
            h = hash_attribute(h, &mesh->attributes[i], mesh->num_points);
        /* not mesh.arena_bytes: it counts pointer-holding structs, whose
         * size differs between 32- and 64-bit targets */
    }
    *hash = h;
    if (*st != LUMO_OK)
        return 0;
    if (lumo_draco_arena_need_ex(g_input, len, flags, &need) != LUMO_OK ||
        mesh->arena_bytes + mesh->work_bytes > need.bytes ||
        (need.exact && mesh->arena_bytes + mesh->work_bytes != need.bytes)) {
        con_str("golden_draco: arena need before decoding is wrong: ");
        con_u64(need.bytes);
        con_nl();
        return 1;
    }
    return 0;
}

/* Both modes; LUMO_DRACO_LEAN must decode the very same mesh. */
static int decode_one(const char *path)
{
    size_t len = 0, lean_arena;
    lumo_draco_mesh mesh;
    lumo_status st, lean_st;
    char label[96], lean_label[96];
    uint64_t h, lean_h;

    golden_label("draco.", path, label, sizeof label);
    golden_label("draco-lean.", path, lean_label, sizeof lean_label);
    if (board_read_file(path, g_input, sizeof g_input, &len) != 0) {
        con_str("golden_draco: cannot read ");
        con_str(path);
        con_nl();
        return 1;
    }
    if (decode_mode(lean_label, len, LUMO_DRACO_LEAN, &mesh, &lean_st, &lean_h))
        return 1;
    lean_arena = mesh.arena_bytes + mesh.work_bytes;
    if (decode_mode(label, len, 0, &mesh, &st, &h))
        return 1;
    golden_hash(label, h);
    con_str(label);
    if (lean_st != st || lean_h != h) {
        con_str(": the lean mode decodes differently");
        con_nl();
        return 1;
    }
    if (st != LUMO_OK) {
        con_str(": ");
        con_str(lumo_strerror(st));
        con_nl();
        return 0;
    }
    con_str(": ");
    con_u64(mesh.num_points);
    con_str(" points, ");
    con_u64(mesh.num_faces);
    con_str(" faces, ");
    con_u64(mesh.num_attributes);
    con_str(" attributes, arena ");
    con_u64(mesh.arena_bytes + mesh.work_bytes);
    con_str(" (lean ");
    con_u64(lean_arena);
    con_str(")");
    con_nl();
    return 0;
}

int main(void)
{
    return golden_done(golden_each_path(LIST_PATH, decode_one));
}
