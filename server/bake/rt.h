/*
 * rt.h — ray queries against a scene through Embree 3. The scene must stay
 * alive and unchanged while the srv_rt exists. Queries are thread-safe.
 */
#ifndef SRV_RT_H
#define SRV_RT_H

#include <stddef.h>
#include "scene/scene.h"

typedef struct srv_rt srv_rt;

typedef struct srv_hit {
    float t;
    vec3  n;          /* unit geometric normal, as wound (front side) */
    vec3  albedo;     /* interpolated vertex albedo */
    int   emitter;    /* hit the surface of an area light */
    int   light;      /* index of that light in scene->lights, or -1 */
    unsigned mesh, prim;  /* the mesh (scene->meshes index) and its triangle */
    float bu, bv;         /* barycentrics of corners 1 and 2 (PRT interreflection) */
} srv_hit;

/* threads: Embree's own build threads (0 = its default). NULL with err. */
srv_rt *srv_rt_create(const srv_scene *s, int threads, char *err, size_t errlen);
void srv_rt_free(srv_rt *rt);

/* Closest hit in (tnear, tfar): 1 and *hit, or 0. */
int srv_rt_intersect(const srv_rt *rt, vec3 o, vec3 d, float tnear, float tfar, srv_hit *hit);
/* 1 when anything lies in (tnear, tfar) along the ray. */
int srv_rt_occluded(const srv_rt *rt, vec3 o, vec3 d, float tnear, float tfar);

/* A length small against the scene, for offsetting ray origins. */
float srv_rt_epsilon(const srv_rt *rt);

#endif
