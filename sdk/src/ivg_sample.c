/*
 * ivg_sample.c — shading from the IVG (seed 000 §3.2, eq. 2).
 *
 * For a point p with unit normal n: the hemisphere of each axis a is picked
 * by the sign of n_a (n_a >= 0 -> +a); its d and c are interpolated
 * trilinearly and separately (as two hardware-filtered 3D textures would
 * be, §3.3); then I_n . n = sum_a n_a^2 (d_a . n) c_a per channel, clamped
 * at 0, and L_r = albedo/pi times that.
 *
 * Fixed point: grid coordinates and trilinear weights in Q16 (one 64-bit
 * multiply per axis, no division per sample); eight Q16 corner weights per
 * point that sum to exactly 2^16 (a constant field comes back exactly),
 * shared by the three hemispheres, one rounding per interpolated value;
 * n_a^2 and d.n are kept exact in Q28 and their product rounded once.
 */
#include "ivg_internal.h"

/* The small steps of a sample are inlined into both samplers even in -Os
 * board builds: called from two places, -Os would keep them out of line,
 * a call per axis, weight and channel (2.7 % of a Cortex-M3 per-pixel
 * frame). */
#if defined(__GNUC__)
#define IVG_STEP static inline __attribute__((always_inline))
#else
#define IVG_STEP static inline
#endif

/* Where p falls along axis a: the cell's first vertex and the Q16 weight of
 * the second (in [0, 2^16]). p is clamped to the grid box. */
IVG_STEP void locate(const lumo_ivg *g, int a, lumo_q16_16 p, uint32_t *cell, uint32_t *t)
{
    int64_t rel = (int64_t)p - g->desc.bmin[a];
    uint32_t last = g->desc.dims[a] - 1u;
    uint64_t u;

    if (rel < 0)
        rel = 0;
    if (rel > (int64_t)g->extent[a])
        rel = g->extent[a];
    /* rel * scale <= (dims-1) * 2^48 + extent/2 < 2^57: no overflow. */
    u = ((uint64_t)rel * g->scale[a] + ((uint64_t)1 << 31)) >> 32;
    if (u >= (uint64_t)last << 16) {
        *cell = last - 1u;
        *t = 1u << 16;
        return;
    }
    *cell = (uint32_t)(u >> 16);
    *t = (uint32_t)(u & 0xFFFFu);
}

/* One interpolated hemisphere: c in UQ16.16, d in Q1.14. */
typedef struct ivg_hemi {
    uint32_t c[3];
    int32_t  d[3];
} ivg_hemi;

/* a * t / 2^16 rounded half up; a, t <= 2^16. */
static uint32_t part(uint32_t a, uint32_t t)
{
    return (uint32_t)(((uint64_t)a * t + (1u << 15)) >> 16);
}

/* The eight trilinear weights of a cell (corner n = x + 2y + 4z) in Q16,
 * summing to exactly 2^16 so a constant field comes back bit for bit: each
 * weight is split into its two children along the next axis as (w - p, p),
 * p = round(w t), so every split keeps the sum and every weight is within
 * one ulp of the exact product and never negative. */
IVG_STEP void cell_weights(const uint32_t t[3], uint32_t w[8])
{
    uint32_t z[2] = {(1u << 16) - t[2], t[2]}, yz[4];   /* yz[y + 2z] */
    int n;

    for (n = 0; n < 2; n++) {
        yz[2 * n + 1] = part(z[n], t[1]);
        yz[2 * n] = z[n] - yz[2 * n + 1];
    }
    for (n = 0; n < 4; n++) {
        uint32_t x1 = part(yz[n], t[0]);
        w[2 * n + 1] = x1;
        w[2 * n] = yz[n] - x1;
    }
}

/* q/127 summed with Q16 weights (S = sum w_n q_n, weights summing to
 * 2^16) to Q1.14, rounded half away from zero: S / 2^16 / 127 * 2^14 =
 * S / 508. With one corner of weight 2^16 this is the decoding of §2.5,
 * floor((|q| 2^14 + 63) / 127), so a vertex comes back as stored. */
IVG_STEP int32_t q_sum_to_q14(int32_t sum)
{
    uint32_t mag = sum < 0 ? (uint32_t)-sum : (uint32_t)sum;
    int32_t v = (int32_t)((2u * mag + 508u) / 1016u);

    return sum < 0 ? -v : v;
}

/* Trilinear interpolation of one hemisphere: base is its packed entry at
 * the cell's first vertex, off[n] the byte offset of corner n; the grid
 * stays packed and each corner is opened here, on sampling: the colour as
 * UQ16.16 (exact, one table step per word: ivg_rgb9e5_open), the direction
 * in the wire's q units, converted to Q1.14 once for the sum. The colour
 * sums stay below 2^48; the direction sums within +-127 x 2^16 < 2^23, so
 * they fit 32 bits (cheaper on the M3). */
static void interpolate(const uint8_t *base, const uint32_t off[8], const uint32_t w[8], ivg_hemi *out)
{
    uint64_t c0 = 0, c1 = 0, c2 = 0;
    int32_t d0 = 0, d1 = 0, d2 = 0;
    int n;

    for (n = 0; n < 8; n++) {
        const uint8_t *p = base + off[n];
        int32_t wn = (int32_t)w[n];
        uint32_t c[3];
        if (wn == 0)
            continue;                 /* a cell face: nothing to open */
        ivg_rgb9e5_open(p + 3, c);
        c0 += (uint64_t)c[0] * (uint32_t)wn;
        c1 += (uint64_t)c[1] * (uint32_t)wn;
        c2 += (uint64_t)c[2] * (uint32_t)wn;
        d0 += (int8_t)p[0] * wn;
        d1 += (int8_t)p[1] * wn;
        d2 += (int8_t)p[2] * wn;
    }
    out->c[0] = (uint32_t)((c0 + (1u << 15)) >> 16);
    out->c[1] = (uint32_t)((c1 + (1u << 15)) >> 16);
    out->c[2] = (uint32_t)((c2 + (1u << 15)) >> 16);
    out->d[0] = q_sum_to_q14(d0);
    out->d[1] = q_sum_to_q14(d1);
    out->d[2] = q_sum_to_q14(d2);
}

/* Byte offsets of the eight corners of a cell (corner n = x + 2y + 4z). */
static void corner_offsets(const lumo_ivg *g, uint32_t off[8])
{
    uint32_t sy = g->desc.dims[0] * IVG_PACKED_VERTEX, sz = sy * g->desc.dims[1];
    int n;

    for (n = 0; n < 8; n++)
        off[n] = (n & 1 ? (uint32_t)IVG_PACKED_VERTEX : 0u) + (n & 2 ? sy : 0u) + (n & 4 ? sz : 0u);
}

/* Largest |n_a^2 (d_a . n)| kept, Q28 (2.0): unreachable with unit n and
 * |d| <= 17/16, it bounds the 64-bit sum for any n the caller passes. */
#define FACTOR_MAX ((int64_t)1 << 29)

/* The cell holding p (the index of its first vertex) and its eight
 * trilinear weights. */
IVG_STEP uint32_t cell_of(const lumo_ivg *g, const lumo_q16_16 p[3], uint32_t w[8])
{
    uint32_t cell[3], t[3];
    int a;

    for (a = 0; a < 3; a++)
        locate(g, a, p[a], &cell[a], &t[a]);
    cell_weights(t, w);
    return cell[0] + g->desc.dims[0] * (cell[1] + g->desc.dims[1] * cell[2]);
}

/* sum += n_a^2 (d_a . n) c_a for the interpolated hemisphere h of axis a
 * (n2 = n_a^2, Q28; sum Q44, |.| < 2^61). */
IVG_STEP void add_hemi(const ivg_hemi *h, const lumo_q1_14 n[3], int64_t n2, int64_t sum[3])
{
    int64_t dn = 0, f;
    int k;

    for (k = 0; k < 3; k++)
        dn += (int64_t)h->d[k] * n[k];                    /* Q28 */
    f = lumo_round_shift(n2 * dn, 28);                    /* Q28 */
    f = f > FACTOR_MAX ? FACTOR_MAX : f < -FACTOR_MAX ? -FACTOR_MAX : f;
    for (k = 0; k < 3; k++)
        sum[k] += (int64_t)h->c[k] * f;
}

IVG_STEP void finish(const int64_t sum[3], lumo_uq16_16 out[3])
{
    int k;

    for (k = 0; k < 3; k++)
        out[k] = lumo_sat_u32(lumo_round_shift(sum[k], 28));
}

void lumo_ivg_irradiance(const lumo_ivg *g, const lumo_q16_16 p[3], const lumo_q1_14 n[3],
                         lumo_uq16_16 out[3])
{
    uint32_t w[8], off[8];
    const uint8_t *base;
    int64_t sum[3] = {0, 0, 0};
    int a;

    out[0] = out[1] = out[2] = 0;
    if (g == NULL)
        return;
    base = ivg_packed_at(&g->level[0], cell_of(g, p, w), 0);
    corner_offsets(g, off);
    for (a = 0; a < 3; a++) {
        int64_t n2 = (int64_t)n[a] * n[a];               /* Q28 */
        ivg_hemi h;
        if (n2 == 0)
            continue;                                     /* no weight: skip */
        interpolate(base + (2 * a + (n[a] < 0)) * IVG_PACKED, off, w, &h);
        add_hemi(&h, n, n2, sum);
    }
    finish(sum, out);
}

/* ---- the sampler: the same sums over a memo of the cell's opened corners */

void lumo_ivg_sampler_init(lumo_ivg_sampler *s, const lumo_ivg *g)
{
    s->grid = g;
    s->cell = UINT32_MAX;
    s->opened = 0;
    if (g)
        corner_offsets(g, s->corner_off);
}

/* Open hemisphere h of the memo's cell: its eight corners unpacked. */
static void open_hemi(lumo_ivg_sampler *s, unsigned h)
{
    const uint8_t *base = ivg_packed_at(&s->grid->level[0], s->cell, h);
    int n, k;

    for (n = 0; n < 8; n++) {
        const uint8_t *p = base + s->corner_off[n];
        uint32_t c[3];
        ivg_rgb9e5_open(p + 3, c);
        for (k = 0; k < 3; k++) {
            s->c[h][k][n] = c[k];
            s->q[h][k][n] = (int8_t)p[k];
        }
    }
    s->opened |= 1u << h;
}

/* interpolate() over the opened corners: the same sums, so the same bits
 * (a zero weight adds nothing whether its corner is opened or not). */
static void interpolate_open(const lumo_ivg_sampler *s, unsigned h, const uint32_t w[8], ivg_hemi *out)
{
    int n, k;

    for (k = 0; k < 3; k++) {
        const uint32_t *c = s->c[h][k];
        const int16_t *q = s->q[h][k];
        uint64_t cs = 0;
        int32_t qs = 0;
        for (n = 0; n < 8; n++) {
            cs += (uint64_t)c[n] * w[n];
            qs += q[n] * (int32_t)w[n];
        }
        out->c[k] = (uint32_t)((cs + (1u << 15)) >> 16);
        out->d[k] = q_sum_to_q14(qs);
    }
}

/* lumo_ivg_irradiance's steps with the corners from the memo. */
void lumo_ivg_sampler_irradiance(lumo_ivg_sampler *s, const lumo_q16_16 p[3], const lumo_q1_14 n[3],
                                 lumo_uq16_16 out[3])
{
    uint32_t w[8], cell;
    int64_t sum[3] = {0, 0, 0};
    unsigned a;

    out[0] = out[1] = out[2] = 0;
    if (s->grid == NULL)
        return;
    cell = cell_of(s->grid, p, w);
    if (cell != s->cell) {
        s->cell = cell;
        s->opened = 0;
    }
    for (a = 0; a < 3; a++) {
        int64_t n2 = (int64_t)n[a] * n[a];
        unsigned h = 2 * a + (n[a] < 0);
        ivg_hemi hh;
        if (n2 == 0)
            continue;
        if (!(s->opened & (1u << h)))
            open_hemi(s, h);
        interpolate_open(s, h, w, &hh);
        add_hemi(&hh, n, n2, sum);
    }
    finish(sum, out);
}

void lumo_ivg_radiance(const lumo_ivg *g, const lumo_q16_16 p[3], const lumo_q1_14 n[3],
                       const lumo_q1_14 albedo[3], lumo_uq16_16 out[3])
{
    lumo_uq16_16 irr[3];
    int k;

    lumo_ivg_irradiance(g, p, n, irr);
    for (k = 0; k < 3; k++) {
        uint64_t rho = albedo[k] > 0 ? (uint64_t)albedo[k] : 0u;
        /* UQ16.16 * Q1.14 * Q16.16 < 2^62; one rounding back to UQ16.16. */
        uint64_t v = lumo_round_shift_u((uint64_t)irr[k] * rho * (uint64_t)LUMO_Q16_INV_PI, 30);
        out[k] = v > UINT32_MAX ? UINT32_MAX : (uint32_t)v;
    }
}
