/* reference.c — path-traced reference images, one image row per work item,
 * one random stream per pixel (deterministic for any thread count). */
#include <stdlib.h>
#include <string.h>
#include "common/parallel.h"
#include "bake/reference.h"

#define MAX_WORKERS 256

typedef struct {
    const srv_tracer       *t;
    const srv_camera       *cam;
    const srv_render_opts *o;
    srv_image              *img;
    srv_trace_stats         stats[MAX_WORKERS];
} render_job;

static void render_row(void *ctx, size_t y, int worker)
{
    render_job *j = ctx;
    srv_image *img = j->img;
    for (int x = 0; x < img->w; x++) {
        srv_rng r;
        vec3 sum = v3(0, 0, 0);
        srv_rng_seed(&r, j->o->seed, (uint64_t)y * (uint64_t)img->w + (uint64_t)x);
        for (int s = 0; s < j->o->spp; s++) {
            float px = (float)x + srv_rng_float(&r), py = (float)y + srv_rng_float(&r);
            vec3 d = srv_camera_ray(j->cam, img->w, img->h, px, py);
            sum = v3_add(sum, srv_trace_camera(j->t, j->cam->eye, d, j->o->indirect_only, &r,
                                               &j->stats[worker]));
        }
        float *out = &img->rgb[3 * ((size_t)y * (size_t)img->w + (size_t)x)];
        out[0] = sum.x / (float)j->o->spp;
        out[1] = sum.y / (float)j->o->spp;
        out[2] = sum.z / (float)j->o->spp;
    }
}

lumo_status srv_render_reference(const srv_tracer *t, const srv_camera *cam, int w, int h,
                                 const srv_render_opts *o, srv_image *img, uint64_t *rays)
{
    render_job *j = calloc(1, sizeof *j);
    img->w = w;
    img->h = h;
    img->rgb = calloc((size_t)w * (size_t)h * 3, sizeof(float));
    if (!j || !img->rgb) {
        free(j);
        srv_image_free(img);
        return LUMO_ERR_NOMEM;
    }
    *j = (render_job){.t = t, .cam = cam, .o = o, .img = img};
    lumo_status rc = srv_parallel_for((size_t)h,
                                      o->threads > MAX_WORKERS ? MAX_WORKERS : o->threads,
                                      render_row, j, "render", o->progress);
    if (rays) {
        *rays = 0;
        for (int i = 0; i < MAX_WORKERS; i++)
            *rays += j->stats[i].rays;
    }
    free(j);
    return rc;
}

void srv_image_free(srv_image *img)
{
    free(img->rgb);
    img->rgb = NULL;
    img->w = img->h = 0;
}
