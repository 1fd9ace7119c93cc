/* cpca.c — clustered PCA (prt/cpca.h): LBG (cpca_lbg.c), PCA per cluster
 * with LAPACKE (seed 003 §3.1.3, Eq. 6), the reconstruction error. */
#include <float.h>
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "prt/cpca_internal.h"

void srv_cpca_default_opts(srv_cpca_opts *o)
{
    *o = (srv_cpca_opts){.clusters = 64, .components = 8, .alpha = 0.0, .threshold = 1e-4,
                         .max_iter = 100, .seed = 1, .threads = 1};
}

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

void srv_cpca_free(srv_cpca *c)
{
    free(c->cluster);
    free(c->count);
    free(c->mean);
    free(c->basis);
    free(c->weight);
    memset(c, 0, sizeof *c);
}

/* Positions in units of the bounding-box diagonal (Eq. 10's distances). */
static float *unit_positions(const float *pos, uint32_t n)
{
    float lo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, hi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
    float *out = malloc(3u * (n ? n : 1) * sizeof *out);
    if (!out)
        return NULL;
    for (uint32_t i = 0; i < 3u * n; i++)
        lo[i % 3] = fminf(lo[i % 3], pos[i]), hi[i % 3] = fmaxf(hi[i % 3], pos[i]);
    double diag = sqrt((double)(hi[0] - lo[0]) * (hi[0] - lo[0]) + (double)(hi[1] - lo[1]) * (hi[1] - lo[1]) +
                       (double)(hi[2] - lo[2]) * (hi[2] - lo[2]));
    for (uint32_t i = 0; i < 3u * n; i++)
        out[i] = (float)((pos[i] - lo[i % 3]) / (diag > 0 ? diag : 1.0));
    return out;
}

/* PCA of one cluster: the covariance's eigenvectors by decreasing
 * eigenvalue (LAPACKE_dsyev), then each member's weights. */
static lumo_status pca_cluster(srv_cpca *c, const double *x, uint32_t cl, double *cov, double *eig)
{
    int dim = c->dim;
    const double *m = &c->mean[cl * (uint32_t)dim];
    memset(cov, 0, (size_t)dim * (size_t)dim * sizeof *cov);
    for (uint32_t i = 0; i < c->n; i++) {
        if (c->cluster[i] != cl)
            continue;
        const double *v = &x[(size_t)i * (size_t)dim];
        for (int a = 0; a < dim; a++)
            for (int b = a; b < dim; b++)
                cov[a * dim + b] += (v[a] - m[a]) * (v[b] - m[b]);
    }
    if (LAPACKE_dsyev(LAPACK_ROW_MAJOR, 'V', 'U', dim, cov, dim, eig) != 0)
        return LUMO_ERR_IO;
    for (int j = 0; j < c->npc; j++)   /* eigenvalues ascend: the last columns first */
        for (int d = 0; d < dim; d++)
            c->basis[((size_t)cl * (size_t)c->npc + (size_t)j) * (size_t)dim + (size_t)d] = cov[d * dim + (dim - 1 - j)];
    for (uint32_t i = 0; i < c->n; i++) {
        if (c->cluster[i] != cl)
            continue;
        for (int j = 0; j < c->npc; j++) {
            const double *b = &c->basis[((size_t)cl * (size_t)c->npc + (size_t)j) * (size_t)dim];
            double w = 0.0;
            for (int d = 0; d < dim; d++)
                w += b[d] * (x[(size_t)i * (size_t)dim + (size_t)d] - m[d]);
            c->weight[(size_t)i * (size_t)c->npc + (size_t)j] = w;
        }
    }
    return LUMO_OK;
}

static lumo_status run_pca(srv_cpca *c, const double *x)
{
    double *cov = malloc((size_t)c->dim * (size_t)c->dim * sizeof *cov), *eig = malloc((size_t)c->dim * sizeof *eig);
    lumo_status st = cov && eig ? LUMO_OK : LUMO_ERR_NOMEM;
    for (int cl = 0; !st && cl < c->k; cl++)
        st = pca_cluster(c, x, (uint32_t)cl, cov, eig);
    free(cov);
    free(eig);
    return st;
}

static lumo_status alloc_result(srv_cpca *c, uint32_t n, int dim, int k, int npc)
{
    memset(c, 0, sizeof *c);
    c->n = n, c->dim = dim, c->k = k, c->npc = npc;
    c->cluster = calloc(n, sizeof *c->cluster);
    c->count = calloc((size_t)k, sizeof *c->count);
    c->mean = calloc((size_t)k * (size_t)dim, sizeof *c->mean);
    c->basis = calloc((size_t)k * (size_t)(npc ? npc : 1) * (size_t)dim, sizeof *c->basis);
    c->weight = calloc((size_t)n * (size_t)(npc ? npc : 1), sizeof *c->weight);
    return c->cluster && c->count && c->mean && c->basis && c->weight ? LUMO_OK : LUMO_ERR_NOMEM;
}

static lumo_status cluster(srv_cpca *c, const double *x, const float *pos, const srv_cpca_opts *o)
{
    int threads = o->threads < 1 ? 1 : o->threads;
    lbg g = {.x = x, .n = c->n, .dim = c->dim, .k = c->k, .alpha = o->alpha, .cluster = c->cluster,
             .count = c->count, .mean = c->mean};
    g.next = malloc(c->n * sizeof *g.next);
    float *up = o->alpha > 0.0 ? unit_positions(pos, c->n) : NULL;
    g.pos = up;
    lumo_status st = g.next && (up || o->alpha == 0.0) ? LUMO_OK : LUMO_ERR_NOMEM;
    srv_cpca_init_means(x, c->n, c->dim, c->k, o->seed, c->mean);
    if (!st)
        st = srv_cpca_lbg(&g, o->max_iter, o->threshold, threads);
    c->iterations = g.iterations;
    srv_kd_free(&g.kd);
    free(g.next);
    free(up);
    return st;
}

lumo_status srv_cpca_build(const double *x, uint32_t n, int dim, const float *pos,
                           const srv_cpca_opts *o, srv_cpca *out)
{
    if (o->clusters < 1 || (uint32_t)o->clusters > n || dim < 1 || dim > SRV_CPCA_MAX_DIM ||
        o->components < 0 || o->components > dim || o->alpha < 0.0 || (o->alpha > 0.0 && !pos) ||
        o->max_iter < 1) {
        memset(out, 0, sizeof *out);
        return LUMO_ERR_ARG;
    }
    lumo_status st = alloc_result(out, n, dim, o->clusters, o->components);
    double t0 = now_s();
    if (!st)
        st = cluster(out, x, pos, o);
    double t1 = now_s();
    if (!st)
        st = run_pca(out, x);
    out->cluster_seconds = t1 - t0, out->pca_seconds = now_s() - t1;
    if (st)
        srv_cpca_free(out);
    return st;
}

void srv_cpca_reconstruct(const srv_cpca *c, uint32_t v, double *out)
{
    uint32_t cl = c->cluster[v];
    memcpy(out, &c->mean[cl * (uint32_t)c->dim], (size_t)c->dim * sizeof *out);
    for (int j = 0; j < c->npc; j++) {
        const double *b = &c->basis[((size_t)cl * (size_t)c->npc + (size_t)j) * (size_t)c->dim];
        double w = c->weight[(size_t)v * (size_t)c->npc + (size_t)j];
        for (int d = 0; d < c->dim; d++)
            out[d] += w * b[d];
    }
}

double srv_cpca_sq_error(const srv_cpca *c, const double *x)
{
    double r[SRV_CPCA_MAX_DIM], s = 0.0;
    for (uint32_t v = 0; v < c->n; v++) {
        srv_cpca_reconstruct(c, v, r);
        for (int d = 0; d < c->dim; d++) {
            double e = x[(size_t)v * (size_t)c->dim + (size_t)d] - r[d];
            s += e * e;
        }
    }
    return c->n ? s / c->n : 0.0;
}

int srv_cpca_per_pass(int dim, int npc, int registers)
{
    int per = (dim * (npc + 1) + 3) / 4;
    return registers / per > 0 ? registers / per : 1;
}
