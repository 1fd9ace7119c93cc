/*
 * mesh_build.c — see mesh_build.h. Desktop code: floats and heap.
 */
#include <math.h>
#include <stdio.h>
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

int host_mesh_add_box(host_mesh *m, const double lo[3], const double hi[3], int inward,
                      const double albedo[3])
{
    double d[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
    int axis, side;

    for (axis = 0; axis < 3; axis++)
        for (side = 0; side < 2; side++) {
            int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
            double c[3], u[3] = {0, 0, 0}, v[3] = {0, 0, 0};
            memcpy(c, lo, sizeof c);
            if (side) c[axis] = hi[axis];
            u[a1] = d[a1];
            v[a2] = d[a2];
            /* u x v points along +axis: flip for the low face (outward) and
             * again for a room. */
            if ((side == 0) != (inward != 0)) {
                c[a1] += d[a1];
                u[a1] = -d[a1];
            }
            if (host_mesh_add_quad(m, c, u, v, 1, 1, albedo))
                return -1;
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

/* ---- models ---------------------------------------------------------------- */

typedef struct raw_model {
    double *p;
    uint32_t *t;
    size_t nv, nt, cap_v, cap_t;
} raw_model;

static int raw_push_v(raw_model *r, const double p[3])
{
    if (r->nv == r->cap_v) {
        size_t cap = r->cap_v ? r->cap_v * 2 : 1024;
        double *np = realloc(r->p, cap * 3 * sizeof *np);
        if (!np) return -1;
        r->p = np;
        r->cap_v = cap;
    }
    memcpy(&r->p[3 * r->nv++], p, 3 * sizeof *p);
    return 0;
}

static int raw_push_t(raw_model *r, uint32_t a, uint32_t b, uint32_t c)
{
    if (r->nt == r->cap_t) {
        size_t cap = r->cap_t ? r->cap_t * 2 : 1024;
        uint32_t *nt = realloc(r->t, cap * 3 * sizeof *nt);
        if (!nt) return -1;
        r->t = nt;
        r->cap_t = cap;
    }
    r->t[3 * r->nt] = a; r->t[3 * r->nt + 1] = b; r->t[3 * r->nt + 2] = c;
    r->nt++;
    return 0;
}

static int read_ply(FILE *f, raw_model *r)
{
    char line[512];
    unsigned long nv = 0, nf = 0, i;

    if (!fgets(line, sizeof line, f) || strncmp(line, "ply", 3))
        return -1;
    while (fgets(line, sizeof line, f)) {
        if (sscanf(line, "element vertex %lu", &nv) == 1) continue;
        if (sscanf(line, "element face %lu", &nf) == 1) continue;
        if (strstr(line, "format") && !strstr(line, "ascii")) return -1;
        if (!strncmp(line, "end_header", 10)) break;
    }
    for (i = 0; i < nv; i++) {
        double p[3];
        if (!fgets(line, sizeof line, f) || sscanf(line, "%lf %lf %lf", &p[0], &p[1], &p[2]) != 3
            || raw_push_v(r, p))
            return -1;
    }
    for (i = 0; i < nf; i++) {
        unsigned long n, k, idx[64];
        int off = 0, used;
        if (!fgets(line, sizeof line, f) || sscanf(line, "%lu%n", &n, &used) != 1 || n < 3 || n > 64)
            return -1;
        off = used;
        for (k = 0; k < n; k++) {
            if (sscanf(line + off, "%lu%n", &idx[k], &used) != 1 || idx[k] >= nv)
                return -1;
            off += used;
        }
        for (k = 1; k + 1 < n; k++)
            if (raw_push_t(r, (uint32_t)idx[0], (uint32_t)idx[k], (uint32_t)idx[k + 1]))
                return -1;
    }
    return 0;
}

static int read_obj(FILE *f, raw_model *r)
{
    char line[512];

    while (fgets(line, sizeof line, f)) {
        if (line[0] == 'v' && line[1] == ' ') {
            double p[3];
            if (sscanf(line + 2, "%lf %lf %lf", &p[0], &p[1], &p[2]) != 3 || raw_push_v(r, p))
                return -1;
        } else if (line[0] == 'f' && line[1] == ' ') {
            long idx[64];
            int n = 0, off = 2, used;
            while (n < 64 && sscanf(line + off, "%ld%n", &idx[n], &used) == 1) {
                off += used;
                while (line[off] && line[off] != ' ' && line[off] != '\t') off++;  /* skip /vt/vn */
                if (idx[n] < 0) idx[n] += (long)r->nv + 1;
                if (idx[n] < 1 || (size_t)idx[n] > r->nv) return -1;
                n++;
            }
            for (int k = 1; k + 1 < n; k++)
                if (raw_push_t(r, (uint32_t)(idx[0] - 1), (uint32_t)(idx[k] - 1), (uint32_t)(idx[k + 1] - 1)))
                    return -1;
        }
    }
    return r->nv ? 0 : -1;
}

int host_mesh_load_model(host_mesh *m, const char *path, double size, double y0,
                         const double albedo[3])
{
    raw_model r = {0};
    FILE *f = fopen(path, "r");
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    double ext = 0, s, *nrm = NULL;
    size_t len = strlen(path), i;
    uint32_t base;
    int rc = -1, k;

    if (!f)
        return -1;
    rc = (len > 4 && !strcmp(path + len - 4, ".obj")) ? read_obj(f, &r) : read_ply(f, &r);
    fclose(f);
    if (rc || r.nv == 0 || reserve(m, (uint32_t)r.nv, (uint32_t)r.nt))
        goto out;
    rc = -1;
    for (i = 0; i < r.nv; i++)
        for (k = 0; k < 3; k++) {
            if (r.p[3 * i + k] < lo[k]) lo[k] = r.p[3 * i + k];
            if (r.p[3 * i + k] > hi[k]) hi[k] = r.p[3 * i + k];
        }
    for (k = 0; k < 3; k++)
        if (hi[k] - lo[k] > ext) ext = hi[k] - lo[k];
    if (ext <= 0)
        goto out;
    s = size / ext;
    nrm = calloc(r.nv * 3, sizeof *nrm);
    if (!nrm)
        goto out;
    for (i = 0; i < r.nt; i++) {     /* area-weighted face normals */
        const uint32_t *t = &r.t[3 * i];
        double e1[3], e2[3], n[3];
        for (k = 0; k < 3; k++) {
            e1[k] = r.p[3 * t[1] + k] - r.p[3 * t[0] + k];
            e2[k] = r.p[3 * t[2] + k] - r.p[3 * t[0] + k];
        }
        cross(e1, e2, n);
        for (k = 0; k < 9; k++)
            nrm[3 * t[k / 3] + (size_t)(k % 3)] += n[k % 3];
    }
    base = m->vertex_count;
    for (i = 0; i < r.nv; i++) {
        double p[3], *n = &nrm[3 * i];
        p[0] = (r.p[3 * i] - (lo[0] + hi[0]) / 2) * s;
        p[1] = (r.p[3 * i + 1] - lo[1]) * s + y0;
        p[2] = (r.p[3 * i + 2] - (lo[2] + hi[2]) / 2) * s;
        normalize(n);
        add_vertex(m, p, n, albedo);
    }
    for (i = 0; i < r.nt; i++)
        add_tri(m, base + r.t[3 * i], base + r.t[3 * i + 1], base + r.t[3 * i + 2]);
    rc = 0;
out:
    free(nrm);
    free(r.p);
    free(r.t);
    return rc;
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

/* ---- strings ---------------------------------------------------------------- */

static int parse_vec(const char **s, double v[3])
{
    char *end;
    int k;
    for (k = 0; k < 3; k++) {
        v[k] = strtod(*s, &end);
        if (end == *s || !isfinite(v[k])) return -1;
        *s = end;
        if (k < 2) {
            if (**s != ',') return -1;
            (*s)++;
        }
    }
    return 0;
}

static int expect(const char **s, char c)
{
    if (**s != c) return -1;
    (*s)++;
    return 0;
}

int host_camera_parse(const char *s, lumo_raster_camera *cam)
{
    double e[3], t[3], u[3], fovy;
    char *end;
    int k;

    if (parse_vec(&s, e) || expect(&s, ':') || parse_vec(&s, t) || expect(&s, ':')
        || parse_vec(&s, u) || expect(&s, ':'))
        return -1;
    fovy = strtod(s, &end);
    if (end == s || *end || !(fovy >= 1 && fovy <= 179))
        return -1;
    for (k = 0; k < 3; k++) {
        cam->eye[k] = host_q16(e[k]);
        cam->target[k] = host_q16(t[k]);
        cam->up[k] = host_q16(u[k]);
    }
    cam->fovy_deg = host_q16(fovy);
    if (!cam->znear)
        cam->znear = host_q16(0.01);
    return 0;
}

static void set_value(lumo_raster_light *l, const double v[3])
{
    int k;
    for (k = 0; k < 3; k++)
        l->value[k] = (lumo_uq16_16)(v[k] <= 0 ? 0 : v[k] >= 65535 ? 0xFFFFFFFFu : floor(v[k] * 65536 + 0.5));
}

static void set_dir(lumo_raster_light *l, double d[3])
{
    int k;
    normalize(d);
    for (k = 0; k < 3; k++)
        l->dir[k] = host_q14(d[k]);
}

int host_light_parse(const char *s, lumo_raster_light *l)
{
    double p[3], d[3], v[3], half;
    char *end;
    int k;

    memset(l, 0, sizeof *l);
    if (!strncmp(s, "point:", 6)) {
        s += 6;
        if (parse_vec(&s, p) || expect(&s, ':') || parse_vec(&s, v) || *s) return -1;
        l->kind = LUMO_LIGHT_POINT;
    } else if (!strncmp(s, "spot:", 5)) {
        s += 5;
        if (parse_vec(&s, p) || expect(&s, ':') || parse_vec(&s, d) || expect(&s, ':')) return -1;
        half = strtod(s, &end);
        if (end == s || !(half > 0 && half < 180)) return -1;
        s = end;
        if (expect(&s, ':') || parse_vec(&s, v) || *s) return -1;
        l->kind = LUMO_LIGHT_SPOT;
        set_dir(l, d);
        l->cos_cutoff = host_q14(cos(half * M_PI / 180));
    } else if (!strncmp(s, "directional:", 12)) {
        s += 12;
        if (parse_vec(&s, d) || expect(&s, ':') || parse_vec(&s, v) || *s) return -1;
        l->kind = LUMO_LIGHT_DIRECTIONAL;
        set_dir(l, d);
        memset(p, 0, sizeof p);
    } else {
        return -1;
    }
    for (k = 0; k < 3; k++)
        l->pos[k] = host_q16(p[k]);
    set_value(l, v);
    return 0;
}

/* ---- the default scene (docs/scene-format.md) --------------------------------- */

int host_scene_default(host_scene *s, const char *model_path)
{
    static const double white[3] = {0.75, 0.75, 0.75}, red[3] = {0.63, 0.065, 0.05},
                        green[3] = {0.14, 0.45, 0.091}, body[3] = {0.72, 0.62, 0.45};
    const double floor_c[3] = {-1, 0, 1}, ceil_c[3] = {-1, 2, -1}, back_c[3] = {-1, 0, -1};
    const double left_c[3] = {-1, 0, 1}, right_c[3] = {1, 0, -1};
    const double ux[3] = {2, 0, 0}, uy[3] = {0, 2, 0}, uz[3] = {0, 0, 2};
    const double mz[3] = {0, 0, -2}, mx[3] = {-2, 0, 0};
    const double centre[3] = {0, 0.45, 0};
    int n = 8;

    memset(s, 0, sizeof *s);
    /* Walls face into the box (normal u x v inwards). */
    if (host_mesh_add_quad(&s->mesh, floor_c, ux, mz, n, n, white)          /* +y */
        || host_mesh_add_quad(&s->mesh, ceil_c, ux, uz, n, n, white)        /* -y */
        || host_mesh_add_quad(&s->mesh, back_c, ux, uy, n, n, white)        /* +z */
        || host_mesh_add_quad(&s->mesh, left_c, mz, uy, n, n, red)          /* +x */
        || host_mesh_add_quad(&s->mesh, right_c, uz, uy, n, n, green))      /* -x */
        return -1;
    (void)mx;
    if (!model_path || host_mesh_load_model(&s->mesh, model_path, 1.4, 0.0, body))
        if (host_mesh_add_sphere(&s->mesh, centre, 0.45, 48, 0, body))
            return -1;
    if (host_light_parse("spot:0,1.95,0:0,-1,0:60:40,40,40", &s->lights[0]))
        return -1;
    s->light_count = 1;
    s->camera.znear = host_q16(0.01);
    return host_camera_parse("0,1,3.4:0,1,0:0,1,0:40", &s->camera);
}

void host_scene_free(host_scene *s)
{
    host_mesh_free(&s->mesh);
}
