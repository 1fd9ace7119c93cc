/*
 * package_load.c — see package_load.h.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo/arena.h"
#include "lumo/package.h"
#include "lumo/session.h"
#include "lumo_host/file_io.h"
#include "lumo_host/package_msg.h"
#include "package_load.h"

/* The chunk type of a progressive stream (docs/package-format.md). */
/* Albedo of a stream that carries none: 0.75 (Q1.14). */
#define HOST_DEFAULT_ALBEDO ((lumo_q1_14)(3 * LUMO_Q14_ONE / 4))

/* Package lights to rasterizer lights. An area light becomes a spot with a
 * 90-degree half angle at its centre facing its normal, with the power of a
 * uniform hemisphere emitter (2 Phi as the point-equivalent power): the
 * client has no area lights (docs/rasterizer.md). */
static void convert_light(const lumo_pkg_light *p, lumo_raster_light *l)
{
    int k;

    memset(l, 0, sizeof *l);
    for (k = 0; k < 3; k++) {
        l->pos[k] = p->pos[k];
        l->dir[k] = p->dir[k];
        l->value[k] = p->power[k];
    }
    l->cos_cutoff = p->cos_half;
    switch (p->kind) {
    case LUMO_LIGHT_POINT: l->kind = LUMO_LIGHT_POINT; break;
    case LUMO_LIGHT_SPOT: l->kind = LUMO_LIGHT_SPOT; break;
    case LUMO_LIGHT_DIRECTIONAL: l->kind = LUMO_LIGHT_DIRECTIONAL; break;
    default:
        l->kind = LUMO_LIGHT_SPOT;
        l->cos_cutoff = 0;
        for (k = 0; k < 3; k++) {
            l->pos[k] = p->pos[k] + p->u[k] / 2 + p->v[k] / 2;
            l->value[k] = p->power[k] > UINT32_MAX / 2 ? UINT32_MAX : p->power[k] * 2;
        }
    }
}

/* Append nv vertices and nt triangles (indices local to the part) to m. */
static int mesh_append(host_mesh *m, const lumo_q16_16 *pos, const lumo_q1_14 *nrm,
                       const lumo_q1_14 *albedo, uint32_t nv, const uint32_t *tris, uint32_t nt)
{
    size_t base = m->vertex_count, vn = base + nv, tn = (size_t)m->tri_count + nt, t;
    void *a = realloc(m->pos, vn * 3 * sizeof *m->pos + 1);
    void *b = a ? realloc(m->normal, vn * 3 * sizeof *m->normal + 1) : NULL;
    void *c = b ? realloc(m->albedo, vn * 3 * sizeof *m->albedo + 1) : NULL;
    void *d = c ? realloc(m->tris, tn * 3 * sizeof *m->tris + 1) : NULL;

    if (a) m->pos = a;
    if (b) m->normal = b;
    if (c) m->albedo = c;
    if (d) m->tris = d;
    if (!d)
        return -1;
    memcpy(m->pos + 3 * base, pos, (size_t)nv * 3 * sizeof *pos);
    memcpy(m->normal + 3 * base, nrm, (size_t)nv * 3 * sizeof *nrm);
    if (albedo)
        memcpy(m->albedo + 3 * base, albedo, (size_t)nv * 3 * sizeof *albedo);
    else   /* a stream without colours: neutral grey (docs/progressive-mesh.md) */
        for (t = 3 * base; t < 3 * vn; t++)
            m->albedo[t] = HOST_DEFAULT_ALBEDO;
    for (t = 0; t < 3 * (size_t)nt; t++)
        m->tris[3 * (size_t)m->tri_count + t] = tris[t] + (uint32_t)base;
    m->vertex_count = m->vertex_cap = (uint32_t)vn;
    m->tri_count = m->tri_cap = (uint32_t)tn;
    return 0;
}

/* The session's meshes, one after the other, into m. */
static int take_meshes(const lumo_session *ses, host_mesh *m, host_load_stats *stats)
{
    const lumo_pkg_info *info = lumo_session_info(ses);
    uint32_t i;

    for (i = 0; i < info->mesh_count; i++) {
        lumo_pmesh_view v;
        lumo_session_progress p;
        if (lumo_session_mesh(ses, i, &v) || lumo_session_mesh_progress(ses, i, &p)
            || mesh_append(m, v.positions, v.normals, v.albedo, v.vertex_count, v.triangles, v.face_count))
            return -1;
        stats->progressive += p.progressive;
        stats->vertices += p.vertices;
        stats->full_vertices += p.full_vertices;
    }
    return 0;
}

/* Which message of the package failed, in words. */
static void describe_failure(const lumo_session_where *w, lumo_status st, char *err, size_t errlen)
{
    if (w->type == LUMO_PKG_PMSH)
        snprintf(err, errlen, "progressive mesh %u, batch %u: %s", w->index, w->batch, lumo_strerror(st));
    else if (w->type == LUMO_PKG_MESH)
        snprintf(err, errlen, "bad MESH chunk %u: %s", w->index, lumo_strerror(st));
    else if (w->type == LUMO_PKG_INFO)
        snprintf(err, errlen, "%s", lumo_strerror(st));
    else
        snprintf(err, errlen, "bad IVG chunk: %s", lumo_strerror(st));
}

int host_lod_parse(const char *s, host_lod *lod)
{
    char *end;
    double p;
    unsigned long n;

    memset(lod, 0, sizeof *lod);
    lod->fraction = 1;
    if (!strcmp(s, "all"))
        return 0;
    if (*s < '0' || *s > '9')
        return -1;
    if (strchr(s, '%')) {
        p = strtod(s, &end);
        if (strcmp(end, "%") || !(p >= 0 && p <= 100))
            return -1;
        lod->fraction = p / 100;
        return 0;
    }
    n = strtoul(s, &end, 10);
    if (*end || n < 1 || n > UINT32_MAX)
        return -1;
    lod->vertices = (uint32_t)n;
    return 0;
}

/* The level of detail as the session counts it: a vertex cap, or parts per
 * million of the streamed vertices (7% of 100 is 70000 ppm: 7 vertices). */
static lumo_session_config session_config(const host_lod *lod)
{
    lumo_session_config cfg = {{0, LUMO_SESSION_LOD_ALL}, LUMO_IVG_SMOOTH};

    if (lod && lod->vertices)
        cfg.lod.vertices = lod->vertices;
    else if (lod && lod->fraction < 1)
        cfg.lod.ppm = (uint32_t)llround(lod->fraction * LUMO_SESSION_LOD_ALL);
    return cfg;
}

/* Feed the whole package to a session in a heap arena sized by the SDK (a
 * desktop may use the heap; the session itself never does). */
static int run_session(const lumo_package *pkg, const host_lod *lod, lumo_session *ses, host_ivg *ivg,
                       char *err, size_t errlen)
{
    lumo_session_config cfg = session_config(lod);
    lumo_session_where w = {0, 0, 0};
    lumo_arena arena;
    lumo_status st;
    size_t bytes;

    if ((st = lumo_session_package_need(pkg, &bytes))) {
        snprintf(err, errlen, "%s", lumo_strerror(st));
        return -1;
    }
    if (!(ivg->memory = malloc(bytes))) {
        snprintf(err, errlen, "no memory for a %zu-byte arena", bytes);
        return -1;
    }
    lumo_arena_init(&arena, ivg->memory, bytes);
    if ((st = lumo_session_init(ses, &cfg, &arena)) || (st = lumo_session_feed_package(ses, pkg, &w))) {
        describe_failure(&w, st, err, errlen);
        return -1;
    }
    lumo_session_update(ses);
    ivg->grid = lumo_session_ivg(ses);
    if (ivg->grid)
        ivg->received = lumo_ivg_received_count(ivg->grid);
    return 0;
}

int host_package_load(const char *path, const host_lod *lod, host_scene *s, host_ivg *ivg,
                      host_load_stats *stats, char *err, size_t errlen)
{
    static lumo_session ses;   /* 19 KB: not on the stack */
    host_load_stats local;
    char why[200];
    size_t size = 0;
    uint8_t *data = host_read_file(path, &size);
    const lumo_pkg_light *lights;
    lumo_package pkg;
    lumo_status st;
    uint32_t i, nl;
    int k;

    if (!stats)
        stats = &local;
    memset(stats, 0, sizeof *stats);
    memset(s, 0, sizeof *s);
    memset(ivg, 0, sizeof *ivg);
    if (!data || size == 0) {   /* an empty file is as unreadable as a missing one */
        free(data);
        snprintf(err, errlen, "%s: cannot read", path);
        return -1;
    }
    if ((st = lumo_package_open(&pkg, data, size))) {
        snprintf(err, errlen, "%s: %s", path,
                 st == LUMO_ERR_VERSION ? host_package_strerror(data, size, st, why, sizeof why) : lumo_strerror(st));
        free(data);
        return -1;
    }
    if (run_session(&pkg, lod, &ses, ivg, why, sizeof why)
        || (take_meshes(&ses, &s->mesh, stats) && snprintf(why, sizeof why, "out of memory"))) {
        snprintf(err, errlen, "%s: %s", path, why);
        free(data);
        host_scene_free(s);
        host_ivg_free(ivg);
        return -1;
    }
    lights = lumo_session_lights(&ses, &nl);
    for (i = 0; i < nl; i++)
        convert_light(&lights[i], &s->lights[s->light_count++]);
    for (k = 0; k < 3; k++) {
        s->camera.eye[k] = lumo_session_info(&ses)->eye[k];
        s->camera.target[k] = lumo_session_info(&ses)->target[k];
        s->camera.up[k] = lumo_session_info(&ses)->up[k];
    }
    s->camera.fovy_deg = lumo_session_info(&ses)->fovy_deg;
    s->camera.znear = host_q16(0.01);
    free(data);
    return 0;
}

void host_ivg_free(host_ivg *ivg)
{
    free(ivg->memory);
    memset(ivg, 0, sizeof *ivg);
}
