/*
 * test_raster.c — the soft rasterizer (rasterizer/soft): fill rule,
 * watertightness, clipping, depth, culling, bands, cache, error paths,
 * and the shading/tone-map arithmetic against double references.
 */
#include <stdio.h>
#include <stdlib.h>
#include "test_common.h"
#include "lumo/raster.h"
#include "../../tools/lumo-render/mesh_build.h"
#include "../../tools/lumo-render/scene_convert.h"
#include "../../rasterizer/soft/raster_internal.h"

#define W 64
#define H 48

typedef struct frame {
    uint32_t color[W * H];
    uint32_t depth[W * H];
    lumo_raster_target t;
} frame;

static void frame_init(frame *f, lumo_pixel_format fmt, uint8_t depth_bits)
{
    memset(f, 0, sizeof *f);
    assert_int_equal(lumo_raster_target_init(&f->t, W, H, 0, H, fmt, f->color, f->depth, depth_bits),
                     LUMO_OK);
    assert_int_equal(lumo_raster_clear(&f->t, 0x000000), LUMO_OK);
}

/* A camera for which world (x, y, 0) is pixel (W/2 + x, H/2 - y): fovy 90
 * degrees (cot = 1 exactly), eye at distance H/2 on +z. */
static void pixel_camera(lumo_raster_view *v)
{
    lumo_raster_camera cam;
    memset(&cam, 0, sizeof cam);
    cam.eye[2] = LUMO_Q16_FROM_INT(H / 2);
    cam.up[1] = LUMO_Q16_ONE;
    cam.fovy_deg = LUMO_Q16_FROM_INT(90);
    cam.znear = LUMO_Q16_FRAC(1, 100);
    assert_int_equal(lumo_raster_view_init(v, &cam, W, H), LUMO_OK);
}

static const lumo_raster_light white_sun = {
    LUMO_LIGHT_DIRECTIONAL, {0, 0, 0}, {0, 0, -LUMO_Q14_ONE}, 0,
    {205887, 205887, 205887},    /* pi W/m^2: a white albedo-1 face gives L = 1 */
    NULL
};

static lumo_raster_scene flat_scene(uint32_t flags)
{
    lumo_raster_scene s;
    memset(&s, 0, sizeof s);
    s.lights = &white_sun;
    s.light_count = 1;
    s.exposure = LUMO_Q16_ONE;
    s.flags = flags;
    return s;
}

static const double white[3] = {1, 1, 1};

/* A triangle in pixel coordinates (x right, y down), z = 0 plane. */
static void add_pixel_tri(host_mesh *m, double x0, double y0, double x1, double y1,
                          double x2, double y2)
{
    double c[3] = {x0 - W / 2.0, H / 2.0 - y0, 0};
    double u[3] = {x1 - x0, y0 - y1, 0}, v[3] = {x2 - x0, y0 - y2, 0};
    uint32_t n0 = m->vertex_count;
    /* A 1x1 quad gives 4 vertices; keep the first triangle's 3 (c, c+u, c+u+v
     * would be wrong): build the triangle directly instead. */
    host_mesh_add_quad(m, c, u, v, 1, 1, white);
    m->tri_count -= 2;
    m->tris[3 * m->tri_count] = n0;
    m->tris[3 * m->tri_count + 1] = n0 + 1;
    m->tris[3 * m->tri_count + 2] = n0 + 2;
    m->tri_count++;
}

static uint32_t count_lit(const frame *f)
{
    uint32_t i, n = 0;
    for (i = 0; i < W * H; i++)
        n += f->color[i] != 0;
    return n;
}

/* ---- fill rule ------------------------------------------------------------- */

/* A square whose edges run through pixel centres, split on its diagonal:
 * the top-left rule takes the top row and left column, not the bottom row
 * and right column, and the diagonal's pixels exactly once. */
static void test_fill_rule_square(void **state)
{
    static frame f;
    host_mesh m = {0};
    lumo_raster_view v;
    lumo_raster_scene s = flat_scene(0);
    lumo_raster_stats st;
    lumo_raster_mesh rm;
    int x, y;
    (void)state;

    pixel_camera(&v);
    /* corners at pixel centres (10.5, 8.5) .. (20.5, 18.5) */
    add_pixel_tri(&m, 10.5, 8.5, 10.5, 18.5, 20.5, 18.5);
    add_pixel_tri(&m, 10.5, 8.5, 20.5, 18.5, 20.5, 8.5);
    rm = host_mesh_raster(&m);
    frame_init(&f, LUMO_PIXEL_XRGB8888, 32);
    assert_int_equal(lumo_raster_draw_stats(&v, &s, &rm, NULL, &f.t, &st), LUMO_OK);
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            int inside = x >= 10 && x < 20 && y >= 8 && y < 18;
            if ((f.color[y * W + x] != 0) != inside)
                fail_msg("pixel (%d, %d) lit=%d want %d", x, y, f.color[y * W + x] != 0, inside);
        }
    assert_int_equal(st.pixels_tested, 100);   /* diagonal pixels not twice */
    host_mesh_free(&m);
}

/* Both windings give the same coverage when culling is off; with culling the
 * clockwise (back-facing) one is dropped. */
static void test_winding_and_culling(void **state)
{
    static frame a, b;
    host_mesh m1 = {0}, m2 = {0};
    lumo_raster_view v;
    lumo_raster_scene s = flat_scene(0);
    lumo_raster_mesh r1, r2;
    (void)state;

    pixel_camera(&v);
    add_pixel_tri(&m1, 3.2, 4.7, 7.9, 40.1, 50.3, 20.6);
    add_pixel_tri(&m2, 3.2, 4.7, 50.3, 20.6, 7.9, 40.1);
    r1 = host_mesh_raster(&m1);
    r2 = host_mesh_raster(&m2);
    frame_init(&a, LUMO_PIXEL_XRGB8888, 32);
    frame_init(&b, LUMO_PIXEL_XRGB8888, 32);
    lumo_raster_draw(&v, &s, &r1, NULL, &a.t);
    lumo_raster_draw(&v, &s, &r2, NULL, &b.t);
    assert_true(count_lit(&a) > 500);
    assert_memory_equal(a.color, b.color, sizeof a.color);
    s.flags = LUMO_RASTER_CULL_BACK;
    frame_init(&a, LUMO_PIXEL_XRGB8888, 32);
    frame_init(&b, LUMO_PIXEL_XRGB8888, 32);
    lumo_raster_draw(&v, &s, &r1, NULL, &a.t);
    lumo_raster_draw(&v, &s, &r2, NULL, &b.t);
    assert_int_equal(count_lit(&a) == 0, 0);
    assert_int_equal(count_lit(&b) == 0, 1);   /* r2's winding is clockwise seen from +z */
    host_mesh_free(&m1);
    host_mesh_free(&m2);
}

/* ---- watertightness ------------------------------------------------------------ */

/* A finely tessellated, jittered mesh larger than the screen, flat-on and
 * tilted in perspective: every pixel is covered exactly once. */
static void watertight_case(double tilt, int jitter_seed)
{
    static frame f;
    host_mesh m = {0};
    lumo_raster_view v;
    lumo_raster_scene s = flat_scene(0);
    lumo_raster_stats st;
    lumo_raster_mesh rm;
    test_rng rng = {0x9E3779B97F4A7C15ull ^ (uint64_t)jitter_seed};
    const double c[3] = {-200, -150, 0}, u[3] = {400, 0, 0}, vv[3] = {0, 300, 0};
    uint32_t i;

    pixel_camera(&v);
    host_mesh_add_quad(&m, c, u, vv, 101, 77, white);
    /* jitter interior vertices (keeps the mesh a partition of the plane),
     * then tilt the plane around the x axis */
    for (i = 0; i < m.vertex_count; i++) {
        int ix = (int)(i % 102), iy = (int)(i / 102);
        double x = m.pos[3 * i] / 65536.0, y = m.pos[3 * i + 1] / 65536.0;
        /* cells are ~3.9 units: moving each vertex by < 0.9 keeps every
         * quad convex, so the triangles never fold over */
        if (ix > 0 && ix < 101 && iy > 0 && iy < 77) {
            x += test_rng_uniform(&rng, -0.9, 0.9);
            y += test_rng_uniform(&rng, -0.9, 0.9);
        }
        m.pos[3 * i] = host_q16(x);
        m.pos[3 * i + 1] = host_q16(y * cos(tilt));
        m.pos[3 * i + 2] = host_q16(-y * sin(tilt));
    }
    rm = host_mesh_raster(&m);
    frame_init(&f, LUMO_PIXEL_XRGB8888, 32);
    assert_int_equal(lumo_raster_draw_stats(&v, &s, &rm, NULL, &f.t, &st), LUMO_OK);
    if (st.pixels_tested != W * H || count_lit(&f) != W * H) {
        int x, y;
        for (y = 0; y < H; y++) {
            for (x = 0; x < W; x++) putchar(f.color[y * W + x] ? '#' : '.');
            putchar('\n');
        }
        fail_msg("tilt %g: %u pixel tests, %u lit, want %d", tilt, st.pixels_tested, count_lit(&f), W * H);
    }
    host_mesh_free(&m);
}

static void test_watertight_flat(void **state)
{
    (void)state;
    watertight_case(0, 1);
    watertight_case(0, 2);
}

static void test_watertight_perspective(void **state)
{
    (void)state;
    watertight_case(0.6, 3);
    watertight_case(-0.5, 4);   /* steeper would show the horizon */
}

/* The fan of a polygon clipped by the near plane must stay watertight too:
 * a tessellated floor running from behind the camera to far away. */
static void test_watertight_clipped_floor(void **state)
{
    static frame f;
    host_mesh m = {0};
    lumo_raster_view v;
    lumo_raster_camera cam;
    lumo_raster_scene s = flat_scene(0);
    lumo_raster_stats st;
    lumo_raster_mesh rm;
    const double c[3] = {-50, 0, 50}, u[3] = {100, 0, 0}, vv[3] = {0, 0, -100};
    int x, y;
    (void)state;

    memset(&cam, 0, sizeof cam);
    cam.eye[1] = LUMO_Q16_ONE;
    cam.target[1] = LUMO_Q16_ONE;
    cam.target[2] = -LUMO_Q16_ONE;
    cam.up[1] = LUMO_Q16_ONE;
    cam.fovy_deg = LUMO_Q16_FROM_INT(60);
    cam.znear = LUMO_Q16_FRAC(1, 20);
    assert_int_equal(lumo_raster_view_init(&v, &cam, W, H), LUMO_OK);
    host_mesh_add_quad(&m, c, u, vv, 37, 29, white);
    rm = host_mesh_raster(&m);
    frame_init(&f, LUMO_PIXEL_XRGB8888, 32);
    s.lights = NULL;
    s.light_count = 0;
    s.indirect = NULL;
    assert_int_equal(lumo_raster_draw_stats(&v, &s, &rm, NULL, &f.t, &st), LUMO_OK);
    assert_true(st.tris_clipped > 0);
    /* No light: everything black; count coverage via the depth buffer. */
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            int covered = f.depth[y * W + x] != 0;
            if (y >= H / 2 + 2 && !covered)
                fail_msg("floor pixel (%d, %d) not covered", x, y);
            if (y < H / 2 - 2 && covered)
                fail_msg("sky pixel (%d, %d) covered", x, y);
        }
    /* each pixel tested once: the floor is one layer */
    {
        uint32_t n = 0;
        for (x = 0; x < W * H; x++) n += f.depth[x] != 0;
        assert_int_equal(st.pixels_tested, n);
    }
    host_mesh_free(&m);
}

/* ---- clipping extremes ----------------------------------------------------------- */

static void test_huge_and_degenerate(void **state)
{
    static frame f;
    lumo_raster_view v;
    lumo_raster_scene s = flat_scene(0);
    lumo_raster_stats st;
    const int32_t B = LUMO_Q16_FROM_INT(30000);
    lumo_q16_16 pos[] = {
        -B, -B, 0,   B, -B, 0,   0, B, 0,                       /* huge, covers all */
        0, 0, LUMO_Q16_FROM_INT(5),  LUMO_Q16_FROM_INT(3), 0, LUMO_Q16_FROM_INT(5),
        LUMO_Q16_FROM_INT(6), 0, LUMO_Q16_FROM_INT(5),          /* collinear */
        0, 0, LUMO_Q16_FROM_INT(100), LUMO_Q16_ONE, 0, LUMO_Q16_FROM_INT(100),
        0, LUMO_Q16_ONE, LUMO_Q16_FROM_INT(100),                /* behind the eye */
    };
    lumo_q1_14 nrm[9 * 3];
    uint32_t tris[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 3, 3, 3};
    lumo_raster_mesh m;
    int i;
    (void)state;

    for (i = 0; i < 27; i++) nrm[i] = (i % 3 == 2) ? LUMO_Q14_ONE : 0;
    memset(&m, 0, sizeof m);
    m.pos = pos;
    m.normal = nrm;
    m.mesh_albedo[0] = m.mesh_albedo[1] = m.mesh_albedo[2] = LUMO_Q14_ONE;
    m.tris = tris;
    m.vertex_count = 9;
    m.tri_count = 4;
    pixel_camera(&v);
    frame_init(&f, LUMO_PIXEL_XRGB8888, 16);
    assert_int_equal(lumo_raster_draw_stats(&v, &s, &m, NULL, &f.t, &st), LUMO_OK);
    assert_int_equal(st.pixels_tested, W * H);
    assert_int_equal(count_lit(&f), W * H);
    /* a white face lit by E = pi: L = 1 -> 255 */
    assert_int_equal(f.color[0], 0xFFFFFF);
}

/* Vertices far outside the screen on every side, triangle through it. */
static void test_far_outside_vertices(void **state)
{
    static frame f;
    host_mesh m = {0};
    lumo_raster_view v;
    lumo_raster_scene s = flat_scene(0);
    lumo_raster_mesh rm;
    int x, y;
    (void)state;

    pixel_camera(&v);
    /* a band crossing the screen diagonally, corners 20000 px away */
    add_pixel_tri(&m, -20000, -20000, 20032, 20024 + 8, 20032 + 8, 20024);
    rm = host_mesh_raster(&m);
    frame_init(&f, LUMO_PIXEL_XRGB8888, 32);
    assert_int_equal(lumo_raster_draw(&v, &s, &rm, NULL, &f.t), LUMO_OK);
    /* a thin sliver along y = x, 8 pixels wide at the screen */
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++)
        {
            /* between the lines y = x and y ~ x - 8 (through the far corners) */
            int inside = y - x <= -1 && y - x >= -7, outside = y - x > 1 || y - x < -10;
            if (f.color[y * W + x] ? outside : inside)
                fail_msg("pixel (%d, %d) lit=%d", x, y, f.color[y * W + x] != 0);
        }
    assert_true(count_lit(&f) > 0);
    host_mesh_free(&m);
}

/* ---- depth ------------------------------------------------------------------------- */

static void depth_case(uint8_t bits)
{
    static frame a, b;
    host_mesh m = {0};
    lumo_raster_view v;
    lumo_raster_scene s = flat_scene(0);
    lumo_raster_mesh rm;
    const double red[3] = {1, 0, 0}, blue[3] = {0, 0, 1};
    /* blue nearer by 0.05 (32-bit) or 2 (16-bit: at w = 24 with znear =
     * 0.01 one step of znear/w is ~0.9 units of depth) */
    const double c1[3] = {-20, -15, 0}, c2[3] = {-5, -5, bits == 16 ? 2.0 : 0.05};
    const double u1[3] = {30, 0, 0}, v1[3] = {0, 25, 0}, u2[3] = {20, 0, 0}, v2[3] = {0, 15, 0};
    uint32_t i, tmp[6];

    pixel_camera(&v);
    host_mesh_add_quad(&m, c1, u1, v1, 3, 2, red);
    host_mesh_add_quad(&m, c2, u2, v2, 2, 3, blue);
    rm = host_mesh_raster(&m);
    frame_init(&a, LUMO_PIXEL_XRGB8888, bits);
    lumo_raster_draw(&v, &s, &rm, NULL, &a.t);
    /* reverse the triangle order */
    for (i = 0; i < m.tri_count / 2; i++) {
        memcpy(tmp, &m.tris[3 * i], 12);
        memcpy(&m.tris[3 * i], &m.tris[3 * (m.tri_count - 1 - i)], 12);
        memcpy(&m.tris[3 * (m.tri_count - 1 - i)], tmp, 12);
    }
    frame_init(&b, LUMO_PIXEL_XRGB8888, bits);
    lumo_raster_draw(&v, &s, &rm, NULL, &b.t);
    assert_memory_equal(a.color, b.color, sizeof a.color);
    assert_int_equal(a.color[(H / 2) * W + W / 2], 0x0000FF);      /* blue in front */
    assert_int_equal(a.color[(H / 2 + 12) * W + W / 2 - 17], 0xFF0000);
    host_mesh_free(&m);
}

static void test_depth16(void **state) { (void)state; depth_case(16); }
static void test_depth32(void **state) { (void)state; depth_case(32); }

/* ---- bands, cache, formats ------------------------------------------------------------ */

static void build_spheres(host_mesh *m)
{
    const double c1[3] = {-0.3, 0, 0}, c2[3] = {0.35, 0.1, -0.4};
    const double a1[3] = {0.8, 0.3, 0.2}, a2[3] = {0.2, 0.5, 0.9};
    const double fc[3] = {-3, -0.5, 3}, fu[3] = {6, 0, 0}, fv[3] = {0, 0, -6};
    host_mesh_add_sphere(m, c1, 0.5, 24, 0, a1);
    host_mesh_add_sphere(m, c2, 0.45, 20, 0, a2);
    host_mesh_add_quad(m, fc, fu, fv, 6, 6, white);
}

static void scene_camera(lumo_raster_view *v)
{
    lumo_raster_camera cam;
    memset(&cam, 0, sizeof cam);
    assert_int_equal(host_camera_from_string("0.3,0.8,2.2:0,0,0:0,1,0:50", &cam), LUMO_OK);
    cam.znear = host_q16(0.05);
    assert_int_equal(lumo_raster_view_init(v, &cam, W, H), LUMO_OK);
}

static lumo_raster_light scene_lights[3];

static lumo_raster_scene lit_scene(uint32_t flags)
{
    lumo_raster_scene s;
    assert_int_equal(host_light_from_string("point:1,2,1.5:30,25,20", &scene_lights[0]), LUMO_OK);
    assert_int_equal(host_light_from_string("spot:-1,1.5,0.5:1,-1,-0.3:25:40,40,60", &scene_lights[1]), LUMO_OK);
    assert_int_equal(host_light_from_string("directional:0.3,-1,-0.2:0.3,0.3,0.35", &scene_lights[2]), LUMO_OK);
    memset(&s, 0, sizeof s);
    s.lights = scene_lights;
    s.light_count = 3;
    s.exposure = LUMO_Q16_ONE;
    s.flags = flags;
    return s;
}

static uint64_t fnv1a(const void *p, size_t n)
{
    const uint8_t *b = p;
    uint64_t h = 1469598103934665603ull;
    while (n--) { h ^= *b++; h *= 1099511628211ull; }
    return h;
}

static void render_bands(const lumo_raster_view *v, const lumo_raster_scene *s,
                         const lumo_raster_mesh *m, const lumo_raster_vertex *cache,
                         lumo_pixel_format fmt, uint8_t bits, int K, uint8_t *out)
{
    static uint32_t color[W * H], depth[W * H];
    size_t px = fmt == LUMO_PIXEL_RGB565 ? 2 : 4;
    int y0;

    for (y0 = 0; y0 < H; y0 += K) {
        lumo_raster_target t;
        int rows = H - y0 < K ? H - y0 : K;
        assert_int_equal(lumo_raster_target_init(&t, W, H, (uint16_t)y0, (uint16_t)rows, fmt,
                                                 color, depth, bits), LUMO_OK);
        assert_int_equal(lumo_raster_clear(&t, 0x102030), LUMO_OK);
        assert_int_equal(lumo_raster_draw(v, s, m, cache, &t), LUMO_OK);
        memcpy(out + (size_t)y0 * W * px, color, (size_t)rows * W * px);
    }
}

static void test_bands_equal_full_frame(void **state)
{
    static uint8_t full[W * H * 4], band[W * H * 4];
    host_mesh m = {0};
    lumo_raster_view v;
    lumo_raster_mesh rm;
    static const uint32_t modes[2] = {0, LUMO_RASTER_PER_PIXEL};
    int mode, fmt, K;
    (void)state;

    build_spheres(&m);
    rm = host_mesh_raster(&m);
    scene_camera(&v);
    for (mode = 0; mode < 2; mode++)
        for (fmt = 0; fmt < 2; fmt++) {
            lumo_raster_scene s = lit_scene(modes[mode] | LUMO_RASTER_CULL_BACK);
            lumo_pixel_format pf = fmt ? LUMO_PIXEL_RGB565 : LUMO_PIXEL_XRGB8888;
            size_t bytes = (size_t)W * H * (fmt ? 2 : 4);
            render_bands(&v, &s, &rm, NULL, pf, 16, H, full);
            for (K = 1; K < H; K++) {
                render_bands(&v, &s, &rm, NULL, pf, 16, K, band);
                if (memcmp(full, band, bytes))
                    fail_msg("mode %d format %d: K=%d differs from the full frame", mode, fmt, K);
            }
        }
    host_mesh_free(&m);
}

/* The vertex cache changes the work, not the bytes; culling changes neither
 * on closed meshes. */
static void test_cache_and_cull_equal(void **state)
{
    static uint8_t a[W * H * 4], b[W * H * 4];
    host_mesh m = {0};
    lumo_raster_view v;
    lumo_raster_mesh rm;
    lumo_raster_vertex *cache;
    int mode;
    (void)state;

    build_spheres(&m);
    m.tri_count -= 72;   /* drop the floor: the spheres alone are closed */
    rm = host_mesh_raster(&m);
    scene_camera(&v);
    cache = malloc(lumo_raster_cache_bytes(rm.vertex_count));
    for (mode = 0; mode < 2; mode++) {
        lumo_raster_scene s = lit_scene(mode ? LUMO_RASTER_PER_PIXEL : 0);
        render_bands(&v, &s, &rm, NULL, LUMO_PIXEL_XRGB8888, 32, H, a);
        s.flags |= LUMO_RASTER_CULL_BACK;
        assert_int_equal(lumo_raster_prepare(&v, &s, &rm, cache), LUMO_OK);
        render_bands(&v, &s, &rm, cache, LUMO_PIXEL_XRGB8888, 32, 7, b);
        assert_memory_equal(a, b, sizeof a);
    }
    free(cache);
    host_mesh_free(&m);
}

/* LUMO_RASTER_DEPTH_FIRST shades each pixel once and changes no byte:
 * colour and depth equal without it, per pixel, for both depth widths and
 * pixel formats, whole frames and bands; pixels_written drops to one per
 * covered pixel (the spheres are drawn with their back faces and over the
 * floor: overdraw). Into a band whose depth holds an earlier draw it does
 * nothing (a tie with that draw would go the other way). */
static void draw_counted(const lumo_raster_view *v, const lumo_raster_scene *s, const lumo_raster_mesh *m,
                         lumo_raster_target *t, int clear, uint32_t *written)
{
    lumo_raster_stats st;

    if (clear)
        assert_int_equal(lumo_raster_clear(t, 0x102030), LUMO_OK);
    assert_int_equal(lumo_raster_draw_stats(v, s, m, NULL, t, &st), LUMO_OK);
    *written += st.pixels_written;
}

static void test_depth_first_same_bytes(void **state)
{
    static uint32_t c0[W * H], d0[W * H], c1[W * H], d1[W * H];
    static const int bands[3] = {H, 16, 7};
    host_mesh m = {0};
    lumo_raster_view v;
    lumo_raster_mesh rm;
    int fmt, bits, k, y0;
    (void)state;

    build_spheres(&m);
    rm = host_mesh_raster(&m);
    scene_camera(&v);
    for (fmt = 0; fmt < 2; fmt++)
        for (bits = 16; bits <= 32; bits += 16)
            for (k = 0; k < 3; k++) {
                lumo_pixel_format pf = fmt ? LUMO_PIXEL_RGB565 : LUMO_PIXEL_XRGB8888;
                lumo_raster_scene s = lit_scene(LUMO_RASTER_PER_PIXEL), sf = s;
                uint32_t plain = 0, first = 0, covered = 0;
                sf.flags |= LUMO_RASTER_DEPTH_FIRST;
                for (y0 = 0; y0 < H; y0 += bands[k]) {
                    lumo_raster_target a, b;
                    uint16_t rows = (uint16_t)(H - y0 < bands[k] ? H - y0 : bands[k]);
                    size_t n = (size_t)W * rows;
                    uint32_t i;
                    assert_int_equal(lumo_raster_target_init(&a, W, H, (uint16_t)y0, rows, pf, c0, d0, (uint8_t)bits), LUMO_OK);
                    assert_int_equal(lumo_raster_target_init(&b, W, H, (uint16_t)y0, rows, pf, c1, d1, (uint8_t)bits), LUMO_OK);
                    draw_counted(&v, &s, &rm, &a, 1, &plain);
                    draw_counted(&v, &sf, &rm, &b, 1, &first);
                    assert_memory_equal(c0, c1, n * (fmt ? 2 : 4));
                    assert_memory_equal(d0, d1, n * (size_t)bits / 8);
                    for (i = 0; i < n; i++)
                        covered += bits == 16 ? ((uint16_t *)(void *)d0)[i] != 0 : d0[i] != 0;
                    /* a second draw into the same band: the pass is skipped */
                    draw_counted(&v, &s, &rm, &a, 0, &plain);
                    draw_counted(&v, &sf, &rm, &b, 0, &first);
                    assert_memory_equal(c0, c1, n * (fmt ? 2 : 4));
                    assert_memory_equal(d0, d1, n * (size_t)bits / 8);
                }
                /* written: once per covered pixel in the first draws, nothing
                 * in the second (all ties lose) for both */
                assert_int_equal(first, covered);
                assert_true(plain > first);
            }
    host_mesh_free(&m);
}

/* box_hidden (raster_span.c) drops a small per-vertex triangle whose box
 * already holds depths its nearest vertex would fail; it runs without
 * stats only (they count the tested pixels). The same bytes either way:
 * the spheres' small triangles with their back faces (overdraw), drawn
 * twice into the same target (the second draw: every triangle hidden),
 * both depth widths and pixel formats, whole frames and bands. */
static void test_hidden_skip_same_bytes(void **state)
{
    static uint32_t c0[W * H], d0[W * H], c1[W * H], d1[W * H];
    static const int bands[2] = {H, 7};
    static const double qa[3] = {-0.8, -0.8, 0}, qb[3] = {-0.8, -0.8, -0.8};
    static const double qu[3] = {1.6, 0, 0}, qv[3] = {0, 1.6, 0}, qw[3] = {0, 1.6, 1.6};
    host_mesh m = {0};
    lumo_raster_view v;
    lumo_raster_mesh rm;
    int fmt, bits, k, y0, pass;
    (void)state;

    build_spheres(&m);
    /* then two finely cut quads through each other: the second's small
     * triangles along the crossing have vertices on both sides of the
     * first's depths (a wrong bound drops pixels there) */
    host_mesh_add_quad(&m, qa, qu, qv, 40, 40, white);
    host_mesh_add_quad(&m, qb, qu, qw, 40, 40, white);
    rm = host_mesh_raster(&m);
    scene_camera(&v);
    for (fmt = 0; fmt < 2; fmt++)
        for (bits = 16; bits <= 32; bits += 16)
            for (k = 0; k < 2; k++)
                for (y0 = 0; y0 < H; y0 += bands[k]) {
                    lumo_pixel_format pf = fmt ? LUMO_PIXEL_RGB565 : LUMO_PIXEL_XRGB8888;
                    lumo_raster_scene s = lit_scene(0);
                    uint16_t rows = (uint16_t)(H - y0 < bands[k] ? H - y0 : bands[k]);
                    size_t n = (size_t)W * rows;
                    lumo_raster_target a, b;
                    lumo_raster_stats st;
                    assert_int_equal(lumo_raster_target_init(&a, W, H, (uint16_t)y0, rows, pf, c0, d0, (uint8_t)bits), LUMO_OK);
                    assert_int_equal(lumo_raster_target_init(&b, W, H, (uint16_t)y0, rows, pf, c1, d1, (uint8_t)bits), LUMO_OK);
                    assert_int_equal(lumo_raster_clear(&a, 0x102030), LUMO_OK);
                    assert_int_equal(lumo_raster_clear(&b, 0x102030), LUMO_OK);
                    for (pass = 0; pass < 2; pass++) {
                        assert_int_equal(lumo_raster_draw_stats(&v, &s, &rm, NULL, &a, &st), LUMO_OK);
                        assert_int_equal(lumo_raster_draw(&v, &s, &rm, NULL, &b), LUMO_OK);
                        assert_memory_equal(c0, c1, n * (fmt ? 2 : 4));
                        assert_memory_equal(d0, d1, n * (size_t)bits / 8);
                    }
                }
    host_mesh_free(&m);
}

/* Golden hashes: any change to the integer pipeline shows here. Update only
 * deliberately (and say why in the commit). */
static void test_golden_hashes(void **state)
{
    static uint8_t img[W * H * 4];
    host_mesh m = {0};
    lumo_raster_view v;
    lumo_raster_mesh rm;
    static const uint64_t golden[4] = {0xea74a931e89348a6ull, 0xb76e5ac5440e195aull,
                                       0x9aea95f7a0274626ull, 0x9e46171ec7b20168ull};
    int mode, fmt, bad = 0;
    (void)state;

    build_spheres(&m);
    rm = host_mesh_raster(&m);
    scene_camera(&v);
    for (mode = 0; mode < 2; mode++)
        for (fmt = 0; fmt < 2; fmt++) {
            lumo_raster_scene s = lit_scene(mode ? LUMO_RASTER_PER_PIXEL : 0);
            uint64_t h;
            render_bands(&v, &s, &rm, NULL, fmt ? LUMO_PIXEL_RGB565 : LUMO_PIXEL_XRGB8888, 32, H, img);
            h = fnv1a(img, (size_t)W * H * (fmt ? 2 : 4));
            if (h != golden[mode * 2 + fmt]) {
                printf("golden[%d] = 0x%016llxull\n", mode * 2 + fmt, (unsigned long long)h);
                bad = 1;
            }
        }
    assert_int_equal(bad, 0);
    host_mesh_free(&m);
}

/* ---- errors ------------------------------------------------------------------------------ */

static void test_errors_leave_target(void **state)
{
    static frame f;
    host_mesh m = {0};
    lumo_raster_view v;
    lumo_raster_scene s = flat_scene(0);
    lumo_raster_mesh rm;
    lumo_raster_camera cam;
    (void)state;

    pixel_camera(&v);
    add_pixel_tri(&m, 1, 1, 1, 30, 30, 30);
    add_pixel_tri(&m, 1, 1, 30, 30, 30, 1);
    m.tris[5] = 99;   /* out of range index in the second triangle */
    rm = host_mesh_raster(&m);
    frame_init(&f, LUMO_PIXEL_XRGB8888, 32);
    assert_int_equal(lumo_raster_draw(&v, &s, &rm, NULL, &f.t), LUMO_ERR_RANGE);
    assert_int_equal(count_lit(&f), 0);
    f.t.band_rows = H + 1;
    assert_int_equal(lumo_raster_draw(&v, &s, &rm, NULL, &f.t), LUMO_ERR_RANGE);
    f.t.band_rows = H;
    f.t.depth_bits = 24;
    assert_int_equal(lumo_raster_draw(&v, &s, &rm, NULL, &f.t), LUMO_ERR_RANGE);
    f.t.depth_bits = 32;
    assert_int_equal(lumo_raster_draw(NULL, &s, &rm, NULL, &f.t), LUMO_ERR_ARG);
    /* degenerate cameras */
    memset(&cam, 0, sizeof cam);
    cam.up[1] = LUMO_Q16_ONE;
    cam.fovy_deg = LUMO_Q16_FROM_INT(45);
    cam.znear = LUMO_Q16_ONE;
    assert_int_equal(lumo_raster_view_init(&v, &cam, W, H), LUMO_ERR_RANGE);   /* eye == target */
    cam.target[1] = LUMO_Q16_FROM_INT(3);
    assert_int_equal(lumo_raster_view_init(&v, &cam, W, H), LUMO_ERR_RANGE);   /* up parallel */
    cam.target[1] = 0;
    cam.target[2] = -LUMO_Q16_ONE;
    cam.fovy_deg = LUMO_Q16_FROM_INT(180);
    assert_int_equal(lumo_raster_view_init(&v, &cam, W, H), LUMO_ERR_RANGE);
    cam.fovy_deg = LUMO_Q16_FROM_INT(45);
    cam.znear = 0;
    assert_int_equal(lumo_raster_view_init(&v, &cam, W, H), LUMO_ERR_RANGE);
    cam.znear = LUMO_Q16_ONE;
    assert_int_equal(lumo_raster_view_init(&v, &cam, W, 4096), LUMO_ERR_RANGE);
    assert_int_equal(lumo_raster_view_init(&v, &cam, W, H), LUMO_OK);
    assert_int_equal(lumo_raster_band_bytes(320, 16, LUMO_PIXEL_RGB565, 16), 320 * 16 * 4);
    assert_int_equal(lumo_raster_band_bytes(320, 0, LUMO_PIXEL_RGB565, 16), 0);
    host_mesh_free(&m);
}

/* ---- arithmetic against doubles ------------------------------------------------------------ */

static void test_cot_half(void **state)
{
    int tenth;
    (void)state;
    for (tenth = 10; tenth <= 1790; tenth += 7) {
        double deg = tenth / 10.0, want = 1.0 / tan(deg * M_PI / 360.0);
        lumo_q16_16 got = lumo_raster_cot_half_deg(host_q16(deg));
        /* one Q16 ulp plus the input's rounding of the angle */
        assert_close(got / 65536.0, want, 2.0 / 65536 + want * 1e-6 + want * want * 1e-5 / 65536 * 180);
    }
    assert_int_equal(lumo_raster_cot_half_deg(LUMO_Q16_FROM_INT(90)), LUMO_Q16_ONE);
    assert_int_equal(lumo_raster_cot_half_deg(0), 0);
}

/* The rasterizer's Newton square root equals lumo_isqrt64 everywhere we
 * can reach: random values of every magnitude, squares and their
 * neighbours, powers of two, the extremes. */
static void test_isqrt(void **state)
{
    test_rng rng = {4242};
    uint64_t r;
    int i, sh;
    (void)state;
    for (r = 0; r < 70000; r++)
        assert_int_equal(lumo_raster_isqrt(r), lumo_isqrt64(r));
    for (i = 0; i < 200000; i++) {
        uint64_t v = test_rng_next(&rng) >> (test_rng_next(&rng) % 64);
        uint64_t q = (uint64_t)lumo_isqrt64(v);
        assert_int_equal(lumo_raster_isqrt(v), q);
        assert_int_equal(lumo_raster_isqrt(q * q), q);
        if (q) assert_int_equal(lumo_raster_isqrt(q * q - 1), q - 1);
    }
    for (sh = 0; sh < 64; sh++) {
        uint64_t p2 = (uint64_t)1 << sh;
        assert_int_equal(lumo_raster_isqrt(p2), lumo_isqrt64(p2));
        assert_int_equal(lumo_raster_isqrt(p2 - 1), lumo_isqrt64(p2 - 1));
        assert_int_equal(lumo_raster_isqrt(p2 + 1), lumo_isqrt64(p2 + 1));
    }
    assert_int_equal(lumo_raster_isqrt(UINT64_MAX), 0xFFFFFFFFu);
    assert_int_equal(lumo_raster_isqrt((uint64_t)0xFFFFFFFFu * 0xFFFFFFFFu), 0xFFFFFFFFu);
}

static double srgb(double v)
{
    v = v < 0 ? 0 : v > 1 ? 1 : v;
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055;
}

static void test_tonemap(void **state)
{
    test_rng rng = {12345};
    int i, off = 0;
    (void)state;
    for (i = 0; i < 200000; i++) {
        uint32_t l = (uint32_t)(test_rng_next(&rng) >> 46);          /* [0, 4) */
        uint32_t e = (uint32_t)(test_rng_next(&rng) >> 47) + 1;     /* (0, 2) */
        double x = (double)l / 65536 * ((double)e / 65536);
        double want = srgb(x) * 255;
        int got = lumo_raster_tonemap(l, e);
        int r = (int)floor(want + 0.5);
        if (got != r) {
            /* only on a rounding boundary (the fixed product is exact to 2^-24) */
            assert_true(fabs(want - floor(want) - 0.5) < 1e-3);
            off++;
        }
    }
    assert_true(off < 50);
    assert_int_equal(lumo_raster_tonemap(LUMO_Q16_ONE, LUMO_Q16_ONE), 255);
    assert_int_equal(lumo_raster_tonemap(0, LUMO_Q16_ONE), 0);
    assert_int_equal(lumo_raster_tonemap(0xFFFFFFFFu, 0xFFFFFFFFu), 255);
}

/* Direct light against the formulas of docs/scene-format.md. */
static void test_irradiance(void **state)
{
    test_rng rng = {777};
    lumo_raster_light l[3];
    lumo_raster_scene s;
    int i, k;
    (void)state;

    assert_int_equal(host_light_from_string("point:0.5,2,-0.3:30,20,10", &l[0]), LUMO_OK);
    assert_int_equal(host_light_from_string("spot:-1,1.5,0.5:1,-1,-0.3:35:40,40,60", &l[1]), LUMO_OK);
    assert_int_equal(host_light_from_string("directional:0.3,-1,-0.2:2,3,4", &l[2]), LUMO_OK);
    memset(&s, 0, sizeof s);
    s.lights = l;
    s.light_count = 3;
    for (i = 0; i < 5000; i++) {
        double p[3], n[3], len = 0, e[3] = {0, 0, 0};
        lumo_q16_16 pq[3];
        lumo_q1_14 nq[3];
        lumo_uq16_16 got[3];
        for (k = 0; k < 3; k++) {
            p[k] = test_rng_uniform(&rng, -1, 1);
            n[k] = test_rng_uniform(&rng, -1, 1);
            len += n[k] * n[k];
        }
        len = sqrt(len);
        for (k = 0; k < 3; k++) {
            n[k] /= len;
            pq[k] = host_q16(p[k]);
            nq[k] = host_q14(n[k]);
        }
        {   /* references from the quantised inputs */
            const double *P[2] = {(const double[]){0.5, 2, -0.3}, (const double[]){-1, 1.5, 0.5}};
            const double phi[2][3] = {{30, 20, 10}, {40, 40, 60}};
            double ax[3] = {1, -1, -0.3}, al = sqrt(1 + 1 + 0.09), dd[3] = {0.3, -1, -0.2},
                   dl = sqrt(0.09 + 1 + 0.04);
            int j;
            for (j = 0; j < 2; j++) {
                double w[3], d2 = 0, c = 0, ca = 0;
                for (k = 0; k < 3; k++) { w[k] = P[j][k] - pq[k] / 65536.0; d2 += w[k] * w[k]; }
                for (k = 0; k < 3; k++) { w[k] /= sqrt(d2); c += nq[k] / 16384.0 * w[k]; ca -= w[k] * ax[k] / al; }
                if (j == 1 && fabs(ca - cos(35 * M_PI / 180)) < 2e-3) goto skip;   /* cone edge */
                if (c <= 0 || (j == 1 && ca < cos(35 * M_PI / 180))) continue;
                for (k = 0; k < 3; k++) e[k] += phi[j][k] / (4 * M_PI) * c / (d2 < 256 / 65536.0 ? 256 / 65536.0 : d2);
            }
            {
                double c = 0;
                for (k = 0; k < 3; k++) c -= nq[k] / 16384.0 * dd[k] / dl;
                if (c > 0) { e[0] += 2 * c; e[1] += 3 * c; e[2] += 4 * c; }
            }
        }
        lumo_raster_irradiance(&s, pq, nq, got);
        for (k = 0; k < 3; k++)
            if (fabs(got[k] / 65536.0 - e[k]) > 4e-3 * e[k] + 4e-4)
                fail_msg("p (%g %g %g) n (%g %g %g) k %d: got %g want %g", p[0], p[1], p[2],
                         n[0], n[1], n[2], k, got[k] / 65536.0, e[k]);
skip:;
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fill_rule_square),
        cmocka_unit_test(test_winding_and_culling),
        cmocka_unit_test(test_watertight_flat),
        cmocka_unit_test(test_watertight_perspective),
        cmocka_unit_test(test_watertight_clipped_floor),
        cmocka_unit_test(test_huge_and_degenerate),
        cmocka_unit_test(test_far_outside_vertices),
        cmocka_unit_test(test_depth16),
        cmocka_unit_test(test_depth32),
        cmocka_unit_test(test_bands_equal_full_frame),
        cmocka_unit_test(test_cache_and_cull_equal),
        cmocka_unit_test(test_depth_first_same_bytes),
        cmocka_unit_test(test_hidden_skip_same_bytes),
        cmocka_unit_test(test_golden_hashes),
        cmocka_unit_test(test_errors_leave_target),
        cmocka_unit_test(test_cot_half),
        cmocka_unit_test(test_isqrt),
        cmocka_unit_test(test_tonemap),
        cmocka_unit_test(test_irradiance),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
