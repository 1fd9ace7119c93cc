/*
 * session_scene.c — see session_scene.h.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "session_scene.h"

/* A dynamic scene's mesh pose (lumo_session_mesh_pose, docs/dynamic.md) on
 * vertices [first, m->vertex_count): turned about +y by yaw, then moved. */
static void apply_pose(const lumo_session *ses, uint32_t i, host_mesh *m, uint32_t first)
{
    lumo_q16_16 t[3], yaw;
    if (lumo_session_mesh_pose(ses, i, t, &yaw) || (!t[0] && !t[1] && !t[2] && !yaw))
        return;
    double a = yaw / 65536.0 * 3.14159265358979323846 / 180.0, c = cos(a), sn = sin(a);
    for (uint32_t v = first; v < m->vertex_count; v++) {
        lumo_q16_16 *p = &m->pos[3 * v];
        lumo_q1_14 *n = &m->normal[3 * v];
        double x = p[0], z = p[2], nx = n[0], nz = n[2];
        p[0] = (lumo_q16_16)lround(c * x + sn * z) + t[0];
        p[1] += t[1];
        p[2] = (lumo_q16_16)lround(-sn * x + c * z) + t[2];
        n[0] = (lumo_q1_14)lround(c * nx + sn * nz);
        n[2] = (lumo_q1_14)lround(-sn * nx + c * nz);
    }
}

/* The session's meshes, one after the other, into m. */
static int take_meshes(const lumo_session *ses, host_mesh *m, host_load_stats *stats)
{
    const lumo_pkg_info *info = lumo_session_info(ses);
    uint32_t i;

    for (i = 0; i < info->mesh_count; i++) {
        lumo_pmesh_view v;
        lumo_session_progress p;
        uint32_t first = m->vertex_count;
        if (lumo_session_mesh(ses, i, &v) || lumo_session_mesh_progress(ses, i, &p)
            || host_mesh_append(m, v.positions, v.normals, v.albedo, v.vertex_count, v.triangles, v.face_count))
            return -1;
        apply_pose(ses, i, m, first);
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
        lumo_raster_light_from_pkg(&lights[i], &s->lights[s->light_count++]);
    lumo_raster_camera_from_info(info, &s->camera);
    memcpy(s->bmin, info->bmin, sizeof s->bmin);
    memcpy(s->bmax, info->bmax, sizeof s->bmax);
    return 0;
}
