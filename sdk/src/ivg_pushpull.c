/*
 * ivg_pushpull.c — 3D push-pull hole filling of the IVG (seed 000 §4.1).
 *
 * A pyramid of coarser grids sits above the received grid (level 0); coarse
 * vertex i lies on fine vertex 2i along every axis of 3 or more vertices, an
 * axis of 2 collapses to 1 (ivg_coarse_dim), so any dims work.
 *
 *  push   level l -> l+1: every coarse vertex is the tent-weighted (1,2,1)
 *         average of the valid fine vertices around it; valid when any was.
 *  smooth (LUMO_IVG_SMOOTH) right after each push: the valid vertices of
 *         the new level are replaced by the (1,2,1)^3 weighted average of
 *         their valid neighbours (the paper's pyramidal filter), computed
 *         by separable passes over one hemisphere at a time.
 *  pull   level l+1 -> l, top down: every invalid vertex of level l is the
 *         trilinear interpolation of level l+1 (weights 1/2 or 1 per axis).
 *
 * Only received values are read at level 0 and only non-received vertices
 * are written there, so received data stay bit-identical and a re-run after
 * more samples recomputes every filled vertex. d and c are averaged
 * separately and d is not renormalised, as trilinear texture filtering of
 * two 3D textures would do (§3.3).
 *
 * Arithmetic: integer weights summing to at most 64, 64-bit colour sums
 * (< 2^38), rounding to nearest with ties away from zero. Each division is
 * done as two 32-bit divisions (the Cortex-M3 has a 32-bit UDIV; a 64-bit
 * division is a slow library call). Bit-exact on every target.
 */
#include <string.h>
#include "ivg_internal.h"

/* Weighted sum of entries. Weights are <= 64 per vertex (tent products),
 * so colour sums stay below 2^38 and direction sums below 2^22. */
typedef struct ivg_acc {
    uint64_t c[LUMO_IVG_AXES][3];
    int32_t  d[LUMO_IVG_AXES][3];
    uint32_t w;
} ivg_acc;

/* Up to three (index, weight) pairs along one axis. */
typedef struct ivg_taps {
    unsigned n;
    uint32_t idx[3];
    uint32_t w[3];
} ivg_taps;

static void taps_add(ivg_taps *t, uint32_t idx, uint32_t w)
{
    t->idx[t->n] = idx;
    t->w[t->n] = w;
    t->n++;
}

/* Fine vertices feeding coarse vertex i (push): tent weights 1,2,1 around
 * fine 2i; a collapsing axis (2 -> 1) averages both; 1 -> 1 is identity. */
static void push_taps(uint32_t i, uint32_t fine, uint32_t coarse, ivg_taps *t)
{
    t->n = 0;
    if (fine == coarse) {
        taps_add(t, i, 1);
    } else if (coarse == 1u) {
        taps_add(t, 0, 1);
        taps_add(t, 1, 1);
    } else {
        /* for even fine dims the last coarse vertex lies one past the
         * fine grid (fine = 2i): only 2i - 1 feeds it */
        if (i > 0u)
            taps_add(t, 2u * i - 1u, 1);
        if (2u * i < fine)
            taps_add(t, 2u * i, 2);
        if (2u * i + 1u < fine)
            taps_add(t, 2u * i + 1u, 1);
    }
}

/* Coarse vertices fine vertex f interpolates from (pull), weights in
 * halves: on a coarse vertex (2) or between two (1, 1). */
static void pull_taps(uint32_t f, uint32_t fine, uint32_t coarse, ivg_taps *t)
{
    t->n = 0;
    if (fine == coarse) {
        taps_add(t, f, 2);
    } else if (coarse == 1u) {
        taps_add(t, 0, 2);
    } else if ((f & 1u) == 0u) {
        taps_add(t, f / 2u, 2);
    } else {
        taps_add(t, f / 2u, 1);
        taps_add(t, f / 2u + 1u, 1);
    }
}

/* Validity by storage index (ivg_plane_slot; the vertex index on level 0,
 * where valid means received). */
static int level_valid(const ivg_level *lv, uint32_t v)
{
    return ivg_bit(lv->valid, v);
}

static void level_set_valid(ivg_level *lv, uint32_t v, int on)
{
    if (on)
        ivg_bit_set(lv->valid, v);
    else
        ivg_bit_clear(lv->valid, v);
}

static int vertex_valid(const lumo_ivg *g, unsigned l, uint32_t v)
{
    return l == 0 ? ivg_bit(g->received_bits, v) : level_valid(&g->level[l], v);
}

/* Add a vertex's six packed entries with weight w (d in q units). */
static void acc_add(ivg_acc *acc, const uint8_t *packed, uint32_t w)
{
    ivg_raw r;
    int a, k;

    for (a = 0; a < LUMO_IVG_AXES; a++) {
        ivg_raw_open(packed + a * IVG_PACKED, &r);
        for (k = 0; k < 3; k++) {
            acc->c[a][k] += (uint64_t)r.c[k] * w;
            acc->d[a][k] += r.q[k] * (int32_t)w;
        }
    }
    acc->w += w;
}

/* round(n / d), ties up, for n < 2^48 and 0 < d < 128, as two 32-bit
 * divisions: round(n/d) = floor((2n + d) / 2d), split at bit 24 so each
 * partial dividend fits 32 bits. */
static uint32_t div_round_u48(uint64_t n, uint32_t d)
{
    uint64_t m = 2u * n + d;
    uint32_t dd = 2u * d;
    uint32_t hi = (uint32_t)(m >> 24);
    uint32_t lo = (hi % dd) << 24 | (uint32_t)(m & 0xFFFFFFu);
    return (uint32_t)(((uint64_t)(hi / dd) << 24) + lo / dd);
}

/* round(n / d), ties away from zero, for |n| < 2^30, 0 < d < 128. */
static int32_t div_round_i32(int32_t n, uint32_t d)
{
    uint32_t mag = n < 0 ? (uint32_t)-n : (uint32_t)n;
    uint32_t q = (2u * mag + d) / (2u * d);
    return n < 0 ? -(int32_t)q : (int32_t)q;
}

/* log2(w) when w is a power of two, else -1. */
static int pow2_shift(uint32_t w)
{
    int s = 0;

    if ((w & (w - 1u)) != 0u)
        return -1;
    while ((1u << s) < w)
        s++;
    return s;
}

/* round(sum / w) for one entry's three colours and three direction
 * components: a shift by s = log2(w) when w is a power of two (pull weights
 * always sum to 8, interior push and smoothing weights to 64), two 32-bit
 * divisions otherwise (s < 0); both give the same result. A weighted average of values in
 * range is in range. */
static void sum_store(const uint64_t c[3], const int32_t d[3], uint32_t w, int s, ivg_raw *e)
{
    int k;

    if (s < 0) {
        for (k = 0; k < 3; k++) {
            e->c[k] = div_round_u48(c[k], w);
            e->q[k] = div_round_i32(d[k], w);
        }
        return;
    }
    for (k = 0; k < 3; k++) {
        uint32_t half = (1u << s) >> 1;
        uint32_t mag = d[k] < 0 ? (uint32_t)-d[k] : (uint32_t)d[k];
        mag = (mag + half) >> s;
        e->c[k] = (uint32_t)((c[k] + half) >> s);
        e->q[k] = d[k] < 0 ? -(int32_t)mag : (int32_t)mag;
    }
}

/* The six averages, each rounded (c to UQ16.16, d to q) and packed. */
static void acc_store(const ivg_acc *acc, uint8_t *packed)
{
    ivg_raw e;
    int a, s = pow2_shift(acc->w);

    for (a = 0; a < LUMO_IVG_AXES; a++) {
        sum_store(acc->c[a], acc->d[a], acc->w, s, &e);
        ivg_raw_pack(&e, packed + a * IVG_PACKED);
    }
}

/* Sum the vertices of level l at the product of the three tap lists,
 * skipping invalid ones when valid_only. */
static void gather(const lumo_ivg *g, unsigned l, const ivg_taps t[3], int valid_only, ivg_acc *acc)
{
    const ivg_level *lv = &g->level[l];
    unsigned x, y, z;

    memset(acc, 0, sizeof *acc);
    for (z = 0; z < t[2].n; z++) {
        for (y = 0; y < t[1].n; y++) {
            uint32_t row = ivg_plane_slot(lv, t[2].idx[z]) + lv->dims[0] * t[1].idx[y];
            uint32_t wyz = t[1].w[y] * t[2].w[z];
            for (x = 0; x < t[0].n; x++) {
                uint32_t v = row + t[0].idx[x];
                if (valid_only && !vertex_valid(g, l, v))
                    continue;
                acc_add(acc, ivg_packed_at(lv, v, 0), wyz * t[0].w[x]);
            }
        }
    }
}

/* Plane k of level l+1 from level l into c (level l+1 itself, or the
 * ring of level 1 before smoothing): tent-weighted average of the valid
 * fine vertices. */
static void push_plane(lumo_ivg *g, unsigned l, uint32_t k, ivg_level *c)
{
    const ivg_level *f = &g->level[l];
    uint32_t i, j, v = ivg_plane_slot(c, k);
    ivg_taps t[3];
    ivg_acc acc;

    push_taps(k, f->dims[2], c->dims[2], &t[2]);
    for (j = 0; j < c->dims[1]; j++) {
        push_taps(j, f->dims[1], c->dims[1], &t[1]);
        for (i = 0; i < c->dims[0]; i++, v++) {
            push_taps(i, f->dims[0], c->dims[0], &t[0]);
            gather(g, l, t, 1, &acc);
            level_set_valid(c, v, acc.w != 0u);
            if (acc.w != 0u)
                acc_store(&acc, ivg_packed_at(c, v, 0));
            else
                memset(ivg_packed_at(c, v, 0), 0, IVG_PACKED_VERTEX);
        }
    }
}

/* dst = left + 2 mid + right (left, right may be NULL; dst may be mid). */
static void sum_mix(ivg_sum *dst, const ivg_sum *left, const ivg_sum *mid, const ivg_sum *right)
{
    int k;

    for (k = 0; k < 3; k++) {
        dst->c[k] = 2u * mid->c[k] + (left ? left->c[k] : 0u) + (right ? right->c[k] : 0u);
        dst->d[k] = 2 * mid->d[k] + (left ? left->d[k] : 0) + (right ? right->d[k] : 0);
    }
    dst->w = 2u * mid->w + (left ? left->w : 0u) + (right ? right->w : 0u);
}

/* (1,2,1) along one line of `len` sums `stride` apart, in place: the
 * unfiltered previous element is kept aside. */
static void sum_pass(ivg_sum *line, uint32_t len, uint32_t stride)
{
    ivg_sum keep[2];                        /* unfiltered i-1 and i */
    uint32_t i;

    for (i = 0; i < len; i++) {
        ivg_sum *cur = &line[i * stride];
        keep[i & 1u] = *cur;
        sum_mix(cur, i > 0u ? &keep[(i - 1u) & 1u] : NULL, &keep[i & 1u],
                i + 1u < len ? cur + stride : NULL);
    }
}

/* Plane z of level lv, hemisphere a, filtered along x and y into s:
 * weight x value and weight over the valid vertices only. */
static void smooth_plane(const ivg_level *lv, int a, uint32_t z, ivg_sum *s)
{
    uint32_t nx = lv->dims[0], ny = lv->dims[1], base = ivg_plane_slot(lv, z), i;
    int k;

    for (i = 0; i < nx * ny; i++) {
        uint32_t v = base + i;
        ivg_raw e = {{0, 0, 0}, {0, 0, 0}};
        int on = level_valid(lv, v);
        if (on)
            ivg_raw_open(ivg_packed_at(lv, v, (unsigned)a), &e);
        for (k = 0; k < 3; k++) {
            s[i].c[k] = e.c[k];
            s[i].d[k] = e.q[k];
        }
        s[i].w = (uint32_t)on;
    }
    for (i = 0; i < ny; i++)
        sum_pass(&s[i * nx], nx, 1);
    for (i = 0; i < nx; i++)
        sum_pass(&s[i], ny, nx);
}

/* The z pass writing plane z of hemisphere a into lv (whose valid
 * vertices are those to write): the x-y sums of planes z-1, z and z+1 are
 * in the ring (slot = plane % 3). */
static void smooth_write(ivg_level *lv, int a, uint32_t z, const ivg_sum *ring)
{
    uint32_t plane = lv->dims[0] * lv->dims[1], nz = lv->dims[2], base = ivg_plane_slot(lv, z), i;
    const ivg_sum *lo = z > 0u ? &ring[((z - 1u) % 3u) * plane] : NULL;
    const ivg_sum *mid = &ring[(z % 3u) * plane];
    const ivg_sum *hi = z + 1u < nz ? &ring[((z + 1u) % 3u) * plane] : NULL;
    ivg_sum out;
    ivg_raw e;

    for (i = 0; i < plane; i++) {
        uint32_t v = base + i;
        if (!level_valid(lv, v))
            continue;
        sum_mix(&out, lo != NULL ? lo + i : NULL, mid + i, hi != NULL ? hi + i : NULL);
        sum_store(out.c, out.d, out.w, pow2_shift(out.w), &e);
        ivg_raw_pack(&e, ivg_packed_at(lv, v, (unsigned)a));
    }
}

/* Pyramidal (1,2,1)^3 filter over the valid vertices of coarse level l
 * kept whole (level 1 as a ring: smooth_level1_plane):
 * every valid vertex becomes the weighted average of the valid vertices
 * around it. The weights are a product, so the sums of weight x value and
 * of weight over valid neighbours are separable: x and y passes per plane
 * into a ring of three planes, and plane z-1 is written once plane z is in
 * the ring (its own values are no longer needed by then). The integer sums
 * are those of the 27-tap filter, and so are the results. An axis of one
 * vertex doubles every sum and weight, which changes no quotient. */
static void smooth(lumo_ivg *g, unsigned l)
{
    ivg_level *lv = &g->level[l];
    uint32_t plane = lv->dims[0] * lv->dims[1], nz = lv->dims[2], z;
    int a;

    for (a = 0; a < LUMO_IVG_AXES; a++) {
        for (z = 0; z < nz; z++) {
            smooth_plane(lv, a, z, &g->scratch[(z % 3u) * plane]);
            if (z > 0u)
                smooth_write(lv, a, z - 1u, g->scratch);
        }
        smooth_write(lv, a, nz - 1u, g->scratch);
    }
}

/* Plane k of level l from level l+1: trilinear fill of its invalid
 * vertices. */
static void pull_plane(lumo_ivg *g, unsigned l, uint32_t k)
{
    ivg_level *f = &g->level[l];
    const ivg_level *c = &g->level[l + 1];
    uint32_t i, j, v = ivg_plane_slot(f, k);
    ivg_taps t[3];
    ivg_acc acc;

    pull_taps(k, f->dims[2], c->dims[2], &t[2]);
    for (j = 0; j < f->dims[1]; j++) {
        pull_taps(j, f->dims[1], c->dims[1], &t[1]);
        for (i = 0; i < f->dims[0]; i++, v++) {
            if (vertex_valid(g, l, v))
                continue;
            pull_taps(i, f->dims[0], c->dims[0], &t[0]);
            gather(g, l + 1, t, 0, &acc);
            acc_store(&acc, ivg_packed_at(f, v, 0));
        }
    }
}

/* ---- level 1, plane by plane (docs/ivg-format.md §6) ----------------------------
 * Level 1 has N/8 to N/6 vertices; kept whole it would cost 6 of the 48
 * bytes a grid vertex may take. It is made in two rings of three planes
 * instead: raw1 (the push from level 0) and level[1] itself (smoothed, and
 * on the way down filled from level 2). A plane is made when it is first
 * needed, in increasing z, so the rings always hold the planes a step
 * reads: smoothing plane z reads raw planes z-1..z+1; the push into level
 * 2 plane m reads planes 2m-1..2m+1; the pull into level 0 plane f reads
 * planes f/2 and f/2+1. The push reads only received vertices of level 0,
 * so the planes made again on the way down are those made on the way up,
 * byte for byte, while level 0 is being filled. */
typedef struct ivg_level1 {
    lumo_ivg *g;
    unsigned  flags;
    uint32_t  raw_next, next;   /* next plane to make: raw, final */
    int       fill;             /* fill invalid vertices from level 2 */
} ivg_level1;

/* The valid bits and entries of raw plane z into level 1's ring. */
static void copy_raw_plane(lumo_ivg *g, uint32_t z)
{
    ivg_level *dst = &g->level[1];
    uint32_t plane = dst->dims[0] * dst->dims[1], v = ivg_plane_slot(dst, z), i;

    memcpy(ivg_packed_at(dst, v, 0), ivg_packed_at(&g->raw1, v, 0), (size_t)plane * IVG_PACKED_VERTEX);
    for (i = 0; i < plane; i++)
        level_set_valid(dst, v + i, level_valid(&g->raw1, v + i));
}

/* Hemisphere a of raw plane n added to the sums s with weight w (valid
 * vertices only). */
static void sum_raw_plane(const ivg_level *raw, int a, uint32_t n, uint32_t w, ivg_sum *s)
{
    uint32_t plane = raw->dims[0] * raw->dims[1], base = ivg_plane_slot(raw, n), i;
    int k;

    for (i = 0; i < plane; i++) {
        ivg_raw e;
        if (!level_valid(raw, base + i))
            continue;
        ivg_raw_open(ivg_packed_at(raw, base + i, (unsigned)a), &e);
        for (k = 0; k < 3; k++) {
            s[i].c[k] += (uint64_t)e.c[k] * w;
            s[i].d[k] += e.q[k] * (int32_t)w;
        }
        s[i].w += w;
    }
}

/* Smoothed plane z of level 1 from raw planes z-1..z+1: smooth() for one
 * plane, with the passes in the other order — per hemisphere the (1,2,1)
 * along z first, into one plane of sums, then along x and y. The sums are
 * exact integers, so the order changes nothing (the same bytes), and each
 * x-y pass runs once per plane as when level 1 was whole. */
static void smooth_level1_plane(lumo_ivg *g, uint32_t z)
{
    ivg_level *lv = &g->level[1];
    uint32_t nx = lv->dims[0], ny = lv->dims[1], nz = lv->dims[2], base = ivg_plane_slot(lv, z), i;
    ivg_sum *s = g->scratch;
    ivg_raw e;
    int a;

    copy_raw_plane(g, z);
    for (a = 0; a < LUMO_IVG_AXES; a++) {
        memset(s, 0, (size_t)nx * ny * sizeof *s);
        if (z > 0u)
            sum_raw_plane(&g->raw1, a, z - 1u, 1u, s);
        sum_raw_plane(&g->raw1, a, z, 2u, s);
        if (z + 1u < nz)
            sum_raw_plane(&g->raw1, a, z + 1u, 1u, s);
        for (i = 0; i < ny; i++)
            sum_pass(&s[i * nx], nx, 1);
        for (i = 0; i < nx; i++)
            sum_pass(&s[i], ny, nx);
        for (i = 0; i < nx * ny; i++) {
            if (!level_valid(lv, base + i))
                continue;
            sum_store(s[i].c, s[i].d, s[i].w, pow2_shift(s[i].w), &e);
            ivg_raw_pack(&e, ivg_packed_at(lv, base + i, (unsigned)a));
        }
    }
}

/* Make level 1's planes up to k (final: pushed, smoothed, filled). */
static void level1_need(ivg_level1 *s, uint32_t k)
{
    lumo_ivg *g = s->g;
    uint32_t nz = g->level[1].dims[2];

    for (; s->next <= k; s->next++) {
        if (s->flags & LUMO_IVG_SMOOTH) {
            uint32_t hi = s->next + 1u < nz ? s->next + 1u : s->next;
            for (; s->raw_next <= hi; s->raw_next++)
                push_plane(g, 0, s->raw_next, &g->raw1);
            smooth_level1_plane(g, s->next);
        } else {
            push_plane(g, 0, s->next, &g->level[1]);
        }
        if (s->fill)
            pull_plane(g, 1, s->next);
    }
}

static void level1_start(ivg_level1 *s, lumo_ivg *g, unsigned flags, int fill)
{
    s->g = g;
    s->flags = flags;
    s->raw_next = s->next = 0;
    s->fill = fill;
}

/* The largest index among the taps along z. */
static uint32_t last_tap(const ivg_taps *t)
{
    return t->idx[t->n - 1u];
}

/* Level l -> l+1, smoothed after; level 1 made as read when it is a
 * ring (s; NULL: kept whole). */
static void push(lumo_ivg *g, unsigned l, unsigned flags, ivg_level1 *s)
{
    ivg_level *c = &g->level[l + 1];
    uint32_t k;
    ivg_taps t;

    for (k = 0; k < c->dims[2]; k++) {
        if (l == 1u && s != NULL) {
            push_taps(k, g->level[1].dims[2], c->dims[2], &t);
            level1_need(s, last_tap(&t));
        }
        push_plane(g, l, k, c);
    }
    if (flags & LUMO_IVG_SMOOTH)
        smooth(g, l + 1);
}

/* Level l from level l+1; into level 0 with level 1 made as read when it
 * is a ring (s; NULL: kept whole). */
static void pull(lumo_ivg *g, unsigned l, ivg_level1 *s)
{
    uint32_t k;
    ivg_taps t;

    for (k = 0; k < g->level[l].dims[2]; k++) {
        if (l == 0u && s != NULL) {
            pull_taps(k, g->level[0].dims[2], g->level[1].dims[2], &t);
            level1_need(s, last_tap(&t));
        }
        pull_plane(g, l, k);
    }
}

lumo_status lumo_ivg_pushpull(lumo_ivg *g, unsigned flags)
{
    ivg_level1 s;
    unsigned l;

    if (g == NULL || (flags & ~LUMO_IVG_SMOOTH) != 0u)
        return LUMO_ERR_ARG;
    if (g->levels < 2u)
        return LUMO_OK;
    if (g->level[1].ring == 0u) {   /* a small grid: level 1 kept whole */
        for (l = 0; l + 1 < g->levels; l++)
            push(g, l, flags, NULL);
        for (l = g->levels - 1; l-- > 0;)
            pull(g, l, NULL);
        return LUMO_OK;
    }
    /* up: level 1 exists only as the push into level 2 reads it */
    level1_start(&s, g, flags, 0);
    for (l = 1; l + 1 < g->levels; l++)
        push(g, l, flags, &s);
    /* down to level 2, then level 1 made again and filled as level 0 reads it */
    for (l = g->levels - 1; l-- > 2;)
        pull(g, l, &s);
    level1_start(&s, g, flags, g->levels > 2u);
    pull(g, 0, &s);
    return LUMO_OK;
}
