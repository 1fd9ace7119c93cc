/* reference.c — path-traced reference images, one image row per work item,
 * one random stream per pixel (deterministic for any thread count). */
#include <stdlib.h>
#include <string.h>
#include "common/parallel.h"
#include "bake/reference.h"

#define MAX_WORKERS 256

typedef struct {
    const lumo_tracer      *t;
    const lumo_camera      *cam;
    const lumo_render_opts *o;
    lumo_image             *img;
    lumo_trace_stats        stats[MAX_WORKERS];
} render_job;

static void render_row(void *ctx, size_t y, int worker)
{
    render_job *j = ctx;
    lumo_image *img = j->img;
    for (int x = 0; x < img->w; x++) {
        lumo_rng r;
        vec3 sum = v3(0, 0, 0);
        lumo_rng_seed(&r, j->o->seed, (uint64_t)y * (uint64_t)img->w + (uint64_t)x);
        for (int s = 0; s < j->o->spp; s++) {
            float px = (float)x + lumo_rng_float(&r), py = (float)y + lumo_rng_float(&r);
            vec3 d = lumo_camera_ray(j->cam, img->w, img->h, px, py);
            sum = v3_add(sum, lumo_trace_camera(j->t, j->cam->eye, d, j->o->indirect_only, &r,
                                                &j->stats[worker]));
        }
        float *out = &img->rgb[3 * ((size_t)y * (size_t)img->w + (size_t)x)];
        out[0] = sum.x / (float)j->o->spp;
        out[1] = sum.y / (float)j->o->spp;
        out[2] = sum.z / (float)j->o->spp;
    }
}

int lumo_render_reference(const lumo_tracer *t, const lumo_camera *cam, int w, int h,
                          const lumo_render_opts *o, lumo_image *img, uint64_t *rays)
{
    render_job *j = calloc(1, sizeof *j);
    img->w = w;
    img->h = h;
    img->rgb = calloc((size_t)w * (size_t)h * 3, sizeof(float));
    if (!j || !img->rgb) {
        free(j);
        lumo_image_free(img);
        return -1;
    }
    *j = (render_job){.t = t, .cam = cam, .o = o, .img = img};
    int rc = lumo_parallel_for((size_t)h, o->threads > MAX_WORKERS ? MAX_WORKERS : o->threads,
                               render_row, j, "render", o->progress);
    if (rays) {
        *rays = 0;
        for (int i = 0; i < MAX_WORKERS; i++)
            *rays += j->stats[i].rays;
    }
    free(j);
    return rc;
}

void lumo_image_free(lumo_image *img)
{
    free(img->rgb);
    img->rgb = NULL;
    img->w = img->h = 0;
}
