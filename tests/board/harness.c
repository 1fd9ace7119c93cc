/* harness.c — the board test harness (see harness.h). */
#include <stddef.h>
#include "board.h"
#include "harness.h"

static unsigned g_passed, g_failed, g_check_failures, g_test_failures;

/* Failed checks printed per test; the rest are only counted, so a broken
 * loop over thousands of vectors does not flood the log. */
#define MAX_PRINTED 8

/* Count a failed check; 1 when it should be printed. */
static int failed_check(void)
{
    g_check_failures++;
    return ++g_test_failures <= MAX_PRINTED;
}

static void where(const char *file, int line, const char *expr)
{
    con_str("  FAIL ");
    con_str(file);
    con_str(":");
    con_i64(line);
    con_str(": ");
    con_str(expr);
}

int bt_check(int ok, const char *file, int line, const char *expr)
{
    if (ok)
        return 1;
    if (!failed_check())
        return 0;
    where(file, line, expr);
    con_nl();
    return 0;
}

int bt_check_near(int64_t got, int64_t want, int64_t tol, const char *file, int line,
                  const char *expr)
{
    int64_t diff = got > want ? got - want : want - got;

    if (diff <= tol && diff >= 0)
        return 1;
    if (!failed_check())
        return 0;
    where(file, line, expr);
    con_str(" = ");
    con_i64(got);
    con_str(", want ");
    con_i64(want);
    if (tol != 0) {
        con_str(" +- ");
        con_i64(tol);
    }
    con_nl();
    return 0;
}

int bt_check_eq(int64_t got, int64_t want, const char *file, int line, const char *expr)
{
    return bt_check_near(got, want, 0, file, line, expr);
}

void bt_run(const char *name, void (*fn)(void))
{
    unsigned before = g_check_failures;

    g_test_failures = 0;
    fn();
    if (g_check_failures == before) {
        g_passed++;
        return;
    }
    g_failed++;
    con_str("FAILED ");
    con_str(name);
    con_str(" (");
    con_u64(g_check_failures - before);
    con_str(" failed checks)");
    con_nl();
}

int bt_finish(void)
{
    size_t stack = board_stack_peak();

    if (stack != 0) {
        con_str("stack peak: ");
        con_u64(stack);
        con_str(" bytes");
        con_nl();
    }
    con_str("RESULT: ");
    con_u64(g_passed);
    con_str(" passed, ");
    con_u64(g_failed);
    con_str(" failed");
    con_nl();
    return g_failed == 0 && g_passed > 0 ? 0 : 1;
}

uint64_t bt_fnv1a(uint64_t h, const void *data, uint32_t n)
{
    const uint8_t *p = data;
    uint32_t i;

    for (i = 0; i < n; i++) {
        h ^= p[i];
        h *= 0x100000001b3ull;
    }
    return h;
}

uint64_t bt_fnv1a_u32(uint64_t h, uint32_t v)
{
    uint8_t b[4];

    b[0] = (uint8_t)v;
    b[1] = (uint8_t)(v >> 8);
    b[2] = (uint8_t)(v >> 16);
    b[3] = (uint8_t)(v >> 24);
    return bt_fnv1a(h, b, 4);
}

uint64_t bt_rng_next(bt_rng *r)
{
    r->s ^= r->s >> 12;
    r->s ^= r->s << 25;
    r->s ^= r->s >> 27;
    return r->s * 2685821657736338717ull;
}
