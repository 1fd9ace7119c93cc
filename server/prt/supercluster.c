/* supercluster.c — triangle overdraw (seed 003 §4.1, Eq. 8) and the
 * cluster selection for super-clusters (§4.3, Fig. 4.6). */
#include <stdlib.h>
#include <string.h>
#include "prt/cpca.h"

/* Distinct labels among a triangle's corners, into l[0..2]; returns how many. */
static int tri_labels(const srv_cpca *c, const uint32_t *t, const uint32_t *pass, uint32_t l[3])
{
    int n = 0;
    for (int i = 0; i < 3; i++) {
        uint32_t x = c->cluster[t[i]];
        x = pass ? pass[x] : x;
        int dup = 0;
        for (int j = 0; j < n; j++)
            dup |= l[j] == x;
        if (!dup)
            l[n++] = x;
    }
    return n;
}

double srv_cpca_overdraw(const srv_cpca *c, const uint32_t *tris, uint32_t ntris, const uint32_t *pass)
{
    uint64_t drawn = 0;
    uint32_t l[3];
    for (uint32_t t = 0; t < ntris; t++)
        drawn += (uint64_t)tri_labels(c, &tris[3 * t], pass, l);
    return ntris ? (double)drawn / ntris : 0.0;
}

/* The triangles each cluster touches, as lists (CSR). */
typedef struct { uint32_t *start, *tri; } touch;

static int build_touch(const srv_cpca *c, const uint32_t *tris, uint32_t ntris, touch *tc)
{
    uint32_t l[3], k = (uint32_t)c->k;
    tc->start = calloc(k + 2, sizeof *tc->start);
    tc->tri = malloc(3u * (ntris ? ntris : 1) * sizeof *tc->tri);
    if (!tc->start || !tc->tri)
        return -1;
    for (uint32_t t = 0; t < ntris; t++)
        for (int i = 0, n = tri_labels(c, &tris[3 * t], NULL, l); i < n; i++)
            tc->start[l[i] + 2]++;
    for (uint32_t x = 0; x < k; x++)
        tc->start[x + 2] += tc->start[x + 1];
    for (uint32_t t = 0; t < ntris; t++)
        for (int i = 0, n = tri_labels(c, &tris[3 * t], NULL, l); i < n; i++)
            tc->tri[tc->start[l[i] + 1]++] = t;
    return 0;
}

/* Step 3: cluster x joins the pass; every triangle it touches that the
 * pass did not touch yet now saves a draw for each other cluster on it. */
static void join(const srv_cpca *c, const uint32_t *tris, const touch *tc, uint32_t x, uint32_t p,
                 uint32_t *pass, uint32_t *tri_pass, uint64_t *gain)
{
    uint32_t l[3];
    pass[x] = p;
    for (uint32_t i = tc->start[x]; i < tc->start[x + 1]; i++) {
        uint32_t t = tc->tri[i];
        if (tri_pass[t] == p + 1)
            continue;
        tri_pass[t] = p + 1;
        for (int j = 0, n = tri_labels(c, &tris[3 * t], NULL, l); j < n; j++)
            if (pass[l[j]] == UINT32_MAX)
                gain[l[j]]++;
    }
}

/* Step 1 (largest) or 2 (most saved draws, ties: the larger) among the
 * clusters not placed yet; UINT32_MAX when all are placed. */
static uint32_t pick(const srv_cpca *c, const uint32_t *pass, const uint64_t *gain)
{
    uint32_t best = UINT32_MAX;
    for (uint32_t x = 0; x < (uint32_t)c->k; x++) {
        if (pass[x] != UINT32_MAX)
            continue;
        if (best == UINT32_MAX || (gain && gain[x] > gain[best]) ||
            ((!gain || gain[x] == gain[best]) && c->count[x] > c->count[best]))
            best = x;
    }
    return best;
}

uint32_t srv_cpca_superclusters(const srv_cpca *c, const uint32_t *tris, uint32_t ntris, int per_pass,
                                uint32_t *pass)
{
    touch tc = {0};
    uint32_t *tri_pass = calloc(ntris ? ntris : 1, sizeof *tri_pass), npass = 0;
    uint64_t *gain = calloc((size_t)c->k, sizeof *gain);
    if (!tri_pass || !gain || build_touch(c, tris, ntris, &tc))
        goto out;
    for (int x = 0; x < c->k; x++)
        pass[x] = UINT32_MAX;
    for (uint32_t x; (x = pick(c, pass, NULL)) != UINT32_MAX; npass++) {
        memset(gain, 0, (size_t)c->k * sizeof *gain);
        join(c, tris, &tc, x, npass, pass, tri_pass, gain);
        for (int i = 1; i < per_pass && (x = pick(c, pass, gain)) != UINT32_MAX; i++)
            join(c, tris, &tc, x, npass, pass, tri_pass, gain);
    }
out:
    free(tc.start);
    free(tc.tri);
    free(tri_pass);
    free(gain);
    return npass;
}
