/*
 * mesh_build.c — see mesh_build.h. Desktop code: floats and heap.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "mesh_build.h"

lumo_q16_16 host_q16(double v)
{
    double s = floor(v * 65536.0 + 0.5);
    if (s > 2147483647.0) return INT32_MAX;
    if (s < -2147483648.0) return INT32_MIN;
    return (lumo_q16_16)s;
}

lumo_q1_14 host_q14(double v)
{
    double s = floor(v * 16384.0 + 0.5);
    if (s > 32767.0) return INT16_MAX;
    if (s < -32768.0) return INT16_MIN;
    return (lumo_q1_14)s;
}

void host_mesh_free(host_mesh *m)
{
    free(m->pos);
    free(m->normal);
    free(m->albedo);
    free(m->tris);
    memset(m, 0, sizeof *m);
}

/* Room for more_v vertices and more_t triangles; counts stay below
 * UINT32_MAX / 3 so that 3 * count never wraps. */
static int reserve(host_mesh *m, uint32_t more_v, uint32_t more_t)
{
    uint64_t need_v = (uint64_t)m->vertex_count + more_v, need_t = (uint64_t)m->tri_count + more_t;

    if (need_v > UINT32_MAX / 3 || need_t > UINT32_MAX / 3)
        return -1;
    if (need_v > m->vertex_cap) {
        uint32_t cap = (uint32_t)(need_v * 2 > UINT32_MAX / 3 ? need_v : need_v * 2);
        void *p = realloc(m->pos, (size_t)cap * 3 * sizeof *m->pos);
        void *n = p ? realloc(m->normal, (size_t)cap * 3 * sizeof *m->normal) : NULL;
        void *a = n ? realloc(m->albedo, (size_t)cap * 3 * sizeof *m->albedo) : NULL;
        if (p) m->pos = p;
        if (n) m->normal = n;
        if (a) m->albedo = a;
        if (!a) return -1;
        m->vertex_cap = cap;
    }
    if (need_t > m->tri_cap) {
        uint32_t cap = (uint32_t)(need_t * 2 > UINT32_MAX / 3 ? need_t : need_t * 2);
        void *t = realloc(m->tris, (size_t)cap * 3 * sizeof *m->tris);
        if (!t) return -1;
        m->tris = t;
        m->tri_cap = cap;
    }
    return 0;
}

int host_mesh_append(host_mesh *m, const lumo_q16_16 *pos, const lumo_q1_14 *normal,
                     const lumo_q1_14 *albedo, uint32_t nv, const uint32_t *tris, uint32_t nt)
{
    uint32_t base = m->vertex_count, t;

    if (nv == 0 && nt == 0)
        return 0;
    if (reserve(m, nv, nt))
        return -1;
    memcpy(m->pos + 3 * (size_t)base, pos, (size_t)nv * 3 * sizeof *pos);
    memcpy(m->normal + 3 * (size_t)base, normal, (size_t)nv * 3 * sizeof *normal);
    if (albedo)
        memcpy(m->albedo + 3 * (size_t)base, albedo, (size_t)nv * 3 * sizeof *albedo);
    else   /* no colours: neutral grey (docs/progressive-mesh.md) */
        for (t = 0; t < 3 * nv; t++)
            m->albedo[3 * (size_t)base + t] = HOST_DEFAULT_ALBEDO;
    for (t = 0; t < 3 * nt; t++)
        m->tris[3 * (size_t)m->tri_count + t] = tris[t] + base;
    m->vertex_count += nv;
    m->tri_count += nt;
    return 0;
}

static void normalize(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (l > 0) { v[0] /= l; v[1] /= l; v[2] /= l; }
}

static void cross(const double a[3], const double b[3], double o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

static uint32_t add_vertex(host_mesh *m, const double p[3], const double n[3], const double a[3])
{
    uint32_t i = m->vertex_count++;
    int k;
    for (k = 0; k < 3; k++) {
        m->pos[3 * i + k] = host_q16(p[k]);
        m->normal[3 * i + k] = host_q14(n[k]);
        m->albedo[3 * i + k] = host_q14(a[k]);
    }
    return i;
}

static void add_tri(host_mesh *m, uint32_t a, uint32_t b, uint32_t c)
{
    uint32_t *t = &m->tris[3 * (size_t)m->tri_count++];
    t[0] = a; t[1] = b; t[2] = c;
}

int host_mesh_add_quad(host_mesh *m, const double c[3], const double u[3], const double v[3],
                       int nu, int nv, const double albedo[3])
{
    double n[3];
    uint32_t base;
    int i, j, k;

    if (nu < 1 || nv < 1 || reserve(m, (uint32_t)((nu + 1) * (nv + 1)), (uint32_t)(2 * nu * nv)))
        return -1;
    cross(u, v, n);
    normalize(n);
    base = m->vertex_count;
    for (j = 0; j <= nv; j++)
        for (i = 0; i <= nu; i++) {
            double p[3];
            for (k = 0; k < 3; k++)
                p[k] = c[k] + u[k] * i / nu + v[k] * j / nv;
            add_vertex(m, p, n, albedo);
        }
    for (j = 0; j < nv; j++)
        for (i = 0; i < nu; i++) {
            uint32_t a = base + (uint32_t)(j * (nu + 1) + i);
            add_tri(m, a, a + 1, a + (uint32_t)nu + 2);
            add_tri(m, a, a + (uint32_t)nu + 2, a + (uint32_t)nu + 1);
        }
    return 0;
}

int host_mesh_add_sphere(host_mesh *m, const double c[3], double r, int seg, int inward,
                         const double albedo[3])
{
    int rings = seg / 2, i, j;
    uint32_t base;

    if (seg < 4 || reserve(m, (uint32_t)((rings + 1) * (seg + 1)), (uint32_t)(2 * rings * seg)))
        return -1;
    base = m->vertex_count;
    for (j = 0; j <= rings; j++) {
        double th = M_PI * j / rings;
        for (i = 0; i <= seg; i++) {
            double ph = 2 * M_PI * i / seg;
            double n[3] = {sin(th) * cos(ph), cos(th), -sin(th) * sin(ph)}, p[3];
            int k;
            for (k = 0; k < 3; k++)
                p[k] = c[k] + r * n[k];
            if (inward) { n[0] = -n[0]; n[1] = -n[1]; n[2] = -n[2]; }
            add_vertex(m, p, n, albedo);
        }
    }
    for (j = 0; j < rings; j++)
        for (i = 0; i < seg; i++) {
            uint32_t a = base + (uint32_t)(j * (seg + 1) + i), b = a + (uint32_t)seg + 1;
            /* Counter-clockwise seen from outside. */
            if (j != 0) {
                if (inward) add_tri(m, a, a + 1, b); else add_tri(m, a, b, a + 1);
            }
            if (j != rings - 1) {
                if (inward) add_tri(m, a + 1, b + 1, b); else add_tri(m, a + 1, b, b + 1);
            }
        }
    return 0;
}

lumo_raster_mesh host_mesh_raster(const host_mesh *m)
{
    lumo_raster_mesh r;
    memset(&r, 0, sizeof r);
    r.pos = m->pos;
    r.normal = m->normal;
    r.albedo = m->albedo;
    r.tris = m->tris;
    r.vertex_count = m->vertex_count;
    r.tri_count = m->tri_count;
    return r;
}

void host_scene_free(host_scene *s)
{
    host_mesh_free(&s->mesh);
}
