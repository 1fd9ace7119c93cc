/* pm_build.c — the progressive mesh of seed 000 §4.2: vertices renumbered by
 * significance (base mesh first, then the last collapsed first), the vertex
 * lookup table, and faces sorted by the level at which they appear. */
#include <stdlib.h>
#include <string.h>
#include "pm/pm_internal.h"

void srv_pm_default_options(srv_pm_options *o)
{
    o->min_vertices = 3;
    o->boundary_weight = 100.0;
    o->flip_cos = 0.2;
    o->round_fraction = 0.1;   /* bench-pm-quality: 0.25 left 13 levels worse than meshoptimizer */
    o->max_error = 0.05;
    o->seed = 1;
}

static const uint32_t *g_level; /* qsort context */

static int cmp_level(const void *a, const void *b)
{
    uint32_t i = *(const uint32_t *)a, j = *(const uint32_t *)b;
    if (g_level[i] != g_level[j])
        return g_level[i] < g_level[j] ? -1 : 1;
    return (i > j) - (i < j);
}

static const uint32_t *g_key; /* qsort context: sort steps by g_key[step] */

static int cmp_key(const void *a, const void *b)
{
    uint32_t i = *(const uint32_t *)a, j = *(const uint32_t *)b;
    return (g_key[i] > g_key[j]) - (g_key[i] < g_key[j]);
}

/* newv[v]: the seed's vertices keep their relative order at 0..s-1; then
 * the rounds, last round first (the last collapsed streams first): the
 * collapses past max_error (s..b-1, inside the base mesh), then those
 * within it (b..n-1); inside a round, whose collapses commute, by the new
 * index of the parent, so the stream's lookup-table entries increase
 * (docs/progressive-mesh.md §2.3). A parent outlives its round, so it is
 * numbered before its children. Without rounds (one collapse each) the
 * step removed at t gets n-1-t. With a seed, the base vertices are
 * numbered differently, so a round may list its splits in another order
 * than without one; the level at the end of each round is the same. */
static int renumber(const srv_pm_clean_mesh *m, const srv_pm_collapses *c, uint32_t *newv)
{
    uint32_t n = m->nv, s = 0;
    uint32_t *steps = malloc(sizeof *steps * (c->count ? c->count : 1));
    uint32_t *key = malloc(sizeof *key * (c->count ? c->count : 1));
    if (!steps || !key)
        return free(steps), free(key), -1;
    memset(newv, 0xff, sizeof *newv * n);
    for (uint32_t t = 0; t < c->count; t++)
        newv[c->removed[t]] = 0;
    for (uint32_t v = 0; v < n; v++)
        newv[v] = newv[v] == 0 ? UINT32_MAX - 1 : s++;
    uint32_t next = s;
    for (uint32_t end = c->count; end > 0;) {
        uint32_t start = end - 1;
        while (start > 0 && c->round[start - 1] == c->round[end - 1])
            start--;
        for (uint32_t t = start; t < end; t++)
            steps[t - start] = t, key[t] = newv[c->target[t]];
        g_key = key;
        qsort(steps, end - start, sizeof *steps, cmp_key);
        for (uint32_t i = 0; i < end - start; i++)
            newv[c->removed[steps[i]]] = next++;
        end = start;
    }
    free(steps);
    free(key);
    return 0;
}

/* Each face that reappears with vertex k = level - 1 starts at the corner
 * showing k (same winding): the stream then need not say where k sits. */
static void rotate_faces(srv_pm *pm)
{
    for (uint32_t f = pm->seed_faces; f < pm->faces; f++) {
        uint32_t *t = pm->tris + 3 * (size_t)f, k = pm->level[f] - 1;
        for (int turn = 0; turn < 2 && srv_pm_resolve(pm, t[0], k + 1) != k; turn++) {
            uint32_t x = t[0];
            t[0] = t[1], t[1] = t[2], t[2] = x;
        }
    }
}

/* Within a level, the face (k, p, x) comes before (k, x, p): the stream
 * then need not say which of an opposite pair is which. */
static void order_pairs(srv_pm *pm)
{
    for (uint32_t f = pm->seed_faces; f + 1 < pm->faces; f++) {
        uint32_t L = pm->level[f];
        if (pm->level[f + 1] != L || (f + 2 < pm->faces && pm->level[f + 2] == L) ||
            (f > pm->seed_faces && pm->level[f - 1] == L))
            continue;  /* only levels with exactly two faces */
        uint32_t *a = pm->tris + 3 * (size_t)f, *b = a + 3, p = pm->parent[L - 1];
        if (srv_pm_resolve(pm, b[1], L) == p && srv_pm_resolve(pm, a[1], L) != p)
            for (int i = 0; i < 3; i++) {
                uint32_t x = a[i];
                a[i] = b[i], b[i] = x;
            }
    }
}

static int assemble(const srv_pm_clean_mesh *m, const srv_pm_collapses *c, srv_pm *pm)
{
    uint32_t n = m->nv, nf = m->nf;
    uint32_t *newv = malloc(sizeof *newv * (n ? n : 1));
    uint32_t *lvl = malloc(sizeof *lvl * (nf ? nf : 1));
    uint32_t *order = malloc(sizeof *order * (nf ? nf : 1));
    int rc = -1;
    if (!newv || !lvl || !order)
        goto done;
    if (renumber(m, c, newv))
        goto done;
    pm->vertices = n, pm->faces = nf;
    pm->seed_vertices = n - c->count;
    pm->base_vertices = n - c->bounded;
    for (uint32_t v = 0; v < n; v++) {
        memcpy(pm->xyz + 3 * (size_t)newv[v], m->xyz + 3 * (size_t)v, 3 * sizeof(float));
        if (m->rgb)
            memcpy(pm->albedo + 3 * (size_t)newv[v], m->rgb + 3 * (size_t)v, 3);
        pm->source[newv[v]] = m->source[v];
        pm->parent[newv[v]] = newv[v];
    }
    for (uint32_t t = 0; t < c->count; t++)
        pm->parent[newv[c->removed[t]]] = newv[c->target[t]];
    /* A face removed at step t comes back with the vertex removed then;
     * the base mesh's faces are those of the seed and those the collapses
     * past max_error removed (levels up to b). */
    for (uint32_t f = 0; f < nf; f++) {
        lvl[f] = c->face_die[f] == UINT32_MAX ? pm->seed_vertices : newv[c->removed[c->face_die[f]]] + 1;
        pm->seed_faces += c->face_die[f] == UINT32_MAX;
        pm->base_faces += lvl[f] <= pm->base_vertices;
        order[f] = f;
    }
    g_level = lvl;
    qsort(order, nf, sizeof *order, cmp_level);
    for (uint32_t i = 0; i < nf; i++) {
        pm->level[i] = lvl[order[i]];
        for (int k = 0; k < 3; k++)
            pm->tris[3 * (size_t)i + k] = newv[m->tris[3 * (size_t)order[i] + k]];
    }
    rotate_faces(pm);
    order_pairs(pm);
    rc = 0;
done:
    free(newv);
    free(lvl);
    free(order);
    return rc;
}

lumo_status srv_pm_build(const float *xyz, uint32_t nv, const uint32_t *tris, uint32_t nf,
                         const srv_pm_options *opt, srv_pm *out)
{
    return srv_pm_build_albedo(xyz, NULL, nv, tris, nf, opt, out);
}

lumo_status srv_pm_build_albedo(const float *xyz, const uint8_t *albedo, uint32_t nv,
                                const uint32_t *tris, uint32_t nf, const srv_pm_options *opt,
                                srv_pm *out)
{
    srv_pm_options def;
    srv_pm_clean_mesh m;
    srv_pm_collapses c;
    memset(out, 0, sizeof *out);
    memset(&c, 0, sizeof c);
    if (!opt) {
        srv_pm_default_options(&def);
        opt = &def;
    }
    lumo_status rc = srv_pm_clean(xyz, albedo, nv, tris, nf, &m);
    if (rc)
        return rc;
    if ((rc = srv_pm_simplify(&m, opt, &c)))
        goto done;
    rc = LUMO_ERR_NOMEM;
    size_t n = m.nv ? m.nv : 1, f = m.nf ? m.nf : 1;
    out->xyz = malloc(sizeof *out->xyz * 3 * n);
    out->parent = malloc(sizeof *out->parent * n);
    out->source = malloc(sizeof *out->source * n);
    out->tris = malloc(sizeof *out->tris * 3 * f);
    out->level = malloc(sizeof *out->level * f);
    out->albedo = albedo ? malloc(3 * n) : NULL;
    if (!out->xyz || !out->parent || !out->source || !out->tris || !out->level || (albedo && !out->albedo))
        goto done;
    if (assemble(&m, &c, out))
        goto done;
    out->welded = m.welded;
    out->dropped_faces = m.dropped_faces;
    rc = LUMO_OK;
done:
    srv_pm_clean_free(&m);
    srv_pm_collapses_free(&c);
    if (rc)
        srv_pm_free(out);
    return rc;
}

void srv_pm_free(srv_pm *pm)
{
    free(pm->xyz);
    free(pm->parent);
    free(pm->tris);
    free(pm->level);
    free(pm->source);
    free(pm->albedo);
    memset(pm, 0, sizeof *pm);
}

uint32_t srv_pm_resolve(const srv_pm *pm, uint32_t v, uint32_t k)
{
    while (v >= k)
        v = pm->parent[v];
    return v;
}

uint32_t srv_pm_level_faces(const srv_pm *pm, uint32_t k)
{
    uint32_t lo = 0, hi = pm->faces;  /* faces are sorted by level */
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (pm->level[mid] <= k)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

uint32_t srv_pm_level(const srv_pm *pm, uint32_t k, uint32_t *out)
{
    uint32_t nf = srv_pm_level_faces(pm, k);
    for (size_t i = 0; i < 3 * (size_t)nf; i++)
        out[i] = srv_pm_resolve(pm, pm->tris[i], k);
    return nf;
}
