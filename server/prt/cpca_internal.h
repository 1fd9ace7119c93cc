/* cpca_internal.h — what the CPCA files share: the per-cluster kd-trees of
 * positions (Eq. 10's nearest member) and the LBG state. */
#ifndef SRV_PRT_CPCA_INTERNAL_H
#define SRV_PRT_CPCA_INTERNAL_H

#include <stdint.h>
#include "lumo/status.h"
#include "prt/cpca.h"

#define SRV_CPCA_MAX_DIM 64

/* One implicit kd-tree per cluster over its members' positions: the
 * members of cluster c are idx[start[c] .. start[c + 1]), each subrange
 * ordered so its middle element splits on the axis of its depth. */
typedef struct srv_kd {
    const float *pos;     /* 3 per vertex */
    uint32_t *idx;        /* n */
    uint32_t *start;      /* k + 1 */
    uint32_t  n, k;
} srv_kd;

/* (Re)build from the labels. 0, or -1 when out of memory. */
int srv_kd_build(srv_kd *t, const float *pos, const uint32_t *label, uint32_t n, uint32_t k);
void srv_kd_free(srv_kd *t);
/* Distance from p to the nearest member of cluster c other than vertex
 * skip (UINT32_MAX: none skipped); DBL_MAX when there is none. */
double srv_kd_nearest(const srv_kd *t, uint32_t c, const float p[3], uint32_t skip);

typedef struct lbg {
    const double *x;      /* n * dim */
    const float  *pos;    /* 3 * n, in bounding-box diagonals (alpha > 0) */
    uint32_t n;
    int      dim, k;
    double   alpha;
    int      coherent;    /* this pass uses Eq. 9 */
    uint32_t *cluster, *next, *count;
    double   *mean;       /* k * dim */
    srv_kd    kd;
    int       iterations;
} lbg;

/* Fig. 3.2 from the means already in g->mean. */
lumo_status srv_cpca_lbg(lbg *g, int max_iter, double threshold, int threads);

#endif
