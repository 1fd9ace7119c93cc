/*
 * golden_raster.c — the soft rasterizer (lumo/raster.h) on the board, frame
 * bytes hashed against the host (ARCHITECTURE.md: the same stream gives the
 * same frame bytes on every board). A Cornell box with a block inside, built
 * in integer code, drawn at 160 x 120: per-vertex lighting to XRGB8888;
 * per-pixel lighting to XRGB8888 in one pass and again in 4 bands of 30
 * rows (the bytes must not depend on the band split — checked here); and
 * per-pixel with IVG indirect light to dithered RGB565 with a 16-bit depth
 * buffer, and the same with the IVG sampled once per vertex side; then
 * with the point light's 6 x 64^2 shadow cube map (drawn on the board by
 * the rasterizer itself): per vertex, per pixel, and per pixel in 4 bands
 * (again equal to the one-pass frame).
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include "lumo/ivg.h"
#include "lumo/raster.h"
#include "board.h"
#include "golden.h"
#include "ivg_wire.h"

int main(void);

#define W 160
#define H 120
#define MAX_VERTS 64
#define MAX_TRIS 48

static lumo_q16_16 g_pos[MAX_VERTS * 3];
static lumo_q1_14 g_nrm[MAX_VERTS * 3], g_alb[MAX_VERTS * 3];
static uint32_t g_tris[MAX_TRIS * 3];
static lumo_raster_mesh g_mesh;
static lumo_raster_vertex g_cache[MAX_VERTS];
static uint32_t g_color[W * H], g_band_color[W * H];
static uint32_t g_depth[W * H];
static uint16_t g_color565[W * H], g_color565_exact[W * H];
static lumo_uq16_16 g_ind[MAX_VERTS * 6];
static uint8_t g_ivg_mem[1u << 16];
static uint8_t g_bundle[WIRE_HEADER + 27u * WIRE_QUANT_RECORD];
#define SHADOW_SIZE 64
static uint16_t g_shadow_map[6 * SHADOW_SIZE * SHADOW_SIZE];

#define Q(n, d) LUMO_Q16_FRAC(n, d)

/* A quad c, c+u, c+u+v, c+v (tenths of a unit), normal n, albedo a. */
static void quad(const int32_t c[3], const int32_t u[3], const int32_t v[3], const int16_t n[3],
                 const int16_t a[3])
{
    uint32_t base = g_mesh.vertex_count, i;
    int k;

    for (i = 0; i < 4; i++) {
        for (k = 0; k < 3; k++) {
            int32_t p = c[k] + ((i == 1 || i == 2) ? u[k] : 0) + (i >= 2 ? v[k] : 0);
            g_pos[(base + i) * 3 + (uint32_t)k] = Q(p, 10);
            g_nrm[(base + i) * 3 + (uint32_t)k] = n[k];
            g_alb[(base + i) * 3 + (uint32_t)k] = a[k];
        }
    }
    for (i = 0; i < 3; i++) {
        g_tris[g_mesh.tri_count * 3 + i] = base + i;
        g_tris[g_mesh.tri_count * 3 + 3 + i] = base + (i == 0 ? 0 : i + 1);
    }
    g_mesh.vertex_count += 4;
    g_mesh.tri_count += 2;
}

static void build_scene(void)
{
    static const int16_t white[3] = {12000, 12000, 12000}, red[3] = {10000, 1000, 1000},
                         green[3] = {1500, 9000, 1500}, grey[3] = {9000, 9000, 8000};
    static const int16_t up[3] = {0, 16384, 0}, down[3] = {0, -16384, 0}, fwd[3] = {0, 0, 16384},
                         right[3] = {16384, 0, 0}, left[3] = {-16384, 0, 0}, back[3] = {0, 0, -16384};
    /* walls of the box [-10, 10]^3 tenths, seen from +z */
    static const int32_t c_floor[3] = {-10, -10, 10}, u_x[3] = {20, 0, 0}, v_mz[3] = {0, 0, -20};
    static const int32_t c_ceil[3] = {-10, 10, 10}, c_back[3] = {-10, -10, -10}, v_y[3] = {0, 20, 0};
    static const int32_t c_left[3] = {-10, -10, 10}, c_right[3] = {10, -10, 10};
    /* a block 6 x 12 x 6 tenths standing on the floor */
    static const int32_t b_front[3] = {-5, -10, 2}, b_u[3] = {6, 0, 0}, b_v[3] = {0, 12, 0};
    static const int32_t b_back[3] = {-5, -10, -4}, b_top[3] = {-5, 2, 2}, b_d[3] = {0, 0, -6};
    static const int32_t b_left[3] = {-5, -10, 2}, b_right[3] = {1, -10, 2};

    memset(&g_mesh, 0, sizeof g_mesh);
    quad(c_floor, u_x, v_mz, up, white);
    quad(c_ceil, u_x, v_mz, down, white);
    quad(c_back, u_x, v_y, fwd, white);
    quad(c_left, v_mz, v_y, right, red);
    quad(c_right, v_mz, v_y, left, green);
    quad(b_front, b_u, b_v, fwd, grey);
    quad(b_back, b_u, b_v, back, grey);
    quad(b_top, b_u, b_d, up, grey);
    quad(b_left, b_d, b_v, left, grey);
    quad(b_right, b_d, b_v, right, grey);
    g_mesh.pos = g_pos;
    g_mesh.normal = g_nrm;
    g_mesh.albedo = g_alb;
    g_mesh.tris = g_tris;
}

/* A 3 x 3 x 3 IVG over the box: each hemisphere's colour leans towards the
 * wall it faces (red on -x, green on +x), d along the axis. */
static const lumo_ivg *build_ivg(void)
{
    static const lumo_ivg_desc desc = {{3, 3, 3}, {-LUMO_Q16_ONE, -LUMO_Q16_ONE, -LUMO_Q16_ONE},
                                       {LUMO_Q16_ONE, LUMO_Q16_ONE, LUMO_Q16_ONE}};
    lumo_arena a;
    lumo_ivg *g;
    size_t n = WIRE_HEADER;
    uint32_t v;
    int ax, k;

    for (v = 0; v < 27; v++) {
        wire_qentry e[6];
        for (ax = 0; ax < 6; ax++) {
            for (k = 0; k < 3; k++) {
                e[ax].d[k] = (int8_t)(k == ax / 2 ? (ax % 2 ? -127 : 127) : 0);
                e[ax].m[k] = (uint16_t)(200 + 20 * v);
            }
            if (ax == LUMO_IVG_NX)
                e[ax].m[0] = 500;
            if (ax == LUMO_IVG_PX)
                e[ax].m[1] = 500;
            e[ax].e = 14;
        }
        n += wire_quant_record(g_bundle + n, v, e);
    }
    wire_header(g_bundle, LUMO_IVG_FORM_QUANTIZED, desc.dims, 27);
    lumo_arena_init(&a, g_ivg_mem, sizeof g_ivg_mem);
    if (lumo_ivg_create(&g, &a, &desc) != LUMO_OK || lumo_ivg_apply_bundle(g, g_bundle, n, NULL) != LUMO_OK)
        return NULL;
    return g;
}

static void init_target(lumo_raster_target *t, lumo_pixel_format f, void *color, uint16_t y,
                        uint16_t rows, uint8_t depth_bits)
{
    lumo_raster_target_init(t, W, H, y, rows, f, color, g_depth, depth_bits);
}

/* Draw one frame (or band); returns 0 on success. */
static int draw(const lumo_raster_scene *s, lumo_raster_target *t)
{
    static const lumo_raster_camera cam = {
        {0, 0, Q(35, 10)}, {0, 0, 0}, {0, LUMO_Q16_ONE, 0}, Q(40, 1), Q(1, 10)
    };
    lumo_raster_view view;

    if (lumo_raster_view_init(&view, &cam, W, H) != LUMO_OK
        || lumo_raster_clear(t, 0x101010u) != LUMO_OK
        || lumo_raster_prepare(&view, s, &g_mesh, g_cache) != LUMO_OK)
        return 1;
    return lumo_raster_draw(&view, s, &g_mesh, g_cache, t) != LUMO_OK;
}

static uint64_t hash_words(const uint32_t *p, size_t n)
{
    uint64_t h = BT_FNV_OFFSET;
    size_t i;

    for (i = 0; i < n; i++)
        h = bt_fnv1a_u32(h, p[i]);
    return h;
}

/* Hash of frame `label` drawn whole, then (check_bands) in 4 bands of 30
 * rows that must give the same bytes. 0 on success. */
static int frame_and_bands(const lumo_raster_scene *s, const char *label, int check_bands)
{
    lumo_raster_target t;
    uint64_t h;
    uint32_t t0;
    uint16_t y;

    init_target(&t, LUMO_PIXEL_XRGB8888, g_color, 0, H, 32);
    t0 = board_ticks();
    if (draw(s, &t) != 0)
        return 1;
    golden_cost(label, t0);
    h = hash_words(g_color, W * H);
    golden_hash(label, h);
    if (!check_bands)
        return 0;
    for (y = 0; y < H; y += 30) {
        init_target(&t, LUMO_PIXEL_XRGB8888, g_band_color + (size_t)y * W, y, 30, 32);
        if (draw(s, &t) != 0)
            return 1;
    }
    if (hash_words(g_band_color, W * H) != h) {
        con_str("golden_raster: banded shadowed frame differs from the one-pass frame\n");
        return 1;
    }
    return 0;
}

/* The point light with its shadow cube map: the map's own cost and bytes,
 * then per-vertex and per-pixel frames. 0 on success. */
static int shadow_frames(const lumo_raster_light *plain)
{
    static lumo_raster_shadow sh;
    lumo_raster_light light = *plain;
    lumo_raster_scene s;
    uint32_t t0 = board_ticks();

    if (lumo_raster_shadow_init(&sh, &light, SHADOW_SIZE, g_shadow_map, sizeof g_shadow_map, NULL, 0, 0)
            != LUMO_OK
        || lumo_raster_shadow_draw(&sh, &g_mesh) != LUMO_OK)
        return 1;
    golden_cost("raster.shadow_map_64", t0);
    golden_hash("raster.shadow_map_64", hash_words((const uint32_t *)(const void *)g_shadow_map,
                                                   sizeof g_shadow_map / 4));
    light.shadow = &sh;
    memset(&s, 0, sizeof s);
    s.lights = &light;
    s.light_count = 1;
    s.exposure = LUMO_Q16_ONE;
    if (frame_and_bands(&s, "raster.vertex_shadow", 0))
        return 1;
    s.flags = LUMO_RASTER_PER_PIXEL;
    return frame_and_bands(&s, "raster.pixel_shadow", 1);
}

/* Where a frame's instructions go (docs/rasterizer.md, "Cost on the
 * Cortex-M3"): clearing the band, transforming the vertices (the cache),
 * and drawing, with the draw's triangle and pixel counts, so that the draw
 * can be divided into per-triangle set-up and per-pixel work; then the
 * same draw again over its own depth ("redraw": every pixel fails the
 * depth test, so it costs the set-up, the rows, the pieces' exact ends and
 * the depth tests, and draw - redraw is the shading and writing of the
 * pixels). */
static int frame_parts(const lumo_raster_scene *s, const char *label)
{
    static const lumo_raster_camera cam = {
        {0, 0, Q(35, 10)}, {0, 0, 0}, {0, LUMO_Q16_ONE, 0}, Q(40, 1), Q(1, 10)
    };
    lumo_raster_view view;
    lumo_raster_target t;
    lumo_raster_stats st;
    uint32_t t0, t1, t2, t3, t4, hz = board_tick_hz();

    init_target(&t, LUMO_PIXEL_XRGB8888, g_color, 0, H, 32);
    if (lumo_raster_view_init(&view, &cam, W, H) != LUMO_OK)
        return 1;
    t0 = board_ticks();
    if (lumo_raster_clear(&t, 0x101010u) != LUMO_OK)
        return 1;
    t1 = board_ticks();
    if (lumo_raster_prepare(&view, s, &g_mesh, g_cache) != LUMO_OK)
        return 1;
    t2 = board_ticks();
    if (lumo_raster_draw_stats(&view, s, &g_mesh, g_cache, &t, &st) != LUMO_OK)
        return 1;
    t3 = board_ticks();
    if (lumo_raster_draw(&view, s, &g_mesh, g_cache, &t) != LUMO_OK)
        return 1;
    t4 = board_ticks();
    if (hz == 0)
        return 0;
    con_str("PARTS ");
    con_str(label);
    con_str(" clear ");
    con_u64((uint64_t)(t1 - t0) * (1000000000u / hz));
    con_str(" prepare ");
    con_u64((uint64_t)(t2 - t1) * (1000000000u / hz));
    con_str(" draw ");
    con_u64((uint64_t)(t3 - t2) * (1000000000u / hz));
    con_str(" redraw ");
    con_u64((uint64_t)(t4 - t3) * (1000000000u / hz));
    con_str(" triangles ");
    con_u64(st.tris_drawn);
    con_str(" pixels_tested ");
    con_u64(st.pixels_tested);
    con_str(" pixels_written ");
    con_u64(st.pixels_written);
    con_nl();
    return 0;
}

/* The per-pixel IVG frame again with the IVG sampled once per vertex side
 * (docs/rasterizer.md, "IVG per vertex"): the samples' cost, the frame's
 * cost and bytes, and how far its codes are from the exact frame's (mean
 * and largest difference of the 8-bit channels the RGB565 pixels hold, in
 * integers so that the host and the board print the same line). */
static int ivg_vertex_frame(const lumo_raster_scene *s)
{
    lumo_raster_target t;
    uint64_t h = BT_FNV_OFFSET, sum = 0;
    uint32_t t0 = board_ticks(), worst = 0;
    size_t i;
    int k;

    if (lumo_raster_indirect_vertices(s, &g_mesh, g_ind) != LUMO_OK)
        return 1;
    golden_cost("raster.ivg_vertices", t0);
    g_mesh.indirect = g_ind;
    init_target(&t, LUMO_PIXEL_RGB565, g_color565, 0, H, 16);
    t0 = board_ticks();
    if (draw(s, &t) != 0)
        return 1;
    golden_cost("raster.pixel_ivgv_565", t0);
    for (i = 0; i < (size_t)W * H; i++)
        h = bt_fnv1a_u32(h, g_color565[i]);
    golden_hash("raster.pixel_ivgv_565", h);
    for (i = 0; i < (size_t)W * H; i++)
        for (k = 0; k < 3; k++) {
            static const unsigned shift[3] = {11, 5, 0}, bits[3] = {5, 6, 5};
            uint32_t a = (g_color565[i] >> shift[k]) & ((1u << bits[k]) - 1u);
            uint32_t b = (g_color565_exact[i] >> shift[k]) & ((1u << bits[k]) - 1u);
            uint32_t d = (a > b ? a - b : b - a) * 255u / ((1u << bits[k]) - 1u);
            sum += d;
            worst = d > worst ? d : worst;
        }
    con_str("DIFF raster.pixel_ivgv_565 vs raster.pixel_ivg_565: mean code difference x1000 ");
    con_u64(sum * 1000u / (3u * W * H));
    con_str(" largest ");
    con_u64(worst);
    con_nl();
    k = frame_parts(s, "raster.pixel_ivgv_xrgb");
    g_mesh.indirect = NULL;
    return k;
}

int main(void)
{
    static const lumo_raster_light light = {
        LUMO_LIGHT_POINT, {0, Q(9, 10), Q(5, 10)}, {0, 0, 0}, 0,
        {LUMO_Q16_FROM_INT(20), LUMO_Q16_FROM_INT(20), LUMO_Q16_FROM_INT(18)}, NULL
    };
    lumo_raster_scene s;
    lumo_raster_target t;
    uint64_t h_pixel, h_bands = BT_FNV_OFFSET;
    uint32_t t0;
    uint16_t y;
    size_t i;

    build_scene();
    memset(&s, 0, sizeof s);
    s.lights = &light;
    s.light_count = 1;
    s.exposure = LUMO_Q16_ONE;

    init_target(&t, LUMO_PIXEL_XRGB8888, g_color, 0, H, 32);
    t0 = board_ticks();
    if (draw(&s, &t) != 0)
        return golden_done(1);
    golden_cost("raster.vertex_xrgb", t0);
    golden_hash("raster.vertex_xrgb", hash_words(g_color, W * H));
    if (frame_parts(&s, "raster.vertex_xrgb"))
        return golden_done(1);

    s.flags = LUMO_RASTER_PER_PIXEL;
    t0 = board_ticks();
    if (draw(&s, &t) != 0)
        return golden_done(1);
    golden_cost("raster.pixel_xrgb", t0);
    h_pixel = hash_words(g_color, W * H);
    golden_hash("raster.pixel_xrgb", h_pixel);
    if (frame_parts(&s, "raster.pixel_xrgb"))
        return golden_done(1);

    /* the same frame in 4 bands of 30 rows into one buffer */
    for (y = 0; y < H; y += 30) {
        init_target(&t, LUMO_PIXEL_XRGB8888, g_band_color + (size_t)y * W, y, 30, 32);
        if (draw(&s, &t) != 0)
            return golden_done(1);
    }
    for (i = 0; i < (size_t)W * H; i++)
        h_bands = bt_fnv1a_u32(h_bands, g_band_color[i]);
    if (h_bands != h_pixel) {
        con_str("golden_raster: banded frame differs from the one-pass frame\n");
        return golden_done(1);
    }

    s.indirect = lumo_raster_ivg_irradiance;
    s.indirect_ctx = build_ivg();
    if (s.indirect_ctx == NULL)
        return golden_done(1);
    init_target(&t, LUMO_PIXEL_RGB565, g_color565, 0, H, 16);
    t0 = board_ticks();
    if (draw(&s, &t) != 0)
        return golden_done(1);
    golden_cost("raster.pixel_ivg_565", t0);
    {
        uint64_t h = BT_FNV_OFFSET;
        for (i = 0; i < (size_t)W * H; i++)
            h = bt_fnv1a_u32(h, g_color565[i]);
        golden_hash("raster.pixel_ivg_565", h);
    }
    memcpy(g_color565_exact, g_color565, sizeof g_color565);
    if (ivg_vertex_frame(&s))
        return golden_done(1);
    s.indirect = NULL;
    s.indirect_ctx = NULL;
    return shadow_frames(&light) ? golden_done(1) : golden_done(0);
}
