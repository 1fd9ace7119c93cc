/* scene.c — scene container and validation (docs/scene-format.md); the
 * light syntax is light_parse.c's. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "scene/scene.h"

void srv_scene_init(srv_scene *s)
{
    memset(s, 0, sizeof *s);
    s->camera = srv_camera_default();
}

void srv_scene_free(srv_scene *s)
{
    for (size_t i = 0; i < s->nmeshes; i++) {
        free(s->meshes[i].pos);
        free(s->meshes[i].albedo);
        free(s->meshes[i].tris);
    }
    free(s->meshes);
    free(s->lights);
    srv_scene_init(s);
}

static lumo_status grow(void **p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap)
        return LUMO_OK;
    size_t ncap = *cap ? *cap * 2 : 8;
    while (ncap < need)
        ncap *= 2;
    void *q = realloc(*p, ncap * elem);
    if (!q)
        return LUMO_ERR_NOMEM;
    *p = q;
    *cap = ncap;
    return LUMO_OK;
}

srv_mesh *srv_scene_add_mesh(srv_scene *s, const char *name, uint32_t nverts, uint32_t ntris)
{
    if (grow((void **)&s->meshes, &s->cap_meshes, s->nmeshes + 1, sizeof *s->meshes))
        return NULL;
    srv_mesh *m = &s->meshes[s->nmeshes];
    memset(m, 0, sizeof *m);
    snprintf(m->name, sizeof m->name, "%s", name ? name : "mesh");
    m->pos = calloc(nverts ? nverts : 1, sizeof *m->pos);
    m->albedo = calloc(nverts ? nverts : 1, sizeof *m->albedo);
    m->tris = calloc(ntris ? 3u * ntris : 1, sizeof *m->tris);
    if (!m->pos || !m->albedo || !m->tris) {
        free(m->pos);
        free(m->albedo);
        free(m->tris);
        return NULL;
    }
    m->nverts = nverts;
    m->ntris = ntris;
    s->nmeshes++;
    return m;
}

lumo_status srv_scene_add_light(srv_scene *s, const srv_light *l)
{
    lumo_status st = grow((void **)&s->lights, &s->cap_lights, s->nlights + 1, sizeof *s->lights);
    if (st)
        return st;
    s->lights[s->nlights++] = *l;
    return LUMO_OK;
}

void srv_scene_override_albedo(srv_scene *s, vec3 albedo)
{
    for (size_t i = 0; i < s->nmeshes; i++)
        for (uint32_t v = 0; v < s->meshes[i].nverts && !s->meshes[i].emitter; v++)
            s->meshes[i].albedo[v] = albedo;
}

int srv_scene_bounds(const srv_scene *s, vec3 *bmin, vec3 *bmax)
{
    int any = 0;
    for (size_t i = 0; i < s->nmeshes; i++)
        for (uint32_t v = 0; v < s->meshes[i].nverts; v++) {
            vec3 p = s->meshes[i].pos[v];
            *bmin = any ? v3_min(*bmin, p) : p;
            *bmax = any ? v3_max(*bmax, p) : p;
            any = 1;
        }
    return any;
}

size_t srv_scene_triangle_count(const srv_scene *s)
{
    size_t n = 0;
    for (size_t i = 0; i < s->nmeshes; i++)
        n += s->meshes[i].ntris;
    return n;
}

static lumo_status validate_mesh(const srv_mesh *m, float min_area, char *err, size_t errlen)
{
    for (uint32_t v = 0; v < m->nverts; v++)
        if (!v3_finite(m->pos[v])) {
            snprintf(err, errlen, "mesh '%s': vertex %u has a non-finite coordinate", m->name, v);
            return LUMO_ERR_NONFINITE;
        }
    for (uint32_t t = 0; t < m->ntris; t++) {
        const uint32_t *ix = &m->tris[3 * t];
        if (ix[0] >= m->nverts || ix[1] >= m->nverts || ix[2] >= m->nverts) {
            snprintf(err, errlen, "mesh '%s': face %u indexes a missing vertex", m->name, t);
            return LUMO_ERR_RANGE;
        }
        vec3 a = m->pos[ix[0]];
        float area = 0.5f * v3_len(v3_cross(v3_sub(m->pos[ix[1]], a), v3_sub(m->pos[ix[2]], a)));
        if (!(area > min_area)) {
            snprintf(err, errlen, "mesh '%s': face %u has zero area", m->name, t);
            return LUMO_ERR_CORRUPT;
        }
    }
    return LUMO_OK;
}

lumo_status srv_scene_check_range(const srv_scene *s, char *err, size_t errlen)
{
    for (size_t i = 0; i < s->nmeshes; i++)
        for (uint32_t v = 0; v < s->meshes[i].nverts; v++)
            for (int a = 0; a < 3; a++) {
                float c = v3_get(s->meshes[i].pos[v], a);
                if (fabsf(c) <= SRV_SCENE_MAX_COORD)
                    continue;
                if (!isfinite(c)) {
                    snprintf(err, errlen, "mesh %zu (%s), vertex %u: non-finite %c", i, s->meshes[i].name, v,
                             "xyz"[a]);
                    return LUMO_ERR_NONFINITE;
                }
                snprintf(err, errlen, "mesh %zu (%s), vertex %u: %c = %.9g m is beyond the client's +-%.0f m "
                         "(Q16.16 positions, lumo/fixed.h): scale the model down", i, s->meshes[i].name, v,
                         "xyz"[a], c, SRV_SCENE_MAX_COORD);
                return LUMO_ERR_RANGE;
            }
    for (size_t i = 0; i < s->nlights; i++) {
        const srv_light *l = &s->lights[i];
        vec3 far = v3_add(l->pos, v3_add(l->u, l->v));
        if (fabsf(v3_maxc(v3(fabsf(l->pos.x), fabsf(l->pos.y), fabsf(l->pos.z)))) > SRV_SCENE_MAX_COORD ||
            fabsf(v3_maxc(v3(fabsf(far.x), fabsf(far.y), fabsf(far.z)))) > SRV_SCENE_MAX_COORD) {
            snprintf(err, errlen, "light %zu: at (%g, %g, %g), beyond the client's +-%.0f m (Q16.16, lumo/fixed.h)",
                     i, l->pos.x, l->pos.y, l->pos.z, SRV_SCENE_MAX_COORD);
            return LUMO_ERR_RANGE;
        }
    }
    return LUMO_OK;
}

lumo_status srv_scene_validate(const srv_scene *s, char *err, size_t errlen)
{
    vec3 lo, hi;
    if (srv_scene_triangle_count(s) == 0 || !srv_scene_bounds(s, &lo, &hi)) {
        snprintf(err, errlen, "the scene has no geometry");
        return LUMO_ERR_ARG;
    }
    if (s->nlights == 0) {
        snprintf(err, errlen, "the scene has no light (add one with --light)");
        return LUMO_ERR_ARG;
    }
    if (s->nlights > LUMO_MAX_LIGHTS) {
        snprintf(err, errlen, "the scene has %zu lights, at most %d are supported", s->nlights,
                 LUMO_MAX_LIGHTS);
        return LUMO_ERR_LIMIT;
    }
    lumo_status rc = srv_scene_check_range(s, err, errlen);
    if (rc)
        return rc;
    /* Zero area relative to the scene's size: float cross products of a
     * metre-sized scene cannot resolve less than ~1e-14 of its extent^2. */
    float ext = v3_len(v3_sub(hi, lo));
    for (size_t i = 0; i < s->nmeshes; i++) {
        lumo_status st = validate_mesh(&s->meshes[i], 1e-14f * ext * ext, err, errlen);
        if (st)
            return st;
    }
    for (size_t i = 0; i < s->nlights; i++) {
        const srv_light *l = &s->lights[i];
        if (!v3_finite(l->pos) || !v3_finite(l->dir) || !v3_finite(l->power) ||
            l->power.x < 0 || l->power.y < 0 || l->power.z < 0) {
            snprintf(err, errlen, "light %zu: non-finite or negative value", i);
            return LUMO_ERR_RANGE;
        }
    }
    return LUMO_OK;
}

lumo_status srv_parse_floats(const char *text, float *out, int n)
{
    const char *p = text;
    for (int i = 0; i < n; i++) {
        char *end;
        errno = 0;
        float f = strtof(p, &end);
        if (end == p || errno || !isfinite(f))
            return LUMO_ERR_ARG;
        out[i] = f;
        p = end;
        if (i + 1 < n) {
            if (*p != ',')
                return LUMO_ERR_ARG;
            p++;
        }
    }
    return *p ? LUMO_ERR_ARG : LUMO_OK;
}
