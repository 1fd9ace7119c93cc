/* vsl_pool.c — the fixed FIFO of photon impacts and the O(1) flux moves of
 * Algorithm 2 (seed 004 §0.5). */
#include <stdlib.h>
#include <string.h>
#include "vsl/vsl_pool.h"

lumo_status srv_vsl_pool_init(srv_vsl_pool *p, size_t cap, size_t nvsl)
{
    memset(p, 0, sizeof *p);
    if (!cap)
        return LUMO_ERR_ARG;
    p->ring = malloc(cap * sizeof *p->ring);
    p->acc = calloc(3 * (nvsl ? nvsl : 1), sizeof *p->acc);
    if (!p->ring || !p->acc) {
        srv_vsl_pool_free(p);
        return LUMO_ERR_NOMEM;
    }
    p->cap = cap;
    p->nvsl = nvsl;
    return LUMO_OK;
}

void srv_vsl_pool_free(srv_vsl_pool *p)
{
    free(p->ring);
    free(p->acc);
    memset(p, 0, sizeof *p);
}

static void move_flux(srv_vsl_pool *p, uint32_t v, const uint32_t f[3], int sign)
{
    for (int c = 0; c < 3; c++)
        p->acc[3 * (size_t)v + (size_t)c] += sign * (int64_t)f[c];
}

void srv_vsl_pool_push(srv_vsl_pool *p, uint32_t vsl, const uint32_t flux[3], uint64_t emitted)
{
    srv_photon *slot = &p->ring[p->head];
    if (p->len == p->cap)   /* V_o.Phi -= P_o.Phi; P_o leaves the queue */
        move_flux(p, slot->vsl, slot->flux, -1);
    else
        p->len++;
    slot->vsl = vsl;
    memcpy(slot->flux, flux, sizeof slot->flux);
    slot->emitted = emitted;
    move_flux(p, vsl, flux, +1);   /* V_n.Phi += P_n.Phi */
    p->head = p->head + 1 == p->cap ? 0 : p->head + 1;
    p->impacts++;
}

const srv_photon *srv_vsl_pool_oldest(const srv_vsl_pool *p)
{
    if (!p->len)
        return NULL;
    return &p->ring[p->len == p->cap ? p->head : 0];
}

uint64_t srv_vsl_pool_emissions(const srv_vsl_pool *p)
{
    if (!p->len)
        return 0;
    size_t newest = p->head ? p->head - 1 : p->cap - 1;
    return p->ring[newest].emitted - srv_vsl_pool_oldest(p)->emitted + 1;
}

void srv_vsl_pool_flux(const srv_vsl_pool *p, uint32_t v, double photon_w, float out[3])
{
    uint64_t e = srv_vsl_pool_emissions(p);
    double k = e ? photon_w / ((double)e * (double)(1u << SRV_PHOTON_FRAC_BITS)) : 0.0;
    for (int c = 0; c < 3; c++)
        out[c] = (float)((double)p->acc[3 * (size_t)v + (size_t)c] * k);
}
