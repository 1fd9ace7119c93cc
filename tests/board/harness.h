/*
 * harness.h — a minimal assertion harness for board test programs.
 *
 * A board test is one C99 program under the client rules (no heap, no float,
 * no stdio) that runs on the host and under QEMU alike:
 *
 *     static void test_mul(void) { BT_EQ(lumo_q16_mul(a, b), 123); }
 *     int main(void)
 *     {
 *         BT_RUN(test_mul);
 *         return bt_finish();
 *     }
 *
 * Each BT_RUN is one test; it fails when any check inside it fails (checks
 * keep running, so one failing vector does not hide the others). bt_finish
 * prints "RESULT: N passed, M failed" and returns the exit status.
 */
#ifndef LUMO_BOARD_HARNESS_H
#define LUMO_BOARD_HARNESS_H

#include <stdint.h>
#include "console.h"

/* Record a check; on failure print where and why. Returns ok. */
int bt_check(int ok, const char *file, int line, const char *expr);
int bt_check_eq(int64_t got, int64_t want, const char *file, int line, const char *expr);
int bt_check_near(int64_t got, int64_t want, int64_t tol, const char *file, int line,
                  const char *expr);
void bt_run(const char *name, void (*fn)(void));
/* Print the totals; returns 0 when every test passed, 1 otherwise. */
int bt_finish(void);

#define BT_CHECK(cond) bt_check((cond) != 0, __FILE__, __LINE__, #cond)
#define BT_EQ(got, want) bt_check_eq((int64_t)(got), (int64_t)(want), __FILE__, __LINE__, #got)
#define BT_NEAR(got, want, tol) \
    bt_check_near((int64_t)(got), (int64_t)(want), (int64_t)(tol), __FILE__, __LINE__, #got)
#define BT_RUN(fn) bt_run(#fn, fn)

/* 64-bit FNV-1a, for hashing outputs that must match across targets. */
#define BT_FNV_OFFSET 0xcbf29ce484222325ull
uint64_t bt_fnv1a(uint64_t h, const void *data, uint32_t n);
/* Hash a 32-bit value as 4 little-endian bytes (independent of host order). */
uint64_t bt_fnv1a_u32(uint64_t h, uint32_t v);

/* Deterministic PRNG (xorshift64*, the same sequence as tests/include). */
typedef struct { uint64_t s; } bt_rng;
uint64_t bt_rng_next(bt_rng *r);

#endif
