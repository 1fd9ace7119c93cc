/*
 * lumo_render.c — lumo-render: draw a .lumo package (or the server's default
 * scene) locally, without a network, with any rasterizer backend; PNG output.
 *
 *   lumo-render FILE.lumo|--default -o OUT.png [--backend soft|osmesa|egl]
 *       [--size WxH] [--camera EYE:TARGET:UP:FOVY] [--per-vertex|--per-pixel]
 *       [--no-indirect] [--frames N --orbit] [--exposure E]
 *       [--model PATH] [--light SPEC] [--bands K] [--rgb565] [--depth16]
 *       [--no-cache] [--cull] [--lod N|P%|all] [--ivg-vertex] [--no-depth-first]
 *       [--prt [--env FILE] [--rotate DEG]]
 *
 * Packages with progressive meshes (PMSH) are decoded through the SDK's
 * lumo_pmesh as on a device, at the level --lod asks (seed 000 §4.2).
 * --default builds the server's scene model (server/scene: default scene,
 * assimp import) and converts it (scene_convert.h); --camera and --light go
 * through the server's parsers there too.
 */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include "lumo/raster.h"
#include "lumo_host/options.h"
#include "lumo_host/png_io.h"
#include "mesh_build.h"
#include "package_load.h"
#include "render_backend.h"
#include "scene/camera.h"
#include "scene/shapes.h"
#include "scene_convert.h"
#include "prt_render.h"
#include "lumo_host/version_line.h"

/* The dragon of the default scene when neither --model nor LUMO_DRAGON names
 * one (the same as lumo-bake's). */
#define DEFAULT_DRAGON "build/data/models/dragon_48k.ply"

static const char usage[] =
    "usage: lumo-render FILE.lumo|--default -o OUT.png [options]\n"
    "  --backend soft|osmesa|egl   renderer (default soft)\n"
    "  --size WxH                  image size (default 320x240, at most 2048x2048)\n"
    "  --camera EYE:TARGET:UP:FOVY camera (default: the package's or the scene's)\n"
    "  --fit                       a camera fitted to the scene's bounds instead (a model\n"
    "                              baked without a camera gets one already)\n"
    "  --per-vertex | --per-pixel  lighting per vertex (default) or per pixel\n"
    "  --no-indirect               direct light only (ignore the IVG)\n"
    "  --frames N --orbit          N frames orbiting the target about UP; prints ms/frame\n"
    "  --exposure E                radiance multiplier before tone mapping (default 1)\n"
    "  --default                   the server's built-in Cornell box (lumo-bake --default,\n"
    "                              no IVG) instead of a package\n"
    "  --model PATH                with --default: this model (any format assimp reads:\n"
    "                              OBJ, PLY, OFF, STL, glTF, ...) instead of the dragon;\n"
    "                              a model that cannot be read is an error (LUMO_DRAGON too)\n"
    "  --light SPEC                replace the lights (repeatable): point:X,Y,Z:R,G,B |\n"
    "                              spot:X,Y,Z:DX,DY,DZ:HALF_DEG:R,G,B |\n"
    "                              directional:DX,DY,DZ:R,G,B | area:X,Y,Z:U..:V..:R,G,B\n"
    "                              (docs/scene-format.md; area: drawn as the client does)\n"
    "  --bands K                   soft: draw in bands of K rows (default: whole frame)\n"
    "  --rgb565 | --depth16        soft: RGB565 output with dither; 16-bit depth\n"
    "  --no-cache                  soft: no transformed-vertex cache\n"
    "  --cull                      drop back faces\n"
    "  --relight                   soft, per vertex: light the vertices every frame (default:\n"
    "                              once, again only when the lights or the IVG change)\n"
    "  --ivg-vertex                soft, per pixel: sample the IVG once per vertex and\n"
    "                              interpolate it (direct light stays per pixel)\n"
    "  --no-depth-first            soft, per pixel: shade every fragment that passes the depth\n"
    "                              test (default, from 4 pixels per triangle: a depth-only\n"
    "                              pass first, each pixel shaded once; the same picture)\n"
    "  --shadows N                 shadow maps of N x N texels per face for every light\n"
    "                              (point: 6 faces; default 0: no shadows; every backend)\n"
    "  --warmup K                  draw K untimed frames first (GL shader compilation)\n"
    "  --lod N|P%|all              level of detail of progressive meshes: at most N vertices\n"
    "                              per mesh, or the base mesh plus P% of the vertices\n"
    "                              streamed after it (0% = base mesh), or all (default)\n"
    "  --prt                       per vertex: relight with the package's PRT (lumo-bake --prt;\n"
    "                              docs/prt.md) under the scene's lights as distant lights,\n"
    "                              or the package's environment (PRTL), or --env; osmesa and\n"
    "                              egl draw the thesis's multipass (one pass per super-cluster)\n"
    "  --env FILE.png              with --prt: an equirectangular environment (y up)\n"
    "  --rotate DEG                with --prt: turn the lighting DEG degrees about +y a frame\n"
    "  --prt-view clusters|passes  with --prt: false colours of each vertex's cluster, or of\n"
    "                              its cluster's draw pass (super-cluster)\n";

typedef struct options {
    const char *input, *output, *backend, *camera, *model;
    const char *lights[LUMO_MAX_LIGHTS];
    int nlights, per_pixel, no_indirect, frames, orbit, use_default, cull, warmup, lod_set, fit, prt;
    int no_depth_first;
    const char *env;
    double rotate;
    int prt_view;
    const char *lod_arg;
    host_lod lod;
    double exposure;
    render_opts ro;
} options;

enum { O_BACKEND = 256, O_SIZE, O_CAMERA, O_PV, O_PP, O_NOIND, O_FRAMES, O_ORBIT, O_EXPOSURE,
       O_DEFAULT, O_MODEL, O_LIGHT, O_BANDS, O_565, O_D16, O_NOCACHE, O_CULL, O_WARMUP, O_LOD, O_SHADOWS, O_RELIGHT, O_FIT, O_IVGV, O_NODF, O_HELP,
       O_PRT, O_ENV, O_ROTATE, O_PRT_VIEW };

static const struct option k_longs[] = {
    {"backend", 1, 0, O_BACKEND}, {"size", 1, 0, O_SIZE}, {"camera", 1, 0, O_CAMERA},
    {"per-vertex", 0, 0, O_PV}, {"per-pixel", 0, 0, O_PP}, {"no-indirect", 0, 0, O_NOIND},
    {"frames", 1, 0, O_FRAMES}, {"orbit", 0, 0, O_ORBIT}, {"exposure", 1, 0, O_EXPOSURE},
    {"default", 0, 0, O_DEFAULT}, {"model", 1, 0, O_MODEL}, {"light", 1, 0, O_LIGHT},
    {"bands", 1, 0, O_BANDS}, {"rgb565", 0, 0, O_565}, {"depth16", 0, 0, O_D16},
    {"no-cache", 0, 0, O_NOCACHE}, {"cull", 0, 0, O_CULL}, {"warmup", 1, 0, O_WARMUP},
    {"lod", 1, 0, O_LOD}, {"shadows", 1, 0, O_SHADOWS}, {"relight", 0, 0, O_RELIGHT}, {"fit", 0, 0, O_FIT},
    {"ivg-vertex", 0, 0, O_IVGV}, {"no-depth-first", 0, 0, O_NODF},
    {"help", 0, 0, O_HELP},
    {"prt", 0, 0, O_PRT}, {"env", 1, 0, O_ENV}, {"rotate", 1, 0, O_ROTATE},
    {"prt-view", 1, 0, O_PRT_VIEW},
    {"output", 1, 0, 'o'}, {0, 0, 0, 0}
};

static void set_defaults(options *o)
{
    memset(o, 0, sizeof *o);
    o->backend = "soft";
    o->frames = 1;
    o->exposure = 1.0;
    o->ro.width = 320;
    o->ro.height = 240;
    o->ro.format = LUMO_PIXEL_XRGB8888;
    o->ro.depth_bits = 32;
    o->lod_arg = "all";
    host_lod_parse(o->lod_arg, &o->lod, NULL, 0);
}

/* The options that take no number: flags and names. */
static int take_flag(options *o, int c, const char *arg, char *err, size_t errlen)
{
    switch (c) {
    case 'o': o->output = arg; return 0;
    case O_BACKEND: o->backend = arg; return 0;
    case O_CAMERA: o->camera = arg; return 0;
    case O_PV: o->per_pixel = 0; return 0;
    case O_PP: o->per_pixel = 1; return 0;
    case O_NOIND: o->no_indirect = 1; return 0;
    case O_ORBIT: o->orbit = 1; return 0;
    case O_DEFAULT: o->use_default = 1; return 0;
    case O_MODEL: o->model = arg; return 0;
    case O_565: o->ro.format = LUMO_PIXEL_RGB565; return 0;
    case O_D16: o->ro.depth_bits = 16; return 0;
    case O_NOCACHE: o->ro.no_cache = 1; return 0;
    case O_CULL: o->cull = 1; return 0;
    case O_RELIGHT: o->ro.relight = 1; return 0;
    case O_FIT: o->fit = 1; return 0;
    case O_IVGV: o->ro.ivg_vertex = 1; return 0;
    case O_NODF: o->no_depth_first = 1; return 0;
    case O_PRT: o->prt = 1; return 0;
    case O_ENV: o->env = arg; return 0;
    case O_PRT_VIEW: {
        static const char *const views[] = {"clusters", "passes"};
        if (host_opt_choice("--prt-view", arg, views, 2, &o->prt_view, err, errlen))
            return -1;
        o->prt_view += HOST_PRT_CLUSTERS;
        return 0;
    }
    default: snprintf(err, errlen, "unhandled option %d", c); return -1;
    }
}

/* What the options ask for together: one input, an output, --model and
 * --lod only where they mean something. */
static int check_args(const options *o, int argc, char **argv, char *err, size_t errlen)
{
    if (optind < argc)
        snprintf(err, errlen, "unexpected argument '%s' (one package at a time; try --help)", argv[optind]);
    else if (!o->input == !o->use_default)
        snprintf(err, errlen, "give a package FILE.lumo or --default, %s (try --help)",
                 o->input ? "not both" : "one of them");
    else if (!o->output)
        snprintf(err, errlen, "no output file: give -o OUT.png (try --help)");
    else if (o->model && !o->use_default)
        snprintf(err, errlen, "--model %s: only with --default (a package holds its own meshes)", o->model);
    else if ((o->env || o->rotate != 0 || o->prt_view) && !o->prt)
        snprintf(err, errlen, "--env, --rotate and --prt-view go with --prt (try --help)");
    else
        return 0;
    return -1;
}

/* One option's value into o; 0, or -1 with the refusal in err. */
static int take_value(options *o, int c, const char *arg, char *err, size_t errlen)
{
    lumo_raster_light light;
    uint32_t w, h;
    int k;

    switch (c) {
    case O_SIZE:
        if (host_opt_size("--size", arg, LUMO_MAX_FRAME_DIM, LUMO_MAX_FRAME_DIM, &w, &h, err, errlen))
            return -1;
        o->ro.width = (uint16_t)w;
        o->ro.height = (uint16_t)h;
        return 0;
    case O_FRAMES: return host_opt_int("--frames", arg, 1, 100000, &o->frames, err, errlen);
    case O_EXPOSURE: return host_opt_double("--exposure", arg, 0, 65535, &o->exposure, err, errlen);
    case O_BANDS:
        if (host_opt_int("--bands", arg, 1, LUMO_MAX_FRAME_DIM, &k, err, errlen))
            return -1;
        o->ro.band_rows = (uint16_t)k;
        return 0;
    case O_WARMUP: return host_opt_int("--warmup", arg, 0, 1000, &o->warmup, err, errlen);
    case O_ROTATE: return host_opt_double("--rotate", arg, -360, 360, &o->rotate, err, errlen);
    case O_LOD:
        if (host_lod_parse(arg, &o->lod, err, errlen))
            return -1;
        o->lod_arg = arg;
        o->lod_set = strcmp(arg, "all") != 0;
        return 0;
    case O_SHADOWS:
        return host_opt_shadows(arg, &o->ro.shadow_size, err, errlen);
    case O_LIGHT:
        if (o->nlights == LUMO_MAX_LIGHTS) {
            snprintf(err, errlen, "--light %s: more than %d lights (LUMO_MAX_LIGHTS, lumo/config.h)", arg,
                     LUMO_MAX_LIGHTS);
            return -1;
        }
        if (host_light_parse("--light", arg, &light, err, errlen))
            return -1;
        o->lights[o->nlights++] = arg;
        return 0;
    default: return take_flag(o, c, arg, err, errlen);
    }
}

/* The whole command line: 0, 1 for --help, or -1 with the refusal in err. */
static int parse_args(int argc, char **argv, options *o, char *err, size_t errlen)
{
    int c;

    set_defaults(o);
    opterr = 0;
    while ((c = host_getopt(argc, argv, ":o:h", k_longs)) != -1) {
        if (c == 'h' || c == O_HELP)
            return 1;
        if (c == '?' || c == ':')
            return host_opt_getopt_error(c, argv[optind - 1], optopt, err, errlen);
        if (take_value(o, c, optarg, err, errlen))
            return -1;
    }
    if (optind < argc)
        o->input = argv[optind++];
    return check_args(o, argc, argv, err, errlen);
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

/* Frame i of an orbit: the eye turned by 360 i / n degrees about the up
 * axis through the target. */
static void orbit_camera(const lumo_raster_camera *base, int i, int n, lumo_raster_camera *out)
{
    double up[3], d[3], t[3], a = 2 * M_PI * i / n, l = 0, dot = 0, c = cos(a), s = sin(a);
    int k;

    *out = *base;
    for (k = 0; k < 3; k++) {
        up[k] = base->up[k] / 65536.0;
        t[k] = base->target[k] / 65536.0;
        d[k] = base->eye[k] / 65536.0 - t[k];
        l += up[k] * up[k];
    }
    l = sqrt(l);
    for (k = 0; k < 3; k++) { up[k] /= l; dot += up[k] * d[k]; }
    /* Rodrigues: d cos a + (up x d) sin a + up (up . d)(1 - cos a) */
    {
        double x[3] = {up[1] * d[2] - up[2] * d[1], up[2] * d[0] - up[0] * d[2], up[0] * d[1] - up[1] * d[0]};
        for (k = 0; k < 3; k++)
            out->eye[k] = host_q16(t[k] + d[k] * c + x[k] * s + up[k] * dot * (1 - c));
    }
}

/* The timed draw, a function of its own so that callgrind can count just
 * these frames (--toggle-collect=timed_frame), not warm-up ones. */
__attribute__((noinline)) static int timed_frame(host_renderer *r, host_prt *prt, const lumo_raster_camera *cam,
                                                 const lumo_raster_scene *s, uint8_t *rgb)
{
    if (prt->gl)   /* --prt on a GL backend: the thesis's multipass (lumo/raster_gl_prt.h) */
        return host_prt_gl_draw(prt, cam, s, rgb) ? LUMO_ERR_STATE : LUMO_OK;
    return host_renderer_draw(r, cam, s, rgb);
}

static void frame_name(const char *out, int i, int n, char *buf, size_t len)
{
    const char *dot = strrchr(out, '.');
    if (n == 1) {
        snprintf(buf, len, "%s", out);
        return;
    }
    if (!dot) dot = out + strlen(out);
    snprintf(buf, len, "%.*s_%03d%s", (int)(dot - out), out, i, dot);
}

/* The package, its meshes at the level --lod asks; one line saying which. */
static int load_package(const options *o, host_scene *scene, host_ivg *ivg)
{
    host_load_stats st;
    char err[512];

    if (host_package_load(o->input, &o->lod, scene, ivg, &st, err, sizeof err)) {
        fprintf(stderr, "lumo-render: error: %s\n", err);
        return -1;
    }
    if (!st.progressive && o->lod_set) {
        fprintf(stderr, "lumo-render: error: %s: --lod needs progressive meshes (the package has raw "
                        "MESH chunks only; bake with --mesh pm)\n", o->input);
        host_scene_free(scene);
        host_ivg_free(ivg);
        return -1;
    }
    if (st.progressive)
        printf("lumo-render: %u progressive meshes at --lod %s: %u of %u vertices, %u triangles\n",
               st.progressive, o->lod_arg, st.vertices, st.full_vertices, scene->mesh.tri_count);
    else
        printf("lumo-render: raw meshes: %u vertices, %u triangles\n", st.vertices, scene->mesh.tri_count);
    return 0;
}

/* The model of the default scene: --model, else LUMO_DRAGON, else the
 * dragon. A file the user named is used or refused, never replaced; only
 * the built-in dragon, when tools/setup.sh has not fetched it, gives way
 * to the server's sphere (said on stderr). NULL with err set on refusal. */
static const char *default_model(const options *o, char *err, size_t errlen)
{
    const char *env = getenv("LUMO_DRAGON");

    if (o->model)
        return host_opt_file("--model", o->model, "model file", err, errlen) ? NULL : o->model;
    if (env)
        return host_opt_file("LUMO_DRAGON", env, "model file", err, errlen) ? NULL : env;
    if (access(DEFAULT_DRAGON, R_OK))
        fprintf(stderr, "lumo-render: note: %s missing (tools/setup.sh fetches it): a sphere in its place\n",
                DEFAULT_DRAGON);
    return DEFAULT_DRAGON;
}

/* The server's default scene (server/scene/default_scene.c, the scene
 * lumo-bake --default bakes) with default_model()'s model. */
static int build_default(const options *o, host_scene *scene)
{
    char err[600];
    const char *model = default_model(o, err, sizeof err);
    srv_scene s;
    lumo_status st;

    if (!model) {
        fprintf(stderr, "lumo-render: error: %s\n", err);
        return -1;
    }
    srv_scene_init(&s);
    st = srv_default_scene(&s, model, err, sizeof err);
    if (!st)
        st = host_scene_from_srv(scene, &s, err, sizeof err);
    srv_scene_free(&s);
    if (st) {
        fprintf(stderr, "lumo-render: error: default scene: %s\n", err);
        return -1;
    }
    return 0;
}

/* Why a camera the rasterizer refuses is degenerate, from its fixed-point
 * values (two points closer than 1/65536 m are one). */
static const char *camera_fault(const lumo_raster_camera *c)
{
    int64_t f[3], x[3];
    int k;

    for (k = 0; k < 3; k++)
        f[k] = (int64_t)c->target[k] - c->eye[k];
    if (!f[0] && !f[1] && !f[2])
        return "eye and target are the same point";
    if (!(c->fovy_deg >= 1 * 65536 && c->fovy_deg <= 179 * 65536))
        return "FOVY must be 1..179 degrees";
    x[0] = f[1] * c->up[2] - f[2] * c->up[1];
    x[1] = f[2] * c->up[0] - f[0] * c->up[2];
    x[2] = f[0] * c->up[1] - f[1] * c->up[0];
    if (!x[0] && !x[1] && !x[2])
        return "UP is zero or parallel to the view direction";
    return "eye, target and UP too close to one another in Q16.16 fixed point";
}

/* --camera over the package's or the scene's camera, then the camera the
 * frames use checked as the rasterizer will (lumo_raster_view_init), so a
 * degenerate one is named here rather than failing frame 0. */
static int set_camera(const options *o, host_scene *scene)
{
    const lumo_raster_camera *c = &scene->camera;
    lumo_raster_view v;
    char why[200];
    srv_camera sc;

    if (o->camera && host_camera_from_string(o->camera, &scene->camera)) {
        if (srv_camera_parse_why(o->camera, &sc, why, sizeof why) == LUMO_OK)
            snprintf(why, sizeof why, "FOVY must be 1..179 degrees");
        fprintf(stderr, "lumo-render: error: --camera %s: %s (docs/scene-format.md)\n",
                o->camera, why);
        return -1;
    }
    /* --fit, then the near plane from the scene's bounds either way. */
    if (host_scene_aim(scene, NULL, o->fit && !o->camera, o->ro.width, o->ro.height, why, sizeof why)) {
        fprintf(stderr, "lumo-render: error: --fit: %s\n", why);
        return -1;
    }
    if (lumo_raster_view_init(&v, c, o->ro.width, o->ro.height) == LUMO_OK)
        return 0;
    if (o->camera) {
        fprintf(stderr, "lumo-render: error: --camera %s: %s in Q16.16 fixed point (points 1/65536 m apart "
                        "at least)\n", o->camera, camera_fault(c));
        return -1;
    }
    fprintf(stderr, "lumo-render: error: %s camera %g,%g,%g:%g,%g,%g:%g,%g,%g:%g: %s (give --camera)\n",
            o->use_default ? "the default scene's" : "the package's", c->eye[0] / 65536.0, c->eye[1] / 65536.0,
            c->eye[2] / 65536.0, c->target[0] / 65536.0, c->target[1] / 65536.0, c->target[2] / 65536.0,
            c->up[0] / 65536.0, c->up[1] / 65536.0, c->up[2] / 65536.0, c->fovy_deg / 65536.0, camera_fault(c));
    return -1;
}

int main(int argc, char **argv)
{
    if (host_version_option(argc, argv, "lumo-render"))
        return 0;
    options o;
    host_scene scene;
    host_ivg ivg;
    host_renderer *r;
    lumo_raster_mesh mesh;
    lumo_raster_scene rs;
    char err[512], why[600];
    uint8_t *rgb;
    double total = 0, best = 1e300;
    lumo_status st;
    int i, rc = 0;

    if ((rc = parse_args(argc, argv, &o, err, sizeof err))) {
        if (rc > 0) {
            fputs(usage, stdout);
            return 0;
        }
        fprintf(stderr, "lumo-render: error: %s\n", err);
        return 2;
    }
    memset(&ivg, 0, sizeof ivg);
    if (o.use_default && o.lod_set) {
        fprintf(stderr, "lumo-render: error: --lod %s: needs a package with progressive meshes, not --default\n",
                o.lod_arg);
        return 1;
    }
    if (o.use_default) {
        if (build_default(&o, &scene))
            return 1;
    } else if (load_package(&o, &scene, &ivg))
        return 1;
    if (set_camera(&o, &scene)) {
        host_scene_free(&scene);
        host_ivg_free(&ivg);
        return 1;
    }
    if (o.nlights) {
        scene.light_count = 0;
        for (i = 0; i < o.nlights; i++)
            if ((st = host_light_parse("--light", o.lights[i], &scene.lights[scene.light_count++], why,
                                       sizeof why))) {
                fprintf(stderr, "lumo-render: error: %s (docs/scene-format.md)\n", why);
                return 1;
            }
    }
    mesh = host_mesh_raster(&scene.mesh);
    static host_prt prt;
    if (o.prt) {
        if (o.use_default || o.per_pixel) {
            fprintf(stderr, "lumo-render: error: --prt needs a package and per-vertex lighting\n");
            return 1;
        }
        if (host_prt_open(&prt, o.input, o.env, &scene, err, sizeof err)) {
            fprintf(stderr, "lumo-render: error: --prt: %s\n", err);
            return 1;
        }
        mesh.lit = prt.lit;   /* drawn as lit, relit by PRT before each frame */
        prt.view = o.prt_view;
        o.ro.relight = 1;
    }
    memset(&rs, 0, sizeof rs);
    rs.lights = scene.lights;
    rs.light_count = scene.light_count;
    rs.exposure = (lumo_uq16_16)floor(o.exposure * 65536 + 0.5);
    /* The depth-first pass pays where the triangles are large enough that
     * the overdraw it saves outweighs a second set-up of each: from 4
     * pixels of frame a triangle (measured, docs/rasterizer.md "Round four";
     * measured again with round five's row kinds: it pays at 6.6 pixels a
     * triangle and costs at 0.4-1.7, docs/benchmarks.md "Round five"). */
    rs.flags = (o.per_pixel ? LUMO_RASTER_PER_PIXEL : 0) | (o.cull ? LUMO_RASTER_CULL_BACK : 0)
             | (o.per_pixel && !o.no_depth_first
                && (uint64_t)o.ro.width * o.ro.height >= 4 * (uint64_t)mesh.tri_count ? LUMO_RASTER_DEPTH_FIRST : 0);
    if (ivg.grid && !o.no_indirect && !o.prt) {   /* PRT carries its own interreflections */
        rs.indirect = lumo_raster_ivg_irradiance;
        rs.indirect_ctx = ivg.grid;
    }
    r = host_renderer_open(o.backend, &mesh, ivg.grid, &o.ro, err, sizeof err);
    if (!r) {
        fprintf(stderr, "lumo-render: error: %s\n", err);
        return 1;
    }
    if (o.prt && host_renderer_gl(r) && host_prt_gl_open(&prt, host_renderer_gl(r), &scene, &mesh, err, sizeof err)) {
        fprintf(stderr, "lumo-render: error: --prt: %s\n", err);
        host_prt_close(&prt);
        host_renderer_close(r);
        return 1;
    }
    rgb = malloc((size_t)o.ro.width * o.ro.height * 3);
    for (i = 0; i < o.warmup && rgb; i++)   /* untimed, also PRT's relight (relight_ms reset below) */
        if (o.prt ? host_prt_relight(&prt, &scene, 0, 0) || timed_frame(r, &prt, &scene.camera, &rs, rgb)
                  : host_renderer_draw(r, &scene.camera, &rs, rgb))
            break;
    prt.relight_ms = 0;
    for (i = 0; i < o.frames && rgb; i++) {
        lumo_raster_camera cam = scene.camera;
        char name[1024];
        double t0, dt;
        if (o.orbit) {
            orbit_camera(&scene.camera, i, o.frames, &cam);
            cam.znear = lumo_raster_znear_for_box(&cam, scene.bmin, scene.bmax);
        }
        if (o.prt && host_prt_relight(&prt, &scene, i, o.rotate)) {
            fprintf(stderr, "lumo-render: error: PRT relight of frame %d failed\n", i);
            rc = 1;
            break;
        }
        t0 = now_ms();
        if ((st = (lumo_status)timed_frame(r, &prt, &cam, &rs, rgb))) {
            fprintf(stderr, "lumo-render: error: frame %d failed: %s\n", i, lumo_strerror(st));
            rc = 1;
            break;
        }
        dt = now_ms() - t0;
        total += dt;
        if (dt < best) best = dt;
        frame_name(o.output, i, o.frames, name, sizeof name);
        if (host_png_write_rgb8(name, rgb, o.ro.width, o.ro.height, err, sizeof err)) {
            fprintf(stderr, "lumo-render: error: %s\n", err);
            rc = 1;
            break;
        }
    }
    if (rc == 0)
        printf("lumo-render: %s, %ux%u, %u triangles, %s lighting%s: %d frame(s), %.3f ms/frame mean, "
               "%.3f ms best\n",
               host_renderer_describe(r), o.ro.width, o.ro.height, mesh.tri_count,
               o.per_pixel ? "per-pixel" : "per-vertex", rs.indirect ? " + IVG" : "", o.frames,
               total / o.frames, best);
    if (rc == 0 && prt.gl) {
        lumo_gl_prt_stats gs;
        lumo_gl_prt_get_stats(prt.gl, &gs);
        printf("lumo-render: PRT multipass: %u passes, %llu of %llu triangles drawn (overdraw %.4f), "
               "GL primitives generated %llu a frame\n", gs.passes, (unsigned long long)gs.drawn,
               (unsigned long long)gs.triangles, gs.triangles ? (double)gs.drawn / gs.triangles : 0.0,
               (unsigned long long)gs.generated);
    }
    if (rc == 0 && o.prt)
        printf("lumo-render: PRT order %u, %u mesh(es), %u clusters, %u components: relight %.3f ms/frame mean\n",
               prt.mesh[0].order, prt.meshes, prt.mesh[0].clusters, prt.mesh[0].components,
               prt.relight_ms / o.frames);
    host_prt_close(&prt);
    free(rgb);
    host_renderer_close(r);
    host_scene_free(&scene);
    host_ivg_free(&ivg);
    return rc;
}
