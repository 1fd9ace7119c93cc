/* default_scene.c — the built-in Cornell-style scene, seed 000 Figure 1 in
 * spirit (values in docs/scene-format.md). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include "scene/import.h"
#include "scene/shapes.h"

#define DRAGON_LENGTH 1.4f

static lumo_status add_room(srv_scene *s)
{
    vec3 white = v3(0.75f, 0.75f, 0.75f);
    vec3 red = v3(0.63f, 0.065f, 0.05f), green = v3(0.14f, 0.45f, 0.091f);
    /* Front faces look into the room; the front (z = +1) stays open. */
    if (srv_add_quad(s, "floor", v3(-1, 0, -1), v3(0, 0, 2), v3(2, 0, 0), white) ||
        srv_add_quad(s, "ceiling", v3(-1, 2, -1), v3(2, 0, 0), v3(0, 0, 2), white) ||
        srv_add_quad(s, "back", v3(-1, 0, -1), v3(2, 0, 0), v3(0, 2, 0), white) ||
        srv_add_quad(s, "left-red", v3(-1, 0, -1), v3(0, 2, 0), v3(0, 0, 2), red) ||
        srv_add_quad(s, "right-green", v3(1, 0, -1), v3(0, 0, 2), v3(0, 2, 0), green))
        return LUMO_ERR_NOMEM;
    return LUMO_OK;
}

/* Fit the model to DRAGON_LENGTH along its longest horizontal axis, centred
 * on the floor's middle, standing on the floor. */
static lumo_status add_dragon(srv_scene *s, const char *path, vec3 albedo, char *err, size_t errlen)
{
    srv_scene tmp;
    srv_xform x = srv_xform_identity();
    vec3 lo, hi;
    srv_scene_init(&tmp);
    lumo_status st = srv_import_file(&tmp, path, &x, &albedo, err, errlen);
    if (!st && !srv_scene_bounds(&tmp, &lo, &hi))
        st = LUMO_ERR_CORRUPT;
    if (st) {
        srv_scene_free(&tmp);
        return st;
    }
    vec3 ext = v3_sub(hi, lo);
    float k = DRAGON_LENGTH / fmaxf(ext.x, ext.z);
    for (size_t i = 0; i < tmp.nmeshes; i++) {
        const srv_mesh *m = &tmp.meshes[i];
        srv_mesh *d = srv_scene_add_mesh(s, "dragon", m->nverts, m->ntris);
        if (!d) {
            srv_scene_free(&tmp);
            return LUMO_ERR_NOMEM;
        }
        for (uint32_t v = 0; v < m->nverts; v++) {
            vec3 p = v3_sub(m->pos[v], v3(0.5f * (lo.x + hi.x), lo.y, 0.5f * (lo.z + hi.z)));
            d->pos[v] = v3_scale(p, k);
            d->albedo[v] = m->albedo[v];
        }
        memcpy(d->tris, m->tris, 3u * m->ntris * sizeof *m->tris);
    }
    srv_scene_free(&tmp);
    return LUMO_OK;
}

lumo_status srv_default_scene(srv_scene *s, const char *dragon, char *err, size_t errlen)
{
    vec3 gold = v3(0.72f, 0.62f, 0.45f);
    struct stat st;
    srv_light spot = {.kind = LUMO_LIGHT_SPOT, .pos = {0, 1.95f, 0}, .dir = {0, -1, 0},
                      .half_angle_deg = 60.0f, .cos_half = 0.5f, .power = {40, 40, 40}};
    if (add_room(s) || srv_scene_add_light(s, &spot)) {
        snprintf(err, errlen, "out of memory");
        return LUMO_ERR_NOMEM;
    }
    s->camera = srv_camera_default();
    s->has_camera = 1;
    if (dragon && stat(dragon, &st) == 0)
        return add_dragon(s, dragon, gold, err, errlen);
    if (srv_add_sphere(s, "sphere", v3(0, 0.45f, 0), 0.45f, 48, gold, 0)) {
        snprintf(err, errlen, "out of memory");
        return LUMO_ERR_NOMEM;
    }
    return LUMO_OK;
}
