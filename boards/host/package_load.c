/*
 * package_load.c — see package_load.h.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo/arena.h"
#include "lumo/package.h"
#include "lumo_host/file_io.h"
#include "package_load.h"

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

static int load_meshes(const lumo_package *pkg, const lumo_pkg_info *info, host_mesh *m)
{
    uint32_t i;

    for (i = 0; i < info->mesh_count; i++) {
        lumo_pkg_mesh_info mi;
        uint32_t base = m->vertex_count, t;
        host_mesh part;
        if (lumo_package_mesh_info(pkg, i, &mi))
            return -1;
        memset(&part, 0, sizeof part);
        part.pos = malloc((size_t)mi.nverts * 3 * sizeof *part.pos + 1);
        part.normal = malloc((size_t)mi.nverts * 3 * sizeof *part.normal + 1);
        part.albedo = malloc((size_t)mi.nverts * 3 * sizeof *part.albedo + 1);
        part.tris = malloc((size_t)mi.ntris * 3 * sizeof *part.tris + 1);
        if (!part.pos || !part.normal || !part.albedo || !part.tris
            || lumo_package_mesh_read(pkg, i, part.pos, part.normal, part.albedo, part.tris)) {
            host_mesh_free(&part);
            return -1;
        }
        /* append */
        {
            size_t nv = (size_t)base + mi.nverts, nt = (size_t)m->tri_count + mi.ntris;
            void *a = realloc(m->pos, nv * 3 * sizeof *m->pos);
            void *b = a ? realloc(m->normal, nv * 3 * sizeof *m->normal) : NULL;
            void *c = b ? realloc(m->albedo, nv * 3 * sizeof *m->albedo) : NULL;
            void *d = c ? realloc(m->tris, nt * 3 * sizeof *m->tris) : NULL;
            if (a) m->pos = a;
            if (b) m->normal = b;
            if (c) m->albedo = c;
            if (d) m->tris = d;
            if (!d) {
                host_mesh_free(&part);
                return -1;
            }
            memcpy(m->pos + 3 * (size_t)base, part.pos, (size_t)mi.nverts * 3 * sizeof *m->pos);
            memcpy(m->normal + 3 * (size_t)base, part.normal, (size_t)mi.nverts * 3 * sizeof *m->normal);
            memcpy(m->albedo + 3 * (size_t)base, part.albedo, (size_t)mi.nverts * 3 * sizeof *m->albedo);
            for (t = 0; t < 3 * mi.ntris; t++)
                m->tris[3 * (size_t)m->tri_count + t] = part.tris[t] + base;
            m->vertex_count = (uint32_t)nv;
            m->tri_count = (uint32_t)nt;
            m->vertex_cap = (uint32_t)nv;
            m->tri_cap = (uint32_t)nt;
        }
        host_mesh_free(&part);
    }
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

int host_package_load(const char *path, host_scene *s, host_ivg *ivg, char *err, size_t errlen)
{
    size_t size = 0;
    uint8_t *data = lumo_read_file(path, &size);
    lumo_package pkg;
    lumo_pkg_info info;
    lumo_status st;
    uint32_t i;
    int k;

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
    if (load_meshes(&pkg, &info, &s->mesh) || load_ivg(&pkg, ivg)) {
        snprintf(err, errlen, "%s: bad mesh or IVG chunk", path);
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
