/*
 * raster_view.c — the camera as integer matrices: an orthonormal basis in
 * Q1.14 and cot(fovy/2) from an integer sine table (no float on the client).
 */
#include "raster_internal.h"

/* pi/180 in Q2.30, rounded: converts a degree fraction to radians. */
#define DEG_TO_RAD_Q30 18740330
#define Q30_ONE ((int64_t)1 << 30)

/* sin and cos of half a Q16.16 angle in degrees in [0, 180), Q2.30: the table
 * gives the whole degree d, the angle-sum identity adds the fraction
 * delta (< 1 degree = 0.0175 rad) with sin delta ~ delta - delta^3/6 and
 * cos delta ~ 1 - delta^2/2, whose truncation errors are below 2^-30. */
static void sincos_half_deg(lumo_q16_16 deg, int64_t *sin_out, int64_t *cos_out)
{
    /* The half angle as Q15.17 degrees is `deg` itself: no bit lost. */
    int d = (int)(deg >> 17);
    int64_t frac = deg & 0x1FFFF;
    int64_t delta = (frac * DEG_TO_RAD_Q30 + 0x10000) >> 17;
    int64_t delta2 = (delta * delta) >> 30;
    int64_t cos_d = Q30_ONE - delta2 / 2;
    int64_t sin_d = delta - ((delta2 * delta) >> 30) / 6;
    int64_t s = lumo_raster_sin_deg[d], c = lumo_raster_sin_deg[90 - d];

    *sin_out = (s * cos_d + c * sin_d) >> 30;
    *cos_out = (c * cos_d - s * sin_d) >> 30;
}

lumo_q16_16 lumo_raster_cot_half_deg(lumo_q16_16 deg)
{
    int64_t s, c;

    if (deg < LUMO_Q16_FROM_INT(1) || deg > LUMO_Q16_FROM_INT(179))
        return 0;
    sincos_half_deg(deg, &s, &c);
    return (lumo_q16_16)(((c << 16) + s / 2) / s);
}

/* a x b for Q1.14 vectors, as Q2.28 integers. */
static void cross_q14(const lumo_q1_14 a[3], const lumo_q1_14 b[3], int32_t out[3])
{
    out[0] = (int32_t)a[1] * b[2] - (int32_t)a[2] * b[1];
    out[1] = (int32_t)a[2] * b[0] - (int32_t)a[0] * b[2];
    out[2] = (int32_t)a[0] * b[1] - (int32_t)a[1] * b[0];
}

/* Normalise a difference of Q16.16 points, which may need 33 bits: halving
 * both keeps the direction. */
static lumo_status normalize_diff(const lumo_q16_16 a[3], const lumo_q16_16 b[3],
                                  lumo_q1_14 out[3])
{
    int32_t v[3];
    int i;

    for (i = 0; i < 3; i++)
        v[i] = (int32_t)(((int64_t)a[i] - b[i]) / 2);
    return lumo_normalize3_q14(v, out);
}

/* Reject up vectors within ~0.5 degree of the view direction: their cross
 * product (Q2.28) is then too short to give a trustworthy direction. */
static int long_enough(const int32_t v[3])
{
    int i;

    for (i = 0; i < 3; i++)
        if (v[i] >= (1 << 21) || v[i] <= -(1 << 21))
            return 1;
    return 0;
}

lumo_status lumo_raster_view_init(lumo_raster_view *v, const lumo_raster_camera *cam,
                                  uint16_t width, uint16_t height)
{
    lumo_raster_view nv;
    int32_t up32[3], tmp[3];
    lumo_q1_14 upn[3];
    lumo_status st;
    int i;

    if (!v || !cam)
        return LUMO_ERR_ARG;
    if (width == 0 || height == 0 || width > LUMO_MAX_FRAME_DIM || height > LUMO_MAX_FRAME_DIM)
        return LUMO_ERR_RANGE;
    if (cam->znear <= 0)
        return LUMO_ERR_RANGE;
    nv.cot_half = lumo_raster_cot_half_deg(cam->fovy_deg);
    if (nv.cot_half == 0)
        return LUMO_ERR_RANGE;
    st = normalize_diff(cam->target, cam->eye, nv.rot[2]);
    if (st)
        return st;
    for (i = 0; i < 3; i++)
        up32[i] = cam->up[i];
    st = lumo_normalize3_q14(up32, upn);
    if (st)
        return st;
    cross_q14(nv.rot[2], upn, tmp);           /* right = forward x up */
    if (!long_enough(tmp) || lumo_normalize3_q14(tmp, nv.rot[0]))
        return LUMO_ERR_RANGE;
    cross_q14(nv.rot[0], nv.rot[2], tmp);     /* true up = right x forward */
    if (lumo_normalize3_q14(tmp, nv.rot[1]))
        return LUMO_ERR_RANGE;
    for (i = 0; i < 3; i++)
        nv.eye[i] = cam->eye[i];
    nv.znear = cam->znear;
    nv.width = width;
    nv.height = height;
    *v = nv;
    return LUMO_OK;
}
