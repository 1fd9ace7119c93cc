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
} tri;

static int64_t floor_div16(int64_t v)
{
    return v >= 0 ? v / 16 : -((-v + 15) / 16);
}

/* Top-left rule for an edge a -> b of a triangle with positive area in
 * y-down screen space: top edges are horizontal going right, left edges go up. */
static int is_top_left(const lumo_raster_sv *a, const lumo_raster_sv *b)
{
    int32_t dx = b->x - a->x, dy = b->y - a->y;
    return dy < 0 || (dy == 0 && dx > 0);
}

static void edge_setup(edge *e, const lumo_raster_sv *p, const lumo_raster_sv *q)
{
    e->a = -((int64_t)q->y - p->y);
    e->b = (int64_t)q->x - p->x;
    e->x0 = p->x;
    e->y0 = p->y;
    e->bias = is_top_left(p, q) ? 0 : 1;
}

/* Number of significant bits of v, by halving. */
static unsigned bit_length(uint64_t v)
{
    unsigned n = 0;

    if (v >> 32) { n += 32; v >>= 32; }
    if (v >> 16) { n += 16; v >>= 16; }
    if (v >> 8)  { n += 8;  v >>= 8; }
    if (v >> 4)  { n += 4;  v >>= 4; }
    if (v >> 2)  { n += 2;  v >>= 2; }
    if (v >> 1)  { n += 1;  v >>= 1; }
    return n + (unsigned)v;
}

/* Scaling shifts and the depth reciprocal. The depth z = sum e_i q_i /
 * sum e_i is linear in screen space and sum e_i is the triangle's doubled
 * area A (exactly when sh == 0; within 2 of A >> sh otherwise, 2^-22 of
 * it), so z = sum w_i q_i / (A >> sh) with a per-triangle reciprocal:
 * (sum w_i q_i) < 2^(t + 30) for t = bit length of A >> sh is shifted
 * right by zs = t - 2 to < 2^32 and multiplied by zr = 2^(32 + zs) /
 * (A >> sh) < 2^31: error below 1.5 units of Q0.30. */
static void tri_setup(tri *t, const lumo_raster_sv *v, int64_t area)
{
    uint64_t qmax = v[0].q, bound, se;
    unsigned b;
    int i;

    t->v = v;
    edge_setup(&t->e[0], &v[1], &v[2]);
    edge_setup(&t->e[1], &v[2], &v[0]);
    edge_setup(&t->e[2], &v[0], &v[1]);
    for (i = 0; i < 3; i++)
        t->step[i] = t->e[i].a * 16;
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
 * in 32 bits. *x0 = first covered pixel, return the last one, or x0 - 1
 * when none. */
static int64_t run_32(const tri *t, const int64_t E[3], int64_t px0, int64_t px1, int64_t *x0)
{
    int32_t lo = 0, hi = (int32_t)(px1 - px0);
    int i;

    for (i = 0; i < 3; i++) {
        int32_t e = (int32_t)E[i], st = (int32_t)t->step[i], b = (int32_t)t->e[i].bias;
        if (st > 0) {
            if (e < b) {
                int32_t k = (b - e + st - 1) / st;          /* first k with e + k st >= b */
                if (k > lo) lo = k;
            }
        } else if (e < b) {
            lo = hi + 1;                                  /* never covered in this row */
        } else if (st < 0) {
            int32_t k = (e - b) / -st;                    /* last k with e + k st >= b */
            if (k < hi) hi = k;
        }
    }
    *x0 = px0 + lo;
    return lo > hi ? *x0 - 1 : px0 + hi;
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

/* The edge values at pixel (px0, py0), and whether every value of the
 * pixel box [px0, px1] x [py0, py1] lies within +-2^30: E is linear, so its
 * extremes over the box are at the box's corners. */
static int box_edges(const tri *t, int64_t px0, int64_t px1, int64_t py0, int64_t py1, int64_t E[3])
{
    int64_t sy = py0 * 16 + 8, sx = px0 * 16 + 8;
    int small = 1, i;

    for (i = 0; i < 3; i++) {
        int64_t dx = t->step[i] * (px1 - px0), dy = t->e[i].b * 16 * (py1 - py0);
        E[i] = t->e[i].a * (sx - t->e[i].x0) + t->e[i].b * (sy - t->e[i].y0);
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

static unsigned gouraud_run_bits(const tri *t, int64_t area)
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
    k = (int)bit_length((uint64_t)area) + (int)bit_length(qmin) - 2 - RUN_PERSPECTIVE_BITS
      - (int)bit_length((uint64_t)num);
    return k < RUN_MIN_BITS ? RUN_MIN_BITS : k > RUN_MAX_BITS ? RUN_MAX_BITS : (unsigned)k;
}

/* (to - from) / n rounded towards zero, n in [1, 2^RUN_MAX_BITS). */
static int32_t seg_step(int32_t from, int32_t to, int32_t n)
{
    return (to - from) / n;
}

/* Depth value of z (Q0.30, in [0, 2^30]) in 16 or 32 bits, 0 kept for
 * "cleared": depth16 and depth32 in 32-bit arithmetic. */
LUMO_RASTER_HOT uint32_t depth_of(uint32_t z, int d16)
{
    if (d16)
        return z >= ((uint32_t)1 << 30) ? 0xFFFFu : (z >> 14) | ((z >> 14) == 0);
    return z >= ((uint32_t)1 << 30) ? 0xFFFFFFFFu : (z << 2) | (z == 0);
}

/* The pixels of a Gouraud run in 32-bit arithmetic, inlined once per pixel
 * format (rgb565) and depth width (d16) so that the loop holds no format
 * test: depth and radiance stepped, depth test, three code look-ups. */
LUMO_RASTER_HOT uint32_t run_pixels(void *depth, uint8_t *line, int32_t count, int x, int y, int32_t z0,
                                    int32_t dz, const int32_t c0[3], const int32_t dc[3], int rgb565, int d16)
{
    /* Unsigned accumulators: every value the run uses lies in [0, 2^30];
     * the step past its last pixel may wrap, which unsigned arithmetic
     * defines. */
    uint32_t written = 0, z = (uint32_t)z0, c[3];
    int32_t k;

    c[0] = (uint32_t)c0[0];
    c[1] = (uint32_t)c0[1];
    c[2] = (uint32_t)c0[2];
    for (k = 0; k < count; k++, x++, z += (uint32_t)dz, c[0] += (uint32_t)dc[0], c[1] += (uint32_t)dc[1],
         c[2] += (uint32_t)dc[2]) {
        uint32_t dv = depth_of(z, d16);
        unsigned r, g, b;
        if (d16 ? dv <= ((uint16_t *)depth)[k] : dv <= ((uint32_t *)depth)[k])
            continue;
        if (d16)
            ((uint16_t *)depth)[k] = (uint16_t)dv;
        else
            ((uint32_t *)depth)[k] = dv;
        r = lumo_raster_srgb_code32(c[0]);
        g = lumo_raster_srgb_code32(c[1]);
        b = lumo_raster_srgb_code32(c[2]);
        if (rgb565) {
            unsigned t = lumo_raster_bayer4[y & 3][x & 3];
            ((uint16_t *)(void *)line)[k] = (uint16_t)((lumo_raster_dither(r, 31, t) << 11)
                                                       | (lumo_raster_dither(g, 63, t) << 5)
                                                       | lumo_raster_dither(b, 31, t));
        } else {
            ((uint32_t *)(void *)line)[k] = ((uint32_t)r << 16) | ((uint32_t)g << 8) | b;
        }
        written++;
    }
    return written;
}

/* A Gouraud run of pixels [a, b] of a row (b - a < 2^run_bits): depth and
 * radiance exact (perspective-correct) at both ends and stepped linearly
 * between them, so a pixel costs additions, the depth test and three table
 * look-ups. Depth is linear in screen space (the steps only round); the
 * radiance's perspective error is bounded by the run's length (gouraud_run_bits). */
static uint32_t run_gouraud(const lumo_raster_ctx *c, const tri *t, const int64_t Ea[3], int64_t a,
                            int64_t b, int64_t y, size_t row, uint8_t *line)
{
    lumo_raster_target *tg = c->target;
    int64_t Eb[3];
    int32_t ca[3], cb[3], dc[3], n = (int32_t)(b - a);
    uint32_t za, zb;
    int32_t z, dz;
    int i;

    za = gouraud_at(t, Ea, ca);
    for (i = 0; i < 3; i++)
        Eb[i] = Ea[i] + t->step[i] * n;
    zb = n ? gouraud_at(t, Eb, cb) : za;
    for (i = 0; i < 3; i++)
        dc[i] = n ? seg_step(ca[i], cb[i], n) : 0;
    z = (int32_t)za;
    dz = n ? seg_step((int32_t)za, (int32_t)zb, n) : 0;
    row += (size_t)a;
    line += (size_t)a * (tg->format == LUMO_PIXEL_RGB565 ? 2u : 4u);
    if (tg->format == LUMO_PIXEL_RGB565)
        return tg->depth_bits == 16 ? run_pixels((uint16_t *)tg->depth + row, line, n + 1, (int)a, (int)y, z, dz, ca, dc, 1, 1)
                                    : run_pixels((uint32_t *)tg->depth + row, line, n + 1, (int)a, (int)y, z, dz, ca, dc, 1, 0);
    return tg->depth_bits == 16 ? run_pixels((uint16_t *)tg->depth + row, line, n + 1, (int)a, (int)y, z, dz, ca, dc, 0, 1)
                                : run_pixels((uint32_t *)tg->depth + row, line, n + 1, (int)a, (int)y, z, dz, ca, dc, 0, 0);
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

/* Rasterize one screen triangle with positive area. */
void lumo_raster_triangle(const lumo_raster_ctx *c, const lumo_raster_sv *v, int64_t area)
{
    const lumo_raster_target *tg = c->target;
    int64_t minx, maxx, miny, maxy, px0, px1, py0, py1, py, Erow[3];
    tri t;
    int i, small;

    minx = maxx = v[0].x;
    miny = maxy = v[0].y;
    for (i = 1; i < 3; i++) {
        if (v[i].x < minx) minx = v[i].x;
        if (v[i].x > maxx) maxx = v[i].x;
        if (v[i].y < miny) miny = v[i].y;
        if (v[i].y > maxy) maxy = v[i].y;
    }
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
    tri_setup(&t, v, area);
    /* a box up to 16 pixels wide is one run per row whatever the length */
    t.run_bits = RUN_MIN_BITS;
    if (!c->depth_only && c->nvar == LUMO_RASTER_VAR_GOURAUD && px1 - px0 >= (1 << RUN_MIN_BITS))
        t.run_bits = gouraud_run_bits(&t, area);
    small = box_edges(&t, px0, px1, py0, py1, Erow);
    for (py = py0; py <= py1; py++, Erow[0] += t.e[0].b * 16, Erow[1] += t.e[1].b * 16, Erow[2] += t.e[2].b * 16) {
        size_t row = (size_t)(py - tg->band_y) * tg->width;
        int64_t E[3], x0, x1;
        E[0] = Erow[0], E[1] = Erow[1], E[2] = Erow[2];
        if (!row_span(&t, px0, px1, small, E, &x0, &x1))
            continue;
        if (c->stats)
            c->stats->pixels_tested += (uint32_t)(x1 - x0 + 1);
        if (c->depth_only)
            span_depth(c, &t, E, x0, x1, row);
        else if (c->nvar == LUMO_RASTER_VAR_GOURAUD)
            span_gouraud(c, &t, E, x0, x1, py, row);
        else
            span_color(c, &t, E, x0, x1, py, row);
    }
}
