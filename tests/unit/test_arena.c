/* test_arena.c — arena allocation, alignment, exhaustion, mark/reset. */
#include "test_common.h"
#include "lumo/arena.h"

static void test_alignment_and_zeroing(void **state)
{
    static uint8_t buf[256];
    lumo_arena a;
    uint8_t *p, *q;
    (void)state;
    memset(buf, 0xAB, sizeof buf);
    assert_int_equal(lumo_arena_init(&a, buf + 3, 200), LUMO_OK);   /* odd start */
    p = lumo_arena_alloc(&a, 5);
    q = lumo_arena_alloc(&a, 1);
    assert_non_null(p);
    assert_non_null(q);
    assert_int_equal((uintptr_t)p % LUMO_ARENA_ALIGN, 0);
    assert_int_equal((uintptr_t)q % LUMO_ARENA_ALIGN, 0);
    assert_int_equal(q - p, 8);
    assert_int_equal(p[4], 0);
    assert_true(a.size >= 200 - LUMO_ARENA_SLACK);
}

static void test_exhaustion_is_clean(void **state)
{
    static uint8_t buf[64];
    lumo_arena a;
    size_t used;
    (void)state;
    lumo_arena_init(&a, buf, sizeof buf);
    assert_non_null(lumo_arena_alloc(&a, 40));
    used = a.used;
    assert_null(lumo_arena_alloc(&a, 40));
    assert_int_equal(a.used, used);           /* failure changes nothing */
    assert_null(lumo_arena_alloc_array(&a, SIZE_MAX / 2, 4));   /* overflow */
    assert_null(lumo_arena_alloc(&a, SIZE_MAX));
    assert_int_equal(lumo_arena_remaining(&a), a.size - 40);   /* size: after aligning buf */
}

static void test_mark_reset_peak(void **state)
{
    static uint8_t buf[128];
    lumo_arena a;
    lumo_arena_mark m;
    (void)state;
    lumo_arena_init(&a, buf, sizeof buf);
    assert_non_null(lumo_arena_alloc(&a, 16));
    m = lumo_arena_get_mark(&a);
    assert_non_null(lumo_arena_alloc(&a, 64));
    lumo_arena_reset(&a, m);
    assert_int_equal(a.used, 16);
    assert_int_equal(a.peak, 80);
    lumo_arena_reset(&a, 1000);   /* a mark beyond the fill level is ignored */
    assert_int_equal(a.used, 16);
}

static void test_size_helpers(void **state)
{
    lumo_arena a;
    (void)state;
    assert_int_equal(lumo_arena_round(0), 0);
    assert_int_equal(lumo_arena_round(1), 8);
    assert_int_equal(lumo_arena_round(SIZE_MAX - 2), SIZE_MAX);
    assert_int_equal(lumo_size_mul(SIZE_MAX, 2), SIZE_MAX);
    assert_int_equal(lumo_size_add(SIZE_MAX, 1), SIZE_MAX);
    assert_int_equal(lumo_arena_init(NULL, NULL, 0), LUMO_ERR_ARG);
    assert_int_equal(lumo_arena_init(&a, NULL, 10), LUMO_ERR_ARG);
    assert_string_equal(lumo_strerror(LUMO_ERR_NOMEM), "arena too small");
    assert_string_equal(lumo_strerror((lumo_status)999), "unknown error");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_alignment_and_zeroing),
        cmocka_unit_test(test_exhaustion_is_clean),
        cmocka_unit_test(test_mark_reset_peak),
        cmocka_unit_test(test_size_helpers),
    };
    return cmocka_run_group_tests_name("arena", tests, NULL, NULL);
}
