/* vsl_photon.c — equal-energy photons from the lights, traced through the
 * instanced scene into the pool (seed 004 §0.5, §0.7.1; vsl_photon.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "common/sample.h"
#include "vsl/vsl_photon.h"

#define MAX_BOUNCES 512          /* safety only: roulette ends paths long before */
#define RR_MAX_SURVIVAL 0.95f    /* the path tracer's (bake/pathtrace.c) */

/* Power a light sends into the scene, W per channel. */
static vec3 emitted_power(const srv_photon_tracer *t, const srv_light *l)
{
    switch (l->kind) {
    case LUMO_LIGHT_SPOT:   /* intensity P / 4pi inside the cone */
        return v3_scale(l->power, 0.5f * (1.0f - l->cos_half));
    case LUMO_LIGHT_DIRECTIONAL:   /* irradiance over the scene's disc */
        return v3_scale(l->power, (float)M_PI * t->radius * t->radius);
    default:
        return l->power;
    }
}

static double channel_sum(vec3 p)
{
    return (double)p.x + (double)p.y + (double)p.z;
}

/* Light choice by emitted power; each photon then carries total / 3 per
 * channel of white: weight = 3 P_c / sum(P). */
static double light_table(srv_photon_tracer *t)
{
    double total = 0.0;
    for (size_t i = 0; i < t->nlights; i++) {
        vec3 p = emitted_power(t, &t->lights[i]);
        double s = channel_sum(p);
        total += s;
        t->cdf[i] = total;
        t->weight[i] = s > 0.0 ? v3_scale(p, (float)(3.0 / s)) : v3(0, 0, 0);
    }
    return total;
}

lumo_status srv_photon_tracer_init(srv_photon_tracer *t, const srv_scene *s, const srv_vsl_rt *rt,
                                   const srv_vsl_index *ix, srv_vsl_pool *pool, uint64_t seed,
                                   char *err, size_t errlen)
{
    vec3 lo, hi;
    memset(t, 0, sizeof *t);
    t->rt = rt, t->ix = ix, t->pool = pool;
    t->nlights = s->nlights < LUMO_MAX_LIGHTS ? s->nlights : LUMO_MAX_LIGHTS;
    memcpy(t->lights, s->lights, t->nlights * sizeof *t->lights);
    if (srv_scene_bounds(s, &lo, &hi)) {
        t->centre = v3_scale(v3_add(lo, hi), 0.5f);
        t->radius = 0.5f * v3_len(v3_sub(hi, lo));
    }
    double total = light_table(t);
    if (!(total > 0.0)) {
        snprintf(err, errlen, "no light emits: photon streaming needs a light with power");
        return LUMO_ERR_ARG;
    }
    t->photon_w = total / 3.0;
    srv_rng_seed(&t->rng, seed, 0x50484F54u);
    return LUMO_OK;
}

lumo_status srv_photon_tracer_set_light(srv_photon_tracer *t, size_t i, const srv_light *l)
{
    if (i >= t->nlights)
        return LUMO_ERR_ARG;
    srv_light old = t->lights[i];
    t->lights[i] = *l;
    double total = light_table(t);
    if (fabs(total / 3.0 - t->photon_w) > 1e-6 * t->photon_w) {
        t->lights[i] = old;
        light_table(t);
        return LUMO_ERR_ARG;
    }
    return LUMO_OK;
}

static size_t pick_light(srv_photon_tracer *t)
{
    double u = (double)srv_rng_float(&t->rng) * t->cdf[t->nlights - 1];
    size_t i = 0;
    while (i + 1 < t->nlights && t->cdf[i] <= u)
        i++;
    return i;
}

/* A photon's origin and direction from light l. */
static void emit(srv_photon_tracer *t, const srv_light *l, vec3 *o, vec3 *d)
{
    srv_rng *r = &t->rng;
    switch (l->kind) {
    case LUMO_LIGHT_SPOT:
        *o = l->pos, *d = srv_cone_dir(l->dir, l->cos_half, r);
        return;
    case LUMO_LIGHT_AREA:
        *o = v3_add(l->pos, v3_add(v3_scale(l->u, srv_rng_float(r)), v3_scale(l->v, srv_rng_float(r))));
        *d = srv_cosine_dir(l->dir, r);
        return;
    case LUMO_LIGHT_DIRECTIONAL: {
        vec3 b1, b2;
        float rad = t->radius * sqrtf(srv_rng_float(r)), phi = 2.0f * (float)M_PI * srv_rng_float(r);
        srv_basis(l->dir, &b1, &b2);
        *o = v3_add(v3_sub(t->centre, v3_scale(l->dir, 2.0f * t->radius)),
                    v3_add(v3_scale(b1, rad * cosf(phi)), v3_scale(b2, rad * sinf(phi))));
        *d = l->dir;
        return;
    }
    default:
        *o = l->pos, *d = srv_cone_dir(v3(0, 1, 0), -1.0f, r);
        return;
    }
}

static void deposit(srv_photon_tracer *t, const srv_vsl_hit *h, vec3 flux)
{
    uint32_t v = srv_vsl_index_nearest(t->ix, h->object, h->local);
    if (v == UINT32_MAX)
        return;
    uint32_t q[3];
    for (int c = 0; c < 3; c++) {
        double x = (double)v3_get(flux, c) * (double)(1u << SRV_PHOTON_FRAC_BITS);
        q[c] = x >= 4294967295.0 ? UINT32_MAX : (uint32_t)lround(x);
    }
    srv_vsl_pool_push(t->pool, v, q, t->emitted);
}

/* One path: every front-face impact deposits rho * flux, then roulette. */
static uint64_t trace_path(srv_photon_tracer *t, vec3 o, vec3 d, vec3 flux)
{
    float eps = srv_vsl_rt_epsilon(t->rt);
    uint64_t impacts = 0;
    for (int bounce = 0; bounce < MAX_BOUNCES; bounce++) {
        srv_vsl_hit h;
        t->rays++;
        if (!srv_vsl_rt_intersect(t->rt, o, d, bounce ? 0.0f : eps, INFINITY, &h) || h.emitter)
            break;
        int front = v3_dot(h.n, d) < 0.0f;
        vec3 n = front ? h.n : v3_scale(h.n, -1.0f), refl = v3_mul(flux, h.albedo);
        if (front)
            deposit(t, &h, refl), impacts++;
        float q = fminf(RR_MAX_SURVIVAL, v3_maxc(h.albedo));
        if (!(q > 0.0f) || srv_rng_float(&t->rng) >= q)
            break;
        flux = v3_scale(refl, 1.0f / q);
        o = v3_add(v3_add(o, v3_scale(d, h.t)), v3_scale(n, eps));
        d = srv_cosine_dir(n, &t->rng);
    }
    return impacts;
}

uint64_t srv_photon_shoot(srv_photon_tracer *t, uint64_t n)
{
    uint64_t impacts = 0;
    for (uint64_t k = 0; k < n; k++) {
        size_t li = pick_light(t);
        vec3 o, d;
        emit(t, &t->lights[li], &o, &d);
        impacts += trace_path(t, o, d, t->weight[li]);
        t->emitted++;
    }
    return impacts;
}

void srv_photon_vsl_flux(const srv_photon_tracer *t, uint32_t v, float out[3])
{
    srv_vsl_pool_flux(t->pool, v, t->photon_w, out);
}
