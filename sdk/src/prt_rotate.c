/* prt_rotate.c — rotating the SH lighting vector in fixed point (lumo/prt.h;
 * seed 003 §3.2 rotates the lighting rather than re-projecting it). The
 * zonal ("ZXZXZ") method: R = Rz(gamma) Ry(beta) Rz(alpha) with
 * Ry(beta) = Rx(-90) Rz(beta) Rx(+90); a z rotation turns each band's
 * (m, -m) pair by m times the angle, Rx(+90)'s blocks are constants
 * (prt_tables.c) and Rx(-90)'s are their transposes. */
#include <string.h>
#include "lumo/prt.h"
#include "prt_internal.h"

/* Q2.30 values in int64 during the rotation; turned to Q16.16 at the end. */
typedef int64_t coeff_t;

/* The pair scaled to unit length in Q2.30: a Q1.14 pair's own length is
 * off by up to ~1e-4, which cos/sin(m t) would raise to the m-th power. */
static void unit_q30(const lumo_q1_14 cs[2], int64_t *c, int64_t *s)
{
    uint64_t r2 = (uint64_t)((int32_t)cs[0] * cs[0] + (int32_t)cs[1] * cs[1]);
    int64_t len = (int64_t)lumo_isqrt64(r2 << 32);   /* |pair| in 2^30 units */
    *c = lumo_prt_div_round((int64_t)cs[0] * ((int64_t)1 << 46), len);
    *s = lumo_prt_div_round((int64_t)cs[1] * ((int64_t)1 << 46), len);
}

/* f turned by Rz(angle): for m > 0, a' = a cos(m t) - b sin(m t),
 * b' = a sin(m t) + b cos(m t), a at index +m, b at -m. cs: Q1.14. */
static void rot_z(coeff_t *v, unsigned order, const lumo_q1_14 cs[2])
{
    int64_t c1, s1;
    unit_q30(cs, &c1, &s1);
    int64_t cm = c1, sm = s1;
    for (unsigned m = 1; m < order; m++) {
        for (unsigned l = m; l < order; l++) {
            coeff_t *a = &v[l * (l + 1) + m], *b = &v[l * (l + 1) - m];
            coeff_t na = lumo_round_shift(*a * cm - *b * sm, 30);
            *b = lumo_round_shift(*a * sm + *b * cm, 30);
            *a = na;
        }
        int64_t nc = lumo_round_shift(cm * c1 - sm * s1, 30);
        sm = lumo_round_shift(sm * c1 + cm * s1, 30);
        cm = nc;
    }
}

/* f turned by Rx(+90) (transpose = 0) or Rx(-90) (transpose = 1). */
static void rot_x90(coeff_t *v, unsigned order, int transpose)
{
    coeff_t t[2 * LUMO_PRT_MAX_ORDER - 1];
    size_t off = 0;
    for (unsigned l = 0; l < order; l++) {
        unsigned n = 2 * l + 1, base = l * l;
        for (unsigned i = 0; i < n; i++) {
            int64_t s = 0;
            for (unsigned j = 0; j < n; j++) {
                int32_t m = transpose ? lumo_prt_rx90[off + j * n + i] : lumo_prt_rx90[off + i * n + j];
                s += lumo_round_shift((int64_t)m * v[base + j], 30);
            }
            t[i] = s;
        }
        memcpy(&v[base], t, n * sizeof *t);
        off += (size_t)n * n;
    }
}

static int unit_pair(const lumo_q1_14 cs[2])
{
    int32_t n = (int32_t)cs[0] * cs[0] + (int32_t)cs[1] * cs[1];   /* Q28, 1.0 = 2^28 */
    return n > (1 << 28) - (1 << 18) && n < (1 << 28) + (1 << 18);
}

lumo_status lumo_prt_light_rotate(const lumo_prt_light *in, const lumo_q1_14 alpha[2],
                                  const lumo_q1_14 beta[2], const lumo_q1_14 gamma[2],
                                  lumo_prt_light *out)
{
    coeff_t v[LUMO_PRT_MAX_COEFFS];
    if (!in || !alpha || !beta || !gamma || !out || in == out)
        return LUMO_ERR_ARG;
    if (in->order < 1 || in->order > LUMO_PRT_MAX_ORDER)
        return LUMO_ERR_RANGE;
    if (!unit_pair(alpha) || !unit_pair(beta) || !unit_pair(gamma))
        return LUMO_ERR_RANGE;
    unsigned order = in->order, nc = order * order;
    out->order = in->order;
    for (unsigned c = 0; c < 3; c++) {
        for (unsigned i = 0; i < nc; i++)
            v[i] = (coeff_t)in->c[c][i] * 16384;   /* Q16.16 -> 30 fraction bits */
        rot_z(v, order, alpha);
        rot_x90(v, order, 0);
        rot_z(v, order, beta);
        rot_x90(v, order, 1);
        rot_z(v, order, gamma);
        for (unsigned i = 0; i < nc; i++)
            out->c[c][i] = lumo_sat_i32(lumo_round_shift(v[i], 14));
        for (unsigned i = nc; i < LUMO_PRT_MAX_COEFFS; i++)
            out->c[c][i] = 0;
    }
    return LUMO_OK;
}
