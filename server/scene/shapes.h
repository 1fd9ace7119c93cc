/*
 * shapes.h — generated geometry: rectangles, cuboids, spheres, area lights,
 * and the built-in default scene (docs/scene-format.md). Winding decides
 * what is solid: front faces look out of matter (see bake inside test).
 */
#ifndef LUMO_SERVER_SHAPES_H
#define LUMO_SERVER_SHAPES_H

#include "scene/scene.h"

/* Rectangle corner + edges u, v; its front face looks along u x v. */
int lumo_add_quad(lumo_scene *s, const char *name, vec3 corner, vec3 u, vec3 v, vec3 albedo);
/* Closed cuboid; normals out (a solid), or in when inward (a room). */
int lumo_add_box(lumo_scene *s, const char *name, vec3 lo, vec3 hi, vec3 albedo, int inward);
/* UV sphere with `segments` longitudes (>= 8) and segments/2 latitudes. */
int lumo_add_sphere(lumo_scene *s, const char *name, vec3 centre, float radius, int segments,
                    vec3 albedo, int inward);
/* Area light: the light plus its black emitting rectangle (visible). */
int lumo_add_area_light(lumo_scene *s, const lumo_light *l);

/* The Cornell-style default scene. dragon: a mesh file to place inside, or
 * NULL / missing file for a generated sphere. err gets a reason on -1. */
int lumo_default_scene(lumo_scene *s, const char *dragon, char *err, size_t errlen);

#endif
