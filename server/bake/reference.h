/*
 * reference.h — the reference renderer: full path tracing (direct +
 * indirect, emitters visible) or the indirect part only, the ground truth
 * the client's images are measured against. Its images go to 8-bit
 * pixels and PNG files through the desktop library (tools/lib:
 * lumo_host/tonemap.h, lumo_host/png_io.h; docs/scene-format.md).
 */
#ifndef SRV_REFERENCE_H
#define SRV_REFERENCE_H

#include <stdint.h>
#include "scene/camera.h"
#include "bake/trace.h"
#include "bake/work.h"
#include "lumo/status.h"

typedef struct srv_image {
    int    w, h;
    float *rgb;     /* w*h*3 linear radiance, rows from the top */
} srv_image;

typedef struct srv_render_opts {
    int      spp;            /* paths per pixel */
    uint64_t seed;
    int      threads;
    int      indirect_only;
    int      progress;
} srv_render_opts;

/* Render into img (allocated here; free with srv_image_free). rays gets
 * the number of rays cast (may be NULL). LUMO_OK, or LUMO_ERR_NOMEM (out
 * of memory, threads cannot start). */
lumo_status srv_render_reference(const srv_tracer *t, const srv_camera *cam, int w, int h,
                                 const srv_render_opts *o, srv_image *img, uint64_t *rays);
void srv_image_free(srv_image *img);
/* img->rgb = w*h*3 zeroed floats: LUMO_OK or LUMO_ERR_NOMEM. */
lumo_status srv_image_alloc(srv_image *img, int w, int h);

/* The render as work (work.h): one item per image row (w*3 floats), so the
 * items of all rows, in order, are srv_image.rgb itself. lumo-bake runs it
 * across MPI ranks (cluster.h); srv_render_reference in this process. The
 * task copies *cam and *o and points at *t. LUMO_OK or LUMO_ERR_NOMEM. */
typedef struct srv_render_task {
    srv_work               work;   /* key: scene, camera, size, spp, seed, indirect_only */
    struct srv_render_job *job;
} srv_render_task;
lumo_status srv_render_task_init(srv_render_task *k, const srv_tracer *t, const srv_camera *cam, int w,
                                 int h, const srv_render_opts *o);
void srv_render_task_free(srv_render_task *k);

#endif
