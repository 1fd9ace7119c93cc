/*
 * raster_scene.c — a package's scene (lumo/scene.h: scene info, lights; what
 * a client session hands out) as the rasterizer's camera and lights. The one
 * conversion every client uses: the board client (boards/client/), and
 * lumo-client and lumo-render through tools/lumo-render/session_scene.c.
 */
#include <string.h>
#include "lumo/raster.h"

void lumo_raster_light_from_pkg(const lumo_pkg_light *p, lumo_raster_light *l)
{
    int k;

    memset(l, 0, sizeof *l);
    for (k = 0; k < 3; k++) {
        l->pos[k] = p->pos[k];
        l->dir[k] = p->dir[k];
        l->value[k] = p->power[k];
    }
    l->cos_cutoff = p->cos_half;
    l->kind = p->kind;
    if (p->kind != LUMO_LIGHT_POINT && p->kind != LUMO_LIGHT_SPOT && p->kind != LUMO_LIGHT_DIRECTIONAL) {
        /* An area light: a spot at its centre facing its normal, a
         * 90-degree half angle, power 2 Phi (docs/rasterizer.md). */
        l->kind = LUMO_LIGHT_SPOT;
        l->cos_cutoff = 0;
        for (k = 0; k < 3; k++) {
            l->pos[k] = p->pos[k] + p->u[k] / 2 + p->v[k] / 2;
            l->value[k] = p->power[k] > UINT32_MAX / 2 ? UINT32_MAX : p->power[k] * 2;
        }
    }
}

void lumo_raster_camera_from_info(const lumo_pkg_info *info, lumo_raster_camera *cam)
{
    int k;

    memset(cam, 0, sizeof *cam);
    for (k = 0; k < 3; k++) {
        cam->eye[k] = info->eye[k];
        cam->target[k] = info->target[k];
        cam->up[k] = info->up[k];
    }
    cam->fovy_deg = info->fovy_deg;
    cam->znear = lumo_raster_znear_for_box(cam, info->bmin, info->bmax);
}

/* The unit view direction of cam (Q1.14); LUMO_ERR_RANGE when eye == target.
 * The difference is halved until it fits int32: only its direction counts. */
static lumo_status view_forward(const lumo_raster_camera *cam, lumo_q1_14 f[3])
{
    int64_t d[3];
    int32_t v[3];
    int k, big = 1;

    for (k = 0; k < 3; k++)
        d[k] = (int64_t)cam->target[k] - cam->eye[k];
    while (big) {
        big = 0;
        for (k = 0; k < 3; k++)
            big |= d[k] > INT32_MAX || d[k] < -INT32_MAX;
        for (k = 0; big && k < 3; k++)
            d[k] /= 2;
    }
    for (k = 0; k < 3; k++)
        v[k] = (int32_t)d[k];
    return lumo_normalize3_q14(v, f);
}

lumo_q16_16 lumo_raster_znear_for_box(const lumo_raster_camera *cam, const lumo_q16_16 bmin[3],
                                      const lumo_q16_16 bmax[3])
{
    lumo_q1_14 f[3];
    int64_t nearest = INT64_MAX, w;
    int c, k;

    if (view_forward(cam, f))
        return LUMO_RASTER_ZNEAR;
    /* The view depth is linear in the point, so over the box its minimum
     * lies at a corner; every triangle lies inside the box, so a near plane
     * at half that depth clips nothing and gives 16-bit depth the most
     * resolution the scene allows (docs/rasterizer.md, "16-bit depth"). */
    for (c = 0; c < 8; c++) {
        w = 0;
        for (k = 0; k < 3; k++) {
            lumo_q16_16 p = (c >> k) & 1 ? bmax[k] : bmin[k];
            w += ((int64_t)p - cam->eye[k]) * f[k];
        }
        if (w < nearest)
            nearest = w;
    }
    nearest >>= LUMO_Q14_SHIFT + 1;
    if (nearest < LUMO_RASTER_ZNEAR_MIN)   /* the eye is inside or beside the box */
        return LUMO_RASTER_ZNEAR;
    return nearest > LUMO_Q16_MAX ? LUMO_Q16_MAX : (lumo_q16_16)nearest;
}
