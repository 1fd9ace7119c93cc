/*
 * vsl_pose.h — a rigid pose of a moving object or light: x_world = R x + t,
 * R a rotation about +y by yaw (the motions of docs/dynamic.md), so normals
 * turn by R alone and the inverse is R^T (x - t).
 */
#ifndef SRV_VSL_POSE_H
#define SRV_VSL_POSE_H

#include <math.h>
#include "common/vec3.h"

typedef struct srv_pose {
    vec3  t;        /* translation, m */
    float yaw_deg;  /* rotation about +y, degrees */
    float c, s;     /* cos, sin of yaw (kept with it by srv_pose_make) */
} srv_pose;

static inline srv_pose srv_pose_make(vec3 t, float yaw_deg)
{
    float a = yaw_deg * (float)M_PI / 180.0f;
    srv_pose p = {t, yaw_deg, cosf(a), sinf(a)};
    return p;
}

static inline srv_pose srv_pose_identity(void) { return srv_pose_make(v3(0, 0, 0), 0.0f); }

static inline vec3 srv_pose_dir(const srv_pose *p, vec3 d)
{
    return v3(p->c * d.x + p->s * d.z, d.y, -p->s * d.x + p->c * d.z);
}

static inline vec3 srv_pose_point(const srv_pose *p, vec3 x) { return v3_add(srv_pose_dir(p, x), p->t); }

static inline vec3 srv_pose_inv_dir(const srv_pose *p, vec3 d)
{
    return v3(p->c * d.x - p->s * d.z, d.y, p->s * d.x + p->c * d.z);
}

static inline vec3 srv_pose_inv_point(const srv_pose *p, vec3 x) { return srv_pose_inv_dir(p, v3_sub(x, p->t)); }

static inline int srv_pose_equal(const srv_pose *a, const srv_pose *b)
{
    return a->t.x == b->t.x && a->t.y == b->t.y && a->t.z == b->t.z && a->yaw_deg == b->yaw_deg;
}

#endif
