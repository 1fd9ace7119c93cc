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
 * multiply per axis, no division per sample); interpolation by three
 * rounds of lerps, so a constant field comes back exactly; n_a^2 and d.n
 * are kept exact in Q28 and their product rounded once to Q28.
 */
#include "ivg_internal.h"

/* Where p falls along axis a: the cell's first vertex and the Q16 weight of
 * the second (in [0, 2^16]). p is clamped to the grid box. */
static void locate(const lumo_ivg *g, int a, lumo_q16_16 p, uint32_t *cell, uint32_t *t)
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

/* One channel of the interpolated hemisphere: d in Q1.14, c in UQ16.16. */
typedef struct ivg_hemi {
    int64_t c[3];
    int64_t d[3];
} ivg_hemi;

static int64_t lerp(int64_t a, int64_t b, uint32_t t)
{
    return a + lumo_round_shift((b - a) * (int64_t)t, 16);
}

static void lerp_hemi(ivg_hemi *out, const ivg_hemi *a, const ivg_hemi *b, uint32_t t)
{
    int k;

    for (k = 0; k < 3; k++) {
        out->c[k] = lerp(a->c[k], b->c[k], t);
        out->d[k] = lerp(a->d[k], b->d[k], t);
    }
}

/* Trilinear interpolation of hemisphere `axis` in the cell at base vertex
 * `v0` with Q16 weights t[3]: lerp along x, then y, then z. */
static void interpolate(const lumo_ivg *g, uint32_t v0, const uint32_t t[3], int axis, ivg_hemi *out)
{
    uint32_t sx = 1, sy = g->desc.dims[0], sz = sy * g->desc.dims[1];
    ivg_hemi h[8];
    int n, k;

    for (n = 0; n < 8; n++) {
        uint32_t v = v0 + (n & 1 ? sx : 0) + (n & 2 ? sy : 0) + (n & 4 ? sz : 0);
        const lumo_ivg_entry *e = &g->level[0].e[(size_t)v * LUMO_IVG_AXES + axis];
        for (k = 0; k < 3; k++) {
            h[n].c[k] = e->c[k];
            h[n].d[k] = e->d[k];
        }
    }
    for (n = 0; n < 4; n++)
        lerp_hemi(&h[n], &h[2 * n], &h[2 * n + 1], t[0]);
    for (n = 0; n < 2; n++)
        lerp_hemi(&h[n], &h[2 * n], &h[2 * n + 1], t[1]);
    lerp_hemi(out, &h[0], &h[1], t[2]);
}

/* Largest |n_a^2 (d_a . n)| kept, Q28 (2.0): unreachable with unit n and
 * |d| <= 17/16, it bounds the 64-bit sum for any n the caller passes. */
#define FACTOR_MAX ((int64_t)1 << 29)

void lumo_ivg_irradiance(const lumo_ivg *g, const lumo_q16_16 p[3], const lumo_q1_14 n[3],
                         lumo_uq16_16 out[3])
{
    uint32_t cell[3], t[3], v0;
    int64_t sum[3] = {0, 0, 0};
    int a, k;

    out[0] = out[1] = out[2] = 0;
    if (g == NULL)
        return;
    for (a = 0; a < 3; a++)
        locate(g, a, p[a], &cell[a], &t[a]);
    v0 = cell[0] + g->desc.dims[0] * (cell[1] + g->desc.dims[1] * cell[2]);
    for (a = 0; a < 3; a++) {
        int64_t n2 = (int64_t)n[a] * n[a];               /* Q28 */
        int64_t dn = 0, f;
        ivg_hemi h;
        if (n2 == 0)
            continue;                                     /* no weight: skip */
        interpolate(g, v0, t, 2 * a + (n[a] < 0), &h);
        for (k = 0; k < 3; k++)
            dn += h.d[k] * n[k];                          /* Q28 */
        f = lumo_round_shift(n2 * dn, 28);                /* Q28 */
        f = f > FACTOR_MAX ? FACTOR_MAX : f < -FACTOR_MAX ? -FACTOR_MAX : f;
        for (k = 0; k < 3; k++)
            sum[k] += h.c[k] * f;                         /* Q44, |.| < 2^61 */
    }
    for (k = 0; k < 3; k++)
        out[k] = lumo_sat_u32(lumo_round_shift(sum[k], 28));
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
