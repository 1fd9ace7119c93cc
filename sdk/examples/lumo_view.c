/*
 * lumo_view.c — the smallest complete lumo client: open a .lumo package,
 * feed it to the client session, draw one frame with the soft rasterizer
 * into a framebuffer the program owns, and write it as a PPM file.
 *
 *   cc -std=c99 lumo_view.c $(pkg-config --cflags --libs lumo-raster) -o lumo_view
 *   ./lumo_view scene.lumo out.ppm [WIDTHxHEIGHT]
 *
 * It draws what `lumo-render scene.lumo -o out.png` draws (the package's
 * camera and lights, lighting per vertex plus the IVG's indirect light,
 * exposure 1, 320x240 by default), byte for byte: `make test` checks it
 * (tests/sdk/sdk_test.sh) against the installed SDK.
 *
 * Memory, as on a device: nothing is allocated. The session's struct, the
 * frame buffers, the package bytes (a package is read in place) and the
 * arena are static arrays; the SDK says how much of the arena a package
 * needs (lumo_session_package_need) and a package that needs more, or a
 * file larger than its buffer, is refused. Build with -DVIEW_ARENA_BYTES=N
 * or -DVIEW_PACKAGE_BYTES=N for other sizes (a firmware: its SRAM budget).
 * The stream protocol (lumo-net.pc, lumo/net_client.h) feeds the same
 * session from a socket or a UART; docs/sdk.md shows where it plugs in.
 */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <lumo/arena.h>
#include <lumo/package.h>
#include <lumo/raster.h>
#include <lumo/session.h>
#include <lumo/version.h>

#define MAX_W 640
#define MAX_H 480
/* lumo-render's albedo for meshes that carry none: 0.75 (Q1.14). */
#define DEFAULT_ALBEDO ((lumo_q1_14)(3 * LUMO_Q14_ONE / 4))

#ifndef VIEW_PACKAGE_BYTES
#define VIEW_PACKAGE_BYTES (16u << 20)
#endif
#ifndef VIEW_ARENA_BYTES
#define VIEW_ARENA_BYTES (32u << 20)
#endif

static lumo_session session;             /* about 21 KB: static, not on the stack */
static uint8_t package_bytes[VIEW_PACKAGE_BYTES];
static uint64_t arena_bytes[VIEW_ARENA_BYTES / 8];   /* 8-byte aligned */
static uint32_t color[MAX_W * MAX_H];    /* XRGB8888, the caller-owned frame */
static uint32_t depth[MAX_W * MAX_H];    /* 32-bit depth */
static uint8_t rgb[MAX_W * MAX_H * 3];   /* the picture as the PPM stores it */

static int fail(const char *what, lumo_status st)
{
    fprintf(stderr, "lumo_view: error: %s: %s\n", what, lumo_strerror(st));
    return 1;
}

/* The whole file into package_bytes (the package is read in place):
 * LUMO_OK, LUMO_ERR_IO, or LUMO_ERR_LIMIT for a file larger than it. */
static lumo_status read_file(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    size_t n;

    if (!f)
        return LUMO_ERR_IO;
    n = fread(package_bytes, 1, sizeof package_bytes, f);
    if (n == sizeof package_bytes && fgetc(f) != EOF) {
        fclose(f);
        return LUMO_ERR_LIMIT;
    }
    fclose(f);
    *size = n;
    return n ? LUMO_OK : LUMO_ERR_IO;
}

/* Feed the whole package to the session, in an arena of exactly the bytes
 * the SDK says it needs (LUMO_ERR_LIMIT past arena_bytes). */
static lumo_status load_scene(const lumo_package *pkg, lumo_arena *arena)
{
    lumo_session_where where;
    lumo_status st;
    size_t need;

    if ((st = lumo_session_package_need(pkg, &need)))
        return st;
    if (need > sizeof arena_bytes)
        return LUMO_ERR_LIMIT;
    lumo_arena_init(arena, arena_bytes, need);
    if ((st = lumo_session_init(&session, NULL, arena)) || (st = lumo_session_feed_package(&session, pkg, &where)))
        return st;
    lumo_session_update(&session);   /* push-pull fills the IVG vertices not received */
    return LUMO_OK;
}

/* Camera, lights and indirect light of the frame, from the session. */
static lumo_status set_up_frame(lumo_raster_view *view, lumo_raster_scene *scene,
                                lumo_raster_light lights[LUMO_MAX_LIGHTS], uint16_t w, uint16_t h)
{
    const lumo_pkg_light *pl = lumo_session_lights(&session, &scene->light_count);
    lumo_raster_camera cam;
    uint32_t i;

    lumo_raster_camera_from_info(lumo_session_info(&session), &cam);
    for (i = 0; i < scene->light_count; i++)
        lumo_raster_light_from_pkg(&pl[i], &lights[i]);
    scene->lights = lights;
    scene->indirect_ctx = lumo_session_ivg(&session);
    scene->indirect = scene->indirect_ctx ? lumo_raster_ivg_irradiance : NULL;
    scene->exposure = LUMO_Q16_ONE;
    scene->flags = 0;   /* per-vertex lighting; LUMO_RASTER_PER_PIXEL for per pixel */
    return lumo_raster_view_init(view, &cam, w, h);
}

/* Every mesh of the session into the target, one after the other with one
 * depth buffer. No vertex cache: the bytes are the same, only slower. */
static lumo_status draw_meshes(const lumo_raster_view *view, const lumo_raster_scene *scene,
                               lumo_raster_target *t)
{
    uint32_t i, n = lumo_session_info(&session)->mesh_count;
    lumo_status st;

    for (i = 0; i < n; i++) {
        lumo_raster_mesh m;
        lumo_pmesh_view v;
        if ((st = lumo_session_mesh(&session, i, &v)))
            return st;
        memset(&m, 0, sizeof m);
        m.pos = v.positions;
        m.normal = v.normals;
        m.albedo = v.albedo;
        m.mesh_albedo[0] = m.mesh_albedo[1] = m.mesh_albedo[2] = DEFAULT_ALBEDO;
        m.tris = v.triangles;
        m.vertex_count = v.vertex_count;
        m.tri_count = v.face_count;
        if ((st = lumo_raster_draw(view, scene, &m, NULL, t)))
            return st;
    }
    return LUMO_OK;
}

/* XRGB8888 rows to a binary PPM (P6). 0 on success. */
static int write_ppm(const char *path, uint16_t w, uint16_t h)
{
    FILE *f = fopen(path, "wb");
    size_t i, n = (size_t)w * h;
    int bad;

    if (!f)
        return -1;
    for (i = 0; i < n; i++) {
        rgb[3 * i] = (uint8_t)(color[i] >> 16);
        rgb[3 * i + 1] = (uint8_t)(color[i] >> 8);
        rgb[3 * i + 2] = (uint8_t)color[i];
    }
    bad = fprintf(f, "P6\n%u %u\n255\n", w, h) < 0 || fwrite(rgb, 3, n, f) != n;
    return (fclose(f) || bad) ? -1 : 0;
}

static int parse_size(const char *s, uint16_t *w, uint16_t *h)
{
    unsigned a, b;
    char tail;

    if (sscanf(s, "%ux%u%c", &a, &b, &tail) != 2 || a < 1 || b < 1 || a > MAX_W || b > MAX_H)
        return -1;
    *w = (uint16_t)a;
    *h = (uint16_t)b;
    return 0;
}

/* Open, load, draw, write. */
static int view(const char *in, const char *out, uint16_t w, uint16_t h)
{
    lumo_raster_light lights[LUMO_MAX_LIGHTS];
    lumo_raster_scene scene;
    lumo_raster_target t;
    lumo_raster_view rv;
    lumo_package pkg;
    lumo_arena arena;
    lumo_status st;
    size_t size = 0;

    if ((st = read_file(in, &size)))
        return fail(in, st);
    if ((st = lumo_package_open(&pkg, package_bytes, size)))
        return fail(in, st);
    if ((st = load_scene(&pkg, &arena)))
        return fail("loading the scene", st);
    memset(&scene, 0, sizeof scene);
    if ((st = set_up_frame(&rv, &scene, lights, w, h)))
        return fail("the package's camera", st);
    if ((st = lumo_raster_target_init(&t, w, h, 0, h, LUMO_PIXEL_XRGB8888, color, depth, 32))
        || (st = lumo_raster_clear(&t, 0)) || (st = draw_meshes(&rv, &scene, &t)))
        return fail("drawing", st);
    if (write_ppm(out, w, h))
        return fail(out, LUMO_ERR_IO);
    printf("lumo_view: lumo %s, %s: %ux%u, %u meshes, %u lights%s -> %s\n", lumo_version_string(), in, w, h,
           lumo_session_info(&session)->mesh_count, scene.light_count, scene.indirect ? " + IVG" : "", out);
    return 0;
}

int main(int argc, char **argv)
{
    uint16_t w = 320, h = 240;

    if (argc < 3 || argc > 4 || (argc == 4 && parse_size(argv[3], &w, &h))) {
        fprintf(stderr, "usage: lumo_view PACKAGE.lumo OUT.ppm [WIDTHxHEIGHT, at most %ux%u]\n", MAX_W, MAX_H);
        return 2;
    }
    /* A library older or newer than the headers compiled against. */
    if (lumo_version() != LUMO_VERSION_NUMBER) {
        fprintf(stderr, "lumo_view: error: library %s, headers %s\n", lumo_version_string(), LUMO_VERSION_STRING);
        return 1;
    }
    return view(argv[1], argv[2], w, h);
}
