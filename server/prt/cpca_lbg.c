/* cpca_lbg.c — LBG clustering with geometry coherence (prt/cpca.h;
 * seed 003 §3.1.2 Fig. 3.2, Eq. 4-5, §4.2 Eq. 9-10). */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "common/parallel.h"
#include "common/rng.h"
#include "prt/cpca_internal.h"

void srv_cpca_init_means(const double *x, uint32_t n, int dim, int k, uint64_t seed, double *mean)
{
    double lo[SRV_CPCA_MAX_DIM], hi[SRV_CPCA_MAX_DIM];
    srv_rng r;
    for (int d = 0; d < dim; d++)
        lo[d] = DBL_MAX, hi[d] = -DBL_MAX;
    for (uint32_t i = 0; i < n; i++)
        for (int d = 0; d < dim; d++) {
            double v = x[(size_t)i * (size_t)dim + (size_t)d];
            lo[d] = fmin(lo[d], v), hi[d] = fmax(hi[d], v);
        }
    srv_rng_seed(&r, seed, 0x4C4247u);
    for (int c = 0; c < k; c++)
        for (int d = 0; d < dim; d++)
            mean[c * dim + d] = lo[d] + (hi[d] - lo[d]) * (srv_rng_u32(&r) / 4294967296.0);
}

static double dist2(const double *a, const double *b, int dim)
{
    double s = 0.0;
    for (int d = 0; d < dim; d++)
        s += (a[d] - b[d]) * (a[d] - b[d]);
    return s;
}

/* Plain assignment: the nearest mean (ties: the lower index). */
static uint32_t nearest_mean(const lbg *g, uint32_t i)
{
    const double *v = &g->x[(size_t)i * (size_t)g->dim];
    double best = DBL_MAX;
    uint32_t bc = 0;
    for (int c = 0; c < g->k; c++) {
        double d = dist2(v, &g->mean[c * g->dim], g->dim);
        if (d < best)
            best = d, bc = (uint32_t)c;
    }
    return bc;
}

/* Eq. 9-10 with k != i: a vertex's distance to its own cluster is to the
 * nearest other member, as to any cluster (counting the vertex itself
 * would make the term zero for the cluster it is in and freeze the first
 * pass's assignment; docs/prt.md "Geometry coherence"). The geometric term
 * (nearest member by kd-tree) is looked up only for clusters whose
 * ||V - mean|| is already below the best so far. */
static uint32_t coherent_mean(const lbg *g, uint32_t i)
{
    const double *v = &g->x[(size_t)i * (size_t)g->dim];
    const float *p = &g->pos[3 * (size_t)i];
    uint32_t bc = g->cluster[i];
    double best = sqrt(dist2(v, &g->mean[bc * (uint32_t)g->dim], g->dim)) + g->alpha * fmin(srv_kd_nearest(&g->kd, bc, p, i), 1e300);
    for (int c = 0; c < g->k; c++) {
        double d = sqrt(dist2(v, &g->mean[c * g->dim], g->dim));
        if ((uint32_t)c == g->cluster[i] || d >= best)
            continue;
        double e = d + g->alpha * srv_kd_nearest(&g->kd, (uint32_t)c, p, i);
        if (e < best || (e == best && (uint32_t)c < bc))
            best = e, bc = (uint32_t)c;
    }
    return bc;
}

#define ASSIGN_BLOCK 256u

static void assign_block(void *ctx, size_t item, int worker)
{
    lbg *g = ctx;
    uint32_t a = (uint32_t)item * ASSIGN_BLOCK, b = a + ASSIGN_BLOCK < g->n ? a + ASSIGN_BLOCK : g->n;
    (void)worker;
    for (uint32_t i = a; i < b; i++)
        g->next[i] = g->coherent ? coherent_mean(g, i) : nearest_mean(g, i);
}

/* Fig. 3.2 step 2 and Eq. 4: the means of the members, the energy. */
static double update_means(lbg *g)
{
    int dim = g->dim;
    memset(g->mean, 0, (size_t)g->k * (size_t)dim * sizeof *g->mean);
    memset(g->count, 0, (size_t)g->k * sizeof *g->count);
    for (uint32_t i = 0; i < g->n; i++) {
        g->count[g->cluster[i]]++;
        for (int d = 0; d < dim; d++)
            g->mean[g->cluster[i] * (uint32_t)dim + (uint32_t)d] += g->x[(size_t)i * (size_t)dim + (size_t)d];
    }
    for (int c = 0; c < g->k; c++)
        for (int d = 0; d < dim && g->count[c]; d++)
            g->mean[c * dim + d] /= g->count[c];
    double e = 0.0;
    for (uint32_t i = 0; i < g->n; i++)
        e += dist2(&g->x[(size_t)i * (size_t)dim], &g->mean[g->cluster[i] * (uint32_t)dim], dim);
    return e;
}

/* §3.1.2 "Null Cluster Avoidance": the empty cluster e takes the members
 * of the largest cluster above its mean on the widest dimension (half by
 * index when they are all equal there). 0 when nothing can be split. */
static int split_largest(lbg *g, uint32_t e)
{
    uint32_t big = 0;
    for (int c = 1; c < g->k; c++)
        if (g->count[c] > g->count[big])
            big = (uint32_t)c;
    if (g->count[big] < 2)
        return 0;
    int dim = g->dim, wd = 0;
    double var[SRV_CPCA_MAX_DIM] = {0};
    for (uint32_t i = 0; i < g->n; i++)
        for (int d = 0; g->cluster[i] == big && d < dim; d++) {
            double t = g->x[(size_t)i * (size_t)dim + (size_t)d] - g->mean[big * (uint32_t)dim + (uint32_t)d];
            var[d] += t * t;
        }
    for (int d = 1; d < dim; d++)
        wd = var[d] > var[wd] ? d : wd;
    uint32_t moved = 0, seen = 0;
    for (uint32_t i = 0; i < g->n; i++) {
        if (g->cluster[i] != big)
            continue;
        int up = var[wd] > 0.0 ? g->x[(size_t)i * (size_t)dim + (size_t)wd] > g->mean[big * (uint32_t)dim + (uint32_t)wd]
                               : seen++ % 2 == 1;
        if (up)
            g->cluster[i] = e, moved++;
    }
    return moved > 0;
}

static double fix_null_clusters(lbg *g, double e)
{
    for (int c = 0; c < g->k; c++)
        if (g->count[c] == 0 && split_largest(g, (uint32_t)c))
            e = update_means(g);
    return e;
}

lumo_status srv_cpca_lbg(lbg *g, int max_iter, double threshold, int threads)
{
    double prev = INFINITY;   /* E_0 = inf, Eq. 5 */
    size_t blocks = (g->n + ASSIGN_BLOCK - 1) / ASSIGN_BLOCK;
    g->iterations = 0;
    for (int it = 0; it < max_iter; it++) {
        g->coherent = g->alpha > 0.0 && it > 0;   /* Eq. 10 needs members */
        if (g->coherent && srv_kd_build(&g->kd, g->pos, g->cluster, g->n, (uint32_t)g->k))
            return LUMO_ERR_NOMEM;
        lumo_status st = srv_parallel_for(blocks, threads, assign_block, g, "lbg", 0);
        if (st)
            return st;
        memcpy(g->cluster, g->next, g->n * sizeof *g->cluster);
        double e = fix_null_clusters(g, update_means(g));
        g->iterations = it + 1;
        if (e == 0.0 || (prev - e) / prev < threshold)
            break;
        prev = e;
    }
    return LUMO_OK;
}
