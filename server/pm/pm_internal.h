/*
 * pm/pm_internal.h — the stages of srv_pm_build() (server/pm/pm_*.c),
 * exposed for the stream builder and the tests.
 */
#ifndef SRV_PM_INTERNAL_H
#define SRV_PM_INTERNAL_H

#include <stdint.h>
#include "pm/pm.h"

/* A cleaned indexed face set: duplicate positions welded, degenerate and
 * duplicate (same vertex set) faces dropped, unreferenced vertices removed.
 * source[v] is the first input vertex of v's weld class. */
typedef struct srv_pm_clean_mesh {
    uint32_t  nv, nf;
    float    *xyz;
    uint8_t  *rgb;            /* 3 per vertex, or NULL: albedo, part of the weld key */
    uint32_t *tris;
    uint32_t *source;
    uint32_t  welded, dropped_faces;
} srv_pm_clean_mesh;

/* LUMO_OK, LUMO_ERR_RANGE (an index >= nv) or LUMO_ERR_NOMEM. */
lumo_status srv_pm_clean(const float *xyz, const uint8_t *rgb, uint32_t nv, const uint32_t *tris,
                         uint32_t nf, srv_pm_clean_mesh *out);
void        srv_pm_clean_free(srv_pm_clean_mesh *m);

/* The collapse sequence of srv_pm_simplify(): at step t vertex removed[t]
 * collapses onto target[t] in round round[t] (non-decreasing; the
 * collapses of one round commute); face_die[f] is the step that removed
 * face f, or UINT32_MAX for faces of the seed mesh (no collapse removed
 * them). Steps 0 .. bounded - 1 are within max_error (they end at the base
 * mesh), steps bounded .. count - 1 go on past it (options seed) to the
 * seed mesh; a round holds only steps of one kind. */
typedef struct srv_pm_collapses {
    uint32_t  count, bounded;
    uint32_t *removed, *target, *round;
    uint32_t *face_die;
} srv_pm_collapses;

/* LUMO_OK or LUMO_ERR_NOMEM. */
lumo_status srv_pm_simplify(const srv_pm_clean_mesh *m, const srv_pm_options *opt,
                            srv_pm_collapses *out);
void        srv_pm_collapses_free(srv_pm_collapses *c);

#endif
