/*
 * vsl_photon.h — photon streaming (seed 004 §0.5, §0.7.1): photons of equal
 * energy shot from the lights in proportion to their emitted power, traced
 * through the instanced scene (vsl_rt.h), each impact on a front face
 * giving the flux the surface reflects, rho * Phi, to the nearest VSL of
 * the object hit (vsl_index.h) through the pool (vsl_pool.h); a Russian
 * roulette at every impact ends the path (survival min(0.95, max rho), the
 * path tracer's, so both estimate the same light).
 *
 * A back-face impact (the outside of a Cornell wall, the inside of a solid)
 * reflects but gives no VSL energy: a VSL shines from its front side only
 * (§0.4.1, the VSL's stored normal).
 *
 * Lights: point (uniform sphere), spot (uniform within its cone, the path
 * tracer's constant-intensity cone), area (cosine about its normal),
 * directional (a disc of the scene's bounding radius upwind).
 */
#ifndef SRV_VSL_PHOTON_H
#define SRV_VSL_PHOTON_H

#include <stdint.h>
#include "common/rng.h"
#include "vsl/vsl_index.h"
#include "vsl/vsl_pool.h"
#include "vsl/vsl_rt.h"

typedef struct srv_photon_tracer {
    const srv_vsl_rt    *rt;
    const srv_vsl_index *ix;
    srv_vsl_pool        *pool;
    srv_light            lights[LUMO_MAX_LIGHTS];   /* world, current (moved) */
    size_t               nlights;
    double               cdf[LUMO_MAX_LIGHTS];      /* light choice by emitted power */
    vec3                 weight[LUMO_MAX_LIGHTS];   /* a photon's initial flux, photon_w units */
    double               photon_w;   /* W: one unit of photon flux (total emitted power / 3) */
    vec3                 centre;     /* scene bounding sphere at creation */
    float                radius;
    uint64_t             emitted;    /* paths shot */
    uint64_t             rays;
    srv_rng              rng;
} srv_photon_tracer;

/* Over s's lights (copied) and the given ray scene, index and pool.
 * LUMO_OK, or LUMO_ERR_ARG with a reason (no light emits). */
lumo_status srv_photon_tracer_init(srv_photon_tracer *t, const srv_scene *s, const srv_vsl_rt *rt,
                                   const srv_vsl_index *ix, srv_vsl_pool *pool, uint64_t seed,
                                   char *err, size_t errlen);

/* Replace light i (moved). Its emitted power must stay the same: a photon's
 * energy is fixed for the pool's lifetime (LUMO_ERR_ARG otherwise). */
lumo_status srv_photon_tracer_set_light(srv_photon_tracer *t, size_t i, const srv_light *l);

/* Shoot n photon paths; returns the impacts pushed into the pool. */
uint64_t srv_photon_shoot(srv_photon_tracer *t, uint64_t n);

/* Reflected flux of VSL v in watts per channel (srv_vsl_pool_flux). */
void srv_photon_vsl_flux(const srv_photon_tracer *t, uint32_t v, float out[3]);

#endif
