/* pm_clean.c — make scanned meshes safe for half-edge collapse (seed 000
 * §4.2 needs a proper indexed face set): weld vertices with identical
 * positions, drop degenerate and duplicate faces, drop unused vertices. */
#include <stdlib.h>
#include <string.h>
#include "pm/pm_internal.h"

static const float *g_sort_xyz;  /* qsort has no context argument in C11 */
static const uint8_t *g_sort_rgb;

/* Weld key: exact position, then albedo (a colour seam is not welded). */
static int same_key(uint32_t i, uint32_t j)
{
    int c = memcmp(g_sort_xyz + 3 * (size_t)i, g_sort_xyz + 3 * (size_t)j, 3 * sizeof(float));
    if (!c && g_sort_rgb)
        c = memcmp(g_sort_rgb + 3 * (size_t)i, g_sort_rgb + 3 * (size_t)j, 3);
    return c;
}

static int cmp_pos(const void *a, const void *b)
{
    uint32_t i = *(const uint32_t *)a, j = *(const uint32_t *)b;
    int c = same_key(i, j);
    if (c)
        return c;
    return (i > j) - (i < j);
}

/* weld[v] = smallest input vertex with v's exact position (and albedo). */
static uint32_t *weld_map(const float *xyz, const uint8_t *rgb, uint32_t nv, uint32_t *welded)
{
    uint32_t *order = malloc(sizeof *order * (nv ? nv : 1));
    uint32_t *weld = malloc(sizeof *weld * (nv ? nv : 1));
    if (!order || !weld) {
        free(order);
        free(weld);
        return NULL;
    }
    for (uint32_t v = 0; v < nv; v++)
        order[v] = v;
    g_sort_xyz = xyz, g_sort_rgb = rgb;
    qsort(order, nv, sizeof *order, cmp_pos);
    *welded = 0;
    for (uint32_t i = 0; i < nv; i++) {
        int same = i > 0 && !same_key(order[i], order[i - 1]);
        weld[order[i]] = same ? weld[order[i - 1]] : order[i];
        *welded += (uint32_t)same;
    }
    free(order);
    return weld;
}

static const uint32_t *g_sort_keys;

static int cmp_face(const void *a, const void *b)
{
    uint32_t i = *(const uint32_t *)a, j = *(const uint32_t *)b;
    int c = memcmp(g_sort_keys + 3 * (size_t)i, g_sort_keys + 3 * (size_t)j, 3 * sizeof(uint32_t));
    if (c)
        return c;
    return (i > j) - (i < j);
}

static void sort3(uint32_t k[3])
{
    uint32_t t;
    if (k[0] > k[1]) t = k[0], k[0] = k[1], k[1] = t;
    if (k[1] > k[2]) t = k[1], k[1] = k[2], k[2] = t;
    if (k[0] > k[1]) t = k[0], k[0] = k[1], k[1] = t;
}

/* keep[f] = 1 for faces that are neither degenerate nor a later copy of an
 * earlier face over the same three vertices (either winding). */
static int face_keep(const uint32_t *tris, uint32_t nf, uint8_t *keep)
{
    uint32_t *keys = malloc(sizeof *keys * 3 * (size_t)(nf ? nf : 1));
    uint32_t *order = malloc(sizeof *order * (nf ? nf : 1));
    if (!keys || !order) {
        free(keys);
        free(order);
        return -1;
    }
    for (uint32_t f = 0; f < nf; f++) {
        memcpy(keys + 3 * (size_t)f, tris + 3 * (size_t)f, 3 * sizeof *keys);
        sort3(keys + 3 * (size_t)f);
        order[f] = f;
    }
    g_sort_keys = keys;
    qsort(order, nf, sizeof *order, cmp_face);
    for (uint32_t i = 0; i < nf; i++) {
        const uint32_t *k = keys + 3 * (size_t)order[i];
        int degenerate = k[0] == k[1] || k[1] == k[2];
        int dup = i > 0 && !memcmp(k, keys + 3 * (size_t)order[i - 1], 3 * sizeof *k);
        keep[order[i]] = (uint8_t)!(degenerate || dup);
    }
    free(keys);
    free(order);
    return 0;
}

lumo_status srv_pm_clean(const float *xyz, const uint8_t *rgb, uint32_t nv, const uint32_t *tris,
                         uint32_t nf, srv_pm_clean_mesh *out)
{
    memset(out, 0, sizeof *out);
    for (size_t i = 0; i < 3 * (size_t)nf; i++)
        if (tris[i] >= nv)
            return LUMO_ERR_RANGE;
    uint32_t *weld = weld_map(xyz, rgb, nv, &out->welded);
    uint32_t *wt = malloc(sizeof *wt * 3 * (size_t)(nf ? nf : 1));
    uint8_t *keep = malloc(nf ? nf : 1);
    uint32_t *newv = malloc(sizeof *newv * (nv ? nv : 1));
    lumo_status rc = LUMO_ERR_NOMEM;
    if (!weld || !wt || !keep || !newv)
        goto done;
    for (size_t i = 0; i < 3 * (size_t)nf; i++)
        wt[i] = weld[tris[i]];
    if (face_keep(wt, nf, keep))
        goto done;
    /* Vertices keep their input order; only referenced ones survive. */
    memset(newv, 0xff, sizeof *newv * nv);
    for (uint32_t f = 0; f < nf; f++)
        for (int c = 0; keep[f] && c < 3; c++)
            newv[wt[3 * (size_t)f + c]] = 0;
    for (uint32_t v = 0; v < nv; v++)
        if (newv[v] == 0)
            newv[v] = out->nv++;
    out->xyz = malloc(sizeof *out->xyz * 3 * (size_t)(out->nv ? out->nv : 1));
    out->source = malloc(sizeof *out->source * (out->nv ? out->nv : 1));
    out->tris = malloc(sizeof *out->tris * 3 * (size_t)(nf ? nf : 1));
    out->rgb = rgb ? malloc(3 * (size_t)(out->nv ? out->nv : 1)) : NULL;
    if (!out->xyz || !out->source || !out->tris || (rgb && !out->rgb))
        goto done;
    for (uint32_t v = 0; v < nv; v++)
        if (newv[v] != UINT32_MAX) {
            memcpy(out->xyz + 3 * (size_t)newv[v], xyz + 3 * (size_t)v, 3 * sizeof(float));
            out->source[newv[v]] = v;
            if (rgb)
                memcpy(out->rgb + 3 * (size_t)newv[v], rgb + 3 * (size_t)v, 3);
        }
    for (uint32_t f = 0; f < nf; f++) {
        if (!keep[f]) {
            out->dropped_faces++;
            continue;
        }
        for (int c = 0; c < 3; c++)
            out->tris[3 * (size_t)out->nf + c] = newv[wt[3 * (size_t)f + c]];
        out->nf++;
    }
    rc = LUMO_OK;
done:
    free(weld);
    free(wt);
    free(keep);
    free(newv);
    if (rc)
        srv_pm_clean_free(out);
    return rc;
}

void srv_pm_clean_free(srv_pm_clean_mesh *m)
{
    free(m->xyz);
    free(m->rgb);
    free(m->tris);
    free(m->source);
    memset(m, 0, sizeof *m);
}
