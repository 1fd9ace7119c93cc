/* reference.c — path-traced reference images, one image row per work item,
 * one random stream per pixel (deterministic for any thread count, chunking
 * or MPI rank count: work.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "bake/reference.h"

struct srv_render_job {
    const srv_tracer *t;
    srv_camera        cam;
    int               w, h;
    srv_render_opts   o;
    size_t            first;    /* the run's first row */
    float            *out;      /* its rows, w*3 floats each */
    srv_trace_stats   stats[SRV_TRACE_MAX_WORKERS];
};
typedef struct srv_render_job render_job;

static void render_row(void *ctx, size_t item, int worker)
{
    render_job *j = ctx;
    size_t y = j->first + item;
    for (int x = 0; x < j->w; x++) {
        srv_rng r;
        vec3 sum = v3(0, 0, 0);
        srv_rng_seed(&r, j->o.seed, (uint64_t)y * (uint64_t)j->w + (uint64_t)x);
        for (int s = 0; s < j->o.spp; s++) {
            float px = (float)x + srv_rng_float(&r), py = (float)y + srv_rng_float(&r);
            vec3 d = srv_camera_ray(&j->cam, j->w, j->h, px, py);
            sum = v3_add(sum, srv_trace_camera(j->t, j->cam.eye, d, j->o.indirect_only, &r, &j->stats[worker]));
        }
        float *out = &j->out[3 * (item * (size_t)j->w + (size_t)x)];
        out[0] = sum.x / (float)j->o.spp;
        out[1] = sum.y / (float)j->o.spp;
        out[2] = sum.z / (float)j->o.spp;
    }
}

static lumo_status render_run(void *ctx, size_t first, size_t count, uint8_t *out, uint64_t *rays)
{
    render_job *j = ctx;
    j->first = first;
    j->out = (float *)(void *)out;
    return srv_trace_parallel(count, j->o.threads, render_row, j, "render", j->stats, rays);
}

static uint64_t key_vec3(uint64_t h, vec3 v)
{
    return srv_key_float(srv_key_float(srv_key_float(h, v.x), v.y), v.z);
}

lumo_status srv_render_task_init(srv_render_task *k, const srv_tracer *t, const srv_camera *cam, int w,
                                 int h, const srv_render_opts *o)
{
    memset(k, 0, sizeof *k);
    render_job *j = calloc(1, sizeof *j);
    if (!j)
        return LUMO_ERR_NOMEM;
    *j = (render_job){.t = t, .cam = *cam, .w = w, .h = h, .o = *o};
    uint64_t key = key_vec3(key_vec3(key_vec3(srv_key_scene(SRV_KEY_INIT, t->s), cam->eye), cam->target), cam->up);
    key = srv_key_u64(srv_key_u64(srv_key_float(key, cam->fovy_deg), (uint64_t)w), (uint64_t)h);
    key = srv_key_u64(srv_key_u64(srv_key_u64(key, (uint64_t)o->spp), o->seed), (uint64_t)o->indirect_only);
    key = srv_key_float(key, t->eps);
    k->work = (srv_work){.name = "reference", .items = (size_t)h, .item_bytes = (size_t)w * 3 * sizeof(float),
                         .chunk_items = srv_work_chunk_items((size_t)h), .key = key, .run = render_run,
                         .ctx = j, .progress = o->progress};
    k->job = j;
    return LUMO_OK;
}

void srv_render_task_free(srv_render_task *k)
{
    free(k->job);
    memset(k, 0, sizeof *k);
}

lumo_status srv_image_alloc(srv_image *img, int w, int h)
{
    img->w = w;
    img->h = h;
    img->rgb = calloc((size_t)w * (size_t)h * 3, sizeof(float));
    return img->rgb ? LUMO_OK : LUMO_ERR_NOMEM;
}

lumo_status srv_render_reference(const srv_tracer *t, const srv_camera *cam, int w, int h,
                                 const srv_render_opts *o, srv_image *img, uint64_t *rays)
{
    srv_render_task k;
    srv_work_report rep;
    char err[256];
    if (srv_image_alloc(img, w, h) || srv_render_task_init(&k, t, cam, w, h, o)) {
        srv_image_free(img);
        return LUMO_ERR_NOMEM;
    }
    lumo_status rc = srv_work_run_local(&k.work, NULL, (uint8_t *)(void *)img->rgb, &rep, err, sizeof err);
    srv_render_task_free(&k);
    if (rays)
        *rays = rep.rays;
    return rc;
}

void srv_image_free(srv_image *img)
{
    free(img->rgb);
    img->rgb = NULL;
    img->w = img->h = 0;
}
