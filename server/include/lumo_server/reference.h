/*
 * reference.h — the reference renderer: full path tracing (direct +
 * indirect, emitters visible) or the indirect part only, the ground truth
 * the client's images are measured against. Tone mapping and PNG output
 * follow docs/scene-format.md.
 */
#ifndef LUMO_SERVER_REFERENCE_H
#define LUMO_SERVER_REFERENCE_H

#include <stdint.h>
#include "lumo_server/camera.h"
#include "lumo_server/trace.h"

typedef struct lumo_image {
    int    w, h;
    float *rgb;     /* w*h*3 linear radiance, rows from the top */
} lumo_image;

typedef struct lumo_render_opts {
    int      spp;            /* paths per pixel */
    uint64_t seed;
    int      threads;
    int      indirect_only;
    int      progress;
} lumo_render_opts;

/* Render into img (allocated here; free with lumo_image_free). rays gets
 * the number of rays cast (may be NULL). 0 or -1. */
int lumo_render_reference(const lumo_tracer *t, const lumo_camera *cam, int w, int h,
                          const lumo_render_opts *o, lumo_image *img, uint64_t *rays);
void lumo_image_free(lumo_image *img);

/* Tone map (x exposure, clamp, sRGB, 8 bits) one linear value. */
uint8_t lumo_tonemap(float v, float exposure);

/* Write an 8-bit sRGB PNG. 0, or -1 with err. */
int lumo_png_write(const char *path, const lumo_image *img, float exposure, char *err, size_t errlen);
/* Read an 8-bit RGB(A) PNG (for comparisons): rgb8 malloc'ed, w*h*3. */
int lumo_png_read(const char *path, uint8_t **rgb8, int *w, int *h);

#endif
