/*
 * bake/budget.h — what a bake will cost, said before it starts, and the
 * budget past which lumo-bake asks for --allow-large.
 *
 * A grid of (nx, ny, nz) vertices at spp paths each holds, while it bakes
 * and is packed, the estimate (3x3 matrices of 6 hemispheres and their
 * standard errors, 289 bytes), both sample bundles (46 + 148 bytes) and
 * the streaming order: SRV_BAKE_BYTES_PER_VERTEX bytes per vertex at the
 * least. Its time grows with the paths traced, vertices x spp (seed 000
 * §3.1: each path is one Monte Carlo sample of the indirect light).
 *
 * The budget: SRV_BAKE_MAX_VERTICES vertices (64^3: about 128 MB, and
 * already more IVG than a thin client holds — lumo/config.h) and
 * SRV_BAKE_MAX_PATHS paths (32^3 at 512 spp, 16.8 M: the paper's 32^3
 * grid at twice the default spp; about 45 s on two cores of the build
 * machine, which traces 0.35-0.45 M paths/s through the default scene).
 * The bake's progress bar then gives its estimate. --cell never clamps: a
 * spacing that asks for more than 256 vertices on an axis (the format's
 * limit, docs/package-format.md "IVGD") is refused with the grid it asked
 * for.
 */
#ifndef SRV_BAKE_BUDGET_H
#define SRV_BAKE_BUDGET_H

#include <stddef.h>
#include <stdint.h>
#include "common/vec3.h"
#include "lumo/status.h"

#define SRV_BAKE_BYTES_PER_VERTEX 483u
#define SRV_BAKE_MAX_VERTICES     ((uint64_t)64 * 64 * 64)
/* A bake of this many paths or more (16^3 at 256 spp, seconds) is announced. */
#define SRV_BAKE_SAY_PATHS        ((uint64_t)16 * 16 * 16 * 256)
#define SRV_BAKE_MAX_PATHS        ((uint64_t)32 * 32 * 32 * 512)

typedef struct srv_bake_plan {
    int      dims[3];
    uint64_t vertices, paths, bytes;
} srv_bake_plan;

/* Vertices per axis for a spacing of `cell` metres over the box lo..hi
 * (ceil(extent / cell) + 1, at least 2). LUMO_OK, or LUMO_ERR_RANGE with
 * the grid asked for in err when an axis needs more than 256 vertices or
 * cell is not a positive finite number. */
lumo_status srv_bake_dims_for_cell(vec3 lo, vec3 hi, float cell, int dims[3], char *err, size_t errlen);

/* The plan of a dims grid at spp paths per vertex. */
srv_bake_plan srv_bake_plan_of(const int dims[3], int spp);

/* "grid 16x16x16 (4096 vertices), 256 spp: 1.05 M paths, at least 2 MB". */
void srv_bake_plan_describe(const srv_bake_plan *p, char *buf, size_t n);

/* LUMO_OK within the budget or when allow_large; else LUMO_ERR_LIMIT with
 * the plan, the budget and the way out in err. */
lumo_status srv_bake_budget_check(const srv_bake_plan *p, int allow_large, char *err, size_t errlen);

#endif
