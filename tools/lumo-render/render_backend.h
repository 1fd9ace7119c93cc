/*
 * render_backend.h — one interface over the three rasterizer backends for
 * the desktop tools (lumo-render, tests, benchmarks): soft (fixed point,
 * bands), osmesa and egl (GLSL).
 */
#ifndef LUMO_HOST_RENDER_BACKEND_H
#define LUMO_HOST_RENDER_BACKEND_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/ivg.h"
#include "lumo/raster.h"

typedef struct render_opts {
    uint16_t width, height;
    uint16_t band_rows;           /* soft: rows per band, 0 = whole frame */
    lumo_pixel_format format;     /* soft: XRGB8888 or RGB565 */
    uint8_t depth_bits;           /* soft: 16 or 32 */
    int no_cache;                 /* soft: transform per triangle */
    int relight;                  /* soft, per vertex: light the vertices every frame
                                   * (default: once per change of lights or IVG) */
    int ivg_vertex;               /* soft, per pixel: the IVG sampled once per vertex side and
                                   * interpolated (lumo_raster_indirect_vertices), direct light
                                   * per pixel; 0: the IVG sampled per pixel */
    uint16_t shadow_size;         /* shadow map texels per side for every light, 0: no
                                   * shadows (docs/rasterizer.md "Shadows") */
} render_opts;

typedef struct host_renderer host_renderer;

/* backend: "soft", "osmesa" or "egl". mesh and ivg (may be NULL) must outlive
 * the renderer. NULL on failure with a message in err. */
host_renderer *host_renderer_open(const char *backend, const lumo_raster_mesh *mesh,
                                  const lumo_ivg *ivg, const render_opts *o,
                                  char *err, size_t errlen);
/* Draw a frame into rgb (width*height*3, top row first). For the soft
 * backend a non-NULL s->indirect must be lumo_raster_ivg_irradiance with
 * the renderer's ivg. 0 on success. */
int host_renderer_draw(host_renderer *r, const lumo_raster_camera *cam,
                       const lumo_raster_scene *s, uint8_t *rgb);
/* e.g. "soft (fixed point, 16-row bands)" or "osmesa: llvmpipe (...)" */
const char *host_renderer_describe(const host_renderer *r);
/* Shadow maps drawn so far (once per change of the lights; the mesh is
 * fixed for a renderer) and their bytes. */
unsigned host_renderer_shadow_builds(const host_renderer *r, size_t *bytes);
/* The --shadows N option of lumo-render and lumo-client: 0 (no shadows) or
 * LUMO_RASTER_SHADOW_MIN_SIZE..LUMO_MAX_FRAME_DIM texels per side into
 * *size. 0, or -1 with a message in err. */
int host_opt_shadows(const char *arg, uint16_t *size, char *err, size_t errlen);
/* Bytes of frame/band buffers and vertex cache the soft backend uses. */
size_t host_renderer_soft_bytes(const host_renderer *r);
void host_renderer_close(host_renderer *r);

#endif
