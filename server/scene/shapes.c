/* shapes.c — rectangles, cuboids, spheres and area-light emitters built in
 * code (for the default scene, scene files and the physics tests). */
#include <math.h>
#include "scene/shapes.h"

static void fill_albedo(srv_mesh *m, vec3 albedo)
{
    for (uint32_t i = 0; i < m->nverts; i++)
        m->albedo[i] = albedo;
}

lumo_status srv_add_quad(srv_scene *s, const char *name, vec3 corner, vec3 u, vec3 v, vec3 albedo)
{
    srv_mesh *m = srv_scene_add_mesh(s, name, 4, 2);
    if (!m)
        return LUMO_ERR_NOMEM;
    m->pos[0] = corner;
    m->pos[1] = v3_add(corner, u);
    m->pos[2] = v3_add(v3_add(corner, u), v);
    m->pos[3] = v3_add(corner, v);
    static const uint32_t t[6] = {0, 1, 2, 0, 2, 3};
    for (int i = 0; i < 6; i++)
        m->tris[i] = t[i];
    fill_albedo(m, albedo);
    return LUMO_OK;
}

lumo_status srv_add_box(srv_scene *s, const char *name, vec3 lo, vec3 hi, vec3 albedo, int inward)
{
    vec3 d = v3_sub(hi, lo);
    vec3 ex = v3(d.x, 0, 0), ey = v3(0, d.y, 0), ez = v3(0, 0, d.z);
    /* Each face as (corner, u, v) with u x v pointing out of the box. */
    vec3 f[6][3] = {
        {lo, ez, ey}, {v3_add(lo, ex), ey, ez},       /* -x, +x */
        {lo, ex, ez}, {v3_add(lo, ey), ez, ex},       /* -y, +y */
        {lo, ey, ex}, {v3_add(lo, ez), ex, ey},       /* -z, +z */
    };
    for (int i = 0; i < 6; i++) {
        vec3 u = inward ? f[i][2] : f[i][1], v = inward ? f[i][1] : f[i][2];
        lumo_status st = srv_add_quad(s, name, f[i][0], u, v, albedo);
        if (st)
            return st;
    }
    return LUMO_OK;
}

lumo_status srv_add_sphere(srv_scene *s, const char *name, vec3 c, float r, int segments,
                           vec3 albedo, int inward)
{
    int nu = segments < 8 ? 8 : segments, nv = nu / 2;
    uint32_t nverts = (uint32_t)((nv - 1) * nu + 2), ntris = (uint32_t)(2 * nu * (nv - 1));
    srv_mesh *m = srv_scene_add_mesh(s, name, nverts, ntris);
    if (!m)
        return LUMO_ERR_NOMEM;
    m->pos[0] = v3_add(c, v3(0, r, 0));
    m->pos[nverts - 1] = v3_add(c, v3(0, -r, 0));
    for (int j = 1; j < nv; j++)
        for (int i = 0; i < nu; i++) {
            double th = M_PI * j / nv, ph = 2.0 * M_PI * i / nu;
            m->pos[1 + (j - 1) * nu + i] = v3_add(c, v3((float)(r * sin(th) * cos(ph)),
                                                         (float)(r * cos(th)),
                                                         (float)(r * sin(th) * sin(ph))));
        }
    uint32_t *t = m->tris;
#define RING(j, i) ((uint32_t)(1 + ((j) - 1) * nu + ((i) % nu)))
    for (int i = 0; i < nu; i++) {          /* caps, then the bands between rings */
        uint32_t a[3] = {0, RING(1, i + 1), RING(1, i)};
        uint32_t b[3] = {nverts - 1, RING(nv - 1, i), RING(nv - 1, i + 1)};
        for (int k = 0; k < 3; k++) t[k] = a[k], t[3 + k] = b[k];
        t += 6;
    }
    for (int j = 1; j < nv - 1; j++)
        for (int i = 0; i < nu; i++) {
            uint32_t q[6] = {RING(j, i), RING(j, i + 1), RING(j + 1, i + 1),
                             RING(j, i), RING(j + 1, i + 1), RING(j + 1, i)};
            for (int k = 0; k < 6; k++) t[k] = q[k];
            t += 6;
        }
#undef RING
    /* The winding above faces out; a room faces in. */
    if (inward)
        for (uint32_t k = 0; k < ntris; k++) {
            uint32_t tmp = m->tris[3 * k + 1];
            m->tris[3 * k + 1] = m->tris[3 * k + 2];
            m->tris[3 * k + 2] = tmp;
        }
    fill_albedo(m, albedo);
    return LUMO_OK;
}

lumo_status srv_add_area_light(srv_scene *s, const srv_light *l)
{
    lumo_status st = srv_scene_add_light(s, l);
    if (!st)
        st = srv_add_quad(s, "area-light", l->pos, l->u, l->v, v3(0, 0, 0));
    if (st)
        return st;
    s->meshes[s->nmeshes - 1].emitter = 1;
    return LUMO_OK;
}
