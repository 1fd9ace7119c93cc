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
#include "lumo/pmesh.h"
#include "lumo_host/file_io.h"
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
    case LUMO_PKG_LIGHT_POINT: l->kind = LUMO_LIGHT_POINT; break;
    case LUMO_PKG_LIGHT_SPOT: l->kind = LUMO_LIGHT_SPOT; break;
    case LUMO_PKG_LIGHT_DIRECTIONAL: l->kind = LUMO_LIGHT_DIRECTIONAL; break;
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

static int load_raw_meshes(const lumo_package *pkg, const lumo_pkg_info *info, host_mesh *m,
                           host_load_stats *stats)
{
    uint32_t i;

    for (i = 0; i < info->mesh_count; i++) {
        lumo_pkg_mesh_info mi;
        host_mesh part;
        int rc;
        if (lumo_package_mesh_info(pkg, i, &mi))
            return -1;
        memset(&part, 0, sizeof part);
        part.pos = malloc((size_t)mi.nverts * 3 * sizeof *part.pos + 1);
        part.normal = malloc((size_t)mi.nverts * 3 * sizeof *part.normal + 1);
        part.albedo = malloc((size_t)mi.nverts * 3 * sizeof *part.albedo + 1);
        part.tris = malloc((size_t)mi.ntris * 3 * sizeof *part.tris + 1);
        rc = !part.pos || !part.normal || !part.albedo || !part.tris
             || lumo_package_mesh_read(pkg, i, part.pos, part.normal, part.albedo, part.tris)
             || mesh_append(m, part.pos, part.normal, part.albedo, mi.nverts, part.tris, mi.ntris);
        host_mesh_free(&part);
        if (rc)
            return -1;
        stats->vertices += mi.nverts;
        stats->full_vertices += mi.nverts;
    }
    return 0;
}

/* The vertex count of the level `lod` asks of a stream with header h. */
static uint32_t lod_target(const host_lod *lod, const lumo_pmesh_header *h)
{
    uint32_t t = h->vertices;

    if (lod && lod->vertices)
        t = lod->vertices < h->vertices ? lod->vertices : h->vertices;
    else if (lod && lod->fraction < 1)
        /* less a hair so that 7% of 100 is 7, not the 8 of 7.000000000000001 */
        t = h->base_vertices + (uint32_t)ceil(lod->fraction * (h->vertices - h->base_vertices) - 1e-9);
    return t < h->base_vertices ? h->base_vertices : t;
}

/* Batches in stream order until the level has `target` vertices, then a
 * step back inside the last batch when it overshoots (lumo_pmesh_rewind):
 * the client path of a device that stops receiving at that level. */
static lumo_status pm_refine(lumo_pmesh *pm, const uint8_t *stream, size_t len, uint32_t target,
                             uint32_t *batch)
{
    size_t at = LUMO_PMESH_HEADER_SIZE, n;
    lumo_pmesh_view v;
    lumo_status st;

    for (*batch = 0;; ++*batch) {
        lumo_pmesh_get_view(pm, &v);
        if (v.vertex_count >= target || lumo_pmesh_complete(pm))
            break;
        if ((st = lumo_pmesh_record_size(stream + at, len - at, &n)))
            return st;
        if (n > len - at)
            return LUMO_ERR_TRUNCATED;
        if ((st = lumo_pmesh_apply(pm, stream + at, n)))
            return st;
        at += n;
    }
    return v.vertex_count > target ? lumo_pmesh_rewind(pm, target) : LUMO_OK;
}

/* Progressive stream `index` at the asked level, appended to m. */
static int load_stream(const uint8_t *stream, size_t len, uint32_t index, const host_lod *lod,
                       host_mesh *m, host_load_stats *stats, char *err, size_t errlen)
{
    lumo_pmesh_header h;
    lumo_pmesh pm;
    lumo_pmesh_view v;
    lumo_arena arena;
    lumo_status st;
    uint32_t batch = 0;
    size_t bytes;
    void *mem;

    if ((st = lumo_pmesh_read_header(stream, len, &h))) {
        snprintf(err, errlen, "progressive mesh %u: bad stream header: %s", index, lumo_strerror(st));
        return -1;
    }
    bytes = lumo_pmesh_arena_bytes(&h);
    if (bytes == SIZE_MAX || !(mem = malloc(bytes))) {
        snprintf(err, errlen, "progressive mesh %u: no memory for a %zu-byte arena", index, bytes);
        return -1;
    }
    lumo_arena_init(&arena, mem, bytes);
    if ((st = lumo_pmesh_init(&pm, &h, &arena))
        || (st = pm_refine(&pm, stream, len, lod_target(lod, &h), &batch))) {
        snprintf(err, errlen, "progressive mesh %u, batch %u: %s", index, batch, lumo_strerror(st));
        free(mem);
        return -1;
    }
    lumo_pmesh_get_view(&pm, &v);
    if (mesh_append(m, v.positions, v.normals, v.albedo, v.vertex_count, v.triangles, v.face_count)) {
        snprintf(err, errlen, "progressive mesh %u: out of memory", index);
        free(mem);
        return -1;
    }
    stats->progressive++;
    stats->vertices += v.vertex_count;
    stats->full_vertices += h.vertices;
    free(mem);
    return 0;
}

/* One PMSH stream per mesh (in mesh order) replaces the MESH chunks. */
static int load_meshes(const lumo_package *pkg, const lumo_pkg_info *info, const host_lod *lod,
                       host_mesh *m, host_load_stats *stats, char *err, size_t errlen)
{
    const uint8_t *stream;
    uint32_t i, len, streams = 0;

    while (lumo_package_find(pkg, LUMO_PKG_PMSH, streams, &stream, &len) == LUMO_OK)
        streams++;
    if (streams == 0) {
        if (load_raw_meshes(pkg, info, m, stats) == 0)
            return 0;
        snprintf(err, errlen, "bad MESH chunk");
        return -1;
    }
    if (streams != info->mesh_count) {
        snprintf(err, errlen, "%u progressive mesh streams for %u meshes", streams, info->mesh_count);
        return -1;
    }
    for (i = 0; i < streams; i++) {
        lumo_package_find(pkg, LUMO_PKG_PMSH, i, &stream, &len);
        if (load_stream(stream, len, i, lod, m, stats, err, errlen))
            return -1;
    }
    return 0;
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

static int load_ivg(const lumo_package *pkg, host_ivg *ivg)
{
    lumo_ivg_desc desc;
    lumo_arena arena;
    size_t bytes;

    memset(ivg, 0, sizeof *ivg);
    if (lumo_package_ivg_desc(pkg, &desc))
        return 0;                                   /* no IVG: fine */
    bytes = lumo_ivg_memory_size(&desc);
    if (!bytes || !(ivg->memory = malloc(bytes + LUMO_ARENA_SLACK)))
        return -1;
    lumo_arena_init(&arena, ivg->memory, bytes + LUMO_ARENA_SLACK);
    if (lumo_ivg_create(&ivg->grid, &arena, &desc))
        return -1;
    /* The quantized form is what a client receives; the float form if the
     * package only has that. */
    if (lumo_package_load_ivg(pkg, ivg->grid, LUMO_IVG_FORM_QUANTIZED, &ivg->received)
        && lumo_package_load_ivg(pkg, ivg->grid, LUMO_IVG_FORM_FLOAT, &ivg->received))
        return -1;
    if (lumo_ivg_received_count(ivg->grid) < lumo_ivg_vertex_count(ivg->grid))
        lumo_ivg_pushpull(ivg->grid, LUMO_IVG_SMOOTH);
    return 0;
}

int host_package_load(const char *path, const host_lod *lod, host_scene *s, host_ivg *ivg,
                      host_load_stats *stats, char *err, size_t errlen)
{
    host_load_stats local;
    char why[200];
    size_t size = 0;
    uint8_t *data = host_read_file(path, &size);
    lumo_package pkg;
    lumo_pkg_info info;
    lumo_status st;
    uint32_t i;
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
    if ((st = lumo_package_open(&pkg, data, size)) || (st = lumo_package_info(&pkg, &info))) {
        snprintf(err, errlen, "%s: %s", path, lumo_strerror(st));
        free(data);
        return -1;
    }
    for (i = 0; i < info.light_count && s->light_count < LUMO_RASTER_MAX_LIGHTS; i++) {
        lumo_pkg_light pl;
        if (lumo_package_light(&pkg, i, &pl) == LUMO_OK)
            convert_light(&pl, &s->lights[s->light_count++]);
    }
    for (k = 0; k < 3; k++) {
        s->camera.eye[k] = info.eye[k];
        s->camera.target[k] = info.target[k];
        s->camera.up[k] = info.up[k];
    }
    s->camera.fovy_deg = info.fovy_deg;
    s->camera.znear = host_q16(0.01);
    if (load_meshes(&pkg, &info, lod, &s->mesh, stats, why, sizeof why)
        || (load_ivg(&pkg, ivg) && snprintf(why, sizeof why, "bad IVG chunk"))) {
        snprintf(err, errlen, "%s: %s", path, why);
        free(data);
        host_scene_free(s);
        host_ivg_free(ivg);
        return -1;
    }
    free(data);
    return 0;
}

void host_ivg_free(host_ivg *ivg)
{
    free(ivg->memory);
    memset(ivg, 0, sizeof *ivg);
}
