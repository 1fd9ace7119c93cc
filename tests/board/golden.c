/* golden.c — output of the golden programs (see golden.h). */
#include "board_io.h"
#include "console.h"
#include "golden.h"

void golden_hash(const char *label, uint64_t h)
{
    con_str("HASH ");
    con_str(label);
    con_str(" ");
    con_hex(h, 16);
    con_nl();
}

void golden_cost(const char *label, uint32_t t0)
{
    uint32_t hz = board_tick_hz(), ticks = board_ticks() - t0;

    if (hz == 0)
        return;
    con_str("COST ");
    con_str(label);
    con_str(" ");
    /* 1e9 ns per second / hz = ns per tick = instructions per tick */
    con_u64((uint64_t)ticks * (1000000000u / hz));
    con_str(" instructions");
    con_nl();
}

int golden_done(int rc)
{
    size_t stack = board_stack_peak();

    if (stack != 0) {
        con_str("stack peak: ");
        con_u64(stack);
        con_str(" bytes");
        con_nl();
    }
    return rc;
}
