/* prt_light.c — the SH lighting vector on the client (lumo/prt.h; seed 003
 * §3.2: the lighting vector, projected from the scene's lights): real SH in
 * fixed point by the associated-Legendre recurrence, integers only. */
#include <string.h>
#include "lumo/prt.h"
#include "prt_internal.h"

lumo_status lumo_prt_light_clear(lumo_prt_light *l, unsigned order)
{
    if (!l)
        return LUMO_ERR_ARG;
    if (order < 1 || order > LUMO_PRT_MAX_ORDER)
        return LUMO_ERR_RANGE;
    memset(l, 0, sizeof *l);
    l->order = (uint8_t)order;
    return LUMO_OK;
}

/* q[l][m] = P_l^m(z) / sin^m, Q30 in int64 (|q| < 2^14 for l < 6, so the
 * products below stay under 2^62). z: Q1.14. */
static void legendre_q(unsigned order, int32_t z, int64_t q[LUMO_PRT_MAX_ORDER][LUMO_PRT_MAX_ORDER])
{
    int64_t qmm = (int64_t)1 << 30;
    for (unsigned m = 0; m < order; m++) {
        if (m > 0)
            qmm *= 2 * (int64_t)m - 1;
        q[m][m] = qmm;
        if (m + 1 < order)
            q[m + 1][m] = lumo_round_shift((int64_t)z * (2 * (int64_t)m + 1) * lumo_round_shift(qmm, 8), 6);
        for (unsigned l = m + 2; l < order; l++) {
            int64_t a = lumo_round_shift((int64_t)z * (2 * (int64_t)l - 1) * lumo_round_shift(q[l - 1][m], 8), 6);
            int64_t b = ((int64_t)l + m - 1) * q[l - 2][m];
            q[l][m] = lumo_prt_div_round(a - b, (int64_t)(l - m));
        }
    }
}

void lumo_prt_sh_eval(unsigned order, const lumo_q1_14 d[3], int32_t *y)
{
    int64_t q[LUMO_PRT_MAX_ORDER][LUMO_PRT_MAX_ORDER];
    int64_t re = (int64_t)1 << 30, im = 0;   /* (x + iy)^m in Q30 */
    legendre_q(order, d[2], q);
    for (unsigned m = 0; m < order; m++) {
        for (unsigned l = m; l < order; l++) {
            /* K (Q30) times q (Q30 -> Q16): Q30 */
            int64_t kq = lumo_round_shift((int64_t)lumo_prt_sh_k[l * (l + 1) / 2 + m] * lumo_round_shift(q[l][m], 14), 16);
            unsigned i = l * (l + 1);
            if (m == 0) {
                y[i] = (int32_t)kq;
                continue;
            }
            y[i + m] = (int32_t)lumo_round_shift(kq * lumo_round_shift(re, 16), 14);
            y[i - m] = (int32_t)lumo_round_shift(kq * lumo_round_shift(im, 16), 14);
        }
        int64_t nre = lumo_round_shift(re * d[0] - im * d[1], 14);
        im = lumo_round_shift(re * d[1] + im * d[0], 14);
        re = nre;
    }
}

lumo_status lumo_prt_light_add_directional(lumo_prt_light *l, const lumo_q1_14 towards[3],
                                           const lumo_uq16_16 e[3])
{
    int32_t y[LUMO_PRT_MAX_COEFFS];
    if (!l || !towards || !e || l->order < 1 || l->order > LUMO_PRT_MAX_ORDER)
        return LUMO_ERR_ARG;
    lumo_prt_sh_eval(l->order, towards, y);
    for (unsigned c = 0; c < 3; c++)
        for (unsigned i = 0; i < (unsigned)l->order * l->order; i++)
            l->c[c][i] = lumo_sat_i32((int64_t)l->c[c][i] + lumo_round_shift((int64_t)e[c] * y[i], 30));
    return LUMO_OK;
}

/* 4 pi in Q16.16. */
#define PRT_FOUR_PI_Q16 823550

/* The local light's offset from the centre, halved until it fits 30 bits
 * (*shift halvings), so that its squared length stays in 64 bits. */
static void light_offset(const lumo_pkg_light *light, const lumo_q16_16 centre[3], int32_t d[3], unsigned *shift)
{
    int64_t v[3], m = 0;
    for (unsigned a = 0; a < 3; a++) {
        int64_t p = light->pos[a];
        if (light->kind == LUMO_LIGHT_AREA)
            p += ((int64_t)light->u[a] + light->v[a]) / 2;
        v[a] = p - centre[a];
        m |= v[a] < 0 ? -v[a] : v[a];
    }
    for (*shift = 0; m >= ((int64_t)1 << 30); (*shift)++)
        m /= 2;
    for (unsigned a = 0; a < 3; a++)
        d[a] = (int32_t)(v[a] / ((int64_t)1 << *shift));
}

/* power / (4 pi r^2) with r^2 = sum d^2 * 4^shift / 2^32, UQ16.16, saturated. */
static lumo_uq16_16 irradiance_at(lumo_uq16_16 power, const int32_t d[3], unsigned shift)
{
    uint64_t r2 = 0;
    for (unsigned a = 0; a < 3; a++)
        r2 += (uint64_t)((int64_t)d[a] * d[a]);
    uint64_t q = ((uint64_t)power << 16) / PRT_FOUR_PI_Q16;   /* power / 4pi, Q16.16 */
    if (2 * shift > 32)
        return 0;
    uint64_t num = q << (32 - 2 * shift);   /* q < 2^29: fits */
    uint64_t e = (num + r2 / 2) / r2;       /* rounded to nearest */
    return e > (uint64_t)UINT32_MAX ? UINT32_MAX : (lumo_uq16_16)e;
}

lumo_status lumo_prt_light_add_pkg(lumo_prt_light *l, const lumo_pkg_light *light, const lumo_q16_16 centre[3])
{
    lumo_q1_14 towards[3];
    lumo_uq16_16 e[3];
    int32_t d[3];
    unsigned shift;
    if (!l || !light || !centre)
        return LUMO_ERR_ARG;
    if (light->kind == LUMO_LIGHT_DIRECTIONAL) {
        for (unsigned a = 0; a < 3; a++)
            towards[a] = (lumo_q1_14)-light->dir[a];
        return lumo_prt_light_add_directional(l, towards, light->power);
    }
    light_offset(light, centre, d, &shift);
    if (lumo_normalize3_q14(d, towards) != LUMO_OK)
        return LUMO_ERR_RANGE;
    if (light->kind == LUMO_LIGHT_SPOT &&
        -((int32_t)towards[0] * light->dir[0] + (int32_t)towards[1] * light->dir[1] + (int32_t)towards[2] * light->dir[2]) <
            (int32_t)light->cos_half * LUMO_Q14_ONE)
        return LUMO_OK;   /* the centre is outside the cone */
    for (unsigned a = 0; a < 3; a++)
        e[a] = irradiance_at(light->power[a], d, shift);
    return lumo_prt_light_add_directional(l, towards, e);
}
