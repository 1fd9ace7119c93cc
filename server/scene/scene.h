/*
 * scene.h — the server's in-memory scene: triangle meshes with per-vertex
 * albedo, lights, a default camera (docs/scene-format.md for units).
 *
 * A scene owns its meshes (heap). Builders (scene_build.c primitives,
 * import.c for files, default_scene.c) add meshes; srv_scene_validate()
 * checks the whole scene before it is baked.
 */
#ifndef SRV_SCENE_H
#define SRV_SCENE_H

#include <stddef.h>
#include <stdint.h>
#include "scene/camera.h"
#include "common/vec3.h"
#include "lumo/config.h"
#include "lumo/scene.h"
#include "lumo/status.h"


/* One light. power: W per channel (point, spot, area) or irradiance in W/m^2
 * (directional). dir: unit spot axis / direction of travel. For an area
 * light pos is a corner and u, v its edges (emits towards u x v). */
typedef struct srv_light {
    lumo_light_kind kind;
    vec3  pos, dir, u, v;
    float half_angle_deg;   /* spot only */
    float cos_half;         /* spot only: cos(half_angle) */
    vec3  power;
} srv_light;

/* A triangle mesh in scene space. emitter: the surface of an area light
 * (black, never shaded; its light comes from next-event estimation). */
typedef struct srv_mesh {
    char     name[64];
    uint32_t nverts, ntris;
    vec3    *pos;         /* nverts */
    vec3    *albedo;      /* nverts, linear, each channel in [0, 0.98] */
    uint32_t *tris;       /* 3 * ntris vertex indices */
    int      emitter;
} srv_mesh;

typedef struct srv_scene {
    srv_mesh   *meshes;
    size_t      nmeshes, cap_meshes;
    srv_light  *lights;
    size_t      nlights, cap_lights;
    srv_camera  camera;     /* default view for the reference renderer */
    int         has_camera;
} srv_scene;

void srv_scene_init(srv_scene *s);
void srv_scene_free(srv_scene *s);

/* Append an empty mesh with room for nverts/ntris; NULL when out of memory.
 * The returned pointer is valid until the next add. */
srv_mesh *srv_scene_add_mesh(srv_scene *s, const char *name, uint32_t nverts, uint32_t ntris);
/* Append a copy of l: LUMO_OK or LUMO_ERR_NOMEM. */
lumo_status srv_scene_add_light(srv_scene *s, const srv_light *l);

/* Replace every albedo (the --albedo option). */
void srv_scene_override_albedo(srv_scene *s, vec3 albedo);

/* Axis-aligned bounds of every mesh; 0 when the scene has no vertex. */
int srv_scene_bounds(const srv_scene *s, vec3 *bmin, vec3 *bmax);

size_t srv_scene_triangle_count(const srv_scene *s);

/* Largest |coordinate| of a scene vertex after import and transforms,
 * metres: the client holds positions in Q16.16 ([-32768, 32768),
 * lumo/fixed.h), and the IVG box is padded beyond the bounds. */
#define SRV_SCENE_MAX_COORD 32000.0f

/* Every vertex within SRV_SCENE_MAX_COORD: LUMO_OK, or LUMO_ERR_RANGE /
 * LUMO_ERR_NONFINITE naming the mesh, the vertex and the value. */
lumo_status srv_scene_check_range(const srv_scene *s, char *err, size_t errlen);

/* Check the scene is bakeable: geometry present, a light present, every
 * coordinate finite and within SRV_SCENE_MAX_COORD, every index in range,
 * no zero-area face. On failure
 * writes a one-line reason into err and returns LUMO_ERR_ARG (no geometry,
 * no light), LUMO_ERR_LIMIT (more than LUMO_MAX_LIGHTS lights),
 * LUMO_ERR_NONFINITE (a vertex), LUMO_ERR_RANGE (a face index, a negative
 * or non-finite light value) or LUMO_ERR_CORRUPT (a zero-area face). */
lumo_status srv_scene_validate(const srv_scene *s, char *err, size_t errlen);

/* Parse a light in the command-line syntax of docs/scene-format.md
 * ("point:X,Y,Z:R,G,B", "spot:...", "directional:...", "area:...")
 * (light_parse.c). LUMO_OK, or with "OPT 'TEXT': why" in err naming the
 * field (kind, position, direction, cone half-angle, corner, edge U/V,
 * power, irradiance) and its value, e.g. "--light 'point:0,1:1,1,1':
 * position needs 3 numbers, got 2": LUMO_ERR_LIMIT (text longer than 511
 * bytes) or LUMO_ERR_ARG. Positions within ±SRV_SCENE_MAX_COORD m, powers
 * in [0, 1e9]. `opt` is how the caller names it ("--light"); *out is
 * untouched on failure. */
lumo_status srv_light_parse_as(const char *opt, const char *text, srv_light *out, char *err, size_t errlen);
/* srv_light_parse_as("light", ...). */
lumo_status srv_light_parse(const char *text, srv_light *out, char *err, size_t errlen);

/* Parse "R,G,B" (or N comma-separated floats) strictly: LUMO_OK, or
 * LUMO_ERR_ARG for anything else (non-finite values included). */
lumo_status srv_parse_floats(const char *text, float *out, int n);

#endif
