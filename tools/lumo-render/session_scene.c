/*
 * session_scene.c — see session_scene.h.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "session_scene.h"

/* The session's meshes, one after the other, into m. */
static int take_meshes(const lumo_session *ses, host_mesh *m, host_load_stats *stats)
{
    const lumo_pkg_info *info = lumo_session_info(ses);
    uint32_t i;

    for (i = 0; i < info->mesh_count; i++) {
        lumo_pmesh_view v;
        lumo_session_progress p;
        if (lumo_session_mesh(ses, i, &v) || lumo_session_mesh_progress(ses, i, &p)
            || host_mesh_append(m, v.positions, v.normals, v.albedo, v.vertex_count, v.triangles, v.face_count))
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
