/*
 * test_raster_shadow.c — the soft rasterizer's shadow maps (docs/rasterizer.md
 * "Shadows"): the shadow of a known occluder under a point light against
 * the server path tracer's direct light (its visibility rays through
 * Embree: srv_direct_irradiance, noise-free for a point light), band and
 * cache independence with shadows on, a spot's one-face map and a
 * directional light's, the map's bytes, and errors.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "test_common.h"
#include "lumo/raster.h"
#include "bake/rt.h"
#include "bake/trace.h"
#include "scene/shapes.h"
#include "../../tools/lumo-render/mesh_build.h"
#include "../../tools/lumo-render/scene_convert.h"

#define W 320
#define H 240
#define MAP 512
/* The shadow's outline: every pixel whose shadow state differs from the
 * path tracer's lies within this many pixels of the tracer's outline. */
#define MAX_OUTLINE_PX 1.0

static uint32_t color[W * H], color2[W * H], depth[W * H];
static uint16_t map_mem[6 * MAP * MAP];

/* A floor, a box hovering over it and a point light (the occluder's
 * shadow falls wholly on the floor). */
static void build_scene(srv_scene *s, const char *light)
{
    srv_light l;
    char err[128];

    srv_scene_init(s);
    assert_int_equal(srv_add_quad(s, "floor", v3(-3, 0, -3), v3(0, 0, 6), v3(6, 0, 0), v3(0.8f, 0.8f, 0.8f)),
                     LUMO_OK);
    assert_int_equal(srv_add_box(s, "box", v3(-0.35f, 0.5f, -0.25f), v3(0.25f, 0.8f, 0.3f), v3(0.7f, 0.6f, 0.5f),
                                 0), LUMO_OK);
    assert_int_equal(srv_light_parse(light, &l, err, sizeof err), LUMO_OK);
    assert_int_equal(srv_scene_add_light(s, &l), LUMO_OK);
    assert_int_equal(srv_camera_parse("0.3,2.2,2.4:0,0.2,0:0,1,0:50", &s->camera), LUMO_OK);
    s->has_camera = 1;
}

/* The path tracer's direct light at every pixel centre: 1 lit, 0 in
 * shadow, -1 nothing hit or facing away from the light. */
static void reference_mask(const srv_scene *s, signed char *mask)
{
    char err[128];
    srv_rt *rt = srv_rt_create(s, 1, err, sizeof err);
    srv_tracer tr;
    int x, y;

    assert_non_null(rt);
    srv_tracer_init(&tr, s, rt);
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            vec3 d = srv_camera_ray(&s->camera, W, H, x + 0.5f, y + 0.5f), p, n, to;
            srv_hit h;
            srv_rng r;
            srv_trace_stats st = {0};
            signed char *m = &mask[y * W + x];
            *m = -1;
            if (!srv_rt_intersect(rt, s->camera.eye, d, 0.0f, INFINITY, &h))
                continue;
            p = v3_add(s->camera.eye, v3_scale(d, h.t));
            n = v3_dot(h.n, d) > 0.0f ? v3_scale(h.n, -1.0f) : h.n;
            to = v3_sub(s->lights[0].pos, p);
            if (v3_dot(to, n) <= 0.0f)
                continue;
            srv_rng_seed(&r, 1, (uint64_t)y * W + (uint64_t)x);
            *m = srv_direct_irradiance(&tr, p, n, &r, &st).y > 0.0f;
        }
    srv_rt_free(rt);
}

static lumo_raster_target target(uint32_t *c, uint16_t y0, uint16_t rows)
{
    lumo_raster_target t;
    assert_int_equal(lumo_raster_target_init(&t, W, H, y0, rows, LUMO_PIXEL_XRGB8888, c + (size_t)y0 * W,
                                             depth, 32), LUMO_OK);
    return t;
}

static void draw(const host_scene *hs, const lumo_raster_mesh *m, const lumo_raster_light *l,
                 uint32_t flags, uint32_t *out, uint16_t band, const lumo_raster_vertex *cache)
{
    lumo_raster_view v;
    lumo_raster_scene s = {l, 1, NULL, NULL, LUMO_Q16_ONE, flags};
    uint16_t y;

    assert_int_equal(lumo_raster_view_init(&v, &hs->camera, W, H), LUMO_OK);
    for (y = 0; y < H; y += band) {
        uint16_t rows = (uint16_t)(H - y < band ? H - y : band);
        lumo_raster_target t = target(out, y, rows);
        assert_int_equal(lumo_raster_clear(&t, 0), LUMO_OK);
        if (cache)
            assert_int_equal(lumo_raster_prepare(&v, &s, m, (lumo_raster_vertex *)cache), LUMO_OK);
        assert_int_equal(lumo_raster_draw(&v, &s, m, cache, &t), LUMO_OK);
    }
}

static lumo_raster_light shadowed_light(const host_scene *hs, const lumo_raster_mesh *m,
                                        lumo_raster_shadow *sh, uint16_t size)
{
    static const lumo_q16_16 centre[3] = {0, 0, 0};
    lumo_raster_light l = hs->lights[0];
    size_t bytes = lumo_raster_shadow_bytes(&l, size);

    assert_true(bytes > 0 && bytes <= sizeof map_mem);
    assert_int_equal(lumo_raster_shadow_init(sh, &l, size, map_mem, bytes, centre, 3 << 16, 0), LUMO_OK);
    assert_int_equal(lumo_raster_shadow_draw(sh, m), LUMO_OK);
    l.shadow = sh;
    return l;
}

static int green(uint32_t c)
{
    return (int)((c >> 8) & 255);
}

/* Distance from (x, y) to the nearest outline pixel of the mask (a lit or
 * shadowed pixel with a 4-neighbour of the other state). */
static double outline_distance(const signed char *mask, int x, int y)
{
    double best = 1e9;
    int u, v, r = 12;

    for (v = y - r; v <= y + r; v++)
        for (u = x - r; u <= x + r; u++) {
            signed char m;
            if (u < 1 || v < 1 || u >= W - 1 || v >= H - 1 || (m = mask[v * W + u]) < 0)
                continue;
            if ((mask[v * W + u - 1] == !m) || (mask[v * W + u + 1] == !m) || (mask[(v - 1) * W + u] == !m)
                || (mask[(v + 1) * W + u] == !m)) {
                double d = sqrt((double)(u - x) * (u - x) + (double)(v - y) * (v - y));
                if (d < best)
                    best = d;
            }
        }
    return best;
}

/* A point light over a box: the client's shadow (visibility < 1/2, i.e.
 * the pixel below 0.73 of its unshadowed sRGB code) against the path
 * tracer's visibility, pixel by pixel. */
static void test_point_shadow_vs_path_tracer(void **state)
{
    static signed char mask[W * H];
    srv_scene s;
    host_scene hs;
    lumo_raster_mesh m;
    lumo_raster_shadow sh;
    lumo_raster_light l;
    char err[128];
    int i, shadow_px = 0, lit_px = 0, wrong = 0;
    double worst = 0;
    (void)state;

    build_scene(&s, "point:0.5,1.7,0.3:30,30,30");
    reference_mask(&s, mask);
    assert_int_equal(host_scene_from_srv(&hs, &s, err, sizeof err), LUMO_OK);
    m = host_mesh_raster(&hs.mesh);
    l = shadowed_light(&hs, &m, &sh, MAP);
    assert_int_equal(sh.faces, 6);
    draw(&hs, &m, &l, LUMO_RASTER_PER_PIXEL, color, H, NULL);
    draw(&hs, &m, &hs.lights[0], LUMO_RASTER_PER_PIXEL, color2, H, NULL);
    for (i = 0; i < W * H; i++) {
        int shadow, lit0 = green(color2[i]);
        if (mask[i] < 0 || lit0 < 8)
            continue;
        shadow = green(color[i]) * 100 < lit0 * 73;
        shadow_px += shadow;
        lit_px += !shadow;
        if (shadow != !mask[i]) {
            double d = outline_distance(mask, i % W, i / W);
            wrong++;
            if (d > worst)
                worst = d;
        }
    }
    printf("point light shadow: %d shadowed, %d lit pixels; %d differ from the path tracer, "
           "at most %.2f px from its outline\n", shadow_px, lit_px, wrong, worst);
    assert_true(shadow_px > 2000);                  /* the box casts a real shadow */
    assert_true(lit_px > 20000);
    assert_true(worst <= MAX_OUTLINE_PX);
    assert_true(wrong * 20 < shadow_px);            /* and the outlines differ by little */
    host_scene_free(&hs);
    srv_scene_free(&s);
}

/* Bands of any height and the vertex cache give the bytes of one pass,
 * with shadows, in both lighting modes, and so do vertices lit once
 * (lumo_raster_light_vertices); shadows darken, never brighten. */
static void test_bands_cache_with_shadows(void **state)
{
    static lumo_raster_vertex cache[256];
    static const uint16_t bands[] = {1, 7, 48, H};
    srv_scene s;
    host_scene hs;
    lumo_raster_mesh m;
    lumo_raster_shadow sh;
    lumo_raster_light l;
    char err[128];
    int mode, i, darker = 0;
    size_t b;
    (void)state;

    build_scene(&s, "spot:0.4,1.8,0.2:-0.2,-1,-0.1:50:40,40,40");
    assert_int_equal(host_scene_from_srv(&hs, &s, err, sizeof err), LUMO_OK);
    m = host_mesh_raster(&hs.mesh);
    assert_true(m.vertex_count <= 256);
    l = shadowed_light(&hs, &m, &sh, 256);
    assert_int_equal(sh.faces, 1);                   /* a 50-degree spot: one face */
    for (mode = 0; mode < 2; mode++) {
        uint32_t flags = mode ? LUMO_RASTER_PER_PIXEL : 0;
        draw(&hs, &m, &l, flags, color, H, NULL);
        for (b = 0; b < sizeof bands / sizeof *bands; b++) {
            draw(&hs, &m, &l, flags, color2, bands[b], b & 1 ? cache : NULL);
            assert_memory_equal(color, color2, sizeof color);
        }
        if (!mode) {                                 /* vertices lit once: the same bytes */
            static lumo_uq16_16 lit[256 * 6];
            lumo_raster_mesh lm = m;
            lumo_raster_scene sc = {&l, 1, NULL, NULL, LUMO_Q16_ONE, flags};
            assert_true(lumo_raster_lit_bytes(m.vertex_count) <= sizeof lit);
            assert_int_equal(lumo_raster_light_vertices(&sc, &m, lit), LUMO_OK);
            lm.lit = lit;
            draw(&hs, &lm, &l, flags, color2, 7, cache);
            assert_memory_equal(color, color2, sizeof color);
            draw(&hs, &lm, &l, flags, color2, H, NULL);
            assert_memory_equal(color, color2, sizeof color);
            assert_int_equal(lumo_raster_light_vertices(NULL, &m, lit), LUMO_ERR_ARG);
            assert_int_equal(lumo_raster_light_vertices(&sc, &m, NULL), LUMO_ERR_ARG);
        }
        draw(&hs, &m, &hs.lights[0], flags, color2, H, NULL);
        for (i = 0; i < W * H; i++) {
            assert_true(green(color[i]) <= green(color2[i]));
            darker += green(color[i]) < green(color2[i]);
        }
    }
    assert_true(darker > 1000);
    host_scene_free(&hs);
    srv_scene_free(&s);
}

/* A directional light's map: the box's shadow lands where the light's
 * direction through the box meets the floor. */
static void test_directional_shadow(void **state)
{
    srv_scene s;
    host_scene hs;
    lumo_raster_mesh m;
    lumo_raster_shadow sh;
    static const lumo_q16_16 under[3] = {-3277, 0, 1638};  /* (-0.05, 0, 0.025) */
    static const lumo_q16_16 out_[3] = {-65536, 0, 65536};
    static const lumo_q1_14 up[3] = {0, 16384, 0};
    char err[128];
    (void)state;

    build_scene(&s, "directional:0,-1,0:2,2,2");
    assert_int_equal(host_scene_from_srv(&hs, &s, err, sizeof err), LUMO_OK);
    m = host_mesh_raster(&hs.mesh);
    (void)shadowed_light(&hs, &m, &sh, 256);
    assert_int_equal(sh.faces, 1);
    assert_int_equal(lumo_raster_shadow_visibility(&sh, under, up), 0);
    assert_int_equal(lumo_raster_shadow_visibility(&sh, out_, up), 256);
    host_scene_free(&hs);
    srv_scene_free(&s);
}

static void test_bytes_and_errors(void **state)
{
    lumo_raster_light point = {LUMO_LIGHT_POINT, {0, 0, 0}, {0, 0, 0}, 0, {1 << 16, 1 << 16, 1 << 16}, NULL};
    lumo_raster_light wide = point, narrow = point, dir = point;
    lumo_raster_shadow sh;
    static const lumo_q16_16 c[3] = {0, 0, 0};
    (void)state;

    wide.kind = narrow.kind = LUMO_LIGHT_SPOT;
    wide.dir[1] = narrow.dir[1] = -16384;
    wide.cos_cutoff = 0;                            /* 90 degrees: a cube */
    narrow.cos_cutoff = 8192;                       /* 60 degrees: one face */
    dir.kind = LUMO_LIGHT_DIRECTIONAL;
    dir.dir[1] = -16384;
    assert_int_equal(lumo_raster_shadow_bytes(&point, 128), 6u * 128 * 128 * 2);
    assert_int_equal(lumo_raster_shadow_bytes(&wide, 64), 6u * 64 * 64 * 2);
    assert_int_equal(lumo_raster_shadow_bytes(&narrow, 256), 256u * 256 * 2);
    assert_int_equal(lumo_raster_shadow_bytes(&dir, 256), 256u * 256 * 2);
    assert_int_equal(lumo_raster_shadow_bytes(&point, 4), 0);
    assert_int_equal(lumo_raster_shadow_bytes(&point, LUMO_MAX_FRAME_DIM + 1), 0);
    assert_int_equal(lumo_raster_shadow_bytes(NULL, 64), 0);
    assert_int_equal(lumo_raster_shadow_init(&sh, &point, 64, map_mem, 6 * 64 * 64 * 2 - 1, c, 0, 0),
                     LUMO_ERR_RANGE);
    assert_int_equal(lumo_raster_shadow_init(&sh, &point, 64, NULL, sizeof map_mem, c, 0, 0), LUMO_ERR_ARG);
    assert_int_equal(lumo_raster_shadow_init(&sh, &dir, 64, map_mem, sizeof map_mem, NULL, 0, 0),
                     LUMO_ERR_ARG);
    assert_int_equal(lumo_raster_shadow_init(&sh, &dir, 64, map_mem, sizeof map_mem, c, INT32_MAX, 0),
                     LUMO_ERR_RANGE);
    assert_int_equal(lumo_raster_shadow_draw(NULL, NULL), LUMO_ERR_ARG);
    /* an empty map shadows nothing */
    assert_int_equal(lumo_raster_shadow_init(&sh, &point, 64, map_mem, sizeof map_mem, c, 0, 0), LUMO_OK);
    {
        lumo_q16_16 p[3] = {65536, -131072, 0};
        lumo_q1_14 n[3] = {0, 16384, 0};
        assert_int_equal(lumo_raster_shadow_visibility(&sh, p, n), 256);
    }
}

/* lumo_raster_shadow_views (what the GL backends draw their maps from):
 * the views of lumo_raster_shadow_init for every kind of light, no depth
 * (a lookup is lit), the same refusals. */
static void test_views_only(void **state)
{
    lumo_raster_light lights[3] = {
        {LUMO_LIGHT_POINT, {0, 2 << 16, 0}, {0, 0, 0}, 0, {1 << 16, 1 << 16, 1 << 16}, NULL},
        {LUMO_LIGHT_SPOT, {0, 2 << 16, 0}, {0, -16384, 0}, 8192, {1 << 16, 1 << 16, 1 << 16}, NULL},
        {LUMO_LIGHT_DIRECTIONAL, {0, 0, 0}, {0, -16384, 0}, 0, {1 << 16, 1 << 16, 1 << 16}, NULL}};
    static const lumo_q16_16 c[3] = {0, 1 << 16, 0};
    lumo_raster_shadow a, b;
    int i;
    (void)state;

    for (i = 0; i < 3; i++) {
        lumo_q16_16 p[3] = {0, 0, 0};
        lumo_q1_14 n[3] = {0, 16384, 0};
        assert_int_equal(lumo_raster_shadow_init(&a, &lights[i], 64, map_mem, sizeof map_mem, c, 2 << 16, 0),
                         LUMO_OK);
        memset(&b, 0x5a, sizeof b);
        assert_int_equal(lumo_raster_shadow_views(&b, &lights[i], 64, c, 2 << 16, 0), LUMO_OK);
        assert_null(b.depth);
        assert_int_equal(b.faces, a.faces);
        assert_int_equal(b.size, 64);
        assert_memory_equal(b.face, a.face, a.faces * sizeof a.face[0]);
        assert_int_equal(lumo_raster_shadow_visibility(&b, p, n), 256);
    }
    assert_int_equal(lumo_raster_shadow_views(NULL, &lights[0], 64, c, 0, 0), LUMO_ERR_ARG);
    assert_int_equal(lumo_raster_shadow_views(&b, NULL, 64, c, 0, 0), LUMO_ERR_ARG);
    assert_int_equal(lumo_raster_shadow_views(&b, &lights[0], 4, c, 0, 0), LUMO_ERR_RANGE);
    assert_int_equal(lumo_raster_shadow_views(&b, &lights[0], 64, c, 0, -1), LUMO_ERR_RANGE);
    assert_int_equal(lumo_raster_shadow_views(&b, &lights[2], 64, NULL, 0, 0), LUMO_ERR_ARG);
    assert_int_equal(b.faces, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_point_shadow_vs_path_tracer),
        cmocka_unit_test(test_bands_cache_with_shadows),
        cmocka_unit_test(test_directional_shadow),
        cmocka_unit_test(test_bytes_and_errors),
        cmocka_unit_test(test_views_only),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
