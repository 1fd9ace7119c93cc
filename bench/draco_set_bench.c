/*
 * draco_set_bench — lumo's Draco decoder on many files in one process, for
 * the attribute benchmark set (bench/draco_attrs.sh, issue 25).
 *
 *   draco-set-bench [lean] FILE.drc...
 *
 * Per file one line: "<file> out=<output bytes> arena=<exact arena bytes>
 * need=<figure before decoding> exact=<0|1> faces=<n> points=<n>". Each
 * decode runs in an arena of lumo_draco_arena_need_ex() bytes, computed
 * before it. Under `valgrind --tool=callgrind --collect-atstart=no` only
 * the decode call is counted and the counts are dumped per file
 * (CALLGRIND_DUMP_STATS_AT with the file name): the same figure as
 * --toggle-collect=lumo_draco_decode_ex, without one valgrind start per
 * file. Run natively the requests do nothing.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <valgrind/callgrind.h>
#include "lumo/draco.h"

static uint8_t *read_all(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    uint8_t *data = NULL;
    long n;
    if (!f)
        return NULL;
    if (fseek(f, 0, SEEK_END) == 0 && (n = ftell(f)) > 0 && fseek(f, 0, SEEK_SET) == 0 &&
        (data = malloc((size_t)n)) && fread(data, 1, (size_t)n, f) != (size_t)n) {
        free(data);
        data = NULL;
    }
    if (data)
        *size = (size_t)n;
    fclose(f);
    return data;
}

static int bench_file(const char *path, unsigned flags)
{
    size_t size;
    uint8_t *data = read_all(path, &size), *mem;
    lumo_draco_need need;
    lumo_draco_mesh m;
    lumo_arena a;
    lumo_status st;
    if (!data || lumo_draco_arena_need_ex(data, size, flags, &need) || !(mem = malloc(need.bytes))) {
        fprintf(stderr, "draco-set-bench: %s: cannot read or size\n", path);
        return 1;
    }
    lumo_arena_init(&a, mem, need.bytes);
    CALLGRIND_TOGGLE_COLLECT;
    st = lumo_draco_decode_ex(data, size, flags, &a, &m);
    CALLGRIND_TOGGLE_COLLECT;
    CALLGRIND_DUMP_STATS_AT(path);
    if (st) {
        fprintf(stderr, "draco-set-bench: %s: %s\n", path, lumo_strerror(st));
        return 1;
    }
    printf("%s out=%zu arena=%zu need=%zu exact=%u faces=%u points=%u\n", path, m.arena_bytes,
           m.arena_bytes + m.work_bytes, need.bytes, need.exact, m.num_faces, m.num_points);
    free(mem);
    free(data);
    return 0;
}

int main(int argc, char **argv)
{
    unsigned flags = 0;
    int i = 1, bad = 0;
    if (argc > 1 && !strcmp(argv[1], "lean")) {
        flags = LUMO_DRACO_LEAN;
        ++i;
    }
    if (i >= argc) {
        fprintf(stderr, "usage: draco-set-bench [lean] FILE.drc...\n");
        return 2;
    }
    for (; i < argc; ++i)
        bad |= bench_file(argv[i], flags);
    return bad;
}
