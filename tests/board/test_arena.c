/*
 * test_arena.c — lumo/arena.h on the board, where size_t is 32 bits: the
 * overflow guards must hold at 2^32, allocation from an odd start must stay
 * 8-aligned, a failure must leave the arena unchanged, and a large arena in
 * the board's scratch memory (PSRAM on mps2-an385) must work end to end.
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include "lumo/arena.h"
#include "board.h"
#include "harness.h"

static uint8_t g_buf[256];

static void test_alignment_and_zeroing(void)
{
    lumo_arena a;
    uint8_t *p, *q;

    memset(g_buf, 0xAB, sizeof g_buf);
    BT_EQ(lumo_arena_init(&a, g_buf + 3, 200), LUMO_OK);
    p = lumo_arena_alloc(&a, 5);
    q = lumo_arena_alloc(&a, 1);
    BT_CHECK(p != NULL && q != NULL);
    if (p == NULL || q == NULL)
        return;
    BT_EQ((uintptr_t)p % LUMO_ARENA_ALIGN, 0);
    BT_EQ((uintptr_t)q % LUMO_ARENA_ALIGN, 0);
    BT_EQ(q - p, 8);
    BT_EQ(p[0], 0);
    BT_EQ(p[7], 0);
    BT_CHECK(a.size >= 200 - LUMO_ARENA_SLACK);
}

static void test_exhaustion_leaves_arena_unchanged(void)
{
    lumo_arena a;
    size_t used;

    lumo_arena_init(&a, g_buf, 64);
    BT_CHECK(lumo_arena_alloc(&a, 40) != NULL);
    used = a.used;
    BT_CHECK(lumo_arena_alloc(&a, 40) == NULL);
    BT_EQ(a.used, used);
    BT_CHECK(lumo_arena_alloc_array(&a, SIZE_MAX / 2, 4) == NULL);
    BT_CHECK(lumo_arena_alloc(&a, SIZE_MAX) == NULL);
    BT_EQ(a.used, used);
    /* g_buf is only byte-aligned: on the Cortex-M3 it lands 4 bytes off
     * an 8-byte boundary, so count from the arena's usable size. */
    BT_CHECK(a.size >= 64 - LUMO_ARENA_SLACK);
    BT_EQ(lumo_arena_remaining(&a), a.size - 40);
}

/* The guards at this target's SIZE_MAX (2^32 - 1 on the Cortex-M3). */
static void test_size_overflow(void)
{
    BT_EQ(lumo_size_mul((size_t)1 << (sizeof(size_t) * 4), (size_t)1 << (sizeof(size_t) * 4)),
          (uint64_t)SIZE_MAX);
    BT_EQ(lumo_size_mul(SIZE_MAX / 3, 3), (uint64_t)(SIZE_MAX / 3 * 3));
    BT_EQ(lumo_size_add(SIZE_MAX - 1, 2), (uint64_t)SIZE_MAX);
    BT_EQ(lumo_arena_round(SIZE_MAX - 3), (uint64_t)SIZE_MAX);
    BT_EQ(lumo_arena_round(9), 16);
    BT_EQ(lumo_arena_round(0), 0);
}

static void test_mark_reset_peak(void)
{
    lumo_arena a;
    lumo_arena_mark m;

    lumo_arena_init(&a, g_buf, 128);
    BT_CHECK(lumo_arena_alloc(&a, 16) != NULL);
    m = lumo_arena_get_mark(&a);
    BT_CHECK(lumo_arena_alloc(&a, 64) != NULL);
    lumo_arena_reset(&a, m);
    BT_EQ(a.used, 16);
    BT_EQ(a.peak, 80);
    lumo_arena_reset(&a, 1000);   /* beyond the fill level: ignored */
    BT_EQ(a.used, 16);
}

/* A 12 MiB arena in scratch memory: fill two big blocks with a pattern and
 * read it back, so the memory map behind board_scratch() is real RAM. */
static void test_big_scratch_arena(void)
{
    size_t bytes = 0, i;
    uint8_t *mem = board_scratch(&bytes);
    lumo_arena a;
    uint32_t *x, *y;
    const size_t words = (6u << 20) / 4;
    uint32_t bad = 0;

    BT_CHECK(bytes >= (12u << 20) + 64);
    BT_EQ(lumo_arena_init(&a, mem, bytes), LUMO_OK);
    x = lumo_arena_alloc_array(&a, words, 4);
    y = lumo_arena_alloc_array(&a, words, 4);
    BT_CHECK(x != NULL && y != NULL);
    if (x == NULL || y == NULL)
        return;
    BT_EQ(x[words - 1], 0);       /* zero-filled by the arena */
    for (i = 0; i < words; i += 1021) {
        x[i] = (uint32_t)i * 2654435761u;
        y[i] = ~x[i];
    }
    for (i = 0; i < words; i += 1021)
        bad += x[i] != (uint32_t)i * 2654435761u || y[i] != ~x[i];
    BT_EQ(bad, 0);
    BT_CHECK(lumo_arena_alloc(&a, bytes) == NULL);
}

int main(void)
{
    BT_RUN(test_alignment_and_zeroing);
    BT_RUN(test_exhaustion_leaves_arena_unchanged);
    BT_RUN(test_size_overflow);
    BT_RUN(test_mark_reset_peak);
    BT_RUN(test_big_scratch_arena);
    return bt_finish();
}
