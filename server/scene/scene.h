/*
 * scene.h — the server's in-memory scene: triangle meshes with per-vertex
 * albedo, lights, a default camera (docs/scene-format.md for units).
 *
 * A scene owns its meshes (heap). Builders (scene_build.c primitives,
 * import.c for files, default_scene.c) add meshes; lumo_scene_validate()
 * checks the whole scene before it is baked.
 */
#ifndef LUMO_SERVER_SCENE_H
#define LUMO_SERVER_SCENE_H

#include <stddef.h>
#include <stdint.h>
#include "scene/camera.h"
#include "common/vec3.h"

/* The package holds at most this many lights (LUMO_PKG_MAX_LIGHTS). */
#define LUMO_SCENE_MAX_LIGHTS 64

typedef enum lumo_light_kind {
    LUMO_LIGHT_POINT = 0, LUMO_LIGHT_SPOT = 1, LUMO_LIGHT_DIRECTIONAL = 2, LUMO_LIGHT_AREA = 3
} lumo_light_kind;

/* One light. power: W per channel (point, spot, area) or irradiance in W/m^2
 * (directional). dir: unit spot axis / direction of travel. For an area
 * light pos is a corner and u, v its edges (emits towards u x v). */
typedef struct lumo_light {
    lumo_light_kind kind;
    vec3  pos, dir, u, v;
    float half_angle_deg;   /* spot only */
    float cos_half;         /* spot only: cos(half_angle) */
    vec3  power;
} lumo_light;

/* A triangle mesh in scene space. emitter: the surface of an area light
 * (black, never shaded; its light comes from next-event estimation). */
typedef struct lumo_mesh {
    char     name[64];
    uint32_t nverts, ntris;
    vec3    *pos;         /* nverts */
    vec3    *albedo;      /* nverts, linear, each channel in [0, 0.98] */
    uint32_t *tris;       /* 3 * ntris vertex indices */
    int      emitter;
} lumo_mesh;

typedef struct lumo_scene {
    lumo_mesh  *meshes;
    size_t      nmeshes, cap_meshes;
    lumo_light *lights;
    size_t      nlights, cap_lights;
    lumo_camera camera;     /* default view for the reference renderer */
    int         has_camera;
} lumo_scene;

void lumo_scene_init(lumo_scene *s);
void lumo_scene_free(lumo_scene *s);

/* Append an empty mesh with room for nverts/ntris; NULL when out of memory.
 * The returned pointer is valid until the next add. */
lumo_mesh *lumo_scene_add_mesh(lumo_scene *s, const char *name, uint32_t nverts, uint32_t ntris);
int lumo_scene_add_light(lumo_scene *s, const lumo_light *l);

/* Replace every albedo (the --albedo option). */
void lumo_scene_override_albedo(lumo_scene *s, vec3 albedo);

/* Axis-aligned bounds of every mesh; 0 when the scene has no vertex. */
int lumo_scene_bounds(const lumo_scene *s, vec3 *bmin, vec3 *bmax);

size_t lumo_scene_triangle_count(const lumo_scene *s);

/* Check the scene is bakeable: geometry present, a light present, every
 * coordinate finite, every index in range, no zero-area face. On failure
 * writes a one-line reason into err and returns -1. */
int lumo_scene_validate(const lumo_scene *s, char *err, size_t errlen);

/* Parse a light in the command-line syntax of docs/scene-format.md
 * ("point:X,Y,Z:R,G,B", "spot:...", "directional:...", "area:...").
 * Returns 0, or -1 with a reason in err. */
int lumo_light_parse(const char *text, lumo_light *out, char *err, size_t errlen);

/* Parse "R,G,B" (or N comma-separated floats) strictly: 0 or -1. */
int lumo_parse_floats(const char *text, float *out, int n);

#endif
