/*
 * raster_shade.c — the shading model shared by per-vertex and per-pixel
 * lighting (docs/rasterizer.md): diffuse direct light, shadowed by the
 * light's shadow map when it has one (raster_shadow.c), plus
 * the IVG's indirect irradiance (seed 000, §3.2), rho/pi, sRGB tone map.
 */
#include "raster_internal.h"

/* 1/(4 pi) and 1/pi in Q0.32, rounded. */
#define INV_4PI_Q32 341782638u
#define INV_PI_Q32  1367130551u
/* Squared distances below this (Q16.16, ~0.004 units^2) are clamped: a light
 * touching a surface would otherwise saturate everything. */
#define MIN_DIST2   256

static uint32_t sat_add_u32(uint32_t a, uint32_t b)
{
    return a > UINT32_MAX - b ? UINT32_MAX : a + b;
}

/* v scaled by a visibility in [0, 256]; 256 leaves v's bits unchanged, so
 * an unshadowed light gives the bytes it gave before shadows existed. */
static uint64_t shadowed(uint64_t v, uint32_t vis)
{
    return vis >= 256 ? v : (v * vis + 128) >> 8;
}

static int32_t clamp_i32(int64_t v, int32_t lim)
{
    if (v > lim) return lim;
    if (v < -lim) return -lim;
    return (int32_t)v;
}

/* Dot product of two Q1.14 vectors, Q1.14; 64-bit because a caller's
 * "unit" vectors may be anything in [-2, 2) (hostile meshes). */
static int32_t dot_q14(const lumo_q1_14 a[3], const lumo_q1_14 b[3])
{
    int64_t d = (int64_t)a[0] * b[0] + (int64_t)a[1] * b[1] + (int64_t)a[2] * b[2];
    return (int32_t)lumo_round_shift(d, LUMO_Q14_SHIFT);
}

/* floor(sqrt(v)) by Newton's method x <- (x + v / x) / 2 started above the
 * root: from an over-estimate the integer iteration decreases to the floor
 * of the root and stops there (the next step would not decrease). The seed,
 * ceil(16 sqrt(top + 1)) for the top 8 bits of v, is at most 1.6% high, so
 * three or four divisions do what lumo_isqrt64's bit-by-bit loop does in up
 * to 32 steps (it was 14% of a per-pixel frame). */
uint32_t lumo_raster_isqrt(uint64_t v)
{
    uint64_t x, y, t = v;
    unsigned b = 0, s;

    if (v == 0)
        return 0;
    if (v < 256)
        x = 16;                                      /* > sqrt(255) */
    else {
        if (t >> 32) { b += 32; t >>= 32; }
        if (t >> 16) { b += 16; t >>= 16; }
        if (t >> 8)  { b += 8;  t >>= 8; }
        if (t >> 4)  { b += 4;  t >>= 4; }
        if (t >> 2)  { b += 2;  t >>= 2; }
        if (t >> 1)  { b += 1; }
        /* b = index of the top bit (>= 8); an even shift s leaves 7 or 8 bits */
        s = (b - 6) & ~1u;
        x = (((uint64_t)lumo_raster_sqrt_seed[v >> s] << (s / 2)) + 15) >> 4;
    }
    for (;;) {
        y = (x + v / x) >> 1;
        if (y >= x)
            return (uint32_t)x;
        x = y;
    }
}

/* |v| rounded to nearest from the exact square: floor root, bumped when v2
 * lies above (r + 1/2)^2. */
static uint64_t round_sqrt(uint64_t v2)
{
    uint64_t r = lumo_raster_isqrt(v2);
    return (v2 - r * r > r) ? r + 1 : r;
}

/* Irradiance of a point or spot light at p facing n (W/m^2, UQ16.16 each):
 * I cos(theta) / r^2 with I = Phi / (4 pi). The light vector l is never
 * normalised: cos(theta) = (n . l) / |l| and the cone test compares
 * -(l . axis) with cos_cutoff |l|, so one square root and one division per
 * light suffice (normalising was 30% of a per-pixel frame). */
static void add_local_light(const lumo_raster_light *L, const lumo_q16_16 p[3],
                            const lumo_q1_14 n[3], lumo_uq16_16 e[3])
{
    int64_t d[3], ln = 0, la = 0, cos_n;
    uint64_t dist2 = 0, dist;
    uint32_t vis = 256;
    int i;

    /* Components beyond +-16384 units are clamped: such a light is too far
     * to matter and the squares must fit 64 bits. */
    for (i = 0; i < 3; i++) {
        d[i] = clamp_i32((int64_t)L->pos[i] - p[i], (int32_t)1 << 30);
        dist2 += (uint64_t)(d[i] * d[i]);                /* Q32 */
        ln += d[i] * n[i];                               /* Q30 */
        la += d[i] * L->dir[i];
    }
    if (ln <= 0)
        return;
    dist = round_sqrt(dist2);                            /* Q16 */
    if (dist == 0)
        return;
    if (L->kind == LUMO_LIGHT_SPOT && -la < (int64_t)L->cos_cutoff * (int64_t)dist)
        return;
    if (L->shadow && (vis = lumo_raster_shadow_visibility(L->shadow, p, n)) == 0)
        return;                                          /* in full shadow */
    cos_n = (ln + (int64_t)(dist / 2)) / (int64_t)dist;  /* Q14 */
    if (cos_n > 2 * LUMO_Q14_ONE)
        cos_n = 2 * LUMO_Q14_ONE;                        /* non-unit n from a hostile mesh */
    dist2 >>= 16;
    if (dist2 < MIN_DIST2)
        dist2 = MIN_DIST2;
    for (i = 0; i < 3; i++) {
        uint64_t inten = ((uint64_t)L->value[i] * INV_4PI_Q32 + ((uint64_t)1 << 31)) >> 32;
        uint64_t num = (inten * (uint64_t)cos_n) << 2;   /* Q30 -> Q32 / Q16 */
        uint64_t q = shadowed((num + dist2 / 2) / dist2, vis);
        e[i] = sat_add_u32(e[i], q > UINT32_MAX ? UINT32_MAX : (uint32_t)q);
    }
}

/* A Q1.14 vector of any length in [-2, 2) to unit length: |v| from one
 * 64-bit square root with 22 fractional bits, then one division for the
 * reciprocal and three multiplies (lumo_normalize3_q14's scaling loop and
 * three divisions cost more per pixel). Error <= 1 ulp. Zero stays zero. */
void lumo_raster_normalize_q14(const int32_t v[3], lumo_q1_14 out[3])
{
    int64_t c[3], k;
    uint64_t s2 = 0, len;
    int i;

    for (i = 0; i < 3; i++) {
        c[i] = v[i] > 32767 ? 32767 : v[i] < -32768 ? -32768 : v[i];
        s2 += (uint64_t)(c[i] * c[i]);                   /* Q28, < 2^32 */
    }
    len = round_sqrt(s2 << 16);                          /* Q22 */
    if (len == 0) {
        out[0] = out[1] = out[2] = 0;
        return;
    }
    k = (int64_t)((((uint64_t)1 << 50) + len / 2) / len);   /* 2^28 / |v|, Q14 units */
    for (i = 0; i < 3; i++)
        out[i] = lumo_sat_i16((int32_t)lumo_round_shift(c[i] * k, 28));
}

/* The interpolated normal of a pixel to unit length. Between vertex
 * normals it is a little shorter than 1: within |v|^2 in [7/8, 9/8] two
 * Newton steps for 1/|v| from 1 (k <- k (3 - |v|^2 k^2) / 2, Q30; error
 * 3/8 e^2 after one step, below 2^-15 after two) replace the square root
 * and the division; other lengths take lumo_raster_normalize_q14. */
void lumo_raster_renormalize_q14(const int32_t v[3], lumo_q1_14 out[3])
{
    const uint64_t lo = (uint64_t)7 << 25, hi = (uint64_t)9 << 25;   /* 7/8, 9/8 in Q28 */
    uint64_t s2 = 0, k = (uint64_t)1 << 30;
    int i, step;

    for (i = 0; i < 3; i++) {
        int64_t c = v[i];
        if (c > 32767 || c < -32768) {
            lumo_raster_normalize_q14(v, out);
            return;
        }
        s2 += (uint64_t)(c * c);                         /* Q28 */
    }
    if (s2 < lo || s2 > hi) {
        lumo_raster_normalize_q14(v, out);
        return;
    }
    for (step = 0; step < 2; step++) {
        uint64_t sk2 = ((s2 << 2) * ((k * k) >> 30)) >> 30;  /* |v|^2 k^2, Q30 */
        k = (k * (((uint64_t)3 << 30) - sk2)) >> 31;
    }
    for (i = 0; i < 3; i++)
        out[i] = lumo_sat_i16((int32_t)lumo_round_shift((int64_t)v[i] * (int64_t)k, 30));
}

static void add_directional(const lumo_raster_light *L, const lumo_q16_16 p[3], const lumo_q1_14 n[3],
                            lumo_uq16_16 e[3])
{
    int32_t cos_n = -dot_q14(n, L->dir);
    uint32_t vis = 256;
    int i;

    if (cos_n <= 0)
        return;
    if (L->shadow && (vis = lumo_raster_shadow_visibility(L->shadow, p, n)) == 0)
        return;
    for (i = 0; i < 3; i++)
        e[i] = sat_add_u32(e[i], (uint32_t)shadowed(lumo_uq16_mul_q14(L->value[i], (lumo_q1_14)cos_n), vis));
}

void lumo_raster_shade_point(const lumo_raster_scene *s, const lumo_q16_16 p[3], const lumo_q1_14 n[3],
                             const int32_t *indirect, lumo_uq16_16 out[3])
{
    lumo_uq16_16 e[3] = {0, 0, 0}, ind[3] = {0, 0, 0};
    uint32_t i, count = s->light_count;

    if (count > LUMO_MAX_LIGHTS)
        count = LUMO_MAX_LIGHTS;
    for (i = 0; i < count; i++) {
        const lumo_raster_light *L = &s->lights[i];
        if (L->kind == LUMO_LIGHT_DIRECTIONAL)
            add_directional(L, p, n, e);
        else
            add_local_light(L, p, n, e);
    }
    if (indirect) {
        for (i = 0; i < 3; i++)
            ind[i] = indirect[i] < 0 ? 0u : (uint32_t)indirect[i];
    } else if (s->indirect) {
        s->indirect(s->indirect_ctx, p, n, ind);
    }
    for (i = 0; i < 3; i++)
        out[i] = sat_add_u32(e[i], ind[i]);
}

/* ---- per-pixel lighting in the Cortex-M3's arithmetic (round four) ------- */

/* u ~ 2^46 / sqrt(v) for v in [2^30, 2^32), in (2^30, 2^31]: a seed within
 * 0.4% (lumo_raster_rsqrt_seed) and one Newton step u (3 - v u^2) / 2
 * (error 1.5 e^2 < 2^-15) in 32 x 32-bit multiplies: no division. */
static uint32_t rsqrt32(uint32_t v)
{
    uint32_t u = lumo_raster_rsqrt_seed[v >> 24];
    uint32_t a = (uint32_t)(((uint64_t)u * u) >> 32);        /* 2^60 / v */
    uint32_t g = (uint32_t)(((uint64_t)v * a) >> 30);        /* 1.0 in Q30 */

    return (uint32_t)(((uint64_t)u * (((uint32_t)3 << 30) - g)) >> 31);
}

/* (a b) >> s saturated to 32 bits, from the product's two words (a 64-bit
 * shift by a variable amount is a branchy sequence on the Cortex-M3). */
static uint32_t mul_shift_sat(uint32_t a, uint32_t b, unsigned s)
{
    uint64_t w = (uint64_t)a * b;
    uint32_t hi = (uint32_t)(w >> 32), lo = (uint32_t)w;

    if (s >= 32)
        return s >= 64 ? 0 : hi >> (s - 32);
    if (s == 0 || hi >> s)
        return s == 0 && hi == 0 ? lo : UINT32_MAX;
    return (hi << (32 - s)) | (lo >> s);
}

/* floor(v / 2^s) for |v| < 2^30 without shifting a negative value. */
static int32_t floor_shift(int32_t v, unsigned s)
{
    return (int32_t)(((uint32_t)v + ((uint32_t)1 << 31)) >> s) - (int32_t)(((uint32_t)1 << 31) >> s);
}

/* add_local_light in 32-bit steps and without a division. The light
 * vector l = pos - p is taken in units of 2^dsh (the triangle's shift,
 * lumo_raster_pixel_fixed_init: every component then below 2^15), so
 * |l|^2, n . l and the cone's l . axis are 32-bit sums; |l|^2 is
 * normalised by an even CLZ shift z to t in [2^30, 2^32) and u =
 * rsqrt32(t) ~ 2^46 / sqrt(t) gives cos = (n . l) u / 2^(46 - z/2) (Q14)
 * and 1/|l|^2 from u^2: E = (I f) >> (27 + 2 dsh - z), f = cos u^2 / 2^47.
 * The same MIN_DIST2 clamp, cone test and shadow as the exact path;
 * relative error about 2^-14 (the seed's Newton step and the 15 bits of
 * the shortest l over the triangle). */
static void add_local_light32(const lumo_raster_light *L, const uint32_t inten[3], unsigned dsh,
                              const lumo_q16_16 p[3], const lumo_q1_14 n[3], lumo_uq16_16 e[3])
{
    int32_t d0 = floor_shift(L->pos[0] - p[0], dsh), d1 = floor_shift(L->pos[1] - p[1], dsh);
    int32_t d2 = floor_shift(L->pos[2] - p[2], dsh), ln = d0 * n[0] + d1 * n[1] + d2 * n[2];
    uint32_t dist2 = (uint32_t)(d0 * d0) + (uint32_t)(d1 * d1) + (uint32_t)(d2 * d2);
    uint32_t vis = 256, top, u, cos_n, f;
    unsigned z, shift;
    int i;

    if (ln <= 0 || dist2 == 0)
        return;
    z = lumo_raster_clz32(dist2) & ~1u;
    top = dist2 << z;
    u = rsqrt32(top);
    if (L->kind == LUMO_LIGHT_SPOT) {
        int32_t la = d0 * L->dir[0] + d1 * L->dir[1] + d2 * L->dir[2];
        uint64_t dist = ((uint64_t)top * u) >> (46 - dsh + z / 2);    /* Q16 */
        if (-(int64_t)la * ((int64_t)1 << dsh) < (int64_t)L->cos_cutoff * (int64_t)dist)
            return;
    }
    if (L->shadow && (vis = lumo_raster_shadow_visibility(L->shadow, p, n)) == 0)
        return;
    /* (ln u) >> (46 - z/2) as a 32-bit shift of the product's top 33 bits
     * (ln u < 2^63): z reaches 30 when |l|^2 < 4 units of 2^dsh, where a
     * shift of the top 32 bits by 14 - z/2 would be by -1 */
    cos_n = (uint32_t)(((uint64_t)(uint32_t)ln * u) >> 31) >> (15 - z / 2);    /* Q14 */
    if (cos_n > 2 * LUMO_Q14_ONE)
        cos_n = 2 * LUMO_Q14_ONE;
    /* |l|^2 (Q32) = dist2 2^(2 dsh) clamped to MIN_DIST2 << 16 */
    if (2 * dsh < 24 && dist2 < ((uint32_t)1 << (24 - 2 * dsh)))
        f = cos_n, shift = 6;
    else
        f = (uint32_t)(((uint64_t)cos_n * (uint32_t)(((uint64_t)u * u) >> 32)) >> 15), shift = 27 + 2 * dsh - z;
    for (i = 0; i < 3; i++)
        e[i] = sat_add_u32(e[i], (uint32_t)shadowed(mul_shift_sat(inten[i], f, shift), vis));
}

/* lumo_raster_renormalize_q14 in 32 bits: |v|^2 (Q28) within [7/8, 9/8],
 * two Newton steps for 1/|v| from 1 in Q28; other lengths take
 * lumo_raster_normalize_q14. */
static void renormalize32(const int32_t v[3], lumo_q1_14 out[3])
{
    const uint32_t lo = (uint32_t)7 << 25, hi = (uint32_t)9 << 25, one = (uint32_t)1 << 28;
    uint32_t s2, k, t;
    int i;

    if (v[0] > 32767 || v[0] < -32768 || v[1] > 32767 || v[1] < -32768 || v[2] > 32767 || v[2] < -32768) {
        lumo_raster_normalize_q14(v, out);
        return;
    }
    s2 = (uint32_t)(v[0] * v[0]) + (uint32_t)(v[1] * v[1]) + (uint32_t)(v[2] * v[2]);   /* Q28 */
    if (s2 < lo || s2 > hi) {
        lumo_raster_normalize_q14(v, out);
        return;
    }
    k = (3 * one - s2) / 2;                                           /* first step from 1 */
    t = (uint32_t)(((uint64_t)s2 * (uint32_t)(((uint64_t)k * k) >> 28)) >> 28);
    k = (uint32_t)(((uint64_t)k * (3 * one - t)) >> 29);
    /* v k rounded, made positive by 2^60 before the shift (|v k| < 2^45) */
    for (i = 0; i < 3; i++)
        out[i] = lumo_sat_i16((int32_t)((int64_t)((uint64_t)((int64_t)v[i] * k + ((int64_t)1 << 60)
                                                              + ((int64_t)1 << 27)) >> 28) - ((int64_t)1 << 32)));
}

/* One pixel of per-pixel lighting from its varyings (position, normal,
 * albedo, and the per-vertex indirect light when nvar says so): the
 * shading of lumo_raster_shade_point, lumo_raster_radiance and the tone
 * map, with the normal renormalised and the point and spot lights
 * evaluated in 32-bit steps (no division), the sRGB codes exact. */
/* (eye - p) . n, Q30: the side of n the eye is on. */
static int64_t facing(const lumo_raster_view *view, const int32_t p[3], const lumo_q1_14 n[3])
{
    return ((int64_t)view->eye[0] - p[0]) * n[0] + ((int64_t)view->eye[1] - p[1]) * n[1]
         + ((int64_t)view->eye[2] - p[2]) * n[2];
}

/* A normal shared by the three vertices, renormalised and turned to the
 * eye: 1 when it is turned the same way at every point of the triangle.
 * (eye - p) . n is affine in p: the same sign at the three vertices (with a
 * margin of 2^20, far more than the interpolation's rounding of p by a
 * unit times |n| < 2^15) is the same sign everywhere between. */
static int fixed_normal(const lumo_raster_view *view, const int32_t *v0, const int32_t *v1,
                        const int32_t *v2, lumo_q1_14 out[3])
{
    const int64_t margin = (int64_t)1 << 20;
    int64_t f0, f1, f2;
    int k;

    for (k = 3; k < 6; k++)
        if (v0[k] != v1[k] || v0[k] != v2[k])
            return 0;
    renormalize32(&v0[3], out);
    f0 = facing(view, v0, out), f1 = facing(view, v1, out), f2 = facing(view, v2, out);
    if (f0 > margin && f1 > margin && f2 > margin)
        return 1;
    if (f0 < -margin && f1 < -margin && f2 < -margin) {
        out[0] = (lumo_q1_14)-out[0], out[1] = (lumo_q1_14)-out[1], out[2] = (lumo_q1_14)-out[2];
        return 1;
    }
    return 0;
}

/* rho (Q1.14, clamped to [0, 1]) times exposure / pi (Q16): Q16. */
static uint32_t rho_k(int32_t rho, uint32_t k)
{
    uint32_t r = rho < 0 ? 0u : rho > LUMO_Q14_ONE ? (uint32_t)LUMO_Q14_ONE : (uint32_t)rho;

    return (uint32_t)(((uint64_t)r * k) >> LUMO_Q14_SHIFT);
}

/* The shift that brings pos - p below 2^15 per axis for every p of the
 * triangle (v0, v1, v2: a pixel's position is a convex combination of
 * theirs, give or take the interpolation's rounding by a unit). The caller
 * keeps |pos - v| < 2^30. */
static unsigned light_shift(const lumo_q16_16 pos[3], const int32_t *v0, const int32_t *v1, const int32_t *v2)
{
    int64_t m = 0;
    unsigned sh = 0;
    int k;

    for (k = 0; k < 3; k++) {
        int64_t a = (int64_t)pos[k] - v0[k], b = (int64_t)pos[k] - v1[k], c = (int64_t)pos[k] - v2[k];
        a = a < 0 ? -a : a, b = b < 0 ? -b : b, c = c < 0 ? -c : c;
        m = a > m ? a : m, m = b > m ? b : m, m = c > m ? c : m;
    }
    while ((m + 2) >> sh >= ((int64_t)1 << 15))
        sh++;
    return sh;
}

/* The sRGB code of E rho exposure / pi from E (UQ16.16) and rho exposure /
 * pi (Q16): Q32, UQ8.24 after >> 8; code 255 from 1.0 (2^32) up. */
LUMO_RASTER_HOT unsigned tone32(uint32_t e, uint32_t rk)
{
    uint64_t v = (uint64_t)e * rk;

    return v >> 32 ? 255u : lumo_raster_srgb_code24((uint32_t)v >> 8);
}

void lumo_raster_pixel_fixed_init(lumo_raster_pixel_fixed *pf, const lumo_raster_view *view,
                                  const lumo_raster_scene *s, const int32_t *v0, const int32_t *v1,
                                  const int32_t *v2)
{
    const uint32_t lim = (uint32_t)1 << 31;
    uint32_t i, l;

    pf->count = s->light_count > LUMO_MAX_LIGHTS ? LUMO_MAX_LIGHTS : s->light_count;
    for (l = 0; l < pf->count; l++) {
        for (i = 0; i < 3; i++)
            pf->inten[l][i] = (uint32_t)(((uint64_t)s->lights[l].value[i] * INV_4PI_Q32 + ((uint64_t)1 << 31)) >> 32);
        pf->dsh[l] = light_shift(s->lights[l].pos, v0, v1, v2);
    }
    pf->k = (uint32_t)(((uint64_t)(s->exposure > lim ? lim : s->exposure) * INV_PI_Q32 + ((uint64_t)1 << 31)) >> 32);
    pf->nfixed = fixed_normal(view, v0, v1, v2, pf->n);
    pf->rfixed = v0[6] == v1[6] && v0[6] == v2[6] && v0[7] == v1[7] && v0[7] == v2[7] && v0[8] == v1[8]
              && v0[8] == v2[8];
    for (i = 0; i < 3; i++)
        pf->rk[i] = rho_k(v0[6 + i], pf->k);
}

/* One pixel of per-pixel lighting from its varyings (position, normal,
 * albedo, and the per-vertex indirect light when nvar says so): the
 * shading of lumo_raster_shade_point, lumo_raster_radiance and the tone
 * map, with the normal renormalised and the point and spot lights
 * evaluated in 32-bit steps (no division), the light intensities and
 * rho exposure / pi from the triangle's constants, the sRGB codes exact. */
void lumo_raster_shade_pixel32(const lumo_raster_view *view, const lumo_raster_scene *s,
                               const lumo_raster_pixel_fixed *pf, unsigned nvar, const int32_t var[],
                               unsigned code[3])
{
    lumo_q1_14 n[3];
    lumo_uq16_16 e[3];
    uint32_t i;

    if (pf->nfixed) {
        n[0] = pf->n[0], n[1] = pf->n[1], n[2] = pf->n[2];
    } else {
        renormalize32(&var[3], n);
        if (facing(view, var, n) < 0)
            n[0] = (lumo_q1_14)-n[0], n[1] = (lumo_q1_14)-n[1], n[2] = (lumo_q1_14)-n[2];
    }
    /* The lights add onto the indirect light: saturating sums of
     * non-negative terms are min(sum, 2^32 - 1) in any order, so this is
     * lumo_raster_shade_point's direct + indirect without the final adds. */
    if (nvar > LUMO_RASTER_VAR_PIXEL) {
        for (i = 0; i < 3; i++)
            e[i] = var[9 + i] < 0 ? 0u : (uint32_t)var[9 + i];
    } else if (s->indirect) {
        s->indirect(s->indirect_ctx, var, n, e);
    } else {
        e[0] = e[1] = e[2] = 0;
    }
    for (i = 0; i < pf->count; i++) {
        const lumo_raster_light *L = &s->lights[i];
        if (L->kind == LUMO_LIGHT_DIRECTIONAL)
            add_directional(L, var, n, e);
        else
            add_local_light32(L, pf->inten[i], pf->dsh[i], var, n, e);
    }
    if (pf->rfixed) {
        code[0] = tone32(e[0], pf->rk[0]);
        code[1] = tone32(e[1], pf->rk[1]);
        code[2] = tone32(e[2], pf->rk[2]);
    } else {
        for (i = 0; i < 3; i++)
            code[i] = tone32(e[i], rho_k(var[6 + i], pf->k));
    }
}

void lumo_raster_irradiance(const lumo_raster_scene *s, const lumo_q16_16 p[3],
                            const lumo_q1_14 n[3], lumo_uq16_16 out[3])
{
    lumo_raster_shade_point(s, p, n, NULL, out);
}

void lumo_raster_radiance(const lumo_uq16_16 e[3], const lumo_q1_14 albedo[3],
                          lumo_uq16_16 out[3])
{
    int i;

    for (i = 0; i < 3; i++) {
        uint64_t rho = albedo[i] < 0 ? 0 : (uint64_t)albedo[i];
        uint64_t er;
        if (rho > (uint64_t)LUMO_Q14_ONE)
            rho = (uint64_t)LUMO_Q14_ONE;
        er = ((uint64_t)e[i] * rho + ((uint64_t)1 << 13)) >> LUMO_Q14_SHIFT;
        out[i] = (lumo_uq16_16)((er * INV_PI_Q32 + ((uint64_t)1 << 31)) >> 32);
    }
}

uint8_t lumo_raster_tonemap(lumo_uq16_16 radiance, lumo_uq16_16 exposure)
{
    const uint32_t lim = (uint32_t)1 << 31;

    return (uint8_t)lumo_raster_srgb_code(((uint64_t)(radiance > lim ? lim : radiance)
                                           * (exposure > lim ? lim : exposure)) >> 8);
}

/* 4x4 Bayer matrix: thresholds 0..15 for the RGB565 ordered dither. */
const uint8_t lumo_raster_bayer4[4][4] = {
    { 0,  8,  2, 10}, {12,  4, 14,  6}, { 3, 11,  1,  9}, {15,  7, 13,  5}
};
