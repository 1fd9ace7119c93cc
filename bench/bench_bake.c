/* bench/bench_bake.c — `make bench-bake`: bake time and rays/s for 16^3 and 32^3
 * grids on the default scene and the dragon at several spp with 1 and 2
 * threads, and the reference renderer's mean CIE Lab Delta E between spp
 * levels. Writes the markdown section on stdout (numbers, not pass/fail). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo_host/image_diff.h"
#include "lumo_host/tonemap.h"
#include "bake/bake.h"
#include "scene/import.h"
#include "common/progress.h"
#include "bake/reference.h"
#include "scene/shapes.h"

#define DRAGON48 "build/data/models/dragon_48k.ply"
#define DRAGON203 "build/data/models/dragon_203k.ply"

typedef struct { const char *name; srv_scene s; srv_rt *rt; srv_tracer t; } bench_scene;

static int make_scene(bench_scene *b, const char *name, int dragon_only)
{
    char err[256];
    srv_xform x = srv_xform_identity();
    b->name = name;
    srv_scene_init(&b->s);
    int rc = dragon_only ? srv_import_file(&b->s, DRAGON203, &x, NULL, err, sizeof err)
                         : srv_default_scene(&b->s, DRAGON48, err, sizeof err);
    if (!rc && dragon_only) {
        srv_light l = {.kind = LUMO_LIGHT_POINT, .pos = {0, 0.35f, 0.2f}, .power = {1, 1, 1}};
        rc = srv_scene_add_light(&b->s, &l);
    }
    if (rc || srv_scene_validate(&b->s, err, sizeof err) || !(b->rt = srv_rt_create(&b->s, 2, err, sizeof err))) {
        fprintf(stderr, "bench-bake: %s: %s\n", name, err);
        return -1;
    }
    srv_tracer_init(&b->t, &b->s, b->rt);
    return 0;
}

static void bake_rows(bench_scene *b)
{
    static const int grids[] = {16, 32}, spps[] = {16, 64, 256};
    char err[256];
    for (int gi = 0; gi < 2; gi++)
        for (int si = 0; si < 3; si++) {
            if (grids[gi] == 32 && spps[si] > 64)
                continue;   /* keeps the step within its time budget */
            double t1 = 0.0;
            for (int threads = 1; threads <= 2; threads++) {
                int dims[3] = {grids[gi], grids[gi], grids[gi]};
                srv_grid g = srv_grid_over(&b->s, dims);
                srv_bake_opts o = {spps[si], 1, threads, 0, 0.25f};
                srv_bake_result r;
                if (srv_bake(&b->t, &g, &o, &r, err, sizeof err))
                    continue;
                if (threads == 1)
                    t1 = r.seconds;
                printf("| %s | %zu | %d³ | %d | %d | %.2f | %.2f | %.2f | %s |\n", b->name,
                       srv_scene_triangle_count(&b->s), grids[gi], spps[si], threads, r.seconds,
                       (double)r.rays * 1e-6, (double)r.rays * 1e-6 / r.seconds,
                       threads == 1 ? "1.00" : (snprintf(err, sizeof err, "%.2f", t1 / r.seconds), err));
                fflush(stdout);
                srv_bake_result_free(&r);
            }
        }
}

/* Relative mean absolute error of I_delta . delta over every valid vertex,
 * hemisphere and channel, of a bake at spp against a 4096-spp bake. */
static void ivg_error_rows(bench_scene *b)
{
    static const int spps[] = {16, 64, 256, 1024};
    int dims[3] = {16, 16, 16};
    srv_grid g = srv_grid_over(&b->s, dims);
    srv_bake_opts o = {4096, 2, 2, 0, 0.25f};
    srv_bake_result truth, r;
    char err[256];
    if (srv_bake(&b->t, &g, &o, &truth, err, sizeof err))
        return;
    for (int i = 0; i < 4; i++) {
        o.spp = spps[i];
        o.seed = 1;
        if (srv_bake(&b->t, &g, &o, &r, err, sizeof err))
            continue;
        double num = 0, den = 0;
        for (size_t v = 0; v < r.nverts; v++)
            for (int h = 0; v < r.nverts && r.valid[v] && truth.valid[v] && h < 6; h++)
                for (int ch = 0; ch < 3; ch++) {
                    size_t at = SRV_BAKE_I(v, h, ch) + (size_t)(h / 2);
                    num += fabs(r.I[at] - truth.I[at]);
                    den += fabs(truth.I[at]);
                }
        printf("| %s | 16³ | %d | %.2f | %.2f %% |\n", b->name, spps[i], r.seconds, 100.0 * num / den);
        fflush(stdout);
        srv_bake_result_free(&r);
    }
    srv_bake_result_free(&truth);
}

static uint8_t *render8(bench_scene *b, int w, int h, int spp, int indirect, double *secs)
{
    srv_image img;
    srv_render_opts o = {spp, 99, 2, indirect, 0};
    double t0 = srv_now();
    if (srv_render_reference(&b->t, &b->s.camera, w, h, &o, &img, NULL))
        return NULL;
    *secs = srv_now() - t0;
    uint8_t *px = host_tonemap_rgb8(img.rgb, (size_t)w * (size_t)h * 3, 1.0f);
    srv_image_free(&img);
    return px;
}

static void reference_rows(bench_scene *b, int indirect)
{
    enum { W = 160, H = 120, TRUTH = 1024 };
    static const int spps[] = {4, 16, 64, 256};
    double secs;
    uint8_t *truth = render8(b, W, H, TRUTH, indirect, &secs);
    if (!truth)
        return;
    for (int i = 0; i < 4; i++) {
        uint8_t *img = render8(b, W, H, spps[i], indirect, &secs);
        host_image_diff d;
        if (!img)
            continue;
        host_image_diff_rgb8(img, truth, (size_t)W * H, &d);
        printf("| %s | %d | %.2f | %.3f |\n", indirect ? "indirect only" : "full", spps[i], secs, d.mean_de);
        free(img);
    }
    free(truth);
}

int main(void)
{
    bench_scene def, dragon;
    if (make_scene(&def, "default (Cornell + dragon 48k)", 0) || make_scene(&dragon, "dragon 203k alone", 1))
        return 1;
    printf("## IVG bake and reference renderer (lumo-bake)\n\n");
    printf("Command: `make bench-bake` (runs `build/host/bench/lumo-bench-bake`, source bench/bench_bake.c). "
           "Seed 1; grid over the scene bounds; Embree 3, paths with NEE + Russian roulette; "
           "rays = all rays cast (path segments + shadow rays). Speed-up = time(1 thread) / time(2 threads).\n\n");
    FILE *la = fopen("/proc/loadavg", "r");
    char load[64] = "?";
    if (la && fgets(load, sizeof load, la))
        load[strcspn(load, " ")] = 0;
    if (la)
        fclose(la);
    printf("1-minute load average when the run started: %s (other jobs on the machine slow the "
           "2-thread rows most).\n\n", load);
    printf("| scene | triangles | grid | spp | threads | time (s) | rays (M) | M rays/s | speed-up |\n");
    printf("|---|---|---|---|---|---|---|---|---|\n");
    bake_rows(&def);
    bake_rows(&dragon);
    printf("\nIVG noise: mean |I_δ·δ − truth| / mean |truth| over all valid vertices, hemispheres and "
           "channels, truth = a 4096-spp bake with another seed (whose own error is about half the 1024-spp row's).\n\n");
    printf("| scene | grid | spp | time (s) | relative error |\n|---|---|---|---|---|\n");
    ivg_error_rows(&def);
    printf("\nReference renderer on the default scene, 160×120, 2 threads: mean CIE Lab ΔE (CIE76, "
           "8-bit sRGB after tone mapping) against a 1024-spp render of the same view.\n\n");
    printf("| image | spp | time (s) | mean ΔE vs 1024 spp |\n|---|---|---|---|\n");
    reference_rows(&def, 0);
    reference_rows(&def, 1);
    srv_rt_free(def.rt);
    srv_rt_free(dragon.rt);
    srv_scene_free(&def.s);
    srv_scene_free(&dragon.s);
    return 0;
}
