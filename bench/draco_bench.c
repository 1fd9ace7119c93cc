/*
 * draco_bench — time lumo's Draco decoder on one file.
 *
 *   draco-bench FILE.drc REPS [lean]
 *
 * `lean`: decode with LUMO_DRACO_LEAN (and its arena need).
 * Prints one line: "lumo ns=<best ns per decode> out=<output bytes>
 * arena=<exact arena bytes> need=<figure before decoding> exact=<0|1>
 * faces=<n> points=<n>". The arena is sized from lumo_draco_arena_need()
 * (computed before decoding, not timed); the reported arena is the
 * decode's exact peak.
 * Under callgrind run with REPS=1 and --toggle-collect=lumo_draco_decode.
 */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "lumo/draco.h"
#include "lumo_host/options.h"

static uint64_t now_ns(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (uint64_t)t.tv_sec * 1000000000u + (uint64_t)t.tv_nsec;
}

int main(int argc, char **argv)
{
    FILE *f;
    uint8_t *data, *mem;
    long size;
    int reps, i;
    char why[160];
    unsigned flags;
    uint64_t best = UINT64_MAX;
    lumo_draco_need need;
    lumo_draco_mesh m;
    size_t bytes;
    if (argc != 3 && argc != 4) {
        fprintf(stderr, "usage: draco-bench FILE.drc REPS [lean]\n");
        return 2;
    }
    if (!(f = fopen(argv[1], "rb"))) {
        fprintf(stderr, "draco-bench: error: %s: cannot open\n", argv[1]);
        return 2;
    }
    flags = argc == 4 && !strcmp(argv[3], "lean") ? LUMO_DRACO_LEAN : 0u;
    if (host_opt_int("REPS", argv[2], 1, 1000000, &reps, why, sizeof why)) {
        fprintf(stderr, "draco-bench: error: %s\n", why);
        return 2;
    }
    fseek(f, 0, SEEK_END);
    size = ftell(f);
    fseek(f, 0, SEEK_SET);
    data = malloc((size_t)size);
    if (!data || fread(data, 1, (size_t)size, f) != (size_t)size)
        return 1;
    fclose(f);
    if (lumo_draco_arena_need_ex(data, (size_t)size, flags, &need))
        return 1;
    bytes = need.bytes;
    mem = malloc(bytes);
    if (!mem)
        return 1;
    for (i = 0; i < reps; ++i) {
        lumo_arena a;
        uint64_t t0;
        lumo_status st;
        lumo_arena_init(&a, mem, bytes);
        t0 = now_ns();
        st = lumo_draco_decode_ex(data, (size_t)size, flags, &a, &m);
        t0 = now_ns() - t0;
        if (st) {
            fprintf(stderr, "draco-bench: %s\n", lumo_strerror(st));
            return 1;
        }
        if (t0 < best)
            best = t0;
    }
    printf("lumo ns=%llu out=%zu arena=%zu need=%zu exact=%u faces=%u points=%u\n",
           (unsigned long long)best, m.arena_bytes, m.arena_bytes + m.work_bytes, need.bytes,
           need.exact, m.num_faces, m.num_points);
    free(mem);
    free(data);
    return 0;
}
