/* vsl_rt.c — one Embree scene per object, instanced into a top level
 * (seed 004 §0.7.1); see vsl_rt.h. */
#include <embree3/rtcore.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "vsl/vsl_rt.h"

struct srv_vsl_rt {
    RTCDevice   dev;
    RTCScene    top;
    RTCScene   *obj;        /* per mesh: its own scene (BVH built once) */
    RTCGeometry *inst;      /* per mesh: its instance in top */
    srv_pose   *pose;
    vec3      **tri_n;      /* per mesh, per triangle, object-frame unit normal */
    const srv_scene *s;
    float       eps;
};

static RTCScene mesh_scene(srv_vsl_rt *rt, const srv_mesh *m, vec3 **tri_n)
{
    RTCScene sc = rtcNewScene(rt->dev);
    RTCGeometry g = rtcNewGeometry(rt->dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *vb = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                        3 * sizeof(float), m->nverts);
    unsigned *ib = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                           3 * sizeof(unsigned), m->ntris);
    *tri_n = malloc((m->ntris ? m->ntris : 1) * sizeof(vec3));
    if (!sc || !vb || !ib || !*tri_n) {
        rtcReleaseGeometry(g);
        return sc;
    }
    for (uint32_t v = 0; v < m->nverts; v++)
        vb[3 * v] = m->pos[v].x, vb[3 * v + 1] = m->pos[v].y, vb[3 * v + 2] = m->pos[v].z;
    for (uint32_t t = 0; t < m->ntris; t++) {
        const uint32_t *ix = &m->tris[3 * t];
        ib[3 * t] = ix[0], ib[3 * t + 1] = ix[1], ib[3 * t + 2] = ix[2];
        vec3 a = m->pos[ix[0]], b = m->pos[ix[1]], c = m->pos[ix[2]];
        (*tri_n)[t] = v3_norm(v3_cross(v3_sub(b, a), v3_sub(c, a)));
    }
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(sc, g, 0);
    rtcReleaseGeometry(g);
    rtcSetSceneBuildQuality(sc, RTC_BUILD_QUALITY_HIGH);
    rtcSetSceneFlags(sc, RTC_SCENE_FLAG_ROBUST);
    rtcCommitScene(sc);
    return sc;
}

/* Embree's 3x4 column-major affine of a pose (srv_pose_point's matrix). */
static void pose_matrix(const srv_pose *p, float m[12])
{
    m[0] = p->c, m[1] = 0, m[2] = -p->s;
    m[3] = 0, m[4] = 1, m[5] = 0;
    m[6] = p->s, m[7] = 0, m[8] = p->c;
    m[9] = p->t.x, m[10] = p->t.y, m[11] = p->t.z;
}

void srv_vsl_rt_set_pose(srv_vsl_rt *rt, uint32_t o, const srv_pose *p)
{
    float m[12];
    rt->pose[o] = *p;
    pose_matrix(p, m);
    rtcSetGeometryTransform(rt->inst[o], 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, m);
    rtcCommitGeometry(rt->inst[o]);
}

const srv_pose *srv_vsl_rt_pose(const srv_vsl_rt *rt, uint32_t o)
{
    return &rt->pose[o];
}

void srv_vsl_rt_commit(srv_vsl_rt *rt)
{
    rtcCommitScene(rt->top);
}

static int add_object(srv_vsl_rt *rt, uint32_t i)
{
    srv_pose id = srv_pose_identity();
    rt->obj[i] = mesh_scene(rt, &rt->s->meshes[i], &rt->tri_n[i]);
    if (!rt->obj[i] || !rt->tri_n[i])
        return -1;
    rt->inst[i] = rtcNewGeometry(rt->dev, RTC_GEOMETRY_TYPE_INSTANCE);
    if (!rt->inst[i])
        return -1;
    rtcSetGeometryInstancedScene(rt->inst[i], rt->obj[i]);
    rtcAttachGeometryByID(rt->top, rt->inst[i], i);
    srv_vsl_rt_set_pose(rt, i, &id);
    return 0;
}

srv_vsl_rt *srv_vsl_rt_create(const srv_scene *s, char *err, size_t errlen)
{
    srv_vsl_rt *rt = calloc(1, sizeof *rt);
    vec3 lo, hi;
    if (!rt || !srv_scene_bounds(s, &lo, &hi))
        goto fail;
    rt->s = s;
    rt->eps = 1e-5f * fmaxf(v3_len(v3_sub(hi, lo)), fmaxf(v3_len(lo), v3_len(hi)));
    rt->dev = rtcNewDevice(NULL);
    rt->obj = calloc(s->nmeshes, sizeof *rt->obj);
    rt->inst = calloc(s->nmeshes, sizeof *rt->inst);
    rt->pose = calloc(s->nmeshes, sizeof *rt->pose);
    rt->tri_n = calloc(s->nmeshes, sizeof *rt->tri_n);
    if (!rt->dev || !rt->obj || !rt->inst || !rt->pose || !rt->tri_n)
        goto fail;
    rt->top = rtcNewScene(rt->dev);
    /* Objects move: a fast top-level build, refit-friendly. */
    rtcSetSceneFlags(rt->top, RTC_SCENE_FLAG_DYNAMIC | RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(rt->top, RTC_BUILD_QUALITY_LOW);
    for (uint32_t i = 0; i < s->nmeshes; i++)
        if (add_object(rt, i))
            goto fail;
    rtcCommitScene(rt->top);
    if (rtcGetDeviceError(rt->dev) == RTC_ERROR_NONE)
        return rt;
fail:
    snprintf(err, errlen, "cannot build the instanced ray-tracing scene (Embree error or out of memory)");
    srv_vsl_rt_free(rt);
    return NULL;
}

void srv_vsl_rt_free(srv_vsl_rt *rt)
{
    if (!rt)
        return;
    for (size_t i = 0; rt->s && i < rt->s->nmeshes; i++) {
        if (rt->inst && rt->inst[i])
            rtcReleaseGeometry(rt->inst[i]);
        if (rt->obj && rt->obj[i])
            rtcReleaseScene(rt->obj[i]);
        if (rt->tri_n)
            free(rt->tri_n[i]);
    }
    if (rt->top)
        rtcReleaseScene(rt->top);
    if (rt->dev)
        rtcReleaseDevice(rt->dev);
    free(rt->obj), free(rt->inst), free(rt->pose), free(rt->tri_n);
    free(rt);
}

int srv_vsl_rt_intersect(const srv_vsl_rt *rt, vec3 o, vec3 d, float tnear, float tfar, srv_vsl_hit *hit)
{
    struct RTCIntersectContext ctx;
    struct RTCRayHit rh;
    rtcInitIntersectContext(&ctx);
    rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z, rh.ray.tnear = tnear;
    rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z, rh.ray.tfar = tfar;
    rh.ray.time = 0.0f, rh.ray.mask = 0xFFFFFFFFu, rh.ray.id = 0, rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(rt->top, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID || rh.hit.instID[0] == RTC_INVALID_GEOMETRY_ID)
        return 0;
    uint32_t ob = rh.hit.instID[0];
    const srv_mesh *m = &rt->s->meshes[ob];
    const uint32_t *ix = &m->tris[3 * rh.hit.primID];
    float u = rh.hit.u, v = rh.hit.v;
    hit->t = rh.ray.tfar;
    hit->object = ob;
    hit->n = srv_pose_dir(&rt->pose[ob], rt->tri_n[ob][rh.hit.primID]);
    hit->local = srv_pose_inv_point(&rt->pose[ob], v3_add(o, v3_scale(d, hit->t)));
    hit->albedo = v3_add(v3_add(v3_scale(m->albedo[ix[0]], 1.0f - u - v), v3_scale(m->albedo[ix[1]], u)),
                         v3_scale(m->albedo[ix[2]], v));
    hit->emitter = m->emitter;
    return 1;
}

float srv_vsl_rt_epsilon(const srv_vsl_rt *rt)
{
    return rt->eps;
}
