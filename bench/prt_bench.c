/* prt_bench.c — `make bench-prt`: the shape of seed 003's Tables 5.2-5.17
 * on lumo's meshes. Per model: the diffuse transfer of the progressive
 * mesh's vertices (order, strata, bounces), then for each cluster count
 * the four methods of the thesis — original CPCA, CPCA with super-clusters
 * (§4.3), geometry coherence (§4.2, alpha), both — with clustering time,
 * average triangle overdraw (Eq. 8) and average squared error against the
 * uncompressed transfer; the Q1.14 chunk's own error; the client's relight
 * cost per vertex against the rasterizer's per-vertex Lambert lighting
 * (lumo_raster_light_vertices, same mesh, same run); with --fps-frames F,
 * each configuration drawn by the GL multipass (lumo/raster_gl_prt.h) on
 * OSMesa for frames per second and the measured overdraw, against a
 * single-pass GL draw of the same mesh in the same run. Markdown to --out. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "lumo/prt.h"
#include "lumo/raster.h"
#include "lumo/raster_gl.h"
#include "lumo/raster_gl_prt.h"
#include "lumo_host/options.h"
#include "pm/pm.h"
#include "pm/pm_load.h"
#include "prt/cpca.h"
#include "prt/prt_pack.h"
#include "prt/transfer.h"

typedef struct {
    const char *out, *cmd, *plot;
    int order, strata, bounces, npc, registers, threads, nk;
    int ks[8], nsweep, fps_frames, width, height;
    double alpha, alpha2, sweep[8];
} bench_opts;

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* The thesis's rows for the same cluster counts: Dino (Tables 5.2-5.5) and
 * Bunny (5.14-5.17): clustering seconds, overdraw, SE per method (original,
 * overdraw red., ours, both; Dino has no "both" row). */
typedef struct { int k; double t[4], od[4], se[4], fps[4]; } thesis_row;
static const thesis_row k_dino[] = {
    {64, {233, 342, 138, -1}, {1.427584, 1.383141, 1.309619, -1}, {0.033846, 0.032895, 0.047968, -1},
     {27.57, 28.12, 32.37, -1}},
    {128, {758, 737, 250, -1}, {1.556363, 1.505114, 1.359051, -1}, {0.014452, 0.014756, 0.027246, -1},
     {26.58, 27.15, 31.91, -1}},
    {192, {915, 1186, 295, -1}, {1.637316, 1.593019, 1.382953, -1}, {0.007938, 0.008764, 0.017335, -1},
     {24.62, 25.60, 30.89, -1}},
    {256, {1624, 1647, 451, -1}, {1.733425, 1.646063, 1.404810, -1}, {0.005371, 0.006344, 0.012216, -1},
     {22.93, 24.43, 30.52, -1}},
};
static const thesis_row k_bunny[] = {
    {64, {340, 438, 606, 434}, {1.305410, 1.275172, 1.239781, 1.207974}, {0.221043, 0.224016, 0.221096, 0.225144},
     {25.86, 26.67, 27.72, 28.53}},
    {128, {766, 908, 1179, 1037}, {1.412708, 1.345726, 1.300917, 1.285856}, {0.118658, 0.117374, 0.118617, 0.113184},
     {25.07, 26.65, 27.61, 28.16}},
    {192, {1339, 1165, 1912, 1355}, {1.471411, 1.420354, 1.356309, 1.337691}, {0.073271, 0.076507, 0.073280, 0.077189},
     {24.65, 25.89, 27.49, 27.83}},
    {256, {1609, 1886, 2293, 2087}, {1.529308, 1.467294, 1.413759, 1.378627}, {0.054466, 0.058319, 0.054501, 0.055894},
     {23.05, 24.45, 25.89, 26.77}},
};

static const thesis_row *thesis_for(const char *model, int k)
{
    const thesis_row *t = strstr(model, "dragon") ? k_dino : strstr(model, "bunny") ? k_bunny : NULL;
    for (int i = 0; t && i < 4; i++)
        if (t[i].k == k)
            return &t[i];
    return NULL;
}

static void cell(FILE *f, double v, const char *fmt)
{
    if (v < 0)
        fprintf(f, " — |");
    else
        fprintf(f, fmt, v);
}

typedef struct { double t, sel_t, od, se, fps, mod; int it; uint32_t passes; } result;

/* The GL side (--fps-frames): one OSMesa context for the run, the model's
 * mesh in the rasterizer's fixed point, a camera framing it, and the
 * single-pass peer's frames per second. */
static struct {
    lumo_osmesa *os;
    lumo_gl *g;
    lumo_raster_mesh rm;
    lumo_raster_camera cam;
    double peer_fps;
} g_gl;

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double cpu_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* The median CPU time of this thread over `frames` frames after 3 warm-up
 * frames, as fps. With LP_NUM_THREADS=0 llvmpipe draws in the calling
 * thread, so the frame's whole cost is this thread's CPU time, which the
 * other work of a shared machine does not inflate (wall-clock time does:
 * measured swings of 2x under a load of 6 on 2 cores).
 * Each frame turns the lighting 7 degrees about +y (a moving environment:
 * the per-cluster table is recomputed every frame, as on a client). */
/* The bench's lighting: two directional lights of 3 W/m², from above and
 * from the side (the same as the rasterizer's Lambert peer below). */
static void bench_light(lumo_prt_light *l, int order)
{
    static const lumo_q1_14 d1[3] = {0, 16384, 0}, d2[3] = {11585, 0, 11585};
    static const lumo_uq16_16 e[3] = {3 << 16, 3 << 16, 3 << 16};
    lumo_prt_light_clear(l, (unsigned)order);
    lumo_prt_light_add_directional(l, d1, e);
    lumo_prt_light_add_directional(l, d2, e);
}

static double gl_fps_of(const bench_opts *o, lumo_gl_prt *gp, const lumo_prt *p, const lumo_prt_light *base,
                        lumo_q16_16 *frame, uint8_t *rgb)
{
    double t[64];
    int n = o->fps_frames < 64 ? o->fps_frames : 64;
    lumo_raster_light rl[2] = {{.kind = LUMO_LIGHT_DIRECTIONAL, .dir = {0, -16384, 0}, .value = {3 << 16, 3 << 16, 3 << 16}},
                               {.kind = LUMO_LIGHT_DIRECTIONAL, .dir = {-11585, 0, -11585}, .value = {3 << 16, 3 << 16, 3 << 16}}};
    lumo_raster_scene rs = {.lights = rl, .light_count = 2, .exposure = LUMO_Q16_ONE};
    for (int i = -3; i < n; i++) {
        double t0 = cpu_s(), a = i * 7.0 * M_PI / 180.0;
        if (gp) {
            lumo_q1_14 one[2] = {LUMO_Q14_ONE, 0}, b[2] = {(lumo_q1_14)lrint(cos(a) * 16384), (lumo_q1_14)lrint(sin(a) * 16384)};
            lumo_prt_light l;
            const lumo_q16_16 *f[1] = {frame};
            if (lumo_prt_light_rotate(base, one, b, one, &l) || lumo_prt_frame(p, &l, frame) ||
                lumo_gl_prt_draw(gp, &g_gl.cam, &rs, f, rgb))
                return -1;
        } else if (lumo_gl_draw(g_gl.g, &g_gl.cam, &rs, rgb))
            return -1;
        if (i >= 0)
            t[i] = cpu_s() - t0;
    }
    qsort(t, (size_t)n, sizeof *t, cmp_double);
    return 1.0 / t[n / 2];
}

/* Frames per second of the GL multipass for clusters c drawn in passes
 * `pass` (NULL: one pass per cluster); *od gets the measured overdraw
 * (the triangles the passes drew / triangles, checked against the GL's
 * own primitive count). */
static double gl_fps(const srv_cpca *c, const uint32_t *pass, const bench_opts *o, double *od)
{
    uint8_t *chunk, *rgb = malloc((size_t)o->width * o->height * 3);
    size_t len;
    lumo_prt p;
    char err[256];
    double fps = -1;
    *od = -1;
    if (!rgb || srv_prt_encode(c, o->order, pass, &chunk, &len) || lumo_prt_parse(&p, chunk, len)) {
        fprintf(stderr, "prt-bench: cannot build the chunk for the GL multipass\n");
        exit(1);
    }
    lumo_q16_16 *frame = malloc(lumo_prt_frame_entries(&p) * sizeof *frame);
    lumo_prt_light base;
    bench_light(&base, o->order);
    uint32_t count = g_gl.rm.vertex_count;
    lumo_gl_prt *gp = frame ? lumo_gl_prt_create(g_gl.g, &g_gl.rm, &p, &count, 1, err, sizeof err) : NULL;
    if (!gp) {
        fprintf(stderr, "prt-bench: GL multipass: %s\n", err);
        exit(1);
    }
    fps = gl_fps_of(o, gp, &p, &base, frame, rgb);
    lumo_gl_prt_stats st;
    lumo_gl_prt_get_stats(gp, &st);
    if (st.generated && st.generated != st.drawn) {
        fprintf(stderr, "prt-bench: the GL generated %llu primitives, %llu were drawn\n",
                (unsigned long long)st.generated, (unsigned long long)st.drawn);
        exit(1);
    }
    *od = (double)st.drawn / (double)st.triangles;
    lumo_gl_prt_destroy(gp);
    free(frame), free(chunk), free(rgb);
    return fps;
}

/* Overdraw per cluster count of the first model, for the plot. */
static struct { int n, k[8]; double od[8][6]; } g_plot;

static void run_method(const srv_pm *pm, const double *x, int nc, const bench_opts *o, int k, double alpha,
                       result *plain, result *super, srv_cpca *keep, int draw)
{
    srv_cpca_opts co;
    srv_cpca c;
    srv_cpca_default_opts(&co);
    co.clusters = k, co.components = o->npc, co.alpha = alpha, co.threads = o->threads;
    if (srv_cpca_build(x, pm->vertices, nc, pm->xyz, &co, &c)) {
        fprintf(stderr, "prt-bench: CPCA failed\n");
        exit(1);
    }
    uint32_t *pass = malloc((size_t)k * sizeof *pass);
    double t0 = now_s();
    super->passes = srv_cpca_superclusters(&c, pm->tris, pm->faces, srv_cpca_per_pass(nc, o->npc, o->registers), pass);
    super->sel_t = now_s() - t0;
    plain->t = super->t = c.cluster_seconds;
    plain->it = super->it = c.iterations;
    plain->od = srv_cpca_overdraw(&c, pm->tris, pm->faces, NULL);
    super->od = srv_cpca_overdraw(&c, pm->tris, pm->faces, pass);
    plain->se = super->se = srv_cpca_sq_error(&c, x);
    plain->passes = (uint32_t)k, plain->sel_t = 0;
    plain->fps = super->fps = plain->mod = super->mod = -1;
    if (draw && g_gl.g) {
        plain->fps = gl_fps(&c, NULL, o, &plain->mod);
        super->fps = gl_fps(&c, pass, o, &super->mod);
    }
    free(pass);
    if (keep)
        *keep = c;
    else
        srv_cpca_free(&c);
}

static void table(FILE *f, const char *model, const srv_pm *pm, const double *x, int nc, const bench_opts *o, int k)
{
    result r[6];
    srv_cpca keep;
    char n4[96], n5[96];
    int rows = o->alpha2 > 0 ? 6 : 4;
    run_method(pm, x, nc, o, k, 0.0, &r[0], &r[1], &keep, 1);
    run_method(pm, x, nc, o, k, o->alpha, &r[2], &r[3], NULL, 1);
    if (rows == 6)
        run_method(pm, x, nc, o, k, o->alpha2, &r[4], &r[5], NULL, 1);
    snprintf(n4, sizeof n4, "Geometry coherence, alpha = %g", o->alpha2);
    snprintf(n5, sizeof n5, "Both, alpha = %g", o->alpha2);
    if (g_plot.n < 8 && strstr(model, "dragon")) {
        g_plot.k[g_plot.n] = k;
        for (int m = 0; m < rows; m++)
            g_plot.od[g_plot.n][m] = r[m].od;
        g_plot.n++;
    }
    const thesis_row *th = thesis_for(model, k);
    const char *names[6] = {"Original CPCA", "CPCA + super-clusters (\"overdraw red.\")",
                            "Geometry coherence (\"our method\")", "Both", n4, n5};
    fprintf(f, "\n**%s, %d clusters, alpha = %.2f** (%d passes of %d clusters for the super-clusters)\n\n", model, k,
            o->alpha, (int)r[1].passes, srv_cpca_per_pass(nc, o->npc, o->registers));
    fprintf(f, "| method | clustering (s) [+ selection] | LBG passes | avg overdraw (Eq. 8) | measured (GL) | fps (GL) "
               "| fps / single pass | avg SE | thesis time (s) | thesis overdraw | thesis FPS | thesis SE |\n");
    fprintf(f, "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (int m = 0; m < rows; m++) {
        if (m % 2)
            fprintf(f, "| %s | %.2f + %.3f | %d | %.4f |", names[m], r[m].t, r[m].sel_t, r[m].it, r[m].od);
        else
            fprintf(f, "| %s | %.2f | %d | %.4f |", names[m], r[m].t, r[m].it, r[m].od);
        cell(f, r[m].mod, " %.4f |");
        cell(f, r[m].fps, " %.1f |");
        cell(f, r[m].fps > 0 && g_gl.peer_fps > 0 ? r[m].fps / g_gl.peer_fps : -1, " %.2f |");
        fprintf(f, " %.3e |", r[m].se);
        cell(f, th && m < 4 ? th->t[m] : -1, " %.0f |");
        cell(f, th && m < 4 ? th->od[m] : -1, " %.4f |");
        cell(f, th && m < 4 ? th->fps[m] : -1, " %.2f |");
        cell(f, th && m < 4 ? th->se[m] : -1, " %.4f |");
        fprintf(f, "\n");
    }
    uint8_t *chunk;
    size_t len;
    if (srv_prt_encode(&keep, o->order, NULL, &chunk, &len) == LUMO_OK) {
        fprintf(f, "\nPRTV chunk (original CPCA): %zu bytes (%.1f per vertex; uncompressed binary32 %zu bytes); "
                   "Q1.14 quantization squared error %.2e (CPCA's own: %.2e).\n",
                len, (double)len / pm->vertices, (size_t)pm->vertices * (size_t)nc * 4u,
                srv_prt_quant_sq_error(&keep, chunk, len), r[0].se);
        free(chunk);
    }
    srv_cpca_free(&keep);
}

static void usage(void)
{
    fputs("usage: prt-bench --out FILE [--plot FILE.svg] [--cmd TEXT] [--order N] [--strata S] [--bounces B] [--components P]\n"
          "                 [--alpha A] [--alpha2 A] [--alpha-sweep A,A,..] [--clusters K,K,..] [--registers R]\n"
          "                 [--threads T] [--fps-frames F] [--size WxH] MODEL...\n",
          stderr);
    exit(2);
}

/* One value of the integer and number options, strictly (lumo_host/options.h):
 * 1 taken, 0 not one of them; a refusal names option and value and exits. */
static int take_number(bench_opts *o, const char *a, const char *v)
{
    static const struct { const char *name; int lo, hi; size_t at; } ints[] = {
        {"--order", 1, LUMO_PRT_MAX_ORDER, offsetof(bench_opts, order)},
        {"--strata", 2, 256, offsetof(bench_opts, strata)},
        {"--bounces", 0, 8, offsetof(bench_opts, bounces)},
        {"--components", 0, LUMO_PRT_MAX_COMPONENTS, offsetof(bench_opts, npc)},
        {"--registers", 0, 65536, offsetof(bench_opts, registers)},
        {"--threads", 1, 256, offsetof(bench_opts, threads)},
        {"--fps-frames", 0, 100000, offsetof(bench_opts, fps_frames)},
    };
    char why[200];
    double d[8];
    int n, rc = 0;
    for (size_t k = 0; k < sizeof ints / sizeof ints[0]; k++)
        if (!strcmp(a, ints[k].name))
            rc = host_opt_int(a, v, ints[k].lo, ints[k].hi, (int *)(void *)((char *)o + ints[k].at), why,
                              sizeof why) ? -1 : 1;
    if (!rc && !strcmp(a, "--size")) {
        uint32_t w = 0, h = 0;
        rc = host_opt_size(a, v, 8192, 8192, &w, &h, why, sizeof why) ? -1 : 1;
        if (rc > 0 && (w < 16 || h < 16))
            rc = -1, snprintf(why, sizeof why, "%s %s: at least 16x16", a, v);
        o->width = (int)w, o->height = (int)h;
    }
    if (!rc && (!strcmp(a, "--alpha") || !strcmp(a, "--alpha2")))
        rc = host_opt_double(a, v, 0, 1e6, a[7] ? &o->alpha2 : &o->alpha, why, sizeof why) ? -1 : 1;
    if (!rc && !strcmp(a, "--alpha-sweep")) {
        rc = host_opt_list(a, v, 0, 1e6, 0, d, 8, &n, why, sizeof why) ? -1 : 1;
        for (o->nsweep = 0; rc > 0 && o->nsweep < n; o->nsweep++)
            o->sweep[o->nsweep] = d[o->nsweep];
    }
    if (!rc && !strcmp(a, "--clusters")) {
        rc = host_opt_list(a, v, 1, LUMO_PRT_MAX_CLUSTERS, 0, d, 8, &n, why, sizeof why) ? -1 : 1;
        for (o->nk = 0; rc > 0 && o->nk < n; o->nk++)
            o->ks[o->nk] = (int)d[o->nk];
        for (int k = 0; rc > 0 && k < n; k++)
            if (d[k] != (double)(int)d[k]) {
                snprintf(why, sizeof why, "%s %s: value %d is not an integer", a, v, k + 1);
                rc = -1;
            }
    }
    if (rc < 0) {
        fprintf(stderr, "lumo-bench-prt: error: %s\n", why);
        exit(2);
    }
    return rc;
}

static int parse(bench_opts *o, int argc, char **argv)
{
    *o = (bench_opts){.cmd = "", .order = 6, .strata = 32, .bounces = 1, .npc = 8, .registers = 256, .threads = 2,
                      .alpha = 0.05, .nk = 4, .ks = {64, 128, 192, 256}, .width = 640, .height = 480};
    int i = 1;
    for (; i < argc && argv[i][0] == '-'; i += 2) {
        if (i + 1 >= argc)
            usage();
        const char *a = argv[i], *v = argv[i + 1];
        if (!strcmp(a, "--out")) o->out = v;
        else if (!strcmp(a, "--cmd")) o->cmd = v;
        else if (!strcmp(a, "--plot")) o->plot = v;
        else if (!take_number(o, a, v))
            usage();
    }
    if (!o->out || i >= argc)
        usage();
    return i;
}

/* Geometry coherence against alpha at the first cluster count: where the
 * term starts to matter in lumo's units (positions in bounding-box
 * diagonals, transfer vectors as projected). */
static void sweep(FILE *f, const srv_pm *pm, const double *x, int nc, const bench_opts *o)
{
    if (!o->nsweep)
        return;
    fprintf(f, "\nGeometry coherence against alpha, %d clusters:\n\n", o->ks[0]);
    fprintf(f, "| alpha | clustering (s) | avg overdraw | with super-clusters | avg SE |\n|---:|---:|---:|---:|---:|\n");
    for (int i = 0; i < o->nsweep; i++) {
        result p, s;
        run_method(pm, x, nc, o, o->ks[0], o->sweep[i], &p, &s, NULL, 0);
        fprintf(f, "| %g | %.2f | %.4f | %.4f | %.3e |\n", o->sweep[i], p.t, p.od, s.od, p.se);
    }
}

/* The progressive mesh's full level as the rasterizer's mesh: positions
 * Q16.16, area-weighted normals Q1.14, a grey albedo of 0.8. */
static void raster_mesh(const srv_pm *pm, lumo_raster_mesh *rm)
{
    uint32_t n = pm->vertices;
    lumo_q16_16 *pos = malloc(3u * n * sizeof *pos);
    lumo_q1_14 *nrm = malloc(3u * n * sizeof *nrm);
    float *fn = malloc(3u * n * sizeof *fn);
    srv_prt_mesh m = {.nverts = n, .ntris = pm->faces, .xyz = pm->xyz, .tris = pm->tris};
    if (!pos || !nrm || !fn) {
        fprintf(stderr, "prt-bench: out of memory\n");
        exit(1);
    }
    srv_prt_vertex_normals(&m, fn);
    for (uint32_t i = 0; i < 3 * n; i++)
        pos[i] = (lumo_q16_16)lrintf(pm->xyz[i] * 65536.0f), nrm[i] = (lumo_q1_14)lrintf(fn[i] * 16383.0f);
    free(fn);
    *rm = (lumo_raster_mesh){.pos = pos, .normal = nrm, .mesh_albedo = {13107, 13107, 13107}, .tris = pm->tris,
                             .vertex_count = n, .tri_count = pm->faces};
}

static void raster_mesh_free(lumo_raster_mesh *rm)
{
    free((void *)rm->pos), free((void *)rm->normal);
}

/* The GL side of a model: its mesh uploaded (the single-pass peer draws
 * it; the far plane follows it), a camera on +z at 2.2 radii framing the
 * bounding box, the peer's frames per second. */
static void gl_model(const srv_pm *pm, const bench_opts *o)
{
    double lo[3] = {1e30, 1e30, 1e30}, hi[3] = {-1e30, -1e30, -1e30}, r = 0;
    raster_mesh_free(&g_gl.rm);
    raster_mesh(pm, &g_gl.rm);
    for (uint32_t i = 0; i < 3 * pm->vertices; i++)
        lo[i % 3] = fmin(lo[i % 3], pm->xyz[i]), hi[i % 3] = fmax(hi[i % 3], pm->xyz[i]);
    for (int k = 0; k < 3; k++)
        r += (hi[k] - lo[k]) * (hi[k] - lo[k]) / 4;
    r = sqrt(r);
    for (int k = 0; k < 3; k++) {
        g_gl.cam.target[k] = (lumo_q16_16)lrint((lo[k] + hi[k]) / 2 * 65536);
        g_gl.cam.eye[k] = g_gl.cam.target[k] + (k == 2 ? (lumo_q16_16)lrint(2.2 * r * 65536) : 0);
        g_gl.cam.up[k] = k == 1 ? LUMO_Q16_ONE : 0;
    }
    g_gl.cam.fovy_deg = 40 << 16;
    g_gl.cam.znear = (lumo_q16_16)lrint(0.05 * r * 65536) + 1;
    if (lumo_gl_set_mesh(g_gl.g, &g_gl.rm)) {
        fprintf(stderr, "prt-bench: uploading the mesh failed\n");
        exit(1);
    }
    uint8_t *rgb = malloc((size_t)o->width * o->height * 3);
    g_gl.peer_fps = rgb ? gl_fps_of(o, NULL, NULL, NULL, NULL, rgb) : -1;
    free(rgb);
}

/* Relight cost: lumo_prt_frame + lumo_prt_shade per frame against
 * lumo_raster_light_vertices with two directional lights, same vertices. */
static void client_cost(FILE *f, const srv_pm *pm, const double *x, int nc, const bench_opts *o)
{
    srv_cpca_opts co;
    srv_cpca c;
    srv_cpca_default_opts(&co);
    co.clusters = 64, co.components = o->npc, co.threads = o->threads;
    uint8_t *chunk;
    size_t len;
    lumo_prt p;
    if (srv_cpca_build(x, pm->vertices, nc, pm->xyz, &co, &c) || srv_prt_encode(&c, o->order, NULL, &chunk, &len) ||
        lumo_prt_parse(&p, chunk, len)) {
        fprintf(stderr, "prt-bench: cannot build the client chunk\n");
        exit(1);
    }
    uint32_t n = pm->vertices;
    lumo_q16_16 *frame = malloc(lumo_prt_frame_entries(&p) * sizeof *frame);
    lumo_uq16_16 *lit = malloc(6u * n * sizeof *lit);
    lumo_raster_mesh rm;
    raster_mesh(pm, &rm);
    lumo_prt_light L;
    bench_light(&L, o->order);
    lumo_raster_light rl[2] = {{.kind = LUMO_LIGHT_DIRECTIONAL, .dir = {0, -16384, 0}, .value = {3 << 16, 3 << 16, 3 << 16}},
                               {.kind = LUMO_LIGHT_DIRECTIONAL, .dir = {-11585, 0, -11585}, .value = {3 << 16, 3 << 16, 3 << 16}}};
    lumo_raster_scene rs = {.lights = rl, .light_count = 2, .exposure = LUMO_Q16_ONE};
    enum { REPS = 40 };
    double t0 = now_s();
    for (int r = 0; r < REPS; r++) {
        lumo_prt_frame(&p, &L, frame);
        lumo_prt_shade(&p, frame, NULL, 0, n, lit);
    }
    double tp = (now_s() - t0) / REPS;
    t0 = now_s();
    for (int r = 0; r < REPS; r++)
        lumo_prt_frame(&p, &L, frame);
    double tf = (now_s() - t0) / REPS;
    t0 = now_s();
    for (int r = 0; r < REPS; r++)
        lumo_raster_light_vertices(&rs, &rm, lit);
    double tl = (now_s() - t0) / REPS;
    fprintf(f, "\nClient relight per frame, %u vertices, order %d, 64 clusters, %d components (host, -O2, "
               "mean of %d frames): PRT %.2f ms (%.1f ns/vertex; of which the per-cluster table %.3f ms), "
               "per-vertex Lambert with 2 directional lights (lumo_raster_light_vertices) %.2f ms "
               "(%.1f ns/vertex): PRT/Lambert = %.2f.\n",
            n, o->order, o->npc, REPS, tp * 1e3, tp * 1e9 / n, tf * 1e3, tl * 1e3, tl * 1e9 / n, tp / tl);
    free(frame), free(lit), free(chunk);
    raster_mesh_free(&rm);
    srv_cpca_free(&c);
}

static void model(FILE *f, const char *path, const bench_opts *o, int first)
{
    float *xyz;
    uint32_t nv, nf, *tris;
    char err[256];
    srv_pm pm;
    if (srv_pm_load(path, &xyz, NULL, &nv, &tris, &nf, err, sizeof err) ||
        srv_pm_build_albedo(xyz, NULL, nv, tris, nf, NULL, &pm)) {
        fprintf(stderr, "prt-bench: %s: %s\n", path, err);
        exit(1);
    }
    int nc = o->order * o->order;
    double *x = malloc((size_t)pm.vertices * (size_t)nc * sizeof *x), t0 = now_s();
    srv_prt_mesh m = {.nverts = pm.vertices, .ntris = pm.faces, .xyz = pm.xyz, .tris = pm.tris};
    srv_prt_transfer_opts to;
    srv_prt_transfer_default_opts(&to);
    to.order = o->order, to.strata = o->strata, to.bounces = o->bounces, to.threads = o->threads;
    if (srv_prt_transfer(&m, &to, x, err, sizeof err)) {
        fprintf(stderr, "prt-bench: %s\n", err);
        exit(1);
    }
    const char *name = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    fprintf(f, "\n### %s: %u vertices, %u triangles (progressive mesh, full level)\n\n", name, pm.vertices, pm.faces);
    fprintf(f, "Transfer: order %d (%d coefficients), %d directions, %d bounce(s): %.1f s on %d threads.\n", o->order,
            nc, o->strata * o->strata, o->bounces, now_s() - t0, o->threads);
    if (g_gl.g) {
        gl_model(&pm, o);
        fprintf(f, "GL (OSMesa: %s, %dx%d, median CPU time of %d frames, the lighting turned 7 degrees a frame): the "
                   "single-pass peer — the same mesh drawn once by lumo_gl_draw, per-vertex Lambert of 2 "
                   "directional lights — %.1f fps.\n", lumo_gl_renderer(g_gl.g), o->width, o->height,
                o->fps_frames, g_gl.peer_fps);
    }
    for (int i = 0; i < o->nk; i++)
        table(f, name, &pm, x, nc, o, o->ks[i]);
    sweep(f, &pm, x, nc, o);
    if (first)
        client_cost(f, &pm, x, nc, o);
    fflush(f);
    free(x), free(xyz), free(tris);
    srv_pm_free(&pm);
}

/* One polyline of the plot: x = clusters 0..300, y = overdraw 1.2..1.9. */
static void poly(FILE *f, int n, const int *k, const double *y, int stride, const char *colour, int dashed)
{
    fprintf(f, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"2\"%s points=\"", colour,
            dashed ? " stroke-dasharray=\"6,4\"" : "");
    for (int i = 0; i < n; i++)
        fprintf(f, "%.1f,%.1f ", 60 + k[i] * 1.6, 360 - (y[i * stride] - 1.2) / 0.7 * 320);
    fprintf(f, "\"/>\n");
}

/* --plot FILE: average triangle overdraw against clusters on the dragon,
 * lumo's four methods (coherence at --alpha2) and the thesis's Dino. */
static void plot(const char *path, const bench_opts *o)
{
    FILE *f = fopen(path, "w");
    static const char *col[4] = {"#c03030", "#3060c0", "#30a040", "#9040a0"};
    static const char *lab[4] = {"CPCA", "super-clusters", "coherence", "both"};
    double th[2][4];
    int tk[4];
    if (!f || g_plot.n == 0)
        return;
    for (int i = 0; i < 4; i++)
        tk[i] = k_dino[i].k, th[0][i] = k_dino[i].od[0], th[1][i] = k_dino[i].od[2];
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"600\" height=\"400\" font-family=\"sans-serif\" "
               "font-size=\"12\">\n<rect width=\"600\" height=\"400\" fill=\"white\"/>\n");
    fprintf(f, "<text x=\"60\" y=\"24\">Average triangle overdraw (Eq. 8), dragon 48k (lines) vs the thesis's Dino "
               "(dashed), alpha %g</text>\n", o->alpha2);
    for (int i = 0; i <= 7; i++) {
        double y = 360 - i * 320.0 / 7;
        fprintf(f, "<line x1=\"60\" x2=\"540\" y1=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/><text x=\"20\" y=\"%.1f\">"
                   "%.1f</text>\n", y, y, y + 4, 1.2 + i * 0.1);
    }
    for (int k = 0; k <= 300; k += 64)
        fprintf(f, "<text x=\"%.1f\" y=\"380\">%d</text>\n", 52 + k * 1.6, k);
    fprintf(f, "<text x=\"250\" y=\"396\">clusters</text>\n");
    for (int m = 0; m < 4; m++) {
        int col_m = m < 2 ? m : m + 2;   /* coherence and both at alpha2 */
        poly(f, g_plot.n, g_plot.k, &g_plot.od[0][col_m], 6, col[m], 0);
        fprintf(f, "<text x=\"420\" y=\"%d\" fill=\"%s\">%s</text>\n", 60 + 16 * m, col[m], lab[m]);
    }
    poly(f, 4, tk, th[0], 1, col[0], 1);
    poly(f, 4, tk, th[1], 1, col[2], 1);
    fprintf(f, "<text x=\"420\" y=\"124\">dashed: thesis CPCA, ours</text>\n</svg>\n");
    fclose(f);
}

int main(int argc, char **argv)
{
    bench_opts o;
    int i = parse(&o, argc, argv);
    FILE *f = fopen(o.out, "w");
    if (!f) {
        fprintf(stderr, "prt-bench: cannot write %s\n", o.out);
        return 1;
    }
    fprintf(f, "## PRT: clustered PCA, geometry coherence, super-clusters (seed 003 Tables 5.2-5.17)\n\n");
    fprintf(f, "Command: `%s`. %d components, %d float4 registers per pass (seed 003 §4.1).\n", o.cmd, o.npc,
            o.registers);
    if (o.fps_frames > 0) {
        char err[256];
        const char *lp = getenv("LP_NUM_THREADS");
        double load[3] = {-1, -1, -1};
        FILE *la = fopen("/proc/loadavg", "r");
        if (la && fscanf(la, "%lf %lf %lf", &load[0], &load[1], &load[2]) != 3)
            load[0] = -1;
        if (la)
            fclose(la);
        if (!(g_gl.os = lumo_osmesa_open(o.width, o.height, err, sizeof err)) || !(g_gl.g = lumo_osmesa_gl(g_gl.os))) {
            fprintf(stderr, "prt-bench: OSMesa: %s\n", err);
            return 1;
        }
        fprintf(f, "\nFrames per second: the GL multipass (lumo/raster_gl_prt.h) on %s, LP_NUM_THREADS=%s, "
                   "load average %.2f %.2f %.2f at the start: fps = 1 / (CPU seconds of a frame), llvmpipe "
                   "drawing in the calling thread when LP_NUM_THREADS=0, so a shared machine's load does not enter "
                   "them; the ratio to the single-pass peer of the same run is the number to compare.\n",
                lumo_gl_renderer(g_gl.g), lp ? lp : "unset", load[0], load[1], load[2]);
    }
    for (int first = 1; i < argc; i++, first = 0)
        model(f, argv[i], &o, first);
    fclose(f);
    raster_mesh_free(&g_gl.rm);
    lumo_osmesa_close(g_gl.os);
    if (o.plot && o.alpha2 > 0)
        plot(o.plot, &o);
    return 0;
}
