/* fact_ticks.c — a fixed integer workload timed with board_ticks(). Under
 * `-icount shift=0` the printed count must be the same on every run, and
 * ticks * (1e9 / tick_hz) must approximate the executed instructions. */
#include <stdint.h>
#include "board.h"
#include "console.h"

int main(void);

static volatile uint32_t g_sink;

int main(void)
{
    uint32_t t0, t1, i, acc = 1;

    t0 = board_ticks();
    for (i = 0; i < 1000000u; i++)   /* ~4-5 instructions per iteration */
        acc = acc * 1664525u + 1013904223u;
    t1 = board_ticks();
    g_sink = acc;
    con_str("TICKS ");
    con_u64(t1 - t0);
    con_str(" HZ ");
    con_u64(board_tick_hz());
    con_nl();
    return 0;
}
