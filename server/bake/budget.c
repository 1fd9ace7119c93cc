/* budget.c — bake/budget.h: the grid a bake will use and its cost. */
#include <math.h>
#include <stdio.h>
#include "bake/budget.h"

#define MAX_DIM 256

lumo_status srv_bake_dims_for_cell(vec3 lo, vec3 hi, float cell, int dims[3], char *err, size_t errlen)
{
    double n[3];
    if (!(cell > 0.0f) || !isfinite(cell)) {
        snprintf(err, errlen, "--cell %g: the spacing must be a positive number of metres", cell);
        return LUMO_ERR_RANGE;
    }
    for (int a = 0; a < 3; a++)
        n[a] = fmax(ceil(((double)v3_get(hi, a) - (double)v3_get(lo, a)) / cell) + 1.0, 2.0);
    if (n[0] > MAX_DIM || n[1] > MAX_DIM || n[2] > MAX_DIM) {
        snprintf(err, errlen, "--cell %g over a %.3g x %.3g x %.3g m scene asks for a %.0fx%.0fx%.0f grid; the "
                 "most is %d per axis (docs/package-format.md \"IVGD\"): use a larger --cell or --grid", cell,
                 v3_get(hi, 0) - v3_get(lo, 0), v3_get(hi, 1) - v3_get(lo, 1), v3_get(hi, 2) - v3_get(lo, 2),
                 n[0], n[1], n[2], MAX_DIM);
        return LUMO_ERR_RANGE;
    }
    for (int a = 0; a < 3; a++)
        dims[a] = (int)n[a];
    return LUMO_OK;
}

srv_bake_plan srv_bake_plan_of(const int dims[3], int spp)
{
    srv_bake_plan p;
    for (int a = 0; a < 3; a++)
        p.dims[a] = dims[a];
    p.vertices = (uint64_t)dims[0] * (uint64_t)dims[1] * (uint64_t)dims[2];
    p.paths = p.vertices * (uint64_t)(spp > 0 ? spp : 0);
    p.bytes = p.vertices * SRV_BAKE_BYTES_PER_VERTEX;
    return p;
}

void srv_bake_plan_describe(const srv_bake_plan *p, char *buf, size_t n)
{
    snprintf(buf, n, "grid %dx%dx%d (%llu vertices), %llu spp: %.2f M paths, at least %.0f MB", p->dims[0],
             p->dims[1], p->dims[2], (unsigned long long)p->vertices,
             (unsigned long long)(p->vertices ? p->paths / p->vertices : 0), (double)p->paths * 1e-6,
             ceil((double)p->bytes / (1 << 20)));
}

lumo_status srv_bake_budget_check(const srv_bake_plan *p, int allow_large, char *err, size_t errlen)
{
    char what[160];
    if (allow_large || (p->vertices <= SRV_BAKE_MAX_VERTICES && p->paths <= SRV_BAKE_MAX_PATHS))
        return LUMO_OK;
    srv_bake_plan_describe(p, what, sizeof what);
    snprintf(err, errlen, "%s: past the budget of %llu vertices (64^3) and %.1f M paths (32^3 at 512 spp, about 45 s on 2 cores); "
             "pass --allow-large to bake it anyway, or use a smaller --grid, larger --cell or fewer --spp", what,
             (unsigned long long)SRV_BAKE_MAX_VERTICES, (double)SRV_BAKE_MAX_PATHS * 1e-6);
    return LUMO_ERR_LIMIT;
}
