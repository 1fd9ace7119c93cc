/*
 * scene_camera.c — a camera that frames a box (docs/scene-format.md,
 * "Fitted camera"): what a scene without a camera gets from the server, and
 * what a client asks for when it refits (lumo-render --fit, lumo-client
 * --fit). Integer code only, so the server and every client fit alike.
 */
#include "lumo/scene.h"

/* tan(20 deg), half the fitted 40-degree vertical field of view (Q16.16). */
#define FIT_TAN_HALF_FOVY ((lumo_q16_16)23853)

/* The camera's basis, Q1.14: a three-quarter view from the front (+z),
 * 30 degrees towards +x and 25 degrees above the horizon (y is up), which
 * sees three faces of any box, so flat and tall models both show their
 * shape. to_eye = (cos25 sin30, sin25, cos25 cos30) points from the target
 * to the eye; right = (cos30, 0, -sin30); up = right x forward. */
static const lumo_q1_14 fit_to_eye[3] = {7424, 6924, 12859};
static const lumo_q1_14 fit_right[3] = {14189, 0, -8192};
static const lumo_q1_14 fit_up[3] = {-3462, 14849, -5996};

static int64_t dot_q14(const int64_t p[3], const lumo_q1_14 v[3])
{
    return (p[0] * v[0] + p[1] * v[1] + p[2] * v[2]) >> LUMO_Q14_SHIFT;
}

/* tan of the horizontal and vertical half angles of a width x height frame
 * (Q16.16, at least one unit). */
static void half_tangents(uint32_t width, uint32_t height, int64_t *tx, int64_t *ty)
{
    *ty = FIT_TAN_HALF_FOVY;
    *tx = (int64_t)FIT_TAN_HALF_FOVY * width / height;
    if (*tx < 1)
        *tx = 1;
}

/* The eye distance from the box centre at which every corner is inside the
 * frame: a corner at offset p is in view when its lateral offsets over its
 * depth (d - p.to_eye) are within the half tangents, so
 *   d >= max(|p.right| / tx, |p.up| / ty) + p.to_eye   over the corners,
 * widened by 1/64 so rounding never crops a corner, and at least 1/1024 m. */
static int64_t fit_distance(const int64_t half[3], int64_t tx, int64_t ty)
{
    int64_t need = 0, p[3], lateral, along, d;
    int c, k;

    for (c = 0; c < 8; c++) {
        for (k = 0; k < 3; k++)
            p[k] = (c >> k) & 1 ? half[k] : -half[k];
        lateral = dot_q14(p, fit_right);
        along = dot_q14(p, fit_up);
        lateral = ((lateral < 0 ? -lateral : lateral) << LUMO_Q16_SHIFT) / tx;
        along = ((along < 0 ? -along : along) << LUMO_Q16_SHIFT) / ty;
        d = (lateral > along ? lateral : along) + dot_q14(p, fit_to_eye);
        if (d > need)
            need = d;
    }
    need += need / 64 + 1;
    return need < (LUMO_Q16_ONE >> 10) ? (LUMO_Q16_ONE >> 10) : need;
}

lumo_status lumo_scene_camera_fit(lumo_pkg_info *info, uint32_t width, uint32_t height)
{
    int64_t tx, ty, dist, half[3], centre[3], eye[3];
    int k;

    if (!info || width == 0 || height == 0)
        return LUMO_ERR_ARG;
    for (k = 0; k < 3; k++) {
        if (info->bmin[k] > info->bmax[k])
            return LUMO_ERR_RANGE;
        centre[k] = ((int64_t)info->bmin[k] + info->bmax[k]) / 2;
        half[k] = ((int64_t)info->bmax[k] - info->bmin[k] + 1) / 2;
    }
    half_tangents(width, height, &tx, &ty);
    dist = fit_distance(half, tx, ty);
    for (k = 0; k < 3; k++) {
        eye[k] = centre[k] + ((dist * fit_to_eye[k]) >> LUMO_Q14_SHIFT);
        if (eye[k] > LUMO_Q16_MAX || eye[k] < LUMO_Q16_MIN)
            return LUMO_ERR_RANGE;
    }
    for (k = 0; k < 3; k++) {
        info->eye[k] = (lumo_q16_16)eye[k];
        info->target[k] = (lumo_q16_16)centre[k];
        info->up[k] = k == 1 ? LUMO_Q16_ONE : 0;
    }
    info->fovy_deg = LUMO_SCENE_FIT_FOVY;
    return LUMO_OK;
}
