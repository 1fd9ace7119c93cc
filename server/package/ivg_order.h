/*
 * package/ivg_order.h — the stratified streaming order of the IVG (seed 000
 * §4.1; docs/protocol.md §4, exact draw in docs/package-format.md "IVGS"):
 * the eight corners, then rounds of one random unsent vertex per slice
 * along the grid's longest axis. The package writer stores both bundles'
 * records in this order and the IVGS chunk that says where rounds start.
 */
#ifndef SRV_IVG_ORDER_H
#define SRV_IVG_ORDER_H

#include <stdint.h>
#include "lumo/status.h"

typedef struct srv_ivg_order {
    uint32_t  axis;          /* lumo_ivg_order_axis of the dims */
    uint32_t  slices;        /* dims[axis] */
    uint32_t  rounds;        /* R: round 0 is the corners */
    uint32_t  count;         /* grid vertices */
    uint32_t *vertex;        /* count vertex indices, in stream order */
    uint32_t *round_first;   /* rounds + 1 entries: first position of each
                                round; the last = count */
} srv_ivg_order;

/* The order of a grid of dims (each in [2, 256]) drawn from `seed`.
 * LUMO_ERR_ARG for bad dims, LUMO_ERR_NOMEM. */
lumo_status srv_ivg_order_make(const uint16_t dims[3], uint64_t seed, srv_ivg_order *o);
void srv_ivg_order_free(srv_ivg_order *o);

#endif
