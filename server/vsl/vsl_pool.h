/*
 * vsl_pool.h — the photon pool of seed 004 §0.5 (Algorithm 2, Figure 6):
 * a fixed-size FIFO of photon impacts, each linked to the VSL it gave its
 * energy to. A new impact, once the pool is full, replaces the oldest:
 *   V_o.Phi -= P_o.Phi;  drop P_o;  V_n.Phi += P_n.Phi      — O(1).
 *
 * Flux is held in integers (units of 2^-SRV_PHOTON_FRAC_BITS of a photon's
 * emitted energy, per channel) so that the VSLs' sum equals the pool's
 * exactly after any number of moves: floating-point += and -= would drift
 * (§0.7.2 bounds the unsynchronised error by one photon; here the books
 * balance to the unit). srv_vsl_pool_flux turns a VSL's count into watts.
 */
#ifndef SRV_VSL_POOL_H
#define SRV_VSL_POOL_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/status.h"

#define SRV_PHOTON_FRAC_BITS 20

typedef struct srv_photon {
    uint32_t vsl;       /* the VSL holding its energy */
    uint32_t flux[3];   /* reflected flux, 2^-20 photon energies per channel */
    uint64_t emitted;   /* serial of the emission (path) it belongs to */
} srv_photon;

typedef struct srv_vsl_pool {
    srv_photon *ring;
    size_t      cap, len, head;    /* head: the oldest when full, else the next free */
    int64_t    *acc;               /* 3 per VSL: the flux of its photons */
    size_t      nvsl;
    uint64_t    impacts;           /* pushed since creation */
} srv_vsl_pool;

/* A pool of cap impacts (>= 1) over nvsl VSLs. LUMO_OK, LUMO_ERR_ARG
 * (cap 0) or LUMO_ERR_NOMEM. */
lumo_status srv_vsl_pool_init(srv_vsl_pool *p, size_t cap, size_t nvsl);
void srv_vsl_pool_free(srv_vsl_pool *p);

/* Algorithm 2: one new impact (vsl < nvsl). */
void srv_vsl_pool_push(srv_vsl_pool *p, uint32_t vsl, const uint32_t flux[3], uint64_t emitted);

/* The oldest photon (NULL when empty). */
const srv_photon *srv_vsl_pool_oldest(const srv_vsl_pool *p);

/* Emissions the pool's photons span: newest serial - oldest serial + 1
 * (0 when empty). The pool stands for the light of that many photons. */
uint64_t srv_vsl_pool_emissions(const srv_vsl_pool *p);

/* Reflected flux of VSL v in watts per channel, given the energy of one
 * emitted photon per unit weight (photon_w, W): acc 2^-20 photon_w / E. */
void srv_vsl_pool_flux(const srv_vsl_pool *p, uint32_t v, double photon_w, float out[3]);

#endif
