/*
 * vsl_bench.c — make bench-vsl (docs/benchmarks.md "Dynamic scenes"): the
 * dynamic engine's pieces against their peers, in one run, as ratios:
 *  - Algorithm 1 (seed 004 §0.4.2, srv_vsl_thin) against the naive removal
 *    the paper compares it with (every pair's distance for every removal);
 *  - the nearest VSL by k-d tree (vsl_index.h) against a linear scan;
 *  - rays through the instanced scene (one Embree instance per object,
 *    vsl_rt.h: what a moved object costs nothing to rebuild) against the
 *    flat scene the bake uses (bake/rt.h), the same rays;
 *  - the engine's photon paths and impacts per second on the demo scene.
 * Usage: lumo-bench-vsl SCENE.txt
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "bake/rt.h"
#include "common/rng.h"
#include "common/sample.h"
#include "scene/import.h"
#include "vsl/vsl_engine.h"

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void bench_thin(void)
{
    printf("\n| N_v (candidates +10%%) | Algorithm 1 | naive removal | naive / Algorithm 1 | same survivors |\n");
    printf("|---|---|---|---|---|\n");
    for (size_t nv = 250; nv <= 1000; nv *= 2) {
        size_t n = nv + nv / 10;
        vec3 *p = malloc(n * sizeof *p);
        uint8_t *a = malloc(n), *b = malloc(n);
        srv_rng r;
        srv_rng_seed(&r, 1, nv);
        for (size_t i = 0; i < n; i++)
            p[i] = v3(srv_rng_float(&r), srv_rng_float(&r), srv_rng_float(&r));
        double t0 = now_s();
        srv_vsl_thin(p, NULL, n, nv, a);
        double t1 = now_s();
        srv_vsl_thin_naive(p, NULL, n, nv, b);
        double t2 = now_s();
        printf("| %zu (%zu) | %.2f ms | %.2f ms | %.0f | %s |\n", nv, n, 1e3 * (t1 - t0), 1e3 * (t2 - t1),
               (t2 - t1) / (t1 - t0), memcmp(a, b, n) ? "no" : "yes");
        free(p), free(a), free(b);
    }
}

/* A photon impact on object o: near one of its VSLs, within a few VSL
 * spacings (the queries Algorithm 2 makes: points on the surface). */
static vec3 impact(const srv_vsl_set *set, uint32_t o, srv_rng *r)
{
    const srv_vsl *v = &set->v[set->first[o] + srv_rng_u32(r) % set->count[o]];
    float k = 3.0f * sqrtf(v->area);
    return v3_add(v->pos, v3(k * (srv_rng_float(r) - 0.5f), k * (srv_rng_float(r) - 0.5f), k * (srv_rng_float(r) - 0.5f)));
}

static void bench_nearest(const srv_scene *s)
{
    printf("\n| VSLs (a wall holds 1/6) | queries | srv_vsl_index_nearest (scan below 256 a object, else k-d tree) | linear scan | scan / index |\n|---|---|---|---|---|\n");
    for (size_t nv = 100; nv <= 10000; nv *= 10) {
        srv_vsl_set set;
        srv_vsl_index ix;
        char err[160];
        srv_vsl_place_opts o = srv_vsl_place_defaults(nv, 1);
        if (srv_vsl_place(s, &o, &set, err, sizeof err) || srv_vsl_index_build(&ix, &set))
            return;
        enum { Q = 200000 };
        srv_rng r;
        srv_rng_seed(&r, 2, nv);
        uint64_t sum_a = 0, sum_b = 0;
        double t0 = now_s();
        for (int q = 0; q < Q; q++) {
            vec3 p = impact(&set, (uint32_t)(q % 6), &r);
            sum_a += srv_vsl_index_nearest(&ix, (uint32_t)(q % 6), p);
        }
        double t1 = now_s();
        srv_rng_seed(&r, 2, nv);
        for (int q = 0; q < Q; q++) {
            vec3 p = impact(&set, (uint32_t)(q % 6), &r);
            uint32_t ob = (uint32_t)(q % 6), best = 0;
            float bd = INFINITY;
            for (uint32_t i = set.first[ob]; i < set.first[ob] + set.count[ob]; i++) {
                vec3 d = v3_sub(p, set.v[i].pos);
                if (v3_dot(d, d) < bd)
                    bd = v3_dot(d, d), best = i;
            }
            sum_b += best;
        }
        double t2 = now_s();
        printf("| %zu | %d | %.1f ns | %.1f ns | %.1f%s |\n", nv, Q, 1e9 * (t1 - t0) / Q, 1e9 * (t2 - t1) / Q,
               (t2 - t1) / (t1 - t0), sum_a == sum_b ? "" : " (DIFFER)");
        srv_vsl_index_free(&ix);
        srv_vsl_set_free(&set);
    }
}

static void bench_rays(const srv_scene *s)
{
    char err[160];
    srv_rt *flat = srv_rt_create(s, 1, err, sizeof err);
    srv_vsl_rt *inst = srv_vsl_rt_create(s, err, sizeof err);
    if (!flat || !inst)
        return;
    enum { R = 1000000 };
    srv_rng r;
    srv_hit h;
    srv_vsl_hit g;
    uint64_t ha = 0, hb = 0;
    double t[2];
    for (int k = 0; k < 2; k++) {
        srv_rng_seed(&r, 3, 0);
        double t0 = now_s();
        for (int i = 0; i < R; i++) {
            vec3 o = v3(1.6f * srv_rng_float(&r) - 0.8f, 0.1f + 1.8f * srv_rng_float(&r), 1.6f * srv_rng_float(&r) - 0.8f);
            vec3 d = srv_cone_dir(v3(0, 1, 0), -1.0f, &r);
            if (k == 0)
                ha += (uint64_t)srv_rt_intersect(flat, o, d, 0, INFINITY, &h);
            else
                hb += (uint64_t)srv_vsl_rt_intersect(inst, o, d, 0, INFINITY, &g);
        }
        t[k] = now_s() - t0;
    }
    printf("\n| rays | flat scene (the bake's) | one instance per object | instanced / flat time | hits |\n");
    printf("|---|---|---|---|---|\n| %d | %.2f Mrays/s | %.2f Mrays/s | %.2f | %llu / %llu |\n", R, R / t[0] / 1e6,
           R / t[1] / 1e6, t[1] / t[0], (unsigned long long)ha, (unsigned long long)hb);
    srv_rt_free(flat);
    srv_vsl_rt_free(inst);
}

static void bench_engine(const srv_scene *s, const srv_motion *m)
{
    char err[160];
    srv_vsl_engine_opts o = srv_vsl_engine_defaults();
    o.dims[0] = o.dims[1] = o.dims[2] = 12;
    srv_vsl_engine *e = srv_vsl_engine_create(s, m, &o, err, sizeof err);
    if (!e)
        return;
    double t0 = now_s();
    int steps = 20;
    for (int k = 0; k < steps; k++)
        srv_vsl_engine_step(e, 0.3 * k);
    double dt = now_s() - t0;
    const srv_photon_tracer *pt = srv_vsl_engine_tracer(e);
    const srv_vsl_ivg *g = srv_vsl_engine_ivg(e);
    printf("\n| engine (400 VSLs, pool 200 000, 12^3 grid, moving light and sphere) | value |\n|---|---|\n");
    printf("| photon paths per second (one thread) | %.0f |\n| impacts per second | %.0f |\n",
           (double)pt->emitted / dt, (double)pt->pool->impacts / dt);
    printf("| step (20 000 paths, VSL states, IVG update) | %.1f ms |\n", 1e3 * dt / steps);
    printf("| VSL republications per step | %.0f of 400 |\n| vertex terms per step | %.0f |\n",
           (double)g->republished / steps, (double)g->touched / steps);
    srv_vsl_engine_free(e);
}

int main(int argc, char **argv)
{
    srv_scene s;
    srv_motion m = {0};
    char err[400];
    if (argc != 2)
        return fprintf(stderr, "usage: lumo-bench-vsl SCENE.txt\n"), 2;
    srv_scene_init(&s);
    if (srv_scene_load(&s, argv[1], err, sizeof err) || srv_motion_load(&m, &s, argv[1], err, sizeof err))
        return fprintf(stderr, "lumo-bench-vsl: %s\n", err), 1;
    printf("lumo-bench-vsl %s (one thread; wall clock on a shared machine)\n", argv[1]);
    bench_thin();
    bench_nearest(&s);
    bench_rays(&s);
    bench_engine(&s, &m);
    srv_scene_free(&s);
    return 0;
}
