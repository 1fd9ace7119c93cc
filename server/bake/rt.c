/* rt.c — Embree 3 scene setup and ray queries. One Embree geometry per mesh
 * (geometry ID = mesh index); normals and albedo come from lumo's own mesh
 * so that the winding convention is ours, not Embree's. */
#include <embree3/rtcore.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "bake/rt.h"

struct srv_rt {
    RTCDevice   dev;
    RTCScene    scene;
    const srv_scene *s;
    vec3      **tri_n;      /* per mesh, per triangle unit normal */
    int        *emit_light; /* per mesh: area light index or -1 */
    float       eps;
};

static int attach_mesh(srv_rt *rt, unsigned id)
{
    const srv_mesh *m = &rt->s->meshes[id];
    RTCGeometry g = rtcNewGeometry(rt->dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *vb = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                        3 * sizeof(float), m->nverts);
    unsigned *ib = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                           3 * sizeof(unsigned), m->ntris);
    rt->tri_n[id] = malloc((m->ntris ? m->ntris : 1) * sizeof(vec3));
    if (!vb || !ib || !rt->tri_n[id]) {
        rtcReleaseGeometry(g);
        return -1;
    }
    for (uint32_t v = 0; v < m->nverts; v++)
        vb[3 * v] = m->pos[v].x, vb[3 * v + 1] = m->pos[v].y, vb[3 * v + 2] = m->pos[v].z;
    memcpy(ib, m->tris, 3u * m->ntris * sizeof(unsigned));
    for (uint32_t t = 0; t < m->ntris; t++) {
        vec3 a = m->pos[m->tris[3 * t]], b = m->pos[m->tris[3 * t + 1]], c = m->pos[m->tris[3 * t + 2]];
        rt->tri_n[id][t] = v3_norm(v3_cross(v3_sub(b, a), v3_sub(c, a)));
    }
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(rt->scene, g, id);
    rtcReleaseGeometry(g);
    return 0;
}

/* The area light whose rectangle a mesh is (emitters are added right after
 * their light, in order). */
static void map_emitters(srv_rt *rt)
{
    size_t next = 0;
    for (size_t i = 0; i < rt->s->nmeshes; i++) {
        rt->emit_light[i] = -1;
        if (!rt->s->meshes[i].emitter)
            continue;
        while (next < rt->s->nlights && rt->s->lights[next].kind != LUMO_LIGHT_AREA)
            next++;
        if (next < rt->s->nlights)
            rt->emit_light[i] = (int)next++;
    }
}

srv_rt *srv_rt_create(const srv_scene *s, int threads, char *err, size_t errlen)
{
    char cfg[64];
    srv_rt *rt = calloc(1, sizeof *rt);
    vec3 lo, hi;
    if (!rt || !srv_scene_bounds(s, &lo, &hi))
        goto fail;
    rt->s = s;
    rt->eps = 1e-5f * fmaxf(v3_len(v3_sub(hi, lo)), v3_maxc(v3_max(v3_max(lo, v3_scale(lo, -1)),
                                                                     v3_max(hi, v3_scale(hi, -1)))));
    snprintf(cfg, sizeof cfg, "threads=%d", threads > 0 ? threads : 0);
    rt->dev = rtcNewDevice(threads > 0 ? cfg : NULL);
    rt->tri_n = calloc(s->nmeshes, sizeof *rt->tri_n);
    rt->emit_light = calloc(s->nmeshes, sizeof *rt->emit_light);
    if (!rt->dev || !rt->tri_n || !rt->emit_light)
        goto fail;
    rt->scene = rtcNewScene(rt->dev);
    /* High quality and robust: results must not depend on build threads. */
    rtcSetSceneBuildQuality(rt->scene, RTC_BUILD_QUALITY_HIGH);
    rtcSetSceneFlags(rt->scene, RTC_SCENE_FLAG_ROBUST);
    for (unsigned i = 0; i < s->nmeshes; i++)
        if (attach_mesh(rt, i))
            goto fail;
    rtcCommitScene(rt->scene);
    if (rtcGetDeviceError(rt->dev) != RTC_ERROR_NONE)
        goto fail;
    map_emitters(rt);
    return rt;
fail:
    snprintf(err, errlen, "cannot build the ray-tracing scene (Embree error or out of memory)");
    srv_rt_free(rt);
    return NULL;
}

void srv_rt_free(srv_rt *rt)
{
    if (!rt)
        return;
    if (rt->scene)
        rtcReleaseScene(rt->scene);
    if (rt->dev)
        rtcReleaseDevice(rt->dev);
    for (size_t i = 0; rt->tri_n && i < rt->s->nmeshes; i++)
        free(rt->tri_n[i]);
    free(rt->tri_n);
    free(rt->emit_light);
    free(rt);
}

static void set_ray(struct RTCRay *r, vec3 o, vec3 d, float tnear, float tfar)
{
    r->org_x = o.x, r->org_y = o.y, r->org_z = o.z, r->tnear = tnear;
    r->dir_x = d.x, r->dir_y = d.y, r->dir_z = d.z, r->tfar = tfar;
    r->time = 0.0f, r->mask = 0xFFFFFFFFu, r->id = 0, r->flags = 0;
}

int srv_rt_intersect(const srv_rt *rt, vec3 o, vec3 d, float tnear, float tfar, srv_hit *hit)
{
    struct RTCIntersectContext ctx;
    struct RTCRayHit rh;
    rtcInitIntersectContext(&ctx);
    set_ray(&rh.ray, o, d, tnear, tfar);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(rt->scene, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
        return 0;
    const srv_mesh *m = &rt->s->meshes[rh.hit.geomID];
    const uint32_t *ix = &m->tris[3 * rh.hit.primID];
    float u = rh.hit.u, v = rh.hit.v;
    hit->t = rh.ray.tfar;
    hit->n = rt->tri_n[rh.hit.geomID][rh.hit.primID];
    hit->albedo = v3_add(v3_add(v3_scale(m->albedo[ix[0]], 1.0f - u - v), v3_scale(m->albedo[ix[1]], u)),
                         v3_scale(m->albedo[ix[2]], v));
    hit->emitter = m->emitter;
    hit->light = rt->emit_light[rh.hit.geomID];
    hit->mesh = rh.hit.geomID, hit->prim = rh.hit.primID, hit->bu = u, hit->bv = v;
    return 1;
}

int srv_rt_occluded(const srv_rt *rt, vec3 o, vec3 d, float tnear, float tfar)
{
    struct RTCIntersectContext ctx;
    struct RTCRay r;
    rtcInitIntersectContext(&ctx);
    set_ray(&r, o, d, tnear, tfar);
    rtcOccluded1(rt->scene, &ctx, &r);
    return r.tfar < 0.0f;
}

float srv_rt_epsilon(const srv_rt *rt)
{
    return rt->eps;
}
