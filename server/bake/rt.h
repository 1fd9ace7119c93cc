/*
 * rt.h — ray queries against a scene through Embree 3. The scene must stay
 * alive and unchanged while the lumo_rt exists. Queries are thread-safe.
 */
#ifndef LUMO_SERVER_RT_H
#define LUMO_SERVER_RT_H

#include <stddef.h>
#include "scene/scene.h"

typedef struct lumo_rt lumo_rt;

typedef struct lumo_hit {
    float t;
    vec3  n;          /* unit geometric normal, as wound (front side) */
    vec3  albedo;     /* interpolated vertex albedo */
    int   emitter;    /* hit the surface of an area light */
    int   light;      /* index of that light in scene->lights, or -1 */
} lumo_hit;

/* threads: Embree's own build threads (0 = its default). NULL with err. */
lumo_rt *lumo_rt_create(const lumo_scene *s, int threads, char *err, size_t errlen);
void lumo_rt_free(lumo_rt *rt);

/* Closest hit in (tnear, tfar): 1 and *hit, or 0. */
int lumo_rt_intersect(const lumo_rt *rt, vec3 o, vec3 d, float tnear, float tfar, lumo_hit *hit);
/* 1 when anything lies in (tnear, tfar) along the ray. */
int lumo_rt_occluded(const lumo_rt *rt, vec3 o, vec3 d, float tnear, float tfar);

/* A length small against the scene, for offsetting ray origins. */
float lumo_rt_epsilon(const lumo_rt *rt);

#endif
