/* kdtree.c — per-cluster nearest-member queries for the geometry-coherence
 * term (seed 003 §4.2, Eq. 10), rebuilt once per LBG pass. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "prt/cpca_internal.h"

static _Thread_local const float *g_sort_pos;
static _Thread_local int g_sort_axis;

static int cmp_axis(const void *a, const void *b)
{
    float x = g_sort_pos[3 * *(const uint32_t *)a + (uint32_t)g_sort_axis];
    float y = g_sort_pos[3 * *(const uint32_t *)b + (uint32_t)g_sort_axis];
    if (x != y)
        return x < y ? -1 : 1;
    return *(const uint32_t *)a < *(const uint32_t *)b ? -1 : 1;
}

static void build_range(const float *pos, uint32_t *idx, uint32_t n, int depth)
{
    if (n < 2)
        return;
    g_sort_pos = pos, g_sort_axis = depth % 3;
    qsort(idx, n, sizeof *idx, cmp_axis);
    build_range(pos, idx, n / 2, depth + 1);
    build_range(pos, idx + n / 2 + 1, n - n / 2 - 1, depth + 1);
}

int srv_kd_build(srv_kd *t, const float *pos, const uint32_t *label, uint32_t n, uint32_t k)
{
    if (!t->idx) {
        t->idx = malloc((n ? n : 1) * sizeof *t->idx);
        t->start = malloc((k + 2) * sizeof *t->start);
        if (!t->idx || !t->start)
            return -1;
    }
    t->pos = pos, t->n = n, t->k = k;
    memset(t->start, 0, (k + 2) * sizeof *t->start);
    for (uint32_t i = 0; i < n; i++)
        t->start[label[i] + 2]++;
    for (uint32_t c = 0; c < k; c++)
        t->start[c + 2] += t->start[c + 1];
    for (uint32_t i = 0; i < n; i++)
        t->idx[t->start[label[i] + 1]++] = i;
    for (uint32_t c = 0; c < k; c++)
        build_range(pos, t->idx + t->start[c], t->start[c + 1] - t->start[c], 0);
    return 0;
}

void srv_kd_free(srv_kd *t)
{
    free(t->idx);
    free(t->start);
    t->idx = t->start = NULL;
}

static void nearest_range(const srv_kd *t, const uint32_t *idx, uint32_t n, int depth, const float p[3],
                          uint32_t skip, double *best)
{
    if (n == 0)
        return;
    uint32_t mid = n / 2;
    const float *q = &t->pos[3 * idx[mid]];
    double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
    double d2 = dx * dx + dy * dy + dz * dz, off = p[depth % 3] - q[depth % 3];
    if (d2 < *best && idx[mid] != skip)
        *best = d2;
    const uint32_t *lo = idx, *hi = idx + mid + 1;
    uint32_t nlo = mid, nhi = n - mid - 1;
    if (off > 0) {   /* the near side first */
        nearest_range(t, hi, nhi, depth + 1, p, skip, best);
        if (off * off < *best)
            nearest_range(t, lo, nlo, depth + 1, p, skip, best);
    } else {
        nearest_range(t, lo, nlo, depth + 1, p, skip, best);
        if (off * off < *best)
            nearest_range(t, hi, nhi, depth + 1, p, skip, best);
    }
}

double srv_kd_nearest(const srv_kd *t, uint32_t c, const float p[3], uint32_t skip)
{
    double best = DBL_MAX;
    uint32_t a = t->start[c], b = t->start[c + 1];
    nearest_range(t, t->idx + a, b - a, 0, p, skip, &best);
    return best == DBL_MAX ? DBL_MAX : sqrt(best);
}
