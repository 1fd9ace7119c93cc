/*
 * trace.h — the path tracer shared by the IVG bake and the reference
 * renderer: diffuse surfaces, next-event estimation towards every light,
 * Russian roulette (seed 000 §3.1: the IVG holds indirect light only).
 */
#ifndef SRV_TRACE_H
#define SRV_TRACE_H

#include <stdint.h>
#include "common/rng.h"
#include "bake/rt.h"

typedef struct srv_tracer {
    const srv_scene *s;
    const srv_rt     *rt;
    float             eps;
} srv_tracer;

/* Per-thread counter of rays cast (for rays/s), one cache line each so
 * that workers counting side by side do not share a line. */
typedef struct { uint64_t rays; uint8_t pad[56]; } srv_trace_stats;

void srv_tracer_init(srv_tracer *t, const srv_scene *s, const srv_rt *rt);

/* Indirect radiance arriving at p from direction d (unit): radiance that
 * bounced at least once (light sources seen directly count zero). Also
 * reports whether the first hit was a back face (*back, may be NULL). */
vec3 srv_trace_indirect(const srv_tracer *t, vec3 p, vec3 d, srv_rng *r, srv_trace_stats *st,
                        int *back);

/* Radiance seen along a camera ray: emitters + direct + indirect, or only
 * the indirect part reflected by the first surface (indirect_only), which
 * is what the client's IVG term reproduces. */
vec3 srv_trace_camera(const srv_tracer *t, vec3 eye, vec3 d, int indirect_only, srv_rng *r,
                      srv_trace_stats *st);

/* Direct irradiance (W/m^2 per channel) at x with unit normal n from every
 * light, with shadow rays (one sample per area light). */
vec3 srv_direct_irradiance(const srv_tracer *t, vec3 x, vec3 n, srv_rng *r, srv_trace_stats *st);

#endif
