/*
 * prt/cpca.h — clustered PCA of per-vertex transfer vectors (seed 003
 * §3.1.2-3.1.3, §4.2, §4.3; Sloan, Hall, Hart & Snyder 2003):
 *
 *  - LBG / k-means (Fig. 3.2) started from random points of the data's
 *    hyper-box, stopped when the energy (Eq. 4) falls by less than a ratio
 *    (Eq. 5); a cluster left empty ("null cluster") takes half of the
 *    largest cluster, split across its widest dimension, until none is empty;
 *  - geometry coherence (§4.2, Eq. 9-10): a vertex goes to the cluster j
 *    minimising ||V_i - mean_j|| + alpha min_{k in j} ||P_i - P_k||, positions
 *    in units of the mesh's bounding-box diagonal; alpha = 0 is plain LBG;
 *  - PCA per cluster (LAPACKE dsyev on the covariance): mean, the first
 *    `components` principal directions, per vertex weights (Eq. 6);
 *  - super-clusters (§4.3, Fig. 4.6) under a per-pass budget of clusters;
 *  - the metrics of Chapter 5: average triangle overdraw (Eq. 8) and the
 *    average squared error against the uncompressed vectors.
 * Every array is malloc'ed; srv_cpca_free releases them.
 */
#ifndef SRV_PRT_CPCA_H
#define SRV_PRT_CPCA_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/status.h"

typedef struct srv_cpca_opts {
    int      clusters;     /* k >= 1 */
    int      components;   /* principal components per cluster, 0..dim (thesis: 8) */
    double   alpha;        /* geometry coherence weight (thesis: 0.05); 0 = off */
    double   threshold;    /* converged when (E_{i-1} - E_i) / E_{i-1} < threshold */
    int      max_iter;     /* cluster passes at most */
    uint64_t seed;         /* the initial means */
    int      threads;
} srv_cpca_opts;

void srv_cpca_default_opts(srv_cpca_opts *o);

typedef struct srv_cpca {
    uint32_t n;           /* vectors */
    int      dim, k, npc;
    uint32_t *cluster;    /* n: each vector's cluster */
    uint32_t *count;      /* k: members */
    double   *mean;       /* k * dim */
    double   *basis;      /* k * npc * dim: component j of cluster c at (c * npc + j) * dim */
    double   *weight;     /* n * npc */
    int       iterations; /* cluster passes run */
    double    cluster_seconds, pca_seconds;
} srv_cpca;

/* The initial means (Fig. 3.2 step 0, §3.1.2): k points drawn uniformly in
 * the axis-aligned hyper-box of the data. mean: k * dim. */
void srv_cpca_init_means(const double *x, uint32_t n, int dim, int k, uint64_t seed, double *mean);

/* Cluster then compress. x: n * dim, pos: 3 * n (needed when alpha > 0,
 * else may be NULL). LUMO_OK, LUMO_ERR_ARG (k < 1 or > n, components out
 * of 0..dim, alpha < 0 or no positions), LUMO_ERR_NOMEM, or LUMO_ERR_IO
 * (LAPACK failed to converge). */
lumo_status srv_cpca_build(const double *x, uint32_t n, int dim, const float *pos,
                           const srv_cpca_opts *o, srv_cpca *out);
void srv_cpca_free(srv_cpca *c);

/* The vector v reconstructed from its cluster and weights (Eq. 6). */
void srv_cpca_reconstruct(const srv_cpca *c, uint32_t v, double *out);

/* Average over the vectors of ||x_v - reconstruction_v||^2. */
double srv_cpca_sq_error(const srv_cpca *c, const double *x);

/* Eq. 8: triangles drawn / triangles, where a triangle is drawn once per
 * distinct pass among its corners; pass[cluster] (NULL: one pass per
 * cluster). */
double srv_cpca_overdraw(const srv_cpca *c, const uint32_t *tris, uint32_t ntris, const uint32_t *pass);

/* §4.3, Fig. 4.6: clusters into passes of at most per_pass clusters each:
 * start a pass with the largest unplaced cluster, then add the cluster
 * that saves the most triangle draws against the pass so far (ties: the
 * larger), until the pass is full. pass: k entries; returns the number
 * of passes, 0 when out of memory. */
uint32_t srv_cpca_superclusters(const srv_cpca *c, const uint32_t *tris, uint32_t ntris, int per_pass,
                                uint32_t *pass);

/* Clusters per GPU pass under a budget of float4 constant registers
 * (seed 003 §4.1: 256), each cluster holding its mean and components. */
int srv_cpca_per_pass(int dim, int npc, int registers);

#endif
