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
#include "common/parallel.h"

typedef struct srv_tracer {
    const srv_scene *s;
    const srv_rt     *rt;
    float             eps;
} srv_tracer;

/* Per-thread counter of rays cast (for rays/s), one cache line each so
 * that workers counting side by side do not share a line. */
typedef struct { uint64_t rays; uint8_t pad[56]; } srv_trace_stats;

/* The most worker threads a traced job runs (more asked for are clamped). */
#define SRV_TRACE_MAX_WORKERS 256

/* Runs fn over count items on `threads` workers (clamped to
 * SRV_TRACE_MAX_WORKERS) with a progress bar named label; stats holds one
 * counter per worker, zeroed here, and their sum is added to *rays. */
lumo_status srv_trace_parallel(size_t count, int threads, srv_item_fn fn, void *ctx, const char *label,
                               srv_trace_stats stats[SRV_TRACE_MAX_WORKERS], uint64_t *rays);

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
