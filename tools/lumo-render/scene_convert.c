/*
 * scene_convert.c — see scene_convert.h. Desktop code: floats and heap.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "scene/camera.h"
#include "scene_convert.h"

/* Power or irradiance to UQ16.16, rounded, saturated to [0, 65536). */
static lumo_uq16_16 uq16(double v)
{
    double s = floor(v * 65536.0 + 0.5);
    if (!(s > 0)) return 0;
    if (s > 4294967295.0) return UINT32_MAX;
    return (lumo_uq16_16)s;
}

static int finite3(vec3 v)
{
    return isfinite(v.x) && isfinite(v.y) && isfinite(v.z);
}

static void q16_3(vec3 v, lumo_q16_16 out[3])
{
    out[0] = host_q16(v.x);
    out[1] = host_q16(v.y);
    out[2] = host_q16(v.z);
}

lumo_status host_camera_from_srv(const srv_camera *c, lumo_raster_camera *out)
{
    lumo_raster_camera r;

    if (!finite3(c->eye) || !finite3(c->target) || !finite3(c->up))
        return LUMO_ERR_NONFINITE;
    if (!(c->fovy_deg >= 1.0f && c->fovy_deg <= 179.0f))
        return LUMO_ERR_RANGE;
    memset(&r, 0, sizeof r);
    q16_3(c->eye, r.eye);
    q16_3(c->target, r.target);
    q16_3(c->up, r.up);
    r.fovy_deg = host_q16(c->fovy_deg);
    r.znear = LUMO_RASTER_ZNEAR;
    *out = r;
    return LUMO_OK;
}

lumo_status host_light_from_srv(const srv_light *l, lumo_raster_light *out)
{
    lumo_pkg_light p;

    if (!finite3(l->pos) || !finite3(l->dir) || !finite3(l->u) || !finite3(l->v) || !finite3(l->power)
        || !isfinite(l->half_angle_deg) || !isfinite(l->cos_half))
        return LUMO_ERR_NONFINITE;
    /* The fields the package writer stores (server/package/pack.c), in the
     * fixed point its reader gives (lumo/scene.h). */
    memset(&p, 0, sizeof p);
    p.kind = l->kind;
    q16_3(l->pos, p.pos);
    q16_3(l->u, p.u);
    q16_3(l->v, p.v);
    p.dir[0] = host_q14(l->dir.x);
    p.dir[1] = host_q14(l->dir.y);
    p.dir[2] = host_q14(l->dir.z);
    p.half_angle_deg = host_q16(l->half_angle_deg);
    p.cos_half = host_q14(l->kind == LUMO_LIGHT_SPOT ? l->cos_half : -1.0f);
    p.power[0] = uq16(l->power.x);
    p.power[1] = uq16(l->power.y);
    p.power[2] = uq16(l->power.z);
    lumo_raster_light_from_pkg(&p, out);
    return LUMO_OK;
}

lumo_status host_camera_from_string(const char *text, lumo_raster_camera *out)
{
    srv_camera c;
    lumo_status st = srv_camera_parse(text, &c);

    return st ? st : host_camera_from_srv(&c, out);
}

lumo_status host_light_parse(const char *opt, const char *text, lumo_raster_light *out, char *err, size_t errlen)
{
    srv_light l;
    lumo_status st = srv_light_parse_as(opt, text, &l, err, errlen);

    if (!st && (st = host_light_from_srv(&l, out)))
        snprintf(err, errlen, "%s '%.200s': %s in the renderer's fixed point", opt, text, lumo_strerror(st));
    return st;
}

lumo_status host_light_from_string(const char *text, lumo_raster_light *out)
{
    char why[600];

    return text ? host_light_parse("light", text, out, why, sizeof why) : LUMO_ERR_ARG;
}

/* ---- meshes -------------------------------------------------------------- */

static const srv_mesh *g_sort_mesh;   /* qsort has no context argument in C11 */

/* Vertex order: position, then albedo (bit patterns: an exact total order),
 * then index, so the first of a run is its smallest vertex. */
static int cmp_vertex(const void *a, const void *b)
{
    uint32_t i = *(const uint32_t *)a, j = *(const uint32_t *)b;
    int c = memcmp(&g_sort_mesh->pos[i], &g_sort_mesh->pos[j], sizeof(vec3));
    if (!c)
        c = memcmp(&g_sort_mesh->albedo[i], &g_sort_mesh->albedo[j], sizeof(vec3));
    return c ? c : (i > j) - (i < j);
}

/* One mesh appended to h. Vertices of one position share a normal (class
 * `at`); vertices of one position and albedo become one vertex (`id`). */
static lumo_status add_mesh(host_mesh *h, const srv_mesh *m, char *err, size_t errlen)
{
    uint32_t n = m->nverts, nt = m->ntris, i, v, k, kept = 0, classes = 0;
    size_t j;
    uint32_t *order = malloc(sizeof *order * (n ? n : 1));
    uint32_t *at = malloc(sizeof *at * (n ? n : 1));
    uint32_t *id = malloc(sizeof *id * (n ? n : 1));
    uint32_t *tris = malloc(sizeof *tris * 3 * (size_t)(nt ? nt : 1));
    double *sum = calloc(3 * (size_t)(n ? n : 1), sizeof *sum);
    lumo_q16_16 *pos = malloc(sizeof *pos * 3 * (size_t)(n ? n : 1));
    lumo_q1_14 *nrm = malloc(sizeof *nrm * 3 * (size_t)(n ? n : 1));
    lumo_q1_14 *alb = malloc(sizeof *alb * 3 * (size_t)(n ? n : 1));
    lumo_status st = LUMO_ERR_NOMEM;

    if (!order || !at || !id || !tris || !sum || !pos || !nrm || !alb) {
        snprintf(err, errlen, "mesh '%s': out of memory", m->name);
        goto out;
    }
    for (j = 0; j < 3 * (size_t)nt; j++)
        if (m->tris[j] >= n) {
            snprintf(err, errlen, "mesh '%s': face %zu indexes a missing vertex", m->name, j / 3);
            st = LUMO_ERR_RANGE;
            goto out;
        }
    for (v = 0; v < n; v++)
        order[v] = v;
    g_sort_mesh = m;
    qsort(order, n, sizeof *order, cmp_vertex);
    /* id[v]: the smallest vertex of v's position and albedo; at[v]: the
     * position class. */
    for (i = 0; i < n; i++) {
        uint32_t a = order[i], b = i ? order[i - 1] : 0;
        int same_pos = i && !memcmp(&m->pos[a], &m->pos[b], sizeof(vec3));
        int same = same_pos && !memcmp(&m->albedo[a], &m->albedo[b], sizeof(vec3));
        at[a] = same_pos ? at[b] : classes++;
        id[a] = same ? id[b] : a;
    }
    /* Area-weighted normals of the wound faces, summed per position. */
    for (i = 0; i < nt; i++) {
        const uint32_t *t = &m->tris[3 * (size_t)i];
        vec3 p0 = m->pos[t[0]], p1 = m->pos[t[1]], p2 = m->pos[t[2]];
        double e1[3] = {(double)p1.x - p0.x, (double)p1.y - p0.y, (double)p1.z - p0.z};
        double e2[3] = {(double)p2.x - p0.x, (double)p2.y - p0.y, (double)p2.z - p0.z};
        double c[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                       e1[0] * e2[1] - e1[1] * e2[0]};
        for (k = 0; k < 9; k++)
            sum[3 * (size_t)at[t[k / 3]] + k % 3] += c[k % 3];
    }
    /* Kept vertices in input order; id[] becomes their new index. */
    for (v = 0; v < n; v++) {
        double *s = &sum[3 * (size_t)at[v]], l;
        if (id[v] != v) {
            id[v] = id[id[v]];   /* id[v] < v: already renumbered */
            continue;
        }
        l = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
        q16_3(m->pos[v], &pos[3 * (size_t)kept]);
        for (k = 0; k < 3; k++)
            nrm[3 * (size_t)kept + k] = l > 0 ? host_q14(s[k] / l) : 0;
        alb[3 * (size_t)kept] = host_q14(m->albedo[v].x);
        alb[3 * (size_t)kept + 1] = host_q14(m->albedo[v].y);
        alb[3 * (size_t)kept + 2] = host_q14(m->albedo[v].z);
        id[v] = kept++;
    }
    for (j = 0; j < 3 * (size_t)nt; j++)
        tris[j] = id[m->tris[j]];
    st = LUMO_OK;
    if (host_mesh_append(h, pos, nrm, alb, kept, tris, nt)) {
        snprintf(err, errlen, "mesh '%s': out of memory or more than %u vertices or triangles", m->name,
                 UINT32_MAX / 3);
        st = LUMO_ERR_LIMIT;
    }
out:
    free(order);
    free(at);
    free(id);
    free(tris);
    free(sum);
    free(pos);
    free(nrm);
    free(alb);
    return st;
}

lumo_status host_scene_from_srv(host_scene *out, const srv_scene *s, char *err, size_t errlen)
{
    lumo_status st;
    size_t i;

    memset(out, 0, sizeof *out);
    if (s->nlights > LUMO_MAX_LIGHTS) {
        snprintf(err, errlen, "the scene has %zu lights, at most %d are supported", s->nlights,
                 LUMO_MAX_LIGHTS);
        return LUMO_ERR_LIMIT;
    }
    for (i = 0; i < s->nlights; i++)
        if ((st = host_light_from_srv(&s->lights[i], &out->lights[out->light_count++]))) {
            snprintf(err, errlen, "light %zu: non-finite value", i);
            return st;
        }
    if ((st = host_camera_from_srv(&s->camera, &out->camera))) {
        snprintf(err, errlen, "camera: %s (the rasterizer draws fields of view in [1, 179] degrees)",
                 lumo_strerror(st));
        return st;
    }
    for (i = 0; i < s->nmeshes; i++)
        if ((st = add_mesh(&out->mesh, &s->meshes[i], err, errlen))) {
            host_scene_free(out);
            return st;
        }
    {
        vec3 lo, hi;
        srv_scene_bounds(s, &lo, &hi);
        q16_3(lo, out->bmin);
        q16_3(hi, out->bmax);
    }
    out->camera.znear = lumo_raster_znear_for_box(&out->camera, out->bmin, out->bmax);
    return LUMO_OK;
}

lumo_status host_scene_aim(host_scene *s, const lumo_raster_camera *view, int fit, uint32_t width,
                           uint32_t height, char *err, size_t errlen)
{
    lumo_status st;

    if (view)
        s->camera = *view;
    else if (fit) {
        lumo_pkg_info box;
        memset(&box, 0, sizeof box);
        memcpy(box.bmin, s->bmin, sizeof box.bmin);
        memcpy(box.bmax, s->bmax, sizeof box.bmax);
        if ((st = lumo_scene_camera_fit(&box, width, height))) {
            snprintf(err, errlen, "cannot fit a camera to the scene's bounds: %s", lumo_strerror(st));
            return st;
        }
        memcpy(s->camera.eye, box.eye, sizeof box.eye);
        memcpy(s->camera.target, box.target, sizeof box.target);
        memcpy(s->camera.up, box.up, sizeof box.up);
        s->camera.fovy_deg = box.fovy_deg;
    }
    s->camera.znear = lumo_raster_znear_for_box(&s->camera, s->bmin, s->bmax);
    return LUMO_OK;
}
