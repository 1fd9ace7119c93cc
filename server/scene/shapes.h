/*
 * shapes.h — generated geometry: rectangles, cuboids, spheres, area lights,
 * and the built-in default scene (docs/scene-format.md). Winding decides
 * what is solid: front faces look out of matter (see bake inside test).
 */
#ifndef SRV_SHAPES_H
#define SRV_SHAPES_H

#include "scene/scene.h"

/* Each adder returns LUMO_OK or LUMO_ERR_NOMEM. */

/* Rectangle corner + edges u, v; its front face looks along u x v. */
lumo_status srv_add_quad(srv_scene *s, const char *name, vec3 corner, vec3 u, vec3 v, vec3 albedo);
/* Closed cuboid; normals out (a solid), or in when inward (a room). */
lumo_status srv_add_box(srv_scene *s, const char *name, vec3 lo, vec3 hi, vec3 albedo, int inward);
/* UV sphere with `segments` longitudes (>= 8) and segments/2 latitudes. */
lumo_status srv_add_sphere(srv_scene *s, const char *name, vec3 centre, float radius, int segments,
                           vec3 albedo, int inward);
/* Area light: the light plus its black emitting rectangle (visible). */
lumo_status srv_add_area_light(srv_scene *s, const srv_light *l);

/* The Cornell-style default scene. dragon: a mesh file to place inside, or
 * NULL / missing file for a generated sphere. On failure err gets a reason
 * (LUMO_ERR_NOMEM, or srv_import_file's status for the dragon). */
lumo_status srv_default_scene(srv_scene *s, const char *dragon, char *err, size_t errlen);

#endif
