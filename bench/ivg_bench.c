/*
 * ivg_bench.c — cost of the IVG client core on the host (seed 000 §4.1,
 * Figure 7): push-pull with and without smoothing on N^3 grids with a share
 * of the vertices received, and shading cost per point.
 *
 *   lumo-bench-ivg time                 table of median host times (all cases)
 *   lumo-bench-ivg pushpull N PCT FLAGS one push-pull, for callgrind
 *                                       (--toggle-collect=lumo_ivg_pushpull)
 *   lumo-bench-ivg sample COUNT MODE    COUNT shaded points, for callgrind
 *                                       (--toggle-collect=lumo_ivg_irradiance);
 *                                       MODE: see make_samples()
 *
 * Inputs are deterministic (fixed PRNG seed): the received vertices are a
 * random PCT% of the grid, sent as one quantized bundle written by the
 * server's encoder, as a client would get them.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <time.h>
#include "lumo/ivg.h"
#include "lumo_host/options.h"
#include "package/ivg_encode.h"

static uint64_t g_rng = 0x9E3779B97F4A7C15ull;

static uint64_t rnd(void)
{
    g_rng ^= g_rng >> 12;
    g_rng ^= g_rng << 25;
    g_rng ^= g_rng >> 27;
    return g_rng * 2685821657736338717ull;
}

static double rnd_unit(void)
{
    return (double)(rnd() >> 11) / 9007199254740992.0;
}

static double now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e9 + ts.tv_nsec;
}

typedef struct bgrid {
    void     *mem;
    lumo_ivg *g;
} bgrid;

static void random_fentry(srv_ivg_fentry *e)
{
    double v[3], len;
    int k;
    do {
        for (k = 0, len = 0; k < 3; k++) {
            v[k] = 2 * rnd_unit() - 1;
            len += v[k] * v[k];
        }
    } while (len < 0.01 || len > 1);
    for (k = 0; k < 3; k++) {
        e->d[k] = (float)(v[k] / sqrt(len));
        e->c[k] = (float)(100 * rnd_unit());
    }
}

/* An N^3 grid over [0, 8]^3 with `pct` % of its vertices received. */
static int make_grid(bgrid *b, unsigned n, unsigned pct)
{
    lumo_ivg_desc d = {{(uint16_t)n, (uint16_t)n, (uint16_t)n}, {0, 0, 0},
                       {LUMO_Q16_FROM_INT(8), LUMO_Q16_FROM_INT(8), LUMO_Q16_FROM_INT(8)}};
    size_t need = lumo_ivg_memory_size(&d), cap;
    uint32_t count = n * n * n, v, sent = 0;
    srv_ivg_writer w;
    lumo_arena a;
    uint8_t *buf;
    lumo_status st;

    b->mem = malloc(need);
    cap = srv_ivg_bundle_bytes(LUMO_IVG_FORM_QUANTIZED, count, 0);
    buf = malloc(cap);
    if (b->mem == NULL || buf == NULL)
        return -1;
    lumo_arena_init(&a, b->mem, need);
    if (lumo_ivg_create(&b->g, &a, &d) != LUMO_OK)
        return -1;
    srv_ivg_writer_begin(&w, buf, cap, LUMO_IVG_FORM_QUANTIZED, d.dims);
    for (v = 0; v < count; v++) {
        srv_ivg_fentry e[LUMO_IVG_AXES];
        int k;
        if (rnd() % 1000u >= pct * 10u)
            continue;
        for (k = 0; k < LUMO_IVG_AXES; k++)
            random_fentry(&e[k]);
        srv_ivg_writer_add(&w, v, e);
        sent++;
    }
    st = lumo_ivg_apply_bundle(b->g, buf, srv_ivg_writer_finish(&w), NULL);
    free(buf);
    if (st != LUMO_OK || sent == 0) {
        fprintf(stderr, "bundle: %s\n", lumo_strerror(st));
        return -1;
    }
    return 0;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Median wall times of `runs` push-pulls without and with smoothing, in
 * milliseconds. The two kinds alternate so that load from other processes
 * on a shared host hits both alike. */
static void time_pushpull(lumo_ivg *g, int runs, double *plain, double *smooth)
{
    double t[2][64];
    int r, f;
    for (r = 0; r < runs; r++) {
        for (f = 0; f < 2; f++) {
            double t0 = now_ns();
            lumo_ivg_pushpull(g, f ? LUMO_IVG_SMOOTH : 0);
            t[f][r] = (now_ns() - t0) / 1e6;
        }
    }
    for (f = 0; f < 2; f++)
        qsort(t[f], (size_t)runs, sizeof t[f][0], cmp_double);
    *plain = t[0][runs / 2];
    *smooth = t[1][runs / 2];
}

typedef struct sample_set {
    lumo_q16_16 (*p)[3];
    lumo_q1_14 (*n)[3];
    int count;
} sample_set;

/* Shading points. SAMPLE_RANDOM: anywhere in the box, in random order
 * (cache-hostile); SAMPLE_RASTER: a plane through the box scanned row by
 * row like a rasterizer's pixels; SAMPLE_RASTER_AXIS: the same with normals
 * along an axis (walls of a Cornell box: one hemisphere instead of three). */
enum { SAMPLE_RANDOM, SAMPLE_RASTER, SAMPLE_RASTER_AXIS, SAMPLE_MODES };
static const char *const k_sample_names[SAMPLE_MODES] = {
    "random points, random normals", "raster-order points, random normals",
    "raster-order points, axis-aligned normals"};

static void make_samples(sample_set *s, int count, int mode)
{
    int i, k, side = (int)sqrt((double)count);
    s->count = count;
    s->p = malloc(sizeof *s->p * (size_t)count);
    s->n = malloc(sizeof *s->n * (size_t)count);
    for (i = 0; i < count; i++) {
        srv_ivg_fentry e;
        random_fentry(&e);
        for (k = 0; k < 3; k++)
            s->n[i][k] = mode == SAMPLE_RASTER_AXIS ? 0 : (lumo_q1_14)lround(e.d[k] * 16384);
        if (mode == SAMPLE_RASTER_AXIS)
            s->n[i][rnd() % 3] = (lumo_q1_14)(rnd() & 1 ? 16384 : -16384);
        if (mode == SAMPLE_RANDOM) {
            for (k = 0; k < 3; k++)
                s->p[i][k] = (lumo_q16_16)(rnd_unit() * 8 * 65536);
        } else {   /* a tilted plane, scanned in rows */
            double u = (double)(i % side) / side, v = (double)(i / side % side) / side;
            s->p[i][0] = (lumo_q16_16)(u * 8 * 65536);
            s->p[i][1] = (lumo_q16_16)(v * 8 * 65536);
            s->p[i][2] = (lumo_q16_16)((1 + 3 * u + 2 * v) * 65536);
        }
    }
}

static uint32_t shade_all(lumo_ivg *g, const sample_set *s)
{
    uint32_t acc = 0;
    int i;
    for (i = 0; i < s->count; i++) {
        lumo_uq16_16 out[3];
        lumo_ivg_irradiance(g, s->p[i], s->n[i], out);
        acc += out[0] ^ out[1] ^ out[2];
    }
    return acc;
}

static int run_time(void)
{
    static const unsigned sizes[3] = {16, 32, 64}, pcts[3] = {10, 25, 50};
    int si, pi;
    for (si = 0; si < 3; si++) {
        int runs = sizes[si] == 16 ? 41 : sizes[si] == 32 ? 21 : 9;
        for (pi = 0; pi < 3; pi++) {
            bgrid b;
            double plain, smooth;
            if (make_grid(&b, sizes[si], pcts[pi]))
                return 1;
            lumo_ivg_pushpull(b.g, LUMO_IVG_SMOOTH);   /* warm the caches */
            time_pushpull(b.g, runs, &plain, &smooth);
            printf("pushpull %u %u %d %.4f %.4f\n", sizes[si], pcts[pi], runs, plain, smooth);
            free(b.mem);
        }
    }
    {
        bgrid b;
        int mode;
        if (make_grid(&b, 32, 25))
            return 1;
        lumo_ivg_pushpull(b.g, LUMO_IVG_SMOOTH);
        for (mode = 0; mode < SAMPLE_MODES; mode++) {
            sample_set s;
            double t[9];
            int r;
            uint32_t sink = 0;
            make_samples(&s, 250000, mode);
            for (r = 0; r < 9; r++) {
                double t0 = now_ns();
                sink += shade_all(b.g, &s);
                t[r] = (now_ns() - t0) / s.count;
            }
            qsort(t, 9, sizeof t[0], cmp_double);
            printf("sample %d %.2f %u %s\n", mode, t[4], sink & 1u, k_sample_names[mode]);
            free(s.p);
            free(s.n);
        }
        free(b.mem);
    }
    return 0;
}

int main(int argc, char **argv)
{
    if (argc >= 2 && strcmp(argv[1], "time") == 0)
        return run_time();
    char why[160];
    if (argc == 5 && strcmp(argv[1], "pushpull") == 0) {
        bgrid b;
        uint32_t n, pct, flags;
        if (host_opt_u32("N", argv[2], 2, 256, &n, why, sizeof why) ||
            host_opt_u32("PCT", argv[3], 0, 100, &pct, why, sizeof why) ||
            host_opt_u32("FLAGS", argv[4], 0, 0xffff, &flags, why, sizeof why))
            return fprintf(stderr, "lumo-bench-ivg pushpull: error: %s\n", why), 2;
        if (make_grid(&b, n, pct))
            return 1;
        lumo_ivg_pushpull(b.g, flags);
        free(b.mem);
        return 0;
    }
    if (argc == 4 && strcmp(argv[1], "sample") == 0) {
        bgrid b;
        sample_set s;
        if (make_grid(&b, 32, 25))
            return 1;
        lumo_ivg_pushpull(b.g, LUMO_IVG_SMOOTH);
        int count, mode;
        if (host_opt_int("COUNT", argv[2], 1, 1 << 24, &count, why, sizeof why) ||
            host_opt_int("MODE", argv[3], 0, SAMPLE_MODES - 1, &mode, why, sizeof why)) {
            free(b.mem);
            return fprintf(stderr, "lumo-bench-ivg sample: error: %s\n", why), 2;
        }
        make_samples(&s, count, mode);
        printf("%u\n", shade_all(b.g, &s) & 1u);
        free(b.mem);
        return 0;
    }
    fprintf(stderr, "usage: %s time | pushpull N PCT FLAGS | sample COUNT MODE\n", argv[0]);
    return 2;
}
