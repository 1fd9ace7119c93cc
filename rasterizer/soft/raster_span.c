/*
 * raster_span.c — one screen triangle to pixels: set-up, edge stepping,
 * spans, depth test, interpolation (docs/rasterizer.md, "The fixed-point
 * pipeline", steps 5-8).
 *
 * Coverage is exact: 64-bit edge functions at pixel centres, stepped by
 * exact integer increments, top-left fill rule. A row is scanned from the
 * bounding box's left edge until the first covered pixel and stops at the
 * first uncovered pixel after it (a triangle is convex: one span per row).
 * Per covered pixel the work is one multiply-shift for the depth (the
 * division by the triangle's area is a per-triangle reciprocal) and, for a
 * pixel that passes the depth test, one division for both perspective
 * barycentrics. Every value is a function of the triangle and the pixel
 * alone, so bands of any height give the bytes of the whole frame.
 */
#include "raster_internal.h"

/* Inlined where the build optimises for speed (the host's -O2: on a mesh
 * of small triangles the calls and their saved registers cost more than
 * the code); a plain call under -Os (the boards), where the larger inlined
 * bodies spill registers (golden_raster per vertex: +0.9 instructions a
 * covered pixel inlined). */
#if defined(__GNUC__) && !defined(__OPTIMIZE_SIZE__)
#define SPAN_FAST static inline __attribute__((always_inline))
#else
#define SPAN_FAST static
#endif

/* Barycentric precision of the interpolation: Q0.16. */
#define BARY_BITS 16
/* Edge functions are scaled down to < 2^24 before the perspective products. */
#define EDGE_BITS 24

typedef struct edge {
    int64_t a, b;      /* E(x, y) = a * (x - x0) + b * (y - y0) */
    int32_t x0, y0;
    int64_t bias;      /* 0 on top-left edges, 1 elsewhere */
} edge;

/* What a triangle's spans need, computed once per triangle. */
typedef struct tri {
    const lumo_raster_sv *v;
    edge e[3];
    int64_t step[3];   /* edge increments per pixel: 16 a */
    unsigned sh;       /* edge functions >> sh < 2^24 */
    unsigned qsh;      /* perspective weights >> qsh < 2^46 */
    unsigned zs;       /* depth: z = ((sum w q) >> zs) * zr >> 32 */
    uint64_t zr;
    unsigned run_bits; /* Gouraud: runs end at multiples of 2^run_bits pixels */
    int edges32;       /* sh == 0 and every edge value of the box within +-2^30 */
    int32_t st32[3], bias32[3];   /* step and bias as 32-bit values (edges32) */
    int32_t dy32[3];              /* the edge values' change per row, 16 b (edges32) */
} tri;

/* floor(v / 16) for |v| < 2^30 (screen sub-pixels lie within +-2^18,
 * raster_draw.c's clamp_sub): v made positive by a multiple of 16 before
 * the shift, no branch. */
#define FLOOR16_BIAS ((int64_t)1 << 30)

static int64_t floor_div16(int64_t v)
{
    return (int64_t)((uint64_t)(v + FLOOR16_BIAS) >> 4) - FLOOR16_BIAS / 16;
}

/* Top-left rule for an edge of a triangle with positive area in y-down
 * screen space, from its coefficients a = -dy, b = dx: top edges are
 * horizontal going right, left edges go up. */
static int is_top_left(int64_t a, int64_t b)
{
    return a > 0 || (a == 0 && b > 0);
}

/* Inlined on the host (SPAN_FAST): three calls a triangle were 0.6 % of a
 * frame of small triangles. */
SPAN_FAST void edge_setup(edge *e, const lumo_raster_sv *p, const lumo_raster_sv *q)
{
    e->a = -((int64_t)q->y - p->y);
    e->b = (int64_t)q->x - p->x;
    e->x0 = p->x;
    e->y0 = p->y;
    e->bias = is_top_left(e->a, e->b) ? 0 : 1;
}

/* Number of significant bits of v, from the leading zeros of its words
 * (one CLZ each on the Cortex-M3; a halving search was 1.4 % of a frame of
 * small triangles on the host). */
static unsigned bit_length(uint64_t v)
{
    uint32_t hi = (uint32_t)(v >> 32), lo = (uint32_t)v;

    if (hi)
        return 64u - lumo_raster_clz32(hi);
    return lo ? 32u - lumo_raster_clz32(lo) : 0u;
}

/* Scaling shifts and the depth reciprocal. The depth z = sum e_i q_i /
 * sum e_i is linear in screen space and sum e_i is the triangle's doubled
 * area A (exactly when sh == 0; within 2 of A >> sh otherwise, 2^-22 of
 * it), so z = sum w_i q_i / (A >> sh) with a per-triangle reciprocal:
 * (sum w_i q_i) < 2^(t + 30) for t = bit length of A >> sh is shifted
 * right by zs = t - 2 to < 2^32 and multiplied by zr = 2^(32 + zs) /
 * (A >> sh) < 2^31: error below 1.5 units of Q0.30. */
SPAN_FAST void tri_scale(tri *t, const lumo_raster_sv *v, int64_t area)
{
    uint64_t qmax = v[0].q, bound, se;
    unsigned b;
    int i;

    t->sh = 0;
    while ((area >> t->sh) >= ((int64_t)1 << EDGE_BITS))
        t->sh++;
    /* Perspective weights e_i q_i are < (area >> sh) * qmax inside the
     * triangle; shifting them by qsh keeps them under 2^46, so that the
     * barycentric reciprocal below has 16 bits of headroom, while their
     * smallest sum, (area >> sh) * qmin, keeps far more than 16 significant
     * bits for any depth ratio the near plane allows. */
    for (i = 1; i < 3; i++)
        if (v[i].q > qmax) qmax = v[i].q;
    t->qsh = 0;
    for (bound = ((uint64_t)area >> t->sh) * qmax; bound >= ((uint64_t)1 << 46); bound >>= 1)
        t->qsh++;
    se = (uint64_t)area >> t->sh;
    b = bit_length(se);
    t->zs = b > 2 ? b - 2 : 0;
    t->zr = ((uint64_t)1 << (32 + t->zs)) / se;
}

/* Edges (64-bit) and tri_scale: any triangle. */
static void tri_setup(tri *t, const lumo_raster_sv *v, int64_t area)
{
    int i;

    t->v = v;
    edge_setup(&t->e[0], &v[1], &v[2]);
    edge_setup(&t->e[1], &v[2], &v[0]);
    edge_setup(&t->e[2], &v[0], &v[1]);
    for (i = 0; i < 3; i++)
        t->step[i] = t->e[i].a * 16;
    tri_scale(t, v, area);
}

/* The set-up of a small triangle (SMALL_TRI: sub-pixel extents below
 * BOX_SURE_EXTENT, doubled area below 2^EDGE_BITS, so sh == 0, and a box
 * under 2^RUN_MIN_BITS pixels wide): only what rows32_draw and the Gouraud
 * spans read, in 32-bit arithmetic (|a|, |b| and the distances of the box's
 * centres to a vertex below 2^14: every edge value below 2^29), and E, the
 * edge values at the box's first centre (sx, sy). t->e and t->step are not
 * made: nothing on that path reads them. The same values as tri_setup and
 * box_edges. */
#define SMALL_TL_SCALE ((int32_t)1 << 15)

LUMO_RASTER_HOT void edge_small(tri *t, int i, const lumo_raster_sv *p, const lumo_raster_sv *q, int32_t sx,
                                 int32_t sy, int64_t E[3])
{
    int32_t a = p->y - q->y, b = q->x - p->x;

    t->st32[i] = a * 16;
    t->dy32[i] = b * 16;
    /* !is_top_left: (a, b) <= (0, 0) in lexicographic order, the sign of
     * a 2^15 + b - 1 (|a|, |b| < 2^14), one shift (4 instructions against
     * 11 for the comparisons without branches, round five part two) */
    t->bias32[i] = (int32_t)((uint32_t)(a * SMALL_TL_SCALE + b - 1) >> 31);
    E[i] = a * (sx - p->x) + b * (sy - p->y);
}

static void tri_setup_small(tri *t, const lumo_raster_sv *v, int64_t area, int32_t sx, int32_t sy, int64_t E[3])
{
    t->v = v;
    edge_small(t, 0, &v[1], &v[2], sx, sy, E);
    edge_small(t, 1, &v[2], &v[0], sx, sy, E);
    edge_small(t, 2, &v[0], &v[1], sx, sy, E);
    tri_scale(t, v, area);
}

/* Depth value in the buffer's width; 0 is reserved for "cleared". */
static uint32_t depth16(uint64_t z30)
{
    uint64_t z = z30 >> 14;
    return z == 0 ? 1u : z > 0xFFFFu ? 0xFFFFu : (uint32_t)z;
}

static uint32_t depth32(uint64_t z30)
{
    uint64_t z = z30 << 2;
    return z == 0 ? 1u : z > 0xFFFFFFFFu ? 0xFFFFFFFFu : (uint32_t)z;
}

/* The pixel's perspective weights w_i q_i and its depth in Q0.30. */
LUMO_RASTER_HOT uint64_t pixel_depth(const tri *t, const int64_t E[3], uint64_t p[3])
{
    int i;

    for (i = 0; i < 3; i++)
        p[i] = (uint64_t)(uint32_t)((uint64_t)E[i] >> t->sh) * t->v[i].q;   /* < 2^54 */
    return ((uint64_t)(uint32_t)((p[0] + p[1] + p[2]) >> t->zs) * (uint32_t)t->zr) >> 32;
}

/* Perspective-correct barycentrics b_i = e_i q_i / sum e_j q_j in Q0.16,
 * b1 and b2 from one reciprocal (each exact or one below). */
static inline void pixel_bary(const tri *t, const int64_t E[3], uint64_t p[3], uint32_t b[3])
{
    uint64_t ps, r;
    int i;

    for (i = 0; i < 3; i++)
        p[i] >>= t->qsh;
    ps = p[0] + p[1] + p[2];
    if (ps == 0) {                           /* only at a vertex of weight 0 */
        for (i = 0; i < 3; i++)
            p[i] = (uint64_t)E[i] >> t->sh;
        ps = p[0] + p[1] + p[2];
        if (ps == 0)
            ps = p[0] = 1;
    }
    r = ((uint64_t)1 << 62) / ps;
    b[1] = (uint32_t)((p[1] * r) >> (62 - BARY_BITS));
    b[2] = (uint32_t)((p[2] * r) >> (62 - BARY_BITS));
    b[0] = (1u << BARY_BITS) - b[1] - b[2];
}

/* The covered run of a row from the edge values at its first pixel, in
 * 32-bit integers (the cheap case on a 32-bit MCU: every edge value of the
 * row within +-2^30). Each edge covers a half-line of the row (e + k s >=
 * bias for k >= or <= a bound), so the run is their intersection, found by
 * one 32-bit division per slanted edge instead of a scan over the pixels:
 * the same run as scanning (the first covered pixel, then up to the first
 * uncovered one). |s| = 16 |a| < 2^23 (the guard band), so b - e + s stays
 * in 32 bits. run32: the run [*lo, returned] of pixels 0..len of the
 * row (empty when *lo is greater); run_32: *x0 = first covered pixel,
 * return the last one, or x0 - 1 when none. */
/* One edge's bound on the run [*lo, *hi]; 0 when it leaves the row
 * uncovered. */
LUMO_RASTER_HOT int run32_edge(int32_t e, int32_t st, int32_t b, int32_t len, int32_t *lo, int32_t *hi)
{
    if (st > 0) {
        if (e < b) {
            int32_t k = (b - e + st - 1) / st;              /* first k with e + k st >= b */
            if (k > len)
                return 0;                                 /* past the box: none */
            if (k > *lo) *lo = k;
        }
    } else if (e < b) {
        return 0;                                         /* never covered in this row */
    } else if (st < 0) {
        int32_t k = (e - b) / -st;                        /* last k with e + k st >= b */
        if (k < *hi) *hi = k;
    }
    return 1;
}

/* The three edges written out (a loop over them was 3 instructions an
 * edge of a row on the host: 1.3 M a frame of small triangles), inlined
 * into rows32_draw's row loop and run_32 (79.3 -> 77.6 M a frame of small
 * triangles, three rows a triangle). */
LUMO_RASTER_HOT int32_t run32(const tri *t, const int32_t E[3], int32_t len, int32_t *lo)
{
    int32_t hi = len;

    *lo = 0;
    if (!run32_edge(E[0], t->st32[0], t->bias32[0], len, lo, &hi)
        || !run32_edge(E[1], t->st32[1], t->bias32[1], len, lo, &hi)
        || !run32_edge(E[2], t->st32[2], t->bias32[2], len, lo, &hi)) {
        *lo = 0;
        return -1;
    }
    return *lo > hi ? *lo - 1 : hi;
}

static int64_t run_32(const tri *t, const int64_t E[3], int64_t px0, int64_t px1, int64_t *x0)
{
    int32_t e[3], lo, hi;

    e[0] = (int32_t)E[0], e[1] = (int32_t)E[1], e[2] = (int32_t)E[2];
    hi = run32(t, e, (int32_t)(px1 - px0), &lo);
    *x0 = px0 + lo;
    return px0 + hi;
}

/* The same in 64-bit integers, for any triangle. */
static int64_t run_64(const tri *t, const int64_t E[3], int64_t px0, int64_t px1, int64_t *x0)
{
    int64_t G[3], px;
    int i;

    for (i = 0; i < 3; i++)
        G[i] = E[i];
    for (px = px0; px <= px1; px++) {
        if (G[0] >= t->e[0].bias && G[1] >= t->e[1].bias && G[2] >= t->e[2].bias)
            break;
        for (i = 0; i < 3; i++)
            G[i] += t->step[i];
    }
    *x0 = px;
    if (px > px1)
        return px - 1;
    for (px++, i = 0; i < 3; i++)
        G[i] += t->step[i];
    for (; px <= px1; px++) {
        if (G[0] < t->e[0].bias || G[1] < t->e[1].bias || G[2] < t->e[2].bias)
            break;
        for (i = 0; i < 3; i++)
            G[i] += t->step[i];
    }
    return px - 1;
}

static int fits_30(int64_t v)
{
    return v < ((int64_t)1 << 30) && v > -((int64_t)1 << 30);
}

/* Vertices whose sub-pixel extents are both below 2^14 bound every edge
 * value of their box: |a|, |b| and the distances |x - x0|, |y - y0| of a
 * pixel centre of the box to a vertex are all below 2^14, so |E| < 2^29
 * and box_edges' corner tests would all pass (most triangles of a mesh:
 * the tests are skipped for them). */
#define BOX_SURE_EXTENT ((int64_t)1 << 14)

/* The edge values at pixel (px0, py0), and whether every value of the
 * pixel box [px0, px1] x [py0, py1] lies within +-2^30: E is linear, so its
 * extremes over the box are at the box's corners (not tested when `sure`,
 * BOX_SURE_EXTENT). */
static int box_edges(const tri *t, int64_t px0, int64_t px1, int64_t py0, int64_t py1, int sure, int64_t E[3])
{
    int64_t sy = py0 * 16 + 8, sx = px0 * 16 + 8;
    int small = 1, i;

    for (i = 0; i < 3; i++)
        E[i] = t->e[i].a * (sx - t->e[i].x0) + t->e[i].b * (sy - t->e[i].y0);
    if (sure)
        return 1;
    for (i = 0; i < 3; i++) {
        int64_t dx = t->step[i] * (px1 - px0), dy = t->e[i].b * 16 * (py1 - py0);
        small &= fits_30(E[i]) && fits_30(E[i] + dx) && fits_30(E[i] + dy) && fits_30(E[i] + dx + dy);
    }
    return small;
}

/* A row's covered span [*x0, *x1] from the edge values at its pixel px0
 * (E: in, then the values at *x0); 0 if none. small: box_edges' answer. */
static int row_span(const tri *t, int64_t px0, int64_t px1, int small, int64_t E[3],
                    int64_t *x0, int64_t *x1)
{
    int i;

    *x1 = small ? run_32(t, E, px0, px1, x0) : run_64(t, E, px0, px1, x0);
    if (*x1 < *x0)
        return 0;
    for (i = 0; i < 3; i++)
        E[i] += t->step[i] * (*x0 - px0);
    return 1;
}

/* ---- spans by kind ------------------------------------------------------- */

/* 1 when the pixel passes the depth test (and its depth is stored). */
LUMO_RASTER_HOT int depth_pass(const lumo_raster_target *tg, size_t at, uint64_t z30)
{
    if (tg->depth_bits == 16) {
        uint16_t *d = (uint16_t *)tg->depth + at;
        uint32_t dz = depth16(z30);
        if (dz <= *d)
            return 0;
        *d = (uint16_t)dz;
        return 1;
    } else {
        uint32_t *d = (uint32_t *)tg->depth + at;
        uint32_t dz = depth32(z30);
        if (dz <= *d)
            return 0;
        *d = dz;
        return 1;
    }
}

/* Depth only: shadow maps (16-bit: the loop as it was, no width test per
 * pixel) and the depth-first pass (either width, through depth_pass). */
static void span_depth(const lumo_raster_ctx *c, const tri *t, int64_t E[3], int64_t x0,
                       int64_t x1, size_t row)
{
    uint16_t *d = (uint16_t *)c->target->depth + row;
    uint64_t p[3];
    int64_t x;
    int i;

    if (c->target->depth_bits != 16) {
        for (x = x0; x <= x1; x++) {
            (void)depth_pass(c->target, row + (size_t)x, pixel_depth(t, E, p));
            for (i = 0; i < 3; i++)
                E[i] += t->step[i];
        }
        return;
    }
    for (x = x0; x <= x1; x++) {
        uint32_t dz = depth16(pixel_depth(t, E, p));
        if (dz > d[x])
            d[x] = (uint16_t)dz;
        for (i = 0; i < 3; i++)
            E[i] += t->step[i];
    }
}

/* b0 a0 + b1 a1 + b2 a2 rounded (b_i >= 0, sum 2^16: a convex combination,
 * within [min a, max a]); the sum is made positive by 2^48 before the
 * shift, so no negative value is shifted. */
static int32_t lerp3(int32_t a0, int32_t a1, int32_t a2, const uint32_t b[3])
{
    int64_t s = (int64_t)a0 * b[0] + (int64_t)a1 * b[1] + (int64_t)a2 * b[2];
    uint64_t u = (uint64_t)(s + ((int64_t)1 << 48) + (1 << (BARY_BITS - 1))) >> BARY_BITS;

    return (int32_t)((int64_t)u - ((int64_t)1 << (48 - BARY_BITS)));
}

/* Per-pixel lighting: position, normal, albedo (and the per-vertex
 * indirect light when the mesh carries it) interpolated, shaded, tone
 * mapped. */
static void shade_pixel(const lumo_raster_ctx *c, const tri *t, const uint32_t b[3], unsigned code[3])
{
    int32_t var[LUMO_RASTER_MAX_VARYINGS];
    lumo_q1_14 n[3], rho[3];
    lumo_uq16_16 e[3], l[3];
    unsigned i;

    for (i = 0; i < c->nvar; i++)
        var[i] = lerp3(t->v[0].var[i], t->v[1].var[i], t->v[2].var[i], b);
    lumo_raster_renormalize_q14(&var[3], n);
    lumo_raster_face_viewer(c->view, var, n, n);
    for (i = 0; i < 3; i++)
        rho[i] = (lumo_q1_14)(var[6 + i] < 0 ? 0 : var[6 + i] > LUMO_Q14_ONE ? LUMO_Q14_ONE : var[6 + i]);
    lumo_raster_shade_point(c->scene, var, n, c->nvar > LUMO_RASTER_VAR_PIXEL ? &var[9] : NULL, e);
    lumo_raster_radiance(e, rho, l);
    for (i = 0; i < 3; i++)
        code[i] = lumo_raster_srgb_code((uint64_t)lumo_raster_exposed(l[i], c->scene->exposure));
}

/* Per-vertex lighting, exact at one pixel: its depth (Q0.30) and the
 * exposed radiance (UQ8.24) interpolated with perspective. The vertices'
 * radiance lies in [0, 2^30] (capped when the vertex is made, raster_draw.c,
 * and clipping interpolates), so the convex combination does too: no clamp
 * per evaluation. */
static uint32_t gouraud_at(const tri *t, const int64_t E[3], int32_t c[3])
{
    const int32_t *v0 = t->v[0].var, *v1 = t->v[1].var, *v2 = t->v[2].var;
    const uint64_t cap = (uint64_t)1 << 30;
    uint64_t p[3], z = pixel_depth(t, E, p);
    uint32_t b[3];
    int i;

    pixel_bary(t, E, p, b);
    for (i = 0; i < 3; i++) {
        uint64_t s = (uint64_t)(uint32_t)v0[i] * b[0] + (uint64_t)(uint32_t)v1[i] * b[1]
                   + (uint64_t)(uint32_t)v2[i] * b[2];
        c[i] = (int32_t)((s + (1u << (BARY_BITS - 1))) >> BARY_BITS);
    }
    return (uint32_t)(z > cap ? cap : z);
}

/* The depth and perspective barycentrics (Q0.31) of one pixel of a
 * triangle whose edge values fit 32 bits unscaled (edges32), in the
 * Cortex-M3's own arithmetic; gouraud_at32 is gouraud_at from them, the
 * radiance a convex combination. The same depth as pixel_depth (one
 * 32 x 32 multiply per weight), and the perspective barycentrics
 * b_i = e_i q_i / sum e_j q_j from the weights' top 32 bits (sum
 * normalised by one CLZ: it is below 2^62) and a reciprocal r = 2^63 / d
 * of the sum's top 32 bits d: one 32-bit division gives r0 = 2^48 / d to
 * 16 bits (the division by d's top 16 bits is up to 4 above it: 5 below,
 * so that 0 < e = 2^48 - d r0 <= 6 d), one Newton step r = 2^15 r0 +
 * r0 e / 2^33 the rest (relative error below 2^-26, from below:
 * b_1 + b_2 <= 1), where gouraud_at truncates b to Q0.16 and calls
 * a 64-bit division. The radiance b_0 c_0 + b_1 c_1 + b_2 c_2 is a convex
 * combination of values in [0, 2^30]: no clamp. A sum below 2^32 (a
 * sub-pixel triangle, or a vertex of weight 0) takes gouraud_at. */
/* b0 a0 + b1 a1 + b2 a2 rounded, a_i in [0, 2^30], b_i in Q0.31 summing to
 * at most 1. */
LUMO_RASTER_HOT int32_t convex3(int32_t a0, int32_t a1, int32_t a2, uint32_t b0, uint32_t b1, uint32_t b2)
{
    return (int32_t)(((uint64_t)(uint32_t)a0 * b0 + (uint64_t)(uint32_t)a1 * b1 + (uint64_t)(uint32_t)a2 * b2
                      + ((uint64_t)1 << 30)) >> 31);
}

/* The depth (Q0.30) from the sum ps of a pixel's weights e_i q_i (below
 * 2^62) as pixel_depth finds it: the per-triangle reciprocal. */
LUMO_RASTER_HOT uint32_t depth_of_sum(const tri *t, uint64_t ps)
{
    return (uint32_t)(((uint64_t)(uint32_t)(ps >> t->zs) * (uint32_t)t->zr) >> 32);
}

/* bary32's depth alone (capped at 2^30): three products, no division. */
LUMO_RASTER_HOT uint32_t depth32_at(const tri *t, const int32_t E[3])
{
    uint32_t z = depth_of_sum(t, (uint64_t)(uint32_t)E[0] * t->v[0].q + (uint64_t)(uint32_t)E[1] * t->v[1].q
                                 + (uint64_t)(uint32_t)E[2] * t->v[2].q);

    return z > ((uint32_t)1 << 30) ? (uint32_t)1 << 30 : z;
}

/* Inlined into its two callers (gouraud_at32, vary_at32) on the host
 * (SPAN_FAST): the call and its saved registers were 2.8 M of a frame's
 * 83.6 M on a mesh of small triangles (docs/benchmarks.md, round five). */
SPAN_FAST uint32_t bary32(const tri *t, const int32_t E[3], uint32_t b[3])
{
    uint64_t p1 = (uint64_t)(uint32_t)E[1] * t->v[1].q, p2 = (uint64_t)(uint32_t)E[2] * t->v[2].q;
    uint64_t ps = (uint64_t)(uint32_t)E[0] * t->v[0].q + p1 + p2, r;
    uint32_t hi = (uint32_t)(ps >> 32), d, r0, z;
    unsigned sh;

    if (hi == 0) {
        int64_t e[3];
        uint64_t p[3];
        e[0] = E[0], e[1] = E[1], e[2] = E[2];
        z = (uint32_t)pixel_depth(t, e, p);
        pixel_bary(t, e, p, b);
        b[0] <<= 31 - BARY_BITS, b[1] <<= 31 - BARY_BITS, b[2] <<= 31 - BARY_BITS;
    } else {
        z = depth_of_sum(t, ps);
        sh = lumo_raster_clz32(hi);                  /* 2..31 */
        d = (hi << sh) | ((uint32_t)ps >> (32 - sh));    /* [2^31, 2^32) */
        r0 = 0xFFFFFFFFu / (d >> 16) - 5u;
        r = ((uint64_t)r0 << 15) + (((uint64_t)r0 * (((uint64_t)1 << 48) - (uint64_t)d * r0)) >> 33);
        b[1] = (uint32_t)(((uint64_t)(((uint32_t)(p1 >> 32) << sh) | ((uint32_t)p1 >> (32 - sh))) * r) >> 32);
        b[2] = (uint32_t)(((uint64_t)(((uint32_t)(p2 >> 32) << sh) | ((uint32_t)p2 >> (32 - sh))) * r) >> 32);
        b[0] = ((uint32_t)1 << 31) - b[1] - b[2];
    }
    return z > ((uint32_t)1 << 30) ? (uint32_t)1 << 30 : z;
}

/* Inlined at span_gouraud32's two evaluations (a piece's start and end) on
 * the host (SPAN_FAST): 80.8 -> 79.3 M a frame of small triangles. */
SPAN_FAST uint32_t gouraud_at32(const tri *t, const int32_t E[3], int32_t c[3])
{
    const int32_t *v0 = t->v[0].var, *v1 = t->v[1].var, *v2 = t->v[2].var;
    uint32_t b[3], z = bary32(t, E, b);

    c[0] = convex3(v0[0], v1[0], v2[0], b[0], b[1], b[2]);
    c[1] = convex3(v0[1], v1[1], v2[1], b[0], b[1], b[2]);
    c[2] = convex3(v0[2], v1[2], v2[2], b[0], b[1], b[2]);
    return z;
}

/* The varyings of any sign at one pixel of an edges32 triangle whose
 * varyings differ by less than 2^30 between its vertices (pixel32_ok):
 * v_0 + b_1 (v_1 - v_0) + b_2 (v_2 - v_0) rounded, from bary32, for the
 * groups of three listed (the others are the same at every vertex). */
static uint32_t vary_at32(const tri *t, const int32_t E[3], const unsigned *group, unsigned ngroups,
                          int32_t out[])
{
    const int32_t *v0 = t->v[0].var, *v1 = t->v[1].var, *v2 = t->v[2].var;
    uint32_t b[3], z = bary32(t, E, b);
    unsigned g, i;

    /* |v_j - v_0| < 2^30 and b < 2^31: the sum lies within +-2^62, made
     * positive by 2^62 before the rounding shift */
    for (g = 0; g < ngroups; g++)
        for (i = group[g]; i < group[g] + 3; i++)
            out[i] = v0[i] + (int32_t)((int64_t)((uint64_t)((int64_t)(v1[i] - v0[i]) * b[1]
                                                            + (int64_t)(v2[i] - v0[i]) * b[2]
                                                            + ((int64_t)1 << 62) + ((int64_t)1 << 30)) >> 31)
                                       - ((int64_t)1 << 31));
    return z;
}

/* Gouraud runs: radiance exact (perspective-correct) at both ends of a run
 * and stepped linearly between, so the run's length bounds the error: over
 * L pixels 1/w changes by r = L |d(1/w)/dx| / (1/w)_min, and the linear
 * steps miss the perspective-correct values by below r / 4 of the change
 * of radiance along the run. Runs are 16 pixels, longer (up to 2048: a
 * whole row) while r <= 2^-RUN_PERSPECTIVE_BITS, from bit lengths (a
 * function of the triangle alone, so bands still give the frame's bytes):
 * a wall facing the camera is one run per row, and each run costs two
 * exact evaluations (64-bit products and a 64-bit division, which a
 * Cortex-M3 does in software). */
#define RUN_MIN_BITS 4
#define RUN_MAX_BITS 11
#define RUN_PERSPECTIVE_BITS 7
/* Per-pixel pieces step the position and normal that the lights are
 * evaluated from: 8 pixels at least, longer while 1/w changes by at most
 * 2^-9 along them (default package, 320x240, against exact varyings at
 * every pixel: mean dE 0.058 with these, 0.120 with the Gouraud pieces'
 * 16 pixels and 2^-7, 0.032 with 4 pixels; docs/rasterizer.md). */
#define PIXEL_MIN_BITS 3
#define PIXEL_PERSPECTIVE_BITS 9

static unsigned gouraud_run_bits(const tri *t, int64_t area, int min_bits, int persp_bits)
{
    int64_t num = 0;
    uint64_t qmin = t->v[0].q;
    int i, k;

    for (i = 0; i < 3; i++) {
        num += t->step[i] * (int64_t)t->v[i].q;        /* |step| < 2^23, q <= 2^30 */
        if (t->v[i].q < qmin)
            qmin = t->v[i].q;
    }
    if (num < 0)
        num = -num;
    /* num 2^k 2^RUN_PERSPECTIVE_BITS <= area qmin, conservatively */
    k = (int)bit_length((uint64_t)area) + (int)bit_length(qmin) - 2 - persp_bits
      - (int)bit_length((uint64_t)num);
    return k < min_bits ? (unsigned)min_bits : k > RUN_MAX_BITS ? RUN_MAX_BITS : (unsigned)k;
}

/* (to - from) / n rounded towards zero, n in [1, 2^RUN_MAX_BITS). */
static int32_t seg_step(int32_t from, int32_t to, int32_t n)
{
    return (to - from) / n;
}

/* Depth value of z (Q0.30, in [0, 2^30]) in 16 or 32 bits, 0 kept for
 * "cleared": depth16 and depth32 in 32-bit arithmetic. With `plain` the
 * caller knows z in [2^14, 2^30) (both ends of the run are, and the steps
 * stay between them), where both are a shift. */
LUMO_RASTER_HOT uint32_t depth_of(uint32_t z, int d16, int plain)
{
    if (plain)
        return d16 ? z >> 14 : z << 2;
    if (d16)
        return z >= ((uint32_t)1 << 30) ? 0xFFFFu : (z >> 14) | ((z >> 14) == 0);
    return z >= ((uint32_t)1 << 30) ? 0xFFFFFFFFu : (z << 2) | (z == 0);
}

/* The sRGB code of a run's value v (the radiance plus half a code-table
 * segment, lumo_raster_srgb_near), clamped to 1.0 unless the run's values
 * are known below it (`plain`). */
LUMO_RASTER_HOT unsigned run_code(uint32_t v, int plain)
{
    const uint32_t one = (uint32_t)1 << 24;

    return lumo_raster_srgb_near(plain || v < one ? v : one);
}

/* One pixel of a Gouraud run: the depth test, then (passed) the depth,
 * three code look-ups and the pixel; 1 when written. r, g, b carry the
 * code table's half step (lumo_raster_srgb_near). */
LUMO_RASTER_HOT uint32_t run_pixel(uint8_t *d, uint8_t *line, const uint8_t *bayer, int x, uint32_t z, uint32_t r,
                                   uint32_t g, uint32_t b, int rgb565, int d16, int plain)
{
    uint32_t dv = depth_of(z, d16, plain);
    unsigned cr, cg, cb;

    if (d16 ? dv <= *(uint16_t *)(void *)d : dv <= *(uint32_t *)(void *)d)
        return 0;
    if (d16)
        *(uint16_t *)(void *)d = (uint16_t)dv;
    else
        *(uint32_t *)(void *)d = dv;
    cr = run_code(r, plain);
    cg = run_code(g, plain);
    cb = run_code(b, plain);
    if (rgb565) {
        unsigned t = bayer[x & 3];
        *(uint16_t *)(void *)line = (uint16_t)((lumo_raster_dither(cr, 31, t) << 11)
                                               | (lumo_raster_dither(cg, 63, t) << 5)
                                               | lumo_raster_dither(cb, 31, t));
    } else {
        *(uint32_t *)(void *)line = ((uint32_t)cr << 16) | ((uint32_t)cg << 8) | cb;
    }
    return 1;
}

/* The pixels of a Gouraud run in 32-bit arithmetic, inlined once per pixel
 * format (rgb565), depth width (d16) and range (plain: every depth in
 * [2^14, 2^30) and every radiance below 2^24, so neither the depth nor the
 * codes need a clamp) so that the loop holds no test but the depth test:
 * depth and radiance stepped, three code look-ups, the pixel. */
LUMO_RASTER_HOT uint32_t run_pixels(void *depth, uint8_t *line, int32_t count, int x, int y, int32_t z0,
                                    int32_t dz, const int32_t c0[3], const int32_t dc[3], int rgb565, int d16,
                                    int plain)
{
    /* Unsigned accumulators: every value the run uses lies in [0, 2^30];
     * the step past its last pixel may wrap, which unsigned arithmetic
     * defines. The steps are locals (stores to the target could alias
     * dc[] and reload them every pixel), the loop runs on the two
     * pointers, and the pixels that fail the depth test are counted
     * instead of those written (fewer registers in the loop). */
    const uint32_t half = (uint32_t)1 << (LUMO_RASTER_SRGB_NEAR_BITS - 1);
    uint32_t fails = 0, z = (uint32_t)z0, r = (uint32_t)c0[0] + half, g = (uint32_t)c0[1] + half,
             b = (uint32_t)c0[2] + half;
    const uint32_t dzu = (uint32_t)dz, dr = (uint32_t)dc[0], dg = (uint32_t)dc[1], db = (uint32_t)dc[2];
    const uint8_t *bayer = lumo_raster_bayer4[y & 3];
    uint8_t *d = (uint8_t *)depth, *end = d + (size_t)count * (d16 ? 2u : 4u);

    for (; d != end; d += d16 ? 2 : 4, line += rgb565 ? 2 : 4, x++, z += dzu, r += dr, g += dg, b += db)
        if (!run_pixel(d, line, bayer, x, z, r, g, b, rgb565, d16, plain))
            fails++;                /* a branch, not 1 - written: 2 instructions a pixel less on the board */
    return (uint32_t)count - fails;
}

/* Whether a run from (za, ca) to (zb, cb) needs no clamp (run_pixels'
 * `plain`): linear steps rounded towards zero stay between the ends. */
static int run_plain(uint32_t za, uint32_t zb, const int32_t ca[3], const int32_t cb[3])
{
    const uint32_t zlo = (uint32_t)1 << 14, zhi = (uint32_t)1 << 30;
    const uint32_t chi = ((uint32_t)1 << 24) - ((uint32_t)1 << (LUMO_RASTER_SRGB_NEAR_BITS - 1));

    return za >= zlo && zb >= zlo && za < zhi && zb < zhi
        && (uint32_t)(ca[0] | cb[0] | ca[1] | cb[1] | ca[2] | cb[2]) < chi;
}

/* run_pixels once per pixel format and depth width for the runs without
 * clamps, each its own function (called once per run): the loop gets the
 * registers to itself instead of sharing them with the triangle's set-up. */
typedef uint32_t (*run_fn)(void *depth, uint8_t *line, int32_t count, int x, int y, int32_t z, int32_t dz,
                           const int32_t c0[3], const int32_t dc[3], unsigned fmt);
#define RUN_VARIANT(name, rgb565, d16)                                                                 \
    static uint32_t name(void *depth, uint8_t *line, int32_t count, int x, int y, int32_t z, int32_t dz, \
                         const int32_t c0[3], const int32_t dc[3], unsigned fmt)                       \
    {                                                                                                  \
        (void)fmt;                                                                                     \
        return run_pixels(depth, line, count, x, y, z, dz, c0, dc, rgb565, d16, 1);                     \
    }
RUN_VARIANT(run_xrgb_d32, 0, 0)
RUN_VARIANT(run_xrgb_d16, 0, 1)
RUN_VARIANT(run_565_d32, 1, 0)
RUN_VARIANT(run_565_d16, 1, 1)

/* The runs that need clamps (a piece reaching code 255 or the depth
 * range's ends: rare) share one function, the format a run-time argument
 * (fmt: bit 0 RGB565, bit 1 16-bit depth), which keeps the image small:
 * the RP2040 port runs from its 264 KiB of SRAM. */
static uint32_t run_clamp(void *depth, uint8_t *line, int32_t count, int x, int y, int32_t z, int32_t dz,
                          const int32_t c0[3], const int32_t dc[3], unsigned fmt)
{
    return run_pixels(depth, line, count, x, y, z, dz, c0, dc, (int)(fmt & 1u), (int)(fmt >> 1), 0);
}

/* The target's fmt for run functions. */
static unsigned run_fmt(const lumo_raster_target *tg)
{
    return (tg->format == LUMO_PIXEL_RGB565 ? 1u : 0u) | (tg->depth_bits == 16 ? 2u : 0u);
}

/* The run function for a target: one per format without clamps, run_clamp
 * with them. */
static const run_fn run_fns[4] = {run_xrgb_d32, run_565_d32, run_xrgb_d16, run_565_d16};   /* by run_fmt */

static run_fn run_for(const lumo_raster_target *tg, int plain)
{
    return plain ? run_fns[run_fmt(tg)] : run_clamp;
}

/* Pixel x of the target's band row `row` (row = band row times width):
 * its depth and colour addresses. */
static void *depth_at(const lumo_raster_target *tg, size_t at)
{
    return tg->depth_bits == 16 ? (void *)((uint16_t *)tg->depth + at) : (void *)((uint32_t *)tg->depth + at);
}

static uint8_t *color_at(const lumo_raster_target *tg, uint8_t *line, int32_t x)
{
    return line + (size_t)x * (tg->format == LUMO_PIXEL_RGB565 ? 2u : 4u);
}

/* A Gouraud run of pixels [a, b] of a row (b - a < 2^run_bits): depth and
 * radiance exact (perspective-correct) at both ends and stepped linearly
 * between them, so a pixel costs additions, the depth test and three table
 * look-ups. Depth is linear in screen space (the steps only round); the
 * radiance's perspective error is bounded by the run's length (gouraud_run_bits). */
static uint32_t run_gouraud(const lumo_raster_ctx *c, const tri *t, const int64_t Ea[3], int64_t a,
                            int64_t b, int64_t y, size_t row, uint8_t *line)
{
    int64_t Eb[3];
    int32_t ca[3], cb[3], dc[3], n = (int32_t)(b - a);
    uint32_t za, zb;
    int i;

    za = gouraud_at(t, Ea, ca);
    for (i = 0; i < 3; i++)
        Eb[i] = Ea[i] + t->step[i] * n;
    zb = n ? gouraud_at(t, Eb, cb) : za;
    for (i = 0; i < 3; i++) {
        if (!n)
            cb[i] = ca[i];
        dc[i] = n ? seg_step(ca[i], cb[i], n) : 0;
    }
    return run_for(c->target, run_plain(za, zb, ca, cb))(depth_at(c->target, row + (size_t)a),
                                                           color_at(c->target, line, (int32_t)a), n + 1, (int)a,
                                                           (int)y, (int32_t)za,
                                                           n ? seg_step((int32_t)za, (int32_t)zb, n) : 0, ca, dc,
                                                           run_fmt(c->target));
}

/* Gouraud spans in runs ending at absolute multiples of 2^run_bits pixels
 * (so a run is a function of the triangle and the row: bands join exactly). */
static void span_gouraud(const lumo_raster_ctx *c, const tri *t, int64_t E[3], int64_t x0,
                         int64_t x1, int64_t y, size_t row)
{
    lumo_raster_target *tg = c->target;
    uint8_t *line = (uint8_t *)tg->color + (size_t)(y - tg->band_y) * tg->color_stride;
    uint32_t written = 0;
    int64_t a = x0;
    int i;

    while (a <= x1) {
        int64_t b = a | (((int64_t)1 << t->run_bits) - 1);
        if (b > x1)
            b = x1;
        written += run_gouraud(c, t, E, a, b, y, row, line);
        for (i = 0; i < 3; i++)
            E[i] += t->step[i] * (b - a + 1);
        a = b + 1;
    }
    if (c->stats)
        c->stats->pixels_written += written;
}

/* What the 32-bit Gouraud rows of one triangle share: the run functions
 * of the target (no clamp, clamp) and its pixel sizes. */
typedef struct rows32 {
    const lumo_raster_ctx *c;
    const tri *t;
    run_fn plain, clamp;
    unsigned dbytes, cbytes, fmt;
    int32_t mask;          /* 2^run_bits - 1 */
    /* per pixel: the groups of three varyings that differ between the
     * vertices (a group equal at all three interpolates to that value
     * exactly: it is not stepped), and the shading's constants */
    unsigned group[4], ngroups, mask_groups;
    lumo_raster_pixel_fixed pf;
    /* the per-vertex indirect light (varyings 9..11), when it differs
     * between the vertices (IND_STEPPED): affine in screen space
     * (ind_setup, ind_row) */
    uint64_t rcp;          /* affine barycentric lambda_i = E_i rcp >> rs, Q0.31 */
    unsigned rs, f;        /* f: fraction bits of the stepped values */
    int32_t d1[3], d2[3];  /* v1 - v0 and v2 - v0 of the three varyings */
    int32_t ind_step[3];   /* change per pixel, Q(f) */
    int32_t ind_dv[3];     /* the same rounded to whole units: a piece's step */
} rows32;

/* v = va + k dv for the groups of three varyings in `groups` (bit j:
 * group j): the varyings of a piece's k-th pixel, made only for the pixels
 * that pass the depth test (k dv stays between the piece's ends). */
LUMO_RASTER_HOT void piece_groups(int32_t *v, const int32_t *va, const int32_t *dv, int32_t k, unsigned groups)
{
    if (groups & 1u)
        v[0] = va[0] + k * dv[0], v[1] = va[1] + k * dv[1], v[2] = va[2] + k * dv[2];
    if (groups & 2u)
        v[3] = va[3] + k * dv[3], v[4] = va[4] + k * dv[4], v[5] = va[5] + k * dv[5];
    if (groups & 4u)
        v[6] = va[6] + k * dv[6], v[7] = va[7] + k * dv[7], v[8] = va[8] + k * dv[8];
    if (groups & 8u)
        v[9] = va[9] + k * dv[9], v[10] = va[10] + k * dv[10], v[11] = va[11] + k * dv[11];
}

/* The per-vertex indirect light of a per-pixel row (LUMO_RASTER_VAR_PIXEL_IND)
 * is interpolated affinely in screen space: linear along the whole row, so
 * it needs no exact value at the ends of the pieces, whose evaluations the
 * other varyings pay (on the Cortex-M3 that was 40 of 420 instructions a
 * covered pixel). The light is the grid's smooth term already sampled at
 * the vertices, and the error of dropping its perspective is measured in
 * docs/rasterizer.md ("IVG per vertex"). Set-up per triangle, from the
 * doubled area A = E_0 + E_1 + E_2 (exact for edges32 triangles, whose
 * inside values are 0 <= E_i <= A < 2^32): rcp = 2^(31 + rs) / A with rs
 * the bit length of A, in (2^31, 2^32], so lambda_i = E_i rcp >> rs <= 2^31
 * and E_i rcp <= 2^63; the values keep f fraction bits, f chosen so that
 * every value of the triangle, times 2^f, stays below 2^29. */
static void ind_setup(rows32 *g, const tri *t, const int64_t Erow[3])
{
    const int32_t *v0 = t->v[0].var + LUMO_RASTER_VAR_PIXEL, *v1 = t->v[1].var + LUMO_RASTER_VAR_PIXEL;
    const int32_t *v2 = t->v[2].var + LUMO_RASTER_VAR_PIXEL;
    const int64_t lim = (int64_t)1 << 32;
    uint64_t area = (uint64_t)(Erow[0] + Erow[1] + Erow[2]), most = 0;
    int64_t dl1, dl2;
    unsigned b;
    int i;

    g->rs = bit_length(area);
    g->rcp = ((uint64_t)1 << (31 + g->rs)) / (area ? area : 1);
    for (i = 0; i < 3; i++) {
        uint64_t m0 = (uint64_t)(v0[i] < 0 ? -(int64_t)v0[i] : v0[i]);
        uint64_t m1 = (uint64_t)(v1[i] < 0 ? -(int64_t)v1[i] : v1[i]);
        uint64_t m2 = (uint64_t)(v2[i] < 0 ? -(int64_t)v2[i] : v2[i]);
        most = m0 > most ? m0 : most, most = m1 > most ? m1 : most, most = m2 > most ? m2 : most;
    }
    b = bit_length(most);
    g->f = b < 29 ? 29 - b : 0;
    /* d lambda per pixel: |st| < 2^23, so |st rcp| < 2^55. Two covered
     * pixels side by side have lambdas in [0, 2^31], so |d lambda| <= 2^31
     * wherever a step is taken; a larger one (a triangle thinner than a
     * pixel) is never stepped, and its step stays 0. */
    dl1 = ((int64_t)t->st32[1] * (int64_t)g->rcp) >> g->rs;
    dl2 = ((int64_t)t->st32[2] * (int64_t)g->rcp) >> g->rs;
    if (dl1 > lim || dl1 < -lim || dl2 > lim || dl2 < -lim)
        dl1 = dl2 = 0;
    for (i = 0; i < 3; i++) {
        g->d1[i] = v1[i] - v0[i], g->d2[i] = v2[i] - v0[i];   /* |d| < 2^30: pixel32_ok */
        g->ind_step[i] = (int32_t)((dl1 * g->d1[i] + dl2 * g->d2[i] + ((int64_t)1 << (30 - g->f))) >> (31 - g->f));
        g->ind_dv[i] = (int32_t)((uint32_t)g->ind_step[i] + ((uint32_t)1 << g->f >> 1)) >> g->f;
    }
}

/* The indirect light at the row's pixel with edge values E, Q(f). */
static void ind_row(const rows32 *g, const tri *t, const int32_t E[3], int32_t w[3])
{
    const int32_t *v0 = t->v[0].var + LUMO_RASTER_VAR_PIXEL;
    /* Q0.30 (<= 2^30: 32-bit products with the differences) */
    int32_t l1 = (int32_t)(((uint64_t)(uint32_t)E[1] * g->rcp) >> (g->rs + 1));
    int32_t l2 = (int32_t)(((uint64_t)(uint32_t)E[2] * g->rcp) >> (g->rs + 1));
    int i;

    for (i = 0; i < 3; i++)
        w[i] = (int32_t)((uint32_t)v0[i] << g->f)
             + (int32_t)(((int64_t)l1 * g->d1[i] + (int64_t)l2 * g->d2[i] + ((int64_t)1 << (29 - g->f))) >> (30 - g->f));
}

/* Whether the indirect light's group changes over the triangle: then it is
 * stepped by piece_groups from ind_row's affine values. */
#define IND_STEPPED(g) ((g)->mask_groups & (1u << (LUMO_RASTER_VAR_PIXEL / 3)))

/* rows32's per-pixel fields for triangle t, Erow its edge values at one
 * pixel (ind_setup's area). */
static void pixel_groups(rows32 *g, const lumo_raster_ctx *c, const tri *t, const int64_t Erow[3])
{
    const int32_t *v0 = t->v[0].var, *v1 = t->v[1].var, *v2 = t->v[2].var;
    unsigned i, k;

    g->ngroups = 0;
    g->mask_groups = 0;
    for (i = 0; i < c->nvar; i += 3) {
        int same = 1;
        for (k = i; k < i + 3; k++)
            same &= v0[k] == v1[k] && v0[k] == v2[k];
        if (same)
            continue;
        g->mask_groups |= 1u << (i / 3);
        if (i == LUMO_RASTER_VAR_PIXEL) {   /* not evaluated at the pieces' ends */
            ind_setup(g, t, Erow);
            continue;
        }
        g->group[g->ngroups++] = i;
    }
    lumo_raster_pixel_fixed_init(&g->pf, c->view, c->scene, v0, v1, v2);
}

/* Whether pixel d fails the depth test at depth z (Q0.30): depth_of's
 * clamped form. */
LUMO_RASTER_HOT int pixel_hidden(const uint8_t *d, uint32_t z, int d16)
{
    return d16 ? depth_of(z, 1, 0) <= *(const uint16_t *)(const void *)d
               : depth_of(z, 0, 0) <= *(const uint32_t *)(const void *)d;
}

/* Whether every pixel of a one-piece span [a, x1] ((a | mask) >= x1; E
 * the edge values at a) fails the depth test: the depths its run would
 * test (bary32's at both ends, stepped by seg_step) from three products
 * each, without the barycentrics. depth_of's clamped form is the plain
 * one wherever a run may be plain (depths in [2^14, 2^30)), so the answer
 * is the run's. On the 48k dragon about 40 % of the depth tests fail
 * (round four: 145 000 tests, 84 400 pixels written a frame): a hidden
 * span needs no barycentrics and no radiance (round five). */
static int span_hidden(const rows32 *g, const int32_t E[3], int32_t a, int32_t x1, const uint8_t *drow)
{
    const tri *t = g->t;
    const int d16 = g->dbytes == 2u;
    const int32_t n = x1 - a;
    uint32_t z = depth32_at(t, E), dz;
    const uint8_t *d = drow + (size_t)a * g->dbytes, *end = d + (size_t)(n + 1) * g->dbytes;
    int32_t Eb[3];

    if (!n)                                  /* one pixel: most spans */
        return pixel_hidden(d, z, d16);
    Eb[0] = E[0] + t->st32[0] * n, Eb[1] = E[1] + t->st32[1] * n, Eb[2] = E[2] + t->st32[2] * n;
    dz = (uint32_t)seg_step((int32_t)z, (int32_t)depth32_at(t, Eb), n);
    for (; d != end; d += g->dbytes, z += dz)
        if (!pixel_hidden(d, z, d16))
            return 0;
    return 1;
}

/* A one-pixel Gouraud span (most spans of a mesh of small triangles):
 * run_pixel inlined, without the pieces' loop and the call through
 * g->plain; called from rows32_draw's loop directly (71.21 -> 70.58 M a
 * frame of small triangles with the hidden spans' skip), and kept out of
 * it (LUMO_RASTER_APART: inlined there, the loop lost 0.9 M a frame). Not on the
 * boards (-Os), whose frames have few one-pixel spans: there the test per
 * row cost 0.7 instructions a covered pixel (golden_raster), and a
 * one-pixel span takes span_gouraud32's pieces. */
#if defined(__OPTIMIZE_SIZE__)
#define ONE_PIXEL_APART 0
#else
#define ONE_PIXEL_APART 1
#endif
/* Its pixel takes run_pixel's clamped forms (plain 0): the same bytes, and
 * cheaper than run_plain's test for one pixel (-0.03 M a frame, round five
 * part two). */
LUMO_RASTER_APART uint32_t pixel_gouraud32(const rows32 *g, const int32_t E[3], int32_t a, int32_t y, uint8_t *drow,
                                uint8_t *crow)
{
    const uint32_t half = (uint32_t)1 << (LUMO_RASTER_SRGB_NEAR_BITS - 1);
    int32_t c[3];
    uint32_t z = gouraud_at32(g->t, E, c);

    return run_pixel(drow + (size_t)a * g->dbytes, crow + (size_t)a * g->cbytes, lumo_raster_bayer4[y & 3], a, z,
                     (uint32_t)c[0] + half, (uint32_t)c[1] + half, (uint32_t)c[2] + half, (int)(g->fmt & 1u),
                     (int)(g->fmt >> 1), 0);
}

/* A Gouraud span [a, x1] of an edges32 triangle in 32-bit arithmetic (a
 * hidden one-piece span never gets here: rows32_draw skips it; nor, on
 * speed-optimised builds, a one-pixel span: pixel_gouraud32), E
 * the edge values at a, drow and crow the depth and colour of the row's
 * pixel 0: the same pieces (ending at absolute multiples of 2^run_bits),
 * each stepped from its first pixel's exact value towards the next
 * piece's first pixel (the row's last pixel for the last piece), so that
 * neighbouring pieces share one exact evaluation. */
static uint32_t span_gouraud32(const rows32 *g, int32_t E[3], int32_t a, int32_t x1, int32_t y, uint8_t *drow,
                               uint8_t *crow)
{
    const tri *t = g->t;
    int32_t ca[3], cb[3], dc[3];
    uint32_t za = gouraud_at32(t, E, ca), zb, written = 0;

    while (a <= x1) {
        int32_t b = (a | g->mask) < x1 ? a | g->mask : x1, e = b < x1 ? b - a + 1 : b - a, dz = 0;
        if (e) {
            E[0] += t->st32[0] * e, E[1] += t->st32[1] * e, E[2] += t->st32[2] * e;
            zb = gouraud_at32(t, E, cb);
            dz = seg_step((int32_t)za, (int32_t)zb, e);
            dc[0] = seg_step(ca[0], cb[0], e), dc[1] = seg_step(ca[1], cb[1], e), dc[2] = seg_step(ca[2], cb[2], e);
        } else {
            zb = za, cb[0] = ca[0], cb[1] = ca[1], cb[2] = ca[2];
            dc[0] = dc[1] = dc[2] = 0;
        }
        written += (run_plain(za, zb, ca, cb) ? g->plain : g->clamp)(drow + (size_t)a * g->dbytes,
                                                                    crow + (size_t)a * g->cbytes, b - a + 1, a,
                                                                    y, (int32_t)za, dz, ca, dc, g->fmt);
        za = zb, ca[0] = cb[0], ca[1] = cb[1], ca[2] = cb[2];
        a = b + 1;
    }
    return written;
}

/* A per-pixel-lit span [a, x1] of an edges32 triangle (pixel32_ok): the
 * Gouraud pieces again, but what is stepped between the exact
 * (perspective-correct) ends is the varyings (position, normal, albedo,
 * per-vertex indirect light), and each pixel that passes the depth test
 * is shaded from them by lumo_raster_shade_pixel32. */
static uint32_t span_pixel32(const rows32 *g, int32_t E[3], int32_t a, int32_t x1, int32_t y, uint8_t *drow,
                             uint8_t *crow)
{
    const tri *t = g->t;
    const lumo_raster_ctx *c = g->c;
    const lumo_raster_target *tg = c->target;
    const unsigned nvar = c->nvar;
    const int d16 = tg->depth_bits == 16, lay = c->laying;
    int32_t va[LUMO_RASTER_MAX_VARYINGS], vb[LUMO_RASTER_MAX_VARYINGS], dv[LUMO_RASTER_MAX_VARYINGS];
    int32_t cur[LUMO_RASTER_MAX_VARYINGS], ind[3] = {0, 0, 0};
    const int32_t a0 = a;
    uint32_t za, zb, written = 0;
    unsigned i, k, code[3];

    for (i = 0; i < nvar; i++)                       /* the groups that do not change */
        cur[i] = t->v[0].var[i];
    if (IND_STEPPED(g)) {
        ind_row(g, t, E, ind);
        for (i = 0; i < 3; i++)
            dv[LUMO_RASTER_VAR_PIXEL + i] = g->ind_dv[i];
    }
    za = vary_at32(t, E, g->group, g->ngroups, va);

    while (a <= x1) {
        int32_t b = (a | g->mask) < x1 ? a | g->mask : x1, e = b < x1 ? b - a + 1 : b - a, dz = 0, x;
        uint32_t z = za;
        if (IND_STEPPED(g))                          /* the indirect light at the piece's start, affine */
            for (i = 0; i < 3; i++)
                va[LUMO_RASTER_VAR_PIXEL + i]
                    = (int32_t)((uint32_t)ind[i] + (uint32_t)(a - a0) * (uint32_t)g->ind_step[i]) >> g->f;
        if (e) {
            E[0] += t->st32[0] * e, E[1] += t->st32[1] * e, E[2] += t->st32[2] * e;
            zb = vary_at32(t, E, g->group, g->ngroups, vb);
            dz = seg_step((int32_t)za, (int32_t)zb, e);
            for (k = 0; k < g->ngroups; k++)
                for (i = g->group[k]; i < g->group[k] + 3; i++)
                    dv[i] = seg_step(va[i], vb[i], e);
        } else {
            zb = za;
            for (k = 0; k < g->ngroups; k++)
                for (i = g->group[k]; i < g->group[k] + 3; i++)
                    vb[i] = va[i], dv[i] = 0;
        }
        for (x = a; x <= b; x++, z += (uint32_t)dz) {
            uint32_t dz_x = depth_of(z, d16, 0);
            uint8_t *dp = drow + (size_t)x * g->dbytes;
            if (d16 ? dz_x > *(uint16_t *)(void *)dp : dz_x > *(uint32_t *)(void *)dp) {
                if (d16)
                    *(uint16_t *)(void *)dp = (uint16_t)dz_x;
                else
                    *(uint32_t *)(void *)dp = dz_x;
                written++;
                if (lay)
                    continue;
                piece_groups(cur, va, dv, x - a, g->mask_groups);
                lumo_raster_shade_pixel32(c->view, c->scene, &g->pf, nvar, cur, code);
                lumo_raster_put_codes(tg, crow, (int)x, (int)y, code[0], code[1], code[2]);
            }
        }
        za = zb;
        for (k = 0; k < g->ngroups; k++)
            for (i = g->group[k]; i < g->group[k] + 3; i++)
                va[i] = vb[i];
        a = b + 1;
    }
    return written;
}

/* Whether span_pixel32 may draw an edges32 triangle: its varyings differ
 * by less than 2^30 between its vertices (the interpolation's products
 * then fit 64 bits and the steps 32), and every point and spot light is
 * within 2^30 (16384 units) of its vertices per axis (add_local_light32's
 * light vector fits 32 bits; a point of the triangle is a convex
 * combination of them). Anything else takes span_color. */
static int pixel32_ok(const lumo_raster_ctx *c, const tri *t)
{
    const int64_t lim = (int64_t)1 << 30;
    const lumo_raster_scene *s = c->scene;
    uint32_t l, count = s->light_count > LUMO_MAX_LIGHTS ? LUMO_MAX_LIGHTS : s->light_count;
    unsigned i;
    int j;

    for (i = 0; i < c->nvar; i++) {
        int64_t a = t->v[0].var[i], b = t->v[1].var[i], d = t->v[2].var[i];
        if (a - b >= lim || b - a >= lim || a - d >= lim || d - a >= lim || b - d >= lim || d - b >= lim)
            return 0;
    }
    for (l = 0; l < count; l++) {
        if (s->lights[l].kind == LUMO_LIGHT_DIRECTIONAL)
            continue;
        for (j = 0; j < 3; j++)
            for (i = 0; i < 3; i++) {
                int64_t d = (int64_t)s->lights[l].pos[i] - t->v[j].var[i];
                if (d >= lim || d <= -lim)
                    return 0;
            }
    }
    return 1;
}

/* Which per-pixel rows a triangle takes, from its doubled area alone (so
 * the host and every board make the same choice, and the depth-first pass
 * lays each triangle's depth through the rows its colour pass uses): one
 * of at least 2^PIXEL_MIN_BITS pixels (one minimum piece) takes the 32-bit
 * piece rows (span_pixel32), a smaller one the exact rows (span_color).
 * Under a piece's worth of pixels the pieces' per-triangle shading
 * constants and two exact piece ends per row cost more than they save on
 * the host, where the exact rows' 64-bit divisions are one instruction
 * each (dragon 48k 640x480 per pixel, callgrind: 596 -> 491 M a frame;
 * the same for any bound from 8 to 1024 pixels, 1 % more at 4;
 * docs/benchmarks.md "Round five"). Doubled area in 1/16 pixel units: 512
 * per pixel. */
#define PIXEL32_MIN_AREA (((int64_t)1 << PIXEL_MIN_BITS) * 512)

/* Whether an edges32 triangle takes span_pixel32 (large enough and
 * pixel32_ok), and then its pieces' length. */
static int pixel32_pieces(const lumo_raster_ctx *c, tri *t, int64_t area)
{
    if (area < PIXEL32_MIN_AREA || !pixel32_ok(c, t))
        return 0;
    t->run_bits = gouraud_run_bits(t, area, PIXEL_MIN_BITS, PIXEL_PERSPECTIVE_BITS);
    return 1;
}

/* The rows of an edges32 triangle (every triangle of a board's frame) in
 * 32-bit arithmetic: edge values stepped from row to row, the run of each
 * row from run32, its pixels from `span` (span_gouraud32 or span_pixel32). */
typedef uint32_t (*span32_fn)(const rows32 *g, int32_t E[3], int32_t a, int32_t x1, int32_t y, uint8_t *drow,
                              uint8_t *crow);

SPAN_FAST void rows32_draw(const lumo_raster_ctx *c, const tri *t, const int64_t Erow[3], int32_t px0,
                        int32_t px1, int32_t py0, int32_t py1, span32_fn span)
{
    const lumo_raster_target *tg = c->target;
    int32_t e0, e1, e2, dy0, dy1, dy2, py;
    uint32_t written = 0;
    lumo_raster_stats *const stats = c->stats;
    uint8_t *drow, *crow;
    size_t dstride, cstride;
    rows32 g;

    g.c = c;
    g.t = t;
    g.fmt = run_fmt(tg);              /* once: the sizes and run functions follow from it */
    g.plain = run_fns[g.fmt];
    g.clamp = run_clamp;
    g.dbytes = g.fmt & 2u ? 2u : 4u;
    g.cbytes = g.fmt & 1u ? 2u : 4u;
    g.mask = ((int32_t)1 << t->run_bits) - 1;
    if (span == span_pixel32 && c->laying)
        g.ngroups = 0, g.mask_groups = 0;   /* the depth-first pass: depth at the same ends, nothing to shade */
    else if (span == span_pixel32)
        pixel_groups(&g, c, t, Erow);
    drow = (uint8_t *)tg->depth + (size_t)(py0 - tg->band_y) * tg->width * g.dbytes;
    crow = (uint8_t *)tg->color + (size_t)(py0 - tg->band_y) * tg->color_stride;
    /* the row's edge values and their steps in scalars, not arrays: GCC
     * -O2 put the arrays in vector registers and shuffled them every row
     * (round five part two) */
    e0 = (int32_t)Erow[0], e1 = (int32_t)Erow[1], e2 = (int32_t)Erow[2];
    dy0 = t->dy32[0], dy1 = t->dy32[1], dy2 = t->dy32[2];
    /* the row strides in locals: the spans' stores could alias *tg */
    dstride = (size_t)tg->width * g.dbytes, cstride = tg->color_stride;
    for (py = py0; py <= py1; py++, e0 += dy0, e1 += dy1, e2 += dy2, drow += dstride, crow += cstride) {
        int32_t E[3], lo, hi;
        E[0] = e0, E[1] = e1, E[2] = e2;
        hi = run32(t, E, px1 - px0, &lo);
        if (hi < lo)
            continue;
        E[0] = e0 + t->st32[0] * lo, E[1] = e1 + t->st32[1] * lo, E[2] = e2 + t->st32[2] * lo;
        if (stats)                /* a test, not a sum kept for nothing: 0.17 M a frame, round five part two */
            stats->pixels_tested += (uint32_t)(hi - lo + 1);
        /* a hidden one-piece Gouraud span is skipped here, before its call
         * (71.21 -> 70.91 M a frame of small triangles, round five) */
        if (span == span_gouraud32 && ((px0 + lo) | g.mask) >= px0 + hi
            && span_hidden(&g, E, px0 + lo, px0 + hi, drow))
            continue;
        if (ONE_PIXEL_APART && span == span_gouraud32 && hi - lo < 2) {
            written += pixel_gouraud32(&g, E, px0 + lo, py, drow, crow);
            if (hi == lo)
                continue;
            E[0] += t->st32[0], E[1] += t->st32[1], E[2] += t->st32[2];
            written += pixel_gouraud32(&g, E, px0 + hi, py, drow, crow);
        } else
            written += span(&g, E, px0 + lo, px0 + hi, py, drow, crow);
    }
    if (stats)
        stats->pixels_written += written;
}

/* rows32_draw once per span kind (the tests of `span` in its row loop are
 * then folded away on the host, where SPAN_FAST inlines it; one function
 * under -Os): raster_peers 64.88 -> 64.54 M a frame (round five part two). */
LUMO_RASTER_APART void rows32_gouraud(const lumo_raster_ctx *c, const tri *t, const int64_t Erow[3], int32_t px0,
                               int32_t px1, int32_t py0, int32_t py1)
{
    rows32_draw(c, t, Erow, px0, px1, py0, py1, span_gouraud32);
}

LUMO_RASTER_APART void rows32_pixel(const lumo_raster_ctx *c, const tri *t, const int64_t Erow[3], int32_t px0,
                             int32_t px1, int32_t py0, int32_t py1)
{
    rows32_draw(c, t, Erow, px0, px1, py0, py1, span_pixel32);
}

/* Per-pixel colour spans: depth test, barycentrics, shading, pixel. */
static void span_color(const lumo_raster_ctx *c, const tri *t, int64_t E[3], int64_t x0,
                       int64_t x1, int64_t y, size_t row)
{
    lumo_raster_target *tg = c->target;
    uint8_t *line = (uint8_t *)tg->color + (size_t)(y - tg->band_y) * tg->color_stride;
    uint32_t written = 0;
    uint64_t p[3];
    uint32_t b[3];
    unsigned code[3];
    int64_t x;
    int i;

    for (x = x0; x <= x1; x++) {
        if (depth_pass(tg, row + (size_t)x, pixel_depth(t, E, p))) {
            pixel_bary(t, E, p, b);
            shade_pixel(c, t, b, code);
            lumo_raster_put_codes(tg, line, (int)x, (int)y, code[0], code[1], code[2]);
            written++;
        }
        for (i = 0; i < 3; i++)
            E[i] += t->step[i];
    }
    if (c->stats)
        c->stats->pixels_written += written;
}

/* A Gouraud triangle that tri_setup_small may set up: what tri_setup,
 * box_edges and the choice of run_bits would find for it is edges32 and
 * RUN_MIN_BITS (most triangles of a mesh at a usual size: every one of
 * the 45 934 a frame with a non-empty box of the 48k dragon at 640x480). */
#define SMALL_TRI(c, sure, area, w) \
    ((c)->nvar == LUMO_RASTER_VAR_GOURAUD && !(c)->depth_only && (sure) \
     && (area) < ((int64_t)1 << EDGE_BITS) && (w) < (1 << RUN_MIN_BITS))

/* Whether every pixel of the box [px0, px1] x [py0, py1] holds a depth
 * that a pixel of depth z (Q0.30) would fail: no pixel of a triangle whose
 * vertices' q are at most z can then pass (its depths are convex
 * combinations of the q, and depth_of_sum's roundings are all downward,
 * so no pixel's depth exceeds the largest q). */
static int box_hidden(const lumo_raster_target *tg, uint32_t z, int32_t px0, int32_t px1, int32_t py0, int32_t py1)
{
    const int d16 = tg->depth_bits == 16;
    const uint32_t dv = depth_of(z, d16, 0);
    int32_t x, y;

    /* the comparison written here rather than through pixel_hidden: typed
     * loads by index are 2 M instructions a frame cheaper than its byte
     * pointers on this path (raster_peers 54.2 -> 56.3 M) */
    for (y = py0; y <= py1; y++) {
        size_t at = (size_t)(y - tg->band_y) * tg->width;
        for (x = px0; x <= px1; x++)
            if (dv > (d16 ? ((const uint16_t *)tg->depth)[at + (size_t)x] : ((const uint32_t *)tg->depth)[at + (size_t)x]))
                return 0;
    }
    return 1;
}

LUMO_RASTER_HOT int32_t min3_32(int32_t a, int32_t b, int32_t c)
{
    int32_t m = a < b ? a : b;

    return m < c ? m : c;
}

LUMO_RASTER_HOT int32_t max3_32(int32_t a, int32_t b, int32_t c)
{
    int32_t m = a > b ? a : b;

    return m > c ? m : c;
}

LUMO_RASTER_HOT uint32_t max3_u32(uint32_t a, uint32_t b, uint32_t c)
{
    uint32_t m = a > b ? a : b;

    return m > c ? m : c;
}

/* Rasterize one screen triangle with positive area. */
void lumo_raster_triangle(const lumo_raster_ctx *c, const lumo_raster_sv *v, int64_t area)
{
    const lumo_raster_target *tg = c->target;
    int64_t minx, maxx, miny, maxy, px0, px1, py0, py1, py, Erow[3];
    tri t;
    int i, small, sure;

    /* scalars, not a loop over the vertices: GCC -O2 loaded x and y in
     * pairs into vector registers and shuffled them (round five part two) */
    minx = min3_32(v[0].x, v[1].x, v[2].x), maxx = max3_32(v[0].x, v[1].x, v[2].x);
    miny = min3_32(v[0].y, v[1].y, v[2].y), maxy = max3_32(v[0].y, v[1].y, v[2].y);
    /* Pixel centres (16 p + 8) inside the bounding box, within the band. */
    px0 = floor_div16(minx - 8 + 15);
    px1 = floor_div16(maxx - 8);
    py0 = floor_div16(miny - 8 + 15);
    py1 = floor_div16(maxy - 8);
    if (px0 < 0) px0 = 0;
    if (px1 > (int64_t)tg->width - 1) px1 = (int64_t)tg->width - 1;
    if (py0 < tg->band_y) py0 = tg->band_y;
    if (py1 > (int64_t)tg->band_y + tg->band_rows - 1) py1 = (int64_t)tg->band_y + tg->band_rows - 1;
    if (px0 > px1 || py0 > py1)
        return;
    if (c->stats)
        c->stats->tris_drawn++;
    sure = maxx - minx < BOX_SURE_EXTENT && maxy - miny < BOX_SURE_EXTENT;
    if (SMALL_TRI(c, sure, area, px1 - px0)) {
        /* hidden where it is drawn: nothing to set up (20 740 of the 45 934
         * small triangles a frame of the 48k dragon: 62.86 -> 54.20 M a
         * frame, docs/benchmarks.md round five part two); not with stats,
         * which count the covered pixels */
        if (!c->stats && box_hidden(tg, max3_u32(v[0].q, v[1].q, v[2].q), (int32_t)px0, (int32_t)px1, (int32_t)py0,
                                    (int32_t)py1))
            return;
        tri_setup_small(&t, v, area, (int32_t)px0 * 16 + 8, (int32_t)py0 * 16 + 8, Erow);
        t.run_bits = RUN_MIN_BITS;
        t.edges32 = 1;
        rows32_gouraud(c, &t, Erow, (int32_t)px0, (int32_t)px1, (int32_t)py0, (int32_t)py1);
        return;
    }
    tri_setup(&t, v, area);
    /* a box up to 16 pixels wide is one run per row whatever the length */
    t.run_bits = RUN_MIN_BITS;
    if (!c->depth_only && c->nvar == LUMO_RASTER_VAR_GOURAUD && px1 - px0 >= (1 << RUN_MIN_BITS))
        t.run_bits = gouraud_run_bits(&t, area, RUN_MIN_BITS, RUN_PERSPECTIVE_BITS);
    small = box_edges(&t, px0, px1, py0, py1, sure, Erow);
    t.edges32 = small && t.sh == 0;
    for (i = 0; i < 3; i++) {
        t.st32[i] = (int32_t)t.step[i];
        t.bias32[i] = (int32_t)t.e[i].bias;
        t.dy32[i] = (int32_t)(t.e[i].b * 16);
    }
    if (t.edges32 && !c->depth_only && (c->nvar == LUMO_RASTER_VAR_GOURAUD || pixel32_pieces(c, &t, area))) {
        (c->nvar == LUMO_RASTER_VAR_GOURAUD ? rows32_gouraud : rows32_pixel)(c, &t, Erow, (int32_t)px0,
                                                                            (int32_t)px1, (int32_t)py0,
                                                                            (int32_t)py1);
        return;
    }
    for (py = py0; py <= py1; py++, Erow[0] += t.e[0].b * 16, Erow[1] += t.e[1].b * 16, Erow[2] += t.e[2].b * 16) {
        size_t row = (size_t)(py - tg->band_y) * tg->width;
        int64_t E[3], x0, x1;
        E[0] = Erow[0], E[1] = Erow[1], E[2] = Erow[2];
        if (!row_span(&t, px0, px1, small, E, &x0, &x1))
            continue;
        if (c->stats)
            c->stats->pixels_tested += (uint32_t)(x1 - x0 + 1);
        if (c->depth_only || c->laying)
            span_depth(c, &t, E, x0, x1, row);
        else if (c->nvar == LUMO_RASTER_VAR_GOURAUD)
            span_gouraud(c, &t, E, x0, x1, py, row);
        else
            span_color(c, &t, E, x0, x1, py, row);
    }
}
