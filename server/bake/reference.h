/*
 * reference.h — the reference renderer: full path tracing (direct +
 * indirect, emitters visible) or the indirect part only, the ground truth
 * the client's images are measured against. Its images go to 8-bit
 * pixels and PNG files through the desktop library (tools/lib:
 * lumo_host/tonemap.h, lumo_host/png_io.h; docs/scene-format.md).
 */
#ifndef LUMO_SERVER_REFERENCE_H
#define LUMO_SERVER_REFERENCE_H

#include <stdint.h>
#include "scene/camera.h"
#include "bake/trace.h"

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

#endif
