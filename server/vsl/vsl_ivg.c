/* vsl_ivg.c — localized IVG updates from the VSLs (vsl_ivg.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "vsl/vsl_ivg.h"

lumo_status srv_vsl_ivg_init(srv_vsl_ivg *v, const srv_grid *g, size_t nvsl, float eps, float tau)
{
    memset(v, 0, sizeof *v);
    if (!(tau >= 0.0f) || !(eps >= 0.0f))
        return LUMO_ERR_ARG;
    v->grid = *g;
    v->nverts = (size_t)g->dims[0] * (size_t)g->dims[1] * (size_t)g->dims[2];
    v->nvsl = nvsl;
    v->eps = eps, v->tau = tau;
    v->I = calloc(v->nverts * SRV_VSL_IVG_VALUES, sizeof *v->I);
    v->pub = calloc(nvsl ? nvsl : 1, sizeof *v->pub);
    v->dirty = calloc(v->nverts, 1);
    if (!v->I || !v->pub || !v->dirty) {
        srv_vsl_ivg_free(v);
        return LUMO_ERR_NOMEM;
    }
    return LUMO_OK;
}

void srv_vsl_ivg_free(srv_vsl_ivg *v)
{
    free(v->I), free(v->pub), free(v->dirty);
    memset(v, 0, sizeof *v);
}

/* Grid index range [lo, hi] along axis a covering [c - r, c + r]. */
static void axis_range(const srv_grid *g, int a, float c, float r, int *lo, int *hi)
{
    float b0 = v3_get(g->bmin, a), b1 = v3_get(g->bmax, a);
    int n = g->dims[a] - 1;
    float step = n > 0 ? (b1 - b0) / (float)n : 1.0f;
    double f0 = floor(((double)c - r - b0) / step), f1 = ceil(((double)c + r - b0) / step);
    *lo = f0 < 0 ? 0 : f0 > n ? n + 1 : (int)f0;
    *hi = f1 > n ? n : f1 < 0 ? -1 : (int)f1;
}

/* Add scale * s's term to every vertex inside its cut-off; mark them. */
static void apply(srv_vsl_ivg *v, const srv_vsl_lit *s, double scale)
{
    int lo[3], hi[3];
    float r = sqrtf(srv_vsl_cutoff2(s, v->eps));
    if (!(v3_maxc(v3(fabsf(s->flux.x), fabsf(s->flux.y), fabsf(s->flux.z))) > 0.0f))
        return;
    for (int a = 0; a < 3; a++)
        axis_range(&v->grid, a, v3_get(s->pos, a), isfinite(r) ? r : INFINITY, &lo[a], &hi[a]);
    for (int k = lo[2]; k <= hi[2]; k++)
        for (int j = lo[1]; j <= hi[1]; j++)
            for (int i = lo[0]; i <= hi[0]; i++) {
                vec3 p = srv_grid_vertex(&v->grid, i, j, k);
                if (!srv_vsl_reaches(s, p, v->eps))
                    continue;
                size_t idx = (size_t)i + (size_t)v->grid.dims[0] * ((size_t)j + (size_t)v->grid.dims[1] * (size_t)k);
                srv_vsl_ivg_add(s, scale, p, v->I + idx * SRV_VSL_IVG_VALUES);
                v->dirty[idx] = 1;
                v->touched++;
            }
}

static float absmax(vec3 a)
{
    return v3_maxc(v3(fabsf(a.x), fabsf(a.y), fabsf(a.z)));
}

static int important(const srv_vsl_ivg *v, const srv_vsl_lit *held, const srv_vsl_lit *now, float mean)
{
    if (held->pos.x != now->pos.x || held->pos.y != now->pos.y || held->pos.z != now->pos.z ||
        held->normal.x != now->normal.x || held->normal.y != now->normal.y || held->normal.z != now->normal.z)
        return 1;
    float scale = fmaxf(mean, fmaxf(absmax(held->flux), absmax(now->flux)));
    return absmax(v3_sub(now->flux, held->flux)) > v->tau * scale;
}

size_t srv_vsl_ivg_update(srv_vsl_ivg *v, const srv_vsl_lit *now)
{
    double sum = 0.0;
    for (size_t s = 0; s < v->nvsl; s++)
        sum += absmax(now[s].flux);
    float mean = v->nvsl ? (float)(sum / (double)v->nvsl) : 0.0f;
    size_t n = 0;
    for (size_t s = 0; s < v->nvsl; s++) {
        if (!important(v, &v->pub[s], &now[s], mean))
            continue;
        apply(v, &v->pub[s], -1.0);
        apply(v, &now[s], +1.0);
        v->pub[s] = now[s];
        n++;
    }
    v->republished += n;
    return n;
}

size_t srv_vsl_ivg_take_dirty(srv_vsl_ivg *v, uint32_t *out, size_t cap)
{
    size_t n = 0;
    for (size_t i = 0; i < v->nverts && n < cap; i++)
        if (v->dirty[i])
            out[n++] = (uint32_t)i, v->dirty[i] = 0;
    return n;
}

void srv_vsl_ivg_full(const srv_grid *g, const srv_vsl_lit *lit, size_t n, float eps, double *I)
{
    size_t nv = (size_t)g->dims[0] * (size_t)g->dims[1] * (size_t)g->dims[2];
    memset(I, 0, nv * SRV_VSL_IVG_VALUES * sizeof *I);
    for (int k = 0; k < g->dims[2]; k++)
        for (int j = 0; j < g->dims[1]; j++)
            for (int i = 0; i < g->dims[0]; i++) {
                vec3 p = srv_grid_vertex(g, i, j, k);
                size_t idx = (size_t)i + (size_t)g->dims[0] * ((size_t)j + (size_t)g->dims[1] * (size_t)k);
                for (size_t s = 0; s < n; s++)
                    if (srv_vsl_reaches(&lit[s], p, eps))
                        srv_vsl_ivg_add(&lit[s], 1.0, p, I + idx * SRV_VSL_IVG_VALUES);
            }
}
