/*
 * net_plan.c — which batch records answer a geometry request
 * (docs/protocol.md §2 DATA "Geometry"). The server plans its answer with
 * these functions and the client predicts it with the same ones, so that a
 * client can pipeline requests with exact cursors.
 */
#include "lumo/net.h"

uint32_t lumo_net_vertices_before(const lumo_pmesh_header *h, uint32_t b)
{
    uint64_t v;

    if (b == 0)
        return 0;
    v = (uint64_t)h->base_vertices + (uint64_t)(b - 1) * h->batch_vertices;
    return v > h->vertices ? h->vertices : (uint32_t)v;
}

uint32_t lumo_net_geometry_end(const lumo_pmesh_header *h, uint32_t cursor, uint32_t amount)
{
    uint64_t target = (uint64_t)lumo_net_vertices_before(h, cursor) + amount;
    uint64_t e;

    /* The largest e with vertices_before(e) <= target: every batch when the
     * target reaches the full mesh, else base + (e - 1) * B <= target. */
    if (target >= h->vertices)
        e = h->batch_count;
    else if (target < h->base_vertices)
        e = 0;
    else
        e = 1 + (target - h->base_vertices) / h->batch_vertices;
    if (e < (uint64_t)cursor + 1)
        e = (uint64_t)cursor + 1;   /* at least one batch */
    if (e > h->batch_count)
        e = h->batch_count;
    return (uint32_t)e;
}
