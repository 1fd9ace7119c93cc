/*
 * session_scene.c — see session_scene.h.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "session_scene.h"

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

int host_scene_from_session(const lumo_session *ses, host_scene *s, host_load_stats *stats)
{
    const lumo_pkg_info *info = lumo_session_info(ses);
    const lumo_pkg_light *lights;
    host_load_stats local;
    uint32_t i, nl;
    int k;

    if (!info)
        return -1;
    if (!stats)
        stats = &local;
    memset(stats, 0, sizeof *stats);
    host_scene_free(s);
    memset(s, 0, sizeof *s);
    if (take_meshes(ses, &s->mesh, stats))
        return -1;
    lights = lumo_session_lights(ses, &nl);
    for (i = 0; i < nl; i++)
        convert_light(&lights[i], &s->lights[s->light_count++]);
    for (k = 0; k < 3; k++) {
        s->camera.eye[k] = info->eye[k];
        s->camera.target[k] = info->target[k];
        s->camera.up[k] = info->up[k];
    }
    s->camera.fovy_deg = info->fovy_deg;
    s->camera.znear = host_q16(0.01);
    return 0;
}
