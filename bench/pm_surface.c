/* bench/pm_surface.c — mesh-to-mesh distances for the simplification
 * benchmark (pm_surface.h): Embree 3 point queries, the closest point on a
 * triangle from server/common/closest.c. */
#include <embree3/rtcore.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "common/closest.h"
#include "pm_surface.h"

struct pm_surface {
    RTCDevice      dev;
    RTCScene       scene;
    const float   *xyz;
    const uint32_t *tris;
    float         *padded;   /* Embree's copy of xyz, with the slack it reads past the end */
};

typedef struct { double x, y, z; } d3;

static d3 at(const float *xyz, uint32_t i)
{
    d3 r = {xyz[3 * (size_t)i], xyz[3 * (size_t)i + 1], xyz[3 * (size_t)i + 2]};
    return r;
}
static d3 sub(d3 a, d3 b) { d3 r = {a.x - b.x, a.y - b.y, a.z - b.z}; return r; }
static d3 madd(d3 a, d3 b, double t) { d3 r = {a.x + t * b.x, a.y + t * b.y, a.z + t * b.z}; return r; }
static double dot(d3 a, d3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

typedef struct { const pm_surface *s; d3 p; double best; } query_state;

static bool on_primitive(struct RTCPointQueryFunctionArguments *args)
{
    query_state *q = args->userPtr;
    const uint32_t *t = q->s->tris + 3 * (size_t)args->primID;
    double p[3] = {q->p.x, q->p.y, q->p.z}, c[3][3];
    for (int k = 0; k < 3; k++)
        for (int a = 0; a < 3; a++)
            c[k][a] = q->s->xyz[3 * (size_t)t[k] + a];
    double dist = sqrt(srv_triangle_dist2(p, c[0], c[1], c[2]));
    if (dist >= q->best)
        return false;
    q->best = dist;
    args->query->radius = (float)dist * 1.0001f + 1e-30f;  /* shrink the search */
    return true;
}

pm_surface *pm_surface_open(const float *xyz, const uint32_t *tris, uint32_t nf)
{
    pm_surface *s = calloc(1, sizeof *s);
    if (!s || !(s->dev = rtcNewDevice("threads=1")))
        return free(s), NULL;
    s->xyz = xyz, s->tris = tris;
    s->scene = rtcNewScene(s->dev);
    RTCGeometry g = rtcNewGeometry(s->dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    uint32_t nv = 0;
    for (size_t i = 0; i < 3 * (size_t)nf; i++)
        nv = tris[i] + 1 > nv ? tris[i] + 1 : nv;
    /* A shared vertex buffer needs 16 bytes of slack after its last element. */
    if (!(s->padded = calloc(3 * (size_t)nv + 4, sizeof *s->padded))) {
        rtcReleaseGeometry(g);
        pm_surface_close(s);
        return NULL;
    }
    memcpy(s->padded, xyz, sizeof *xyz * 3 * (size_t)nv);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, s->padded, 0, 12, nv);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, tris, 0, 12, nf);
    rtcCommitGeometry(g);
    rtcAttachGeometry(s->scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(s->scene);
    if (rtcGetDeviceError(s->dev) != RTC_ERROR_NONE) {
        pm_surface_close(s);
        return NULL;
    }
    return s;
}

void pm_surface_close(pm_surface *s)
{
    if (!s)
        return;
    if (s->scene)
        rtcReleaseScene(s->scene);
    rtcReleaseDevice(s->dev);
    free(s->padded);
    free(s);
}

double pm_surface_distance(const pm_surface *s, const double p[3])
{
    query_state q = {s, {p[0], p[1], p[2]}, INFINITY};
    struct RTCPointQuery pq = {.x = (float)p[0], .y = (float)p[1], .z = (float)p[2],
                               .time = 0, .radius = INFINITY};
    struct RTCPointQueryContext ctx;
    rtcInitPointQueryContext(&ctx);
    rtcPointQuery(s->scene, &pq, &ctx, on_primitive, &q);
    return q.best;
}

static uint64_t xorshift(uint64_t *s)
{
    *s ^= *s << 13, *s ^= *s >> 7, *s ^= *s << 17;
    return *s;
}

static double uniform(uint64_t *s) { return (double)(xorshift(s) >> 11) * (1.0 / 9007199254740992.0); }

static double tri_area(const float *xyz, const uint32_t *t)
{
    d3 a = at(xyz, t[0]), e1 = sub(at(xyz, t[1]), a), e2 = sub(at(xyz, t[2]), a);
    d3 c = {e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x};
    return 0.5 * sqrt(dot(c, c));
}

/* A point uniform on triangle t. */
static void sample_triangle(const float *xyz, const uint32_t *t, uint64_t *rng, double p[3])
{
    double r1 = uniform(rng), r2 = uniform(rng);
    if (r1 + r2 > 1)
        r1 = 1 - r1, r2 = 1 - r2;
    d3 a = at(xyz, t[0]), q = madd(madd(a, sub(at(xyz, t[1]), a), r1), sub(at(xyz, t[2]), a), r2);
    p[0] = q.x, p[1] = q.y, p[2] = q.z;
}

void pm_surface_one_sided(const float *xyz, const uint32_t *tris, uint32_t nf, const pm_surface *b,
                          uint32_t samples, uint64_t seed, double *mean_sq, double *max)
{
    double *cdf = malloc(sizeof *cdf * (nf ? nf : 1)), total = 0, sq = 0, mx = 0;
    uint64_t rng = seed | 1;
    *mean_sq = 0, *max = 0;
    if (!cdf || !nf)
        return free(cdf);
    for (uint32_t f = 0; f < nf; f++)
        cdf[f] = total += tri_area(xyz, tris + 3 * (size_t)f);
    for (uint32_t i = 0; i < samples && total > 0; i++) {
        double r = uniform(&rng) * total, p[3];
        uint32_t lo = 0, hi = nf - 1;
        while (lo < hi) {
            uint32_t mid = lo + (hi - lo) / 2;
            if (cdf[mid] <= r)
                lo = mid + 1;
            else
                hi = mid;
        }
        sample_triangle(xyz, tris + 3 * (size_t)lo, &rng, p);
        double d = pm_surface_distance(b, p);
        sq += d * d, mx = d > mx ? d : mx;
    }
    for (size_t i = 0; i < 3 * (size_t)nf; i++) {
        const float *v = xyz + 3 * (size_t)tris[i];
        double p[3] = {v[0], v[1], v[2]}, d = pm_surface_distance(b, p);
        mx = d > mx ? d : mx;
    }
    free(cdf);
    *mean_sq = samples ? sq / samples : 0, *max = mx;
}
