/* golden.c — output of the golden programs (see golden.h). */
#include <string.h>
#include "board.h"
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

void golden_label(const char *prefix, const char *path, char *out, size_t cap)
{
    const char *base = path, *p;
    size_t np = strlen(prefix), n;

    for (p = path; *p != '\0'; p++)
        if (*p == '/')
            base = p + 1;
    if (cap == 0)
        return;
    np = np < cap - 1 ? np : cap - 1;
    memcpy(out, prefix, np);
    n = strlen(base);
    if (n > cap - 1 - np)
        n = cap - 1 - np;
    memcpy(out + np, base, n);
    out[np + n] = '\0';
}

#define GOLDEN_LIST_MAX 8192u
#define GOLDEN_PATH_MAX 200u

int golden_each_path(const char *list_path, int (*each)(const char *path))
{
    static uint8_t list[GOLDEN_LIST_MAX];
    size_t len = 0, i = 0;
    int failed = 0;

    if (board_read_file(list_path, list, sizeof list - 1, &len) != 0) {
        con_str("cannot read ");
        con_str(list_path);
        con_nl();
        return 1;
    }
    list[len] = '\n';
    while (i < len) {
        char path[GOLDEN_PATH_MAX];
        size_t n = 0;
        while (i < len && list[i] != '\n') {
            if (n < GOLDEN_PATH_MAX - 1)
                path[n++] = (char)list[i];
            i++;
        }
        i++;
        path[n] = '\0';
        if (n > 0)
            failed |= each(path);
    }
    return failed;
}
