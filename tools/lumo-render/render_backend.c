/*
 * render_backend.c — see render_backend.h.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo/raster_gl.h"
#include "lumo_host/options.h"
#include "render_backend.h"

enum kind { SOFT, OSMESA, EGL };

struct host_renderer {
    enum kind kind;
    render_opts o;
    const lumo_raster_mesh *mesh;
    lumo_raster_vertex *cache;
    void *color, *depth;
    lumo_osmesa *osmesa;
    lumo_egl *egl;
    lumo_gl *gl;
    char desc[160];
    /* shadows: the lights the maps were drawn for, and copies of them that
     * point at the maps */
    lumo_raster_light shadow_key[LUMO_MAX_LIGHTS], shadow_lights[LUMO_MAX_LIGHTS];
    lumo_raster_shadow shadow[LUMO_MAX_LIGHTS];
    uint16_t *shadow_depth[LUMO_MAX_LIGHTS];
    uint32_t shadow_count;
    unsigned shadow_builds;
    size_t shadow_bytes;
    /* per-vertex lighting, lit once per change of the lights or the IVG */
    lumo_uq16_16 *lit;
    lumo_raster_mesh lit_mesh;
    lumo_raster_light lit_key[LUMO_MAX_LIGHTS];
    lumo_raster_scene lit_scene;
    unsigned lit_shadow_builds, lit_builds;
    /* per-pixel lighting with the IVG per vertex: sampled once per IVG */
    lumo_uq16_16 *ind;
    lumo_raster_mesh ind_mesh;
    const void *ind_ctx;
    /* per-pixel lighting with the IVG per pixel: the sampler's memo */
    lumo_ivg_sampler sampler;
};

/* The mesh to draw per pixel with the IVG interpolated from the vertices:
 * the renderer's with `indirect` sampled once for the scene's IVG (it
 * depends on neither the lights nor the view). NULL on failure. */
static const lumo_raster_mesh *ind_mesh(host_renderer *r, const lumo_raster_scene *s)
{
    size_t bytes = lumo_raster_lit_bytes(r->mesh->vertex_count);

    if (r->ind && r->ind_ctx == s->indirect_ctx)
        return &r->ind_mesh;
    if (!r->ind && !(r->ind = malloc(bytes ? bytes : 1)))
        return NULL;
    r->ind_mesh = *r->mesh;
    if (lumo_raster_indirect_vertices(s, &r->ind_mesh, r->ind))
        return NULL;
    r->ind_mesh.indirect = r->ind;
    r->ind_ctx = s->indirect_ctx;
    return &r->ind_mesh;
}

/* The mesh to draw per vertex: the renderer's with `lit` filled for scene
 * s, lit again only when s's lights, IVG or exposure-independent inputs
 * changed (diffuse light does not depend on the view). NULL on failure. */
static const lumo_raster_mesh *lit_mesh(host_renderer *r, const lumo_raster_scene *s)
{
    size_t bytes = lumo_raster_lit_bytes(r->mesh->vertex_count);

    if (r->lit && r->lit_builds && s->light_count == r->lit_scene.light_count
        && s->indirect == r->lit_scene.indirect && s->indirect_ctx == r->lit_scene.indirect_ctx
        && r->shadow_builds == r->lit_shadow_builds
        && !memcmp(s->lights, r->lit_key, s->light_count * sizeof *s->lights))
        return &r->lit_mesh;
    if (!r->lit && !(r->lit = malloc(bytes ? bytes : 1)))
        return NULL;
    r->lit_mesh = *r->mesh;
    r->lit_mesh.lit = NULL;
    if (lumo_raster_light_vertices(s, &r->lit_mesh, r->lit))
        return NULL;
    r->lit_mesh.lit = r->lit;
    r->lit_scene = *s;
    memcpy(r->lit_key, s->lights, s->light_count * sizeof *s->lights);
    r->lit_shadow_builds = r->shadow_builds;
    r->lit_builds++;
    return &r->lit_mesh;
}

/* Centre and radius of the mesh's bounding box (directional lights' maps). */
static void mesh_bounds(const lumo_raster_mesh *m, lumo_q16_16 centre[3], lumo_q16_16 *radius)
{
    int64_t lo[3] = {INT32_MAX, INT32_MAX, INT32_MAX}, hi[3] = {INT32_MIN, INT32_MIN, INT32_MIN};
    double r2 = 0;
    uint32_t v;
    int k;

    for (v = 0; v < m->vertex_count; v++)
        for (k = 0; k < 3; k++) {
            int64_t p = m->pos[3 * (size_t)v + k];
            if (p < lo[k]) lo[k] = p;
            if (p > hi[k]) hi[k] = p;
        }
    for (k = 0; k < 3; k++) {
        centre[k] = m->vertex_count ? (lumo_q16_16)((lo[k] + hi[k]) / 2) : 0;
        r2 += m->vertex_count ? (double)(hi[k] - lo[k]) * (hi[k] - lo[k]) / 4 : 0;
    }
    *radius = (lumo_q16_16)(sqrt(r2) + 65536);
}

static int same_light(const lumo_raster_light *a, const lumo_raster_light *b)
{
    return a->kind == b->kind && !memcmp(a->pos, b->pos, sizeof a->pos) && !memcmp(a->dir, b->dir, sizeof a->dir)
        && a->cos_cutoff == b->cos_cutoff;
}

/* Draw the maps again only when a light moved or changed (the mesh is the
 * renderer's own and fixed); a light's power does not change its map. The
 * GL backends take the views only and draw their own maps from them
 * (rasterizer/gl/raster_gl_shadow.c, again only when the views change). */
static int shadows_update(host_renderer *r, const lumo_raster_scene *s)
{
    lumo_q16_16 centre[3], radius;
    uint32_t i;

    for (i = 0; i < s->light_count && s->light_count == r->shadow_count; i++)
        if (!same_light(&s->lights[i], &r->shadow_key[i]))
            break;
    if (s->light_count == r->shadow_count && i == s->light_count) {
        for (i = 0; i < s->light_count; i++) {     /* power may change freely */
            const lumo_raster_shadow *sh = r->shadow_lights[i].shadow;
            r->shadow_lights[i] = s->lights[i];
            r->shadow_lights[i].shadow = sh;
        }
        return 0;
    }
    mesh_bounds(r->mesh, centre, &radius);
    r->shadow_bytes = 0;
    for (i = 0; i < s->light_count; i++) {
        size_t bytes = lumo_raster_shadow_bytes(&s->lights[i], r->o.shadow_size);
        r->shadow_key[i] = s->lights[i];
        r->shadow_lights[i] = s->lights[i];
        free(r->shadow_depth[i]);
        r->shadow_depth[i] = NULL;
        if (r->kind != SOFT) {
            if (!bytes || lumo_raster_shadow_views(&r->shadow[i], &s->lights[i], r->o.shadow_size, centre,
                                                   radius, 0))
                return -1;
            r->shadow_lights[i].shadow = &r->shadow[i];
            r->shadow_bytes += bytes * 2;                  /* 32-bit float texels */
            continue;
        }
        r->shadow_depth[i] = bytes ? malloc(bytes) : NULL;
        if (!r->shadow_depth[i]
            || lumo_raster_shadow_init(&r->shadow[i], &s->lights[i], r->o.shadow_size, r->shadow_depth[i],
                                       bytes, centre, radius, 0)
            || lumo_raster_shadow_draw(&r->shadow[i], r->mesh))
            return -1;
        r->shadow_lights[i].shadow = &r->shadow[i];
        r->shadow_bytes += bytes;
    }
    r->shadow_count = s->light_count;
    r->shadow_builds++;
    return 0;
}

unsigned host_renderer_shadow_builds(const host_renderer *r, size_t *bytes)
{
    if (bytes)
        *bytes = r->shadow_bytes;
    return r->shadow_builds;
}

int host_opt_shadows(const char *arg, uint16_t *size, char *err, size_t errlen)
{
    int k;

    if (host_opt_int("--shadows", arg, 0, LUMO_MAX_FRAME_DIM, &k, err, errlen))
        return -1;
    if (k != 0 && k < LUMO_RASTER_SHADOW_MIN_SIZE) {
        snprintf(err, errlen, "--shadows %s: 0 (no shadows) or %d..%d texels per side", arg,
                 LUMO_RASTER_SHADOW_MIN_SIZE, LUMO_MAX_FRAME_DIM);
        return -1;
    }
    *size = (uint16_t)k;
    return 0;
}

static int open_soft(host_renderer *r, char *err, size_t errlen)
{
    const render_opts *o = &r->o;
    uint16_t rows = o->band_rows && o->band_rows < o->height ? o->band_rows : o->height;
    size_t px = o->format == LUMO_PIXEL_RGB565 ? 2 : 4;

    r->o.band_rows = rows;
    r->color = malloc((size_t)o->width * rows * px);
    r->depth = malloc((size_t)o->width * rows * (o->depth_bits / 8u));
    if (!o->no_cache)
        r->cache = malloc(lumo_raster_cache_bytes(r->mesh->vertex_count) + 1);
    if (!r->color || !r->depth || (!o->no_cache && !r->cache)) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    snprintf(r->desc, sizeof r->desc, "soft (fixed point, %s, %u-bit depth, %u-row bands%s%s%s)",
             o->format == LUMO_PIXEL_RGB565 ? "RGB565" : "XRGB8888", o->depth_bits, rows,
             o->no_cache ? ", no vertex cache" : "", o->relight ? ", lit every frame" : "",
             o->ivg_vertex ? ", IVG per vertex" : "");
    return 0;
}

host_renderer *host_renderer_open(const char *backend, const lumo_raster_mesh *mesh,
                                  const lumo_ivg *ivg, const render_opts *o,
                                  char *err, size_t errlen)
{
    host_renderer *r = calloc(1, sizeof *r);

    if (!r) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    r->o = *o;
    r->mesh = mesh;
    if (!strcmp(backend, "soft")) {
        r->kind = SOFT;
        if (open_soft(r, err, errlen))
            goto fail;
        return r;
    }
    if (!strcmp(backend, "osmesa")) {
        r->kind = OSMESA;
        r->osmesa = lumo_osmesa_open(o->width, o->height, err, errlen);
        r->gl = r->osmesa ? lumo_osmesa_gl(r->osmesa) : NULL;
        if (r->gl)
            snprintf(r->desc, sizeof r->desc, "osmesa: %s", lumo_gl_renderer(r->gl));
    } else if (!strcmp(backend, "egl")) {
        r->kind = EGL;
        r->egl = lumo_egl_open(o->width, o->height, err, errlen);
        r->gl = r->egl ? lumo_egl_gl(r->egl) : NULL;
        if (r->gl)
            snprintf(r->desc, sizeof r->desc, "egl (%s): %s", lumo_egl_describe(r->egl),
                     lumo_gl_renderer(r->gl));
    } else {
        snprintf(err, errlen, "unknown backend '%s' (soft, osmesa, egl)", backend);
        goto fail;
    }
    if (!r->gl)
        goto fail;
    if (lumo_gl_set_mesh(r->gl, mesh) || lumo_gl_set_ivg(r->gl, ivg)) {
        snprintf(err, errlen, "%s: uploading the scene failed", backend);
        goto fail;
    }
    return r;
fail:
    host_renderer_close(r);
    return NULL;
}

static void band_to_rgb(const host_renderer *r, const lumo_raster_target *t, uint8_t *rgb)
{
    uint32_t x, y;

    for (y = 0; y < t->band_rows; y++) {
        uint8_t *dst = rgb + ((size_t)(t->band_y + y) * t->width) * 3;
        for (x = 0; x < t->width; x++) {
            if (r->o.format == LUMO_PIXEL_RGB565) {
                uint16_t p = ((const uint16_t *)t->color)[(size_t)y * t->width + x];
                dst[3 * x] = (uint8_t)(((p >> 11) * 255 + 15) / 31);
                dst[3 * x + 1] = (uint8_t)((((p >> 5) & 63) * 255 + 31) / 63);
                dst[3 * x + 2] = (uint8_t)(((p & 31) * 255 + 15) / 31);
            } else {
                uint32_t p = ((const uint32_t *)t->color)[(size_t)y * t->width + x];
                dst[3 * x] = (uint8_t)(p >> 16);
                dst[3 * x + 1] = (uint8_t)(p >> 8);
                dst[3 * x + 2] = (uint8_t)p;
            }
        }
    }
}

static int draw_soft(host_renderer *r, const lumo_raster_camera *cam, const lumo_raster_scene *scene,
                     uint8_t *rgb)
{
    lumo_raster_view v;
    lumo_raster_target t;
    lumo_raster_scene shadowed = *scene;
    const lumo_raster_scene *s = scene;
    const lumo_raster_mesh *mesh = r->mesh;
    uint32_t y0;

    if (r->o.shadow_size && scene->light_count) {
        if (shadows_update(r, scene))
            return -1;
        shadowed.lights = r->shadow_lights;
        s = &shadowed;
    }

    if (lumo_raster_view_init(&v, cam, r->o.width, r->o.height))
        return -1;
    if (!(s->flags & LUMO_RASTER_PER_PIXEL) && !r->o.relight && !(mesh = lit_mesh(r, s)))
        return -1;
    if ((s->flags & LUMO_RASTER_PER_PIXEL) && r->o.ivg_vertex && s->indirect && !(mesh = ind_mesh(r, s)))
        return -1;
    if ((s->flags & LUMO_RASTER_PER_PIXEL) && !r->o.ivg_vertex && s->indirect == lumo_raster_ivg_irradiance) {
        /* same values through the sampler's memo (the grid may have changed
         * since the last frame: a fresh memo) */
        lumo_ivg_sampler_init(&r->sampler, (const lumo_ivg *)s->indirect_ctx);
        shadowed.indirect = lumo_raster_ivg_sampler_irradiance;
        shadowed.indirect_ctx = &r->sampler;
        s = &shadowed;
    }
    if (r->cache && lumo_raster_prepare(&v, s, mesh, r->cache))
        return -1;
    for (y0 = 0; y0 < r->o.height; y0 += r->o.band_rows) {
        uint16_t rows = (uint16_t)(r->o.height - y0 < r->o.band_rows ? r->o.height - y0 : r->o.band_rows);
        if (lumo_raster_target_init(&t, (uint16_t)r->o.width, (uint16_t)r->o.height, (uint16_t)y0,
                                    rows, r->o.format, r->color, r->depth, r->o.depth_bits)
            || lumo_raster_clear(&t, 0) || lumo_raster_draw(&v, s, mesh, r->cache, &t))
            return -1;
        band_to_rgb(r, &t, rgb);
    }
    return 0;
}

int host_renderer_draw(host_renderer *r, const lumo_raster_camera *cam,
                       const lumo_raster_scene *s, uint8_t *rgb)
{
    lumo_raster_scene shadowed = *s;

    if (r->kind == SOFT)
        return draw_soft(r, cam, s, rgb);
    if (r->o.shadow_size && s->light_count) {
        if (shadows_update(r, s))
            return -1;
        shadowed.lights = r->shadow_lights;
    }
    return lumo_gl_draw(r->gl, cam, &shadowed, rgb);
}

const char *host_renderer_describe(const host_renderer *r)
{
    return r->desc;
}

size_t host_renderer_soft_bytes(const host_renderer *r)
{
    if (r->kind != SOFT)
        return 0;
    return lumo_raster_band_bytes(r->o.width, r->o.band_rows, r->o.format, r->o.depth_bits)
         + (r->cache ? lumo_raster_cache_bytes(r->mesh->vertex_count) : 0)
         + (r->lit ? lumo_raster_lit_bytes(r->mesh->vertex_count) : 0)
         + (r->ind ? lumo_raster_lit_bytes(r->mesh->vertex_count) : 0);
}

lumo_gl *host_renderer_gl(host_renderer *r)
{
    return r->gl;
}

void host_renderer_close(host_renderer *r)
{
    uint32_t i;

    if (!r)
        return;
    lumo_osmesa_close(r->osmesa);
    lumo_egl_close(r->egl);
    for (i = 0; i < LUMO_MAX_LIGHTS; i++)
        free(r->shadow_depth[i]);
    free(r->lit);
    free(r->ind);
    free(r->cache);
    free(r->color);
    free(r->depth);
    free(r);
}
