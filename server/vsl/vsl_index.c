/* vsl_index.c — per-object k-d trees for the nearest VSL (vsl_index.h).
 * Implicit layout: a range's median is its node, the halves its children. */
#include <stdlib.h>
#include <string.h>
#include "vsl/vsl_index.h"

typedef struct { const srv_vsl *v; int axis; } sort_ctx;

static int cmp_axis(const void *a, const void *b, void *ctx)
{
    const sort_ctx *c = ctx;
    uint32_t i = *(const uint32_t *)a, j = *(const uint32_t *)b;
    float x = v3_get(c->v[i].pos, c->axis), y = v3_get(c->v[j].pos, c->axis);
    return x < y ? -1 : x > y ? 1 : (i > j) - (i < j);
}

static int widest_axis(const srv_vsl_set *set, const uint32_t *n, size_t len)
{
    vec3 lo = set->v[n[0]].pos, hi = lo;
    for (size_t i = 1; i < len; i++)
        lo = v3_min(lo, set->v[n[i]].pos), hi = v3_max(hi, set->v[n[i]].pos);
    vec3 e = v3_sub(hi, lo);
    return e.x >= e.y && e.x >= e.z ? 0 : e.y >= e.z ? 1 : 2;
}

static void build(srv_vsl_index *ix, size_t lo, size_t hi)
{
    if (hi <= lo)
        return;
    sort_ctx c = {ix->set->v, widest_axis(ix->set, ix->node + lo, hi - lo)};
    qsort_r(ix->node + lo, hi - lo, sizeof *ix->node, cmp_axis, &c);
    size_t mid = lo + (hi - lo) / 2;
    ix->axis[mid] = (uint8_t)c.axis;
    build(ix, lo, mid);
    build(ix, mid + 1, hi);
}

lumo_status srv_vsl_index_build(srv_vsl_index *ix, const srv_vsl_set *set)
{
    ix->set = set;
    ix->node = malloc((set->n ? set->n : 1) * sizeof *ix->node);
    ix->axis = calloc(set->n ? set->n : 1, 1);
    if (!ix->node || !ix->axis) {
        srv_vsl_index_free(ix);
        return LUMO_ERR_NOMEM;
    }
    for (size_t i = 0; i < set->n; i++)
        ix->node[i] = (uint32_t)i;
    for (size_t o = 0; o < set->nobjects; o++)
        build(ix, set->first[o], (size_t)set->first[o] + set->count[o]);
    return LUMO_OK;
}

void srv_vsl_index_free(srv_vsl_index *ix)
{
    free(ix->node);
    free(ix->axis);
    ix->node = NULL;
    ix->axis = NULL;
}

typedef struct { uint32_t best; float d2; } nearest;

static void search(const srv_vsl_index *ix, size_t lo, size_t hi, vec3 p, nearest *q)
{
    if (hi <= lo)
        return;
    size_t mid = lo + (hi - lo) / 2;
    uint32_t v = ix->node[mid];
    vec3 d = v3_sub(p, ix->set->v[v].pos);
    float d2 = v3_dot(d, d), delta = v3_get(d, ix->axis[mid]);
    if (d2 < q->d2 || (d2 == q->d2 && v < q->best))
        q->best = v, q->d2 = d2;
    int left_first = delta < 0.0f;
    search(ix, left_first ? lo : mid + 1, left_first ? mid : hi, p, q);
    if (delta * delta <= q->d2)   /* the sphere crosses the split plane */
        search(ix, left_first ? mid + 1 : lo, left_first ? hi : mid, p, q);
}

/* Below this many VSLs an object is scanned: the tree's descent costs more
 * than it saves (make bench-vsl: the scan wins by 2x at ~170 VSLs a
 * object, the tree by 7x at ~1 700; 256 lies between). */
#define SCAN_BELOW 256u

static void scan(const srv_vsl_index *ix, size_t lo, size_t hi, vec3 p, nearest *q)
{
    for (size_t i = lo; i < hi; i++) {
        vec3 d = v3_sub(p, ix->set->v[i].pos);
        float d2 = v3_dot(d, d);
        if (d2 < q->d2 || (d2 == q->d2 && i < q->best))
            q->best = (uint32_t)i, q->d2 = d2;
    }
}

uint32_t srv_vsl_index_nearest(const srv_vsl_index *ix, uint32_t o, vec3 p)
{
    nearest q = {UINT32_MAX, INFINITY};
    if (o >= ix->set->nobjects)
        return UINT32_MAX;
    size_t lo = ix->set->first[o], hi = lo + ix->set->count[o];
    if (ix->set->count[o] < SCAN_BELOW)
        scan(ix, lo, hi, p, &q);
    else
        search(ix, lo, hi, p, &q);
    return q.best;
}
