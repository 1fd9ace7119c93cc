/* transfer.c — diffuse PRT transfer vectors per vertex (prt/transfer.h):
 * the shadow pass (Eq. 1 for a diffuse BRDF) and the interreflection passes
 * (Eq. 2-3), traced with Embree through bake/rt.h. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "bake/rt.h"
#include "common/parallel.h"
#include "common/rng.h"
#include "prt/sh.h"
#include "prt/transfer.h"

void srv_prt_transfer_default_opts(srv_prt_transfer_opts *o)
{
    *o = (srv_prt_transfer_opts){.order = 6, .strata = 32, .shadowed = 1, .bounces = 0, .seed = 1,
                                 .threads = 0, .progress = 0};
}

void srv_prt_vertex_normals(const srv_prt_mesh *m, float *n)
{
    memset(n, 0, 3u * m->nverts * sizeof *n);
    for (uint32_t t = 0; t < m->ntris; t++) {
        const uint32_t *ix = &m->tris[3 * t];
        const float *a = &m->xyz[3 * ix[0]], *b = &m->xyz[3 * ix[1]], *c = &m->xyz[3 * ix[2]];
        float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        float fn[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        for (int k = 0; k < 3; k++)
            for (int a2 = 0; a2 < 3; a2++)
                n[3 * ix[k] + (uint32_t)a2] += fn[a2];
    }
    for (uint32_t v = 0; v < m->nverts; v++) {
        float *p = &n[3 * v], l = sqrtf(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        if (l > 0)
            p[0] /= l, p[1] /= l, p[2] /= l;
        else
            p[0] = 0, p[1] = 0, p[2] = 1;
    }
}

/* The pass state shared by the workers; every output is per vertex. */
typedef struct {
    const srv_prt_mesh *m;
    const srv_prt_transfer_opts *o;
    const srv_rt *rt;
    float   eps;
    int     nc, ndir;
    float  *dir;         /* 3 * ndir */
    double *ydir;        /* nc * ndir */
    float  *normal;      /* 3 * nverts */
    const double *prev;  /* bounce b-1 alone, nc per vertex (bounce passes) */
    double *out;         /* this pass alone, nc per vertex */
} pass_ctx;

/* Stratified directions: strata^2 cells of (z, phi), jittered from the seed. */
static void make_dirs(pass_ctx *c)
{
    srv_rng r;
    int s = c->o->strata;
    srv_rng_seed(&r, c->o->seed, 0x505254u);
    for (int i = 0; i < s; i++)
        for (int j = 0; j < s; j++) {
            int k = i * s + j;
            double u = (i + (srv_rng_u32(&r) + 0.5) / 4294967296.0) / s;
            double w = (j + (srv_rng_u32(&r) + 0.5) / 4294967296.0) / s;
            double z = 1.0 - 2.0 * u, rr = sqrt(fmax(0.0, 1.0 - z * z)), phi = 2.0 * M_PI * w;
            double d[3] = {rr * cos(phi), rr * sin(phi), z};
            for (int a = 0; a < 3; a++)
                c->dir[3 * k + a] = (float)d[a];
            srv_sh_eval(c->o->order, d, &c->ydir[(size_t)k * (size_t)c->nc]);
        }
}

static vec3 vtx(const srv_prt_mesh *m, uint32_t v)
{
    return v3(m->xyz[3 * v], m->xyz[3 * v + 1], m->xyz[3 * v + 2]);
}

/* rho_q T_q^{b-1} at a hit: barycentric mix of the hit triangle's corners. */
static double hit_transfer(const pass_ctx *c, const srv_hit *h, int k)
{
    const uint32_t *ix = &c->m->tris[3 * h->prim];
    double b[3] = {1.0 - h->bu - h->bv, h->bu, h->bv};
    double rho = (h->albedo.x + h->albedo.y + h->albedo.z) / 3.0, s = 0.0;
    for (int i = 0; i < 3; i++)
        s += b[i] * c->prev[(size_t)ix[i] * (size_t)c->nc + (size_t)k];
    return rho * s;
}

static void pass_vertex(void *ctx, size_t item, int worker)
{
    pass_ctx *c = ctx;
    (void)worker;
    uint32_t v = (uint32_t)item;
    vec3 n = v3(c->normal[3 * v], c->normal[3 * v + 1], c->normal[3 * v + 2]);
    vec3 o = v3_add(vtx(c->m, v), v3_scale(n, c->eps));
    double *t = &c->out[(size_t)v * (size_t)c->nc], w0 = 4.0 * M_PI / c->ndir / M_PI;
    memset(t, 0, (size_t)c->nc * sizeof *t);
    for (int d = 0; d < c->ndir; d++) {
        vec3 s = v3(c->dir[3 * d], c->dir[3 * d + 1], c->dir[3 * d + 2]);
        float cs = v3_dot(n, s);
        const double *y = &c->ydir[(size_t)d * (size_t)c->nc];
        if (cs <= 0.0f)
            continue;
        if (!c->prev) {   /* shadow pass, Eq. 1 */
            if (c->o->shadowed && srv_rt_occluded(c->rt, o, s, 0.0f, INFINITY))
                continue;
            for (int k = 0; k < c->nc; k++)
                t[k] += w0 * cs * y[k];
            continue;
        }
        srv_hit h;   /* light-transport pass, Eq. 2-3: only blocked directions */
        if (!srv_rt_intersect(c->rt, o, s, 0.0f, INFINITY, &h) || v3_dot(h.n, s) >= 0.0f)
            continue;   /* nothing, or the back of a face: diffuse backs are black */
        for (int k = 0; k < c->nc; k++)
            t[k] += w0 * cs * hit_transfer(c, &h, k);
    }
}

static lumo_status check(const srv_prt_mesh *m, const srv_prt_transfer_opts *o, char *err, size_t errlen)
{
    if (o->order < 1 || o->order > SRV_SH_MAX_ORDER || o->strata < 2 || o->strata > 1024 || o->bounces < 0) {
        snprintf(err, errlen, "prt: order must be 1..%d, strata 2..1024, bounces >= 0", SRV_SH_MAX_ORDER);
        return LUMO_ERR_ARG;
    }
    if (!m->nverts || !m->ntris) {
        snprintf(err, errlen, "prt: empty mesh");
        return LUMO_ERR_ARG;
    }
    for (size_t i = 0; i < 3u * (size_t)m->ntris; i++)
        if (m->tris[i] >= m->nverts) {
            snprintf(err, errlen, "prt: face index %u out of range", m->tris[i]);
            return LUMO_ERR_ARG;
        }
    return LUMO_OK;
}

/* The mesh as a one-mesh scene for the tracer (albedo for rho_q). */
static lumo_status mesh_scene(const srv_prt_mesh *m, srv_scene *s)
{
    srv_scene_init(s);
    srv_mesh *sm = srv_scene_add_mesh(s, "prt", m->nverts, m->ntris);
    if (!sm)
        return LUMO_ERR_NOMEM;
    for (uint32_t v = 0; v < m->nverts; v++) {
        sm->pos[v] = vtx(m, v);
        sm->albedo[v] = m->albedo ? v3(m->albedo[3 * v] / 255.0f, m->albedo[3 * v + 1] / 255.0f,
                                       m->albedo[3 * v + 2] / 255.0f)
                                  : v3(0.8f, 0.8f, 0.8f);
    }
    memcpy(sm->tris, m->tris, 3u * m->ntris * sizeof *m->tris);
    return LUMO_OK;
}

static lumo_status run_passes(pass_ctx *c, double *out)
{
    size_t n = (size_t)c->m->nverts * (size_t)c->nc;
    double *prev = malloc(n * sizeof *prev), *cur = malloc(n * sizeof *cur);
    lumo_status st = prev && cur ? LUMO_OK : LUMO_ERR_NOMEM;
    c->prev = NULL, c->out = out;
    if (!st)
        st = srv_parallel_for(c->m->nverts, c->o->threads, pass_vertex, c, "prt shadow", c->o->progress);
    if (!st)
        memcpy(prev, out, n * sizeof *prev);
    for (int b = 0; !st && b < c->o->bounces; b++) {
        c->prev = prev, c->out = cur;
        st = srv_parallel_for(c->m->nverts, c->o->threads, pass_vertex, c, "prt bounce", c->o->progress);
        for (size_t i = 0; !st && i < n; i++)
            out[i] += cur[i];
        double *t = prev;
        prev = cur, cur = t;
    }
    free(prev);
    free(cur);
    return st;
}

lumo_status srv_prt_transfer(const srv_prt_mesh *m, const srv_prt_transfer_opts *o, double *out,
                             char *err, size_t errlen)
{
    lumo_status st = check(m, o, err, errlen);
    if (st)
        return st;
    pass_ctx c = {.m = m, .o = o, .nc = o->order * o->order, .ndir = o->strata * o->strata};
    srv_scene s;
    st = mesh_scene(m, &s);
    c.dir = malloc(3u * (size_t)c.ndir * sizeof *c.dir);
    c.ydir = malloc((size_t)c.ndir * (size_t)c.nc * sizeof *c.ydir);
    c.normal = malloc(3u * m->nverts * sizeof *c.normal);
    srv_rt *rt = NULL;
    if (!st && (!c.dir || !c.ydir || !c.normal))
        st = LUMO_ERR_NOMEM;
    if (!st && !(rt = srv_rt_create(&s, o->threads, err, errlen)))
        st = LUMO_ERR_NOMEM;
    if (!st) {
        c.rt = rt, c.eps = 10.0f * srv_rt_epsilon(rt);
        make_dirs(&c);
        srv_prt_vertex_normals(m, c.normal);
        st = run_passes(&c, out);
        if (st)
            snprintf(err, errlen, "prt: out of memory");
    } else if (st == LUMO_ERR_NOMEM && !rt) {
        snprintf(err, errlen, "prt: out of memory or no ray-tracing scene");
    }
    srv_rt_free(rt);
    srv_scene_free(&s);
    free(c.dir);
    free(c.ydir);
    free(c.normal);
    return st;
}
