/*
 * ivg_order.c — the IVG streaming order (package/ivg_order.h). The draw is
 * specified byte for byte in docs/package-format.md "IVGS"; a second
 * implementation following that text gives the same order
 * (tests/server/test_server_order.c has one).
 */
#include <stdlib.h>
#include <string.h>
#include "common/rng.h"
#include "lumo/ivg.h"
#include "package/ivg_order.h"

void srv_ivg_order_free(srv_ivg_order *o)
{
    free(o->vertex);
    free(o->round_first);
    memset(o, 0, sizeof *o);
}

lumo_status srv_ivg_order_make(const uint16_t dims[3], uint64_t seed, srv_ivg_order *o)
{
    memset(o, 0, sizeof *o);
    for (int a = 0; a < 3; a++)
        if (dims[a] < LUMO_IVG_MIN_DIM || dims[a] > LUMO_IVG_MAX_DIM)
            return LUMO_ERR_ARG;
    uint32_t nx = dims[0], ny = dims[1], n = nx * ny * dims[2];
    uint32_t axis = lumo_ivg_order_axis(dims), slices = dims[axis], per_slice = n / slices;
    /* Each slice's unsent vertices (corners excluded), kept in increasing
     * index order: slice s uses list[s * per_slice ..], left[s] of them. */
    uint32_t *list = malloc(sizeof *list * n), *left = calloc(slices, sizeof *left);
    o->vertex = malloc(sizeof *o->vertex * n);
    o->round_first = malloc(sizeof *o->round_first * (LUMO_IVG_ORDER_MAX_ROUNDS + 1u));
    if (!list || !left || !o->vertex || !o->round_first) {
        free(list), free(left);
        srv_ivg_order_free(o);
        return LUMO_ERR_NOMEM;
    }
    o->axis = axis, o->slices = slices, o->count = n;
    uint32_t at = 0, most = 0;
    for (uint32_t v = 0; v < n; v++) {
        uint32_t c[3] = {v % nx, v / nx % ny, v / (nx * ny)};
        int corner = 1;
        for (int a = 0; a < 3; a++)
            corner &= c[a] == 0 || c[a] == dims[a] - 1u;
        if (corner)
            o->vertex[at++] = v;   /* round 0: the corners, increasing index */
        else
            list[c[axis] * per_slice + left[c[axis]]++] = v;
    }
    o->round_first[0] = 0;
    o->rounds = 1;
    for (uint32_t s = 0; s < slices; s++)
        most = left[s] > most ? left[s] : most;
    uint64_t state = seed;
    for (uint32_t r = 1; r <= most; r++) {
        o->round_first[o->rounds++] = at;
        for (uint32_t s = 0; s < slices; s++) {
            uint32_t *l = list + (size_t)s * per_slice;
            if (left[s] == 0)
                continue;
            uint32_t j = (uint32_t)(srv_splitmix64_next(&state) % left[s]);
            o->vertex[at++] = l[j];
            l[j] = l[--left[s]];
        }
    }
    o->round_first[o->rounds] = at;
    free(list);
    free(left);
    return LUMO_OK;
}
