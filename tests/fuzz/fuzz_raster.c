/*
 * fuzz_raster.c — hostile geometry for the soft rasterizer: any camera, any
 * vertex positions and normals (including huge, degenerate, behind the eye),
 * any indices, lights and flags. Properties checked on every input, beyond
 * the sanitizers: a draw either succeeds or leaves the target untouched, and
 * drawing in bands of K rows with the vertex cache gives the bytes of the
 * whole frame drawn without it — also with a shadow map drawn from the
 * hostile mesh on light 0 and with the vertices lit once.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "lumo/raster.h"

#define W 40
#define H 24
#define NV 9
#define NT 8

typedef struct reader { const uint8_t *p; size_t n; } reader;

static uint32_t take(reader *r, unsigned bytes)
{
    uint32_t v = 0;
    unsigned i;
    for (i = 0; i < bytes; i++) {
        v = (v << 8) | (r->n ? *r->p : 0u);
        if (r->n) { r->p++; r->n--; }
    }
    return v;
}

/* A coordinate: mostly small (so triangles land on screen), sometimes raw. */
static int32_t coord(reader *r)
{
    uint32_t sel = take(r, 1);
    if (sel < 200)
        return ((int32_t)(take(r, 2) & 0xFFFF) - 32768) * 16;   /* +-8 units */
    return (int32_t)take(r, 4);
}

static void draw_frame(const lumo_raster_view *v, const lumo_raster_scene *s,
                       const lumo_raster_mesh *m, const lumo_raster_vertex *cache,
                       lumo_pixel_format f, uint8_t bits, int K, uint8_t *out, lumo_status *st)
{
    static uint32_t color[W * H], depth[W * H];
    size_t px = f == LUMO_PIXEL_RGB565 ? 2 : 4;
    int y0;

    *st = LUMO_OK;
    for (y0 = 0; y0 < H; y0 += K) {
        lumo_raster_target t;
        int rows = H - y0 < K ? H - y0 : K;
        lumo_raster_target_init(&t, W, H, (uint16_t)y0, (uint16_t)rows, f, color, depth, bits);
        lumo_raster_clear(&t, 0x123456);
        *st = lumo_raster_draw(v, s, m, cache, &t);
        if (*st != LUMO_OK) {
            /* on error the band is as cleared */
            lumo_raster_target c = t;
            static uint32_t ref[W * H];
            c.color = ref;
            lumo_raster_clear(&c, 0x123456);
            if (memcmp(ref, color, (size_t)rows * W * px))
                abort();
            return;
        }
        memcpy(out + (size_t)y0 * W * px, color, (size_t)rows * W * px);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static uint8_t full[W * H * 4], band[W * H * 4];
    static lumo_raster_vertex cache[NV];
    static uint16_t shadow_mem[6 * 16 * 16];
    static lumo_raster_shadow sh;
    static lumo_uq16_16 lit[6 * NV];
    reader r = {data, size};
    lumo_raster_camera cam;
    lumo_raster_view view;
    lumo_raster_light lights[2];
    lumo_raster_scene s;
    lumo_raster_mesh m, lm;
    lumo_q16_16 pos[3 * NV];
    lumo_q1_14 nrm[3 * NV], alb[3 * NV];
    uint32_t tris[3 * NT];
    lumo_status st0, st1, st2;
    lumo_pixel_format f;
    uint8_t bits;
    uint32_t extra;
    int i, K;

    memset(&cam, 0, sizeof cam);
    for (i = 0; i < 3; i++) {
        cam.eye[i] = coord(&r);
        cam.target[i] = coord(&r);
        cam.up[i] = coord(&r);
    }
    cam.fovy_deg = (lumo_q16_16)take(&r, 4);
    cam.znear = (lumo_q16_16)take(&r, 3);
    if (lumo_raster_view_init(&view, &cam, W, H) != LUMO_OK)
        return 0;
    for (i = 0; i < 3 * NV; i++) {
        pos[i] = coord(&r);
        nrm[i] = (lumo_q1_14)take(&r, 2);
        alb[i] = (lumo_q1_14)take(&r, 2);
    }
    for (i = 0; i < 3 * NT; i++)
        tris[i] = take(&r, 1) % (NV + 1);           /* NV: out of range */
    memset(lights, 0, sizeof lights);
    for (i = 0; i < 2; i++) {
        int k;
        lights[i].kind = (lumo_light_kind)(take(&r, 1) % 3);
        for (k = 0; k < 3; k++) {
            lights[i].pos[k] = coord(&r);
            lights[i].dir[k] = (lumo_q1_14)take(&r, 2);  /* beyond +-1: refused */
            lights[i].value[k] = take(&r, 4);
        }
        lights[i].cos_cutoff = (lumo_q1_14)take(&r, 2);
    }
    memset(&s, 0, sizeof s);
    s.lights = lights;
    s.light_count = take(&r, 1) % 3;
    s.exposure = take(&r, 4);
    s.flags = take(&r, 1) & 3u;
    memset(&m, 0, sizeof m);
    m.pos = pos;
    m.normal = nrm;
    m.albedo = (take(&r, 1) & 1) ? alb : NULL;
    m.mesh_albedo[0] = alb[0]; m.mesh_albedo[1] = alb[1]; m.mesh_albedo[2] = alb[2];
    m.tris = tris;
    m.vertex_count = NV;
    m.tri_count = NT;
    f = (take(&r, 1) & 1) ? LUMO_PIXEL_RGB565 : LUMO_PIXEL_XRGB8888;
    bits = (take(&r, 1) & 1) ? 16 : 32;
    K = 1 + (int)(take(&r, 1) % H);
    extra = take(&r, 1);
    if (extra & 4)  /* axes within +-1 (else refused), so that the lights shade */
        for (i = 0; i < 2; i++)
            for (int k = 0; k < 3; k++)
                lights[i].dir[k] = (lumo_q1_14)(lights[i].dir[k] / 2);
    /* light 0 with a shadow map drawn from this very mesh (any light, any
     * bounds), and vertices lit once for the banded draw */
    if ((extra & 1) && s.light_count
        && lumo_raster_shadow_init(&sh, &lights[0], 16, shadow_mem, sizeof shadow_mem, pos,
                                   (lumo_q16_16)take(&r, 4), (lumo_q16_16)take(&r, 3)) == LUMO_OK
        && lumo_raster_shadow_draw(&sh, &m) == LUMO_OK)
        lights[0].shadow = &sh;
    lm = m;
    if ((extra & 2) && lumo_raster_light_vertices(&s, &m, lit) == LUMO_OK)
        lm.lit = lit;

    /* whole frame without the vertex cache, bands with it */
    draw_frame(&view, &s, &m, NULL, f, bits, H, full, &st1);
    st0 = lumo_raster_prepare(&view, &s, &lm, cache);
    if (st0 != LUMO_OK) {  /* refused (an axis beyond +-1): the whole frame alike */
        if (st1 != st0)
            abort();
        return 0;
    }
    draw_frame(&view, &s, &lm, cache, f, bits, K, band, &st2);
    if (st1 != st2)
        abort();
    if (st1 == LUMO_OK && memcmp(full, band, (size_t)W * H * (f == LUMO_PIXEL_RGB565 ? 2 : 4)))
        abort();
    return 0;
}
