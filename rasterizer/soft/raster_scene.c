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
    cam->znear = LUMO_RASTER_ZNEAR;
}
