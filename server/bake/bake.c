/* bake.c — the IVG bake, seed 000 §3.1 (estimator and sampling in bake.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "bake/bake.h"
#include "common/progress.h"

/* The bake as srv_work: run() computes the vertices [first, first+count)
 * into records at out. */
struct srv_bake_job {
    const srv_tracer     *t;
    srv_grid              g;
    srv_bake_opts         o;
    size_t                first;
    srv_bake_record      *out;
    srv_trace_stats       stats[SRV_TRACE_MAX_WORKERS];
};
typedef struct srv_bake_job bake_job;

srv_grid srv_grid_over(const srv_scene *s, const int dims[3])
{
    srv_grid g;
    memset(&g, 0, sizeof g);
    for (int a = 0; a < 3; a++)
        g.dims[a] = dims[a];
    srv_scene_bounds(s, &g.bmin, &g.bmax);
    /* A flat scene (one floor quad) still needs a box with volume: the
     * client requires bmax > bmin on every axis. */
    float ext = v3_maxc(v3_sub(g.bmax, g.bmin)), pad = fmaxf(0.01f * ext, 1e-3f);
    vec3 lo = g.bmin, hi = g.bmax;
    if (hi.x - lo.x < pad) g.bmin.x -= pad, g.bmax.x += pad;
    if (hi.y - lo.y < pad) g.bmin.y -= pad, g.bmax.y += pad;
    if (hi.z - lo.z < pad) g.bmin.z -= pad, g.bmax.z += pad;
    return g;
}

vec3 srv_grid_vertex(const srv_grid *g, int i, int j, int k)
{
    vec3 e = v3_sub(g->bmax, g->bmin);
    return v3_add(g->bmin, v3(e.x * (float)i / (float)(g->dims[0] - 1),
                              e.y * (float)j / (float)(g->dims[1] - 1),
                              e.z * (float)k / (float)(g->dims[2] - 1)));
}

/* Uniform direction on the sphere from (u1, u2) in [0,1)^2. */
static vec3 sphere_dir(float u1, float u2)
{
    float z = 1.0f - 2.0f * u1, r = sqrtf(fmaxf(0.0f, 1.0f - z * z)), phi = 2.0f * (float)M_PI * u2;
    return v3(r * cosf(phi), r * sinf(phi), z);
}

/* Grid vertices on the bounds lie on the outermost walls: move them inside
 * by a hair so that rays leave from the scene's side of the wall. */
static vec3 vertex_position(const bake_job *j, size_t v)
{
    const srv_grid *g = &j->g;
    int i = (int)(v % (size_t)g->dims[0]), jj = (int)((v / (size_t)g->dims[0]) % (size_t)g->dims[1]);
    int k = (int)(v / ((size_t)g->dims[0] * (size_t)g->dims[1]));
    vec3 p = srv_grid_vertex(g, i, jj, k), in = v3_scale(v3(1, 1, 1), 4.0f * j->t->eps);
    return v3_max(v3_add(g->bmin, in), v3_min(v3_sub(g->bmax, in), p));
}

static void bake_vertex(void *ctx, size_t item, int worker)
{
    bake_job *j = ctx;
    size_t v = j->first + item;
    int spp = j->o.spp, side = (int)sqrtf((float)spp), back = 0;
    double sum[6][3][3], sq[6][3];
    srv_rng r;
    vec3 p = vertex_position(j, v);
    memset(sum, 0, sizeof sum);
    memset(sq, 0, sizeof sq);
    srv_rng_seed(&r, j->o.seed, v);
    for (int s = 0; s < spp; s++) {
        /* side*side jittered strata first; the remainder uniform. */
        float u1 = srv_rng_float(&r), u2 = srv_rng_float(&r);
        if (s < side * side)
            u1 = ((float)(s % side) + u1) / (float)side, u2 = ((float)(s / side) + u2) / (float)side;
        vec3 w = sphere_dir(u1, u2);
        int b;
        vec3 L = v3_scale(srv_trace_indirect(j->t, p, w, &r, &j->stats[worker], &b), 4.0f * (float)M_PI);
        back += b;
        for (int a = 0; a < 3; a++) {
            float wa = v3_get(w, a);
            int h = 2 * a + (wa < 0.0f);
            for (int ch = 0; ch < 3; ch++) {
                double l = v3_get(L, ch);
                for (int c = 0; c < 3; c++)
                    sum[h][ch][c] += l * v3_get(w, c);
                sq[h][ch] += (l * wa) * (l * wa);
            }
        }
    }
    srv_bake_record *rec = &j->out[item];
    memset(rec, 0, sizeof *rec);
    rec->valid = (float)back <= j->o.solid_fraction * (float)spp;
    for (int h = 0; h < 6; h++)
        for (int ch = 0; ch < 3; ch++) {
            double mean = sum[h][ch][h / 2] * (h & 1 ? -1.0 : 1.0) / spp;
            double var = sq[h][ch] / spp - mean * mean;
            rec->se[h * 3 + ch] = (float)sqrt(fmax(var, 0.0) / spp);
            for (int c = 0; c < 3; c++)
                rec->I[(h * 3 + ch) * 3 + c] = rec->valid ? (float)(sum[h][ch][c] / spp) : 0.0f;
        }
}

static lumo_status bake_run(void *ctx, size_t first, size_t count, uint8_t *out, uint64_t *rays)
{
    bake_job *j = ctx;
    j->first = first;
    j->out = (srv_bake_record *)(void *)out;
    return srv_trace_parallel(count, j->o.threads, bake_vertex, j, "bake", j->stats, rays);
}

/* Refuse up front what would only be killed later: calloc of a huge grid
 * succeeds lazily under overcommit and the bake dies half-way. */
static int fits_in_memory(size_t nverts, char *err, size_t errlen)
{
    /* the records (work.h) and the result they are copied into */
    double need = (double)nverts * ((double)sizeof(srv_bake_record) + (6 * 9 + 6 * 3) * 4.0 + 1.0);
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    if (pages > 0 && page > 0 && need > 0.75 * (double)pages * (double)page) {
        snprintf(err, errlen, "a %zu-vertex grid needs %.1f GiB, more than this machine has; use a smaller --grid",
                 nverts, need / (1024.0 * 1024.0 * 1024.0));
        return 0;
    }
    return 1;
}

lumo_status srv_bake_task_init(srv_bake_task *k, const srv_tracer *t, const srv_grid *g,
                               const srv_bake_opts *o, char *err, size_t errlen)
{
    size_t nverts = (size_t)g->dims[0] * (size_t)g->dims[1] * (size_t)g->dims[2];
    memset(k, 0, sizeof *k);
    if (!fits_in_memory(nverts, err, errlen))
        return LUMO_ERR_NOMEM;
    bake_job *j = calloc(1, sizeof *j);
    if (!j) {
        snprintf(err, errlen, "out of memory");
        return LUMO_ERR_NOMEM;
    }
    *j = (bake_job){.t = t, .g = *g, .o = *o};
    uint64_t key = srv_key_scene(SRV_KEY_INIT, t->s);
    for (int a = 0; a < 3; a++)
        key = srv_key_u64(key, (uint64_t)g->dims[a]);
    key = srv_key_float(srv_key_float(srv_key_float(key, g->bmin.x), g->bmin.y), g->bmin.z);
    key = srv_key_float(srv_key_float(srv_key_float(key, g->bmax.x), g->bmax.y), g->bmax.z);
    key = srv_key_u64(srv_key_u64(key, (uint64_t)o->spp), o->seed);
    key = srv_key_float(srv_key_float(key, o->solid_fraction), t->eps);
    k->work = (srv_work){.name = "ivg", .items = nverts, .item_bytes = sizeof(srv_bake_record),
                         .chunk_items = srv_work_chunk_items(nverts), .key = key, .run = bake_run,
                         .ctx = j, .progress = o->progress};
    k->job = j;
    return LUMO_OK;
}

lumo_status srv_bake_task_result(const srv_bake_task *k, const uint8_t *records, srv_bake_result *res,
                                 char *err, size_t errlen)
{
    const srv_bake_record *rec = (const srv_bake_record *)(const void *)records;
    memset(res, 0, sizeof *res);
    res->grid = k->job->g;
    res->nverts = k->work.items;
    res->I = malloc(res->nverts * 6 * 9 * sizeof *res->I);
    res->se = malloc(res->nverts * 6 * 3 * sizeof *res->se);
    res->valid = malloc(res->nverts);
    if (!res->I || !res->se || !res->valid) {
        srv_bake_result_free(res);
        snprintf(err, errlen, "out of memory for a %zu-vertex grid", k->work.items);
        return LUMO_ERR_NOMEM;
    }
    for (size_t v = 0; v < res->nverts; v++) {
        memcpy(&res->I[SRV_BAKE_I(v, 0, 0)], rec[v].I, sizeof rec[v].I);
        memcpy(&res->se[v * 6 * 3], rec[v].se, sizeof rec[v].se);
        res->valid[v] = rec[v].valid;
    }
    return LUMO_OK;
}

void srv_bake_task_free(srv_bake_task *k)
{
    free(k->job);
    memset(k, 0, sizeof *k);
}

lumo_status srv_bake(const srv_tracer *t, const srv_grid *g, const srv_bake_opts *o,
                     srv_bake_result *res, char *err, size_t errlen)
{
    srv_bake_task k;
    srv_work_report rep;
    memset(res, 0, sizeof *res);
    lumo_status st = srv_bake_task_init(&k, t, g, o, err, errlen);
    if (st)
        return st;
    uint8_t *records = malloc(k.work.items * k.work.item_bytes);
    if (!records) {
        srv_bake_task_free(&k);
        snprintf(err, errlen, "out of memory for a %zu-vertex grid", k.work.items);
        return LUMO_ERR_NOMEM;
    }
    st = srv_work_run_local(&k.work, NULL, records, &rep, err, errlen);
    if (!st)
        st = srv_bake_task_result(&k, records, res, err, errlen);
    free(records);
    srv_bake_task_free(&k);
    if (st)
        return st;
    res->rays = rep.rays;
    res->seconds = rep.seconds;
    return LUMO_OK;
}

void srv_bake_result_free(srv_bake_result *res)
{
    free(res->I);
    free(res->se);
    free(res->valid);
    memset(res, 0, sizeof *res);
}
