/*
 * vsl_rt.h — photon ray queries for a scene whose objects move (seed 004
 * §0.7.1: "a bounding box and a kd-tree for each object, so that moving
 * one object does not require any kd-tree reconstruction"): each mesh is
 * its own Embree scene, built once, placed in a top-level scene as an
 * instance with the object's pose. Moving an object sets its instance's
 * transform and commits the top level only (a BVH over the instances'
 * boxes, O(objects)); the mesh BVHs are never rebuilt.
 *
 * Not thread-safe against srv_vsl_rt_set_pose: the caller (the engine's
 * one thread) changes poses between queries.
 */
#ifndef SRV_VSL_RT_H
#define SRV_VSL_RT_H

#include <stddef.h>
#include <stdint.h>
#include "scene/scene.h"
#include "vsl/vsl_pose.h"

typedef struct srv_vsl_rt srv_vsl_rt;

typedef struct srv_vsl_hit {
    float    t;
    vec3     n;         /* world unit geometric normal, as wound (front side) */
    vec3     local;     /* hit point in the object's frame */
    vec3     albedo;
    uint32_t object;    /* mesh index */
    int      emitter;
} srv_vsl_hit;

/* Every mesh of s at the identity pose. s must outlive the srv_vsl_rt.
 * NULL with a reason in err. */
srv_vsl_rt *srv_vsl_rt_create(const srv_scene *s, char *err, size_t errlen);
void srv_vsl_rt_free(srv_vsl_rt *rt);

/* Set object o's pose (takes effect at the next commit). */
void srv_vsl_rt_set_pose(srv_vsl_rt *rt, uint32_t o, const srv_pose *p);
const srv_pose *srv_vsl_rt_pose(const srv_vsl_rt *rt, uint32_t o);
/* Rebuild the top level over the instances (no mesh BVH is rebuilt). */
void srv_vsl_rt_commit(srv_vsl_rt *rt);

/* Closest hit in (tnear, tfar): 1 and *hit, or 0. */
int srv_vsl_rt_intersect(const srv_vsl_rt *rt, vec3 o, vec3 d, float tnear, float tfar, srv_vsl_hit *hit);
float srv_vsl_rt_epsilon(const srv_vsl_rt *rt);

#endif
