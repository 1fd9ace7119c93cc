/*
 * session_scene.h — what a client session holds (lumo/session.h), as the
 * desktop renderers draw it: every mesh at its current level appended into
 * one host mesh, the lights as rasterizer lights, the default camera. Used
 * by lumo-render (packages from disk) and lumo-client (streamed scenes).
 */
#ifndef LUMO_HOST_SESSION_SCENE_H
#define LUMO_HOST_SESSION_SCENE_H

#include "lumo/session.h"
#include "mesh_build.h"

/* What a scene took from its session. */
typedef struct host_load_stats {
    uint32_t progressive;     /* meshes from PMSH streams (0: raw MESH chunks) */
    uint32_t vertices;        /* vertices of the levels held, all meshes */
    uint32_t full_vertices;   /* vertices of the full meshes */
} host_load_stats;

/* Replace *s (freed first: zero it before the first call) with the
 * session's scene; stats may be NULL. 0 on success, -1 without memory or
 * before the session has its scene info. */
int host_scene_from_session(const lumo_session *ses, host_scene *s, host_load_stats *stats);

#endif
