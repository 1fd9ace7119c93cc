/*
 * vsl_ivg.h — the IVG re-evaluated from the VSLs where they changed: seed
 * 000's "fast update mechanism for dynamic 3D scenes, with a localized
 * computation in regions of important changes" (its §6), fed by seed 004's
 * VSLs (vsl_light.h for the per-VSL term).
 *
 * The grid holds, per vertex p, sum over VSLs s of I_s(p) taken from the
 * state of s last *published*, for the vertices inside that state's
 * cut-off sphere (§0.7.3). An update republishes only the VSLs whose state
 * changed importantly — moved with their object, or flux changed by more
 * than tau of max(its flux, the mean VSL flux) — and for each touches only
 * the vertices inside its old and new cut-off spheres: the old term out,
 * the new term in (doubles, so the books do not drift). Between updates a
 * VSL's held flux is within tau of its pool flux, so the grid is within
 * tau (relative, per VSL) of a full evaluation of the current VSLs.
 *
 * Cost: O(VSLs) to find the changed ones, plus O(vertices in the cut-off
 * box) per changed VSL; memory 54 doubles a vertex plus one srv_vsl_lit
 * a VSL.
 */
#ifndef SRV_VSL_IVG_H
#define SRV_VSL_IVG_H

#include <stddef.h>
#include <stdint.h>
#include "bake/bake.h"
#include "vsl/vsl_light.h"

#define SRV_VSL_IVG_VALUES 54   /* per vertex: 6 hemispheres x 3 channels x 3 */

typedef struct srv_vsl_ivg {
    srv_grid     grid;
    size_t       nverts, nvsl;
    double      *I;          /* nverts x 54, the srv_bake_result layout */
    srv_vsl_lit *pub;        /* per VSL: the state I holds */
    uint8_t     *dirty;      /* per vertex: changed since the last take */
    float        eps;        /* cut-off, W/m^2 (§0.7.3: 1e-6) */
    float        tau;        /* relative flux change that republishes */
    uint64_t     republished, touched;   /* totals: VSLs, vertex terms */
} srv_vsl_ivg;

/* An all-zero grid over g for nvsl VSLs holding zero flux. LUMO_OK,
 * LUMO_ERR_ARG (tau < 0 or eps < 0) or LUMO_ERR_NOMEM. */
lumo_status srv_vsl_ivg_init(srv_vsl_ivg *v, const srv_grid *g, size_t nvsl, float eps, float tau);
void srv_vsl_ivg_free(srv_vsl_ivg *v);

/* Republish the VSLs of now (nvsl of them) that changed importantly;
 * returns how many were. */
size_t srv_vsl_ivg_update(srv_vsl_ivg *v, const srv_vsl_lit *now);

/* The changed vertices (indices i + nx (j + ny k)), at most cap, cleared
 * as taken; returns the count written. */
size_t srv_vsl_ivg_take_dirty(srv_vsl_ivg *v, uint32_t *out, size_t cap);

/* Reference: every VSL of lit over every vertex of g (inside its cut-off)
 * into I (nverts x 54, zeroed first). */
void srv_vsl_ivg_full(const srv_grid *g, const srv_vsl_lit *lit, size_t n, float eps, double *I);

#endif
