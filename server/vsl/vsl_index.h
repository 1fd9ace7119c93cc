/*
 * vsl_index.h — the nearest-VSL lookup of Algorithm 2 (seed 004 §0.5,
 * "find the VSL V_n closest to P_n"): one balanced k-d tree per object in
 * the object's frame, so a moved object keeps its tree (the photon's hit
 * point is taken into the object's frame instead). The search is limited
 * to the hit object's VSLs: a photon on the sphere gives its energy to the
 * sphere, never to the floor beneath it, and a VSL moves with the energy
 * it holds (§0.4.2 note (i)).
 *
 * Cost: build O(n log^2 n) once; a query O(log n) expected (descent plus
 * the few subtrees the nearest-so-far sphere crosses), no allocation; an
 * object with fewer than 256 VSLs is scanned instead (faster there:
 * docs/benchmarks.md "Dynamic scenes").
 */
#ifndef SRV_VSL_INDEX_H
#define SRV_VSL_INDEX_H

#include <stdint.h>
#include "vsl/vsl.h"

typedef struct srv_vsl_index {
    const srv_vsl_set *set;
    uint32_t *node;   /* set->n VSL indices; object o's tree is node[first[o] ..] in implicit form */
    uint8_t  *axis;   /* split axis of each node */
} srv_vsl_index;

/* LUMO_OK or LUMO_ERR_NOMEM. set must outlive the index. */
lumo_status srv_vsl_index_build(srv_vsl_index *ix, const srv_vsl_set *set);
void srv_vsl_index_free(srv_vsl_index *ix);

/* The VSL of object o nearest to p (object frame), ties to the lower
 * index; UINT32_MAX when o has none. */
uint32_t srv_vsl_index_nearest(const srv_vsl_index *ix, uint32_t o, vec3 p);

#endif
