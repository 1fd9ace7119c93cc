/* pathtrace.c — diffuse path tracing with next-event estimation and Russian
 * roulette. Light sources are reached only by next-event estimation: a path
 * that hits an emitter ends there, so no light is counted twice. */
#include <math.h>
#include <string.h>
#include "bake/trace.h"
#include "common/sample.h"

#define MAX_BOUNCES 512     /* safety only: roulette ends paths long before */
#define RR_MAX_SURVIVAL 0.95f

void srv_tracer_init(srv_tracer *t, const srv_scene *s, const srv_rt *rt)
{
    t->s = s;
    t->rt = rt;
    t->eps = srv_rt_epsilon(rt);
}

lumo_status srv_trace_parallel(size_t count, int threads, srv_item_fn fn, void *ctx, const char *label,
                               srv_trace_stats stats[SRV_TRACE_MAX_WORKERS], uint64_t *rays)
{
    memset(stats, 0, SRV_TRACE_MAX_WORKERS * sizeof *stats);
    if (threads > SRV_TRACE_MAX_WORKERS)
        threads = SRV_TRACE_MAX_WORKERS;
    lumo_status st = srv_parallel_for(count, threads, fn, ctx, label, 0);
    for (int w = 0; w < SRV_TRACE_MAX_WORKERS; w++)
        *rays += stats[w].rays;
    return st;
}

static int visible(const srv_tracer *t, vec3 x, vec3 n, vec3 w, float dist, srv_trace_stats *st)
{
    st->rays++;
    vec3 o = v3_add(x, v3_scale(n, t->eps));
    return !srv_rt_occluded(t->rt, o, w, 0.0f, dist * (1.0f - 1e-4f) - t->eps);
}

/* Irradiance from one light: seed 000 §3 conventions, docs/scene-format.md. */
static vec3 light_irradiance(const srv_tracer *t, const srv_light *l, vec3 x, vec3 n, srv_rng *r,
                             srv_trace_stats *st)
{
    vec3 zero = v3(0, 0, 0);
    if (l->kind == LUMO_LIGHT_DIRECTIONAL) {
        vec3 w = v3_scale(l->dir, -1.0f);
        float c = v3_dot(n, w);
        if (c <= 0.0f || !visible(t, x, n, w, INFINITY, st))
            return zero;
        return v3_scale(l->power, c);
    }
    vec3 lp = l->pos;
    if (l->kind == LUMO_LIGHT_AREA)
        lp = v3_add(lp, v3_add(v3_scale(l->u, srv_rng_float(r)), v3_scale(l->v, srv_rng_float(r))));
    vec3 to = v3_sub(lp, x);
    float d2 = v3_dot(to, to), d = sqrtf(d2);
    if (!(d > 0.0f))
        return zero;
    vec3 w = v3_scale(to, 1.0f / d);
    float c = v3_dot(n, w);
    if (c <= 0.0f)
        return zero;
    float g;   /* intensity-like factor towards x, per unit power */
    if (l->kind == LUMO_LIGHT_AREA) {
        float cl = -v3_dot(l->dir, w);
        if (cl <= 0.0f)
            return zero;
        g = cl / (float)M_PI;          /* Le * A * cos_l with Le = P/(pi A) */
    } else {
        if (l->kind == LUMO_LIGHT_SPOT && -v3_dot(w, l->dir) < l->cos_half)
            return zero;
        g = 1.0f / (4.0f * (float)M_PI);
    }
    if (!visible(t, x, n, w, d, st))
        return zero;
    return v3_scale(l->power, g * c / d2);
}

vec3 srv_direct_irradiance(const srv_tracer *t, vec3 x, vec3 n, srv_rng *r, srv_trace_stats *st)
{
    vec3 e = v3(0, 0, 0);
    for (size_t i = 0; i < t->s->nlights; i++)
        e = v3_add(e, light_irradiance(t, &t->s->lights[i], x, n, r, st));
    return e;
}

/* Outgoing radiance (no emission) of the diffuse surface at x, normal n
 * already turned towards the viewer. With cosine sampling the throughput
 * of a bounce is the albedo; roulette survives with probability max(rho). */
static vec3 outgoing(const srv_tracer *t, vec3 x, vec3 n, vec3 rho, int direct, srv_rng *r,
                     srv_trace_stats *st)
{
    vec3 sum = v3(0, 0, 0), thr = v3(1, 1, 1);
    for (int bounce = 0; bounce < MAX_BOUNCES; bounce++) {
        thr = v3_mul(thr, rho);
        if (direct)
            sum = v3_add(sum, v3_mul(thr, v3_scale(srv_direct_irradiance(t, x, n, r, st),
                                                   1.0f / (float)M_PI)));
        direct = 1;
        float q = fminf(RR_MAX_SURVIVAL, v3_maxc(thr));
        if (!(q > 0.0f) || srv_rng_float(r) >= q)
            break;
        thr = v3_scale(thr, 1.0f / q);
        vec3 w = srv_cosine_dir(n, r);
        srv_hit h;
        st->rays++;
        if (!srv_rt_intersect(t->rt, v3_add(x, v3_scale(n, t->eps)), w, 0.0f, INFINITY, &h) || h.emitter)
            break;
        x = v3_add(x, v3_scale(w, h.t));
        n = v3_dot(h.n, w) > 0.0f ? v3_scale(h.n, -1.0f) : h.n;
        rho = h.albedo;
    }
    return sum;
}

vec3 srv_trace_indirect(const srv_tracer *t, vec3 p, vec3 d, srv_rng *r, srv_trace_stats *st,
                        int *back)
{
    srv_hit h;
    st->rays++;
    if (back)
        *back = 0;
    if (!srv_rt_intersect(t->rt, p, d, 0.0f, INFINITY, &h))
        return v3(0, 0, 0);
    int is_back = v3_dot(h.n, d) > 0.0f;
    if (back)
        *back = is_back;
    if (h.emitter)
        return v3(0, 0, 0);
    vec3 x = v3_add(p, v3_scale(d, h.t));
    return outgoing(t, x, is_back ? v3_scale(h.n, -1.0f) : h.n, h.albedo, 1, r, st);
}

static vec3 emitted(const srv_tracer *t, const srv_hit *h, vec3 d)
{
    if (h->light < 0 || v3_dot(h->n, d) >= 0.0f)
        return v3(0, 0, 0);
    const srv_light *l = &t->s->lights[h->light];
    float area = v3_len(v3_cross(l->u, l->v));
    return v3_scale(l->power, 1.0f / ((float)M_PI * area));
}

vec3 srv_trace_camera(const srv_tracer *t, vec3 eye, vec3 d, int indirect_only, srv_rng *r,
                      srv_trace_stats *st)
{
    srv_hit h;
    st->rays++;
    if (!srv_rt_intersect(t->rt, eye, d, 0.0f, INFINITY, &h))
        return v3(0, 0, 0);
    if (h.emitter)
        return indirect_only ? v3(0, 0, 0) : emitted(t, &h, d);
    vec3 x = v3_add(eye, v3_scale(d, h.t));
    vec3 n = v3_dot(h.n, d) > 0.0f ? v3_scale(h.n, -1.0f) : h.n;
    return outgoing(t, x, n, h.albedo, !indirect_only, r, st);
}
